//! Polar (G12.1) and cylindrical (G7.1) interpolation through the whole
//! runtime: the trace's joints (X, C or Z, C) turned back into the
//! programmed plane lie on the programmed path, and the tangential speed
//! is the programmed F away from the corners. The paths are written out
//! here from the programs by hand (centres and radii in the comments),
//! not taken from the kernel.

mod common;

use common::{certify, run_split_with, run_with, Run};
use nc::Machine;
use std::f64::consts::PI;

fn c_machine() -> Machine {
    let mut m = Machine::reference();
    m.axes.c.enabled = true;
    m
}

fn run_c(src: &str, jerk: bool) -> Run {
    let r = run_with(
        src,
        c_machine(),
        runtime::AutoAck,
        |cfg| cfg.jerk_limited = jerk,
        |_, _| {},
        120.0,
    );
    assert!(r.alarm.is_none(), "{:?}", r.alarm);
    r
}

/// A piece of the programmed path in the plane (first axis, second axis).
enum Piece {
    Line((f64, f64), (f64, f64)),
    /// Centre, radius, start angle and signed sweep (radians,
    /// counter-clockwise from the first axis).
    Arc((f64, f64), f64, f64, f64),
}

impl Piece {
    fn ends(&self) -> [(f64, f64); 2] {
        match *self {
            Piece::Line(a, b) => [a, b],
            Piece::Arc(c, r, a0, sweep) => [
                (c.0 + r * a0.cos(), c.1 + r * a0.sin()),
                (c.0 + r * (a0 + sweep).cos(), c.1 + r * (a0 + sweep).sin()),
            ],
        }
    }

    fn distance(&self, p: (f64, f64)) -> f64 {
        let d = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
        match *self {
            Piece::Line(a, b) => {
                let (vx, vy) = (b.0 - a.0, b.1 - a.1);
                let t =
                    (((p.0 - a.0) * vx + (p.1 - a.1) * vy) / (vx * vx + vy * vy)).clamp(0.0, 1.0);
                d(p, (a.0 + t * vx, a.1 + t * vy))
            }
            Piece::Arc(c, r, a0, sweep) => {
                let phi = (p.1 - c.1).atan2(p.0 - c.0);
                // How far along the sweep's direction the point's angle is.
                let t = (sweep.signum() * (phi - a0)).rem_euclid(2.0 * PI);
                if t <= sweep.abs() {
                    (d(p, c) - r).abs()
                } else {
                    let [e0, e1] = self.ends();
                    d(p, e0).min(d(p, e1))
                }
            }
        }
    }
}

fn distance(path: &[Piece], p: (f64, f64)) -> f64 {
    path.iter()
        .map(|s| s.distance(p))
        .fold(f64::INFINITY, f64::min)
}

/// Every period of `lines` lies on `path` within 0.005 mm, and the speed
/// between two periods at least 1 mm from every corner is F within 0.5 %
/// (the trace's own feed column too).
fn check(
    r: &Run,
    lines: std::ops::RangeInclusive<u32>,
    plane: impl Fn(&runtime::SetPoint) -> (f64, f64),
    path: &[Piece],
    f: f64,
) {
    let dt = r.cfg.period_s;
    let corners: Vec<(f64, f64)> = path.iter().flat_map(Piece::ends).collect();
    let away = |p: (f64, f64)| corners.iter().all(|c| (p.0 - c.0).hypot(p.1 - c.1) > 1.0);
    let (mut on, mut timed) = (0, 0);
    for w in r.pts.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if !lines.contains(&b.line) {
            continue;
        }
        let q = plane(b);
        let off = distance(path, q);
        assert!(
            off <= 0.005,
            "t={} line {}: {q:?} is {off} mm off the path",
            b.time_s,
            b.line
        );
        on += 1;
        let p = plane(a);
        if lines.contains(&a.line) && away(p) && away(q) {
            let v = (q.0 - p.0).hypot(q.1 - p.1) / dt * 60.0;
            assert!(
                (v - f).abs() <= 0.005 * f,
                "t={}: tangential feed {v} mm/min, F{f}",
                b.time_s
            );
            assert!(
                (b.feed - f).abs() <= 0.005 * f,
                "t={}: trace feed {}",
                b.time_s,
                b.feed
            );
            timed += 1;
        }
    }
    // The path is long enough that most periods count.
    assert!(
        on > 1000 && timed > on / 2,
        "{on} periods on the path, {timed} timed"
    );
}

/// A closed contour about the spindle centre in the polar plane (X as a
/// radius x, the hypothetical axis c), never nearer to it than 10 mm.
const POLAR: &str = "G98
G00 X40 Z-2 C0
G12.1
G01 X20 C10 F300
G03 X-20 C10 R10
G01 C-10
G03 X20 C-10 R10
G01 X40 C0
G13.1
M30
";

