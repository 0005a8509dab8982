//! W118 at run time through the C interface: a thread whose S comes from
//! a variable (gbcc cannot know it) starts 1 mm before its block's end
//! and stops 1 mm after: the motion warns of both, once each; the text
//! is gbcc's wording. On a split controller the real-time half takes
//! them.

mod periods;

use gbc::*;
use periods::{blank, controller_on, free, load, period};
use std::ffi::c_char;

/// Lead 3 at 1500 rpm is v = 75 mm/s. The reference machine's Z has
/// 2000 mm/s² and keeps back 3 × 1000/60 = 50 of them while it follows
/// the spindle: it needs 75² / (2 × 1950) = 1.442 mm to reach thread
/// speed and 75² / (2 × 2000) = 1.406 mm to stop; the G32 from Z1 to Z0
/// gives 1 mm.
const SHORT_THREAD: &str = "#1=1500\nG97 S#1 M03\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM30\n";

fn none() -> GbcRoomWarning {
    GbcRoomWarning {
        code: 7,
        line: 7,
        column: 7,
        file: 7,
        exit: true,
        long_z: false,
        room_mm: 7.0,
        need_mm: 7.0,
        rpm: 7.0,
    }
}

/// Takes the warnings waiting on `c`.
fn take_all(c: GbcController, into: &mut Vec<GbcRoomWarning>) {
    loop {
        let mut w = none();
        assert_eq!(unsafe { gbc_take_room_warning(c, &mut w) }, GbcStatus::Ok);
        if w.code == 0 {
            return;
        }
        into.push(w);
    }
}

fn text(w: &GbcRoomWarning) -> String {
    let mut buf = [0 as c_char; 256];
    let mut len = 0;
    let status = unsafe { gbc_room_warning_text(w, buf.as_mut_ptr(), buf.len(), &mut len) };
    assert_eq!(status, GbcStatus::Ok);
    let s = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    let s = s.to_string_lossy().into_owned();
    assert_eq!(s.len(), len);
    s
}

/// The two warnings of [`SHORT_THREAD`], checked against the figures
/// in its comment.
fn check(got: &[GbcRoomWarning]) {
    assert_eq!(got.len(), 2, "{got:?}");
    let (entry, exit) = (&got[0], &got[1]);
    assert!(!entry.exit && exit.exit);
    for w in got {
        assert_eq!(w.code, GBC_ROOM_WARNING_CODE);
        assert_eq!((w.file, w.line, w.column), (0, 4, 1));
        assert!(w.long_z);
        assert_eq!((w.room_mm, w.rpm), (1.0, 1500.0));
    }
    assert!((entry.need_mm - 5625.0 / 3900.0).abs() < 1e-9, "{entry:?}");
    assert!((exit.need_mm - 5625.0 / 4000.0).abs() < 1e-9, "{exit:?}");
    assert_eq!(
        text(entry),
        "thread too short to reach its lead: at 1500 rpm Z needs 1.442 mm to reach thread speed, this block gives 1.000 mm"
    );
    assert_eq!(
        text(exit),
        "no room to stop at the thread's end: at 1500 rpm Z needs 1.406 mm to stop from thread speed, this block gives 1.000 mm"
    );
}

#[test]
fn a_whole_controller_warns_of_a_thread_without_room_once() {
    let (m, c) = controller_on("");
    let mut got = Vec::new();
    // None before a program is loaded.
    take_all(c, &mut got);
    load(c, SHORT_THREAD);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..200_000 {
        let (_, state) = period(c);
        take_all(c, &mut got);
        assert_ne!(state, GbcRunState::Alarm);
        if state == GbcRunState::Ended {
            break;
        }
    }
    check(&got);
    free(m, c);
}

#[test]
fn a_thread_with_room_is_not_warned() {
    let (m, c) = controller_on("");
    load(c, &SHORT_THREAD.replace("Z1\n", "Z3\n"));
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut got = Vec::new();
    while period(c).1 != GbcRunState::Ended {
        take_all(c, &mut got);
    }
    assert!(got.is_empty(), "{got:?}");
    free(m, c);
}

#[test]
fn the_real_time_half_takes_them_and_the_interpreter_half_refuses() {
    let (m, c) = controller_on("");
    load(c, SHORT_THREAD);
    let mut rt = 0;
    assert_eq!(unsafe { gbc_controller_split(c, &mut rt) }, GbcStatus::Ok);
    let mut w = none();
    assert_eq!(
        unsafe { gbc_take_room_warning(c, &mut w) },
        GbcStatus::WrongKind
    );
    assert_eq!(gbc_cycle_start(rt), GbcStatus::Ok);
    let mut got = Vec::new();
    for _ in 0..200_000 {
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        let mut sp = blank();
        assert_eq!(unsafe { gbc_tick(rt, &mut sp) }, GbcStatus::Ok);
        take_all(rt, &mut got);
        let st = periods::state_info(rt).state;
        assert_ne!(st, GbcRunState::Alarm);
        if st == GbcRunState::Ended {
            break;
        }
    }
    check(&got);
    assert_eq!(gbc_realtime_free(rt), GbcStatus::Ok);
    free(m, c);
}

#[test]
fn the_text_needs_a_warning() {
    let mut w = none();
    w.code = 0;
    let mut len = 0;
    let null = std::ptr::null_mut();
    let status = unsafe { gbc_room_warning_text(&w, null, 0, &mut len) };
    assert_eq!(status, GbcStatus::InvalidArgument);
    let status = unsafe { gbc_room_warning_text(std::ptr::null(), null, 0, &mut len) };
    assert_eq!(status, GbcStatus::NullPointer);
    // The length alone: cap 0.
    w.code = GBC_ROOM_WARNING_CODE;
    let status = unsafe { gbc_room_warning_text(&w, null, 0, &mut len) };
    assert_eq!(status, GbcStatus::Ok);
    assert_eq!(len, text(&w).len());
    let (m, c) = controller_on("");
    let status = unsafe { gbc_take_room_warning(c, std::ptr::null_mut()) };
    assert_eq!(status, GbcStatus::NullPointer);
    free(m, c);
}
