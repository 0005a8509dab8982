//! Printing the legs of a roughing cycle (`plan::roughing`).
//!
//! Legs are printed here rather than through `Nc::rapid`/`Nc::line`: those
//! are the path of programmed G00/G01 blocks (corners, compensation), and a
//! generated leg takes part in neither.

use crate::base::error::NcError;
use crate::base::event::Event;
use crate::exec::{Nc, Sink};
use crate::plan::curve::ConicKind;
use crate::plan::roughing::Step;

/// Prints `steps` from the tool position, moving it.
pub fn print(nc: &mut Nc, sink: &mut dyn Sink, steps: &[Step]) -> Result<(), NcError> {
    nc.generate(steps.len())?;
    for &step in steps {
        match step {
            Step::Rapid(to) => {
                nc.st.pos = to;
                sink.emit(Event::Rapid {
                    x: to.x(),
                    z: to.z,
                    c: None,
                });
            }
            Step::Line(to) => {
                nc.feed_due(sink);
                nc.st.pos = to;
                sink.emit(Event::Line {
                    x: to.x(),
                    z: to.z,
                    c: None,
                });
            }
            Step::Arc { to, centre, dir } => {
                nc.feed_due(sink);
                nc.st.pos = to;
                sink.emit(Event::Arc {
                    dir,
                    x: to.x(),
                    z: to.z,
                    cx: centre.x(),
                    cz: centre.z,
                });
            }
            Step::Conic { to, dir, kind } => {
                nc.feed_due(sink);
                nc.st.pos = to;
                sink.emit(match kind {
                    ConicKind::Ellipse { a, b, q } => Event::Ellipse {
                        dir,
                        x: to.x(),
                        z: to.z,
                        a,
                        b,
                        q,
                    },
                    ConicKind::Parabola { p, q } => Event::Parabola {
                        dir,
                        x: to.x(),
                        z: to.z,
                        p,
                        q,
                    },
                });
            }
        }
    }
    Ok(())
}
