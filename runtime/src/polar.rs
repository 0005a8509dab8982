//! Polar (G12.1) and cylindrical (G7.1) interpolation in the runtime: the
//! programmed path lies in a plane of its own, the axes that move are X
//! and C (polar) or Z and C (cylinder).
//!
//! While a plane is on, the planner and the interpolator work in it as
//! they do in the ZX plane: the moves' points are plane points (`V2` with
//! the plane's first axis as `z` and its second as `r`, as the kernel's
//! plane.rs orients arcs), so lines, arcs, the look-ahead, the corners
//! and the acceleration all act on the programmed path and F is the
//! tangential feed along it. Each period the interpolator's plane point is
//! turned into joint positions here ([`PlaneRun::follow`]):
//!
//! - polar: X = 2·√(x² + c²), C = the angle of (x, c) from +X, followed
//!   continuously (a circle about the centre is a whole turn of C); Z
//!   stays where the map says;
//! - cylinder: Z = the plane's Z, C = s / r in degrees (s the developed
//!   length, r the cylinder's radius); X stays where the map says.
//!
//! The axis the map holds (polar Z, cylinder X) moves with a straight
//! move of the plane, in proportion along it (the planner's third
//! coordinate, which is C's outside a plane: planner.rs); alone, it moves
//! between two switches: the plane ends, the axis moves as an ordinary
//! move, the plane starts again at the same plane point with the new Z or
//! X (translate.rs, `PlaneAxis`).
//!
//! The joints' limits hold: the planner caps each plane move for what
//! the joints need of it (planner.rs, `plane_limits`), and a move that
//! passes near the centre, where C turns fast, is queued in pieces
//! ([`cuts`]) so that it slows there only. A G00 in the plane follows the
//! plane's straight line (interpolate.rs, `axis_rapid`).
//!
//! A switch ([`PlaneSwitch`]) is a queue item: the move before it ends at
//! rest, and the interpolator's point changes from machine axes to plane
//! point (or back) there.

use crate::geom::Curve;
use crate::math::V2;
use alloc::vec::Vec;

/// How plane points map to joints while a plane is on (work coordinates,
/// the joint that stays included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneMap {
    /// G12.1: Z (work) stays here while the plane is on.
    Polar {
        /// Z, work coordinates.
        z: f64,
    },
    /// G7.1: the cylinder's radius; X (work radius) stays.
    Cylinder {
        /// The cylinder's radius, mm.
        radius: f64,
        /// X as a radius, work coordinates.
        r: f64,
    },
}

impl PlaneMap {
    /// The plane point of a canon plane move's two numbers (event.rs:
    /// polar X diameter and C mm, cylinder Z and C degrees).
    pub fn point(&self, a: f64, b: f64) -> V2 {
        match *self {
            PlaneMap::Polar { .. } => V2::new(b, a * 0.5),
            PlaneMap::Cylinder { radius, .. } => V2::new(a, radius * b.to_radians()),
        }
    }

    /// Where the map holds the axis outside the plane: polar Z, cylinder
    /// X as a radius (work coordinates, mm). A straight move may take it
    /// along (the planner's third coordinate, planner.rs).
    pub fn held(&self) -> f64 {
        match *self {
            PlaneMap::Polar { z } => z,
            PlaneMap::Cylinder { r, .. } => r,
        }
    }

    /// The same map with the axis outside the plane at `v` (`held`).
    pub fn with_held(self, v: f64) -> PlaneMap {
        match self {
            PlaneMap::Polar { .. } => PlaneMap::Polar { z: v },
            PlaneMap::Cylinder { radius, .. } => PlaneMap::Cylinder { radius, r: v },
        }
    }

