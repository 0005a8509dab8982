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
//!
//! The same guard checks the soft limits (travel.rs), where the slide
//! point counts, tool offset included. It follows the tool as printed,
//! from block to block: a corner or a compensated element prints a block
//! late, so the programmed point is not where the next event starts.

use crate::base::gcode::Stroke;
use alloc::format;

use crate::base::error::{Alarm, NcError};
use crate::base::event::{Event, Num};
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::state::State;
use crate::exec::travel::Slide;
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
    // Blocks ran unguarded before: where the tool was printed is not known.
    nc.st.printed = None;
    if code != Stroke::On || !m.enabled {
        nc.st.stroke2 = None;
        return;
    }
    let word = |letter: u8, default: f64| nc.len_of(p, letter).unwrap_or(default);
    // (X and I are X values, kept as diameters as the machine file's.)
    let x_word = |letter: u8, default: f64| {
        nc.len_of(p, letter)
            .map_or(default, |v| nc.machine.diameter(v))
    };
    let area = Area {
        plus: (x_word(b'X', m.plus.x), word(b'Z', m.plus.z)),
        minus: (x_word(b'I', m.minus.x), word(b'K', m.minus.z)),
        forbid_outside: m.forbid_outside,
    };
    nc.st.stroke2 = Some(area);
}

/// Points along the path of a motion event, its end last: an arc's every
/// degree or finer (chords of the circle); any other move's end alone.
struct PathPoints {
    centre: Pt,
    start: f64,
    sweep: f64,
    r0: f64,
    r1: f64,
    n: usize,
    i: usize,
    to: Pt,
}

impl PathPoints {
    fn of(e: &Event, from: Pt, to: Pt) -> PathPoints {
        let mut path = PathPoints {
            centre: Pt::ZERO,
            start: 0.0,
            sweep: 0.0,
            r0: 0.0,
            r1: 0.0,
            n: 1,
            i: 0,
            to,
        };
        let (Event::Arc { dir, cx, cz, .. } | Event::ArcThread { dir, cx, cz, .. }) = *e else {
            return path;
        };
        let c = Pt::new(cx / 2.0, cz);
        let (a0, a1) = (from.sub(c), to.sub(c));
        let start = libm::atan2(a0.r, a0.z);
        let mut sweep = libm::atan2(a1.r, a1.z) - start;
        let tau = 2.0 * core::f64::consts::PI;
        // G03 turns from +Z towards +X (dialect.md §2.4).
        let ccw = matches!(dir, crate::base::event::Dir::Ccw);
        if ccw && sweep <= 1e-12 {
            sweep += tau;
        } else if !ccw && sweep >= -1e-12 {
            sweep -= tau;
        }
        let radius = |p: Pt| libm::sqrt(p.r * p.r + p.z * p.z);
        path.centre = c;
        (path.start, path.sweep) = (start, sweep);
        (path.r0, path.r1) = (radius(a0), radius(a1));
        path.n = (libm::ceil(sweep.abs().to_degrees()) as usize).clamp(1, 360);
        path
    }
}

impl Iterator for PathPoints {
    type Item = Pt;

    fn next(&mut self) -> Option<Pt> {
        if self.i >= self.n {
            return None;
        }
        self.i += 1;
        if self.i == self.n {
            return Some(self.to);
        }
        let t = self.i as f64 / self.n as f64;
        let (s, k) = libm::sincos(self.start + self.sweep * t);
        let r = self.r0 + (self.r1 - self.r0) * t;
        Some(Pt::new(self.centre.r + r * s, self.centre.z + r * k))
    }
}

/// A sink that passes events on until one would take the tool where it
/// may not go (the G22 area, or past the soft limits: travel.rs); from
/// then on it drops them and keeps the alarm. A `FEED` waits for the
/// event after it, so the feed of a refused move is not printed either.
pub struct Guard<'a> {
    inner: &'a mut dyn Sink,
    /// The area G22 forbids, while it is in force.
    area: Option<Area>,
    /// The soft limits, on a machine with them.
    slide: Option<Slide>,
    origin: Pt,
    /// Reference points 1–4, machine coordinates.
    refs: [Pt; 4],
    /// Where the tool stands (work coordinates): the start of the next
    /// motion event; not known after leaving a cylinder plane.
    at: Pt,
    at_known: bool,
    feed: Option<Event>,
    fault: Option<NcError>,
}

