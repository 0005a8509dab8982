//! Hand-checked corners, angle programming and conics through `Nc::exec`.
//! Every expected coordinate is worked out in the comment above it (or by
//! a formula written out in the test), not taken from the implementation.

use alloc::format;
use alloc::string::String;
use alloc::string::ToString;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::NcError;
use crate::base::event::Event;
use crate::base::machine::{ChamferType, Machine};
use crate::base::point::Pt;
use crate::base::words::{addr, Word, COMMA_A, COMMA_C, COMMA_R, LITERAL, NO_POINT};
use crate::exec::Nc;

/// The words of one block written like a program line: `G01 X20 ,C1`.
fn words(block: &str) -> Vec<Word> {
    block
        .split_whitespace()
        .map(|w| {
            let (a, num) = match w.strip_prefix(',') {
                Some(rest) => {
                    let a = match rest.as_bytes()[0] {
                        b'A' => COMMA_A,
                        b'C' => COMMA_C,
                        _ => COMMA_R,
                    };
                    (a, &rest[1..])
                }
                None => (addr(w.as_bytes()[0]), &w[1..]),
            };
            let flags = if num.contains('.') {
                LITERAL
            } else {
                LITERAL | NO_POINT
            };
            Word {
                addr: a,
                value: num.parse().expect("a number"),
                flags,
            }
        })
        .collect()
}

/// Runs the blocks on `m`, flushes at the end and returns the canon.
fn run_on(m: Machine, blocks: &[&str]) -> Result<Vec<String>, NcError> {
    let mut nc = Nc::new(m);
    let mut ev: Vec<Event> = Vec::new();
    for b in blocks {
        nc.exec(&words(b), &mut ev)?;
    }
    nc.flush(&mut ev)?;
    Ok(ev.iter().map(|e| e.to_string()).collect())
}

fn run(blocks: &[&str]) -> Vec<String> {
    run_on(Machine::reference(), blocks).expect("the blocks run")
}

fn code_of(blocks: &[&str]) -> u16 {
    run_on(Machine::reference(), blocks)
        .expect_err("an alarm")
        .code
}

fn type_one() -> Machine {
    let mut m = Machine::reference();
    m.cycles.chamfer_type = ChamferType::I;
    m
}

/// Compares canon lines: same keywords and field names, numbers within
/// 0.001 (canon.md).
fn assert_canon(got: &[String], want: &[String]) {
    let same = got.len() == want.len()
        && got.iter().zip(want).all(|(g, w)| {
            let (g, w): (Vec<&str>, Vec<&str>) = (g.split(' ').collect(), w.split(' ').collect());
            g.len() == w.len()
                && g.iter()
                    .zip(&w)
                    .all(|(a, b)| match (a.split_once('='), b.split_once('=')) {
                        (Some((ka, va)), Some((kb, vb))) => {
                            ka == kb
                                && match (va.parse::<f64>(), vb.parse::<f64>()) {
                                    (Ok(x), Ok(y)) => (x - y).abs() <= 0.001,
                                    _ => va == vb,
                                }
                        }
                        _ => a == b,
                    })
        });
    assert!(same, "canon differs\n got: {got:#?}\nwant: {want:#?}");
}

fn lines(want: &[&str]) -> Vec<String> {
    want.iter().map(|s| s.to_string()).collect()
}

fn line(x: f64, z: f64) -> String {
    format!("LINE X={x:.5} Z={z:.5}")
}

fn arc(dir: &str, x: f64, z: f64, cx: f64, cz: f64) -> String {
    format!("ARC DIR={dir} X={x:.5} Z={z:.5} CX={cx:.5} CZ={cz:.5}")
}

const FEED: &str = "FEED F=0.1 MODE=MIN";

#[test]
fn chamfer_type_two_between_lines() {
    // The face X0→X20 at Z0 (+X), then −Z: T1 1 mm back down the face
    // (X18), T2 1 mm along the cylinder (Z-1).
    let got = run(&["G01 Z0 F0.1", "X20 L1", "Z-20"]);
    assert_canon(
        &got,
        &lines(&[
            FEED,
            "LINE X=0 Z=0",
            "LINE X=18 Z=0",
            "LINE X=20 Z=-1",
            "LINE X=20 Z=-20",
        ]),
    );
}

