//! The split controller: the interpreter on a thread of its own, the
//! real-time half ticked on this one without ever waiting for it — the
//! same program, the same canon, the same rules in every period.

mod common;

use common::{check_end_points, check_limits, run, run_split, run_split_with, SHAFT};
use nc::Machine;
use runtime::RunState;
use std::fmt::Write;

/// 3 000 short segments: more than the ring and the planner hold, so
/// the interpreter keeps meeting a full queue and the real-time half
/// keeps taking its bounded share per period.
fn contour() -> String {
    let mut s = String::from("O0002\nG98 G00 X40 Z2\nG01 F3000\n");
    for i in 0..3000 {
        let z = -0.05 * f64::from(i);
        let x = 40.0 + 4.0 * (f64::from(i) * 0.02).sin();
        let _ = writeln!(s, "X{x:.3} Z{z:.3}");
    }
    s.push_str("G00 X100 Z50\nM30\n");
    s
}

#[test]
fn a_split_run_makes_the_same_canon_and_keeps_every_rule() {
    for src in [SHAFT.to_string(), contour()] {
        let one = run(&src);
        let two = run_split(&src);
        assert_eq!(two.state, RunState::Ended);
        assert_eq!(two.canon, one.canon);
        check_end_points(&two);
        check_limits(&two, false);
        let (a, b) = (one.pts.last().unwrap(), two.pts.last().unwrap());
        assert_eq!((a.x, a.z), (b.x, b.z));
    }
}

/// #5042 waits for all motion sent before it to have run, across the
/// threads as in one context.
#[test]
fn a_current_position_read_waits_for_the_motion_across_threads() {
    let src = "O0015\nG98 G01 Z-30 F600\n#100 = #5042\nG01 Z[#100 - 5]\nM30\n";
    let r = run_split(src);
    assert_eq!(r.state, RunState::Ended);
    assert!((r.pts.last().unwrap().z + 35.0).abs() < 1e-9);
    assert_eq!(r.canon, run(src).canon);
}

/// The skip report crosses back: the block after G31 starts where the
/// axes stopped, #5062 holds the skip point.
#[test]
fn the_skip_signal_ends_a_g31_move_across_threads() {
    let src = "O0012\nG98 G31 Z-50 F600\n#100 = #5062\nG01 Z[#100 + 2]\nM30\n";
    let mut hit_z = None;
    let r = run_split_with(src, Machine::reference(), runtime::AutoAck, |rt, sp| {
        if sp.z <= -20.0 && hit_z.is_none() {
            hit_z = Some(sp.z);
            rt.set_skip_input(true);
        }
    });
    assert_eq!(r.state, RunState::Ended);
    let hit = hit_z.unwrap();
    assert!((r.pts.last().unwrap().z - (hit + 2.0)).abs() < 1e-9);
    check_limits(&r, false);
    // A G31 of zero length runs nothing and must not hold the program.
    let r = run_split("O0018\nG98 G00 X10 Z5\nG31 F100\nG01 Z0\nM30\n");
    assert_eq!(r.state, RunState::Ended);
}

/// Reset drops what is in flight and restarts the program where the axes
/// stopped; cycle start runs it to its end.
#[test]
fn reset_restarts_the_interpreter_where_the_axes_stopped() {
    let mut reset = false;
    let mut restarted = false;
    let r = run_split_with(SHAFT, Machine::reference(), runtime::AutoAck, |rt, sp| {
        // In the Z-20 cut, well under way.
        if !reset && sp.line == 5 && sp.feed > 0.0 {
            rt.reset();
            reset = true;
        }
        if reset && !restarted && rt.state() == RunState::Idle {
            assert_eq!(sp.feed, 0.0, "reset left the axes moving");
            restarted = true;
            rt.cycle_start();
        }
    });
    assert!(restarted);
    assert_eq!(r.state, RunState::Ended);
    check_limits(&r, false);
    let last = r.pts.last().unwrap();
    assert_eq!((last.x, last.z), (100.0, 50.0));
    // The program ran once up to the reset, then whole: its first rapid
    // (X40 Z2) is in the canon twice.
    let firsts = r
        .canon
        .iter()
        .filter(|e| matches!(e, nc::Event::Rapid { x, z, .. } if *x == 40.0 && *z == 2.0))
        .count();
    assert_eq!(firsts, 2);
}

#[test]
fn a_program_alarm_names_its_place_across_threads() {
    let r = run_split("O0014\nG98 G01 Z-5 F600\n#3000 = 12 (STOP HERE)\nG01 Z-10\nM30\n");
    assert_eq!(r.state, RunState::Alarm(3012));
    assert!((r.pts.last().unwrap().z + 5.0).abs() < 1e-9);
    let alarm = r.alarm.unwrap();
    assert_eq!((alarm.message.as_str(), alarm.line), ("STOP HERE", 3));
}

#[test]
fn the_halves_can_move_to_their_threads() {
    fn send<T: Send>() {}
    send::<runtime::Interpreter>();
    send::<runtime::Realtime<runtime::AutoAck>>();
}

