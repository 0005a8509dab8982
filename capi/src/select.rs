//! Selecting another program (`runtime::Controller::select_program`): the
//! operator picks the next program while the machine stands idle; the
//! axes, the offset page, #500–#999 and the panel stay.

use crate::restart::LastRestart;
use crate::{fail, module_at, with_ctl, Ctl, GbcController, GbcStatus, Outcome};
use runtime::SelectRefused;

/// Replaces the loaded program with another `.gbc` (`len` bytes at
/// `gbc`, copied) while the controller is idle: before its first cycle
/// start, or after `gbc_reset` once `gbc_state` gives
/// `GBC_RUN_STATE_IDLE`. The new program starts where the axes stand,
/// with the power-on modes, at the next `gbc_cycle_start`; the offset
/// page, #500–#999, the panel's switches and the JIT setting stay.
/// Without a program loaded, it is `gbc_controller_load`'s
/// [`GbcStatus::NoProgram`].
///
/// On the interpreter half of a split controller, in any state: the
/// program takes the loaded one's place at the real-time half's next
/// `gbc_reset` (give it after this call), and runs at the cycle start
/// after it; a program restart asked for before this call is dropped.
///
/// Refused, keeping the program loaded: [`GbcStatus::InvalidModule`]
/// (not a valid `.gbc`), [`GbcStatus::MachineMismatch`] (compiled for
/// other compile-time keys), [`GbcStatus::NotIdle`] (a whole controller
/// only). `gbc_controller_select_source` selects G-code text, compiled
/// here.
///
/// # Safety
/// `gbc` is null or points at `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn gbc_controller_select(
    controller: GbcController,
    gbc: *const u8,
    len: usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        // SAFETY: the caller's promise.
        let module = unsafe { module_at(gbc, len)? };
        select(c, module)
    })
}

/// Puts the verified `module` in the loaded program's place (on a split
/// controller, at its next reset): what `gbc_controller_select` and
/// `gbc_controller_select_source` do once they have one.
/// [`GbcStatus::NotIdle`] or [`GbcStatus::MachineMismatch`], keeping the
/// program loaded.
pub(crate) fn select(c: &mut Ctl, module: isa::Module) -> Outcome {
    c.program()?.select_program(module).map_err(|e| match e {
        SelectRefused::NotIdle => fail(
            GbcStatus::NotIdle,
            "another program is selected while no program runs: gbc_reset first, \
             and wait for GBC_RUN_STATE_IDLE",
        ),
        SelectRefused::Machine(_) => fail(GbcStatus::MachineMismatch, e.to_string()),
    })?;
    // A restart waiting for the reset was asked for the program replaced.
    if matches!(c.restart, LastRestart::Pending) {
        c.restart = LastRestart::None;
    }
    Ok(())
}
