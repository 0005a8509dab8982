//! Selecting another program (`runtime::Controller::select_program`): the
//! operator picks the next program while the machine stands idle; the
//! axes, the offset page, #500–#999 and the panel stay.

use crate::host::HostPlc;
use crate::{fail, module_at, with_ctl, GbcController, GbcStatus, Outcome};
use runtime::{Controller, SelectRefused};

/// Replaces the loaded program with another `.gbc` (`len` bytes at
/// `gbc`, copied) while the controller is idle: before its first cycle
/// start, or after `gbc_reset` once `gbc_state` gives
/// `GBC_RUN_STATE_IDLE`. The new program starts where the axes stand,
/// with the power-on modes, at the next `gbc_cycle_start`; the offset
/// page, #500–#999, the panel's switches and the JIT setting stay.
/// Without a program loaded, it is `gbc_controller_load`'s
/// [`GbcStatus::NoProgram`].
///
/// Refused, keeping the program loaded: [`GbcStatus::InvalidModule`]
/// (not a valid `.gbc`), [`GbcStatus::MachineMismatch`] (compiled for
/// other compile-time keys), [`GbcStatus::NotIdle`].
/// `gbc_controller_select_source` selects G-code text, compiled here.
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
        select(c.run()?, module)
    })
}

/// Puts the verified `module` in the loaded program's place: what
/// `gbc_controller_select` and `gbc_controller_select_source` do once
/// they have one. [`GbcStatus::NotIdle`] or
/// [`GbcStatus::MachineMismatch`], keeping the program loaded.
pub(crate) fn select(r: &mut Controller<HostPlc>, module: isa::Module) -> Outcome {
    r.select_program(module).map_err(|e| match e {
        SelectRefused::NotIdle => fail(
            GbcStatus::NotIdle,
            "another program is selected while no program runs: gbc_reset first, \
             and wait for GBC_RUN_STATE_IDLE",
        ),
        SelectRefused::Machine(_) => fail(GbcStatus::MachineMismatch, e.to_string()),
    })
}
