//! Vector and element helpers in the ZX plane. A `Pt` doubles as a vector
//! here: `z` is the horizontal component, `r` the vertical one, so "left"
//! and "counter-clockwise" mean what they mean in the ZX view (dialect.md
//! §2.4: G02 is clockwise in this view).

use alloc::vec;
use alloc::vec::Vec;

use crate::base::geom::Element;
use crate::base::point::Pt;
use core::f64::consts::TAU;

/// Lengths below this are treated as zero (mm).
pub const EPS_LEN: f64 = 1e-6;

pub fn dot(a: Pt, b: Pt) -> f64 {
    a.z * b.z + a.r * b.r
}

/// z–r cross product: > 0 when `b` turns left of `a`.
pub fn cross(a: Pt, b: Pt) -> f64 {
    a.z * b.r - a.r * b.z
}

pub fn scale(v: Pt, k: f64) -> Pt {
    Pt::new(v.r * k, v.z * k)
}

pub fn norm(v: Pt) -> f64 {
    libm::hypot(v.r, v.z)
}

/// The unit vector of `v`, `None` for a (near) zero vector.
pub fn unit(v: Pt) -> Option<Pt> {
    let n = norm(v);
    (n > 1e-12).then(|| scale(v, 1.0 / n))
}

/// `v` turned 90° counter-clockwise.
pub fn left(v: Pt) -> Pt {
    Pt::new(v.z, -v.r)
}

/// The unit vector at `deg` degrees counter-clockwise from +Z.
pub fn heading(deg: f64) -> Pt {
    let a = deg.to_radians();
    Pt::new(libm::sin(a), libm::cos(a))
}

/// The polar angle of `p` about `c`, counter-clockwise from +Z.
fn polar(c: Pt, p: Pt) -> f64 {
    libm::atan2(p.r - c.r, p.z - c.z)
}

/// `p` turned by `phi` radians about `c`, counter-clockwise when `ccw`.
pub fn rotate(p: Pt, c: Pt, phi: f64, ccw: bool) -> Pt {
    let a = if ccw { phi } else { -phi };
    let (s, k) = (libm::sin(a), libm::cos(a));
    let (dz, dr) = (p.z - c.z, p.r - c.r);
    Pt::new(c.r + dz * s + dr * k, c.z + dz * k - dr * s)
}

/// How far round an arc about `c` one travels from `a` to `b` in its
/// direction, in [0, 2π).
pub fn travel(c: Pt, a: Pt, b: Pt, cw: bool) -> f64 {
    let d = if cw {
        polar(c, a) - polar(c, b)
    } else {
        polar(c, b) - polar(c, a)
    };
    crate::base::geom::rem_euclid(d, TAU)
}

/// The swept angle of an arc; start = end is a full circle (I/K form).
pub fn sweep(from: Pt, to: Pt, centre: Pt, cw: bool) -> f64 {
    if from.dist(to) < 1e-9 {
        return TAU;
    }
    travel(centre, from, to, cw)
}

/// Whether `e` is shorter than `eps` (the contour and compensation rules
/// ask for most elements). An arc's sweep is at least the distance between
/// its unit radius vectors: that chord is 2·sin(θ/2) ≤ θ the short way
/// round, and the long way round is at least π > 2. So r·|u0 − u1| ≥ eps
/// answers no without the arc's trigonometry; the slack keeps rounding
/// from deciding it.
pub fn shorter_than(e: &Element, eps: f64) -> bool {
    if let Element::Arc {
        from, to, centre, ..
    } = *e
    {
        let (a, b) = (from.sub(centre), to.sub(centre));
        let (ra, rb) = (plain_norm(a), plain_norm(b));
        if ra > 0.0 && rb > 0.0 {
            let gap = plain_norm(scale(a, 1.0 / ra).sub(scale(b, 1.0 / rb)));
            if ra * gap >= eps * (1.0 + 1e-6) {
                return false;
            }
        }
    }
    length(e) < eps
}

/// A vector's length by a plain square root (for bounds, where the last
/// bit does not matter).
fn plain_norm(v: Pt) -> f64 {
    libm::sqrt(v.r * v.r + v.z * v.z)
}

pub fn length(e: &Element) -> f64 {
    match *e {
        Element::Line { from, to } => from.dist(to),
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => from.dist(centre) * sweep(from, to, centre, cw),
    }
}

/// The unit direction of travel of `e` at its point `p` (`None` for a
/// zero-length line or a degenerate arc).
pub fn tangent_at(e: &Element, p: Pt) -> Option<Pt> {
    match *e {
        Element::Line { from, to } => unit(to.sub(from)),
        Element::Arc { centre, cw, .. } => {
            let t = unit(left(p.sub(centre)))?;
            Some(if cw { scale(t, -1.0) } else { t })
        }
    }
}

/// `e` with a new end point (same line, same circle).
pub fn with_end(e: &Element, p: Pt) -> Element {
    match *e {
        Element::Line { from, .. } => Element::Line { from, to: p },
        Element::Arc {
            from, centre, cw, ..
        } => Element::Arc {
            from,
            to: p,
            centre,
            cw,
        },
    }
}

/// `e` with a new start point.
pub fn with_start(e: &Element, p: Pt) -> Element {
    match *e {
        Element::Line { to, .. } => Element::Line { from: p, to },
        Element::Arc { to, centre, cw, .. } => Element::Arc {
            from: p,
            to,
            centre,
            cw,
        },
    }
}

/// Whether `p` (known to lie on the line or circle of `e`) lies on the
/// element itself, its end points included.
pub fn contains(e: &Element, p: Pt) -> bool {
    match *e {
        Element::Line { from, to } => {
            let len = from.dist(to);
            let Some(t) = unit(to.sub(from)) else {
                return false;
            };
            let u = dot(p.sub(from), t);
            (-EPS_LEN..=len + EPS_LEN).contains(&u)
        }
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => {
            let rho = from.dist(centre);
            let slack = EPS_LEN / rho.max(EPS_LEN);
            let a = travel(centre, from, p, cw);
            // Just before the start wraps round to nearly 2π.
            a <= sweep(from, to, centre, cw) + slack || a >= TAU - slack
        }
    }
}

/// Where the line p + λt (t a unit vector) meets the circle about c:
/// |p + λt − c|² = rad² → λ² + 2λ(w·t) + |w|² − rad² = 0.
pub fn line_circle(p: Pt, t: Pt, c: Pt, rad: f64) -> Vec<Pt> {
    let w = p.sub(c);
    let half_b = dot(w, t);
    let disc = half_b * half_b - (dot(w, w) - rad * rad);
    if disc < -1e-9 {
        return Vec::new();
    }
    let s = libm::sqrt(disc.max(0.0));
    vec![p.add(scale(t, -half_b - s)), p.add(scale(t, -half_b + s))]
}

/// Where two circles meet: the foot at distance a from c1 along the centre
/// line (the radical line), then ± h across it.
pub fn circle_circle(c1: Pt, r1: f64, c2: Pt, r2: f64) -> Vec<Pt> {
    let d = c1.dist(c2);
    if d < 1e-12 {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h2 = r1 * r1 - a * a;
    if h2 < -1e-9 {
        return Vec::new();
    }
    let h = libm::sqrt(h2.max(0.0));
    let u = scale(c2.sub(c1), 1.0 / d);
    let foot = c1.add(scale(u, a));
    vec![foot.add(scale(left(u), h)), foot.add(scale(left(u), -h))]
}
