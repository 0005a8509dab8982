//! Stored stroke check 2 (G22/G23, dialect.md §4.4): a box in machine
//! coordinates whose inside (№172.2 = 0) or outside (№172.2 = 1) the tool
//! may not enter.
//!
//! The kernel checks the end point of every motion event, cycle legs and
//! corner elements included, before the event leaves the block: the event
//! that would end in the forbidden area is not printed and the block stops
//! with E7002, so the canon ends as canon.md's ALARM section says. The path
//! between end points is the runtime's to check. Points are the programmed
//! tool point in machine coordinates (work point + workpiece origin, X as a
//! diameter), as #5021 reads them; tool offsets are the runtime's.

use crate::base::gcode::Stroke;
use alloc::format;

use crate::base::error::{Alarm, NcError};
use crate::base::event::Event;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Sink};

/// The forbidden area while G22 is in force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    /// + limits (X diameter, Z), machine coordinates, mm.
    pub plus: (f64, f64),
    /// − limits.
    pub minus: (f64, f64),
    /// The outside of the box is forbidden (else the inside).
    pub forbid_outside: bool,
}

impl Area {
    /// Whether the machine point (X diameter, Z) lies in the forbidden part.
    /// The boundary itself is allowed on both sides.
    pub fn forbids(&self, x: f64, z: f64) -> bool {
        let (lo_x, hi_x) = ordered(self.minus.0, self.plus.0);
        let (lo_z, hi_z) = ordered(self.minus.1, self.plus.1);
        let inside = x > lo_x && x < hi_x && z > lo_z && z < hi_z;
        let outside = x < lo_x || x > hi_x || z < lo_z || z > hi_z;
        if self.forbid_outside {
            outside
        } else {
            inside
        }
    }
}

fn ordered(a: f64, b: f64) -> (f64, f64) {
    if a <= b {
        (a, b)
    } else {
        (b, a)
    }
}

/// G22 (on, with X Z I K or the machine's №100/№101 for what the block
/// leaves out) or G23 (off). Without stroke check 2 (№172.4 = 0), G22 has
/// no effect.
pub fn select(nc: &mut Nc, code: Stroke, p: &Parsed) {
    let m = &nc.machine.stroke_check_2;
    if code != Stroke::On || !m.enabled {
        nc.st.stroke2 = None;
        return;
    }
    let word = |letter: u8, default: f64| nc.len_of(p, letter).unwrap_or(default);
    let area = Area {
        plus: (word(b'X', m.plus.x), word(b'Z', m.plus.z)),
        minus: (word(b'I', m.minus.x), word(b'K', m.minus.z)),
        forbid_outside: m.forbid_outside,
    };
    nc.st.stroke2 = Some(area);
}

/// The end point (X diameter, Z; work coordinates) of a motion event.
fn end_of(e: &Event) -> Option<(f64, f64)> {
    match *e {
        Event::Rapid { x, z, .. }
        | Event::Line { x, z, .. }
        | Event::Arc { x, z, .. }
        | Event::Ellipse { x, z, .. }
        | Event::Parabola { x, z, .. }
        | Event::Thread { x, z, .. }
        | Event::ArcThread { x, z, .. }
        | Event::Skip { x, z, .. } => Some((x, z)),
        _ => None,
    }
}

/// A sink that passes events on until one ends in the forbidden area;
/// from then on it drops them and keeps the alarm. A `FEED` waits for the
/// event after it, so the feed of a refused move is not printed either.
pub struct Guard<'a> {
    inner: &'a mut dyn Sink,
    area: Area,
    origin: Pt,
    feed: Option<Event>,
    fault: Option<NcError>,
}

