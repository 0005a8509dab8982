//! The events a run produces, and their canon text (canon.md).

use alloc::format;
use alloc::string::String;

use core::fmt::{self, Display, Write};

use super::decimal;
use super::error::NcError;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    Cw,
    Ccw,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpindleDir {
    Cw,
    Ccw,
    Stop,
}

/// The plane of polar (G12.1) or cylindrical (G7.1) interpolation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    /// G12.1: X (a diameter) and the hypothetical axis C (mm, a radius).
    Polar,
    /// G7.1: Z and C (degrees) on the cylinder of the mode's radius.
    Cylinder,
}

/// How a move of the polar or cylinder plane runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneMotion {
    Rapid,
    Line,
    /// An arc about the centre (`ca`, `cb`), in the coordinates of the
    /// end point.
    Arc {
        dir: Dir,
        ca: f64,
        cb: f64,
    },
    /// G6.2/G6.3 in the plane: semi-axes A, B (mm), the axis at Q
    /// degrees counter-clockwise from the plane's first axis.
    Ellipse {
        dir: Dir,
        a: f64,
        b: f64,
        q: f64,
    },
    /// G7.2/G7.3 in the plane: parameter P (mm), the symmetry axis at Q
    /// degrees from the plane's first axis.
    Parabola {
        dir: Dir,
        p: f64,
        q: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopKind {
    M00,
    M01,
    M02,
    M30,
    M99,
}

/// One canon event. Coordinates are work coordinates in mm, X as a
/// diameter, exactly as printed.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// `c`: the C axis position (degrees), printed only on a machine with
    /// a C axis, when the block programs C/H or the move turns C.
    Rapid {
        x: f64,
        z: f64,
        c: Option<f64>,
    },
    Line {
        x: f64,
        z: f64,
        c: Option<f64>,
    },
    Arc {
        dir: Dir,
        x: f64,
        z: f64,
        cx: f64,
        cz: f64,
    },
    /// G6.2/G6.3: end point, semi-axes A (along the axis at Q) and B in
    /// mm, axis angle Q in degrees.
    Ellipse {
        dir: Dir,
        x: f64,
        z: f64,
        a: f64,
        b: f64,
        q: f64,
    },
    /// G7.2/G7.3: end point, parameter p (mm) and symmetry-axis angle Q
    /// in degrees.
    Parabola {
        dir: Dir,
        x: f64,
        z: f64,
        p: f64,
        q: f64,
    },
    Thread {
        x: f64,
        z: f64,
        c: Option<f64>,
        lead: f64,
        dlead: Option<f64>,
        q: Option<f64>,
    },
    /// G32.2/G32.3: one arc cut at constant lead (end point and centre as
    /// `Arc`, the lead along the arc's long axis).
    ArcThread {
        dir: Dir,
        x: f64,
        z: f64,
        cx: f64,
        cz: f64,
        lead: f64,
        q: Option<f64>,
    },
    Dwell {
        s: f64,
    },
    Feed {
        f: f64,
        per_rev: bool,
    },
    Speed {
        s: f64,
        css: bool,
        max: Option<f64>,
    },
    Spindle(SpindleDir),
    Tool {
        t: u32,
        d: u32,
    },
    M(u32),
    Origin {
        x: f64,
        z: f64,
    },
    /// The axes that went home; `c` only on a machine with a C axis.
    Home {
        n: u32,
        x: bool,
        z: bool,
        c: bool,
    },
    Stop(StopKind),
    Skip {
        x: f64,
        z: f64,
    },
    Gear {
        n: u32,
    },
    /// `#3006 = n (TEXT)`: a message stop. The canon prints the text
    /// only; the number is for a host that tells messages apart by it.
    Message {
        /// The value written to #3006 as a whole number: rounded half away
        /// from zero, vacant as 0, below 0 as 0, beyond `u32::MAX` as
        /// `u32::MAX`.
        number: u32,
        /// The block's comment.
        text: String,
    },
    /// `POLAR MODE=ON`: G12.1.
    PolarOn,
    /// `POLAR MODE=OFF X= C=`: G13.1, with the joint position polar
    /// interpolation left X (a diameter) and C (degrees) at; Z is where it
    /// was at G12.1.
    PolarOff {
        x: f64,
        c: f64,
    },
    /// `CYLINDER MODE=ON R=` / `CYLINDER MODE=OFF`: `G7.1 C<radius>` / `G7.1 C0`.
    Cylinder(Option<f64>),
    /// A move in the plane of polar or cylindrical interpolation, printed
    /// in its coordinates: polar `X=` (diameter) `C=` (mm), cylinder `Z=`
    /// `C=` (degrees). The arc centre as `CX=`/`CZ=` and `CC=`. `off`:
    /// the end of the axis outside the plane where a straight move takes
    /// it along (polar `Z=`, cylinder `X=`, a diameter), printed last.
    PlaneMove {
        plane: Plane,
        motion: PlaneMotion,
        a: f64,
        b: f64,
        off: Option<f64>,
    },
    /// During polar (cylindrical) interpolation the axis outside the plane
    /// moves alone and the plane point stands: `RAPID Z=` / `LINE Z=`
    /// (polar), `RAPID X=` / `LINE X=` (cylinder, X a diameter). `c` is
    /// the C angle the joints stand at (degrees): the runtime leaves the
    /// plane there for the move and comes back; the line does not print it.
    PlaneAxis {
        plane: Plane,
        rapid: bool,
        to: f64,
        c: f64,
    },
    Alarm {
        code: u32,
        msg: String,
    },
}

