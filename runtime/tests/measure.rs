//! Tool setting by a measured cut: the offset's geometry becomes the
//! slide's position less the work origin, the measurement and the wear,
//! and the next run cuts the measured size. The figures are by hand.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, JogRate, Manual, ManualAxis, MeasureRefused, MeasuredAxis, RunState};

/// Offset 1: geometry X2 (diameter) Z3, wear X0.1; work and machine
/// coordinates are one on the reference machine.
const MACHINE: &str = "[[tools.offset]]\nnumber = 1\nx = 2.0\nz = 3.0\nwear_x = 0.1\n";
const CUT: &str = "T0101\nG00 X50 Z2\nG01 Z-10 F500\nM30\n";

fn controller() -> Controller {
    let machine = Machine::from_toml(MACHINE).expect("a machine file");
    let m = module(CUT, &machine);
    Controller::new(m, machine, runtime::AutoAck).expect("loads")
}

/// The cut ends at X50 Z-10 with offset 1: the slide at X52.1 Z-7.
/// Measured 49.96 on the diameter: the geometry becomes 52.1 − 49.96 −
/// 0.1 = 2.04 (the tool cut 0.04 small); the face at Z-10.03:
/// −7 + 10.03 = 3.03. The wear stays 0.1. Run again, the slide stands at
/// X50 + 2.04 + 0.1 = 52.14 and Z-10 + 3.03 = -6.97.
#[test]
fn a_measured_cut_sets_the_offset_s_geometry() {
    let mut ctl = controller();
    let first = run_to_end(&mut ctl);
    assert!((first.axis_x - 52.1).abs() < 1e-9 && (first.axis_z + 7.0).abs() < 1e-9);
    let l = ctl
        .measure_tool_offset(1, MeasuredAxis::X, 49.96)
        .expect("measured");
    assert!(
        (l.x - 2.04).abs() < 1e-12 && l.wear_x == 0.1 && l.z == 3.0,
        "{l:?}"
    );
    let l = ctl
        .measure_tool_offset(1, MeasuredAxis::Z, -10.03)
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

/// As an operator sets a tool: `T0101` and a cut along Z at X50 in MDI,
/// Z jogged clear (X stays on the diameter cut: the slide at 52.1), the
/// diameter measured 50.03; with G54 at X0 Z-100 and EXOFS Z5 (work Z0 at
/// machine Z-95). By hand: X 52.1 − 0 − 50.03 − 0.1 = 1.97 (the tool cut
/// 0.03 large). A face then cut at work Z-1 (machine Z-96 + 3 = -93 for
/// the slide) measures Z-1.02: −93 + 95 + 1.02 = 3.02.
#[test]
fn a_tool_set_in_mdi_after_jogging_clear() {
    let machine = Machine::from_toml(MACHINE).expect("a machine file");
    let mut ctl = controller();
    let g54 = runtime::Xz { x: 0.0, z: -100.0 };
    assert_eq!(ctl.set_work_offset(runtime::WorkOffset::G54, g54), Ok(()));
    let exofs = runtime::Xz { x: 0.0, z: 5.0 };
    assert_eq!(
        ctl.set_work_offset(runtime::WorkOffset::External, exofs),
        Ok(())
    );
    mdi(
        &mut ctl,
        module("T0101\nG00 X50 Z2\nG01 Z-10 F500\n", &machine),
    );
    jog(&mut ctl, ManualAxis::Z, 30.0);
    let l = ctl
        .measure_tool_offset(1, MeasuredAxis::X, 50.03)
        .expect("measured");
    assert!((l.x - 1.97).abs() < 1e-12, "{l:?}");
    mdi(
        &mut ctl,
        module("T0101\nG00 X60 Z2\nG01 Z-1 F500\nX40\n", &machine),
    );
    jog(&mut ctl, ManualAxis::X, 20.0);
    let l = ctl
        .measure_tool_offset(1, MeasuredAxis::Z, -1.02)
        .expect("measured");
    assert!(
        (l.z - 3.02).abs() < 1e-12 && (l.x - 1.97).abs() < 1e-12,
        "{l:?}"
    );
}

/// Refused, changing nothing: while the axes move, an offset outside the
/// table, a geometry beyond the page's range.
#[test]
fn a_measurement_needs_standing_axes_and_a_row_of_the_page() {
    let mut ctl = controller();
    let page = ctl.tool_offset(1);
    ctl.cycle_start();
    for _ in 0..300 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.state(), RunState::Running);
    assert_eq!(
        ctl.measure_tool_offset(1, MeasuredAxis::X, 50.0),
        Err(MeasureRefused::NotStanding)
    );
    run_to_end(&mut ctl);
    let outside = ctl.measure_tool_offset(33, MeasuredAxis::X, 50.0);
    assert!(matches!(&outside, Err(MeasureRefused::Page(e)) if e.key == "tools.offsets"));
    let far = ctl.measure_tool_offset(1, MeasuredAxis::Z, 2.0e6);
    assert!(matches!(far, Err(MeasureRefused::Page(_))), "{far:?}");
    assert_eq!(ctl.tool_offset(1), page);
}

