//! MDI (`runtime::Controller::mdi`): blocks the operator types at the
//! panel — `M03 S500`, `T0303`, `G00 X80 Z20` — compiled here for the
//! controller's machine and run in the program's place while the machine
//! stands idle; when they end the program is back.

use crate::source::{compile, text_at};
use crate::{fail, put, with_ctl, GbcController, GbcStatus};
use core::ffi::c_char;
use runtime::SelectRefused;

/// The most bytes of text `gbc_mdi` takes: MDI is typed by hand, and
/// the bound keeps the compiler's memory bounded too.
pub const GBC_MDI_CAPACITY: usize = 1 << 20;

/// [`GBC_MDI_CAPACITY`] and its name, for `text_at`.
const MDI_CAPACITY: (usize, &str) = (GBC_MDI_CAPACITY, "GBC_MDI_CAPACITY");

/// The name the MDI text is compiled under: `gbc_last_error`'s
/// diagnostics, a `GbcAlarm`'s file and `gbc_file_name` give it.
const SOURCE: &str = "MDI";

/// Compiles the blocks the operator typed — `len` bytes of G-code at
/// `text`, one or more blocks (no NUL needed, a final newline neither;
/// read during the call only) — for the controller's machine (with the
/// offset page as it stands) and hands them over while the controller is
/// idle: before the program's first cycle start, or after `gbc_reset`
/// once `gbc_state` gives `GBC_RUN_STATE_IDLE`. They take the program's
/// place where the axes stand, with the power-on modes; the next
/// `gbc_cycle_start` runs them, with every rule of a run (limits,
/// alarms, which name the file "MDI" and its line; tool life). When they
/// end the controller is idle at once — no reset: the spindle keeps
/// turning and the coolant stays as the blocks left them — and the
/// program is back at its start, where the axes stand, for the next
/// cycle start (`gbc_in_mdi` turns false at the `gbc_run_ahead` after
/// the end). A `gbc_reset` during them ends them (the spindle stops) and
/// brings the program back; so do a program restart and
/// `gbc_controller_select`. MDI given again before a cycle start replaces
/// the blocks given before. The program that comes back starts with the
/// power-on modes: a `G99` or `T0303` given in MDI does not carry into
/// it. An empty text (`len` 0, `text` then may be null) is blocks that do
/// nothing, as the compiler takes it.
///
/// The statuses, each with `gbc_last_error`'s text saying why; a refusal
/// changes nothing (the program, or the MDI blocks given before, stay):
/// - `text` null while `len` is not 0: [`GbcStatus::NullPointer`];
/// - `len` above [`GBC_MDI_CAPACITY`]: [`GbcStatus::InvalidArgument`];
/// - no program loaded: [`GbcStatus::NoProgram`] (MDI takes the place of
///   one: load it first);
/// - the text does not compile: [`GbcStatus::CompileError`], with the
///   compiler's diagnostic of its first error as `gbcc` prints it
///   without colour: a first line `MDI:line:column: error[Ennnn]:
///   message`, then a few lines with the source and the place marked (a
///   host showing one line takes the text up to the first newline).
///   Warnings do not refuse. A call (`M98 P1234`) of a program that
///   neither the text nor the machine file's library folders
///   (`macro.library_dirs`) hold is an error. The text is compiled
///   before the state is looked at, so it is this status even while a
///   program runs;
/// - a program runs, stands stopped, ended or in an alarm, or a manual
///   move or a reset runs: [`GbcStatus::NotIdle`];
/// - blocks for another machine configuration would be
///   [`GbcStatus::MachineMismatch`], as for `gbc_controller_select`;
///   compiled for the controller's own machine, they never are.
///
/// # Safety
/// `text` is null or readable for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn gbc_mdi(
    controller: GbcController,
    text: *const c_char,
    len: usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        // The arguments first, after the handle and before the program,
        // as `gbc_restart_from` checks them.
        // SAFETY: the caller's promise.
        let src = unsafe { text_at(text, len, "the MDI text", MDI_CAPACITY)? };
        let mut p = c.program()?;
        let blocks = compile(SOURCE, src, &options(p.machine()))?;
        p.mdi(blocks).map_err(|e| match e {
            SelectRefused::NotIdle => fail(
                GbcStatus::NotIdle,
                "MDI is taken only while the machine is idle: gbc_reset first, and wait \
                 for GBC_RUN_STATE_IDLE",
            ),
            SelectRefused::Machine(_) => fail(GbcStatus::MachineMismatch, e.to_string()),
        })
    })
}

/// Whether MDI blocks are loaded or running, to `*out`: true from a
/// `gbc_mdi` taken until the `gbc_run_ahead` that sees their end (or a
/// reset, restart or `gbc_controller_select` that ends them); the program
/// is back when it turns false. False without a program.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_in_mdi(controller: GbcController, out: *mut bool) -> GbcStatus {
    with_ctl(controller, |c| {
        let on = c.program().is_ok_and(|p| p.in_mdi());
        // SAFETY: the caller's promise.
        unsafe { put(out, on) }
    })
}

/// `compiler::compile`'s options for MDI blocks on `machine`.
fn options(machine: &nc::Machine) -> compiler::Options {
    compiler::Options {
        machine: machine.clone(),
        // Whole, not a chunk at a time: the chunked compile of a long
        // plain text parses it on a second thread, which text typed by
        // hand (at most GBC_MDI_CAPACITY, so its tree stays bounded) has
        // no need of. (A text of 10 000 blocks or more may still be
        // dry-run, and has its trees freed, on threads of their own, as
        // `gbc_controller_load_source` tells.)
        chunk_bytes: usize::MAX,
        ..compiler::Options::default()
    }
}
