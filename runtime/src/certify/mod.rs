//! The motion certificate (`gbvm check`): checks a run's set points period
//! by period against the machine's limits, independently of how the
//! interpolator made them.
//!
//! Fed with the canon events (as a [`Sink`], in program order, ahead of
//! the motion) and with every period's [`SetPoint`], a [`Certifier`]
//! checks:
//!
//! - per axis (X radial, Z, C), from finite differences of the axis set
//!   points in **machine** coordinates (so an origin change is no jump):
//!   velocity within the rapid rate in rapid periods and within the
//!   maximum cutting feed otherwise, acceleration within the axis's limit,
//!   and jerk within its limit where the machine limits jerk (not in or
//!   next to thread periods, which follow the spindle and are never
//!   jerk-limited); all within [`LIMIT_TOL`] of the limit (rounding);
//! - on a machine with soft limits, each axis within its travel, within
//!   [`TRAVEL_MM`];
//! - every end point of the canon's moves reached in order, within
//!   [`END_POINT_MM`], in work coordinates as the canon gives them (at a
//!   corner a thread chain turns at speed, within the period's
//!   discretisation bound of the axes that follow the turn if larger,
//!   [`chain_corner_mm`]); in the plane of polar or cylindrical
//!   interpolation, where the joints the plane's moves leave, with C, in
//!   space (the tool about the spindle's axis, `PlaneEnd`); the move
//!   after the plane starts where its last move left X and Z;
//! - the lead of a thread (travel per spindle turn along the long axis as
//!   the kernel names it, [`nc::thread_room::z_is_long`]) within
//!   [`LEAD_TOL`] of the programmed one (G34: of the lead at that point),
//!   away from the incomplete leads at both ends: the distance the long
//!   axis needs to reach thread speed at the acceleration both axes allow
//!   ([`incomplete_lead`]), and where a chain's corner changes the speed
//!   of the next leg's long axis, the travel in which that axis catches
//!   up with the chain ([`catch_up_lead`]);
//! - G96: while cutting, the spindle at the speed the surface speed asks
//!   at the programmed diameter (clamped by G50 S, the spindle's range and
//!   override), within [`CSS_TOL`], except while the spindle is still
//!   changing speed at its full acceleration;
//! - the spindle within its top speed and its acceleration.
//!
//! It keeps the worst figure of each kind and the first violation. Its
//! state is a few numbers and the queue of end points not reached yet.

mod chain;

use crate::config::{Axis, Config};
use crate::interpolate::{Motion, SetPoint};
use crate::math::{PI, V2};
use crate::polar::PlaneMap;
use alloc::collections::VecDeque;
pub use chain::{
    axis_steps, catch_up_lead, catch_up_time, chain_corner_mm, incomplete_lead, tail_time,
};
use chain::{long_is_z, long_len, per_turn, CatchUp};
use core::fmt;
use nc::event::SpindleDir;
use nc::{Event, Sink};

/// Velocity, acceleration, jerk and spindle limits hold within this share
/// of the limit (1e-6: floating-point rounding, nothing more).
pub const LIMIT_TOL: f64 = 1e-6;
/// An axis stays within its travel (soft limits) within this distance
/// (rounding), mm.
pub const TRAVEL_MM: f64 = 1e-6;
/// A canon end point is reached when the path passes within this distance
/// (the 0.001 mm resolution), mm.
pub const END_POINT_MM: f64 = 0.001;
/// A set point of a straight or circular feed lies within this distance of
/// its canon move (the 0.001 mm resolution: set points lie on the path,
/// only the chord between two of them cuts a corner or an arc), mm.
pub const PATH_MM: f64 = 0.001;
/// How many moves before the one done last, and after the one running,
/// the path check looks at.
const PASSED: usize = 3;
/// The most moves ahead within a period's travel it looks at.
const MAX_AHEAD: usize = 256;
/// An arc of a smaller radius (mm) may run within its chord: see
/// [`Kind::Path`].
pub const MICRO_ARC_MM: f64 = 0.005;
/// The measured lead may differ from the programmed one by this share.
pub const LEAD_TOL: f64 = 1e-4;
/// A G96 spindle speed may differ from its target by this share.
pub const CSS_TOL: f64 = 1e-6;
/// The lead is checked from this much beyond the incomplete-lead length
/// (and one period's travel), a margin for the discrete entry.
pub const ENTRY_MARGIN: f64 = 0.1;

/// What a figure measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Axis velocity.
    Velocity,
    /// Axis acceleration.
    Acceleration,
    /// Axis jerk.
    Jerk,
    /// Axis position against its travel (soft limits): the distance
    /// beyond the nearer limit (negative inside).
    Travel,
    /// A canon end point not reached (distance of the nearest approach).
    EndPoint,
    /// A set point of a feed off its canon line or arc (the distance; an
    /// arc of a radius below [`MICRO_ARC_MM`] may run along its chord), of
    /// a rapid outside the rectangle of its ends, or of a thread outside
    /// the box of the chain's legs around it.
    Path,
    /// Thread lead.
    Lead,
    /// G96 surface speed (the spindle speed against its target).
    SurfaceSpeed,
    /// Spindle speed.
    SpindleSpeed,
    /// Spindle acceleration.
    SpindleAccel,
}

impl Kind {
    /// Every kind, in the order of the summary.
    pub const ALL: [Kind; 10] = [
        Kind::Velocity,
        Kind::Acceleration,
        Kind::Jerk,
        Kind::Travel,
        Kind::EndPoint,
        Kind::Path,
        Kind::Lead,
        Kind::SurfaceSpeed,
        Kind::SpindleSpeed,
        Kind::SpindleAccel,
    ];

    fn index(self) -> usize {
        self as usize
    }

    /// The name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Velocity => "velocity",
            Kind::Acceleration => "acceleration",
            Kind::Jerk => "jerk",
            Kind::Travel => "travel",
            Kind::EndPoint => "end point",
            Kind::Path => "path",
            Kind::Lead => "thread lead",
            Kind::SurfaceSpeed => "surface speed",
            Kind::SpindleSpeed => "spindle speed",
            Kind::SpindleAccel => "spindle acceleration",
        }
    }
}

/// What a figure is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Subject {
    /// The X slide (radial).
    X,
    /// The Z slide.
    Z,
    /// The C axis (degrees).
    C,
    /// The spindle.
    Spindle,
    /// The tool's path.
    Path,
}

impl Subject {
    fn name(self) -> &'static str {
        match self {
            Subject::X => "X",
            Subject::Z => "Z",
            Subject::C => "C",
            Subject::Spindle => "spindle",
            Subject::Path => "path",
        }
    }

    /// The unit of a figure of this kind.
    fn unit(self, kind: Kind) -> &'static str {
        let deg = self == Subject::C;
        match kind {
            Kind::Velocity if deg => "deg/s",
            Kind::Acceleration if deg => "deg/s²",
            Kind::Jerk if deg => "deg/s³",
            Kind::Velocity => "mm/s",
            Kind::Acceleration => "mm/s²",
            Kind::Jerk => "mm/s³",
            Kind::EndPoint | Kind::Path | Kind::Travel => "mm",
            Kind::Lead => "mm/rev",
            Kind::SurfaceSpeed | Kind::SpindleSpeed => "rev/min",
            Kind::SpindleAccel => "rev/min/s",
        }
    }
}

/// One figure at its place: a violation, or the worst of its kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figure {
    /// What it measures.
    pub kind: Kind,
    /// Of which axis (or the spindle, or the path).
    pub subject: Subject,
    /// Time at the end of the period, s.
    pub time_s: f64,
    /// Source file index of the block running (as [`SetPoint::file`]).
    pub file: u16,
    /// Its source line.
    pub line: u32,
    /// The measured value (velocity, acceleration …; for a lead or a G96
    /// speed, the measured lead or rpm).
    pub value: f64,
    /// Its limit (for a lead or a G96 speed: the programmed lead, the
    /// target rpm).
    pub limit: f64,
    /// How far it is from holding: |value| / limit for limits, the
    /// relative (or, for end points, absolute) deviation otherwise.
    pub ratio: f64,
}

impl Figure {
    /// Whether the figure breaks its bound.
    pub fn violates(&self) -> bool {
        match self.kind {
            Kind::EndPoint | Kind::Path => self.ratio > self.limit,
            Kind::Travel => self.ratio > TRAVEL_MM,
            Kind::Lead => self.ratio > LEAD_TOL,
            Kind::SurfaceSpeed => self.ratio > CSS_TOL,
            _ => self.ratio > 1.0 + LIMIT_TOL,
        }
    }
}

impl fmt::Display for Figure {
    /// `at 1.234000 s: Z acceleration 15000.000 mm/s² exceeds its limit 2000.000 mm/s²`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = self.subject.unit(self.kind);
        write!(f, "at {:.6} s: ", self.time_s)?;
        match self.kind {
            // (A full circle's end point the tool never came back to.)
            Kind::EndPoint if self.value.is_infinite() => write!(
                f,
                "a canon end point is not reached: the path does not come back to it (the end of a full circle, where it began)"
            ),
            Kind::EndPoint => write!(
                f,
                "a canon end point is not reached: the path passes {:.4} mm from it at the nearest (tolerance {} mm)",
                self.value, self.limit
            ),
            Kind::Path => write!(
                f,
                "the tool leaves the programmed path by {:.4} mm (tolerance {} mm)",
                self.value, self.limit
            ),
            Kind::Lead => write!(
                f,
                "thread lead {:.6} {unit} where {:.6} is programmed ({:.4} % off, tolerance {} %)",
                self.value,
                self.limit,
                self.ratio * 100.0,
                LEAD_TOL * 100.0
            ),
            Kind::SurfaceSpeed => write!(
                f,
                "G96 spindle speed {:.3} {unit} where the surface speed asks {:.3} ({:.4} % off)",
                self.value,
                self.limit,
                self.ratio * 100.0
            ),
            Kind::Travel => write!(
                f,
                "{} at {:.3} {unit} leaves its travel: the limit is {:.3} {unit}",
                self.subject.name(),
                self.value,
                self.limit
            ),
            _ => write!(
                f,
                "{} {} {:.3} {unit} exceeds its limit {:.3} {unit}",
                self.subject.name(),
                self.kind.name(),
                self.value.abs(),
                self.limit
            ),
        }
    }
}

/// The spindle state the canon set before a move.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SpindleCmd {
    on: bool,
    /// G96 surface speed, m/min (`None` in G97).
    css: Option<f64>,
    /// G50 S (infinite when none).
    clamp: f64,
}

/// A canon move whose end point the path has not reached yet.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pending {
    /// End point, work coordinates (radius, Z).
    end: V2,
    /// Start: the previous end point (`None` when unknown).
    start: Option<V2>,
    /// Lead and lead change of a straight thread.
    thread: Option<(f64, f64)>,
    /// The distance within which the path reaches it: [`END_POINT_MM`],
    /// or at a corner a thread chain turns at speed the bound of
    /// [`chain_corner_mm`].
    tol: f64,
    /// A thread leg that continues its chain at speed: how each axis's
    /// speed (mm per turn, radial X and Z) changes at the corner where
    /// it starts; 0 otherwise.
    enter: V2,
    /// Whether the end point is a corner a thread chain turns at speed.
    corner: bool,
    /// The way to it the tool must keep.
    shape: Shape,
    spindle: SpindleCmd,
    /// The nearest approach so far: distance and place.
    nearest: f64,
    at: (f64, u16, u32),
    /// A full circle ([`comes_back`]) whose end point the tool has not
    /// come back to yet: it starts on it, so there it is not due.
    away: bool,
    /// A move of polar or cylindrical interpolation (`end` its joints X
    /// and Z): the walk holds the tool to its end in space.
    plane: Option<PlaneEnd>,
}

/// Where a move in the plane of polar or cylindrical interpolation leaves
/// the joints, beyond X and Z: as the tool about the spindle's axis,
/// (r cos C, r sin C, Z) in space, the end of each of the plane's moves is
/// a point of its own (in X and Z alone a polar contour passes its end
/// radius many times, a cylinder's C moves none), and the walk holds the
/// tool to them in order; the set points of the plane are held to no move
/// after it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PlaneEnd {
    /// C at the end, degrees.
    c: f64,
    /// X (Z) at the end is not known: the plane started where the tool
    /// came by a way of its own (home) and its moves did not set it; the
    /// walk takes the tool's own.
    free_r: bool,
    free_z: bool,
}

/// Polar or cylindrical interpolation while it is on, as the translator
/// follows it (translate.rs): the map, and where its moves leave the
/// joints X (a radius) and Z, work coordinates (`None`: not known).
#[derive(Debug, Clone, Copy, PartialEq)]
struct PlaneTrack {
    map: PlaneMap,
    r: Option<f64>,
    z: Option<f64>,
    /// C where the plane's last end point stands (`None` before one).
    c: Option<f64>,
}

impl PlaneTrack {
    /// Whether joints at `r`, `z`, `c` are where the last end point left
    /// them: a move that goes nowhere (a `LINE Z=` to the Z the tool
    /// stands at) runs no period, so its end point is not waited for.
    fn stands_at(&self, r: Option<f64>, z: Option<f64>, c: f64) -> bool {
        let same = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-9,
            (None, None) => true,
            _ => false,
        };
        // (C counts in whole turns where the kernel unwinds it, the
        // joints' map does not: the same place.)
        let turn = |d: f64| libm::fabs(d - 360.0 * libm::round(d / 360.0)) <= 1e-9;
        same(self.r, r) && same(self.z, z) && self.c.is_some_and(|p| turn(p - c))
    }
}

