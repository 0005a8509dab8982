//! Every entry point, called with a null handle, a freed one, a forged
//! one and one of the wrong kind, returns the documented status and
//! touches nothing; null out-pointers and misuse (no program, a second
//! load, a tick in an alarm) are reported too.

mod periods;

use gbc::*;
use periods::{blank, no_alarm};
use std::ptr::null_mut;

fn reference() -> GbcMachine {
    let mut m = 0;
    assert_eq!(unsafe { gbc_machine_reference(&mut m) }, GbcStatus::Ok);
    m
}

fn controller(m: GbcMachine) -> GbcController {
    let mut c = 0;
    assert_eq!(
        unsafe { gbc_controller_new(m, std::ptr::null(), &mut c) },
        GbcStatus::Ok
    );
    c
}

fn module(src: &str) -> Vec<u8> {
    let out = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
    out.module.expect("compiles").to_bytes()
}

fn state_info() -> GbcStateInfo {
    GbcStateInfo {
        state: GbcRunState::Ended,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    }
}

fn lengths() -> GbcOffsetLengths {
    GbcOffsetLengths {
        x: 0.0,
        z: 0.0,
        wear_x: -0.01,
        wear_z: 0.0,
    }
}

/// An entry point called on a controller handle.
type Call = Box<dyn Fn(GbcController) -> GbcStatus>;

