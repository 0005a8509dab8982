//! The exact curves the interpolator follows, in slide coordinates.
//!
//! Every curve is parametrised by λ ∈ [0, 1]. Lines and arcs are evaluated
//! in closed form at λ = s / length, so the interpolated point is on the
//! curve to rounding; ellipses and parabolas have no closed-form arc
//! length, so the interpolator advances λ by a midpoint step of the arc
//! length (error O(ds³) per period) and lands on λ = 1 at the end.
//!
//! A line or an arc is the kernel's element ([`nc::geom::Element`]) put in
//! this form by [`Curve::of`]; the conics exist only here.

use crate::math::{is_pos, rem_euclid, sqrt, wrap_pi, TAU, V2};

#[derive(Debug, Clone, Copy, PartialEq)]
/// An exact curve, parametrised by λ ∈ [0, 1] over its length.
pub enum Curve {
    /// From `p0` by `d`.
    Line {
        /// Start.
        p0: V2,
        /// Start to end.
        d: V2,
    },
    /// Centre `c`; radius `r0 + dr·λ` (an end point off the circle by up
    /// to the arc tolerance makes a slight spiral, so both ends are
    /// exact); direction from the centre `u0` turned by `dth·λ` (dth > 0:
    /// CCW), `u1` at the end. Kept as vectors, not angles: a move needs
    /// one `atan2` to set up and one `sin`/`cos` pair per period.
    Arc {
        /// Centre.
        c: V2,
        /// Unit direction from the centre at the start.
        u0: V2,
        /// ... at the end.
        u1: V2,
        /// Radius at the start.
        r0: f64,
        /// Radius change over the arc.
        dr: f64,
        /// Swept angle, radians (> 0: CCW).
        dth: f64,
    },
    /// `c + u·a·cos t + w·b·sin t`, `t = t0 + dt·λ`, `w` = `u` turned +90°.
    Ellipse {
        /// Centre.
        c: V2,
        /// Unit direction of the `a` axis.
        u: V2,
        /// Semi-axis along `u`.
        a: f64,
        /// Semi-axis across `u`.
        b: f64,
        /// Parameter at the start.
        t0: f64,
        /// Parameter change over the curve.
        dt: f64,
    },
    /// Axis `u`, vertex at local y = y0 from `o` (the start): local
    /// y = `yend·λ`, x = y (y − 2y0) / 2p, which is (y − y0)² / 2p less
    /// its value at the start. (Written from the vertex, x is the
    /// difference of two numbers as large as y0²/2p: far out on a flat
    /// parabola, 10⁷ mm and more, whose rounding moved the point by
    /// nanometres from period to period, enough to break C's jerk limit
    /// near the centre of polar interpolation.)
    Parabola {
        /// Origin of the local frame.
        o: V2,
        /// Unit direction of the axis.
        u: V2,
        /// Parameter p.
        p: f64,
        /// Local y of the vertex.
        y0: f64,
        /// Local y at the end.
        yend: f64,
    },
}

/// Panels of the Simpson rule for the length of a conic.
const SIMPSON: usize = 64;

/// How much longer than 2a (mm) an ellipse's chord, stretched into a
/// circle's, may be: the kernel lets half of it exceed the radius by
/// 0.001 mm (dialect.md §4.1 rule 2), and the curve it accepted must be
/// the curve drawn.
const CHORD_SLACK: f64 = 0.002 + 1e-9;

/// The unit vector of a conic's axis at `q` radians from +Z, turned in the
/// G02 sense: towards −X (dialect.md §2.4; the kernel's `plan::conic`).
fn conic_axis(q: f64) -> V2 {
    V2::polar(-q)
}

/// `u` turned by `a` (from +Z towards +X).
#[inline]
fn turn(u: V2, a: f64) -> V2 {
    let (s, c) = crate::math::sin_cos(a);
    u * c + u.perp() * s
}

/// The angle in [0, 2π) from unit direction `u0` to unit direction `u`,
/// turning the way `dth` does (> 0: CCW).
pub(crate) fn turn_to(u0: V2, dth: f64, u: V2) -> f64 {
    let phi = libm::atan2(u0.z * u.r - u0.r * u.z, u0.dot(u));
    rem_euclid(phi * dth.signum(), TAU)
}