impl Event {
    /// Feed events are preceded by `FEED` when the feed changed.
    pub fn is_feed(&self) -> bool {
        matches!(
            self,
            Event::Line { .. }
                | Event::Arc { .. }
                | Event::Ellipse { .. }
                | Event::Parabola { .. }
                | Event::Skip { .. }
                | Event::PlaneMove {
                    motion: PlaneMotion::Line
                        | PlaneMotion::Arc { .. }
                        | PlaneMotion::Ellipse { .. }
                        | PlaneMotion::Parabola { .. },
                    ..
                }
                | Event::PlaneAxis { rapid: false, .. }
        )
    }

    /// Where a move in X and Z ends (X a diameter, Z; work coordinates);
    /// `None` for any other event, a plane's moves included.
    pub fn end(&self) -> Option<(f64, f64)> {
        match *self {
            Event::Rapid { x, z, .. }
            | Event::Line { x, z, .. }
            | Event::Arc { x, z, .. }
            | Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. }
            | Event::Thread { x, z, .. }
            | Event::ArcThread { x, z, .. }
            | Event::Skip { x, z } => Some((x, z)),
            _ => None,
        }
    }

    /// A motion of the tool (for G66 and the block counter).
    pub fn is_motion(&self) -> bool {
        matches!(
            self,
            Event::Rapid { .. }
                | Event::Line { .. }
                | Event::Arc { .. }
                | Event::Ellipse { .. }
                | Event::Parabola { .. }
                | Event::Thread { .. }
                | Event::ArcThread { .. }
                | Event::Skip { .. }
                | Event::PlaneMove { .. }
                | Event::PlaneAxis { .. }
        )
    }
}

/// A number as the canon prints it: at most 4 decimals, no trailing zeros,
/// no trailing point, `-0` as `0`.
pub struct Num(pub f64);

impl Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match decimal::ten_thousandths(self.0) {
            Some(n) => decimal::write_ten_thousandths(f, n),
            None => exact_formatter(f, self.0),
        }
    }
}

/// Values past the integer fast path (not finite, or above about 9·10¹⁴),
/// through the standard library's formatter.
fn exact_formatter(f: &mut fmt::Formatter<'_>, v: f64) -> fmt::Result {
    let mut s = format!("{v:.4}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".into();
    }
    f.write_str(&s)
}

/// The optional ` C=` field of `RAPID`, `LINE` and `THREAD` (canon.md).
struct CField(Option<f64>);

