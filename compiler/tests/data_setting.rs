//! G10 L3 / G10 L52 … G11 (dialect.md §4.9) and tool life (§6.3) through
//! the compiler and the VM; expected values checked by hand against
//! machine.md (reference parameters) and the rules of the two sections.

use compiler::{compile, Compiled, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn compiled(src: &str) -> Compiled {
    compile("d.nc", src.as_bytes(), &Options::default())
}

/// (code, line) of every diagnostic.
fn diags(src: &str) -> Vec<(&'static str, usize)> {
    let c = compiled(src);
    c.diags
        .iter()
        .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
        .collect()
}

fn run_with(src: &str, machine: Machine) -> (Vec<String>, Status, Vm) {
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    let c = compile("d.nc", src.as_bytes(), &opts);
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), machine);
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    let canon = events.iter().map(|e| e.to_string()).collect();
    (canon, status, vm)
}

fn run(src: &str) -> (Vec<String>, Status, Vm) {
    run_with(src, Machine::reference())
}

#[test]
fn an_unknown_literal_parameter_is_e2050_at_its_line() {
    assert_eq!(
        diags("G10 L52\nN172 R#100\nN999 R#101\nG11\nM30\n"),
        [("E2050", 3)]
    );
}

#[test]
fn plc_parameters_are_e2099() {
    assert_eq!(diags("G10 L52\nK5 R#100\nG11\nM30\n"), [("E2099", 2)]);
    assert_eq!(diags("G10 L52\nD5 W1\nG11\nM30\n"), [("E2099", 2)]);
    // DT and DC are no addresses of the grammar; they get E2099 too.
    assert_eq!(diags("G10 L52\nDT5 R#100\nG11\nM30\n"), [("E2099", 2)]);
    assert_eq!(diags("G10 L52\nDC5 W1\nG11\nM30\n"), [("E2099", 2)]);
}

#[test]
fn a_parameter_block_needs_r_or_w_but_not_both() {
    assert_eq!(diags("G10 L52\nN172\nG11\nM30\n"), [("E2006", 2)]);
    assert_eq!(diags("G10 L52\nN172 R#1 W1\nG11\nM30\n"), [("E2007", 2)]);
}

#[test]
fn other_g10_forms_are_e2004() {
    assert_eq!(diags("G10 P1 X10 Z5\nM30\n"), [("E2004", 1)]);
    assert_eq!(diags("G00 X1\nG10 L2 P1 X10\nM30\n"), [("E2004", 2)]);
}

#[test]
fn g11_without_g10_and_ignored_words_are_w104() {
    assert_eq!(diags("G11\nM30\n"), [("W104", 1)]);
    // X on the group block and S on its own block are not tool-life words.
    assert_eq!(
        diags("G10 L3\nP1 L10 X5\nT0101\nS300\nG11\nM30\n"),
        [("W104", 2), ("W104", 4)]
    );
    // A tool before any group has nowhere to go.
    assert_eq!(
        diags("G10 L3\nT0101\nP1 L5\nT0202\nG11\nM30\n"),
        [("W104", 2)]
    );
    // A call inside the mode is program flow, not an ignored word; M30 is
    // ignored like any other word (the kernel does not end the run there).
    assert_eq!(
        diags("G10 L3\nM98 P1000\nM30\nG11\nM30\nO1000\nM99\n"),
        [("W104", 3)]
    );
    // F in a parameter block.
    assert_eq!(diags("G10 L52\nN172 R#1 F5\nG11\nM30\n"), [("W104", 2)]);
}

#[test]
fn n_inside_g10_l52_is_no_sequence_number() {
    // GOTO 172 finds no block N172: the N172 of the parameter block does
    // not count.
    assert_eq!(
        diags("G10 L52\nN172 R#100\nG11\nGOTO172\nM30\n"),
        [("E2010", 4)]
    );
    // N19 is once a sequence number and once a parameter: no W103.
    let src = "#2=0\nN19 #2=#2+1\nG10 L52\nN19 R#1\nG11\nIF[#2LT2]GOTO19\nM30\n";
    assert_eq!(diags(src), []);
    let (canon, status, vm) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["STOP KIND=M30"]);
    assert_eq!(vm.variable(2), Ok(2.0));
    // №019 (thread pull-out) is 0 on the reference machine.
    assert_eq!(vm.variable(1), Ok(0.0));
}

#[test]
fn n_inside_g10_l52_is_no_profile_number() {
    // N22 stands once in the profile and once as parameter №022: the G71
    // finds one N22 and no W103.
    let src = "G99 G00 X40 Z2\nG71 U1 R0.5\nG71 P22 Q23 U0.2 W0.1 F0.2\nN22 G00 X30\nN23 G01 Z-10\nG10 L52\nN22 P2 R#1\nG11\nM30\n";
    assert_eq!(diags(src), []);
}