#[test]
fn chamfer_type_one_uses_the_chamfer_length() {
    // Type I: L2 is the length of the chamfer line. At a 90° corner the
    // chamfer points are L/(2·sin 45°) = √2 from the corner: T1 at
    // r 10 − √2 (X 20 − 2√2), T2 at Z −√2.
    let d = 2.0 / (2.0 * 45f64.to_radians().sin());
    let got = run_on(type_one(), &["G01 Z0 F0.1", "X20 L2", "Z-20"]).unwrap();
    let want = vec![
        FEED.into(),
        line(0.0, 0.0),
        line(20.0 - 2.0 * d, 0.0),
        line(20.0, -d),
        line(20.0, -20.0),
    ];
    assert_canon(&got, &want);
    // ,C is always type II, whatever №181.0 says.
    let got = run_on(type_one(), &["G01 Z0 F0.1", "X20 ,C2", "Z-20"]).unwrap();
    assert_canon(
        &got,
        &lines(&[
            FEED,
            "LINE X=0 Z=0",
            "LINE X=16 Z=0",
            "LINE X=20 Z=-2",
            "LINE X=20 Z=-20",
        ]),
    );
}

#[test]
fn chamfer_between_a_line_and_an_arc() {
    // −Z from X20 Z0 to Z-10, then G03 R10 to X40 Z-20 about (r10, z-20):
    // the arc leaves P = (r10, z-10) going +X, a 90° right turn.
    // T1 = 2 mm back along the line: Z-8. T2: the chord of 2 mm on a
    // circle of radius 10 subtends φ = 2·asin(0.1), so T2 = centre +
    // 10·(cos φ, sin φ) in (z, r) = (z -20 + 9.8, r 10 + 1.98997).
    let phi = 2.0 * (0.1f64).asin();
    let (z2, r2) = (-20.0 + 10.0 * phi.cos(), 10.0 + 10.0 * phi.sin());
    assert!((Pt::new(r2, z2).dist(Pt::new(10.0, -10.0)) - 2.0).abs() < 1e-9);
    let got = run(&["G00 X20 Z0", "G01 Z-10 L2 F0.1", "G03 X40 Z-20 R10"]);
    let want = vec![
        "RAPID X=20 Z=0".into(),
        FEED.into(),
        line(20.0, -8.0),
        line(2.0 * r2, z2),
        arc("CCW", 40.0, -20.0, 20.0, -20.0),
    ];
    assert_canon(&got, &want);
}

#[test]
fn rounding_between_a_line_and_an_arc() {
    // The same corner with D2, a right turn: the fillet's centre M lies
    // 2 mm to the right of the line (r 12) and 2 mm outside the arc, on
    // the circle of radius 12 about (r10, z-20): (z + 20)² + 2² = 12², so
    // z = −20 + √140. T1 is M's foot on the line, T2 = centre + 10/12·(M −
    // centre); the fillet runs CW.
    let mz = -20.0 + 140f64.sqrt();
    let (t2z, t2r) = (-20.0 + (mz + 20.0) * 10.0 / 12.0, 10.0 + 2.0 * 10.0 / 12.0);
    let got = run(&["G00 X20 Z0", "G01 Z-10 D2 F0.1", "G03 X40 Z-20 R10"]);
    let want = vec![
        "RAPID X=20 Z=0".into(),
        FEED.into(),
        line(20.0, mz),
        arc("CW", 2.0 * t2r, t2z, 24.0, mz),
        arc("CCW", 40.0, -20.0, 20.0, -20.0),
    ];
    assert_canon(&got, &want);
}

