//! From canon events (work coordinates, X as a diameter) to runtime
//! commands (machine axes, slide units): the work zero of `ORIGIN`, the
//! tool length offsets of `TOOL` (which the canon never shows), the modal
//! feed of `FEED`.
//!
//! `ELLIPSE`, `PARABOLA` and `ARCTHREAD` become exact curves; should a
//! move ever end elsewhere than followed here, it is caught after the block
//! by comparing the kernel's programmed point with this one, and reached
//! by a line.

use crate::command::{Command, Ending, Feed, Move, MoveKind, Path, PauseKind, Thread};
use crate::math::V2;
use crate::plc::{PlcFunction, SpindleDir};
use crate::polar::{PlaneMap, PlaneSwitch};
use alloc::string::String;
use alloc::vec::Vec;
use nc::event::{Dir, PlaneMotion, SpindleDir as NcDir, StopKind};
use nc::exec::switches::Switch;
use nc::{Event, Machine};

#[derive(Debug, Clone)]
/// Turns canon events into commands in machine coordinates.
pub struct Translator {
    /// Work zero in machine coordinates.
    pub origin: V2,
    /// Active tool length offset (geometry + wear).
    pub tool_off: V2,
    /// The modal feed (F and G98/G99).
    pub feed: Feed,
    /// The programmed point, work coordinates (the canon's last point).
    pub work: V2,
    /// Texts of `MESSAGE` stops, by index.
    pub messages: Vec<String>,
    /// A G31 move was queued in the current block.
    pub skip_queued: bool,
    /// The C angle the next move turns C to (`None`: it stays); set by the
    /// `C=` field of the event being translated.
    c: Option<f64>,
    /// The C angle the axes stand at (the last `C=`, polar or cylinder
    /// end), degrees.
    c_now: f64,
    /// Polar or cylindrical interpolation while it is on (polar.rs).
    plane: Option<crate::polar::PlaneMap>,
    /// The plane point the last plane move ended at.
    plane_at: V2,
    /// The run is of MDI blocks: it ends as MDI does ([`Ending::Mdi`]).
    pub mdi: bool,
}

impl Translator {
    /// A translator whose work zero is `origin` (machine coordinates), the
    /// tool at machine zero (homed at power-on, machine.md §1).
    pub fn new(origin: V2) -> Translator {
        Translator {
            origin,
            tool_off: V2::ZERO,
            feed: Feed {
                f: 0.0,
                per_rev: false,
                fixed: false,
            },
            work: V2::ZERO - origin,
            messages: Vec::new(),
            skip_queued: false,
            c: None,
            c_now: 0.0,
            plane: None,
            plane_at: V2::ZERO,
            mdi: false,
        }
    }

    /// How the run ends at a program end of kind `k`.
    pub fn ending(&self, k: Ending) -> Ending {
        if self.mdi {
            Ending::Mdi
        } else {
            k
        }
    }

    /// The axes stand at C angle `c` (a restart after a reset).
    pub fn set_c(&mut self, c: f64) {
        self.c_now = c;
    }

    /// Polar or cylindrical interpolation is on.
    pub fn in_plane(&self) -> bool {
        self.plane.is_some()
    }

    fn shift(&self) -> V2 {
        self.origin + self.tool_off
    }

    fn axis(&self, work: V2) -> V2 {
        work + self.shift()
    }

    fn mv(&mut self, kind: MoveKind, to_work: V2, path: impl FnOnce(V2, V2) -> Path) -> Command {
        self.work = to_work;
        let shift = self.shift();
        Command::Move(Move {
            kind,
            path: path(self.axis(to_work), shift),
            shift,
            c: self.c.take(),
        })
    }

