//! `gbcc -E`: the program as plain G-code after macros, subprograms and
//! cycles are resolved — what the machine is really told to do, block by
//! block, with absolute coordinates and the source block as a comment.

use nc::event::Num;
use nc::event::{Dir, Plane, PlaneMotion, SpindleDir, StopKind};
use nc::Event;
use std::collections::HashMap;
use std::fmt::Write;

/// Turns canon events into G-code text.
pub struct Expand {
    pub out: String,
    /// Source line → its sequence number (for the comment).
    seqs: HashMap<u32, u32>,
    /// The source line of the block being printed.
    line: u32,
    last_line: u32,
    /// (X, Z) of the last point, for arc centres relative to the start.
    at: (f64, f64),
    feed: Option<(f64, bool)>,
    /// The C angle of the last `C=` (the start of a G7.1 plane).
    c_now: f64,
    /// In a polar or cylinder plane: the last plane point as printed
    /// (polar X C, cylinder Z C), and the cylinder's radius.
    plane_at: (f64, f64),
    radius: f64,
}

impl Expand {
    pub fn new(seqs: HashMap<u32, u32>) -> Expand {
        Expand {
            out: String::new(),
            seqs,
            line: 0,
            last_line: 0,
            at: (0.0, 0.0),
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
        match self.seqs.get(&self.line) {
            Some(n) => format!(" (N{n}, LINE {})", self.line),
            None => format!(" (LINE {})", self.line),
        }
    }

    fn block(&mut self, text: String) {
        let note = self.origin_comment();
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
    /// starting at (`x`, `z`).
    pub fn block_events(&mut self, events: &[Event], line: u32, start: (f64, f64)) {
        self.line = line;
        self.at = start;
        for e in events {
            self.event(e);
        }
    }

    fn event(&mut self, e: &Event) {
        if let Event::Rapid { c: Some(c), .. } | Event::Line { c: Some(c), .. } = e {
            self.c_now = *c;
        }
        let text = match e {
            Event::PolarOn => {
                self.plane_at = (self.at.0, 0.0);
                "G12.1".into()
            }
            Event::PolarOff { c, .. } => {
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
            } => self.plane_move(*plane, *motion, *a, *b),
            Event::Rapid { x, z, c } => format!("G00 X{} Z{}{}", n(*x), n(*z), c_word(*c)),
            Event::Line { x, z, c } => format!("G01 X{} Z{}{}", n(*x), n(*z), c_word(*c)),
            Event::Arc { dir, x, z, cx, cz } => {
                let g = if *dir == Dir::Cw { "G02" } else { "G03" };
                // I is a radius value relative to the start, K relative too.
                let (i, k) = ((cx - self.at.0) / 2.0, cz - self.at.1);
                format!("{g} X{} Z{} I{} K{}", n(*x), n(*z), n(i), n(k))
            }
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
                    Some(d) => format!("G34 X{} Z{} F{} R{}", n(*x), n(*z), n(*lead), n(*d)),
                    None => format!("G32 X{} Z{} F{}", n(*x), n(*z), n(*lead)),
                };
                if let Some(q) = q {
                    let _ = write!(s, " Q{}", n(q * 1000.0));
                }
                s
            }
            Event::Dwell { s } => format!("G04 X{}", n(*s)),
            Event::Feed { f, per_rev } => {
                let m = self.mode(*f, *per_rev);
                format!("{m}F{}", n(*f))
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
            Event::Origin { x, z } => format!("(WORK ZERO AT MACHINE X{} Z{})", n(*x), n(*z)),
            Event::Home { n: p, x, z, c } => format!(
                "(AT REFERENCE POINT {p}:{}{}{})",
                if *x { " X" } else { "" },
                if *z { " Z" } else { "" },
                if *c { " C" } else { "" }
            ),
            Event::Stop(k) => match k {
                StopKind::M00 => "M00".into(),
                StopKind::M01 => "M01".into(),
                StopKind::M02 => "M02".into(),
                StopKind::M30 => "M30".into(),
                StopKind::M99 => "M99".into(),
            },
            Event::Skip { x, z } => format!("G31 X{} Z{}", n(*x), n(*z)),
            Event::Message(t) => format!("(MESSAGE: {t})"),
            Event::Alarm { code, msg } => format!("(ALARM {code}: {msg})"),
            other => format!("({other})"),
        };
        if let Some((x, z)) = end_point(e) {
            self.at = (x, z);
        }
        self.block(text);
    }
}

impl Expand {
    /// A move of polar (`X C`) or cylindrical (`Z C`) interpolation; a
    /// polar arc's centre as I/J from its start, a cylinder's as R
    /// (negative beyond a half circle), the only form G7.1 takes.
    fn plane_move(&mut self, plane: Plane, motion: PlaneMotion, a: f64, b: f64) -> String {
        let first = if plane == Plane::Polar { 'X' } else { 'Z' };
        let from = std::mem::replace(&mut self.plane_at, (a, b));
        if plane == Plane::Cylinder {
            self.c_now = b;
        }
        let (g, centre) = match motion {
            PlaneMotion::Rapid => ("G00", None),
            PlaneMotion::Line => ("G01", None),
            PlaneMotion::Arc { dir, ca, cb } => (
                if dir == Dir::Cw { "G02" } else { "G03" },
                Some((dir, ca, cb)),
            ),
        };
        let mut s = format!("{g} {first}{} C{}", n(a), n(b));
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
                let cross = u0.0 * u1.1 - u0.1 * u1.0;
                let long = if dir == Dir::Ccw {
                    cross < 0.0
                } else {
                    cross > 0.0
                };
                let r = u1.0.hypot(u1.1);
                let _ = write!(s, " R{}", n(if long { -r } else { r }));
            }
        }
        s
    }
}

/// The C word of a move on a machine with a C axis.
fn c_word(c: Option<f64>) -> String {
    c.map_or(String::new(), |c| format!(" C{}", n(c)))
}

/// Where an event leaves the tool.
fn end_point(e: &Event) -> Option<(f64, f64)> {
    match *e {
        Event::Rapid { x, z, .. } | Event::Line { x, z, .. } | Event::Skip { x, z } => Some((x, z)),
        Event::Arc { x, z, .. } | Event::Thread { x, z, .. } => Some((x, z)),
        _ => None,
    }
}