impl<'a> Guard<'a> {
    /// The checks in force as the block about to run finds them; the
    /// tool where the last block left it.
    pub fn new(inner: &'a mut dyn Sink, nc: &Nc) -> Guard<'a> {
        Guard {
            inner,
            area: nc.st.stroke2,
            slide: Slide::of(nc),
            origin: nc.st.origin(),
            refs: [1, 2, 3, 4].map(|n| nc.reference_point(n)),
            at: nc.st.printed.unwrap_or(nc.st.pos),
            at_known: true,
            feed: None,
            fault: None,
        }
    }

    /// The end of the block: the alarm, or the events still held back.
    /// What the next block's guard starts from goes back to the state.
    pub fn finish(mut self, st: &mut State) -> Option<NcError> {
        if self.fault.is_none() {
            if let Some(f) = self.feed.take() {
                self.inner.emit(f);
            }
        }
        st.printed = self.at_known.then_some(self.at);
        if let Some(s) = &self.slide {
            st.slide_off = s.offset();
        }
        self.fault
    }

    fn machine(&self, p: Pt) -> Pt {
        p.add(self.origin)
    }

    /// E7002 if event `e` takes the tool where it may not go; else the
    /// guard follows the tool (and the slide) to where it leaves them.
    fn check(&mut self, e: &Event) -> Result<(), NcError> {
        match *e {
            Event::Tool { d, .. } => {
                let m = self.machine(self.at);
                if let Some(s) = &mut self.slide {
                    s.tool(d);
                    s.check(m, "the tool's offset")?;
                }
            }
            Event::Home { n, x, z, .. } => self.home(n, x, z)?,
            Event::Origin { x, z } => {
                // The tool stays put; its work coordinates change.
                let m = self.machine(self.at);
                self.origin = Pt::xz(x, z);
                self.at = m.sub(self.origin);
            }
            Event::PolarOff { x, .. } => self.at.r = x / 2.0,
            // The plane's moves print no work point to follow.
            Event::Cylinder(None) => self.at_known = false,
            _ => {
                if let Some((x, z)) = e.end() {
                    let to = Pt::xz(x, z);
                    self.check_move(e, to)?;
                    self.at = to;
                }
            }
        }
        Ok(())
    }

    /// A motion event from the current point to `to`.
    fn check_move(&self, e: &Event, to: Pt) -> Result<(), NcError> {
        let end = self.machine(to);
        if let Some(area) = &self.area {
            let (x, z) = (Num(end.x()), Num(end.z));
            if area.forbids(end.x(), end.z) {
                let msg = format!("the move ends at machine X{x} Z{z}, in the area G22 forbids");
                return Err(NcError::new(Alarm::StrokeLimit, msg));
            }
            if self.crosses(area, e, to) {
                let msg =
                    format!("the move to machine X{x} Z{z} runs through the area G22 forbids");
                return Err(NcError::new(Alarm::StrokeLimit, msg));
            }
        }
        if let Some(s) = &self.slide {
            // The travel is a box: a straight move between two points
            // inside it stays inside, an arc may bulge out.
            for p in PathPoints::of(e, self.at, to) {
                s.check(self.machine(p), "the move")?;
            }
        }
        Ok(())
    }

    /// Whether the path of motion event `e` from the current point runs
    /// through the forbidden area. An ellipse or a parabola is checked at
    /// its end point only.
    fn crosses(&self, area: &Area, e: &Event, to: Pt) -> bool {
        if matches!(e, Event::Ellipse { .. } | Event::Parabola { .. }) {
            return false;
        }
        let xz = |p: Pt| {
            let m = self.machine(p);
            (m.x(), m.z)
        };
        let mut prev = self.at;
        PathPoints::of(e, self.at, to).any(|p| {
            let crossed = area.crossed_by(xz(prev), xz(p));
            prev = p;
            crossed
        })
    }

    /// G28/G30: the named axes go to reference point `n` and the tool
    /// offset is off (the kernel's position, as the runtime's).
    fn home(&mut self, n: u32, x: bool, z: bool) -> Result<(), NcError> {
        let rp = self.refs[(n as usize).clamp(1, 4) - 1];
        let home = |p: Pt| Pt::new(if x { rp.r } else { p.r }, if z { rp.z } else { p.z });
        let before = self.machine(self.at);
        if let Some(s) = &mut self.slide {
            // An axis that stays keeps its slide where it stood.
            let slide = home(before.add(s.offset()));
            s.home();
            s.check(slide, "the return to the reference point")?;
        }
        self.at = home(before).sub(self.origin);
        Ok(())
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
        if let Err(fault) = self.check(&e) {
            self.fault = Some(fault);
            return;
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
        run_on(&mut Lathe::new(), blocks)
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

    /// The reference machine (travel X −260…+2 as a diameter, Z −510…+2;
    /// work zero = machine zero) with soft limits, and offset 1 of
    /// X−10 Z−10 (geometry −9.8/−10.3 plus wear −0.2/+0.3).
    fn soft_limited() -> Lathe {
        let mut machine = crate::base::machine::Machine::reference();
        machine.axes.x.soft_limits = true;
        machine.axes.z.soft_limits = true;
        let mut nc = crate::exec::Nc::new(machine);
        nc.st.geom[0] = [-9.8, -10.3, 0.0];
        nc.st.wear[0] = [-0.2, 0.3, 0.0, 0.0];
        Lathe { nc }
    }

    /// `run` on lathe `m`.
    fn run_on(m: &mut Lathe, blocks: &[&str]) -> (Vec<alloc::string::String>, u16) {
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
    fn a_move_past_the_travel_stops_before_its_events() {
        let mut m = soft_limited();
        let (canon, code) = run_on(&mut m, &["G00 X-50 Z0", "G98 G01 Z-600 F100", "G00 X-100"]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=-50 Z=0"]);
        // Up to the end of travel itself is allowed.
        let mut m = soft_limited();
        let (_, code) = run_on(&mut m, &["G00 X-260 Z2", "G98 G01 Z-510 F100"]);
        assert_eq!(code, 0);
    }

    #[test]
    fn an_arc_bulging_past_the_travel_stops_before_it() {
        // From X0 Z-10 to X0 Z-30 with R10: the centre is r 0, Z−20. G03
        // turns from +Z towards +X, so from Z−10 (angle 0) to Z−30 (180°)
        // it passes r 10 (X20) at Z−20, past X's + end (2). G02 passes
        // X−20 instead, inside the travel.
        let mut m = soft_limited();
        let (canon, code) = run_on(&mut m, &["G00 X0 Z-10", "G98 G03 X0 Z-30 R10 F100"]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=0 Z=-10"]);
        let mut m = soft_limited();
        let (_, code) = run_on(&mut m, &["G00 X0 Z-10", "G98 G02 X0 Z-30 R10 F100"]);
        assert_eq!(code, 0);
    }

    #[test]
    fn the_slide_carries_the_tool_offset_until_a_return() {
        // With offset 1 (X−10 Z−10) the slide stands 10 below the
        // programmed X (a diameter) and Z: X12 puts it at X2, the end of
        // travel; Z12 at Z2.
        let mut m = soft_limited();
        let (canon, code) = run_on(&mut m, &["T0101", "G00 X12 Z12", "G28 U0 W0", "G00 X12"]);
        // G28 cancels the offset: X12 is then the slide's X12, past +2.
        assert_eq!(code, 7002);
        assert_eq!(
            canon,
            ["TOOL T=1 D=1", "RAPID X=12 Z=12", "HOME N=1 AXES=XZ"]
        );
    }

    #[test]
    fn an_offset_that_takes_the_slide_past_the_travel_is_refused() {
        // At machine zero, offset 1 moves the slide by −10 −10: inside.
        // Standing at X−255 (diameter) it would take X to −265, past −260.
        let mut m = soft_limited();
        let (canon, code) = run_on(&mut m, &["T0101", "T0100"]);
        assert_eq!((canon.len(), code), (2, 0));
        let (canon, code) = run_on(&mut m, &["G00 X-255", "T0101"]);
        assert_eq!(code, 7002);
        assert_eq!(canon, ["RAPID X=-255 Z=0"]);
    }
}
