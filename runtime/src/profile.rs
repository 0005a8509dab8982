//! Acceleration-limited speed profiles in discrete time.
//!
//! The interpolator moves `v·dt` along the path each period and may change
//! `v` by at most `a·dt` from one period to the next: that is linear
//! acceleration before interpolation, and it bounds the second difference
//! of every sampled position by `a·dt²`, which is exactly what a drive sees.
//! The planner and the interpolator therefore need the braking limit in the
//! same discrete form, not the continuous `sqrt(u² + 2·a·d)`: following the
//! continuous curve overshoots a stop by up to one period of travel, or
//! needs more than `a` in the last period.
//!
//! [`brake_limit`] is the largest speed for the coming period from which a
//! sequence of periods, each at most `a·dt` slower than the one before,
//! either lands exactly on the point `d` ahead, or crosses it at a speed of
//! at most `u`. Taking that speed leaves, one period later, a limit of at
//! least `v − a·dt` (the rest of the same sequence), so following the limit
//! never needs a harder deceleration than `a`.

use nc::geom::floor_non_negative;

/// The braking limit for distance `d` (mm) to a point that may be crossed
/// at speed `u` (mm/s; 0: a stop exactly on it), acceleration `a`, period
/// `dt`.
pub fn brake_limit(d: f64, u: f64, a: f64, dt: f64) -> f64 {
    let u = u.max(0.0);
    if d <= 0.0 || !crate::math::is_pos(a) {
        return u;
    }
    let adt = a * dt;
    let cross = crossing(d, u, adt, dt);
    // The landing limit is below sqrt(2·a·d) + a·dt: skip it (a square
    // root) when the crossing limit is above that already.
    if cross > adt && (cross - adt) * (cross - adt) >= 2.0 * a * d {
        return cross;
    }
    landing(d, adt, dt).max(cross)
}

/// The fastest sequence that lands exactly on the point: m periods each
/// `a·dt` slower than the one before, then a last one of `ε ∈ (0, a·dt]`;
/// it covers `dt·((m+1)·ε + a·dt·m(m+1)/2)`.
fn landing(d: f64, adt: f64, dt: f64) -> f64 {
    let d_dt = d / dt;
    let x = d_dt / adt;
    // n = m + 1 periods: the smallest n with n(n+1)/2 ≥ x.
    let t = (libm::sqrt(1.0 + 8.0 * x) - 1.0) * 0.5;
    let mut n = floor_non_negative(t);
    if n < t {
        n += 1.0;
    }
    n = n.max(1.0);
    if n * (n + 1.0) * 0.5 < x {
        n += 1.0;
    }
    if n > 1.0 && (n - 1.0) * n * 0.5 >= x {
        n -= 1.0;
    }
    let m = n - 1.0;
    let eps = ((d_dt - adt * m * (m + 1.0) * 0.5) / n).clamp(0.0, adt);
    eps + m * adt
}

/// The fastest sequence that crosses the point at `w ≤ u` after m slower
/// and slower periods: `w + m·a·dt`, the m periods before the crossing
/// covering at most `d`.
fn crossing(d: f64, u: f64, adt: f64, dt: f64) -> f64 {
    if u <= 0.0 {
        return 0.0;
    }
    let h = 0.5 * adt;
    // The real m at which w = u exactly (the closed form of the sum).
    let v = libm::sqrt((u + h) * (u + h) + 2.0 * (adt / dt) * d) - h;
    let m1 = floor_non_negative(((v - u) / adt).max(0.0));
    let mut best = u + m1 * adt;
    let m2 = m1 + 1.0;
    let w = (d / dt - adt * m2 * (m2 + 1.0) * 0.5) / m2;
    if w >= 0.0 {
        best = best.max(w.min(u) + m2 * adt);
    }
    best
}

/// As [`brake_limit`] when it can matter, else ∞: when `u ≥ top`, or the
/// point is
/// farther than the distance needed to come down from `top + a·dt` to
/// `u` (periods `a·dt` apart: `(v² − u² + a·dt·(v − u)) / 2a`), the limit
/// is at least `top`, the most the speed can reach this period, and
/// nothing needs computing.
#[inline]
pub fn brake_limit_above(d: f64, u: f64, a: f64, dt: f64, top: f64) -> f64 {
    let u = u.max(0.0);
    // The limit is never below u.
    if u >= top {
        return f64::INFINITY;
    }
    let adt = a * dt;
    let v = top.max(u) + adt;
    if a > 0.0 && 2.0 * a * d >= v * v - u * u + adt * (v - u) {
        return f64::INFINITY;
    }
    brake_limit(d, u, a, dt)
}