fn polar_path() -> Vec<Piece> {
    vec![
        // X40 C0 is (20, 0); X20 C10 is (10, 10).
        Piece::Line((20.0, 0.0), (10.0, 10.0)),
        // (10, 10) to (−10, 10) with R10: the chord is the diameter, the
        // centre (0, 10); counter-clockwise from 0° over the top.
        Piece::Arc((0.0, 10.0), 10.0, 0.0, PI),
        Piece::Line((-10.0, 10.0), (-10.0, -10.0)),
        // (−10, −10) to (10, −10): centre (0, −10), counter-clockwise
        // from 180° through the bottom (0, −20).
        Piece::Arc((0.0, -10.0), 10.0, PI, PI),
        Piece::Line((10.0, -10.0), (20.0, 0.0)),
    ]
}

/// The polar plane point of a period: x = X/2·cos C, c = X/2·sin C.
fn polar_plane(p: &runtime::SetPoint) -> (f64, f64) {
    let (r, c) = (p.x / 2.0, p.c.expect("a C column").to_radians());
    (r * c.cos(), r * c.sin())
}

#[test]
fn polar_interpolation_follows_the_cartesian_path_at_f() {
    for jerk in [false, true] {
        let r = run_c(POLAR, jerk);
        check(&r, 4..=8, polar_plane, &polar_path(), 300.0);
        // Z stays; the contour goes once round the centre: C ends at 360°.
        assert!(r
            .pts
            .iter()
            .filter(|p| (4..=8).contains(&p.line))
            .all(|p| (p.z + 2.0).abs() < 1e-9));
        let last = r.pts.last().expect("periods");
        assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6 && (last.x - 40.0).abs() < 1e-6);
    }
}

/// A groove on the cylinder of radius 20: C in degrees, developed as
/// s = 20·C·π/180 mm.
const CYLINDER: &str = "G98
G00 X40 Z0 C0
G7.1 C20.
G01 Z-10 C90 F200
G02 Z-30 R10
G01 Z-40 C0
G7.1 C0
M30
";

#[test]
fn cylindrical_interpolation_follows_the_developed_path_at_f() {
    // C90 on radius 20 is s = 10π = 31.4159 mm.
    let s90 = 10.0 * PI;
    let path = [
        Piece::Line((0.0, 0.0), (s90, -10.0)),
        // From Z−10 to Z−30 at s90, R10, clockwise as seen with s to the
        // right and Z up: centre (s90, −20), from 90° down through 0°.
        Piece::Arc((s90, -20.0), 10.0, PI / 2.0, -PI),
        Piece::Line((s90, -30.0), (0.0, -40.0)),
    ];
    // The plane point of a period: (20·C·π/180, Z).
    let plane = |p: &runtime::SetPoint| (20.0 * p.c.expect("a C column").to_radians(), p.z);
    for jerk in [false, true] {
        let r = run_c(CYLINDER, jerk);
        check(&r, 4..=6, plane, &path, 200.0);
        // X stays at 40 all the while.
        assert!(r
            .pts
            .iter()
            .filter(|p| (4..=6).contains(&p.line))
            .all(|p| (p.x - 40.0).abs() < 1e-9));
    }
}

#[test]
fn the_distance_cut_is_the_path_in_the_plane() {
    // `POLAR`'s contour: two lines of √200, two half circles of R10 and
    // a line of 20: 2·14.1421 + 2·31.4159 + 20 = 111.1150 mm, where X and
    // Z alone travel about 43 mm.
    let r = run_c(POLAR, false);
    let mut s = runtime::stats::Stats::new(r.cfg.period_s);
    for p in &r.pts {
        s.add(p);
    }
    let want = 2.0 * 200f64.sqrt() + 2.0 * 10.0 * PI + 20.0;
    assert!(
        (s.cut_mm - want).abs() < 0.01,
        "{} against {want}",
        s.cut_mm
    );
}

#[test]
fn the_run_agrees_with_the_canon() {
    let r = run_c(POLAR, false);
    let canon: Vec<String> = r.canon.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        canon,
        [
            "RAPID X=40 Z=-2 C=0",
            "POLAR MODE=ON",
            "FEED F=300 MODE=MIN",
            "LINE X=20 C=10",
            "ARC DIR=CCW X=-20 C=10 CX=0 CC=10",
            "LINE X=-20 C=-10",
            "ARC DIR=CCW X=20 C=-10 CX=0 CC=-10",
            "LINE X=40 C=0",
            // Once round the centre counter-clockwise: C = 360°.
            "POLAR MODE=OFF X=40 C=360",
            "STOP KIND=M30",
        ]
    );
}