/// The way a canon move goes to its end point, as far as the path check
/// holds the tool to it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    /// A straight feed (G01, G31): the segment from the start.
    Line,
    /// A circular feed: the circle about `centre` through the end point,
    /// counter-clockwise (G03) or not.
    Arc { centre: V2, ccw: bool },
    /// A rapid: each axis runs at its own rate (a dog-leg), so the tool
    /// stays within the rectangle of the start and the end.
    Rapid,
    /// A thread leg: its axes follow the chain's corners within their
    /// acceleration, never past the chain's point, so the tool stays
    /// within the box of the legs around it.
    Thread,
    /// Not checked: a conic, a circular thread.
    Free,
}

/// The checker of one run (see the module's text).
#[derive(Debug, Clone)]
pub struct Certifier {
    dt: f64,
    axes: [Option<Axis>; 3],
    jerk: bool,
    spindle: crate::config::SpindleConfig,
    spindle_ovr: f64,
    /// Machine positions (X radius, Z, C) of the last four periods, the
    /// newest last (the axes stood before the first period).
    pos: [[f64; 3]; 4],
    /// The motion of the last three periods, the newest last.
    motion: [Motion; 3],
    prev: Option<SetPoint>,
    prev_rpm: f64,
    /// The move whose end point was reached last.
    done: Option<Pending>,
    /// The moves whose end points were reached before it, the newest
    /// first: end points of µm moves within the tolerance of the tool
    /// count at once, ahead of it, and the path check still finds the
    /// tool on them.
    passed: [Option<Pending>; PASSED],
    /// The axes' catch-ups still open in a thread chain (radial X, Z).
    catch_up: [CatchUp; 2],
    pending: VecDeque<Pending>,
    last_end: Option<V2>,
    /// The work zero the canon printed last (machine coordinates).
    origin: Option<V2>,
    /// Polar or cylindrical interpolation while it is on.
    plane: Option<PlaneTrack>,
    /// The last event was a thread move: a thread move now continues its
    /// chain (the runtime runs them on without a stop).
    chain_open: bool,
    cmd: SpindleCmd,
    periods: u64,
    end_points: u64,
    reached: u64,
    lead_periods: u64,
    /// Periods whose set point was held to its canon move.
    path_periods: u64,
    css_periods: u64,
    worst: [Option<Figure>; Kind::ALL.len()],
    first: Option<Figure>,
}

impl Certifier {
    /// A certifier for a run with settings `cfg` whose axes start at
    /// machine X `axis_x` (a diameter), Z `axis_z` and C `c` (degrees).
    pub fn new(cfg: &Config, axis_x: f64, axis_z: f64, c: f64) -> Certifier {
        let start = [axis_x * 0.5, axis_z, c];
        Certifier {
            dt: cfg.period_s,
            axes: [Some(cfg.x), Some(cfg.z), cfg.c],
            jerk: cfg.jerk_limited,
            spindle: cfg.spindle,
            spindle_ovr: cfg.spindle_override_pct / 100.0,
            pos: [start; 4],
            motion: [Motion::None; 3],
            prev: None,
            prev_rpm: 0.0,
            done: None,
            passed: [None; PASSED],
            catch_up: [CatchUp::NONE; 2],
            pending: VecDeque::new(),
            last_end: None,
            origin: None,
            plane: None,
            chain_open: false,
            cmd: SpindleCmd {
                on: false,
                css: None,
                clamp: f64::INFINITY,
            },
            periods: 0,
            end_points: 0,
            reached: 0,
            lead_periods: 0,
            path_periods: 0,
            css_periods: 0,
            worst: [None; Kind::ALL.len()],
            first: None,
        }
    }

    /// The first violation, if any.
    pub fn violation(&self) -> Option<&Figure> {
        self.first.as_ref()
    }

    /// The worst figure of a kind so far (`None`: nothing measured).
    pub fn worst(&self, kind: Kind) -> Option<&Figure> {
        self.worst[kind.index()].as_ref()
    }

    /// Periods checked.
    pub fn periods(&self) -> u64 {
        self.periods
    }

    fn note(&mut self, fig: Figure) {
        let w = &mut self.worst[fig.kind.index()];
        if w.is_none_or(|w| fig.ratio > w.ratio) {
            *w = Some(fig);
        }
        if self.first.is_none() && fig.violates() {
            self.first = Some(fig);
        }
    }

    /// Checks one period.
    pub fn period(&mut self, p: &SetPoint) {
        self.periods += 1;
        self.pos.copy_within(1.., 0);
        self.pos[3] = [p.axis_x * 0.5, p.axis_z, p.c.unwrap_or(0.0)];
        self.motion.copy_within(1.., 0);
        self.motion[2] = p.motion;
        self.axis_limits(p);
        self.spindle_limits(p);
        let prev = self.prev.unwrap_or(SetPoint {
            // Before the first period: at the start, the same work shift.
            x: p.x - (self.pos[3][0] - self.pos[2][0]) * 2.0,
            z: p.z - (self.pos[3][1] - self.pos[2][1]),
            axis_x: self.pos[2][0] * 2.0,
            axis_z: self.pos[2][1],
            ..*p
        });
        // The move running: the one whose end point is next, unless the
        // path is still at the end point reached last (reached within
        // its tolerance, that move may have a step to go).
        let here = V2::from_xz(p.x, p.z);
        let running = match self.done {
            Some(d) if (d.end - here).norm() <= END_POINT_MM => Some(d),
            _ => self.pending.front().copied(),
        };
        if let Some(m) = running {
            self.thread_lead(&prev, p, &m);
            self.surface_speed(&prev, p, &m);
        }
        self.on_path(&prev, p);
        self.end_points(&prev, p);
        self.prev_rpm = p.spindle_rpm;
        self.prev = Some(*p);
    }

    /// Velocity, acceleration and jerk of X, Z and C.
    fn axis_limits(&mut self, p: &SetPoint) {
        let (dt, [p0, p1, p2, p3]) = (self.dt, self.pos);
        let subjects = [Subject::X, Subject::Z, Subject::C];
        for (i, ax) in self.axes.into_iter().enumerate() {
            let Some(ax) = ax else { continue };
            let at = |kind, value: f64, limit: f64| Figure {
                kind,
                subject: subjects[i],
                time_s: p.time_s,
                file: p.file,
                line: p.line,
                value,
                limit,
                ratio: value.abs() / limit,
            };
            let vlim = if p.motion == Motion::Rapid {
                ax.rapid
            } else {
                ax.max_feed
            };
            if ax.soft_limits {
                self.note(travel(at(Kind::Travel, p3[i], 0.0), ax, i == 0));
            }
            self.note(at(Kind::Velocity, (p3[i] - p2[i]) / dt, vlim));
            let a = (p3[i] - 2.0 * p2[i] + p1[i]) / (dt * dt);
            self.note(at(Kind::Acceleration, a, ax.accel));
            let thread = self.motion.contains(&Motion::Thread);
            if self.jerk && !thread {
                let j = (p3[i] - 3.0 * p2[i] + 3.0 * p1[i] - p0[i]) / (dt * dt * dt);
                self.note(at(Kind::Jerk, j, ax.jerk));
            }
        }
    }

    fn spindle_limits(&mut self, p: &SetPoint) {
        let at = |kind, value: f64, limit: f64| Figure {
            kind,
            subject: Subject::Spindle,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value,
            limit,
            ratio: value.abs() / limit,
        };
        let top = self.spindle.max_rpm;
        let accel = self.spindle.accel_rpm_s;
        self.note(at(Kind::SpindleSpeed, p.spindle_rpm, top));
        let a = (p.spindle_rpm - self.prev_rpm) / self.dt;
        self.note(at(Kind::SpindleAccel, a, accel));
    }

    /// The lead of a thread period, away from the incomplete leads.
    fn thread_lead(&mut self, prev: &SetPoint, p: &SetPoint, m: &Pending) {
        let (Some((lead, dlead)), Some(start), Motion::Thread) = (m.thread, m.start, p.motion)
        else {
            return;
        };
        let turns = p.spindle_turns - prev.spindle_turns;
        if turns <= 1e-9 {
            return;
        }
        let d = m.end - start;
        let long_z = long_is_z(d);
        let long = |v: V2| if long_z { v.z } else { v.r };
        let (a, b) = (V2::from_xz(prev.x, prev.z), V2::from_xz(p.x, p.z));
        let q0 = (long(a) - long(start)).abs();
        let q1 = (long(b) - long(start)).abs();
        let rest = (long(m.end) - long(b)).abs();
        let want = if dlead == 0.0 {
            lead
        } else {
            libm::sqrt((lead * lead + dlead * (q0 + q1)).max(0.0))
        };
        let v = want * p.spindle_rpm.abs() / 60.0;
        let [ax, az, _] = self.axes;
        let (Some(ax), Some(az)) = (ax, az) else {
            return;
        };
        let (la, sa) = if long_z { (az, ax) } else { (ax, az) };
        let short = if long_z { d.r } else { d.z };
        let room = incomplete_lead(v, la.accel, sa.accel, long(d), short) * (1.0 + ENTRY_MARGIN)
            + v * self.dt;
        if q0 < room || rest < room {
            return;
        }
        let catching_up = v * self.catch_up[usize::from(long_z)].lead_s;
        if q0 < catching_up * (1.0 + ENTRY_MARGIN) + 2.0 * v * self.dt {
            return;
        }
        self.lead_periods += 1;
        let got = (long(b) - long(a)).abs() / turns;
        self.note(Figure {
            kind: Kind::Lead,
            subject: Subject::Path,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value: got,
            limit: want,
            ratio: (got - want).abs() / want,
        });
    }

    /// G96 while cutting: the spindle at the surface speed's target.
    fn surface_speed(&mut self, prev: &SetPoint, p: &SetPoint, m: &Pending) {
        let (Some(vc), true, Motion::Feed | Motion::Arc) = (m.spindle.css, m.spindle.on, p.motion)
        else {
            return;
        };
        // The spindle of a period follows the diameter it began at.
        let d = prev.x.abs();
        let lim = m.spindle.clamp.min(self.spindle.max_rpm);
        let n = if d < 1e-9 {
            lim
        } else {
            (1000.0 * vc / (PI * d) * self.spindle_ovr).min(lim)
        };
        let target = if n > 0.0 {
            n.max(self.spindle.min_rpm)
        } else {
            return;
        };
        let rpm = p.spindle_rpm.abs();
        let step = (p.spindle_rpm - prev.spindle_rpm).abs();
        if step >= self.spindle.accel_rpm_s * self.dt * (1.0 - 1e-9) {
            return; // still changing speed at full acceleration
        }
        self.css_periods += 1;
        self.note(Figure {
            kind: Kind::SurfaceSpeed,
            subject: Subject::Spindle,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value: rpm,
            limit: target,
            ratio: (rpm - target).abs() / target,
        });
    }

    /// End point `m` is reached (or passed by): the move is done.
    fn reach(&mut self, m: Pending) {
        if let Some(d) = self.done {
            self.passed.rotate_right(1);
            self.passed[0] = Some(d);
        }
        self.done = Some(m);
    }

    /// A straight or circular feed's set point on its canon move, a
    /// rapid's within its rectangle: on the move whose end point is next,
    /// or on one of the [`PASSED`] moves before or after it. (Set points lie on
    /// the path; only the chord between two of them cuts a corner or an
    /// arc.) Not in a period whose work frame changed, nor for a move not
    /// checked ([`Shape::Free`]).
    fn on_path(&mut self, prev: &SetPoint, p: &SetPoint) {
        if !frame_kept(prev, p) {
            return;
        }
        let rapid = match p.motion {
            Motion::Feed | Motion::Arc => false,
            Motion::Rapid => true,
            Motion::Thread => return self.in_chain(prev, p),
            _ => return,
        };
        let here = V2::from_xz(p.x, p.z);
        let kind = |m: &Pending| (m.shape == Shape::Rapid) == rapid;
        // The move running must be one of the period's kind and known
        // (not one that starts where the tool came home, say).
        let front = self.pending.front().copied().filter(kind);
        let Some(on_front) = front.and_then(|m| off_shape(&m, here)) else {
            return;
        };
        // (A period may pass the end points of many µm moves before the
        // walk counts them: the moves ahead within the period's travel
        // count, at least PASSED of them; and the walk may count some
        // ahead of the tool.)
        let travel = (here - V2::from_xz(prev.x, prev.z)).norm() + PATH_MM;
        let mut run = 0.0;
        let ahead = self.pending.iter().skip(1).take(MAX_AHEAD).take_while(|m| {
            let counted = run <= travel;
            run += m.start.map_or(f64::INFINITY, |a| (m.end - a).norm());
            counted
        });
        let d = ahead
            .copied()
            .chain(self.pending.iter().skip(1).take(PASSED).copied())
            .chain(self.done)
            .chain(self.passed.iter().flatten().copied())
            .filter(|m| kind(m))
            .filter_map(|m| off_shape(&m, here))
            .fold(on_front, f64::min);
        self.path_periods += 1;
        self.note(Figure {
            kind: Kind::Path,
            subject: Subject::Path,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value: d,
            limit: PATH_MM,
            ratio: d,
        });
    }

