//! `gbcc -E`: the program as plain G-code after macros, subprograms and
//! cycles are resolved — what the machine is really told to do, block by
//! block, with absolute coordinates and the source block as a comment.

use nc::event::Num;
use nc::event::{Dir, Plane, PlaneMotion, SpindleDir, StopKind};
use nc::Event;
use std::collections::HashMap;
use std::fmt::Write;

/// The comment of a run-time alarm that no G-code raises.
const NOT_WRITTEN: &str =
    "the run stops here; an alarm that is not a #3000 one is not written as G-code";

/// Turns canon events into G-code text.
pub struct Expand {
    pub out: String,
    /// Source line → its sequence number (for the comment).
    seqs: HashMap<u32, u32>,
    /// The source line of the block being printed.
    line: u32,
    last_line: u32,
    /// Whether its words were computed as it ran (the compiler did not
    /// know them).
    dynamic: bool,
    /// (X, Z) of the last point as printed, for arc centres relative to
    /// the start: the end of the last printed move, not the kernel's
    /// position, which runs ahead of the printed moves under tool nose
    /// radius compensation.
    at: (f64, f64),
    /// Take `at` from the kernel at the next block: at the start, and
    /// after a return to a reference point (whose machine position the
    /// events do not carry).
    resync: bool,
    /// The work zero in machine coordinates (X a diameter), to print a
    /// moved zero as the G50 that moves it there.
    origin: (f64, f64),
    /// An M29 was printed and no move since: a block whose events are
    /// one rigid-tapping hole is written as its G84/G88 block, as no
    /// move may come between the M29 and it.
    rigid: bool,
    /// Every number gets a decimal point (the machine reads one without
    /// as increments).
    point: bool,
    feed: Option<(f64, bool)>,
    /// The C angle of the last `C=` (the start of a G7.1 plane).
    c_now: f64,
    /// In a polar or cylinder plane: the last plane point as printed
    /// (polar X C, cylinder Z C), and the cylinder's radius.
    plane_at: (f64, f64),
    radius: f64,
}

impl Expand {
    /// `origin` is the work zero (machine coordinates, X a diameter) the
    /// run starts with; `point`, that every number is written with a
    /// decimal point (on a machine that reads one without in increments).
    pub fn new(seqs: HashMap<u32, u32>, origin: (f64, f64), point: bool) -> Expand {
        Expand {
            out: String::new(),
            seqs,
            line: 0,
            last_line: 0,
            dynamic: false,
            at: (0.0, 0.0),
            resync: true,
            origin,
            point,
            rigid: false,
            feed: None,
            c_now: 0.0,
            plane_at: (0.0, 0.0),
            radius: 0.0,
        }
    }

    fn origin_comment(&mut self) -> String {
        if self.line == self.last_line {
            return String::new();
        }
        self.last_line = self.line;
        let dynamic = if self.dynamic { ", DYNAMIC" } else { "" };
        match self.seqs.get(&self.line) {
            Some(n) => format!(" (N{n}, LINE {}{dynamic})", self.line),
            None => format!(" (LINE {}{dynamic})", self.line),
        }
    }

    fn block(&mut self, text: String) {
        let note = self.origin_comment();
        if text.starts_with('#') {
            // A comment on a #3000/#3006 line is its message: the source
            // line goes on a line of its own before it.
            if !note.is_empty() {
                let _ = writeln!(self.out, "{}", note.trim_start());
            }
            let _ = writeln!(self.out, "{text}");
            return;
        }
        let _ = writeln!(self.out, "{text}{note}");
    }

    fn mode(&mut self, f: f64, per_rev: bool) -> String {
        let mut s = String::new();
        if self.feed.map(|(_, r)| r) != Some(per_rev) {
            s.push_str(if per_rev { "G99 " } else { "G98 " });
        }
        self.feed = Some((f, per_rev));
        s
    }
}

fn n(v: f64) -> Num {
    Num(v)
}

impl Expand {
    /// Prints the events of one block that ran at source `line`, the tool
    /// starting at (`x`, `z`); `dynamic`: its words were computed as it
    /// ran.
    pub fn block_events(&mut self, events: &[Event], line: u32, dynamic: bool, start: (f64, f64)) {
        self.line = line;
        self.dynamic = dynamic;
        if std::mem::take(&mut self.resync) {
            self.at = start;
        }
        if self.rigid {
            if let Some(tap) = rigid_tap(events, self.at) {
                self.at = tap.s0;
                let text = self.tap_block(&tap);
                self.block(text);
                return;
            }
        }
        for e in events {
            self.event(e);
        }
    }

