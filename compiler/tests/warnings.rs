//! The warnings of dialect.md §8 that the compiler reports from a block's
//! words (W106, W109), from the call graph (W115, W121) and from the dry run of
//! a static program (W105, W107, W108, W110, W111, W112, W114, W125): each fires
//! where the section of the code says and not on the corrected program.
//! The dry run's warnings hold for the program made dynamic too, where
//! the compile-time run in the VM finds them (`predict`). Every expected
//! (code, line) pair is read off the program by hand.

use compiler::{compile, Options};

/// (code, line) of every warning of the W105–W115 family, in order.
/// Each time, the same program made dynamic by a macro statement at its
/// end must get the same warnings of the blocks it runs ([`ran`]).
/// (W125, a feed per minute below 1, is left out: many of these
/// programs feed per revolution in G98 for brevity; `w125_*` tests it.)
fn warnings(src: &str) -> Vec<(&'static str, usize)> {
    let static_run = of(src);
    let dynamic = of(&format!("{src}#1=1\n"));
    assert_eq!(ran(&dynamic), ran(&static_run), "made dynamic: {src}");
    static_run.into_iter().filter(|w| w.0 != "W125").collect()
}

fn of(src: &str) -> Vec<(&'static str, usize)> {
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    c.diags
        .iter()
        .filter(|(_, d)| !matches!(d.code, "W101" | "W104" | "W113" | "W116" | "W117"))
        .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
        .collect()
}