    /// The joints (work coordinates) at plane point `p`; C in degrees,
    /// for the polar plane its angle in (−180°, 180°].
    pub fn joints(&self, p: V2) -> (V2, f64) {
        match *self {
            PlaneMap::Polar { z } => (
                V2::new(libm::hypot(p.z, p.r), z),
                libm::atan2(p.r, p.z).to_degrees(),
            ),
            PlaneMap::Cylinder { radius, r } => (V2::new(r, p.r), (p.z / radius).to_degrees()),
        }
    }
}

/// A switch of the plane: a queue item.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSwitch {
    /// The mapping from here on; `None`: joint motion again.
    pub map: Option<PlaneMap>,
    /// The interpolator's point after the switch: the plane point at the
    /// start, the machine axes at the end.
    pub at: V2,
    /// The C angle at the switch, degrees.
    pub c: f64,
    /// Machine axes minus programmed joints while the plane is on (work
    /// zero + tool offset), and the queue's shift after it ends.
    pub shift: V2,
}

impl PlaneSwitch {
    /// The planner's and the interpolator's third coordinate after the
    /// switch: the axis the plane holds while a plane is on, C's angle
    /// after it ends.
    pub fn third(&self) -> f64 {
        self.map.map_or(self.c, |m| m.held())
    }
}

/// The interpolator's state while a plane is on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneRun {
    map: PlaneMap,
    shift: V2,
    /// The joints of the last period (work coordinates) and C, followed
    /// continuously.
    work: V2,
    c: f64,
    /// The polar angle of the last period, to unwrap C.
    angle: f64,
}

impl PlaneRun {
    /// The state at a switch that turns a plane on, from its start point.
    pub fn start(map: PlaneMap, sw: &PlaneSwitch) -> PlaneRun {
        let (work, angle) = map.joints(sw.at);
        let mut run = PlaneRun {
            map,
            shift: sw.shift,
            work,
            c: sw.c,
            angle,
        };
        if let PlaneMap::Cylinder { .. } = map {
            run.c = angle;
        }
        run
    }

    /// Moves the joints to plane point `p`, the axis outside the plane to
    /// `held` (`PlaneMap::held`).
    pub fn follow(&mut self, p: V2, held: f64) {
        self.map = self.map.with_held(held);
        let (work, angle) = self.map.joints(p);
        self.work = work;
        match self.map {
            PlaneMap::Polar { .. } => {
                // The change of angle the shorter way round: a period
                // turns C by far less than half a turn.
                let mut d = angle - self.angle;
                if d > 180.0 {
                    d -= 360.0;
                } else if d < -180.0 {
                    d += 360.0;
                }
                self.c += d;
                self.angle = angle;
            }
            PlaneMap::Cylinder { .. } => self.c = angle,
        }
    }

    /// The joints in work coordinates (X as a radius).
    pub fn work(&self) -> V2 {
        self.work
    }

    /// The joints in machine coordinates.
    pub fn axes(&self) -> V2 {
        self.work + self.shift
    }

    /// The C angle, degrees.
    pub fn c(&self) -> f64 {
        self.c
    }
}

/// A move whose distance from the centre stays within this factor is
/// planned whole (most moves).
const SPAN: f64 = 2.0;

/// How much the distance from the centre may grow along one piece of a
/// move that is cut: C turns at v·h/ρ², so the speed C allows grows
/// with ρ², and a piece capped at its least ρ gets at least 1/1.1² ≈
/// 83 % of what C allows anywhere on it.
const GROWTH: f64 = 1.1;

