//! Compile → write → load → verify → run, in process, against canons
//! checked by hand; and corrupted modules are rejected.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn build(src: &str) -> isa::Module {
    let c = compile("test.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    c.module.expect("a module")
}

/// Runs the bytes of a module as gbvm would: load (verifying), then run.
fn canon_of(bytes: &[u8]) -> (Vec<String>, Status) {
    let module = isa::Module::from_bytes(bytes).expect("the module loads");
    let mut vm = Vm::new(module, Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    (events.iter().map(|e| e.to_string()).collect(), status)
}

const SHAFT: &str = include_str!("../../examples/shaft.nc");

#[test]
fn the_example_round_trips_and_prints_its_hand_checked_canon() {
    let module = build(SHAFT);
    let bytes = module.to_bytes();
    let (canon, status) = canon_of(&bytes);
    assert_eq!(status, Status::Done);
    // Hand check: G50 X100 Z50 at machine 0 → zero at X-100 Z-50; the arc
    // G02 X60 Z-35 R5 from X50 Z-30: start r25 z-30, end r30 z-35, centre
    // r30 z-30 (a quarter, clockwise); the groove subprogram runs twice:
    // W-5 then U-12/U12 from X70 at Z-55 and Z-60.
    let expected = [
        "ORIGIN X=-100 Z=-50",
        "TOOL T=1 D=1",
        "SPINDLE DIR=CW",
        "SPEED S=800 MODE=RPM",
        "M CODE=8",
        "RAPID X=40 Z=2",
        "FEED F=0.2 MODE=REV",
        "LINE X=40 Z=-20",
        "LINE X=50 Z=-30",
        "ARC DIR=CW X=60 Z=-35 CX=60 CZ=-30",
        "LINE X=60 Z=-50",
        "RAPID X=70 Z=-50",
        "RAPID X=70 Z=-55",
        "FEED F=0.08 MODE=REV",
        "LINE X=58 Z=-55",
        "DWELL S=0.5",
        "RAPID X=70 Z=-55",
        "RAPID X=70 Z=-60",
        "LINE X=58 Z=-60",
        "DWELL S=0.5",
        "RAPID X=70 Z=-60",
        "RAPID X=100 Z=50",
        "M CODE=9",
        "STOP KIND=M30",
    ];
    assert_eq!(canon, expected);
}

#[test]
fn every_truncation_and_bit_flip_of_a_compiled_module_is_rejected() {
    let bytes = build("N1 G00 X10 Z2\n#1=#1+1\nIF[#1LT3]GOTO1\nM30\n").to_bytes();
    assert!(isa::Module::from_bytes(&bytes).is_ok());
    for len in 0..bytes.len() {
        assert!(
            isa::Module::from_bytes(&bytes[..len]).is_err(),
            "truncated at {len}"
        );
    }
    for bit in 0..bytes.len() * 8 {
        let mut b = bytes.clone();
        b[bit / 8] ^= 1 << (bit % 8);
        assert!(isa::Module::from_bytes(&b).is_err(), "bit {bit} flipped");
    }
}

#[test]
fn a_run_time_alarm_names_its_source_line() {
    let module = build("G00 X10\n#1=0\n#2=5/#1\nM30\n");
    let (canon, status) = canon_of(&module.to_bytes());
    let Status::Alarm(a) = status else {
        panic!("expected an alarm, got {status:?}")
    };
    assert_eq!((a.code, a.line), (5001, 3));
    assert!(
        a.header().starts_with("test.nc:3:1: alarm[E5001]: "),
        "{}",
        a.header()
    );
    assert_eq!(
        canon
            .last()
            .map(String::as_str)
            .unwrap_or("")
            .split(' ')
            .next(),
        Some("ALARM")
    );
}

#[test]
fn a_literal_division_by_zero_warns_and_alarms_only_when_reached() {
    let c = compile(
        "w.nc",
        b"#1=1\nIF[#1EQ1]GOTO3\n#2=1/0\nN3 G00 X5\nM30\n",
        &Options::default(),
    );
    assert!(!c.has_errors());
    assert!(
        c.diags.iter().any(|(_, d)| d.code == "W116"),
        "{}",
        c.render()
    );
    let (canon, status) = canon_of(&c.module.expect("module").to_bytes());
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=5 Z=0", "STOP KIND=M30"]);
}

/// `M98 P… L[…]`: a written program with a computed count is a call of a
/// known program (`callsub`, not looked up at run time), run L times.
#[test]
fn a_computed_count_calls_a_known_program() {
    let src = "#1=#500\nM98 P1000 L[#1+2]\nM30\nO1000\nG00 U2\nM99\n";
    let c = compile("l.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let module = c.module.expect("module");
    assert!(module
        .code
        .iter()
        .any(|i| matches!(i, isa::Instr::CallSub { .. })));
    assert!(!module
        .code
        .iter()
        .any(|i| matches!(i, isa::Instr::CallSubDyn { .. })));
    // #500 is vacant: L[vacant + 2] = 2 runs.
    let (canon, status) = canon_of(&module.to_bytes());
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=2 Z=0", "RAPID X=4 Z=0", "STOP KIND=M30"]);
}

#[test]
fn structure_errors_are_compile_errors_at_their_line() {
    let long_then_o0000 = "G01 X10 Z-1 F100\n".repeat(20_000) + "O0000\nM30\n";
    let cases: [(&str, &str, usize); 10] = [
        // The blocks before the first O line are the main program, O0000:
        // a later O0000 defines it again (static, with macros, or after
        // a long plain part compiled a chunk at a time).
        ("G00 X10\nO0000\nM30\n", "E1005", 2),
        ("#1=1\nG00 X10\nO0000\nM30\n", "E1005", 3),
        (&long_then_o0000, "E1005", 20_001),
        ("G00 X10\nM98 P1234\nM30\n", "E2012", 2),
        // With L, P is the program even when L is computed.
        ("#1=#500\nM98 P1234 L[#1+1]\nM30\n", "E2012", 2),
        ("GOTO 50\nM30\n", "E2010", 1),
        ("WHILE[1LT2]DO4\nEND4\n", "E2013", 1),
        ("G00 X0\nEND1\n", "E2014", 2),
        ("G00 X10 Z0\nG02 X10 Z-30 R5\n", "E4001", 2),
        ("T3301\n", "E7004", 1),
    ];
    for (src, code, line) in cases {
        let c = compile("e.nc", src.as_bytes(), &Options::default());
        let (f, d) = c
            .diags
            .iter()
            .find(|(_, d)| d.is_error())
            .unwrap_or_else(|| panic!("no error for {src:?}"));
        assert_eq!(d.code, code, "{src:?}: {}", c.render());
        assert_eq!(c.files[*f].line_col(d.span.start).0, line, "{src:?}");
    }
}

/// A DO label open twice, or a fourth loop inside three: one error at
/// that DO. Its END closes it, so the outer ENDs meet their own DOs and
/// no error about crossed loops follows. Crossed loops: one error at the
/// END that crosses, none at the crossed loop's own END; a stray END
/// leaves the loop around it open for its own END.
#[test]
fn a_loop_error_is_told_once() {
    let open_twice = "WHILE[#1LT1]DO1\nWHILE[#1LT1]DO2\nWHILE[#1LT1]DO1\n\
                      #1=1\nEND1\nEND2\nEND1\nM30\n";
    let four_deep = "WHILE[#1LT1]DO1\nWHILE[#1LT1]DO2\nWHILE[#1LT1]DO3\n\
                     WHILE[#1LT1]DO2\n#1=1\nEND2\nEND3\nEND2\nEND1\nM30\n";
    let crossed = "#1=0\nWHILE[#1LT1]DO1\nWHILE[#1LT1]DO2\n#1=1\nEND1\nEND2\nM30\n";
    let stray = "#1=0\nWHILE[#1LT1]DO1\n#1=1\nEND2\nEND1\nM30\n";
    for (src, line) in [(open_twice, 3), (four_deep, 4), (crossed, 5), (stray, 4)] {
        let c = compile("e.nc", src.as_bytes(), &Options::default());
        let errors: Vec<_> = (c.diags.iter())
            .filter(|(_, d)| d.is_error())
            .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
            .collect();
        assert_eq!(errors, [("E2014", line)], "{}", c.render());
    }
}

#[test]
fn folding_off_and_on_run_the_same() {
    let src = "#1=[2+3]*SIN[30]\n#2=ATAN[1]/[-1]\nG01 X[#1*4] Z[-#2/10] F100\nM30\n";
    let run = |optimize| {
        let c = compile(
            "f.nc",
            src.as_bytes(),
            &Options {
                optimize,
                ..Options::default()
            },
        );
        canon_of(&c.module.expect("module").to_bytes()).0
    };
    assert_eq!(run(false), run(true));
    // 5·sin 30° = 2.5 → X10; ATAN[1]/[-1] = 135° → Z-13.5.
    assert_eq!(run(true)[1], "LINE X=10 Z=-13.5");
}
