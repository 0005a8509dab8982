//! G90 and G94 under G41/G42 (comp.md §9): the cut and the feed retract
//! are moved towards the start point A, the four legs kept.

use super::startup;
use crate::base::error::NcError;
use crate::base::point::Pt;
use crate::exec::Nc;
use crate::plan::comp;

/// G41/G42 in force: the legs of a G90 or G94 cycle moved by the tool of
/// the active offset (`plan::comp::turning_cycle`). R and T are read now
/// (§1).
pub fn turning_cycle(nc: &Nc, facing: bool, a: Pt, legs: [&mut Pt; 3]) -> Result<(), NcError> {
    let Some(side) = nc.st.modal.comp().side() else {
        return Ok(());
    };
    let tool = startup::read_tool(nc, side)?;
    comp::turning_cycle(facing, a, legs, &tool);
    Ok(())
}
