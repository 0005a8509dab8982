//! Polar and cylindrical interpolation in the kernel: the canon of the
//! plane, the joint position it leaves, the alarms of dialect.md §4.6.
//! Every expected figure is worked out by hand in the comments.

use crate::exec::cycles::testing::Lathe;
use alloc::vec::Vec;

use super::swept;
use crate::base::point::Pt;

fn lines(m: &mut Lathe, blocks: &[&str]) -> Vec<alloc::string::String> {
    blocks.iter().flat_map(|b| m.run(b)).collect()
}

fn var(m: &Lathe, n: u32) -> Option<f64> {
    m.nc.read_var(n).ok().flatten()
}

#[test]
fn polar_lines_arcs_and_polar_coordinates() {
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z-2 C0",
            // The plane starts at X40 (radius 20), C0.
            "G98 G12.1",
            // To (x 10, c 10): joint radius √200 = 14.1421, angle 45°.
            "G01 X20 C10 F100",
            // Chord from (10, 10) to (−10, 10) is 20 = 2R: centre (0, 10);
            // counter-clockwise over the top (0, 20): C turns from 45° to
            // 135° through 90°, +90°.
            "G03 X-20 C10 R10",
            // G16: radius 10 at 180° is (−10, 0); C turns from 135° to
            // 180°, the joint radius is 10 (X20).
            "G16",
            "G01 X10 C180",
            "G15",
            "G13.1",
            "G00 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=-2 C=0",
            "POLAR MODE=ON",
            "FEED F=100 MODE=MIN",
            "LINE X=20 C=10",
            "ARC DIR=CCW X=-20 C=10 CX=0 CC=10",
            "LINE X=-20 C=0",
            "POLAR MODE=OFF X=20 C=180",
            "RAPID X=20 Z=-2 C=0",
        ]
    );
    assert_eq!(var(&m, 5043), Some(0.0));
}

#[test]
fn a_full_circle_about_the_centre_turns_c_a_whole_turn() {
    let mut m = Lathe::with_c();
    // From (10, 0) with I−10 the centre is the spindle's: the end is the
    // start, a whole circle clockwise, so C turns −360°.
    let l = lines(&mut m, &["G00 X20 Z0 C0", "G12.1", "G02 I-10 F50", "G13.1"]);
    assert_eq!(
        l,
        [
            "RAPID X=20 Z=0 C=0",
            "POLAR MODE=ON",
            "FEED F=50 MODE=MIN",
            "ARC DIR=CW X=20 C=0 CX=0 CC=0",
            "POLAR MODE=OFF X=20 C=-360",
        ]
    );
    assert_eq!(var(&m, 5043), Some(-360.0));
    // A whole turn leaves C at 0° modulo 360: polar interpolation may
    // start again.
    assert_eq!(m.run("G12.1"), ["POLAR MODE=ON"]);
}

#[test]
fn cylinder_lines_and_arcs() {
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z0 C0",
            "G7.1 C20.",
            // C90 on radius 20 is the arc length 20·π/2 = 31.4159 mm.
            "G01 Z-10 C90 F200",
            // From Z−10 to Z−30 at the same C: the chord 20 = 2R, centre
            // at Z−20, C90.
            "G02 Z-30 R10",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=0 C=0",
            "CYLINDER MODE=ON R=20",
            "FEED F=200 MODE=MIN",
            "LINE Z=-10 C=90",
            "ARC DIR=CW Z=-30 C=90 CZ=-20 CC=90",
            "CYLINDER MODE=OFF",
        ]
    );
    assert_eq!(var(&m, 5043), Some(90.0));
    assert_eq!(m.run("G00 X50"), ["RAPID X=50 Z=-30"]);
}