#[test]
fn g10_l52_reads_and_writes_end_to_end() {
    // №172 = 00010000 (bit 4 on), №022 of Z = 10000 mm/min, №181 written
    // to 0 and read back; #103 = #100 + #101 = 20000. X[#100/1000] moves
    // to X10: the compiler did not fold #100 as vacant.
    let src = "G10 L52\nN172 R#100\nN22 P2 R#101\nN181 W0\nN181 R#[100+2]\nG11\n\
               #103=#100+#101\nG00 X[#100/1000] Z[#102]\nM30\n";
    let (canon, status, vm) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=10 Z=0", "STOP KIND=M30"]);
    assert_eq!(vm.variable(100), Ok(10000.0));
    assert_eq!(vm.variable(101), Ok(10000.0));
    assert_eq!(vm.variable(102), Ok(0.0));
    assert_eq!(vm.variable(103), Ok(20000.0));
}

#[test]
fn g10_l52_writes_a_system_variable_too() {
    // R#2001 fills wear offset X of offset 1 with №141 (50 mm/min).
    let (_, status, vm) = run("G10 L52\nN141 R#2001\nG11\nM30\n");
    assert_eq!(status, Status::Done);
    assert_eq!(vm.variable(2001), Ok(50.0));
}

#[test]
fn a_bad_write_value_is_a_run_time_alarm() {
    // 12 has the digit 2: not a bit pattern. Computed: E5010 at run time.
    let (_, status, _) = run("#1=12\nG10 L52\nN172 W#1\nG11\nM30\n");
    let Status::Alarm(a) = status else {
        panic!("{status:?}")
    };
    assert_eq!(a.code, 5010);
    // Written: the literal's fault, E1010 before the run; so are an axis
    // P4 and a tool-life group P33 or unit Q3.
    assert_eq!(diags("G10 L52\nN172 W12\nG11\nM30\n"), [("E1010", 2)]);
    assert_eq!(diags("G10 L52\nN22 P4 R100\nG11\nM30\n"), [("E1010", 2)]);
    assert_eq!(diags("G10 L3\nP33 L10\nG11\nM30\n"), [("E1010", 2)]);
    assert_eq!(diags("G10 L3\nP1 L10 Q3\nG11\nM30\n"), [("E1010", 2)]);
}

#[test]
fn tool_life_end_to_end() {
    // Group 1, life 2 uses: T0101 twice, then T0202; T0188 cancels the
    // offset of the current tool (2). Group 3 was never set: E7005 on
    // line 10, which the dry run finds too (W124).
    let src = "G10 L3\nP1 L2 Q1\nT0101\nT0202\nG11\nT0199\nT0199\nT0199\nT0188\nT0399\nM30\n";
    assert_eq!(diags(src), [("W124", 10)]);
    let (canon, status, _) = run(src);
    assert_eq!(
        canon,
        [
            "TOOL T=1 D=1",
            "TOOL T=1 D=1",
            "TOOL T=2 D=2",
            "TOOL T=2 D=0",
            "ALARM CODE=7005 MSG=\"tool-life group 3 has no tool (G10 L3 or [[tool_life.group]])\""
        ]
    );
    assert!(matches!(status, Status::Alarm(_)));
}

#[test]
fn the_machine_file_table_is_the_power_on_table() {
    let m = Machine::from_toml(
        "[[tool_life.group]]\nnumber = 2\nlife = 1\nunit = \"count\"\ntools = [505, 606]\n",
    )
    .expect("machine");
    let (canon, status, _) = run_with("T0299\nT0299\nM30\n", m);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["TOOL T=5 D=5", "TOOL T=6 D=6", "STOP KIND=M30"]);
}

#[test]
fn a_static_tool_life_program_dry_runs_without_error() {
    // Static: the compiler runs it through the kernel; E7005 stays a
    // run-time alarm.
    let c = compiled("T0199\nM30\n");
    assert!(!c.has_errors(), "{}", c.render());
}

#[test]
fn a_read_overrides_what_constant_folding_knew() {
    // #100 = 5 is known to the folder; the G10 L52 read makes it №172
    // (10000), so X[#100/1000] is X10, not X0.005. W takes a computed
    // value: #1 = 10100 sets bits 4 and 2 of №172, read back into #2.
    let src =
        "#100=5\n#1=10100\nG10 L52\nN172 R#100\nN172 W#1\nN172 R#2\nG11\nG00 X[#100/1000]\nM30\n";
    let (canon, status, vm) = run(src);
    assert_eq!(status, Status::Done);
    assert_eq!(canon, ["RAPID X=10 Z=0", "STOP KIND=M30"]);
    assert_eq!(vm.variable(2), Ok(10100.0));
}
