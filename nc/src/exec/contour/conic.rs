//! Ellipse and parabola blocks G6.2/G6.3 and G7.2/G7.3 (dialect.md
//! §4.1): the curve comes from `plan::conic`, the canon event from here.

use crate::base::error::NcError;
use crate::base::event::{Dir, Event};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Sink};
use crate::plan::conic::{ellipse_centre, parabola_vertex};
use crate::plan::curve::Curve;
use crate::plan::reader::Shape;

/// A G6.2, G6.3, G7.2 or G7.3 block that may move.
pub fn run(
    nc: &mut Nc,
    ellipse: bool,
    cw: bool,
    p: &Parsed,
    sink: &mut dyn Sink,
) -> Result<bool, NcError> {
    if !p.has_axis() {
        return Ok(false);
    }
    let (from, to) = (nc.st.pos, nc.target(p));
    if crate::exec::comp::conic_compensated(nc)? {
        let Some(curve) = nc.reader().conic_curve(ellipse, cw, p, from, to)? else {
            return Ok(false);
        };
        compensated(nc, &curve, sink)?;
        return Ok(true);
    }
    let dir = if cw { Dir::Cw } else { Dir::Ccw };
    match nc.reader().conic_shape(ellipse, p)? {
        Shape::Ellipse { a, b, q } => {
            let Some(c) = ellipse_centre(from, to, a, b, q, cw)? else {
                return Ok(false);
            };
            super::flush(nc, sink)?;
            nc.feed_due(sink);
            sink.emit(if (a - b).abs() < 1e-9 {
                Event::Arc {
                    dir,
                    x: to.x(),
                    z: to.z,
                    cx: c.x(),
                    cz: c.z,
                }
            } else {
                Event::Ellipse {
                    dir,
                    x: to.x(),
                    z: to.z,
                    a,
                    b,
                    q,
                }
            });
        }
        Shape::Parabola { p: pp, q } => {
            if from.dist(to) < 1e-9 {
                return Ok(false);
            }
            parabola_vertex(from, to, pp, q, cw)?;
            super::flush(nc, sink)?;
            nc.feed_due(sink);
            sink.emit(Event::Parabola {
                dir,
                x: to.x(),
                z: to.z,
                p: pp,
                q,
            });
        }
    }
    nc.st.pos = to;
    Ok(true)
}

/// How far the chords of a compensated conic may stand off the curve (mm):
/// the least input increment, below anything the program can express.
pub const CHORD_TOLERANCE: f64 = 0.001;

/// The most chords one conic becomes (a 180° ellipse of 1 m needs far
/// fewer at 0.001 mm).
const MAX_CHORDS: usize = 1 << 14;

/// Under G41/G42 (seed 000, G6.2 note 9, G7.2 note 7) a conic runs as the
/// chords of a polyline inscribed in it, each within `CHORD_TOLERANCE` of
/// the curve, through the compensation like G01 moves: the nose then runs
/// R off the programmed curve (type C offsets the chords and rounds their
/// outside corners). An ellipse with A = B is the arc it is.
fn compensated(nc: &mut Nc, curve: &Curve, sink: &mut dyn Sink) -> Result<(), NcError> {
    if let Some(arc) = curve.element() {
        return super::feed_element(nc, arc, None, sink);
    }
    // At an inside corner the chords start with the one that reaches the
    // crossing of the offsets: the ones before lie wholly in the trim.
    let first = match nc.st.contour.last_compensated() {
        Some((prev, tool)) => crate::exec::comp::conic::start_param(&prev, &tool, curve)?,
        None => 0.0,
    };
    let mut from = curve.start();
    for s in chord_params(curve).into_iter().filter(|&s| s > first) {
        let to = curve.at(s);
        super::feed_element(nc, Element::Line { from, to }, None, sink)?;
        from = to;
    }
    Ok(())
}

/// The parameters of the polyline's vertices after the start, evenly
/// spaced in the curve's parameter: the count doubles until every chord's
/// middle lies within the tolerance of the curve's middle point.
pub(crate) fn chord_params(curve: &Curve) -> alloc::vec::Vec<f64> {
    let mut n = 4;
    while n < MAX_CHORDS {
        let fits = (0..n).all(|i| {
            let (s0, s1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
            let (a, b, m) = (curve.at(s0), curve.at(s1), curve.at((s0 + s1) / 2.0));
            m.dist(Pt::new((a.r + b.r) / 2.0, (a.z + b.z) / 2.0)) <= CHORD_TOLERANCE
        });
        if fits {
            break;
        }
        n *= 2;
    }
    (1..=n).map(|i| i as f64 / n as f64).collect()
}
