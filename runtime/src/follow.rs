//! Axis following in thread chains.
//!
//! A thread chain is a function of the spindle angle: the long axis runs
//! at lead × spindle speed and the programmed path says where the other
//! axis must be at that point. Where the chain turns a corner at thread
//! speed (a G92/G76/G78 pull-out chamfer, a G32 run-out, a chained taper)
//! the short axis would have to change its speed in one period, which no
//! servo can. A real control lets that axis follow its command with its
//! acceleration limit, so the corner is cut round and the pull-out ends a
//! little later than programmed. [`Follower`] does the same: each axis
//! tracks the chain's point with at most its acceleration per period and
//! at most its top speed, closing any lag with a braking law so that it
//! lands on the point without overshoot when the point stands, and never
//! runs faster than it could stop where the point would if the point
//! braked at the axis's whole acceleration (the end of a chain). While it follows exactly (the
//! ramp, the locked helix) the set point is the chain point, bit for bit.
//!
//! It touches only its own fields: nothing allocates, nothing locks.

use crate::math::V2;
use crate::profile::{brake_limit, stopping_distance};

/// The share of an axis's acceleration that closes a lag; the rest is left
/// for the chain point's own speed changes. *Choice*: one half.
pub const CLOSE_SHARE: f64 = 0.5;

/// A lag this small (mm) is closed in the period: below the trace's
/// resolution (µm) by three orders of magnitude.
const SNAP_MM: f64 = 1e-9;

/// How many of the corners ahead where the point slows on an axis the
/// follower is told of ([`Ahead::slows`]).
pub const SLOWS: usize = 4;

/// What lies ahead of the followed point on one axis, in the direction it
/// moves there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ahead {
    /// How far on the point will still run before the axis stops or
    /// turns there (0: not known).
    pub run: f64,
    /// Whether the point stops or turns there on this axis, which the axis
    /// must then not pass (else the run ends where nothing more is known).
    pub stops: bool,
    /// Corners before that where the point runs on slower: how far on
    /// each is (mm), and the point's speed after it (mm/s); the nearest
    /// first, each slower than those before it, unused ones at infinity.
    /// The point runs no slower than that up to the next (where there are
    /// more, the last one carries the slowest speed of those beyond).
    pub slows: [(f64, f64); SLOWS],
    /// The point's speed on the axis on the leg it runs now (mm/s; 0:
    /// not known): over a period that crossed a corner its step is partly
    /// the speed before it.
    pub speed: f64,
    /// Where the run ends at the chain's end: how the point brakes for it.
    pub end: Option<EndBrake>,
}

/// How the chain's point brakes on one axis for the chain's end: from
/// `from` mm before the end (no sooner), at no more than `decel`. An
/// axis closing a lag on the point must not catch it as it slows
/// (`closing_speed`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndBrake {
    /// The axis distance before the end where the point begins to brake
    /// (mm).
    pub from: f64,
    /// The point's deceleration on the axis (mm/s²).
    pub decel: f64,
}

impl Ahead {
    /// Nothing known ahead.
    pub const UNKNOWN: Ahead = Ahead {
        run: 0.0,
        stops: false,
        slows: [(f64::INFINITY, 0.0); SLOWS],
        speed: 0.0,
        end: None,
    };
}

/// The set point of one axis following a moving point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct AxisFollow {
    /// Set point, slide units.
    p: f64,
    /// Its speed over the last period.
    v: f64,
    /// The followed point in the last period.
    t: f64,
    /// The corners ahead where the point slows, as of the last period
    /// (where each is on the axis, and the point's speed after it): the
    /// point may pass more than one in a period.
    corners: [Option<(f64, f64)>; SLOWS],
}