/// The PLC is the real-time half's: M08 acknowledged only after 100
/// periods holds the next cut there, as in one context.
#[test]
fn the_next_block_waits_for_the_plc_across_threads() {
    struct Slow(u32);
    impl runtime::Plc for Slow {
        fn request(&mut self, f: runtime::PlcFunction) {
            if f == runtime::PlcFunction::M(8) {
                self.0 = 100;
            }
        }
        fn done(&mut self, _: runtime::PlcFunction) -> bool {
            self.0 = self.0.saturating_sub(1);
            self.0 == 0
        }
    }
    let src = "O0010\nG98 G01 Z-1 F600\nM08\nG01 Z-2\nM30\n";
    let r = run_split_with(src, Machine::reference(), Slow(0), |_, _| {});
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    // Z stands at -1 for the 100 periods of the handshake (and for any
    // periods the queue waited for the interpreter).
    let standing = r.pts.iter().filter(|p| (p.z + 1.0).abs() < 1e-12).count();
    assert!(standing >= 100, "{standing}");
}

/// Feed hold on the real-time half decelerates on the path; cycle start
/// resumes, and the run ends where the program does.
#[test]
fn feed_hold_and_single_block_work_across_threads() {
    let (mut held, mut resumed) = (false, false);
    let r = run_split_with(SHAFT, Machine::reference(), runtime::AutoAck, |rt, sp| {
        if !held && sp.line == 6 && sp.feed > 0.0 {
            rt.feed_hold();
            held = true;
        }
        if held && !resumed && rt.state() == RunState::Held {
            assert_eq!(sp.feed, 0.0, "held while moving");
            resumed = true;
            rt.cycle_start();
        }
    });
    assert!(resumed);
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    check_limits(&r, false);
    // Single block: the helper presses cycle start at every stop.
    let stops = std::cell::Cell::new(0);
    let r = run_split_with(
        "O0013\nG98 G01 Z-1 F600\nZ-2\nZ-3\nM30\n",
        Machine::reference(),
        runtime::AutoAck,
        |rt, sp| {
            if sp.time_s < 0.002 {
                rt.set_single_block(true);
            }
            if let RunState::Stopped(runtime::command::PauseKind::SingleBlock) = rt.state() {
                stops.set(stops.get() + 1);
            }
        },
    );
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    assert_eq!(stops.get(), 3);
}

/// Both halves driven from this thread, in turn, until the real-time
/// half is in `until` (at most 60 simulated seconds): the last set point.
fn drive_until(
    interp: &mut runtime::Interpreter,
    rt: &mut runtime::Realtime<runtime::AutoAck>,
    until: RunState,
) -> runtime::SetPoint {
    for _ in 0..60_000 {
        interp.run_ahead();
        let sp = rt.tick();
        match rt.state() {
            s if s == until => return sp,
            RunState::Stopped(_) => rt.cycle_start(),
            _ => {}
        }
    }
    panic!("not {until:?} within 60 s: {:?}", rt.state());
}

/// Another program on a split controller: selected on the interpreter
/// half, it takes the program's place at the real-time half's reset and
/// starts where the axes stand (as `select.rs` on a whole controller:
/// X40 stays, Z from 2 by W−12 to −10, #500 kept); the motion's alarms
/// name its file from then on.
#[test]
fn another_program_is_selected_for_the_next_reset() {
    let machine = Machine::reference();
    let first = common::module("#500=7\nG00 X40 Z2\nM30\n", &machine);
    let compile = |name: &str, src: &str| {
        let out = compiler::compile(name, src.as_bytes(), &compiler::Options::default());
        out.module.expect("compiles")
    };
    let second = compile(
        "second.nc",
        "#100=#500\nG01 W-12 F300\n#3000=12 (AT THE END)\nM30\n",
    );
    let ctl = runtime::Controller::new(first, machine, runtime::AutoAck).expect("loads");
    let (mut interp, mut rt) = ctl.split();
    rt.cycle_start();
    let end = drive_until(&mut interp, &mut rt, RunState::Ended);
    assert_eq!((end.x, end.z), (40.0, 2.0));
    assert_eq!(interp.select_program(second), Ok(()));
    assert!(interp.select_pending());
    // Until the reset the program loaded stays.
    assert_eq!(interp.file_name(0), Some("test.nc"));
    rt.reset();
    drive_until(&mut interp, &mut rt, RunState::Idle);
    // The interpreter learns of the reset at its next run-ahead.
    interp.run_ahead();
    assert!(!interp.select_pending());
    assert_eq!(interp.file_name(0), Some("second.nc"));
    rt.cycle_start();
    let end = drive_until(&mut interp, &mut rt, RunState::Alarm(3012));
    assert_eq!((end.x, end.z), (40.0, -10.0));
    assert_eq!(interp.variable(100), Ok(7.0));
    let alarm = rt.alarm().expect("an alarm");
    assert_eq!((alarm.file.as_str(), alarm.line), ("second.nc", 3));
    let text = interp.vm_alarm().expect("the VM's alarm").message;
    assert_eq!(text, "AT THE END");
}

#[test]
fn a_program_for_another_machine_is_not_selected() {
    let machine = Machine::reference();
    let ctl = runtime::Controller::new(
        common::module("G00 X40 Z2\nM30\n", &machine),
        machine,
        runtime::AutoAck,
    )
    .expect("loads");
    let (mut interp, _rt) = ctl.split();
    let radius = Machine::from_toml("[axes.x]\ndiameter = false\n").expect("a machine file");
    let other = common::module("G00 X20 Z2\nM30\n", &radius);
    assert!(matches!(
        interp.select_program(other),
        Err(runtime::SelectRefused::Machine(_))
    ));
    assert!(!interp.select_pending());
}
