//! Manual motion between programs: the jog, incremental (step and
//! handwheel) and reference-return modes of a control's panel.
//!
//! A manual command is a move like a program's, queued and run by the
//! same planner and interpolator, so it keeps every axis within its rate,
//! acceleration (and jerk) limits and its soft limits, and its set
//! points are those of any move. It is taken only while no program
//! runs (`RunState::Idle`: before the first cycle start, or after a
//! reset). Its moves replace what the interpreter had queued ahead, and
//! when they have run (or `manual_stop` stopped them) the engine resets:
//! the program starts again from its beginning where the axes now stand,
//! as after any reset. Meanwhile the interpreter finds the queue full
//! and waits; the restart drops what it held.

use super::{Engine, RunState};
use crate::command::{Command, Feed, Move, MoveKind, Path, Tag};
use crate::config::Axis;
use crate::planner::Full;
use crate::plc::Plc;

/// How far a continuous jog runs on an axis without soft limits, mm (C:
/// degrees): it runs until `manual_stop`, as on a machine whose limit
/// switches stop it.
pub const JOG_REACH: f64 = 10_000.0;

/// The axis a manual command moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ManualAxis {
    /// The cross slide.
    X,
    /// The carriage.
    Z,
    /// The C axis, on a machine with one: degrees, rates in degrees per
    /// minute, no soft limits.
    C,
}

/// How fast a manual move runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JogRate {
    /// The axis's rapid rate, under the rapid override.
    Rapid,
    /// A feed, mm/min (on X the radial speed, as the machine file's
    /// rates; on C degrees per minute), under the feed override and
    /// within the axis's maximum cutting feed.
    Feed(f64),
}

/// A manual command.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Manual {
    /// A continuous jog toward + (`plus`) or −, until
    /// [`Engine::manual_stop`] or the axis's soft limit (without soft
    /// limits, [`JOG_REACH`]).
    Jog {
        /// The axis.
        axis: ManualAxis,
        /// Toward + (else −).
        plus: bool,
        /// How fast.
        rate: JogRate,
    },
    /// An incremental jog, or a handwheel's pulses times its increment:
    /// `distance` mm, signed (X on the diameter, as the machine file and
    /// the set points write it). Steps given while one runs follow it.
    Step {
        /// The axis.
        axis: ManualAxis,
        /// mm, signed (X a diameter).
        distance: f64,
        /// How fast.
        rate: JogRate,
    },
    /// A reference return: the axis goes to machine zero, the reference
    /// point, at the reference-return feed (№113).
    Home {
        /// The axis.
        axis: ManualAxis,
    },
}

/// Why a manual command was refused; nothing moved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ManualRefused {
    /// A program runs, stands stopped, ended or raised an alarm: manual
    /// moves are made between programs (reset first).
    NotIdle,
    /// A distance or feed that is not a finite number, or a feed ≤ 0.
    BadValue,
    /// C on a machine without a C axis.
    NoSuchAxis,
    /// The queue is full (steps given faster than the axes follow).
    Full,
}

impl<P: Plc> Engine<P> {
    /// Takes a manual command while no program runs (module comment).
    pub fn manual(&mut self, m: Manual) -> Result<(), ManualRefused> {
        let appending = self.manual && !self.reset_req;
        if !appending && (self.state != RunState::Idle || self.reset_req) {
            return Err(ManualRefused::NotIdle);
        }
        let (axis, to, kind) = self.manual_move(m)?;
        if !appending {
            self.begin_manual();
        }
        let mut end = self.q.tail();
        let mut c = None;
        match axis {
            ManualAxis::X => end.r = to,
            ManualAxis::Z => end.z = to,
            ManualAxis::C => c = Some(to),
        }
        let mv = Move {
            kind,
            path: Path::Line { to: end },
            shift: self.shift,
            c,
        };
        let pushed = self.q.push(Command::Move(mv), Tag::default());
        self.q.replan();
        pushed.map(|_| ()).map_err(|Full| ManualRefused::Full)
    }

    /// Stops a manual move: the axes decelerate to a stop, and the engine
    /// resets there. Nothing without a manual move.
    pub fn manual_stop(&mut self) {
        if self.manual {
            self.reset_req = true;
        }
    }

    /// The axis, its end coordinate (machine, X a radius) and the kind of
    /// move of `m`, starting from the end of what is queued.
    fn manual_move(&self, m: Manual) -> Result<(ManualAxis, f64, MoveKind), ManualRefused> {
        let (axis, rate) = match m {
            Manual::Jog { axis, rate, .. } | Manual::Step { axis, rate, .. } => (axis, rate),
            Manual::Home { axis } => (axis, JogRate::Feed(self.cfg.home_feed * 60.0)),
        };
        let (a, from) = self.manual_axis(axis).ok_or(ManualRefused::NoSuchAxis)?;
        // The machine file's X is a diameter; the queue's X a radius.
        let k = if axis == ManualAxis::X { 0.5 } else { 1.0 };
        let to = match m {
            Manual::Jog { plus: true, .. } => a.travel().map_or(from + JOG_REACH, |(_, max)| max),
            Manual::Jog { plus: false, .. } => a.travel().map_or(from - JOG_REACH, |(min, _)| min),
            Manual::Step { distance, .. } if distance.is_finite() => {
                let to = from + distance * k;
                a.travel().map_or(to, |(min, max)| to.max(min).min(max))
            }
            Manual::Step { .. } => return Err(ManualRefused::BadValue),
            Manual::Home { .. } => 0.0,
        };
        let kind = match rate {
            JogRate::Rapid => MoveKind::Rapid,
            JogRate::Feed(f) if f.is_finite() && f > 0.0 => MoveKind::Feed(Feed {
                f: f / 60.0,
                per_rev: false,
                fixed: false,
            }),
            JogRate::Feed(_) => return Err(ManualRefused::BadValue),
        };
        Ok((axis, to, kind))
    }

    /// The settings of `axis` and its coordinate where the queue ends
    /// (`None`: C on a machine without it).
    fn manual_axis(&self, axis: ManualAxis) -> Option<(&Axis, f64)> {
        let (at, c) = match self.manual {
            true => (self.q.tail(), self.q.tail_c()),
            false => (self.pos, self.c),
        };
        match axis {
            ManualAxis::X => Some((&self.cfg.x, at.r)),
            ManualAxis::Z => Some((&self.cfg.z, at.z)),
            ManualAxis::C => Some((self.cfg.c.as_ref()?, c)),
        }
    }

    /// A manual session starts: the queue the interpreter filled ahead is
    /// dropped (the reset at the end queues it again).
    fn begin_manual(&mut self) {
        self.lock_axes();
        self.q.clear();
        self.q.set_tail(self.pos);
        self.q.set_tail_c(self.c);
        self.started = false;
        self.manual = true;
        self.state = RunState::Running;
    }

    /// A period of a manual session: its moves run; when they have, the
    /// engine resets where the axes stand.
    /// (Feed hold stops a manual move as `manual_stop` does: cycle start
    /// has nothing to resume.)
    pub(super) fn manual_period(&mut self) {
        self.cycle_start = false;
        self.run();
        if matches!(self.state, RunState::Starved | RunState::Held) {
            self.reset_req = true;
        }
    }
}
