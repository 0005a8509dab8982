//! Threads: a chain of spindle-synchronised moves, one period at a time.
//!
//! A chain waits for the spindle's speed, plans its ramp, waits for the
//! index pulse (plus the start angle Q), then follows the spindle: the
//! long axis ramps up as a function of the spindle angle and locks onto
//! the helix, move after move of the chain, until it brakes for the
//! chain's end (or stands there with the spindle, in a rigid reversal).

use super::{Engine, Motion, RoomWarning};
use crate::command::{MoveKind, Tag, Thread};
use crate::follow::{Ahead, EndBrake, SLOWS};
use crate::geom::Curve;
use crate::math::V2;
use crate::planner::{ItemKind, Segment};
use crate::plc::{Plc, PlcFunction, SpindleDir};
use crate::profile::{brake_limit, stopping_distance};
use nc::error::Alarm;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Phase {
    /// Not in a thread.
    Off,
    /// Waiting for the spindle to reach its speed.
    WaitSpeed,
    /// Waiting for the index pulse + Q (`k`: the last whole count seen).
    WaitIndex { k: f64 },
    /// Accelerating from rest as a function of the spindle angle.
    Ramp,
    /// Position = lead × turns (minus a fixed lag).
    Locked,
    /// Braking to the end of the chain (the thread's run-out).
    Brake,
}

/// A thread chain in progress. Positions are functions of the spindle
/// angle θ (turns since the start pulse), so every pass of a multi-pass
/// thread follows the same helix whatever the period phase of its start:
/// a ramp at constant acceleration `alpha·θ²/2` (long-axis mm), then the
/// locked helix `S(θ − lag)`, tangent to the ramp where they meet.
#[derive(Debug, Clone, Copy)]
pub(super) struct ThreadRun {
    pub(super) phase: Phase,
    theta0: f64,
    alpha: f64,
    theta_l: f64,
    theta_lag: f64,
    /// Long-axis travel of the chain segments already left (ramp).
    g_base: f64,
    /// Lead revolutions at which the current segment starts (locked).
    phi_base: f64,
    /// Long-axis progress in the current segment.
    q: f64,
    /// Last synchronised path speed (the braking starts from it).
    pub(super) v_sync: f64,
    /// A rigid-tapping reversal is armed: the spindle brakes to the
    /// chain's end and the axis follows it there.
    rigid: bool,
}

impl ThreadRun {
    pub(super) const OFF: ThreadRun = ThreadRun {
        phase: Phase::Off,
        theta0: 0.0,
        alpha: 0.0,
        theta_l: 0.0,
        theta_lag: 0.0,
        g_base: 0.0,
        phi_base: 0.0,
        q: 0.0,
        v_sync: 0.0,
        rigid: false,
    };

    /// A chain whose first move has begun: it waits for the spindle.
    pub(super) const STARTING: ThreadRun = ThreadRun {
        phase: Phase::WaitSpeed,
        ..ThreadRun::OFF
    };
}

/// Revolutions to cover `q` along the long axis at lead `l` + `dl` per rev.
fn revs_for(q: f64, l: f64, dl: f64) -> f64 {
    if dl.abs() < 1e-15 {
        return q / l;
    }
    let disc = l * l + 2.0 * dl * q;
    if disc <= 0.0 {
        return f64::INFINITY;
    }
    (libm::sqrt(disc) - l) / dl
}

/// The speed of an axis a thread leg moves by `d` (mm) at `rps` spindle
/// turns a second, where the leg's long axis runs at its lead × rps.
fn axis_speed(leg: &Segment, d: f64, rps: f64) -> f64 {
    let MoveKind::Thread(t) = leg.kind else {
        return 0.0;
    };
    if leg.long_len > 0.0 {
        t.lead * rps * d / leg.long_len
    } else {
        0.0
    }
}

