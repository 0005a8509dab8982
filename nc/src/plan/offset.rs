//! Offset geometry (comp.md §2, §5): normals, offset curves and where two
//! of them meet. Points double as vectors, `z` horizontal and `r` up, as in
//! `plan::elem`.

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::plan::elem::{
    circle_circle, cross, dot, left, line_circle, scale, tangent_at, travel, unit, EPS_LEN,
};
use core::f64::consts::{PI, TAU};

/// The compensated tool as read at a start-up (comp.md §1): later T words
/// and offset writes wait for the next start-up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tool {
    /// +1 for G41 (tool left of the path), −1 for G42.
    pub side: f64,
    /// The nose radius R (geometry + wear), ≥ 0.
    pub radius: f64,
    /// v(T)·R: from the nose centre to the printed imaginary tip.
    pub tip: Pt,
}

/// The normal R·n of a direction `t`: left(t) for G41 (side +1),
/// right(t) for G42; zero for no direction.
pub fn normal(t: Option<Pt>, tool: &Tool) -> Pt {
    t.map_or(Pt::default(), |t| scale(left(t), tool.side * tool.radius))
}

/// The nose centre over point `p` of `e`, on the normal there.
pub fn over(e: &Element, p: Pt, tool: &Tool) -> Pt {
    p.add(normal(tangent_at(e, p), tool))
}

/// Whether the tool runs on the centre's side of an arc: G42 on G02, G41
/// on G03 (the centre lies right of a clockwise travel).
fn centre_side(cw: bool, tool: &Tool) -> bool {
    (tool.side < 0.0) == cw
}

/// The radius of an arc's offset circle; E4036 when the tool on the
/// centre's side does not fit (ρ − R ≤ 0).
fn offset_radius(from: Pt, centre: Pt, cw: bool, tool: &Tool) -> Result<f64, NcError> {
    let rho = from.dist(centre);
    if !centre_side(cw, tool) {
        return Ok(rho + tool.radius);
    }
    let rad = rho - tool.radius;
    if rad <= EPS_LEN {
        return fail(
            Alarm::CompInterference,
            format!(
                "compensation interference: the arc of radius {rho:.4} is not larger than the nose radius {:.4}",
                tool.radius
            ),
        );
    }
    Ok(rad)
}

/// E4036 for an arc too small for the tool on its centre side.
pub fn check_arc(e: &Element, tool: &Tool) -> Result<(), NcError> {
    if let Element::Arc {
        from, centre, cw, ..
    } = *e
    {
        offset_radius(from, centre, cw, tool)?;
    }
    Ok(())
}

/// An element's offset curve: a line (a point on it and its direction) or
/// a circle.
#[derive(Debug, Clone, Copy)]
pub enum Curve {
    Line { p: Pt, t: Pt },
    Circle { c: Pt, rad: f64 },
}

pub fn curve(e: &Element, tool: &Tool) -> Result<Curve, NcError> {
    match *e {
        Element::Line { from, to } => {
            let t = unit(to.sub(from)).unwrap_or(Pt::new(0.0, 1.0));
            Ok(Curve::Line {
                p: from.add(normal(Some(t), tool)),
                t,
            })
        }
        Element::Arc {
            from, centre, cw, ..
        } => Ok(Curve::Circle {
            c: centre,
            rad: offset_radius(from, centre, cw, tool)?,
        }),
    }
}

/// The points where two offset curves meet (none, one or two).
pub fn meet(a: &Curve, b: &Curve) -> Vec<Pt> {
    match (*a, *b) {
        (Curve::Line { p: p1, t: t1 }, Curve::Line { p: p2, t: t2 }) => {
            let det = cross(t1, t2);
            if det.abs() < 1e-12 {
                return Vec::new();
            }
            // p1 + λ·t1 lies on the second line: (p1 + λ·t1 − p2) × t2 = 0.
            let lambda = cross(p2.sub(p1), t2) / det;
            vec![p1.add(scale(t1, lambda))]
        }
        (Curve::Line { p, t }, Curve::Circle { c, rad })
        | (Curve::Circle { c, rad }, Curve::Line { p, t }) => line_circle(p, t, c, rad),
        (Curve::Circle { c: c1, rad: r1 }, Curve::Circle { c: c2, rad: r2 }) => {
            circle_circle(c1, r1, c2, r2)
        }
    }
}

/// E4036 when the compensated part of `e` from centre point `s` to `f`
/// would run backwards: against the line's direction, or round the arc
/// by a negative angle.
pub fn check_forward(e: &Element, s: Pt, f: Pt) -> Result<(), NcError> {
    let backwards = match *e {
        Element::Line { from, to } => {
            unit(to.sub(from)).is_some_and(|t| dot(f.sub(s), t) < -EPS_LEN)
        }
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => {
            let sweep = crate::plan::elem::sweep(from, to, centre, cw);
            // How far each end moved along the travel, in (−π, π].
            let shift = |a: Pt, b: Pt| {
                let d = travel(centre, a, b, cw);
                if d > PI {
                    d - TAU
                } else {
                    d
                }
            };
            let rad = s.dist(centre).max(EPS_LEN);
            sweep + shift(to, f) - shift(from, s) < -EPS_LEN / rad
        }
    };
    if backwards {
        return fail(
            Alarm::CompInterference,
            "compensation interference: the compensated path of this element would run backwards",
        );
    }
    Ok(())
}
