//! Pass `fold`: constant propagation over the control-flow graph.
//!
//! Small programs whose IR after the passes is worked out by hand (what is
//! known where follows from the rules in `compiler/src/fold.rs`), and a
//! few hundred random macro programs of branches, loops, numbered blocks,
//! computed GOTOs and calls, each run to its end compiled with -O0 (no
//! folding) and -O1: the events, the end status and every variable a
//! program can write must be the same, bit for bit.

use compiler::{compile, compile_ir, ir, Options};
use isa::{Instr, Module};
use nc::event::Event;
use nc::Machine;
use vm::Vm;

mod common;
use common::Rng;

/// The IR listing of `src` after the passes (-O1).
fn listing(src: &str) -> String {
    let (c, ir) = compile_ir("t.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let ir = ir.expect("the IR of a program that compiles");
    assert_eq!(ir::validate(&ir), Ok(()));
    ir::print::print(&ir, &c.files)
}

/// The printed operations of `src`'s source line `line`.
fn ops_of_line(src: &str, line: usize) -> Vec<String> {
    let at = format!("; t.nc:{line}:");
    listing(src)
        .lines()
        .filter(|l| l.contains(&at))
        .map(|l| l.split(';').next().unwrap_or("").trim().to_string())
        .collect()
}

fn assert_op(src: &str, line: usize, want: &str) {
    let ops = ops_of_line(src, line);
    assert!(
        ops.iter().any(|o| o == want),
        "line {line}: {want:?} not in {ops:?}\n{}",
        listing(src)
    );
}

#[test]
fn a_numbered_block_keeps_what_is_known_unless_a_computed_goto_brings_other_values() {
    // No jump to a number: N10 is entered only from line 1.
    assert_op(
        "#1=2\nN10 G01 X#1 Z-1 F100\nM30\n",
        2,
        "move G1 X2 Z-1 F100",
    );
    // A computed GOTO may enter N10 after line 3, with #1 = 3.
    let src = "#1=2\nN10 G01 X#1 Z-1 F100\n#1=3\nIF[#9GT0]GOTO#8\nM30\n";
    assert_op(src, 2, "move G1 X#1 Z-1 F100");
    // ... or with #1 = 2 as on line 1: the same value both ways.
    let src = "#1=2\nN10 G01 X#1 Z-1 F100\nIF[#9GT0]GOTO#8\nM30\n";
    assert_op(src, 2, "move G1 X2 Z-1 F100");
}

#[test]
fn a_loop_keeps_what_its_body_leaves_unchanged() {
    let src = "#1=2\n#3=0\nWHILE[#3LT3]DO1\nG01 X#1 Z#3 F100\n#3=#3+1\nEND1\nM30\n";
    assert_op(src, 4, "move G1 X2 Z#3 F100");
    assert_op(src, 3, "branch #3 LT 3 then bb2 else bb3");
    assert_op(src, 5, "#3 = #3 + 1");
}

#[test]
fn after_a_conditional_assignment_only_a_value_the_same_both_ways_is_known() {
    assert_op(
        "#1=2\nIF[#9GT0]THEN#1=2\nG01 X#1 Z-1 F100\nM30\n",
        3,
        "move G1 X2 Z-1 F100",
    );
    assert_op(
        "#1=2\nIF[#9GT0]THEN#1=3\nG01 X#1 Z-1 F100\nM30\n",
        3,
        "move G1 X#1 Z-1 F100",
    );
}

#[test]
fn a_call_forgets_only_what_its_program_may_write() {
    // O9000 writes #100 and its own #1 (a local of its level when G65
    // calls it, the caller's when M98 does); O9001 writes nothing.
    let src = "#1=2\n#100=5\n#101=6\nG65 P9000\nG01 X#1 Z#100 F100\nG01 X#101 Z-2\nM98 P9001\nG01 X#1 Z#101\nM98 P9000\nG01 X#1 Z#101\nM30\nO9000\n#100=7\n#1=8\nM99\nO9001\nG00 U1\nM99\n";
    assert_op(src, 5, "move G1 X2 Z#100 F100");
    assert_op(src, 6, "move G1 X6 Z-2");
    assert_op(src, 8, "move G1 X2 Z6");
    assert_op(src, 10, "move G1 X#1 Z6");
    // What the programs a callee calls write counts too, and a call of a
    // computed program number may write anything.
    let nested = "#1=2\n#101=6\nM98 P9001\nG01 X#1 Z#101 F100\nM30\nO9001\nM98 P9002\nM99\nO9002\n#101=1\nM99\n";
    assert_op(nested, 4, "move G1 X2 Z#101 F100");
    let computed = "#1=2\n#9=9001\nM98 P#9\nG01 X#1 Z-1 F100\nM30\nO9001\nM99\n";
    assert_op(computed, 4, "move G1 X#1 Z-1 F100");
}

#[test]
fn a_called_program_knows_what_every_call_passes() {
    // O9010's #1 and #2 are the arguments of its one call; #3 was not
    // passed: vacant, its word left out.
    let one = "G65 P9010 A10 B2\nM30\nO9010\nG01 X#1 Z-#2 F100\nG01 X#3 Z-3\nM99\n";
    assert_op(one, 4, "move G1 X10 Z-2 F100");
    assert_op(one, 5, "move G1 Z-3");
    // The caller's own locals are not the macro's.
    let own = "#1=5\n#3=6\nG65 P9010 A10 B2\nM30\nO9010\nG01 X#1 Z-#2 F100\nG01 X#3 Z-3\nM99\n";
    assert_op(own, 6, "move G1 X10 Z-2 F100");
    assert_op(own, 7, "move G1 Z-3");
    // Two calls with different values of A: #1 is not known, #2 is.
    let two = "G65 P9010 A10 B2\nG65 P9010 A20 B2\nM30\nO9010\nG01 X#1 Z-#2 F100\nM99\n";
    assert_op(two, 5, "move G1 X#1 Z-2 F100");
    // M98 shares the locals: O1000 knows #5 (and #100) from its caller.
    let sub = "#5=3\n#100=4\nM98 P1000\nM30\nO1000\nG01 X#5 Z-#100 F100\nM99\n";
    assert_op(sub, 6, "move G1 X3 Z-4 F100");
    // Called twice by its count, it starts the second time with what the
    // first left: nothing is passed but a macro's arguments.
    let twice = "#5=3\nM98 P1000 L2\nM30\nO1000\nG01 X#5 Z-1 F100\n#5=#5+1\nM99\n";
    assert_op(twice, 5, "move G1 X#5 Z-1 F100");
    let g65_twice = "#100=4\nG65 P9010 L2 A10\nM30\nO9010\nG01 X#1 Z-#100 F100\n#100=#100+1\nM99\n";
    assert_op(g65_twice, 5, "move G1 X10 Z[-#100] F100");
    // A G66 macro knows its arguments, not the common variables (it runs
    // after later moves).
    let modal = "#100=4\nG66 P9010 A7\nG01 U1 F100\nG67\nM30\nO9010\nG00 X#1 Z#100\nM99\n";
    assert_op(modal, 7, "move G0 X7 Z#100");
    // A call of a computed program number may reach any program.
    let computed = "#9=9010\nG65 P#9 A10\nG65 P9010 A10\nM30\nO9010\nG01 X#1 Z-1 F100\nM99\n";
    assert_op(computed, 6, "move G1 X#1 Z-1 F100");
}

#[test]
fn under_g66_a_move_may_change_the_common_variables() {
    // The move on line 4 calls O9000, which sets #100 = 20: folding #100
    // as 1 on line 5 would be wrong.
    let src = "G66 P9000\n#100=1\n#1=4\nG01 U1 W-1 F100\n#101=#100+#1\nG67\nG00 X#101 Z5\nM30\nO9000\n#100=20\nM99\n";
    assert_op(src, 5, "#101 = #100 + 4");
    let events = run(&module(src, true));
    assert!(
        events.iter().any(|e| e.to_string() == "RAPID X=24 Z=5"),
        "{events:?}"
    );
    // The same through a subprogram whose move calls the macro: O9001
    // writes nothing itself, but may write what O9000 writes.
    let src = "#100=1\nG66 P9000\nM98 P9001\nG67\nG00 X#100 Z5\nM30\nO9000\n#100=20\nM99\nO9001\nG01 U1 W-1 F100\nM99\n";
    assert_op(src, 5, "move G0 X#100 Z5");
}

#[test]
fn macro_a_operations_fold_like_assignments() {
    // H01 sets #1 = 5, H02 #2 = 5 + 3, H26 #2 = #2 * 3 / 4 (it reads its
    // own destination), H21 #3 = sqrt of a #9 nobody set: not known.
    let src = "G65 H01 P#1 Q5\nG65 H02 P#2 Q#1 R3\nG65 H26 P#2 Q3 R4\nG65 H21 P#3 Q#9\nG01 X#2 Z#3 F100\nM30\n";
    assert_op(src, 2, "g65 H02 #2 = 8");
    assert_op(src, 3, "g65 H26 #2 = 6");
    assert_op(src, 4, "g65 H21 #3 = SQRT[#9]");
    assert_op(src, 5, "move G1 X6 Z#3 F100");
    // H01 ignores R, but R is still read: a variable that does not exist
    // there is the block's alarm, folded or not.
    let src = "G65 H01 P#1 Q5 R#[0-1]\nG00 X#1 Z1\nM30\n";
    assert_eq!(alarm(src), Some((1, 5008)));
    let mut vm = Vm::new(module(src, false), Machine::reference());
    assert!(matches!(vm.run(&mut Vec::new()), vm::Status::Alarm(a) if a.code == 5008));
}

#[test]
fn a_vacant_value_leaves_its_word_out() {
    // #0 is always vacant; #1 is known to be too.
    let src = "G01 X#0 Z-1 F100\n#1=#0\nG01 X20 Z#1\nM30\n";
    assert_op(src, 1, "move G1 Z-1 F100");
    assert_op(src, 3, "move G1 X20");
}

#[test]
fn a_value_that_faults_stays_to_raise_its_alarm_when_it_runs() {
    let src = "#1=0\n#2=1/#1\nG01 X#2 Z-1 F100\nM30\n";
    assert_op(src, 2, "#2 = 1 / #1");
    assert_op(src, 3, "move G1 X#2 Z-1 F100");
}

/// The W116 warnings of `src` (-O1): line and the alarm code named.
fn w116(src: &str) -> Vec<(usize, u32)> {
    let c = compile("t.nc", src.as_bytes(), &Options::default());
    c.diags
        .iter()
        .filter(|(_, d)| d.code == "W116")
        .map(|(_, d)| {
            let line = src[..d.span.start as usize].matches('\n').count() + 1;
            let code = d.message.split("alarm E").nth(1).unwrap_or("");
            (line, code[..4].parse().unwrap_or(0))
        })
        .collect()
}

/// The line and code of the alarm that ends the run of `src`.
fn alarm(src: &str) -> Option<(usize, u32)> {
    let mut vm = Vm::new(module(src, true), Machine::reference());
    match vm.run(&mut Vec::new()) {
        vm::Status::Alarm(a) => Some((a.line as usize, a.code)),
        _ => None,
    }
}

#[test]
fn a_fault_the_known_values_prove_is_w116_and_the_run_raises_it_there() {
    for (src, line, code) in [
        // Division by a variable known to be 0.
        ("#1=0\n#2=1/#1\nM30\n", 2, 5001),
        // A square root of a value known negative, past a numbered block.
        ("#1=-4\nN10 #2=SQRT[#1]\nM30\n", 2, 5002),
        // A division by a variable known to be 0, of one not known.
        ("#1=0\n#2=#9/#1\nM30\n", 2, 5001),
        // A computed GOTO to a number no block has.
        ("#5=15\nGOTO#5\nN10 M30\n", 2, 6001),
        // A G code that does not exist, once its value is known.
        ("#1=1.5\nG#1 X10 Z1\nM30\n", 2, 2001),
        // A tool number beyond the tool table.
        ("#1=9999\nT#1\nM30\n", 2, 7004),
    ] {
        assert_eq!(w116(src), [(line, code)], "{src}");
        assert_eq!(alarm(src), Some((line, code)), "{src}");
    }
    // Known only on one path: no warning.
    let src = "#1=1\nIF[#9GT0]THEN#1=0\n#2=1/#1\nM30\n";
    assert_eq!(w116(src), []);
    // A fault of constants alone is build's W116, warned of once.
    assert_eq!(w116("#1=5\n#2=#1+1/0\nM30\n"), [(2, 5001)]);
}

fn module(src: &str, optimize: bool) -> Module {
    let opts = Options {
        optimize,
        ..Options::default()
    };
    let c = compile("t.nc", src.as_bytes(), &opts);
    let text = c.render();
    c.module.unwrap_or_else(|| panic!("{src}\n{text}"))
}

fn run(m: &Module) -> Vec<Event> {
    let mut vm = Vm::new(m.clone(), Machine::reference());
    let mut events = Vec::new();
    vm.run(&mut events);
    events
}

/// Statements over a few locals and common variables: assignments,
/// conditionals, loops, numbered blocks, forward GOTOs (static and
/// computed), calls and moves with computed words.
fn random_program(rng: &mut Rng) -> String {
    const VARS: &[&str] = &["#1", "#2", "#3", "#100", "#101", "#500"];
    const VALUES: &[&str] = &[
        "1", "2", "-3", "0.5", "#0", "#1", "#2", "#3", "#100", "#101", "#500",
    ];
    let mut src = String::from("O0001\nG00 X50 Z2\n");
    let mut label = 10;
    let val = |rng: &mut Rng| rng.pick(VALUES).to_string();
    let expr = |rng: &mut Rng| match rng.below(6) {
        0 => val(rng),
        1 => format!("{}+{}", val(rng), val(rng)),
        2 => format!("{}-{}", val(rng), val(rng)),
        3 => format!("[{}+{}]*0.5", val(rng), val(rng)),
        4 => format!("ABS[{}]", val(rng)),
        _ => format!("{}/{}", val(rng), val(rng)),
    };
    for _ in 0..rng.below(16) + 4 {
        let var = rng.pick(VARS);
        match rng.below(12) {
            0..=2 => src += &format!("{var}={}\n", expr(rng)),
            3 => src += &format!("IF[{}GT{}]THEN{var}={}\n", val(rng), val(rng), expr(rng)),
            4 => {
                src += &format!(
                    "IF[{}LT{}]GOTO{label}\n{var}={}\nN{label} G01 X[{}+30] Z-1 F100\n",
                    val(rng),
                    val(rng),
                    expr(rng),
                    val(rng)
                );
                label += 10;
            }
            5 => {
                src += &format!(
                    "#30={label}\n{var}={}\nIF[{}EQ{}]GOTO#30\n{var}={}\nN{label} {var}={var}+1\n",
                    expr(rng),
                    val(rng),
                    val(rng),
                    expr(rng)
                );
                label += 10;
            }
            6 => {
                src += &format!(
                    "#20=0\nWHILE[#20LT2]DO1\nG01 X[{}+30] Z-#20 F100\n{var}={}\n#20=#20+1\nEND1\n",
                    val(rng),
                    expr(rng)
                )
            }
            7 => {
                src += &format!(
                    "N{label} G01 X[{}+30] Z[{}-2] F[{}+100]\n",
                    val(rng),
                    val(rng),
                    val(rng)
                );
                label += 10;
            }
            8 => {
                src += rng.pick(&[
                    "M98 P1000\n",
                    "G65 P1002 A#1 B#100\n",
                    "G65 P1002 A3 B[2+0.5]\n",
                    "M98 P1000 L2\n",
                ])
            }
            9 => {
                src += rng.pick(&[
                    "G66 P1001\nG01 U1 W-1 F100\nG67\n",
                    "G66 P1001\nM98 P1000\nG67\n",
                ])
            }
            10 => {
                let h = rng.pick(&[
                    "01", "02", "03", "04", "05", "21", "22", "23", "26", "27", "31",
                ]);
                let var = &var[1..];
                src += &format!("G65 H{h} P#{var} Q{} R{}\n", val(rng), val(rng));
            }
            _ => src += &format!("G01 X[{}+30] Z-#2 F100\n", val(rng)),
        }
        if rng.below(4) == 0 {
            src += &format!("N{label}\n");
            label += 10;
        }
    }
    src += "#31=#1\n#32=#2\n#33=#3\nM30\n";
    src += "O1000\n#1=#1+1\nG01 W-0.5 F100\n#100=#100*2\nM99\n";
    src += "O1001\n#101=#101+1\n#1=9\nM99\n";
    src += "O1002\n#100=#1+#2\n#500=#2\nM99\n";
    src
}

/// Variables a program may have written: locals, commons, persistents.
const WRITTEN: &[u32] = &[1, 2, 3, 20, 30, 31, 32, 33, 100, 101, 500];

/// What a run gave: its events, how it ended, the variables' bits, and
/// the line and code of its alarm.
type Outcome = (Vec<Event>, String, Vec<u64>, Option<u32>, Option<u32>);

/// Runs `m` one instruction at a time. No line of `warned` (W116) may be
/// left without its alarm: the run must stop on it or stay.
fn outcome(m: Module, warned: &[usize], src: &str) -> Outcome {
    let line_of = |m: &Module, pc: u32| m.lines.get(pc as usize).map_or(0, |l| l.line as usize);
    let mut vm = Vm::new(m, Machine::reference());
    let mut events = Vec::new();
    let status = loop {
        let before = line_of(vm.module(), vm.pc());
        let status = vm.step(1, &mut events);
        let after = line_of(vm.module(), vm.pc());
        let left = matches!(status, vm::Status::Event | vm::Status::OutOfBudget) && after != before;
        assert!(
            !(left && warned.contains(&before)),
            "line {before} ran past its W116:\n{src}"
        );
        if !matches!(
            status,
            vm::Status::Event | vm::Status::OutOfBudget | vm::Status::Sync
        ) {
            break status;
        }
    };
    let vars = WRITTEN
        .iter()
        .map(|&n| vm.variable(n).map_or(u64::MAX, f64::to_bits))
        .collect();
    let (line, code) = match &status {
        vm::Status::Alarm(a) => (Some(a.line), Some(a.code)),
        _ => (None, None),
    };
    (events, format!("{status:?}"), vars, line, code)
}

fn variable_loads(m: &Module) -> usize {
    m.code
        .iter()
        .filter(|i| matches!(i, Instr::LoadVar { .. } | Instr::LoadVarInd { .. }))
        .count()
}

#[test]
fn random_macro_programs_run_the_same_folded_and_not() {
    let mut rng = Rng(0x5eed_f01d);
    let (mut loads_o0, mut loads_o1, mut events, mut warned) = (0, 0, 0, 0);
    // (`FOLD_CASES=n` runs more: the note of the stop gives a long run.)
    let cases = std::env::var("FOLD_CASES").map_or(300, |n| n.parse().unwrap_or(300));
    for i in 0..cases {
        let src = random_program(&mut rng);
        let (o0, o1) = (module(&src, false), module(&src, true));
        loads_o0 += variable_loads(&o0);
        loads_o1 += variable_loads(&o1);
        let warnings = w116(&src);
        // (On an IF line the warning is of the statement after THEN or
        // GOTO, which the condition may skip.)
        let unconditional = |l: &usize| !src.lines().nth(l - 1).unwrap_or("").starts_with("IF");
        let lines: Vec<usize> = warnings.iter().map(|w| w.0).filter(unconditional).collect();
        let (a, b) = (outcome(o0, &[], &src), outcome(o1, &lines, &src));
        assert_eq!(a, b, "program {i}:\n{src}");
        // A run that alarms on a line W116 names raises the alarm named.
        if let Some(&(_, code)) = warnings.iter().find(|(l, _)| a.3 == Some(*l as u32)) {
            assert_eq!(a.4, Some(code), "program {i}:\n{src}");
            warned += 1;
        }
        events += a.0.len();
    }
    // The programs run (moves, not just alarms), and folding removes a
    // good share of the variable reads.
    assert!(events >= 1_500, "{events} events");
    eprintln!("variable reads: -O0 {loads_o0}, -O1 {loads_o1}; events {events}; {warned} alarms on a W116 line");
    assert!(warned >= 15, "{warned} runs alarmed where W116 said");
    assert!(
        loads_o1 * 100 <= loads_o0 * 95,
        "-O1 reads {loads_o1} variables where -O0 reads {loads_o0}"
    );
}
