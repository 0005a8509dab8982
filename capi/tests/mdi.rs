//! MDI through the C interface (`gbc_mdi`, `gbc_in_mdi`): blocks typed at
//! the panel run in the program's place; when they end the machine is
//! idle at once, the spindle as they left it, and the program is back at
//! its start where the axes stand. Refusals change nothing.

mod periods;

use core::ffi::c_char;
use gbc::*;
use periods::*;
use std::ptr::{null, null_mut};

/// The program loaded: to X40 Z2, a cut to Z-20, out to X60 Z2.
const MAIN: &str = "G00 X40 Z2\nG01 Z-20 F300\nG00 X60 Z2\nM30\n";

fn module(src: &str) -> Vec<u8> {
    let out = compiler::compile("main.nc", src.as_bytes(), &compiler::Options::default());
    out.module.expect("compiles").to_bytes()
}

/// A controller of the reference machine, no program yet.
fn controller() -> (GbcMachine, GbcController) {
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(gbc_machine_reference(&mut m), GbcStatus::Ok);
        assert_eq!(gbc_controller_new(m, null(), &mut c), GbcStatus::Ok);
    }
    (m, c)
}

/// A controller with `MAIN` loaded.
fn loaded() -> (GbcMachine, GbcController) {
    let (m, c) = controller();
    let prog = module(MAIN);
    assert_eq!(
        unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
    (m, c)
}

fn mdi(c: GbcController, text: &str) -> GbcStatus {
    unsafe { gbc_mdi(c, text.as_ptr().cast(), text.len()) }
}

fn in_mdi(c: GbcController) -> bool {
    let mut out = false;
    assert_eq!(unsafe { gbc_in_mdi(c, &mut out) }, GbcStatus::Ok);
    out
}

/// Cycle start, then every period until the MDI blocks have ended (a
/// run-ahead after the tick sees it); the set points of the run. The
/// blocks never stand ended: the machine is idle at once.
fn run_mdi(c: GbcController) -> Vec<GbcSetPoint> {
    run_mdi_with(c, |_| {})
}

/// As [`run_mdi`], calling `each` with each period's set point while
/// the blocks run.
fn run_mdi_with(c: GbcController, mut each: impl FnMut(&GbcSetPoint)) -> Vec<GbcSetPoint> {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut pts = Vec::new();
    for _ in 0..400_000 {
        let (sp, st) = period(c);
        each(&sp);
        pts.push(sp);
        assert!(
            !matches!(st, GbcRunState::Alarm | GbcRunState::Ended),
            "{st:?}"
        );
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        if !in_mdi(c) {
            assert_eq!(state(c), GbcRunState::Idle);
            return pts;
        }
    }
    panic!("the MDI blocks did not end: {:?}", state(c));
}

/// Cycle start, then every period until the program has ended; the set
/// points of the run.
fn run_to_end(c: GbcController) -> Vec<GbcSetPoint> {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut pts = Vec::new();
    for _ in 0..400_000 {
        let (sp, st) = period(c);
        pts.push(sp);
        match st {
            GbcRunState::Ended => return pts,
            GbcRunState::Alarm | GbcRunState::Stopped => panic!("{st:?}"),
            _ => {}
        }
    }
    panic!("the program did not end");
}

/// The main program runs from its start to its end at X60 Z2: its first
/// rapid goes towards X40 Z2 from where the axes stood, at (x, z).
fn main_program_runs_from(c: GbcController, x: f64, z: f64) -> GbcSetPoint {
    assert!(!in_mdi(c));
    let pts = run_to_end(c);
    let moving = pts
        .iter()
        .find(|p| p.motion == GbcMotion::Rapid)
        .expect("the first rapid");
    assert_eq!(moving.line, 1, "the program's first block");
    assert!(
        (moving.x - x).abs() < 1.0 && (moving.z - z).abs() < 1.0,
        "left from X{x} Z{z}: {moving:?}"
    );
    let end = *pts.last().expect("periods");
    assert_eq!((end.x, end.z), (60.0, 2.0));
    end
}

fn file_name(c: GbcController, index: u16) -> String {
    let mut buf = [0 as c_char; 64];
    assert_eq!(
        unsafe { gbc_file_name(c, index, buf.as_mut_ptr(), buf.len(), null_mut()) },
        GbcStatus::Ok
    );
    let text = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    text.to_string_lossy().into_owned()
}

#[test]
fn the_spindle_started_in_mdi_keeps_turning_and_the_program_comes_back() {
    let (m, c) = loaded();
    assert!(!in_mdi(c));
    // No final newline: the operator's text as typed.
    assert_eq!(mdi(c, "M03 S500"), GbcStatus::Ok);
    assert!(in_mdi(c));
    assert_eq!(state(c), GbcRunState::Idle, "loaded, not started");
    run_mdi(c);
    assert!(!in_mdi(c));
    // Idle from then on, with no reset: the spindle reaches 500 rpm and
    // stays there.
    let mut reached = None;
    for i in 0..5_000 {
        let (sp, st) = period(c);
        assert_eq!(st, GbcRunState::Idle, "period {i}");
        assert!(!in_mdi(c));
        match reached {
            None if sp.spindle_rpm == 500.0 => reached = Some(i),
            None => assert!((0.0..500.0).contains(&sp.spindle_rpm), "{sp:?}"),
            Some(_) => assert_eq!(sp.spindle_rpm, 500.0, "period {i}"),
        }
        assert_eq!((sp.x, sp.z), (0.0, 0.0), "the axes stand");
    }
    assert!(reached.is_some_and(|i| i < 4_000), "{reached:?}");
    // Cycle start runs the program from its start, the spindle still on.
    let end = main_program_runs_from(c, 0.0, 0.0);
    assert_eq!(end.spindle_rpm, 500.0);
    free(m, c);
}

#[test]
fn the_program_starts_where_the_mdi_blocks_left_the_axes() {
    let (m, c) = loaded();
    assert_eq!(mdi(c, "G00 X80 Z20\n"), GbcStatus::Ok);
    // The rapid runs as line 1 of the file "MDI".
    let mut rapid = None;
    let pts = run_mdi_with(c, |p| {
        if p.motion == GbcMotion::Rapid && rapid.is_none() {
            rapid = Some((p.line, file_name(c, p.file)));
        }
    });
    assert_eq!(rapid, Some((1, "MDI".to_string())));
    let last = pts.last().expect("periods");
    assert_eq!((last.x, last.z), (80.0, 20.0));
    assert_eq!(last.spindle_rpm, 0.0);
    // The program back: its file again, from X80 Z20.
    main_program_runs_from(c, 80.0, 20.0);
    assert_eq!(file_name(c, 0), "main.nc");
    free(m, c);
}

#[test]
fn mdi_given_again_replaces_the_blocks_not_yet_run() {
    let (m, c) = loaded();
    assert_eq!(mdi(c, "M03 S500\n"), GbcStatus::Ok);
    assert_eq!(mdi(c, "G00 X80 Z20\n"), GbcStatus::Ok);
    let pts = run_mdi(c);
    let last = pts.last().expect("periods");
    assert_eq!((last.x, last.z, last.spindle_rpm), (80.0, 20.0, 0.0));
    main_program_runs_from(c, 80.0, 20.0);
    free(m, c);
}

#[test]
fn an_empty_text_is_blocks_that_do_nothing() {
    let (m, c) = loaded();
    for text in ["", "  \n\t\n"] {
        assert_eq!(mdi(c, text), GbcStatus::Ok, "{text:?}");
        assert!(in_mdi(c));
        let pts = run_mdi(c);
        assert!(pts.iter().all(|p| (p.x, p.z) == (0.0, 0.0)), "{text:?}");
    }
    // A null text of length 0 is empty as well.
    assert_eq!(unsafe { gbc_mdi(c, null(), 0) }, GbcStatus::Ok);
    run_mdi(c);
    main_program_runs_from(c, 0.0, 0.0);
    free(m, c);
}

#[test]
fn a_text_that_does_not_compile_is_refused_with_the_compilers_diagnostic() {
    let (m, c) = loaded();
    // (text, the diagnostic's first line up to the message)
    let cases = [
        ("G01 X", "MDI:1:5: error[E1007]: `X` has no value"),
        ("G999\n", "MDI:1:1: error[E2001]: unknown G code G999"),
        ("#1=[", "MDI:1:5: error[E1014]: expression syntax"),
        ("G00 X80\nG01 Z", "MDI:2:5: error[E1007]: `Z` has no value"),
        ("M98 P1234", "MDI:1:1: error[E2012]: M98 calls O1234"),
    ];
    for (text, header) in cases {
        assert_eq!(mdi(c, text), GbcStatus::CompileError, "{text:?}");
        let e = last_error();
        assert!(e.starts_with(header), "{text:?}: {e:?}");
        // The first error only, with its source line; no warning.
        assert_eq!(e.matches("error[").count(), 1, "{e}");
        assert!(!e.contains("warning"), "{e}");
        assert!(e.lines().count() <= 8, "{e}");
        assert!(!in_mdi(c), "{text:?}");
        assert_eq!(state(c), GbcRunState::Idle);
    }
    // Nothing changed: the program runs as loaded.
    main_program_runs_from(c, 0.0, 0.0);
    free(m, c);
}

#[test]
fn a_refused_text_keeps_the_mdi_blocks_given_before() {
    let (m, c) = loaded();
    assert_eq!(mdi(c, "G00 X80 Z20"), GbcStatus::Ok);
    assert_eq!(mdi(c, "G999"), GbcStatus::CompileError);
    assert!(in_mdi(c));
    let pts = run_mdi(c);
    let last = pts.last().expect("periods");
    assert_eq!((last.x, last.z), (80.0, 20.0));
    free(m, c);
}

#[test]
fn mdi_needs_an_idle_machine() {
    let (m, c) = loaded();
    // While the program runs.
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..200 {
        period(c);
    }
    assert_eq!(state(c), GbcRunState::Running);
    assert_eq!(mdi(c, "M03 S500"), GbcStatus::NotIdle);
    assert!(last_error().contains("gbc_reset"), "{}", last_error());
    assert!(!in_mdi(c));
    // The run goes on to its end (no second cycle start needed: the one
    // given is still in force), and at the end MDI is refused too.
    for _ in 0..400_000 {
        if period(c).1 == GbcRunState::Ended {
            break;
        }
    }
    assert_eq!(state(c), GbcRunState::Ended);
    assert_eq!(mdi(c, "M03 S500"), GbcStatus::NotIdle);
    // A text that does not compile is that, whatever the state.
    assert_eq!(mdi(c, "G999"), GbcStatus::CompileError);
    // After a reset it is taken.
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    for _ in 0..100_000 {
        if period(c).1 == GbcRunState::Idle {
            break;
        }
    }
    assert_eq!(mdi(c, "M03 S500"), GbcStatus::Ok);
    assert!(in_mdi(c));
    free(m, c);
}

#[test]
fn a_reset_ends_the_mdi_blocks_and_brings_the_program_back() {
    let (m, c) = loaded();
    // 50 mm at 100 mm/min: half a minute, far longer than the test waits.
    assert_eq!(mdi(c, "G98 G01 W-50 F100\n"), GbcStatus::Ok);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..2_000 {
        period(c);
    }
    assert_eq!(state(c), GbcRunState::Running);
    assert!(in_mdi(c));
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    let mut stood = blank();
    for _ in 0..100_000 {
        let (sp, st) = period(c);
        stood = sp;
        if st == GbcRunState::Idle {
            break;
        }
    }
    assert_eq!(state(c), GbcRunState::Idle);
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert!(!in_mdi(c));
    assert!(stood.z < 0.0 && stood.z > -50.0, "{stood:?}");
    main_program_runs_from(c, 0.0, stood.z);
    free(m, c);
}

#[test]
fn an_alarm_in_mdi_names_the_mdi_line() {
    let (m, c) = loaded();
    assert_eq!(mdi(c, "M03 S500\n#3000 = 7 (MDI ALARM)\n"), GbcStatus::Ok);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..100_000 {
        if period(c).1 == GbcRunState::Alarm {
            break;
        }
    }
    let st = state_info(c);
    assert_eq!((st.state, st.alarm_code), (GbcRunState::Alarm, 3007));
    let mut a = no_alarm();
    assert_eq!(unsafe { gbc_alarm(c, &mut a) }, GbcStatus::Ok);
    assert_eq!((a.code, a.line), (3007, 2));
    let file = std::ffi::CStr::from_bytes_until_nul(&a.file).expect("NUL");
    assert_eq!(file.to_str(), Ok("MDI"));
    // In the alarm MDI is refused; the reset brings the program back.
    assert_eq!(mdi(c, "M05"), GbcStatus::NotIdle);
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    let mut sp = blank();
    for _ in 0..100_000 {
        assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
        assert_eq!(unsafe { gbc_tick(c, &mut sp) }, GbcStatus::Ok);
        if state(c) == GbcRunState::Idle {
            break;
        }
    }
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert!(!in_mdi(c));
    main_program_runs_from(c, 0.0, 0.0);
    free(m, c);
}

#[test]
fn bad_arguments_are_refused_and_change_nothing() {
    // Without a program: MDI takes the place of one.
    let (m, c) = controller();
    assert_eq!(mdi(c, "M03 S500"), GbcStatus::NoProgram);
    assert!(last_error().contains("no program"), "{}", last_error());
    assert!(!in_mdi(c), "false without a program");
    free(m, c);

    let (m, c) = loaded();
    assert_eq!(unsafe { gbc_mdi(c, null(), 8) }, GbcStatus::NullPointer);
    assert!(last_error().contains("null"), "{}", last_error());
    assert_eq!(unsafe { gbc_in_mdi(c, null_mut()) }, GbcStatus::NullPointer);
    // One byte over the bound, a real buffer of it: refused before it is
    // read, with the bound named.
    let long = vec![b'\n'; GBC_MDI_CAPACITY + 1];
    assert_eq!(
        unsafe { gbc_mdi(c, long.as_ptr().cast(), long.len()) },
        GbcStatus::InvalidArgument
    );
    let e = last_error();
    assert!(
        e.contains("GBC_MDI_CAPACITY") && e.contains("1048577"),
        "{e}"
    );
    assert!(!in_mdi(c));
    // Null with a length beyond the bound: the pointer is what is wrong.
    assert_eq!(
        unsafe { gbc_mdi(c, null(), usize::MAX) },
        GbcStatus::NullPointer
    );
    // At the bound it is taken: a long comment, as a paste might bring.
    let mut full = vec![b'X'; GBC_MDI_CAPACITY];
    full[0] = b'(';
    full[GBC_MDI_CAPACITY - 2] = b')';
    full[GBC_MDI_CAPACITY - 1] = b'\n';
    assert_eq!(
        unsafe { gbc_mdi(c, full.as_ptr().cast(), full.len()) },
        GbcStatus::Ok,
        "{}",
        last_error()
    );
    assert!(in_mdi(c));
    free(m, c);
}
