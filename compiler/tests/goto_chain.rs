//! A long chain of GOTOs compiles, every jump landing on its block
//! (issue 20: the targets were found by a scan per GOTO, quadratic in the
//! chain; 99 998 blocks took 8 s). No timing is asserted: the chain is
//! long enough that the old scan would do 450 million comparisons.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

#[test]
fn a_long_goto_chain_compiles_and_runs_block_by_block() {
    // N1 GOTO3, N3 GOTO5, … : each block jumps over the next (which
    // would set #100), so a wrong target shows as a #100 write.
    const N: u32 = 30_000;
    let mut src = String::new();
    for i in (1..N).step_by(2) {
        src.push_str(&format!("N{i} GOTO{}\nN{} #100=#100+1\n", i + 2, i + 1));
    }
    src.push_str(&format!("N{} G00 X#100 Z0\nM30\n", N + 1));
    let c = compile("chain.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let module = c.module.expect("a module");
    let mut vm = Vm::new(module, Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    assert_eq!(vm.run(&mut events), Status::Done);
    // #100 stayed vacant (read as 0): no skipped block ran.
    let canon: Vec<String> = events.iter().map(ToString::to_string).collect();
    assert_eq!(canon, ["RAPID X=0 Z=0", "STOP KIND=M30"]);
}

#[test]
fn a_repeated_n_warns_and_the_first_is_used_and_a_missing_one_is_e2010() {
    let src = "GOTO5\nN5 G00 X1 Z0\nN5 G00 X2 Z0\nM30\n";
    let c = compile("dup.nc", src.as_bytes(), &Options::default());
    assert!(c.render().contains("warning[W103]"), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("a module"), Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    vm.run(&mut events);
    assert_eq!(events[0].to_string(), "RAPID X=1 Z=0");
    // The same, where the first N5 is a block of no code of its own: both
    // name the same place (this was an internal error, E0000).
    let src = "GOTO5\nG00 X9 Z0\nN5\nN5 G00 X2 Z0\nM30\n";
    let c = compile("dup.nc", src.as_bytes(), &Options::default());
    let mut vm = Vm::new(c.module.expect("a module"), Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    vm.run(&mut events);
    assert_eq!(events[0].to_string(), "RAPID X=2 Z=0");
    let c = compile("miss.nc", b"GOTO7\nN5 M30\n", &Options::default());
    assert!(c.render().contains("error[E2010]"), "{}", c.render());
}
