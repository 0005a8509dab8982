//! Programs given as G-code text (`gbc_controller_load_source`,
//! `gbc_controller_select_source`): compiled in the library for the
//! controller's machine, they run period by period as the same text
//! compiled by the compiler here and loaded as a `.gbc`; a program called
//! from a library folder of the machine file is found; refusals load
//! nothing and keep what was loaded.

mod periods;

use core::ffi::c_char;
use gbc::*;
use periods::*;
use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::ptr::{null, null_mut};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace")
        .to_path_buf()
}

fn read(relative: &str) -> String {
    let path = repo().join(relative);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The `.gbc` of `src` as the file `name`, compiled here for the machine
/// of the machine file `machine` (the reference machine for "").
fn module(name: &str, src: &str, machine: &str) -> Vec<u8> {
    let opts = compiler::Options {
        machine: nc::Machine::from_toml(machine).expect("a machine file"),
        ..compiler::Options::default()
    };
    let out = compiler::compile(name, src.as_bytes(), &opts);
    out.module.expect("compiles").to_bytes()
}

/// A controller of the machine file `machine` ("" is the reference
/// machine), no program yet, no host.
fn controller(machine: &str) -> (GbcMachine, GbcController) {
    let (mut m, mut c) = (0, 0);
    unsafe {
        assert_eq!(
            gbc_machine_from_toml(machine.as_ptr().cast(), machine.len(), &mut m),
            GbcStatus::Ok
        );
        assert_eq!(gbc_controller_new(m, null(), &mut c), GbcStatus::Ok);
    }
    (m, c)
}

fn load_source(c: GbcController, name: &CStr, text: &str) -> GbcStatus {
    unsafe { gbc_controller_load_source(c, name.as_ptr(), text.as_ptr().cast(), text.len()) }
}

fn select_source(c: GbcController, name: &CStr, text: &str) -> GbcStatus {
    unsafe { gbc_controller_select_source(c, name.as_ptr(), text.as_ptr().cast(), text.len()) }
}

/// Cycle start, then every period until the program has ended; the set
/// points of the run.
fn run_to_end(c: GbcController) -> Vec<GbcSetPoint> {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut pts = Vec::new();
    for _ in 0..2_000_000 {
        let (sp, st) = period(c);
        pts.push(sp);
        match st {
            GbcRunState::Ended => return pts,
            GbcRunState::Alarm | GbcRunState::Stopped => {
                panic!("{st:?}: alarm {}", state_info(c).alarm_code)
            }
            _ => {}
        }
    }
    panic!("the program did not end");
}

/// Reset, and the periods until the controller is idle.
fn reset(c: GbcController) {
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    for _ in 0..10_000 {
        period(c);
        if state(c) == GbcRunState::Idle {
            return;
        }
    }
    panic!("no idle after the reset: {:?}", state(c));
}

fn file_name(c: GbcController, index: u16) -> String {
    let mut len = 0;
    assert_eq!(
        unsafe { gbc_file_name(c, index, null_mut(), 0, &mut len) },
        GbcStatus::Ok
    );
    let mut buf = vec![0 as c_char; len + 1];
    assert_eq!(
        unsafe { gbc_file_name(c, index, buf.as_mut_ptr(), buf.len(), null_mut()) },
        GbcStatus::Ok
    );
    let text = unsafe { CStr::from_ptr(buf.as_ptr()) };
    text.to_string_lossy().into_owned()
}

/// `src` on the machine file `machine`, once compiled here and loaded
/// with `gbc_controller_load`, once given as text to
/// `gbc_controller_load_source`: the two runs give the same set point in
/// every period (every field: positions, counts, spindle, feed, line,
/// file, tool, motion, time), to the end. The number of periods.
fn same_run_both_ways(name: &CStr, src: &str, machine: &str) -> usize {
    let file = name.to_str().expect("UTF-8");
    let (m, by_bytes) = controller(machine);
    let prog = module(file, src, machine);
    assert_eq!(
        unsafe { gbc_controller_load(by_bytes, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
    let expected = run_to_end(by_bytes);
    free(m, by_bytes);

    let (m, by_text) = controller(machine);
    assert_eq!(load_source(by_text, name, src), GbcStatus::Ok);
    assert_eq!(state(by_text), GbcRunState::Idle, "loaded, waiting");
    assert_eq!(file_name(by_text, 0), file);
    let got = run_to_end(by_text);
    free(m, by_text);

    for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
        assert_eq!(g, e, "{file}: period {i}");
    }
    assert_eq!(got.len(), expected.len(), "{file}: periods");
    got.len()
}

#[test]
fn a_program_given_as_text_runs_as_its_module_does() {
    let shaft = read("examples/shaft.nc");
    let periods = same_run_both_ways(c"shaft.nc", &shaft, "");
    // Not an empty run: the shaft turns, grooves and goes home.
    assert!(periods > 1000, "{periods} periods");
}

#[test]
fn the_text_is_compiled_for_the_controllers_own_machine() {
    // The slant-bed machine reads X30 as 30 mm ("calculator" decimal
    // point) and has its own offsets: a module compiled for the reference
    // machine would not load on it, nor run the same.
    let machine = read("examples/gsk980tdi-slant-bed.toml");
    let shaft = read("examples/shaft.nc");
    let periods = same_run_both_ways(c"shaft.nc", &shaft, &machine);
    assert!(periods > 1000, "{periods} periods");
}

#[test]
fn a_long_plain_text_compiled_a_chunk_at_a_time_runs_as_its_module_does() {
    // Over the compiler's chunk (compiler::CHUNK_BYTES): the chunked
    // compile, with its second thread, is the library's too.
    let mut src = String::from("G00 X40 Z2\nG01 F3000\n");
    let mut i = 0;
    while src.len() <= 2 * compiler::CHUNK_BYTES {
        let x = 40.0 + f64::from(i % 2) * 0.4;
        let z = 2.0 - f64::from(i) * 0.01;
        src.push_str(&format!("X{x:.3} Z{z:.3}\n"));
        i += 1;
    }
    src.push_str("G00 X60\nM30\n");
    let periods = same_run_both_ways(c"long.nc", &src, "");
    assert!(periods > usize::try_from(i).expect("blocks"), "{periods}");
}

/// A folder of its own under the target's temporary directory, empty.
fn temp_folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("capi-source-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    dir
}

#[test]
fn a_called_program_is_found_in_the_machine_files_library_folder() {
    let dir = temp_folder("library");
    // The subprogram: 5 mm towards the chuck, then back to the caller.
    std::fs::write(dir.join("O1234.nc"), "O1234\nG00 W-5\nM99\n").expect("written");
    let main = "G00 X40 Z2\nM98 P1234\nG00 X60\nM30\n";

    // Without the folder the call is the compiler's error E2012.
    let (m, c) = controller("");
    assert_eq!(load_source(c, c"main.nc", main), GbcStatus::CompileError);
    let text = last_error();
    assert!(text.starts_with("main.nc:2:1: error[E2012]"), "{text}");
    assert!(text.contains("O1234"), "{text}");
    free(m, c);

    // The machine file names it: the program loads and runs through it.
    let folder = dir.to_str().expect("a UTF-8 path");
    let machine = format!("[macro]\nlibrary_dirs = [{folder:?}]\n");
    let (m, c) = controller(&machine);
    assert_eq!(load_source(c, c"main.nc", main), GbcStatus::Ok);
    let pts = run_to_end(c);
    let end = *pts.last().expect("periods");
    assert_eq!((end.x, end.z), (60.0, -3.0));
    // The subprogram's move ran from its own file, named by its path.
    let sub = pts.iter().find(|p| p.file == 1).expect("periods in O1234");
    assert_eq!(sub.line, 2, "O1234's G00 W-5");
    assert_eq!(file_name(c, 1), dir.join("O1234.nc").display().to_string());
    assert_eq!(file_name(c, 0), "main.nc");
    free(m, c);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Line 3, `G01 X`: a word without a value (gbcc: `error[E1007]`).
const BAD: &str = "G00 X40 Z2\nG01 Z-5 F300\nG01 X\nM30\n";

#[test]
fn a_text_that_does_not_compile_is_refused_with_the_first_error() {
    let (m, c) = controller("");
    assert_eq!(load_source(c, c"lathe.nc", BAD), GbcStatus::CompileError);
    let text = last_error();
    let first = text.lines().next().expect("a first line");
    assert!(first.starts_with("lathe.nc:3:5: error[E1007]"), "{text}");
    // The compiler's own first error, compiled here.
    let out = compiler::compile("lathe.nc", BAD.as_bytes(), &compiler::Options::default());
    let (_, d) = out
        .diags
        .iter()
        .find(|(_, d)| d.is_error())
        .expect("an error");
    assert!(first.contains(&format!("error[{}]", d.code)), "{text}");
    assert!(text.contains("G01 X"), "the source line: {text}");
    // Nothing loaded: no program to run, and a valid text loads after it.
    assert_eq!(gbc_run_ahead(c), GbcStatus::NoProgram);
    assert_eq!(state_info(c).blocks, 0);
    assert_eq!(load_source(c, c"lathe.nc", MOVE), GbcStatus::Ok);
    let end = *run_to_end(c).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, 2.0));
    free(m, c);
}

#[test]
fn the_name_is_the_program_nc_when_null_or_empty() {
    for name in [null(), c"".as_ptr()] {
        let (m, c) = controller("");
        let s = unsafe { gbc_controller_load_source(c, name, BAD.as_ptr().cast(), BAD.len()) };
        assert_eq!(s, GbcStatus::CompileError);
        let text = last_error();
        assert!(text.starts_with("program.nc:3:5: "), "{text}");
        let s = unsafe { gbc_controller_load_source(c, name, MOVE.as_ptr().cast(), MOVE.len()) };
        assert_eq!(s, GbcStatus::Ok);
        assert_eq!(file_name(c, 0), "program.nc");
        free(m, c);
    }
}

/// A program that goes to X40 Z2.
const MOVE: &str = "G00 X40 Z2\nM30\n";

#[test]
fn bad_arguments_are_refused_before_a_byte_is_read() {
    let (m, c) = controller("");
    let small = [b' '; 8];
    unsafe {
        assert_eq!(
            gbc_controller_load_source(c, null(), null(), 8),
            GbcStatus::NullPointer
        );
        assert!(last_error().contains("null"), "{}", last_error());
        // A length far past the 8 bytes there are: refused, not read.
        for len in [GBC_SOURCE_CAPACITY + 1, usize::MAX] {
            assert_eq!(
                gbc_controller_load_source(c, null(), small.as_ptr().cast(), len),
                GbcStatus::InvalidArgument,
                "{len}"
            );
            assert!(
                last_error().contains("GBC_SOURCE_CAPACITY"),
                "{}",
                last_error()
            );
            assert_eq!(
                gbc_controller_select_source(c, null(), small.as_ptr().cast(), len),
                GbcStatus::InvalidArgument,
                "{len}"
            );
        }
        assert_eq!(
            gbc_controller_select_source(c, null(), null(), 8),
            GbcStatus::NullPointer
        );
        // Nothing loaded by the refusals.
        assert_eq!(gbc_run_ahead(c), GbcStatus::NoProgram);
        // Valid arguments, no program: select_source has none to replace.
        assert_eq!(select_source(c, c"next.nc", MOVE), GbcStatus::NoProgram);
        // An empty text (null with len 0 too) is what the compiler makes
        // of it: a program that does nothing, loaded.
        assert_eq!(
            gbc_controller_load_source(c, null(), null(), 0),
            GbcStatus::Ok
        );
        run_to_end(c);
    }
    free(m, c);
}

#[test]
fn a_second_load_is_refused_as_gbc_controller_load_refuses_it() {
    let (m, c) = controller("");
    assert_eq!(load_source(c, c"first.nc", MOVE), GbcStatus::Ok);
    let prog = module("t.nc", MOVE, "");
    let by_bytes = unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) };
    assert_eq!(by_bytes, GbcStatus::AlreadyLoaded);
    assert_eq!(load_source(c, c"second.nc", MOVE), by_bytes);
    assert!(last_error().contains("already"), "{}", last_error());
    // Before the arguments, as gbc_controller_load checks its bytes after.
    let null_bytes = unsafe { gbc_controller_load(c, null(), 10) };
    let null_text = unsafe { gbc_controller_load_source(c, null(), null(), 10) };
    assert_eq!((null_text, null_bytes), (by_bytes, by_bytes));
    // Even a text that would not compile: the program stays.
    assert_eq!(load_source(c, c"bad.nc", BAD), by_bytes);
    assert_eq!(file_name(c, 0), "first.nc");
    let end = *run_to_end(c).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, 2.0));
    free(m, c);
}

