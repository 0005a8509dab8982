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

    /// The joints (work coordinates) at plane point `p` with the axis
    /// outside the plane at `held`.
    pub fn joints_at(&self, p: V2, held: f64) -> V2 {
        self.map.with_held(held).joints(p).0
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

/// What the polar plane's caps need of a move's path about the centre
/// (planner.rs, `plane_limits`): upper bounds, over the path's points q,
/// of h/ρ² (C's turn per mm of path), h²/ρ³ (X's bend) and κ/ρ + 2h/ρ³
/// (C's acceleration per (mm/s)²), where ρ = |q| (at least a floor), h =
/// |q × t| the lever of the direction t about the centre and κ the
/// curvature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentreBounds {
    /// h/ρ².
    pub turn: f64,
    /// h²/ρ³.
    pub bend: f64,
    /// κ/ρ + 2h/ρ³.
    pub spin: f64,
}

/// Samples of an ellipse or a parabola for its [`CentreBounds`].
const CONIC_SAMPLES: u32 = 256;

impl CentreBounds {
    /// The bounds of `curve`, ρ at least `floor`. A line or an arc takes
    /// them at its least distance and its largest lever (geom.rs, exact);
    /// an ellipse or a parabola, whose nearest point and largest lever
    /// lie far apart (a half ellipse about the centre ran at half its F
    /// so), piece by piece between samples.
    pub fn of(curve: &Curve, floor: f64) -> CentreBounds {
        let k = 1.0 / curve.min_radius();
        match curve {
            Curve::Ellipse { .. } | Curve::Parabola { .. } => {
                CentreBounds::sampled(curve, floor, k)
            }
            _ => {
                let rho = curve.min_distance_to(V2::ZERO).max(floor);
                CentreBounds::at(rho, curve.lever_about(V2::ZERO), k)
            }
        }
    }

    fn at(rho: f64, h: f64, k: f64) -> CentreBounds {
        let rho3 = rho * rho * rho;
        CentreBounds {
            turn: h / (rho * rho),
            bend: h * h / rho3,
            spin: k / rho + 2.0 * h / rho3,
        }
    }