/// The warnings of the blocks a run executes: a static program's dry run
/// gives them, and a program with macros the compile-time run in the VM
/// (not W107, which the VM's run tells as its E7001 alarm, W124).
fn ran(found: &[(&'static str, usize)]) -> Vec<(&'static str, usize)> {
    let ran = [
        "W105", "W108", "W110", "W111", "W112", "W114", "W118", "W125", "W126",
    ];
    found
        .iter()
        .copied()
        .filter(|(c, _)| ran.contains(c))
        .collect()
}

#[test]
fn w105_inch_lengths_without_a_point_in_calculator_mode() {
    // §1.9: G20, calculator mode (the reference), |value| ≥ 100, no point.
    // U630 is the roughing depth of the first G71 block; R5 is below 100.
    let src = "G20\nG00 X2. Z0.1\nG71 U630 R5\nG71 P10 Q20 U0.01 W0.005 F0.01\nN10 G00 X1.\nG01 Z-1.\nN20 X2.\nM30\n";
    assert_eq!(warnings(src), [("W105", 3)]);
    // With the point, or in G21, nothing.
    assert_eq!(warnings(&src.replace("U630", "U0.063")), []);
    assert_eq!(warnings("G21\nG00 X150 Z100\nM30\n"), []);
    // G04 X is seconds, not a length.
    assert_eq!(warnings("G20\nG04 X150\nM30\n"), []);
}

#[test]
fn a_warning_is_said_once_however_often_the_dry_run_passes_there() {
    // The profile stands before its G71: after the cycle the run goes on
    // after N110, meets the G71 again, and loops until the dry run's step
    // budget (a fuzzed program; it repeated each W105 5 127 times). U1000,
    // R500 and U100 are inch lengths without a point: once each. Where the
    // run stops, W120 (once too), at a block of the loop.
    let src = "G18 G20 G40 G80 G90 G99\nN100 G00 X1.5513\nN103 G01 Z-.050 F.008\nN110 G00 X2.625\n\
               G00 X5. Z7.5\nG71 U1000 R500\nG71 P100 Q110 U100 W70 S460 F.008\n";
    let (stop, found): (Vec<_>, Vec<_>) = warnings(src).into_iter().partition(|w| w.0 == "W120");
    assert_eq!(found, [("W105", 6), ("W105", 6), ("W105", 7)]);
    assert!(matches!(stop[..], [("W120", 5..=7)]), "{stop:?}");
}

#[test]
fn w106_two_codes_of_one_group() {
    // G00 and G01 are both group 01 (§3): the warning at the second.
    assert_eq!(warnings("G00 G01 X20 F0.1\nM30\n"), [("W106", 1)]);
    // G98 (group 03) and G01 (group 01): different groups.
    assert_eq!(warnings("G98 G01 X20 F100\nM30\n"), []);
}

#[test]
fn w107_a_roughing_cycle_at_f0_as_in_seed_004() {
    // Seed 004's G71 example: the F20 stands in the profile (N60), used
    // by G70 only; the roughing of N40 runs at the modal F, which is 0.
    let src = "O0004\nG00 X200 Z262\nN30 G71 U5 R1\nN40 G71 P50 Q80 U0.6 W0.2\nN50 G00 X160\nN60 G01 Z260 F20\nN70 G01 X195 Z210\nN80 G01 Z200\nM30\n";
    assert_eq!(warnings(src), [("W107", 4)]);
    // An F on the cycle block: none.
    assert_eq!(warnings(&src.replace("W0.2\n", "W0.2 F0.3\n")), []);
    // Any feed move: G01 with no F since power-on.
    assert_eq!(warnings("G00 X20 Z2\nG01 X10\nM30\n"), [("W107", 2)]);
    // The run stops there (E7001): a later alarm is never reached, and
    // no W124 names it (the `compiler` fuzz target: T-16, E5010 when
    // computed; written, it is E1010 wherever it stands).
    let later = "#1=-16\nG00 X20 Z2\nG01 X10\nT#1\nM30\n";
    // (With a macro the program is not static: the run's E7001 is W124.)
    assert_eq!(of(later), [("W124", 3)]);
    // Reached, the folded T-16 always fails there: W116 (which `of`
    // leaves out) and no W124.
    let every_code = |src: String| {
        let c = compile("w.nc", src.as_bytes(), &Options::default());
        c.diags.iter().map(|(_, d)| d.code).collect::<Vec<_>>()
    };
    assert_eq!(
        every_code(later.replace("G01 X10", "G01 X10 F100")),
        ["W116"]
    );
    assert_eq!(every_code(later.replace("T#1", "T-16")), ["E1010"]);
}

#[test]
fn w108_an_arc_or_conic_that_ends_where_it_starts() {
    // §4.1 rule 3: G02 with R from X20 Z0 to X20 Z0.
    assert_eq!(
        warnings("G98 F100\nG00 X20 Z0\nG02 X20 Z0 R5\nM30\n"),
        [("W108", 3)]
    );
    // An ellipse with X and Z omitted (end = start).
    assert_eq!(
        warnings("G98 F100\nG00 X20 Z0\nG6.2 A10 B5\nM30\n"),
        [("W108", 3)]
    );
    // A full circle by I/K is a move.
    assert_eq!(warnings("G98 F100\nG00 X20 Z0\nG02 I-5\nM30\n"), []);
}

#[test]
fn w109_g28_without_axes() {
    assert_eq!(warnings("G28\nM30\n"), [("W109", 1)]);
    assert_eq!(warnings("G28 U0 W0\nM30\n"), []);
}

#[test]
fn w110_a_thread_in_constant_surface_speed() {
    // §4.10: G92 in G96.
    assert_eq!(
        warnings("G96 S150 M03\nG00 X25 Z5\nG92 X19 Z-20 F1.5\nG00 X30\nM30\n"),
        [("W110", 3)]
    );
    assert_eq!(
        warnings("G97 S800 M03\nG00 X25 Z5\nG92 X19 Z-20 F1.5\nG00 X30\nM30\n"),
        []
    );
}

#[test]
fn w111_a_feed_mode_change_without_f_at_the_change() {
    // §4.10: F200 mm/min would be read as 200 mm/rev after G99.
    assert_eq!(
        warnings("G98 G01 X20 F200\nG99\nM03 S500\nG01 Z-10\nM30\n"),
        [("W111", 2)]
    );
    // A new F before the next feed move: nothing.
    assert_eq!(warnings("G98 G01 X20 F200\nG99\nG01 Z-10 F0.2\nM30\n"), []);
    // Only rapids follow: the old F is never used.
    assert_eq!(warnings("G98 G01 X20 F200\nG99\nG00 Z10\nM30\n"), []);
    // G70 under the new G99: its profile's first feed (N2) brings F0.1,
    // so F200 is never read in mm/rev.
    let g70 = "G98 G00 X50 Z2 F200\nG99 G70 P1 Q2\nM30\nN1 G00 X40\nN2 G01 Z-10 F0.1\n";
    assert_eq!(warnings(g70), []);
    // The message names the F in force at the change.
    let src = "G98 G01 X20 F200\nG99\nM03 S500\nG01 Z-10\nM30\n";
    let w = compile("w.nc", src.as_bytes(), &Options::default()).render();
    assert!(w.contains("the F200 given in mm/min"), "{w}");
}

#[test]
fn w112_a_corner_word_ignored() {
    // §5.1: the next move goes the same way (Z-10 then Z-20).
    assert_eq!(
        warnings("G98 F100\nG01 Z-10 ,C1\nG01 Z-20\nM30\n"),
        [("W112", 2)]
    );
    // The next move is a G00.
    assert_eq!(
        warnings("G98 F100\nG01 Z-10 L1\nG00 X30\nM30\n"),
        [("W112", 2)]
    );
    // A real corner: the chamfer is made.
    assert_eq!(warnings("G98 F100\nG01 Z-10 ,C1\nG01 X30\nM30\n"), []);
    // The M30 block prints the waiting element, without its corner.
    assert_eq!(warnings("G98 F100\nG01 Z-10 ,C1\nM30\n"), [("W112", 2)]);
    // The second block of a line (after `;`) is found at its column.
    assert_eq!(
        warnings("G98 F100;G01 Z-10 ,C1\nG01 Z-20\nM30\n"),
        [("W112", 1)]
    );
    // §5.1: a corner word on a profile's nf block (line 7) is ignored, for
    // G71 and G70 alike (told once); one before the nf block is made.
    let profile = |nf: &str| {
        format!("G99 S500 M03\nG00 X50 Z2\nG71 U5 R0.5\nG71 P10 Q20 F0.2\nN10 G00 X30\nG01 Z-20 ,C1\nN20 X50{nf}\nG70 P10 Q20\nM30\n")
    };
    assert_eq!(warnings(&profile(" ,C1")), [("W112", 7)]);
    assert_eq!(warnings(&profile(" L1")), [("W112", 7)]);
    assert_eq!(warnings(&profile("")), []);
}

#[test]
fn w114_s_above_the_spindle_maximum() {
    // The reference spindle's maximum is 3000 rpm (machine.md).
    assert_eq!(warnings("G97 S99999 M03\nM30\n"), [("W114", 1)]);
    assert_eq!(warnings("G97 S2000 M03\nM30\n"), []);
    // In G96 S is a surface speed, and G50 S is the limit itself.
    assert_eq!(warnings("G50 S5000\nG96 S4000 M03\nM30\n"), []);
}

#[test]
fn w115_unconditional_recursion() {
    // The example: M98 P0004 inside O0004.
    let src = "M98 P0004\nM30\nO0004\nG00 U1\nM98 P0004\nM99\n";
    assert_eq!(warnings(src), [("W115", 5)]);
    // Through two programs: both calls lead back.
    let src = "M98 P1\nM30\nO0001\nM98 P2\nM99\nO0002\nM98 P1\nM99\n";
    assert_eq!(warnings(src), [("W115", 4), ("W115", 7)]);
    // Behind a condition: no warning.
    let src = "M98 P0004\nM30\nO0004\n#1=#1+1\nIF [#1 GT 3] GOTO 9\nM98 P0004\nN9 M99\n";
    assert_eq!(warnings(src), []);
}

/// A main program calling O0001, each O000n calling O000(n+1) with
/// `call` (`M98 P` or `G65 P`) down to O000`depth`, which moves; `guard`
/// stands before the call of O0004.
fn nested(call: &str, depth: u32, guard: &str) -> String {
    let mut src = format!("{call}1\nM30\n");
    for n in 1..depth {
        let guard = if n == 4 { guard } else { "" };
        src.push_str(&format!("O{n:04}\n{guard}{call}{}\nM99\n", n + 1));
    }
    src.push_str(&format!("O{depth:04}\nG01 U1 F100\nM99\n"));
    src
}

/// The line and code of the alarm a run of `src` ends with.
fn alarm_of(src: &str) -> Option<(u32, u32)> {
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    let module = c.module?;
    let mut vm = vm::Vm::new(module, Options::default().machine);
    let mut events: Vec<nc::Event> = Vec::new();
    match vm.run(&mut events) {
        vm::Status::Alarm(a) => Some((a.code, a.line)),
        _ => None,
    }
}

#[test]
fn w121_calls_that_always_nest_too_deep() {
    // §7.12: four subprogram levels. The main program (lines 1–2), then
    // O000n on lines 3n to 3n + 2, its call on line 3n + 1: O0005's call
    // by O0004 (line 13) opens a fifth level.
    let five = nested("M98 P", 5, "");
    assert_eq!(warnings(&five), [("W121", 13)]);
    // The run stops there.
    assert_eq!(alarm_of(&five), Some((6004, 13)));
    // Four levels: none, and the run ends at M30.
    assert_eq!(warnings(&nested("M98 P", 4, "")), []);
    assert_eq!(alarm_of(&nested("M98 P", 4, "")), None);
    // Four macro levels, G65 each (the same lines): the fifth too deep.
    let five = nested("G65 P", 5, "");
    assert_eq!(warnings(&five), [("W121", 13)]);
    assert_eq!(alarm_of(&five), Some((6004, 13)));
    assert_eq!(warnings(&nested("G65 P", 4, "")), []);
    // Behind a condition W121 does not take the call as made on every
    // run. This run is known, though: #1 is vacant, which is not 0, so
    // no GOTO; the fifth call, on line 15, stops it (W124).
    let guarded = nested("M98 P", 5, "IF[#1EQ0]GOTO9\nN9\n");
    assert_eq!(warnings(&guarded), [("W124", 15)]);
    assert_eq!(alarm_of(&guarded), Some((6004, 15)));
    // Four of each kind, eight calls in all: the limit, not past it.
    let mixed = "M98 P1\nM30\nO0001\nM98 P2\nM99\nO0002\nM98 P3\nM99\nO0003\nM98 P4\nM99\n\
                 O0004\nG65 P5\nM99\nO0005\nG65 P6\nM99\nO0006\nG65 P7\nM99\nO0007\nG65 P8\nM99\n\
                 O0008\nG01 U1 F100\nM99\n";
    assert_eq!(warnings(mixed), []);
    assert_eq!(alarm_of(mixed), None);
    // Recursion is W115's alone, though it nests too deep as well.
    assert_eq!(warnings("M98 P1\nM30\nO0001\nM98 P1\nM99\n"), [("W115", 4)]);
}

/// W125 alone, as `warnings` checks it (made dynamic too).
fn w125(src: &str) -> Vec<usize> {
    let found = of(src);
    let dynamic = of(&format!("{src}#1=1\n"));
    assert_eq!(ran(&dynamic), ran(&found), "made dynamic: {src}");
    found
        .into_iter()
        .filter(|w| w.0 == "W125")
        .map(|w| w.1)
        .collect()
}

#[test]
fn w125_a_feed_per_revolution_in_g98() {
    // G98 is the power-on feed mode: F0.2 is 0.2 mm/min. Said once, at
    // the F word of the first feed move (line 2), not at the later ones.
    let src = "G00 X20 Z2\nG01 Z-5 F0.2\nX30\nG00 X40\nG01 Z-20 F0.3\nM30\n";
    assert_eq!(w125(src), [2]);
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    let d = &c.diags[0].1;
    assert_eq!((d.span.start, d.span.end), (19, 23), "{}", c.render());
    // In G99 the same F is 0.2 mm/rev; F1 and above in G98 is a feed.
    assert!(w125(&format!("G99\n{src}")).is_empty());
    assert!(w125("G00 X20 Z2\nG01 Z-5 F1\nM30\n").is_empty());
    assert_eq!(w125("G00 X20 Z2\nG01 Z-5 F0.999\nM30\n"), [2]);
    // An F set on a block of its own; in G20 (in/min).
    assert_eq!(w125("F0.2\nG00 X20 Z2\nG01 Z-5\nM30\n"), [1]);
    assert_eq!(w125("G20\nG00 X2. Z0.1\nG01 Z-1. F0.008\nM30\n"), [3]);
    // Only rapids: the F is never used.
    assert!(w125("G00 X20 Z2 F0.2\nG00 Z-5\nM30\n").is_empty());
}

#[test]
fn w125_at_a_cycle_but_not_at_a_thread() {
    // A roughing cycle feeds at its F (line 3).
    let g71 = "G00 X52 Z2\nG71 U1.5 R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\nN10 G00 X20\nG01 Z-20\nN20 X52\nM30\n";
    assert_eq!(w125(g71), [3]);
    // A thread's F is its lead: G32 and G92 with F0.5 cut no feed move.
    let threads = "M03 S500\nG00 X20 Z2\nG32 Z-20 F0.5\nG00 X30\nZ2\nG92 X19 Z-20 F0.5\nM30\n";
    assert!(w125(threads).is_empty());
    // A thread between the F and its first feed move: the F word is
    // named (line 3), not the lead's (line 4), which the feed does not
    // take.
    let after = "M03 S500\nG00 X20 Z2\nF0.2\nG32 Z-20 F1.5\nG00 X30\nG01 Z-30\nM30\n";
    assert_eq!(w125(after), [3]);
}

#[test]
fn w125_at_the_f_word_of_a_block_that_calls() {
    // M98's P is the call's, not an NC word, so the F stands at another
    // place among the block's words than among its NC words: W125 names
    // the F word itself.
    let src = "G00 X20 Z2\nM98 P1000 F0.2\nG01 Z-5\nM30\nO1000\nG00 X20\nM99\n";
    assert_eq!(w125(src), [2]);
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    let (_, d) = (c.diags.iter()).find(|(_, d)| d.code == "W125").unwrap();
    assert_eq!(&src[d.span.start as usize..d.span.end as usize], "F0.2");
}

#[test]
fn w104_and_w108_in_polar_and_cylindrical_interpolation() {
    let mut opts = Options::default();
    opts.machine.axes.c.enabled = true;
    let found = |src: &str| {
        let c = compile("w.nc", src.as_bytes(), &opts);
        assert!(!c.has_errors(), "{}", c.render());
        (c.diags.iter())
            .filter(|(_, d)| d.code != "W101")
            .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
            .collect::<Vec<_>>()
    };
    // An arc ignores the axis outside the plane (seed 000): W104 at Z (W)
    // in polar interpolation, at X (U) in cylindrical; G01 moves it and
    // gets nothing. The arc from (10, 10) to (−10, 10) leaves the joints'
    // X where it was (√200 from the centre at both ends) but moves on
    // the path: no W108. G04 X in cylindrical interpolation is a dwell.
    let src = "G98 G00 X40 Z2 C0\nG12.1\nG01 X20 C10 F300\nG01 Z-2\nG03 X-20 C10 R10 W1\nG13.1\nG00 C0\nG7.1 C20.\nG01 Z-10 C90\nG02 Z-20 R5 X30\nG04 X1\nG7.1 C0\nM30\n";
    assert_eq!(found(src), [("W104", 5), ("W104", 10)]);
    // The compile-time run of the program made dynamic finds them too.
    assert_eq!(found(&format!("{src}#1=1\n")), [("W104", 5), ("W104", 10)]);
    // So does an ellipse, and a G01 taking Z along gets nothing: from
    // (20, 0) about the centre to (−20, 0), then back up along a line to
    // (−10, 10) with Z.
    let src =
        "G98 G00 X40 Z2 C0\nG12.1\nG6.3 X-40 C0 A20 B10 Z-3 F300\nG01 X-20 C10 Z2\nG13.1\nM30\n";
    assert_eq!(found(src), [("W104", 3)]);
    // An arc in the plane that ends where it starts moves nothing: W108.
    let src = "G98 G00 X40 Z2 C0\nG12.1\nG01 X20 C10 F300\nG02 X20 C10 R5\nG13.1\nM30\n";
    assert_eq!(found(src), [("W108", 4)]);
}

/// W126 alone, with the messages (made dynamic too).
fn w126(src: &str) -> Vec<(usize, String)> {
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    let dynamic = of(&format!("{src}#1=1\n"));
    assert_eq!(ran(&dynamic), ran(&of(src)), "made dynamic: {src}");
    c.diags
        .iter()
        .filter(|(_, d)| d.code == "W126")
        .map(|(f, d)| (c.files[*f].line_col(d.span.start).0, d.message.clone()))
        .collect()
}

#[test]
fn w126_a_thread_too_fast_for_the_axis() {
    // Lead 4 at 1500 rpm: Z runs at 4 × 1500 = 6000 mm/min, above the
    // reference machine's 5000 (the run stops with E4010). Lead 3 asks
    // 4500: no warning.
    let src = "G97 S1500 M03\nG00 X30 Z5\nG32 Z-20 F4\nG00 X40\nM30\n";
    let w = w126(src);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, 3);
    assert!(
        w[0].1
            .contains("asks Z for 6000 mm/min, above its maximum cutting feed of 5000"),
        "{}",
        w[0].1
    );
    assert_eq!(w126(&src.replace("F4", "F3")), []);
    // A taper whose long axis is X (20 on the radius against 5 along Z):
    // X at 3 × 1500 = 4500 mm/min, above its 4000; Z at 4500 × 5/20 =
    // 1125. At 1000 rpm X needs 3000: no warning.
    let taper = "G97 S1500 M03\nG00 X20 Z5\nG32 X60 Z0 F3\nG00 X80\nM30\n";
    let w = w126(taper);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].1
            .contains("asks X for 4500 mm/min, above its maximum cutting feed of 4000"),
        "{}",
        w[0].1
    );
    assert_eq!(w126(&taper.replace("S1500", "S1000")), []);
    // A later block of a chain counts too, where the run stops at the
    // chain's start: a 45° G92 pull-out at lead 4.5 and 1000 rpm asks X
    // for 4500 mm/min (Z's 4500 is within its 5000); lead 3.9 asks 3900.
    let pull_out = "G97 S1000 M03\nG00 X30 Z5\nG92 X20 Z-20 F4.5 J3 K3\nG00 X60 Z20\nM30\n";
    let w = w126(pull_out);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, 3);
    assert!(
        w[0].1.contains("asks X for 4500 mm/min")
            && w[0]
                .1
                .ends_with("the run stops with E4010 at the start of its thread chain"),
        "{}",
        w[0].1
    );
    assert_eq!(w126(&pull_out.replace("F4.5", "F3.9")), []);
    // A G32 run-out whose long axis is X (2 mm out on the radius, 0.5
    // along Z) at lead 3 along X and 1500 rpm: X at 4500 mm/min, warned
    // at the run-out's block; the Z thread before it (4500) is not.
    let run_out = "G97 S1500 M03\nG00 X30 Z5\nG32 Z-20 F3\nG32 X34 W-0.5\nG00 X40\nM30\n";
    let w = w126(run_out);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, 4);
    assert!(w[0].1.contains("asks X for 4500 mm/min"), "{}", w[0].1);
}