#[test]
fn the_split_controller_follows_the_same_path() {
    // The interpreter on a thread of its own: the queue may starve and
    // the motion wait, so only the path is checked, not the speed.
    let r = run_split_with(POLAR, c_machine(), runtime::AutoAck, |_, _| {});
    assert!(r.alarm.is_none(), "{:?}", r.alarm);
    let path = polar_path();
    let mut on = 0;
    for p in r.pts.iter().filter(|p| (4..=8).contains(&p.line)) {
        let q = polar_plane(p);
        assert!(distance(&path, q) <= 0.005, "t={}: {q:?}", p.time_s);
        on += 1;
    }
    assert!(on > 1000, "{on}");
    let last = r.pts.last().expect("periods");
    assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6);
}

/// The polar contour of `POLAR` with Z plunging alone at (−10, 10), after
/// the first arc, and rising at the end (seed 000: the axis outside the
/// plane moves as commanded).
const POLAR_PLUNGE: &str = "G98
G00 X40 Z-2 C0
G12.1
G01 X20 C10 F300
G03 X-20 C10 R10
G01 Z-5 F50
G01 C-10 F300
G03 X20 C-10 R10
G01 X40 C0
G00 Z2
G13.1
M30
";

#[test]
fn z_moves_alone_during_polar_interpolation() {
    for jerk in [false, true] {
        let r = run_c(POLAR_PLUNGE, jerk);
        let path = polar_path();
        check(&r, 4..=5, polar_plane, &path[..2], 300.0);
        check(&r, 7..=9, polar_plane, &path[2..], 300.0);
        // The plunge at (−10, 10): X = 2·√200 = 28.2843, C = 135°; Z from
        // −2 down to −5 at F50, never past it.
        let x = 2.0 * 200f64.sqrt();
        let plunge: Vec<_> = r.pts.iter().filter(|p| p.line == 6).collect();
        assert!(plunge.len() > 1000, "{}", plunge.len());
        for p in &plunge {
            let c = p.c.expect("a C column");
            assert!((p.x - x).abs() < 1e-9 && (c - 135.0).abs() < 1e-6, "{p:?}");
            assert!((-5.0 - 1e-9..=-2.0 + 1e-9).contains(&p.z), "{p:?}");
        }
        let mid = plunge[plunge.len() / 2];
        assert!((mid.feed - 50.0).abs() <= 0.25, "{}", mid.feed);
        // The rest of the contour runs at Z−5; G00 Z2 lifts alone at the
        // end, where the contour closed once round the centre.
        assert!(r
            .pts
            .iter()
            .filter(|p| (7..=9).contains(&p.line))
            .all(|p| (p.z + 5.0).abs() < 1e-9));
        let last = r.pts.last().expect("periods");
        assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6, "{last:?}");
        assert!((last.x - 40.0).abs() < 1e-6 && (last.z - 2.0).abs() < 1e-9);
        let canon: Vec<String> = r.canon.iter().map(|e| e.to_string()).collect();
        assert!(canon.contains(&"LINE Z=-5".to_string()), "{canon:?}");
        assert!(canon.contains(&"RAPID Z=2".to_string()), "{canon:?}");
    }
}

/// The groove of `CYLINDER`, fed in along X alone first (X40 to X36 on
/// the cylinder of radius 20), then cut at that depth and backed out.
const CYLINDER_INFEED: &str = "G98
G00 X40 Z0 C0
G7.1 C20.
G01 X36 F20
G01 Z-10 C90 F200
G00 U4
G7.1 C0
M30
";

#[test]
fn x_moves_alone_during_cylindrical_interpolation() {
    let r = run_c(CYLINDER_INFEED, false);
    // The infeed: Z and C stand, X from 40 to 36 at F20.
    let infeed: Vec<_> = r.pts.iter().filter(|p| p.line == 4).collect();
    assert!(infeed.len() > 1000, "{}", infeed.len());
    for p in &infeed {
        assert!(p.z.abs() < 1e-9 && p.c.unwrap_or(1.0).abs() < 1e-9, "{p:?}");
        assert!((36.0 - 1e-9..=40.0 + 1e-9).contains(&p.x), "{p:?}");
    }
    // The line at X36 on the developed surface (s = 20·C·π/180, Z), then
    // X back to 40 with Z−10, C90 standing.
    let s90 = 10.0 * PI;
    for p in r.pts.iter().filter(|p| p.line == 5) {
        let (s, z) = (20.0 * p.c.expect("a C column").to_radians(), p.z);
        let off = Piece::Line((0.0, 0.0), (s90, -10.0)).distance((s, z));
        assert!(off <= 0.005 && (p.x - 36.0).abs() < 1e-9, "{p:?}");
    }
    let last = r.pts.last().expect("periods");
    assert!((last.x - 40.0).abs() < 1e-9 && (last.z + 10.0).abs() < 1e-9);
    assert!((last.c.unwrap_or(0.0) - 90.0).abs() < 1e-9, "{last:?}");
}