    /// A thread period's set point within the box of the chain's legs
    /// around it: the legs done before the one running ([`PASSED`] of
    /// them), that one, and those ahead within the period's travel and
    /// the farthest an axis may lag behind the chain's point (v²/2a at
    /// its top speed). Each axis runs between where it was and the
    /// chain's point, so a set point outside that box ran past the chain
    /// (the root of a thread, a corner). Only while a thread leg of known
    /// start runs.
    fn in_chain(&mut self, prev: &SetPoint, p: &SetPoint) {
        let thread = |m: &&Pending| m.shape == Shape::Thread;
        let Some((front, start)) = self
            .pending
            .front()
            .filter(thread)
            .and_then(|m| Some((m, m.start?)))
        else {
            return;
        };
        let here = V2::from_xz(p.x, p.z);
        let lag = |a: &Option<Axis>| a.map_or(0.0, |a| a.max_feed * a.max_feed / (2.0 * a.accel));
        let reach = (here - V2::from_xz(prev.x, prev.z)).norm()
            + lag(&self.axes[0]).max(lag(&self.axes[1]));
        let (mut lo, mut hi) = (start, start);
        let mut widen = |m: &Pending| {
            for q in m.start.into_iter().chain([m.end]) {
                lo = V2::new(lo.r.min(q.r), lo.z.min(q.z));
                hi = V2::new(hi.r.max(q.r), hi.z.max(q.z));
            }
        };
        widen(front);
        let mut run = 0.0;
        for m in self.pending.iter().skip(1).take(MAX_AHEAD).filter(thread) {
            if run > reach {
                break;
            }
            widen(m);
            run += m.start.map_or(f64::INFINITY, |a| (m.end - a).norm());
        }
        for m in self
            .done
            .iter()
            .chain(self.passed.iter().flatten())
            .filter(thread)
        {
            widen(m);
        }
        let out = |v: f64, a: f64, b: f64| (a - v).max(v - b).max(0.0);
        let d = libm::hypot(out(here.r, lo.r, hi.r), out(here.z, lo.z, hi.z));
        self.path_periods += 1;
        self.note(Figure {
            kind: Kind::Path,
            subject: Subject::Path,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value: d,
            limit: PATH_MM,
            ratio: d,
        });
    }

    /// Pops the end points this period's path reached, in order. One
    /// that the path cut by (it came within a period's travel of it and
    /// moves away) is a violation at its nearest approach, and the walk
    /// goes on from the next, so that one miss does not hide the rest.
    fn end_points(&mut self, prev: &SetPoint, p: &SetPoint) {
        let step = Step::new(prev, p);
        // Where the walk stands on the step (a share of it, 0 at its
        // start): the next end point is reached after the last one (a
        // short move back may end within the tolerance of where this step
        // began).
        let mut from = 0.0;
        let mut first = true;
        while let Some(mut m) = self.pending.front().copied() {
            let way = step.way(&m);
            if m.away {
                if !way.returns(from, m.tol) {
                    self.waiting(p);
                    break;
                }
                m.away = false;
                if let Some(f) = self.pending.front_mut() {
                    f.away = false;
                }
            }
            // After an end point reached in this step, the next is due in
            // it only where the rest of the step runs past it. One the
            // step ends on or short of may be a µm move's the tool runs
            // after the ones it still has to run (it stands within a µm
            // of several): judged now, the tool going on to those would
            // look like leaving it, a miss.
            if !first && way.joined() {
                let t = way.param(from);
                if !(t > 0.0 && t < 1.0) {
                    break;
                }
            }
            m.tol = self.tol_of(&m, p.spindle_rpm);
            let d = way.dist(from);
            // The step ends where it is nearest to the end point: the tool
            // may still get nearer, and the end points after it are not
            // due yet (points a µm apart lie within the tolerance of one
            // step together).
            let closing = way.joined() && d > 0.0 && way.param(from) >= 1.0;
            if closing {
                self.nearer(d, p);
                break;
            }
            if d <= m.tol || m.nearest <= m.tol {
                if way.joined() {
                    from += (1.0 - from) * way.param(from).clamp(0.0, 1.0);
                }
                first = false;
                self.reached += 1;
                self.passed(m, p.spindle_rpm);
                continue;
            }
            // The period's travel is the axes' step: where the frame
            // jumped, b − a is the jump, not a way the tool went.
            if d > m.nearest && m.nearest <= way.travel {
                self.missed(&m);
                self.passed(m, p.spindle_rpm);
                continue;
            }
            self.nearer(d, p);
            break;
        }
    }

    /// The next end point is a full circle's, and the tool has not come
    /// back to it: where the walk began to wait, the place a miss is
    /// reported at if it never comes back.
    fn waiting(&mut self, p: &SetPoint) {
        if let Some(f) = self.pending.front_mut() {
            if f.at.0 == 0.0 {
                f.at = (p.time_s, p.file, p.line);
            }
        }
    }

    /// The next end point is `d` from this period's step: its nearest
    /// approach so far?
    fn nearer(&mut self, d: f64, p: &SetPoint) {
        if let Some(f) = self.pending.front_mut() {
            if d < f.nearest {
                f.nearest = d;
                f.at = (p.time_s, p.file, p.line);
            }
        }
    }

    /// The walk leaves end point `m`, the next pending, reached or missed.
    fn passed(&mut self, m: Pending, rpm: f64) {
        self.reach(m);
        self.pending.pop_front();
        self.turned(&m, rpm);
    }

    /// The distance within which the path reaches end point `m` with the
    /// spindle at `rpm`: its own ([`END_POINT_MM`], [`chain_corner_mm`]),
    /// and at a corner of a thread chain that the chain reaches before an
    /// axis has caught up with the corners before it ([`CatchUp`]), that
    /// axis's lag too: at most c²/2a for steps c in its speed (the lag it
    /// builds while reaching its new speed).
    fn tol_of(&self, m: &Pending, rpm: f64) -> f64 {
        let Some(leg_s) = leg_time(m, rpm).filter(|_| m.corner) else {
            return m.tol;
        };
        let stops = self.stops_at(m, rpm);
        let mut lag2 = 0.0;
        for ((axis, up), stop) in self.axes.iter().zip(&self.catch_up).zip(stops) {
            // (The margin of the lead's check: the follower is discrete.)
            let open = up.lag_s * (1.0 + ENTRY_MARGIN) + 2.0 * self.dt > leg_s;
            if let (Some(ax), true) = (axis, open || stop > 0.0) {
                let c = if open { up.c + stop } else { stop };
                let lag = c * c / (2.0 * ax.accel);
                lag2 += lag * lag;
            }
        }
        m.tol + libm::sqrt(lag2)
    }

    /// The speed (mm/s, radial X and Z) each axis sheds running into the
    /// corner at the end of leg `m`, where the chain stops, turns or slows
    /// it there or within its stopping distance after: the follower slows
    /// it ahead so as never to pass the chain's point, at most down to
    /// where it would pass each such corner no faster than the chain runs
    /// on from there, and the corner is cut by up to the lag that builds,
    /// at most Δv²/2a.
    fn stops_at(&self, m: &Pending, rpm: f64) -> [f64; 2] {
        let (Some((lead, _)), Some(start)) = (m.thread, m.start) else {
            return [0.0; 2];
        };
        let rps = rpm.abs() / 60.0;
        let u = per_turn(m.end - start, lead);
        let later = || self.pending.iter().skip_while(|p| p.end != m.end).skip(1);
        [0, 1].map(|i| {
            let along = |d: V2| if i == 0 { d.r } else { d.z };
            let (Some(ax), dir) = (self.axes[i], along(u)) else {
                return 0.0;
            };
            let (v, a) = (dir.abs() * rps, ax.accel);
            // The fastest the axis may pass m's end, and how far on the
            // axis the leg after it starts from there.
            let (mut here, mut dist, mut on) = (v, 0.0, m.corner);
            for n in later() {
                let (Some((next_lead, _)), Some(from), true) = (n.thread, n.start, on) else {
                    break;
                };
                let w = along(per_turn(n.end - from, next_lead));
                let run_on = if w * dir > 0.0 { w.abs() * rps } else { 0.0 };
                here = here.min(libm::sqrt(run_on * run_on + 2.0 * a * dist));
                if run_on == 0.0 || 2.0 * a * dist > v * v {
                    break;
                }
                (dist, on) = (dist + along(n.end - from).abs(), n.corner);
            }
            (v - here).max(0.0)
        })
    }

    /// The chain turned from leg `m` into the next pending one (or `m`
    /// ended a move off a chain): the catch-ups still open lose the leg's
    /// time, and the corner adds its own steps in the axes' speeds.
    fn turned(&mut self, m: &Pending, rpm: f64) {
        let next = self.pending.front().copied();
        let (Some(leg_s), Some(n)) = (leg_time(m, rpm).filter(|_| m.corner), next) else {
            self.catch_up = [CatchUp::NONE; 2];
            return;
        };
        let (Some((lead, _)), Some(start)) = (n.thread, n.start) else {
            self.catch_up = [CatchUp::NONE; 2];
            return;
        };
        let rps = rpm.abs() / 60.0;
        let u = per_turn(n.end - start, lead);
        let steps = [(n.enter.r, u.r), (n.enter.z, u.z)];
        let runs = [self.axis_run(0), self.axis_run(1)];
        for (i, (du, ui)) in steps.into_iter().enumerate() {
            let up = &mut self.catch_up[i];
            up.lead_s = (up.lead_s - leg_s).max(0.0);
            up.lag_s = (up.lag_s - leg_s).max(0.0);
            if up.lag_s == 0.0 {
                up.c = 0.0;
            }
            let Some(ax) = self.axes[i].filter(|_| du != 0.0) else {
                continue;
            };
            // Faster in the leg's direction on this axis, or slower.
            let w0 = if ui != 0.0 {
                du * ui.signum()
            } else {
                -du.abs()
            } * rps;
            up.add(&ax, ui.abs() * rps, w0, runs[i]);
        }
    }

    /// How far the chain runs on axis `i` (0: radial X, 1: Z) from the
    /// start of the next pending move in the direction it moves there, up
    /// to where that axis stops or turns, or the chain queued so far ends.
    fn axis_run(&self, i: usize) -> f64 {
        let along = |d: V2| if i == 0 { d.r } else { d.z };
        let (mut run, mut dir) = (0.0, 0.0);
        for m in &self.pending {
            let (Some(_), Some(start)) = (m.thread, m.start) else {
                break;
            };
            let d = along(m.end - start);
            if d == 0.0 || d * dir < 0.0 {
                break;
            }
            (run, dir) = (run + d.abs(), d);
            if !m.corner {
                break;
            }
        }
        run
    }

    fn missed(&mut self, m: &Pending) {
        let (time_s, file, line) = m.at;
        self.note(Figure {
            kind: Kind::EndPoint,
            subject: Subject::Path,
            time_s,
            file,
            line,
            value: m.nearest,
            limit: m.tol,
            ratio: m.nearest,
        });
    }

    /// Ends the run: `ended` when the program ran to its end (else the
    /// end points still ahead are not owed).
    pub fn finish(&mut self, ended: bool) {
        if !ended {
            return;
        }
        if let Some(mut m) = self.pending.front().copied() {
            m.tol = self.tol_of(&m, self.prev_rpm);
            if m.nearest <= m.tol {
                // The tool stands where it came within the tolerance.
                self.reached += 1;
                self.pending.pop_front();
            } else {
                self.missed(&m);
            }
        }
    }

    fn push_move(&mut self, x: f64, z: f64, thread: Option<(f64, f64)>, shape: Shape) {
        let end = V2::from_xz(x, z);
        self.end_points += 1;
        let mut enter = V2::ZERO;
        // A thread move that continues a chain: the corner where the
        // previous one ends is taken at thread speed.
        if let (true, Some(out), Some(start)) = (self.chain_open, thread, self.last_end) {
            let ax = self.axes[0].map_or(0.0, |a| a.accel);
            let az = self.axes[1].map_or(0.0, |a| a.accel);
            let dt = self.dt;
            if let Some(prev) = self.pending.back_mut() {
                if let (Some(inc), Some(from)) = (prev.thread, prev.start) {
                    let legs = [(prev.end - from, inc), (end - start, out)];
                    prev.tol = END_POINT_MM.max(chain_corner_mm(legs, [ax, az], dt));
                    prev.corner = true;
                    enter = axis_steps(legs);
                }
            }
            self.widen_before_corner();
        }
        self.pending.push_back(Pending {
            end,
            start: self.last_end,
            thread,
            tol: END_POINT_MM,
            enter,
            corner: false,
            shape,
            spindle: self.cmd,
            nearest: f64::INFINITY,
            at: (0.0, 0, 0),
            plane: None,
            away: comes_back(self.last_end, end, shape),
        });
        self.last_end = Some(end);
    }

    /// A move of the plane ends with the joints at X (a radius) `r`, Z
    /// `z` (`None`: not known) and C `c`: not held to a way (as
    /// [`Shape::Free`]), its end held in space ([`PlaneEnd`]). The next
    /// move starts there where X and Z are known.
    fn push_plane(&mut self, r: Option<f64>, z: Option<f64>, c: f64) {
        self.end_points += 1;
        self.pending.push_back(Pending {
            end: V2::new(r.unwrap_or(0.0), z.unwrap_or(0.0)),
            start: self.last_end,
            thread: None,
            tol: END_POINT_MM,
            enter: V2::ZERO,
            corner: false,
            shape: Shape::Free,
            spindle: self.cmd,
            nearest: f64::INFINITY,
            at: (0.0, 0, 0),
            plane: Some(PlaneEnd {
                c,
                free_r: r.is_none(),
                free_z: z.is_none(),
            }),
            away: false,
        });
        self.last_end = r.zip(z).map(|(r, z)| V2::new(r, z));
    }

    /// Polar or cylindrical interpolation starts with `map` where the last
    /// move ended (the plane's start moves no joint).
    fn plane_on(&mut self, map: PlaneMap) {
        self.plane = Some(PlaneTrack {
            map,
            r: self.last_end.map(|e| e.r),
            z: self.last_end.map(|e| e.z),
            c: None,
        });
    }