impl AxisFollow {
    /// One period towards the point `t` with acceleration `a`, never
    /// faster than `vmax`, with what lies `ahead` of the point.
    fn step(&mut self, t: f64, a: f64, vmax: f64, ahead_of: &Ahead, dt: f64) {
        let vt = (t - self.t) / dt;
        // The lag before this period; the relative speed that closes it.
        let e0 = self.t - self.p;
        let close = brake_limit(e0.abs(), 0.0, CLOSE_SHARE * a, dt).copysign(e0);
        // Closing a lag must neither take the axis past its top speed nor
        // past the point: the point may stop within the axis's
        // acceleration (a chain's end), so the axis keeps a speed from
        // which it stops where the point would (and a period's speed
        // change more: a point running on at a constant speed is followed
        // exactly). The speed clamp holds whatever the last period's speed
        // was: that one kept it too.
        let want = vt + close;
        let ahead = (t - self.p) * want.signum();
        // How far on the point may still run: where the chain stops or
        // turns the axis, exactly as far as it says (the axis must not
        // pass that: it brakes ahead of the point, and the lead there is
        // incomplete, as at a chain's end); else at least as far as it
        // would if it braked from the next period on, and as far as the
        // chain says (a lag then closes at the closing share, not in an
        // ever slower tail as the axis nears the point).
        let (until, stops) = (ahead_of.run, ahead_of.stops);
        let on = vt * want > 0.0;
        let runs_on = if !on {
            0.0
        } else if stops {
            until
        } else {
            (stopping_distance(vt.abs(), a, dt) - vt.abs() * dt).max(until)
        };
        // (A hair of rounding over, so that a point followed exactly stays so.)
        let over = |v: f64| v * (1.0 + 1e-12) + 1e-12;
        let mut room = over(brake_limit(ahead + runs_on, 0.0, a, dt));
        if on {
            room = room.min(over(self.passing_limit(t, vt, ahead, ahead_of, a, dt)));
        }
        self.corners = ahead_of
            .slows
            .map(|(d, u)| (on && d.is_finite()).then(|| (t + d.copysign(vt), u)));
        let v = want
            .clamp(-room, room)
            .clamp(self.v - a * dt, self.v + a * dt)
            .min(vmax)
            .max(-vmax);
        let mut p = self.p + v * dt;
        if (t - p).abs() <= SNAP_MM {
            p = t;
        }
        self.v = (p - self.p) / dt;
        self.p = p;
        self.t = t;
    }

    /// The fastest the axis may run in this period, moving as the point
    /// does, `ahead` mm behind where the point `t` now is, and never pass
    /// the point: a lagging axis closing its lag above the point's speed
    /// can still slow to that speed before it reaches the point (which
    /// the closing share keeps to, unless the axis came in faster), and
    /// after a corner ahead where the point slows to u, the axis, braking
    /// from now on at its whole acceleration, ends no farther on than the
    /// point once both run at u: (v − u)² ≤ 2a·(ahead − u·dt + d − u·τ),
    /// τ being when the point reaches the corner (a 45° leg into a
    /// steeper one; in the frame that runs with the point, the gap before
    /// this period is ahead − u·dt). The point runs at s (or its leg's
    /// speed, where that is lower), and after each corner at that
    /// corner's speed, up to the next: it is no sooner there (in a ramp
    /// it only runs faster), so each line d + u·(t − τ) lies below the
    /// point from then on, and an axis behind them all is behind the
    /// point. The corners the point passed in this period count so too
    /// (d = 0): its speed over the period is still partly the faster one.
    /// Where the chain's end lies ahead, each line bends into the point's
    /// braking where the line reaches the braking's start (no later than
    /// the point does, which is then no slower), and the axis closes on
    /// it no faster than [`closing_speed`] allows.
    fn passing_limit(&self, t: f64, vt: f64, ahead: f64, ahead_of: &Ahead, a: f64, dt: f64) -> f64 {
        let s = vt.abs();
        // The limit behind the line of speed u through the corner d mm
        // on, reached at τ.
        let behind = |u: f64, d: f64, tau: f64| {
            let gap = ahead - u * dt + d - u * tau;
            let mut w = brake_limit(gap, 0.0, a, dt);
            if let Some(end) = ahead_of.end {
                let tb = (tau + (ahead_of.run - end.from - d) / u).max(0.0);
                w = w.min(closing_speed(gap, a, end.decel, tb, u / end.decel, dt));
            }
            u + w
        };
        let mut lim = f64::INFINITY;
        if ahead > 0.0 {
            lim = behind(s, 0.0, 0.0);
        }
        for &(c, u) in self.corners.iter().flatten() {
            if (t - c) * vt >= 0.0 && u < s {
                lim = lim.min(behind(u, 0.0, 0.0));
            }
        }
        // (Where the point is at each corner, and when, at the speeds
        // before it.)
        let leg = if ahead_of.speed > 0.0 {
            s.min(ahead_of.speed)
        } else {
            s
        };
        let (mut at, mut tau, mut speed) = (0.0, 0.0, leg);
        for &(d, u) in ahead_of.slows.iter().filter(|c| c.0.is_finite()) {
            tau += (d - at) / speed;
            at = d;
            if u < speed {
                speed = u;
                lim = lim.min(behind(u, d, tau));
            }
        }
        lim
    }
}

