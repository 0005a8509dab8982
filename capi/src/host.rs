//! The host's callbacks as the runtime's [`Plc`] and the VM's [`Storage`].

use crate::types::{GbcHost, GbcPlcFunction, GBC_PERSISTENT_COUNT};
use runtime::{Plc, PlcFunction};

/// The PLC of a C host.
pub struct HostPlc(pub GbcHost);

impl Plc for HostPlc {
    fn request(&mut self, f: PlcFunction) {
        if let Some(cb) = self.0.plc_request {
            let call = GbcPlcFunction::from(f);
            // SAFETY: the host promised a callable function and that
            // `user` stays valid while the controller lives (GbcHost).
            unsafe { cb(self.0.user, &call) };
        }
    }

    fn done(&mut self, f: PlcFunction) -> bool {
        match self.0.plc_done {
            Some(cb) => {
                let call = GbcPlcFunction::from(f);
                // SAFETY: as in `request`.
                unsafe { cb(self.0.user, &call) }
            }
            None => true,
        }
    }
}

/// #500–#999 kept by the host.
pub struct HostStorage(pub GbcHost);

// SAFETY: the VM is `Send` so that a Rust host may move it to a thread of
// its own; the C interface never moves a controller between threads
// itself, and the header tells the host that its callbacks run on the
// thread that calls `gbc_run_ahead`.
unsafe impl Send for HostStorage {}

impl vm::Storage for HostStorage {
    fn store(&mut self, persistent: &[f64; GBC_PERSISTENT_COUNT]) -> Result<(), String> {
        let Some(cb) = self.0.vars_store else {
            return Ok(());
        };
        // SAFETY: the array has the documented 500 entries; see HostPlc.
        match unsafe { cb(self.0.user, persistent.as_ptr()) } {
            0 => Ok(()),
            e => Err(format!("the host's vars_store returned {e}")),
        }
    }
}

/// Asks the host for #500–#999 at load; `None` if it refused.
pub fn load_vars(host: &GbcHost) -> Option<[f64; GBC_PERSISTENT_COUNT]> {
    let mut vars = [f64::NAN; GBC_PERSISTENT_COUNT];
    if let Some(cb) = host.vars_load {
        // SAFETY: a writable array of the documented 500 entries.
        if unsafe { cb(host.user, vars.as_mut_ptr()) } != 0 {
            return None;
        }
    }
    Some(vars)
}