/// A ramp of G12.1: from (x 20, c 0) at Z2 to (x 10, c 10) at Z−2 in one
/// G01 (X and C from (20, 0) to (10, 10): 10√2 = 14.1421 in the plane, Z
/// 4 down: 14.6969 in space), then on at Z−2 to (x −10, c 10).
const POLAR_RAMP: &str = "G98
G00 X40 Z2 C0
G12.1
G01 X20 C10 Z-2 F300
G01 X-20 C10
G13.1
M30
";

#[test]
fn z_moves_along_a_line_of_polar_interpolation() {
    let len3 = (200.0f64 + 16.0).sqrt();
    for jerk in [false, true] {
        let r = run_c(POLAR_RAMP, jerk);
        let ramp: Vec<_> = r.pts.iter().filter(|p| p.line == 4).collect();
        assert!(ramp.len() > 2000, "{}", ramp.len());
        for p in &ramp {
            // On the line in space: the plane point's distance along it
            // from (20, 0) gives Z in proportion.
            let (x, c) = polar_plane(p);
            let along = ((20.0 - x) + c) / 2f64.sqrt();
            let off = Piece::Line((20.0, 0.0), (10.0, 10.0)).distance((x, c));
            let z = 2.0 - 4.0 * along / 200f64.sqrt();
            assert!(off <= 0.005 && (p.z - z).abs() <= 0.005, "{p:?} {z}");
            assert!((-2.0 - 1e-9..=2.0 + 1e-9).contains(&p.z), "{p:?}");
        }
        // F is the speed along the line in space, the trace's feed too:
        // Z runs at 300·4/14.6969 = 81.65 mm/min.
        let mid = ramp[ramp.len() / 2];
        assert!((mid.feed - 300.0).abs() <= 0.5, "{}", mid.feed);
        let (a, b) = (ramp[ramp.len() / 2 - 50], ramp[ramp.len() / 2 + 50]);
        let vz = (a.z - b.z) / (b.time_s - a.time_s) * 60.0;
        assert!((vz - 300.0 * 4.0 / len3).abs() < 0.5, "{vz}");
        // Then at Z−2 round to (−10, 10): X = 2·√200, C = 135°.
        for p in r.pts.iter().filter(|p| p.line == 5) {
            assert!((p.z + 2.0).abs() < 1e-9, "{p:?}");
        }
        let last = r.pts.last().expect("periods");
        assert!((last.x - 2.0 * 200f64.sqrt()).abs() < 1e-6, "{last:?}");
        assert!((last.c.unwrap_or(0.0) - 135.0).abs() < 1e-6, "{last:?}");
        let canon: Vec<String> = r.canon.iter().map(|e| e.to_string()).collect();
        assert!(
            canon.contains(&"LINE X=20 C=10 Z=-2".to_string()),
            "{canon:?}"
        );
        // No period runs faster than both rapids together (X 6 000, Z
        // 10 000 mm/min: 11 662), the switches of the plane included,
        // where the point changes coordinates (it read 10.7 million).
        let top = r.pts.iter().map(|p| p.feed).fold(0.0, f64::max);
        assert!(top <= 11_662.0, "{top}");
    }
}

#[test]
fn x_moves_along_a_line_of_cylindrical_interpolation() {
    // On the cylinder of radius 20, from Z0 C0 at X40 to Z−10 C90 at X36:
    // s from 0 to 10π, Z to −10 (18.6210 on the surface), X 2 down as a
    // radius (18.7285 in all).
    let src = "G98\nG00 X40 Z0 C0\nG7.1 C20.\nG01 Z-10 C90 X36 F200\nG7.1 C0\nM30\n";
    let s90 = 10.0 * PI;
    let surface = (s90 * s90 + 100.0f64).sqrt();
    for jerk in [false, true] {
        let r = run_c(src, jerk);
        let ramp: Vec<_> = r.pts.iter().filter(|p| p.line == 4).collect();
        assert!(ramp.len() > 2000, "{}", ramp.len());
        for p in &ramp {
            let (s, z) = (20.0 * p.c.expect("a C column").to_radians(), p.z);
            let off = Piece::Line((0.0, 0.0), (s90, -10.0)).distance((s, z));
            let x = 40.0 - 4.0 * s.hypot(z) / surface;
            assert!(off <= 0.005 && (p.x - x).abs() <= 0.01, "{p:?} {x}");
        }
        let mid = ramp[ramp.len() / 2];
        assert!((mid.feed - 200.0).abs() <= 0.5, "{}", mid.feed);
        let last = r.pts.last().expect("periods");
        assert!((last.x - 36.0).abs() < 1e-9 && (last.z + 10.0).abs() < 1e-9);
        assert!((last.c.unwrap_or(0.0) - 90.0).abs() < 1e-9, "{last:?}");
    }
}

