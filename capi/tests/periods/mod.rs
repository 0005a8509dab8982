//! What the tests that drive a controller period by period through the C
//! functions share: a zeroed set point and alarm, the state, one period,
//! freeing, a controller on a machine file, a program loaded into it,
//! the last error text.
#![allow(dead_code)]

use gbc::*;

pub fn blank() -> GbcSetPoint {
    GbcSetPoint {
        time_s: 0.0,
        x: 0.0,
        z: 0.0,
        axis_x: 0.0,
        axis_z: 0.0,
        count_x: 0,
        count_z: 0,
        count_c: 0,
        c: 0.0,
        has_c: false,
        spindle_rpm: 0.0,
        spindle_turns: 0.0,
        feed: 0.0,
        line: 0,
        file: 0,
        tool: 0,
        motion: GbcMotion::None,
    }
}

/// An alarm record with nothing in it, for `gbc_alarm` to fill.
pub fn no_alarm() -> GbcAlarm {
    GbcAlarm {
        code: 0,
        line: 0,
        column: 0,
        message: [0; GBC_TEXT_CAPACITY],
        file: [0; GBC_TEXT_CAPACITY],
        message_len: 0,
        file_len: 0,
    }
}

/// `src` compiled for the reference machine and loaded into `c`.
pub fn load(c: GbcController, src: &str) {
    let opts = compiler::Options::default();
    let prog = compiler::compile("p.nc", src.as_bytes(), &opts);
    let prog = prog.module.expect("compiles").to_bytes();
    assert_eq!(
        unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
}

pub fn state_info(c: GbcController) -> GbcStateInfo {
    let mut st = GbcStateInfo {
        state: GbcRunState::Alarm,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    };
    assert_eq!(unsafe { gbc_state(c, &mut st) }, GbcStatus::Ok);
    st
}

pub fn state(c: GbcController) -> GbcRunState {
    state_info(c).state
}

/// One period: run-ahead, tick, the state after it.
pub fn period(c: GbcController) -> (GbcSetPoint, GbcRunState) {
    let mut sp = blank();
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
    (sp, state(c))
}

/// Frees a controller and its machine.
pub fn free(m: GbcMachine, c: GbcController) {
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

/// A controller with no program on the machine of TOML `text`.
pub fn controller_on(text: &str) -> (GbcMachine, GbcController) {
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(
            gbc_machine_from_toml(text.as_ptr().cast(), text.len(), &mut m),
            GbcStatus::Ok
        );
        assert_eq!(
            gbc_controller_new(m, std::ptr::null(), &mut c),
            GbcStatus::Ok
        );
    }
    (m, c)
}

/// `gbc_last_error`'s whole text.
pub fn last_error() -> String {
    let mut len = 0;
    assert_eq!(
        unsafe { gbc_last_error(std::ptr::null_mut(), 0, &mut len) },
        GbcStatus::Ok
    );
    let mut buf = vec![0 as core::ffi::c_char; len + 1];
    assert_eq!(
        unsafe { gbc_last_error(buf.as_mut_ptr(), buf.len(), std::ptr::null_mut()) },
        GbcStatus::Ok
    );
    let text = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    text.to_string_lossy().into_owned()
}
