//! Ellipses (G6.2/G6.3) and parabolas (G7.2/G7.3) in the plane of polar
//! or cylindrical interpolation (seed 000 names them there: the axis
//! outside the plane is ignored in them, as in an arc). The block's words
//! are those of the ZX plane with the plane's first axis in Z's place: A
//! and B (or P) are lengths in the plane (mm), Q the axis angle from the
//! plane's first axis, counter-clockwise as seen in the plane's view (X
//! to the right and C up for G12.1, C to the right and Z up for G7.1), as
//! arcs are oriented there (plane.rs). The curve is the kernel's own
//! (`plan::conic`, `plan::curve`), in plane points; under compensation
//! its chords (`compensated`).

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, PlaneMotion};
use crate::base::gcode::Motion;
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::contour::conic::chord_params;
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::conic::{ellipse_centre, parabola_vertex};
use crate::plan::curve::{ConicKind, Curve};

use super::{Kind, PlaneState};

/// Halvings of a conic at most while its turn about the centre is
/// counted: a piece is then some 10⁻¹² of the curve (only pieces near
/// the centre are halved that far).
const MAX_DEPTH: u32 = 40;

/// A conic block of the plane to plane point `to`.
pub(super) fn run(
    nc: &mut Nc,
    st: PlaneState,
    code: Motion,
    to: Pt,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let ellipse = code.is_ellipse();
    let cw = code.is_cw_conic();
    let Some(curve) = nc.reader().conic_curve(ellipse, cw, p, st.pt, to)? else {
        return Ok(());
    };
    let dir = if cw { Dir::Cw } else { Dir::Ccw };
    let Curve::Conic { kind, .. } = curve else {
        // An ellipse with A = B: the arc it is.
        let Some(Element::Arc { centre, .. }) = curve.element() else {
            return Ok(());
        };
        let (ca, cb) = st.printed(centre);
        let motion = PlaneMotion::Arc { dir, ca, cb };
        let step = super::Step {
            motion,
            to,
            path: Some((centre, cw)),
            off: None,
        };
        return super::run_move(nc, st, step, sink, out);
    };
    if crate::exec::comp::compensating(nc) {
        out.moved = true;
        return compensated(nc, st, &curve, sink);
    }
    let turn = match st.kind {
        Kind::Polar => {
            let (turn, near) = about_centre(&curve);
            if near < nc.machine.machine.resolution_mm {
                return fail(
                    Alarm::PolarInComp,
                    "this curve of polar interpolation passes through the spindle centre, where C would turn half a turn at once: program the path round the centre",
                );
            }
            turn
        }
        Kind::Cylinder(_) => 0.0,
    };
    out.moved = true;
    let motion = match kind {
        ConicKind::Ellipse { a, b, q } => PlaneMotion::Ellipse { dir, a, b, q },
        ConicKind::Parabola { p, q } => PlaneMotion::Parabola { dir, p, q },
    };
    print(nc, st, motion, (to, turn), sink);
    Ok(())
}

/// Under G41/G42 a conic of the plane runs as the chords of a polyline
/// inscribed in it, each within 0.001 mm of the curve, through the
/// compensation as lines of the plane, as in the ZX plane (contour
/// conic.rs, seed 000 G6.2 note 9): the tool's centre runs R off the
/// chords, round their outside corners. At an inside corner the chords
/// start with the one that reaches the crossing of the offsets.
fn compensated(
    nc: &mut Nc,
    mut st: PlaneState,
    curve: &Curve,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let first = match nc.st.contour.last_compensated() {
        Some((prev, tool)) => crate::exec::comp::conic::start_param(&prev, &tool, curve)?,
        None => 0.0,
    };
    for s in chord_params(curve).into_iter().filter(|&s| s > first) {
        super::compensated(nc, st, (false, None), curve.at(s), None, sink)?;
        st = nc.st.plane.unwrap_or(st);
    }
    Ok(())
}

/// Moves the plane point, the joints and C (by `turn` radians about the
/// centre in the polar plane) to `to`, and prints the conic.
fn print(
    nc: &mut Nc,
    mut st: PlaneState,
    motion: PlaneMotion,
    (to, turn): (Pt, f64),
    sink: &mut dyn Sink,
) {
    nc.feed_due(sink);
    nc.st.c = match st.kind {
        Kind::Polar => nc.st.c + turn.to_degrees(),
        Kind::Cylinder(radius) => (to.z / radius).to_degrees(),
    };
    nc.st.pos = st.joints(to, nc.st.pos);
    (st.pt, st.tool) = (to, to);
    nc.st.plane = Some(st);
    super::emit_move(&st, motion, to, None, sink);
}

/// The curve of a conic the canon printed from `from` to `to` (plane
/// points), for its length; `None` for other motions or one that the
/// kernel would not have printed.
pub(crate) fn printed_curve(from: Pt, to: Pt, motion: PlaneMotion) -> Option<Curve> {
    match motion {
        PlaneMotion::Ellipse { dir, a, b, q } => {
            let cw = dir == Dir::Cw;
            let centre = ellipse_centre(from, to, a, b, q, cw).ok()??;
            Some(Curve::ellipse(from, to, centre, a, b, q, cw))
        }
        PlaneMotion::Parabola { dir, p, q } => {
            let cw = dir == Dir::Cw;
            let vertex = parabola_vertex(from, to, p, q, cw).ok()?;
            Some(Curve::parabola(from, to, vertex, p, q, cw))
        }
        _ => None,
    }
}