#[test]
fn an_ellipse_of_polar_interpolation_runs_round_the_centre_at_f() {
    // The ellipse x²/20² + c²/10² = 1 about the centre, counter-clockwise
    // in two halves from (20, 0): C turns a whole turn. Where it passes
    // nearest the centre, at (0, ±10), C turns at v/10 = 0.5 rad/s at F300
    // (5 mm/s), within its 30°/s (0.5236 rad/s): F runs all along but
    // where it starts and stops. (Capped at its least distance and its
    // largest lever, 10 and 20, it ran at half of F.)
    let src = "G98\nG00 X40 Z2 C0\nG12.1\nG6.3 X-40 C0 A20 B10 Q0 F300\nG6.3 X40 C0 A20 B10 Q0\nG13.1\nM30\n";
    for jerk in [false, true] {
        let r = run_c(src, jerk);
        let on: Vec<_> = r.pts.iter().filter(|p| (4..=5).contains(&p.line)).collect();
        // 2π·√((20² + 10²)/2) ≈ 99.3 mm (the ellipse's perimeter is 96.9)
        // at 5 mm/s: some 19 000 periods.
        assert!(on.len() > 19_000, "{}", on.len());
        for p in &on {
            let (x, c) = polar_plane(p);
            let e = ((x / 20.0).powi(2) + (c / 10.0).powi(2)).sqrt();
            assert!((e - 1.0).abs() * 10.0 <= 0.005, "{p:?}");
            assert!(p.feed <= 300.5, "{p:?}");
        }
        let mut feeds: Vec<f64> = on.iter().map(|p| p.feed).collect();
        feeds.sort_by(f64::total_cmp);
        assert!(
            feeds[feeds.len() / 10] >= 299.0,
            "{}",
            feeds[feeds.len() / 10]
        );
        let last = r.pts.last().expect("periods");
        assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6, "{last:?}");
        assert!((last.x - 40.0).abs() < 1e-6, "{last:?}");
        let canon: Vec<String> = r.canon.iter().map(|e| e.to_string()).collect();
        assert!(canon.contains(&"ELLIPSE DIR=CCW X=-40 C=0 A=20 B=10 Q=0".to_string()));
    }
}

#[test]
fn a_parabola_of_cylindrical_interpolation_runs_on_the_developed_surface() {
    // On the cylinder of radius 20, the parabola G7.2 (P 5 mm, its axis
    // along C: Q0) from s 0, Z0 to s 10π (C90), Z−10, clockwise with C
    // to the right and Z up: Z falls, so it opens towards −s (σ = −1 in
    // plan conic.rs), and σ(s − u0) = (Z − v0)²/2P through both ends
    // gives v0 = −5 − 5π = −20.708 (Z), u0 = v0²/10 = 42.882 (s): every
    // period's (s, Z) lies on s = u0 − (Z − v0)²/10. (Its direction
    // turns from (4.14, −1) to (2.14, −1): clockwise.)
    let src = "G98\nG00 X40 Z0 C0\nG7.1 C20.\nG7.2 Z-10 C90 P5000 Q0 F200\nG7.1 C0\nM30\n";
    let v0 = -5.0 - 5.0 * PI;
    let u0 = v0 * v0 / 10.0;
    for jerk in [false, true] {
        let r = run_c(src, jerk);
        let on: Vec<_> = r.pts.iter().filter(|p| p.line == 4).collect();
        assert!(on.len() > 1000, "{}", on.len());
        for p in &on {
            let (s, z) = (20.0 * p.c.expect("a C column").to_radians(), p.z);
            let want = u0 - (z - v0).powi(2) / 10.0;
            // (|ds/dZ| is at least 2·10.7/10 = 2.1 along it: 5 µm along s
            // is within 5 µm of the curve.)
            assert!((s - want).abs() <= 0.005, "{p:?} {want}");
            assert!((p.x - 40.0).abs() < 1e-9, "{p:?}");
        }
        let last = r.pts.last().expect("periods");
        assert!((last.z + 10.0).abs() < 1e-9, "{last:?}");
        assert!((last.c.unwrap_or(0.0) - 90.0).abs() < 1e-9, "{last:?}");
    }
}

