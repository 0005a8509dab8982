//! The host's side through the C interface: PLC functions with a slow
//! FIN, #500–#999 loaded and stored through callbacks (and kept over a
//! reset), the skip signal of G31.

mod periods;

use core::ffi::c_void;
use gbc::*;
use periods::{blank, controller_on, free, last_error, no_alarm};

#[derive(Default)]
struct Host {
    requests: Vec<GbcPlcFunction>,
    /// Periods left until the coolant valve reports on.
    coolant_busy: u32,
    stores: Vec<[f64; GBC_PERSISTENT_COUNT]>,
    start: Vec<(usize, f64)>,
}

unsafe extern "C" fn request(user: *mut c_void, f: *const GbcPlcFunction) {
    let h = unsafe { &mut *user.cast::<Host>() };
    let f = unsafe { *f };
    if f.kind == GbcPlcKind::M && f.code == 8 {
        h.coolant_busy = 30;
    }
    h.requests.push(f);
}

unsafe extern "C" fn done(user: *mut c_void, _: *const GbcPlcFunction) -> bool {
    let h = unsafe { &mut *user.cast::<Host>() };
    h.coolant_busy = h.coolant_busy.saturating_sub(1);
    h.coolant_busy == 0
}

unsafe extern "C" fn load(user: *mut c_void, vars: *mut f64) -> i32 {
    let h = unsafe { &mut *user.cast::<Host>() };
    let vars = unsafe { std::slice::from_raw_parts_mut(vars, GBC_PERSISTENT_COUNT) };
    assert!(vars.iter().all(|v| v.is_nan()), "handed over vacant");
    for &(i, v) in &h.start {
        vars[i] = v;
    }
    0
}

unsafe extern "C" fn store(user: *mut c_void, vars: *const f64) -> i32 {
    let h = unsafe { &mut *user.cast::<Host>() };
    let vars = unsafe { std::slice::from_raw_parts(vars, GBC_PERSISTENT_COUNT) };
    h.stores.push(vars.try_into().unwrap());
    0
}

fn module(src: &str) -> Vec<u8> {
    let out = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
    out.module.expect("compiles").to_bytes()
}

/// The host lives on the heap and is reached through its raw pointer
/// only, as the library reaches it.
fn new_host(h: Host) -> *mut Host {
    Box::into_raw(Box::new(h))
}

fn new_controller(host: *mut Host, prog: &[u8]) -> (GbcMachine, GbcController) {
    let cb = GbcHost {
        user: host.cast(),
        plc_request: Some(request),
        plc_done: Some(done),
        vars_load: Some(load),
        vars_store: Some(store),
    };
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(gbc_machine_reference(&mut m), GbcStatus::Ok);
        assert_eq!(gbc_controller_new(m, &cb, &mut c), GbcStatus::Ok);
        assert_eq!(
            gbc_controller_load(c, prog.as_ptr(), prog.len()),
            GbcStatus::Ok
        );
    }
    (m, c)
}

/// Ticks to the end (pressing cycle start at stops); calls `each` after
/// every period.
fn run(c: GbcController, mut each: impl FnMut(&GbcSetPoint)) -> Vec<GbcSetPoint> {
    let mut pts = Vec::new();
    let mut st = GbcStateInfo {
        state: GbcRunState::Idle,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    };
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..200_000 {
        let mut sp = blank();
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        each(&sp);
        pts.push(sp);
        assert_eq!(unsafe { gbc_state(c, &mut st) }, GbcStatus::Ok);
        match st.state {
            GbcRunState::Ended => return pts,
            GbcRunState::Stopped => assert_eq!(gbc_cycle_start(c), GbcStatus::Ok),
            GbcRunState::Alarm => panic!("alarm {}", st.alarm_code),
            _ => {}
        }
    }
    panic!("did not end");
}