/// The angle (radians, counter-clockwise positive) a conic turns about
/// the plane's origin, and a lower bound of its distance from it, within
/// 2 % (`CLOSE`). A convex piece that turns by less than half a turn lies
/// in the triangle of its chord and its end tangents (one that turns by
/// less than `STRAIGHT`, whose tangents barely meet, within its turn
/// times its chord of the chord): where the origin lies outside that
/// the piece turns about it as its chord does (by less than half a
/// turn), and is no nearer. Pieces that hold the origin, or are much
/// nearer than their ends, are halved, at most `MAX_PIECES` of them (a
/// piece left then that turns by half a turn is taken to hold it).
pub(crate) fn about_centre(curve: &Curve) -> (f64, f64) {
    let mut budget = MAX_PIECES;
    piece(curve, (0.0, 1.0), 0, &mut budget)
}

/// A piece's lower bound of the distance is taken once it is at least
/// this share of its ends' distance.
const CLOSE: f64 = 0.98;

/// A piece turning by less than this (radians) is bounded by its chord.
const STRAIGHT: f64 = 1e-4;

/// Pieces looked at, at most (the `plane` fuzz target's flat ellipses,
/// their sides straight to 10⁻¹² rad, were once halved towards 2⁴⁰
/// pieces).
const MAX_PIECES: u32 = 1 << 16;

fn piece(curve: &Curve, (s0, s1): (f64, f64), depth: u32, budget: &mut u32) -> (f64, f64) {
    *budget = budget.saturating_sub(1);
    let (p0, p1) = (curve.at(s0), curve.at(s1));
    let near = match (curve.direction(s0), curve.direction(s1)) {
        (Some(d0), Some(d1)) => piece_distance(p0, d0, p1, d1),
        _ => None,
    };
    let ends = p0.norm().min(p1.norm());
    let done = near.is_some_and(|n| n >= CLOSE * ends);
    if done || depth >= MAX_DEPTH || *budget == 0 {
        let turn = libm::atan2(cross(p0, p1), p0.dot(p1));
        return (turn, near.unwrap_or(0.0));
    }
    let mid = (s0 + s1) / 2.0;
    let (t0, d0) = piece(curve, (s0, mid), depth + 1, budget);
    let (t1, d1) = piece(curve, (mid, s1), depth + 1, budget);
    (t0 + t1, d0.min(d1))
}

/// A lower bound of the distance of the origin from a piece from `p0`
/// (direction `d0`) to `p1` (direction `d1`) that turns by less than half
/// a turn; 0 where the piece may hold it; `None` where the piece turns
/// by half a turn or more.
fn piece_distance(p0: Pt, d0: Pt, p1: Pt, d1: Pt) -> Option<f64> {
    let turn = libm::atan2(cross(d0, d1).abs(), d0.dot(d1));
    if turn < STRAIGHT {
        let bulge = p0.dist(p1) * turn;
        return Some((segment_distance(p0, p1) - bulge).max(0.0));
    }
    tangent_corner(p0, d0, p1, d1).map(|t| triangle_distance([p0, t, p1]))
}

/// The z·r cross product of two plane vectors (counter-clockwise from
/// the first axis positive).
fn cross(a: Pt, b: Pt) -> f64 {
    a.z * b.r - a.r * b.z
}

/// Where the tangent at `p0` (direction `d0`) meets the one at `p1`
/// (direction `d1`), ahead of the first and behind the second: the
/// triangle's third corner; `None` where the piece turns by half a turn
/// or more.
fn tangent_corner(p0: Pt, d0: Pt, p1: Pt, d1: Pt) -> Option<Pt> {
    let den = cross(d0, d1);
    if den.abs() < 1e-12 {
        return None;
    }
    let chord = p1.sub(p0);
    let (t, u) = (cross(chord, d1) / den, cross(d0, chord) / den);
    (t >= 0.0 && u >= 0.0).then(|| p0.add(Pt::new(d0.r * t, d0.z * t)))
}

/// The distance of the origin from a triangle (0 inside it).
fn triangle_distance(c: [Pt; 3]) -> f64 {
    let side = |a: Pt, b: Pt| cross(b.sub(a), Pt::new(-a.r, -a.z));
    let s = [side(c[0], c[1]), side(c[1], c[2]), side(c[2], c[0])];
    if s.iter().all(|v| *v >= 0.0) || s.iter().all(|v| *v <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|i| segment_distance(c[i], c[(i + 1) % 3]))
        .fold(f64::INFINITY, f64::min)
}

/// The distance of the origin from the segment `p0`–`p1`.
fn segment_distance(p0: Pt, p1: Pt) -> f64 {
    let d = p1.sub(p0);
    let len2 = d.dot(d);
    let t = match len2 > 0.0 {
        true => (-p0.dot(d) / len2).clamp(0.0, 1.0),
        false => 0.0,
    };
    p0.add(Pt::new(d.r * t, d.z * t)).norm()
}