/// Every entry point that takes a controller, with valid other arguments.
fn controller_calls() -> Vec<(&'static str, Call)> {
    let prog = module("O1\nM30\n");
    vec![
        (
            "gbc_controller_load",
            Box::new(move |h| unsafe { gbc_controller_load(h, prog.as_ptr(), prog.len()) }),
        ),
        ("gbc_run_ahead", Box::new(|h| gbc_run_ahead(h))),
        (
            "gbc_tick",
            Box::new(|h| unsafe { gbc_tick(h, &mut blank()) }),
        ),
        (
            "gbc_state",
            Box::new(|h| {
                let mut s = std::mem::MaybeUninit::<GbcStateInfo>::uninit();
                unsafe { gbc_state(h, s.as_mut_ptr()) }
            }),
        ),
        (
            "gbc_alarm",
            Box::new(|h| unsafe { gbc_alarm(h, &mut no_alarm()) }),
        ),
        (
            "gbc_message",
            Box::new(|h| {
                let mut buf = [0 as core::ffi::c_char; 64];
                unsafe { gbc_message(h, buf.as_mut_ptr(), buf.len(), null_mut()) }
            }),
        ),
        (
            "gbc_file_name",
            Box::new(|h| {
                let mut buf = [0 as core::ffi::c_char; 64];
                unsafe { gbc_file_name(h, 0, buf.as_mut_ptr(), buf.len(), null_mut()) }
            }),
        ),
        (
            "gbc_set_feed_override",
            Box::new(|h| gbc_set_feed_override(h, 50.0)),
        ),
        (
            "gbc_set_rapid_override",
            Box::new(|h| gbc_set_rapid_override(h, 25.0)),
        ),
        (
            "gbc_set_spindle_override",
            Box::new(|h| gbc_set_spindle_override(h, 120.0)),
        ),
        ("gbc_feed_hold", Box::new(|h| gbc_feed_hold(h))),
        ("gbc_cycle_start", Box::new(|h| gbc_cycle_start(h))),
        ("gbc_reset", Box::new(|h| gbc_reset(h))),
        (
            "gbc_set_single_block",
            Box::new(|h| gbc_set_single_block(h, true)),
        ),
        (
            "gbc_set_optional_stop",
            Box::new(|h| gbc_set_optional_stop(h, false)),
        ),
        ("gbc_set_dry_run", Box::new(|h| gbc_set_dry_run(h, true))),
        (
            "gbc_set_machine_lock",
            Box::new(|h| gbc_set_machine_lock(h, true)),
        ),
        ("gbc_set_aux_lock", Box::new(|h| gbc_set_aux_lock(h, true))),
        (
            "gbc_set_block_skip",
            Box::new(|h| gbc_set_block_skip(h, 1, false)),
        ),
        (
            "gbc_set_skip_input",
            Box::new(|h| gbc_set_skip_input(h, true)),
        ),
        (
            "gbc_spindle_feedback",
            Box::new(|h| gbc_spindle_feedback(h, 1.0, 600.0)),
        ),
        (
            "gbc_spindle_simulated",
            Box::new(|h| gbc_spindle_simulated(h)),
        ),
        ("gbc_restart_from", Box::new(|h| gbc_restart_from(h, 1, 1))),
        ("gbc_restart_result", Box::new(|h| gbc_restart_result(h))),
        (
            "gbc_restart_from_seq",
            Box::new(|h| gbc_restart_from_seq(h, 1, 1)),
        ),
        (
            "gbc_tool_offset",
            Box::new(|h| unsafe { gbc_tool_offset(h, 1, &mut lengths()) }),
        ),
        (
            "gbc_set_tool_offset",
            Box::new(|h| unsafe { gbc_set_tool_offset(h, 1, &lengths()) }),
        ),
        (
            "gbc_work_offset",
            Box::new(|h| {
                let (mut x, mut z) = (0.0, 0.0);
                unsafe { gbc_work_offset(h, GBC_WORK_OFFSET_G54, &mut x, &mut z) }
            }),
        ),
        (
            "gbc_set_work_offset",
            Box::new(|h| gbc_set_work_offset(h, GBC_WORK_OFFSET_G54, 0.0, -100.0)),
        ),
        (
            "gbc_restart_m_codes",
            Box::new(|h| {
                let mut len = 0;
                unsafe { gbc_restart_m_codes(h, std::ptr::null_mut(), 0, &mut len) }
            }),
        ),
        (
            "gbc_controller_select",
            Box::new(|h| unsafe { gbc_controller_select(h, [0u8; 4].as_ptr(), 4) }),
        ),
        (
            "gbc_active_codes",
            Box::new(|h| {
                let mut a = GbcActiveCodes {
                    g: [0; GBC_ACTIVE_GROUPS],
                    f: 0.0,
                    s: 0.0,
                    t: 0,
                };
                unsafe { gbc_active_codes(h, &mut a) }
            }),
        ),
        (
            "gbc_restart_destination",
            Box::new(|h| {
                let (mut x, mut z) = (0.0, 0.0);
                unsafe { gbc_restart_destination(h, &mut x, &mut z) }
            }),
        ),
        (
            "gbc_variable",
            Box::new(|h| {
                let mut v = 0.0;
                unsafe { gbc_variable(h, 500, &mut v) }
            }),
        ),
        (
            "gbc_set_variable",
            Box::new(|h| gbc_set_variable(h, 500, 1.0)),
        ),
        (
            "gbc_measure_tool_offset",
            Box::new(|h| gbc_measure_tool_offset(h, 1, GBC_AXIS_X, 50.0)),
        ),
        (
            "gbc_distance_to_go",
            Box::new(|h| {
                let (mut x, mut z) = (0.0, 0.0);
                unsafe { gbc_distance_to_go(h, &mut x, &mut z) }
            }),
        ),
        (
            "gbc_parts",
            Box::new(|h| {
                let mut p = GbcParts {
                    machined: 0.0,
                    required: 0.0,
                };
                unsafe { gbc_parts(h, &mut p) }
            }),
        ),
        (
            "gbc_set_parts",
            Box::new(|h| {
                let p = GbcParts {
                    machined: 1.0,
                    required: 2.0,
                };
                gbc_set_parts(h, p)
            }),
        ),
        (
            "gbc_parts_reached",
            Box::new(|h| unsafe { gbc_parts_reached(h, &mut false) }),
        ),
        (
            "gbc_tool_life",
            Box::new(|h| {
                let mut t = std::mem::MaybeUninit::<GbcToolLife>::uninit();
                unsafe { gbc_tool_life(h, 1, 0, t.as_mut_ptr()) }
            }),
        ),
        (
            "gbc_set_tool_life_used",
            Box::new(|h| gbc_set_tool_life_used(h, 1, 0, 1.0)),
        ),
        (
            "gbc_renew_tool_life",
            Box::new(|h| gbc_renew_tool_life(h, 1)),
        ),
        (
            "gbc_mdi",
            Box::new(|h| unsafe { gbc_mdi(h, c"M03 S500".as_ptr(), 8) }),
        ),
        (
            "gbc_in_mdi",
            Box::new(|h| unsafe { gbc_in_mdi(h, &mut false) }),
        ),
        (
            "gbc_controller_load_source",
            Box::new(|h| unsafe {
                gbc_controller_load_source(h, c"t.nc".as_ptr(), c"M30".as_ptr(), 3)
            }),
        ),
        (
            "gbc_controller_select_source",
            Box::new(|h| unsafe {
                gbc_controller_select_source(h, c"t.nc".as_ptr(), c"M30".as_ptr(), 3)
            }),
        ),
        (
            "gbc_controller_split",
            Box::new(|h| {
                let mut rt = 0;
                unsafe { gbc_controller_split(h, &mut rt) }
            }),
        ),
        (
            "gbc_message_index",
            Box::new(|h| {
                let mut i = 0;
                unsafe { gbc_message_index(h, &mut i) }
            }),
        ),
        (
            "gbc_message_at",
            Box::new(|h| {
                let mut buf = [0 as core::ffi::c_char; 64];
                unsafe { gbc_message_at(h, 0, buf.as_mut_ptr(), buf.len(), null_mut()) }
            }),
        ),
        (
            "gbc_take_room_warning",
            Box::new(|h| unsafe { gbc_take_room_warning(h, &mut std::mem::zeroed()) }),
        ),
        ("gbc_controller_free", Box::new(|h| gbc_controller_free(h))),
    ]
}

