//! Tool setting by a measured cut: the offset in force moves by the
//! programmed point less the measurement, and the next run cuts the
//! measured size. The figures are by hand.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, MeasureRefused, MeasuredAxis, RunState};

/// Offset 1: geometry X2 (diameter) Z3, wear X0.1; work and machine
/// coordinates are one on the reference machine.
const MACHINE: &str = "[[tools.offset]]\nnumber = 1\nx = 2.0\nz = 3.0\nwear_x = 0.1\n";
const CUT: &str = "T0101\nG00 X50 Z2\nG01 Z-10 F500\nM30\n";

fn controller() -> Controller {
    let machine = Machine::from_toml(MACHINE).expect("a machine file");
    let m = module(CUT, &machine);
    Controller::new(m, machine, runtime::AutoAck).expect("loads")
}

/// The cut ends at X50 Z-10 with offset 1 in force. Measured 49.96 on
/// the diameter: the tool cut 0.04 small, so its X geometry grows to
/// 2 + 0.04 = 2.04; the face measured at Z-10.03: Z grows to 3.03. The
/// wear stays 0.1. Run again, the slide stands at X50 + 2.04 + 0.1 =
/// 52.14 and Z-10 + 3.03 = -6.97 (52.1 and -7 before).
#[test]
fn a_measured_cut_moves_the_offset_in_force() {
    let mut ctl = controller();
    let first = run_to_end(&mut ctl);
    assert!((first.axis_x - 52.1).abs() < 1e-9 && (first.axis_z + 7.0).abs() < 1e-9);
    let (n, l) = ctl
        .measure_tool_offset(MeasuredAxis::X, 49.96)
        .expect("measured");
    assert_eq!(n, 1);
    assert!(
        (l.x - 2.04).abs() < 1e-12 && l.wear_x == 0.1 && l.z == 3.0,
        "{l:?}"
    );
    let (_, l) = ctl
        .measure_tool_offset(MeasuredAxis::Z, -10.03)
        .expect("measured");
    assert!(
        (l.z - 3.03).abs() < 1e-12 && (l.x - 2.04).abs() < 1e-12,
        "{l:?}"
    );
    assert_eq!(ctl.tool_offset(1), Some(l));
    reset_to_idle(&mut ctl);
    let again = run_to_end(&mut ctl);
    assert!((again.axis_x - 52.14).abs() < 1e-9, "{again:?}");
    assert!((again.axis_z + 6.97).abs() < 1e-9, "{again:?}");
    assert_eq!((again.x, again.z), (50.0, -10.0));
}

/// Refused, changing nothing: before any T word, while the axes move,
/// and a geometry beyond the page's range.
#[test]
fn a_measurement_needs_an_offset_in_force_and_standing_axes() {
    let mut ctl = controller();
    let page = ctl.tool_offset(1);
    assert_eq!(
        ctl.measure_tool_offset(MeasuredAxis::X, 50.0),
        Err(MeasureRefused::NoOffset)
    );
    ctl.cycle_start();
    for _ in 0..300 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.state(), RunState::Running);
    assert_eq!(
        ctl.measure_tool_offset(MeasuredAxis::X, 50.0),
        Err(MeasureRefused::NotStanding)
    );
    run_to_end(&mut ctl);
    let far = ctl.measure_tool_offset(MeasuredAxis::Z, 2.0e6);
    assert!(matches!(far, Err(MeasureRefused::Page(_))), "{far:?}");
    assert_eq!(ctl.tool_offset(1), page);
}
