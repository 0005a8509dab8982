//! A feed move at F = 0 (dialect.md §4.1 G01, E7001): the move is printed
//! as it is, after its `FEED F=0`, and the block stops there with E7001,
//! the alarm the runtime raises when it would execute it. The kernel
//! raises it too so that a canon run without interpolation ends as a run
//! through the runtime does, with the alarm as the last line.

use crate::base::error::{Alarm, NcError};
use crate::base::event::Event;
use crate::base::point::Pt;
use crate::exec::Sink;

/// A sink that passes events on until a feed move runs at F = 0, then
/// drops the rest of the block and keeps the alarm.
pub struct Watch<'a> {
    inner: &'a mut dyn Sink,
    /// The last `FEED` printed was F = 0.
    zero: bool,
    /// The tool's position (work coordinates, X as a radius).
    at: Pt,
    fault: Option<NcError>,
}

impl<'a> Watch<'a> {
    /// `printed`: the last `FEED` printed before the block (F, per rev);
    /// `at`: where the tool stands.
    pub fn new(inner: &'a mut dyn Sink, printed: Option<(f64, bool)>, at: Pt) -> Watch<'a> {
        Watch {
            inner,
            zero: printed.is_some_and(|(f, _)| f == 0.0),
            at,
            fault: None,
        }
    }

    /// The end of the block: E7001 if a feed move ran at F = 0.
    pub fn finish(self) -> Option<NcError> {
        self.fault
    }
}

impl Sink for Watch<'_> {
    fn emit(&mut self, e: Event) {
        if self.fault.is_some() {
            return;
        }
        if let Event::Feed { f, .. } = e {
            self.zero = f == 0.0;
        }
        let end = match e {
            Event::Rapid { x, z, .. }
            | Event::Line { x, z, .. }
            | Event::Arc { x, z, .. }
            | Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. }
            | Event::Thread { x, z, .. }
            | Event::ArcThread { x, z, .. }
            | Event::Skip { x, z } => Some(Pt::new(x / 2.0, z)),
            _ => None,
        };
        // A line or skip that goes nowhere is no move for the runtime
        // either; an arc with equal ends is a full circle.
        let moves = match e {
            Event::Line { .. } | Event::Skip { .. } => end.is_some_and(|p| p.dist(self.at) > 1e-9),
            _ => true,
        };
        let zero_move = e.is_feed() && self.zero && moves;
        self.inner.emit(e);
        if let Some(p) = end {
            self.at = p;
        }
        if zero_move {
            self.fault = Some(NcError::new(
                Alarm::ZeroFeed,
                "a feed move with F = 0 cannot run: give the block or an earlier one an F",
            ));
        }
    }
}
