//! Manual moves between programs: jog, step (handwheel) and reference
//! return run within the axes' limits, stop where they are told, and the
//! program then starts from where the axes stand.

mod common;

use common::{check_limits, module, Run};
use nc::Machine;
use runtime::{Config, Controller, JogRate, Manual, ManualAxis, ManualRefused, RunState, SetPoint};

/// A controller for `src` on `machine`, its interpreter run ahead (the
/// queue filled from the power-on position, as a host does before cycle
/// start).
fn controller(src: &str, machine: Machine) -> Controller {
    let m = module(src, &machine);
    let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
    ctl.run_ahead();
    ctl
}

/// Ticks `ctl` until `done` says so (at most 60 simulated s), pressing
/// through stops, the set points added to `pts`.
fn tick_until(
    ctl: &mut Controller,
    pts: &mut Vec<SetPoint>,
    mut done: impl FnMut(&mut Controller, &SetPoint) -> bool,
) {
    loop {
        ctl.run_ahead();
        let sp = ctl.tick();
        pts.push(sp);
        if done(ctl, &sp) {
            return;
        }
        assert!(sp.time_s < 60.0, "not done within 60 s: {:?}", ctl.state());
    }
}

/// The run so far, for the limit checks of `common`.
fn as_run(pts: Vec<SetPoint>, machine: &Machine) -> Run {
    Run {
        pts,
        canon: Vec::new(),
        state: RunState::Idle,
        alarm: None,
        cfg: Config::from_machine(machine),
    }
}

const PROGRAM: &str = "O0001\nG00 X20 Z5\nM30\n";

#[test]
fn a_step_moves_the_axis_and_the_program_starts_from_there() {
    let mut ctl = controller(PROGRAM, Machine::reference());
    let mut pts = Vec::new();
    let step = Manual::Step {
        axis: ManualAxis::Z,
        distance: -10.0,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step), Ok(()));
    assert_eq!(ctl.state(), RunState::Manual);
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    let stood = *pts.last().unwrap();
    assert_eq!((stood.axis_x, stood.axis_z), (0.0, -10.0));
    // Cycle start: the program's rapid runs from Z-10 up to Z5.
    let manual_periods = pts.len();
    ctl.cycle_start();
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Ended);
    let end = pts.last().unwrap();
    assert_eq!((end.axis_x, end.axis_z), (20.0, 5.0));
    let program = &pts[manual_periods..];
    assert!(program.iter().all(|p| p.axis_z >= -10.0));
    assert!(program.iter().any(|p| (-9.0..-1.0).contains(&p.axis_z)));
    check_limits(&as_run(pts, &Machine::reference()), false);
}

#[test]
fn a_jog_runs_until_stopped_within_its_feed_and_the_axis_limits() {
    let mut ctl = controller(PROGRAM, Machine::reference());
    let mut pts = Vec::new();
    let jog = Manual::Jog {
        axis: ManualAxis::X,
        plus: true,
        rate: JogRate::Feed(1200.0),
    };
    assert_eq!(ctl.manual(jog), Ok(()));
    tick_until(&mut ctl, &mut pts, |_, sp| sp.time_s >= 0.5);
    ctl.manual_stop();
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    // 1200 mm/min of radius is 20 mm/s: at most 10 mm in the 0.5 s, less
    // the start's acceleration (1500 mm/s² reaches it in 13 ms), and a
    // few periods of braking.
    let dt = Config::from_machine(&Machine::reference()).period_s;
    let r: Vec<f64> = pts.iter().map(|p| p.axis_x / 2.0).collect();
    let end = *r.last().unwrap();
    assert!((9.5..10.5).contains(&end), "stopped at a radius of {end}");
    let fastest = r.windows(2).map(|w| (w[1] - w[0]) / dt).fold(0.0, f64::max);
    assert!(fastest <= 20.0 + 1e-9, "{fastest} mm/s");
    assert!(r.windows(2).all(|w| w[1] >= w[0]), "X went back");
    assert_eq!(pts.last().unwrap().axis_z, 0.0);
    check_limits(&as_run(pts, &Machine::reference()), false);
}