/// (line, message) of each W104 of `src`, which must be the same when a
/// macro statement at its end makes the program dynamic (the
/// compile-time run in the VM finds them then).
fn w104(src: &str) -> Vec<(usize, String)> {
    let of = |src: &str| -> Vec<(usize, String)> {
        let c = compile("w.nc", src.as_bytes(), &Options::default());
        assert!(!c.has_errors(), "{}", c.render());
        (c.diags.iter())
            .filter(|(_, d)| d.code == "W104")
            .map(|(f, d)| (c.files[*f].line_col(d.span.start).0, d.message.clone()))
            .collect()
    };
    let found = of(src);
    assert_eq!(of(&format!("{src}#1=1\n")), found, "made dynamic: {src}");
    found
}

#[test]
fn w104_a_letter_the_motion_does_not_use() {
    // §1.8: a Fanuc corner R and chamfer I on G01 (here D and L), R on
    // a G00, I on an ellipse, A on a parabola, E anywhere.
    let src = "G00 X20 Z2\nG01 Z-10 R2 F100\nG01 X30 I1\nG00 X40 R3\n\
               G6.2 X30 Z-20 A10 B5 I3\nG7.2 X40 Z-30 P10 A3\nG01 X50 E1\nM30\n";
    let w = w104(src);
    let lines: Vec<usize> = w.iter().map(|(l, _)| *l).collect();
    assert_eq!(lines, [2, 3, 4, 5, 6, 7], "{w:?}");
    assert_eq!(
        w[0].1,
        "R is ignored: G01 does not use it: a rounding is D (or ,R)"
    );
    assert_eq!(
        w[1].1,
        "I is ignored: G01 does not use it: a chamfer is L (or ,C)"
    );
    assert_eq!(w[4].1, "A is ignored: G7.2 does not use it");
    // An older system's taper I on G90 (G94: K): here R.
    let w = w104("G00 X40 Z2\nG90 X30 Z-20 I-1 F100\nG94 X20 Z-5 K-1\nM30\n");
    let told: Vec<&str> = w.iter().map(|(_, m)| m.as_str()).collect();
    assert_eq!(
        told,
        [
            "I is ignored: G90 does not use it: a taper is R (the Fanuc A system's word)",
            "K is ignored: G94 does not use it: a taper is R (the Fanuc A system's word)"
        ]
    );
    // The modal motion decides: X30 I1 after a G02 is an arc's centre.
    assert_eq!(
        w104("G00 X20 Z2\nG02 X30 Z-3 I5 K0 F100\nX40 Z-8 I5 K0\nM30\n"),
        []
    );
    // §4.1 rule 1: with R, an arc's I and K are ignored.
    let w = w104("G00 X20 Z2\nG02 X40 Z-20 R15 I3 F100\nM30\n");
    assert_eq!(
        w,
        [(2, "I is ignored: G02 takes its radius from R".to_string())]
    );
    // Words each block's function uses: corners, angles, thread words,
    // cycles, calls, G22's limits, G04, G50, M98's P and L, M99's P.
    let used = "G00 X20 Z2\nG01 Z-10 L1 F100\nG01 X30 D1\nG01 X40 Q45000\n\
                G02 X50 Z-10 I5 K0 L1\nG32 Z-30 F2 J1 K1 Q0\nG92 X38 Z-40 F2 J1 K1 L2\n\
                G90 X36 Z-40 R-1 F100\nG22 X100 Z100 I-100 K-100\nG23\nG04 P100\nG50 X20 Z2\n\
                M98 P1000 L2\nM30\nO1000\nG00 X30\nM99 P0\n";
    assert_eq!(w104(used), []);
    // M98's P and L count beside another word of its block: only that
    // word is told (they were too, as G00's).
    let w = w104("G00 X20 Z2\nM98 P1000 L2 R5\nM30\nO1000\nG00 X30\nM99\n");
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].1, "R is ignored: G00 does not use it");
}