#[test]
fn rounding_between_two_arcs() {
    // G03 R10 from X0 Z0 to X20 Z-10 about O1 = (r0, z-10), then G02 R10
    // to X0 Z-20 about O2 = (r10, z-20). At P = (r10, z-10) the path goes
    // −Z, then −X: a left turn, so the fillet is CCW with its centre M on
    // the left: inside the first circle (radius 10 − 2 = 8 about O1) and
    // outside the second (10 + 2 = 12 about O2). |O1O2| = √200; along
    // O1→O2 M lies a = (64 − 144 + 200)/(2√200) from O1 and h = √(64 − a²)
    // off the line, on P's side.
    let (o1, o2) = (Pt::new(0.0, -10.0), Pt::new(10.0, -20.0));
    let d = 200f64.sqrt();
    let a = (64.0 - 144.0 + 200.0) / (2.0 * d);
    let h = (64.0 - a * a).sqrt();
    let (uz, ur) = ((o2.z - o1.z) / d, (o2.r - o1.r) / d);
    // The normal (z, r) = (ur, −uz) points towards P.
    let m = Pt::new(o1.r + a * ur - h * uz, o1.z + a * uz + h * ur);
    assert!(m.dist(Pt::new(10.0, -10.0)) < 3.0);
    let t1 = Pt::new(
        o1.r + (m.r - o1.r) * 10.0 / 8.0,
        o1.z + (m.z - o1.z) * 10.0 / 8.0,
    );
    let t2 = Pt::new(
        o2.r + (m.r - o2.r) * 10.0 / 12.0,
        o2.z + (m.z - o2.z) * 10.0 / 12.0,
    );
    let got = run(&["G03 X20 Z-10 R10 D2 F0.1", "G02 X0 Z-20 R10"]);
    let want = vec![
        FEED.into(),
        arc("CCW", t1.x(), t1.z, 0.0, -10.0),
        arc("CCW", t2.x(), t2.z, m.x(), m.z),
        arc("CW", 0.0, -20.0, 20.0, -20.0),
    ];
    assert_canon(&got, &want);
}

#[test]
fn corner_words_are_ignored_where_the_rules_say() {
    // Same direction: nothing inserted.
    let got = run(&["G01 Z-10 L1 F0.1", "Z-20"]);
    assert_canon(&got, &lines(&[FEED, "LINE X=0 Z=-10", "LINE X=0 Z=-20"]));
    // A line running on into a tangent arc: the same direction too.
    let got = run(&["G01 X20 Z0 F0.1", "Z-10 ,R1", "G02 X40 Z-20 R10"]);
    assert_canon(
        &got,
        &lines(&[
            FEED,
            "LINE X=20 Z=0",
            "LINE X=20 Z=-10",
            "ARC DIR=CW X=40 Z=-20 CX=40 CZ=-10",
        ]),
    );
    // A G00 next: E1 whole.
    let got = run(&["G01 X20 L1 F0.1", "G00 Z5"]);
    assert_canon(&got, &lines(&[FEED, "LINE X=20 Z=0", "RAPID X=20 Z=5"]));
    // A group-00 code first: E1 whole, then the dwell, then E2 whole.
    let got = run(&["G01 X20 L1 F0.1", "G04 P500", "Z-20"]);
    assert_canon(
        &got,
        &lines(&[FEED, "LINE X=20 Z=0", "DWELL S=0.5", "LINE X=20 Z=-20"]),
    );
    // A zero-length move has no direction: no corner on either side.
    let got = run(&["G01 X20 L1 F0.1", "X20", "Z-20"]);
    assert_canon(
        &got,
        &lines(&[FEED, "LINE X=20 Z=0", "LINE X=20 Z=0", "LINE X=20 Z=-20"]),
    );
}

#[test]
fn the_canon_keeps_block_order_around_a_corner() {
    // E1 and the chamfer belong to the L block; M08 (a block without a
    // move) and the next block's S come after them, before E2.
    let got = run(&["G01 X20 L1 F0.1", "M08", "Z-20 S500 M05"]);
    let want = lines(&[
        FEED,
        "LINE X=18 Z=0",
        "LINE X=20 Z=-1",
        "M CODE=8",
        "SPEED S=500 MODE=RPM",
        "LINE X=20 Z=-20",
        "SPINDLE DIR=STOP",
    ]);
    assert_canon(&got, &want);
    // The chamfer runs at the F of its own block, E2 at the new one.
    let got = run(&["G01 X20 L1 F0.1", "Z-20 F0.2"]);
    assert_canon(
        &got,
        &lines(&[
            FEED,
            "LINE X=18 Z=0",
            "LINE X=20 Z=-1",
            "FEED F=0.2 MODE=MIN",
            "LINE X=20 Z=-20",
        ]),
    );
}

