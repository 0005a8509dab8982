//! How far the compile-time dry run goes: each block's first pass is
//! free, so a straight program is dry-run to its end however long; the
//! passes beyond (loop rounds, repeated calls, cycle legs) may add 200 000
//! blocks, and where they run out the compiler says so (W120). It follows
//! M98, M-code calls (M9000–M9999) and G65 into the programs they call.

use compiler::{compile, Options};

mod common;
use common::{codes, messages};

/// The whole-file path (one chunk as long as any program).
fn whole_file() -> Options {
    Options {
        chunk_bytes: usize::MAX,
        ..Options::default()
    }
}

/// A rapid to X50 Z2 on line 1, then `n` feed moves on lines 2…n + 1:
/// move `i` (from 1) to X = i mod 50 + 0.5, Z = -(i mod 70 + 0.25).
fn moves(n: u32) -> String {
    let mut src = String::from("G98 G00 X50 Z2\n");
    for i in 1..=n {
        src.push_str(&format!("G01 X{}.5 Z-{}.25 F100\n", i % 50, i % 70));
    }
    src
}

#[test]
fn a_straight_program_is_dry_run_to_its_end() {
    // 250 000 moves, then an arc of R1 from X0.5 Z-30.25 (the last move,
    // i = 250 000: 250 000 mod 50 = 0, mod 70 = 30) to X90 Z-5, whose end
    // is √(44.75² + 25.25²) = 51.38 mm away: E4001 at compile time, on
    // line 250 002, however far past 200 000 blocks it stands.
    let mut src = moves(250_000);
    src.push_str("G02 X90 Z-5 R1\nM30\n");
    let expected = [("E4001", 250_002)];
    assert_eq!(codes(&src, &Options::default()), expected);
    assert_eq!(codes(&src, &whole_file()), expected);
}

/// A main program that calls O0002 `l` times; O0002 is 39 moves and its
/// M99, 40 blocks, on lines 5 to 44.
fn repeated_call(l: u32) -> String {
    let mut src = format!("O0001\nM98 P0002 L{l}\nM30\nO0002\n");
    for i in 0..39 {
        src.push_str(if i % 2 == 0 {
            "G01 U1 F100\n"
        } else {
            "G01 U-1\n"
        });
    }
    src.push_str("M99\n");
    src
}

#[test]
fn a_repeated_call_runs_its_first_pass_free_and_200_000_blocks_more() {
    // Pass 1 of O0002 is its blocks' first; passes 2…L run 40 blocks
    // again each. L5001: 5 000 × 40 = 200 000 again, all of the budget.
    assert_eq!(codes(&repeated_call(5001), &Options::default()), []);
    // L5002: the 200 001st block run again is the first of pass 5 002,
    // on line 5, where the run stops.
    assert_eq!(
        codes(&repeated_call(5002), &Options::default()),
        [("W120", 5)]
    );
    assert_eq!(
        codes(&repeated_call(9999), &Options::default()),
        [("W120", 5)]
    );
}

#[test]
fn a_program_that_never_ends_is_told_once() {
    // The profile (N10–N30) stands before its G71: after the cycle the
    // run goes on after N30 and comes back to the G71, for ever.
    let src = "G98 G00 X60 Z2\nN10 G00 X40\nN20 G01 Z-30 F100\nN30 X60\nG00 X60 Z2\n\
               G71 U2 R1\nG71 P10 Q30 U0.5 W0.1 F150\nM30\n";
    let found = codes(src, &Options::default());
    assert_eq!(found.len(), 1, "{found:?}");
    let (code, line) = found[0];
    assert_eq!(code, "W120");
    // (Which block of the loop spends the budget depends on the cycle's
    // legs; it is one of them.)
    assert!((5..=7).contains(&line), "{found:?}");
    // With the cycle before its profile the run ends at M30.
    let right = "G98 G00 X60 Z2\nG71 U2 R1\nG71 P10 Q30 U0.5 W0.1 F150\nN10 G00 X40\n\
                 N20 G01 Z-30 F100\nN30 X60\nM30\n";
    assert_eq!(codes(right, &Options::default()), []);
}