#[test]
fn the_axis_outside_the_plane_moves_alone() {
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z2 C0",
            "G12.1",
            // To (x 10, c 10): joint radius √200, C 45°.
            "G01 X20 C10 F300",
            // Z plunges alone (seed 000: "moves as commanded"); the plane
            // point and the joints stand.
            "G01 Z-2 F50",
            "G00 W4",
            // In an arc Z is ignored: the arc of the first test, over the
            // top from 45° to 135°.
            "G03 X-20 C10 R10 Z7",
            "G13.1",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=2 C=0",
            "POLAR MODE=ON",
            "FEED F=300 MODE=MIN",
            "LINE X=20 C=10",
            "FEED F=50 MODE=MIN",
            "LINE Z=-2",
            "RAPID Z=2",
            "ARC DIR=CCW X=-20 C=10 CX=0 CC=10",
            // X = 2·√200 = 28.2843.
            "POLAR MODE=OFF X=28.2843 C=135",
        ]
    );
    assert_eq!(var(&m, 5042), Some(2.0));
    // On the cylinder of radius 20, X moves alone (a diameter; U adds to
    // it), Z and C stand.
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z0 C0",
            "G7.1 C20.",
            "G01 Z-10 C90 F200",
            "G01 X36 F20",
            "G00 U4",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=0 C=0",
            "CYLINDER MODE=ON R=20",
            "FEED F=200 MODE=MIN",
            "LINE Z=-10 C=90",
            "FEED F=20 MODE=MIN",
            "LINE X=36",
            "RAPID X=40",
            "CYLINDER MODE=OFF",
        ]
    );
    assert_eq!(var(&m, 5041), Some(40.0));
    assert_eq!(var(&m, 5043), Some(90.0));
}

#[test]
fn the_axis_outside_the_plane_moves_with_a_straight_move() {
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z2 C0",
            "G12.1",
            // A ramp: to (x 10, c 10) while Z goes to −2; the plane point
            // and the joints as in the first test (radius √200, C 45°).
            "G01 X20 C10 Z-2 F300",
            // W with a plane word: up 4 to Z2 while C goes to 0 (the
            // point (10, 0), C back to 0°).
            "G00 C0 W4",
            // A plane word that does not move the plane point: Z alone.
            "G01 X20 Z-1",
            "G13.1",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=2 C=0",
            "POLAR MODE=ON",
            "FEED F=300 MODE=MIN",
            "LINE X=20 C=10 Z=-2",
            "RAPID X=20 C=0 Z=2",
            "LINE Z=-1",
            "POLAR MODE=OFF X=20 C=0",
        ]
    );
    assert_eq!(var(&m, 5042), Some(-1.0));
    // On the cylinder of radius 20, X (a diameter, U adding to it) moves
    // with Z and C: to Z−10 at 90° while X goes to 36, then back by U4
    // with H−90.
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z0 C0",
            "G7.1 C20.",
            "G01 Z-10 C90 X36 F200",
            "G00 U4 H-90",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=0 C=0",
            "CYLINDER MODE=ON R=20",
            "FEED F=200 MODE=MIN",
            "LINE Z=-10 C=90 X=36",
            "RAPID Z=-10 C=0 X=40",
            "CYLINDER MODE=OFF",
        ]
    );
    assert_eq!(var(&m, 5041), Some(40.0));
    assert_eq!(var(&m, 5042), Some(-10.0));
    assert_eq!(var(&m, 5043), Some(0.0));
}

#[test]
fn ellipses_and_parabolas_in_the_plane() {
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z2 C0",
            "G12.1",
            // A half ellipse about the centre, A 20 along X (Q0), B 10
            // along C: from (x 20, c 0) counter-clockwise over (0, 10) to
            // (−20, 0), C from 0° to 180°; the other half back under it
            // to 360°. Z is ignored in it (W104 at compile time).
            "G6.3 X-40 C0 A20 B10 Q0 F300",
            "G6.3 X40 C0 A20 B10 Q0 Z5",
        ],
    );
    assert_eq!(
        l,
        [
            "RAPID X=40 Z=2 C=0",
            "POLAR MODE=ON",
            "FEED F=300 MODE=MIN",
            "ELLIPSE DIR=CCW X=-40 C=0 A=20 B=10 Q=0",
            "ELLIPSE DIR=CCW X=40 C=0 A=20 B=10 Q=0",
        ]
    );
    assert_eq!(m.run("G13.1"), ["POLAR MODE=OFF X=40 C=360"]);
    // An ellipse with A = B: from (20, 0) to (10, 10), A 10 along C
    // (Q90000: 90°), B 10: the quarter circle clockwise (X to the right,
    // C up) about (20, 10) prints as the arc it is; C turns to 45°.
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z2 C0",
            "G12.1",
            "G6.2 X20 C10 A10 B10 Q90000 F300",
            "G13.1",
        ],
    );
    assert_eq!(
        l[3..],
        [
            "ARC DIR=CW X=20 C=10 CX=40 CC=10",
            // X = 2·√200 = 28.2843.
            "POLAR MODE=OFF X=28.2843 C=45",
        ]
    );
    // On the cylinder of radius 20 a parabola (P 5 mm) from Z0 C0 to
    // Z−10 C90: Z and C end there.
    let mut m = Lathe::with_c();
    let l = lines(
        &mut m,
        &[
            "G98 G00 X40 Z0 C0",
            "G7.1 C20.",
            "G7.2 Z-10 C90 P5000 Q0 F200",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l[2..],
        [
            "FEED F=200 MODE=MIN",
            "PARABOLA DIR=CW Z=-10 C=90 P=5 Q=0",
            "CYLINDER MODE=OFF",
        ]
    );
    assert_eq!(var(&m, 5042), Some(-10.0));
    assert_eq!(var(&m, 5043), Some(90.0));
}