#[test]
fn a_rapid_in_the_polar_plane_follows_its_straight_line() {
    // G00 from (x 10, c 10) to (x −10, c 0): along that line (each axis
    // on its own, c would arrive first, a dog-leg), labelled a rapid, at
    // no more than the slower axis's rapid rate (X: 100 mm/s).
    let src = "G98\nG00 X40 Z-2 C0\nG12.1\nG01 X20 C10 F300\nG00 X-20 C0\nG13.1\nM30\n";
    let r = run_c(src, false);
    let line = [Piece::Line((10.0, 10.0), (-10.0, 0.0))];
    let rapid: Vec<_> = r.pts.iter().filter(|p| p.line == 5).collect();
    assert!(rapid.len() > 100, "{}", rapid.len());
    for w in rapid.windows(2) {
        let (p, q) = (polar_plane(w[0]), polar_plane(w[1]));
        assert!(distance(&line, q) < 0.005, "{q:?} off the line");
        assert_eq!(w[1].motion, runtime::Motion::Rapid);
        let v = (q.0 - p.0).hypot(q.1 - p.1) / r.cfg.period_s;
        assert!(v <= 100.0 + 1e-6, "{v} mm/s");
    }
    let end = polar_plane(rapid[rapid.len() - 1]);
    assert!((end.0 + 10.0).abs() < 1e-6 && end.1.abs() < 1e-6, "{end:?}");
}

#[test]
fn the_travel_is_the_joints_in_a_plane() {
    // Soft limits X −1…60 (a diameter), Z −20…5, work = machine. The
    // contour of `POLAR` keeps the joints within them (X 20…40 from the
    // centre, Z −2), though its plane points reach c = −10 and x = −10,
    // which as X would lie outside: it runs to its end. A line out to
    // (x 35, c 0), X70, leaves the travel: E7002 at its line.
    let mut m = c_machine();
    m.axes.x.soft_limits = true;
    (m.axes.x.min_mm, m.axes.x.max_mm) = (-1.0, 60.0);
    m.axes.z.soft_limits = true;
    (m.axes.z.min_mm, m.axes.z.max_mm) = (-20.0, 5.0);
    let run = |src: &str| run_with(src, m.clone(), runtime::AutoAck, |_| {}, |_, _| {}, 120.0);
    let r = run(POLAR);
    assert!(
        r.alarm.is_none() && r.state == runtime::RunState::Ended,
        "{:?}",
        r.alarm
    );
    let out = POLAR.replace("G01 X40 C0\n", "G01 X70 C0\n");
    let r = run(&out);
    let alarm = r.alarm.expect("an alarm");
    assert_eq!((alarm.code, alarm.line), (7002, 8), "{alarm:?}");
}

/// A square about the centre, counter-clockwise, milled from outside with
/// G42 and a tool of radius 2 (offset 1; its tip 3 is not used in the
/// plane), Z plunging where the tool stands after the first side.
const POLAR_COMP: &str = "G98
G00 X40 Z-2 C0 T0101
G12.1
G42 G01 X20 C-10 F300
C10
G01 Z-5 F50
G01 X-20 F300
C-10
X20
G40 X40 C0
G00 Z2
G13.1
M30
";

/// The tool centre's path of `POLAR_COMP`, worked out by hand. The sides
/// x = 10, c = 10, x = −10, c = −10 are offset outwards by 2; every
/// corner turns left with the tool on the right, outside: an arc of
/// radius 2 about the corner.
fn polar_comp_path() -> Vec<Piece> {
    vec![
        // The start-up runs to the first side's start normal (12, −10).
        Piece::Line((20.0, 0.0), (12.0, -10.0)),
        Piece::Line((12.0, -10.0), (12.0, 10.0)),
        Piece::Arc((10.0, 10.0), 2.0, 0.0, PI / 2.0),
        Piece::Line((10.0, 12.0), (-10.0, 12.0)),
        Piece::Arc((-10.0, 10.0), 2.0, PI / 2.0, PI / 2.0),
        Piece::Line((-12.0, 10.0), (-12.0, -10.0)),
        Piece::Arc((-10.0, -10.0), 2.0, PI, PI / 2.0),
        Piece::Line((-10.0, -12.0), (10.0, -12.0)),
        // The last side ends on its own normal (10, −12); the cancel runs
        // from there to the programmed (20, 0).
        Piece::Line((10.0, -12.0), (20.0, 0.0)),
    ]
}

