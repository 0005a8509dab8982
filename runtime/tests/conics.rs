//! Ellipses and parabolas with a turned axis (Q ≠ 0): the interpolated
//! points lie on the curve the program names, worked out here by hand from
//! dialect.md §2.4 and §4.1 (the axis turns from +Z towards −X; G6.2/G7.2
//! are clockwise in the ZX view, +Z right, +X up), not from the runtime's
//! or the kernel's own formulas.

mod common;

use common::*;
use runtime::{Motion, RunState};

/// The points of line `line` fed along, as (r, z) with r = X/2 (a conic
/// is a feed along a curve: [`Motion::Arc`]).
fn fed_points(r: &Run, line: u32) -> Vec<(f64, f64)> {
    r.pts
        .iter()
        .filter(|p| p.line == line && p.motion == Motion::Arc)
        .map(|p| (p.x / 2.0, p.z))
        .collect()
}

/// The largest distance of the points from the straight line a–b.
fn off_chord(pts: &[(f64, f64)], a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dr, dz) = (b.0 - a.0, b.1 - a.1);
    let len = (dr * dr + dz * dz).sqrt();
    pts.iter()
        .map(|p| ((p.0 - a.0) * dz - (p.1 - a.1) * dr).abs() / len)
        .fold(0.0, f64::max)
}

/// `G6.3 … A20 B10 Q30000` from X20 Z-2.6795 to X57.3205 Z-15: the issue's
/// ellipse centred at X40 Z-20 (r 20, z -20). Its major axis points at 30°
/// from +Z towards −X: u = (r −sin 30°, z cos 30°) = (−0.5, 0.8660), and
/// the minor axis v = (r 0.8660, z 0.5). The start is centre + 20·u
/// = (r 10, z −2.6795), the end centre + 10·v = (r 28.660, z −15): a
/// quarter of the ellipse, counter-clockwise in the ZX view (from the
/// major axis end towards the minor axis end on the +r side).
#[test]
fn an_ellipse_with_a_turned_axis_is_drawn_on_its_ellipse() {
    let r = run("O0001\nG98 G00 X20 Z-2.6795\nG6.3 X57.3205 Z-15 A20 B10 Q30000 F100\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    let pts = fed_points(&r, 3);
    assert!(pts.len() > 100, "{} points", pts.len());
    let (s30, c30) = (0.5, 0.75f64.sqrt());
    for &(pr, pz) in &pts {
        let (dr, dz) = (pr - 20.0, pz + 20.0);
        let xi = dr * -s30 + dz * c30; // along the major axis
        let eta = dr * c30 + dz * s30; // along the minor axis
        let f = (xi / 20.0).powi(2) + (eta / 10.0).powi(2);
        // 1 ± 0.0005 is within 0.005 mm of the curve for these semi-axes.
        assert!(
            (f - 1.0).abs() < 5e-4,
            "({pr}, {pz}) is off the ellipse: {f}"
        );
        // The quarter between the two axis ends.
        assert!(
            xi > -1e-3 && eta > -1e-3,
            "({pr}, {pz}) on the wrong quarter"
        );
    }
    // Not a chord: the quarter bulges well away from it (by hand, the
    // point at 45° is 20·0.7071, 10·0.7071 along the axes, about 4.1 mm
    // from the chord).
    assert!(off_chord(&pts, (10.0, -2.6795), (28.6603, -15.0)) > 3.5);
}

/// `G7.2 X20 Z-10 P5000 Q135000` from X0 Z0: p = 5 mm, the axis at 135°
/// towards −X: u = (r −sin 135°, z cos 135°) = (−0.7071, −0.7071). The
/// chord from (r 0, z 0) to (r 10, z −10) is square to the axis (its
/// projection on u is 0 at both ends), so the vertex lies on the chord's
/// mid-normal: half the chord is 7.0711 across the axis, and
/// y² = 2px gives x = 50 / 10 = 5 mm along the axis from the chord.
/// Clockwise (G7.2) from start to end the curve bulges to the left of the
/// chord's direction (dz −10, dr 10), i.e. towards (dz −1, dr −1)/√2 = u:
/// the vertex is the mid point (r 5, z −5) + 5·u = (r 1.4645, z −8.5355),
/// and every point P has, with ξ = (P − V)·u and η across the axis,
/// −ξ = η² / 10.
#[test]
fn a_parabola_with_a_turned_axis_is_drawn_on_its_parabola() {
    let r = run("O0002\nG98 F100\nG00 X0 Z0\nG7.2 X20 Z-10 P5000 Q135000\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    let pts = fed_points(&r, 4);
    assert!(pts.len() > 100, "{} points", pts.len());
    let h = 0.5f64.sqrt();
    let (ur, uz) = (-h, -h);
    let (vr, vz) = (5.0 + 5.0 * ur, -5.0 + 5.0 * uz);
    for &(pr, pz) in &pts {
        let (dr, dz) = (pr - vr, pz - vz);
        let xi = dr * ur + dz * uz;
        let eta = dr * uz - dz * ur;
        let miss = -xi - eta * eta / 10.0;
        // Along the axis; the slope is at most 2·7.07/10 here, so 0.005
        // along the axis is within 0.005 mm of the curve.
        assert!(
            miss.abs() < 5e-3,
            "({pr}, {pz}) is off the parabola by {miss}"
        );
    }
    assert!(off_chord(&pts, (0.0, 0.0), (10.0, -10.0)) > 4.9);
}
