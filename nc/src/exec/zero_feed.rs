//! A feed move at F = 0 (dialect.md §4.1 G01, E7001): the move is printed
//! as it is, after its `FEED F=0`, and the block stops there with E7001,
//! the alarm the runtime raises when it would execute it. The kernel
//! raises it too so that a canon run without interpolation ends as a run
//! through the runtime does, with the alarm as the last line.

use crate::base::error::{Alarm, NcError};
use crate::base::event::Event;
use crate::base::gcode::{Comp, OneShot};
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Sink};

/// Whether the block about to run can print a feed move at F = 0, so that
/// it needs a [`Watch`]; most blocks cannot, and run without one.
///
/// Events an earlier block left waiting (the contour queue and the
/// compensation look-ahead) carry the feed of their own block, and G70–G73
/// run profile blocks with their own F: such blocks are always watched.
/// G76 and G78 print thread passes and rapids only (plan::threading), no
/// feed move. Otherwise a `FEED` of 0 is in force at the start of the
/// block (printed or modal) or the block may print one: every other
/// `FEED` is the modal F (`Nc::feed_due`, which only the block's own F
/// word changes, unless it is a thread's lead) or a G36/G37 measuring
/// feed. So a block whose F is not 0 cannot make one: the feed it prints
/// is F times the unit (1 or 25.4), not 0 either.
pub fn may_fault(nc: &Nc, p: &Parsed) -> bool {
    let st = &nc.st;
    if st.contour.is_holding()
        || st.modal.comp() != Comp::Off
        || crate::exec::comp::running(nc)
        || !nc.profile.is_empty()
    {
        return true;
    }
    if matches!(
        p.one_shot(),
        Some(OneShot::MultiThread | OneShot::SpiralThread)
    ) {
        return false;
    }
    st.feed_printed.is_some_and(|(f, _)| f == 0.0)
        || st.feed == 0.0
        || (p.get(b'F').is_some_and(|f| f == 0.0) && !f_is_lead(nc, p))
        || matches!(p.one_shot(), Some(OneShot::MeasureX | OneShot::MeasureZ))
}

/// Whether the F of a block without G codes is a thread lead, not a feed:
/// as the modal state says, which such a block does not change.
fn f_is_lead(nc: &Nc, p: &Parsed) -> bool {
    p.gs().next().is_none() && crate::exec::cycles::f_is_lead(nc, p)
}

/// A sink that passes events on until a feed move runs at F = 0, then
/// drops the rest of the block and keeps the alarm.
pub struct Watch<'a> {
    inner: &'a mut dyn Sink,
    /// The last `FEED` printed was F = 0.
    zero: bool,
    /// The tool's position (work coordinates, X as a radius).
    at: Pt,
    /// The block the events come from, when the kernel told one: a
    /// corner's arc printed with an earlier block's element faults there.
    told: Option<u32>,
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
            told: None,
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
        let end = e.end().map(|(x, z)| Pt::xz(x, z));
        // Only a feed move after `FEED F=0` can fault: the usual event
        // costs the matches above and nothing more.
        let zero_move = self.zero && e.is_feed() && self.moves(&e, end);
        self.inner.emit(e);
        if let Some(p) = end {
            self.at = p;
        }
        if zero_move {
            let e = NcError::new(
                Alarm::ZeroFeed,
                "a feed move with F = 0 cannot run: give the block or an earlier one an F",
            );
            self.fault = Some(match self.told {
                Some(block) => e.at(block),
                None => e,
            });
        }
    }

    fn origin(&mut self, block: u32) {
        self.told = Some(block);
        self.inner.origin(block);
    }
}