impl Display for CField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(c) => write!(f, " C={}", Num(c)),
            None => Ok(()),
        }
    }
}

fn dir(d: Dir) -> &'static str {
    match d {
        Dir::Cw => "CW",
        Dir::Ccw => "CCW",
    }
}

/// A message of the implementation's in ASCII, for the canon: the signs
/// its wording uses spelled out (`…` as `...`, `−` as `-`, `Δd` as `dd`,
/// `°` as ` deg`); any other character outside ASCII stays, to print as
/// `?`.
pub fn ascii(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '…' => out.push_str("..."),
            '−' | '–' | '—' => out.push('-'),
            'Δ' => out.push('d'),
            '°' => out.push_str(" deg"),
            '≤' => out.push_str("<="),
            '≥' => out.push_str(">="),
            '×' => out.push('x'),
            '÷' => out.push('/'),
            '√' => out.push_str("sqrt"),
            '²' => out.push_str("^2"),
            '№' => out.push_str("No."),
            'µ' => out.push('u'),
            '≠' => out.push_str("!="),
            c => out.push(c),
        }
    }
    out
}

/// A program's text (a comment: the `MESSAGE`, a `#3000` or `G65 H99`
/// alarm) as the canon prints it, without its quotes: `"` and every
/// byte outside printable ASCII as `?` (canon.md). The text is kept as
/// the program wrote it for hosts, so `é`, two bytes of UTF-8, is `??`,
/// as the bytes of the file.
pub fn canon_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if is_plain(c) {
            out.push(c);
        } else {
            out.extend(core::iter::repeat_n('?', c.len_utf8()));
        }
    }
    out
}

/// Printable ASCII but `"`: what a canon string prints as it is.
fn is_plain(c: char) -> bool {
    c != '"' && (' '..='~').contains(&c)
}

/// An alarm's `MSG` between its quotes: a program's alarm has the
/// program's text ([`canon_text`]); the implementation's wording is
/// ASCII but for the few signs [`ascii`] leaves, each one `?`.
fn alarm_text(code: u32, msg: &str) -> String {
    if NcError::is_program_alarm(code) {
        canon_text(msg)
    } else {
        msg.chars()
            .map(|c| if is_plain(c) { c } else { '?' })
            .collect()
    }
}