#[test]
fn bad_handles_are_reported_by_every_entry_point() {
    let m = reference();
    let dead = controller(m);
    assert_eq!(gbc_controller_free(dead), GbcStatus::Ok);
    let live = controller(m);
    // Made-up numbers: slot 0, a slot past the table, a live slot with
    // another generation or another kind in the handle, the live handle
    // with bits set that the library never sets (24–31).
    let forged = [
        1,
        0xffff,
        live ^ (1 << 33),
        live ^ (3 << 16),
        live | (1 << 24),
        live | (0x5a << 24),
        live | (0xff << 24),
        u64::MAX,
    ];
    for (name, call) in controller_calls() {
        assert_eq!(call(0), GbcStatus::InvalidHandle, "{name}(0)");
        assert_eq!(call(dead), GbcStatus::InvalidHandle, "{name}(freed)");
        for f in forged {
            assert_eq!(call(f), GbcStatus::InvalidHandle, "{name}({f:#x})");
        }
        // A live machine where a controller belongs.
        assert_eq!(call(m), GbcStatus::WrongKind, "{name}(machine)");
    }
    // The machine side: freed, null, and a controller where a machine
    // belongs.
    let mut out = 0;
    assert_eq!(
        unsafe { gbc_controller_new(0, std::ptr::null(), &mut out) },
        GbcStatus::InvalidHandle
    );
    assert_eq!(
        unsafe { gbc_controller_new(live, std::ptr::null(), &mut out) },
        GbcStatus::WrongKind
    );
    assert_eq!(gbc_machine_free(live), GbcStatus::WrongKind);
    assert_eq!(gbc_realtime_free(live), GbcStatus::WrongKind);
    assert_eq!(gbc_realtime_free(0), GbcStatus::InvalidHandle);
    assert_eq!(gbc_machine_free(0), GbcStatus::InvalidHandle);
    assert_eq!(out, 0, "nothing written on failure");
    // Nothing was freed by the wrong-kind calls.
    assert_eq!(gbc_controller_free(live), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::InvalidHandle);
    assert_eq!(
        unsafe { gbc_controller_new(m, std::ptr::null(), &mut out) },
        GbcStatus::InvalidHandle
    );
}