/// How much faster than the point an axis `g` mm behind it (in the
/// frame that runs with the point) may run and never pass it, where the
/// point runs on for `tb` seconds, then slows at `decel` and stands
/// after `ts` more. Braking at `a` from now on, the axis either matches
/// the point's speed within `tb` (the relative speed w ≤ a·tb; that it
/// stops within g is the plain limit), or it is x = w − a·tb faster when
/// the point begins to brake, with G − x·tb left (G = g − a·tb²/2), and
/// closes at r = a − decel from then on: the gap is least where x runs
/// out (x ≤ r·ts: x² + 2·r·tb·x ≤ 2·r·G) or where the point stands (x ≥
/// r·ts: G − x·(tb + ts) + r·ts²/2 ≥ 0); after that the axis only has to
/// stop where the point stands, which the plain limit to the chain's end
/// holds. One period's speed step off (the continuous bound is a little
/// over the discrete one).
fn closing_speed(g: f64, a: f64, decel: f64, tb: f64, ts: f64, dt: f64) -> f64 {
    let before = a * tb;
    let r = a - decel;
    let big_g = g - 0.5 * a * tb * tb;
    let at_stand = (big_g + 0.5 * r * ts * ts) / (tb + ts);
    let x = if at_stand >= r * ts || r <= 0.0 {
        at_stand
    } else {
        let disc = r * tb * r * tb + 2.0 * r * big_g;
        if disc < 0.0 {
            0.0
        } else {
            (libm::sqrt(disc) - r * tb).min(r * ts)
        }
    };
    if x > 0.0 {
        (before + x - a * dt).max(before)
    } else {
        before
    }
}

/// What the follower knows of each axis (radial X, Z) in a period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowAxes {
    /// Acceleration, mm/s².
    pub acc: [f64; 2],
    /// Top speed, mm/s.
    pub vmax: [f64; 2],
    /// What lies ahead of the point on each axis.
    pub ahead: [Ahead; 2],
}

/// X (radial) and Z following the chain point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Follower {
    axes: [AxisFollow; 2],
    engaged: bool,
}

impl Follower {
    /// Whether the set point may differ from the programmed point: in a
    /// thread chain, and after it until the lag is closed.
    pub fn engaged(&self) -> bool {
        self.engaged
    }