/// Runs `src` on the C-axis machine with a tool of radius 2 (offset 1;
/// its tip 3 is not used in the plane), jerk limiting as `jerk` says.
fn run_comp(src: &str, jerk: bool) -> Run {
    let toml = "[axes.c]\nenabled = true\n[[tools.offset]]\nnumber = 1\nradius = 2\ntip = 3\n";
    let machine = Machine::from_toml(toml).expect("a machine file");
    let r = run_with(
        src,
        machine,
        runtime::AutoAck,
        |cfg| cfg.jerk_limited = jerk,
        |_, _| {},
        120.0,
    );
    assert!(r.alarm.is_none(), "{:?}", r.alarm);
    r
}

#[test]
fn polar_compensation_runs_the_tool_centre_round_the_contour() {
    for jerk in [false, true] {
        let r = run_comp(POLAR_COMP, jerk);
        let path = polar_comp_path();
        check(&r, 4..=5, polar_plane, &path, 300.0);
        check(&r, 7..=10, polar_plane, &path, 300.0);
        // The plunge waits for the corner after the first side (it runs
        // with the next block's events, yet its periods carry its own
        // line): the tool stands at that side's end (12, 10), X =
        // 2·√244, C = atan2(10, 12).
        let (x, c) = (2.0 * 244f64.sqrt(), 10f64.atan2(12.0).to_degrees());
        let plunge: Vec<_> = r.pts.iter().filter(|p| p.line == 6).collect();
        assert!(plunge.len() > 1000, "{}", plunge.len());
        for p in &plunge {
            let pc = p.c.expect("a C column");
            assert!((p.x - x).abs() < 1e-9 && (pc - c).abs() < 1e-6, "{p:?}");
            assert!((-5.0 - 1e-9..=-2.0 + 1e-9).contains(&p.z), "{p:?}");
        }
        // Once round the centre, back at X40 C0 (360°).
        let last = r.pts.last().expect("periods");
        assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6, "{last:?}");
        assert!((last.x - 40.0).abs() < 1e-6 && (last.z - 2.0).abs() < 1e-9);
    }
}

/// `POLAR_COMP` with Z going down along the sides under compensation:
/// −2 to −3 along the first, to −4 along the second, and back up to 2
/// along the cancel.
const POLAR_COMP_RAMPS: &str = "G98
G00 X40 Z-2 C0 T0101
G12.1
G42 G01 X20 C-10 F300
C10 Z-3
G01 X-20 Z-4
C-10
X20
G40 X40 C0 Z2
G13.1
M30
";

#[test]
fn a_compensated_line_of_polar_interpolation_takes_z_along() {
    let path = polar_comp_path();
    for jerk in [false, true] {
        let r = run_comp(POLAR_COMP_RAMPS, jerk);
        // In the plane the tool centre runs the path of `POLAR_COMP`, at
        // F where Z stands.
        check(&r, 4..=4, polar_plane, &path, 300.0);
        check(&r, 7..=8, polar_plane, &path, 300.0);
        let on = |line: u32| -> Vec<_> {
            let pts: Vec<_> = r.pts.iter().filter(|p| p.line == line).collect();
            assert!(pts.len() > 500, "line {line}: {}", pts.len());
            for p in &pts {
                assert!(distance(&path, polar_plane(p)) <= 0.005, "{p:?}");
            }
            pts
        };
        // The first side, (12, −10) to (12, 10): Z in proportion to c.
        for p in on(5) {
            let (_, c) = polar_plane(p);
            assert!((p.z - (-2.0 - (c + 10.0) / 20.0)).abs() < 0.005, "{p:?}");
        }
        // Line 6: the corner's arc about (10, 10), x above 10, holds Z at
        // −3; the side (10, 12) to (−10, 12) takes it to −4.
        let mut on_arc = 0;
        for p in on(6) {
            let (x, _) = polar_plane(p);
            if x > 10.0 {
                assert!((p.z + 3.0).abs() < 1e-9, "{p:?}");
                on_arc += 1;
            } else {
                assert!((p.z - (-3.0 - (10.0 - x) / 20.0)).abs() < 0.005, "{p:?}");
            }
        }
        assert!(on_arc > 100, "{on_arc}");
        // The rest of the square at −4; the cancel from (10, −12) to
        // (20, 0) back up to 2, in proportion.
        for p in on(7).into_iter().chain(on(8)) {
            assert!((p.z + 4.0).abs() < 1e-9, "{p:?}");
        }
        let cancel = on(9);
        for p in &cancel {
            let (x, _) = polar_plane(p);
            assert!(
                (p.z - (-4.0 + 6.0 * (x - 10.0) / 10.0)).abs() < 0.005,
                "{p:?}"
            );
        }
        // F along the line in space: √244 = 15.6205 in the plane, √280 =
        // 16.7332 with Z, the plane point at 300·15.6205/16.7332 = 280.05.
        let (a, b) = (cancel[cancel.len() / 2], cancel[cancel.len() / 2 + 1]);
        let (pa, pb) = (polar_plane(a), polar_plane(b));
        let v = (pb.0 - pa.0).hypot(pb.1 - pa.1) / r.cfg.period_s * 60.0;
        assert!(
            (v - 280.05).abs() < 0.5 && (b.feed - 300.0).abs() < 0.5,
            "{v} {b:?}"
        );
        let last = r.pts.last().expect("periods");
        assert!((last.c.unwrap_or(0.0) - 360.0).abs() < 1e-6, "{last:?}");
        assert!((last.x - 40.0).abs() < 1e-6 && (last.z - 2.0).abs() < 1e-9);
    }
}

