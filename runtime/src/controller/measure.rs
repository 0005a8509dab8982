//! Tool setting by a measured cut: the operator cuts a diameter (or
//! faces) with the tool whose offset is in force, measures the part and
//! enters the measurement, as on a GSK980TDi's trial-cut tool setting or
//! a Fanuc's "measured value direct input". The control moves the
//! offset's geometry by what the programmed point and the measurement
//! differ, so that the same program cuts the measured size next time.
//!
//! The slide stands at the programmed point plus the work origin plus the
//! offset in force (geometry and wear); the tool's tip, at the measured
//! point plus the work origin plus its true offset. So the true offset is
//! the one in force plus the programmed point less the measurement, and
//! the wear stays as it was.

use super::Controller;
use crate::interpolate::RunState;
use crate::plc::Plc;
use nc::machine_check::BadKey;
use nc::offset_page::OffsetLengths;

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
    /// No tool offset is in force (no T word yet, T..00, or a reset
    /// since): call the tool with its offset (`T0101`) and cut first.
    NoOffset,
    /// The new geometry is out of the offset page's range.
    Page(BadKey),
}

impl core::fmt::Display for MeasureRefused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MeasureRefused::NotStanding => write!(
                f,
                "a measurement needs the axes standing, idle or at the program's end"
            ),
            MeasureRefused::NoOffset => write!(
                f,
                "no tool offset is in force: call the tool with its offset (T0101) and cut first"
            ),
            MeasureRefused::Page(e) => write!(f, "{}: {}", e.key, e.msg),
        }
    }
}

impl core::error::Error for MeasureRefused {}

impl<P: Plc> Controller<P> {
    /// Tool setting by a measured cut (docs/embedding.md, "The offset
    /// page"): `measured` is the diameter (X) or face (Z) the operator
    /// measured, in work coordinates, after cutting with the tool whose
    /// offset is in force (the T word the last block left). That
    /// offset's geometry moves by the programmed point less the
    /// measurement, on the page, for every run from now on; the wear
    /// stays. Gives the offset's number and its new lengths.
    pub fn measure_tool_offset(
        &mut self,
        axis: MeasuredAxis,
        measured: f64,
    ) -> Result<(u32, OffsetLengths), MeasureRefused> {
        let standing = matches!(self.engine.state(), RunState::Idle | RunState::Ended);
        let at = self.engine.work_point();
        let (true, Some(at)) = (standing, at) else {
            return Err(MeasureRefused::NotStanding);
        };
        let number = self.engine.active_codes().t % 100;
        let Some(mut lengths) = self.tool_offset(number).filter(|_| number > 0) else {
            return Err(MeasureRefused::NoOffset);
        };
        match axis {
            MeasuredAxis::X => lengths.x += at.x - measured,
            MeasuredAxis::Z => lengths.z += at.z - measured,
        }
        self.set_tool_offset(number, lengths)
            .map_err(MeasureRefused::Page)?;
        Ok((number, lengths))
    }
}