impl Display for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Event::Rapid { x, z, c } => {
                write!(f, "RAPID X={} Z={}{}", Num(*x), Num(*z), CField(*c))
            }
            Event::Line { x, z, c } => write!(f, "LINE X={} Z={}{}", Num(*x), Num(*z), CField(*c)),
            Event::Arc {
                dir: d,
                x,
                z,
                cx,
                cz,
            } => write!(
                f,
                "ARC DIR={} X={} Z={} CX={} CZ={}",
                dir(*d),
                Num(*x),
                Num(*z),
                Num(*cx),
                Num(*cz)
            ),
            Event::Ellipse {
                dir: d,
                x,
                z,
                a,
                b,
                q,
            } => write!(
                f,
                "ELLIPSE DIR={} X={} Z={} A={} B={} Q={}",
                dir(*d),
                Num(*x),
                Num(*z),
                Num(*a),
                Num(*b),
                Num(*q)
            ),
            Event::Parabola { dir: d, x, z, p, q } => write!(
                f,
                "PARABOLA DIR={} X={} Z={} P={} Q={}",
                dir(*d),
                Num(*x),
                Num(*z),
                Num(*p),
                Num(*q)
            ),
            Event::Thread {
                x,
                z,
                c,
                lead,
                dlead,
                q,
            } => {
                write!(
                    f,
                    "THREAD X={} Z={}{} LEAD={}",
                    Num(*x),
                    Num(*z),
                    CField(*c),
                    Num(*lead)
                )?;
                if let Some(d) = dlead {
                    write!(f, " DLEAD={}", Num(*d))?;
                }
                if let Some(q) = q {
                    write!(f, " Q={}", Num(*q))?;
                }
                Ok(())
            }
            Event::ArcThread {
                dir: d,
                x,
                z,
                cx,
                cz,
                lead,
                q,
            } => {
                write!(
                    f,
                    "ARCTHREAD DIR={} X={} Z={} CX={} CZ={} LEAD={}",
                    dir(*d),
                    Num(*x),
                    Num(*z),
                    Num(*cx),
                    Num(*cz),
                    Num(*lead)
                )?;
                if let Some(q) = q {
                    write!(f, " Q={}", Num(*q))?;
                }
                Ok(())
            }
            Event::Dwell { s } => write!(f, "DWELL S={}", Num(*s)),
            Event::Feed { f: feed, per_rev } => write!(
                f,
                "FEED F={} MODE={}",
                Num(*feed),
                if *per_rev { "REV" } else { "MIN" }
            ),
            Event::Speed { s, css, max } => {
                write!(
                    f,
                    "SPEED S={} MODE={}",
                    Num(*s),
                    if *css { "CSS" } else { "RPM" }
                )?;
                if let Some(m) = max {
                    write!(f, " MAX={}", Num(*m))?;
                }
                Ok(())
            }
            Event::Spindle(d) => f.write_str(match d {
                SpindleDir::Cw => "SPINDLE DIR=CW",
                SpindleDir::Ccw => "SPINDLE DIR=CCW",
                SpindleDir::Stop => "SPINDLE DIR=STOP",
            }),
            Event::Tool { t, d } => write!(f, "TOOL T={t} D={d}"),
            Event::M(code) => write!(f, "M CODE={code}"),
            Event::Origin { x, z } => write!(f, "ORIGIN X={} Z={}", Num(*x), Num(*z)),
            Event::Home { n, x, z, c } => {
                f.write_str("HOME N=")?;
                write!(f, "{n} AXES=")?;
                if *x {
                    f.write_char('X')?;
                }
                if *z {
                    f.write_char('Z')?;
                }
                if *c {
                    f.write_char('C')?;
                }
                Ok(())
            }
            Event::Stop(k) => write!(f, "STOP KIND={k:?}"),
            Event::Skip { x, z } => write!(f, "SKIP X={} Z={}", Num(*x), Num(*z)),
            Event::Gear { n } => write!(f, "GEAR N={n}"),
            Event::Message { text, .. } => write!(f, "MESSAGE TEXT=\"{}\"", canon_text(text)),
            Event::Alarm { code, msg } => {
                write!(f, "ALARM CODE={code} MSG=\"{}\"", alarm_text(*code, msg))
            }
            Event::PolarOn => f.write_str("POLAR MODE=ON"),
            Event::PolarOff { x, c } => write!(f, "POLAR MODE=OFF X={} C={}", Num(*x), Num(*c)),
            Event::Cylinder(Some(r)) => write!(f, "CYLINDER MODE=ON R={}", Num(*r)),
            Event::Cylinder(None) => f.write_str("CYLINDER MODE=OFF"),
            Event::PlaneMove {
                plane,
                motion,
                a,
                b,
                off,
            } => {
                let (first, other) = match plane {
                    Plane::Polar => ('X', 'Z'),
                    Plane::Cylinder => ('Z', 'X'),
                };
                match motion {
                    PlaneMotion::Rapid => f.write_str("RAPID ")?,
                    PlaneMotion::Line => f.write_str("LINE ")?,
                    PlaneMotion::Arc { dir: d, .. } => write!(f, "ARC DIR={} ", dir(*d))?,
                    PlaneMotion::Ellipse { dir: d, .. } => write!(f, "ELLIPSE DIR={} ", dir(*d))?,
                    PlaneMotion::Parabola { dir: d, .. } => write!(f, "PARABOLA DIR={} ", dir(*d))?,
                }
                write!(f, "{first}={} C={}", Num(*a), Num(*b))?;
                match motion {
                    PlaneMotion::Arc { ca, cb, .. } => {
                        write!(f, " C{first}={} CC={}", Num(*ca), Num(*cb))?
                    }
                    PlaneMotion::Ellipse { a, b, q, .. } => {
                        write!(f, " A={} B={} Q={}", Num(*a), Num(*b), Num(*q))?
                    }
                    PlaneMotion::Parabola { p, q, .. } => {
                        write!(f, " P={} Q={}", Num(*p), Num(*q))?
                    }
                    PlaneMotion::Rapid | PlaneMotion::Line => {}
                }
                if let Some(v) = off {
                    write!(f, " {other}={}", Num(*v))?;
                }
                Ok(())
            }
            Event::PlaneAxis {
                plane, rapid, to, ..
            } => {
                let kind = if *rapid { "RAPID" } else { "LINE" };
                let axis = match plane {
                    Plane::Polar => 'Z',
                    Plane::Cylinder => 'X',
                };
                write!(f, "{kind} {axis}={}", Num(*to))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn numbers_print_as_the_canon_wants() {
        let p = |v: f64| Num(v).to_string();
        assert_eq!(p(12.5), "12.5");
        assert_eq!(p(-3.0), "-3");
        assert_eq!(p(0.0125), "0.0125");
        assert_eq!(p(-0.00001), "0");
        assert_eq!(p(1145.91559), "1145.9156");
        assert_eq!(p(100.0), "100");
    }

    #[test]
    fn strings_replace_quotes_and_non_ascii() {
        // A program's text: one `?` for each byte, as canon.md words it
        // (é is two in UTF-8, the tab one, € three).
        let e = Event::Message {
            number: 7,
            text: "CHECK \"INSERT\" \u{e9}\t\u{20ac}".into(),
        };
        assert_eq!(e.to_string(), "MESSAGE TEXT=\"CHECK ?INSERT? ??????\"");
        let e = Event::Alarm {
            code: 3005,
            msg: "\"\u{e9}\"".into(),
        };
        assert_eq!(e.to_string(), "ALARM CODE=3005 MSG=\"????\"");
        // The implementation's wording: a sign `ascii` leaves is one `?`.
        let e = Event::Alarm {
            code: 7002,
            msg: "within \u{3b5} of \"X\"".into(),
        };
        assert_eq!(e.to_string(), "ALARM CODE=7002 MSG=\"within ? of ?X?\"");
    }

    #[test]
    fn events_print_their_fields_in_order() {
        let e = Event::Arc {
            dir: Dir::Ccw,
            x: 30.0,
            z: -5.0,
            cx: 20.0,
            cz: -5.0,
        };
        assert_eq!(e.to_string(), "ARC DIR=CCW X=30 Z=-5 CX=20 CZ=-5");
        let e = Event::Ellipse {
            dir: Dir::Cw,
            x: 40.0,
            z: -10.0,
            a: 10.0,
            b: 5.0,
            q: 30.0,
        };
        assert_eq!(e.to_string(), "ELLIPSE DIR=CW X=40 Z=-10 A=10 B=5 Q=30");
        assert!(e.is_feed() && e.is_motion());
        let e = Event::Parabola {
            dir: Dir::Ccw,
            x: 20.0,
            z: -8.0,
            p: 2.5,
            q: 0.0,
        };
        assert_eq!(e.to_string(), "PARABOLA DIR=CCW X=20 Z=-8 P=2.5 Q=0");
        assert!(e.is_feed() && e.is_motion());
        let e = Event::Home {
            n: 1,
            x: true,
            z: false,
            c: false,
        };
        assert_eq!(e.to_string(), "HOME N=1 AXES=X");
        let e = Event::Home {
            n: 1,
            x: false,
            z: true,
            c: true,
        };
        assert_eq!(e.to_string(), "HOME N=1 AXES=ZC");
        let e = Event::Line {
            x: 20.0,
            z: -5.0,
            c: Some(-45.5),
        };
        assert_eq!(e.to_string(), "LINE X=20 Z=-5 C=-45.5");
        let e = Event::Thread {
            x: 0.0,
            z: -10.0,
            c: Some(90.0),
            lead: 1.5,
            dlead: None,
            q: None,
        };
        assert_eq!(e.to_string(), "THREAD X=0 Z=-10 C=90 LEAD=1.5");
        let e = Event::Speed {
            s: 600.0,
            css: false,
            max: Some(2000.0),
        };
        assert_eq!(e.to_string(), "SPEED S=600 MODE=RPM MAX=2000");
    }

    #[test]
    fn plane_events_print_the_planes_letters() {
        let arc = |plane| Event::PlaneMove {
            plane,
            motion: PlaneMotion::Arc {
                dir: Dir::Cw,
                ca: 0.0,
                cb: 2.5,
            },
            a: 10.0,
            b: -5.0,
            off: None,
        };
        assert_eq!(
            arc(Plane::Polar).to_string(),
            "ARC DIR=CW X=10 C=-5 CX=0 CC=2.5"
        );
        assert_eq!(
            arc(Plane::Cylinder).to_string(),
            "ARC DIR=CW Z=10 C=-5 CZ=0 CC=2.5"
        );
        let line = Event::PlaneMove {
            plane: Plane::Polar,
            motion: PlaneMotion::Line,
            a: 40.0,
            b: 0.0,
            off: None,
        };
        assert_eq!(line.to_string(), "LINE X=40 C=0");
        let ramp = Event::PlaneMove {
            plane: Plane::Polar,
            motion: PlaneMotion::Line,
            a: 40.0,
            b: 0.0,
            off: Some(-1.5),
        };
        assert_eq!(ramp.to_string(), "LINE X=40 C=0 Z=-1.5");
        let ellipse = Event::PlaneMove {
            plane: Plane::Polar,
            motion: PlaneMotion::Ellipse {
                dir: Dir::Ccw,
                a: 10.0,
                b: 5.0,
                q: 30.0,
            },
            a: 20.0,
            b: 2.5,
            off: None,
        };
        assert_eq!(
            ellipse.to_string(),
            "ELLIPSE DIR=CCW X=20 C=2.5 A=10 B=5 Q=30"
        );
        let parabola = Event::PlaneMove {
            plane: Plane::Cylinder,
            motion: PlaneMotion::Parabola {
                dir: Dir::Cw,
                p: 4.0,
                q: 0.0,
            },
            a: -5.0,
            b: 45.0,
            off: None,
        };
        assert_eq!(parabola.to_string(), "PARABOLA DIR=CW Z=-5 C=45 P=4 Q=0");
        assert!(ellipse.is_feed() && parabola.is_feed());
        assert!(line.is_feed() && line.is_motion());
        let rapid = Event::PlaneMove {
            plane: Plane::Cylinder,
            motion: PlaneMotion::Rapid,
            a: -3.0,
            b: 90.0,
            off: Some(24.0),
        };
        assert_eq!(rapid.to_string(), "RAPID Z=-3 C=90 X=24");
        assert!(!rapid.is_feed() && rapid.is_motion());
        let plunge = Event::PlaneAxis {
            plane: Plane::Polar,
            rapid: false,
            to: -2.5,
            c: 135.0,
        };
        assert_eq!(plunge.to_string(), "LINE Z=-2.5");
        assert!(plunge.is_feed() && plunge.is_motion());
        let infeed = Event::PlaneAxis {
            plane: Plane::Cylinder,
            rapid: true,
            to: 30.0,
            c: 90.0,
        };
        assert_eq!(infeed.to_string(), "RAPID X=30");
        assert!(!infeed.is_feed() && infeed.is_motion());
        assert_eq!(Event::PolarOn.to_string(), "POLAR MODE=ON");
        let off = Event::PolarOff { x: 20.0, c: -90.0 };
        assert_eq!(off.to_string(), "POLAR MODE=OFF X=20 C=-90");
        assert_eq!(
            Event::Cylinder(Some(12.5)).to_string(),
            "CYLINDER MODE=ON R=12.5"
        );
        assert_eq!(Event::Cylinder(None).to_string(), "CYLINDER MODE=OFF");
    }
}
