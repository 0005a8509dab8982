//! Joining two compensated elements at their common point Q (comp.md §4,
//! §5): the legs of the queue take the corner points of `plan::comp`.

use super::{Leg, Role};
use crate::base::error::NcError;
use crate::base::geom::Element;
use crate::plan::comp::{corner_points, startup_end};
use crate::plan::elem::tangent_at;
use crate::plan::offset::{check_forward, over};

/// Joins element `e1` (leg `l1`, a start-up or an element) with the next
/// element `e2` (leg `l2`): sets where `l1` ends, where `l2` starts and
/// the arc round an outside corner. E4036 when the offset curves of an
/// inside corner do not meet, or `e1`'s compensated part runs backwards.
pub fn join(e1: &Element, l1: &mut Leg, e2: &Element, l2: &mut Leg) -> Result<(), NcError> {
    let tool = l1.tool;
    if l1.role != Role::Body {
        let c = startup_end(e1, tangent_at(e2, e2.start()), &tool);
        (l1.end, l2.start) = (Some(c), Some(c));
        return Ok(());
    }
    let (a, b, arc) = corner_points(e1, e2, &tool)?;
    (l1.end, l2.start, l2.corner) = (Some(a), Some(b), arc);
    let start = l1.start.unwrap_or_else(|| over(e1, e1.start(), &tool));
    check_forward(e1, start, a)
}
