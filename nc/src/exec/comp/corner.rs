//! Joining two compensated elements at their common point Q (comp.md §4,
//! §5): tangent, inside and outside corners.

use super::{startup, Leg, Role, Tool};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::plan::elem::{cross, dot, tangent_at};
use crate::plan::offset::{check_arc, check_forward, curve, meet, normal, over};

/// Directions closer than this (cross product of unit vectors) are
/// parallel (comp.md §5).
const PARALLEL: f64 = 1e-9;

/// The kind of corner at a join, looking along the travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Tangent,
    Inside,
    Outside,
}

/// Classifies the turn from direction `t1` into `t2` for side `side`
/// (+1 G41, −1 G42): inside when the path turns towards the tool's far
/// side (G41 turning left, G42 turning right); a reversal is outside.
pub fn kind(t1: Pt, t2: Pt, side: f64) -> Kind {
    let turn = cross(t1, t2);
    if turn.abs() < PARALLEL {
        return if dot(t1, t2) > 0.0 {
            Kind::Tangent
        } else {
            Kind::Outside
        };
    }
    if side * turn > 0.0 {
        Kind::Inside
    } else {
        Kind::Outside
    }
}

/// Joins element `e1` (leg `l1`, a start-up or an element) with the next
/// element `e2` (leg `l2`): sets where `l1` ends, where `l2` starts and
/// the arc round an outside corner. E4036 when the offset curves of an
/// inside corner do not meet, or `e1`'s compensated part runs backwards.
pub fn join(e1: &Element, l1: &mut Leg, e2: &Element, l2: &mut Leg) -> Result<(), NcError> {
    let tool = l1.tool;
    // Also a rounding that an L/D word inserted must fit the tool.
    check_arc(e2, &tool)?;
    if l1.role != Role::Body {
        let c = startup::end(e1, tangent_at(e2, e2.start()), &tool);
        (l1.end, l2.start) = (Some(c), Some(c));
        return Ok(());
    }
    let (a, b, arc) = corner_points(e1, e2, &tool)?;
    (l1.end, l2.start, l2.corner) = (Some(a), Some(b), arc);
    let start = l1.start.unwrap_or_else(|| over(e1, e1.start(), &tool));
    check_forward(e1, start, a)
}

/// Where element 1 ends and element 2 starts at their common point Q, and
/// the arc between them at an outside corner (comp.md §5 table).
fn corner_points(
    e1: &Element,
    e2: &Element,
    tool: &Tool,
) -> Result<(Pt, Pt, Option<Element>), NcError> {
    let q = e1.end();
    let (Some(t1), Some(t2)) = (tangent_at(e1, q), tangent_at(e2, e2.start())) else {
        // No direction at Q (an element used up by a corner word): the
        // element ends on its own normal and the next starts there.
        let a = over(e1, q, tool);
        return Ok((a, a, None));
    };
    let (a, b) = (q.add(normal(Some(t1), tool)), q.add(normal(Some(t2), tool)));
    Ok(match kind(t1, t2, tool.side) {
        Kind::Tangent => (a, a, None),
        Kind::Inside => {
            let p = inside_point(e1, e2, q, tool)?;
            (p, p, None)
        }
        Kind::Outside => (a, b, outside_arc(q, a, b, tool)),
    })
}

/// The intersection of the two offset curves nearest to Q.
fn inside_point(e1: &Element, e2: &Element, q: Pt, tool: &Tool) -> Result<Pt, NcError> {
    let (c1, c2) = (curve(e1, tool)?, curve(e2, tool)?);
    let nearest = meet(&c1, &c2)
        .into_iter()
        .min_by(|a, b| a.dist(q).total_cmp(&b.dist(q)));
    match nearest {
        Some(p) => Ok(p),
        None => fail(
            Alarm::CompInterference,
            "compensation interference: the offset paths of an inside corner do not meet",
        ),
    }
}

/// The arc about Q from `a` to `b`: clockwise for G41, counter-clockwise
/// for G42 (a reversal is a half circle the same way). None for a zero
/// radius, where it would have no length.
fn outside_arc(q: Pt, a: Pt, b: Pt, tool: &Tool) -> Option<Element> {
    (tool.radius > crate::plan::elem::EPS_LEN).then_some(Element::Arc {
        from: a,
        to: b,
        centre: q,
        cw: tool.side > 0.0,
    })
}
