//! The operator's macro-variable page (`runtime::Controller::variable`,
//! `set_variable`): any variable read as the program would read it now,
//! and #500–#999 set, handed to `vars_store` at once.

use crate::{fail, put, with_ctl, GbcController, GbcStatus};
use runtime::VariableRefused;

/// Variable `n` as the program would read it now, to `*value` (NaN:
/// vacant). The controller reads ahead of the motion: it is the value
/// after the blocks read so far. A number the dialect does not have:
/// [`GbcStatus::InvalidArgument`]; no program loaded:
/// [`GbcStatus::NoProgram`].
///
/// # Safety
/// `value` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_variable(
    controller: GbcController,
    n: u32,
    value: *mut f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let v = c
            .program()?
            .variable(n)
            .map_err(|e| fail(GbcStatus::InvalidArgument, format!("#{n}: {}", e.message)))?;
        // SAFETY: the caller's promise.
        unsafe { put(value, v) }
    })
}

/// Sets #500–#999 variable `n` to `value` (NaN: vacant), as the
/// operator's macro-variable page does: kept over resets and program
/// selections, handed to `vars_store` at once, read by the blocks the
/// controller reads from now on. Another number or an infinite value:
/// [`GbcStatus::InvalidArgument`]; `vars_store` failing:
/// [`GbcStatus::HostFailure`] (the value is set nonetheless); no program
/// loaded: [`GbcStatus::NoProgram`].
#[no_mangle]
pub extern "C" fn gbc_set_variable(controller: GbcController, n: u32, value: f64) -> GbcStatus {
    with_ctl(controller, |c| {
        c.program()?.set_variable(n, value).map_err(|e| {
            let status = match e {
                VariableRefused::Storage(_) => GbcStatus::HostFailure,
                VariableRefused::NotPersistent(_) | VariableRefused::NotFinite(_) => {
                    GbcStatus::InvalidArgument
                }
            };
            fail(status, e.to_string())
        })
    })
}