#[test]
fn the_turn_of_a_conic_about_the_centre() {
    use super::conic::about_centre;
    use crate::plan::curve::Curve;
    // Plane points are (r: c, z: x). The half ellipse about the centre
    // turns half a turn and comes 10 (B) near it; one about (x 30, c 0)
    // from (x 50, c 0) to (x 10, c 0) over the top (A 20, B 5) turns
    // from 0° back to 0° (the centre stays outside): 0, 10 from it at
    // its end (x 10).
    let (a, b) = (Pt::new(0.0, 20.0), Pt::new(0.0, -20.0));
    let half = Curve::ellipse(a, b, Pt::new(0.0, 0.0), 20.0, 10.0, 0.0, false);
    let (turn, near) = about_centre(&half);
    assert!((turn - core::f64::consts::PI).abs() < 1e-12, "{turn}");
    assert!((9.8..=10.0).contains(&near), "{near}");
    let (a, b) = (Pt::new(0.0, 50.0), Pt::new(0.0, 10.0));
    let away = Curve::ellipse(a, b, Pt::new(0.0, 30.0), 20.0, 5.0, 0.0, false);
    let (turn, near) = about_centre(&away);
    assert!(turn.abs() < 1e-12, "{turn}");
    assert!((9.8..=10.0).contains(&near), "{near}");
    // The other way round, under the centre's x axis: the same.
    let under = Curve::ellipse(a, b, Pt::new(0.0, 30.0), 20.0, 5.0, 0.0, true);
    assert!(about_centre(&under).0.abs() < 1e-12);
    // A flat ellipse (B 1 µm) about the centre: half a turn, 1 µm from
    // it (a bound by its radius of curvature, B²/A, halved it 2⁴⁰ times).
    let (a, b) = (Pt::new(0.0, 20.0), Pt::new(0.0, -20.0));
    let flat = Curve::ellipse(a, b, Pt::new(0.0, 0.0), 20.0, 0.001, 0.0, false);
    let (turn, near) = about_centre(&flat);
    assert!((turn - core::f64::consts::PI).abs() < 1e-12, "{turn}");
    assert!((0.00098..=0.001).contains(&near), "{near}");
    // A flat half ellipse (A 5 along c, B 0.1 µm) beside the centre, from
    // (x 20, c 0) to (x 20, c 10): its sides are straight to 10⁻⁸ rad,
    // where the tangents' triangle is lost in rounding (halving them had
    // no end); it turns as its chord, atan2(10, 20), and comes 20 near.
    let (a, b) = (Pt::new(0.0, 20.0), Pt::new(10.0, 20.0));
    let thin = Curve::ellipse(a, b, Pt::new(5.0, 20.0), 5.0, 1e-7, 90.0, false);
    let (turn, near) = about_centre(&thin);
    assert!((turn - libm::atan2(10.0, 20.0)).abs() < 1e-9, "{turn}");
    assert!((19.6..=20.0).contains(&near), "{near}");
}

#[test]
fn the_distance_of_a_move_from_the_centre() {
    use super::nearest_to_centre;
    use crate::base::point::Pt;
    // Plane points are (r: c, z: x). A line from (x 20, c 0) to
    // (x −20, c 0) crosses the centre; one at c 3 passes 3 from it; one
    // that stops short at x 5 is 5 away at its end.
    let (a, b) = (Pt::new(0.0, 20.0), Pt::new(0.0, -20.0));
    assert_eq!(nearest_to_centre(a, b, None), 0.0);
    let up = Pt::new(3.0, 0.0);
    assert_eq!(nearest_to_centre(a + up, b + up, None), 3.0);
    assert_eq!(nearest_to_centre(a, Pt::new(0.0, 5.0), None), 5.0);
    // The circle about (x 0, c 10) of radius 10 touches the centre at its
    // bottom. From (x 10, c 10) to (x −10, c 10) counter-clockwise (over
    // the top) the arc stays √200 away at its ends; clockwise it passes
    // through the bottom, the centre itself.
    let (from, to, c) = (
        Pt::new(10.0, 10.0),
        Pt::new(10.0, -10.0),
        Pt::new(10.0, 0.0),
    );
    assert!((nearest_to_centre(from, to, Some((c, false))) - 200f64.sqrt()).abs() < 1e-12);
    assert!(nearest_to_centre(from, to, Some((c, true))) < 1e-12);
    // A full circle about (x 0, c 15) of radius 5: 10 away at its bottom.
    let top = Pt::new(20.0, 0.0);
    let d = nearest_to_centre(top, top, Some((Pt::new(15.0, 0.0), true)));
    assert!((d - 10.0).abs() < 1e-12, "{d}");
}