    /// One period: the set point for the programmed point `target`
    /// (`thread`: the period belongs to a thread chain), with the axes'
    /// accelerations `acc` and top speeds `vmax` and what lies ahead of
    /// the point on each axis (radial X, Z). Outside threads the set point is the target
    /// and the follower only keeps pace.
    pub fn step(&mut self, target: V2, thread: bool, axes: FollowAxes, dt: f64) -> V2 {
        let ts = [target.r, target.z];
        if !self.engaged && !thread {
            for (ax, &t) in self.axes.iter_mut().zip(&ts) {
                ax.v = (t - ax.p) / dt;
                ax.p = t;
                ax.t = t;
                ax.corners = [None; SLOWS];
            }
            return target;
        }
        let mut exact = true;
        for (i, (ax, &t)) in self.axes.iter_mut().zip(&ts).enumerate() {
            let before = ax.t;
            ax.step(t, axes.acc[i], axes.vmax[i], &axes.ahead[i], dt);
            exact &= ax.p == t && ax.v == (t - before) / dt;
        }
        self.engaged = thread || !exact;
        V2::new(self.axes[0].p, self.axes[1].p)
    }

    /// Drops any lag (a reset that re-seeds the machine position).
    pub fn snap(&mut self, at: V2) {
        for (ax, t) in self.axes.iter_mut().zip([at.r, at.z]) {
            *ax = AxisFollow {
                p: t,
                v: 0.0,
                t,
                corners: [None; SLOWS],
            };
        }
        self.engaged = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 0.001;

    /// A point that jumps from standing to 15 mm/s (a 45° pull-out at the
    /// speed of lead 1.5 × 600 rpm): the follower reaches the speed in
    /// 15 / (1500 · 0.001) = 10 periods, never changes its speed by more
    /// than a·dt = 1.5 mm/s per period, and lands exactly on the point
    /// where it stops.
    #[test]
    fn a_step_in_speed_is_followed_within_the_acceleration() {
        let mut f = AxisFollow::default();
        let (a, v) = (1500.0, 15.0);
        let mut t = 0.0;
        let mut prev_v = 0.0;
        let mut reached = None;
        for k in 0..400 {
            if k < 100 {
                t += v * DT;
            }
            f.step(t, a, f64::INFINITY, &Ahead::UNKNOWN, DT);
            assert!((f.v - prev_v).abs() <= a * DT * (1.0 + 1e-9), "period {k}");
            if reached.is_none() && f.v >= v - 1e-9 {
                reached = Some(k + 1);
            }
            prev_v = f.v;
        }
        assert_eq!(reached, Some(10));
        assert_eq!(f.p, t);
        assert_eq!(f.v, 0.0);
    }

    /// A point that jumps to 50 mm/s (a 45° pull-out of lead 2 at 1500
    /// rpm), runs 60 periods and brakes at the axis's whole acceleration
    /// (the chain's end): the axis, 0.8 mm behind after its ramp, closes
    /// the lag without passing its top speed (66.667 mm/s, 4000 mm/min)
    /// and without running past the point where it stops (the law that
    /// only closed the lag went past it by 0.1 mm).
    #[test]
    fn a_lag_closes_within_the_top_speed_and_never_past_a_braking_point() {
        let (a, vmax) = (1500.0, 4000.0 / 60.0);
        // The point: 60 periods at 50 mm/s, then 1.5 mm/s slower each
        // period down to a stand (period 94 on).
        let mut path = alloc::vec::Vec::new();
        let (mut t, mut vt) = (0.0, 50.0);
        for k in 0..400 {
            if k >= 60 {
                vt = f64::max(vt - a * DT, 0.0);
            }
            t += vt * DT;
            path.push(t);
        }
        let end = t;
        let mut f = AxisFollow::default();
        let mut prev_v = 0.0;
        for (k, &t) in path.iter().enumerate() {
            f.step(t, a, vmax, &Ahead::UNKNOWN, DT);
            assert!(
                f.v.abs() <= vmax * (1.0 + 1e-12),
                "period {k}: {} mm/s",
                f.v
            );
            // (The snap onto the point may add SNAP_MM in a period.)
            let step = (f.v - prev_v).abs();
            assert!(step <= a * DT + SNAP_MM / DT, "period {k}: {step}");
            assert!(f.p <= end + 1e-12, "period {k}: {} past {end}", f.p);
            prev_v = f.v;
        }
        assert_eq!(f.p, end, "lands on the point");
    }

    /// A point that jumps from standing to 15 mm/s and runs on for 2 mm
    /// (a run-out whose long axis is this one): the axis ramps in 10
    /// periods, 0.0675 mm behind then (0.15 less 1.5·(1+…+10)·0.001), and
    /// closes the lag at half its acceleration: up to c_p over the point
    /// at a, down on the closing curve at a/2, with c_p²·3/2a = 0.0675,
    /// c_p = 8.2 mm/s: 5.5 + 11 ms, on the point after about 26.5 periods.
    /// Not told how far the point runs on, the axis keeps a speed from
    /// which it could stop where the point would if it braked now, and
    /// the lag closes ever slower (time constant 15/1500 = 10 ms): 10 µm
    /// are still left at period 32.
    #[test]
    fn a_lag_closes_at_the_closing_share_when_the_point_runs_on() {
        let (a, v) = (1500.0, 15.0);
        let run = |until: f64| {
            let mut f = AxisFollow::default();
            let mut t = 0.0;
            let mut on_point = None;
            for k in 0..60 {
                t += v * DT;
                let ahead = Ahead {
                    run: (2.0 - t).max(0.0) * until,
                    ..Ahead::UNKNOWN
                };
                f.step(t, a, 4000.0 / 60.0, &ahead, DT);
                if on_point.is_none() && f.p == t {
                    on_point = Some(k + 1);
                }
                if k + 1 == 32 {
                    return (on_point, t - f.p, f.v);
                }
            }
            unreachable!()
        };
        let (told, lag, speed) = run(1.0);
        assert!(told.is_some_and(|k| (26..=28).contains(&k)), "{told:?}");
        assert_eq!(lag, 0.0);
        assert!((speed - v).abs() < 1e-6, "{speed}");
        let (untold, lag, _) = run(0.0);
        assert_eq!(untold, None);
        assert!(lag > 5e-3, "{lag}");
    }

    /// A point that jumps to 50 mm/s, runs 2 mm and slows to 5 mm/s at a
    /// corner (a 45° leg of a chain into a steep one): the axis, 0.83 mm
    /// behind after its ramp and closing the lag above 50 mm/s, has to
    /// come down to 5 mm/s. Told of the corner while it lies ahead of the
    /// point, it never passes the point and never turns back; told only
    /// that the point runs on, it passes the point by more than 0.1 mm
    /// and comes back.
    #[test]
    fn an_axis_told_of_a_slower_corner_never_passes_the_point() {
        let (a, vmax, corner) = (1500.0, 4000.0 / 60.0, 2.0);
        let run = |told: bool| {
            let mut f = AxisFollow::default();
            let (mut t, mut over, mut back) = (0.0, f64::NEG_INFINITY, 0.0f64);
            for _ in 0..400 {
                t = if t < corner {
                    (t + 50.0 * DT).min(corner)
                } else {
                    t + 5.0 * DT
                };
                let ahead = Ahead {
                    run: 10.0 - t,
                    stops: false,
                    slows: if told && t < corner {
                        [
                            (corner - t, 5.0),
                            (f64::INFINITY, 0.0),
                            (f64::INFINITY, 0.0),
                            (f64::INFINITY, 0.0),
                        ]
                    } else {
                        Ahead::UNKNOWN.slows
                    },
                    speed: 0.0,
                    end: None,
                };
                f.step(t, a, vmax, &ahead, DT);
                over = over.max(f.p - t);
                back = back.min(f.v);
            }
            (over, back)
        };
        let (over, back) = run(true);
        assert!(over <= 1e-12, "passed the point by {over} mm");
        assert!(back >= 0.0, "turned back at {back} mm/s");
        let (over, back) = run(false);
        assert!(over > 0.1 && back < 0.0, "{over} {back}");
    }

    /// An axis following a point that runs `legs` (length mm, speed mm/s)
    /// one after another from 0 and stops at their end, the axis running
    /// with it at the first leg's speed from the start, told what lies
    /// ahead as the runtime tells it (`chain_runs_on`: the corners where
    /// the point runs slower than on every leg before, and where it
    /// stops). How far the axis ever was past the point, and its most
    /// negative speed.
    fn follow_legs(legs: &[(f64, f64)], a: f64, vmax: f64) -> (f64, f64) {
        follow_braking_legs(legs, 0.0, legs[0].1, a, vmax)
    }

    /// The same, where the point brakes for the end at `decel` on its
    /// last leg (0: it stops there at once) once the leg's rest is its
    /// stopping distance, as a chain brakes for its end, and the axis
    /// starts at speed `v0`.
    fn follow_braking_legs(
        legs: &[(f64, f64)],
        decel: f64,
        v0: f64,
        a: f64,
        vmax: f64,
    ) -> (f64, f64) {
        let total: f64 = legs.iter().map(|l| l.0).sum();
        let last = legs[legs.len() - 1];
        let from = stopping_distance(last.1, decel, DT);
        let end = (decel > 0.0 && from <= last.0).then_some(EndBrake { from, decel });
        let mut f = AxisFollow {
            v: v0,
            ..AxisFollow::default()
        };
        let (mut over, mut back) = (f64::NEG_INFINITY, 0.0f64);
        let (mut k, mut into, mut t) = (0, 0.0, 0.0);
        for _ in 0..20_000 {
            // One period of the point: on along the legs at their speeds,
            // no faster than it can still stop at the end.
            let before = t;
            let mut left = DT;
            while k < legs.len() && left > 0.0 {
                let step = (legs[k].1 * left).min(legs[k].0 - into);
                into += step;
                t += step;
                left -= step / legs[k].1;
                if into >= legs[k].0 {
                    (k, into) = (k + 1, 0.0);
                }
            }
            let rest = total - before;
            if decel > 0.0 && rest <= last.0 && t - before > brake_limit(rest, 0.0, decel, DT) * DT
            {
                (t, into) = (before + brake_limit(rest, 0.0, decel, DT) * DT, 0.0);
                k = 0;
                while k < legs.len() && into + legs[k].0 <= t {
                    into += legs[k].0;
                    k += 1;
                }
                into = t - into;
            }
            let mut ahead = Ahead {
                run: total - t,
                stops: true,
                end,
                ..Ahead::UNKNOWN
            };
            let (mut n, mut slowest, mut run) = (0, legs.get(k).map_or(0.0, |l| l.1), 0.0);
            ahead.speed = slowest;
            for (j, leg) in legs.iter().enumerate().skip(k) {
                if j > k && leg.1 < slowest {
                    if n < SLOWS {
                        ahead.slows[n] = (run, leg.1);
                        n += 1;
                    } else {
                        ahead.slows[SLOWS - 1].1 = leg.1;
                    }
                    slowest = leg.1;
                }
                run += if j == k { leg.0 - into } else { leg.0 };
            }
            f.step(t, a, vmax, &ahead, DT);
            over = over.max(f.p - t);
            back = back.min(f.v);
        }
        assert!((t - total).abs() < 1e-9 && f.p == t, "lands on the point");
        (over, back)
    }

    /// A point that runs at 66.667 mm/s (lead 4 at 1000 rev/min), slows
    /// to 22.7 mm/s for 16 µm and then to 0.27 mm/s for 16 µm (a chain of
    /// short legs into a radial one: the thread target's finding), then
    /// runs on at 66.667 mm/s: it passes both corners within one period.
    /// The axis has to brake for the slower one over 1.11 mm and must
    /// never pass the point. Remembering only the nearest corner of the
    /// last period, it braked for the faster one alone in the period the
    /// point passed both, and ran past the point (in the thread target's
    /// chain it sped up by a·dt there and ran 0.06 mm past).
    #[test]
    fn an_axis_whose_point_passes_two_corners_in_a_period_never_passes_it() {
        let legs = [
            (3.0, 200.0 / 3.0),
            (0.016, 22.7),
            (0.016, 0.27),
            (3.0, 200.0 / 3.0),
        ];
        let (over, back) = follow_legs(&legs, 2000.0, 4000.0 / 60.0);
        assert!(over <= 1e-12, "passed the point by {over} mm");
        assert!(back >= 0.0, "turned back at {back} mm/s");
    }

    /// Corners in a row where the point slows step by step: 60 mm/s,
    /// then 0.3 mm at 20 mm/s, then 1 mm/s. The point reaches the second
    /// corner 10 ms later than at 60 mm/s all the way, so an axis that
    /// took it to come at d/60 s would brake too late for it (it ran
    /// 0.01 mm past the point once the point had passed the first
    /// corner, its step over that period still partly at 60). And six
    /// such corners, more than the follower is told of one by one: the
    /// slowest speed counts from the last one it is told of.
    #[test]
    fn corners_that_slow_the_point_step_by_step_are_never_passed() {
        let steps = [(3.0, 60.0), (0.3, 20.0), (2.0, 1.0), (3.0, 60.0)];
        let (over, back) = follow_legs(&steps, 1500.0, 4000.0 / 60.0);
        assert!(over <= 1e-12, "passed the point by {over} mm");
        assert!(back >= 0.0, "turned back at {back} mm/s");
        let many = [
            (3.0, 60.0),
            (0.05, 50.0),
            (0.05, 40.0),
            (0.05, 30.0),
            (0.05, 20.0),
            (0.05, 10.0),
            (2.0, 0.5),
        ];
        let (over, back) = follow_legs(&many, 1500.0, 4000.0 / 60.0);
        assert!(over <= 1e-12, "passed the point by {over} mm");
        assert!(back >= 0.0, "turned back at {back} mm/s");
    }

    /// A point that runs at 66.667 mm/s (X long on a thread leg), then
    /// slows to 1.04 mm/s for its last 0.0465 mm (a leg along Z of 2.984
    /// mm at lead 4, 1000 rev/min), where it brakes for the chain's end at
    /// 31.2 mm/s² (the path's 2000 mm/s² times X's share) over its last
    /// 17.8 µm. The axis at 1500 mm/s² starts at 10 mm/s as the point
    /// jumps to its speed, and closes the lag at up to 100 mm/s, braking
    /// for the corner on the line of the slow leg. Taking the point to run
    /// on at 1.04 mm/s, it caught the point as the point braked, passed it
    /// by 1.1 µm and came back (in the thread target's chain by 0.85 µm).
    /// Told how the point brakes, it never passes it and never turns back.
    #[test]
    fn an_axis_closing_on_a_point_that_brakes_for_the_end_never_passes_it() {
        let legs = [(2.03, 200.0 / 3.0), (0.0465, 1.04)];
        let (over, back) = follow_braking_legs(&legs, 31.2, 10.0, 1500.0, 100.0);
        assert!(over <= 1e-12, "passed the point by {over} mm");
        assert!(back >= 0.0, "turned back at {back} mm/s");
    }

    /// A point that moves within the limit is followed exactly.
    #[test]
    fn a_point_within_the_limit_is_followed_exactly() {
        let mut f = AxisFollow::default();
        for k in 0..50 {
            // 1000 mm/s², under the 1500 of the axis.
            let t = 0.5 * 1000.0 * ((k + 1) as f64 * DT).powi(2);
            f.step(t, 1500.0, f64::INFINITY, &Ahead::UNKNOWN, DT);
            assert_eq!(f.p, t);
        }
    }
}