    fn event(&mut self, e: &Event) {
        match e {
            Event::M(29) => self.rigid = true,
            // A move that is not a tapping cycle ends rigid tapping
            // (cycles.md §22), in the program and in its expansion.
            e if end_point(e).is_some() => self.rigid = false,
            _ => {}
        }
        if let Event::Rapid { c: Some(c), .. } | Event::Line { c: Some(c), .. } = e {
            self.c_now = *c;
        }
        let text = match e {
            Event::PolarOn => {
                self.plane_at = (self.at.0, 0.0);
                "G12.1".into()
            }
            Event::PolarOff { x, c } => {
                self.at.0 = *x;
                self.c_now = *c;
                "G13.1".into()
            }
            Event::Cylinder(Some(r)) => {
                self.radius = *r;
                self.plane_at = (self.at.1, self.c_now);
                format!("G7.1 C{}", n(*r))
            }
            Event::Cylinder(None) => "G7.1 C0".into(),
            Event::PlaneMove {
                plane,
                motion,
                a,
                b,
                off,
            } => self.plane_move(*plane, *motion, (*a, *b), *off),
            Event::PlaneAxis {
                plane, rapid, to, ..
            } => {
                let g = if *rapid { "G00" } else { "G01" };
                match plane {
                    Plane::Polar => {
                        self.at.1 = *to;
                        format!("{g} Z{}", self.w(*to))
                    }
                    Plane::Cylinder => {
                        self.at.0 = *to;
                        format!("{g} X{}", self.w(*to))
                    }
                }
            }
            Event::Rapid { x, z, c } => {
                format!("G00 X{} Z{}{}", self.w(*x), self.w(*z), self.c_word(*c))
            }
            Event::Line { x, z, c } => {
                format!("G01 X{} Z{}{}", self.w(*x), self.w(*z), self.c_word(*c))
            }
            Event::Arc { dir, x, z, cx, cz } => {
                let g = if *dir == Dir::Cw { "G02" } else { "G03" };
                format!(
                    "{g} X{} Z{}{}",
                    self.w(*x),
                    self.w(*z),
                    self.centre(*cx, *cz)
                )
            }
            Event::Ellipse { dir, x, z, a, b, q } => format!(
                "{} X{} Z{}{}",
                conic_code(true, *dir),
                self.w(*x),
                self.w(*z),
                self.ellipse_words(*a, *b, *q)
            ),
            Event::Parabola { dir, x, z, p, q } => format!(
                "{} X{} Z{}{}",
                conic_code(false, *dir),
                self.w(*x),
                self.w(*z),
                parabola_words(*p, *q)
            ),
            // A thread's C= is the angle C holds (a G32 cannot turn C).
            Event::Thread {
                x,
                z,
                lead,
                dlead,
                q,
                ..
            } => {
                let mut s = match dlead {
                    Some(d) => format!(
                        "G34 X{} Z{} F{} R{}",
                        self.w(*x),
                        self.w(*z),
                        self.w(*lead),
                        self.w(*d)
                    ),
                    None => format!("G32 X{} Z{} F{}", self.w(*x), self.w(*z), self.w(*lead)),
                };
                s.push_str(&q_word(*q));
                s
            }
            Event::ArcThread {
                dir,
                x,
                z,
                cx,
                cz,
                lead,
                q,
            } => {
                let g = if *dir == Dir::Cw { "G32.2" } else { "G32.3" };
                let r = self.radius_word(*dir, (*x, *z), (*cx, *cz));
                format!(
                    "{g} X{} Z{} R{} F{}{}",
                    self.w(*x),
                    self.w(*z),
                    self.w(r),
                    self.w(*lead),
                    q_word(*q)
                )
            }
            Event::Dwell { s } => format!("G04 X{}", self.w(*s)),
            Event::Feed { f, per_rev } => {
                let m = self.mode(*f, *per_rev);
                format!("{m}F{}", self.w(*f))
            }
            Event::Speed {
                s,
                css,
                max: Some(m),
            } => format!(
                "G50 S{} ({} S{})",
                n(*m),
                if *css { "G96" } else { "G97" },
                n(*s)
            ),
            Event::Speed { s, css, max: None } => {
                format!("{} S{}", if *css { "G96" } else { "G97" }, n(*s))
            }
            Event::Spindle(d) => match d {
                SpindleDir::Cw => "M03".into(),
                SpindleDir::Ccw => "M04".into(),
                SpindleDir::Stop => "M05".into(),
            },
            Event::Tool { t, d } => format!("T{t:02}{d:02}"),
            Event::M(code) => format!("M{code:02}"),
            Event::Origin { x, z } => self.zero_moved(*x, *z),
            Event::Home { n: p, x, z, c } => {
                // From the point it stands at, so that the intermediate
                // leg has no length and prints nothing (cycles.md §14).
                self.resync = true;
                let g = if *p == 1 {
                    "G28".to_string()
                } else {
                    format!("G30 P{p}")
                };
                let axes: String = [(*x, " U0"), (*z, " W0"), (*c, " H0")]
                    .iter()
                    .filter(|(on, _)| *on)
                    .map(|(_, word)| *word)
                    .collect();
                format!("{g}{axes}")
            }
            Event::Stop(k) => match k {
                StopKind::M00 => "M00".into(),
                StopKind::M01 => "M01".into(),
                StopKind::M02 => "M02".into(),
                StopKind::M30 => "M30".into(),
                StopKind::M99 => "M99".into(),
            },
            Event::Skip { x, z } => format!("G31 X{} Z{}", n(*x), n(*z)),
            Event::Message { number, text } => format!("#3006={number} ({})", comment(text)),
            Event::Alarm { code, msg } => alarm(*code, msg),
            other => format!("({})", comment(&other.to_string())),
        };
        if let Some((x, z)) = end_point(e) {
            self.at = (x, z);
        }
        self.block(text);
    }
}

