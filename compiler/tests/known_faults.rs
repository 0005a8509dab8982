//! W119: an arc of a program with macros that cannot be drawn from the
//! point the compiler knows the tool stands at, whatever path reaches it.

use compiler::{compile, Options};
use nc::Machine;
use vm::{Status, Vm};

mod common;
use common::Rng;

/// The codes and lines of the diagnostics of `src`, and whether it
/// compiled to a module.
fn diagnostics(src: &str) -> (Vec<(String, usize)>, bool) {
    let c = compile("t.nc", src.as_bytes(), &Options::default());
    let found = c
        .diags
        .iter()
        .map(|(f, d)| {
            let line = c.files[*f].line_col(d.span.start).0;
            (d.code.to_string(), line)
        })
        .collect();
    (found, c.module.is_some())
}

fn w119(src: &str) -> Vec<usize> {
    let (found, compiled) = diagnostics(src);
    assert!(compiled, "{src}: {found:?}");
    found
        .into_iter()
        .filter(|(code, _)| code == "W119")
        .map(|(_, line)| line)
        .collect()
}

#[test]
fn an_arc_that_cannot_close_is_warned_of_and_still_compiles() {
    // From X0 Z0 to X20 Z-30 the half chord is 15.8 mm: R2 cannot reach.
    let src = "#1=1\nG00 X0 Z0\nG02 X20 Z-30 R2\nM30\n";
    assert_eq!(w119(src), [3]);
    let c = compile("t.nc", src.as_bytes(), &Options::default());
    let d = &c.diags[0].1;
    assert!(d.message.contains("E4001"), "{}", d.message);
    // I/K puts the centre at X0 Z-10 (radius 10); the end point X20 Z-30
    // is 22.4 mm from it: off the circle.
    assert_eq!(w119("#1=1\nG00 X0 Z0\nG03 X20 Z-30 I0 K-10\nM30\n"), [3]);
    // A start point computed from values the compiler folds is known.
    assert_eq!(w119("#1=0\nG00 X#1 Z0\nG02 X20 Z-30 R2\nM30\n"), [3]);
}

#[test]
fn the_position_is_followed_through_a_block_with_two_motion_codes() {
    // `G00 G01`: G01 wins (W106), and the block is a plain line to X10
    // Z0; from there R1 cannot reach X20 Z-5 (half chord 7.07 mm).
    let src = "#1=1\nG00 X20 Z2\nG00 G01 X10 Z0 F100\nG02 X20 Z-5 R1\nM30\n";
    let (found, _) = diagnostics(src);
    let w = |c: &str, l| (c.to_string(), l);
    assert_eq!(found, [w("W106", 3), w("W119", 4)]);
    // Written the other way round, the last code is G02 itself: the arc
    // of line 3 goes from X20 Z2 to X10 Z0 with R10 and ends where line
    // 4's short arc starts.
    let src = "#1=1\nG00 X20 Z2\nG01 G02 X10 Z0 R10 F100\nG02 X20 Z-5 R1\nM30\n";
    let (found, _) = diagnostics(src);
    assert_eq!(found, [w("W106", 3), w("W119", 4)]);
}

#[test]
fn no_warning_where_the_arc_can_be_drawn_or_its_start_is_not_known() {
    // R20 reaches.
    assert!(w119("#1=1\nG00 X0 Z0\nG02 X20 Z-30 R20\nM30\n").is_empty());
    // The start point is computed (#500 is kept from run to run: not
    // known to the compiler).
    assert!(w119("G00 X#500 Z0\nG02 X20 Z-30 R2\nM30\n").is_empty());
    // Paths meet from two points.
    let join = "G00 X0 Z0\nIF[#500EQ1]GOTO10\nG00 Z-20\nN10 G02 X20 Z-30 R2\nM30\n";
    assert!(w119(join).is_empty());
    // Compensation bends the path: the kernel decides as it runs.
    assert!(w119("#1=1\nT0101\nG00 X0 Z0\nG42 G01 X2 F1\nG02 X20 Z-30 R2\nM30\n").is_empty());
}

#[test]
fn a_static_program_gets_the_error_itself() {
    let (found, compiled) = diagnostics("G00 X0 Z0\nG02 X20 Z-30 R2\nM30\n");
    assert!(!compiled);
    assert_eq!(found, [("E4001".to_string(), 2)]);
}

