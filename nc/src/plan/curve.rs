//! Contour elements as parametric curves: a point at every parameter
//! s ∈ [0, 1], where a coordinate crosses a level, where it has an extreme.
//! The roughing cycles cut elements at levels and walk them in pieces, so
//! they work on parameter ranges of whole elements rather than building
//! new, possibly degenerate, arcs.

use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::plan::elem::{dot, left, norm, scale};
use core::f64::consts::{FRAC_PI_2, PI, TAU};

/// Points and levels closer than this (mm) are the same (cycles.md §0).
pub const EPS: f64 = 1e-6;

/// How far an arc may turn back past an extreme point and still count as
/// monotonic (mm). Programs give their points to 0.001 mm, so the arc
/// through a rounded tangent point can dip a few µm past the tangent: that
/// is rounding, not a profile turning back.
pub const SLACK: f64 = 1e-3;

/// A few curve parameters, kept in place: a curve has at most two roots
/// or extremes on an axis, and the roughing cycles ask for them for every
/// element at every level, so they are no heap vectors. Room for four
/// (the two ends and two extremes between them).
#[derive(Debug, Clone, Copy, Default)]
pub struct Params {
    v: [f64; 4],
    n: usize,
}

impl Params {
    /// Adds a parameter; the capacity is what the curves need (above),
    /// and a fifth would be dropped rather than panic.
    pub fn push(&mut self, s: f64) {
        if let Some(slot) = self.v.get_mut(self.n) {
            *slot = s;
            self.n += 1;
        }
    }

    fn of(values: impl IntoIterator<Item = f64>) -> Params {
        let mut out = Params::default();
        for s in values {
            out.push(s);
        }
        out
    }

    /// In order, the ones within 1e-12 of the one before dropped.
    fn sorted(mut self) -> Params {
        self.v[..self.n].sort_by(f64::total_cmp);
        let mut kept = Params::default();
        for &s in self.iter() {
            if kept.last().is_none_or(|&k| (s - k).abs() >= 1e-12) {
                kept.push(s);
            }
        }
        kept
    }
}

impl core::ops::Deref for Params {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.v[..self.n]
    }
}

impl IntoIterator for Params {
    type Item = f64;
    type IntoIter = core::iter::Take<core::array::IntoIter<f64, 4>>;
    fn into_iter(self) -> Self::IntoIter {
        self.v.into_iter().take(self.n)
    }
}

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

/// What a conic of a profile prints as: the words of its block, in real
/// (program) coordinates, whatever frame the cycle computes in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConicKind {
    /// G6.2/G6.3: semi-axes A, B (mm), axis angle Q (degrees).
    Ellipse { a: f64, b: f64, q: f64 },
    /// G7.2/G7.3: parameter p (mm), axis angle Q (degrees).
    Parabola { p: f64, q: f64 },
}

