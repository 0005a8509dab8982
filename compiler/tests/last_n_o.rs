//! #4114 (last N) and #4115 (running program number), which the VM
//! answers from the module's sequence tables (dialect.md §7.2).

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn run(src: &str) -> Vm {
    let c = compile("test.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let mut vm = Vm::new(c.module.expect("a module"), Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    assert_eq!(vm.run(&mut events), Status::Done);
    vm
}

#[test]
fn last_n_and_program_number() {
    // #101: no N yet (vacant); #102: N20's block itself; #103: after N30
    // and a block without N; in O2000 (called by M98 from N40, no N of its
    // own) #104 keeps the caller's N40 and #105 is 2000; back in O0100,
    // #106 = 100.
    let src = "O0100\n#101 = #4114\nN20 #102 = #4114\nN30 G00 X10\nG00 Z5\n#103 = #4114\n\
               N40 M98 P2000\n#106 = #4115\nM30\nO2000\n#104 = #4114\n#105 = #4115\nM99\n";
    let vm = run(src);
    let var = |n| vm.variable(n).ok().filter(|v| !v.is_nan());
    assert_eq!(var(101), None);
    assert_eq!(var(102), Some(20.0));
    assert_eq!(var(103), Some(30.0));
    assert_eq!(var(104), Some(40.0));
    assert_eq!(var(105), Some(2000.0));
    assert_eq!(var(106), Some(100.0));
}
