//! Tool life management (dialect.md §6.3, §4.9): the table of tool groups
//! that `G10 L3` writes (the machine file's `[[tool_life.group]]` at power
//! on), `Txx99` and `Txx88`, and the clock of "minutes" groups.
//!
//! **Decisions.** A "count" group counts one use at each `Txx99` that
//! selects one of its tools. A "minutes" group counts the cutting time of
//! the feed moves made while its tool is the one selected: the length of
//! each feed event divided by its feed, both taken from the canon the
//! kernel prints (so cycles, corners and profiles are all counted). A
//! per-revolution feed (G99) and a thread lead become mm/min with the
//! spindle speed in force — the G97 rpm, or in G96 the rpm at the mean
//! diameter of the move, clamped as the kernel clamps CSS — and a move made
//! with the spindle stopped counts no time (the runtime raises E7003 for
//! it). Ellipses and parabolas count their chord. Rapids and dwells count
//! nothing. A move of polar or cylindrical interpolation counts its length
//! in the plane (the arc's along the arc) at the programmed feed; the axis
//! outside the plane moving alone counts its own travel.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event, Plane, PlaneMotion, SpindleDir};
use crate::base::machine::Machine;
use crate::base::point::Pt;
use crate::base::words::Word;
use crate::exec::plane::{Kind, PlaneState};
use crate::exec::{Nc, Outcome, Sink};

/// How a group measures life.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LifeUnit {
    Count,
    Minutes,
}

/// One group of the table: its tools (T values, tool × 100 + offset) in
/// the order they are used, and what each has used so far.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    pub number: u32,
    pub life: f64,
    pub unit: LifeUnit,
    pub tools: Vec<u32>,
    pub used: Vec<f64>,
    /// The tool the last `Txx99` selected (index into `tools`).
    pub current: Option<usize>,
}

impl Group {
    pub fn new(number: u32, life: f64, unit: LifeUnit) -> Group {
        Group {
            number,
            life,
            unit,
            tools: Vec::new(),
            used: Vec::new(),
            current: None,
        }
    }

    pub fn add(&mut self, t: u32) {
        self.tools.push(t);
        self.used.push(0.0);
    }

    /// The first tool that is not worn out.
    fn usable(&self) -> Option<usize> {
        (0..self.tools.len()).find(|&i| self.used[i] < self.life)
    }
}

/// The tool-life table and the clock of the minutes groups.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolLife {
    pub groups: Vec<Group>,
    /// The minutes-group tool that feed moves wear now: (group, tool)
    /// indices. A T word other than Txx99/Txx88 ends it.
    pub timed: Option<(usize, usize)>,
    pub clock: Clock,
}

impl ToolLife {
    /// The machine file's table (validated by `Machine::validate`).
    pub fn power_on(m: &Machine) -> ToolLife {
        let mut life = ToolLife::default();
        for g in &m.tool_life.group {
            let unit = if g.unit == "minutes" {
                LifeUnit::Minutes
            } else {
                LifeUnit::Count
            };
            let mut group = Group::new(g.number, g.life, unit);
            for &t in &g.tools {
                group.add(t);
            }
            life.groups.push(group);
        }
        life
    }

    /// Replaces the whole table (`G10 L3`).
    pub fn clear(&mut self) {
        *self = ToolLife::default();
    }

    /// Opens group `number` (a group given again starts afresh).
    pub fn open(&mut self, number: u32, life: f64, unit: LifeUnit) {
        self.groups.retain(|g| g.number != number);
        self.groups.push(Group::new(number, life, unit));
        self.timed = None;
    }

    /// Adds a tool to the group opened last; false when none is open.
    pub fn add_tool(&mut self, t: u32) -> bool {
        match self.groups.last_mut() {
            Some(g) => {
                g.add(t);
                true
            }
            None => false,
        }
    }

    fn has_minutes(&self) -> bool {
        self.groups.iter().any(|g| g.unit == LifeUnit::Minutes)
    }

    /// The group with this number, or E7005.
    fn group(&self, number: u32) -> Result<usize, NcError> {
        match self.groups.iter().position(|g| g.number == number) {
            Some(i) if !self.groups[i].tools.is_empty() => Ok(i),
            _ => fail(
                Alarm::ToolLifeOut,
                format!("tool-life group {number} has no tool (G10 L3 or [[tool_life.group]])"),
            ),
        }
    }
}

