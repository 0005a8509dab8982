//! The offset page (`runtime::Controller::set_tool_offset`,
//! `set_work_offset`): the tool offsets' lengths and the work offsets an
//! operator edits between runs, as a control's offset screens do.
//!
//! Before a program is loaded the page is the controller's copy of the
//! machine, which the program loaded later starts from (as the panel's
//! switches are kept for it); once one is loaded, that program's
//! controller has it.

use crate::{fail, put, put_xz, with_ctl, Failure, GbcController, GbcStatus};
use crate::{GBC_AXIS_X, GBC_AXIS_Z};
use runtime::{BadKey, MeasureRefused, MeasuredAxis, OffsetLengths, WorkOffset, Xz};

/// `which` of `gbc_work_offset`/`gbc_set_work_offset`: the external work
/// offset (EXOFS, #5201/#5202), which shifts every work system.
pub const GBC_WORK_OFFSET_EXTERNAL: u32 = 0;
/// `which` of a work offset: G54 (#5221/#5222).
pub const GBC_WORK_OFFSET_G54: u32 = 1;
/// `which` of a work offset: G55 (#5241/#5242).
pub const GBC_WORK_OFFSET_G55: u32 = 2;
/// `which` of a work offset: G56 (#5261/#5262).
pub const GBC_WORK_OFFSET_G56: u32 = 3;
/// `which` of a work offset: G57 (#5281/#5282).
pub const GBC_WORK_OFFSET_G57: u32 = 4;
/// `which` of a work offset: G58 (#5301/#5302).
pub const GBC_WORK_OFFSET_G58: u32 = 5;
/// `which` of a work offset: G59 (#5321/#5322).
pub const GBC_WORK_OFFSET_G59: u32 = 6;

/// The lengths of one tool offset on the offset page, mm, X on the
/// diameter (#2701, #2801, #2001, #2101 for offset 1). The nose radius and
/// tip direction are not here: they are compiled into the program (change
/// them in the machine file and compile again).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcOffsetLengths {
    /// Geometry along X (diameter).
    pub x: f64,
    /// Geometry along Z.
    pub z: f64,
    /// Wear along X (diameter): −0.04 when the part came out 0.04 large.
    pub wear_x: f64,
    /// Wear along Z.
    pub wear_z: f64,
}

impl From<OffsetLengths> for GbcOffsetLengths {
    fn from(l: OffsetLengths) -> GbcOffsetLengths {
        GbcOffsetLengths {
            x: l.x,
            z: l.z,
            wear_x: l.wear_x,
            wear_z: l.wear_z,
        }
    }
}

impl From<GbcOffsetLengths> for OffsetLengths {
    fn from(l: GbcOffsetLengths) -> OffsetLengths {
        OffsetLengths {
            x: l.x,
            z: l.z,
            wear_x: l.wear_x,
            wear_z: l.wear_z,
        }
    }
}

/// The lengths of tool offset `number` (1 to the machine's
/// `tools.offsets`, 32 on the reference machine) as the runs start with
/// them: the offset page's values, not a program's own writes (`#2001 =
/// …`, which last for its run). Another number:
/// [`GbcStatus::InvalidArgument`].
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_tool_offset(
    controller: GbcController,
    number: u32,
    out: *mut GbcOffsetLengths,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if out.is_null() {
            return Err(fail(GbcStatus::NullPointer, "the output pointer is null"));
        }
        let lengths = match c.program() {
            Ok(p) => p.tool_offset(number),
            Err(_) => c.machine.offset_lengths(number),
        };
        let Some(lengths) = lengths else {
            return Err(fail(
                GbcStatus::InvalidArgument,
                format!(
                    "tool offset {number} is outside the table: offsets are 1 … {} \
                     (tools.offsets)",
                    c.machine.tools.offsets
                ),
            ));
        };
        // SAFETY: checked non-null; the caller's promise.
        unsafe { put(out, lengths.into()) }
    })
}

/// Sets the lengths of tool offset `number` on the offset page (the
/// operator corrects a wear): they hold for every run after the edit —
/// at once while the controller is idle (a program loaded but not
/// started starts afresh with them), else from the next `gbc_reset` (a
/// running program keeps the values it started with). Before a program
/// is loaded they are kept for it. A program's own writes (`#2001 = …`)
/// last for its run only. The nose radius and tip stay.
///
/// Refused with [`GbcStatus::InvalidArgument`], changing nothing, for a
/// number outside 1 … `tools.offsets` or a value that is not finite or
/// beyond ±10⁶ mm (`gbc_last_error` names the machine-file key and
/// why); a null `lengths` is [`GbcStatus::NullPointer`].
///
/// # Safety
/// `lengths` is null or readable.
#[no_mangle]
pub unsafe extern "C" fn gbc_set_tool_offset(
    controller: GbcController,
    number: u32,
    lengths: *const GbcOffsetLengths,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if lengths.is_null() {
            return Err(fail(GbcStatus::NullPointer, "the input pointer is null"));
        }
        // SAFETY: non-null and readable by the caller's promise.
        let l = OffsetLengths::from(unsafe { lengths.read() });
        let r = match c.program() {
            Ok(mut p) => p.set_tool_offset(number, l),
            Err(_) => c.machine.set_offset_lengths(number, l),
        };
        r.map_err(|e| refused(&format!("tool offset {number}"), e))
    })
}

