//! The operator's macro-variable page: the controller reads any variable
//! as the program would read it now, and sets #500–#999 (handed to the
//! storage at once, kept over resets, read by the blocks read after the
//! edit); other numbers are refused (docs/embedding.md).

mod common;

use common::module;
use nc::{Event, Machine};
use runtime::{Controller, RunState, VariableRefused};
use std::sync::{Arc, Mutex};

/// A storage that keeps every set it is handed, or fails.
struct Kept(Arc<Mutex<Vec<[f64; 500]>>>, bool);

impl vm::Storage for Kept {
    fn store(&mut self, persistent: &[f64; 500]) -> Result<(), String> {
        if self.1 {
            return Err("the card is full".into());
        }
        self.0.lock().map_err(|e| e.to_string())?.push(*persistent);
        Ok(())
    }
}

fn controller(src: &str) -> Controller {
    let machine = Machine::reference();
    Controller::new(module(src, &machine), machine, runtime::AutoAck).expect("loads")
}

/// Runs to the end; the canon.
fn run(ctl: &mut Controller) -> Vec<Event> {
    let mut canon = Vec::new();
    ctl.cycle_start();
    for _ in 0..100_000 {
        ctl.run_ahead_tap(&mut canon);
        ctl.tick();
        if ctl.state() == RunState::Ended {
            return canon;
        }
    }
    panic!("no end: {:?}", ctl.state());
}

#[test]
fn a_persistent_variable_set_while_idle_is_read_by_the_run_and_stored() {
    let mut ctl = controller("G00 X[#500*2] Z5\nM30\n");
    let stored = Arc::new(Mutex::new(Vec::new()));
    ctl.vm_mut()
        .set_storage(Box::new(Kept(stored.clone(), false)));
    assert_eq!(ctl.set_variable(500, 12.5), Ok(()));
    assert_eq!(ctl.variable(500).map(f64::to_bits), Ok(12.5f64.to_bits()));
    let sets = stored.lock().expect("a lock").clone();
    assert_eq!((sets.len(), sets[0][0]), (1, 12.5));
    let canon = run(&mut ctl);
    let rapid = Event::Rapid {
        x: 25.0,
        z: 5.0,
        c: None,
    };
    assert!(canon.contains(&rapid), "{canon:?}");
    // Kept over a reset; NaN makes it vacant.
    ctl.reset();
    for _ in 0..10_000 {
        ctl.tick();
    }
    assert_eq!(ctl.variable(500), Ok(12.5));
    assert_eq!(ctl.set_variable(500, f64::NAN), Ok(()));
    assert!(ctl.variable(500).is_ok_and(f64::is_nan));
}

#[test]
fn only_500_to_999_can_be_set() {
    let mut ctl = controller("#100=7\nG00 X10\nM30\n");
    for n in [1, 33, 100, 199, 499, 1000, 2001, 3000, 5001] {
        assert_eq!(
            ctl.set_variable(n, 1.0),
            Err(VariableRefused::NotPersistent(n))
        );
    }
    assert_eq!(
        ctl.set_variable(999, f64::INFINITY),
        Err(VariableRefused::NotFinite(999))
    );
    assert_eq!(ctl.set_variable(999, -1.0e9), Ok(()));
    // What the program set is read as it stands after the blocks read.
    assert!(ctl.variable(100).is_ok_and(f64::is_nan));
    ctl.run_ahead();
    assert_eq!(ctl.variable(100), Ok(7.0));
}

#[test]
fn a_failing_storage_is_told_and_the_value_still_set() {
    let mut ctl = controller("M30\n");
    ctl.vm_mut()
        .set_storage(Box::new(Kept(Arc::default(), true)));
    let r = ctl.set_variable(600, 4.0);
    assert!(
        matches!(&r, Err(VariableRefused::Storage(e)) if e.contains("the card is full")),
        "{r:?}"
    );
    assert_eq!(ctl.variable(600), Ok(4.0));
}

/// The split controller's interpreter half holds the VM: the page is
/// there.
#[test]
fn the_interpreter_half_has_the_page() {
    let ctl = controller("G00 X[#501] Z5\nM30\n");
    let (mut interp, mut rt) = ctl.split();
    assert_eq!(interp.set_variable(501, 30.0), Ok(()));
    assert_eq!(
        interp.set_variable(101, 30.0),
        Err(VariableRefused::NotPersistent(101))
    );
    let mut canon = Vec::new();
    rt.cycle_start();
    for _ in 0..100_000 {
        interp.run_ahead_tap(&mut canon);
        rt.tick();
        if rt.state() == RunState::Ended {
            break;
        }
    }
    let rapid = Event::Rapid {
        x: 30.0,
        z: 5.0,
        c: None,
    };
    assert!(canon.contains(&rapid), "{canon:?}");
    assert_eq!(interp.variable(501), Ok(30.0));
}
