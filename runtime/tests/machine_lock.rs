//! Machine lock through the controller: the program runs period for
//! period as it would unlocked (the oracle: the same program run without
//! the lock), while the axes, and the drives' counts, stand where they
//! stood at cycle start; the reset after it brings the program's point
//! back to the axes, so the next run moves as from a fresh start. And
//! the auxiliary function lock: the M, S and T functions pass
//! unexecuted.

mod common;

use common::{module, reset_to_idle, run_to_end};
use nc::Machine;
use runtime::plc::PlcFunction;
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

/// A PLC that records what it is asked to do.
#[derive(Default)]
struct Recorder(Vec<PlcFunction>);

impl runtime::Plc for Recorder {
    fn request(&mut self, f: PlcFunction) {
        self.0.push(f);
    }
    fn done(&mut self, _: PlcFunction) -> bool {
        true
    }
}

/// Runs `src` to its end or an alarm (at most 60 simulated s); `live` is
/// called before each period with its index.
fn run_recorded(
    src: &str,
    setup: impl FnOnce(&mut Controller<Recorder>),
    mut live: impl FnMut(&mut Controller<Recorder>, usize),
) -> (Vec<SetPoint>, Vec<PlcFunction>, RunState) {
    let machine = Machine::reference();
    let m = module(src, &machine);
    let mut ctl = Controller::new(m, machine, Recorder::default()).expect("loads");
    setup(&mut ctl);
    ctl.cycle_start();
    let mut pts = Vec::new();
    for i in 0..60_000 {
        live(&mut ctl, i);
        ctl.run_ahead();
        pts.push(ctl.tick());
        if matches!(ctl.state(), RunState::Ended | RunState::Alarm(_)) {
            break;
        }
    }
    let asked = core::mem::take(&mut ctl.engine_mut().plc_mut().0);
    (pts, asked, ctl.state())
}

const FUNCTIONS: &str = "T0202\nM03 S500\nM08\nG98 G01 W-5 F300\nM09\nM05\nG04 X0.2\nM30\n";

/// Auxiliary function lock: the PLC is asked for nothing, the spindle
/// never turns and the turret stays on tool 1 (power-on T0100), while
/// the move runs to its end as unlocked.
#[test]
fn aux_lock_passes_the_functions_unexecuted() {
    let (free, asked, state) = run_recorded(FUNCTIONS, |_| {}, |_, _| {});
    assert_eq!(state, RunState::Ended);
    assert!(
        asked.contains(&PlcFunction::M(8)) && asked.len() >= 6,
        "{asked:?}"
    );
    assert!(free.iter().any(|p| p.spindle_rpm == 500.0 && p.tool == 2));

    let (locked, asked, state) = run_recorded(FUNCTIONS, |c| c.set_aux_lock(true), |_, _| {});
    assert_eq!(state, RunState::Ended);
    assert_eq!(asked, []);
    assert!(locked.iter().all(|p| p.spindle_rpm == 0.0 && p.tool == 1));
    let (a, b) = (
        free.last().expect("periods"),
        locked.last().expect("periods"),
    );
    assert_eq!((a.x, a.z), (b.x, b.z));
    assert_eq!((b.x, b.z), (0.0, -5.0));
}

/// Switched on while the spindle turns (after the M03 ran, at the cut):
/// the M05 after it is not executed either, so the spindle turns on
/// through the dwell; the functions before the switch were.
#[test]
fn aux_lock_is_read_as_the_motion_reaches_each_function() {
    let mut cutting = false;
    let (pts, asked, state) = run_recorded(
        FUNCTIONS,
        |_| {},
        |c, _| {
            if !cutting && c.engine().active_codes().f == 300.0 {
                cutting = true;
                c.set_aux_lock(true);
            }
        },
    );
    assert!(cutting);
    assert_eq!(state, RunState::Ended);
    assert!(!asked.contains(&PlcFunction::M(9)), "{asked:?}");
    assert!(asked.contains(&PlcFunction::M(8)), "{asked:?}");
    let dwell: Vec<f64> = pts
        .iter()
        .filter(|p| p.line == 7)
        .map(|p| p.spindle_rpm)
        .collect();
    assert!(
        dwell.len() >= 100 && dwell.iter().all(|&r| r == 500.0),
        "{dwell:?}"
    );
}

/// Feed per revolution needs the turning spindle the lock keeps from
/// starting: E7003, as a real control waits for it; with dry run the
/// feed moves at the dry-run rate and the run ends. A thread needs it
/// with dry run too.
#[test]
fn aux_lock_with_feed_per_revolution_needs_dry_run() {
    let src = "M03 S500\nG99 G01 W-5 F0.2\nM30\n";
    let (_, _, state) = run_recorded(src, |c| c.set_aux_lock(true), |_, _| {});
    assert_eq!(state, RunState::Alarm(7003));
    let dry = |c: &mut Controller<Recorder>| {
        c.set_aux_lock(true);
        c.set_dry_run(true);
    };
    let (pts, asked, state) = run_recorded(src, dry, |_, _| {});
    assert_eq!((state, asked), (RunState::Ended, vec![]));
    assert_eq!(pts.last().map(|p| p.z), Some(-5.0));
    // A thread stays on the spindle, dry run or not.
    let thread = "M03 S500\nG00 X20 Z2\nG32 Z-10 F1.5\nM30\n";
    let (_, _, state) = run_recorded(thread, dry, |_, _| {});
    assert_eq!(state, RunState::Alarm(7003));
}