#[test]
fn w104_a_word_a_form_ignores() {
    // §4.3: G92's P asks for thread repair, off on the reference machine
    // (№174.4 = 0).
    let w = w104("G97 S500 M3\nG00 X40 Z5\nG92 X30 Z-20 F1.5 P1\nM30\n");
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, 3);
    assert!(
        w[0].1.starts_with("P is ignored: thread repair is off"),
        "{}",
        w[0].1
    );
    // §4.12: the one-block G76 (K, D) takes no P; the two-block form's
    // second block does (k).
    let modal = "G97 S500 M3\nG00 X40 Z5\nG76 P020060 Q100 R0.05\n";
    let w = w104(&format!("{modal}G76 X30 Z-20 K1 D0.3 F1.5 A60 P1\nM30\n"));
    assert_eq!(w.iter().map(|w| w.0).collect::<Vec<_>>(), [4], "{w:?}");
    assert_eq!(
        w104(&format!("{modal}G76 X30 Z-20 P900 Q300 F1.5\nM30\n")),
        []
    );
    // cycles.md §4: in a G90 run, `R-1` alone runs nothing and is not
    // kept (X44 then runs with the run's R, 0); the R of a block that runs
    // the cycle is taken.
    let run = "G00 X50 Z5\nG90 X40 Z-20 F0.2\nR-1\nX44\nM30\n";
    let w = w104(run);
    assert_eq!(w.iter().map(|w| w.0).collect::<Vec<_>>(), [3], "{w:?}");
    assert!(
        w[0].1.starts_with("R is ignored: a block without X"),
        "{}",
        w[0].1
    );
    assert_eq!(w104("G00 X50 Z5\nG90 X40 Z-20 F0.2\nX44 R-1\nM30\n"), []);
    // §5.2: X Z Q ends angle programming; without its first block (Q
    // alone) the block is a plain line and Q is ignored. A block without
    // axis words may stand between the two; X with Q alone is the line
    // at an angle.
    let w = w104("G00 X40 Z5\nG01 X30 Z-20 Q30000 F100\nM30\n");
    assert_eq!(w.iter().map(|w| w.0).collect::<Vec<_>>(), [2], "{w:?}");
    assert!(w[0].1.contains("no Q_ block began it"), "{}", w[0].1);
    let pair = "G00 X40 Z5\nG01 Q150000 F100\nM08\nG01 X60 Z-20 Q180000\nM30\n";
    assert_eq!(w104(pair), []);
    assert_eq!(w104("G00 X40 Z5\nG01 X50 Q30000 F100\nM30\n"), []);
    // cycles.md §15.5: G71's J1 repeats type II's allowance pass; type I
    // (the ns block names X only) ignores J, type II any J but 1.
    let g71 = |j: &str, ns: &str| {
        w104(&format!(
            "G00 X52 Z2\nG71 U1 R0.5\nG71 P10 Q20 U0.2 W0.1 F100 {j}\nN10 G00 {ns}\nG01 Z-10\nN20 G01 X50\nM30\n"
        ))
    };
    let w = g71("J1", "X20");
    assert_eq!(w.iter().map(|w| w.0).collect::<Vec<_>>(), [3], "{w:?}");
    assert!(w[0].1.contains("type I"), "{}", w[0].1);
    assert_eq!(g71("J1", "X20 Z0"), []);
    assert_eq!(g71("J2", "X20 Z0").len(), 1);
    assert_eq!(g71("", "X20"), []);
    // A drilling cycle's Q is its peck (conformance g83_peck_j0).
    let drill = "G99 M03 S800\nG00 X0 Z3\nG83 X0 Z-12 Q5000 R2 F0.08\nG80\nM30\n";
    assert_eq!(w104(drill), []);
}

