//! Programs given as G-code text: a control takes its programs as text
//! (from USB, DNC, its editor) and runs them. The text is compiled here
//! for the controller's machine, as `gbcc --machine FILE` compiles it,
//! and the module loaded or selected as `gbc_controller_load` and
//! `gbc_controller_select` take one. The compile and its first error's
//! diagnostic are shared with `gbc_mdi`.

use crate::{fail, install, select, with_ctl, Failure, GbcController, GbcStatus};
use core::ffi::{c_char, CStr};

/// The most bytes of text `gbc_controller_load_source` and
/// `gbc_controller_select_source` take (256 MiB): far above any program
/// a control keeps, it keeps a wrong `len` from making the library read
/// and allocate without bound.
pub const GBC_SOURCE_CAPACITY: usize = 1 << 28;

/// The file name a program text is compiled under when the host gives
/// none.
const DEFAULT_NAME: &str = "program.nc";

/// Compiles `len` bytes of G-code at `text` — a program file's contents,
/// no NUL needed (read during the call only) — for the controller's
/// machine, and loads the module as `gbc_controller_load` loads a `.gbc`:
/// the controller asks the host for #500–#999 (`vars_load`) and waits for
/// cycle start; the panel's switches, the offset page and the production
/// counters set before are the program's.
///
/// `name` is the program's file name, a NUL-terminated string (read
/// during the call only; bytes that are not UTF-8 become U+FFFD): the
/// diagnostics, a `GbcAlarm`'s file and `gbc_file_name` give it. Null or
/// empty, it is "program.nc".
///
/// The compile is `gbcc`'s for the machine file the controller was made
/// from (`gbcc --machine FILE`, no other option): a program the text
/// calls (`M98 P1234`, `G65 P1234`) and does not hold is looked for in
/// the machine file's library folders (`macro.library_dirs`; a relative
/// folder is taken from the host process's working directory, as `gbcc`
/// takes it from its own). Warnings do not refuse and are not given.
///
/// The compile runs in this call, on the calling thread: call it from
/// the ordinary context, never the real-time one. It takes what the
/// text takes (100 000 blocks, 1.5 MB: 20 to 40 ms on a PC), and the
/// controller is busy meanwhile: one call at a time per handle, so no
/// `gbc_tick` on it until this returns. Long texts bring helper threads:
/// a text of plain blocks (no macro statement, computed word, call,
/// G70–G73 cycle or `/`) longer than 64 KiB is compiled a chunk at a
/// time, parsed and dry-run on a second thread while the calling one
/// builds the module; a program without macros of 10 000 blocks or more
/// compiled whole is dry-run on a second thread beside the building.
/// Both are joined before the call returns; the syntax trees of a
/// program of 10 000 blocks or more are then freed on a thread of their
/// own, which may outlive the call briefly. Where a thread cannot be
/// started, its work is done on the calling one.
///
/// The statuses, each with `gbc_last_error`'s text saying why; a refusal
/// loads nothing:
/// - a program already loaded: [`GbcStatus::AlreadyLoaded`], as for
///   `gbc_controller_load` (before the arguments are looked at);
/// - `text` null while `len` is not 0: [`GbcStatus::NullPointer`]
///   (`len` 0 is an empty program, `text` then may be null);
/// - `len` above [`GBC_SOURCE_CAPACITY`]: [`GbcStatus::InvalidArgument`],
///   before a byte is read;
/// - the text does not compile: [`GbcStatus::CompileError`], with the
///   compiler's diagnostic of its first error as `gbcc` prints it
///   without colour: a first line `name:line:column: error[Ennnn]:
///   message`, then a few lines with the source and the place marked (a
///   host showing one line takes the text up to the first newline);
/// - `vars_load` refuses or gives an infinite value:
///   [`GbcStatus::HostFailure`], as for `gbc_controller_load`.
///
/// # Safety
/// `name` is null or a NUL-terminated string; `text` is null or readable
/// for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn gbc_controller_load_source(
    controller: GbcController,
    name: *const c_char,
    text: *const c_char,
    len: usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if c.loaded() {
            return Err(GbcStatus::AlreadyLoaded.into());
        }
        // SAFETY: the caller's promise.
        let src = unsafe { text_at(text, len, "the program text", SOURCE_CAPACITY)? };
        // SAFETY: the caller's promise.
        let name = unsafe { name_at(name) };
        let module = compile(&name, src, &options(&c.machine))?;
        install(c, module)
    })
}