/// Whether turning from unit direction `u0` by `dth` passes through unit
/// direction `u`.
fn sweeps_through(u0: V2, dth: f64, u: V2) -> bool {
    turn_to(u0, dth, u) <= dth.abs()
}

impl Curve {
    /// The interpolation form of a kernel element.
    pub fn of(e: nc::geom::Element) -> Curve {
        match e {
            nc::geom::Element::Line { from, to } => Curve::line(from, to),
            nc::geom::Element::Arc {
                from,
                to,
                centre,
                cw,
            } => Curve::arc(from, to, centre, !cw),
        }
    }

    /// The straight line from `from` to `to`.
    pub fn line(from: V2, to: V2) -> Curve {
        Curve::Line {
            p0: from,
            d: to - from,
        }
    }

    /// An arc from `from` to `to` around `c`; `ccw` for G03. Equal end
    /// points make a full circle. A radius too small to define a direction
    /// degrades to a line, which still ends exactly on `to`.
    pub fn arc(from: V2, to: V2, c: V2, ccw: bool) -> Curve {
        let (a, b) = (from - c, to - c);
        let (r0, r1) = (a.norm(), b.norm());
        if !(r0 > 1e-9 && r1 > 1e-9 && c.is_finite()) {
            return Curve::line(from, to);
        }
        let (u0, u1) = (a * (1.0 / r0), b * (1.0 / r1));
        let full = (to - from).norm() < 1e-9;
        // The angle from u0 to u1 counter-clockwise, then into [0, 2π).
        let ang = libm::atan2(u0.z * u1.r - u0.r * u1.z, u0.dot(u1));
        let mut d = rem_euclid(if ccw { ang } else { -ang }, TAU);
        if full {
            d = TAU;
        }
        Curve::Arc {
            c,
            u0,
            u1,
            r0,
            dr: r1 - r0,
            dth: if ccw { d } else { -d },
        }
    }

    /// G6.2/G6.3: of the two ellipses with semi-axes `a` (along the angle
    /// `q` from +Z, turned in the G02 sense, towards −X: dialect.md §2.4)
    /// and `b` through both points, the one whose arc in the programmed
    /// direction is at most 180° (dialect.md §4.1). A chord up to
    /// `CHORD_SLACK` longer than 2a is a half ellipse, as the kernel takes
    /// it. `None` when no ellipse fits.
    pub fn ellipse(from: V2, to: V2, a: f64, b: f64, q_rad: f64, ccw: bool) -> Option<Curve> {
        if !(is_pos(a) && is_pos(b)) {
            return None;
        }
        let u = conic_axis(q_rad);
        let w = u.perp();
        // In a frame stretched along w by a/b the ellipse is a circle of
        // radius a; a positive stretch keeps the turning sense.
        let k = a / b;
        let e = to - from;
        let ep = V2::new(e.dot(w) * k, e.dot(u)); // (local y, local x)
        let chord = ep.norm();
        if !is_pos(chord - 1e-9) || chord > 2.0 * a + CHORD_SLACK {
            return None;
        }
        // A chord up to the slack longer than 2a: the half ellipse grown
        // by chord / 2a (its shape kept) so that it passes through both
        // points. Centred on the chord's middle with the axes as written,
        // it would start up to the slack away from the tool, a step in
        // one period (47 nm of C on a cylinder broke C's jerk 15 times).
        let (a, b) = match chord > 2.0 * a {
            true => (0.5 * chord, b * (0.5 * chord / a)),
            false => (a, b),
        };
        let mid = ep * 0.5;
        let h = sqrt((a * a - chord * chord * 0.25).max(0.0));
        // The centre lies left of the chord for a CCW arc of ≤ 180°.
        let left = ep.perp() * (1.0 / chord);
        let cp = if ccw { mid + left * h } else { mid - left * h };
        let ang = |p: V2| libm::atan2(p.r, p.z);
        let t0 = ang(V2::ZERO - cp);
        let t1 = ang(ep - cp);
        let mut dt = wrap_pi(t1 - t0);
        if ccw && dt < 0.0 {
            dt += TAU;
        } else if !ccw && dt > 0.0 {
            dt -= TAU;
        }
        let c = from + u * cp.z + w * (cp.r / k);
        Some(Curve::Ellipse { c, u, a, b, t0, dt })
    }

