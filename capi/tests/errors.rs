//! `gbc_last_error` after every kind of failure: each failing call
//! replaces the text with one about itself (never a stale one from an
//! earlier call), a successful call leaves it, and it is per thread. The
//! text is given as `snprintf` would: the full length, a cut detectable.

mod periods;

use core::ffi::c_char;
use gbc::*;
use periods::blank;
use std::ptr::null_mut;

/// The text `gbc_last_error` gives now, read with a length query first.
fn last_error() -> String {
    let mut len = usize::MAX;
    assert_eq!(
        unsafe { gbc_last_error(null_mut(), 0, &mut len) },
        GbcStatus::Ok
    );
    let mut buf = vec![0 as c_char; len + 1];
    let mut again = 0;
    assert_eq!(
        unsafe { gbc_last_error(buf.as_mut_ptr(), buf.len(), &mut again) },
        GbcStatus::Ok
    );
    assert_eq!(again, len);
    let bytes: Vec<u8> = buf[..len].iter().map(|&c| c as u8).collect();
    String::from_utf8(bytes).expect("UTF-8")
}

/// A failure whose text names a machine key, so a stale text is seen.
const STALE: &str = "interpolation_period_ms";

fn plant_stale_error() {
    let text = b"[machine]\ninterpolation_period_ms = -1\n";
    let mut m = 0;
    assert_eq!(
        unsafe { gbc_machine_from_toml(text.as_ptr().cast(), text.len(), &mut m) },
        GbcStatus::InvalidMachine
    );
    assert!(last_error().contains(STALE));
}

/// `call` fails with `status` and leaves a text that mentions `about`.
fn fails_with(what: &str, status: GbcStatus, about: &str, call: impl FnOnce() -> GbcStatus) {
    plant_stale_error();
    assert_eq!(call(), status, "{what}");
    let text = last_error();
    assert!(!text.contains(STALE), "{what}: stale text {text:?}");
    assert!(text.contains(about), "{what}: {text:?} lacks {about:?}");
}

fn module(src: &str) -> Vec<u8> {
    let out = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
    out.module.expect("compiles").to_bytes()
}

