//! The geometry of chamfer L / rounding D corners between two contour
//! elements (cycles.md §13), as a pure function of the elements.

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use super::elem::{self, circle_circle, cross, dot, left, line_circle, scale, unit, EPS_LEN};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::base::machine::ChamferType;
use crate::base::point::Pt;

/// What a corner word asks for at the end of its element. `word` is the
/// word's address (`base::words::addr`: L, D, ,C or ,R): an error about
/// the corner names it, on the block that carries it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Corner {
    /// `L` or `,C`: a straight chamfer. `ChamferType::II` (№181.0 = 1, the
    /// reference, and always for `,C`): `size` is the straight distance from
    /// the corner to each chamfer point. `ChamferType::I`: `size` is the
    /// length of the chamfer line, the two chamfer points being equally far
    /// from the corner.
    Chamfer {
        size: f64,
        kind: ChamferType,
        word: u8,
    },
    /// `D` or `,R`: an arc of this radius tangent to both elements on the
    /// inside of the turn.
    Round { radius: f64, word: u8 },
}

impl Corner {
    /// The address of the word that asked for it.
    pub fn word(&self) -> u8 {
        match *self {
            Corner::Chamfer { word, .. } | Corner::Round { word, .. } => word,
        }
    }
}

/// Tangents closer than this (cross product of unit vectors) are parallel.
const PARALLEL: f64 = 1e-7;

/// Joins element `e1` and element `e2` at their common point P (the end
/// of `e1`; `e2` must start there) with the corner `c`.
///
/// Returns `(e1 shortened, the inserted element, e2 shortened)`:
/// - a chamfer inserts `Element::Line` T1→T2, where T1 is the point of
///   `e1` and T2 the point of `e2` at the chamfer distance from P (on an
///   arc: where the circle of that radius about P cuts the arc, nearest
///   to P along the arc);
/// - a rounding inserts `Element::Arc` T1→T2 about the centre M that lies
///   at distance D from both elements on the inside of the turn, T1 and T2
///   being the feet of M on the elements; it runs counter-clockwise in the
///   ZX view (`cw: false`) when the path turns left there, clockwise when
///   it turns right.
///
/// The shortened elements keep their line or circle; either may come out
/// of zero length when the corner uses the whole element (the caller
/// decides whether to print it).
///
/// `Ok(None)`: the corner is ignored, silently (W112): the two
/// directions at P are the same (a tangent join, also line into a tangent
/// arc), or one element has zero length and so no direction.
///
/// Errors: E4007 when T1 or T2 would not lie on its element (chamfer or
/// radius too large) or when the path reverses at P (no inside of the turn,
/// no chamfer line), about the corner's word.
pub fn corner(
    e1: &Element,
    e2: &Element,
    c: Corner,
) -> Result<Option<(Element, Element, Element)>, NcError> {
    joined(e1, e2, c).map_err(|e| e.on_addr(c.word()))
}

/// [`corner`] without naming the word.
fn joined(e1: &Element, e2: &Element, c: Corner) -> Result<Option<Joined>, NcError> {
    let p = e1.end();
    if elem::shorter_than(e1, EPS_LEN) || elem::shorter_than(e2, EPS_LEN) {
        return Ok(None);
    }
    let (Some(t1), Some(t2)) = (elem::tangent_at(e1, p), elem::tangent_at(e2, p)) else {
        return Ok(None);
    };
    if cross(t1, t2).abs() < PARALLEL {
        if dot(t1, t2) > 0.0 {
            return Ok(None);
        }
        return fail(
            Alarm::CornerTooLarge,
            "the path reverses at the corner: there is no corner to chamfer or round",
        );
    }
    match c {
        Corner::Chamfer { size, kind, .. } => chamfer(e1, e2, size, kind).map(Some),
        Corner::Round { radius, .. } => round(e1, e2, radius, cross(t1, t2) > 0.0).map(Some),
    }
}

type Joined = (Element, Element, Element);

fn too_large(what: &str, size: f64) -> NcError {
    NcError::new(
        Alarm::CornerTooLarge,
        format!("{what} {size:.4} is too large: the corner point would fall outside an element"),
    )
}

/// The point of `e` at straight distance `d` from P, walking into `e`
/// from its end (`from_end`, for E1) or from its start (E2).
fn reach(e: &Element, d: f64, from_end: bool) -> Option<Pt> {
    let p = if from_end { e.end() } else { e.start() };
    match *e {
        Element::Line { from, to } => {
            if d > from.dist(to) + EPS_LEN {
                return None;
            }
            let t = unit(to.sub(from))?;
            Some(p.add(scale(t, if from_end { -d } else { d })))
        }
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => {
            let rho = from.dist(centre);
            if d > 2.0 * rho + EPS_LEN {
                return None;
            }
            // A chord of length d subtends 2·asin(d / 2ρ).
            let phi = 2.0 * libm::asin((d / (2.0 * rho)).min(1.0));
            if phi > elem::sweep(from, to, centre, cw) + EPS_LEN / rho {
                return None;
            }
            // Back along the arc from its end, forward from its start.
            let ccw = if from_end { cw } else { !cw };
            Some(elem::rotate(p, centre, phi, ccw))
        }
    }
}

/// The largest straight distance from P that `reach` can walk on `e`.
fn reach_limit(e: &Element) -> f64 {
    match *e {
        Element::Line { from, to } => from.dist(to),
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => {
            let rho = from.dist(centre);
            let s = elem::sweep(from, to, centre, cw);
            if s >= core::f64::consts::PI {
                2.0 * rho
            } else {
                2.0 * rho * libm::sin(s / 2.0)
            }
        }
    }
}