#[test]
fn w104_a_word_a_cycle_run_drops_in_silence() {
    // The lead is F or I (threads per inch), F when both are written
    // (cycles.md §0, "thread lead and feed"): I beside F is ignored, in a
    // G92 block and in a later block of its run (line 4) alike. An I
    // without F is the lead (25.4/2 = 12.7 mm): no warning.
    let i = "I is ignored: F gives the lead; I (threads per inch) counts only in a block without F";
    let head = "G97 S500 M3\nG00 X40 Z5\n";
    let w = w104(&format!("{head}G92 X30 Z-20 F1.5 I2\nX29 F1.5 I2\nM30\n"));
    assert_eq!(w, [(3, i.to_string()), (4, i.to_string())]);
    assert_eq!(w104(&format!("{head}G92 X30 Z-20 I2\nM30\n")), []);
    assert_eq!(
        w104(&format!("{head}G32 Z-20 F1.5 I2\nM30\n")),
        [(3, i.to_string())]
    );
    // cycles.md §4: L, like R, is a value of the G92 run; a block without
    // an axis word runs nothing and keeps neither (line 4, both words),
    // also where thread repair makes its P ignored (line 5, three words:
    // the P rule no longer hides the others).
    let dropped = |l: char| {
        format!("{l} is ignored: a block without X, U, Z or W does not run the cycle, and its {l} is not kept for the next block")
    };
    let repair = "P is ignored: thread repair is off on this machine (№174.4)".to_string();
    let run = format!("{head}G92 X30 Z-20 F1.5\nR-1 L2\nR-1 L2 P1\nX29\nM30\n");
    let mut want = vec![
        (4, dropped('R')),
        (4, dropped('L')),
        (5, dropped('R')),
        (5, dropped('L')),
        (5, repair),
    ];
    // (In any order within a block: the text form sorts them by column.)
    let mut found = w104(&run);
    found.sort();
    want.sort();
    assert_eq!(found, want);
    // G92.1 drops R alone as G92 does.
    let rigid = format!("{head}G92.1 X30 Z-20 F1.5\nR-1\nX29\nM30\n");
    assert_eq!(w104(&rigid), [(4, dropped('R'))]);
    // G76's second block reads I as threads per inch, and F wins (line
    // 4); in the one-block K/D form (line 5) I is the taper: used.
    let g76 = format!(
        "{head}G76 P010060 Q100 R0.1\nG76 X28 Z-20 P1000 Q300 F1.5 I2\nG76 X28 Z-20 I-1 K1 D300 F1.5\nM30\n"
    );
    assert_eq!(w104(&g76), [(4, i.to_string())]);
}