#[test]
fn the_dry_run_follows_g65_and_m_code_calls() {
    // G02 from X50 Z2 to X90 Z-5 (radii 25 → 45, 7 along Z) with R1:
    // the end is √(20² + 7²) = 21.19 mm away, more than 2R. In a program
    // called by G65 or by M9001: E4001 at compile time, in the callee.
    let g65 = "G98 G00 X50 Z2\nG65 P9001 A1\nG00 X60\nM30\nO9001\nG02 X90 Z-5 R1\nM99\n";
    let found = messages(g65, &Options::default());
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].0, found[0].1), ("E4001", 6));
    assert!(found[0].2.contains("21.1896 mm away"), "{found:?}");
    let m9001 = "G98 G00 X50 Z2\nM9001\nM30\nO9001\nG02 X90 Z-5 R1\nM99\n";
    assert_eq!(codes(m9001, &Options::default()), [("E4001", 5)]);
    // G65's L: pass 1 goes U30 to X80 Z2, then arcs to X90 Z-5 (radii
    // 40 → 45, 7 along Z: √74 = 8.60 mm, within 2R = 14); pass 2 goes
    // U30 to X120 Z-5 and arcs back to X90 Z-5, 15 mm away: E4001 then.
    let l2 = "G98 G00 X50 Z2\nG65 P9001 L2\nM30\nO9001\nG01 U30 F100\nG02 X90 Z-5 R7\nM99\n";
    let found = messages(l2, &Options::default());
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].0, found[0].1), ("E4001", 6));
    assert!(found[0].2.contains("15.0000 mm away"), "{found:?}");
    assert_eq!(codes(&l2.replace("L2", "L1"), &Options::default()), []);
}

/// The options of a machine whose run may execute `max` blocks, the
/// program compiled a chunk of 4 KiB at a time or whole.
fn budget(max: u64, chunked: bool) -> Options {
    let mut opts = Options::default();
    opts.machine.run.max_blocks = max;
    opts.chunk_bytes = if chunked { 4096 } else { usize::MAX };
    opts
}

/// The (code, line) of the alarm a run on the VM stops with, under a
/// budget of `max` blocks (`None` when it ends without). The program
/// must compile.
fn vm_alarm(src: &str, max: u64) -> Option<(u32, u32)> {
    let opts = budget(max, false);
    let module = compile("d.nc", src.as_bytes(), &opts).module;
    let mut vm = vm::Vm::new(module.expect("compiles"), opts.machine.clone());
    vm.max_blocks = max;
    let mut events: Vec<nc::Event> = Vec::new();
    match vm.run(&mut events) {
        vm::Status::Alarm(a) => Some((a.code, a.line)),
        _ => None,
    }
}

/// The line of the alarm E6005 a run on the VM stops with, under a
/// budget of `max` blocks (`None` when it ends without).
fn vm_budget_line(src: &str, max: u64) -> Option<u32> {
    vm_alarm(src, max).and_then(|(code, line)| (code == 6005).then_some(line))
}

#[test]
fn a_run_longer_than_the_block_budget_is_told_where_it_stops() {
    // A rapid on line 1, 1 500 moves on lines 2…1501, M30 on line 1502:
    // 1 502 blocks. Under a budget of 1 000 the 1 001st block, on line
    // 1001, is the first past it; the VM stops there too.
    let mut src = moves(1500);
    src.push_str("M30\n");
    for chunked in [true, false] {
        assert_eq!(codes(&src, &budget(1000, chunked)), [("W122", 1001)]);
        // The whole program fits in 1 502; with 1 501 its M30 is past it.
        assert_eq!(codes(&src, &budget(1502, chunked)), []);
        assert_eq!(codes(&src, &budget(1501, chunked)), [("W122", 1502)]);
    }
    assert_eq!(vm_budget_line(&src, 1000), Some(1001));
    assert_eq!(vm_budget_line(&src, 1501), Some(1502));
    assert_eq!(vm_budget_line(&src, 1502), None);
    // The help says how large a budget the program needs.
    let c = compile("d.nc", src.as_bytes(), &budget(1000, false));
    let help = c.diags[0].1.help.clone().unwrap_or_default();
    assert!(help.contains("N at least 1502"), "{help}");
}