impl Watch<'_> {
    /// Whether a feed event moves the tool. A line or skip that goes
    /// nowhere is no move for the runtime either; an arc with equal ends
    /// is a full circle.
    fn moves(&self, e: &Event, end: Option<Pt>) -> bool {
        match e {
            Event::Line { .. } | Event::Skip { .. } => end.is_some_and(|p| p.dist(self.at) > 1e-9),
            _ => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::base::event::Event;
    use crate::exec::cycles::testing::{words, Lathe};
    use alloc::string::{String, ToString};
    use alloc::vec::Vec;

    /// The canon of every block, the faulty one's events included (they
    /// reach the sink before its alarm), and the alarm's code.
    fn run(blocks: &[&str]) -> (Vec<String>, u16) {
        let mut m = Lathe::new();
        let mut events: Vec<Event> = Vec::new();
        for b in blocks {
            if let Err(e) = m.nc.exec(&words(b), &mut events) {
                return (events.iter().map(|e| e.to_string()).collect(), e.code);
            }
        }
        (events.iter().map(|e| e.to_string()).collect(), 0)
    }

    #[test]
    fn a_feed_move_without_f_is_printed_then_stops() {
        // No F since power-on: the move is printed as it is (FEED F=0),
        // then E7001 (dialect.md §4.1, G01).
        let (canon, code) = run(&["G98 G01 X10", "G00 X50"]);
        assert_eq!(code, 7001);
        assert_eq!(canon, ["FEED F=0 MODE=MIN", "LINE X=10 Z=0"]);
    }

    #[test]
    fn a_block_that_writes_f0_is_watched() {
        // F100 is in force; the block's own F0 is the feed of its move.
        let (canon, code) = run(&["G98 G01 X10 F100", "G01 X20 F0", "G00 X50"]);
        assert_eq!(code, 7001);
        assert_eq!(
            canon,
            [
                "FEED F=100 MODE=MIN",
                "LINE X=10 Z=0",
                "FEED F=0 MODE=MIN",
                "LINE X=20 Z=0"
            ]
        );
        // And back from F0 to a feed: the block runs.
        let (_, code) = run(&["G98 G00 X10 F0", "G01 X20 F100"]);
        assert_eq!(code, 0);
    }

    #[test]
    fn rapids_and_a_move_that_goes_nowhere_run_at_f0() {
        let (canon, code) = run(&["G00 X10 Z5", "G98 G01 X10 Z5", "G00 X20"]);
        assert_eq!(code, 0, "{canon:?}");
    }

    #[test]
    fn an_element_queued_at_f0_stops_the_block_that_prints_it() {
        // The G01 X10 element waits for its L1 chamfer; the F100 block
        // moves nothing; G01 Z-10 has no F of its own, yet prints the
        // waiting element with the F = 0 it was queued with: shortened by
        // the 1 mm chamfer to radius 4 (X8), then E7001 in that block.
        let (canon, code) = run(&["G98 G00 X0 Z0", "G01 X10 F0 L1", "F100", "G01 Z-10"]);
        assert_eq!(code, 7001);
        assert_eq!(
            canon,
            ["RAPID X=0 Z=0", "FEED F=0 MODE=MIN", "LINE X=8 Z=0"]
        );
    }

    #[test]
    fn a_thread_lead_is_no_feed() {
        // No F since power-on; G76's F is its lead and its passes are
        // threads and rapids: the cycle runs to its end (no E7001) and
        // prints no FEED.
        let (canon, code) = run(&[
            "G00 X32 Z5",
            "G76 P20060 Q20 R0.02",
            "G76 X25.1 Z-40 P2450 Q350 F4",
        ]);
        assert_eq!(code, 0, "{canon:?}");
        assert!(canon.iter().any(|l| l.starts_with("THREAD")), "{canon:?}");
        assert!(!canon.iter().any(|l| l.starts_with("FEED")), "{canon:?}");
        // F = 0 is still in force for the feed move after the cycle.
        let (_, code) = run(&["G00 X32 Z5", "G76 X25.1 Z-40 P2450 Q350 F4", "G01 Z-50"]);
        assert_eq!(code, 7001);
    }

    #[test]
    fn a_roughing_cycle_at_f0_stops_after_its_first_feed_move() {
        // G90 X40 Z-10 from X50 Z2: a rapid to X40, then the first feed
        // leg to Z-10, then E7001; the rest of the cycle is not printed.
        let (canon, code) = run(&["G00 X50 Z2", "G98 G90 X40 Z-10"]);
        assert_eq!(code, 7001);
        assert_eq!(
            canon,
            [
                "RAPID X=50 Z=2",
                "RAPID X=40 Z=2",
                "FEED F=0 MODE=MIN",
                "LINE X=40 Z=-10"
            ]
        );
    }
}