#[test]
fn a_waiting_element_is_printed_at_the_end() {
    // M30: E1 whole before the stop.
    let got = run(&["G01 X20 L1 F0.1", "M30"]);
    assert_canon(&got, &lines(&[FEED, "LINE X=20 Z=0", "STOP KIND=M30"]));
    // The end of the run (Nc::flush) prints what still waits.
    let mut nc = Nc::new(Machine::reference());
    let mut ev: Vec<Event> = Vec::new();
    nc.exec(&words("G01 X20 D1 F0.1"), &mut ev).unwrap();
    nc.exec(&words("M09"), &mut ev).unwrap();
    assert_eq!(ev.len(), 0);
    nc.flush(&mut ev).unwrap();
    assert_canon(
        &ev.iter().map(|e| e.to_string()).collect::<Vec<_>>(),
        &lines(&[FEED, "LINE X=20 Z=0", "M CODE=9"]),
    );
}

#[test]
fn corner_word_errors() {
    assert_eq!(code_of(&["G00 X20 L1"]), 2040);
    assert_eq!(code_of(&["G01 X20 L1 D1 F0.1"]), 2040);
    assert_eq!(code_of(&["G01 X20 L1 ,R1 F0.1"]), 2040);
    assert_eq!(code_of(&["G01 X20 L0 F0.1"]), 2040);
    assert_eq!(code_of(&["G02 X20 Z-10 R10 D-1 F0.1"]), 2040);
    // A mill's offset number (`G41 D1`) on G00 is told what D is here.
    let help = |block| {
        run_on(Machine::reference(), &[block])
            .err()
            .and_then(|e| e.help)
    };
    let told = help("G41 D1").unwrap_or_default();
    assert!(told.starts_with("D is a corner rounding here"), "{told}");
    assert_eq!(help("G00 X20 L1"), None);
    // The face is 10 mm (radius) long: L11 does not fit on it.
    assert_eq!(code_of(&["G01 X20 L11 F0.1", "Z-20"]), 4007);
    // E2 is 5 mm long: D10 needs 10 mm of it at a 90° corner.
    assert_eq!(code_of(&["G01 X20 D10 F0.1", "Z-5"]), 4007);
    // The path reverses.
    assert_eq!(code_of(&["G01 Z-10 L1 F0.1", "Z0"]), 4007);
}

#[test]
fn angle_one_block_forms() {
    // From X20 Z0 (r10) at 150°: direction (cos 150°, sin 150°) in (z, r).
    // X40: Δr = 10, ΔZ = 10·cos/sin = −10·√3.
    let z1 = -10.0 * 3f64.sqrt();
    // Then Z-30 at 180°: r stays. Then W-10 at ,A135: Δr = +10.
    let got = run(&[
        "G00 X20 Z0",
        "G01 X40 Q150000 F0.1",
        "Z-30 Q180000",
        "W-10 ,A135",
    ]);
    let want = vec![
        "RAPID X=20 Z=0".into(),
        FEED.into(),
        line(40.0, z1),
        line(40.0, -30.0),
        line(60.0, -40.0),
    ];
    assert_canon(&got, &want);
    // G00 too (positioning only).
    let got = run(&["G00 U20 Q45000"]);
    assert_canon(&got, &lines(&["RAPID X=20 Z=10"]));
    // X Z Q without a first block: an ordinary line.
    let got = run(&["G01 X10 Z-5 Q30000 F0.1"]);
    assert_canon(&got, &lines(&[FEED, "LINE X=10 Z=-5"]));
}

#[test]
fn angle_errors() {
    // X with an angle within 1° of 0°/180°, Z within 1° of 90°/270°.
    assert_eq!(code_of(&["G01 X50 Q180500 F0.1"]), 4008);
    assert_eq!(code_of(&["G01 X50 Q1000 F0.1"]), 4008);
    assert!(run_on(Machine::reference(), &["G01 X50 Q1001 F0.1"]).is_ok());
    assert_eq!(code_of(&["G01 Z-5 Q90000 F0.1"]), 4008);
    assert_eq!(code_of(&["G01 Z-5 ,A269.5 F0.1"]), 4008);
    // Two lines within 1° of each other.
    assert_eq!(code_of(&["G01 Q180000 F0.1", "X20 Z-30 Q180500"]), 4008);
    // The second block without absolute X, Z and Q.
    assert_eq!(code_of(&["G01 Q180000 F0.1", "X20 W-30 Q90000"]), 4008);
    assert_eq!(code_of(&["G01 Q180000 F0.1", "X20 Z-30"]), 4008);
    assert_eq!(code_of(&["G01 Q180000 F0.1", "G02 X20 Z-30 R20"]), 4008);
    // Two blocks in between (one is allowed).
    assert_eq!(
        code_of(&["G01 Q180000 F0.1", "M08", "S500", "X20 Z-30 Q90000"]),
        4008
    );
    // The program ends before the second block.
    assert_eq!(code_of(&["G01 Q180000 F0.1", "M30"]), 4008);
}