    /// A move in the plane to its point (`a`, `b`) as the canon prints it
    /// (polar X a diameter and C mm, cylinder Z and C degrees); `off`:
    /// where it takes the axis outside the plane along (polar Z, cylinder
    /// X a diameter). The joints as the translator turns the plane point
    /// into them ([`PlaneMap::joints`]).
    fn plane_move(&mut self, a: f64, b: f64, off: Option<f64>) {
        let Some(mut t) = self.plane else {
            return;
        };
        let (w, c) = t.map.joints(t.map.point(a, b));
        match t.map {
            PlaneMap::Polar { .. } => {
                t.r = Some(w.r);
                t.z = off.or(t.z);
            }
            PlaneMap::Cylinder { .. } => {
                t.r = off.map(|x| x * 0.5).or(t.r);
                t.z = Some(w.z);
            }
        }
        self.plane_end(t, c);
    }

    /// The plane's joints after a move, with C at `c`: an end point to
    /// reach, unless the move went nowhere.
    fn plane_end(&mut self, mut t: PlaneTrack, c: f64) {
        let moved = self
            .plane
            .is_none_or(|before| !before.stands_at(t.r, t.z, c));
        t.c = Some(c);
        self.plane = Some(t);
        if moved {
            self.push_plane(t.r, t.z, c);
        }
    }

    /// The axis outside the plane moves alone to `to` (polar Z, cylinder
    /// X a diameter), the joints of the plane standing at C `c`.
    fn plane_axis(&mut self, to: f64, c: f64) {
        let Some(mut t) = self.plane else {
            return;
        };
        match t.map {
            PlaneMap::Polar { .. } => t.z = Some(to),
            PlaneMap::Cylinder { .. } => t.r = Some(to * 0.5),
        }
        self.plane_end(t, c);
    }

    /// The plane ends (`POLAR MODE=OFF` gives X, a diameter, as the
    /// joints stand): the next move starts where its moves left X and Z,
    /// not where the plane started.
    fn plane_off(&mut self, x: Option<f64>) {
        let Some(mut t) = self.plane.take() else {
            return;
        };
        if let Some(x) = x {
            t.r = Some(x * 0.5);
        }
        self.last_end = t.r.zip(t.z).map(|(r, z)| V2::new(r, z));
    }

    /// The end points of the thread legs that end less than a period's
    /// travel before the corner the last pending leg ends at (legs of a
    /// few µm): the chain may pass them and the corner in one period, so
    /// that period's chord is bent by the corner as much as the corner's
    /// own; they take its tolerance.
    fn widen_before_corner(&mut self) {
        let top = |a: &Option<Axis>| a.map_or(0.0, |a| a.max_feed);
        let reach = libm::hypot(top(&self.axes[0]), top(&self.axes[1])) * self.dt;
        let mut legs = self.pending.iter_mut().rev();
        let Some(corner) = legs.next().filter(|m| m.corner) else {
            return;
        };
        let (tol, mut run) = (
            corner.tol,
            corner
                .start
                .map_or(f64::INFINITY, |a| (corner.end - a).norm()),
        );
        for m in legs {
            let Some(start) = m.start.filter(|_| m.thread.is_some() && run <= reach) else {
                break;
            };
            m.tol = m.tol.max(tol);
            run += (m.end - start).norm();
        }
    }

    /// The one-line summary: the worst figure of each kind.
    pub fn summary(&self) -> Summary<'_> {
        Summary(self)
    }
}

/// Whether the work frame stayed the same over the period from `prev` to
/// `p`: the work point moved as the axes did.
fn frame_kept(prev: &SetPoint, p: &SetPoint) -> bool {
    let moved = V2::new((p.axis_x - prev.axis_x) * 0.5, p.axis_z - prev.axis_z);
    let step = V2::from_xz(p.x, p.z) - V2::from_xz(prev.x, prev.z);
    (step - moved).norm() <= 1e-9
}

/// How far `p` lies off the way of move `m` (`None`: not checked, or its
/// start is unknown). An arc counts its whole circle (a set point on the
/// circle but off the arc lies far from the moves before and after, whose
/// end points the walk holds the tool to).
fn off_shape(m: &Pending, p: V2) -> Option<f64> {
    match m.shape {
        Shape::Line => Some(seg_dist(p, m.start?, m.end)),
        Shape::Arc { centre, .. } => {
            let r = (m.end - centre).norm();
            let off = ((p - centre).norm() - r).abs();
            // An arc of a radius below the resolution runs as its chord
            // (planner.rs); one of a few µm, whose centre the canon
            // rounds to 0.1 µm, is held to its chord too, which lies
            // within its radius of it.
            Some(match m.start {
                Some(a) if r < MICRO_ARC_MM => off.min(seg_dist(p, a, m.end)),
                _ => off,
            })
        }
        Shape::Rapid => {
            let a = m.start?;
            let out = |v: f64, a: f64, b: f64| (a.min(b) - v).max(v - a.max(b)).max(0.0);
            Some(libm::hypot(out(p.r, a.r, m.end.r), out(p.z, a.z, m.end.z)))
        }
        // (Threads: `Certifier::in_chain`.)
        Shape::Thread | Shape::Free => None,
    }
}

/// Whether a move from `start` to `end` of `shape` leaves its end point
/// and comes back to it: a full circle, whose end is its start (as the
/// runtime takes an arc whose ends are within 1e-9 mm, geom.rs), or an
/// arc that ends within the tolerance of its start the long way round.
/// The walk must not count its end point where the circle begins. Only
/// from a radius of [`MICRO_ARC_MM`]: a smaller arc may run as its chord
/// (and jerk limiting's averaging shrinks it), so the tool need not leave.
fn comes_back(start: Option<V2>, end: V2, shape: Shape) -> bool {
    let (Some(a), Shape::Arc { centre, ccw }) = (start, shape) else {
        return false;
    };
    let (u, v) = (a - centre, end - centre);
    if (end - a).norm() > END_POINT_MM || u.norm() < MICRO_ARC_MM {
        return false;
    }
    // The turn from u to v the arc's way, in [0, 2π) (geom.rs `arc`).
    let ang = libm::atan2(u.z * v.r - u.r * v.z, u.dot(v));
    let sweep = crate::math::rem_euclid(if ccw { ang } else { -ang }, 2.0 * PI);
    (end - a).norm() < 1e-9 || sweep > PI
}

/// The time a thread leg takes at `rpm` (its long-axis travel at lead
/// × speed); `None` off a thread or with the spindle standing.
fn leg_time(m: &Pending, rpm: f64) -> Option<f64> {
    let (Some((lead, _)), Some(start)) = (m.thread, m.start) else {
        return None;
    };
    let v = lead * rpm.abs() / 60.0;
    (v > 0.0).then(|| long_len(m.end - start) / v)
}

/// One period's step of the work point, for the end points' walk.
struct Step {
    a: V2,
    b: V2,
    /// The axes' own step (X on the diameter halved).
    moved: V2,
    /// The work point moved as the axes did: no work shift changed.
    joined: bool,
    /// The step's ends in space ([`space`]), for the moves of a plane.
    a3: P3,
    b3: P3,
}

impl Step {
    fn new(prev: &SetPoint, p: &SetPoint) -> Step {
        let (a, b) = (V2::from_xz(prev.x, prev.z), V2::from_xz(p.x, p.z));
        let moved = V2::new((p.axis_x - prev.axis_x) * 0.5, p.axis_z - prev.axis_z);
        let joined = ((b - a) - moved).norm() <= 1e-9;
        Step {
            a,
            b,
            moved,
            joined,
            a3: space(a.r, a.z, prev.c.unwrap_or(0.0)),
            b3: space(b.r, b.z, p.c.unwrap_or(0.0)),
        }
    }

    /// The step as the walk holds it to the end point of `m`: in work X
    /// (a radius) and Z, or for a move of a plane in space. Where the
    /// work shift changed (G50, G54…, a tool offset) the work point
    /// jumped: the period's path is the axes' step in the old frame
    /// before the jump, or in the new one after it (no shift changes in a
    /// plane).
    fn way(&self, m: &Pending) -> Way {
        let flat = |v: V2| [v.r, v.z, 0.0];
        let Some(pe) = m.plane else {
            let (a, b, e, moved) = (self.a, self.b, m.end, self.moved);
            return Way {
                a: flat(a),
                b: flat(b),
                e: flat(e),
                travel: moved.norm(),
                split: (!self.joined)
                    .then(|| seg_dist(e, a, a + moved).min(seg_dist(e, b - moved, b))),
            };
        };
        // (Where the plane's end is not known in X or Z: the tool's own.)
        let r = if pe.free_r { self.b.r } else { m.end.r };
        let z = if pe.free_z { self.b.z } else { m.end.z };
        Way {
            a: self.a3,
            b: self.b3,
            e: space(r, z, pe.c),
            travel: norm3(sub3(self.b3, self.a3)),
            split: None,
        }
    }
}

/// A point in the walk's space: work X (a radius), Z and 0 off a plane,
/// (r cos C, r sin C, Z) in one ([`space`]).
type P3 = [f64; 3];

/// The tool at work X radius `r`, Z `z` and C `c` (degrees) as a point in
/// space about the spindle's axis.
fn space(r: f64, z: f64, c: f64) -> P3 {
    let (sin, cos) = crate::math::sin_cos(c.to_radians());
    [r * cos, r * sin, z]
}