/// A macro program of random moves (arcs by R and by I/K, many of them
/// impossible), with branches that join, a loop and a mode change now
/// and then.
fn arc_program(rng: &mut Rng) -> String {
    let mut src = String::from("#1=0\nG00 X40 Z2\n");
    let mut label = 10;
    for _ in 0..rng.below(12) + 4 {
        let (x, z) = (rng.below(60), rng.below(40));
        match rng.below(9) {
            0 | 1 => src += &format!("G01 X{x} Z-{z} F100\n"),
            2 => src += &format!("U{} W-{}\n", rng.below(9), rng.below(9)),
            3 | 4 => {
                let g = 2 + rng.below(2);
                // (Now and then a block with two motion codes, W106: the
                // last one runs.)
                let lead = ["", "G01 "][usize::from(x % 4 == 0)];
                src += &format!("{lead}G0{g} X{x} Z-{z} R{}\n", 1 + rng.below(30));
            }
            5 => {
                let g = 2 + rng.below(2);
                let (i, k) = (rng.below(20), rng.below(20));
                src += &format!("G0{g} X{x} Z-{z} I{i} K-{k}\n");
            }
            6 => {
                src += &format!("IF[#500EQ1]GOTO{label}\nG00 X{x}\nN{label} M08\n");
                label += 10;
            }
            7 => src += "#1=0\nWHILE[#1LT2]DO1\nG01 W-1 F100\n#1=#1+1\nEND1\n",
            _ => src += rng.pick(&["G20\n", "G21\n", "G99\n", "G98\n", "T0101\n"]),
        }
    }
    src + "M30\n"
}

/// "Whenever it is reached": in 300 random macro programs of moves, every
/// run that reaches a block W119 names stops there with the alarm W119
/// named (E4001, E4002, or E2006 for a modal arc without its centre).
#[test]
fn a_run_that_reaches_a_w119_block_alarms_there() {
    let mut rng = Rng(0x0119_0119_2026_1203);
    let (mut warned, mut reached) = (0, 0);
    for _ in 0..300 {
        let src = arc_program(&mut rng);
        let c = compile("t.nc", src.as_bytes(), &Options::default());
        let Some(module) = c.module else {
            continue;
        };
        // Each W119's line and the alarm it names ("raises E4001 …").
        let named: Vec<(u32, u32)> = c
            .diags
            .iter()
            .filter(|(_, d)| d.code == "W119")
            .map(|(f, d)| {
                let code = d.message.split_once("raises E").and_then(|(_, rest)| {
                    rest.split_whitespace().next().and_then(|c| c.parse().ok())
                });
                let line = c.files[*f].line_col(d.span.start).0 as u32;
                (line, code.unwrap_or_else(|| panic!("{}", d.message)))
            })
            .collect();
        let lines: Vec<u32> = named.iter().map(|&(line, _)| line).collect();
        warned += lines.len();
        if lines.is_empty() {
            continue;
        }
        let mut vm = Vm::new(module, Machine::reference());
        let mut sink = Vec::new();
        for _ in 0..100_000 {
            let pc = vm.pc() as usize;
            let runs_block = vm.module().code.get(pc).is_some_and(common::runs_block);
            let line = vm.module().lines.get(pc).unwrap_or_default().line;
            let status = vm.step(1, &mut sink);
            sink.clear();
            if runs_block && lines.contains(&line) {
                reached += 1;
                let alarmed = matches!(&status, Status::Alarm(a)
                    if named.contains(&(line, a.code)) && a.line == line);
                assert!(alarmed, "{src}\nline {line}: {status:?}");
                break;
            }
            if matches!(status, Status::Done | Status::Alarm(_)) {
                break;
            }
        }
    }
    eprintln!("{warned} W119 warnings, {reached} of their blocks reached");
    assert!(reached >= 10, "only {reached} W119 blocks reached");
}

/// A program longer than the search's bound compiles without it.
#[test]
fn a_long_program_is_not_searched() {
    let head = "#1=1\nG00 X0 Z0\nG02 X20 Z-30 R2\n";
    let short = format!("{head}M30\n");
    assert_eq!(w119(&short), [3]);
    let moves = "G01 X1 Z-1 F100\n".repeat(compiler::known_faults::MAX_OPS);
    assert!(w119(&format!("{head}{moves}M30\n")).is_empty());
}