/// How the chain's point brakes on an axis for the chain's end, on the
/// chain's last leg `leg` (which moves the axis by `d` mm). The chain
/// brakes along that leg's path at its acceleration once the leg's rest
/// is its stopping distance (`chain_brake_limit`), so on the axis the
/// point slows at a·d/len from the stopping distance of its speed there
/// at that rate. Not known where the leg is shorter than that (W118):
/// the braking then begins on a leg before it, at other rates.
fn end_brake(leg: &Segment, d: f64, rps: f64, dt: f64) -> Option<EndBrake> {
    let decel = if leg.len > 0.0 {
        leg.a * d / leg.len
    } else {
        0.0
    };
    let from = stopping_distance(axis_speed(leg, d, rps), decel, dt);
    (decel > 0.0 && from <= d).then_some(EndBrake { from, decel })
}

/// The long axis's share of a move's path acceleration, `long` being the
/// move's length along it.
fn long_accel(seg: &Segment, long: f64) -> f64 {
    let u_long = if seg.len > 0.0 { long / seg.len } else { 1.0 };
    if matches!(seg.curve, crate::geom::Curve::Line { .. }) {
        seg.a * u_long
    } else {
        0.5 * seg.a
    }
}

/// Where the chain stands at a spindle angle: its `k`-th queued move,
/// `q` mm along that move's long axis, the move starting at `base` (long
/// mm in the ramp, lead revolutions when locked).
#[derive(Debug, Clone, Copy)]
struct ChainPoint {
    k: usize,
    q: f64,
    base: f64,
    ramp: bool,
}

impl<P: Plc> Engine<P> {
    /// A spindle-synchronised chain.
    pub(super) fn step_thread(&mut self) {
        let MoveKind::Thread(t) = self.cur.kind else {
            return;
        };
        self.motion = Motion::Thread;
        if self.thread.phase == Phase::WaitSpeed {
            if let Some(at) = self.spindle.take_rigid_origin() {
                // The move out of a rigid reversal: locked to the spindle
                // from the bottom's angle, no index pulse to wait for.
                self.thread = ThreadRun {
                    phase: Phase::Locked,
                    theta0: at,
                    ..ThreadRun::OFF
                };
            }
        }
        if self.thread.phase == Phase::WaitSpeed {
            self.wait_speed(&t);
            return;
        }
        if let Phase::WaitIndex { k } = self.thread.phase {
            if !self.index_passed(&t, k) {
                return;
            }
        }
        if self.thread.phase == Phase::Brake || self.reset_req {
            if self.thread.phase != Phase::Brake {
                self.thread.phase = Phase::Brake;
                self.thread.v_sync = 0.0;
            }
            self.step_path();
            return;
        }
        self.follow_spindle(&t);
    }

    /// Waits for the spindle to turn at its speed (E7005 when it stands
    /// too long), then plans the ramp and waits for the index pulse.
    fn wait_speed(&mut self, t: &Thread) {
        let work_x = (self.pos - self.shift).x();
        if self.spindle.commanded(work_x) <= 0.0 || self.spindle.stopped() {
            self.stall_s += self.dt;
            if self.stall_s >= self.cfg.spindle.stall_timeout_s {
                let tag = self.tag;
                self.raise(Alarm::SpindleStopped.into(), tag);
            }
            return;
        }
        if self.spindle.at_speed(work_x) {
            self.plan_ramp(t, work_x);
        }
    }

    /// The ramp of a chain whose spindle turns at its speed: an alarm
    /// when the lead at this speed asks an axis for more than its feed.
    fn plan_ramp(&mut self, t: &Thread, work_x: f64) {
        let seg = self.cur;
        let rps = self.spindle.rpm().abs() / 60.0;
        // The speed the spindle is settling to (at_speed allows 0.5 %
        // below it): the thread runs at that.
        let rps_ref = rps.max(self.spindle.commanded(work_x) / 60.0);
        if !crate::math::is_pos(t.lead) || self.chain_too_fast(rps_ref) {
            let tag = self.tag;
            self.raise(Alarm::BadThread.into(), tag);
            return;
        }
        let d = seg.to - seg.from;
        let dl = if seg.long_z { d.z.abs() } else { d.r.abs() };
        let a_long = long_accel(&seg, dl);
        // The ramp is a function of the spindle angle: plan it for the
        // speed the spindle is settling to (at_speed allows 0.5 % below
        // it), with the share `ramp_accel` leaves for ω̇.
        let a_ramp = nc::thread_room::ramp_accel(a_long, t.lead, self.cfg.spindle.accel_rpm_s);
        let alpha = a_ramp / (rps_ref * rps_ref);
        self.check_room(a_ramp, rps_ref);
        let (l, dlead) = (t.lead, t.dlead);
        let (theta_l, theta_lag) = if dlead.abs() > 1e-15 && alpha > dlead {
            let phi = l * (-1.0 + libm::sqrt(alpha / (alpha - dlead))) / dlead;
            let th = (l + dlead * phi) / alpha;
            (th, th - phi)
        } else {
            (l / alpha, l / (2.0 * alpha))
        };
        let qf = crate::math::rem_euclid(t.q_deg, 360.0) / 360.0;
        self.thread = ThreadRun {
            phase: Phase::WaitIndex {
                k: crate::math::floor(self.spindle.turns() - qf),
            },
            alpha,
            theta_l,
            theta_lag,
            ..ThreadRun::OFF
        };
    }