#[test]
fn null_pointers_and_bad_arguments_are_refused() {
    let m = reference();
    let c = controller(m);
    unsafe {
        assert_eq!(gbc_machine_reference(null_mut()), GbcStatus::NullPointer);
        assert_eq!(
            gbc_machine_from_toml(std::ptr::null(), 0, &mut 0),
            GbcStatus::NullPointer
        );
        let text = b"[machine]\ninterpolation_period_ms = -1\n";
        let mut out = 0;
        assert_eq!(
            gbc_machine_from_toml(text.as_ptr().cast(), text.len(), &mut out),
            GbcStatus::InvalidMachine
        );
        let mut msg = [0 as core::ffi::c_char; 256];
        let mut len = 0;
        assert_eq!(
            gbc_last_error(msg.as_mut_ptr(), msg.len(), &mut len),
            GbcStatus::Ok
        );
        let msg = std::ffi::CStr::from_ptr(msg.as_ptr()).to_string_lossy();
        assert!(msg.contains("interpolation_period_ms"), "{msg}");
        assert_eq!(len, msg.len());
        assert_eq!(
            gbc_last_error(null_mut(), 10, null_mut()),
            GbcStatus::NullPointer
        );
        let bad = [0xffu8, 0xfe];
        assert_eq!(
            gbc_machine_from_toml(bad.as_ptr().cast(), 2, &mut out),
            GbcStatus::InvalidArgument
        );
        assert_eq!(
            gbc_controller_new(m, std::ptr::null(), null_mut()),
            GbcStatus::NullPointer
        );
        assert_eq!(
            gbc_controller_load(c, std::ptr::null(), 10),
            GbcStatus::NullPointer
        );
        let junk = b"not a module";
        assert_eq!(
            gbc_controller_load(c, junk.as_ptr(), junk.len()),
            GbcStatus::InvalidModule
        );
        // Before a program: the switches are kept, the motion calls refused.
        assert_eq!(gbc_set_feed_override(c, 80.0), GbcStatus::Ok);
        for set in [
            gbc_set_feed_override,
            gbc_set_rapid_override,
            gbc_set_spindle_override,
        ] {
            assert_eq!(set(c, f64::NAN), GbcStatus::InvalidArgument);
            // Out of range, infinity too: clamped (host.rs checks to what).
            for pct in [f64::INFINITY, f64::NEG_INFINITY, 1e300, -5.0] {
                assert_eq!(set(c, pct), GbcStatus::Ok, "{pct}");
            }
        }
        assert_eq!(
            gbc_spindle_feedback(c, 0.0, f64::INFINITY),
            GbcStatus::InvalidArgument
        );
        assert_eq!(
            gbc_spindle_feedback(c, f64::NAN, 1.0),
            GbcStatus::InvalidArgument
        );
        assert_eq!(gbc_tick(c, &mut blank()), GbcStatus::NoProgram);
        assert_eq!(gbc_run_ahead(c), GbcStatus::NoProgram);
        assert_eq!(gbc_cycle_start(c), GbcStatus::NoProgram);
        let mut st = state_info();
        st.blocks = 99;
        assert_eq!(gbc_state(c, &mut st), GbcStatus::Ok);
        assert_eq!((st.state, st.blocks), (GbcRunState::Idle, 0));
        // Block skip: switches 1–9 only.
        assert_eq!(gbc_set_block_skip(c, 9, false), GbcStatus::Ok);
        for n in [0, 10, 255] {
            assert_eq!(gbc_set_block_skip(c, n, true), GbcStatus::InvalidArgument);
        }
        // A bad argument with a bad handle: the handle is reported.
        assert_eq!(gbc_set_feed_override(0, f64::NAN), GbcStatus::InvalidHandle);
        assert_eq!(gbc_set_block_skip(0, 0, true), GbcStatus::InvalidHandle);
        assert_eq!(
            gbc_set_work_offset(0, 7, f64::NAN, 0.0),
            GbcStatus::InvalidHandle
        );
        assert_eq!(
            gbc_set_tool_offset(0, 0, std::ptr::null()),
            GbcStatus::InvalidHandle
        );
        // The offset page before a program: kept for it (host.rs); null
        // pointers and bad arguments refused.
        assert_eq!(
            gbc_set_tool_offset(c, 1, std::ptr::null()),
            GbcStatus::NullPointer
        );
        assert_eq!(gbc_tool_offset(c, 1, null_mut()), GbcStatus::NullPointer);
        assert_eq!(
            gbc_work_offset(c, GBC_WORK_OFFSET_G54, null_mut(), null_mut()),
            GbcStatus::NullPointer
        );
        assert_eq!(
            gbc_set_tool_offset(c, 33, &lengths()),
            GbcStatus::InvalidArgument
        );
        assert_eq!(
            gbc_set_work_offset(c, 7, 0.0, 0.0),
            GbcStatus::InvalidArgument
        );

        let prog = module("O1\nG00 W-1\nM30\n");
        assert_eq!(
            gbc_controller_load(c, prog.as_ptr(), prog.len()),
            GbcStatus::Ok
        );
        assert_eq!(
            gbc_controller_load(c, prog.as_ptr(), prog.len()),
            GbcStatus::AlreadyLoaded
        );
        assert_eq!(gbc_tick(c, null_mut()), GbcStatus::NullPointer);
        assert_eq!(gbc_state(c, null_mut()), GbcStatus::NullPointer);
        assert_eq!(gbc_alarm(c, null_mut()), GbcStatus::NullPointer);
        assert_eq!(
            gbc_message(c, null_mut(), 5, null_mut()),
            GbcStatus::NullPointer
        );
        assert_eq!(
            gbc_file_name(c, 0, null_mut(), 5, null_mut()),
            GbcStatus::NullPointer
        );
        // cap 0 without len has nothing to give.
        let mut buf = [0 as core::ffi::c_char; 4];
        assert_eq!(
            gbc_file_name(c, 0, buf.as_mut_ptr(), 0, null_mut()),
            GbcStatus::NullPointer
        );
    }
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

#[test]
fn a_tick_in_an_alarm_is_refused_until_reset() {
    let m = reference();
    let c = controller(m);
    // #3000 = 7 raises alarm 3007 with its text on line 3.
    let prog = module("O1\nG00 W-1\n#3000 = 7 (TOOL BROKEN)\nM30\n");
    let mut sp = blank();
    let mut st = state_info();
    unsafe {
        assert_eq!(
            gbc_controller_load(c, prog.as_ptr(), prog.len()),
            GbcStatus::Ok
        );
        assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
        let mut ticks = 0;
        loop {
            assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
            assert_eq!(gbc_tick(c, &mut sp), GbcStatus::Ok);
            assert_eq!(gbc_state(c, &mut st), GbcStatus::Ok);
            ticks += 1;
            if st.state == GbcRunState::Alarm || ticks > 100_000 {
                break;
            }
        }
        assert_eq!((st.state, st.alarm_code), (GbcRunState::Alarm, 3007));
        let mut a = no_alarm();
        assert_eq!(gbc_alarm(c, &mut a), GbcStatus::Ok);
        assert_eq!((a.code, a.line), (3007, 3));
        let text = std::ffi::CStr::from_bytes_until_nul(&a.message).unwrap();
        assert_eq!(text.to_str().unwrap(), "TOOL BROKEN");
        let file = std::ffi::CStr::from_bytes_until_nul(&a.file).unwrap();
        assert_eq!(file.to_str().unwrap(), "t.nc");
        // The misuse: ticking on in the alarm.
        let before = sp;
        assert_eq!(gbc_tick(c, &mut sp), GbcStatus::Alarm);
        assert_eq!(sp, before, "nothing written");
        // Reset: the ticks run the reset and the alarm clears.
        assert_eq!(gbc_reset(c), GbcStatus::Ok);
        for _ in 0..10 {
            assert_eq!(gbc_tick(c, &mut sp), GbcStatus::Ok);
        }
        assert_eq!(gbc_state(c, &mut st), GbcStatus::Ok);
        assert_eq!(st.state, GbcRunState::Idle);
        assert_eq!(gbc_alarm(c, &mut a), GbcStatus::Ok);
        assert_eq!(a.code, 0);
    }
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}
