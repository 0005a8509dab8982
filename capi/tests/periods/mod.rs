//! What the tests that drive a controller period by period through the C
//! functions share: a zeroed set point, the state, one period, freeing.
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