#[test]
fn the_alarms_of_polar_and_cylindrical_interpolation() {
    let e = |blocks: &[&str]| {
        let mut m = Lathe::with_c();
        blocks.iter().find_map(|b| m.try_run(b).err()).unwrap_or(0)
    };
    // E4033: compensation on, G99, C not at 0°, a tool change inside.
    assert_eq!(e(&["G42 G01 X20 Z0 F1", "G12.1"]), 4033);
    assert_eq!(e(&["G99", "G12.1"]), 4033);
    assert_eq!(e(&["G99", "G7.1 C10"]), 4033);
    assert_eq!(e(&["G00 C30", "G12.1"]), 4033);
    // (A negative X at C 0 is the plane's point (x < 0, 0), whose joints
    // are X > 0 at C 180°; X0 starts at the centre.)
    assert_eq!(e(&["G00 X-20 C0", "G12.1"]), 4033);
    assert_eq!(e(&["G00 X0 C0", "G12.1"]), 0);
    assert_eq!(e(&["G12.1", "T0101"]), 4033);
    assert_eq!(e(&["G7.1 C10", "T0202"]), 4033);
    assert_eq!(e(&["G12.1", "G99 G01 X10 F1"]), 4033);
    // In the block that starts the mode, whatever the words' order: its
    // T and G99 act inside it (group 0 comes first).
    assert_eq!(e(&["G12.1 G99"]), 4033);
    assert_eq!(e(&["G12.1 T0202"]), 4033);
    assert_eq!(e(&["T0202 G7.1 C10"]), 4033);
    // A move through the spindle centre: a line, a rapid, an arc.
    assert_eq!(e(&["G00 X40", "G12.1", "G01 X-40 F100"]), 4033);
    assert_eq!(e(&["G00 X40", "G12.1", "G00 X-20"]), 4033);
    // (About (x 5, c 5) from (x 10, c 0) to (x 0, c 10): clockwise through
    // the centre, counter-clockwise through (x 10, c 10).)
    assert_eq!(e(&["G00 X20", "G12.1", "G02 X0 C10 I-5 J5 F100"]), 4033);
    assert_eq!(e(&["G00 X20", "G12.1", "G03 X0 C10 I-5 J5 F100"]), 0);
    assert_eq!(e(&["G00 X20", "G12.1", "G01 X-20 C0.01 F100"]), 0);
    // E2007: G16 outside G12.1; words or modes that cannot stand there.
    assert_eq!(e(&["G16"]), 2007);
    assert_eq!(e(&["G12.1", "G13.1", "G16"]), 2007);
    assert_eq!(e(&["G12.1 X10"]), 2007);
    assert_eq!(e(&["G12.1", "G7.1 C10"]), 2007);
    assert_eq!(e(&["G12.1", "G02 X10 C5 K5 F1"]), 2007);
    assert_eq!(e(&["G7.1 C10", "G02 Z-5 C30 I5 F1"]), 2007);
    assert_eq!(e(&["G12.1", "G71 U1 R1"]), 2007);
    assert_eq!(e(&["G12.1", "G28 U0"]), 2007);
    // Drilling cycles (they would shrink to one rapid to the bottom) and
    // work systems: inside, in the starting block, or in force at G12.1.
    assert_eq!(e(&["G12.1", "G83 Z-5 Q1000 F50"]), 2007);
    assert_eq!(e(&["G7.1 C10", "G87 X10 Q1000 F50"]), 2007);
    assert_eq!(e(&["G83 Z-5 Q1000 F50", "G12.1"]), 2007);
    assert_eq!(e(&["G83 Z-5 Q1000 F50", "G80", "G12.1"]), 0);
    assert_eq!(e(&["G12.1", "G55"]), 2007);
    assert_eq!(e(&["G12.1 G55"]), 2007);
    // E2099: what is not supported yet.
    assert_eq!(e(&["G7.1 C10 J5 L2 R1 K0.2"]), 2099);
    // The axis outside the plane moves with a line, compensated or not
    // (a line from the centre that takes Z along is still E4033).
    assert_eq!(e(&["G00 X40", "G12.1", "G42 G01 X10 Z-5 F1"]), 0);
    assert_eq!(e(&["G00 X40", "G12.1", "G42 G01 X10 F1", "G40 X20 W1"]), 0);
    assert_eq!(e(&["G7.1 C10", "G41 G01 X10 Z-5 F1"]), 0);
    assert_eq!(e(&["G7.1 C10", "G41 G01 Z-5 F1", "G01 U1 C30"]), 0);
    assert_eq!(e(&["G00 X40", "G12.1", "G01 X10 Z-5 F1"]), 0);
    assert_eq!(e(&["G12.1", "G01 X10 Z-5 F1"]), 4033);
    assert_eq!(e(&["G7.1 C10", "G01 U1 C30 F1"]), 0);
    // Ellipses and parabolas: one that cannot join its points (chord 40
    // > 2A), one that passes 0.5 µm from the centre (B), one under
    // compensation (its chords).
    assert_eq!(e(&["G00 X40", "G12.1", "G6.2 X-40 C0 A5 B3 F1"]), 4005);
    assert_eq!(
        e(&["G00 X40", "G12.1", "G6.3 X-40 C0 A20 B0.0005 F1"]),
        4033
    );
    assert_eq!(e(&["G00 X40", "G12.1", "G6.3 X-40 C0 A20 B1 F1"]), 0);
    assert_eq!(
        e(&["G00 X40", "G12.1", "G42 G01 X10 F1", "G6.3 X-10 C0 A5 B3"]),
        0
    );
    // (The chord along the axis, C: Q0 is along the first axis.)
    assert_eq!(e(&["G7.1 C10", "G7.2 C30 P100 F1"]), 4006);
    // Compensation runs inside, but not where the mode ends: G40 alone
    // leaves its cancel to the next move.
    assert_eq!(e(&["G00 X40", "G12.1", "G42 G01 X10 F1", "G13.1"]), 4033);
    assert_eq!(
        e(&["G00 X40", "G12.1", "G42 G01 X10 F1", "G40", "G13.1"]),
        4033
    );
    assert_eq!(
        e(&["G00 X40", "G12.1", "G42 G01 X10 F1", "G40 X20", "G13.1"]),
        0
    );
    assert_eq!(e(&["G7.1 C10", "G41 G01 Z-5 F1", "G7.1 C0"]), 4033);
    assert_eq!(e(&["G7.1 C10", "G41 G01 Z-5 F1", "G40 C5", "G7.1 C0"]), 0);
    // E2006: G7.1 without its radius; E2003 without a C axis.
    assert_eq!(e(&["G7.1"]), 2006);
    let bare = crate::exec::cycles::testing::run_err;
    assert_eq!(bare(&["G12.1"]), 2003);
    assert_eq!(bare(&["G7.1 C10"]), 2003);
    // A dwell runs inside; G13.1 and G7.1 C0 outside their modes do nothing.
    assert_eq!(e(&["G12.1", "G04 X1", "G13.1", "G13.1", "G7.1 C0"]), 0);
}

