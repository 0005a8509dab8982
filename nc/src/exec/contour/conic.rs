//! Ellipse and parabola blocks G6.2/G6.3 and G7.2/G7.3 (dialect.md
//! §4.1): the curve comes from `plan::conic`, the canon event from here.

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event};
use crate::block::Parsed;
use crate::exec::{Nc, Sink};
use crate::plan::conic::{ellipse_centre, parabola_vertex};

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
    let q = p.get(b'Q').unwrap_or(0.0) * 0.001;
    let dir = if cw { Dir::Cw } else { Dir::Ccw };
    if ellipse {
        let a = nc.len_of(p, b'A').unwrap_or(0.0);
        let b = nc.len_of(p, b'B').unwrap_or(0.0);
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
    } else {
        // P is an integer in increments, its sign ignored.
        let inc = if nc.st.inch() { 0.0001 * 25.4 } else { 0.001 };
        let pp = p.get(b'P').unwrap_or(0.0).abs() * inc;
        if pp <= 0.0 {
            return fail(
                Alarm::BadParabola,
                "G7.2/G7.3 need a parameter P greater than 0",
            );
        }
        if from.dist(to) < 1e-9 {
            return Ok(false);
        }
        parabola_vertex(from, to, pp, q.abs(), cw)?;
        super::flush(nc, sink)?;
        nc.feed_due(sink);
        sink.emit(Event::Parabola {
            dir,
            x: to.x(),
            z: to.z,
            p: pp,
            q: q.abs(),
        });
    }
    nc.st.pos = to;
    Ok(true)
}