    /// Whether a queued leg of the chain asks an axis for more than its
    /// feed at `rps` spindle turns a second: the long axis runs at lead ×
    /// rps, the short one in proportion. Every leg counts, not only the
    /// first: a pull-out whose axis cannot run at its speed would otherwise
    /// brake the chain out of step with the spindle and spoil the lead.
    fn chain_too_fast(&self, rps: f64) -> bool {
        let mut k = 0;
        while let Some(seg) = self.q.seg(k) {
            let MoveKind::Thread(t) = seg.kind else { break };
            let d = seg.to - seg.from;
            let (dl, dsh, lax, sax) = if seg.long_z {
                (d.z.abs(), d.r.abs(), &self.cfg.z, &self.cfg.x)
            } else {
                (d.r.abs(), d.z.abs(), &self.cfg.x, &self.cfg.z)
            };
            let vlong = t.lead * rps;
            let vshort = if dl > 0.0 { vlong * dsh / dl } else { 0.0 };
            if vlong > lax.max_feed * (1.0 + 1e-9) || vshort > sax.max_feed * (1.0 + 1e-9) {
                return true;
            }
            if seg.v_exit <= 0.0 || !self.thread_next(k) {
                break;
            }
            k += 1;
        }
        false
    }

    /// Whether the index pulse (+ Q) has passed since count `k`: the ramp
    /// then starts from it.
    fn index_passed(&mut self, t: &Thread, k: f64) -> bool {
        let qf = crate::math::rem_euclid(t.q_deg, 360.0) / 360.0;
        let now = crate::math::floor(self.spindle.turns() - qf);
        if now <= k {
            return false;
        }
        self.thread.theta0 = now + qf;
        self.thread.phase = Phase::Ramp;
        true
    }

    /// Ramp or locked: moves to the chain's point at this spindle angle,
    /// or starts braking when that point is beyond what the path can
    /// still stop in.
    fn follow_spindle(&mut self, t: &Thread) {
        let theta = self.spindle.turns() - self.thread.theta0;
        self.lock_after_ramp(t, theta);
        let mut at = self.chain_point(theta);
        let Some(target) = self.q.seg(at.k).copied() else {
            return;
        };
        if !at.ramp && (target.v_exit <= 0.0 || !self.thread_next(at.k)) {
            if !self.thread.rigid {
                self.arm_rigid(at.k, &target, at.base);
            }
            if self.thread.rigid
                && self
                    .spindle
                    .rigid_at()
                    .is_some_and(|turns| self.spindle.turns() >= turns)
            {
                // The spindle stands at the bottom: so does the axis.
                at.q = target.long_len;
            }
        }
        let guess = if at.k == 0 { self.lam } else { 0.0 };
        let lam = target
            .curve
            .lam_at_long(target.long_z, at.q, target.long_len, guess);
        let (dist, scale) = self.chain_distance(at.k, lam);
        let v = dist.max(0.0) / self.dt;
        let at_end = self
            .q
            .seg(at.k)
            .is_some_and(|s| at.q >= s.long_len && s.v_exit <= 0.0);
        if !self.thread.rigid && (v > self.chain_brake_limit(at.k) || at_end) {
            self.thread.phase = Phase::Brake;
            self.thread.v_sync = self.v;
            self.step_path();
            return;
        }
        // (The path speed on the move the point lies on.)
        self.commit_chain_point(at, &target, lam, v / scale);
        if self.thread.rigid && at_end {
            // At the bottom with the spindle: what is left is standing.
            self.thread.phase = Phase::Brake;
        }
    }