/// The reference machine with its C axis and offset 1: nose radius 2,
/// tip 3 (which polar and cylindrical interpolation do not use).
fn with_c_and_tool() -> Lathe {
    let toml = "[axes.c]\nenabled = true\n[[tools.offset]]\nnumber = 1\nradius = 2\ntip = 3\n";
    let m = crate::base::machine::Machine::from_toml(toml).expect("a machine file");
    Lathe {
        nc: crate::exec::Nc::new(m),
    }
}

#[test]
fn a_compensated_ellipse_runs_its_chords_offset_in_the_plane() {
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z-2 C0 T0101",
            "G98 G12.1",
            // From (20, 0) to (15, 0), then the half ellipse x²/15² +
            // c²/8² = 1 counter-clockwise over (0, 8) to (−15, 0), the
            // tool (radius 2) on its left: inside it, towards the centre;
            // the cancel to (−20, 0).
            "G41 G01 X30 F100",
            "G6.3 X-30 C0 A15 B8 Q0",
            "G40 G01 X-40",
            "G13.1",
        ],
    );
    // Every point the tool's centre is printed at along the ellipse lies
    // 2 mm inside it, within the chords' 0.001 mm: its distance from 20
    // 000 points of the curve.
    let ellipse: Vec<Pt> = (0..=20_000)
        .map(|i| {
            let t = core::f64::consts::PI * f64::from(i) / 20_000.0;
            Pt::new(8.0 * libm::sin(t), 15.0 * libm::cos(t))
        })
        .collect();
    let points: Vec<Pt> = l
        .iter()
        .filter(|line| line.starts_with("LINE") || line.starts_with("ARC"))
        .filter_map(|line| {
            let mut w = line.split(' ').filter_map(|w| w.split_once('='));
            let x: f64 = w.find(|(k, _)| *k == "X")?.1.parse().ok()?;
            let c: f64 = w.find(|(k, _)| *k == "C")?.1.parse().ok()?;
            Some(Pt::new(c, x / 2.0))
        })
        .collect();
    // (The start-up's end and the outside-corner arc at (15, 0) before
    // them; the cancel's end after.)
    let along: Vec<&Pt> = points.iter().filter(|p| p.r > 0.5).collect();
    assert!(along.len() > 100, "{}", along.len());
    for p in along {
        let d = ellipse.iter().map(|q| q.dist(*p)).fold(f64::MAX, f64::min);
        assert!((d - 2.0).abs() < 0.002, "{p:?} {d}");
        assert!((p.z / 15.0).powi(2) + (p.r / 8.0).powi(2) < 1.0, "{p:?}");
    }
    assert_eq!(
        l.last().map(|s| s.as_str()),
        Some("POLAR MODE=OFF X=40 C=180")
    );
}

