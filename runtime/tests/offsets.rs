//! The offset page: tool offset lengths and work offsets a host edits
//! between runs hold for every run after the edit; a program's own
//! writes hold for its run only (machine.md).

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, OffsetLengths, RunState, SetPoint, WorkOffset, Xz};

/// T0101, a cut to X40 Z-20, then #100 reads offset 1's wear X.
const CUT: &str = "T0101\nG00 X40 Z2\nG01 Z-20 F300\n#100=#2001\nM30\n";

fn controller(src: &str) -> Controller {
    let machine = Machine::reference();
    Controller::new(module(src, &machine), machine, runtime::AutoAck).expect("loads")
}

const WEAR: OffsetLengths = OffsetLengths {
    x: 0.0,
    z: 0.0,
    wear_x: -0.04,
    wear_z: 0.02,
};

/// A wear of X −0.04 (the part came out 0.04 large on the diameter) and
/// Z +0.02: the slide goes that much further, the programmed point is
/// the same, and #2001 reads it; it holds for the next run too.
#[test]
fn a_wear_edit_moves_the_slide_in_every_later_run() {
    let mut ctl = controller(CUT);
    let plain = run_to_end(&mut ctl);
    assert_eq!((plain.axis_x, plain.axis_z), (40.0, -20.0));
    reset_to_idle(&mut ctl);
    assert_eq!(ctl.set_tool_offset(1, WEAR), Ok(()));
    assert_eq!(ctl.tool_offset(1), Some(WEAR));
    for _ in 0..2 {
        let worn = run_to_end(&mut ctl);
        assert_eq!((worn.x, worn.z), (40.0, -20.0));
        assert!((worn.axis_x - 39.96).abs() < 1e-9, "{worn:?}");
        assert!((worn.axis_z + 19.98).abs() < 1e-9, "{worn:?}");
        assert_eq!(ctl.vm().variable(100), Ok(-0.04));
        reset_to_idle(&mut ctl);
    }
}

/// An edit while idle before the first cycle start applies to the run
/// about to start, though the program has already been read ahead.
#[test]
fn an_edit_before_cycle_start_applies_to_that_run() {
    let mut ctl = controller(CUT);
    ctl.run_ahead();
    assert_eq!(ctl.set_tool_offset(1, WEAR), Ok(()));
    let worn = run_to_end(&mut ctl);
    assert!((worn.axis_x - 39.96).abs() < 1e-9, "{worn:?}");
}

/// While a program runs, an edit waits for the next reset.
#[test]
fn an_edit_while_running_holds_from_the_next_reset() {
    let mut ctl = controller(CUT);
    ctl.cycle_start();
    for _ in 0..10 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.set_tool_offset(1, WEAR), Ok(()));
    let this_run = run_to_end(&mut ctl);
    assert_eq!((this_run.axis_x, this_run.axis_z), (40.0, -20.0));
    reset_to_idle(&mut ctl);
    let next = run_to_end(&mut ctl);
    assert!((next.axis_x - 39.96).abs() < 1e-9, "{next:?}");
}

/// A program's own write to a wear (#2001) lasts for its run: after a
/// reset the page's value is back.
#[test]
fn a_program_s_write_lasts_for_its_run() {
    let src = "#2001=#2001+1\nT0101\nG00 X40 Z2\n#100=#2001\nM30\n";
    let mut ctl = controller(src);
    assert_eq!(ctl.set_tool_offset(1, WEAR), Ok(()));
    for _ in 0..2 {
        let end = run_to_end(&mut ctl);
        assert!((end.axis_x - 40.96).abs() < 1e-9, "{end:?}");
        assert_eq!(ctl.vm().variable(100), Ok(0.96));
        reset_to_idle(&mut ctl);
    }
    assert_eq!(ctl.tool_offset(1), Some(WEAR));
}

/// G55 touched off at Z-250: the program's Z2 is machine Z-248.
#[test]
fn a_work_offset_edit_moves_the_work_zero() {
    let mut ctl = controller("G55 G00 X40 Z2\nM30\n");
    let at = Xz { x: 0.0, z: -250.0 };
    assert_eq!(ctl.set_work_offset(WorkOffset::G55, at), Ok(()));
    assert_eq!(ctl.work_offset(WorkOffset::G55), at);
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (40.0, 2.0));
    assert_eq!((end.axis_x, end.axis_z), (40.0, -248.0));
}

#[test]
fn a_bad_edit_is_refused_and_changes_nothing() {
    let mut ctl = controller(CUT);
    let bad = OffsetLengths {
        wear_z: f64::NAN,
        ..WEAR
    };
    assert!(ctl.set_tool_offset(1, bad).is_err());
    assert!(ctl.set_tool_offset(33, WEAR).is_err());
    assert_eq!(ctl.tool_offset(1), Some(OffsetLengths::default()));
    let end = run_to_end(&mut ctl);
    assert_eq!((end.axis_x, end.axis_z), (40.0, -20.0));
}

/// A split controller takes the edit at its next reset.
#[test]
fn a_split_controller_takes_an_edit_at_its_reset() {
    let (mut interp, mut rt) = controller(CUT).split();
    assert_eq!(interp.set_tool_offset(1, WEAR), Ok(()));
    rt.reset();
    let mut last = SetPoint::default();
    let mut started = false;
    for _ in 0..400_000 {
        interp.run_ahead();
        last = rt.tick();
        if rt.state() == RunState::Idle && !started {
            rt.cycle_start();
            started = true;
        }
        if rt.state() == RunState::Ended {
            break;
        }
    }
    assert_eq!(rt.state(), RunState::Ended);
    assert!((last.axis_x - 39.96).abs() < 1e-9, "{last:?}");
}