fn worn_out(number: u32) -> NcError {
    NcError::new(
        Alarm::ToolLifeOut,
        format!("every tool of tool-life group {number} is worn out"),
    )
}

/// The T word hook of the kernel: `Some` when the T word is a tool-life
/// word (offset 99 or 88) and this module printed its `TOOL`; `None` for
/// an ordinary T word, which also ends the timing of a minutes tool.
pub fn t_word(
    nc: &mut Nc,
    tool: u32,
    offset: u32,
    sink: &mut dyn Sink,
) -> Option<Result<(), NcError>> {
    match offset {
        99 => Some(select(nc, tool, sink)),
        88 => Some(cancel_offset(nc, tool, sink)),
        _ => {
            nc.st.data.life.timed = None;
            None
        }
    }
}

/// `Txx99`: the next usable tool of group xx, with its offset.
fn select(nc: &mut Nc, number: u32, sink: &mut dyn Sink) -> Result<(), NcError> {
    let life = &mut nc.st.data.life;
    let gi = life.group(number)?;
    let g = &mut life.groups[gi];
    let ti = g.usable().ok_or_else(|| worn_out(number))?;
    if g.unit == LifeUnit::Count {
        g.used[ti] += 1.0;
    }
    g.current = Some(ti);
    life.timed = (g.unit == LifeUnit::Minutes).then_some((gi, ti));
    let t = g.tools[ti];
    set_tool(nc, t / 100, t % 100, sink);
    Ok(())
}

/// `Txx88`: group xx's current tool without offset. A group never
/// selected yet takes the tool a `Txx99` would (no use counted).
fn cancel_offset(nc: &mut Nc, number: u32, sink: &mut dyn Sink) -> Result<(), NcError> {
    let life = &nc.st.data.life;
    let g = &life.groups[life.group(number)?];
    let ti = g
        .current
        .or_else(|| g.usable())
        .ok_or_else(|| worn_out(number))?;
    let tool = g.tools[ti] / 100;
    set_tool(nc, tool, 0, sink);
    Ok(())
}

fn set_tool(nc: &mut Nc, tool: u32, offset: u32, sink: &mut dyn Sink) {
    nc.st.tool = tool;
    nc.st.offset = offset;
    sink.emit(Event::Tool { t: tool, d: offset });
}

/// Runs one block through `exec` and charges the cutting time of its feed
/// events to the minutes tool. Only used while the table has a minutes
/// group, so other programs pay nothing for it.
pub fn timed(
    nc: &mut Nc,
    words: &[Word],
    sink: &mut dyn Sink,
    exec: fn(&mut Nc, &[Word], &mut dyn Sink) -> Result<Outcome, NcError>,
) -> Result<Outcome, NcError> {
    if !nc.st.data.life.has_minutes() {
        return exec(nc, words, sink);
    }
    let mut clock = core::mem::take(&mut nc.st.data.life.clock);
    if !clock.synced {
        clock.sync(nc);
    }
    let before = nc.st.data.life.timed;
    let mut timer = Timer {
        inner: sink,
        clock: &mut clock,
        spindle_max: nc.machine.spindle.max_rpm,
        reference: reference_points(&nc.machine),
        plane: nc.st.plane,
    };
    let result = exec(nc, words, &mut timer);
    let life = &mut nc.st.data.life;
    // Moves printed before the block's T word were cut by the tool that
    // was timed when the block began.
    charge(life, before, clock.before_tool);
    charge(life, life.timed, clock.minutes);
    clock.before_tool = 0.0;
    clock.minutes = 0.0;
    clock.tool_seen = false;
    life.clock = clock;
    result
}

fn charge(life: &mut ToolLife, who: Option<(usize, usize)>, minutes: f64) {
    if let Some((g, t)) = who {
        if let Some(used) = life.groups.get_mut(g).and_then(|g| g.used.get_mut(t)) {
            *used += minutes;
        }
    }
}

fn reference_points(m: &Machine) -> [Pt; 4] {
    let r = &m.reference_points;
    [
        Pt::default(),
        Pt::xz(r.second.x, r.second.z),
        Pt::xz(r.third.x, r.third.z),
        Pt::xz(r.fourth.x, r.fourth.z),
    ]
}