#[test]
fn polar_compensation_offsets_the_tool_centre_in_the_plane() {
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z-2 C0 T0101",
            // Plane points (x, c), x = X/2: the plane starts at (20, 0).
            "G98 G12.1",
            // Start-up to the start normal of the next element, which
            // runs +c: the tool on its left is at x − 2, (8, 0).
            "G41 G01 X20 F100",
            // Up along x = 10, offset to x = 8, to (8, 20); the path then
            // turns right (+x), the tool outside the corner: an arc about
            // the corner (10, 20) from (8, 20) to (10, 22), clockwise.
            "C20",
            // Along c = 20 offset to c = 22; the turn up again (+c) is a
            // left turn, the tool inside: the two offset lines c = 22 and
            // x = 18 meet at (18, 22).
            "X40",
            // The cancel: up along x = 20 offset to x = 18, and ends on
            // its own normal at (18, 30)? No: a cancel move runs from the
            // last element's end normal to the programmed point (comp.md
            // §6), so the element before ends at its end normal (20, 22)
            // and the cancel runs from there to (20, 30).
            "G40 C30",
            "G13.1",
        ],
    );
    // The joints at the end: radius √(20² + 30²) = 36.0555, X 72.1110;
    // C atan2(30, 20) = 56.3099°, the path never turning about the centre.
    assert_eq!(
        l,
        [
            "TOOL T=1 D=1",
            "RAPID X=40 Z=-2 C=0",
            "POLAR MODE=ON",
            "FEED F=100 MODE=MIN",
            "LINE X=16 C=0",
            "LINE X=16 C=20",
            "ARC DIR=CW X=20 C=22 CX=20 CC=20",
            "LINE X=40 C=22",
            "LINE X=40 C=30",
            "POLAR MODE=OFF X=72.111 C=56.3099",
        ]
    );
}

#[test]
fn a_compensated_line_takes_the_axis_outside_the_plane_along() {
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z-2 C0 T0101",
            // The path of `polar_compensation_offsets_the_tool_centre_in_the_plane`,
            // Z going down along each line.
            "G98 G12.1",
            "G41 G01 X20 Z-3 F100",
            "C20 Z-4",
            // W from the Z the last block programmed (−4), though that
            // side still waits for this block's corner.
            "X40 W-1",
            "G40 C30 Z0",
            "G13.1",
        ],
    );
    // The start-up, the side and the cancel take Z to their blocks' ends;
    // the arc round the outside corner, which comes before its block's
    // own element, holds it at −4, as a corner block of its own would.
    assert_eq!(
        l,
        [
            "TOOL T=1 D=1",
            "RAPID X=40 Z=-2 C=0",
            "POLAR MODE=ON",
            "FEED F=100 MODE=MIN",
            "LINE X=16 C=0 Z=-3",
            "LINE X=16 C=20 Z=-4",
            "ARC DIR=CW X=20 C=22 CX=20 CC=20",
            "LINE X=40 C=22 Z=-5",
            "LINE X=40 C=30 Z=0",
            "POLAR MODE=OFF X=72.111 C=56.3099",
        ]
    );
    assert_eq!(m.nc.st.pos.z, 0.0);
    // On the cylinder X (a diameter) goes along: the path of
    // `cylinder_compensation_offsets_the_tool_centre_on_the_surface`.
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z0 C0 T0101",
            "G98 G7.1 C20.",
            "G41 G01 Z-10 X39 F100",
            "C90 U-1",
            "G40 Z0 X40",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "TOOL T=1 D=1",
            "RAPID X=40 Z=0 C=0",
            "CYLINDER MODE=ON R=20",
            "FEED F=100 MODE=MIN",
            "LINE Z=-8 C=0 X=39",
            "LINE Z=-8 C=90 X=38",
            "LINE Z=0 C=90 X=40",
            "CYLINDER MODE=OFF",
        ]
    );
}

