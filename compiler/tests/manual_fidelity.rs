//! The manual's own examples that gbc once got wrong (issue 16): each
//! expected canon or diagnostic is worked out by hand from the seeds.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn machine(toml: &str) -> Machine {
    Machine::from_toml(toml).expect("a valid machine file")
}

fn run_on(src: &str, m: Machine) -> (Vec<String>, Status) {
    let opts = Options {
        machine: m.clone(),
        ..Options::default()
    };
    let c = compile("m.nc", src.as_bytes(), &opts);
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), m);
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    (events.iter().map(|e| e.to_string()).collect(), status)
}

fn run(src: &str) -> Vec<String> {
    let (canon, status) = run_on(src, Machine::reference());
    assert_eq!(status, Status::Done, "{canon:?}");
    canon
}

/// The codes of the compile-time errors, with their line numbers.
fn errors_on(src: &str, m: Machine) -> Vec<(String, usize)> {
    let opts = Options {
        machine: m,
        ..Options::default()
    };
    let c = compile("m.nc", src.as_bytes(), &opts);
    c.diags
        .iter()
        .filter(|(_, d)| d.is_error())
        .map(|(f, d)| (d.code.to_string(), c.files[*f].line_col(d.span.start).0))
        .collect()
}

const G55: &str = "[coords]\ng55 = { x = -20.0, z = -30.0 }\n";

