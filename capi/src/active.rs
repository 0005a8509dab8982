//! What the operator's screen shows of the block the motion runs: the
//! codes in force (`runtime::Controller::active_codes`: the G code of
//! each modal group, F, S and the T word, as they stood after the block)
//! and the distance its move has to go. The VM reads ahead of the motion;
//! these follow the motion.

use crate::split::with_motion;
use crate::{put, put_xz, GbcController, GbcStatus};
use runtime::ActiveCodes;

/// The number of modal groups in [`GbcActiveCodes::g`].
pub const GBC_ACTIVE_GROUPS: usize = 13;

/// The codes in force for the block the motion runs (or last ran).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcActiveCodes {
    /// The G code in force in each modal group, in tenths (G01 is 10,
    /// G96 is 960, G12.1 is 121), the groups in this order: 1 motion,
    /// 2 speed mode (G96/G97), 3 feed mode (G98/G99), 6 units (G20/G21),
    /// 7 nose-radius compensation, 9 stroke check (G22/G23), 10 drilling
    /// cycle, 12 modal call (G66/G67), 14 work system (G54–G59), 15 exact
    /// stop (G61/G64), 16 plane, 17 polar command (G15/G16), 21 polar
    /// interpolation (G12.1/G13.1).
    pub g: [u16; GBC_ACTIVE_GROUPS],
    /// F as last programmed (mm/min under G98, mm/rev under G99, inch
    /// units under G20); 0 before any.
    pub f: f64,
    /// S as last programmed (rev/min under G97, m/min under G96); 0
    /// before any.
    pub s: f64,
    /// The T word as last programmed, tool × 100 + offset (101: tool 1,
    /// offset 1); 0 before any.
    pub t: u32,
}

impl From<ActiveCodes> for GbcActiveCodes {
    fn from(a: ActiveCodes) -> GbcActiveCodes {
        GbcActiveCodes {
            g: a.g,
            f: a.f,
            s: a.s,
            t: a.t,
        }
    }
}

/// The codes in force for the block whose motion runs, as a control's
/// screen shows them: before the first block and after a reset, those a
/// run starts with (the machine's power-on codes, F, S and T 0), as also
/// before a program is loaded; after a program restart's search, until
/// the cycle start runs its approach, those the run resumes with. A move
/// that waited in the kernel for the next block (nose-radius
/// compensation, a corner word) shows the codes after that block.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_active_codes(
    controller: GbcController,
    out: *mut GbcActiveCodes,
) -> GbcStatus {
    with_motion(controller, |s| {
        let codes = match s.motion {
            Ok(m) => m.engine().active_codes(),
            Err(machine) => ActiveCodes::power_on(machine),
        };
        // SAFETY: the caller's promise.
        unsafe { put(out, GbcActiveCodes::from(codes)) }
    })
}

/// How far the move that runs still has to go, mm, X on the diameter (as
/// positions are shown), to `*x` and `*z` (both required): its end point
/// less the programmed point the axes are at; in polar or cylindrical
/// interpolation, the joints at its end less the joints now. 0 and 0
/// while no program move runs (idle, at a stop or the end, in an alarm,
/// in a dwell or a PLC function, during a reset or a manual move) and
/// before a program is loaded.
///
/// # Safety
/// `x` and `z` are null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_distance_to_go(
    controller: GbcController,
    x: *mut f64,
    z: *mut f64,
) -> GbcStatus {
    with_motion(controller, |s| {
        let d = s.motion.ok().map(|m| m.engine().distance_to_go());
        let d = d.unwrap_or(runtime::Xz { x: 0.0, z: 0.0 });
        // SAFETY: the caller's promise.
        unsafe { put_xz(x, z, d) }
    })
}