#[test]
fn angle_two_block_form() {
    // From X0 Z0 at 135° until the line through X20 Z-30 at 180° (r = 10):
    // λ·sin 135° = 10 gives the intersection r10 z-10.
    let got = run(&["G01 Q135000 F0.1", "X20 Z-30 Q180000"]);
    assert_canon(&got, &lines(&[FEED, "LINE X=20 Z=-10", "LINE X=20 Z=-30"]));
    // One block in between prints after the first line (block order).
    let got = run(&["G01 Q135000 F0.1", "M08", "X20 Z-30 Q180000"]);
    assert_canon(
        &got,
        &lines(&[FEED, "LINE X=20 Z=-10", "M CODE=8", "LINE X=20 Z=-30"]),
    );
    // With L2 on the first block, at the intersection I = (r10, z-10):
    // T1 = I − 2·(cos 135°, sin 135°), T2 = I + 2·(−1, 0) in (z, r).
    let s = 2.0 * 45f64.to_radians().sin();
    let got = run(&["G01 Q135000 L2 F0.1", "X20 Z-30 Q180000"]);
    let want = vec![
        FEED.into(),
        line(2.0 * (10.0 - s), -10.0 + s),
        line(20.0, -12.0),
        line(20.0, -30.0),
    ];
    assert_canon(&got, &want);
    // A corner waiting before the first block joins the first line:
    // −Z to X20 Z-10 with L1, then 135° (up and back) to r = 15.
    let got = run(&["G01 X20 Z0 F0.1", "Z-10 L1", "Q135000", "X30 Z-40 Q180000"]);
    let want = vec![
        FEED.into(),
        line(20.0, 0.0),
        line(20.0, -9.0),
        line(
            2.0 * (10.0 + 1.0 * 45f64.to_radians().sin()),
            -10.0 - 45f64.to_radians().cos(),
        ),
        line(30.0, -15.0),
        line(30.0, -40.0),
    ];
    assert_canon(&got, &want);
}

#[test]
fn ellipses() {
    // A = 20 along Z, B = 10: the quarter from X0 Z0 to X20 Z-20 about
    // (r0, z-20) runs CCW; the CW one of ≤ 180° is about (r10, z0).
    let got = run(&["G99 M03 S500", "G6.3 X20 Z-20 A20 B10 F0.1"]);
    assert_canon(
        &got,
        &lines(&[
            "SPINDLE DIR=CW",
            "SPEED S=500 MODE=RPM",
            "FEED F=0.1 MODE=REV",
            "ELLIPSE DIR=CCW X=20 Z=-20 A=20 B=10 Q=0",
        ]),
    );
    let from = Pt::new(0.0, 0.0);
    let c = super::ellipse_centre(from, Pt::new(10.0, -20.0), 20.0, 10.0, 0.0, false)
        .unwrap()
        .unwrap();
    assert!(c.dist(Pt::new(0.0, -20.0)) < 1e-9);
    let c = super::ellipse_centre(from, Pt::new(10.0, -20.0), 20.0, 10.0, 0.0, true)
        .unwrap()
        .unwrap();
    assert!(c.dist(Pt::new(10.0, 0.0)) < 1e-9);
    // Q90 turns the major axis from +Z towards −X: A along r. From
    // (r0, z0) on the major axis to (r20, z-10) on the minor one, CW,
    // about (r20, z0).
    let c = super::ellipse_centre(from, Pt::new(20.0, -10.0), 20.0, 10.0, 90.0, true)
        .unwrap()
        .unwrap();
    assert!(c.dist(Pt::new(20.0, 0.0)) < 1e-9);
    let got = run(&["G6.2 X40 Z-10 A20 B10 Q90000 F0.1"]);
    assert_canon(
        &got,
        &lines(&[FEED, "ELLIPSE DIR=CW X=40 Z=-10 A=20 B=10 Q=90"]),
    );
    // A = B: a circular arc, printed as ARC (G02 R10 from X0 Z0 to X20
    // Z-10 is about r10 z0).
    let got = run(&["G6.2 X20 Z-10 A10 B10 F0.1"]);
    assert_canon(&got, &lines(&[FEED, "ARC DIR=CW X=20 Z=-10 CX=20 CZ=0"]));
    // End = start: nothing.
    assert!(run(&["G6.2 X0 Z0 A10 B5 F0.1"]).is_empty());
}

