//! Contour elements as parametric curves: a point at every parameter
//! s ∈ [0, 1], where a coordinate crosses a level, where it has an extreme.
//! The roughing cycles cut elements at levels and walk them in pieces, so
//! they work on parameter ranges of whole elements rather than building
//! new, possibly degenerate, arcs.

use alloc::vec;
use alloc::vec::Vec;

use crate::base::geom::Element;
use crate::base::point::Pt;
use core::f64::consts::{FRAC_PI_2, PI, TAU};

/// Points and levels closer than this (mm) are the same (cycles.md §0).
pub const EPS: f64 = 1e-6;

/// How far an arc may turn back past an extreme point and still count as
/// monotonic (mm). Programs give their points to 0.001 mm, so the arc
/// through a rounded tangent point can dip a few µm past the tangent: that
/// is rounding, not a profile turning back.
pub const SLACK: f64 = 1e-3;

/// `sign(v)` of cycles.md §0: 0 when |v| ≤ 1e-6.
pub fn sign(v: f64) -> f64 {
    if v > EPS {
        1.0
    } else if v < -EPS {
        -1.0
    } else {
        0.0
    }
}

/// One coordinate of the ZX plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    R,
    Z,
}

pub fn coord(p: Pt, axis: Axis) -> f64 {
    match axis {
        Axis::R => p.r,
        Axis::Z => p.z,
    }
}

/// An [`Element`] with its angles resolved once, for the roughing cycles'
/// searches ([`Curve::new`] and [`Curve::element`] convert). Angles are measured in
/// the (z, r) plane from +Z towards +r, so G03 (counter-clockwise in the ZX
/// view) has a positive sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Curve {
    Line {
        from: Pt,
        to: Pt,
    },
    Arc {
        from: Pt,
        to: Pt,
        centre: Pt,
        cw: bool,
        radius: f64,
        a0: f64,
        sweep: f64,
    },
}

fn angle(centre: Pt, p: Pt) -> f64 {
    libm::atan2(p.r - centre.r, p.z - centre.z)
}

impl Curve {
    /// An arc element whose end equals its start is a full circle: a
    /// 0° arc (R form) never becomes an element.
    pub fn new(e: Element) -> Curve {
        match e {
            Element::Line { from, to } => Curve::Line { from, to },
            Element::Arc {
                from,
                to,
                centre,
                cw,
            } => {
                let a0 = angle(centre, from);
                let a1 = angle(centre, to);
                let mut turn =
                    crate::base::geom::rem_euclid(if cw { a0 - a1 } else { a1 - a0 }, TAU);
                if turn < 1e-12 || from.dist(to) < 1e-9 {
                    turn = TAU;
                }
                Curve::Arc {
                    from,
                    to,
                    centre,
                    cw,
                    radius: from.dist(centre),
                    a0,
                    sweep: if cw { -turn } else { turn },
                }
            }
        }
    }

    pub fn element(&self) -> Element {
        match *self {
            Curve::Line { from, to } => Element::Line { from, to },
            Curve::Arc {
                from,
                to,
                centre,
                cw,
                ..
            } => Element::Arc {
                from,
                to,
                centre,
                cw,
            },
        }
    }

    pub fn start(&self) -> Pt {
        self.element().start()
    }

    pub fn end(&self) -> Pt {
        self.element().end()
    }

    /// The same curve moved by `d` (arc centres too).
    pub fn shifted(&self, d: Pt) -> Curve {
        Curve::new(self.element().shifted(d))
    }

    /// The curve mirrored at r = z (the two axes exchanged): G72 runs the
    /// G71 algorithm on the mirrored profile. A mirror turns clockwise
    /// into counter-clockwise.
    pub fn swapped(&self) -> Curve {
        let s = swap;
        Curve::new(match self.element() {
            Element::Line { from, to } => Element::Line {
                from: s(from),
                to: s(to),
            },
            Element::Arc {
                from,
                to,
                centre,
                cw,
            } => Element::Arc {
                from: s(from),
                to: s(to),
                centre: s(centre),
                cw: !cw,
            },
        })
    }