/// The distance a stop from speed `v` takes when every period is `a·dt`
/// slower than the one before (the inverse of the landing limit).
pub fn stopping_distance(v: f64, a: f64, dt: f64) -> f64 {
    if !crate::math::is_pos(a) || v <= 0.0 {
        return 0.0;
    }
    let n = libm::ceil(v / (a * dt));
    // v, v − a·dt, …, down to the last positive one.
    let m = n - 1.0;
    dt * (n * v - a * dt * m * (m + 1.0) * 0.5)
}

/// One period of a speed that follows `target` with acceleration `a`:
/// never more than `a·dt` away from `v`, never negative.
pub fn approach(v: f64, target: f64, a: f64, dt: f64) -> f64 {
    let step = a * dt;
    target.clamp(v - step, v + step).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 0.001;
    const A: f64 = 1500.0;

    /// Following the limit from rest at the stop: lands exactly, never
    /// decelerates by more than a·dt.
    fn run_to_stop(d0: f64, v0: f64) -> (f64, f64) {
        let mut d = d0;
        let mut v = v0;
        let mut worst: f64 = 0.0;
        for _ in 0..100_000 {
            let lim = brake_limit(d, 0.0, A, DT);
            let nv = approach(v, lim.min(1e9), A, DT);
            worst = worst.max(v - nv);
            v = nv;
            let ds = v * DT;
            if ds >= d - 1e-12 {
                return (d - ds, worst);
            }
            d -= ds;
        }
        (d, worst)
    }

    #[test]
    fn stops_land_exactly() {
        for &d in &[1e-6, 0.0005, 0.0015, 0.003, 0.1, 1.0, 12.345, 100.0] {
            let (left, worst) = run_to_stop(d, 0.0);
            assert!(left.abs() < 1e-9, "d={d}: {left} left");
            assert!(worst <= A * DT * (1.0 + 1e-9), "d={d}: decel step {worst}");
        }
    }

    /// The shortcut answers ∞ only where the exact limit reaches `top`,
    /// and the exact limit everywhere else: over a grid of distances,
    /// crossing speeds, accelerations, periods and tops.
    #[test]
    fn limit_above_is_the_limit_or_a_proof_it_reaches_top() {
        let mut shortcuts = 0;
        for i in 0..400 {
            let d = 1e-5 * 1.05f64.powi(i);
            for &u in &[0.0, 0.2, 3.0, 25.0, 120.0] {
                for &(a, dt) in &[(A, DT), (300.0, 0.000125), (5000.0, 0.008)] {
                    for &top in &[0.5, 10.0, 33.3, 150.0, 1000.0] {
                        let exact = brake_limit(d, u, a, dt);
                        let above = brake_limit_above(d, u, a, dt, top);
                        if above == f64::INFINITY {
                            shortcuts += 1;
                            assert!(exact >= top, "d={d} u={u} a={a} dt={dt} top={top}");
                        } else {
                            assert_eq!(above.to_bits(), exact.to_bits());
                        }
                    }
                }
            }
        }
        assert!(shortcuts > 1000, "{shortcuts}");
    }

    #[test]
    fn limit_is_self_consistent() {
        for i in 1..2000 {
            let d = i as f64 * 0.0137;
            for &u in &[0.0, 0.3, 1.5, 10.0, 50.0] {
                let v = brake_limit(d, u, A, DT);
                let next = brake_limit(d - v * DT, u, A, DT);
                assert!(next >= v - A * DT - 1e-9, "d={d} u={u}: {v} then {next}");
                assert!(v >= u - 1e-12);
            }
        }
    }

    /// The period that passes the point (or the one after a period that
    /// ends exactly on it) runs at most at u.
    #[test]
    fn crossing_speed_stays_below_u() {
        for &(d0, u) in &[(3.0, 5.0), (0.00575, 5.0), (0.1, 0.7), (7.77, 20.0)] {
            let mut d: f64 = d0;
            let mut v = 0.0;
            loop {
                let lim = brake_limit(d, u, A, DT);
                v = approach(v, lim.min(80.0), A, DT);
                if d <= 1e-12 || v * DT > d + 1e-12 {
                    assert!(v <= u + 1e-9, "d0={d0}: crossed at {v}");
                    break;
                }
                d -= v * DT;
            }
        }
    }

    #[test]
    fn stopping_distance_matches_the_limit() {
        for &v in &[0.5, 1.5, 3.0, 33.3, 83.3] {
            let d = stopping_distance(v, A, DT);
            let lim = brake_limit(d, 0.0, A, DT);
            assert!((lim - v).abs() < A * DT + 1e-9, "v={v}: d={d} lim={lim}");
        }
    }
}
