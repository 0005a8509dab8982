//! Ellipses G6.2/G6.3 and parabolas G7.2/G7.3 (dialect.md §4.1): the
//! curve through the start and end points, as pure functions of them.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom;
use crate::base::point::Pt;
use crate::plan::elem::{dot, left, scale};

/// Half a chord may exceed the semi-axis by this much and still be a
/// half ellipse (as for arcs, dialect.md §4.1 rule 2).
const SLACK_MM: f64 = 0.001;

/// The unit vector of a conic's axis at `deg` degrees from +Z, turning in
/// the G02 sense (towards −X in the ZX view, dialect.md §2.4).
pub(crate) fn axis(deg: f64) -> Pt {
    let a = deg.to_radians();
    Pt::new(-libm::sin(a), libm::cos(a))
}

/// The centre of the ellipse with semi-axis `a` along the axis at `q_deg`
/// and `b` across it that runs from `from` to `to` clockwise (`cw`) or
/// counter-clockwise in an arc of at most 180°. Stretching the ellipse by
/// a/b across its axis makes it a circle of radius `a` without changing
/// the sense of travel, so the centre is that of the ≤ 180° circular arc
/// there. `None` when `to` = `from` (no move). E4005 when no such ellipse
/// exists (the chord longer than 2A, or too long across the axis).
pub fn ellipse_centre(
    from: Pt,
    to: Pt,
    a: f64,
    b: f64,
    q_deg: f64,
    cw: bool,
) -> Result<Option<Pt>, NcError> {
    if a <= 0.0 || b <= 0.0 {
        return fail(
            Alarm::BadEllipse,
            "G6.2/G6.3 need semi-axes A and B greater than 0",
        );
    }
    let chord = from.dist(to);
    if chord < 1e-9 {
        return Ok(None);
    }
    if chord / 2.0 > a + SLACK_MM {
        return fail(
            Alarm::BadEllipse,
            format!(
                "the end point is {chord:.4} mm away, more than 2A = {:.4}",
                2.0 * a
            ),
        );
    }
    let (u, v) = (axis(q_deg), left(axis(q_deg)));
    // Ellipse frame, stretched: ξ along the axis, η across it × a/b.
    let to_circle = |p: Pt| Pt::new(dot(p, v) * a / b, dot(p, u));
    let centre = match geom::centre_from_radius(to_circle(from), to_circle(to), a, cw) {
        Ok(c) => c,
        Err(_) => {
            return fail(
                Alarm::BadEllipse,
                "no ellipse with these semi-axes and axis angle joins the two points",
            )
        }
    };
    Ok(centre.map(|c| scale(u, c.z).add(scale(v, c.r * b / a))))
}

/// The vertex of the parabola y² = 2px (parameter `p` mm, symmetry axis
/// at `q_deg` from +Z in the G02 sense) through `from` and `to`. Of the two
/// parabolas with that axis (opening either way along it) it is the one
/// that runs from `from` to `to` clockwise when `cw`, counter-clockwise
/// otherwise. E4006 when the chord is parallel to the symmetry axis.
pub fn parabola_vertex(from: Pt, to: Pt, p: f64, q_deg: f64, cw: bool) -> Result<Pt, NcError> {
    if p <= 0.0 {
        return fail(
            Alarm::BadParabola,
            "G7.2/G7.3 need a parameter P greater than 0",
        );
    }
    let (u, v) = (axis(q_deg), left(axis(q_deg)));
    let (us, vs, ue, ve) = (dot(from, u), dot(from, v), dot(to, u), dot(to, v));
    if (ve - vs).abs() < 1e-9 {
        return fail(
            Alarm::BadParabola,
            "the chord of the parabola is parallel to its symmetry axis",
        );
    }
    // Opening towards +u the curve turns clockwise while v grows.
    let grows = ve > vs;
    let sigma = if grows == cw { 1.0 } else { -1.0 };
    // σ(u − u0) = (v − v0)² / 2p through both points.
    let v0 = (vs + ve) / 2.0 - sigma * p * (us - ue) / (vs - ve);
    let u0 = us - sigma * (vs - v0) * (vs - v0) / (2.0 * p);
    Ok(scale(u, u0).add(scale(v, v0)))
}