    /// Between two samples the path runs at most L (the conic's top speed
    /// dP/dλ over the step of λ), so ρ lies within L/2 of the nearer
    /// sample's and h, which changes by κ·(q·n) ≤ κ·ρ a mm, within κ·ρ·L/2
    /// of the larger one's.
    fn sampled(curve: &Curve, floor: f64, k: f64) -> CentreBounds {
        let n = f64::from(CONIC_SAMPLES);
        let speed = match *curve {
            Curve::Ellipse { a, b, dt, .. } => a.max(b) * dt.abs(),
            _ => curve.deriv(0.0).norm().max(curve.deriv(1.0).norm()),
        };
        let half = 0.5 * speed / n;
        let at = |i: u32| {
            let lam = f64::from(i) / n;
            let (q, t) = (curve.point(lam), curve.tangent(lam));
            (q.norm(), (q.z * t.r - q.r * t.z).abs())
        };
        let mut prev = at(0);
        let mut b = CentreBounds::at(f64::INFINITY, 0.0, 0.0);
        for i in 1..=CONIC_SAMPLES {
            let next = at(i);
            let rho = (prev.0.min(next.0) - half).max(floor);
            let far = prev.0.max(next.0) + half;
            let piece = CentreBounds::at(rho, prev.1.max(next.1) + k * far * half, k);
            b = CentreBounds {
                turn: b.turn.max(piece.turn),
                bend: b.bend.max(piece.bend),
                spin: b.spin.max(piece.spin),
            };
            prev = next;
        }
        b
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
/// within a factor of `SPAN`. An ellipse or a parabola is halved instead
/// where its samples' ρ grows by more than `GROWTH` (`conic_cuts`).
pub fn cuts(curve: &Curve) -> Vec<f64> {
    if let Curve::Ellipse { .. } | Curve::Parabola { .. } = curve {
        return conic_cuts(curve);
    }
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

/// Halvings of a conic at most (a piece of 2⁻²⁴ of it).
const CONIC_DEPTH: u32 = 24;

/// The cuts of an ellipse or a parabola whose distance from the centre
/// more than doubles along it: halves, recursively, of each piece whose
/// samples' distance grows by more than `GROWTH` (9 samples a piece:
/// the cuts only have to make the pieces short near the centre, where
/// ρ changes fast; [`CentreBounds`] bounds each piece exactly).
fn conic_cuts(curve: &Curve) -> Vec<f64> {
    let spread = |l0: f64, l1: f64, n: u32| {
        (0..=n).fold((f64::INFINITY, 0.0f64), |(near, far), i| {
            let rho = curve
                .point(l0 + (l1 - l0) * f64::from(i) / f64::from(n))
                .norm();
            (near.min(rho), far.max(rho))
        })
    };
    let (near, far) = spread(0.0, 1.0, 64);
    let mut cuts = Vec::new();
    if crate::math::is_pos(near) && far > SPAN * near {
        halve(&spread, (0.0, 1.0), 0, &mut cuts);
    }
    cuts
}

/// Adds the cuts of the piece `(l0, l1)` in order (`conic_cuts`).
fn halve(
    spread: &impl Fn(f64, f64, u32) -> (f64, f64),
    (l0, l1): (f64, f64),
    depth: u32,
    cuts: &mut Vec<f64>,
) {
    let (near, far) = spread(l0, l1, 8);
    if far <= GROWTH * near || depth >= CONIC_DEPTH {
        return;
    }
    let mid = (l0 + l1) / 2.0;
    halve(spread, (l0, mid), depth + 1, cuts);
    cuts.push(mid);
    halve(spread, (mid, l1), depth + 1, cuts);
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
    fn the_centre_bounds_of_an_ellipse_hold_its_points_closely() {
        // The half ellipse (x, c) = (20 cos t, 10 sin t), t from 0 to π
        // (plane points V2(c, x)): h/ρ² and h²/ρ³ over 100 000 of its
        // points, h = |q × q′|/|q′|, from the formula, not the runtime's
        // curve.
        let curve = Curve::ellipse(
            V2::new(0.0, 20.0),
            V2::new(0.0, -20.0),
            20.0,
            10.0,
            0.0,
            true,
        )
        .expect("an ellipse");
        let (mut turn, mut bend) = (0f64, 0f64);
        for i in 0..=100_000 {
            let t = core::f64::consts::PI * f64::from(i) / 100_000.0;
            let (x, c) = (20.0 * t.cos(), 10.0 * t.sin());
            let (dx, dc) = (-20.0 * t.sin(), 10.0 * t.cos());
            let rho = x.hypot(c);
            let h = (x * dc - c * dx).abs() / dx.hypot(dc);
            turn = turn.max(h / (rho * rho));
            bend = bend.max(h * h / (rho * rho * rho));
        }
        // (At (0, 10): h = ρ = 10, 0.1.) The bounds are within 6 and 10 % (256
        // samples, the curvature taken at its largest, B²/A = 5 mm).
        assert!((turn - 0.1).abs() < 1e-6, "{turn}");
        let b = CentreBounds::of(&curve, 0.001);
        assert!(b.turn >= turn && b.turn <= 1.06 * turn, "{} {turn}", b.turn);
        assert!(b.bend >= bend && b.bend <= 1.1 * bend, "{} {bend}", b.bend);
    }

    #[test]
    fn a_parabola_near_the_centre_is_cut_where_its_distance_grows() {
        // x = u0 + c²/2.6 (P 1.3, its axis along x) through (10, ±5):
        // u0 = 10 − 25/2.6 = 0.385, its vertex that far from the centre.
        // Of the two senses the one opening towards +x holds it.
        let (from, to) = (V2::new(-5.0, 10.0), V2::new(5.0, 10.0));
        let curve = [true, false]
            .into_iter()
            .filter_map(|ccw| Curve::parabola(from, to, 1.3, 0.0, ccw))
            .find(|c| c.point(0.5).norm() < 1.0)
            .expect("the parabola opening towards +x");
        assert!((curve.point(0.5).norm() - (10.0 - 25.0 / 2.6)).abs() < 1e-9);
        let mut bounds = alloc::vec![0.0];
        bounds.extend(cuts(&curve));
        bounds.push(1.0);
        // From 0.385 to 11.18 (√125) on each side: 1.1^k for k up to 35.
        assert!((40..400).contains(&bounds.len()), "{}", bounds.len());
        for w in bounds.windows(2) {
            assert!(w[0] < w[1], "{bounds:?}");
            let d: Vec<f64> = (0..=200)
                .map(|i| {
                    curve
                        .point(w[0] + (w[1] - w[0]) * f64::from(i) / 200.0)
                        .norm()
                })
                .collect();
            let (near, far) = d
                .iter()
                .fold((f64::MAX, 0f64), |(a, b), &x| (a.min(x), b.max(x)));
            assert!(far <= 1.2 * near, "{w:?}: {near}…{far}");
        }
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