#[test]
fn w104_a_letter_the_drilling_cycle_in_force_does_not_use() {
    // dialect.md §4.8: the cycle in force owns the block. A mill's L
    // (repeats; here K) on G83, and Q, R on a rigid tap (G84 takes P, F or
    // I, K, M); in a later hole of the cycle too. Its own words: none.
    let src = "G99 M03 S800\nG00 X0 Z3\nG83 X0 Z-12 Q5000 R2 P100 J1 K2 F0.08 L2\n\
               X10 Z-8 L3\nG80\nG00 X0 Z3\nM29 S500\nG84 X0 Z-10 F1.25 Q1000 R1 P100 K1\n\
               G80\nM30\n";
    let w = w104(src);
    let found: Vec<(usize, &str)> = w.iter().map(|(l, m)| (*l, &m[..1])).collect();
    assert_eq!(found, [(3, "L"), (4, "L"), (8, "Q"), (8, "R")], "{w:?}");
    assert_eq!(w[0].1, "L is ignored: G83 does not use it");
    assert_eq!(w[2].1, "Q is ignored: G84 does not use it");
    // After G80 the motion owns the block again: an R on G01 is told as
    // the motion's.
    let w = w104("G00 X0 Z3\nG83 X0 Z-12 F0.08\nG80\nG01 X10 R1\nM30\n");
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].1.ends_with("a rounding is D (or ,R)"), "{}", w[0].1);
}