    /// The commands of one event; `nc` is the kernel after the block
    /// (for tool offset tables), `m` the machine (reference points).
    pub fn event(&mut self, e: &Event, nc: &nc::Nc, m: &Machine, out: &mut Vec<Command>) {
        let line = |to: V2, _| Path::Line { to };
        self.feed.fixed = nc.switch(Switch::NoFeedOverride);
        if let Event::Rapid { c: Some(c), .. } | Event::Line { c: Some(c), .. } = e {
            self.c_now = *c;
        }
        match e {
            Event::Rapid { x, z, c } => {
                self.c = *c;
                out.push(self.mv(MoveKind::Rapid, V2::from_xz(*x, *z), line))
            }
            Event::Line { x, z, c } => {
                self.c = *c;
                let k = MoveKind::Feed(self.feed);
                out.push(self.mv(k, V2::from_xz(*x, *z), line));
            }
            Event::Arc { dir, x, z, cx, cz } => {
                let k = MoveKind::Feed(self.feed);
                let c = V2::from_xz(*cx, *cz);
                let ccw = *dir == Dir::Ccw;
                out.push(self.mv(k, V2::from_xz(*x, *z), |to, sh| Path::Arc {
                    to,
                    centre: c + sh,
                    ccw,
                }));
            }
            // A thread's C= is the angle C holds (caxis.rs): nothing turns.
            Event::Thread {
                x,
                z,
                lead,
                dlead,
                q,
                ..
            } => {
                let k = MoveKind::Thread(Thread {
                    lead: *lead,
                    dlead: dlead.unwrap_or(0.0),
                    q_deg: q.unwrap_or(0.0),
                });
                out.push(self.mv(k, V2::from_xz(*x, *z), line));
            }
            Event::Skip { x, z } => {
                let k = MoveKind::Skip(self.feed);
                out.push(self.mv(k, V2::from_xz(*x, *z), line));
                self.skip_queued = true;
            }
            Event::Dwell { s } => out.push(Command::Dwell(*s)),
            Event::Feed { f, per_rev } => {
                self.feed = Feed {
                    f: if *per_rev { *f } else { *f / 60.0 },
                    per_rev: *per_rev,
                    fixed: self.feed.fixed,
                };
            }
            Event::Speed { s, css, max } => out.push(Command::Plc(PlcFunction::Speed {
                s: *s,
                css: *css,
                max: *max,
            })),
            Event::Spindle(d) => {
                let d = match d {
                    NcDir::Cw => SpindleDir::Cw,
                    NcDir::Ccw => SpindleDir::Ccw,
                    NcDir::Stop => SpindleDir::Stop,
                };
                out.push(Command::Plc(PlcFunction::Spindle(d)));
            }
            Event::Tool { t, d } => {
                out.push(Command::Plc(PlcFunction::Tool { t: *t, d: *d }));
                let off = tool_offset(nc, *d);
                if off != self.tool_off {
                    // The offset takes effect at once: the axes move, the
                    // programmed point stays.
                    self.tool_off = off;
                    let shift = self.shift();
                    out.push(Command::Move(Move {
                        kind: MoveKind::Offset,
                        path: Path::Line {
                            to: self.axis(self.work),
                        },
                        shift,
                        c: None,
                    }));
                }
            }
            Event::M(code) => out.push(Command::Plc(PlcFunction::M(*code))),
            Event::Gear { n } => out.push(Command::Plc(PlcFunction::Gear(*n))),
            Event::Origin { x, z } => {
                let machine = self.work + self.origin;
                self.origin = V2::from_xz(*x, *z);
                self.work = machine - self.origin;
                out.push(Command::Shift(self.shift()));
            }
            Event::Home { n, x, z, c } => {
                let rp = reference_point(m, *n);
                // G28/G30 cancel the tool length offset (dialect.md §4.4):
                // the axes themselves go to the reference point.
                let mut to = self.axis(self.work);
                if *x {
                    to.r = rp.r;
                }
                if *z {
                    to.z = rp.z;
                }
                self.tool_off = V2::ZERO;
                self.work = to - self.origin;
                if *c {
                    self.c_now = 0.0;
                }
                let shift = self.shift();
                out.push(Command::Move(Move {
                    kind: MoveKind::Rapid,
                    path: Path::Line { to },
                    shift,
                    // The C reference point is 0° (nc caxis.rs).
                    c: c.then_some(0.0),
                }));
                out.push(Command::Shift(shift));
            }
            Event::Stop(k) => out.push(match k {
                StopKind::M00 => Command::Pause(PauseKind::M00),
                StopKind::M01 => Command::Pause(PauseKind::M01),
                StopKind::M30 => Command::End(self.ending(Ending::M30)),
                StopKind::M02 | StopKind::M99 => Command::End(self.ending(Ending::Stop)),
            }),
            Event::Message { number, text } => {
                self.messages.push(text.clone());
                out.push(Command::Pause(PauseKind::Message {
                    number: *number,
                    index: self.messages.len() as u32 - 1,
                }));
            }
            Event::Alarm { code, .. } => out.push(Command::Alarm(*code)),
            Event::PolarOn => {
                let map = PlaneMap::Polar { z: self.work.z };
                self.plane_on(map, map.point(self.work.x(), 0.0), out);
            }
            Event::Cylinder(Some(radius)) => {
                let map = PlaneMap::Cylinder {
                    radius: *radius,
                    r: self.work.r,
                };
                self.plane_on(map, map.point(self.work.z, self.c_now), out);
            }
            Event::PolarOff { x, c } => {
                self.work.r = x * 0.5;
                self.c_now = *c;
                self.plane_off(out);
            }
            Event::Cylinder(None) => self.plane_off(out),
            Event::PlaneMove {
                motion, a, b, off, ..
            } => {
                if let Some(map) = self.plane {
                    self.plane_move(map, *motion, map.point(*a, *b), *off, out);
                }
            }
            Event::PlaneAxis { rapid, to, c, .. } => {
                if let Some(map) = self.plane {
                    self.plane_axis(map, *rapid, *to, *c, out);
                }
            }
            Event::Ellipse { dir, x, z, a, b, q } => {
                let (a, b, q, ccw) = (*a, *b, q.to_radians(), *dir == Dir::Ccw);
                let k = MoveKind::Feed(self.feed);
                out.push(self.mv(k, V2::from_xz(*x, *z), |to, _| Path::Ellipse {
                    to,
                    a,
                    b,
                    q,
                    ccw,
                }));
            }
            Event::Parabola { dir, x, z, p, q } => {
                let (p, q, ccw) = (*p, q.to_radians(), *dir == Dir::Ccw);
                let k = MoveKind::Feed(self.feed);
                out.push(self.mv(k, V2::from_xz(*x, *z), |to, _| Path::Parabola {
                    to,
                    p,
                    q,
                    ccw,
                }));
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
                let c = V2::from_xz(*cx, *cz);
                let ccw = *dir == Dir::Ccw;
                let k = MoveKind::Thread(Thread {
                    lead: *lead,
                    dlead: 0.0,
                    q_deg: q.unwrap_or(0.0),
                });
                out.push(self.mv(k, V2::from_xz(*x, *z), |to, sh| Path::Arc {
                    to,
                    centre: c + sh,
                    ccw,
                }));
            }
        }
    }
}