#[test]
fn every_failure_sets_a_text_about_itself() {
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(gbc_machine_reference(&mut m), GbcStatus::Ok);
        assert_eq!(
            gbc_controller_new(m, std::ptr::null(), &mut c),
            GbcStatus::Ok
        );
    }
    let mut sp = blank();
    let null = GbcStatus::NullPointer;
    fails_with("tick, null out", null, "null", || unsafe {
        gbc_tick(c, null_mut())
    });
    fails_with("machine, null out", null, "null", || unsafe {
        gbc_machine_reference(null_mut())
    });
    fails_with("load, null bytes", null, "null", || unsafe {
        gbc_controller_load(c, std::ptr::null(), 10)
    });
    let invalid = GbcStatus::InvalidHandle;
    fails_with("tick(0)", invalid, "handle", || unsafe {
        gbc_tick(0, &mut sp)
    });
    fails_with("forged", invalid, "handle", || unsafe {
        gbc_tick(c | (0x5a << 24), &mut sp)
    });
    fails_with("machine_free(0)", invalid, "handle", || gbc_machine_free(0));
    fails_with("wrong kind", GbcStatus::WrongKind, "kind", || unsafe {
        gbc_tick(m, &mut sp)
    });
    fails_with("no program", GbcStatus::NoProgram, "no program", || {
        gbc_run_ahead(c)
    });
    let arg = GbcStatus::InvalidArgument;
    fails_with("jit 3", arg, "JIT", || gbc_set_jit(c, 3));
    fails_with("block skip 0", arg, "block-skip", || {
        gbc_set_block_skip(c, 0, true)
    });
    fails_with("block skip 10", arg, "block-skip", || {
        gbc_set_block_skip(c, 10, true)
    });
    fails_with("NaN override", arg, "NaN", || {
        gbc_set_feed_override(c, f64::NAN)
    });
    fails_with("infinite encoder", arg, "infinite", || {
        gbc_spindle_feedback(c, f64::INFINITY, 0.0)
    });
    // The restart's arguments are checked before the program is looked for.
    fails_with("restart pass 0", arg, "pass", || gbc_restart_from(c, 1, 0));
    fails_with("restart line 0", arg, "line", || gbc_restart_from(c, 0, 1));
    fails_with(
        "restart, no program",
        GbcStatus::NoProgram,
        "no program",
        || gbc_restart_from_seq(c, 10, 1),
    );
    // The offset page: the refused key and why, after what was edited.
    fails_with("tool offset 33", arg, "tool offset 33", || {
        let mut out = std::mem::MaybeUninit::<GbcOffsetLengths>::uninit();
        unsafe { gbc_tool_offset(c, 33, out.as_mut_ptr()) }
    });
    let nan = GbcOffsetLengths {
        x: 0.0,
        z: 0.0,
        wear_x: f64::NAN,
        wear_z: 0.0,
    };
    fails_with("NaN wear", arg, "wear_x: NaN", || unsafe {
        gbc_set_tool_offset(c, 1, &nan)
    });
    fails_with("set tool offset 0", arg, "outside the table", || unsafe {
        gbc_set_tool_offset(c, 0, &GbcOffsetLengths { wear_x: 0.0, ..nan })
    });
    fails_with("set tool offset, null", null, "null", || unsafe {
        gbc_set_tool_offset(c, 1, std::ptr::null())
    });
    fails_with("work offset 7", arg, "GBC_WORK_OFFSET_G59", || {
        gbc_set_work_offset(c, 7, 0.0, 0.0)
    });
    fails_with("infinite work offset", arg, "coords.g56.x", || {
        gbc_set_work_offset(c, GBC_WORK_OFFSET_G56, f64::INFINITY, 0.0)
    });
    fails_with("work offset, null", null, "null", || unsafe {
        gbc_work_offset(c, GBC_WORK_OFFSET_G54, null_mut(), null_mut())
    });
    // The production counters: what was refused and why.
    fails_with("parts 1.5", arg, "whole numbers", || {
        let p = GbcParts {
            machined: 1.5,
            required: 0.0,
        };
        gbc_set_parts(c, p)
    });
    fails_with("tool life group 1", arg, "no tool-life group 1", || {
        let mut out = std::mem::MaybeUninit::<GbcToolLife>::uninit();
        unsafe { gbc_tool_life(c, 1, 0, out.as_mut_ptr()) }
    });
    fails_with("renew group 1", arg, "no tool-life group 1", || {
        gbc_renew_tool_life(c, 1)
    });
    fails_with("parts, null", null, "null", || unsafe {
        gbc_parts(c, null_mut())
    });
    // MDI: its arguments are checked before the program is looked for.
    fails_with("mdi, null text", null, "null", || unsafe {
        gbc_mdi(c, std::ptr::null(), 8)
    });
    fails_with("mdi, too long", arg, "GBC_MDI_CAPACITY", || {
        let long = vec![b' '; GBC_MDI_CAPACITY + 1];
        unsafe { gbc_mdi(c, long.as_ptr().cast(), long.len()) }
    });
    fails_with(
        "mdi, no program",
        GbcStatus::NoProgram,
        "no program",
        || {
            let text = b"M03 S500";
            unsafe { gbc_mdi(c, text.as_ptr().cast(), text.len()) }
        },
    );
    fails_with("in_mdi, null", null, "null", || unsafe {
        gbc_in_mdi(c, null_mut())
    });
    // Program text: its arguments before the program is looked for, by
    // select_source; the bound before a byte is read.
    fails_with("load_source, null text", null, "null", || unsafe {
        gbc_controller_load_source(c, std::ptr::null(), std::ptr::null(), 8)
    });
    fails_with("load_source, too long", arg, "GBC_SOURCE_CAPACITY", || {
        let text = b"M30\n";
        unsafe { gbc_controller_load_source(c, std::ptr::null(), text.as_ptr().cast(), usize::MAX) }
    });
    fails_with("select_source, null text", null, "null", || unsafe {
        gbc_controller_select_source(c, std::ptr::null(), std::ptr::null(), 8)
    });
    fails_with(
        "select_source, too long",
        arg,
        "GBC_SOURCE_CAPACITY",
        || {
            let text = b"M30\n";
            let len = GBC_SOURCE_CAPACITY + 1;
            unsafe { gbc_controller_select_source(c, std::ptr::null(), text.as_ptr().cast(), len) }
        },
    );
    fails_with(
        "select_source, no program",
        GbcStatus::NoProgram,
        "no program",
        || {
            let text = b"M30\n";
            unsafe {
                gbc_controller_select_source(c, c"t.nc".as_ptr(), text.as_ptr().cast(), text.len())
            }
        },
    );
    // A program text that does not compile: the compiler's diagnostic
    // under the name given, its line and code; nothing loaded.
    fails_with(
        "load_source, compile error",
        GbcStatus::CompileError,
        "part.nc:2:1: error[E2001]",
        || {
            let text = b"G00 X40 Z2\nG999\nM30\n";
            unsafe {
                gbc_controller_load_source(c, c"part.nc".as_ptr(), text.as_ptr().cast(), text.len())
            }
        },
    );
    fails_with(
        "nothing loaded by it",
        GbcStatus::NoProgram,
        "no program",
        || gbc_run_ahead(c),
    );
    // A bad handle and a bad argument: the status and the text both tell
    // of the handle.
    fails_with("NaN, bad handle", invalid, "handle", || {
        gbc_set_feed_override(0, f64::NAN)
    });
    fails_with("jit 3, bad handle", invalid, "handle", || gbc_set_jit(0, 3));
    fails_with("work offset 7, bad handle", invalid, "handle", || {
        gbc_set_work_offset(0, 7, 0.0, 0.0)
    });
    let prog = module("O1\nM30\n");
    assert_eq!(
        unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
    fails_with(
        "second load",
        GbcStatus::AlreadyLoaded,
        "already",
        || unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
    );
    fails_with(
        "second load, from text",
        GbcStatus::AlreadyLoaded,
        "already",
        || unsafe { gbc_controller_load_source(c, std::ptr::null(), c"M30".as_ptr(), 3) },
    );
    fails_with(
        "select_source, compile error",
        GbcStatus::CompileError,
        "program.nc:1:1: error[E2001]",
        || unsafe { gbc_controller_select_source(c, std::ptr::null(), c"G999".as_ptr(), 4) },
    );
    // An MDI text that does not compile: the compiler's diagnostic, its
    // file, line, column and code.
    fails_with(
        "mdi, compile error",
        GbcStatus::CompileError,
        "MDI:1:1: error[E2001]",
        || {
            let text = b"G999";
            unsafe { gbc_mdi(c, text.as_ptr().cast(), text.len()) }
        },
    );
    let mut buf = [0 as c_char; 8];
    fails_with("message, cap 0, no len", null, "nothing", || unsafe {
        gbc_message(c, buf.as_mut_ptr(), 0, null_mut())
    });
    // gbc_last_error's own failure replaces the text too.
    fails_with("last_error, null buf", null, "buf is null", || unsafe {
        gbc_last_error(null_mut(), 10, null_mut())
    });
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

#[test]
fn success_leaves_the_text_and_each_thread_has_its_own() {
    plant_stale_error();
    let mut m = 0;
    assert_eq!(unsafe { gbc_machine_reference(&mut m) }, GbcStatus::Ok);
    assert!(last_error().contains(STALE), "a success cleared it");
    std::thread::spawn(|| {
        assert_eq!(last_error(), "", "a new thread starts empty");
        assert_eq!(gbc_run_ahead(0), GbcStatus::InvalidHandle);
        assert!(last_error().contains("handle"));
    })
    .join()
    .expect("the other thread");
    assert!(last_error().contains(STALE), "another thread's failure");
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}

#[test]
fn a_cut_text_is_told_by_its_full_length() {
    plant_stale_error();
    let full = last_error();
    assert!(full.len() > 16, "{full}");
    let mut buf = [0x55 as c_char; 17];
    let mut len = 0;
    assert_eq!(
        unsafe { gbc_last_error(buf.as_mut_ptr(), 16, &mut len) },
        GbcStatus::Ok
    );
    assert_eq!(len, full.len(), "the full length, not the cut one");
    let cut = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) };
    assert_eq!(cut.to_bytes(), &full.as_bytes()[..15]);
    assert_eq!(buf[16], 0x55, "nothing written past cap");
    // A `cap` beyond the buffer is read as "enough room": only the text
    // and its NUL are written.
    let mut roomy = [0x55 as c_char; 512];
    assert_eq!(
        unsafe { gbc_last_error(roomy.as_mut_ptr(), usize::MAX, &mut len) },
        GbcStatus::Ok
    );
    let whole = unsafe { std::ffi::CStr::from_ptr(roomy.as_ptr()) };
    assert_eq!(whole.to_bytes(), full.as_bytes());
    assert_eq!(roomy[full.len() + 1], 0x55);
    // A length query writes no text; without `len` it has nothing to give.
    assert_eq!(
        unsafe { gbc_last_error(null_mut(), 0, null_mut()) },
        GbcStatus::NullPointer
    );
}

#[test]
fn the_library_is_the_headers_version() {
    assert_eq!(gbc_abi_version(), GBC_ABI_VERSION);
}