    /// G7.2/G7.3: the parabola y² = 2px with its axis at angle `q` from
    /// +Z (in the G02 sense, as an ellipse's) through both points, opening
    /// to the side that makes the arc turn in the programmed direction.
    /// `None` when the chord is parallel to the axis or `p` is 0.
    pub fn parabola(from: V2, to: V2, p: f64, q_rad: f64, ccw: bool) -> Option<Curve> {
        let p = p.abs();
        if !is_pos(p) {
            return None;
        }
        let u = conic_axis(q_rad);
        let w = u.perp();
        let e = to - from;
        let (xe, ye) = (e.dot(u), e.dot(w));
        if !is_pos(ye.abs() - 1e-9) {
            return None;
        }
        // Traversed towards +y the parabola opening to +x turns clockwise.
        let p = if ccw == (ye > 0.0) { -p } else { p };
        let y0 = (ye * ye - 2.0 * p * xe) / (2.0 * ye);
        Some(Curve::Parabola {
            o: from,
            u,
            p,
            y0,
            yend: ye,
        })
    }

    /// The point at parameter `lam` (0: start, 1: end).
    pub fn point(&self, lam: f64) -> V2 {
        match *self {
            Curve::Line { p0, d } => p0 + d * lam,
            Curve::Arc {
                c, u0, r0, dr, dth, ..
            } => c + turn(u0, dth * lam) * (r0 + dr * lam),
            Curve::Ellipse { c, u, a, b, t0, dt } => {
                let (s, k) = crate::math::sin_cos(t0 + dt * lam);
                c + u * (a * k) + u.perp() * (b * s)
            }
            Curve::Parabola { o, u, p, y0, yend } => {
                let y = yend * lam;
                let x = y * (y - 2.0 * y0) / (2.0 * p);
                o + u * x + u.perp() * y
            }
        }
    }

    /// dP/dλ.
    pub fn deriv(&self, lam: f64) -> V2 {
        match *self {
            Curve::Line { d, .. } => d,
            Curve::Arc {
                u0, r0, dr, dth, ..
            } => {
                let u = turn(u0, dth * lam);
                u * dr + u.perp() * ((r0 + dr * lam) * dth)
            }
            Curve::Ellipse {
                u, a, b, t0, dt, ..
            } => {
                let (s, k) = crate::math::sin_cos(t0 + dt * lam);
                (u * (-a * s) + u.perp() * (b * k)) * dt
            }
            Curve::Parabola { u, p, y0, yend, .. } => {
                let y = yend * lam;
                (u * ((y - y0) / p) + u.perp()) * yend
            }
        }
    }

    /// The length, mm.
    pub fn length(&self) -> f64 {
        match *self {
            Curve::Line { d, .. } => d.norm(),
            // (Lengths in mm: a plain square root cannot overflow, and
            // `libm::hypot`'s scaling costs as much as the rest of a push.)
            Curve::Arc { r0, dr, dth, .. } => {
                let arc = (r0 + 0.5 * dr) * dth;
                sqrt(dr * dr + arc * arc)
            }
            _ => {
                let h = 1.0 / SIMPSON as f64;
                let mut sum = self.deriv(0.0).norm() + self.deriv(1.0).norm();
                for i in 1..SIMPSON {
                    let w = if i % 2 == 1 { 4.0 } else { 2.0 };
                    sum += w * self.deriv(i as f64 * h).norm();
                }
                sum * h / 3.0
            }
        }
    }

    /// Whether λ = s / length exactly (lines, arcs).
    pub fn is_linear_in_length(&self) -> bool {
        matches!(self, Curve::Line { .. } | Curve::Arc { .. })
    }