fn chamfer(e1: &Element, e2: &Element, size: f64, kind: ChamferType) -> Result<Joined, NcError> {
    let d = match kind {
        ChamferType::II => size,
        ChamferType::I => type_one_distance(e1, e2, size)?,
    };
    let (Some(a), Some(b)) = (reach(e1, d, true), reach(e2, d, false)) else {
        return Err(too_large("chamfer", size));
    };
    Ok((
        elem::with_end(e1, a),
        Element::Line { from: a, to: b },
        elem::with_start(e2, b),
    ))
}

/// Type I: the distance d from P at which the chamfer line T1T2 is `len`
/// long. On two lines d = len / (2·sin(θ/2)); with arcs the chord length
/// is found numerically: the first d (from P outwards) where it reaches
/// `len`, by a scan and then bisection.
fn type_one_distance(e1: &Element, e2: &Element, len: f64) -> Result<f64, NcError> {
    let limit = reach_limit(e1).min(reach_limit(e2));
    let gap = |d: f64| match (reach(e1, d, true), reach(e2, d, false)) {
        (Some(a), Some(b)) => a.dist(b),
        _ => 0.0,
    };
    const STEPS: u32 = 256;
    let mut lo = 0.0;
    for k in 1..=STEPS {
        let hi = limit * f64::from(k) / f64::from(STEPS);
        if gap(hi) >= len {
            let mut hi = hi;
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if gap(mid) >= len {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Ok(hi);
        }
        lo = hi;
    }
    Err(too_large("chamfer", len))
}

/// An element's line or circle moved by `d` to side `side` (+1 left of
/// its direction of travel, −1 right).
enum Offset {
    Line { p: Pt, t: Pt },
    Circle { c: Pt, rad: f64 },
}

fn offset(e: &Element, d: f64, side: f64) -> Result<Offset, NcError> {
    match *e {
        Element::Line { from, to } => {
            let t = unit(to.sub(from)).ok_or_else(|| too_large("corner radius", d))?;
            Ok(Offset::Line {
                p: from.add(scale(left(t), side * d)),
                t,
            })
        }
        Element::Arc {
            from, centre, cw, ..
        } => {
            let rho = from.dist(centre);
            // The centre lies left of the travel on a G03 arc.
            let centre_inside = (side > 0.0) != cw;
            let rad = if centre_inside { rho - d } else { rho + d };
            if rad < EPS_LEN {
                return Err(too_large("corner radius", d));
            }
            Ok(Offset::Circle { c: centre, rad })
        }
    }
}

/// Where two offset curves meet (none, one or two points).
fn meet(a: &Offset, b: &Offset) -> Vec<Pt> {
    match (a, b) {
        (Offset::Line { p: p1, t: t1 }, Offset::Line { p: p2, t: t2 }) => {
            let det = cross(*t1, *t2);
            if det.abs() < 1e-12 {
                return Vec::new();
            }
            let lambda = cross(p2.sub(*p1), *t2) / det;
            vec![p1.add(scale(*t1, lambda))]
        }
        (Offset::Line { p, t }, Offset::Circle { c, rad })
        | (Offset::Circle { c, rad }, Offset::Line { p, t }) => line_circle(*p, *t, *c, *rad),
        (Offset::Circle { c: c1, rad: r1 }, Offset::Circle { c: c2, rad: r2 }) => {
            circle_circle(*c1, *r1, *c2, *r2)
        }
    }
}

/// The foot of `m` on the line or circle of `e`.
fn foot(e: &Element, m: Pt) -> Option<Pt> {
    match *e {
        Element::Line { from, to } => {
            let t = unit(to.sub(from))?;
            Some(from.add(scale(t, dot(m.sub(from), t))))
        }
        Element::Arc { from, centre, .. } => {
            let u = unit(m.sub(centre))?;
            Some(centre.add(scale(u, from.dist(centre))))
        }
    }
}

/// A fillet about `m` from `a` to `b` that runs on from `e1` at `a` and
/// into `e2` at `b` in the same direction as they travel.
fn fillet_fits(e1: &Element, e2: &Element, m: Pt, a: Pt, b: Pt, ccw: bool) -> bool {
    let along = |p: Pt| {
        let t = left(p.sub(m));
        if ccw {
            t
        } else {
            scale(t, -1.0)
        }
    };
    let same = |e: &Element, p: Pt| elem::tangent_at(e, p).is_some_and(|t| dot(t, along(p)) > 0.0);
    elem::contains(e1, a) && elem::contains(e2, b) && same(e1, a) && same(e2, b)
}

fn round(e1: &Element, e2: &Element, radius: f64, turns_left: bool) -> Result<Joined, NcError> {
    let side = if turns_left { 1.0 } else { -1.0 };
    let (o1, o2) = (offset(e1, radius, side)?, offset(e2, radius, side)?);
    let p = e1.end();
    // Of the centres that give a proper fillet, the one nearest the corner.
    let best = meet(&o1, &o2)
        .into_iter()
        .filter_map(|m| {
            let (a, b) = (foot(e1, m)?, foot(e2, m)?);
            fillet_fits(e1, e2, m, a, b, turns_left).then_some((m, a, b))
        })
        .min_by(|x, y| x.0.dist(p).total_cmp(&y.0.dist(p)));
    let Some((m, a, b)) = best else {
        return Err(too_large("corner radius", radius));
    };
    let fillet = Element::Arc {
        from: a,
        to: b,
        centre: m,
        cw: !turns_left,
    };
    Ok((elem::with_end(e1, a), fillet, elem::with_start(e2, b)))
}