impl Expand {
    /// A rigid-tapping hole as its cycle block: G84 along Z, G88 along X.
    fn tap_block(&self, tap: &Tap) -> String {
        let (x, z) = (self.w(tap.s1.0), self.w(tap.s1.1));
        let mut s = if tap.s1.0 == tap.s0.0 {
            format!("G84 X{x} Z{z}")
        } else {
            format!("G88 Z{z} X{x}")
        };
        let lead = if tap.left { -tap.lead } else { tap.lead };
        let _ = write!(s, " F{}", self.w(lead));
        if let Some(d) = tap.dwell {
            let _ = write!(s, " P{}", (d * 1000.0).round());
        }
        if let Some(m) = tap.m {
            let _ = write!(s, " M{m}");
        }
        s
    }

    /// An ellipse's A, B (lengths) and Q (0.001°, as the block reads it).
    fn ellipse_words(&self, a: f64, b: f64, q: f64) -> String {
        format!(" A{} B{}{}", self.w(a), self.w(b), q_word(Some(q)))
    }

    /// A value of a dimension word, every digit of it (the shortest text
    /// that reads back as the same `f64`), with a decimal point on a
    /// machine that reads a number without one in increments.
    fn w(&self, v: f64) -> String {
        let v = if v == 0.0 { 0.0 } else { v }; // no "-0"
        let mut s = v.to_string();
        if self.point && !s.contains('.') {
            s.push('.');
        }
        s
    }

    /// The C word of a move on a machine with a C axis.
    fn c_word(&self, c: Option<f64>) -> String {
        c.map_or(String::new(), |c| format!(" C{}", self.w(c)))
    }

    /// The I/K words of an arc centred at (`cx`, `cz`) from the last point
    /// as printed (I a radius), so that the centre read back is the
    /// centre that ran.
    fn centre(&self, cx: f64, cz: f64) -> String {
        let (i, k) = ((cx - self.at.0) / 2.0, cz - self.at.1);
        format!(" I{} K{}", self.w(i), self.w(k))
    }

    /// The R word of an arc from the last point to `end` about `centre`
    /// (X diameters): its radius, negative beyond a half circle. An arc
    /// thread is written with R, as the G32.2 read back takes its I as
    /// the source of this program's arcs do not.
    fn radius_word(&self, dir: Dir, end: (f64, f64), centre: (f64, f64)) -> f64 {
        // (Z, radius) from the centre: Z across, X up, as a front lathe
        // is seen, where G02 turns clockwise.
        let u0 = (self.at.1 - centre.1, (self.at.0 - centre.0) / 2.0);
        let u1 = (end.1 - centre.1, (end.0 - centre.0) / 2.0);
        signed_radius(dir, u0, u1)
    }

