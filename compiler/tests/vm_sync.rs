//! `Vm::sync_positions`: a read of the current position stops the VM with
//! `Status::Sync` once per stretch between NC blocks; block-end positions
//! never do, and a VM without the flag never stops.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn vm_for(src: &str, sync: bool) -> Vm {
    let c = compile("test.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("a module"), Machine::reference());
    vm.sync_positions = sync;
    vm
}

/// The statuses of a whole run, `OutOfBudget` left out.
fn statuses(vm: &mut Vm) -> Vec<Status> {
    let mut events: Vec<Event> = Vec::new();
    let mut out = Vec::new();
    loop {
        match vm.step(1 << 16, &mut events) {
            Status::OutOfBudget => {}
            s @ (Status::Done | Status::Alarm(_)) => {
                out.push(s);
                return out;
            }
            s => out.push(s),
        }
    }
}

const SRC: &str = "O0001\nG00 X10 Z5\n#101 = #5041\n#102 = #5042 + #5041\n#105 = #5021\n\
                   #103 = #5001\nG00 X[#101 + 2] Z#102\n#104 = #[5040 + 2]\nM30\n";

#[test]
fn current_position_reads_wait_once_per_stretch() {
    let mut vm = vm_for(SRC, true);
    // Block 1 moves; the four current-position reads after it wait once; #5001 does not;
    // block 2 moves; the indirect read of #5042 waits again; the M30
    // block ends the run (its STOP event comes with `Done`).
    assert_eq!(
        statuses(&mut vm),
        [
            Status::Event,
            Status::Sync,
            Status::Event,
            Status::Sync,
            Status::Done
        ]
    );
    // The reads took their values after the wait: X10 Z5, then X12 Z15.
    assert_eq!(vm.variable(101).ok(), Some(10.0));
    assert_eq!(vm.variable(102).ok(), Some(15.0));
    assert_eq!(vm.variable(103).ok(), Some(10.0));
    assert_eq!(vm.variable(104).ok(), Some(15.0));
}

#[test]
fn without_the_flag_the_vm_never_waits() {
    let mut vm = vm_for(SRC, false);
    assert_eq!(
        statuses(&mut vm),
        [Status::Event, Status::Event, Status::Done]
    );
}