/// The moves after a plane start where its last move left the joints, not
/// where the plane started: `gbvm check` certifies them (it held the move
/// after G13.1 to a start at the X of G12.1, and the plane's own periods
/// to that move), and the trace runs them from there. Each case: the
/// program, the line of the move after the plane, where the joints stand
/// for it (X a diameter, Z; C) as worked out from the program, and
/// whether it runs along X (else along Z).
#[test]
fn the_move_after_a_plane_starts_where_the_plane_ended() {
    let cases = [
        // G01 X10 C0 from X20: the plane point (C 0, X radius 5), so the
        // joints stand at X10 C0, Z5 as at G12.1; G00 X30 runs along X
        // from there, then G01 Z−5.
        (
            "G98 G00 X20 Z5 C0\nG12.1\nG01 X10 C0 F100\nG13.1\nG00 X30\nG01 Z-5 F200\nM30\n",
            5,
            (10.0, 5.0, 0.0),
            true,
        ),
        // G01 X10 C5: the plane point (5, 5) is √50 = 7.0711 from the
        // centre at 45°, so the joints stand at X 2·√50 = 14.1421, C45;
        // G01 Z−5 runs along Z there (the plane's periods, at Z5 and X
        // from 20 down to 14.14, are on no part of it), then G00 X30.
        (
            "G98 G00 X20 Z5 C0\nG12.1\nG01 X10 C5 F100\nG13.1\nG01 Z-5 F200\nG00 X30\nM30\n",
            5,
            (2.0 * 50f64.sqrt(), 5.0, 45.0),
            false,
        ),
        // G7.1 on a cylinder of radius 10: G01 Z−10 C90, then X alone to
        // 18; the joints stand at X18 Z−10 C90 after G7.1 C0, and G01 X30
        // runs along X from there (not from X20 Z0, where G7.1 began).
        (
            "G98 G00 X20 Z0 C0\nG7.1 C10.\nG01 Z-10 C90 F200\nG01 X18 F200\nG7.1 C0\n\
             G01 X30 F200\nG00 Z5\nM30\n",
            6,
            (18.0, -10.0, 90.0),
            true,
        ),
    ];
    for (src, line, (x, z, c), along_x) in cases {
        for jerk in [false, true] {
            assert_eq!(certify(src, &c_machine(), jerk), Some(Ok(())), "{src}");
            let r = run_c(src, jerk);
            let after: Vec<_> = r.pts.iter().filter(|p| p.line == line).collect();
            assert!(after.len() > 10, "{src}: {}", after.len());
            for p in &after {
                let held = if along_x { p.z - z } else { p.x - x };
                assert!(held.abs() < 1e-6, "{src}: {p:?}");
                assert!((p.c.expect("a C column") - c).abs() < 1e-6, "{src}: {p:?}");
            }
            // Its first period a step of a few µm from the plane's end.
            let first = after[0];
            assert!(
                (first.x - x).abs() < 0.01 && (first.z - z).abs() < 0.01,
                "{src}: {first:?}"
            );
        }
    }
}

/// A move that goes nowhere in the plane (`G01 Z-5` where Z is at −5
/// already) runs no period: its end point is not waited for, though the
/// C the kernel gives it and the C the joints' map gives the move before
/// may differ by whole turns. Found by the harness's random plane
/// contours.
#[test]
fn a_plane_move_that_goes_nowhere_is_no_end_point_to_wait_for() {
    let machine = Machine::from_toml("[axes.c]\nenabled = true\n").unwrap();
    let src = "G98 G00 X40 Z2 C0\nG12.1\nG01 X-56.235 C3.373 F100\nG7.3 X-25.647 C14.980 P4800 Q0 F100\nG01 X-33.176 C-15.137 F100\nG01 Z-4.778 F100\nG7.2 X20.000 C-0.235 P12700 Q0 F100\nG01 X-30.353 C-19.843 Z-5.000 F100\nG01 Z-5.000 F100\nG13.1\nM30\n";
    for jerk in [false, true] {
        assert_eq!(certify(src, &machine, jerk), Some(Ok(())), "jerk {jerk}");
    }
}
