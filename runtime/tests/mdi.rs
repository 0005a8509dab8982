//! MDI: blocks the operator types run in the program's place; when they
//! end the machine is idle at once, the spindle as they left it, and the
//! program is back at its start where the axes stand.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, RunState, SelectRefused, SetPoint};

const MAIN: &str = "G00 X40 Z2\nG01 Z-20 F300\nG00 X60 Z2\nM30\n";

fn controller(machine: &Machine) -> Controller {
    Controller::new(module(MAIN, machine), machine.clone(), runtime::AutoAck).expect("loads")
}

/// Cycle start, then every period until the MDI blocks have ended and
/// the program is back; the last set point.
fn run_mdi(ctl: &mut Controller) -> SetPoint {
    ctl.cycle_start();
    for _ in 0..400_000 {
        ctl.run_ahead();
        let sp = ctl.tick();
        match ctl.state() {
            RunState::Alarm(a) => panic!("alarm {a}"),
            RunState::Ended => panic!("the MDI blocks stood ended"),
            _ => {}
        }
        ctl.run_ahead();
        if !ctl.in_mdi() {
            assert_eq!(ctl.state(), RunState::Idle);
            return sp;
        }
    }
    panic!("not done: {:?}", ctl.state());
}

#[test]
fn the_spindle_started_in_mdi_keeps_turning_and_the_program_comes_back() {
    let m = Machine::reference();
    let mut ctl = controller(&m);
    assert_eq!(ctl.mdi(module("M03 S500\n", &m)), Ok(()));
    assert!(ctl.in_mdi());
    run_mdi(&mut ctl);
    assert!(!ctl.in_mdi());
    // Idle, and the spindle reaches 500 rpm and stays there.
    let mut sp = SetPoint::default();
    for _ in 0..5_000 {
        ctl.run_ahead();
        sp = ctl.tick();
        assert_eq!(ctl.state(), RunState::Idle);
    }
    assert_eq!(sp.spindle_rpm, 500.0);
    // Cycle start runs the program from its start, the spindle still on.
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (60.0, 2.0));
    assert_eq!(end.spindle_rpm, 500.0);
}

#[test]
fn the_program_starts_where_the_mdi_blocks_left_the_axes() {
    let m = Machine::reference();
    let mut ctl = controller(&m);
    assert_eq!(ctl.mdi(module("G00 X80 Z20\n", &m)), Ok(()));
    let sp = run_mdi(&mut ctl);
    assert_eq!((sp.x, sp.z), (80.0, 20.0));
    // The program's first rapid leaves from X80 Z20 towards X40 Z2.
    ctl.cycle_start();
    ctl.run_ahead();
    let first = ctl.tick();
    ctl.run_ahead();
    let second = ctl.tick();
    assert!(first.x <= 80.0 && first.z <= 20.0, "{first:?}");
    assert!(second.x < first.x && second.z < first.z, "{second:?}");
    assert!(80.0 - second.x < 1.0 && 20.0 - second.z < 1.0, "{second:?}");
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (60.0, 2.0));
}

#[test]
fn a_reset_ends_the_mdi_blocks() {
    let m = Machine::reference();
    let mut ctl = controller(&m);
    assert_eq!(ctl.mdi(module("G98 G01 W-50 F100\n", &m)), Ok(()));
    ctl.cycle_start();
    for _ in 0..2_000 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.state(), RunState::Running);
    reset_to_idle(&mut ctl);
    ctl.run_ahead();
    assert!(!ctl.in_mdi());
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (60.0, 2.0));
}

#[test]
fn mdi_needs_an_idle_machine_and_blocks_for_it() {
    let m = Machine::reference();
    let mut ctl = controller(&m);
    run_to_end(&mut ctl);
    assert_eq!(
        ctl.mdi(module("M03 S500\n", &m)),
        Err(SelectRefused::NotIdle)
    );
    reset_to_idle(&mut ctl);
    let radius = Machine::from_toml("[axes.x]\ndiameter = false\n").expect("a machine file");
    assert!(matches!(
        ctl.mdi(module("M03 S500\n", &radius)),
        Err(SelectRefused::Machine(_))
    ));
    assert!(!ctl.in_mdi());
}

#[test]
fn a_tool_selected_in_mdi_counts_its_use() {
    let text = "[[tool_life.group]]\nnumber = 1\nlife = 2\nunit = \"count\"\ntools = [101, 202]\n";
    let m = Machine::from_toml(text).expect("a machine file");
    let mut ctl = controller(&m);
    assert_eq!(ctl.mdi(module("T0199\n", &m)), Ok(()));
    let sp = run_mdi(&mut ctl);
    assert_eq!(sp.tool, 1);
    assert_eq!(ctl.counters().life[0].used, [1.0, 0.0]);
}

#[test]
fn a_split_controller_runs_mdi_blocks_after_its_reset() {
    let m = Machine::reference();
    let (mut interp, mut rt) = controller(&m).split();
    assert_eq!(interp.mdi(module("M03 S500\nG00 X80 Z20\n", &m)), Ok(()));
    rt.reset();
    let (mut started, mut ran) = (false, false);
    let mut sp = SetPoint::default();
    for _ in 0..400_000 {
        interp.run_ahead();
        sp = rt.tick();
        match rt.state() {
            RunState::Idle if !started => {
                rt.cycle_start();
                started = true;
            }
            RunState::Idle if ran => break,
            RunState::Running => ran = true,
            _ => {}
        }
    }
    assert!(ran && rt.state() == RunState::Idle);
    assert_eq!((sp.x, sp.z), (80.0, 20.0));
    // The program is back: cycle start runs it to its end.
    rt.cycle_start();
    for _ in 0..400_000 {
        interp.run_ahead();
        sp = rt.tick();
        if rt.state() == RunState::Ended {
            break;
        }
    }
    assert_eq!(rt.state(), RunState::Ended);
    assert_eq!((sp.x, sp.z), (60.0, 2.0));
    assert!(sp.spindle_rpm == 500.0, "{sp:?}");
}

#[test]
fn blocks_not_started_give_way_to_an_edit_or_new_blocks() {
    let m = Machine::reference();
    let mut ctl = controller(&m);
    assert_eq!(ctl.mdi(module("G00 X80 Z20\n", &m)), Ok(()));
    // New blocks replace them; the program still comes back after.
    assert_eq!(ctl.mdi(module("G00 X70 Z30\n", &m)), Ok(()));
    let sp = run_mdi(&mut ctl);
    assert_eq!((sp.x, sp.z), (70.0, 30.0));
    // An edit of the offset page starts the program afresh.
    assert_eq!(ctl.mdi(module("G00 X80 Z20\n", &m)), Ok(()));
    let wear = runtime::OffsetLengths::default();
    assert_eq!(ctl.set_tool_offset(1, wear), Ok(()));
    assert!(!ctl.in_mdi());
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (60.0, 2.0));
}