#[test]
fn w112_a_corner_word_before_a_conic_of_a_profile() {
    // dialect.md §5.1: the next move must be G01–G03; a profile's conic is
    // not. Told once, though G71 and G70 both read the profile.
    let src = "G00 X42 Z2\nG71 U2 R0.5\nG71 P10 Q20 U0.4 W0.1 F100\nN10 G00 X0\nG01 Z0 L1\n\
               G6.3 X30 Z-10 A15 B10 Q90000\nN20 G01 Z-20\nG70 P10 Q20\nM30\n";
    assert_eq!(warnings(src), [("W112", 5)]);
    assert_eq!(warnings(&src.replace(" L1", "")), []);
    // Before a line the chamfer applies.
    assert_eq!(
        warnings(&src.replace("G01 Z0 L1", "G01 Z0 L1\nG01 X10 Z-1")),
        []
    );
}

#[test]
fn w104_a_letter_a_group_00_code_does_not_use() {
    // The code owns its block (§3): its own words count, the axes only
    // where it takes them.
    let w = w104("G04 X1 Z5\nG00 X40 Z5\nG28 U0 W0 R5\nG50 X40 Z5 R3\nM30\n");
    let found: Vec<(usize, &str)> = w.iter().map(|(l, m)| (*l, &m[..1])).collect();
    assert_eq!(found, [(1, "Z"), (3, "R"), (4, "R")], "{w:?}");
    assert_eq!(w[0].1, "Z is ignored: G04 does not use it");
    // With G01 in force a G28's R is the G28's, not a G01 corner's.
    let w = w104("G00 X40 Z5\nG01 X30 F100\nG28 U0 W0 R5\nM30\n");
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].1, "R is ignored: G28 does not use it");
    let profile = "N10 G00 X20\nN20 G01 Z-5 F100\nM30\n";
    let w = w104(&format!("G00 X40 Z5\nG70 P10 Q20 X3\n{profile}"));
    assert_eq!(w.iter().map(|w| w.0).collect::<Vec<_>>(), [2], "{w:?}");
    // The cycles' and the other codes' own words: none.
    let used = format!(
        "G00 X40 Z5\nG04 P100\nG04 U1\nG50 S2000\nG28 U0 W0\nG50 X40 Z5\n\
         G71 U1 R0.5\nG71 P10 Q20 U0.2 W0.1 F100 S500 T0101\nG74 R1\nG74 X0 Z-10 P1000 Q2000 F100\n{profile}"
    );
    assert_eq!(w104(&used), []);
}

#[test]
fn w104_a_letter_the_form_of_a_cycle_block_does_not_use() {
    // cycles.md §0: a G71–G73 block with P or Q is the cycle block, a
    // G74–G78 block with an axis word the second; each form has its own
    // words (dialect.md §4.8, §4.12).
    let profile = "N10 G00 X20\nN20 G01 Z-5 F100\n";
    let lines = |w: &[(usize, String)]| w.iter().map(|w| w.0).collect::<Vec<_>>();
    let w = w104(&format!(
        "G00 X40 Z5\nG71 U1 R0.5 W0.3\nG71 P10 Q20 U0.2 W0.1 R1 F100\n{profile}\
         G72 W1 R0.5 U0.3\nG73 U1 W1 R2 K3\nM30\n"
    ));
    assert_eq!(lines(&w), [2, 3, 6, 7], "{w:?}");
    assert_eq!(
        w[0].1,
        "W is ignored: G71's first block (U R) does not use it"
    );
    assert_eq!(
        w[1].1,
        "R is ignored: G71's cycle block (P Q U W D K J) does not use it"
    );
    assert_eq!(
        w[2].1,
        "U is ignored: G72's first block (W R) does not use it"
    );
    // (A G73 block with Q alone is a cycle block without its P: E2020.)
    let threads = "G97 S500 M3\nG00 X40 Z5\n\
                   G76 P020060 Q100 R0.05 I4\n\
                   G76 X30 Z-20 P900 Q300 F1.5 A29\n\
                   G76 X30 Z-20 K0.9 D0.3 F1.5 R1 Q2\n\
                   G74 R1 Q2000\nG74 X0 Z-10 P1000 Q2000 F100\nG00 X40 Z5\n\
                   G78 P010060 Q100 R0.05 D1 L1 E1\nG78 X30 Z-20 P900 Q300 F1.5 E1\nM30\n";
    let w = w104(threads);
    let found: Vec<(usize, &str)> = w.iter().map(|(l, m)| (*l, &m[..1])).collect();
    assert_eq!(
        found,
        [(3, "I"), (4, "A"), (5, "R"), (5, "Q"), (6, "Q"), (10, "E")],
        "{w:?}"
    );
    assert_eq!(
        w[2].1,
        "R is ignored: G76's one-block form (X Z U W I K D A) does not use it"
    );
    assert_eq!(
        w[4].1,
        "Q is ignored: G74's first block (R) does not use it"
    );
    // Each form's own words: none.
    let used = "G97 S500 M3\nG00 X40 Z5\nG76 P020060 Q100 R0.05 J1 K1\n\
                G76 X30 Z-20 R-1 P900 Q300 F1.5\nG76 U-10 W-20 P900 Q300 I16\n\
                G76 X30 Z-20 I-1 K0.9 D0.3 F1.5 A60\nG00 X40 Z5\n\
                G75 R1\nG75 X20 Z-10 P1000 Q2000 R0.1 F100\nG00 X40 Z5\n\
                G78 P010060 Q100 R0.05 J1 K1 D1 L1 E1\nG78 X30 Z-20 R0 P900 Q300 F1.5\n\
                G73 U1 W1 R2\nG73 P10 Q20 U0.2 W0.1 F100\n\
                G71 P10 Q20 U0.2 W0.1 D1 F100\nM30\n"
        .to_string()
        + profile;
    assert_eq!(w104(&used), []);
}