#[test]
fn cylinder_compensation_offsets_the_tool_centre_on_the_surface() {
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z0 C0 T0101",
            // Developed points (s, z), s = 20·C·π/180, seen with s to the
            // right and Z up: the plane starts at (0, 0).
            "G98 G7.1 C20.",
            // Start-up to the next element's start normal: that element
            // runs +s, the tool on its left is at z + 2: (0, −8).
            "G41 G01 Z-10 F100",
            // C90: s = 10π, along z = −10 offset to z = −8.
            "C90",
            // The cancel from that element's end normal (10π, −8) to the
            // programmed (10π, 0).
            "G40 Z0",
            "G7.1 C0",
        ],
    );
    assert_eq!(
        l,
        [
            "TOOL T=1 D=1",
            "RAPID X=40 Z=0 C=0",
            "CYLINDER MODE=ON R=20",
            "FEED F=100 MODE=MIN",
            "LINE Z=-8 C=0",
            "LINE Z=-8 C=90",
            "LINE Z=0 C=90",
            "CYLINDER MODE=OFF",
        ]
    );
    assert_eq!(var(&m, 5043), Some(90.0));
}

#[test]
fn a_move_of_the_axis_outside_the_plane_waits_behind_a_compensated_element() {
    let mut m = with_c_and_tool();
    let l = lines(
        &mut m,
        &[
            "G00 X40 Z-2 C0 T0101",
            "G98 G12.1",
            // As in `polar_compensation_offsets_the_tool_centre_in_the_plane`:
            // the start-up to (8, 0), then up along x = 8.
            "G41 G01 X20 F100",
            "C20",
            // Z goes down where the tool stands once the corner after the
            // side is known: (8, 20), C = atan2(20, 8) = 68.1986°. Its
            // feed is printed before it; the side along c = 20 waits.
            "Z-5 F50",
            "G01 X40 F100",
        ],
    );
    assert_eq!(
        l,
        [
            "TOOL T=1 D=1",
            "RAPID X=40 Z=-2 C=0",
            "POLAR MODE=ON",
            "FEED F=100 MODE=MIN",
            "LINE X=16 C=0",
            "LINE X=16 C=20",
            "FEED F=50 MODE=MIN",
            "LINE Z=-5",
        ]
    );
    // The tool stands where the side along x = 8 ended; the programmed
    // point is the last block's (20, 20).
    let Some(crate::exec::plane::PlaneState { pt, tool, .. }) = m.nc.st.plane else {
        panic!("polar interpolation is on");
    };
    assert_eq!([tool.z, tool.r, pt.z, pt.r], [8.0, 20.0, 20.0, 20.0]);
    let c = var(&m, 5043).expect("C");
    assert!((c - 20f64.atan2(8.0).to_degrees()).abs() < 1e-9, "{c}");
    // Six more blocks that move only Z are allowed; a seventh is E4034.
    for k in 0..6 {
        m.run(&alloc::format!("Z-{}", 6 + k));
    }
    assert_eq!(m.try_run("Z-20"), Err(4034));
}

#[test]
fn a_compensated_path_through_the_centre_is_e4033() {
    let run = |side: &str| {
        let mut m = with_c_and_tool();
        let blocks = [
            "G00 X40 Z-2 C0 T0101",
            "G98 G12.1",
            // The start-up to (10, 2), then along c = 2 to (−10, 2): 2 from
            // the centre, the tool's radius.
            &alloc::format!("{side} G01 X20 C2 F300"),
            "X-20",
            "G40 X-40 C0",
        ];
        blocks.iter().find_map(|b| m.try_run(b).err()).unwrap_or(0)
    };
    // G42 keeps the centre right of the −x move, at c = 4; G41 puts it at
    // c = 0, through the centre, found when that element prints (with
    // the cancel).
    assert_eq!(run("G42"), 0);
    assert_eq!(run("G41"), 4033);
}