    /// λ after moving `ds` further from `lam` (conics: a Runge–Kutta
    /// step of dλ/ds = 1/|dP/dλ|, whose error over a curve stays far below
    /// a nanometre; the midpoint step it replaced drifted by 15 nm along
    /// a flat ellipse, which the end point then took in one period).
    pub fn advance(&self, lam: f64, s_after: f64, ds: f64, len: f64) -> f64 {
        if self.is_linear_in_length() || len <= 0.0 {
            return if len > 0.0 {
                (s_after / len).min(1.0)
            } else {
                1.0
            };
        }
        let rate = |l: f64| 1.0 / self.deriv(l.clamp(0.0, 1.0)).norm().max(1e-12);
        let k1 = rate(lam);
        let k2 = rate(lam + 0.5 * ds * k1);
        let k3 = rate(lam + 0.5 * ds * k2);
        let k4 = rate(lam + ds * k3);
        (lam + ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)).clamp(0.0, 1.0)
    }

    /// The unit tangent at λ.
    pub fn tangent(&self, lam: f64) -> V2 {
        self.deriv(lam).unit()
    }

    /// The unit tangents at both ends (without trigonometry for arcs).
    pub fn end_tangents(&self) -> (V2, V2) {
        match *self {
            Curve::Line { d, .. } => {
                let u = d.unit();
                (u, u)
            }
            Curve::Arc {
                u0,
                u1,
                r0,
                dr,
                dth,
                ..
            } => (
                (u0 * dr + u0.perp() * (r0 * dth)).unit(),
                (u1 * dr + u1.perp() * ((r0 + dr) * dth)).unit(),
            ),
            _ => (self.tangent(0.0), self.tangent(1.0)),
        }
    }

    /// A lower bound of the radius of curvature (∞ for a line).
    pub fn min_radius(&self) -> f64 {
        match *self {
            Curve::Line { .. } => f64::INFINITY,
            Curve::Arc { r0, dr, .. } => r0.min(r0 + dr),
            Curve::Ellipse { a, b, .. } => b * b / a,
            Curve::Parabola { p, .. } => p.abs(),
        }
    }

    /// The largest rate |dκ/ds| at which the curvature changes along the
    /// curve, 1/mm², over the whole ellipse or parabola it is a piece of
    /// (0 for lines and arcs). Ellipse (x, y) = (a cos t, b sin t), a ≥ b,
    /// c = a² − b²: dκ/ds = −(3/2)·a·b·c·sin 2t / D³ with D = a² sin² t +
    /// b² cos² t; in s = sin² t its square is largest where 4c·s² −
    /// (5c + 2b²)·s + b² = 0 (the root in 0…1). Parabola y² = 2px: dκ/ds
    /// = −3u / (p²(1 + u²)³) with u = y/p, largest at u = 1/√5:
    /// 3·5^(5/2)/(6³·p²) = 0.7765/p².
    pub fn max_curvature_rate(&self) -> f64 {
        match *self {
            Curve::Line { .. } | Curve::Arc { .. } => 0.0,
            Curve::Ellipse { a, b, .. } => {
                let (a, b) = (a.max(b), a.min(b));
                let c = a * a - b * b;
                if !is_pos(c) {
                    return 0.0;
                }
                let m = 5.0 * c + 2.0 * b * b;
                let s = (m - sqrt((m * m - 16.0 * c * b * b).max(0.0))) / (8.0 * c);
                let d = b * b + c * s;
                1.5 * a * b * c * 2.0 * sqrt((s * (1.0 - s)).max(0.0)) / (d * d * d)
            }
            Curve::Parabola { p, .. } => 3.0 * libm::pow(5.0, 2.5) / (216.0 * p * p),
        }
    }

    /// A lower bound of the distance from point `p` to the curve: exact
    /// for a line and a circular arc (a slight spiral counts its smaller
    /// radius), the nearer end or the sampled points' less one step for
    /// the conics (polar.rs bounds a conic of the polar plane point by
    /// point).
    pub fn min_distance_to(&self, p: V2) -> f64 {
        let ends = self.point(0.0).dist(p).min(self.end().dist(p));
        match *self {
            Curve::Line { p0, d } => {
                let len2 = d.dot(d);
                if len2 == 0.0 {
                    return ends;
                }
                let t = ((p - p0).dot(d) / len2).clamp(0.0, 1.0);
                (p0 + d * t).dist(p)
            }
            Curve::Arc {
                c, u0, r0, dr, dth, ..
            } => {
                let off = p - c;
                let dist = off.norm();
                let (near_r, far_r) = (r0.min(r0 + dr), r0.max(r0 + dr));
                if dist == 0.0 {
                    return near_r;
                }
                // The circle's nearest point lies towards `p` from the
                // centre: on the arc when the sweep reaches its direction.
                if !sweeps_through(u0, dth, off * (1.0 / dist)) {
                    return ends;
                }
                if dist < near_r {
                    near_r - dist
                } else {
                    (dist - far_r).max(0.0)
                }
            }
            Curve::Ellipse { .. } | Curve::Parabola { .. } => {
                let n = 64;
                let mut best = ends;
                let mut prev = self.point(0.0);
                for k in 1..=n {
                    let next = self.point(f64::from(k) / f64::from(n));
                    // A chord's points lie within half its length of an end.
                    best = best.min(next.dist(p) - 0.5 * prev.dist(next));
                    prev = next;
                }
                best.max(0.0)
            }
        }
    }

    /// An upper bound of the lever of the curve's direction about point
    /// `p`: |(q − p) × t| over its points q, t the unit tangent there. At
    /// path speed v the direction from `p` turns at most v·lever/ρ², ρ the
    /// distance from `p`. A line's is its distance from `p` extended; an
    /// arc's the largest |r + (c − p)·u| over its points c + r·u; a
    /// conic's its farthest point's distance.
    pub fn lever_about(&self, p: V2) -> f64 {
        match *self {
            Curve::Line { p0, d } => {
                let len = d.norm();
                if len == 0.0 {
                    return 0.0;
                }
                let q = p0 - p;
                (q.z * d.r - q.r * d.z).abs() / len
            }
            Curve::Arc {
                c,
                u0,
                u1,
                r0,
                dr,
                dth,
            } => {
                // At the point c + r·u the lever is |r + (c − p)·u|, at
                // its largest at an end or where the arc turns through the
                // direction of c − p (r + |c − p|) or the opposite one
                // (|r − |c − p||); a spiral's r anywhere between its ends'.
                let q = c - p;
                let d = q.norm();
                let (r1, mut lever) = (r0 + dr, 0.0f64);
                for (r, u) in [(r0, u0), (r1, u1)] {
                    lever = lever.max((r + q.dot(u)).abs() + dr.abs());
                }
                if d > 0.0 {
                    let v = q * (1.0 / d);
                    if sweeps_through(u0, dth, v) {
                        lever = lever.max(r0.max(r1) + d);
                    }
                    if sweeps_through(u0, dth, -v) {
                        lever = lever.max((r0 - d).abs().max((r1 - d).abs()));
                    }
                }
                lever
            }
            Curve::Ellipse { .. } | Curve::Parabola { .. } => {
                let n = 64;
                let mut far: f64 = 0.0;
                let mut prev = self.point(0.0);
                for k in 0..=n {
                    let next = self.point(f64::from(k) / f64::from(n));
                    far = far.max(next.dist(p) + 0.5 * prev.dist(next));
                    prev = next;
                }
                far
            }
        }
    }

    /// The end point (exact for every kind).
    pub fn end(&self) -> V2 {
        self.point(1.0)
    }

    /// λ at which the long-axis coordinate has moved `q` from the start
    /// (threads: lines exactly, arcs by Newton from `guess`).
    pub fn lam_at_long(&self, long_z: bool, q: f64, total: f64, guess: f64) -> f64 {
        if total <= 0.0 {
            return 1.0;
        }
        if let Curve::Line { .. } = self {
            return (q / total).clamp(0.0, 1.0);
        }
        let p0 = self.point(0.0);
        let comp = |v: V2| if long_z { v.z } else { v.r };
        let mut lam = guess.clamp(0.0, 1.0);
        for _ in 0..8 {
            let f = (comp(self.point(lam) - p0)).abs() - q;
            let df = comp(self.deriv(lam)).abs().max(1e-9);
            let next = (lam - f / df).clamp(0.0, 1.0);
            if (next - lam).abs() < 1e-13 {
                return next;
            }
            lam = next;
        }
        lam
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: V2, b: V2) -> bool {
        (a - b).norm() < 1e-9
    }

    #[test]
    fn arcs_end_exactly_and_turn_the_right_way() {
        // Quarter circle CCW from (r 10, z 0) about (r 0, z 0) to (r 0, z 10)?
        // Angles run from +Z towards +X: (r 10, z 0) is at 90°.
        let from = V2::new(10.0, 0.0);
        let to = V2::new(0.0, 10.0);
        let a = Curve::arc(from, to, V2::ZERO, false);
        assert!(near(a.point(0.0), from) && near(a.point(1.0), to));
        assert!((a.length() - 10.0 * core::f64::consts::FRAC_PI_2).abs() < 1e-9);
        let b = Curve::arc(from, to, V2::ZERO, true);
        assert!((b.length() - 30.0 * core::f64::consts::FRAC_PI_2).abs() < 1e-9);
        let full = Curve::arc(from, from, V2::ZERO, true);
        assert!((full.length() - 20.0 * core::f64::consts::PI).abs() < 1e-9);
    }

    #[test]
    fn the_distance_to_a_point_is_the_nearest_of_the_curve() {
        // Sampled densely, no point of the curve is nearer than the bound,
        // and for lines and arcs the bound is reached within the sampling.
        let o = V2::ZERO;
        let curves = [
            // A line passing 5 from the origin, and one ending before its
            // foot (nearest: its end (r 3, z 4), 5 away).
            (Curve::line(V2::new(5.0, -10.0), V2::new(5.0, 10.0)), 5.0),
            (Curve::line(V2::new(3.0, 4.0), V2::new(3.0, 10.0)), 5.0),
            // About (r 0, z 10), radius 10 (`arc`'s last argument: CCW,
            // angles from +Z towards +R): from (r 0, z 20) CW through
            // (r −10, z 10) to the origin itself: 0.
            (
                Curve::arc(
                    V2::new(0.0, 20.0),
                    V2::new(0.0, 0.0),
                    V2::new(0.0, 10.0),
                    false,
                ),
                0.0,
            ),
            // The same circle CW the short way from (r 10, z 10) to (r 0,
            // z 20): its nearest point is the start, √200 away; CCW the
            // long way it passes the origin.
            (
                Curve::arc(
                    V2::new(10.0, 10.0),
                    V2::new(0.0, 20.0),
                    V2::new(0.0, 10.0),
                    false,
                ),
                200f64.sqrt(),
            ),
            (
                Curve::arc(
                    V2::new(10.0, 10.0),
                    V2::new(0.0, 20.0),
                    V2::new(0.0, 10.0),
                    true,
                ),
                0.0,
            ),
            // A circle about the origin: its radius.
            (
                Curve::arc(V2::new(7.0, 0.0), V2::new(7.0, 0.0), o, true),
                7.0,
            ),
        ];
        for (curve, want) in curves {
            let bound = curve.min_distance_to(o);
            let sampled = (0..=100_000)
                .map(|k| curve.point(f64::from(k) / 1e5).dist(o))
                .fold(f64::INFINITY, f64::min);
            assert!(bound <= sampled + 1e-12, "{curve:?}: {bound} > {sampled}");
            assert!(
                (bound - want).abs() < 1e-9,
                "{curve:?}: {bound}, not {want}"
            );
            assert!(
                sampled - bound < 1e-3,
                "{curve:?}: {bound} far below {sampled}"
            );
        }
    }

    #[test]
    fn the_lever_bounds_how_fast_the_direction_from_a_point_turns() {
        // |(q − p) × t| sampled along each curve stays within the lever;
        // a line's is reached everywhere (its distance extended: 5).
        let o = V2::ZERO;
        let curves = [
            Curve::line(V2::new(5.0, -10.0), V2::new(5.0, 3.0)),
            Curve::arc(
                V2::new(10.0, 10.0),
                V2::new(0.0, 20.0),
                V2::new(0.0, 10.0),
                true,
            ),
            Curve::arc(V2::new(7.0, 0.0), V2::new(7.0, 0.0), o, true),
            // About (r 0, z 10), radius 2, from (r 2) CCW (from +Z to +R,
            // so from 90° on to 180°) through (z 8), the point nearest the
            // origin, where the lever is 10 − 2 = 8 (at the ends 2); CW
            // through (z 12), where it is 12.
            Curve::arc(
                V2::new(2.0, 10.0),
                V2::new(-2.0, 10.0),
                V2::new(0.0, 10.0),
                true,
            ),
            Curve::arc(
                V2::new(2.0, 10.0),
                V2::new(-2.0, 10.0),
                V2::new(0.0, 10.0),
                false,
            ),
        ];
        for curve in curves {
            let lever = curve.lever_about(o);
            for k in 0..=1000 {
                let lam = f64::from(k) / 1000.0;
                let (q, t) = (curve.point(lam), curve.tangent(lam));
                let arm = (q.z * t.r - q.r * t.z).abs();
                assert!(arm <= lever + 1e-9, "{curve:?} at {lam}: {arm} > {lever}");
            }
        }
        let line = Curve::line(V2::new(5.0, -10.0), V2::new(5.0, 3.0));
        assert!((line.lever_about(o) - 5.0).abs() < 1e-12);
        let arc = |ccw| {
            Curve::arc(
                V2::new(2.0, 10.0),
                V2::new(-2.0, 10.0),
                V2::new(0.0, 10.0),
                ccw,
            )
        };
        assert!((arc(true).lever_about(o) - 8.0).abs() < 1e-12);
        assert!((arc(false).lever_about(o) - 12.0).abs() < 1e-12);
        // The circle about the origin turns its direction at v/r: lever r.
        let circle = Curve::arc(V2::new(7.0, 0.0), V2::new(7.0, 0.0), o, true);
        assert!((circle.lever_about(o) - 7.0).abs() < 1e-12);
    }

    #[test]
    fn a_kernel_element_becomes_the_same_curve() {
        use nc::geom::Element;
        // G02 (cw) from (r 10, z 0) to (r 0, z 10) about the origin: in the
        // ZX view (Z right, X up) clockwise from 90° down to 0° is a quarter
        // circle, 5π long; G03 the other three quarters, 15π.
        let (from, to) = (V2::new(10.0, 0.0), V2::new(0.0, 10.0));
        let arc = |cw| Element::Arc {
            from,
            to,
            centre: V2::ZERO,
            cw,
        };
        let g02 = Curve::of(arc(true));
        assert!((g02.length() - 5.0 * core::f64::consts::PI).abs() < 1e-9);
        let g03 = Curve::of(arc(false));
        assert!((g03.length() - 15.0 * core::f64::consts::PI).abs() < 1e-9);
        assert!(near(
            g02.point(0.5),
            V2::new(10.0, 10.0) * (0.5 * core::f64::consts::SQRT_2)
        ));
        assert_eq!(Curve::of(Element::Line { from, to }), Curve::line(from, to));
    }

    #[test]
    fn ellipse_passes_through_both_points() {
        let from = V2::new(5.0, 0.0);
        let to = V2::new(10.0, -12.0);
        for &ccw in &[false, true] {
            let e = Curve::ellipse(from, to, 10.0, 6.0, 0.3, ccw).unwrap();
            assert!(near(e.point(0.0), from), "{e:?}");
            assert!(near(e.point(1.0), to), "{e:?}");
            if let Curve::Ellipse { dt, .. } = e {
                assert!(dt.abs() <= core::f64::consts::PI + 1e-12);
                assert_eq!(dt > 0.0, ccw);
            }
        }
        assert!(Curve::ellipse(from, to, 1.0, 0.5, 0.0, true).is_none());
        // A half ellipse whose chord is 0.0015 mm longer than 2a, as the
        // kernel accepts it (half the chord within 0.001 of a), is drawn.
        let far = V2::new(5.0, -20.0015);
        let half = Curve::ellipse(from, far, 10.0, 6.0, 0.0, true).unwrap();
        // It starts and ends on the points, to far less than a nanometre.
        let gap = |p: V2, q: V2| (p - q).norm();
        assert!(gap(half.point(0.0), from) < 1e-12, "{half:?}");
        assert!(gap(half.point(1.0), far) < 1e-12, "{half:?}");
        assert!(Curve::ellipse(from, V2::new(5.0, -20.003), 10.0, 6.0, 0.0, true).is_none());
    }

    #[test]
    fn parabola_passes_through_both_points_and_turns() {
        let from = V2::new(2.0, 0.0);
        let to = V2::new(8.0, -9.0);
        for &ccw in &[false, true] {
            let p = Curve::parabola(from, to, 3.0, 0.0, ccw).unwrap();
            assert!(near(p.point(0.0), from));
            assert!(near(p.point(1.0), to));
            // Turning sense: cross product of successive tangents.
            let t0 = p.tangent(0.2);
            let t1 = p.tangent(0.8);
            let cross = t0.z * t1.r - t0.r * t1.z;
            assert_eq!(cross > 0.0, ccw, "{p:?}");
        }
    }

    #[test]
    fn a_far_flat_parabola_is_smooth_to_the_last_digits() {
        // The plane fuzz target's parabola: 48 mm across 0.078 mm, P
        // 53.464, its vertex about 10⁷ mm away (the plane's first axis in
        // Z's place, C in X's). Points even in λ lie even in the local y,
        // and the local x is quadratic in y, so the third differences of
        // the points vanish but for rounding at the size of the
        // coordinates (tens of mm: 10⁻¹⁴).
        let from = V2::new(0.0, 20.0);
        let to = V2::new(-0.078, -28.1175);
        let p = Curve::parabola(from, to, 53.464, 0.0, false).unwrap();
        let at = |i: i32| p.point(f64::from(i) / 1000.0);
        for i in 0..997 {
            let d3 = at(i + 3) - at(i + 2) * 3.0 + at(i + 1) * 3.0 - at(i);
            assert!(d3.norm() < 1e-12, "{d3:?}");
        }
    }

    #[test]
    fn the_curvature_rate_is_the_largest_along_the_curve() {
        // Against the curvature of 200 000 points of each, from the
        // formula κ = |x′y″ − y′x″| / |(x′, y′)|³ and differences.
        let ellipse = |t: f64| {
            let (a, b) = (7.5f64, 2.25f64);
            let (d1, d2) = ((-a * t.sin(), b * t.cos()), (-a * t.cos(), -b * t.sin()));
            let speed = d1.0.hypot(d1.1);
            ((d1.0 * d2.1 - d1.1 * d2.0).abs() / speed.powi(3), speed)
        };
        let parabola = |y: f64| {
            let p = 1.5f64;
            // x = y²/2p: x′ = y/p, x″ = 1/p.
            let speed = (y / p).hypot(1.0);
            ((1.0 / p) / speed.powi(3), speed)
        };
        let rate = |f: &dyn Fn(f64) -> (f64, f64), lo: f64, hi: f64| {
            let n = 200_000;
            let h = (hi - lo) / f64::from(n);
            (0..n)
                .map(|i| {
                    let t = lo + h * f64::from(i);
                    let ((k0, s0), (k1, s1)) = (f(t), f(t + h));
                    (k1 - k0).abs() / (0.5 * (s0 + s1) * h)
                })
                .fold(0.0, f64::max)
        };
        let e = Curve::ellipse(V2::new(0.0, 7.5), V2::new(0.0, -7.5), 7.5, 2.25, 0.0, true)
            .expect("an ellipse");
        let want = rate(&ellipse, 0.0, core::f64::consts::PI);
        assert!(
            (e.max_curvature_rate() - want).abs() < 1e-3 * want,
            "{want}"
        );
        let p = Curve::parabola(V2::new(-3.0, 3.0), V2::new(3.0, 3.0), 1.5, 0.0, true)
            .expect("a parabola");
        let want = rate(&parabola, -20.0, 20.0);
        assert!(
            (p.max_curvature_rate() - want).abs() < 1e-3 * want,
            "{want}"
        );
        assert_eq!(
            Curve::line(V2::ZERO, V2::new(1.0, 1.0)).max_curvature_rate(),
            0.0
        );
    }

    #[test]
    fn conic_advance_follows_arc_length() {
        let e = Curve::ellipse(
            V2::new(5.0, 0.0),
            V2::new(10.0, -12.0),
            10.0,
            6.0,
            0.3,
            false,
        )
        .unwrap();
        let len = e.length();
        let (mut s, mut lam) = (0.0, 0.0);
        let ds = 0.01;
        while s + ds < len {
            s += ds;
            lam = e.advance(lam, s, ds, len);
        }
        // The drift over the whole curve stays far below the resolution.
        let rest = (e.point(1.0) - e.point(lam)).norm();
        assert!(
            (rest - (len - s)).abs() < 1e-6,
            "rest {rest} vs {}",
            len - s
        );
    }
}