    /// A work zero moved to (`x`, `z`) (machine coordinates), whatever
    /// moved it (G50, G52, G54..G59, a work-offset variable), as the G50
    /// that gives the point the tool stands at its coordinates from there.
    fn zero_moved(&mut self, x: f64, z: f64) -> String {
        let machine = (self.at.0 + self.origin.0, self.at.1 + self.origin.1);
        self.origin = (x, z);
        self.at = (machine.0 - x, machine.1 - z);
        format!("G50 X{} Z{}", self.w(self.at.0), self.w(self.at.1))
    }
}

impl Expand {
    /// A move of polar (`X C`) or cylindrical (`Z C`) interpolation; a
    /// polar arc's centre as I/J from its start, a cylinder's as R
    /// (negative beyond a half circle), the only form G7.1 takes.
    fn plane_move(
        &mut self,
        plane: Plane,
        motion: PlaneMotion,
        (a, b): (f64, f64),
        off: Option<f64>,
    ) -> String {
        let first = if plane == Plane::Polar { 'X' } else { 'Z' };
        let from = std::mem::replace(&mut self.plane_at, (a, b));
        if plane == Plane::Cylinder {
            // Z moves with the plane (polar X: from `POLAR MODE=OFF`).
            self.at.1 = a;
            self.c_now = b;
        }
        let (g, centre) = match motion {
            PlaneMotion::Rapid => ("G00", None),
            PlaneMotion::Line => ("G01", None),
            PlaneMotion::Arc { dir, ca, cb } => (
                if dir == Dir::Cw { "G02" } else { "G03" },
                Some((dir, ca, cb)),
            ),
            PlaneMotion::Ellipse { dir, .. } => (conic_code(true, dir), None),
            PlaneMotion::Parabola { dir, .. } => (conic_code(false, dir), None),
        };
        let mut s = format!("{g} {first}{} C{}", n(a), n(b));
        match motion {
            PlaneMotion::Ellipse {
                a: sa, b: sb, q, ..
            } => s.push_str(&self.ellipse_words(sa, sb, q)),
            PlaneMotion::Parabola { p, q, .. } => s.push_str(&parabola_words(p, q)),
            _ => {}
        }
        match (centre, plane) {
            (None, _) => {}
            (Some((_, ca, cb)), Plane::Polar) => {
                let _ = write!(s, " I{} J{}", n((ca - from.0) / 2.0), n(cb - from.1));
            }
            (Some((dir, ca, cb)), Plane::Cylinder) => {
                // The developed surface: s = r·C·π/180 across, Z up.
                let k = self.radius.to_radians();
                let u0 = ((from.1 - cb) * k, from.0 - ca);
                let u1 = ((b - cb) * k, a - ca);
                let _ = write!(s, " R{}", n(signed_radius(dir, u0, u1)));
            }
        }
        // The axis outside the plane, moving along (a straight move only).
        match (off, plane) {
            (None, _) => {}
            (Some(z), Plane::Polar) => {
                self.at.1 = z;
                let _ = write!(s, " Z{}", self.w(z));
            }
            (Some(x), Plane::Cylinder) => {
                self.at.0 = x;
                let _ = write!(s, " X{}", self.w(x));
            }
        }
        s
    }
}

/// The R word of an arc turning `dir` from `u0` to `u1` (the start and
/// end relative to the centre, in a plane where G02 turns clockwise): its
/// radius, negative when the arc sweeps more than a half circle.
fn signed_radius(dir: Dir, u0: (f64, f64), u1: (f64, f64)) -> f64 {
    let cross = u0.0 * u1.1 - u0.1 * u1.0;
    let long = match dir {
        Dir::Ccw => cross < 0.0,
        Dir::Cw => cross > 0.0,
    };
    let r = u1.0.hypot(u1.1);
    if long {
        -r
    } else {
        r
    }
}