impl<'a> Guard<'a> {
    pub fn new(inner: &'a mut dyn Sink, area: Area, origin: Pt) -> Guard<'a> {
        Guard {
            inner,
            area,
            origin,
            feed: None,
            fault: None,
        }
    }

    /// The end of the block: the alarm, or the events still held back.
    pub fn finish(mut self) -> Option<NcError> {
        if self.fault.is_none() {
            if let Some(f) = self.feed.take() {
                self.inner.emit(f);
            }
        }
        self.fault
    }
}

impl Sink for Guard<'_> {
    fn emit(&mut self, e: Event) {
        if self.fault.is_some() {
            return;
        }
        if matches!(e, Event::Feed { .. }) {
            if let Some(f) = self.feed.replace(e) {
                self.inner.emit(f);
            }
            return;
        }
        if let Some((x, z)) = end_of(&e) {
            let (mx, mz) = (x + self.origin.x(), z + self.origin.z);
            if self.area.forbids(mx, mz) {
                self.fault = Some(NcError::new(
                    Alarm::StrokeLimit,
                    format!(
                        "the move ends at machine X{} Z{}, in the area G22 forbids",
                        crate::base::event::Num(mx),
                        crate::base::event::Num(mz)
                    ),
                ));
                return;
            }
        }
        if let Some(f) = self.feed.take() {
            self.inner.emit(f);
        }
        self.inner.emit(e);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(forbid_outside: bool) -> Area {
        Area {
            plus: (100.0, 50.0),
            minus: (-10.0, -20.0),
            forbid_outside,
        }
    }

    #[test]
    fn inside_is_forbidden_by_default() {
        let a = area(false);
        assert!(a.forbids(20.0, 0.0));
        assert!(!a.forbids(120.0, 0.0));
        assert!(!a.forbids(20.0, 60.0));
        // The boundary is allowed.
        assert!(!a.forbids(100.0, 0.0));
        assert!(!a.forbids(20.0, -20.0));
    }

    #[test]
    fn outside_is_forbidden_by_172_2() {
        let a = area(true);
        assert!(!a.forbids(20.0, 0.0));
        assert!(a.forbids(120.0, 0.0));
        assert!(a.forbids(20.0, -30.0));
        assert!(!a.forbids(100.0, 50.0));
    }

    #[test]
    fn limits_written_the_wrong_way_round_make_the_same_box() {
        let a = Area {
            plus: (-10.0, -20.0),
            minus: (100.0, 50.0),
            forbid_outside: false,
        };
        assert!(a.forbids(20.0, 0.0));
        assert!(!a.forbids(120.0, 0.0));
    }

    use crate::exec::cycles::testing::Lathe;
    use alloc::vec::Vec;

    /// Runs blocks until one stops; the canon so far and the alarm code.
    fn run(blocks: &[&str]) -> (Vec<alloc::string::String>, u16) {
        let mut m = Lathe::new();
        let mut canon = Vec::new();
        for b in blocks {
            match m.try_run(b) {
                Ok(lines) => canon.extend(lines),
                Err(code) => return (canon, code),
            }
        }
        (canon, 0)
    }

    #[test]
    fn g22_words_are_limits_not_a_move() {
        // The reference machine's work zero is machine zero, so machine and
        // work coordinates agree here.
        let (canon, code) = run(&["G00 X150 Z10", "G22 X100. Z50. I-10. K-20.", "G00 X120 Z0"]);
        assert_eq!(code, 0);
        assert_eq!(canon, ["RAPID X=150 Z=10", "RAPID X=120 Z=0"]);
    }

    #[test]
    fn a_move_ending_inside_stops_before_its_events() {
        let (canon, code) = run(&[
            "G00 X150 Z10",
            "G22 X100. Z50. I-10. K-20.",
            "G98 G01 X20 F100",
            "G00 X150",
        ]);
        assert_eq!(code, 7002);
        // Neither the refused LINE nor the FEED before it is printed.
        assert_eq!(canon, ["RAPID X=150 Z=10"]);
    }

    #[test]
    fn a_cycle_leg_ending_inside_stops_the_cycle() {
        // G90 from X150 Z10 to X80 Z-10: the first leg rapids to X80 Z10,
        // which lies inside the box (X −10…100, Z −20…50): the cycle stops
        // before printing anything.
        let (canon, code) = run(&[
            "G00 X150 Z10",
            "G22 X100. Z50. I-10. K-20.",
            "G98 G90 X80 Z-10 F100",
        ]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=150 Z=10"]);
    }

    #[test]
    fn g23_switches_the_check_off() {
        let (canon, code) = run(&[
            "G00 X150 Z10",
            "G22 X100. Z50. I-10. K-20.",
            "G23",
            "G00 X20",
        ]);
        assert_eq!(code, 0);
        assert_eq!(canon, ["RAPID X=150 Z=10", "RAPID X=20 Z=10"]);
    }

    #[test]
    fn without_stroke_check_2_g22_does_nothing() {
        let mut machine = crate::base::machine::Machine::reference();
        machine.stroke_check_2.enabled = false;
        let mut m = Lathe {
            nc: crate::exec::Nc::new(machine),
        };
        assert!(m.try_run("G22 X100. Z50. I-10. K-20.").is_ok());
        assert_eq!(
            m.try_run("G00 X20 Z0"),
            Ok(alloc::vec!["RAPID X=20 Z=0".into()])
        );
    }
}
