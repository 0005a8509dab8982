//! Nose-radius compensation geometry (comp.md §4, §5, §9) that needs no
//! queue: the imaginary tip, the end of a start-up move, the corner
//! points where two compensated elements join, and the legs of a G90/G94
//! cycle under G41/G42. The executor's queue (`exec::comp`) holds the
//! elements and asks these functions where each one starts and ends.

use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::plan::elem::{cross, dot, left, scale, tangent_at, unit};
use crate::plan::offset::{curve, meet, normal, over, Curve, Tool};

/// v(T): the imaginary tip seen from the nose centre, per unit radius
/// (Fanuc numbering: 1–4 the quadrants counter-clockwise from (+Z, +X),
/// 5–8 the axis directions from +Z; 0, 9 and anything else the centre).
pub fn tip_vector(t: f64) -> Pt {
    // (Δr, Δz): `Pt::new` takes r first.
    let (dr, dz) = match crate::block::round_half_away(t) as i64 {
        1 => (1.0, 1.0),
        2 => (1.0, -1.0),
        3 => (-1.0, -1.0),
        4 => (-1.0, 1.0),
        5 => (0.0, 1.0),
        6 => (1.0, 0.0),
        7 => (0.0, -1.0),
        8 => (-1.0, 0.0),
        _ => (0.0, 0.0),
    };
    Pt::new(dr, dz)
}

/// Where the start-up move `e` ends when the next element starts in
/// direction `t2` (`None`: no compensated element follows, so the
/// start-up's own direction counts): C = Q + R·n(t2).
pub fn startup_end(e: &Element, t2: Option<Pt>, tool: &Tool) -> Pt {
    let q = e.end();
    let t = t2.or_else(|| tangent_at(e, q));
    q.add(normal(t, tool))
}

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

/// Where element 1 ends and element 2 starts at their common point Q, and
/// the arc between them at an outside corner (comp.md §5 table).
pub fn corner_points(
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

/// Unit directions along r (X) and along Z.
const ALONG_R: Pt = Pt::new(1.0, 0.0);
const ALONG_Z: Pt = Pt::new(0.0, 1.0);

/// The line `from` → `to` moved R along its unit normal towards `a`, then
/// by v(T)·R; `None` for a zero-length line, which has no normal.
fn moved(from: Pt, to: Pt, a: Pt, tool: &Tool) -> Option<Curve> {
    let t = unit(to.sub(from))?;
    let n = left(t);
    let towards_a = if dot(a.sub(from), n) < 0.0 { -1.0 } else { 1.0 };
    let shift = scale(n, towards_a * tool.radius).add(tool.tip);
    Some(Curve::Line {
        p: from.add(shift),
        t,
    })
}

fn cross_point(a: &Curve, b: &Curve) -> Option<Pt> {
    meet(a, b).first().copied()
}

/// Moves the ends of a G90 (`facing` false) or G94 cycle's legs 1–3
/// (cut start S, cut end E, retract end F; A the start point) when
/// G41/G42 is in force: leg 1 to moved ℓ2 on its own line, leg 2 to the
/// meeting of moved ℓ2 and ℓ3, leg 3 to moved ℓ3 on the line of leg 4.
/// Leg 4 returns to A uncompensated. A cut or
/// retract of zero length has no side: the cycle then runs as programmed.
pub fn turning_cycle(facing: bool, a: Pt, legs: [&mut Pt; 3], tool: &Tool) {
    let [s, e, f] = legs;
    let (Some(cut), Some(back)) = (moved(*s, *e, a, tool), moved(*e, *f, a, tool)) else {
        return;
    };
    // G90: leg 1 runs along X at Z = zA, leg 4 along Z at X = xA; G94
    // the other way round.
    let (leg1, leg4) = if facing {
        (ALONG_Z, ALONG_R)
    } else {
        (ALONG_R, ALONG_Z)
    };
    let line1 = Curve::Line { p: a, t: leg1 };
    let line4 = Curve::Line { p: a, t: leg4 };
    let ends = (
        cross_point(&cut, &line1),
        cross_point(&cut, &back),
        cross_point(&back, &line4),
    );
    if let (Some(p1), Some(p2), Some(p3)) = ends {
        (*s, *e, *f) = (p1, p2, p3);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(from: Pt, to: Pt) -> Element {
        Element::Line { from, to }
    }

    fn tool(side: f64) -> Tool {
        Tool {
            side,
            radius: 1.0,
            tip: Pt::ZERO,
        }
    }

    fn near(a: Pt, b: Pt) -> bool {
        a.dist(b) < 1e-12
    }

    #[test]
    fn a_shoulder_is_an_inside_corner_for_g42_and_outside_for_g41() {
        // Turning along -Z at r 10, then facing out along +X at z -10.
        // Looking along the travel, G42 keeps the nose on the right: +r
        // on the first element, +z on the second; the path turns right,
        // towards the nose, so the offset lines r 11 and z -9 meet.
        let (e1, e2) = (
            line(Pt::new(10.0, 0.0), Pt::new(10.0, -10.0)),
            line(Pt::new(10.0, -10.0), Pt::new(20.0, -10.0)),
        );
        let (a, b, arc) = corner_points(&e1, &e2, &tool(-1.0)).unwrap();
        assert!(near(a, Pt::new(11.0, -9.0)) && near(b, a) && arc.is_none());
        // G41: the nose on the left (r 9, then z -11), an outside corner
        // rounded clockwise about Q from 6 o'clock to 9 o'clock.
        let (a, b, arc) = corner_points(&e1, &e2, &tool(1.0)).unwrap();
        assert!(near(a, Pt::new(9.0, -10.0)) && near(b, Pt::new(10.0, -11.0)));
        assert_eq!(
            arc,
            Some(Element::Arc {
                from: a,
                to: b,
                centre: Pt::new(10.0, -10.0),
                cw: true,
            })
        );
    }

    #[test]
    fn tips_are_the_fanuc_quadrants() {
        assert_eq!(tip_vector(3.0), Pt::new(-1.0, -1.0));
        assert_eq!(tip_vector(6.0), Pt::new(1.0, 0.0));
        assert_eq!(tip_vector(9.0), Pt::ZERO);
    }
}