#[test]
fn a_jog_and_a_step_stop_at_the_soft_limit() {
    // The reference Z travels from -510 to 2 mm.
    let machine = Machine::from_toml("[axes.z]\nsoft_limits = true\n").expect("a machine file");
    let mut ctl = controller(PROGRAM, machine.clone());
    let mut pts = Vec::new();
    let jog = Manual::Jog {
        axis: ManualAxis::Z,
        plus: true,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(jog), Ok(()));
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    assert_eq!(pts.last().unwrap().axis_z, 2.0);
    // Already at the limit, a step beyond it does not move; one back does.
    for (distance, at) in [(50.0, 2.0), (-20.0, -18.0)] {
        let step = Manual::Step {
            axis: ManualAxis::Z,
            distance,
            rate: JogRate::Feed(3000.0),
        };
        assert_eq!(ctl.manual(step), Ok(()));
        tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
        assert_eq!(pts.last().unwrap().axis_z, at);
    }
    assert_eq!(ctl.state(), RunState::Idle);
    check_limits(&as_run(pts, &machine), false);
}

#[test]
fn a_reference_return_goes_to_machine_zero_at_the_return_feed() {
    let mut ctl = controller(PROGRAM, Machine::reference());
    let mut pts = Vec::new();
    // X+30 of diameter is 15 mm of radius; a step given while another
    // runs follows it, and so does a reference return.
    let steps = [(ManualAxis::X, 30.0), (ManualAxis::Z, -40.0)];
    for (axis, distance) in steps {
        let rate = JogRate::Rapid;
        assert_eq!(
            ctl.manual(Manual::Step {
                axis,
                distance,
                rate
            }),
            Ok(())
        );
    }
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    let at = *pts.last().unwrap();
    assert_eq!((at.axis_x, at.axis_z), (30.0, -40.0));
    let from = pts.len();
    for axis in [ManualAxis::Z, ManualAxis::X] {
        assert_eq!(ctl.manual(Manual::Home { axis }), Ok(()));
    }
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    let at = *pts.last().unwrap();
    assert_eq!((at.axis_x, at.axis_z), (0.0, 0.0));
    // №113: 4000 mm/min, 66.7 mm/s along the path of each return.
    let dt = Config::from_machine(&Machine::reference()).period_s;
    let fastest = (pts[from - 1..].windows(2))
        .map(|w| (w[1].axis_x / 2.0 - w[0].axis_x / 2.0).hypot(w[1].axis_z - w[0].axis_z) / dt)
        .fold(0.0, f64::max);
    assert!(fastest <= 4000.0 / 60.0 + 1e-9, "{fastest} mm/s");
    assert!(fastest > 60.0, "{fastest} mm/s");
    check_limits(&as_run(pts, &Machine::reference()), false);
}

#[test]
fn manual_moves_are_made_between_programs() {
    let mut ctl = controller(PROGRAM, Machine::reference());
    let step = |distance| Manual::Step {
        axis: ManualAxis::Z,
        distance,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step(f64::NAN)), Err(ManualRefused::BadValue));
    let slow = Manual::Jog {
        axis: ManualAxis::Z,
        plus: false,
        rate: JogRate::Feed(0.0),
    };
    assert_eq!(ctl.manual(slow), Err(ManualRefused::BadValue));
    assert_eq!(ctl.state(), RunState::Idle);
    let mut pts = Vec::new();
    ctl.cycle_start();
    tick_until(&mut ctl, &mut pts, |_, _| true);
    assert_eq!(ctl.manual(step(-1.0)), Err(ManualRefused::NotIdle));
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Ended);
    assert_eq!(ctl.manual(step(-1.0)), Err(ManualRefused::NotIdle));
    // After a reset the program waits at its start: manual moves again.
    ctl.reset();
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    assert_eq!(ctl.manual(step(-1.0)), Ok(()));
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    assert_eq!(pts.last().unwrap().axis_z, 4.0);
}

