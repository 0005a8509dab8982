//! How far a point lies off the way of a canon move, and whether an arc
//! leaves its end point and comes back to it.

use super::pending::{Pending, Shape};
use super::{END_POINT_MM, MICRO_ARC_MM};
use crate::math::{PI, V2};

/// How far `p` lies off the way of move `m` (`None`: not checked, or its
/// start is unknown). An arc counts its whole circle (a set point on the
/// circle but off the arc lies far from the moves before and after, whose
/// end points the walk holds the tool to).
pub(super) fn off_shape(m: &Pending, p: V2) -> Option<f64> {
    match m.shape {
        Shape::Line => Some(seg_dist(p, m.start?, m.end)),
        Shape::Arc { centre, .. } => {
            let r = (m.end - centre).norm();
            let off = ((p - centre).norm() - r).abs();
            // An arc of a radius below the resolution runs as its chord
            // (planner.rs); one of a few µm, whose centre the canon
            // rounds to 0.1 µm, is held to its chord too, which lies
            // within its radius of it.
            Some(match m.start {
                Some(a) if r < MICRO_ARC_MM => off.min(seg_dist(p, a, m.end)),
                _ => off,
            })
        }
        Shape::Rapid => {
            let a = m.start?;
            let out = |v: f64, a: f64, b: f64| (a.min(b) - v).max(v - a.max(b)).max(0.0);
            Some(libm::hypot(out(p.r, a.r, m.end.r), out(p.z, a.z, m.end.z)))
        }
        // (Threads: `Certifier::in_chain`.)
        Shape::Thread | Shape::Free => None,
    }
}

/// Whether a move from `start` to `end` of `shape` leaves its end point
/// and comes back to it: a full circle, whose end is its start (as the
/// runtime takes an arc whose ends are within 1e-9 mm, geom.rs), or an
/// arc that ends within the tolerance of its start the long way round.
/// The walk must not count its end point where the circle begins. Only
/// from a radius of [`MICRO_ARC_MM`]: a smaller arc may run as its chord
/// (and jerk limiting's averaging shrinks it), so the tool need not leave.
pub(super) fn comes_back(start: Option<V2>, end: V2, shape: Shape) -> bool {
    let (Some(a), Shape::Arc { centre, ccw }) = (start, shape) else {
        return false;
    };
    let (u, v) = (a - centre, end - centre);
    if (end - a).norm() > END_POINT_MM || u.norm() < MICRO_ARC_MM {
        return false;
    }
    // The turn from u to v the arc's way, in [0, 2π) (geom.rs `arc`).
    let ang = libm::atan2(u.z * v.r - u.r * v.z, u.dot(v));
    let sweep = crate::math::rem_euclid(if ccw { ang } else { -ang }, 2.0 * PI);
    (end - a).norm() < 1e-9 || sweep > PI
}

/// Distance from `p` to the segment `a`–`b`.
pub(super) fn seg_dist(p: V2, a: V2, b: V2) -> f64 {
    (p - seg_nearest(p, a, b)).norm()
}

/// The point of the segment `a`–`b` nearest to `p`.
fn seg_nearest(p: V2, a: V2, b: V2) -> V2 {
    let d = b - a;
    let t = seg_param(p, a, b).clamp(0.0, 1.0);
    a + V2::new(d.r * t, d.z * t)
}

/// Where `p` projects on the line through `a` and `b`: 0 at `a`, 1 at
/// `b` (0 when they coincide).
fn seg_param(p: V2, a: V2, b: V2) -> f64 {
    let d = b - a;
    let len2 = d.r * d.r + d.z * d.z;
    if len2 > 0.0 {
        ((p - a).r * d.r + (p - a).z * d.z) / len2
    } else {
        0.0
    }
}