    /// The end of the ramp: lock onto the helix through the ramp's point
    /// at θ_l (where they are tangent), not through the last period's
    /// point: that one lies up to a period behind, which would stall the
    /// axis for a period and shift the helix by the period phase of the
    /// start.
    fn lock_after_ramp(&mut self, t: &Thread, theta: f64) {
        let th = &mut self.thread;
        if th.phase == Phase::Ramp && theta >= th.theta_l {
            let q_l = 0.5 * th.alpha * th.theta_l * th.theta_l - th.g_base;
            th.phi_base = (th.theta_l - th.theta_lag) - revs_for(q_l, t.lead, t.dlead);
            th.phase = Phase::Locked;
        }
    }

    /// The chain's point at spindle angle `theta`: on the ramp, or on the
    /// helix, as far along the queued moves of the chain as it reaches.
    fn chain_point(&self, theta: f64) -> ChainPoint {
        let (mut k, mut q) = (0usize, 0.0);
        let ramp = self.thread.phase == Phase::Ramp;
        let mut base;
        if ramp {
            let g = 0.5 * self.thread.alpha * theta * theta;
            base = self.thread.g_base;
            while let Some(sk) = self.q.seg(k) {
                q = g - base;
                if q <= sk.long_len || sk.v_exit <= 0.0 || !self.thread_next(k) {
                    q = q.min(sk.long_len);
                    break;
                }
                base += sk.long_len;
                k += 1;
            }
        } else {
            let phi = theta - self.thread.theta_lag;
            base = self.thread.phi_base;
            while let Some(sk) = self.q.seg(k) {
                let MoveKind::Thread(tk) = sk.kind else { break };
                let r = revs_for(sk.long_len, tk.lead, tk.dlead);
                let local = phi - base;
                if local <= r || sk.v_exit <= 0.0 || !self.thread_next(k) {
                    q = (tk.lead * local + 0.5 * tk.dlead * local * local)
                        .min(sk.long_len)
                        .max(0.0);
                    break;
                }
                base += r;
                k += 1;
            }
        }
        ChainPoint { k, q, base, ramp }
    }

    /// The path distance from where the head move stands to parameter
    /// `lam` of the `k`-th queued move, the later moves seen from the
    /// head (`Segment::chain_scale`): this period's, to check against the
    /// envelope. And the scale of the `k`-th move seen from the head.
    fn chain_distance(&self, k: usize, lam: f64) -> (f64, f64) {
        let seg = self.cur;
        let mut dist = if k == 0 {
            (lam - self.lam) * seg.len
        } else {
            (1.0 - self.lam) * seg.len
        };
        let mut scale = 1.0;
        for j in 1..=k {
            if let (Some(before), Some(sj)) = (self.q.seg(j - 1), self.q.seg(j)) {
                scale *= before.chain_scale(sj);
                dist += if j == k { lam * sj.len } else { sj.len } * scale;
            }
        }
        (dist, scale)
    }

    /// The fastest a period may go and still stop on the ends ahead, to
    /// the `k`-th queued move (at least the head's).
    fn chain_brake_limit(&self, k: usize) -> f64 {
        let seg = self.cur;
        let a = seg.a;
        let d = seg.len - self.s;
        let mut lim = brake_limit(d, seg.v_exit, a, self.dt);
        let mut acc = d;
        // The later legs seen from the head (`Segment::chain_scale`).
        let mut scale = 1.0;
        for j in 0..k.max(1) {
            let (Some(sj), Some(n)) = (self.q.seg(j), self.q.seg(j + 1)) else {
                break;
            };
            if sj.v_exit <= 0.0 {
                break;
            }
            scale *= sj.chain_scale(n);
            acc += n.len * scale;
            lim = lim.min(brake_limit(
                acc,
                n.v_exit * scale,
                a.min(n.a * scale),
                self.dt,
            ));
        }
        lim
    }