#[test]
fn select_source_swaps_the_program_while_idle() {
    let (m, c) = controller("");
    assert_eq!(load_source(c, c"first.nc", MOVE), GbcStatus::Ok);
    let end = *run_to_end(c).last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, 2.0));
    // Ended is not idle: refused, after the compile.
    let second = "G01 W-12 F300\nM30\n";
    assert_eq!(select_source(c, c"second.nc", second), GbcStatus::NotIdle);
    assert!(last_error().contains("gbc_reset"), "{}", last_error());
    reset(c);
    // A text that does not compile keeps the program loaded.
    assert_eq!(select_source(c, c"bad.nc", BAD), GbcStatus::CompileError);
    assert!(last_error().starts_with("bad.nc:3:5: error[E1007]"));
    assert_eq!(file_name(c, 0), "first.nc");
    // Idle: the second program, which starts where the axes stand
    // (an incremental W-12 from Z2).
    assert_eq!(select_source(c, c"second.nc", second), GbcStatus::Ok);
    assert_eq!(file_name(c, 0), "second.nc");
    let pts = run_to_end(c);
    let end = *pts.last().expect("periods");
    assert_eq!((end.x, end.z), (40.0, -10.0));
    assert!(
        pts.iter().all(|p| p.line == 1 || p.line == 2),
        "second.nc's lines"
    );
    free(m, c);
}

#[test]
fn select_source_while_running_is_refused_and_the_program_goes_on() {
    let (m, c) = controller("");
    let first = "G00 X40 Z2\nG01 Z-30 F300\nM30\n";
    assert_eq!(load_source(c, c"first.nc", first), GbcStatus::Ok);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut mid = blank();
    for _ in 0..200 {
        mid = period(c).0;
    }
    assert_eq!(state(c), GbcRunState::Running);
    assert_eq!(select_source(c, c"next.nc", MOVE), GbcStatus::NotIdle);
    // The compile comes first: an error is told even while it runs.
    assert_eq!(select_source(c, c"bad.nc", BAD), GbcStatus::CompileError);
    // The first program runs on, from where it was, to its own end.
    let mut end = mid;
    for _ in 0..2_000_000 {
        let (sp, st) = period(c);
        end = sp;
        if st == GbcRunState::Ended {
            break;
        }
        assert_eq!(st, GbcRunState::Running);
    }
    assert_eq!(state(c), GbcRunState::Ended);
    assert_eq!((end.x, end.z), (40.0, -30.0));
    assert_eq!(file_name(c, 0), "first.nc");
    free(m, c);
}