fn sub3(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm3(a: P3) -> f64 {
    libm::sqrt(dot3(a, a))
}

/// One period's step and one end point `e`, in the walk's space for it
/// ([`Step::way`]).
struct Way {
    a: P3,
    b: P3,
    e: P3,
    /// The axes' travel in the period.
    travel: f64,
    /// Where the work frame jumped: the distance of the end point from
    /// the step's two pieces.
    split: Option<f64>,
}

impl Way {
    fn joined(&self) -> bool {
        self.split.is_none()
    }

    /// The point at share `s` of the step.
    fn at(&self, s: f64) -> P3 {
        let d = sub3(self.b, self.a);
        [
            self.a[0] + d[0] * s,
            self.a[1] + d[1] * s,
            self.a[2] + d[2] * s,
        ]
    }

    /// Where the end point projects on the rest of the step from share
    /// `from` on: 0 there, 1 at the step's end (0 when it is empty).
    fn param(&self, from: f64) -> f64 {
        let a = self.at(from);
        let d = sub3(self.b, a);
        let len2 = dot3(d, d);
        if len2 > 0.0 {
            dot3(sub3(self.e, a), d) / len2
        } else {
            0.0
        }
    }

    /// Whether the rest of the step from share `from` comes back to the
    /// end point from away: it ends more than `tol` from it and nearer to
    /// it than it began (a full circle's distance from its end grows
    /// until the far side, then shrinks). Not across a frame jump.
    fn returns(&self, from: f64, tol: f64) -> bool {
        let began = norm3(sub3(self.e, self.at(from)));
        let ends = norm3(sub3(self.e, self.b));
        self.joined() && ends > tol && ends < began
    }

    /// How far the end point is from the step's path from share `from`
    /// on.
    fn dist(&self, from: f64) -> f64 {
        if let Some(d) = self.split {
            return d;
        }
        let s = from + (1.0 - from) * self.param(from).clamp(0.0, 1.0);
        norm3(sub3(self.e, self.at(s)))
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn seg_dist(p: V2, a: V2, b: V2) -> f64 {
    (p - seg_nearest(p, a, b)).norm()
}

/// The point of the segment `a`–`b` nearest to `p`.
fn seg_nearest(p: V2, a: V2, b: V2) -> V2 {
    let d = b - a;
    let t = seg_param(p, a, b).clamp(0.0, 1.0);
    a + V2::new(d.r * t, d.z * t)
}

/// Where `p` projects on the line through `a` and `b`: 0 at `a`, 1 at
/// `b` (0 when they coincide).
fn seg_param(p: V2, a: V2, b: V2) -> f64 {
    let d = b - a;
    let len2 = d.r * d.r + d.z * d.z;
    if len2 > 0.0 {
        ((p - a).r * d.r + (p - a).z * d.z) / len2
    } else {
        0.0
    }
}

impl Sink for Certifier {
    fn emit(&mut self, e: Event) {
        // Consecutive thread moves form a chain; anything between ends it.
        let thread = matches!(e, Event::Thread { .. });
        match e {
            Event::Line { x, z, .. } | Event::Skip { x, z } => {
                self.push_move(x, z, None, Shape::Line)
            }
            Event::Arc { dir, x, z, cx, cz } => {
                let centre = V2::from_xz(cx, cz);
                let ccw = dir == nc::event::Dir::Ccw;
                self.push_move(x, z, None, Shape::Arc { centre, ccw })
            }
            Event::Rapid { x, z, .. } => self.push_move(x, z, None, Shape::Rapid),
            Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. }
            | Event::ArcThread { x, z, .. } => self.push_move(x, z, None, Shape::Free),
            Event::Thread {
                x, z, lead, dlead, ..
            } => self.push_move(x, z, Some((lead, dlead.unwrap_or(0.0))), Shape::Thread),
            Event::Speed { s, css, max } => {
                if let Some(m) = max {
                    self.cmd.clamp = if m > 0.0 { m } else { f64::INFINITY };
                }
                self.cmd.css = css.then_some(s.max(0.0));
            }
            Event::Spindle(d) => self.cmd.on = d != SpindleDir::Stop,
            // The tool goes home by a way of its own: the next move's
            // start is not the last end point.
            Event::Home { .. } => self.last_end = None,
            // The plane's moves: where they leave the joints (the runtime's
            // translator, translate.rs), so that the move after the plane
            // starts there.
            Event::PolarOn => self.plane_on(PlaneMap::Polar { z: 0.0 }),
            Event::Cylinder(Some(radius)) => self.plane_on(PlaneMap::Cylinder { radius, r: 0.0 }),
            Event::PlaneMove { a, b, off, .. } => self.plane_move(a, b, off),
            Event::PlaneAxis { to, c, .. } => self.plane_axis(to, c),
            Event::PolarOff { x, .. } => self.plane_off(Some(x)),
            Event::Cylinder(None) => self.plane_off(None),
            // A new work zero (machine coordinates, X a diameter): the last
            // end point, where the next move starts, is the same place in
            // the new frame (unknown when the old zero was never printed).
            Event::Origin { x, z } => {
                let origin = V2::from_xz(x, z);
                let shift = self.origin.map(|old| origin - old);
                self.last_end = self.last_end.zip(shift).map(|(e, s)| e - s);
                if let Some(t) = &mut self.plane {
                    t.r = t.r.zip(shift).map(|(r, s)| r - s.r);
                    t.z = t.z.zip(shift).map(|(z, s)| z - s.z);
                }
                self.origin = Some(origin);
            }
            _ => {}
        }
        self.chain_open = thread;
    }
}

/// A travel figure of `ax` at `fig.value` (machine coordinates; X a
/// radius, given as a diameter as the machine file writes it): against
/// the nearer limit.
fn travel(mut fig: Figure, ax: Axis, diameter: bool) -> Figure {
    let v = fig.value;
    let (limit, beyond) = if v - ax.min < ax.max - v {
        (ax.min, ax.min - v)
    } else {
        (ax.max, v - ax.max)
    };
    let k = if diameter { 2.0 } else { 1.0 };
    (fig.value, fig.limit, fig.ratio) = (v * k, limit * k, beyond * k);
    fig
}

/// The summary line (see [`Certifier::summary`]).
pub struct Summary<'a>(&'a Certifier);

impl fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.0;
        write!(
            f,
            "{} periods ({:.3} s)",
            c.periods,
            c.periods as f64 * c.dt
        )?;
        for kind in Kind::ALL {
            let w = c.worst(kind);
            match (kind, w) {
                (Kind::Jerk, None) if !c.jerk => write!(f, "; jerk: not limited")?,
                (Kind::Travel, None) => write!(f, "; travel: not limited")?,
                (Kind::Travel, Some(w)) => write!(
                    f,
                    "; travel: {} {:.3} mm {} its limit ({} at {:.3} mm, line {})",
                    if w.ratio > 0.0 { "worst" } else { "nearest" },
                    w.ratio.abs(),
                    if w.ratio > 0.0 { "beyond" } else { "inside" },
                    w.subject.name(),
                    w.value,
                    w.line
                )?,
                (Kind::EndPoint, _) => {
                    write!(f, "; end points: {} of {} reached", c.reached, c.end_points)?
                }
                (Kind::Path, Some(w)) => write!(
                    f,
                    "; path: worst {:.4} mm off ({} periods, line {})",
                    w.value, c.path_periods, w.line
                )?,
                (Kind::Lead, Some(w)) => write!(
                    f,
                    "; thread lead: worst {:.4} % off ({} periods, line {})",
                    w.ratio * 100.0,
                    c.lead_periods,
                    w.line
                )?,
                (Kind::SurfaceSpeed, Some(w)) => write!(
                    f,
                    "; surface speed: worst {:.4} % off the G96 target ({} periods, line {})",
                    w.ratio * 100.0,
                    c.css_periods,
                    w.line
                )?,
                (_, Some(w)) => write!(
                    f,
                    "; {}: worst {:.1} % of the limit ({} {:.3} {}, line {})",
                    kind.name(),
                    w.ratio * 100.0,
                    w.subject.name(),
                    w.value.abs(),
                    w.subject.unit(kind),
                    w.line
                )?,
                (_, None) => write!(f, "; {}: none", kind.name())?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;
    use alloc::vec::Vec;

    /// A run on the reference machine (X 1500, Z 2000 mm/s², feeds
    /// ≤ 4000/5000 mm/min, rapids 6000/10000 mm/min, period 1 ms),
    /// starting at machine zero = work zero.
    fn certifier() -> Certifier {
        Certifier::new(&Config::default(), 0.0, 0.0, 0.0)
    }

    /// A set point at period `k` (time k ms), work = machine + `shift`
    /// (diameter, Z).
    fn at(k: u32, axis: (f64, f64), shift: (f64, f64), motion: Motion) -> SetPoint {
        SetPoint {
            time_s: f64::from(k) * 0.001,
            x: axis.0 + shift.0,
            z: axis.1 + shift.1,
            axis_x: axis.0,
            axis_z: axis.1,
            line: 10 + k,
            motion,
            ..SetPoint::default()
        }
    }

    /// Z positions of a stop-to-stop feed at 2000 mm/s² (the limit):
    /// z = −a·t²/2 for 10 periods, then braking symmetrically.
    fn z_profile(a: f64) -> Vec<f64> {
        let dt = 0.001;
        let mut z = Vec::new();
        for k in 1..=10 {
            let t = f64::from(k) * dt;
            z.push(-a * t * t / 2.0);
        }
        let top = -a * (10.0 * dt) * (10.0 * dt) / 2.0;
        for k in 1..=10 {
            let t = f64::from(10 - k) * dt;
            z.push(2.0 * top + a * t * t / 2.0);
        }
        z
    }

    #[test]
    fn a_move_at_the_limits_is_certified() {
        let mut c = certifier();
        let z = z_profile(2000.0);
        // The canon end point: Z = 2 × (−2000 × 0.01² / 2) = −0.2.
        c.emit(Event::Line {
            x: 0.0,
            z: -0.2,
            c: None,
        });
        for (k, &z) in z.iter().enumerate() {
            c.period(&at(k as u32 + 1, (0.0, z), (0.0, 0.0), Motion::Feed));
        }
        c.finish(true);
        assert_eq!(c.violation(), None);
        // Top speed 2000 × 0.01 = 20 mm/s, but the finite difference of
        // period 10 is (z10 − z9)/dt = 2000 × (0.1² − 0.09²)/2 … /dt
        // = 19 mm/s; the acceleration is exactly the limit.
        let v = c.worst(Kind::Velocity).unwrap();
        assert!((v.value.abs() - 19.0).abs() < 1e-6, "{v:?}");
        let a = c.worst(Kind::Acceleration).unwrap();
        assert!((a.ratio - 1.0).abs() < 1e-6, "{a:?}");
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 1 of 1 reached"));
    }

    #[test]
    fn a_thread_start_in_one_period_is_caught() {
        // Z from rest to 1.5 mm/rev × 600 rev/min = 15 mm/s at once: the
        // second difference is 0.015 mm / (1 ms)² = 15 000 mm/s².
        let mut c = certifier();
        c.period(&at(1, (0.0, 0.0), (0.0, 0.0), Motion::Thread));
        c.period(&at(2, (0.0, -0.015), (0.0, 0.0), Motion::Thread));
        let v = *c.violation().expect("a violation");
        assert_eq!(
            (v.kind, v.subject, v.line),
            (Kind::Acceleration, Subject::Z, 12)
        );
        assert!((v.value.abs() - 15_000.0).abs() < 1e-6, "{v:?}");
        assert_eq!(v.limit, 2000.0);
        let text = v.to_string();
        assert!(
            text.contains(
                "at 0.002000 s: Z acceleration 15000.000 mm/s² exceeds its limit 2000.000 mm/s²"
            ),
            "{text}"
        );
    }

    #[test]
    fn feeds_and_rapids_have_their_own_speed_limits() {
        // 0.07 mm of radius in 1 ms = 70 mm/s: above X's cutting feed
        // (4000 mm/min = 66.667 mm/s), below its rapid (100 mm/s). The
        // acceleration is measured too, so X builds the speed slowly:
        // 70 mm/s at 1500 mm/s² takes 47 periods (70/1.5).
        for (motion, bad) in [(Motion::Rapid, false), (Motion::Feed, true)] {
            let mut c = certifier();
            let (mut r, mut v, mut k) = (0.0f64, 0.0f64, 0);
            while k < 200 {
                v = (v + 1.5).min(70.0); // mm/s gained per period
                r += v * 0.001;
                k += 1;
                c.period(&at(k, (2.0 * r, 0.0), (0.0, 0.0), motion));
            }
            let f = c.worst(Kind::Velocity).unwrap();
            assert!((f.value - 70.0).abs() < 1e-6, "{f:?}");
            assert_eq!(c.violation().is_some(), bad, "{motion:?}");
            if bad {
                let f = c.violation().unwrap();
                assert_eq!(
                    (f.kind, f.subject, f.limit),
                    (Kind::Velocity, Subject::X, 4000.0 / 60.0)
                );
            }
        }
    }

    #[test]
    fn an_origin_change_is_no_jump_and_end_points_follow_it() {
        // G00 Z-0.2 in work = machine; then G50 moves work zero by 100 mm
        // (work Z = machine Z + 100): the next end point, Z = 99.8 in the
        // new work frame, is the machine's Z −0.2 again … back to 0.
        let mut c = certifier();
        c.emit(Event::Line {
            x: 0.0,
            z: -0.2,
            c: None,
        });
        let z = z_profile(2000.0);
        let mut k = 0;
        for &z in &z {
            k += 1;
            c.period(&at(k, (0.0, z), (0.0, 0.0), Motion::Feed));
        }
        c.emit(Event::Origin { x: 0.0, z: 100.0 });
        c.emit(Event::Line {
            x: 0.0,
            z: 100.0,
            c: None,
        });
        k += 1;
        c.period(&at(k, (0.0, -0.2), (0.0, 100.0), Motion::None));
        for &z in &z {
            k += 1;
            c.period(&at(k, (0.0, -0.2 - z), (0.0, 100.0), Motion::Feed));
        }
        c.finish(true);
        assert_eq!(c.violation(), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 2 of 2 reached"));
    }

    #[test]
    fn a_shift_after_the_tool_settled_misses_no_end_point() {
        // Jerk limiting: the canon runs ahead of the set points, so the
        // next end point (work Z−0.1 after a shift of 0.3 mm, machine
        // Z−0.4) is queued while the tool settles on Z−0.2: its last
        // period, from Z−0.1995 (within the tolerance) to Z−0.2, goes
        // away from the next point in the old frame (0.0995 → 0.1 mm).
        // The shift then moves the tool's work point 0.3 mm without a
        // step: the tool did not cut by the point, which it reaches
        // 0.2 mm later.
        let mut c = certifier();
        c.emit(Event::Line {
            x: 0.0,
            z: -0.2,
            c: None,
        });
        let z = z_profile(2000.0);
        let mut k = 0;
        for &z in &z {
            k += 1;
            c.period(&at(k, (0.0, z * 0.9975), (0.0, 0.0), Motion::Feed));
        }
        c.emit(Event::Origin { x: 0.0, z: 0.3 });
        c.emit(Event::Line {
            x: 0.0,
            z: -0.1,
            c: None,
        });
        for shift in [0.0, 0.3] {
            k += 1;
            c.period(&at(k, (0.0, -0.2), (0.0, shift), Motion::Feed));
        }
        for &z in &z {
            k += 1;
            c.period(&at(k, (0.0, -0.2 + z), (0.0, 0.3), Motion::Feed));
        }
        c.finish(true);
        assert_eq!(c.violation(), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 2 of 2 reached"));
    }

    #[test]
    fn a_shift_and_the_first_step_in_one_period() {
        // Standing at machine X40 Z10 = work X40 Z10; G55 moves work zero
        // so that the point is X35, and the same period steps 0.003 mm
        // (diameter) towards X30: the zero-length RAPID X35 is where the
        // step began in the new frame, so it is reached.
        let mut c = Certifier::new(&Config::default(), 40.0, 10.0, 0.0);
        c.emit(Event::Origin { x: 5.0, z: 0.0 });
        c.emit(Event::Rapid {
            x: 35.0,
            z: 10.0,
            c: None,
        });
        c.period(&at(1, (40.0, 10.0), (0.0, 0.0), Motion::None));
        c.period(&at(2, (39.997, 10.0), (-5.0, 0.0), Motion::Rapid));
        c.finish(true);
        assert_eq!(c.violation(), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 1 of 1 reached"));
    }

    #[test]
    fn an_end_point_not_reached_is_reported_where_the_path_came_nearest() {
        // The path stops 0.002 mm short of Z−0.2: it came nearest on its
        // last period (line 30), 0.002 mm away.
        let mut c = certifier();
        c.emit(Event::Line {
            x: 0.0,
            z: -0.2,
            c: None,
        });
        for (k, &z) in z_profile(2000.0).iter().enumerate() {
            c.period(&at(k as u32 + 1, (0.0, z * 0.99), (0.0, 0.0), Motion::Feed));
        }
        assert_eq!(c.violation(), None); // not yet: the run goes on
        c.finish(true);
        let f = *c.violation().expect("the end point is missed");
        assert_eq!((f.kind, f.line), (Kind::EndPoint, 30));
        assert!((f.value - 0.002).abs() < 1e-9, "{f:?}");
        // A run that stopped early (an alarm) owes no end points.
        let mut c = certifier();
        c.emit(Event::Line {
            x: 0.0,
            z: -0.2,
            c: None,
        });
        c.finish(false);
        assert_eq!(c.violation(), None);
    }

    #[test]
    fn a_reversal_after_an_end_point_reached_early_is_no_miss() {
        // G01 X0.004 (radius 0.002) then back to X−0.003 (radius −0.0015),
        // as a random contour ran them: the period to r 0.0015 comes
        // 0.0005 mm near the first end point and still closes on it, the
        // next one ends on it, the tool stands a period and comes back.
        // Had the first counted as reached at 0.0005 mm, the path would
        // have neared r −0.0015 no more than 0.0015 mm and then left it,
        // by as much as it moved: a cut corner to the walk, though the
        // tool was still going to the first end point. It reaches both.
        let mut c = certifier();
        for x in [0.004, -0.003] {
            c.emit(Event::Line { x, z: 0.0, c: None });
        }
        let radii = [0.0, 0.0015, 0.002, 0.002, 0.0005, -0.00125, -0.0015];
        for (k, &r) in radii.iter().enumerate() {
            c.period(&at(k as u32 + 1, (2.0 * r, 0.0), (0.0, 0.0), Motion::Feed));
        }
        c.finish(true);
        assert_eq!(c.violation(), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 2 of 2 reached"));
    }

    /// How the trace of `full_circle` runs the circle.
    #[derive(Clone, Copy)]
    enum Round {
        /// All the way round, back on its end point.
        Whole,
        /// Its last quarter spirals out to 0.002 mm beyond the end point
        /// on the radius; the last line then runs back to its own end.
        Wide,
        /// Not at all: the tool goes straight on.
        Skipped,
    }

    /// `G01 Z−10` from X20 Z0 (line 2), a full G03 circle about X16 Z−10
    /// (radius 2, tangent to the line, line 3), `G01 Z−20` (line 4), at
    /// 0.01 mm a period; the circle in 1257 periods (2π·2/1257 = 0.009997
    /// mm of arc), run as `round` says.
    fn full_circle(round: Round) -> Certifier {
        let mut c = Certifier::new(&Config::default(), 20.0, 0.0, 0.0);
        c.emit(Event::Line {
            x: 20.0,
            z: -10.0,
            c: None,
        });
        c.emit(Event::Arc {
            dir: nc::event::Dir::Ccw,
            x: 20.0,
            z: -10.0,
            cx: 16.0,
            cz: -10.0,
        });
        c.emit(Event::Line {
            x: 20.0,
            z: -20.0,
            c: None,
        });
        let mut k = 0;
        let mut step = |c: &mut Certifier, r: f64, z: f64, line: u32, motion: Motion| {
            k += 1;
            c.period(&SetPoint {
                line,
                ..at(k, (2.0 * r, z), (0.0, 0.0), motion)
            });
        };
        step(&mut c, 10.0, 0.0, 2, Motion::None);
        for i in 1..=1000 {
            step(&mut c, 10.0, -0.01 * f64::from(i), 2, Motion::Feed);
        }
        let n = 1257;
        let mut back = 0.0;
        for i in 1..=n {
            if let Round::Skipped = round {
                break;
            }
            let phi = 2.0 * PI * f64::from(i) / f64::from(n);
            // (Wide: the radius grows by 0.002 over the last quarter.)
            if let Round::Wide = round {
                back = (0.002 * (phi - 1.5 * PI) / (0.5 * PI)).max(0.0);
            }
            let rad = 2.0 + back;
            step(
                &mut c,
                8.0 + rad * phi.cos(),
                -10.0 - rad * phi.sin(),
                3,
                Motion::Arc,
            );
        }
        for i in 1..=1000 {
            let t = f64::from(i) / 1000.0;
            step(
                &mut c,
                10.0 + back * (1.0 - t),
                -10.0 - 10.0 * t,
                4,
                Motion::Feed,
            );
        }
        c.finish(true);
        c
    }

    /// A full circle starts on its end point, but that end point is due
    /// when the tool comes back to it, not where it leaves it.
    #[test]
    fn a_full_circle_ends_where_it_comes_back() {
        let c = full_circle(Round::Whole);
        assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 3 of 3 reached"));
        // Coming back 0.002 mm wide of it is a miss, at the circle's last
        // period (line 3): its chord ends 0.002 mm out on the radius and
        // passes the end point at 0.002·cos(δ/2) ≈ 0.002 − 6e-9 mm (δ the
        // 0.005 rad a period turns).
        let c = full_circle(Round::Wide);
        let f = *c.worst(Kind::EndPoint).expect("the circle's end is missed");
        assert!(f.violates() && (f.value - 0.002).abs() < 1e-8, "{f:?}");
        assert_eq!(f.line, 3);
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 2 of 3 reached"));
        // A circle the tool never ran: its end point is not reached at its
        // start. The miss is placed where the walk began to wait for it:
        // the period that reached the circle's start (line 2's last).
        let c = full_circle(Round::Skipped);
        let f = *c
            .worst(Kind::EndPoint)
            .expect("the skipped circle is caught");
        let at_1001 = (f.time_s - 1.001).abs() < 1e-9;
        assert!(f.violates() && f.line == 2 && at_1001, "{f:?}");
        assert!(f.to_string().contains("does not come back to it"), "{f}");
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 1 of 3 reached"));
    }

    #[test]
    fn end_points_are_reached_in_order_within_a_step() {
        // G01 W−0.003, back to Z0, then to (r 0.0015, Z −0.004), at 1–2 µm
        // a period. The step from Z −0.001 to −0.0026 ends 0.0004 mm short
        // of the first end point and began 0.001 mm from the second:
        // that one is only reached after the first, on the way back. Taken
        // at once, the walk judged the third from Z −0.003, where it came
        // 0.0018 mm near, and called the step that leaves Z0 for it, by
        // 0.002 mm, a miss.
        let mut c = certifier();
        for (x, z) in [(0.0, -0.003), (0.0, 0.0), (0.003, -0.004)] {
            c.emit(Event::Line { x, z, c: None });
        }
        let path = [
            (0.0, -0.001),
            (0.0, -0.0026),
            (0.0, -0.003),
            (0.0, -0.001),
            (0.0, 0.0),
            (0.000703, -0.001874),
            (0.0014, -0.00375),
            (0.0015, -0.004),
        ];
        for (k, &(r, z)) in path.iter().enumerate() {
            c.period(&at(k as u32 + 1, (2.0 * r, z), (0.0, 0.0), Motion::Feed));
        }
        c.finish(true);
        // (The made-up steps break the axes' acceleration: only the end
        // points are judged here.)
        assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 3 of 3 reached"));
    }

    #[test]
    fn a_corner_cut_between_two_periods_is_a_miss_and_the_walk_goes_on() {
        // G01 Z−0.1 then X0.1 (radius 0.05) at 20 mm/s: the periods at Z
        // −0.095 and then (X 0.03, Z −0.1)… jump over the corner Z−0.1: the
        // chord from (r 0, Z −0.095) to (r 0.015, Z −0.1) passes it at
        // 0.005 × 0.015 / hypot(0.015, 0.005) = 0.0047434 mm, its nearest
        // (period 6, line 16). The next end point is reached.
        let mut c = certifier();
        c.emit(Event::Line {
            x: 0.0,
            z: -0.1,
            c: None,
        });
        c.emit(Event::Line {
            x: 0.1,
            z: -0.1,
            c: None,
        });
        let path = [
            (0.0, -0.02),
            (0.0, -0.04),
            (0.0, -0.06),
            (0.0, -0.08),
            (0.0, -0.095),
            (0.03, -0.1),
            (0.07, -0.1),
            (0.1, -0.1),
        ];
        for (k, &xz) in path.iter().enumerate() {
            c.period(&at(k as u32 + 1, xz, (0.0, 0.0), Motion::Feed));
        }
        c.finish(true);
        let f = *c.worst(Kind::EndPoint).expect("the corner is missed");
        assert_eq!(f.line, 16);
        let want = 0.005 * 0.015 / libm::hypot(0.015, 0.005);
        assert!(
            (f.value - want).abs() < 1e-12 && (want - 0.0047434).abs() < 1e-7,
            "{f:?}"
        );
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 1 of 2 reached"));
    }

    #[test]
    fn incomplete_lead_lengths() {
        // 1.5 mm/rev at 600 rev/min: 15 mm/s; Z at 2000 mm/s² needs
        // 15² / (2 × 2000) = 0.05625 mm.
        assert!((incomplete_lead(15.0, 2000.0, 1500.0, 30.0, 0.0) - 0.05625).abs() < 1e-12);
        // A 45° taper: X (1500 mm/s²) must follow Z one to one, so Z may
        // accelerate at only 1500: 225 / 3000 = 0.075 mm.
        assert!((incomplete_lead(15.0, 2000.0, 1500.0, 10.0, -10.0) - 0.075).abs() < 1e-12);
        // A shallow taper (X 1 in Z 4): X allows 1500 × 4 = 6000 > 2000.
        assert!((incomplete_lead(15.0, 2000.0, 1500.0, -8.0, 2.0) - 0.05625).abs() < 1e-12);
    }

    /// A G32 Z−30 with lead 1.5 at 600 rev/min (0.01 rev per period):
    /// Z ramps at 2000 mm/s² to 15 mm/s (7.5 periods: take 8 at the
    /// limit, then exactly 0.015 mm per period), with one wrong period
    /// at `bad` where Z moves 0.0151 mm.
    fn thread(bad: Option<u32>) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Spindle(SpindleDir::Cw));
        c.emit(Event::Rapid {
            x: 0.0,
            z: 0.0,
            c: None,
        });
        c.emit(Event::Thread {
            x: 0.0,
            z: -30.0,
            c: None,
            lead: 1.5,
            dlead: None,
            q: None,
        });
        let (mut z, mut v, mut turns) = (0.0f64, 0.0f64, 0.0);
        // 1900 periods: Z ends at about −28.4, short of the run-out.
        for k in 1..=1900u32 {
            v = (v + 2.0).min(15.0); // mm/s: 2000 mm/s² × 1 ms
            let step = if Some(k) == bad { 0.0151 } else { v * 0.001 };
            z -= step;
            turns += 0.01;
            let p = SetPoint {
                spindle_rpm: 600.0,
                spindle_turns: turns,
                ..at(k, (0.0, z), (0.0, 0.0), Motion::Thread)
            };
            c.period(&p);
        }
        c
    }

    /// A feed along Z from X20 Z0 to Z−10, then a quarter arc about X20
    /// Z−12 to X24 Z−12, every 10 µm of Z a period; the period `off`
    /// strays `by` mm out on the radius.
    fn along(off: u32, by: f64) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Rapid {
            x: 20.0,
            z: 0.0,
            c: None,
        });
        c.emit(Event::Line {
            x: 20.0,
            z: -10.0,
            c: None,
        });
        c.emit(Event::Arc {
            dir: nc::event::Dir::Ccw,
            x: 24.0,
            z: -12.0,
            cx: 20.0,
            cz: -12.0,
        });
        let mut k = 0;
        let mut step = |c: &mut Certifier, r: f64, z: f64, motion: Motion| {
            k += 1;
            let r = if k == off { r + by } else { r };
            c.period(&at(k, (2.0 * r, z), (0.0, 0.0), motion));
        };
        step(&mut c, 10.0, 0.0, Motion::None);
        for i in 1..=1000 {
            step(&mut c, 10.0, -0.01 * f64::from(i), Motion::Feed);
        }
        // The arc: r = 10 + 2·sin θ, z = −12 + 2·cos θ, θ from 0 to 90°.
        for i in 1..=300 {
            let t = core::f64::consts::FRAC_PI_2 * f64::from(i) / 300.0;
            step(
                &mut c,
                10.0 + 2.0 * t.sin(),
                -12.0 + 2.0 * t.cos(),
                Motion::Arc,
            );
        }
        c.finish(true);
        c
    }

    #[test]
    fn the_tool_is_held_to_its_lines_and_arcs() {
        let c = along(0, 0.0);
        let w = c.worst(Kind::Path).unwrap();
        assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
        // (The first period jumps from machine zero: only the path and
        // the end points matter here.)
        assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("path: worst 0.0000 mm off (1300 periods"));
        // 1.5 µm out on the radius in period 500 (Z −4.99), off the line
        // by as much, or in period 1290 (86.7° round the arc), off the
        // circle by √((2·sin 86.7° + 0.0015)² + (2·cos 86.7°)²) − 2 =
        // 1.49751 µm: caught; 0.5 µm is within the resolution.
        for (off, by) in [(500, 0.0015), (1290, 0.00149751)] {
            let w = *along(off, 0.0015).worst(Kind::Path).unwrap();
            assert!(w.violates() && (w.value - by).abs() < 1e-8, "{w:?}");
            assert_eq!(w.line, 10 + off);
            assert!(!along(off, 0.0005).worst(Kind::Path).unwrap().violates());
        }
    }

    /// A rapid from X20 Z0 to X40 Z−10 as a dog-leg: X (10 → 20 on the
    /// radius) at 0.1 a period, Z at 0.05, so X arrives first; the period
    /// `off` strays `by` mm beyond Z0.
    fn dog_leg(off: u32, by: f64) -> Certifier {
        let mut c = certifier();
        for (x, z) in [(20.0, 0.0), (40.0, -10.0)] {
            c.emit(Event::Rapid { x, z, c: None });
        }
        c.period(&at(1, (20.0, 0.0), (0.0, 0.0), Motion::None));
        for k in 2..=201u32 {
            let i = f64::from(k - 1);
            let (r, mut z) = ((10.0 + 0.1 * i).min(20.0), -0.05 * i);
            if k == off {
                z = by;
            }
            c.period(&at(k, (2.0 * r, z), (0.0, 0.0), Motion::Rapid));
        }
        c
    }

    #[test]
    fn a_rapid_is_held_to_the_rectangle_of_its_ends() {
        let w = *dog_leg(0, 0.0).worst(Kind::Path).unwrap();
        assert!(w.value == 0.0 && !w.violates(), "{w:?}");
        // Z at +0.002 in period 50 (X at 14.9, inside): 0.002 mm out.
        let w = *dog_leg(50, 0.002).worst(Kind::Path).unwrap();
        assert!(w.violates() && (w.value - 0.002).abs() < 1e-12, "{w:?}");
        assert_eq!(w.line, 60);
    }

    /// `G00 X20 Z5 C0 / G12.1 / G01 X10 C0 / G13.1 / G01 Z−5` by hand:
    /// the plane's line in 50 periods from the radius 10 to `to` at Z5
    /// and C0 (the canon's end: 5), the line after it in 100 periods from
    /// Z5 to Z−5 at the radius `to`, `by` mm beyond in period `off`.
    fn after_polar(to: f64, off: u32, by: f64) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Rapid {
            x: 20.0,
            z: 5.0,
            c: Some(0.0),
        });
        c.emit(Event::PolarOn);
        c.emit(Event::PlaneMove {
            plane: nc::event::Plane::Polar,
            motion: nc::event::PlaneMotion::Line,
            a: 10.0,
            b: 0.0,
            off: None,
        });
        c.emit(Event::PolarOff { x: 10.0, c: 0.0 });
        c.emit(Event::Line {
            x: 10.0,
            z: -5.0,
            c: None,
        });
        c.period(&at(1, (20.0, 5.0), (0.0, 0.0), Motion::None));
        let mut k = 1;
        for i in 1..=50 {
            k += 1;
            let r = 10.0 + (to - 10.0) * f64::from(i) / 50.0;
            c.period(&at(k, (2.0 * r, 5.0), (0.0, 0.0), Motion::Feed));
        }
        for i in 1..=100 {
            k += 1;
            let r = if k == off { to + by } else { to };
            let z = 5.0 - 10.0 * f64::from(i) / 100.0;
            c.period(&at(k, (2.0 * r, z), (0.0, 0.0), Motion::Feed));
        }
        c.finish(true);
        c
    }

    #[test]
    fn the_move_after_polar_interpolation_starts_where_the_plane_ended() {
        // The line after G13.1 runs from X10 (the radius 5), where the
        // plane's line ended, not from X20, where the plane began (the
        // plane's periods at Z5, X 20 → 10, lie 1.4 mm and more off the
        // line from X20 Z5 to X10 Z−5 but are held to no line).
        let c = after_polar(5.0, 0, 0.0);
        let w = c.worst(Kind::Path).unwrap();
        assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
        assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 3 of 3 reached"));
        // 2 µm out on the radius in period 100 of the run (Z0.1): caught.
        let w = *after_polar(5.0, 100, 0.002).worst(Kind::Path).unwrap();
        assert!(w.violates() && (w.value - 0.002).abs() < 1e-9, "{w:?}");
        assert_eq!(w.line, 110);
        // A plane that stops at X12: its end point, X10, is missed by 1 mm
        // on the radius (where the tool stood at the nearest), and the
        // walk waits there (the line after it is not the move running).
        let c = after_polar(6.0, 0, 0.0);
        let e = c.worst(Kind::EndPoint).unwrap();
        assert!(e.violates() && (e.value - 1.0).abs() < 1e-9, "{e:?}");
        assert_eq!(e.line, 61);
    }

    /// `G00 X20 Z0 C0 / G7.1 C10. / G01 Z−10 C90 / G7.1 C0 / G01 X30` by
    /// hand: the plane's line in 100 periods from Z0 C0 to Z−10 and C
    /// `to` (the canon's end: 90°) at X20, then the line along X to X30
    /// at Z−10 in 50 periods.
    fn after_cylinder(to: f64) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Rapid {
            x: 20.0,
            z: 0.0,
            c: Some(0.0),
        });
        c.emit(Event::Cylinder(Some(10.0)));
        c.emit(Event::PlaneMove {
            plane: nc::event::Plane::Cylinder,
            motion: nc::event::PlaneMotion::Line,
            a: -10.0,
            b: 90.0,
            off: None,
        });
        c.emit(Event::Cylinder(None));
        c.emit(Event::Line {
            x: 30.0,
            z: -10.0,
            c: None,
        });
        let with_c = |p: SetPoint, deg: f64| SetPoint { c: Some(deg), ..p };
        c.period(&with_c(at(1, (20.0, 0.0), (0.0, 0.0), Motion::None), 0.0));
        let mut k = 1;
        for i in 1..=100 {
            k += 1;
            let f = f64::from(i) / 100.0;
            let p = at(k, (20.0, -10.0 * f), (0.0, 0.0), Motion::Feed);
            c.period(&with_c(p, to * f));
        }
        for i in 1..=50 {
            k += 1;
            let x = 20.0 + 10.0 * f64::from(i) / 50.0;
            c.period(&with_c(at(k, (x, -10.0), (0.0, 0.0), Motion::Feed), to));
        }
        c.finish(true);
        c
    }

    #[test]
    fn the_move_after_cylindrical_interpolation_starts_where_the_plane_ended() {
        // From X20 Z−10 (not Z0, where G7.1 began).
        let c = after_cylinder(90.0);
        let w = c.worst(Kind::Path).unwrap();
        assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
        assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 3 of 3 reached"));
        // The plane ends at C80, not C90: X and Z as programmed, but the
        // tool stands 2 · 10 · sin 5° = 1.74311 mm from the plane's end
        // about the spindle's axis.
        let e = *after_cylinder(80.0).worst(Kind::EndPoint).unwrap();
        let chord = 20.0 * 5f64.to_radians().sin();
        assert!(e.violates() && (e.value - chord).abs() < 1e-9, "{e:?}");
    }

    /// A G78 pass: a run-in from X25 Z5 to X23 Z4, the thread to Z−13, a
    /// pull-out to X25 Z−15, 20 + 340 + 40 periods along the legs; in
    /// period `off` of the thread X stands `by` mm (radius) below its
    /// root, X23, as an axis that ran past the run-in's corner did.
    fn g78_pass(off: u32, by: f64) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Rapid {
            x: 25.0,
            z: 5.0,
            c: None,
        });
        for (x, z) in [(23.0, 4.0), (23.0, -13.0), (25.0, -15.0)] {
            c.emit(Event::Thread {
                x,
                z,
                c: None,
                lead: 2.0,
                dlead: None,
                q: None,
            });
        }
        c.period(&at(1, (25.0, 5.0), (0.0, 0.0), Motion::None));
        let legs = [
            ((25.0, 5.0), (23.0, 4.0), 20),
            ((23.0, 4.0), (23.0, -13.0), 340),
        ];
        let mut k = 1;
        for ((x0, z0), (x1, z1), n) in legs.into_iter().chain([((23.0, -13.0), (25.0, -15.0), 40)])
        {
            for i in 1..=n {
                let f = f64::from(i) / f64::from(n);
                let mut x = x0 + (x1 - x0) * f;
                k += 1;
                if k == off {
                    x -= 2.0 * by;
                }
                c.period(&at(k, (x, z0 + (z1 - z0) * f), (0.0, 0.0), Motion::Thread));
            }
        }
        c
    }

    #[test]
    fn a_thread_is_held_to_the_box_of_its_chain() {
        let w = *g78_pass(0, 0.0).worst(Kind::Path).unwrap();
        assert!(w.value == 0.0 && !w.violates(), "{w:?}");
        // 0.05 mm below the root in the thread's 5th period (period 26).
        let w = *g78_pass(26, 0.05).worst(Kind::Path).unwrap();
        assert!(w.violates() && (w.value - 0.05).abs() < 1e-9, "{w:?}");
        assert_eq!(w.line, 36);
        // Half a resolution below is within it.
        assert!(!g78_pass(26, 0.0005).worst(Kind::Path).unwrap().violates());
    }

    #[test]
    fn the_catch_up_of_a_long_axis_that_a_corner_turns() {
        // A Z thread of lead 1.5 into a run-out 2 mm out on the radius and
        // 1 along Z: X is long there, at lead 1.5 × 2 = 3 along X, 1.5 of
        // Z a turn as before; X ran at 0 before, so it must run 3 mm per
        // turn faster. A 45° pull-out keeps Z long at Z's speed, and X
        // steps by 1.5.
        let z_thread = (V2::new(0.0, -20.0), (1.5, 0.0));
        let run_out = (V2::new(2.0, -1.0), (3.0, 0.0));
        assert_eq!(axis_steps([z_thread, run_out]), V2::new(3.0, 0.0));
        let pull_out = (V2::new(2.0, -2.0), (1.5, 0.0));
        assert_eq!(axis_steps([z_thread, pull_out]), V2::new(1.5, 0.0));
        // From rest to 15 mm/s at 1500 mm/s²: 15/1500 s to reach it, then
        // up 15/√3 at a and down at a/2: (0.01 + 0.0057735 + 0.011547) s
        // × 15 mm/s = 0.40981 mm.
        let d = catch_up_lead(15.0, 15.0, 1500.0, 66.667, LEAD_TOL);
        assert!((d - 0.409808).abs() < 1e-6, "{d}");
        // At 60 mm/s the peak (34.6 mm/s over the point) is cut to 6.667 by
        // the top speed: 0.04 s to reach 60, a lag of 1.2 mm; 0.004444 s up,
        // 0.008889 s down, which close 6.667²·3/3000 = 0.04444 mm, and
        // (1.2 − 0.04444)/6.667 = 0.17333 s at the top speed between:
        // 0.226667 s × 60 = 13.6 mm.
        let d = catch_up_lead(60.0, 60.0, 1500.0, 200.0 / 3.0, LEAD_TOL);
        assert!((d - 13.6).abs() < 1e-9, "{d}");
        // A thread at the axis's top speed: the lag stays, the lead is
        // kept once the axis runs at it (2/1500·... = 0.04444 s × 66.667).
        let v = 200.0 / 3.0;
        let d = catch_up_lead(v, v, 1500.0, v, LEAD_TOL);
        assert!((d - v * v / 1500.0).abs() < 1e-9, "{d}");
        assert_eq!(catch_up_lead(15.0, 0.0, 1500.0, 66.667, LEAD_TOL), 0.0);
    }

    /// A Z thread of lead 2 (X 20, Z 0 to −10, 500 periods at 0.02 mm)
    /// into a run-out to X 36 Z −12 at lead 4 along X (X 0.04 mm and Z
    /// 0.01 mm a period, 200 periods), the spindle at 600 rev/min, every
    /// period on the programmed chain except one 0.0401 mm step of X at
    /// `bad` periods into the run-out.
    fn run_out(bad: u32) -> Certifier {
        let mut c = certifier();
        c.emit(Event::Spindle(SpindleDir::Cw));
        c.emit(Event::Rapid {
            x: 20.0,
            z: 0.0,
            c: None,
        });
        for (x, z, lead) in [(20.0, -10.0, 2.0), (36.0, -12.0, 4.0)] {
            c.emit(Event::Thread {
                x,
                z,
                c: None,
                lead,
                dlead: None,
                q: None,
            });
        }
        let (mut r, mut z, mut turns) = (10.0, 0.0, 0.0);
        for k in 1..=700u32 {
            if k <= 500 {
                z -= 0.02;
            } else {
                r += if k - 500 == bad { 0.0401 } else { 0.04 };
                z -= 0.01;
            }
            turns += 0.01;
            let p = SetPoint {
                spindle_rpm: 600.0,
                spindle_turns: turns,
                ..at(k, (2.0 * r, z), (0.0, 0.0), Motion::Thread)
            };
            c.period(&p);
        }
        c
    }

    #[test]
    fn a_run_out_whose_long_axis_is_x_is_checked_after_the_catch_up() {
        // X must start at 40 mm/s: 40/1500 × (1 + 3/√3) = 0.072855 s,
        // 2.914 mm of X, + 10 % + 2 periods: 3.286 mm, 82 periods. A
        // wrong step in period 60 (X 2.4 mm out) is left out, one in
        // period 120 (4.8 mm) is caught: 0.25 % off. (Without the
        // catch-up only the incomplete lead, 40²/3000 × 1.1 + 0.04 =
        // 0.627 mm, would be left out.)
        let c = run_out(60);
        let w = c.worst(Kind::Lead).unwrap();
        assert!(!w.violates(), "{w:?}");
        let c = run_out(120);
        let w = *c.worst(Kind::Lead).unwrap();
        assert!(w.violates(), "{w:?}");
        assert_eq!(w.line, 10 + 620);
        assert!((w.value - 4.01).abs() < 1e-6 && w.limit == 4.0, "{w:?}");
    }

    #[test]
    fn the_lead_is_checked_after_the_incomplete_lead() {
        // The ramp (lead below 1.5) is within the incomplete lead:
        // 0.05625 × 1.1 + 0.015 = 0.0769 mm; period 8 ends at
        // 2+4+…+14 µm + 15 = 0.071 mm, so period 9, which starts there,
        // is left out too; from period 10 on (Z −0.086 at its start) the
        // lead is 1.5.
        // Periods 10 to 1900 are checked: 1891. (The spindle is at 600
        // from the first period, a jump the spindle check reports; only
        // the lead matters here.)
        let c = thread(None);
        let w = c.worst(Kind::Lead).unwrap();
        assert!(w.ratio < 1e-9 && !w.violates(), "{w:?}");
        assert!(
            c.summary().to_string().contains("(1891 periods"),
            "{}",
            c.summary()
        );
        // A period of 0.0151 mm in a turn of 0.01: lead 1.51, 0.667 % off.
        let c = thread(Some(500));
        let f = *c.worst(Kind::Lead).unwrap();
        assert!(f.violates());
        assert_eq!(f.line, 510);
        assert!((f.value - 1.51).abs() < 1e-9 && f.limit == 1.5, "{f:?}");
    }

    #[test]
    fn a_45_degree_pull_out_is_measured_along_z() {
        // The kernel's rule: Z is long when it moves at least as far as
        // X; a travel rounded 1.8e-15 mm the other way is still a tie.
        assert!(long_is_z(V2::new(2.0000000000000018, -2.0)));
        assert!(long_is_z(V2::new(2.0, -2.0)));
        assert!(!long_is_z(V2::new(2.001, -2.0)));
        // G32 Z−30 at lead 1.5, 600 rev/min (Z ramped to 15 mm/s as in
        // `thread`), then a 45° pull-out to r 2.0000000000000018 Z−32.
        // Z stays locked at 0.015 mm per 0.01 turn; X starts from rest at
        // the corner and, lagging, gains 1.5 mm/s per period (its
        // 1500 mm/s²) up to 20 mm/s to catch up: measured along X the
        // lead would reach 0.020 / 0.01 = 2.0, 33 % off. Along Z it is
        // 1.5 in every period checked, the chamfer's too: from
        // 15²/(2 × 1500) × 1.1 + 0.015 = 0.0975 mm past the corner.
        let mut c = certifier();
        c.emit(Event::Spindle(SpindleDir::Cw));
        c.emit(Event::Rapid {
            x: 0.0,
            z: 0.0,
            c: None,
        });
        for (x, z) in [(0.0, -30.0), (4.0000000000000036, -32.0)] {
            c.emit(Event::Thread {
                x,
                z,
                c: None,
                lead: 1.5,
                dlead: None,
                q: None,
            });
        }
        let (mut r, mut z, mut vz, mut vx, mut turns) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0);
        let mut k = 0;
        let mut chamfer = 0;
        while z > -31.8 {
            k += 1;
            vz = (vz + 2.0).min(15.0);
            z -= vz * 0.001;
            if z < -30.0 {
                vx = (vx + 1.5).min(20.0);
                r += vx * 0.001;
                chamfer += 1;
            }
            turns += 0.01;
            c.period(&SetPoint {
                spindle_rpm: 600.0,
                spindle_turns: turns,
                ..at(k, (2.0 * r, z), (0.0, 0.0), Motion::Thread)
            });
        }
        assert!(vx == 20.0 && chamfer > 100, "{vx} {chamfer}");
        let w = c.worst(Kind::Lead).unwrap();
        assert!(w.ratio < 1e-9 && !w.violates(), "{w:?}");
    }

    #[test]
    fn the_bound_of_a_chain_corner() {
        let (acc, dt) = ([1500.0, 2000.0], 0.001);
        let b = |d0: (f64, f64), l0: f64, d1: (f64, f64), l1: f64| {
            let legs = [
                (V2::new(d0.0, d0.1), (l0, 0.0)),
                (V2::new(d1.0, d1.1), (l1, 0.0)),
            ];
            chain_corner_mm(legs, acc, dt)
        };
        let near = |a: f64, b: f64| (a - b).abs() < 1e-15;
        // Z thread into a 45° pull-out, lead 1.5: per turn (0, −1.5) then
        // (1.5, −1.5); Z keeps its speed, X changes: 1500 × 0.001² mm.
        assert!(near(b((0.0, -30.0), 1.5, (2.0, -2.0), 1.5), 0.0015));
        // A taper (r 1 in Z 35) into its pull-out: still only X.
        assert!(near(b((1.0, -35.0), 2.0, (1.0, -2.0), 2.0), 0.0015));
        // A face thread (X long) into a run-out along Z: Z changes.
        assert!(near(b((-10.0, 0.0), 1.5, (-2.0, -1.0), 1.5), 0.002));
        // A run-out with J > K at lead × J/K keeps Z at 2 per turn (the
        // kernel's rule): (0, −2) then X-long (3, −1) at lead 6, (6, −2).
        assert!(near(b((0.0, -10.0), 2.0, (3.0, -1.0), 6.0), 0.0015));
        // At the bare lead 2 Z would slow to 0.667 per turn: both axes,
        // √(1500² + 2000²) × 0.001² = 0.0025 mm.
        assert!(near(b((0.0, -10.0), 2.0, (3.0, -1.0), 2.0), 0.0025));
        // A straight chain: nothing turns.
        assert_eq!(b((0.0, -10.0), 2.0, (0.0, -5.0), 2.0), 0.0);
        // G34: the lead at the end of the first leg, √(2² + 2 × 0.1 × 10)
        // = √6, is the second leg's start: nothing turns.
        let legs = [
            (V2::new(0.0, -10.0), (2.0, 0.1)),
            (V2::new(0.0, -5.0), (libm::sqrt(6.0), 0.1)),
        ];
        assert_eq!(chain_corner_mm(legs, acc, dt), 0.0);
    }

    /// Lead 1.5 at 600 rev/min (0.015 mm of Z a period) from Z−29.9551
    /// into a 45° pull-out at Z−30: the period that turns ends 0.0149 mm
    /// into the corner, 0.0001 mm past it, with X `x1` mm (radius) out.
    /// Returns the certifier after six periods.
    fn corner(x1: f64, thread: bool) -> Certifier {
        let mut c = Certifier::new(&Config::default(), 0.0, -29.9551, 0.0);
        c.emit(Event::Rapid {
            x: 0.0,
            z: -29.9551,
            c: None,
        });
        for (x, z) in [(0.0, -30.0), (4.0, -32.0)] {
            c.emit(if thread {
                Event::Thread {
                    x,
                    z,
                    c: None,
                    lead: 1.5,
                    dlead: None,
                    q: None,
                }
            } else {
                Event::Line { x, z, c: None }
            });
        }
        let path = [
            (0.0, -29.9701),
            (0.0, -29.9851),
            (x1, -30.0001),
            (x1 + 0.003, -30.0151),
            (x1 + 0.0075, -30.0301),
            (x1 + 0.0135, -30.0451),
        ];
        for (k, &(r, z)) in path.iter().enumerate() {
            c.period(&at(k as u32 + 1, (2.0 * r, z), (0.0, 0.0), Motion::Thread));
        }
        c
    }

    #[test]
    fn a_chain_corner_at_speed_is_reached_within_one_period_of_acceleration() {
        // X from rest at its full 1500 mm/s² moves a·dt² = 0.0015 mm in
        // the period that turns: the chord from (r 0, Z −29.9851) to
        // (0.0015, −30.0001) passes the corner (0, −30) at
        // 0.0149 × 0.0015 / hypot(0.0015, 0.015) = 0.0014826 mm: more than
        // 0.001, within the corner's bound of 0.0015 mm.
        let want = 0.0149 * 0.0015 / libm::hypot(0.0015, 0.015);
        assert!((want - 0.0014826).abs() < 1e-7);
        let c = corner(0.0015, true);
        assert!(c.worst(Kind::EndPoint).is_none(), "{}", c.summary());
        assert!(c
            .summary()
            .to_string()
            .contains("end points: 2 of 3 reached"));
        // The same path programmed as feeds is no thread chain: 0.001 mm.
        let c = corner(0.0015, false);
        let f = *c.worst(Kind::EndPoint).expect("missed");
        assert!(f.violates() && f.limit == END_POINT_MM, "{f:?}");
        assert!((f.value - want).abs() < 1e-9, "{f:?}");
        // An X that jumps twice a·dt² (0.003 mm) misses the corner by
        // 0.0149 × 0.003 / hypot(0.003, 0.015) = 0.0029221 mm > 0.0015.
        let c = corner(0.003, true);
        let f = *c.worst(Kind::EndPoint).expect("missed");
        assert!(f.violates() && (f.limit - 0.0015).abs() < 1e-15, "{f:?}");
        let want = 0.0149 * 0.003 / libm::hypot(0.003, 0.015);
        assert!((f.value - want).abs() < 1e-9 && (want - 0.0029221).abs() < 1e-7);
        assert!(f.to_string().contains("(tolerance 0.0015 mm)"), "{f}");
    }

    #[test]
    fn the_spindle_keeps_its_acceleration() {
        // 1000 rev/min/s is 1 rev/min per period: a step of 2 is twice it.
        let mut c = certifier();
        let p = |k, rpm| SetPoint {
            spindle_rpm: rpm,
            ..at(k, (0.0, 0.0), (0.0, 0.0), Motion::None)
        };
        c.period(&p(1, 1.0));
        c.period(&p(2, 2.0));
        assert_eq!(c.violation(), None);
        c.period(&p(3, 4.0));
        let f = *c.violation().unwrap();
        assert_eq!(
            (f.kind, f.value, f.limit),
            (Kind::SpindleAccel, 2000.0, 1000.0)
        );
    }

    #[test]
    fn g96_holds_the_surface_speed() {
        // G96 S150 at X50: 1000 × 150 / (π × 50) = 954.93 rev/min.
        let target = 1000.0 * 150.0 / (PI * 50.0);
        let run = |rpm: [f64; 3]| {
            let mut c = Certifier::new(&Config::default(), 50.0, 0.0, 0.0);
            c.emit(Event::Speed {
                s: 150.0,
                css: true,
                max: None,
            });
            c.emit(Event::Spindle(SpindleDir::Cw));
            c.emit(Event::Line {
                x: 50.0,
                z: -10.0,
                c: None,
            });
            // Feeding at X50 (it stays: a face would change the target).
            for (k, rpm) in rpm.into_iter().enumerate() {
                c.period(&SetPoint {
                    spindle_rpm: rpm,
                    ..at(
                        k as u32 + 1,
                        (50.0, -0.001 * k as f64),
                        (0.0, 0.0),
                        Motion::Feed,
                    )
                });
            }
            c.worst(Kind::SurfaceSpeed).copied()
        };
        let held = run([target; 3]).unwrap();
        assert!(held.ratio < 1e-12 && !held.violates(), "{held:?}");
        // 900 rev/min steady: (954.93 − 900) / 954.93 = 5.75 % off.
        let off = run([900.0; 3]).unwrap();
        assert!(off.violates());
        assert!((off.ratio - (target - 900.0) / target).abs() < 1e-12);
        assert!((off.ratio - 0.0575).abs() < 1e-4);
        // Still speeding up at the spindle's 1 rev/min per period: exempt.
        let chasing = run([898.0, 899.0, 900.0]).unwrap();
        assert_eq!(chasing.time_s, 0.001, "only the first period counts");
    }

    #[test]
    fn travel_is_checked_where_the_machine_has_soft_limits() {
        // Z's travel −5…2: standing at Z−4.999 (0.001 mm inside), then a
        // step of 0.002 mm to Z−5.001 (0.001 mm beyond: a violation).
        // X at X4 (radius 2) against −260…2 as a diameter (the
        // reference): 1 mm inside its upper limit, as a diameter.
        let mut cfg = Config::default();
        (cfg.x.soft_limits, cfg.x.min, cfg.x.max) = (true, -130.0, 1.0);
        (cfg.z.soft_limits, cfg.z.min, cfg.z.max) = (true, -5.0, 2.0);
        let mut c = Certifier::new(&cfg, 0.0, -4.999, 0.0);
        for k in 1..=3 {
            c.period(&at(k, (0.0, -4.999), (0.0, 0.0), Motion::None));
        }
        let w = *c.worst(Kind::Travel).unwrap();
        assert!((w.ratio + 0.001).abs() < 1e-9 && w.limit == -5.0, "{w:?}");
        assert!(c.violation().is_none());
        assert!(c
            .summary()
            .to_string()
            .contains("travel: nearest 0.001 mm inside its limit (Z at -4.999 mm, line 11)"));
        c.period(&at(4, (0.0, -5.001), (0.0, 0.0), Motion::Feed));
        let v = *c.violation().unwrap();
        assert_eq!((v.kind, v.subject, v.line), (Kind::Travel, Subject::Z, 14));
        assert!((v.ratio - 0.001).abs() < 1e-9, "{v:?}");
        assert!(v
            .to_string()
            .ends_with("Z at -5.001 mm leaves its travel: the limit is -5.000 mm"));
        // X as a diameter: radius 0.5 against the upper limit 1 (X2).
        let mut c = Certifier::new(&cfg, 1.0, 0.0, 0.0);
        c.period(&at(1, (1.0, 0.0), (0.0, 0.0), Motion::None));
        let w = *c.worst(Kind::Travel).unwrap();
        assert_eq!(
            (w.subject, w.value, w.limit, w.ratio),
            (Subject::X, 1.0, 2.0, -1.0)
        );
        // Without soft limits: not limited (standing at Z−900).
        let mut c = Certifier::new(&Config::default(), 0.0, -900.0, 0.0);
        c.period(&at(1, (0.0, -900.0), (0.0, 0.0), Motion::None));
        assert!(c.worst(Kind::Travel).is_none() && c.violation().is_none());
        assert!(c.summary().to_string().contains("travel: not limited"));
    }

    #[test]
    fn jerk_is_checked_where_the_machine_limits_it() {
        // Z starts at 2000 mm/s² at once: the third difference of
        // 0, 0, 0, −0.001 mm (a·dt²/2) is 0.001 mm / 1e-9 s³ = 1e6 mm/s³,
        // 40 × the 25 000 mm/s³ limit. Without jerk limiting it is not
        // checked.
        for jerk in [false, true] {
            let cfg = Config {
                jerk_limited: jerk,
                ..Config::default()
            };
            let mut c = Certifier::new(&cfg, 0.0, 0.0, 0.0);
            for (k, z) in [0.0, 0.0, 0.0, -0.001].into_iter().enumerate() {
                c.period(&at(k as u32 + 1, (0.0, z), (0.0, 0.0), Motion::Feed));
            }
            let w = c.worst(Kind::Jerk);
            if jerk {
                let w = w.unwrap();
                assert!(
                    (w.value + 1.0e6).abs() < 1e-3 && w.limit == 25_000.0,
                    "{w:?}"
                );
                assert_eq!(c.violation().map(|f| f.kind), Some(Kind::Jerk));
            } else {
                assert!(w.is_none());
                assert!(c.summary().to_string().contains("jerk: not limited"));
            }
        }
    }
}