    /// The point at parameter s; the ends are returned exactly.
    pub fn at(&self, s: f64) -> Pt {
        if s <= 0.0 {
            return self.start();
        }
        if s >= 1.0 {
            return self.end();
        }
        match *self {
            Curve::Line { from, to } => {
                Pt::new(from.r + (to.r - from.r) * s, from.z + (to.z - from.z) * s)
            }
            Curve::Arc {
                centre,
                radius,
                a0,
                sweep,
                ..
            } => {
                let a = a0 + sweep * s;
                Pt::new(
                    centre.r + radius * libm::sin(a),
                    centre.z + radius * libm::cos(a),
                )
            }
        }
    }

    /// The parameter of angle `a` on an arc, if it lies inside (0, 1).
    fn param_of_angle(a0: f64, sweep: f64, a: f64) -> Option<f64> {
        let turn = crate::base::geom::rem_euclid(if sweep < 0.0 { a0 - a } else { a - a0 }, TAU);
        let s = turn / sweep.abs();
        (s > 1e-12 && s < 1.0 - 1e-12).then_some(s)
    }

    fn arc_params(a0: f64, sweep: f64, angles: &[f64]) -> Vec<f64> {
        let mut out: Vec<f64> = angles
            .iter()
            .filter_map(|&a| Curve::param_of_angle(a0, sweep, a))
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        out
    }

    /// Parameters strictly inside (0, 1) where `axis` equals `level`.
    pub fn roots(&self, axis: Axis, level: f64) -> Vec<f64> {
        match *self {
            Curve::Line { from, to } => {
                let (a, b) = (coord(from, axis), coord(to, axis));
                if (b - a).abs() < 1e-12 {
                    return Vec::new();
                }
                let s = (level - a) / (b - a);
                if s > 1e-12 && s < 1.0 - 1e-12 {
                    vec![s]
                } else {
                    Vec::new()
                }
            }
            Curve::Arc {
                centre,
                radius,
                a0,
                sweep,
                ..
            } => {
                if radius < 1e-12 {
                    return Vec::new();
                }
                let v = (level - coord(centre, axis)) / radius;
                if v.abs() > 1.0 + 1e-12 {
                    return Vec::new();
                }
                let v = v.clamp(-1.0, 1.0);
                let angles = match axis {
                    // r = cr + ρ·sin a
                    Axis::R => [libm::asin(v), PI - libm::asin(v)],
                    // z = cz + ρ·cos a
                    Axis::Z => [libm::acos(v), -libm::acos(v)],
                };
                Curve::arc_params(a0, sweep, &angles)
            }
        }
    }

    /// Parameters strictly inside (0, 1) where `axis` has an extreme (only
    /// arcs have them).
    pub fn extremes(&self, axis: Axis) -> Vec<f64> {
        match *self {
            Curve::Line { .. } => Vec::new(),
            Curve::Arc { a0, sweep, .. } => {
                let angles = match axis {
                    Axis::R => [FRAC_PI_2, -FRAC_PI_2],
                    Axis::Z => [0.0, PI],
                };
                Curve::arc_params(a0, sweep, &angles)
            }
        }
    }

    /// The parameters of [s0, s1] where `axis` may turn: the ends and the
    /// extremes between them, in order.
    fn samples(&self, axis: Axis, s0: f64, s1: f64) -> Vec<f64> {
        let mut v = vec![s0];
        v.extend(
            self.extremes(axis)
                .into_iter()
                .filter(|&s| s > s0 && s < s1),
        );
        v.push(s1);
        v
    }