impl Translator {
    /// A plane starts at plane point `at`.
    fn plane_on(&mut self, map: PlaneMap, at: V2, out: &mut Vec<Command>) {
        self.plane = Some(map);
        self.plane_at = at;
        out.push(Command::Plane(PlaneSwitch {
            map: Some(map),
            at,
            c: self.c_now,
            shift: self.shift(),
        }));
    }

    /// The plane ends where its last move left the joints.
    fn plane_off(&mut self, out: &mut Vec<Command>) {
        if self.plane.take().is_none() {
            return;
        }
        out.push(Command::Plane(PlaneSwitch {
            map: None,
            at: self.axis(self.work),
            c: self.c_now,
            shift: self.shift(),
        }));
    }

    /// A move in the plane to plane point `to`: plane points, no shift
    /// (polar.rs); the joints follow in `work` and `c_now` (the polar C
    /// only at the end, from `POLAR MODE=OFF`). `off`: where a straight
    /// move takes the axis outside the plane (polar Z, cylinder X as a
    /// diameter), the move's third coordinate (planner.rs).
    fn plane_move(
        &mut self,
        map: PlaneMap,
        motion: PlaneMotion,
        to: V2,
        off: Option<f64>,
        out: &mut Vec<Command>,
    ) {
        let from = self.plane_at;
        let held = match map {
            PlaneMap::Polar { .. } => off,
            PlaneMap::Cylinder { .. } => off.map(|x| x * 0.5),
        };
        let (h0, map) = (map.held(), map.with_held(held.unwrap_or(map.held())));
        self.plane = Some(map);
        let (kind, arc) = match motion {
            PlaneMotion::Rapid => (MoveKind::Rapid, None),
            PlaneMotion::Line => (MoveKind::Feed(self.feed), None),
            PlaneMotion::Arc { dir, ca, cb } => (
                MoveKind::Feed(self.feed),
                Some((map.point(ca, cb), dir == Dir::Ccw)),
            ),
            PlaneMotion::Ellipse { .. } | PlaneMotion::Parabola { .. } => {
                (MoveKind::Feed(self.feed), None)
            }
        };
        let path = |to| plane_path(motion, arc, to);
        if let PlaneMap::Polar { .. } = map {
            // Near the centre in pieces, each capped for its own distance
            // (polar.rs). (A conic that cannot be drawn, which only a
            // crafted module asks for, goes whole: the planner raises its
            // alarm.)
            let curve = plane_curve(motion, arc, from, to);
            for (curve, lam) in curve
                .iter()
                .flat_map(|c| crate::polar::cuts(c).into_iter().map(move |l| (c, l)))
            {
                out.push(Command::Move(Move {
                    kind,
                    path: path(curve.point(lam)),
                    shift: V2::ZERO,
                    // (A line's λ is in proportion to its length.)
                    c: held.map(|h1| h0 + (h1 - h0) * lam),
                }));
            }
        }
        let path = path(to);
        self.plane_at = to;
        let (work, c) = map.joints(to);
        self.work = work;
        if let PlaneMap::Cylinder { .. } = map {
            self.c_now = c;
        }
        out.push(Command::Move(Move {
            kind,
            path,
            shift: V2::ZERO,
            c: held,
        }));
    }
}