#[test]
fn on_a_split_controller_the_interpreter_restarts_where_the_axes_stand() {
    let m = module(PROGRAM, &Machine::reference());
    let ctl = Controller::new(m, Machine::reference(), runtime::AutoAck).expect("loads");
    let (mut interp, mut rt) = ctl.split();
    interp.run_ahead();
    let step = Manual::Step {
        axis: ManualAxis::X,
        distance: 50.0,
        rate: JogRate::Rapid,
    };
    assert_eq!(rt.manual(step), Ok(()));
    let mut last = rt.tick();
    let mut started = false;
    for _ in 0..200_000 {
        interp.run_ahead();
        last = rt.tick();
        if rt.state() == RunState::Idle && !started {
            assert_eq!((last.axis_x, last.axis_z), (50.0, 0.0));
            rt.cycle_start();
            started = true;
        }
        if rt.state() == RunState::Ended {
            break;
        }
    }
    // The program's G00 X20 Z5 ran from X50: it came back in on X.
    assert_eq!(rt.state(), RunState::Ended);
    assert_eq!((last.axis_x, last.axis_z), (20.0, 5.0));
}

#[test]
fn under_jerk_limiting_manual_moves_keep_the_jerk_too() {
    let machine = Machine::from_toml("[motion]\njerk_limiting = true\n").expect("a machine file");
    let mut ctl = controller(PROGRAM, machine.clone());
    let mut pts = Vec::new();
    let moves = [
        Manual::Step {
            axis: ManualAxis::X,
            distance: 40.0,
            rate: JogRate::Rapid,
        },
        Manual::Step {
            axis: ManualAxis::Z,
            distance: -25.0,
            rate: JogRate::Feed(2000.0),
        },
        Manual::Home {
            axis: ManualAxis::X,
        },
    ];
    for m in moves {
        assert_eq!(ctl.manual(m), Ok(()));
    }
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    let at = *pts.last().unwrap();
    assert_eq!((at.axis_x, at.axis_z), (0.0, -25.0));
    let run = as_run(pts, &machine);
    check_limits(&run, false);
    let worst = common::worst_jerk(&run);
    assert!(worst <= 1.0 + 1e-6, "jerk {worst} of the limit");
}

#[test]
fn c_turns_by_hand_and_the_program_starts_from_its_angle() {
    // A step of C+90 at rapid, then a jog asked at 3600°/min, held to C's
    // maximum cutting feed of 1800°/min (30°/s), stopped after 0.5 s:
    // about 15° more (the start's 8 ms at 3600°/s² lose what the braking
    // adds). The program then reads the angle (#5003) and turns C by H30
    // from there.
    let mut machine = Machine::reference();
    machine.axes.c.enabled = true;
    let src = "O0001\n#100=#5003\nG00 H30\nM30\n";
    let mut ctl = controller(src, machine.clone());
    let mut pts = Vec::new();
    let step = Manual::Step {
        axis: ManualAxis::C,
        distance: 90.0,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step), Ok(()));
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    assert_eq!(pts.last().unwrap().c, Some(90.0));
    let jog = Manual::Jog {
        axis: ManualAxis::C,
        plus: true,
        rate: JogRate::Feed(3600.0),
    };
    assert_eq!(ctl.manual(jog), Ok(()));
    let t0 = pts.last().unwrap().time_s;
    tick_until(&mut ctl, &mut pts, |_, sp| sp.time_s >= t0 + 0.5);
    ctl.manual_stop();
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Idle);
    let stood = pts.last().unwrap().c.unwrap();
    assert!((104.5..105.5).contains(&stood), "C stood at {stood}");
    ctl.cycle_start();
    tick_until(&mut ctl, &mut pts, |c, _| c.state() == RunState::Ended);
    assert_eq!(ctl.vm().variable(100).ok(), Some(stood));
    assert_eq!(pts.last().unwrap().c, Some(stood + 30.0));
    // Without a C axis: refused.
    let mut ctl = controller(PROGRAM, Machine::reference());
    assert_eq!(ctl.manual(step), Err(ManualRefused::NoSuchAxis));
}