#[test]
fn plc_functions_wait_for_their_fin() {
    let prog = module("O1\nT0202\nM03 S500\nM08\nG98 G01 W-1 F600\nM30\n");
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    let pts = run(c, |_| {});
    let kinds: Vec<(GbcPlcKind, u32)> = unsafe { &(*host).requests }
        .iter()
        .map(|f| (f.kind, f.code))
        .collect();
    assert!(kinds.contains(&(GbcPlcKind::Tool, 2)), "{kinds:?}");
    assert!(kinds.contains(&(GbcPlcKind::SpindleCw, 0)), "{kinds:?}");
    assert!(kinds.contains(&(GbcPlcKind::M, 8)), "{kinds:?}");
    let s = unsafe { &(*host).requests }
        .iter()
        .find(|f| f.kind == GbcPlcKind::Speed)
        .unwrap();
    assert_eq!((s.s, s.css), (500.0, false));
    assert!(s.max_rpm.is_nan());
    // The feed after M08 starts only with its FIN: T, M03, S and M08 are
    // all handed over in period 0, whose poll is M08's first; the 30th
    // poll, in period 29, reports FIN and the feed starts in that period.
    let first_move = pts.iter().position(|p| p.z != 0.0).unwrap();
    assert_eq!(first_move, 29);
    assert_eq!(pts.last().unwrap().tool, 2);
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

#[test]
fn persistent_variables_go_through_the_host_and_outlive_a_reset() {
    let prog = module("O1\n#500 = #500 + 1\nG00 W-1\nM30\n");
    let host = new_host(Host {
        start: vec![(0, 41.0)],
        ..Host::default()
    });
    let (m, c) = new_controller(host, &prog);
    run(c, |_| {});
    assert_eq!(unsafe { &(*host).stores }.len(), 1);
    assert_eq!(unsafe { &(*host).stores }[0][0], 42.0);
    assert!(unsafe { &(*host).stores }[0][1].is_nan());
    // Reset and run again: #500 counts on from 42 (non-volatile).
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    let mut sp = blank();
    for _ in 0..10 {
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
    }
    run(c, |_| {});
    assert_eq!(unsafe { &(*host).stores }.last().unwrap()[0], 43.0);
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

#[test]
fn the_skip_signal_ends_a_g31_move() {
    // G31 along Z at F100 = 1.667 mm/s; the signal comes at 0.5 s, after
    // about 0.83 mm. The program copies the skip position (#996, Z) to
    // #510, which the host stores.
    let prog = module("O1\nG98 G31 W-10 F100\n#510 = #996\nM30\n");
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    let pts = run(c, |sp| {
        if sp.time_s >= 0.5 {
            assert_eq!(gbc_set_skip_input(c, true), GbcStatus::Ok);
        }
    });
    let end = pts.last().unwrap().z;
    assert!((-0.9..-0.7).contains(&end), "stopped at {end}");
    let hit = unsafe { &(*host).stores }.last().expect("#510 stored")[10];
    assert!((hit - end).abs() < 0.01, "hit {hit}, stop {end}");
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// The counts are the axis set points in whole 0.001 mm steps: within
/// half a step every period, and the end X20.0004 Z-5.0006 (machine zero
/// is work zero on the reference machine) as 20 000.4 and −5 000.6 steps
/// rounded to 20 000 and −5 001; no C axis, no C count.
#[test]
fn the_set_points_come_in_counts_too() {
    let prog = module("O1\nG98 G01 X20.0004 Z-5.0006 F600\nM30\n");
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    let pts = run(c, |sp| {
        assert!((sp.count_x as f64 * 0.001 - sp.axis_x).abs() <= 0.0005 + 1e-12);
        assert!((sp.count_z as f64 * 0.001 - sp.axis_z).abs() <= 0.0005 + 1e-12);
        assert_eq!(sp.count_c, 0);
    });
    let end = pts.last().unwrap();
    assert_eq!((end.count_x, end.count_z), (20_000, -5_001));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// `gbc_set_jit`: a macro loop run with its rounds compiled gives the
/// same set points, period by period, as interpreted; #500 written inside
/// the loop reaches the host's store all the same; a value outside the
/// three modes is refused.
#[test]
fn a_compiled_macro_loop_gives_the_same_set_points() {
    let prog = module(
        "O1\n#1=0\nG00 X40 Z0\nWHILE[#1LE90]DO1\nG01 X[40+4*SIN[#1]] Z[-#1*0.1] F300\n#500=#1\n#1=#1+3\nEND1\nM30\n",
    );
    let mut runs = Vec::new();
    for mode in [GBC_JIT_OFF, GBC_JIT_ALWAYS] {
        let host = new_host(Host::default());
        let (m, c) = new_controller(host, &prog);
        assert_eq!(gbc_set_jit(c, mode), GbcStatus::Ok);
        let points: Vec<(u64, u64, u32)> = run(c, |_| {})
            .iter()
            .map(|p| (p.x.to_bits(), p.z.to_bits(), p.line))
            .collect();
        let stored = unsafe { &(*host).stores }.last().map(|s| s[0]);
        runs.push((points, stored));
        assert_eq!(gbc_set_jit(c, 3), GbcStatus::InvalidArgument);
        assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
        assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
        drop(unsafe { Box::from_raw(host) });
    }
    assert_eq!(runs[0].1, Some(90.0));
    assert!(runs[0].0.len() > 100, "{} periods", runs[0].0.len());
    assert!(runs[0] == runs[1], "the set points differ");
}

/// The first `ticks` periods of `prog` with `setup` applied after the
/// load: the Z set point, the feed and the spindle speed, bit for bit.
fn periods(prog: &[u8], ticks: usize, setup: impl Fn(GbcController)) -> Vec<[u64; 3]> {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, prog);
    setup(c);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut out = Vec::new();
    for _ in 0..ticks {
        let mut sp = blank();
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        out.push([sp.z.to_bits(), sp.feed.to_bits(), sp.spindle_rpm.to_bits()]);
    }
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
    out
}

/// ±infinity is out of range like any other value: clamped to the
/// override's end, as the header says (only NaN is refused).
#[test]
fn an_infinite_override_is_clamped() {
    let prog = module("O1\nM03 S1000\nG98 G01 W-20 F500\nM30\n");
    let run = |feed: f64, spindle: f64| {
        periods(&prog, 400, |c| {
            assert_eq!(gbc_set_feed_override(c, feed), GbcStatus::Ok);
            assert_eq!(gbc_set_spindle_override(c, spindle), GbcStatus::Ok);
        })
    };
    let top = run(150.0, 200.0);
    assert_eq!(run(f64::INFINITY, f64::INFINITY), top);
    assert_eq!(run(f64::NEG_INFINITY, f64::NEG_INFINITY), run(0.0, 0.0));
    // The overrides took effect: 150 % of F500, 200 % of S1000.
    let last = top.last().expect("periods");
    assert!(
        (f64::from_bits(last[1]) - 750.0).abs() < 1e-6,
        "{}",
        f64::from_bits(last[1])
    );
    assert_ne!(top, run(100.0, 100.0));
}

/// The text of the message stop the controller stands at, and its
/// full length in bytes.
fn message_text(c: GbcController) -> (String, usize) {
    let mut buf = [0 as core::ffi::c_char; 32];
    let mut len = usize::MAX;
    let s = unsafe { gbc_message(c, buf.as_mut_ptr(), buf.len(), &mut len) };
    assert_eq!(s, GbcStatus::Ok);
    let text = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    (text.to_string_lossy().into_owned(), len)
}

fn state(c: GbcController) -> GbcStateInfo {
    let mut st = GbcStateInfo {
        state: GbcRunState::Idle,
        stop: GbcStopKind::None,
        message: u32::MAX,
        alarm_code: 0,
        blocks: 0,
    };
    assert_eq!(unsafe { gbc_state(c, &mut st) }, GbcStatus::Ok);
    st
}

/// Runs `prog` to its end, pressing cycle start at every stop; `at_stop`
/// sees the controller at each message stop. Returns each message stop's
/// `GbcStateInfo::message` and text.
fn message_stops(prog: &[u8], mut at_stop: impl FnMut(GbcController)) -> Vec<(u32, String)> {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, prog);
    let st = state(c);
    assert_eq!(
        (st.stop, st.message),
        (GbcStopKind::None, 0),
        "before the start"
    );
    assert_eq!(message_text(c), (String::new(), 0));
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut stops = Vec::new();
    let mut st = state(c);
    for _ in 0..200_000 {
        let mut sp = blank();
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        st = state(c);
        if st.stop != GbcStopKind::Message {
            assert_eq!(st.message, 0, "{:?}", st.state);
            assert_eq!(message_text(c), (String::new(), 0), "{:?}", st.state);
        }
        match st.state {
            GbcRunState::Ended => break,
            GbcRunState::Stopped => {
                assert_eq!(st.stop, GbcStopKind::Message);
                let (text, len) = message_text(c);
                assert_eq!(len, text.len());
                stops.push((st.message, text));
                at_stop(c);
                assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
            }
            _ => {}
        }
    }
    assert_eq!(st.state, GbcRunState::Ended);
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
    stops
}

/// `GbcStateInfo::message` is the value the program wrote to `#3006`,
/// and `gbc_message` the text of the stop the controller stands at.
#[test]
fn a_message_stop_gives_the_number_written_to_3006() {
    let prog = module("O1\nG00 X40 Z2\n#3006=7(SEVEN)\nG00 X30\n#3006=1(ONE)\nM30\n");
    let stops = message_stops(&prog, |_| {});
    assert_eq!(stops, [(7, "SEVEN".into()), (1, "ONE".into())]);
}

/// `#3006 = 0` and a vacant value give 0, as outside a message stop: the
/// stop kind tells them apart. A fraction is rounded half away from zero,
/// a negative value is 0, one beyond 32 bits UINT32_MAX.
#[test]
fn a_message_number_is_made_whole_and_0_is_told_apart_by_the_stop() {
    let prog = module(concat!(
        "O1\n#3006=0(ZERO)\n#3006=#0(VACANT)\n#3006=2.5(HALF)\n",
        "#3006=-4(NEGATIVE)\n#3006=5000000000(BIG)\nM30\n"
    ));
    let stops = message_stops(&prog, |_| {});
    let want = [
        (0, "ZERO"),
        (0, "VACANT"),
        (3, "HALF"),
        (0, "NEGATIVE"),
        (u32::MAX, "BIG"),
    ];
    assert_eq!(stops, want.map(|(n, t)| (n, t.to_string())));
}

/// Texts come as the program wrote them, UTF-8 (the canon prints
/// `CHECK ?INSERT? ??`); a comment that is not UTF-8 (Latin-1 here)
/// comes as the canon prints it, `?` for each byte outside printable
/// ASCII, `"` included.
#[test]
fn a_message_is_the_programs_utf8_text() {
    let src = b"O1\n#3006=1(CHECK \"INSERT\" \xc3\xa9)\n#3006=2(CAF\xc9 \"1\")\nM30\n";
    let out = compiler::compile("t.nc", src, &compiler::Options::default());
    let prog = out.module.expect("compiles").to_bytes();
    let stops = message_stops(&prog, |_| {});
    let want = [(1, "CHECK \"INSERT\" \u{e9}"), (2, "CAF? ?1?")];
    assert_eq!(stops, want.map(|(n, t)| (n, t.to_string())));
}

/// At a stop the text is cut as `snprintf` cuts, with its full length;
/// a null buffer with cap 0 asks for the length alone.
#[test]
fn a_cut_message_gives_its_full_length() {
    let prog = module("O1\nG00 X40 Z2\n#3006=7(SEVEN)\nM30\n");
    let mut checked = false;
    message_stops(&prog, |c| {
        // Three bytes of room: "SE" and the NUL; the full length 5.
        let mut small = [0x55 as core::ffi::c_char; 4];
        let mut len = 0;
        assert_eq!(
            unsafe { gbc_message(c, small.as_mut_ptr(), 3, &mut len) },
            GbcStatus::Ok
        );
        assert_eq!(len, 5);
        let cut = unsafe { std::ffi::CStr::from_ptr(small.as_ptr()) };
        assert_eq!(cut.to_bytes(), b"SE");
        assert_eq!(small[3], 0x55, "nothing past cap");
        len = 0;
        assert_eq!(
            unsafe { gbc_message(c, std::ptr::null_mut(), 0, &mut len) },
            GbcStatus::Ok
        );
        assert_eq!(len, 5);
        checked = true;
    });
    assert!(checked, "no message stop");
}

/// A file name longer than any buffer: `gbc_file_name` and `gbc_alarm`
/// cut it at a character boundary and give its full length.
#[test]
fn cut_names_and_alarm_texts_give_their_full_length() {
    let name = "é".repeat(150); // 300 bytes
    let src = "O1\nG00 W-1\n#3000 = 5 (TOOL BROKEN \u{e9})\nM30\n";
    let out = compiler::compile(&name, src.as_bytes(), &compiler::Options::default());
    let prog = out.module.expect("compiles").to_bytes();
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);

    let mut buf = [0x55 as core::ffi::c_char; 17];
    let mut len = 0;
    assert_eq!(
        unsafe { gbc_file_name(c, 0, buf.as_mut_ptr(), 16, &mut len) },
        GbcStatus::Ok
    );
    assert_eq!(len, 300);
    // 15 bytes of room hold 7 two-byte characters.
    let cut = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    assert_eq!(cut.to_str().expect("UTF-8"), "é".repeat(7));
    assert_eq!(buf[16], 0x55);

    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut st = GbcStateInfo {
        state: GbcRunState::Idle,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    };
    for _ in 0..100_000 {
        let mut sp = blank();
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        assert_eq!(unsafe { gbc_state(c, &mut st) }, GbcStatus::Ok);
        if st.state == GbcRunState::Alarm {
            break;
        }
    }
    assert_eq!(st.alarm_code, 3005);
    let mut a = no_alarm();
    assert_eq!(unsafe { gbc_alarm(c, &mut a) }, GbcStatus::Ok);
    let text = std::ffi::CStr::from_bytes_until_nul(&a.message).expect("NUL");
    // The program's text, UTF-8 (the canon's MSG is `TOOL BROKEN ??`).
    assert_eq!(text.to_str(), Ok("TOOL BROKEN \u{e9}"));
    assert_eq!(a.message_len, 14, "not cut");
    let file = std::ffi::CStr::from_bytes_until_nul(&a.file).expect("NUL");
    assert_eq!(file.to_str().expect("UTF-8"), "é".repeat(127));
    assert_eq!(a.file_len, 300, "cut: the full length");
    assert!(a.file_len >= GBC_TEXT_CAPACITY);
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// Manual moves through the C ABI: a step of X+20 (diameter) at rapid, a
/// reference return of Z after a jog stopped, the state `Manual` while
/// they run; then the program's G01 W-1 starts from where Z stands.
/// Refused while the program runs, and for an axis or feed out of range.
#[test]
fn manual_moves_go_through_the_c_abi() {
    let prog = module("O1\nG98 G01 W-1 F600\nM30\n");
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    let tick = |n: usize| {
        let mut sp = blank();
        for _ in 0..n {
            assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
            assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        }
        (sp, state(c).state)
    };
    assert_eq!(gbc_jog_step(c, GBC_AXIS_X, 20.0, 0.0), GbcStatus::Ok);
    assert_eq!(tick(1).1, GbcRunState::Manual);
    let (sp, state) = tick(5_000);
    assert_eq!(
        (state, sp.axis_x, sp.axis_z),
        (GbcRunState::Idle, 20.0, 0.0)
    );
    // A jog of Z toward − at 600 mm/min, stopped after 1 s: about 10 mm.
    assert_eq!(gbc_jog(c, GBC_AXIS_Z, false, 600.0), GbcStatus::Ok);
    tick(1_000);
    assert_eq!(gbc_manual_stop(c), GbcStatus::Ok);
    let (sp, state) = tick(1_000);
    assert_eq!(state, GbcRunState::Idle);
    assert!((-10.1..-9.8).contains(&sp.axis_z), "Z at {}", sp.axis_z);
    assert_eq!(gbc_home(c, GBC_AXIS_Z), GbcStatus::Ok);
    let (sp, _) = tick(5_000);
    assert_eq!((sp.axis_x, sp.axis_z), (20.0, 0.0));
    assert_eq!(gbc_jog(c, 2, true, 0.0), GbcStatus::InvalidArgument);
    assert_eq!(
        gbc_jog(c, GBC_AXIS_X, true, -1.0),
        GbcStatus::InvalidArgument
    );
    let pts = run(c, |_| {});
    assert_eq!(gbc_jog_step(c, GBC_AXIS_X, 1.0, 0.0), GbcStatus::NotIdle);
    let end = pts.last().unwrap();
    assert_eq!((end.axis_x, end.axis_z), (20.0, -1.0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// Two tools: T01 turns X52 down to Z-30; T02, from N100 on line 10,
/// turns X40 down to Z-20 and faces out to X50.
const TWO_TOOLS: &str = concat!(
    "G50 X200 Z100\n",
    "T0101\n",
    "G97 S1000 M03\n",
    "G00 X52 Z2\n",
    "G99 G01 Z-30 F0.2\n",
    "G00 X60 Z2\n",
    "T0202\n",
    "S800 M04\n",
    "G00 X40 Z2\n",
    "N100 G01 Z-20 F0.1\n",
    "X50\n",
    "M30\n",
);

/// A restart asked for through the C ABI.
type Restart = fn(GbcController) -> GbcStatus;

/// The PLC functions the host got, as (kind, code, S).
fn plc_seen(host: *mut Host) -> Vec<(GbcPlcKind, u32, f64)> {
    unsafe { &(*host).requests }
        .iter()
        .map(|f| (f.kind, f.code, f.s))
        .collect()
}

/// Program restart at N100 (and at its line, 10, which is the same run):
/// the search runs lines 1–9 with nothing moving and no PLC function;
/// at cycle start the PLC gets only the restored T0202, S800 and M04,
/// and the axes go from where they stand — X200 Z100, the G50 point — to
/// N100's start X40 Z2, X first (Z stays at 100), with tool 2 and the
/// spindle turning backwards. The cut at F0.1 mm/rev and 800 rev/min
/// runs at 80 mm/min; tool 1's cut (X52 to Z-30) never runs.
#[test]
fn a_program_restart_goes_through_the_c_abi() {
    let prog = module(TWO_TOOLS);
    let restarts: [Restart; 2] = [
        |c| gbc_restart_from_seq(c, 100, 1),
        |c| gbc_restart_from(c, 10, 1),
    ];
    let mut runs = Vec::new();
    for restart in restarts {
        let host = new_host(Host::default());
        let (m, c) = new_controller(host, &prog);
        assert_eq!(restart(c), GbcStatus::Ok);
        assert_eq!(state(c).state, GbcRunState::Idle);
        assert_eq!(plc_seen(host), [], "the search hands nothing over");
        let pts = run(c, |_| {});
        assert_eq!(state(c).state, GbcRunState::Ended);
        let want = [
            (GbcPlcKind::Tool, 2, 0.0),
            (GbcPlcKind::Speed, 0, 800.0),
            (GbcPlcKind::SpindleCcw, 0, 0.0),
        ];
        assert_eq!(plc_seen(host), want);
        check_restarted_run(&pts);
        runs.push(pts.iter().map(|p| (p.x, p.z, p.line)).collect::<Vec<_>>());
        assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
        assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
        drop(unsafe { Box::from_raw(host) });
    }
    assert!(runs[0] == runs[1], "N100 and line 10 run differently");
}

/// The set points of `TWO_TOOLS` restarted at N100.
fn check_restarted_run(pts: &[GbcSetPoint]) {
    let first = pts[0];
    assert!(first.x < 200.0 && first.z == 100.0, "{first:?}");
    assert!(pts.iter().all(|p| p.tool == 2));
    // The approach: a rapid of X to 40 at Z100, then one of Z.
    let z_moves = pts.iter().position(|p| p.z != 100.0).expect("Z moves");
    assert_eq!(pts[z_moves - 1].x, 40.0);
    assert!(pts[..z_moves].iter().all(|p| p.motion != GbcMotion::Feed));
    // Never forwards; at 800 backwards once up to speed, for every cut.
    assert!(pts.iter().all(|p| p.spindle_rpm <= 0.0));
    let cuts: Vec<_> = pts.iter().filter(|p| p.motion == GbcMotion::Feed).collect();
    assert!(cuts.iter().all(|p| p.spindle_rpm == -800.0));
    let mid = cuts[cuts.len() / 4];
    assert_eq!(mid.line, 10);
    assert!((mid.feed - 80.0).abs() < 1e-6, "feed {}", mid.feed);
    // Tool 1's cut is skipped: nothing at X52 below Z2, nothing past Z-20.
    assert!(!pts.iter().any(|p| p.x == 52.0 && p.z <= 2.0));
    assert!(pts.iter().all(|p| p.z >= -20.0));
    let end = pts.last().expect("periods");
    assert_eq!((end.x, end.z), (50.0, -20.0));
}

/// Refused restarts: pass or line 0 (bad values), a line without a block,
/// an N the program lacks, a pass the run never reaches, a restart while
/// the program runs or after it ended. A refused restart leaves the
/// program at its start, even after one that was taken: cycle start runs
/// it whole, and tool 1's cut reaches X52 Z-30.
#[test]
fn a_refused_restart_leaves_the_program_at_its_start() {
    let prog = module(TWO_TOOLS);
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    assert_eq!(gbc_restart_result(c), GbcStatus::RestartNotFound);
    assert_eq!(gbc_restart_from_seq(c, 100, 1), GbcStatus::Ok);
    assert_eq!(gbc_restart_result(c), GbcStatus::Ok);
    assert_ne!(state(c).blocks, 0, "the search ran");
    assert_eq!(gbc_restart_from_seq(c, 100, 0), GbcStatus::InvalidArgument);
    assert!(last_error().contains("pass"), "{}", last_error());
    assert_eq!(gbc_restart_from(c, 0, 1), GbcStatus::InvalidArgument);
    let not_found: [(Restart, &str); 3] = [
        (|c| gbc_restart_from(c, 99, 1), "line 99"),
        (|c| gbc_restart_from_seq(c, 7, 1), "N7"),
        (|c| gbc_restart_from_seq(c, 100, 2), "N100"),
    ];
    for (restart, why) in not_found {
        assert_eq!(restart(c), GbcStatus::RestartNotFound, "{why}");
        let text = last_error();
        assert!(text.contains(why), "{text}");
        // The result tells the same again, with the same text.
        assert_eq!(gbc_restart_result(c), GbcStatus::RestartNotFound);
        assert_eq!(last_error(), text);
    }
    assert_eq!(state(c).state, GbcRunState::Idle);
    let mut while_running = None;
    let pts = run(c, |_| {
        while_running.get_or_insert_with(|| (gbc_restart_from_seq(c, 100, 1), state(c).state));
    });
    assert_eq!(
        while_running,
        Some((GbcStatus::NotIdle, GbcRunState::Running))
    );
    assert!(pts.iter().any(|p| (p.x, p.z, p.tool) == (52.0, -30.0, 1)));
    let seen = plc_seen(host);
    assert_eq!(
        seen[..2],
        [(GbcPlcKind::Tool, 1, 0.0), (GbcPlcKind::Speed, 0, 1000.0)]
    );
    assert_eq!(gbc_restart_from(c, 10, 1), GbcStatus::NotIdle, "ended");
    assert!(last_error().contains("gbc_reset"), "{}", last_error());
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// A search that meets an alarm (`#3000`) or a block a thread chain
/// continues says so, with its own status and text; the controller
/// stands in no alarm and the program stays at its start.
#[test]
fn a_restart_refused_by_its_search_says_why() {
    let cases = [
        (
            "O1\n#3000=1(NO STOCK)\nN10 G00 W-1\nM30\n",
            GbcStatus::RestartAlarm,
            "NO STOCK",
        ),
        (
            "O1\nG00 X40 Z2\nG32 Z-10 F2\nN10 G32 X44 Z-12\nG00 X50\nM30\n",
            GbcStatus::RestartHeld,
            "thread chain",
        ),
    ];
    for (src, status, why) in cases {
        let prog = module(src);
        let host = new_host(Host::default());
        let (m, c) = new_controller(host, &prog);
        assert_eq!(gbc_restart_from_seq(c, 10, 1), status, "{src}");
        assert!(last_error().contains(why), "{}", last_error());
        let st = state(c);
        assert_eq!(
            (st.state, st.alarm_code, st.blocks),
            (GbcRunState::Idle, 0, 0)
        );
        assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
        assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
        drop(unsafe { Box::from_raw(host) });
    }
}

/// T0101, a rapid to X40 Z2 and a cut to Z-20.
const WEAR_CUT: &str = "T0101\nG00 X40 Z2\nG01 Z-20 F300\nM30\n";

/// A wear of X −0.04 (the part came out 0.04 large on the diameter) and
/// Z +0.02 on offset 1.
const WEAR: GbcOffsetLengths = GbcOffsetLengths {
    x: 0.0,
    z: 0.0,
    wear_x: -0.04,
    wear_z: 0.02,
};

/// Tool offset `number` as the page has it.
fn tool_offset(c: GbcController, number: u32) -> GbcOffsetLengths {
    let mut out = GbcOffsetLengths {
        x: f64::NAN,
        z: f64::NAN,
        wear_x: f64::NAN,
        wear_z: f64::NAN,
    };
    assert_eq!(
        unsafe { gbc_tool_offset(c, number, &mut out) },
        GbcStatus::Ok
    );
    out
}

/// Work offset `which` as the page has it.
fn work_offset(c: GbcController, which: u32) -> (f64, f64) {
    let (mut x, mut z) = (f64::NAN, f64::NAN);
    assert_eq!(
        unsafe { gbc_work_offset(c, which, &mut x, &mut z) },
        GbcStatus::Ok
    );
    (x, z)
}

/// Reset, ticked until the controller is idle again.
fn reset(c: GbcController) {
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    let mut sp = blank();
    for _ in 0..100_000 {
        if state(c).state == GbcRunState::Idle {
            return;
        }
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
    }
    panic!("the reset did not finish");
}

/// The wear set through `gbc_set_tool_offset` while idle: the slide goes
/// that much further (Fanuc: the offset is added to the commanded
/// position, so X40 is machine X39.96 and Z-20 machine Z-19.98), the
/// programmed point stays X40 Z-20, and it holds for the next run too.
#[test]
fn a_wear_set_through_c_moves_the_slide() {
    let prog = module(WEAR_CUT);
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    assert_eq!(
        tool_offset(c, 1),
        GbcOffsetLengths {
            x: 0.0,
            z: 0.0,
            wear_x: 0.0,
            wear_z: 0.0
        }
    );
    assert_eq!(unsafe { gbc_set_tool_offset(c, 1, &WEAR) }, GbcStatus::Ok);
    assert_eq!(tool_offset(c, 1), WEAR, "read back exactly");
    for _ in 0..2 {
        let pts = run(c, |_| {});
        let end = pts.last().expect("periods");
        assert_eq!((end.x, end.z), (40.0, -20.0));
        assert!((end.axis_x - 39.96).abs() < 1e-9, "{end:?}");
        assert!((end.axis_z + 19.98).abs() < 1e-9, "{end:?}");
        reset(c);
    }
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// An edit while the program runs waits for the next reset: this run
/// keeps the values it started with, the next one has the edit.
#[test]
fn a_wear_set_while_running_holds_from_the_reset() {
    let prog = module(WEAR_CUT);
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    let mut set = false;
    let pts = run(c, |_| {
        if !set {
            assert_eq!(state(c).state, GbcRunState::Running);
            assert_eq!(unsafe { gbc_set_tool_offset(c, 1, &WEAR) }, GbcStatus::Ok);
            set = true;
        }
    });
    assert!(set);
    assert_eq!(tool_offset(c, 1), WEAR, "the page has it at once");
    let end = pts.last().expect("periods");
    assert_eq!(
        (end.axis_x, end.axis_z),
        (40.0, -20.0),
        "this run keeps its own"
    );
    reset(c);
    let end = *run(c, |_| {}).last().expect("periods");
    assert!((end.axis_x - 39.96).abs() < 1e-9, "{end:?}");
    assert!((end.axis_z + 19.98).abs() < 1e-9, "{end:?}");
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// G55 touched off at Z-250 before the program is loaded: the controller
/// keeps it for the program, whose Z2 is machine Z-248.
#[test]
fn a_work_offset_set_through_c_moves_the_work_zero() {
    let prog = module("G55 G00 X40 Z2\nM30\n");
    let host = new_host(Host::default());
    let cb = GbcHost {
        user: host.cast(),
        plc_request: Some(request),
        plc_done: Some(done),
        vars_load: Some(load),
        vars_store: Some(store),
    };
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(gbc_machine_reference(&mut m), GbcStatus::Ok);
        assert_eq!(gbc_controller_new(m, &cb, &mut c), GbcStatus::Ok);
    }
    assert_eq!(work_offset(c, GBC_WORK_OFFSET_G55), (0.0, 0.0));
    assert_eq!(
        gbc_set_work_offset(c, GBC_WORK_OFFSET_G55, 0.0, -250.0),
        GbcStatus::Ok
    );
    assert_eq!(work_offset(c, GBC_WORK_OFFSET_G55), (0.0, -250.0));
    assert_eq!(work_offset(c, GBC_WORK_OFFSET_G54), (0.0, 0.0));
    assert_eq!(
        unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
    assert_eq!(work_offset(c, GBC_WORK_OFFSET_G55), (0.0, -250.0));
    let end = *run(c, |_| {}).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, 2.0));
    assert_eq!((end.axis_x, end.axis_z), (40.0, -248.0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// Refused edits and reads: a NaN or too large value, offsets 0 and 33,
/// a `which` that is no `GBC_WORK_OFFSET_*`, null pointers. Each says
/// why, writes no output, and changes nothing: the page keeps the wear
/// set before, and the run moves by it alone.
#[test]
fn a_bad_offset_edit_is_refused_and_changes_nothing() {
    let prog = module(WEAR_CUT);
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &prog);
    assert_eq!(unsafe { gbc_set_tool_offset(c, 1, &WEAR) }, GbcStatus::Ok);
    let arg = GbcStatus::InvalidArgument;
    let nan = GbcOffsetLengths {
        wear_x: f64::NAN,
        ..WEAR
    };
    assert_eq!(unsafe { gbc_set_tool_offset(c, 1, &nan) }, arg);
    let text = last_error();
    assert!(
        text.contains("tool offset 1") && text.contains("wear_x"),
        "{text}"
    );
    assert!(text.contains("NaN"), "{text}");
    let far = GbcOffsetLengths { z: 2.0e6, ..WEAR };
    assert_eq!(unsafe { gbc_set_tool_offset(c, 1, &far) }, arg);
    assert!(last_error().contains(".z:"), "{}", last_error());
    for number in [0, 33, u32::MAX] {
        assert_eq!(unsafe { gbc_set_tool_offset(c, number, &WEAR) }, arg);
        let text = last_error();
        assert!(text.contains(&format!("tool offset {number}")), "{text}");
        assert!(text.contains("outside the table"), "{text}");
        let mut out = WEAR;
        out.x = 7.0;
        assert_eq!(unsafe { gbc_tool_offset(c, number, &mut out) }, arg);
        assert!(last_error().contains("1 … 32"), "{}", last_error());
        assert_eq!(out.x, 7.0, "nothing written");
    }
    for which in [7, 0xFFFF_FFFF] {
        assert_eq!(gbc_set_work_offset(c, which, 0.0, -250.0), arg);
        assert!(last_error().contains("GBC_WORK_OFFSET"), "{}", last_error());
        let (mut x, mut z) = (1.0, 2.0);
        assert_eq!(unsafe { gbc_work_offset(c, which, &mut x, &mut z) }, arg);
        assert_eq!((x, z), (1.0, 2.0), "nothing written");
    }
    for (x, z) in [(0.0, f64::INFINITY), (f64::NAN, 0.0), (0.0, -1.5e6)] {
        assert_eq!(gbc_set_work_offset(c, GBC_WORK_OFFSET_G55, x, z), arg);
        assert!(last_error().contains("coords.g55"), "{}", last_error());
    }
    let null = GbcStatus::NullPointer;
    let mut v = 3.0;
    unsafe {
        assert_eq!(gbc_set_tool_offset(c, 1, std::ptr::null()), null);
        assert_eq!(gbc_tool_offset(c, 1, std::ptr::null_mut()), null);
        let w = GBC_WORK_OFFSET_G54;
        assert_eq!(gbc_work_offset(c, w, &mut v, std::ptr::null_mut()), null);
        assert_eq!(gbc_work_offset(c, w, std::ptr::null_mut(), &mut v), null);
    }
    assert_eq!(v, 3.0, "nothing written");
    assert_eq!(tool_offset(c, 1), WEAR);
    assert_eq!(tool_offset(c, 32).wear_x, 0.0);
    for which in GBC_WORK_OFFSET_EXTERNAL..=GBC_WORK_OFFSET_G59 {
        assert_eq!(work_offset(c, which), (0.0, 0.0), "{which}");
    }
    let end = *run(c, |_| {}).last().expect("periods");
    assert!((end.axis_x - 39.96).abs() < 1e-9, "{end:?}");
    assert!((end.axis_z + 19.98).abs() < 1e-9, "{end:?}");
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// Another program selected after a reset starts where the first left
/// the axes (X40 Z2): a move of Z alone keeps X40. A module that is not
/// valid, or a select while the program runs or has ended, is refused
/// and keeps the program loaded.
#[test]
fn another_program_is_selected_where_the_axes_stand() {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &module("G00 X40 Z2\nM30\n"));
    let end = *run(c, |_| {}).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, 2.0));
    let second = module("G01 W-12 F300\nM30\n");
    let select = |bytes: &[u8]| unsafe { gbc_controller_select(c, bytes.as_ptr(), bytes.len()) };
    assert_eq!(select(&second), GbcStatus::NotIdle, "ended");
    assert!(last_error().contains("gbc_reset"), "{}", last_error());
    reset(c);
    assert_eq!(select(b"not a module"), GbcStatus::InvalidModule);
    assert_eq!(select(&second), GbcStatus::Ok);
    let end = *run(c, |_| {}).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, -10.0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// The M codes of the machine's own before the restart block (M10, then
/// M14), which the restart does not give again: the count alone, a
/// buffer that holds one, one that holds both; none after a refusal.
#[test]
fn a_restart_tells_the_m_codes_it_does_not_give_again() {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &module("M10\nG00 X50 Z2\nM14\nN20 G00 X60\nM30\n"));
    assert_eq!(gbc_restart_from_seq(c, 20, 1), GbcStatus::Ok);
    let mut len = 0;
    let count = unsafe { gbc_restart_m_codes(c, std::ptr::null_mut(), 0, &mut len) };
    assert_eq!((count, len), (GbcStatus::Ok, 2));
    let mut one = [0u32; 1];
    let s = unsafe { gbc_restart_m_codes(c, one.as_mut_ptr(), 1, &mut len) };
    assert_eq!((s, one, len), (GbcStatus::Ok, [10], 2));
    let mut both = [0u32; 4];
    let s = unsafe { gbc_restart_m_codes(c, both.as_mut_ptr(), 4, &mut len) };
    assert_eq!((s, both, len), (GbcStatus::Ok, [10, 14, 0, 0], 2));
    let null = unsafe { gbc_restart_m_codes(c, both.as_mut_ptr(), 4, std::ptr::null_mut()) };
    assert_eq!(null, GbcStatus::NullPointer);
    assert_eq!(gbc_restart_from_seq(c, 30, 1), GbcStatus::RestartNotFound);
    let s = unsafe { gbc_restart_m_codes(c, both.as_mut_ptr(), 4, &mut len) };
    assert_eq!((s, len), (GbcStatus::Ok, 0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// The destination of a restart: N20 starts where the block before left
/// the tool, X50 Z2 (work coordinates); NaN before any restart and after
/// a refused one.
#[test]
fn a_restart_tells_where_its_approach_goes() {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &module("M10\nG00 X50 Z2\nM14\nN20 G00 X60\nM30\n"));
    let destination = |c| {
        let (mut x, mut z) = (0.0, 0.0);
        let s = unsafe { gbc_restart_destination(c, &mut x, &mut z) };
        assert_eq!(s, GbcStatus::Ok);
        (x, z)
    };
    let (x, z) = destination(c);
    assert!(x.is_nan() && z.is_nan());
    assert_eq!(gbc_restart_from_seq(c, 20, 1), GbcStatus::Ok);
    assert_eq!(destination(c), (50.0, 2.0));
    let mut z = 0.0;
    let null = unsafe { gbc_restart_destination(c, std::ptr::null_mut(), &mut z) };
    assert_eq!(null, GbcStatus::NullPointer);
    assert_eq!(gbc_restart_from_seq(c, 30, 1), GbcStatus::RestartNotFound);
    assert!(destination(c).0.is_nan());
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// The macro-variable page through C: #500–#999 set (handed to
/// `vars_store` at once) and read back; what the program set read as it
/// stands after the blocks read; other numbers and infinity refused.
#[test]
fn the_macro_variable_page_goes_through_the_c_abi() {
    let host = new_host(Host {
        start: vec![(0, 3.0)],
        ..Host::default()
    });
    let (m, c) = new_controller(host, &module("#100=#500+4\nG00 X[#510] Z5\nM30\n"));
    let read = |n| {
        let mut v = f64::NAN;
        let s = unsafe { gbc_variable(c, n, &mut v) };
        (s, v)
    };
    assert_eq!(read(500), (GbcStatus::Ok, 3.0));
    assert_eq!(gbc_set_variable(c, 510, 42.0), GbcStatus::Ok);
    assert_eq!(read(510), (GbcStatus::Ok, 42.0));
    let stores = unsafe { &(*host).stores };
    assert_eq!(stores.last().map(|s| (s[0], s[10])), Some((3.0, 42.0)));
    for n in [1, 100, 499, 1000, 5001] {
        assert_eq!(
            gbc_set_variable(c, n, 1.0),
            GbcStatus::InvalidArgument,
            "#{n}"
        );
        assert!(last_error().contains("only #500–#999"), "{}", last_error());
    }
    assert_eq!(
        gbc_set_variable(c, 520, f64::INFINITY),
        GbcStatus::InvalidArgument
    );
    assert_eq!(read(7777).0, GbcStatus::InvalidArgument);
    let null = unsafe { gbc_variable(c, 500, std::ptr::null_mut()) };
    assert_eq!(null, GbcStatus::NullPointer);
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert_eq!(read(100), (GbcStatus::Ok, 7.0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
}

/// Tool setting by a measured cut through C: on the reference machine
/// offset 1 is all 0 and work zero is machine zero; the cut ends at X50
/// Z-10 and measures 49.96, so by hand its X geometry becomes
/// 50 − 49.96 = 0.04. Refused before a program is loaded, for another
/// axis, for NaN and for an offset outside the table (1 … 32).
#[test]
fn a_measured_cut_sets_the_tool_offset_through_c() {
    let host = new_host(Host::default());
    let (m, c) = new_controller(host, &module("T0101\nG00 X50 Z2\nG01 Z-10 F500\nM30\n"));
    run(c, |_| {});
    let measure = |n, axis, v| gbc_measure_tool_offset(c, n, axis, v);
    assert_eq!(measure(1, GBC_AXIS_C, 49.96), GbcStatus::InvalidArgument);
    assert_eq!(measure(1, GBC_AXIS_X, f64::NAN), GbcStatus::InvalidArgument);
    assert_eq!(measure(33, GBC_AXIS_X, 49.96), GbcStatus::InvalidArgument);
    assert_eq!(measure(1, GBC_AXIS_X, 49.96), GbcStatus::Ok);
    let mut l = GbcOffsetLengths {
        x: f64::NAN,
        z: f64::NAN,
        wear_x: f64::NAN,
        wear_z: f64::NAN,
    };
    assert_eq!(unsafe { gbc_tool_offset(c, 1, &mut l) }, GbcStatus::Ok);
    assert!((l.x - 0.04).abs() < 1e-12, "{l:?}");
    assert_eq!((l.z, l.wear_x, l.wear_z), (0.0, 0.0, 0.0));
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    drop(unsafe { Box::from_raw(host) });
    // No program: no slide position to measure from.
    let (m, c) = controller_on("");
    assert_eq!(
        gbc_measure_tool_offset(c, 1, GBC_AXIS_X, 50.0),
        GbcStatus::NoProgram
    );
    free(m, c);
}
