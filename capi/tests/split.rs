//! A controller split in two through the C interface: the interpreter
//! half runs the VM on a thread of its own while the real-time half
//! ticks on this one, calls on the two at the same time; each call goes
//! to its half, the other half refuses it.

mod periods;

use gbc::*;
use periods::{blank, controller_on, load, no_alarm};
use std::ffi::c_char;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A controller with `src` loaded, split: (machine, interpreter, real-time).
fn split(src: &str) -> (GbcMachine, GbcController, GbcController) {
    let (m, c) = controller_on("");
    load(c, src);
    let mut rt = 0;
    assert_eq!(unsafe { gbc_controller_split(c, &mut rt) }, GbcStatus::Ok);
    assert_ne!(rt, 0);
    (m, c, rt)
}

fn free(m: GbcMachine, interp: GbcController, rt: GbcController) {
    assert_eq!(gbc_realtime_free(rt), GbcStatus::Ok);
    assert_eq!(gbc_controller_free(interp), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

fn state(rt: GbcController) -> GbcStateInfo {
    let mut st = GbcStateInfo {
        state: GbcRunState::Idle,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    };
    assert_eq!(unsafe { gbc_state(rt, &mut st) }, GbcStatus::Ok);
    st
}

/// 200 000 rounds of a macro loop before the first move: on a whole
/// controller they would all run inside one `gbc_run_ahead` between two
/// ticks; split, the ticks go on (starved) while the VM computes.
const LOOP_THEN_MOVES: &str =
    "#1=0\nWHILE[#1LT200000]DO1\n#1=#1+1\nEND1\nG00 X40 Z-20\nG98 G01 Z-30 F300\nM30\n";

#[test]
fn the_halves_run_on_two_threads() {
    let (m, interp, rt) = split(LOOP_THEN_MOVES);
    let stop = AtomicBool::new(false);
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut pts = Vec::new();
    std::thread::scope(|s| {
        s.spawn(|| {
            while !stop.load(Ordering::Acquire) {
                assert_eq!(gbc_run_ahead(interp), GbcStatus::Ok);
                std::thread::yield_now();
            }
        });
        assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
        loop {
            let mut sp = blank();
            assert_eq!(unsafe { gbc_tick(rt, &mut sp) }, GbcStatus::Ok);
            pts.push(sp);
            match state(rt).state {
                GbcRunState::Ended => break,
                GbcRunState::Starved => std::thread::yield_now(),
                GbcRunState::Alarm => panic!("alarm at {sp:?}"),
                _ => {}
            }
            assert!(Instant::now() < deadline, "the split run did not end");
        }
        stop.store(true, Ordering::Release);
    });
    let end = pts.last().expect("periods");
    assert_eq!(
        (end.x, end.z, end.axis_x, end.axis_z),
        (40.0, -30.0, 40.0, -30.0)
    );
    assert_eq!((end.count_x, end.count_z), (40_000, -30_000));
    // The G01 at F300 ran at F300 (5 mm/s: 0.005 mm a 1 ms period), and
    // no period jumped: each X or Z step within the rapid rate, 0.2 mm.
    let top = pts.iter().filter(|p| p.line == 6).map(|p| p.feed);
    assert!((top.fold(0.0, f64::max) - 300.0).abs() < 1e-6);
    for w in pts.windows(2) {
        let (dx, dz) = (w[1].axis_x - w[0].axis_x, w[1].axis_z - w[0].axis_z);
        assert!(
            dx.abs() / 2.0 <= 0.2 + 1e-9 && dz.abs() <= 0.2 + 1e-9,
            "{w:?}"
        );
    }
    // The real-time half counts no blocks; the interpreter's run did.
    assert_eq!(state(rt).blocks, 0);
    free(m, interp, rt);
}

#[test]
fn each_call_goes_to_its_half() {
    let (m, interp, rt) = split("G00 X10\nM30\n");
    let mut sp = blank();
    assert_eq!(unsafe { gbc_tick(interp, &mut sp) }, GbcStatus::WrongKind);
    assert_eq!(gbc_cycle_start(interp), GbcStatus::WrongKind);
    assert_eq!(gbc_set_feed_override(interp, 50.0), GbcStatus::WrongKind);
    assert_eq!(gbc_set_machine_lock(interp, true), GbcStatus::WrongKind);
    assert_eq!(gbc_run_ahead(rt), GbcStatus::WrongKind);
    assert_eq!(gbc_set_variable(rt, 500, 1.0), GbcStatus::WrongKind);
    assert_eq!(gbc_set_block_skip(rt, 1, false), GbcStatus::WrongKind);
    // The measured cut is the interpreter's (the real-time half
    // publishes where it stands: idle at power-on); a second split.
    assert_eq!(
        gbc_measure_tool_offset(rt, 1, GBC_AXIS_X, 50.0),
        GbcStatus::WrongKind
    );
    assert_eq!(
        gbc_measure_tool_offset(interp, 1, GBC_AXIS_X, 50.0),
        GbcStatus::Ok
    );
    let mut l = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { gbc_tool_offset(interp, 1, &mut l) }, GbcStatus::Ok);
    // By hand: the slide at machine zero, measured 50: geometry −50.
    assert_eq!(l.x, -50.0);
    let mut again = 0;
    assert_eq!(
        unsafe { gbc_controller_split(interp, &mut again) },
        GbcStatus::WrongKind
    );
    assert_eq!(gbc_controller_free(rt), GbcStatus::WrongKind);
    // The interpreter's page calls and the real-time half's switches.
    assert_eq!(gbc_set_variable(interp, 500, 3.0), GbcStatus::Ok);
    let mut v = 0.0;
    assert_eq!(unsafe { gbc_variable(interp, 500, &mut v) }, GbcStatus::Ok);
    assert_eq!(v, 3.0);
    assert_eq!(gbc_set_block_skip(interp, 1, false), GbcStatus::Ok);
    assert_eq!(gbc_set_feed_override(rt, 50.0), GbcStatus::Ok);
    assert_eq!(gbc_set_machine_lock(rt, true), GbcStatus::Ok);
    free(m, interp, rt);
    // Without a program there is nothing to split.
    let (m, c) = controller_on("");
    let mut rt = 0;
    assert_eq!(
        unsafe { gbc_controller_split(c, &mut rt) },
        GbcStatus::NoProgram
    );
    periods::free(m, c);
}

/// Both halves from one thread, in turn.
fn period(interp: GbcController, rt: GbcController) -> GbcStateInfo {
    assert_eq!(gbc_run_ahead(interp), GbcStatus::Ok);
    assert_eq!(unsafe { gbc_tick(rt, &mut blank()) }, GbcStatus::Ok);
    state(rt)
}

#[test]
fn a_message_stop_and_an_alarm_across_the_halves() {
    let (m, interp, rt) = split("G00 X10\n#3006=7(HELLO)\nG00 X20\n#1=SQRT[-1]\nM30\n");
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    let mut st = period(interp, rt);
    for _ in 0..100_000 {
        if st.state != GbcRunState::Running && st.state != GbcRunState::Starved {
            break;
        }
        st = period(interp, rt);
    }
    assert_eq!(
        (st.state, st.stop, st.message),
        (GbcRunState::Stopped, GbcStopKind::Message, 7)
    );
    let mut index = u32::MAX;
    assert_eq!(unsafe { gbc_message_index(rt, &mut index) }, GbcStatus::Ok);
    assert_eq!(index, 0);
    let mut buf = [0 as c_char; 16];
    let mut len = 0;
    let got = unsafe { gbc_message_at(interp, index, buf.as_mut_ptr(), buf.len(), &mut len) };
    assert_eq!((got, len), (GbcStatus::Ok, 5));
    let text: Vec<u8> = buf[..5].iter().map(|&c| c as u8).collect();
    assert_eq!(text, b"HELLO");

    // The SQRT of a negative number is the VM's alarm: the real-time
    // half stands in it with its code; the interpreter has its text.
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    for _ in 0..100_000 {
        if period(interp, rt).state == GbcRunState::Alarm {
            break;
        }
    }
    let st = state(rt);
    assert_eq!(st.state, GbcRunState::Alarm);
    let mut a = no_alarm();
    assert_eq!(unsafe { gbc_alarm(interp, &mut a) }, GbcStatus::Ok);
    assert_eq!((a.code, a.line), (st.alarm_code, 4));
    assert!(a.message_len > 0);
    let mut engine = no_alarm();
    assert_eq!(unsafe { gbc_alarm(rt, &mut engine) }, GbcStatus::Ok);
    assert_eq!(engine.code, st.alarm_code);
    free(m, interp, rt);
}

/// The interpreter half freed first: the real-time half runs what was
/// queued, then stands starved, and is freed on its own.
#[test]
fn either_half_may_be_freed_first() {
    let (m, interp, rt) = split("G00 X10\nG00 X20\nM30\n");
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    period(interp, rt);
    assert_eq!(gbc_controller_free(interp), GbcStatus::Ok);
    let mut last = blank();
    for _ in 0..20_000 {
        assert_eq!(unsafe { gbc_tick(rt, &mut last) }, GbcStatus::Ok);
    }
    assert_ne!(state(rt).state, GbcRunState::Alarm);
    assert!(last.x > 0.0, "the queued moves ran: {last:?}");
    assert_eq!(gbc_realtime_free(rt), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

/// A program restart on a split controller: asked on the interpreter
/// half, run by the real-time half's reset and the run-ahead after it.
/// At line 4 the approach goes from machine zero to the end of line 3,
/// X60 Z-10, and lines 1–3 never move the axes; at line 4's third pass,
/// which never comes, the restart is refused and the program runs from
/// its start.
#[test]
fn a_restart_goes_with_the_real_time_half_s_reset() {
    const SRC: &str = "G00 X50 Z2\nG98 G01 Z-10 F500\nG00 X60\nG00 X30 Z2\nG01 Z-20\nM30\n";
    for (pass, taken) in [(1, true), (3, false)] {
        let (m, interp, rt) = split(SRC);
        assert_eq!(gbc_restart_result(interp), GbcStatus::RestartNotFound);
        assert_eq!(gbc_restart_from(interp, 4, pass), GbcStatus::Ok);
        assert_eq!(gbc_restart_result(interp), GbcStatus::RestartPending);
        assert_eq!(gbc_restart_result(rt), GbcStatus::WrongKind);
        assert_eq!(gbc_reset(rt), GbcStatus::Ok);
        let mut result = GbcStatus::RestartPending;
        for _ in 0..10_000 {
            period(interp, rt);
            result = gbc_restart_result(interp);
            if result != GbcStatus::RestartPending {
                break;
            }
        }
        let (mut x, mut z) = (0.0, 0.0);
        assert_eq!(
            unsafe { gbc_restart_destination(interp, &mut x, &mut z) },
            GbcStatus::Ok
        );
        if taken {
            assert_eq!(result, GbcStatus::Ok);
            assert_eq!((x, z), (60.0, -10.0));
        } else {
            assert_eq!(result, GbcStatus::RestartNotFound);
            assert!(x.is_nan() && z.is_nan());
        }
        assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
        let mut lines = Vec::new();
        let mut last = blank();
        for _ in 0..200_000 {
            assert_eq!(gbc_run_ahead(interp), GbcStatus::Ok);
            assert_eq!(unsafe { gbc_tick(rt, &mut last) }, GbcStatus::Ok);
            if last.motion != GbcMotion::None {
                lines.push(last.line);
            }
            if state(rt).state == GbcRunState::Ended {
                break;
            }
        }
        assert_eq!(state(rt).state, GbcRunState::Ended);
        assert_eq!((last.x, last.z), (30.0, -20.0));
        assert_eq!(lines.iter().any(|&l| l < 4), !taken, "{pass}");
        free(m, interp, rt);
    }
}

/// Runs both halves in turn until the real-time half is in `until`.
fn until(interp: GbcController, rt: GbcController, until: GbcRunState) -> GbcSetPoint {
    for _ in 0..100_000 {
        assert_eq!(gbc_run_ahead(interp), GbcStatus::Ok);
        let mut sp = blank();
        assert_eq!(unsafe { gbc_tick(rt, &mut sp) }, GbcStatus::Ok);
        if state(rt).state == until {
            return sp;
        }
    }
    panic!("never {until:?}");
}

/// Another program selected on the interpreter half, as text, while
/// the first has ended: it takes the first's place at the real-time
/// half's reset, starts where the axes stand (X40 Z2, then W−12), and
/// the real-time half's alarm names its file; a restart asked for the
/// first program is dropped.
#[test]
fn another_program_takes_the_place_at_the_reset() {
    let (m, interp, rt) = split("G00 X40 Z2\nM30\n");
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    let end = until(interp, rt, GbcRunState::Ended);
    assert_eq!((end.x, end.z), (40.0, 2.0));
    assert_eq!(gbc_restart_from(interp, 1, 1), GbcStatus::Ok);
    let src = "G98 G01 W-12 F300\n#3000=12 (AT THE END)\nM30\n";
    let status = unsafe {
        gbc_controller_select_source(
            interp,
            c"second.nc".as_ptr(),
            src.as_ptr().cast(),
            src.len(),
        )
    };
    assert_eq!(status, GbcStatus::Ok);
    assert_eq!(gbc_restart_result(interp), GbcStatus::RestartNotFound);
    // The real-time half does not select.
    let status = unsafe {
        gbc_controller_select_source(rt, c"x.nc".as_ptr(), src.as_ptr().cast(), src.len())
    };
    assert_eq!(status, GbcStatus::WrongKind);
    assert_eq!(gbc_reset(rt), GbcStatus::Ok);
    until(interp, rt, GbcRunState::Idle);
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    let end = until(interp, rt, GbcRunState::Alarm);
    assert_eq!((end.x, end.z), (40.0, -10.0));
    let mut a = no_alarm();
    assert_eq!(unsafe { gbc_alarm(rt, &mut a) }, GbcStatus::Ok);
    let file = String::from_utf8_lossy(&a.file[..a.file_len]).into_owned();
    assert_eq!((a.code, file.as_str(), a.line), (3012, "second.nc", 2));
    free(m, interp, rt);
}
