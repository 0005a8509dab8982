//! The kernel's short path for plain moves (`nc::exec::plain`) gives
//! what its general path gives: every suite program and a few hundred
//! random macro programs run in the VM both ways, one instruction at a
//! time; after each, the events printed and the kernel's whole state
//! must be the same.

use compiler::{compile, Options};
use nc::Machine;
use vm::Vm;

mod common;
use common::{random_program, Rng};

/// Instructions run per program at most (the suites' loops are short).
const STEPS: usize = 100_000;

/// Runs `src` both ways; the number of instructions compared, or `None`
/// when it does not compile.
fn same_both_ways(name: &str, src: &[u8], machine: &Machine) -> Option<usize> {
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    let module = compile(name, src, &opts).module?;
    let vms = [true, false].map(|plain| {
        let mut vm = Vm::new(module.clone(), machine.clone());
        vm.nc.set_plain_path(plain);
        vm
    });
    Some(common::lockstep(name, vms, STEPS))
}

#[test]
fn every_suite_program_runs_the_same_both_ways() {
    let (mut programs, mut steps) = (0, 0);
    for (name, src, machine) in common::suite() {
        if let Some(n) = same_both_ways(&name, &src, &machine) {
            programs += 1;
            steps += n;
        }
    }
    eprintln!("{programs} programs, {steps} instructions compared");
    assert!(programs >= 100, "only {programs} programs compiled");
}

#[test]
fn random_programs_run_the_same_both_ways() {
    let mut rng = Rng(0x0b1a_c0de_2026_1202);
    let machine = Machine::reference();
    let mut programs = 0;
    for i in 0..300 {
        let src = random_program(&mut rng);
        let name = format!("random{i}.nc\n{src}");
        programs += usize::from(same_both_ways(&name, src.as_bytes(), &machine).is_some());
    }
    assert!(programs >= 280, "only {programs} of 300 compiled");
}