/// MDI blocks run to their end.
fn mdi(ctl: &mut Controller, blocks: isa::Module) {
    assert_eq!(ctl.mdi(blocks), Ok(()));
    ctl.cycle_start();
    for _ in 0..100_000 {
        ctl.run_ahead();
        ctl.tick();
        if !ctl.in_mdi() && ctl.state() == RunState::Idle {
            return;
        }
    }
    panic!("the MDI blocks did not end: {:?}", ctl.state());
}

/// An incremental jog of `mm`, at rapid, to its end.
fn jog(ctl: &mut Controller, axis: ManualAxis, mm: f64) {
    let step = Manual::Step {
        axis,
        distance: mm,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step), Ok(()));
    for _ in 0..100_000 {
        ctl.run_ahead();
        ctl.tick();
        if ctl.state() == RunState::Idle {
            return;
        }
    }
    panic!("the jog did not end");
}

/// Both halves of a split controller from this thread, in turn, until
/// the real-time half is in `until`: the last set point, the periods
/// the axes were moving and those of them the interpreter refused a
/// measurement in.
fn drive(
    interp: &mut runtime::Interpreter,
    rt: &mut runtime::Realtime<runtime::AutoAck>,
    until: RunState,
) -> (runtime::SetPoint, u32, u32) {
    let (mut moving, mut refused) = (0, 0);
    for _ in 0..100_000 {
        interp.run_ahead();
        let sp = rt.tick();
        if rt.state() == until {
            return (sp, moving, refused);
        }
        if rt.state() == RunState::Running {
            moving += 1;
            let r = interp.measure_tool_offset(1, MeasuredAxis::X, 49.96);
            refused += u32::from(r == Err(MeasureRefused::NotStanding));
        }
    }
    panic!("never {until:?}");
}

/// The same cut on a split controller: while it runs the interpreter
/// refuses a measurement (the real-time half publishes no standing
/// point); at its end (slide at X52.1) the measurement 49.96 gives
/// geometry 2.04 as on a whole controller, and the run after the reset
/// cuts with it: the slide at 52.14.
#[test]
fn a_split_controller_measures_where_the_real_time_half_stands() {
    let (mut interp, mut rt) = controller().split();
    rt.cycle_start();
    let (end, moving, refused) = drive(&mut interp, &mut rt, RunState::Ended);
    assert!(moving > 100 && refused == moving, "{refused} of {moving}");
    assert!((end.axis_x - 52.1).abs() < 1e-9, "{end:?}");
    let l = interp
        .measure_tool_offset(1, MeasuredAxis::X, 49.96)
        .expect("measured");
    assert!((l.x - 2.04).abs() < 1e-12 && l.wear_x == 0.1, "{l:?}");
    assert_eq!(interp.tool_offset(1), Some(l));
    rt.reset();
    drive(&mut interp, &mut rt, RunState::Idle);
    rt.cycle_start();
    let (again, ..) = drive(&mut interp, &mut rt, RunState::Ended);
    assert!((again.axis_x - 52.14).abs() < 1e-9, "{again:?}");
}