#[test]
fn ellipse_errors() {
    assert_eq!(code_of(&["G6.2 X20 Z-10 B10 F0.1"]), 4005);
    assert_eq!(code_of(&["G6.2 X20 Z-10 A10 B0 F0.1"]), 4005);
    // 50 mm apart, more than 2A = 40.
    assert_eq!(code_of(&["G6.2 Z-50 A20 B10 F0.1"]), 4005);
    // 30 mm apart across the axis: no ellipse with B = 10 spans it.
    assert_eq!(code_of(&["G6.2 X60 A20 B10 F0.1"]), 4005);
}

#[test]
fn parabolas() {
    // p = 5 mm (P5000), axis along +Z: u = v²/10 through the vertex at
    // the start X0 Z0 reaches r10 at z10, turning clockwise (G7.2).
    let got = run(&["G7.2 X20 Z10 P5000 F0.1"]);
    assert_canon(&got, &lines(&[FEED, "PARABOLA DIR=CW X=20 Z=10 P=5 Q=0"]));
    let v = super::parabola_vertex(Pt::new(0.0, 0.0), Pt::new(10.0, 10.0), 5.0, 0.0, true).unwrap();
    assert!(v.dist(Pt::new(0.0, 0.0)) < 1e-9);
    // G7.3 opens the other way: −(z − 10) = (r − 10)²/10, vertex r10 z10.
    let v =
        super::parabola_vertex(Pt::new(0.0, 0.0), Pt::new(10.0, 10.0), 5.0, 0.0, false).unwrap();
    assert!(v.dist(Pt::new(10.0, 10.0)) < 1e-9);
    // Q90: the axis points −X; the parabola r = −z²/10 through the
    // vertex X0 Z0 reaches z10 at r-10, bending down (clockwise) on the
    // way: G7.2 has its vertex at the start.
    let v =
        super::parabola_vertex(Pt::new(0.0, 0.0), Pt::new(-10.0, 10.0), 5.0, 90.0, true).unwrap();
    assert!(v.dist(Pt::new(0.0, 0.0)) < 1e-9, "{v:?}");
    // The sign of P is ignored.
    let got = run(&["G7.3 X20 Z10 P-5000 Q45000 F0.1"]);
    assert_canon(&got, &lines(&[FEED, "PARABOLA DIR=CCW X=20 Z=10 P=5 Q=45"]));
    assert!(run(&["G7.2 X0 Z0 P5000 F0.1"]).is_empty());
    assert_eq!(code_of(&["G7.2 X20 Z10 F0.1"]), 4006);
    // The chord along the symmetry axis.
    assert_eq!(code_of(&["G7.2 Z-10 P5000 F0.1"]), 4006);
}

#[test]
fn the_public_corner_function() {
    use super::{corner, Corner};
    use crate::base::geom::Element;
    // Line–line 90° rounding: T1 = P − D·t1, T2 = P + D·t2, M = P − D·t1 + D·t2.
    let e1 = Element::Line {
        from: Pt::new(10.0, 0.0),
        to: Pt::new(10.0, -15.0),
    };
    let e2 = Element::Line {
        from: Pt::new(10.0, -15.0),
        to: Pt::new(15.0, -15.0),
    };
    let (a, ins, b) = corner(
        &e1,
        &e2,
        Corner::Round {
            radius: 2.0,
            word: addr(b'D'),
        },
    )
    .unwrap()
    .unwrap();
    assert!(a.end().dist(Pt::new(10.0, -13.0)) < 1e-9);
    assert!(b.start().dist(Pt::new(12.0, -15.0)) < 1e-9);
    let Element::Arc { centre, cw, .. } = ins else {
        panic!("a fillet is an arc")
    };
    assert!(centre.dist(Pt::new(12.0, -13.0)) < 1e-9 && cw);
    assert_eq!(
        corner(
            &e1,
            &e1_after(&e1),
            Corner::Round {
                radius: 1.0,
                word: addr(b'D'),
            }
        )
        .unwrap(),
        None
    );
}

