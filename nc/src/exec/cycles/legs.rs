//! Printing a cycle's path: the legs themselves are the planner's
//! (`plan::legs`).

use super::words::EPS;
use crate::base::error::NcError;
use crate::base::event::Event;
use crate::exec::{Nc, Sink};
pub(crate) use crate::plan::legs::{jk_pair, same, Leg, PullOut};

/// Prints a path from the current point. With `skip_zero` a move that ends
/// where the tool already is, is left out: a leg the cycle generates
/// (cycles.md §0); G33 prints its programmed moves whatever their length.
pub(crate) fn emit(
    nc: &mut Nc,
    legs: &[Leg],
    skip_zero: bool,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    nc.generate(legs.len())?;
    for &leg in legs {
        let to = match leg {
            Leg::Rapid(to) | Leg::Line(to) | Leg::Thread { to, .. } => Some(to),
            Leg::RapidC(to, c) if (c - nc.st.c).abs() <= EPS => Some(to),
            _ => None,
        };
        if skip_zero && to.is_some_and(|to| same(to, nc.st.pos)) {
            continue;
        }
        emit_one(nc, leg, sink);
    }
    Ok(())
}

fn emit_one(nc: &mut Nc, leg: Leg, sink: &mut dyn Sink) {
    match leg {
        Leg::Rapid(to) => nc.rapid(to, sink),
        Leg::RapidC(to, c) => {
            let from = core::mem::replace(&mut nc.st.c, c);
            nc.rapid_c(to, from, sink);
        }
        Leg::Line(to) => {
            nc.feed_due(sink);
            nc.st.pos = to;
            sink.emit(Event::Line {
                x: to.x(),
                z: to.z,
                c: nc.c_field(nc.st.c),
            });
        }
        Leg::Thread { to, lead, dlead, q } => {
            nc.st.pos = to;
            sink.emit(Event::Thread {
                x: to.x(),
                z: to.z,
                c: nc.c_field(nc.st.c),
                lead,
                dlead,
                q,
            });
        }
        Leg::Spindle(dir) => {
            nc.st.spindle = dir;
            sink.emit(Event::Spindle(dir));
        }
        Leg::Dwell(s) => {
            // The virtual clock (#3001) counts dwells, as G04 does.
            nc.st.clock_ms += s * 1000.0;
            sink.emit(Event::Dwell { s });
        }
        Leg::M(code) => sink.emit(Event::M(code)),
    }
}