/// A line, an arc or a conic with its parameters resolved once, for the
/// roughing cycles' searches ([`Curve::new`] and [`Curve::element`] convert
/// lines and arcs). Angles are measured in the (z, r) plane from +Z towards
/// +r, so G03 (counter-clockwise in the ZX view) has a positive sweep.
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
    /// An ellipse or parabola as p(τ) = origin + e1·f1(τ) + e2·f2(τ), with
    /// (f1, f2) = (cos τ, sin τ) for an ellipse (origin its centre, e1 and
    /// e2 its semi-axes as vectors) and (τ², τ) for a parabola (origin its
    /// vertex; its points are taken from `from`). τ runs linearly from
    /// `t0` to `t1` over s ∈ [0, 1]. This form survives the moves and the
    /// mirror of the cycles unchanged.
    Conic {
        from: Pt,
        to: Pt,
        origin: Pt,
        e1: Pt,
        e2: Pt,
        t0: f64,
        t1: f64,
        kind: ConicKind,
        cw: bool,
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

    /// The ellipse from `from` to `to` about `centre`, semi-axis `a` along
    /// the axis at `q_deg` (from +Z in the G02 sense, `plan::conic`) and
    /// `b` across it, the way `cw` says, in at most 180°.
    pub fn ellipse(from: Pt, to: Pt, centre: Pt, a: f64, b: f64, q_deg: f64, cw: bool) -> Curve {
        let (u, v) = conic_axes(q_deg);
        let param = |p: Pt| {
            let d = p.sub(centre);
            libm::atan2(dot(d, v) / b, dot(d, u) / a)
        };
        let t0 = param(from);
        let turn =
            crate::base::geom::rem_euclid(if cw { t0 - param(to) } else { param(to) - t0 }, TAU);
        Curve::Conic {
            from,
            to,
            origin: centre,
            e1: scale(u, a),
            e2: scale(v, b),
            t0,
            t1: if cw { t0 - turn } else { t0 + turn },
            kind: ConicKind::Ellipse { a, b, q: q_deg },
            cw,
        }
    }

    /// The parabola y² = 2px from `from` to `to` with its vertex at
    /// `vertex` and its axis at `q_deg` (`plan::conic::parabola_vertex`).
    pub fn parabola(from: Pt, to: Pt, vertex: Pt, p: f64, q_deg: f64, cw: bool) -> Curve {
        let (u, v) = conic_axes(q_deg);
        // Across the axis τ = the distance from the axis; along it the
        // curve opens towards +u or −u, whichever holds the points.
        let (w0, w1) = (dot(from.sub(vertex), v), dot(to.sub(vertex), v));
        let along = dot(from.sub(vertex), u) + dot(to.sub(vertex), u);
        let sigma = if along < 0.0 { -1.0 } else { 1.0 };
        Curve::Conic {
            from,
            to,
            origin: vertex,
            e1: scale(u, sigma / (2.0 * p)),
            e2: v,
            t0: w0,
            t1: w1,
            kind: ConicKind::Parabola { p, q: q_deg },
            cw,
        }
    }

    /// The line or arc as a contour element; `None` for a conic, which
    /// the corner geometry does not take.
    pub fn element(&self) -> Option<Element> {
        match *self {
            Curve::Line { from, to } => Some(Element::Line { from, to }),
            Curve::Arc {
                from,
                to,
                centre,
                cw,
                ..
            } => Some(Element::Arc {
                from,
                to,
                centre,
                cw,
            }),
            Curve::Conic { .. } => None,
        }
    }

    pub fn start(&self) -> Pt {
        match *self {
            Curve::Line { from, .. } | Curve::Arc { from, .. } | Curve::Conic { from, .. } => from,
        }
    }

    pub fn end(&self) -> Pt {
        match *self {
            Curve::Line { to, .. } | Curve::Arc { to, .. } | Curve::Conic { to, .. } => to,
        }
    }

    /// The same curve moved by `d` (arc centres too).
    pub fn shifted(&self, d: Pt) -> Curve {
        match (*self, self.element()) {
            (
                Curve::Conic {
                    from, to, origin, ..
                },
                _,
            ) => self.with_points(from.add(d), to.add(d), origin.add(d), |v| v),
            (_, Some(e)) => Curve::new(e.shifted(d)),
            (c, None) => c,
        }
    }

    /// A conic with new end points and origin and its axis vectors mapped.
    fn with_points(&self, from: Pt, to: Pt, origin: Pt, f: impl Fn(Pt) -> Pt) -> Curve {
        match *self {
            Curve::Conic {
                e1,
                e2,
                t0,
                t1,
                kind,
                cw,
                ..
            } => Curve::Conic {
                from,
                to,
                origin,
                e1: f(e1),
                e2: f(e2),
                t0,
                t1,
                kind,
                cw,
            },
            c => c,
        }
    }

    /// The curve mirrored at r = z (the two axes exchanged): G72 runs the
    /// G71 algorithm on the mirrored profile. A mirror turns clockwise
    /// into counter-clockwise.
    pub fn swapped(&self) -> Curve {
        let s = swap;
        let Some(element) = self.element() else {
            let Curve::Conic {
                from,
                to,
                origin,
                cw,
                ..
            } = *self
            else {
                return *self;
            };
            return match self.with_points(s(from), s(to), s(origin), s) {
                Curve::Conic {
                    from,
                    to,
                    origin,
                    e1,
                    e2,
                    t0,
                    t1,
                    kind,
                    ..
                } => Curve::Conic {
                    from,
                    to,
                    origin,
                    e1,
                    e2,
                    t0,
                    t1,
                    kind,
                    cw: !cw,
                },
                c => c,
            };
        };
        Curve::new(match element {
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
            Curve::Conic {
                from,
                e1,
                e2,
                t0,
                t1,
                kind: ConicKind::Parabola { .. },
                ..
            } => {
                // From the start, not the vertex: far out on a flat
                // parabola the vertex lies 10⁷ mm away, and the point as
                // the difference of two such numbers is off by 10 nm.
                let dt = (t1 - t0) * s;
                from.add(scale(e1, dt * (2.0 * t0 + dt))).add(scale(e2, dt))
            }
            Curve::Conic {
                origin,
                e1,
                e2,
                t0,
                t1,
                kind,
                ..
            } => {
                let (f1, f2) = conic_basis(kind, t0 + (t1 - t0) * s);
                origin.add(scale(e1, f1)).add(scale(e2, f2))
            }
        }
    }

    /// The parameter of angle `a` on an arc, if it lies inside (0, 1).
    fn param_of_angle(a0: f64, sweep: f64, a: f64) -> Option<f64> {
        let turn = crate::base::geom::rem_euclid(if sweep < 0.0 { a0 - a } else { a - a0 }, TAU);
        let s = turn / sweep.abs();
        (s > 1e-12 && s < 1.0 - 1e-12).then_some(s)
    }

    fn arc_params(a0: f64, sweep: f64, angles: &[f64]) -> Params {
        Params::of(
            angles
                .iter()
                .filter_map(|&a| Curve::param_of_angle(a0, sweep, a)),
        )
        .sorted()
    }

    /// Parameters strictly inside (0, 1) where `axis` equals `level`.
    pub fn roots(&self, axis: Axis, level: f64) -> Params {
        match *self {
            Curve::Line { from, to } => {
                let (a, b) = (coord(from, axis), coord(to, axis));
                if (b - a).abs() < 1e-12 {
                    return Params::default();
                }
                let s = (level - a) / (b - a);
                Params::of((s > 1e-12 && s < 1.0 - 1e-12).then_some(s))
            }
            Curve::Arc {
                centre,
                radius,
                a0,
                sweep,
                ..
            } => {
                if radius < 1e-12 {
                    return Params::default();
                }
                let v = (level - coord(centre, axis)) / radius;
                if v.abs() > 1.0 + 1e-12 {
                    return Params::default();
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
            Curve::Conic {
                origin,
                e1,
                e2,
                t0,
                t1,
                kind,
                ..
            } => {
                let (c1, c2) = (coord(e1, axis), coord(e2, axis));
                let rest = coord(origin, axis) - level;
                match kind {
                    // c1·cos τ + c2·sin τ = ρ·cos(τ − φ) = level − origin.
                    ConicKind::Ellipse { .. } => {
                        let rho = libm::hypot(c1, c2);
                        if rho < 1e-12 || (rest / rho).abs() > 1.0 + 1e-12 {
                            return Params::default();
                        }
                        let phi = libm::atan2(c2, c1);
                        let d = libm::acos((-rest / rho).clamp(-1.0, 1.0));
                        Curve::arc_params(t0, t1 - t0, &[phi + d, phi - d])
                    }
                    // c1·τ² + c2·τ + rest = 0.
                    ConicKind::Parabola { .. } => {
                        let taus = quadratic_roots(c1, c2, rest);
                        linear_params(t0, t1, &taus)
                    }
                }
            }
        }
    }

    /// Parameters strictly inside (0, 1) where `axis` has an extreme (only
    /// arcs and conics have them).
    pub fn extremes(&self, axis: Axis) -> Params {
        match *self {
            Curve::Line { .. } => Params::default(),
            Curve::Arc { a0, sweep, .. } => {
                let angles = match axis {
                    Axis::R => [FRAC_PI_2, -FRAC_PI_2],
                    Axis::Z => [0.0, PI],
                };
                Curve::arc_params(a0, sweep, &angles)
            }
            Curve::Conic {
                e1,
                e2,
                t0,
                t1,
                kind,
                ..
            } => {
                let (c1, c2) = (coord(e1, axis), coord(e2, axis));
                match kind {
                    ConicKind::Ellipse { .. } => {
                        let phi = libm::atan2(c2, c1);
                        Curve::arc_params(t0, t1 - t0, &[phi, phi + PI])
                    }
                    ConicKind::Parabola { .. } if c1.abs() > 1e-15 => {
                        linear_params(t0, t1, &[-c2 / (2.0 * c1)])
                    }
                    ConicKind::Parabola { .. } => Params::default(),
                }
            }
        }
    }

    /// The parameters of [s0, s1] where `axis` may turn: the ends and the
    /// extremes between them, in order.
    fn samples(&self, axis: Axis, s0: f64, s1: f64) -> Params {
        let mut v = Params::default();
        v.push(s0);
        for s in self
            .extremes(axis)
            .into_iter()
            .filter(|&s| s > s0 && s < s1)
        {
            v.push(s);
        }
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
        let values = Params::of(
            self.samples(axis, s0, s1)
                .into_iter()
                .map(|s| coord(self.at(s), axis)),
        );
        let whole = match (values.first(), values.last()) {
            (Some(a), Some(b)) => dir * (b - a) >= -EPS,
            _ => true,
        };
        whole && values.windows(2).all(|w| dir * (w[1] - w[0]) >= -SLACK)
    }

    /// The unit direction of travel at parameter s (`None` where the
    /// curve stands still).
    pub fn direction(&self, s: f64) -> Option<Pt> {
        let d = match *self {
            Curve::Line { from, to } => to.sub(from),
            Curve::Arc { sweep, .. } => {
                // Perpendicular to the radius, the way the arc turns.
                let p = self.at(s);
                let Curve::Arc { centre, .. } = *self else {
                    return None;
                };
                scale(left(p.sub(centre)), sweep.signum())
            }
            Curve::Conic {
                e1,
                e2,
                t0,
                t1,
                kind,
                ..
            } => {
                let t = t0 + (t1 - t0) * s.clamp(0.0, 1.0);
                let (d1, d2) = match kind {
                    ConicKind::Ellipse { .. } => (-libm::sin(t), libm::cos(t)),
                    ConicKind::Parabola { .. } => (2.0 * t, 1.0),
                };
                scale(scale(e1, d1).add(scale(e2, d2)), (t1 - t0).signum())
            }
        };
        crate::plan::elem::unit(d)
    }

    /// The length of the part [s0, s1].
    pub fn length(&self, s0: f64, s1: f64) -> f64 {
        match *self {
            Curve::Line { .. } => self.at(s0).dist(self.at(s1)),
            Curve::Arc { radius, sweep, .. } => radius * sweep.abs() * (s1 - s0).abs(),
            Curve::Conic { .. } => self.conic_length(s0, s1),
        }
    }

    /// Composite Simpson over 64 intervals of the speed |p′|: the speed of
    /// an ellipse arc of ≤ 180° or of a parabola piece is smooth, and the
    /// error (below 1e-7 mm on profile-sized pieces) is inside the 1e-6 mm
    /// the cycles compare lengths with.
    fn conic_length(&self, s0: f64, s1: f64) -> f64 {
        const N: u32 = 64;
        let Curve::Conic {
            e1,
            e2,
            t0,
            t1,
            kind,
            ..
        } = *self
        else {
            return 0.0;
        };
        let speed = |s: f64| {
            let t = t0 + (t1 - t0) * s;
            let (d1, d2) = match kind {
                ConicKind::Ellipse { .. } => (-libm::sin(t), libm::cos(t)),
                ConicKind::Parabola { .. } => (2.0 * t, 1.0),
            };
            norm(scale(e1, d1).add(scale(e2, d2))) * (t1 - t0).abs()
        };
        let h = (s1 - s0) / f64::from(N);
        let mut sum = speed(s0) + speed(s1);
        for i in 1..N {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * speed(s0 + h * f64::from(i));
        }
        (sum * h / 3.0).abs()
    }
}

/// The unit vectors along and across a conic's axis at `q_deg` (from +Z
/// in the G02 sense, as `plan::conic` reads Q).
fn conic_axes(q_deg: f64) -> (Pt, Pt) {
    let u = crate::plan::conic::axis(q_deg);
    (u, left(u))
}

/// (f1, f2) of `Curve::Conic` at τ.
fn conic_basis(kind: ConicKind, t: f64) -> (f64, f64) {
    match kind {
        ConicKind::Ellipse { .. } => (libm::cos(t), libm::sin(t)),
        ConicKind::Parabola { .. } => (t * t, t),
    }
}

/// The real roots of a·τ² + b·τ + c = 0 (a line when a is 0).
fn quadratic_roots(a: f64, b: f64, c: f64) -> Params {
    if a.abs() < 1e-15 {
        return if b.abs() < 1e-15 {
            Params::default()
        } else {
            Params::of([-c / b])
        };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return Params::default();
    }
    // The form without cancellation: q = −(b + sign(b)·√disc)/2.
    let q = -0.5 * (b + if b < 0.0 { -1.0 } else { 1.0 } * libm::sqrt(disc));
    if q.abs() < 1e-300 {
        return Params::of([0.0]);
    }
    Params::of([q / a, c / q])
}

/// The parameters s ∈ (0, 1) of the τ values, τ = t0 + (t1 − t0)·s.
fn linear_params(t0: f64, t1: f64, taus: &[f64]) -> Params {
    if (t1 - t0).abs() < 1e-15 {
        return Params::default();
    }
    Params::of(
        taus.iter()
            .map(|&t| (t - t0) / (t1 - t0))
            .filter(|&s| s > 1e-12 && s < 1.0 - 1e-12),
    )
    .sorted()
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
    fn an_ellipse_quarter_has_its_roots_extremes_and_length() {
        // The quarter about r0 z-10 from r0 z0 to r15 z-10 (A15 along r,
        // B10 along z, Q90°, counter-clockwise): r = 15·sin θ,
        // z = −10 + 10·cos θ.
        let c = Curve::ellipse(
            Pt::new(0.0, 0.0),
            Pt::new(15.0, -10.0),
            Pt::new(0.0, -10.0),
            15.0,
            10.0,
            90.0,
            false,
        );
        for s in [0.0, 0.3, 0.7, 1.0] {
            let p = c.at(s);
            let f = (p.r / 15.0).powi(2) + ((p.z + 10.0) / 10.0).powi(2);
            assert!((f - 1.0).abs() < 1e-12, "s={s}: {p:?}");
        }
        // r = 9: sin θ = 0.6, z = −10 + 8 = −2.
        let s = c.roots(Axis::R, 9.0);
        assert_eq!(s.len(), 1);
        assert!((c.at(s[0]).z + 2.0).abs() < 1e-12);
        assert!(c.extremes(Axis::R).is_empty() && c.extremes(Axis::Z).is_empty());
        assert!(c.monotone(Axis::R, 1.0, 0.0, 1.0) && c.monotone(Axis::Z, -1.0, 0.0, 1.0));
        // A circle written as an ellipse: a quarter of 2π·5.
        let q = Curve::ellipse(
            Pt::new(0.0, 5.0),
            Pt::new(5.0, 0.0),
            Pt::new(0.0, 0.0),
            5.0,
            5.0,
            0.0,
            false,
        );
        assert!((q.length(0.0, 1.0) - 2.5 * PI).abs() < 1e-9);
    }

    #[test]
    fn a_parabola_piece_has_its_roots_extreme_and_length() {
        // Vertex at the origin, axis +Z (Q0), p = 2: z = r²/4, here from
        // r−2 (z1) to r4 (z4). The lowest z is at the vertex, r0 (s = 1/3).
        let c = Curve::parabola(
            Pt::new(-2.0, 1.0),
            Pt::new(4.0, 4.0),
            Pt::new(0.0, 0.0),
            2.0,
            0.0,
            true,
        );
        assert!(c.at(0.5).dist(Pt::new(1.0, 0.25)) < 1e-12);
        let e = c.extremes(Axis::Z);
        assert_eq!(e.len(), 1);
        assert!((e[0] - 1.0 / 3.0).abs() < 1e-12);
        // z = 1 again at r2.
        let s = c.roots(Axis::Z, 1.0);
        assert_eq!(s.len(), 1);
        assert!(c.at(s[0]).dist(Pt::new(2.0, 1.0)) < 1e-12);
        // Arc length of z = r²/(2p) from 0 to w: w/2·√(1 + (w/p)²) +
        // p/2·asinh(w/p); the piece is the sum for w = 2 and w = 4.
        let len = |w: f64| w / 2.0 * (1.0 + (w / 2.0).powi(2)).sqrt() + libm::asinh(w / 2.0);
        let d = (c.length(0.0, 1.0) - (len(2.0) + len(4.0))).abs();
        // Simpson's rule over 64 intervals: within 1e-7 mm here.
        assert!(d < 1e-7, "{d}");
    }

    #[test]
    fn a_far_flat_parabola_is_smooth_to_the_last_digits() {
        // 48 mm along its axis across 0.078 mm, p 53.464: its vertex lies
        // about 10⁷ mm away. τ is even in s and the curve quadratic in τ,
        // so the third differences of its points vanish but for rounding
        // at the size of the coordinates (10⁻¹⁴ mm).
        let (from, to) = (Pt::new(0.0, 20.0), Pt::new(-0.039, -28.1175));
        let vertex = crate::plan::conic::parabola_vertex(from, to, 53.464, 0.0, true).unwrap();
        assert!(vertex.norm() > 1e6, "{vertex:?}");
        let c = Curve::parabola(from, to, vertex, 53.464, 0.0, true);
        assert!(c.at(0.999_999_999).dist(to) < 1e-6);
        let at = |i: i32| c.at(f64::from(i) / 1000.0);
        for i in 0..997 {
            let d3 = at(i + 3)
                .sub(scale(at(i + 2), 3.0))
                .add(scale(at(i + 1), 3.0))
                .sub(at(i));
            assert!(d3.norm() < 1e-12, "{d3:?}");
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
