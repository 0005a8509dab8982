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
//!
//! [`Sink`]: nc::Sink

mod chain;
mod corners;
mod figure;
mod limits;
mod path;
mod pending;
mod plane;
mod shape;
mod sink;
mod spindle;
mod step;
mod summary;
mod walk;

#[cfg(test)]
mod tests;

use crate::config::{Axis, Config};
use crate::interpolate::{Motion, SetPoint};
use crate::math::V2;
use alloc::collections::VecDeque;
use chain::CatchUp;
pub use chain::{
    axis_steps, catch_up_lead, catch_up_time, chain_corner_mm, incomplete_lead, tail_time,
};
pub use figure::{Figure, Kind, Subject};
use pending::{Pending, SpindleCmd};
use plane::PlaneTrack;
pub use summary::Summary;

/// Velocity, acceleration, jerk and spindle limits hold within this share
/// of the limit (1e-6: floating-point rounding, nothing more).
pub const LIMIT_TOL: f64 = 1e-6;
/// An axis stays within its travel (soft limits) within this distance
/// (rounding), mm.
pub const TRAVEL_MM: f64 = 1e-6;
/// A canon end point is reached when the path passes within this distance
/// (the 0.001 mm resolution), mm.
pub const END_POINT_MM: f64 = 0.001;
/// What a distance computed from set points may carry of rounding, mm: a
/// point exactly at a tolerance is within it (1e-15 mm over did fail a
/// µm move's end point once).
const ROUNDING_MM: f64 = 1e-9;
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

    /// Keeps `fig` if it is the worst of its kind so far, and if it is
    /// the first violation.
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
            Some(d) if (d.end - here).norm() <= END_POINT_MM + ROUNDING_MM => Some(d),
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
}
