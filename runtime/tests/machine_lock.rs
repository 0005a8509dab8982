//! Machine lock through the controller: the program runs period for
//! period as it would unlocked (the oracle: the same program run without
//! the lock), while the axes, and the drives' counts, stand where they
//! stood at cycle start; the reset after it brings the program's point
//! back to the axes, so the next run moves as from a fresh start.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::{Controller, JogRate, Manual, ManualAxis, RunState, SetPoint};

/// Offset 1: X2 (diameter) Z3, wear X0.1; Z has 0.03 mm of backlash,
/// which the counts take up once Z has moved in −.
const MACHINE: &str =
    "[axes.z]\nbacklash_mm = 0.03\n[[tools.offset]]\nnumber = 1\nx = 2.0\nz = 3.0\nwear_x = 0.1\n";
/// Ends at X50 Z-10: with offset 1 the slide at X52.1 Z-7, whose counts
/// take up the backlash: Z -7.03.
const CUT: &str = "T0101\nG00 X50 Z2\nG01 Z-10 F500\nM30\n";

fn controller() -> Controller {
    let machine = Machine::from_toml(MACHINE).expect("a machine file");
    let m = module(CUT, &machine);
    Controller::new(m, machine, runtime::AutoAck).expect("loads")
}

/// Cycle start, then every period to the end; `at` is called before
/// each period with its index.
fn periods(ctl: &mut Controller, mut at: impl FnMut(&mut Controller, usize)) -> Vec<SetPoint> {
    ctl.cycle_start();
    let mut pts = Vec::new();
    for i in 0..400_000 {
        at(ctl, i);
        ctl.run_ahead();
        pts.push(ctl.tick());
        match ctl.state() {
            RunState::Ended => return pts,
            RunState::Alarm(a) => panic!("alarm {a}"),
            _ => {}
        }
    }
    panic!("not done: {:?}", ctl.state());
}

/// What the program does in a period: its point, speed, block, motion,
/// tool and spindle; not the axes.
fn program_side(p: &SetPoint) -> (f64, f64, f64, f64, u32, u32, f64) {
    (p.time_s, p.x, p.z, p.feed, p.line, p.tool, p.spindle_rpm)
}

fn slide(p: &SetPoint) -> (f64, f64, i64, i64) {
    (p.axis_x, p.axis_z, p.counts.x, p.counts.z)
}

#[test]
fn a_locked_run_runs_the_program_while_the_axes_stand() {
    let free = periods(&mut controller(), |_, _| {});
    let end = free.last().expect("periods");
    assert_eq!(slide(end), (52.1, -7.0, 52_100, -7_030));

    let mut ctl = controller();
    ctl.set_machine_lock(true);
    let locked = periods(&mut ctl, |_, _| {});
    assert_eq!(locked.len(), free.len());
    for (l, f) in locked.iter().zip(&free) {
        assert_eq!(program_side(l), program_side(f));
        assert_eq!(l.motion, f.motion);
        // Power-on: the slide at machine X0 Z0.
        assert_eq!(slide(l), (0.0, 0.0, 0, 0), "{l:?}");
    }
    assert!(ctl.engine().axes_locked());
    let standing = ctl.engine().machine_point().expect("outside a plane");
    assert_eq!((standing.x, standing.z), (0.0, 0.0));

    // The reset brings the point back to the slide; the lock still on
    // holds the next run too. Off, the run moves as the first free one.
    reset_to_idle(&mut ctl);
    assert!(!ctl.engine().axes_locked());
    let p = ctl.engine().position();
    assert_eq!((p.x(), p.z), (0.0, 0.0));
    let again = periods(&mut ctl, |_, _| {});
    assert!(again.iter().all(|p| slide(p) == (0.0, 0.0, 0, 0)));
    reset_to_idle(&mut ctl);
    ctl.set_machine_lock(false);
    let after = periods(&mut ctl, |_, _| {});
    assert_eq!(after.len(), free.len());
    for (a, f) in after.iter().zip(&free) {
        assert_eq!((a.x, a.z, slide(a)), (f.x, f.z, slide(f)));
    }
}

/// Switched on or off mid-run, the switch waits for the next start: the
/// axes must not stop, or start, within one period.
#[test]
fn the_switch_is_read_when_a_run_starts() {
    let mut ctl = controller();
    let pts = periods(&mut ctl, |c, i| {
        if i == 300 {
            c.set_machine_lock(true);
        }
    });
    assert_eq!(
        slide(pts.last().expect("periods")),
        (52.1, -7.0, 52_100, -7_030)
    );
    assert!(!ctl.engine().axes_locked());

    reset_to_idle(&mut ctl);
    let pts = periods(&mut ctl, |c, i| {
        if i == 300 {
            c.set_machine_lock(false);
        }
    });
    // Held where the first run left the slide.
    assert!(pts.iter().all(|p| slide(p) == (52.1, -7.0, 52_100, -7_030)));
    assert_eq!(ctl.state(), RunState::Ended);
    assert!(ctl.engine().axes_locked());
}

/// A jog under machine lock moves the programmed point, not the slide;
/// when it ends, the point is back on the slide.
#[test]
fn a_locked_jog_leaves_the_slide_standing() {
    let mut ctl = controller();
    ctl.set_machine_lock(true);
    let step = Manual::Step {
        axis: ManualAxis::Z,
        distance: -30.0,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step), Ok(()));
    let mut lowest = 0.0_f64;
    for _ in 0..100_000 {
        ctl.run_ahead();
        let p = ctl.tick();
        assert_eq!(slide(&p), (0.0, 0.0, 0, 0), "{p:?}");
        lowest = lowest.min(ctl.engine().position().z);
        if ctl.state() == RunState::Idle {
            break;
        }
    }
    assert_eq!(lowest, -30.0);
    assert_eq!(ctl.engine().position().z, 0.0);
    // Unlocked, the next run starts from the slide: as the free run.
    ctl.set_machine_lock(false);
    let end = run_to_end(&mut ctl);
    assert_eq!(slide(&end), (52.1, -7.0, 52_100, -7_030));
}

/// The machine file's `operator.machine_lock`, on a split controller:
/// the program reaches its end, the axes stay at power-on.
#[test]
fn the_machine_file_locks_a_split_controller() {
    let machine = Machine::from_toml("[operator]\nmachine_lock = true\n").expect("a machine file");
    let run = common::run_split_with(CUT, machine, runtime::AutoAck, |_, _| {});
    assert_eq!(run.state, RunState::Ended);
    let end = run.pts.last().expect("periods");
    assert_eq!((end.x, end.z), (50.0, -10.0));
    assert!(run.pts.iter().all(|p| slide(p) == (0.0, 0.0, 0, 0)));
}