/// What the clock needs from the canon between events: where the tool is
/// (machine coordinates), the zero, the feed and the spindle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Clock {
    pub synced: bool,
    pub at: Pt,
    pub origin: Pt,
    pub feed: f64,
    pub per_rev: bool,
    pub speed: f64,
    pub css: bool,
    pub rpm_limit: Option<f64>,
    pub running: bool,
    /// Cutting minutes of the block so far, after its T word.
    pub minutes: f64,
    /// Cutting minutes of the block before its T word.
    pub before_tool: f64,
    pub tool_seen: bool,
}

impl Clock {
    /// Starts from the kernel's state (the first block a minutes group
    /// sees).
    fn sync(&mut self, nc: &Nc) {
        let st = &nc.st;
        let (feed, per_rev) = st.feed_printed.unwrap_or((0.0, st.per_rev()));
        *self = Clock {
            synced: true,
            at: st.machine_pos(),
            origin: st.origin(),
            feed,
            per_rev,
            speed: if st.css_mode() { st.css } else { st.rpm },
            css: st.css_mode(),
            rpm_limit: st.rpm_limit,
            running: st.spindle != SpindleDir::Stop,
            ..Clock::default()
        };
    }

    /// The rpm at diameter `x` (work coordinates), 0 when stopped.
    fn rpm(&self, x: f64, spindle_max: f64) -> f64 {
        if !self.running {
            return 0.0;
        }
        if !self.css {
            return self.speed.min(spindle_max);
        }
        let limit = self.rpm_limit.map_or(spindle_max, |l| l.min(spindle_max));
        if x.abs() < 1e-9 {
            return limit;
        }
        (1000.0 * self.speed / (core::f64::consts::PI * x.abs())).min(limit)
    }
}

/// The sink that watches the canon for the clock.
struct Timer<'a> {
    inner: &'a mut dyn Sink,
    clock: &'a mut Clock,
    spindle_max: f64,
    reference: [Pt; 4],
    /// Polar or cylindrical interpolation, as the block found it and its
    /// plane moves left it.
    plane: Option<PlaneState>,
}

