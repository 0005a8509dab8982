//! The tool data a start-up reads (comp.md §1, §3).

use alloc::format;

use super::Tool;
use crate::base::error::{fail, Alarm, NcError};
use crate::exec::Nc;
use crate::plan::comp::tip_vector;
use crate::plan::elem::scale;

/// The radius R (geometry + wear) and tip of the active offset, on
/// `side`. Offset 0, or a number past the table (88, 99), has none.
/// E4036 for a negative radius (wear larger than the geometry).
pub fn read_tool(nc: &Nc, side: f64) -> Result<Tool, NcError> {
    let i = (nc.st.offset as usize).checked_sub(1);
    let geom = i.and_then(|i| nc.st.geom.get(i));
    let wear = i.and_then(|i| nc.st.wear.get(i));
    let radius = geom.map_or(0.0, |g| g[2]) + wear.map_or(0.0, |w| w[2]);
    // In polar and cylindrical interpolation the tool is taken at its
    // centre: tip direction 0 (dialect.md §4.6).
    let tip = match nc.st.plane {
        Some(_) => 0.0,
        None => wear.map_or(0.0, |w| w[3]),
    };
    if radius.is_nan() || radius < 0.0 {
        return fail(
            Alarm::CompInterference,
            format!(
                "the nose radius of offset {} is negative ({radius:.4}): the wear is larger than the geometry",
                nc.st.offset
            ),
        );
    }
    Ok(Tool {
        side,
        radius,
        tip: scale(tip_vector(tip), radius),
    })
}
