//! Rules of dialect.md §1–§7 that an audit against the spec found broken:
//! each expected diagnostic or canon line is worked out by hand from the
//! section named beside it.

mod common;

use common::{codes, messages};
use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn on(machine: &str) -> Options {
    Options {
        machine: Machine::from_toml(machine).expect("a valid machine file"),
        ..Options::default()
    }
}

fn errors(src: &str) -> Vec<(&'static str, usize)> {
    codes(src, &Options::default())
}

/// The VM after a run on `opts`'s machine, the run's events and how it
/// ended.
fn vm_run(src: &str, opts: &Options) -> (Vm, Vec<Event>, Status) {
    let c = compile("p.nc", src.as_bytes(), opts);
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), opts.machine.clone());
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    (vm, events, status)
}

/// The canon of a run on `opts`'s machine, and how it ended.
fn run_on(src: &str, opts: &Options) -> (Vec<String>, Status) {
    let (_, events, status) = vm_run(src, opts);
    (events.iter().map(|e| e.to_string()).collect(), status)
}

fn alarm_of(src: &str) -> u32 {
    match run_on(src, &Options::default()).1 {
        Status::Alarm(a) => a.code,
        other => panic!("{src}: {other:?}"),
    }
}

#[test]
fn a_decimal_point_on_an_m_code_is_e1009() {
    // §1.9: M is among the "always integers"; M3.5 must not turn the
    // spindle either way.
    for m in ["M3.5", "M3.", "M8.0"] {
        assert_eq!(errors(&format!("{m} S100\nM30\n")), [("E1009", 1)], "{m}");
    }
    // A computed M is rounded half away from zero: 3.5 is M04.
    let (canon, _) = run_on("#1=3.5\nM#1 S100\nM30\n", &Options::default());
    assert_eq!(canon[0], "SPINDLE DIR=CCW");
}

#[test]
fn a_program_number_with_a_decimal_point_is_e1009() {
    // §1.9 lists O among the integer-only addresses.
    assert_eq!(errors("O1.0\nM30\n"), [("E1009", 1)]);
}