impl Timer<'_> {
    /// A move to `to` (work coordinates): its length and minutes at
    /// `rate` mm/min (0: no time).
    fn cut(&mut self, to: Pt, length: f64, rate: f64) {
        if rate > 0.0 {
            let m = length / rate;
            if self.clock.tool_seen {
                self.clock.minutes += m;
            } else {
                self.clock.before_tool += m;
            }
        }
        self.clock.at = to.add(self.clock.origin);
    }

    /// The feed rate in mm/min of a feed move ending at work point `to`.
    fn feed_rate(&self, to: Pt) -> f64 {
        if !self.clock.per_rev {
            return self.clock.feed;
        }
        let mid = (self.start().x() + to.x()) / 2.0;
        self.clock.feed * self.clock.rpm(mid, self.spindle_max)
    }

    fn thread_rate(&self, to: Pt, lead: f64) -> f64 {
        let mid = (self.start().x() + to.x()) / 2.0;
        lead.abs() * self.clock.rpm(mid, self.spindle_max)
    }

    /// The start of the next move, work coordinates.
    fn start(&self) -> Pt {
        self.clock.at.sub(self.clock.origin)
    }

    fn watch(&mut self, e: &Event) {
        match *e {
            Event::Feed { f, per_rev } => {
                self.clock.feed = f;
                self.clock.per_rev = per_rev;
            }
            Event::Speed { s, css, max } => {
                if let Some(limit) = max {
                    self.clock.rpm_limit = Some(limit);
                }
                self.clock.speed = s;
                self.clock.css = css;
            }
            Event::Spindle(dir) => self.clock.running = dir != SpindleDir::Stop,
            Event::Tool { .. } => self.clock.tool_seen = true,
            Event::Origin { x, z } => {
                // The tool stays put; its work coordinates change.
                self.clock.origin = Pt::xz(x, z);
            }
            Event::Home { n, x, z, .. } => {
                let rp = self.reference[(n.clamp(1, 4) - 1) as usize];
                if x {
                    self.clock.at.r = rp.r;
                }
                if z {
                    self.clock.at.z = rp.z;
                }
            }
            _ => self.watch_move(e),
        }
    }

    /// A move of the ZX plane: its length at its rate.
    fn watch_move(&mut self, e: &Event) {
        let start = self.start();
        match *e {
            Event::Rapid { x, z, .. } => self.cut(Pt::xz(x, z), 0.0, 0.0),
            Event::Line { x, z, .. }
            | Event::Skip { x, z }
            | Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. } => {
                let to = Pt::xz(x, z);
                let rate = self.feed_rate(to);
                self.cut(to, start.dist(to), rate);
            }
            Event::Arc {
                dir, x, z, cx, cz, ..
            } => {
                let to = Pt::xz(x, z);
                let rate = self.feed_rate(to);
                let len = arc_length(start, to, Pt::xz(cx, cz), dir == Dir::Cw);
                self.cut(to, len, rate);
            }
            Event::Thread { x, z, lead, .. } => {
                let to = Pt::xz(x, z);
                let rate = self.thread_rate(to, lead);
                self.cut(to, start.dist(to), rate);
            }
            Event::ArcThread {
                dir,
                x,
                z,
                cx,
                cz,
                lead,
                ..
            } => {
                let to = Pt::xz(x, z);
                let rate = self.thread_rate(to, lead);
                let len = arc_length(start, to, Pt::xz(cx, cz), dir == Dir::Cw);
                self.cut(to, len, rate);
            }
            _ => self.watch_plane(e),
        }
    }

    /// Polar and cylindrical interpolation: the plane's state and moves.
    fn watch_plane(&mut self, e: &Event) {
        let start = self.start();
        match *e {
            Event::PolarOn => {
                let pt = Pt::new(0.0, start.r);
                self.plane = Some(PlaneState {
                    kind: Kind::Polar,
                    pt,
                    tool: pt,
                });
            }
            // C, where the cylinder's plane starts, is not in the canon:
            // the next block takes the kernel's state (G7.1 stands alone).
            Event::Cylinder(_) => self.plane = None,
            Event::PolarOff { x, .. } => {
                self.plane = None;
                self.cut(Pt::new(x / 2.0, start.z), 0.0, 0.0);
            }
            Event::PlaneMove {
                motion, a, b, off, ..
            } => self.plane_move(motion, (a, b), off),
            Event::PlaneAxis {
                plane, rapid, to, ..
            } => {
                let to = match plane {
                    Plane::Polar => Pt::new(start.r, to),
                    Plane::Cylinder => Pt::new(to / 2.0, start.z),
                };
                let rate = if rapid { 0.0 } else { self.feed_rate(to) };
                self.cut(to, start.dist(to), rate);
            }
            _ => {}
        }
    }

    /// A move in the plane: its length there (with the axis outside the
    /// plane moving along, `off`, the length of the line in space), at the
    /// programmed feed; the joints follow it.
    fn plane_move(&mut self, motion: PlaneMotion, (a, b): (f64, f64), off: Option<f64>) {
        let start = self.start();
        let Some(mut st) = self.plane else {
            return;
        };
        let to = st.point(a, b);
        let (length, rate) = match motion {
            PlaneMotion::Rapid => (0.0, 0.0),
            PlaneMotion::Line => (st.pt.dist(to), self.feed_rate(start)),
            PlaneMotion::Arc { dir, ca, cb } => {
                let centre = st.point(ca, cb);
                let cw = dir == Dir::Cw;
                (arc_length(st.pt, to, centre, cw), self.feed_rate(start))
            }
            PlaneMotion::Ellipse { .. } | PlaneMotion::Parabola { .. } => {
                let curve = crate::exec::plane::printed_curve(st.pt, to, motion);
                let length = curve.map_or(0.0, |c| c.length(0.0, 1.0));
                (length, self.feed_rate(start))
            }
        };
        st.pt = to;
        self.plane = Some(st);
        let mut at = st.joints(to, start);
        let mut length = length;
        if let Some(v) = off {
            let moved = match st.kind {
                Kind::Polar => core::mem::replace(&mut at.z, v) - v,
                Kind::Cylinder(_) => core::mem::replace(&mut at.r, v / 2.0) - v / 2.0,
            };
            length = libm::hypot(length, moved);
        }
        self.cut(at, length, rate);
    }
}

impl Sink for Timer<'_> {
    fn emit(&mut self, e: Event) {
        self.watch(&e);
        self.inner.emit(e);
    }

    fn origin(&mut self, block: u32) {
        self.inner.origin(block);
    }
}