/// One hole of rigid tapping as its events print it (cycles.md §22):
/// [RAPID to s0] [M α] [SPINDLE tapping way] THREAD to s1 [DWELL]
/// SPINDLE reverse, THREAD to s0, SPINDLE tapping way [M α+1].
struct Tap {
    s0: (f64, f64),
    s1: (f64, f64),
    lead: f64,
    /// Turning CCW to tap: a left-hand thread, F < 0.
    left: bool,
    dwell: Option<f64>,
    m: Option<u32>,
}

/// The hole a block's events tap, starting from `at`; None when they are
/// anything else.
fn rigid_tap(events: &[Event], at: (f64, f64)) -> Option<Tap> {
    let mut rest = events;
    let mut s0 = at;
    if let [Event::Rapid { x, z, c: None }, more @ ..] = rest {
        s0 = (*x, *z);
        rest = more;
    }
    let mut m = None;
    if let [Event::M(a), more @ ..] = rest {
        m = Some(*a);
        rest = more;
    }
    if let [Event::Spindle(_), more @ ..] = rest {
        rest = more;
    }
    let [Event::Thread {
        x,
        z,
        lead,
        dlead: None,
        q: None,
        c: None,
    }, more @ ..] = rest
    else {
        return None;
    };
    let (s1, lead) = ((*x, *z), *lead);
    rest = more;
    let mut dwell = None;
    if let [Event::Dwell { s }, more @ ..] = rest {
        dwell = Some(*s);
        rest = more;
    }
    let [Event::Spindle(rev), Event::Thread {
        x, z, lead: back, ..
    }, Event::Spindle(tap), more @ ..] = rest
    else {
        return None;
    };
    let closes = (*x, *z) == s0 && *back == lead && rev != tap && *tap != SpindleDir::Stop;
    let end_ok = match (m, more) {
        (None, []) => true,
        (Some(a), [Event::M(b)]) => *b == a + 1,
        _ => false,
    };
    let along_one_axis = s1.0 == s0.0 || s1.1 == s0.1;
    (closes && end_ok && along_one_axis && *rev != SpindleDir::Stop).then_some(Tap {
        s0,
        s1,
        lead,
        left: *tap == SpindleDir::Ccw,
        dwell,
        m,
    })
}

/// The G code of an ellipse (G6.2/G6.3) or a parabola (G7.2/G7.3).
fn conic_code(ellipse: bool, dir: Dir) -> &'static str {
    match (ellipse, dir) {
        (true, Dir::Cw) => "G6.2",
        (true, Dir::Ccw) => "G6.3",
        (false, Dir::Cw) => "G7.2",
        (false, Dir::Ccw) => "G7.3",
    }
}

/// A parabola's P (an integer of 0.001 mm, as the block reads it; `-E`
/// writes mm) and Q (0.001°).
fn parabola_words(p: f64, q: f64) -> String {
    format!(" P{}{}", (p * 1000.0).round(), q_word(Some(q)))
}

/// The Q word of a thread's start angle or a conic's axis angle, in the
/// integer 0.001° the dialect takes.
fn q_word(q: Option<f64>) -> String {
    q.map_or(String::new(), |q| format!(" Q{}", (q * 1000.0).round()))
}

/// Text for inside a comment: a parenthesis would nest or end it.
fn comment(t: &str) -> String {
    t.replace('(', "[").replace(')', "]")
}

/// A run-time alarm: a `#3000` alarm as the `#3000` write that raises it;
/// another (a check of the dialect, the block budget) cannot be written as
/// G-code, and the output says so where the run stopped.
fn alarm(code: u32, msg: &str) -> String {
    match code.checked_sub(3000).filter(|v| *v < 1000) {
        Some(v) if msg.is_empty() => format!("#3000={v}"),
        Some(v) => format!("#3000={v} ({})", comment(msg)),
        None => format!("(ALARM {code}: {}: {NOT_WRITTEN})", comment(msg)),
    }
}

/// Where an event leaves the tool.
fn end_point(e: &Event) -> Option<(f64, f64)> {
    match *e {
        Event::Rapid { x, z, .. } | Event::Line { x, z, .. } | Event::Skip { x, z } => Some((x, z)),
        Event::Arc { x, z, .. } | Event::Thread { x, z, .. } => Some((x, z)),
        Event::Ellipse { x, z, .. } | Event::Parabola { x, z, .. } => Some((x, z)),
        _ => None,
    }
}