/// The angle about the origin along an arc, summed over 100 000 steps of
/// the arc (an independent count of `swept`).
fn swept_by_steps(c: Pt, r: f64, a0: f64, span: f64) -> f64 {
    let at = |a: f64| Pt::new(c.r + r * libm::sin(a), c.z + r * libm::cos(a));
    let n = 100_000;
    let mut total = 0.0;
    let mut prev = at(a0);
    for k in 1..=n {
        let p = at(a0 + span * f64::from(k) / f64::from(n));
        let d = libm::atan2(p.r, p.z) - libm::atan2(prev.r, prev.z);
        total += d - core::f64::consts::TAU * libm::round(d / core::f64::consts::TAU);
        prev = p;
    }
    total
}

#[test]
fn swept_counts_the_turns_of_an_arc_that_passes_near_the_centre() {
    use core::f64::consts::PI;
    let deg = |d: f64| d.to_radians();
    // (centre, radius, start angle about the centre, signed span)
    let arcs = [
        // (Pt::new takes the second axis first: the centres are on the
        // second axis.) 5 µm below the origin, which lies between the arc
        // and the chord of its 5° about the bottom (chords of 5°
        // miscounted it by a turn): about +210°.
        (Pt::new(20.0, 0.0), 20.005, deg(-122.5), deg(60.0)),
        (Pt::new(20.0, 0.0), 20.005, deg(-57.5), deg(-60.0)),
        // The origin 5 µm outside the circle.
        (Pt::new(20.0, 0.0), 19.995, deg(-122.5), deg(60.0)),
        // A full circle about an inner point off its centre, both ways.
        (Pt::new(3.0, 4.0), 10.0, deg(30.0), 2.0 * PI),
        (Pt::new(3.0, 4.0), 10.0, deg(30.0), -2.0 * PI),
        // A full circle that leaves the origin outside.
        (Pt::new(30.0, 0.0), 10.0, deg(30.0), 2.0 * PI),
        // Most of a circle about an inner point.
        (Pt::new(1.0, -2.0), 8.0, deg(100.0), deg(-300.0)),
    ];
    for (c, r, a0, span) in arcs {
        let at = |a: f64| Pt::new(c.r + r * libm::sin(a), c.z + r * libm::cos(a));
        let (from, to) = (
            at(a0),
            if span.abs() == 2.0 * PI {
                at(a0)
            } else {
                at(a0 + span)
            },
        );
        let got = swept(from, to, Some((c, span < 0.0)));
        let want = swept_by_steps(c, r, a0, span);
        assert!(
            (got - want).abs() < 1e-6,
            "{c:?} r{r}: {got} against {want}"
        );
    }
    // The first passes below the origin from its left to its right,
    // counter-clockwise: the long way round, the end's angle less the
    // start's plus a whole turn.
    let at = |a: f64| (20.005 * deg(a).cos(), 20.0 + 20.005 * deg(a).sin());
    let ((zs, rs), (ze, re)) = (at(-122.5), at(-62.5));
    let want = re.atan2(ze) - rs.atan2(zs) + 2.0 * PI;
    let first = swept_by_steps(Pt::new(20.0, 0.0), 20.005, deg(-122.5), deg(60.0));
    assert!(
        (first - want).abs() < 1e-6 && want > deg(200.0),
        "{first} {want}"
    );
}

/// Inside G12.1 the position variables read the joints, as the control's
/// position display shows them (language.md, "position variables in a
/// plane"): after the line to the plane point (x 10, c 10) X is the joint
/// diameter 2·√200 = 28.2843 and C the angle 45°, not the plane's X20 C10.
#[test]
fn position_variables_read_the_joints_inside_a_plane() {
    let mut m = Lathe::with_c();
    lines(&mut m, &["G98 G00 X40 Z-2 C0", "G12.1", "G01 X20 C10 F100"]);
    for n in [5001, 5021, 5041] {
        let x = var(&m, n).unwrap();
        assert!((x - 2.0 * libm::sqrt(200.0)).abs() < 1e-9, "#{n} = {x}");
    }
    for n in [5003, 5023, 5043] {
        let c = var(&m, n).unwrap();
        assert!((c - 45.0).abs() < 1e-9, "#{n} = {c}");
    }
    assert_eq!(var(&m, 5002), Some(-2.0));
}
