//! Stored stroke check 2 (G22/G23, dialect.md §4.4): a box in machine
//! coordinates whose inside (№172.2 = 0) or outside (№172.2 = 1) the tool
//! may not enter.
//!
//! The kernel checks every motion event, cycle legs and corner elements
//! included, before the event leaves the block: the event that would end
//! in the forbidden area, or whose path runs through it, is not printed
//! and the block stops with E7002, so the canon ends as canon.md's ALARM
//! section says, and a plain canon run ends as a run through the runtime
//! does. Paths are the programmed ones: straight for lines, threads and
//! rapids (as the runtime moves a rapid), circular for arcs (checked every
//! degree); an ellipse or a parabola is checked at its end point only.
//! Points are the programmed tool point in machine coordinates (the work
//! point plus the workpiece origin, X as a diameter), as #5021 reads them;
//! tool offsets are the runtime's, which checks the slide path every
//! period.

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
    /// Whether the straight path between two machine points (X diameter,
    /// Z) runs through the forbidden part. A box is convex, so a path
    /// between two allowed points can only cross a forbidden inside: the
    /// part of the segment within the open box (Liang–Barsky) is checked
    /// for a length.
    pub fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        if self.forbids(a.0, a.1) || self.forbids(b.0, b.1) {
            return true;
        }
        if self.forbid_outside {
            return false;
        }
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let axes = [
            (a.0, b.0 - a.0, ordered(self.minus.0, self.plus.0)),
            (a.1, b.1 - a.1, ordered(self.minus.1, self.plus.1)),
        ];
        for (p, d, (lo, hi)) in axes {
            if d.abs() < 1e-12 {
                if p <= lo || p >= hi {
                    return false;
                }
                continue;
            }
            let (ta, tb) = ((lo - p) / d, (hi - p) / d);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        // (A path along an edge or through a corner stays allowed.)
        t1 - t0 > 1e-9
    }

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
    /// Where the tool stands (work coordinates): the start of the next
    /// motion event.
    at: Pt,
    feed: Option<Event>,
    fault: Option<NcError>,
}

impl<'a> Guard<'a> {
    /// `at`: the tool's work position when the block begins.
    pub fn new(inner: &'a mut dyn Sink, area: Area, origin: Pt, at: Pt) -> Guard<'a> {
        Guard {
            inner,
            area,
            origin,
            at,
            feed: None,
            fault: None,
        }
    }

    /// Whether the path of motion event `e` from the current point runs
    /// into the forbidden area (its end point included).
    fn refuses(&self, e: &Event, to: Pt) -> bool {
        let machine = |p: Pt| (p.x() + self.origin.x(), p.z + self.origin.z);
        let arc = match *e {
            Event::Arc { dir, cx, cz, .. } | Event::ArcThread { dir, cx, cz, .. } => {
                Some((Pt::new(cx / 2.0, cz), dir))
            }
            Event::Ellipse { .. } | Event::Parabola { .. } => {
                let (x, z) = machine(to);
                return self.area.forbids(x, z);
            }
            _ => None,
        };
        let Some((c, dir)) = arc else {
            return self.area.crossed_by(machine(self.at), machine(to));
        };
        // The arc every degree (or finer), as chords of the circle.
        let (a0, a1) = (self.at.sub(c), to.sub(c));
        let start = libm::atan2(a0.r, a0.z);
        let mut sweep = libm::atan2(a1.r, a1.z) - start;
        let tau = 2.0 * core::f64::consts::PI;
        let ccw = matches!(dir, crate::base::event::Dir::Ccw);
        // G03 turns from +Z towards +X (dialect.md §2.4).
        if ccw && sweep <= 1e-12 {
            sweep += tau;
        } else if !ccw && sweep >= -1e-12 {
            sweep -= tau;
        }
        let radius = |p: Pt| libm::sqrt(p.r * p.r + p.z * p.z);
        let (r0, r1) = (radius(a0), radius(a1));
        let n = (libm::ceil(sweep.abs().to_degrees()) as usize).clamp(1, 360);
        let mut prev = self.at;
        for i in 1..=n {
            let t = i as f64 / n as f64;
            let (s, k) = libm::sincos(start + sweep * t);
            let r = r0 + (r1 - r0) * t;
            let p = if i == n {
                to
            } else {
                Pt::new(c.r + r * s, c.z + r * k)
            };
            if self.area.crossed_by(machine(prev), machine(p)) {
                return true;
            }
            prev = p;
        }
        false
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
            let to = Pt::new(x / 2.0, z);
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
            if self.refuses(&e, to) {
                self.fault = Some(NcError::new(
                    Alarm::StrokeLimit,
                    format!(
                        "the move to machine X{} Z{} runs through the area G22 forbids",
                        crate::base::event::Num(mx),
                        crate::base::event::Num(mz)
                    ),
                ));
                return;
            }
            self.at = to;
        }
        if let Some(f) = self.feed.take() {
            self.inner.emit(f);
        }
        self.inner.emit(e);
    }

    fn origin(&mut self, block: u32) {
        self.inner.origin(block);
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
    fn a_line_through_the_area_stops_before_it() {
        // From X150 Z10 to X-20 Z10: both ends lie outside the box
        // (X −10…100 is the inside; X −20 is beyond it), the line runs
        // straight through it along Z10 (inside Z −20…50).
        let (canon, code) = run(&[
            "G00 X150 Z10",
            "G22 X100. Z50. I-10. K-20.",
            "G98 G01 X-20 F100",
        ]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=150 Z=10"]);
        // Along an edge (Z50, the boundary) the path stays allowed.
        let (_, code) = run(&[
            "G00 X150 Z50",
            "G22 X100. Z50. I-10. K-20.",
            "G98 G01 X-20 F100",
        ]);
        assert_eq!(code, 0);
    }

    #[test]
    fn an_arc_bulging_into_the_area_stops_before_it() {
        // Box X 0…40 (r 0…20), Z −20…−10. The G02 from X60 Z0 to X60 Z-30
        // with R15 has its centre at r 30 − √(15² − 15²) = r 30, Z −15
        // (a half circle): its lowest point is r 15 (X30) at Z −15, inside
        // the box, although both ends (X60) lie outside it.
        let (canon, code) = run(&[
            "G00 X60 Z0",
            "G22 X40. Z-10. I0. K-20.",
            "G98 G02 X60 Z-30 R15 F100",
        ]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=60 Z=0"]);
        // The same arc the other way round (G03) bulges away from it.
        let (_, code) = run(&[
            "G00 X60 Z0",
            "G22 X40. Z-10. I0. K-20.",
            "G98 G03 X60 Z-30 R15 F100",
        ]);
        assert_eq!(code, 0);
    }

    #[test]
    fn crossing_tests_by_hand() {
        let a = area(false);
        // Straight through the inside, both ends outside.
        assert!(a.crossed_by((-20.0, 0.0), (120.0, 0.0)));
        // Past a corner, outside: from X110 Z40 to X90 Z60 the line
        // X + Z = 150 meets X = 100 at Z50, the corner itself, and stays
        // outside elsewhere.
        assert!(!a.crossed_by((110.0, 40.0), (90.0, 60.0)));
        // Cutting the corner off: X + Z = 140 runs inside from X100 Z40
        // to X90 Z50.
        assert!(a.crossed_by((110.0, 30.0), (80.0, 60.0)));
        // Forbidden outside: a line between two inside points stays in.
        assert!(!area(true).crossed_by((0.0, 0.0), (90.0, 40.0)));
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
