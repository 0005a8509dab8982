//! Tool setting by a measured cut: the operator cuts a diameter (or
//! faces) with a tool, measures the part and enters the measurement on
//! that tool's offset, as on a GSK980TDi's trial-cut tool setting or a
//! Fanuc's "measured value direct input". The control works out the
//! offset's geometry from where the slide stands, so that a program cuts
//! the measured size with it.
//!
//! The slide stands at the tool's tip plus its offset (geometry and
//! wear), and the tip at the measured point plus the work origin a run
//! starts in (G54, shifted by EXOFS). So the geometry is the slide's
//! position less the work origin, the measurement and the wear, whatever
//! offset moved the slide there.

use super::Controller;
use crate::interpolate::{Engine, RunState};
use crate::plc::Plc;
use nc::machine::Xz;
use nc::machine_check::BadKey;
use nc::offset_page::{OffsetLengths, WorkOffset};
use nc::Machine;

/// The axis a measurement was taken on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasuredAxis {
    /// A diameter (X on the diameter, in work coordinates).
    X,
    /// A face's Z, in work coordinates.
    Z,
}

/// Why [`Controller::measure_tool_offset`] changed nothing.
#[derive(Debug, Clone, PartialEq)]
pub enum MeasureRefused {
    /// The axes move, a program stands stopped or in an alarm, or a
    /// plane of polar or cylindrical interpolation is in force: measure
    /// with the machine idle or at the program's end.
    NotStanding,
    /// The offset number is outside the table, or the new geometry out
    /// of the page's range.
    Page(BadKey),
}

impl core::fmt::Display for MeasureRefused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MeasureRefused::NotStanding => write!(
                f,
                "a measurement needs the axes standing, idle or at the program's end"
            ),
            MeasureRefused::Page(e) => write!(f, "{}: {}", e.key, e.msg),
        }
    }
}

impl core::error::Error for MeasureRefused {}

impl<P: Plc> Controller<P> {
    /// Tool setting by a measured cut (docs/embedding.md, "The offset
    /// page"): after cutting with the tool of offset `number`, the
    /// operator measured `measured`, the diameter (X) or the face (Z) in
    /// the work system a run starts in (G54 shifted by EXOFS). The
    /// offset's geometry on that axis becomes the slide's position less
    /// that work origin, the measurement and the wear, on the page, for
    /// every run from now on. Gives the offset's new lengths.
    pub fn measure_tool_offset(
        &mut self,
        number: u32,
        axis: MeasuredAxis,
        measured: f64,
    ) -> Result<OffsetLengths, MeasureRefused> {
        let slide = standing_point(&self.engine).ok_or(MeasureRefused::NotStanding)?;
        let l = set_measured(&mut self.ra.machine, number, axis, measured, slide)?;
        self.apply_page();
        Ok(l)
    }
}

/// The machine set point where the axes stand idle or at the program's
/// end, outside polar and cylindrical interpolation: where a
/// measurement may be taken.
pub(crate) fn standing_point<P: Plc>(engine: &Engine<P>) -> Option<Xz> {
    let standing = matches!(engine.state(), RunState::Idle | RunState::Ended);
    standing.then(|| engine.machine_point()).flatten()
}

/// Sets offset `number`'s geometry on `axis` on the page of `machine`
/// from a measurement taken with the slide at `slide`; its new lengths.
pub(crate) fn set_measured(
    machine: &mut Machine,
    number: u32,
    axis: MeasuredAxis,
    measured: f64,
    slide: Xz,
) -> Result<OffsetLengths, MeasureRefused> {
    let mut l = machine.offset_row(number).map_err(MeasureRefused::Page)?;
    let (shift, g54) = (
        machine.work_offset_of(WorkOffset::External),
        machine.work_offset_of(WorkOffset::G54),
    );
    match axis {
        MeasuredAxis::X => l.x = slide.x - shift.x - g54.x - measured - l.wear_x,
        MeasuredAxis::Z => l.z = slide.z - shift.z - g54.z - measured - l.wear_z,
    }
    machine
        .set_offset_lengths(number, l)
        .map_err(MeasureRefused::Page)?;
    Ok(l)
}