/// The lines of W101 (running off the last block) in a program.
fn w101(src: &str) -> Vec<usize> {
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    c.diags
        .iter()
        .filter(|(_, d)| d.code == "W101")
        .map(|(f, d)| c.files[*f].line_col(d.span.start).0)
        .collect()
}

/// W101 says a program runs past its last block (dialect.md §1.2): only
/// when a path gets there.
#[test]
fn w101_only_when_the_run_can_get_past_the_last_block() {
    // No end at all.
    assert_eq!(w101("G00 X1\nG00 X2\n"), [2]);
    // G70's profile after M30 is read, not run through (cycles.md §8).
    let g70 = "G99 S500 M03\nG00 X50 Z2\nG70 P10 Q20 F0.2\nM30\nN10 G00 X30\nG01 Z-20\nN20 X50\n";
    assert_eq!(w101(g70), Vec::<usize>::new());
    // G71 goes on after nf (cycles.md §5): past the last block.
    let g71 = "G99 S500 M03\nG00 X50 Z2\nG71 U2 R1\nG71 P10 Q20 F0.2\nM30\nN10 G00 X30\nG01 Z-20\nN20 X50\n";
    assert_eq!(w101(g71), [8]);
    // A block after M30 that nothing jumps to; then one a GOTO reaches,
    // literal or computed.
    assert_eq!(w101("G00 X1\nM30\nN10 G00 X2\n"), Vec::<usize>::new());
    assert_eq!(w101("GOTO 10\nM30\nN10 G00 X2\n"), [3]);
    assert_eq!(w101("#1=10\nGOTO #1\nM30\nN10 G00 X2\n"), [4]);
}

/// W127 alone: the lines it stands on, and its first message.
fn w127(src: &str) -> (Vec<usize>, String) {
    let c = compile("w.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let found: Vec<_> = c.diags.iter().filter(|(_, d)| d.code == "W127").collect();
    let lines = found
        .iter()
        .map(|(f, d)| c.files[*f].line_col(d.span.start).0);
    let message = found.first().map(|(_, d)| d.message.clone());
    (lines.collect(), message.unwrap_or_default())
}

#[test]
fn w127_a_loop_that_never_ends_once_it_goes_round() {
    // The counter is never stepped: the test on line 2 reads #1 alone.
    let forgot = "#1=0\nWHILE[#1LT3]DO1\nG00 U-1\nEND1\nM30\n";
    let (lines, message) = w127(forgot);
    assert_eq!(lines, [2]);
    assert!(
        message.contains("reads only #1, which nothing"),
        "{message}"
    );
    // Stepped, it ends.
    assert_eq!(w127(&forgot.replace("END1", "#1=#1+1\nEND1")).0, []);
    // No way out at all: on the DO.
    let (lines, message) = w127("G00 X50 Z2\nDO1\nG00 U-1\nEND1\nM30\n");
    assert_eq!(lines, [2]);
    assert!(message.contains("nothing leaves it"), "{message}");
    // A backward GOTO whose test never changes; an inner loop that steps
    // the outer loop's counter, not its own (line 4).
    assert_eq!(w127("#1=0\nN5 G00 U-1\nIF[#1LT5]GOTO5\nM30\n").0, [3]);
    let inner = "#1=0\nWHILE[#1LT10]DO1\n#2=0\nWHILE[#2LT3]DO2\n#1=#1+1\nEND2\nEND1\nM30\n";
    assert_eq!(w127(inner).0, [4]);
    // Silent where the loop may change its test in a way not followed, or
    // leave by another way: an input; a call; a `/` block; a write to a
    // computed number; a computed M code; a GOTO out (the END is then dead
    // code); a second way out, which leaves at once on every pass (to a
    // block that steps #1 and goes back before the WHILE); a way out
    // behind a branch, first met on the tenth round.
    for quiet in [
        "WHILE[#1000EQ0]DO1\nEND1\nM30\n",
        "#1=1\nWHILE[#1LT3]DO1\nM98 P100\nEND1\nM30\nO100\nM99\n",
        "#1=1\nWHILE[#1LT3]DO1\n/#1=5\nEND1\nM30\n",
        "#1=1\nWHILE[#1LT3]DO1\n#[#2]=5\nEND1\nM30\n",
        "#1=1\n#2=8\nWHILE[#1LT3]DO1\nM#2\nEND1\nM30\n",
        "#1=1\nWHILE[#1LT3]DO1\nGOTO5\nEND1\nN5 M30\n",
        "#1=0\n#2=1\nN1 WHILE[#1LT3]DO1\nIF[#2EQ1]GOTO50\nEND1\nM30\nN50 #1=#1+1\nGOTO1\n",
        "#2=0\nWHILE[#1LT3]DO1\n#2=#2+1\nIF[#2LT10]GOTO7\nIF[#3EQ0]GOTO9\nN7 G00 U-1\nEND1\nN9 M30\n",
    ] {
        assert_eq!(w127(quiet).0, [], "{quiet}");
    }
}