    /// The smallest and largest value of `axis` over [s0, s1].
    pub fn range(&self, axis: Axis, s0: f64, s1: f64) -> (f64, f64) {
        self.samples(axis, s0, s1)
            .into_iter()
            .map(|s| coord(self.at(s), axis))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// Whether `axis` never moves against `dir` over [s0, s1]: from end to
    /// end by no more than 1e-6 (cycles.md §15.1), and an arc not past an
    /// extreme by more than `SLACK`.
    pub fn monotone(&self, axis: Axis, dir: f64, s0: f64, s1: f64) -> bool {
        let values: Vec<f64> = self
            .samples(axis, s0, s1)
            .into_iter()
            .map(|s| coord(self.at(s), axis))
            .collect();
        let whole = match (values.first(), values.last()) {
            (Some(a), Some(b)) => dir * (b - a) >= -EPS,
            _ => true,
        };
        whole && values.windows(2).all(|w| dir * (w[1] - w[0]) >= -SLACK)
    }

    /// The length of the part [s0, s1].
    pub fn length(&self, s0: f64, s1: f64) -> f64 {
        match *self {
            Curve::Line { .. } => self.at(s0).dist(self.at(s1)),
            Curve::Arc { radius, sweep, .. } => radius * sweep.abs() * (s1 - s0).abs(),
        }
    }
}

/// The two coordinates exchanged (see `Curve::swapped`).
pub fn swap(p: Pt) -> Pt {
    Pt::new(p.z, p.r)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(from: Pt, to: Pt, centre: Pt, cw: bool) -> Curve {
        Curve::new(Element::Arc {
            from,
            to,
            centre,
            cw,
        })
    }

    #[test]
    fn a_quarter_arc_has_its_midpoint_on_the_circle() {
        // G02 from r17 z-38 to r22 z-43 about r22 z-38 (g71_od_profile).
        let c = arc(
            Pt::new(17.0, -38.0),
            Pt::new(22.0, -43.0),
            Pt::new(22.0, -38.0),
            true,
        );
        let m = c.at(0.5);
        let h = 5.0 * core::f64::consts::FRAC_1_SQRT_2;
        assert!((m.r - (22.0 - h)).abs() < 1e-9 && (m.z - (-38.0 - h)).abs() < 1e-9);
        // Level r = 21.5, 0.5 below the centre: z = -38 - sqrt(25 - 0.25).
        let s = c.roots(Axis::R, 21.5);
        assert_eq!(s.len(), 1);
        let z = c.at(s[0]).z;
        assert!((z - (-38.0 - (25.0f64 - 0.25).sqrt())).abs() < 1e-9);
    }

    #[test]
    fn a_half_circle_has_an_extreme_inside() {
        // From z0 over the top (r = 5) to z10, clockwise, centre z5 r0.
        let c = arc(
            Pt::new(0.0, 0.0),
            Pt::new(0.0, 10.0),
            Pt::new(0.0, 5.0),
            true,
        );
        assert_eq!(c.extremes(Axis::R).len(), 1);
        assert!(c.monotone(Axis::Z, 1.0, 0.0, 1.0));
        assert!(!c.monotone(Axis::R, 1.0, 0.0, 1.0));
        assert!((c.range(Axis::R, 0.0, 1.0).1 - 5.0).abs() < 1e-9);
    }

    #[test]
    fn mirroring_flips_the_direction_and_keeps_the_points() {
        let c = arc(
            Pt::new(0.0, 0.0),
            Pt::new(5.0, 5.0),
            Pt::new(5.0, 0.0),
            true,
        );
        let m = c.swapped();
        let Curve::Arc { cw, .. } = m else {
            panic!("an arc")
        };
        assert!(!cw);
        for s in [0.0, 0.25, 0.5, 0.9, 1.0] {
            assert!(m.at(s).dist(swap(c.at(s))) < 1e-9);
        }
    }

    #[test]
    fn a_rounded_tangent_point_is_not_a_turn() {
        // A CW arc of R3 about r12.1 z-17.6334 starting at r9.1 z-17.63,
        // 0.0034 mm right of the bottom: it dips 1.9 µm below r9.1 first.
        let c = arc(
            Pt::new(9.1, -17.63),
            Pt::new(10.765, -20.32),
            Pt::new(12.1, -17.6334),
            true,
        );
        assert_eq!(c.extremes(Axis::R).len(), 1);
        assert!(c.monotone(Axis::R, 1.0, 0.0, 1.0));
        // The bottom R2 arc of a bore (r7 → r5 about r6 z-28.268) bulges
        // 0.268 mm past z-30 and comes back: a real turn.
        let c = arc(
            Pt::new(7.0, -30.0),
            Pt::new(5.0, -30.0),
            Pt::new(6.0, -30.0 + 3f64.sqrt()),
            false,
        );
        assert!(!c.monotone(Axis::Z, -1.0, 0.0, 1.0));
        assert!((c.range(Axis::Z, 0.0, 1.0).0 - (-30.0 + 3f64.sqrt() - 2.0)).abs() < 1e-9);
    }
}
