//! Macro calls (dialect.md §7.9–§7.12) end to end, canons checked by hand.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn run_with(src: &str, machine: Machine) -> (Vec<String>, Status) {
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    let c = compile("m.nc", src.as_bytes(), &opts);
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), machine);
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    (events.iter().map(|e| e.to_string()).collect(), status)
}

fn run(src: &str) -> (Vec<String>, Status) {
    run_with(src, Machine::reference())
}

#[test]
fn g65_arguments_of_both_specifications() {
    // A→#1, B→#2, X→#24; the second I is I2 → #7, the second K is K2 → #9.
    // The macro moves to X = #1 + #2 + #24 = 1 + 2 + 30 = 33, Z = #7 + #9 = -5.
    let src = "G65 P9001 A1 B2 X30 I0 K0 I-2 K-3\nM30\nO9001\nG00 X[#1+#2+#24] Z[#7+#9]\nM99\n";
    let (canon, status) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=33 Z=-5", "STOP KIND=M30"]);
}

#[test]
fn g65_gives_a_fresh_local_level_and_m98_shares_it() {
    // #1 = 7 in the main program; G65 sees A = 1 as #1 and no #2; after the
    // call #1 is 7 again. M98 shares level 0: O0002 sets #1 = 9.
    let src = "#1=7\nG65 P0001 A1\nG00 X#1\nM98 P0002\nG00 X#1\nM30\nO0001\nG00 X[#1*10] Z#2\nM99\nO0002\n#1=9\nM99\n";
    let (canon, _) = run(src);
    // Z#2 is vacant in the macro, so the word is left out (Z stays 0).
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=0",
            "RAPID X=7 Z=0",
            "RAPID X=9 Z=0",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn g66_calls_after_every_move_until_g67() {
    // Each move is followed by the macro, which dwells #17 ms: the argument
    // Q lands in #17 (P names the program). M08 alone does not move.
    let src =
        "G66 P9002 Q250\nG00 X10\nG01 Z-5 F100\nM08\nG67\nG00 X20\nM30\nO9002\nG04 P#17\nM99\n";
    let (canon, _) = run(src);
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=0",
            "DWELL S=0.25",
            "FEED F=100 MODE=MIN",
            "LINE X=10 Z=-5",
            "DWELL S=0.25",
            "M CODE=8",
            "RAPID X=20 Z=-5",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn m9000_codes_call_o9000_programs() {
    let src = "G00 X10\nM9005\nM30\nO9005\nG00 U4\nM99\n";
    let (canon, _) = run(src);
    assert_eq!(canon, ["RAPID X=10 Z=0", "RAPID X=14 Z=0", "STOP KIND=M30"]);
}

#[test]
fn g_code_macros_call_o9010_onwards() {
    let m = Machine::from_toml("[macro]\ng_code_macros = [0, 150, 0, 0, 0, 0, 0, 0, 0, 0]\n")
        .expect("machine");
    // №087 = 150 → G150 calls O9011 with A → #1.
    let src = "G150 A12\nM30\nO9011\nG00 X#1\nM99\n";
    let (canon, _) = run_with(src, m);
    assert_eq!(canon, ["RAPID X=12 Z=0", "STOP KIND=M30"]);
}

#[test]
fn the_fifth_macro_level_is_e6004() {
    // Each level calls the next: levels 1–4 print, the fifth call alarms.
    let src = "G65 P1\nM30\nO1\nG00 W-1\nG65 P2\nM99\nO2\nG00 W-1\nG65 P3\nM99\nO3\nG00 W-1\nG65 P4\nM99\nO4\nG00 W-1\nG65 P5\nM99\nO5\nG00 W-1\nM99\n";
    let (canon, status) = run(src);
    let Status::Alarm(a) = status else {
        panic!("{status:?}")
    };
    assert_eq!(a.code, 6004);
    assert_eq!(canon.iter().filter(|l| l.starts_with("RAPID")).count(), 4);
}

#[test]
fn macro_a_h_codes_compute_and_jump() {
    // H02 #100 = 3 + 4; H81 jumps to N20 when #100 = 7, skipping X99.
    let src = "G65 H01 P#101 Q3\nG65 H02 P#100 Q#101 R4\nG65 H81 P20 Q#100 R7\nG00 X99\nN20 G00 X#100\nM30\n";
    let (canon, _) = run(src);
    assert_eq!(canon, ["RAPID X=7 Z=0", "STOP KIND=M30"]);
}

#[test]
fn a_g65_h_alarm_takes_the_blocks_comment_as_its_message() {
    // As `#3000 = n (TEXT)` (dialect.md §7.3): H01 into #3006 is a message
    // stop, H02 into #3000 the alarm 3000 + 2 + 3.
    let src = "G65 H01 P#3006 Q1 (CHECK THE CHUCK)\nG65 H02 P#3000 Q2 R3 (NO FEED)\nM30\n";
    let (canon, status) = run(src);
    assert_eq!(
        canon,
        [
            "MESSAGE TEXT=\"CHECK THE CHUCK\"",
            "ALARM CODE=3005 MSG=\"NO FEED\""
        ]
    );
    assert!(matches!(status, Status::Alarm(a) if a.code == 3005 && a.line == 2));
    // Without a comment the message is empty, as for `#3000 = n`.
    let (canon, _) = run("G65 H01 P#3000 Q1\nM30\n");
    assert_eq!(canon, ["ALARM CODE=3001 MSG=\"\""]);
    // G65 H99 Q7 is alarm 507: the comment, else a message of gbc's.
    let (canon, _) = run("G65 H99 Q7 (SPINDLE NOT READY)\nM30\n");
    assert_eq!(canon, ["ALARM CODE=507 MSG=\"SPINDLE NOT READY\""]);
    let (canon, _) = run("G65 H99 Q7\nM30\n");
    assert_eq!(canon, ["ALARM CODE=507 MSG=\"G65 H99 user alarm\""]);
}

#[test]
fn h_after_p_is_argument_11_not_the_h_form() {
    // Seed 003, argument specification I: H → #11. The block is a macro
    // call because P (the program) comes first; the H form starts with H.
    // O9100 moves to X = #11 (5) and Z = #1 (vacant: the word is left
    // out and Z stays 0; then 1).
    let src = "G65 P9100 H5\nG65 P9100 A1 H5\nM30\nO9100\nG00 X#11 Z#1\nM99\n";
    let (canon, status) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=5 Z=0", "RAPID X=5 Z=1", "STOP KIND=M30"]);
}

/// The code and line of the first error of a program that must not
/// compile.
fn first_error(src: &str) -> (&'static str, usize) {
    let c = compile("m.nc", src.as_bytes(), &Options::default());
    assert!(c.has_errors(), "expected an error:\n{src}");
    let (unit, d) = c
        .diags
        .iter()
        .find(|(_, d)| d.is_error())
        .expect("an error");
    let line = src[..d.span.start as usize].matches('\n').count() + 1;
    assert_eq!(*unit, 0);
    (d.code, line)
}

/// The words of a call the kernel never sees are checked as it checks a
/// block's (dialect.md §1.7, §1.9, §6.1, §7.9): each program has the bad
/// block on line 2 and O1000/O9001/O9002 to call.
#[test]
fn call_blocks_are_checked_like_any_block() {
    let progs = "N10 M30\nO1000\nM99\nO9001\nM99\nO9002\nM99\n";
    let cases = [
        // Two calling M codes, or one with a program end: E1012.
        ("M98 P1000 M9001", "E1012"),
        ("M9001 M9002", "E1012"),
        ("M98 P1000 M99", "E1012"),
        ("M98 P1000 M30", "E1012"),
        ("M99 M30", "E1012"),
        ("M03 M08 M10 M98 P1000", "E1012"),
        // An address twice: E1011 (a G65's P or L, the H form's words).
        ("M98 P1000 P9001", "E1011"),
        ("G65 P1000 A1 L2 L3", "E1011"),
        ("G65 P1000 P9001", "E1011"),
        ("G65 H02 P#1 Q5 R3 H03", "E1011"),
        ("G65 H01 P#1 P#2 Q5", "E1011"),
        // A point on a program number, a count or a sequence number: E1009.
        ("G65 P1000 L2.5", "E1009"),
        ("M98 P1000 L2.", "E1009"),
        ("M98 P1000.", "E1009"),
        ("G66 P1000 L1.", "E1009"),
        ("M99 P10.", "E1009"),
        ("GOTO 10.", "E1009"),
        ("G65 H80 P10.", "E1009"),
        // A written count outside 1…9999: E1010; GOTO 0: E2010.
        ("G65 P1000 L0", "E1010"),
        ("M98 P1000 L0", "E1010"),
        ("G65 P1000 L10000", "E1010"),
        ("GOTO 0", "E2010"),
    ];
    for (block, code) in cases {
        let src = format!("G00 X1\n{block}\n{progs}");
        assert_eq!(first_error(&src), (code, 2), "{block}");
    }
    // The same words, well formed, compile.
    for block in [
        "M98 P1000 L2",
        "G65 P1000 L9999",
        "M98 P1000 M08",
        "G65 H80 P10",
    ] {
        let src = format!("G00 X1\n{block}\n{progs}");
        let c = compile("m.nc", src.as_bytes(), &Options::default());
        assert!(!c.has_errors(), "{block}: {}", c.render());
    }
}

/// G65 H81/H82 count a vacant operand as 0 (dialect.md §7.5): #1 is
/// vacant, so H81 (Q = R) jumps over X1 and H82 (Q ≠ R) does not jump.
#[test]
fn h81_and_h82_count_a_vacant_operand_as_zero() {
    let src =
        "G65 H81 P10 Q#1 R0\nG00 X1\nN10 G00 X2\nG65 H82 P20 Q#1 R0\nG00 X3\nN20 G00 X4\nM30\n";
    let (canon, status) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(
        canon,
        [
            "RAPID X=2 Z=0",
            "RAPID X=3 Z=0",
            "RAPID X=4 Z=0",
            "STOP KIND=M30"
        ]
    );
}

/// The alarm a program's run stops with, if any.
fn alarm_of(src: &str) -> Option<u32> {
    let c = compile("m.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    match vm.run(&mut events) {
        Status::Alarm(a) => Some(a.code),
        _ => None,
    }
}

/// §7.7: a GOTO may leave loops, but not enter one from outside it:
/// E2015 for a written target (G65 H80–H86 too), E6008 for a computed one.
#[test]
fn a_jump_into_a_loop_from_outside_it() {
    let body = "WHILE [#1 LT 2] DO1\nN10 G00 X1\n#1=#1+1\nEND1\nM30\n";
    // Computed (#1000 is 0 on the reference machine): E6008 when it runs.
    assert_eq!(
        alarm_of(&format!("#5=#1000+10\nGOTO #5\n{body}")),
        Some(6008)
    );
    // From one loop into the next, which does not hold it.
    let sibling = format!("WHILE [#2 LT 1] DO1\n#2=1\nGOTO [#1000+10]\nEND1\n{body}");
    assert_eq!(alarm_of(&sibling), Some(6008));
    // Written: compile errors at the target word.
    assert_eq!(first_error(&format!("G65 H80 P10\n{body}")), ("E2015", 1));
    assert_eq!(
        first_error(&format!("G65 H81 P10 Q0 R0\n{body}")),
        ("E2015", 1)
    );
    assert_eq!(first_error(&format!("GOTO 10\n{body}")), ("E2015", 1));
}

/// Out of an inner loop into the outer one's body, computed: allowed. By
/// hand: #2 = 0 prints X0, then #1 = 1 jumps to N20 (leaving DO2 inside
/// DO1); #2 = 1 prints X10 and jumps again; #2 = 2 ends the outer loop.
#[test]
fn a_jump_out_of_an_inner_loop_stays_in_the_outer() {
    let src = "#2=0\nWHILE [#2 LT 2] DO1\n#1=0\nWHILE [#1 LT 2] DO2\n\
               #5=20\nIF [#1 EQ 1] GOTO #5\nN10 G00 X[#1+#2*10]\n#1=#1+1\nEND2\n\
               N20 #2=#2+1\nEND1\nN30 M30\n";
    let (canon, status) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=0 Z=0", "RAPID X=10 Z=0", "STOP KIND=M30"]);
}

/// A call's M code computed (dialect.md §6.1, §7.10, §7.11): `M#1` calls
/// or returns after its block, as the written code does. By hand: O9001
/// prints X3; M98 P1000 L2 prints X1 twice (O1000 returns by a computed
/// M99 before its X2); a packed P21000 is twice too; O9002 is missing.
#[test]
fn a_computed_m_code_calls_and_returns() {
    let progs = "G00 X7\nM30\nO1000\nG00 X1\n#2=99\nM#2\nG00 X2\nM99\nO9001\nG00 X3\nM99\n";
    let canon = |head: &str| run(&format!("{head}\n{progs}")).0;
    assert_eq!(
        canon("#1=9001\nM#1"),
        ["RAPID X=3 Z=0", "RAPID X=7 Z=0", "STOP KIND=M30"]
    );
    let twice = [
        "RAPID X=1 Z=0",
        "RAPID X=1 Z=0",
        "RAPID X=7 Z=0",
        "STOP KIND=M30",
    ];
    assert_eq!(canon("#1=98\nM#1 P1000 L2"), twice);
    assert_eq!(canon("#1=98\nM#1 P21000"), twice);
    assert_eq!(alarm_of(&format!("#1=9002\nM#1\n{progs}")), Some(6003));
    assert_eq!(alarm_of(&format!("#1=98\nM#1\n{progs}")), Some(2006));
    // A computed L of 0, and a vacant packed P.
    assert_eq!(
        alarm_of(&format!("#2=0\nM98 P1000 L#2\n{progs}")),
        Some(5010)
    );
    assert_eq!(alarm_of(&format!("M98 P#3\n{progs}")), Some(5009));
}

/// §1.6: a jump target that occurs more than once is W103 and the first
/// block is used, for G65 H80–H86 (§7.8) as for GOTO. By hand: H80 P5
/// jumps to the first N5 (line 2, X1), which runs on into the second
/// (X2); H81 jumps when #1 = 1 = R, to the same first N5.
#[test]
fn a_macro_jump_to_a_repeated_number_is_w103() {
    let w103 = |src: &str| {
        let c = compile("m.nc", src.as_bytes(), &Options::default());
        c.diags
            .iter()
            .filter(|(_, d)| d.code == "W103")
            .map(|(f, d)| {
                let (line, col) = c.files[*f].line_col(d.span.start);
                (line, col, d.message.clone())
            })
            .collect::<Vec<_>>()
    };
    let msg = "N5 occurs more than once: the first block is used".to_string();
    let tail = "N5 G00 X1\nN5 G00 X2\nM30\n";
    let h80 = format!("G65 H80 P5\n{tail}");
    assert_eq!(w103(&h80), [(1, 9, msg.clone())]);
    let h81 = format!("#1=1\nG65 H81 P5 Q#1 R1\n{tail}");
    assert_eq!(w103(&h81), [(2, 9, msg.clone())]);
    assert_eq!(w103(&format!("GOTO 5\n{tail}")), [(1, 6, msg)]);
    let (canon, status) = run(&h80);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=1 Z=0", "RAPID X=2 Z=0", "STOP KIND=M30"]);
}