#[test]
fn a_computed_dwell_p_is_whole_milliseconds() {
    // §1.9: G04 P is ms, an integer; a computed value rounds half away
    // from zero: 1.4 → 1 ms, 1000.6 → 1001 ms, -2.5 → -3 → 0 (§4.2).
    let src = "#1=1.4\nG04 P#1\n#2=-2.5\nG04 P#2\nG04 P[1000.6]\nM30\n";
    let (canon, status) = run_on(src, &Options::default());
    assert_eq!(status, Status::Done);
    assert_eq!(
        canon,
        [
            "DWELL S=0.001",
            "DWELL S=0",
            "DWELL S=1.001",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn g96_on_a_gear_spindle_is_e2003() {
    // §6.2 and §8.2: a gear spindle has no surface speed.
    let gear = on("[spindle]\ntype = \"gear\"\n");
    assert_eq!(codes("G96 S1\nM30\n", &gear), [("E2003", 1)]);
    assert_eq!(codes("G97 S02\nM30\n", &gear), []);
}

#[test]
fn written_numbers_out_of_their_range_are_e1010_even_where_never_reached() {
    // §1.9 and §8.1: G30 P 2–4 (§4.4), G31 P and G04 Q 1–4 (§4.2, §4.5),
    // T 0–9999.
    for block in [
        "G30 P5 U0",
        "G30 P1 U0",
        "G31 X10 F10 P5",
        "G04 P100 Q5",
        "G04 P100 Q0",
        "T10000",
        "T-1",
    ] {
        assert_eq!(
            errors(&format!("{block}\nM30\n")),
            [("E1010", 1)],
            "{block}"
        );
        // Behind an IF that never holds: still the literal's fault.
        let skipped = format!("#1=1\nIF[#1EQ2]GOTO10\nGOTO20\nN10 {block}\nN20 M30\n");
        assert_eq!(errors(&skipped), [("E1010", 4)], "{block}");
    }
    assert_eq!(
        errors("G30 P4 U0\nG31 X10 F10 P4\nG04 P100 Q1\nT0\nM30\n"),
        []
    );
}

#[test]
fn computed_numbers_out_of_their_range_are_e5010() {
    // §8.4: E5010 is the computed value's; E1010 is a compile-time code.
    for src in [
        "#1=10000\nM#1\nM30\n",
        "#1=-5\nS#1\nM30\n",
        "#1=-5\nG98 F#1\nM30\n",
        "#1=5\nG30 P#1 U0\nM30\n",
        "#1=0\nG04 P100 Q#1\nM30\n",
        "#1=-16\nT#1\nM30\n",
    ] {
        assert_eq!(alarm_of(src), 5010, "{src}");
    }
}

#[test]
fn g65_or_g66_not_first_in_its_block_is_e2002() {
    // §7.9: "G65/G66 must be the first word after N": E2002 at the call.
    for block in ["G67 G66 P1", "G00 G65 P1", "G00 G66 P1", "X1 G65 P1"] {
        let src = format!("{block}\nM30\nO1\nM99\n");
        let m = messages(&src, &Options::default());
        assert_eq!(m.len(), 1, "{block}: {m:?}");
        assert_eq!((m[0].0, m[0].1), ("E2002", 1), "{block}");
        assert!(m[0].2.contains("must be the first word"), "{block}: {m:?}");
    }
}

#[test]
fn a_computed_g_code_is_named_as_computed() {
    // #1 = 1.25 is no G code; the message must not call it G1.3.
    let src = "#1=1.25\nG#1 X10\nM30\n";
    let c = compile("p.nc", src.as_bytes(), &Options::default());
    let mut vm = Vm::new(c.module.expect("module"), Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    let Status::Alarm(a) = vm.run(&mut events) else {
        panic!("no alarm")
    };
    assert!(a.message.contains("G1.25"), "{}", a.message);
}

#[test]
fn blocks_before_the_first_o_line_say_what_became_of_the_o_program() {
    // docs/language.md §1: they are O0000, the main program, and O0001 a
    // subprogram; W101's help says so, naming O0001.
    let m = messages("G00 X10 Z5\nO1\nG00 X1\nM30\n", &Options::default());
    assert_eq!((m[0].0, m[0].1), ("W101", 1));
    let c = compile(
        "p.nc",
        b"G00 X10 Z5\nO1\nG00 X1\nM30\n",
        &Options::default(),
    );
    let help = c.diags[0].1.help.clone().unwrap_or_default();
    assert!(
        help.contains("O0001") && help.contains("subprogram"),
        "{help}"
    );
    // A file that is O programs only gets no such help.
    let c = compile("p.nc", b"O5\nG00 X10 Z5\nO1\nM99\n", &Options::default());
    assert!(
        c.diags.iter().all(|(_, d)| d.help.is_none()),
        "{}",
        c.render()
    );
}

#[test]
fn the_tool_starts_at_machine_zero_whatever_the_work_offsets() {
    // §2.5, machine.md §1: homed at power-on, the tool at machine X0 Z0.
    // With G54 at machine X5 Z7 that is work X-5 Z-7, and G53 X0 Z0 goes
    // nowhere.
    let g54 = on("[coords]\ng54 = { x = 5.0, z = 7.0 }\n");
    let (canon, _) = run_on("G00 U0 W0\nG53 X0 Z0\nG00 U0 W0\nM30\n", &g54);
    assert_eq!(
        canon,
        [
            "RAPID X=-5 Z=-7",
            "RAPID X=-5 Z=-7",
            "RAPID X=-5 Z=-7",
            "STOP KIND=M30"
        ]
    );
    // EXOFS (1, 1) and G55 (2, 3): work zero at machine (3, 4).
    let both = on("[coords]\nexofs = { x = 1.0, z = 1.0 }\ng55 = { x = 2.0, z = 3.0 }\n");
    let (canon, _) = run_on("G55 G00 U0 W0\nM30\n", &both);
    assert_eq!(canon[..2], ["ORIGIN X=3 Z=4", "RAPID X=-3 Z=-4"]);
}

#[test]
fn feed_is_printed_when_it_differs_as_printed() {
    // canon.md, FEED: "when its F or MODE, as printed, differs from the
    // last FEED printed". F0.20001 and F0.20004 print as 0.2; 0.2002 not.
    let src = "G99 F0.2\nG00 X10 Z0\nG01 Z-12\nF0.20001 Z-13\nF0.20004 Z-14\nF0.2002 Z-15\nM30\n";
    let (canon, _) = run_on(src, &Options::default());
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=0",
            "FEED F=0.2 MODE=REV",
            "LINE X=10 Z=-12",
            "LINE X=10 Z=-13",
            "LINE X=10 Z=-14",
            "FEED F=0.2002 MODE=REV",
            "LINE X=10 Z=-15",
            "STOP KIND=M30"
        ]
    );
}

/// Offset 1: a 0.8 mm nose, tip 3 (comp.md §11).
const NOSE: &str = "[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n";

#[test]
fn an_interference_stands_on_the_block_of_its_element() {
    // comp.md §5: "ρ − R ≤ 0: E4036 at the arc's block", and §7: a
    // rounding is an element of the block that carries D. The D0.5 turns
    // right from −Z to +X: clockwise, G42 on the centre's side, 0.5 < 0.8.
    let head = "O1\nG99 T0101\nG00 X60 Z5\n";
    let small = format!("{head}G42 G00 X20 Z2\nG01 Z-10 D0.5 F0.1\nX30\nG40 G00 X70 Z5\nM30\n");
    assert_eq!(codes(&small, &on(NOSE)), [("E4036", 5)]);
    // X19.8 after Z-10 under G42: past the outside corner its offset runs
    // from r 10 to the inside point at r 10.7, backwards against −r. The
    // block is line 6, whatever blocks without a move come after it.
    let back =
        format!("{head}G42 G01 X20 Z0 F0.1\nG01 Z-10\nG01 X19.8\nG01 Z-20\nG40 G00 X70\nM30\n");
    assert_eq!(codes(&back, &on(NOSE)), [("E4036", 6)]);
    let idle = back.replace("G01 X19.8\n", "G01 X19.8\nM08\nG04 X1\nM09\n");
    assert_eq!(codes(&idle, &on(NOSE)), [("E4036", 6)]);
}

#[test]
fn the_element_that_interferes_is_not_printed() {
    // canon.md, ALARM: the faulty block's motion is not printed. X#1 =
    // 19.8 is the element that runs backwards (line 7); Z-10 ends on its
    // own normal at Z-10.8 (r 10 + 0.8 · (0, −1) turned by G42), and
    // neither the corner's arc nor X19.8's leg is printed.
    let src = "O1\nG99 T0101\n#1=19.8\nG00 X60 Z5\nG42 G01 X20 Z0 F0.1\nG01 Z-10\nG01 X#1\nG01 Z-20\nG40 G00 X70\nM30\n";
    let (canon, status) = run_on(src, &on(NOSE));
    let Status::Alarm(a) = status else {
        panic!("{canon:?}")
    };
    assert_eq!((a.code, a.line), (4036, 7));
    assert_eq!(
        canon[..5],
        [
            "TOOL T=1 D=1",
            "RAPID X=60 Z=5",
            "FEED F=0.1 MODE=REV",
            "LINE X=20 Z=-0.8",
            "LINE X=20 Z=-10.8"
        ]
    );
    assert!(canon[5].starts_with("ALARM CODE=4036"), "{canon:?}");
    assert_eq!(canon.len(), 6);
}

#[test]
fn a_corner_arc_at_f0_faults_at_the_block_it_is_printed_with() {
    // comp.md §5: the outside corner's arc is a feed move at the modal F,
    // printed with element 2 as the first leg of its block. Before Z-20
    // (line 7) that arc runs at F0: W107 there, and E7001 when run.
    let src = "O1\nT0101\nG00 X60 Z5\nG42 G00 X20 Z2\nG00 Z-10\nX30\nZ-20\nG40 G00 X70 Z5\nM30\n";
    assert_eq!(codes(src, &on(NOSE)), [("W107", 7)]);
    let (canon, status) = run_on(src, &on(NOSE));
    let Status::Alarm(a) = status else {
        panic!("{canon:?}")
    };
    assert_eq!((a.code, a.line), (7001, 7));
}

#[test]
fn an_error_about_one_word_points_at_that_word() {
    // dialect.md §0 asks for the line; the column of the offending word
    // tells a reader which of a block's words it is.
    for (block, col) in [
        ("G00 X10 X20", 9),
        ("S100 M3.5", 6),
        ("G0 X10 H1.", 8),
        ("G01 X10 F-0.2", 9),
        ("G30 P5 U0", 5),
        ("M03 M08 T10000", 9),
        // A drilling block's second M word (its one M is the clamp code).
        ("G83 X0 Z-10 Q2000 F0.1 M08 M09", 28),
        // Rigid tapping without its M29: the G84.
        ("G98 G84 Z-10 F1", 5),
        // A second M29 (the first in the block before).
        ("M29 S100\nM05 M29 S100", 5),
    ] {
        let src = format!("{block}\nM30\n");
        let c = compile("p.nc", src.as_bytes(), &Options::default());
        let (f, d) = &c.diags[0];
        assert!(d.is_error(), "{block}: {}", c.render());
        let line = block.lines().count();
        assert_eq!(c.files[*f].line_col(d.span.start), (line, col), "{block}");
    }
}

#[test]
fn an_error_about_one_of_a_planes_words_points_at_that_word() {
    // §4.6: in G12.1 a T word, a G99 and a G54..G59 or drilling code are
    // refused: the error stands on the word (the G among the block's G
    // codes), where it underlined the whole block.
    let opts = on("[axes.c]\nenabled = true\n");
    for (block, col) in [
        ("G01 X10 C5 T0101", 12),
        ("G98 G99 G01 X10 C5", 5),
        ("G01 G55 X10 C5", 5),
        ("G98 G83 X10 C5", 5),
    ] {
        let src = format!("G98 G00 X20 Z5 C0\nG12.1\n{block}\nG13.1\nM30\n");
        let c = compile("p.nc", src.as_bytes(), &opts);
        let (f, d) = (c.diags.iter().find(|(_, d)| d.is_error()))
            .unwrap_or_else(|| panic!("{block}: {}", c.render()));
        assert_eq!(c.files[*f].line_col(d.span.start), (3, col), "{block}");
    }
}

#[test]
fn a_decimal_point_on_a_word_in_increments_hints_the_increments() {
    // §4.13: "`Q3.` on G83/G74/G75/G76 | E1009 | these take integer
    // 0.001-mm units: `Q3000`"; §1.9: angles in 0.001°.
    let cases = [
        ("G76 X26 Z-20 P1000 Q3. F2", "write Q3000"),
        ("G74 X20 Z-10 P1.5 Q2000 F0.1", "write P1500"),
        ("G83 Z-10 Q1.5 F50", "write Q1500"),
        ("G32 Z-20 F2 Q90.", "for 90° write Q90000"),
        // G76's first block P is digits, not increments.
        ("G76 P010060. Q50", "write P10060"),
    ];
    for (block, hint) in cases {
        let src = format!("G00 X30 Z5\n{block}\nM30\n");
        let found = messages(&src, &Options::default());
        assert_eq!(found.len(), 1, "{block}: {found:?}");
        let (code, line, msg) = &found[0];
        assert_eq!((*code, *line), ("E1009", 2), "{block}");
        assert!(msg.ends_with(&format!("{hint})")), "{block}: {msg}");
    }
}

#[test]
fn g76_without_finishing_passes_is_out_of_range() {
    // §4.8 G76: "m 01–99". P000060 is m = 00 (the thread would stay d
    // short of its depth), P1000060 m = 100; P010060 is m = 01.
    let prog = |p: &str| {
        format!("G97 S500 M03\nG00 X30 Z5\nG76 {p} Q100 R0.2\nG76 X26 Z-20 P1000 Q400 F2\nM30\n")
    };
    assert_eq!(errors(&prog("P000060")), [("E1010", 3)]);
    assert_eq!(errors(&prog("P1000060")), [("E1010", 3)]);
    assert_eq!(errors(&prog("P010060")), []);
    // Computed: E5010 when the block runs.
    assert_eq!(alarm_of(&prog("P#1").replace("G97", "#1=60\nG97")), 5010);
}

#[test]
fn a_call_or_a_return_ends_a_thread_chain() {
    // cycles.md §16.2: "Any other NC block ends the chain". The M99 after
    // the sub's G32 ends it, so that block runs out (§16.4): K2 back from
    // Z−10 is Z−8, J1 lifts the radius by 1 (X30 → X32). The G32 after
    // the call starts a new chain and runs out the same way (J/K modal).
    let src = "G97 S300 M03\nG00 X30 Z5\nM98 P1000\nG32 Z-30\nG00 X40\nM30\nO1000\nG32 Z-10 F2 J1 K2\nM99\n";
    let (canon, status) = run_on(src, &Options::default());
    assert_eq!(status, Status::Done);
    let threads: Vec<&str> = canon
        .iter()
        .map(String::as_str)
        .filter(|l| l.starts_with("THREAD"))
        .collect();
    assert_eq!(
        threads,
        [
            "THREAD X=30 Z=-8 LEAD=2",
            "THREAD X=32 Z=-10 LEAD=2",
            "THREAD X=30 Z=-28 LEAD=2",
            "THREAD X=32 Z=-30 LEAD=2"
        ]
    );
    // The same with the call between two thread blocks of the main
    // program: the first one runs out before M98.
    let src = "G97 S300 M03\nG00 X30 Z5\nG32 Z-10 F2 J1 K2\nM98 P1000\nG32 Z-30\nM30\nO1000\nM99\n";
    let (canon, _) = run_on(src, &Options::default());
    assert_eq!(canon[3], "THREAD X=30 Z=-8 LEAD=2");
    assert_eq!(canon[4], "THREAD X=32 Z=-10 LEAD=2");
}

#[test]
fn a_work_zero_written_inside_the_plane_stops_the_run() {
    // §4.6: the plane is fixed to the work zero where the mode starts; a
    // #5221 write inside would move it under the tool (G54–G59 are E2007
    // there). Known when compiled: W124, and E4033 when run.
    let opts = on("[axes.c]\nenabled = true\n");
    for (start, write, end) in [
        ("G12.1", "#5221=-10.", "G13.1"),
        ("G7.1 C10.", "#5222=-5.", "G7.1 C0"),
    ] {
        let src = format!("G98 G00 X20 Z5 C0\n{start}\nG01 X10 C5 F100\n{write}\n{end}\nM30\n");
        assert_eq!(codes(&src, &opts), [("W124", 4)], "{write}");
        match run_on(&src, &opts).1 {
            Status::Alarm(a) => assert_eq!(a.code, 4033, "{write}"),
            other => panic!("{write}: {other:?}"),
        }
    }
}

#[test]
fn group_12_reads_g66_while_a_modal_call_is_in_force() {
    // §7.2: #4012 is the G code in force in group 12 (§3: G66 G67, G67 at
    // power-on), in the macro G66 calls too.
    let src = "#500=#4012\nG66 P9001 A1\n#501=#4012\nG00 X1\n#502=#4012\nG67\n#503=#4012\nM30\nO9001\n#510=#4012\nM99\n";
    let (vm, _, status) = vm_run(src, &Options::default());
    assert_eq!(status, Status::Done);
    let read = |n: u32| vm.variable(n).ok();
    assert_eq!(
        [500, 501, 502, 510, 503].map(read),
        [Some(67.0), Some(66.0), Some(66.0), Some(66.0), Some(67.0)]
    );
}

#[test]
fn a_computed_g_that_rounds_to_minus_zero_is_g00() {
    // §7.6: G values are rounded to one decimal, and −0 is 0.
    for src in ["#1=-0.04\nG#1 X1\nM30\n", "G[-0.04] X1\nM30\n"] {
        let (canon, status) = run_on(src, &Options::default());
        assert_eq!(status, Status::Done, "{src}");
        assert_eq!(canon[0], "RAPID X=1 Z=0", "{src}");
    }
    // −0.05 rounds away from zero to G−0.1: no G code.
    assert_eq!(alarm_of("#1=-0.05\nG#1 X1\nM30\n"), 2001);
}

#[test]
fn g66_calls_follow_group_01_moves_only() {
    // §7.9 Decision: "every group-01 move counts (also G6.x, G7.x,
    // threads, G90/G92/G94)"; a group-00 function that moves (G28, G31,
    // G53, G30) or cycle (G71) is not one. The macro records #4114, the
    // sequence number of the block it follows: N5 (G00), N11 (G90) and
    // N12 (a G01 with G09, the exact stop that rides on it).
    let src = "G00 X50 Z2\nG66 P9001\nN1 G28 U0\nN2 G31 X10 Z-1 F100\nN3 G50 X60 Z5\nN4 G04 X1\nN5 G00 X50 Z2\nN6 G71 U1 R0.5\nN7 G71 P10 Q20 U0 W0 F100\nN10 G00 X40\nN20 G01 Z-10\nN8 G30 P2 U0\nN9 G53 X0 Z0\nN11 G90 X40 Z-5 F100\nN12 G09 G01 X30\nG67\nM30\nO9001\n#100=#100+1\n#[600+#100]=#4114\nM99\n";
    let (vm, _, status) = vm_run(src, &Options::default());
    assert_eq!(status, Status::Done);
    assert_eq!(vm.variable(100).ok(), Some(3.0));
    assert_eq!(vm.variable(601).ok(), Some(5.0));
    assert_eq!(vm.variable(602).ok(), Some(11.0));
    assert_eq!(vm.variable(603).ok(), Some(12.0));
}

#[test]
fn g65_h99_takes_a_variable_q() {
    // §7.8: "Q and R are variables or constants"; H99 is alarm 500 + n,
    // n = Q (§8.4: 500–599). A vacant Q is no Q (§7.5), so 0; a computed
    // Q outside 0…99 is a value out of range (E5010).
    let run = |q: &str| {
        alarm_of(&format!(
            "#1=1\n#2=100\nG65 H99 P#500 Q{q} (OVERHEAT)\nM30\n"
        ))
    };
    assert_eq!(run("#1"), 501);
    assert_eq!(run("[#1+98]"), 599);
    assert_eq!(run("#3"), 500);
    assert_eq!(run("#2"), 5010);
    let (canon, _) = run_on(
        "#1=7\nG65 H99 P#500 Q#1 (OVERHEAT)\nM30\n",
        &Options::default(),
    );
    assert_eq!(canon, ["ALARM CODE=507 MSG=\"OVERHEAT\""]);
}

/// The first diagnostic of `src` on `opts`'s machine: its code, line,
/// column, message and the text it underlines.
fn first_diag(src: &str, opts: &Options) -> (&'static str, usize, usize, String, String) {
    let c = compile("p.nc", src.as_bytes(), opts);
    let Some((f, d)) = c.diags.first() else {
        panic!("no diagnostic for\n{src}");
    };
    let (line, col) = c.files[*f].line_col(d.span.start);
    let text = src
        .get(d.span.start as usize..d.span.end as usize)
        .unwrap_or_default();
    (d.code, line, col, d.message.clone(), text.to_string())
}

#[test]
fn words_that_cannot_stand_there_are_named_at_the_word() {
    // §2.1 (no Y, no C on the reference lathe: E2005) and §4 (E2007):
    // the diagnostic underlines the word at fault; of two words that
    // cannot stand together (X and U), the one written later.
    let y = "this machine has no Y axis";
    let h = "this machine has no C axis (H is the incremental C angle)";
    let xu = "X and U in one block: write the X end point either absolute or incremental";
    let zw = "Z and W in one block: write the Z end point either absolute or incremental";
    let cases: [(&str, &str, usize, usize, &str, &str); 11] = [
        ("G00 Z10 Y5\nM30\n", "E2005", 1, 9, y, "Y5"),
        ("G00 Z10 V5\nM30\n", "E2005", 1, 9, y, "V5"),
        ("G00 Z10 H5\nM30\n", "E2005", 1, 9, h, "H5"),
        (
            "G00 Z10 C5\nM30\n",
            "E2005",
            1,
            9,
            "this machine has no C axis",
            "C5",
        ),
        ("G00 X10 U5\nM30\n", "E2007", 1, 9, xu, "U5"),
        ("G00 U5 X10\nM30\n", "E2007", 1, 8, xu, "X10"),
        ("G00 X10 Z10 W5\nM30\n", "E2007", 1, 13, zw, "W5"),
        (
            "G01 X20 Z-10 Q30000 ,A30 F1\nM30\n",
            "E2007",
            1,
            21,
            "Q and ,A both give the angle: write one of them",
            ",A30",
        ),
        // Rules of the run (the dry run of a static program).
        (
            "G33 Z-10 U2 F1\nM30\n",
            "E2007",
            1,
            10,
            "G33 taps along Z at the current X: X/U cannot stand in a G33 block",
            "U2",
        ),
        (
            "G36 U-2.\nM30\n",
            "E2007",
            1,
            5,
            "G36 takes the absolute measuring position X, not U",
            "U-2.",
        ),
        (
            "G53 U2\nM30\n",
            "E2007",
            1,
            5,
            "G53 takes machine coordinates X/Z only, not U/W",
            "U2",
        ),
    ];
    for (src, code, line, col, msg, text) in cases {
        let want = (code, line, col, msg.to_string(), text.to_string());
        assert_eq!(first_diag(src, &Options::default()), want, "{src}");
    }
}

#[test]
fn a_word_the_run_refuses_is_named_at_the_word() {
    // §1.9: a count with a decimal point (E1009) found by the cycle, not
    // by the block's rules: G92's L in a block of the run that does not
    // name G92. In a G71 profile block (§4.8) X and U (E2007) stand on
    // the profile block's U. Under a C axis, C with H, a chamfer beside
    // a C move, and C under compensation (§2.1, E2007).
    let count = "L is a count here; a decimal point is not allowed";
    let profile =
        "G00 X30 Z5\nG71 U1 R1\nG71 P10 Q20 U0.2 W0.1 F1\nN10 G00 X10 U1\nN20 G01 Z-10\nM30\n";
    let xu = "X and U in one block: write the X end point either absolute or incremental";
    let reference = Options::default();
    assert_eq!(
        first_diag("G00 X30 Z5\nG92 X20 Z-10 F1\nX19 L2.\nM30\n", &reference),
        ("E1009", 3, 5, count.to_string(), "L2.".to_string())
    );
    assert_eq!(
        first_diag(profile, &reference),
        ("E2007", 4, 13, xu.to_string(), "U1".to_string())
    );
    let c_axis = on("[axes.c]\nenabled = true\n");
    let cases = [
        (
            "G00 X10 C5 H2\nM30\n",
            12,
            "C and H in one block: write the C angle either absolute or incremental",
            "H2",
        ),
        (
            "G01 X10 C10 L1 F1\nM30\n",
            13,
            "a block that turns C takes no chamfer, corner rounding or angle (L, D, Q, ,C, ,R, ,A)",
            "L1",
        ),
        (
            "G42 G01 X10 C10 F1\nM30\n",
            13,
            "C cannot move under nose-radius compensation: cancel it with G40 first",
            "C10",
        ),
    ];
    for (src, col, msg, text) in cases {
        let want = ("E2007", 1, col, msg.to_string(), text.to_string());
        assert_eq!(first_diag(src, &c_axis), want, "{src}");
    }
}

#[test]
fn a_word_rule_proven_by_folding_warns_at_the_word() {
    // §0: a fault proven for a computed block is W116 at that line; the
    // word the rule names is the repeated X (E1011 when it runs).
    let (code, line, col, msg, text) = first_diag("#1=5\nG00 X10 X#1\nM30\n", &Options::default());
    assert_eq!((code, line, col, text.as_str()), ("W116", 2, 9, "X#1"));
    assert!(msg.contains("E1011"), "{msg}");
}

#[test]
fn a_corner_too_large_stands_on_its_word_with_the_next_move_labelled() {
    // §5.1: the chamfer belongs to the block that carries L; it is found
    // too large only when the next move is known. From X50 Z5 the L15 line
    // runs 15 mm along Z; X40 then runs 5 mm (radius) down: the chamfer's
    // second point, 15 mm along it (type II, №181.0 = 1), is off it.
    let src = "G00 X50 Z5\nG01 Z-10 L15 F1\nX40\nM30\n";
    let msg = "chamfer 15.0000 is too large: the corner point would fall outside an element";
    let want = ("E4007", 2, 10, msg.to_string(), "L15".to_string());
    assert_eq!(first_diag(src, &Options::default()), want);
    let c = compile("p.nc", src.as_bytes(), &Options::default());
    let related = c.diags.first().and_then(|(f, d)| {
        let (span, label) = d.related.clone()?;
        Some((c.files[*f].line_col(span.start), label))
    });
    assert_eq!(related, Some(((3, 1), "the next move".to_string())));
    // In a G71 profile the corner word's block (line 5) stands, and the
    // note names the cycle (line 3) that ran it.
    let profile = "G00 X50 Z2\nG71 U1 R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\nN10 G00 X20\nG01 Z-10 L15\nN20 X40\nM30\n";
    let want = ("E4007", 5, 10, msg.to_string(), "L15".to_string());
    assert_eq!(first_diag(profile, &Options::default()), want);
    let c = compile("p.nc", profile.as_bytes(), &Options::default());
    let notes = c.diags.first().map(|(_, d)| d.notes.clone());
    assert_eq!(
        notes,
        Some(vec!["in the profile of the cycle at line 3".to_string()])
    );
    // An interference about an earlier element (comp.md §5, E4036 at
    // line 6) is no profile's: the block that ran is labelled, no note.
    let comp = "O1\nG99 T0101\nG00 X60 Z5\nG42 G01 X20 Z0 F0.1\nG01 Z-10\nG01 X19.8\nM08\nG01 Z-20\nG40 G00 X70\nM30\n";
    let c = compile("p.nc", comp.as_bytes(), &on(NOSE));
    let found = c.diags.first().map(|(f, d)| {
        let related = d
            .related
            .as_ref()
            .map(|(s, l)| (c.files[*f].line_col(s.start), l.clone()));
        (
            d.code,
            c.files[*f].line_col(d.span.start),
            related,
            d.notes.len(),
        )
    });
    let next = Some(((8, 1), "the next move".to_string()));
    assert_eq!(found, Some(("E4036", (6, 1), next, 0)));
    // A run (the L computed): the alarm names the L block, line 3.
    let (_, _, status) = vm_run(
        "#1=15\nG00 X50 Z5\nG01 Z-10 L#1 F1\nX40\nM30\n",
        &Options::default(),
    );
    let Status::Alarm(a) = status else {
        panic!("{status:?}")
    };
    assert_eq!((a.code, a.line), (4007, 3));
}

#[test]
fn a_pull_out_lead_above_the_maximum_is_e4010() {
    // cycles.md §12: a pull-out that lifts J10 (radius) over K1 along Z
    // has X as its long axis and cuts at lead·J/K = 100·10/1 = 1000 mm,
    // above threads.max_lead_mm (500 on the reference machine, §4.3
    // "lead ≤ the maximum"). The block names no one word: it stands on
    // the block.
    let msg = "the pull-out leg's lead 1000 mm (100 × J10 / K1: it lifts more than it advances) is above the maximum lead of 500 mm";
    let src = "G00 X30 Z5\nG92 X28 Z-20 F100 J10 K1\nM30\n";
    let (code, line, col, message, _) = first_diag(src, &Options::default());
    assert_eq!((code, line, col, message.as_str()), ("E4010", 2, 1, msg));
    // G76's pull-out of its first block (line 2), cut by the second.
    let g76 = "G00 X30 Z5\nG76 P010060 Q100 R0.1 J10 K1\nG76 X28 Z-20 P1000 Q300 F100\nM30\n";
    let (code, line, _, message, _) = first_diag(g76, &Options::default());
    assert_eq!((code, line, message.as_str()), ("E4010", 3, msg));
    // At F50 the leg's lead is 500 mm, the most allowed: it runs.
    assert!(messages(&src.replace("F100", "F50"), &Options::default()).is_empty());
}