/// Work offset `which` (a `GBC_WORK_OFFSET_*`) as the runs start with it,
/// mm (X on the diameter), to `*x` and `*z` (both required). Another
/// `which`: [`GbcStatus::InvalidArgument`].
///
/// # Safety
/// `x` and `z` are null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_work_offset(
    controller: GbcController,
    which: u32,
    x: *mut f64,
    z: *mut f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        // (A null pointer is told before a bad `which`.)
        if x.is_null() || z.is_null() {
            return Err(fail(GbcStatus::NullPointer, "an output pointer is null"));
        }
        let w = work_offset(which)?;
        let at = match c.program() {
            Ok(p) => p.work_offset(w),
            Err(_) => c.machine.work_offset_of(w),
        };
        // SAFETY: the caller's promise.
        unsafe { put_xz(x, z, at) }
    })
}

/// Sets work offset `which` (a `GBC_WORK_OFFSET_*`) to `x`, `z` (mm, X on
/// the diameter: the operator touches off a work zero); it holds for the
/// runs after the edit as `gbc_set_tool_offset`'s lengths do. Refused
/// with [`GbcStatus::InvalidArgument`], changing nothing, for another
/// `which` or a value that is not finite or beyond ±10⁶ mm
/// (`gbc_last_error` says which and why).
#[no_mangle]
pub extern "C" fn gbc_set_work_offset(
    controller: GbcController,
    which: u32,
    x: f64,
    z: f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let w = work_offset(which)?;
        let at = Xz { x, z };
        let r = match c.program() {
            Ok(mut p) => p.set_work_offset(w, at),
            Err(_) => c.machine.set_work_offset(w, at),
        };
        r.map_err(|e| refused(&format!("work offset {w:?}"), e))
    })
}

/// The work offset a `GBC_WORK_OFFSET_*` names; any other number C
/// passes is refused, never cast.
fn work_offset(which: u32) -> Result<WorkOffset, Failure> {
    Ok(match which {
        GBC_WORK_OFFSET_EXTERNAL => WorkOffset::External,
        GBC_WORK_OFFSET_G54 => WorkOffset::G54,
        GBC_WORK_OFFSET_G55 => WorkOffset::G55,
        GBC_WORK_OFFSET_G56 => WorkOffset::G56,
        GBC_WORK_OFFSET_G57 => WorkOffset::G57,
        GBC_WORK_OFFSET_G58 => WorkOffset::G58,
        GBC_WORK_OFFSET_G59 => WorkOffset::G59,
        _ => {
            return Err(fail(
                GbcStatus::InvalidArgument,
                "the work offset is not GBC_WORK_OFFSET_EXTERNAL or GBC_WORK_OFFSET_G54 … \
                 GBC_WORK_OFFSET_G59",
            ))
        }
    })
}

/// Tool setting by a measured cut (`runtime::Controller::
/// measure_tool_offset`): after cutting with the tool of offset `number`,
/// the operator measured `measured` mm on `axis` ([`GBC_AXIS_X`]: the
/// diameter, [`GBC_AXIS_Z`]: the face), in the work system a run starts in
/// (G54 shifted by EXOFS). The offset's geometry on that axis becomes the
/// slide's position less that work origin, the measurement and the wear,
/// on the page, for every run from now on; `gbc_tool_offset` reads it.
///
/// On the interpreter half of a split controller, the slide is where the
/// real-time half last published it standing, and the edit holds from
/// its next reset (as every edit of the page there).
///
/// Refused, changing nothing: [`GbcStatus::NoProgram`] before a program
/// is loaded; [`GbcStatus::NotIdle`] unless the axes stand idle or at the
/// program's end (not in polar or cylindrical interpolation);
/// [`GbcStatus::InvalidArgument`] for another axis, a value that is not
/// finite, an offset outside the table or a geometry beyond the page's
/// range (`gbc_last_error` says which).
#[no_mangle]
pub extern "C" fn gbc_measure_tool_offset(
    controller: GbcController,
    number: u32,
    axis: u8,
    measured: f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let axis = match axis {
            GBC_AXIS_X => MeasuredAxis::X,
            GBC_AXIS_Z => MeasuredAxis::Z,
            _ => {
                return Err(fail(
                    GbcStatus::InvalidArgument,
                    "the axis is not GBC_AXIS_X or GBC_AXIS_Z",
                ))
            }
        };
        if !measured.is_finite() {
            return Err(fail(
                GbcStatus::InvalidArgument,
                "the measurement is not finite",
            ));
        }
        c.program()?
            .measure_tool_offset(number, axis, measured)
            .map_err(|e| {
                let status = match &e {
                    MeasureRefused::NotStanding => GbcStatus::NotIdle,
                    MeasureRefused::Page(_) => GbcStatus::InvalidArgument,
                };
                fail(status, e.to_string())
            })?;
        Ok(())
    })
}

/// A refused edit: the machine-file key and why, after what was edited.
pub(crate) fn refused(what: &str, e: BadKey) -> Failure {
    fail(
        GbcStatus::InvalidArgument,
        format!("{what} refused: {}: {}", e.key, e.msg),
    )
}