/// The straight continuation of a line (same direction).
fn e1_after(e: &crate::base::geom::Element) -> crate::base::geom::Element {
    let (s, t) = (e.start(), e.end());
    crate::base::geom::Element::Line {
        from: t,
        to: Pt::new(2.0 * t.r - s.r, 2.0 * t.z - s.z),
    }
}

#[test]
fn type_one_chamfer_onto_an_arc() {
    use super::{corner, Corner};
    use crate::base::geom::Element;
    // −Z to P = (r10, z-10), then G03 about (r10, z-20): type I puts both
    // chamfer points equally far from P with the chamfer line L long.
    let p = Pt::new(10.0, -10.0);
    let e1 = Element::Line {
        from: Pt::new(10.0, 0.0),
        to: p,
    };
    let e2 = Element::Arc {
        from: p,
        to: Pt::new(20.0, -20.0),
        centre: Pt::new(10.0, -20.0),
        cw: false,
    };
    let c = Corner::Chamfer {
        size: 2.0,
        kind: ChamferType::I,
        word: addr(b'L'),
    };
    let (a, ins, b) = corner(&e1, &e2, c).unwrap().unwrap();
    let (t1, t2) = (a.end(), b.start());
    assert!((t1.dist(p) - t2.dist(p)).abs() < 1e-9);
    assert!((t1.dist(t2) - 2.0).abs() < 1e-9);
    assert!((t2.dist(Pt::new(10.0, -20.0)) - 10.0).abs() < 1e-9);
    assert_eq!(ins, Element::Line { from: t1, to: t2 });
    // Too long for the 10 mm line: E4007.
    let c = Corner::Chamfer {
        size: 30.0,
        kind: ChamferType::I,
        word: addr(b'L'),
    };
    let e = corner(&e1, &e2, c).unwrap_err();
    assert_eq!((e.code, e.addr), (4007, Some(addr(b'L'))));
}

/// `shorter_than` answers as `length(e) < eps` does: a quarter circle of
/// radius 1 is π/2 ≈ 1.5708 long; a start = end arc is a full circle
/// (2π·2 ≈ 12.566); an arc starting on its centre has no length; and a
/// spread of generated arcs, away from the boundary, agrees with `length`.
#[test]
fn shorter_than_agrees_with_the_arc_length() {
    use crate::base::geom::Element;
    use crate::plan::elem::{length, shorter_than};
    let arc = |from: Pt, to: Pt, centre: Pt, cw: bool| Element::Arc {
        from,
        to,
        centre,
        cw,
    };
    let quarter = arc(
        Pt::new(1.0, 0.0),
        Pt::new(0.0, 1.0),
        Pt::new(0.0, 0.0),
        true,
    );
    assert!(!shorter_than(&quarter, 1.57));
    assert!(shorter_than(&quarter, 1.571));
    let full = arc(
        Pt::new(2.0, 0.0),
        Pt::new(2.0, 0.0),
        Pt::new(0.0, 0.0),
        false,
    );
    assert!(!shorter_than(&full, 12.56));
    assert!(shorter_than(&full, 12.57));
    let on_centre = arc(
        Pt::new(0.0, 0.0),
        Pt::new(0.0, 1.0),
        Pt::new(0.0, 0.0),
        false,
    );
    assert!(shorter_than(&on_centre, 1e-6));
    let mut x: u64 = 3;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0
    };
    for _ in 0..5_000 {
        let e = arc(
            Pt::new(next(), next()),
            Pt::new(next(), next()),
            Pt::new(next(), next()),
            next() > 0.0,
        );
        let eps = (next() + 10.0) * 2.0;
        let len = length(&e);
        if (len - eps).abs() > 1e-6 * eps {
            assert_eq!(shorter_than(&e, eps), len < eps, "{e:?} {eps}");
        }
    }
}