#[test]
fn selecting_g55_keeps_the_tool_where_it_is() {
    // G55 zero at machine X-20 Z-30. The tool stands at machine X10 Z10
    // (G54 = machine here), so in G55 it is at X10+20 = 30, Z10+30 = 40:
    // U0 W0 goes nowhere and prints those coordinates, as #5041/#5042 read.
    let src = "G00 X10 Z10\nG55\nG00 U0 W0\nG00 X#5041 Z[#5042+1]\nM30\n";
    let (canon, _) = run_on(src, machine(G55));
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=10",
            "ORIGIN X=-20 Z=-30",
            "RAPID X=30 Z=40",
            "RAPID X=30 Z=41",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn g50_after_g55_puts_the_zero_under_the_tool() {
    // The tool at machine X10 Z10; G50 X0 Z0 makes that point the zero:
    // ORIGIN X=10 Z=10 (machine), and #5041/#5042 read 0/0.
    let src = "G00 X10 Z10\nG55\nG50 X0 Z0\nG00 X[#5041+1] Z[#5042+2]\nM30\n";
    let (canon, _) = run_on(src, machine(G55));
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=10",
            "ORIGIN X=-20 Z=-30",
            "ORIGIN X=10 Z=10",
            "RAPID X=1 Z=2",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn g55_with_g50_in_one_block_is_ignored() {
    // Seed 000, G54–G59 note 6: in G55 G50 X0 Z0 only G50 acts, so G54
    // stays (#4014 = 54) and the zero is the tool's point, machine X10 Z10.
    let src = "G00 X10 Z10\nG55 G50 X0 Z0\nG00 X#4014 Z#5042\nM30\n";
    let (canon, _) = run_on(src, machine(G55));
    assert_eq!(
        canon,
        [
            "RAPID X=10 Z=10",
            "ORIGIN X=10 Z=10",
            "RAPID X=54 Z=0",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn g04_with_x_and_u_dwells_the_x_time() {
    // Seed 000, G04 note 3: with X and U both written, X is in force.
    assert_eq!(
        run("G04 X3 U5\nG04 U1.5\nM30\n"),
        ["DWELL S=3", "DWELL S=1.5", "STOP KIND=M30"]
    );
}

#[test]
fn g05_back_to_its_start_is_e4004() {
    // No end point: the end is the start, a full circle G05 cannot make;
    // the same code as an explicit X0 Z0.
    let m = Machine::reference;
    let implicit = "G00 X0 Z0\nG05 I10 K-10 F100\nM30\n";
    assert_eq!(errors_on(implicit, m()), [("E4004".to_string(), 2)]);
    let explicit = "G00 X0 Z0\nG05 X0 Z0 I10 K-10 F100\nM30\n";
    assert_eq!(errors_on(explicit, m()), [("E4004".to_string(), 2)]);
}

#[test]
fn g16_outside_polar_interpolation_is_e2007() {
    // dialect.md §4.6: G16 only inside G12.1.
    let src = "G00 X10\nG16\nM30\n";
    assert_eq!(
        errors_on(src, Machine::reference()),
        [("E2007".to_string(), 2)]
    );
}

#[test]
fn a_written_gear_code_out_of_range_is_a_compile_error() {
    // dialect.md §6.2: S00…S04 on a gear spindle; a literal S05 is E1010
    // at compile time, a computed one the run-time E5010.
    let gear = || machine("[spindle]\ntype = \"gear\"\n");
    assert_eq!(
        errors_on("M03 S05\nM30\n", gear()),
        [("E1010".to_string(), 1)]
    );
    let (canon, status) = run_on("M03 S04\nM30\n", gear());
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["SPINDLE DIR=CW", "GEAR N=4", "STOP KIND=M30"]);
    let computed = "#1=5\nM03 S#1\nM30\n";
    let (canon, status) = run_on(computed, gear());
    assert!(matches!(status, Status::Alarm(_)), "{status:?}");
    assert!(canon
        .last()
        .is_some_and(|l| l.starts_with("ALARM CODE=5010")));
}

/// The rendered diagnostics of a program that must not compile.
fn rendered(src: &str) -> String {
    let c = compile("m.nc", src.as_bytes(), &Options::default());
    assert!(c.has_errors(), "expected an error");
    c.render()
}

#[test]
fn e4009_points_at_the_profile_block_that_turns_back() {
    // The bore of a real program (corpus icnc…Cesar-Rottava…O001, N420–N490):
    // N490 G03 X10 Z-30 R2 runs from r7 to r5 about r6 z(−30 + √3): the
    // arc bulges to z = −30 + √3 − 2 = −30.2679, 0.268 mm past its end Z-30,
    // against the cut (−Z). The error stands on the cycle block (line 3,
    // dialect.md §8.3), points to N490 and says how to get out.
    let src = "G00 X9 Z2 G99 F0.1\nG71 U0.5 R0.3\nG71 P440 Q490 U0 W0 F0.1\nN440 G00 X30\nN450 G01 Z-10\nN460 G03 X26 Z-12 R2\nN470 G01 X14 Z-20\nN480 Z-30\nN490 G03 X10 Z-30 R2\nM30\n";
    let out = rendered(src);
    assert!(
        out.contains("m.nc:3:1: error[E4009]: the G71 profile is not monotonic: a profile block reaches Z-30.2679, 0.268 mm past its end point Z-30"),
        "{out}"
    );
    // The snippet shows N490 (line 9) labelled under the cycle block.
    assert!(
        out.contains("9 │ N490 G03 X10 Z-30 R2\n  │ -------------------- this block"),
        "{out}"
    );
    assert!(out.contains("help: G71 cuts along Z"), "{out}");
}

#[test]
fn e4009_calls_a_pocket_of_type_i_by_its_name() {
    // Type I (the ns block names X only) with K1: N4 goes from X30 down to
    // X24, back into the material; the way out is type II.
    let src = "G00 X40 Z2\nG71 U3 R1\nG71 P1 Q7 K1 F0.2\nN1 G00 X20\nG01 Z-10\nX30\nZ-20\nX24\nZ-30\nN7 X40\nM30\n";
    let out = rendered(src);
    assert!(
        out.contains("m.nc:3:1: error[E4009]: the G71 profile is not monotonic: a profile block runs back along X from X30 to X24"),
        "{out}"
    );
    assert!(out.contains("8 │ X24\n  │ --- this block"), "{out}");
    assert!(out.contains("type II"), "{out}");
}
