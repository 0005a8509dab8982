//! Ending a compensated element on its own normal (comp.md §6): before a
//! cancel move, a change of side, a suspension or the end of the run.

use super::{Leg, Role};
use crate::base::error::NcError;
use crate::base::geom::Element;
use crate::plan::offset::{check_forward, over};

/// `e` (leg `l`) ends at Q + R·n(t), t its own direction at its end; a
/// start-up that nothing compensated follows uses its own direction.
/// E4036 when the element's compensated part would run backwards.
pub fn close(e: &Element, l: &mut Leg) -> Result<(), NcError> {
    let tool = l.tool;
    match l.role {
        Role::Start => l.end = Some(crate::plan::comp::startup_end(e, None, &tool)),
        Role::Body => {
            let end = over(e, e.end(), &tool);
            l.end = Some(end);
            let start = l.start.unwrap_or_else(|| over(e, e.start(), &tool));
            check_forward(e, start, end)?;
        }
        Role::Zero => {}
    }
    Ok(())
}