#[test]
fn a_cycle_counts_as_its_legs_against_the_block_budget() {
    // G71 roughs X60 down to X20 at 1 mm a side: about 20 passes of
    // several legs each, more than a budget of 10 blocks holds, so the
    // run stops at the cycle's block, line 3, in the VM as in the
    // dry run; with the default budget it does not.
    let src = "G98 G00 X60 Z2\nG71 U1 R0.5\nG71 P10 Q30 U0.5 W0.1 F150\nN10 G00 X20\n\
               N20 G01 Z-30 F100\nN30 X60\nG00 X100 Z50\nM30\n";
    assert_eq!(codes(src, &budget(10, false)), [("W122", 3)]);
    assert_eq!(vm_budget_line(src, 10), Some(3));
    assert_eq!(codes(src, &Options::default()), []);
}

#[test]
fn the_dry_run_returns_where_m99_p_says() {
    // O0002 feeds to Z-10 and returns to the main program's N100, past
    // line 3. From X50 Z-10, line 3's arc to X90 Z-5 would span
    // √(20² + 5²) = 20.6 mm with R1: never run, so no error; the VM runs
    // the program to its end without an alarm.
    let skipped = "G98 G00 X50 Z2\nM98 P0002\nG02 X90 Z-5 R1\nN100 G01 X60 F100\nM30\n\
                   O0002\nG01 Z-10 F100\nM99 P100\n";
    assert_eq!(codes(skipped, &Options::default()), []);
    let default_budget = Options::default().machine.run.max_blocks;
    assert_eq!(vm_alarm(skipped, default_budget), None);
    // The same arc at N100, where the run goes on: E4001 on line 4, found
    // at compile time (the dry run used to end at the M99 P).
    let run = "G98 G00 X50 Z2\nM98 P0002\nG00 X50\nN100 G02 X90 Z-5 R1\nM30\n\
               O0002\nG01 Z-10 F100\nM99 P100\n";
    assert_eq!(codes(run, &Options::default()), [("E4001", 4)]);
    // With L the passes before the last run O0002 again: W-10 once
    // leaves Z-8, where an arc of R10.5 to X90 Z-5 spans √(20² + 3²) =
    // 20.22 mm ≤ 21; twice leaves Z-18, √(20² + 13²) = 23.85 mm > 21.
    let passes = |l: u32| {
        format!(
            "G98 G00 X50 Z2\nM98 P0002 L{l}\nG00 X50\nN100 G02 X90 Z-5 R10.5\nM30\n\
             O0002\nG01 W-10 F100\nM99 P100\n"
        )
    };
    assert_eq!(codes(&passes(1), &Options::default()), []);
    assert_eq!(codes(&passes(2), &Options::default()), [("E4001", 4)]);
    // An M99 P back to a block before the call loops: each round runs
    // lines 2, 3, 6 and 7 again, 4 blocks, so 50 000 rounds spend the
    // 200 000 and the next round's first block, line 2, stops the run.
    let looping = "G98\nN10 G00 U1\nM98 P2\nM30\nO0002\nG00 W1\nM99 P10\n";
    assert_eq!(codes(looping, &Options::default()), [("W120", 2)]);
    // No block N200 to return to: the run stops with E6002 at the M99,
    // line 8, and the dry run warns there (W123).
    let missing = run.replace("P100\n", "P200\n");
    let found = messages(&missing, &Options::default());
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].0, found[0].1), ("W123", 8));
    assert!(
        found[0]
            .2
            .contains("N200 of the calling program, the main program"),
        "{found:?}"
    );
    assert_eq!(vm_alarm(&missing, default_budget), Some((6002, 8)));
}