/// The path of a plane move (or of a piece of it) to `to` (`arc`: an
/// arc's centre and sense).
fn plane_path(motion: PlaneMotion, arc: Option<(V2, bool)>, to: V2) -> Path {
    match (motion, arc) {
        (PlaneMotion::Ellipse { dir, a, b, q }, _) => Path::Ellipse {
            to,
            a,
            b,
            q: q.to_radians(),
            ccw: dir == Dir::Ccw,
        },
        (PlaneMotion::Parabola { dir, p, q }, _) => Path::Parabola {
            to,
            p,
            q: q.to_radians(),
            ccw: dir == Dir::Ccw,
        },
        (_, None) => Path::Line { to },
        (_, Some((centre, ccw))) => Path::Arc { to, centre, ccw },
    }
}

/// The exact curve of a plane move from `from` to `to` (`arc`: an arc's
/// centre and sense); `None` for a conic that cannot be drawn.
fn plane_curve(
    motion: PlaneMotion,
    arc: Option<(V2, bool)>,
    from: V2,
    to: V2,
) -> Option<crate::geom::Curve> {
    use crate::geom::Curve;
    match (motion, arc) {
        (PlaneMotion::Ellipse { dir, a, b, q }, _) => {
            Curve::ellipse(from, to, a, b, q.to_radians(), dir == Dir::Ccw)
        }
        (PlaneMotion::Parabola { dir, p, q }, _) => {
            Curve::parabola(from, to, p, q.to_radians(), dir == Dir::Ccw)
        }
        (_, None) => Some(Curve::line(from, to)),
        (_, Some((centre, ccw))) => Some(Curve::arc(from, to, centre, ccw)),
    }
}

impl Translator {
    /// The axis outside the plane moves to `to` (polar Z; cylinder X, a
    /// diameter) with the joints of the plane standing at C `c`: the plane
    /// ends there, the axis moves as an ordinary move, and the plane
    /// starts again at the same plane point with the new Z (X).
    fn plane_axis(&mut self, map: PlaneMap, rapid: bool, to: f64, c: f64, out: &mut Vec<Command>) {
        let at = self.plane_at;
        self.c_now = c;
        self.plane_off(out);
        let (work, map) = match map {
            PlaneMap::Polar { .. } => (V2::new(self.work.r, to), PlaneMap::Polar { z: to }),
            PlaneMap::Cylinder { radius, .. } => {
                let r = to * 0.5;
                (V2::new(r, self.work.z), PlaneMap::Cylinder { radius, r })
            }
        };
        let kind = if rapid {
            MoveKind::Rapid
        } else {
            MoveKind::Feed(self.feed)
        };
        out.push(self.mv(kind, work, |to, _| Path::Line { to }));
        self.plane_on(map, at, out);
    }
}

/// Geometry + wear of offset `d` (X as a diameter in the tables).
pub fn tool_offset(nc: &nc::Nc, d: u32) -> V2 {
    let (x, z) = nc.tool_offset(d);
    V2::new(x * 0.5, z)
}

/// Reference point n in machine coordinates (1 = machine zero).
pub fn reference_point(m: &Machine, n: u32) -> V2 {
    let r = &m.reference_points;
    match n {
        2 => V2::from_xz(r.second.x, r.second.z),
        3 => V2::from_xz(r.third.x, r.third.z),
        4 => V2::from_xz(r.fourth.x, r.fourth.z),
        _ => V2::ZERO,
    }
}