    /// Moves to the chain's point: the moves before the `k`-th leave the
    /// queue, and the head is the one the point lies on.
    fn commit_chain_point(&mut self, at: ChainPoint, target: &Segment, lam: f64, v: f64) {
        // A point on the k-th move's start ends the period on the corner:
        // it ran the move before (`Engine::ran`).
        if at.k > 0 && lam * target.len <= 1e-12 {
            self.ran = self.q.get(at.k - 1).map(|it| it.tag);
        }
        for _ in 0..at.k {
            self.q.pop();
        }
        if at.k > 0 {
            if let Some(it) = self.q.get(0) {
                self.tag = it.tag;
                self.shift = it.shift;
                if let ItemKind::Move(n) = &it.kind {
                    self.cur = *n;
                }
            }
            if at.ramp {
                self.thread.g_base = at.base;
            } else {
                self.thread.phi_base = at.base;
            }
        }
        self.thread.q = at.q;
        self.lam = lam;
        self.s = lam * target.len;
        self.pos = target.curve.point(lam);
        self.v = v;
        self.thread.v_sync = v;
    }

    /// Arms a rigid-tapping reversal when the chain ends on the k-th
    /// queued move (`target`, started at lead revolution `base`) and the
    /// spindle reverses right after it (dwells between allowed, no M05:
    /// a floating holder's G33 stops the spindle first) before a thread
    /// back. The spindle then brakes at min(its acceleration, the long
    /// axis's / lead) to stand exactly where the axis reaches the end.
    fn arm_rigid(&mut self, k: usize, target: &Segment, base: f64) {
        let MoveKind::Thread(tk) = target.kind else {
            return;
        };
        if self.spindle.is_measured() || tk.dlead.abs() > 1e-15 || !crate::math::is_pos(tk.lead) {
            return;
        }
        let reverse = match self.spindle.dir() {
            SpindleDir::Cw => SpindleDir::Ccw,
            SpindleDir::Ccw => SpindleDir::Cw,
            _ => return,
        };
        let mut j = k + 1;
        let mut reversed = false;
        loop {
            match self.q.get(j).map(|i| i.kind) {
                Some(ItemKind::Dwell(_)) if !reversed => {}
                Some(ItemKind::Plc(PlcFunction::Spindle(d))) if !reversed && d == reverse => {
                    reversed = true;
                }
                Some(ItemKind::Plc(PlcFunction::Speed { .. })) if reversed => {}
                Some(ItemKind::Move(n)) if reversed && matches!(n.kind, MoveKind::Thread(_)) => {
                    break;
                }
                _ => return,
            }
            j += 1;
        }
        let a_long = long_accel(target, target.long_len);
        let accel = (self.cfg.spindle.accel_rpm_s / 60.0).min(a_long / tk.lead);
        let th = &self.thread;
        let at = th.theta0 + th.theta_lag + base + target.long_len / tk.lead;
        let rem = at - self.spindle.turns();
        let w = self.spindle.rpm().abs() / 60.0;
        if !crate::math::is_pos(accel) || rem < w * w / (2.0 * accel) + w * self.dt {
            // Too late to stop the spindle there: the axis brakes alone.
            return;
        }
        self.spindle.rigid_stop(at, accel);
        self.thread.rigid = true;
    }