/// Where to cut a move of the polar plane that passes near the centre,
/// as parameters λ in (0, 1), increasing: on each piece the distance ρ
/// from the centre changes by at most a factor of `GROWTH` about the
/// nearest point, so the planner's caps, taken at a piece's least ρ
/// (planner.rs), slow the move near the centre only. Empty where ρ stays
/// within a factor of `SPAN`.
pub fn cuts(curve: &Curve) -> Vec<f64> {
    let near = curve.min_distance_to(V2::ZERO);
    let far = curve.point(0.0).norm().max(curve.end().norm());
    let mut cuts = Vec::new();
    let Some(nearest) = Nearest::of(curve) else {
        return cuts;
    };
    if !crate::math::is_pos(near) || far <= SPAN * near {
        return cuts;
    }
    for at in nearest.at() {
        // (At most 256 steps: ρ from the resolution to beyond any
        // machine's reach is about 220; were it more, the last piece would
        // only be capped more than it needs.)
        let mut rho = GROWTH * near;
        for _ in 0..256 {
            let Some(d) = nearest.reach(rho).filter(|_| rho < GROWTH * far) else {
                break;
            };
            cuts.extend(
                [at - d, at + d]
                    .into_iter()
                    .filter(|l| (1e-6..1.0 - 1e-6).contains(l)),
            );
            rho *= GROWTH;
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| *a - *b < 1e-6);
    cuts
}

/// How a line or an arc of the polar plane draws away from the centre:
/// where its nearest point is, and how far along ρ reaches a value.
enum Nearest {
    /// The foot of the perpendicular from the centre (λ, perhaps outside
    /// 0…1), the line's distance from the centre, its length.
    Line { foot: f64, lever: f64, len: f64 },
    /// The arc's λ at the circle's point nearest the centre (the next one
    /// a turn before too), the centre's distance, the radius, the sweep.
    Arc {
        at: f64,
        dist: f64,
        radius: f64,
        span: f64,
    },
}

impl Nearest {
    fn of(curve: &Curve) -> Option<Nearest> {
        match *curve {
            Curve::Line { p0, d } => {
                let len2 = d.dot(d);
                (len2 > 0.0).then(|| Nearest::Line {
                    foot: -p0.dot(d) / len2,
                    lever: curve.lever_about(V2::ZERO),
                    len: crate::math::sqrt(len2),
                })
            }
            Curve::Arc { c, u0, r0, dth, .. } => {
                let dist = c.norm();
                if dist == 0.0 || dth == 0.0 {
                    return None; // ρ stays the radius
                }
                // The direction from the centre towards the plane's centre,
                // reached after turning `reach` the arc's way.
                let reach = crate::geom::turn_to(u0, dth, c * (-1.0 / dist));
                Some(Nearest::Arc {
                    at: reach / dth.abs(),
                    dist,
                    radius: r0,
                    span: dth.abs(),
                })
            }
            Curve::Ellipse { .. } | Curve::Parabola { .. } => None,
        }
    }

    /// The λ of the nearest points the move may come near.
    fn at(&self) -> [f64; 2] {
        match *self {
            // (The same point twice: its cuts dedup.)
            Nearest::Line { foot, .. } => [foot, foot],
            Nearest::Arc { at, span, .. } => [at, at - 2.0 * core::f64::consts::PI / span],
        }
    }

    /// The change of λ from a nearest point at which ρ reaches `rho`;
    /// `None` where it never does.
    fn reach(&self, rho: f64) -> Option<f64> {
        match *self {
            Nearest::Line { lever, len, .. } => {
                Some(crate::math::sqrt((rho * rho - lever * lever).max(0.0)) / len)
            }
            Nearest::Arc {
                dist, radius, span, ..
            } => {
                // ρ² = dist² + radius² − 2·dist·radius·cos(turn)
                let cos = (dist * dist + radius * radius - rho * rho) / (2.0 * dist * radius);
                (cos >= -1.0).then(|| libm::acos(cos.min(1.0)) / span)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polar_joints_and_unwrapping() {
        let map = PlaneMap::Polar { z: -2.0 };
        // X20 C0 is the plane point (x 10, c 0).
        let at = map.point(20.0, 0.0);
        assert_eq!(at, V2::new(0.0, 10.0));
        let sw = PlaneSwitch {
            map: Some(map),
            at,
            c: 360.0,
            shift: V2::new(1.0, 5.0),
        };
        let mut run = PlaneRun::start(map, &sw);
        assert_eq!(run.axes(), V2::new(11.0, 3.0));
        // Around the centre counter-clockwise in quarter steps, (r, z) =
        // (c, x): 90°, 180°, −90° (= 270°), 0° (= 360°): C gains a whole
        // turn from where it started (360°).
        for (r, z) in [(10.0, 0.0), (0.0, -10.0), (-10.0, 0.0), (0.0, 10.0)] {
            run.follow(V2::new(r, z), -2.0);
        }
        assert!((run.c() - 720.0).abs() < 1e-9, "{}", run.c());
        // (x 3, c 4): radius 5, angle atan2(4, 3) = 53.1301°.
        // Z taken along to −3: the machine's Z is 5 lower.
        run.follow(V2::new(4.0, 3.0), -3.0);
        assert!((run.work().r - 5.0).abs() < 1e-12);
        assert_eq!(run.axes().z, 2.0);
        assert!((run.c() - 720.0 - 53.130_102_354).abs() < 1e-6);
    }

    #[test]
    fn a_move_near_the_centre_is_cut_where_its_distance_grows_by_a_tenth() {
        // Sampled, each piece's farthest point is at most 1.1 times as far
        // from the centre as its nearest: a line 0.5 from it, an arc
        // passing 0.25 from it, and (no cut) a line that stays within
        // twice its least distance.
        let o = V2::ZERO;
        let moves = [
            Curve::line(V2::new(0.5, 10.0), V2::new(0.5, -10.0)),
            Curve::line(V2::new(0.5, 10.0), V2::new(0.5, 0.0)),
            // About (r 0, z 10.25), radius 10, counter-clockwise (from +Z
            // towards +R) from (r 10) round through (r 0, z 0.25).
            Curve::arc(
                V2::new(10.0, 10.25),
                V2::new(-10.0, 10.25),
                V2::new(0.0, 10.25),
                true,
            ),
            Curve::line(V2::new(10.0, 10.0), V2::new(10.0, -10.0)),
        ];
        let counts: Vec<usize> = moves.iter().map(|m| cuts(m).len()).collect();
        for (m, k) in moves.iter().zip(&counts) {
            let mut bounds = alloc::vec![0.0];
            bounds.extend(cuts(m));
            bounds.push(1.0);
            for w in bounds.windows(2) {
                assert!(w[0] < w[1], "{bounds:?}");
                let d: Vec<f64> = (0..=1000)
                    .map(|i| {
                        m.point(w[0] + (w[1] - w[0]) * f64::from(i) / 1000.0)
                            .dist(o)
                    })
                    .collect();
                let (near, far) = d
                    .iter()
                    .fold((f64::MAX, 0f64), |(a, b), &x| (a.min(x), b.max(x)));
                let growth = if *k == 0 { 2.0 } else { 1.1 };
                assert!(
                    far <= growth * near * (1.0 + 1e-6),
                    "{m:?} {k}: {near}…{far}"
                );
            }
        }
        // The lines: from 0.5 the distance reaches 0.5·1.1^k for k = 1 …
        // 31 before the ends (10.01; 1.1^31 = 19.19, 1.1^32 = 21.11 >
        // 20.02): 31 cuts each side. The arc: from 0.25 it reaches
        // 0.25·1.1^k for k = 1 … 42 before its ends (√205 = 14.32;
        // 1.1^42 = 54.76, 1.1^43 = 60.24 > 57.27): 42 each side.
        assert_eq!(counts, [62, 31, 84, 0]);
    }

    #[test]
    fn cylinder_joints() {
        let map = PlaneMap::Cylinder {
            radius: 20.0,
            r: 15.0,
        };
        // Z−10 C90 on radius 20: s = 20·π/2.
        let p = map.point(-10.0, 90.0);
        assert!((p.z - 31.415_926_536).abs() < 1e-6 && p.r == -10.0);
        let (work, c) = map.joints(p);
        assert_eq!(work, V2::new(15.0, -10.0));
        assert!((c - 90.0).abs() < 1e-9);
    }
}