/// Compiles `len` bytes of G-code at `text` as
/// `gbc_controller_load_source` does (`name`, the library folders, the
/// calling thread and the time it takes the same; the machine with the
/// offset page as it stands) and selects the module as
/// `gbc_controller_select` selects a `.gbc`: it replaces the loaded
/// program while the controller is idle, before its first cycle start or
/// after `gbc_reset` once `gbc_state` gives `GBC_RUN_STATE_IDLE`. The new
/// program starts where the axes stand, with the power-on modes, at the
/// next `gbc_cycle_start`; the offset page, #500–#999, the panel's
/// switches and the JIT setting stay. On the interpreter half of a split
/// controller it takes the loaded program's place at the real-time
/// half's next `gbc_reset`, as `gbc_controller_select`'s does.
///
/// The statuses, each with `gbc_last_error`'s text saying why; a refusal
/// keeps the program loaded:
/// - `text` null while `len` is not 0: [`GbcStatus::NullPointer`];
/// - `len` above [`GBC_SOURCE_CAPACITY`]: [`GbcStatus::InvalidArgument`],
///   before a byte is read;
/// - no program loaded: [`GbcStatus::NoProgram`], as for
///   `gbc_controller_select` (`gbc_controller_load_source` loads the
///   first);
/// - the text does not compile: [`GbcStatus::CompileError`], as for
///   `gbc_controller_load_source`. The text is compiled before the state
///   is looked at, so it is this status even while a program runs;
/// - a program runs, stands stopped, ended or in an alarm, or a manual
///   move or a reset runs: [`GbcStatus::NotIdle`] (after the compile; a
///   whole controller only);
/// - a module for another machine configuration would be
///   [`GbcStatus::MachineMismatch`]; compiled for the controller's own
///   machine, it never is.
///
/// # Safety
/// `name` is null or a NUL-terminated string; `text` is null or readable
/// for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn gbc_controller_select_source(
    controller: GbcController,
    name: *const c_char,
    text: *const c_char,
    len: usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        // The arguments first, as `gbc_controller_select` checks its bytes.
        // SAFETY: the caller's promise.
        let src = unsafe { text_at(text, len, "the program text", SOURCE_CAPACITY)? };
        // SAFETY: the caller's promise.
        let name = unsafe { name_at(name) };
        let module = compile(&name, src, &options(c.program()?.machine()))?;
        select(c, module)
    })
}

/// [`GBC_SOURCE_CAPACITY`] and its name, for [`text_at`].
const SOURCE_CAPACITY: (usize, &str) = (GBC_SOURCE_CAPACITY, "GBC_SOURCE_CAPACITY");

/// The `len` bytes of G-code at `text` (`what` names them in the
/// refusals): null with `len` above 0 is [`GbcStatus::NullPointer`], a
/// `len` above `capacity` (the bound and its constant's name)
/// [`GbcStatus::InvalidArgument`], both before a byte is read; `len` 0 is
/// the empty text, whatever `text` is.
///
/// # Safety
/// `text` is null or readable for `len` bytes, for `'a`.
pub(crate) unsafe fn text_at<'a>(
    text: *const c_char,
    len: usize,
    what: &str,
    (capacity, capacity_name): (usize, &str),
) -> Result<&'a [u8], Failure> {
    if text.is_null() && len > 0 {
        return Err(fail(
            GbcStatus::NullPointer,
            format!("{what} is null while len is not 0"),
        ));
    }
    if len > capacity {
        return Err(fail(
            GbcStatus::InvalidArgument,
            format!("{what} is {len} bytes: at most {capacity_name} ({capacity}) are taken"),
        ));
    }
    if len == 0 {
        return Ok(&[]);
    }
    // SAFETY: non-null (checked) and readable for `len` bytes by the
    // caller's promise.
    Ok(unsafe { core::slice::from_raw_parts(text.cast::<u8>(), len) })
}

/// The program's file name: the host's NUL-terminated string (not UTF-8:
/// each bad sequence U+FFFD), or [`DEFAULT_NAME`] for null or empty.
///
/// # Safety
/// `name` is null or a NUL-terminated string.
unsafe fn name_at(name: *const c_char) -> String {
    if name.is_null() {
        return DEFAULT_NAME.to_string();
    }
    // SAFETY: non-null, and NUL-terminated by the caller's promise.
    let name = unsafe { CStr::from_ptr(name) }.to_string_lossy();
    match name.is_empty() {
        true => DEFAULT_NAME.to_string(),
        false => name.into_owned(),
    }
}

/// `gbcc`'s options for `machine` (`gbcc --machine FILE`): its library
/// folders come with it, the compiler's own chunked compile of a long
/// text is kept.
fn options(machine: &nc::Machine) -> compiler::Options {
    compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    }
}

/// The module of the text `src`, compiled as the file `name` with
/// `opts`, or the first error's diagnostic as the compiler renders it
/// (`gbcc`'s text without colour): its gcc-style header line, then the
/// source line with the place marked and the compiler's note, a few
/// lines in all, as [`GbcStatus::CompileError`].
pub(crate) fn compile(
    name: &str,
    src: &[u8],
    opts: &compiler::Options,
) -> Result<isa::Module, Failure> {
    let out = compiler::compile(name, src, opts);
    if let Some(module) = out.module {
        return Ok(module);
    }
    let first = out
        .diags
        .iter()
        .find(|(_, d)| d.is_error())
        .and_then(|(f, d)| Some(out.files.get(*f)?.render(d).trim_end().to_string()));
    Err(fail(
        GbcStatus::CompileError,
        first.unwrap_or_else(|| format!("{name} does not compile")),
    ))
}