/// The length of an arc in the ZX view (+Z right, +r up; G02 clockwise);
/// end = start is a full circle.
pub fn arc_length(from: Pt, to: Pt, centre: Pt, cw: bool) -> f64 {
    crate::plan::elem::length(&crate::base::geom::Element::Arc {
        from,
        to,
        centre,
        cw,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exec::cycles::testing::Lathe;

    fn lathe_with(toml: &str) -> Lathe {
        let m = Machine::from_toml(toml).unwrap_or_else(|e| panic!("{e}"));
        Lathe { nc: Nc::new(m) }
    }

    const TWO_USES: &str =
        "[[tool_life.group]]\nnumber = 1\nlife = 2\nunit = \"count\"\ntools = [101, 202]\n";

    #[test]
    fn a_count_group_uses_each_tool_life_times() {
        let mut m = lathe_with(TWO_USES);
        assert_eq!(m.run("T0199"), ["TOOL T=1 D=1"]);
        assert_eq!(m.run("T0199"), ["TOOL T=1 D=1"]);
        // Tool 1 has had its two uses: the group goes on with T0202.
        assert_eq!(m.run("T0199"), ["TOOL T=2 D=2"]);
        assert_eq!(m.run("T0188"), ["TOOL T=2 D=0"]);
        assert_eq!(m.run("T0199"), ["TOOL T=2 D=2"]);
        assert_eq!(m.try_run("T0199"), Err(7005));
    }

    #[test]
    fn an_unknown_or_empty_group_is_e7005() {
        let mut m = lathe_with(TWO_USES);
        assert_eq!(m.try_run("T0599"), Err(7005));
        assert_eq!(m.try_run("T0588"), Err(7005));
        m.run("G10 L3");
        m.run("P4 L10");
        m.run("G11");
        assert_eq!(m.try_run("T0499"), Err(7005));
        // G10 L3 replaced the machine file's group 1.
        assert_eq!(m.try_run("T0199"), Err(7005));
    }

    #[test]
    fn txx88_before_any_txx99_takes_the_next_tool_without_a_use() {
        let mut m = lathe_with(TWO_USES);
        assert_eq!(m.run("T0188"), ["TOOL T=1 D=0"]);
        assert_eq!(m.nc.st.data.life.groups[0].used, [0.0, 0.0]);
    }

    fn minutes_lathe() -> Lathe {
        let mut m = Lathe::new();
        for b in ["G10 L3", "P1 L1 Q2", "T0101", "T0202", "G11"] {
            assert!(m.run(b).is_empty());
        }
        m
    }

    fn used(m: &Lathe) -> Vec<f64> {
        m.nc.st.data.life.groups[0].used.clone()
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn a_minutes_group_counts_cutting_time() {
        let mut m = minutes_lathe();
        assert_eq!(m.run("T0199"), ["TOOL T=1 D=1"]);
        // A rapid counts nothing; 60 mm at F120 mm/min is 0.5 min.
        m.run("G00 X20 Z0");
        m.run("G01 W-60 F120");
        assert!(close(&used(&m), &[0.5, 0.0]), "{:?}", used(&m));
        // Per revolution: 0.2 mm/rev at 500 rpm is 100 mm/min; 50 mm is
        // 0.5 min, and tool 1 (life 1 min) is worn out.
        m.run("M03 S500");
        m.run("G99 G01 W-50 F0.2");
        assert!(close(&used(&m), &[1.0, 0.0]), "{:?}", used(&m));
        assert_eq!(m.run("T0199"), ["TOOL T=2 D=2"]);
        // A semicircle of radius 10 (length 10π) at 0.2 × 500 mm/min.
        m.run("G02 W-20 R10");
        let pi = core::f64::consts::PI;
        assert!(
            close(&used(&m), &[1.0, 10.0 * pi / 100.0]),
            "{:?}",
            used(&m)
        );
    }

    #[test]
    fn timing_stops_at_another_tool_and_at_a_stopped_spindle() {
        let mut m = minutes_lathe();
        m.run("T0199");
        m.run("T0303");
        m.run("G01 W-60 F120");
        assert!(close(&used(&m), &[0.0, 0.0]));
        // The T0199 of a block times the block's own move: 12 mm at F120.
        m.run("T0199 G01 W-12");
        assert!(close(&used(&m), &[0.1, 0.0]), "{:?}", used(&m));
        // G99 with the spindle stopped: no time (the runtime's E7003).
        m.run("G99 G01 W-10 F0.2");
        assert!(close(&used(&m), &[0.1, 0.0]), "{:?}", used(&m));
    }

    /// A minutes group (tool 1: 1 min) on a lathe with a C axis.
    fn c_axis_minutes() -> Lathe {
        let mut m = lathe_with("[axes.c]\nenabled = true\n");
        for b in ["G10 L3", "P1 L1 Q2", "T0101", "G11", "T0199", "G98"] {
            m.run(b);
        }
        m
    }

    #[test]
    fn polar_interpolation_counts_the_path_in_its_plane() {
        let mut m = c_axis_minutes();
        let pi = core::f64::consts::PI;
        // From X20 (10 mm from the centre), C0: 10 mm along C at F100.
        for b in ["G00 X20 Z0 C0", "G12.1", "G01 X20 C10 F100"] {
            m.run(b);
        }
        assert!(close(&used(&m), &[0.1]), "{:?}", used(&m));
        // A half circle of radius 10 about X0 C10: 10π mm.
        m.run("G03 X-20 C10 R10");
        assert!(close(&used(&m), &[0.1 + 0.1 * pi]), "{:?}", used(&m));
        // Z alone: 5 mm; a rapid in the plane: nothing.
        m.run("G01 Z-5");
        m.run("G00 X20 C0");
        assert!(close(&used(&m), &[0.15 + 0.1 * pi]), "{:?}", used(&m));
        // After G13.1 the tool is at X20 (the plane's last point): a feed
        // from there along Z counts its 10 mm.
        m.run("G13.1");
        m.run("G01 W-10");
        assert!(close(&used(&m), &[0.25 + 0.1 * pi]), "{:?}", used(&m));
        // A line that takes Z along counts its length in space: from
        // (x 10, c 0) at Z−15 to (x 10, c 12) at Z−10, 13 mm (5-12-13).
        m.run("G12.1");
        m.run("G01 C12 Z-10");
        assert!(close(&used(&m), &[0.38 + 0.1 * pi]), "{:?}", used(&m));
        m.run("G13.1");
        // (Z−10 after it: W−10 from there to Z−20 is 10 mm more.)
        m.run("G01 W-10");
        assert!(close(&used(&m), &[0.48 + 0.1 * pi]), "{:?}", used(&m));
    }

    #[test]
    fn cylindrical_interpolation_counts_the_developed_path() {
        let mut m = c_axis_minutes();
        // X40 → X36 alone: 2 mm at F20.
        for b in ["G00 X40 Z0 C0", "G7.1 C20.", "G01 X36 F20"] {
            m.run(b);
        }
        assert!(close(&used(&m), &[0.1]), "{:?}", used(&m));
        // 10 mm along Z and 90° on the radius 20 (10π mm) at F200.
        m.run("G01 Z-10 C90 F200");
        let along = libm::hypot(10.0, 10.0 * core::f64::consts::PI);
        assert!(close(&used(&m), &[0.1 + along / 200.0]), "{:?}", used(&m));
        // The joints followed: Z is at −10, so W−5 after G7.1 C0 is 5 mm.
        m.run("G7.1 C0");
        m.run("G01 W-5");
        let want = 0.1 + along / 200.0 + 5.0 / 200.0;
        assert!(close(&used(&m), &[want]), "{:?}", used(&m));
    }

    #[test]
    fn arc_lengths_follow_the_direction() {
        // The shaft example's quarter: X50 Z-30 → X60 Z-35, centre X60 Z-30.
        let (a, b, c) = (
            Pt::xz(50.0, -30.0),
            Pt::xz(60.0, -35.0),
            Pt::xz(60.0, -30.0),
        );
        let quarter = 5.0 * core::f64::consts::FRAC_PI_2;
        assert!((arc_length(a, b, c, true) - quarter).abs() < 1e-9);
        assert!((arc_length(a, b, c, false) - 3.0 * quarter).abs() < 1e-9);
        // End = start: a full circle.
        let full = arc_length(a, a, c, true);
        assert!((full - 10.0 * core::f64::consts::PI).abs() < 1e-9);
    }
}