    /// W118 at a thread start: the chain's first move against the entry
    /// length at `a_ramp`, and its last move, when it is queued already,
    /// against the stopping length.
    fn check_room(&mut self, a_ramp: f64, rps: f64) {
        let Some(first) = self.q.seg(0).copied() else {
            return;
        };
        let MoveKind::Thread(t) = first.kind else {
            return;
        };
        let v = t.lead * rps;
        let need = v * v / (2.0 * a_ramp);
        let warn = |seg: &Segment, tag: Tag, exit: bool, need: f64| RoomWarning {
            tag,
            exit,
            room_mm: seg.long_len,
            need_mm: need,
            rpm: rps * 60.0,
            long_z: seg.long_z,
        };
        if first.long_len < need {
            self.room_warning[0] = Some(warn(&first, self.tag, false, need));
        }
        // The last move of the chain, if the queue holds the chain's end.
        let mut k = 0;
        while self.thread_next(k) && self.q.seg(k).is_some_and(|s| s.v_exit > 0.0) {
            k += 1;
        }
        if self.q.get(k + 1).is_none() {
            return;
        }
        let (Some(last), Some(tag)) = (self.q.seg(k).copied(), self.q.get(k).map(|i| i.tag)) else {
            return;
        };
        let MoveKind::Thread(tl) = last.kind else {
            return;
        };
        let a_long = long_accel(&last, last.long_len);
        let v = tl.lead * rps;
        let need = v * v / (2.0 * a_long);
        if last.long_len < need {
            self.room_warning[1] = Some(warn(&last, tag, true, need));
        }
    }

    /// What lies ahead of the chain's point on `axis` (0: radial X, 1: Z)
    /// in the direction it moves there, over the straight legs of the
    /// chain, up to where that axis stops or turns; counted no further
    /// than `enough` (what the follower could use at its top speed).
    /// Unknown off a thread chain or on an arc. Where the run ends at a
    /// corner that stops or turns the axis, or at the chain's end, the
    /// axis must not pass it (docs/language.md: never past where the
    /// chain stops). The corners before it where the point runs on
    /// slower on the axis are the slows, at the speed the spindle turns
    /// now.
    pub(super) fn chain_runs_on(&self, axis: usize, enough: f64) -> Ahead {
        let along = |p: V2| if axis == 0 { p.r } else { p.z };
        let straight = |s: &Segment| matches!(s.curve, Curve::Line { .. });
        let Some(head) = self.q.seg(0).filter(|s| straight(s)) else {
            return Ahead::UNKNOWN;
        };
        let mut ahead = Ahead::UNKNOWN;
        if !matches!(head.kind, MoveKind::Thread(_)) {
            // The chain ended in this period: the move after it waits
            // until the axes meet the point where the chain left it.
            ahead.stops = true;
            return ahead;
        }
        let dir = along(head.to) - along(head.from);
        if dir == 0.0 {
            // The point stands on this axis.
            ahead.stops = true;
            return ahead;
        }
        let mut run = (along(head.to) - along(self.pos)) * dir.signum();
        if run < 0.0 {
            return ahead;
        }
        let rps = self.spindle.rpm().abs() / 60.0;
        let mut slowest = axis_speed(head, dir.abs(), rps);
        ahead.speed = slowest;
        let (mut leg_k, mut d_k) = (*head, dir.abs());
        let mut n = 0;
        let on = |k: usize| self.q.seg(k).is_some_and(|s| s.v_exit > 0.0) && self.thread_next(k);
        let mut k = 0;
        while run < enough {
            if !on(k) {
                // The chain ends: the point stops there, even where the
                // last leg is too short for it to brake (W118).
                ahead.stops = true;
                ahead.end = end_brake(&leg_k, d_k, rps, self.dt);
                break;
            }
            k += 1;
            let Some(leg) = self.q.seg(k).filter(|s| straight(s)) else {
                break;
            };
            let d = along(leg.to) - along(leg.from);
            if d * dir <= 0.0 {
                ahead.stops = true;
                break;
            }
            let u = axis_speed(leg, d.abs(), rps);
            (leg_k, d_k) = (*leg, d.abs());
            // (Slower by more than rounding: legs of one speed are not
            // corners that slow the axis. Past SLOWS corners the last one
            // takes the slower speed: the point is then taken to slow
            // sooner than it does, which only holds the axis back more.)
            if u < slowest * (1.0 - 1e-9) {
                if n < SLOWS {
                    ahead.slows[n] = (run, u);
                    n += 1;
                } else {
                    ahead.slows[SLOWS - 1].1 = u;
                }
                slowest = u;
            }
            run += d.abs();
        }
        ahead.run = run;
        ahead
    }

    fn thread_next(&self, k: usize) -> bool {
        matches!(self.q.seg(k + 1).map(|s| s.kind), Some(MoveKind::Thread(_)))
    }
}
