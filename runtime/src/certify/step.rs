//! One period's step of the work point as the end points' walk measures
//! it: in work X and Z, or in space for a move of a plane.

use super::pending::Pending;
use super::shape::seg_dist;
use crate::interpolate::SetPoint;
use crate::math::V2;

/// Whether the work frame stayed the same over the period from `prev` to
/// `p`: the work point moved as the axes did.
pub(super) fn frame_kept(prev: &SetPoint, p: &SetPoint) -> bool {
    let moved = V2::new((p.axis_x - prev.axis_x) * 0.5, p.axis_z - prev.axis_z);
    let step = V2::from_xz(p.x, p.z) - V2::from_xz(prev.x, prev.z);
    (step - moved).norm() <= 1e-9
}

/// One period's step of the work point, for the end points' walk.
pub(super) struct Step {
    a: V2,
    b: V2,
    /// The axes' own step (X on the diameter halved).
    moved: V2,
    /// The work point moved as the axes did: no work shift changed.
    joined: bool,
    /// The step's ends in space ([`space`]), for the moves of a plane.
    a3: P3,
    b3: P3,
}

impl Step {
    pub(super) fn new(prev: &SetPoint, p: &SetPoint) -> Step {
        let (a, b) = (V2::from_xz(prev.x, prev.z), V2::from_xz(p.x, p.z));
        let moved = V2::new((p.axis_x - prev.axis_x) * 0.5, p.axis_z - prev.axis_z);
        let joined = ((b - a) - moved).norm() <= 1e-9;
        Step {
            a,
            b,
            moved,
            joined,
            a3: space(a.r, a.z, prev.c.unwrap_or(0.0)),
            b3: space(b.r, b.z, p.c.unwrap_or(0.0)),
        }
    }

    /// The step as the walk holds it to the end point of `m`: in work X
    /// (a radius) and Z, or for a move of a plane in space. Where the
    /// work shift changed (G50, G54…, a tool offset) the work point
    /// jumped: the period's path is the axes' step in the old frame
    /// before the jump, or in the new one after it (no shift changes in a
    /// plane).
    pub(super) fn way(&self, m: &Pending) -> Way {
        let flat = |v: V2| [v.r, v.z, 0.0];
        let Some(pe) = m.plane else {
            let (a, b, e, moved) = (self.a, self.b, m.end, self.moved);
            return Way {
                a: flat(a),
                b: flat(b),
                e: flat(e),
                travel: moved.norm(),
                split: (!self.joined)
                    .then(|| seg_dist(e, a, a + moved).min(seg_dist(e, b - moved, b))),
            };
        };
        // (Where the plane's end is not known in X or Z: the tool's own.)
        let r = if pe.free_r { self.b.r } else { m.end.r };
        let z = if pe.free_z { self.b.z } else { m.end.z };
        Way {
            a: self.a3,
            b: self.b3,
            e: space(r, z, pe.c),
            travel: norm3(sub3(self.b3, self.a3)),
            split: None,
        }
    }
}

/// A point in the walk's space: work X (a radius), Z and 0 off a plane,
/// (r cos C, r sin C, Z) in one ([`space`]).
type P3 = [f64; 3];

/// The tool at work X radius `r`, Z `z` and C `c` (degrees) as a point in
/// space about the spindle's axis.
fn space(r: f64, z: f64, c: f64) -> P3 {
    let (sin, cos) = crate::math::sin_cos(c.to_radians());
    [r * cos, r * sin, z]
}

fn sub3(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm3(a: P3) -> f64 {
    libm::sqrt(dot3(a, a))
}

/// One period's step and one end point `e`, in the walk's space for it
/// ([`Step::way`]).
pub(super) struct Way {
    a: P3,
    b: P3,
    e: P3,
    /// The axes' travel in the period.
    pub(super) travel: f64,
    /// Where the work frame jumped: the distance of the end point from
    /// the step's two pieces.
    split: Option<f64>,
}

impl Way {
    pub(super) fn joined(&self) -> bool {
        self.split.is_none()
    }

    /// The point at share `s` of the step.
    fn at(&self, s: f64) -> P3 {
        let d = sub3(self.b, self.a);
        [
            self.a[0] + d[0] * s,
            self.a[1] + d[1] * s,
            self.a[2] + d[2] * s,
        ]
    }

    /// Where the end point projects on the rest of the step from share
    /// `from` on: 0 there, 1 at the step's end (0 when it is empty).
    pub(super) fn param(&self, from: f64) -> f64 {
        let a = self.at(from);
        let d = sub3(self.b, a);
        let len2 = dot3(d, d);
        if len2 > 0.0 {
            dot3(sub3(self.e, a), d) / len2
        } else {
            0.0
        }
    }

    /// Whether the rest of the step from share `from` comes back to the
    /// end point from away: it ends more than `tol` from it and nearer to
    /// it than it began (a full circle's distance from its end grows
    /// until the far side, then shrinks). Not across a frame jump.
    pub(super) fn returns(&self, from: f64, tol: f64) -> bool {
        let began = norm3(sub3(self.e, self.at(from)));
        let ends = norm3(sub3(self.e, self.b));
        self.joined() && ends > tol && ends < began
    }

    /// How far the end point is from the step's path from share `from`
    /// on.
    pub(super) fn dist(&self, from: f64) -> f64 {
        if let Some(d) = self.split {
            return d;
        }
        let s = from + (1.0 - from) * self.param(from).clamp(0.0, 1.0);
        norm3(sub3(self.e, self.at(s)))
    }
}
