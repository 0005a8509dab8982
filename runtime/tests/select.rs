//! Selecting another program while idle: the axes, #500–#999 and the
//! offset page stay, and the new program starts where the axes stand.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, OffsetLengths, SelectRefused};

const FIRST: &str = "#500=7\nG00 X40 Z2\nM30\n";
/// Starts with a move of Z alone: X stays where the first program left it.
const SECOND: &str = "#100=#500\nT0101\nG01 W-12 F300\nM30\n";

#[test]
fn the_next_program_starts_where_the_axes_stand() {
    let machine = Machine::reference();
    let mut ctl =
        Controller::new(module(FIRST, &machine), machine.clone(), runtime::AutoAck).expect("loads");
    let wear = OffsetLengths {
        wear_x: -0.04,
        ..OffsetLengths::default()
    };
    assert_eq!(ctl.set_tool_offset(1, wear), Ok(()));
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (40.0, 2.0));
    // Ended: a program is selected after a reset.
    let second = module(SECOND, &machine);
    assert_eq!(
        ctl.select_program(second.clone()),
        Err(SelectRefused::NotIdle)
    );
    reset_to_idle(&mut ctl);
    assert_eq!(ctl.select_program(second), Ok(()));
    let end = run_to_end(&mut ctl);
    // X40 (and its wear, now that T0101 is active), Z from 2 to -10.
    assert_eq!((end.x, end.z), (40.0, -10.0));
    assert!((end.axis_x - 39.96).abs() < 1e-9, "{end:?}");
    assert_eq!(ctl.vm().variable(100), Ok(7.0));
    // A reset runs the selected program again, from where it ended. (A
    // reset starts with the power-on tool offset, none: the slide at X
    // 39.96 is the programmed X 39.96 until T0101 shifts it once more.)
    reset_to_idle(&mut ctl);
    let again = run_to_end(&mut ctl);
    assert!(
        (again.x - 39.96).abs() < 1e-9 && again.z == -22.0,
        "{again:?}"
    );
    assert!((again.axis_x - 39.92).abs() < 1e-9, "{again:?}");
}

#[test]
fn a_program_for_another_machine_is_refused() {
    let machine = Machine::reference();
    let mut ctl =
        Controller::new(module(FIRST, &machine), machine, runtime::AutoAck).expect("loads");
    let radius = Machine::from_toml("[axes.x]\ndiameter = false\n").expect("a machine file");
    let other = module("G00 X20 Z2\nM30\n", &radius);
    assert!(matches!(
        ctl.select_program(other),
        Err(SelectRefused::Machine(_))
    ));
    let end = run_to_end(&mut ctl);
    assert_eq!((end.x, end.z), (40.0, 2.0));
}
