//! The command-line contract of gbcc and gbvm: exit codes, output names,
//! diagnostic formats, and rejection of damaged modules.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-driver-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn gbvm(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn compile_and_run_with_the_default_output_name() {
    let d = dir("ok");
    std::fs::write(d.join("part.nc"), "G00 X10 Z2\nG01 Z-5 F100\nM30\n").unwrap();
    let out = gbcc(&["part.nc"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(d.join("part.gbc").exists());
    let run = gbvm(&["run", "part.gbc", "--emit", "canon"], &d);
    assert_eq!(run.status.code(), Some(0));
    assert_eq!(
        text(&run.stdout),
        "RAPID X=10 Z=2\nFEED F=100 MODE=MIN\nLINE X=10 Z=-5\nSTOP KIND=M30\n"
    );
    assert_eq!(gbvm(&["verify", "part.gbc"], &d).status.code(), Some(0));
    assert!(text(&gbvm(&["disasm", "part.gbc"], &d).stdout).contains("move b0 (G0 X10 Z2)"));
}

/// A failed compile leaves no module where it would have written one (as
/// gcc removes a failed output): the old program is not run by mistake.
/// What is not a module at that name stays.
#[test]
fn a_failed_compile_leaves_no_stale_module() {
    let d = dir("stale");
    std::fs::write(d.join("part.nc"), "G00 X10 Z2\nM30\n").unwrap();
    assert_eq!(gbcc(&["part.nc"], &d).status.code(), Some(0));
    assert!(d.join("part.gbc").exists());
    std::fs::write(d.join("part.nc"), "G00 X10 Z2\nG01 X\nM30\n").unwrap();
    assert_eq!(gbcc(&["part.nc"], &d).status.code(), Some(1));
    assert!(!d.join("part.gbc").exists(), "the old module stayed");
    // A compile that succeeds writes its module where the old one was.
    std::fs::write(d.join("good.nc"), "G00 X20 Z2\nM30\n").unwrap();
    assert_eq!(gbcc(&["part.nc", "-o", "x.gbc"], &d).status.code(), Some(1));
    assert_eq!(gbcc(&["good.nc", "-o", "x.gbc"], &d).status.code(), Some(0));
    assert_eq!(gbcc(&["good.nc", "-o", "x.gbc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "x.gbc", "--emit", "canon"], &d);
    assert_eq!(text(&run.stdout), "RAPID X=20 Z=2\nSTOP KIND=M30\n");
    // Text at the output's name is not a module: a failed compile keeps it.
    std::fs::write(d.join("notes.gbc"), "not a module\n").unwrap();
    assert_eq!(
        gbcc(&["part.nc", "-o", "notes.gbc"], &d).status.code(),
        Some(1)
    );
    assert_eq!(
        std::fs::read(d.join("notes.gbc")).unwrap(),
        b"not a module\n"
    );
    // Nor does a syntax check or a listing remove a module.
    assert_eq!(
        gbcc(&["part.nc", "-fsyntax-only", "-o", "x.gbc"], &d)
            .status
            .code(),
        Some(1)
    );
    assert_eq!(
        gbcc(&["part.nc", "-S", "-o", "x.gbc"], &d).status.code(),
        Some(1)
    );
    assert!(d.join("x.gbc").exists());
}

#[test]
fn errors_exit_1_with_gcc_style_headers_and_json_on_request() {
    let d = dir("err");
    std::fs::write(d.join("bad.nc"), "G00 X10\nM98 P4321\n").unwrap();
    let out = gbcc(&["bad.nc", "-o", "bad.gbc"], &d);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.starts_with("bad.nc:2:1: error[E2012]: "), "{err}");
    let json = gbcc(&["bad.nc", "-fdiagnostics-format=json"], &d);
    let line = text(&json.stderr);
    assert!(
        line.contains("\"line_start\":2")
            && line.contains("\"code\":\"E2012\"")
            && line.contains("\"file_name\":\"bad.nc\""),
        "{line}"
    );
    std::fs::write(d.join("syntax.nc"), "G00 X1.2.3\n").unwrap();
    let s = gbcc(&["syntax.nc", "-fsyntax-only"], &d);
    assert_eq!(s.status.code(), Some(1));
    assert!(text(&s.stderr).contains("error[E1007]"));
}

#[test]
fn diagnostics_are_printed_in_source_order() {
    // The passes find these in their own order: W106 and W109 from the
    // words, W119 from pass `modal`, then the compile-time run's W114 and
    // W110 (its alarm at line 9 is W119's). gbcc prints them by line, as
    // a reader meets them.
    let d = dir("order");
    let src = "#1=1\nG0 G1 X10 Z2 F100\nG28\nS99999 M3\nG96 S100\nG32 Z-10 F1.5\n\
               G97 S500\nG0 X50 Z2\nG2 X20 Z-30\nM30\n";
    std::fs::write(d.join("o.nc"), src).unwrap();
    let out = gbcc(&["o.nc", "-o", "o.gbc"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    let headers: Vec<(&str, &str)> = err
        .lines()
        .filter(|l| l.starts_with("o.nc:"))
        .filter_map(|l| {
            let place = l.split(": ").next()?;
            Some((place, l.split('[').nth(1)?.split(']').next()?))
        })
        .collect();
    assert_eq!(
        headers,
        [
            ("o.nc:2:4", "W106"),
            ("o.nc:3:1", "W109"),
            ("o.nc:4:1", "W114"),
            ("o.nc:6:1", "W110"),
            ("o.nc:9:1", "W119"),
        ]
    );
}

/// 1 for both tools, as canon.md gives `gbvm run` ("usage, load or
/// verification error"): not gbvm's alarm code 2.
#[test]
fn usage_errors_exit_1() {
    let d = dir("usage");
    assert_eq!(gbcc(&[], &d).status.code(), Some(1));
    assert_eq!(
        gbcc(&["x.nc", "-fno-such-thing"], &d).status.code(),
        Some(1)
    );
    assert_eq!(gbvm(&["run"], &d).status.code(), Some(1));
}

#[test]
fn run_time_alarms_exit_2_and_name_the_block() {
    let d = dir("alarm");
    std::fs::write(d.join("a.nc"), "G00 X10\n#1=SQRT[-4]\nM30\n").unwrap();
    assert_eq!(gbcc(&["a.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "a.gbc"], &d);
    assert_eq!(run.status.code(), Some(2));
    assert!(text(&run.stdout)
        .lines()
        .last()
        .unwrap_or("")
        .starts_with("ALARM CODE=5002 MSG="));
    assert!(
        text(&run.stderr).starts_with("a.nc:2:1: alarm[E5002]: "),
        "{}",
        text(&run.stderr)
    );
}

#[test]
fn damaged_and_mismatched_modules_are_refused_with_exit_1() {
    let d = dir("damaged");
    std::fs::write(d.join("p.nc"), "G00 X10\nM30\n").unwrap();
    assert_eq!(gbcc(&["p.nc"], &d).status.code(), Some(0));
    let bytes = std::fs::read(d.join("p.gbc")).unwrap();
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 0x10;
    std::fs::write(d.join("flipped.gbc"), &flipped).unwrap();
    std::fs::write(d.join("short.gbc"), &bytes[..bytes.len() - 3]).unwrap();
    for f in ["flipped.gbc", "short.gbc"] {
        let run = gbvm(&["run", f], &d);
        assert_eq!(run.status.code(), Some(1), "{f}");
        assert!(run.stdout.is_empty());
    }
    // Compiled for the reference machine, run on one with another decimal
    // point mode: the meaning would change, so it is refused.
    std::fs::write(
        d.join("inc.toml"),
        "[machine]\ndecimal_point = \"increment\"\n",
    )
    .unwrap();
    assert_eq!(
        gbvm(&["run", "p.gbc", "--machine", "inc.toml"], &d)
            .status
            .code(),
        Some(1)
    );
}

#[test]
fn max_blocks_and_repeat() {
    let d = dir("budget");
    std::fs::write(d.join("loop.nc"), "N1 G00 U1\nGOTO1\n").unwrap();
    assert_eq!(gbcc(&["loop.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "loop.gbc", "--max-blocks", "10"], &d);
    assert_eq!(run.status.code(), Some(2));
    assert!(text(&run.stdout)
        .lines()
        .last()
        .unwrap_or("")
        .starts_with("ALARM CODE=6005"));
    // The alarm says what sets the budget, for a program that is just long.
    let err = text(&run.stderr);
    assert!(
        err.contains("run.max_blocks") && err.contains("--max-blocks"),
        "{err}"
    );
    std::fs::write(d.join("m99.nc"), "G00 U2\nM99\n").unwrap();
    assert_eq!(gbcc(&["m99.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "m99.gbc", "--repeat", "3"], &d);
    assert_eq!(
        text(&run.stdout),
        "RAPID X=2 Z=0\nRAPID X=4 Z=0\nRAPID X=6 Z=0\nSTOP KIND=M99\n"
    );
}

/// E4009 stands on the cycle block (dialect.md §8.3) at run time too, and
/// its message names the profile block that turns back. #500 is vacant, so
/// #1 = 35 is known only when the program runs: N40 (line 10) runs back
/// along X from X40 to X35 under the cycle of line 6.
#[test]
fn a_profile_that_turns_back_alarms_at_the_cycle_block() {
    let d = dir("turns_back");
    let src = "O0100\nG99 M03 S500\nG00 X50 Z2\n#1=#500+35\nG71 U2 R1\n\
               G71 P10 Q20 F0.2\nN10 G00 X30\nG01 Z-10\nX40 Z-15\nX#1 Z-20\n\
               Z-30\nN20 X50\nM30\n";
    std::fs::write(d.join("t.nc"), src).unwrap();
    assert_eq!(gbcc(&["t.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "t.gbc"], &d);
    assert_eq!(run.status.code(), Some(2));
    assert_eq!(
        text(&run.stderr).lines().next().unwrap_or(""),
        "t.nc:6:1: alarm[E4009]: the G71 profile is not monotonic: \
         a profile block runs back along X from X40 to X35 (line 10)"
    );
}

/// A canned cycle counts as the moves it generates (dialect.md §7.12, "all
/// passes counted"). G90 from X50 Z2 to X40 Z-20 makes four: rapid in, cut,
/// out, rapid back (cycles.md). Blocks: G00 is 1, G90 is 2, its three
/// further moves 3–5, M30 6.
#[test]
fn a_cycle_counts_its_moves_against_the_block_budget() {
    let d = dir("budget_cycle");
    std::fs::write(d.join("c.nc"), "G00 X50 Z2\nG90 X40 Z-20 F0.2\nM30\n").unwrap();
    assert_eq!(gbcc(&["c.nc"], &d).status.code(), Some(0));
    let cycle = "RAPID X=50 Z=2\nRAPID X=40 Z=2\nFEED F=0.2 MODE=MIN\nLINE X=40 Z=-20\n\
                 LINE X=50 Z=-20\nRAPID X=50 Z=2\n";
    let run = gbvm(&["run", "c.gbc", "--max-blocks", "6"], &d);
    assert_eq!(text(&run.stdout), format!("{cycle}STOP KIND=M30\n"));
    // One block fewer: the M30 block is past the budget.
    let run = gbvm(&["run", "c.gbc", "--max-blocks", "5"], &d);
    assert_eq!(run.status.code(), Some(2));
    let out = text(&run.stdout);
    assert_eq!(
        out.strip_suffix('\n')
            .and_then(|o| o.rsplit_once('\n'))
            .map(|(a, _)| a),
        Some(cycle.trim_end())
    );
    assert!(
        text(&run.stderr).starts_with("c.nc:3:1: alarm[E6005]"),
        "{}",
        text(&run.stderr)
    );
    // Two fewer: the cycle itself does not fit and prints none of its moves.
    let run = gbvm(&["run", "c.gbc", "--max-blocks", "4"], &d);
    assert_eq!(run.status.code(), Some(2));
    let out = text(&run.stdout);
    assert!(out.starts_with("RAPID X=50 Z=2\nALARM CODE=6005 "), "{out}");
    assert!(
        text(&run.stderr).starts_with("c.nc:2:1: alarm[E6005]"),
        "{}",
        text(&run.stderr)
    );
}

#[test]
fn defines_and_expansion() {
    let d = dir("define");
    std::fs::write(d.join("d.nc"), "G00 X#100 Z[#100/2]\nM30\n").unwrap();
    assert_eq!(gbcc(&["d.nc", "-D", "#100=8"], &d).status.code(), Some(0));
    assert_eq!(
        text(&gbvm(&["run", "d.gbc"], &d).stdout),
        "RAPID X=8 Z=4\nSTOP KIND=M30\n"
    );
    let e = gbcc(&["d.nc", "-E", "-D", "#100=8"], &d);
    assert_eq!(e.status.code(), Some(0));
    assert!(
        text(&e.stdout).starts_with("G00 X8 Z4 (LINE 1)\n"),
        "{}",
        text(&e.stdout)
    );
}

#[test]
fn gbcc_predicts_the_run_with_the_vars_file_of_gbvm() {
    // The same file for both: with #500 = 0 the run divides by zero on
    // line 2, which gbcc tells and gbvm then stops at; a malformed file
    // is refused naming its line.
    let d = dir("vars");
    std::fs::write(
        d.join("v.nc"),
        "G98 G00 X50 Z2\n#1=60/#500\nG01 X#1 Z-5 F100\nM30\n",
    )
    .unwrap();
    std::fs::write(d.join("vars.txt"), "#500=0\n").unwrap();
    let plain = gbcc(&["v.nc"], &d);
    assert_eq!(plain.status.code(), Some(0));
    assert!(
        !text(&plain.stderr).contains("W124"),
        "{}",
        text(&plain.stderr)
    );
    let told = gbcc(&["v.nc", "--vars", "vars.txt"], &d);
    assert_eq!(told.status.code(), Some(0));
    assert!(
        text(&told.stderr).starts_with("v.nc:2:1: warning[W124]: the run stops here with E5001"),
        "{}",
        text(&told.stderr)
    );
    let run = gbvm(&["run", "v.gbc", "--vars", "vars.txt"], &d);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        text(&run.stderr).contains("v.nc:2:1: alarm[E5001]"),
        "{}",
        text(&run.stderr)
    );
    // -E runs the program from the same values.
    std::fs::write(d.join("ok.txt"), "#500=2\n").unwrap();
    let e = gbcc(&["v.nc", "-E", "--vars", "ok.txt"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    assert!(text(&e.stdout).contains("X30 Z-5"), "{}", text(&e.stdout));
    std::fs::write(d.join("bad.txt"), "#500=0\n#1000=1\n").unwrap();
    let bad = gbcc(&["v.nc", "--vars", "bad.txt"], &d);
    assert_eq!(bad.status.code(), Some(1));
    assert!(
        text(&bad.stderr).contains("bad.txt:2: expected"),
        "{}",
        text(&bad.stderr)
    );
}

#[test]
fn the_expanded_program_marks_the_blocks_computed_as_it_ran() {
    let d = dir("dynamic");
    // Line 5's words change with #1 (computed in the loop): DYNAMIC. #5 is
    // 7 on every path, so pass fold made line 6 a literal block: not
    // marked; nor are the literal blocks.
    let src = "G98 G00 X50 Z2\n#1=0\n#5=7\nWHILE[#1LT2]DO1\nG01 X[40-#1] Z-#1 F100\nG01 X#5 Z-9\n#1=#1+1\nEND1\nM30\n";
    std::fs::write(d.join("e.nc"), src).unwrap();
    let e = gbcc(&["e.nc", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    assert_eq!(
        text(&e.stdout),
        "G00 X50 Z2 (LINE 1)\nG98 F100 (LINE 5, DYNAMIC)\nG01 X40 Z0\nG01 X7 Z-9 (LINE 6)\n\
         G01 X39 Z-1 (LINE 5, DYNAMIC)\nG01 X7 Z-9 (LINE 6)\nM30 (LINE 9)\n"
    );
}

#[test]
fn the_expanded_program_keeps_the_number_of_a_message() {
    // The canon prints a message's text only; -E writes the number the
    // program gave #3006 (made whole), which a host sees.
    let d = dir("message");
    let src = "G00 X50 Z2\n#3006=7 (SEVEN)\n#3006=2.5 (HALF)\nM30\n";
    std::fs::write(d.join("m.nc"), src).unwrap();
    let e = gbcc(&["m.nc", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    let out = text(&e.stdout);
    let messages: Vec<&str> = out.lines().filter(|l| l.starts_with('#')).collect();
    assert_eq!(messages, ["#3006=7 (SEVEN)", "#3006=3 (HALF)"], "{out}");
}

#[test]
fn a_message_and_a_work_offset_write_are_listed_under_their_own_lines() {
    // A statement between blocks prints under its line, not the next
    // block's: line 3's message waits behind line 2's chamfer, line 5's
    // #5221 moves the work zero (a G50 in the listing).
    let d = dir("statement");
    let src =
        "G00 X50 Z2\nG01 X40 Z0 F100 ,C1\n#3006=1 (CHECK)\nG01 Z-20\n#5221=10\nG00 X60\nM30\n";
    std::fs::write(d.join("s.nc"), src).unwrap();
    let e = gbcc(&["s.nc", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    let out = text(&e.stdout);
    let after = |line: &str| {
        let at = out.lines().position(|l| l == line);
        at.and_then(|i| out.lines().nth(i + 1)).unwrap_or_default()
    };
    assert_eq!(after("(LINE 3)"), "#3006=1 (CHECK)", "{out}");
    assert_eq!(
        after("G01 X40 Z-20 (LINE 4)"),
        "G50 X30 Z-20 (LINE 5)",
        "{out}"
    );
    assert!(out.contains("\nG00 X60 Z-20 (LINE 6)\n"), "{out}");
}

#[test]
fn a_move_that_waited_for_the_next_block_keeps_its_line() {
    // Under G42 each element waits for the next block (where it ends
    // depends on it), and line 5's chamfer for line 6: printed as the next
    // block runs, each still names its own line (they named the next).
    let d = dir("waited");
    std::fs::write(
        d.join("t.toml"),
        "[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n",
    )
    .unwrap();
    let src = "G98 G00 X20 Z2 T0101\nG42 G01 Z0 F300\nG01 Z-10\nX30 Z-15\nZ-25 L2\nX40\nG40 G00 X50 Z5\nM30\n";
    std::fs::write(d.join("w.nc"), src).unwrap();
    let e = gbcc(&["w.nc", "--machine", "t.toml", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    let lines: Vec<(String, String)> = text(&e.stdout)
        .lines()
        .filter_map(|l| l.split_once(" (LINE "))
        .map(|(code, line)| (code.to_string(), line.trim_end_matches(')').to_string()))
        .collect();
    let starts: Vec<(&str, &str)> = lines.iter().map(|(c, l)| (&c[..3], l.as_str())).collect();
    // (Each comment marks the first block of its line; the start-up to
    // Z−0.8 is line 2's, the corner arc after the slope line 5's.)
    assert_eq!(
        starts,
        [
            ("T01", "1"),
            ("G98", "2"),
            ("G01", "3"),
            ("G01", "4"),
            ("G03", "5"),
            ("G01", "6"),
            ("G00", "7"),
            ("M30", "8")
        ]
    );
}

#[test]
fn a_machine_with_a_c_axis() {
    let d = dir("caxis");
    std::fs::write(d.join("c.toml"), "[axes.c]\nenabled = true\n").unwrap();
    // Two holes 90° apart from C0 (H is applied per repeat), then a C-only
    // feed by H-22.5: 180 − 22.5 = 157.5.
    let src = "G00 X20 Z3 C0\nG83 X20 Z-5 H90 K2 F50\nG80\nG01 H-22.5 F200\nM30\n";
    std::fs::write(d.join("holes.nc"), src).unwrap();
    let out = gbcc(&["holes.nc", "--machine", "c.toml"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let run = gbvm(&["run", "holes.gbc", "--machine", "c.toml"], &d);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let hole =
        |c: &str| format!("RAPID X=20 Z=3 C={c}\nLINE X=20 Z=-5 C={c}\nRAPID X=20 Z=3 C={c}\n");
    let want = format!(
        "RAPID X=20 Z=3 C=0\n{}{}FEED F=200 MODE=MIN\nLINE X=20 Z=3 C=157.5\nSTOP KIND=M30\n",
        hole("90").replacen('\n', "\nFEED F=50 MODE=MIN\n", 1),
        hole("180")
    );
    assert_eq!(text(&run.stdout), want);
    // The trace has its c column; the last period stands at C157.5.
    let trace = gbvm(
        &["run", "holes.gbc", "--machine", "c.toml", "--emit", "trace"],
        &d,
    );
    let t = text(&trace.stdout);
    assert!(
        t.starts_with("time_s,x,z,c,spindle_rpm,feed,line,motion,tool,file\n"),
        "{t:.80}"
    );
    let last = t.lines().last().unwrap_or_default();
    assert_eq!(last.split(',').nth(3), Some("157.500000"), "{last}");
    let json = gbvm(
        &[
            "run",
            "holes.gbc",
            "--machine",
            "c.toml",
            "--emit",
            "trace",
            "--format",
            "json",
        ],
        &d,
    );
    assert!(text(&json.stdout).contains(",\"c\":157.500000,"));
    // The reference machine has no C axis: E2005 at compile time.
    let out = gbcc(&["holes.nc", "-o", "ref.gbc"], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("E2005"), "{}", text(&out.stderr));
}

#[test]
fn polar_and_cylindrical_interpolation_expand_to_the_same_canon() {
    let d = dir("polar");
    std::fs::write(d.join("c.toml"), "[axes.c]\nenabled = true\n").unwrap();
    // A polar contour with a G16 line and both arc forms, then a groove
    // on a cylinder of radius 20 with an arc longer than a half circle
    // (R-20, which the expansion must write negative again).
    // Z plunges and X feeds in alone inside the planes; after each plane
    // an arc whose centre the expansion writes as I/K from where the
    // plane left the tool.
    let src = "G98 G00 X40 Z-2 C0\nG12.1\nG01 X20 C10 F300\nG01 Z-4 F50\nG03 X-20 C10 R10\nG16\nG01 X10 C180\nG15\nG03 X20 C0 I10 J0\nG00 W2\nG13.1\nG02 X30 Z-7 R5\nG00 C0\nG7.1 C20.\nG01 Z-10 C90 F200\nG01 U-4 F20\nG03 Z-20 C0 R-20\nG00 X40\nG7.1 C0\nG02 X40 Z-25 R5\nM30\n";
    std::fs::write(d.join("p.nc"), src).unwrap();
    let canon = |file: &str| {
        let out = gbcc(&[file, "--machine", "c.toml", "-o", "p.gbc"], &d);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        let run = gbvm(&["run", "p.gbc", "--machine", "c.toml"], &d);
        assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
        text(&run.stdout)
    };
    let first = canon("p.nc");
    assert!(first.contains("POLAR MODE=OFF X=20 C=360\n"), "{first}");
    assert!(first.contains("\nLINE Z=-4\n"), "{first}");
    assert!(first.contains("\nLINE X=26\n"), "{first}");
    let e = gbcc(&["p.nc", "--machine", "c.toml", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    let expanded = text(&e.stdout);
    assert!(expanded.contains("G12.1"), "{expanded}");
    std::fs::write(d.join("e.nc"), &expanded).unwrap();
    assert_eq!(canon("e.nc"), first, "{expanded}");
    // Ramps and conics: Z along a line of the polar plane, an ellipse and
    // a parabola there, X along a line of the cylinder and a parabola on
    // it; then an ellipse and a parabola in the ZX plane (which `-E` once
    // wrote as comments), the arc after them taking I/K from their ends.
    let src = "G98 G00 X40 Z2 C0\nG12.1\nG01 X20 C10 Z-2 F300\nG6.3 X-20 C10 A20 B10 Q0\n\
               G7.2 X-40 C-10 P8000 Q90000\nG00 X40 C0 Z2\nG13.1\nG00 C0\nG7.1 C20.\n\
               G01 Z-10 C90 X36 F200\nG7.3 Z-20 C0 P5000 Q0\nG00 X40\nG7.1 C0\n\
               G01 X20 Z-30\nG6.2 X40 Z-40 A20 B10 Q0\nG7.3 X30 Z-50 P4000 Q0\nG02 X40 Z-55 R5\nM30\n";
    std::fs::write(d.join("p.nc"), src).unwrap();
    let first = canon("p.nc");
    for line in [
        "LINE X=20 C=10 Z=-2",
        "ELLIPSE DIR=CCW X=-20 C=10 A=20 B=10 Q=0",
        "PARABOLA DIR=CW X=-40 C=-10 P=8 Q=90",
        "LINE Z=-10 C=90 X=36",
        "ELLIPSE DIR=CW X=40 Z=-40 A=20 B=10 Q=0",
    ] {
        assert!(first.contains(&format!("{line}\n")), "{line}\n{first}");
    }
    let e = gbcc(&["p.nc", "--machine", "c.toml", "-E"], &d);
    assert_eq!(e.status.code(), Some(0), "{}", text(&e.stderr));
    let expanded = text(&e.stdout);
    assert!(!expanded.contains("(ELLIPSE"), "{expanded}");
    std::fs::write(d.join("e.nc"), &expanded).unwrap();
    assert_eq!(canon("e.nc"), first, "{expanded}");
}

#[test]
fn a_polar_alarm_at_run_time_names_its_line() {
    let d = dir("polar_alarm");
    std::fs::write(d.join("c.toml"), "[axes.c]\nenabled = true\n").unwrap();
    // #500 is vacant: C#1 is known only when the program runs, so the
    // check that G12.1 finds C at 0 is the VM's (E4033, dialect.md §4.6).
    let src = "G00 X40 Z0\n#1 = #500 + 30\nG00 C#1\nG12.1\nM30\n";
    std::fs::write(d.join("r.nc"), src).unwrap();
    let out = gbcc(&["r.nc", "--machine", "c.toml"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let run = gbvm(&["run", "r.gbc", "--machine", "c.toml"], &d);
    assert_eq!(run.status.code(), Some(2));
    let canon = text(&run.stdout);
    assert!(
        canon.ends_with("RAPID X=40 Z=0 C=30\nALARM CODE=4033 MSG=\"G12.1 polar interpolation starts with C at 0 degrees, C is at 30.0000: turn it to 0 first (G00 C0)\"\n"),
        "{canon}"
    );
    assert!(
        text(&run.stderr).starts_with("r.nc:4:1: alarm[E4033]"),
        "{}",
        text(&run.stderr)
    );
}
