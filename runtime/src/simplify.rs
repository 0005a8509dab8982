//! Polyline simplification (Ramer–Douglas–Peucker): drops every point
//! whose removal moves the line by at most a tolerance. The plot uses it
//! so that a path of thousands of 1 ms periods along one straight move
//! draws as its two end points.

use alloc::vec::Vec;

/// The points of `pts` to keep so that no dropped point lies farther
/// than `tol` from the kept polyline. The first and last always stay.
/// Iterative (an explicit stack), so a long path cannot overflow the
/// call stack.
pub fn simplify(pts: &[(f64, f64)], tol: f64) -> Vec<(f64, f64)> {
    if pts.len() < 3 {
        return pts.to_vec();
    }
    let mut keep = alloc::vec![false; pts.len()];
    keep[0] = true;
    keep[pts.len() - 1] = true;
    let mut stack = alloc::vec![(0usize, pts.len() - 1)];
    while let Some((a, b)) = stack.pop() {
        let mut far = (0.0, 0);
        for i in a + 1..b {
            let d = distance_to_segment(pts[i], pts[a], pts[b]);
            if d > far.0 {
                far = (d, i);
            }
        }
        if far.0 > tol {
            keep[far.1] = true;
            stack.push((a, far.1));
            stack.push((far.1, b));
        }
    }
    pts.iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

/// The distance of `p` from the segment `a`–`b`.
fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    libm::hypot(p.0 - (a.0 + t * dx), p.1 - (a.1 + t * dy))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_run_keeps_its_ends_and_corners() {
        // 0 → 10 along Z in 0.01 steps, then up 5 in X in 0.01 steps: an
        // L of 1501 points, which is its three corners.
        let mut pts: Vec<(f64, f64)> = (0..=1000).map(|i| (i as f64 * 0.01, 0.0)).collect();
        pts.extend((1..=500).map(|i| (10.0, i as f64 * 0.01)));
        assert_eq!(
            simplify(&pts, 0.001),
            [(0.0, 0.0), (10.0, 0.0), (10.0, 5.0)]
        );
    }

    #[test]
    fn a_bump_above_the_tolerance_stays() {
        // A 0.01 bump at Z 5 survives a tolerance of 0.005 and goes at
        // 0.02 (its distance from the chord is exactly 0.01).
        let pts = [(0.0, 0.0), (5.0, 0.01), (10.0, 0.0)];
        assert_eq!(simplify(&pts, 0.005).len(), 3);
        assert_eq!(simplify(&pts, 0.02), [(0.0, 0.0), (10.0, 0.0)]);
    }

    #[test]
    fn an_arc_keeps_enough_points_to_stay_within_the_tolerance() {
        // A half circle of radius 10 by 1000 points, tolerance 0.01: a
        // chord of angle θ deviates by r(1 − cos θ/2), so each kept chord
        // spans at most 2·acos(1 − 0.001) ≈ 0.0894 rad and π needs at least
        // 35 of them; every dropped point is within 0.01 of the result.
        let pts: Vec<(f64, f64)> = (0..=1000)
            .map(|i| {
                let a = core::f64::consts::PI * i as f64 / 1000.0;
                (10.0 * libm::cos(a), 10.0 * libm::sin(a))
            })
            .collect();
        let kept = simplify(&pts, 0.01);
        assert!(kept.len() >= 36 && kept.len() < 100, "{}", kept.len());
        for p in &pts {
            let d = kept
                .windows(2)
                .map(|w| distance_to_segment(*p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.01, "{d}");
        }
    }

    #[test]
    fn short_inputs_are_returned_as_they_are() {
        assert!(simplify(&[], 1.0).is_empty());
        assert_eq!(simplify(&[(1.0, 2.0)], 1.0), [(1.0, 2.0)]);
    }
}
