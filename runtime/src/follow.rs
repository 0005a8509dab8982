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
//! tracks the chain's point with at most its acceleration per period,
//! closing any lag with a braking law so that it lands on the point
//! without overshoot when the point stands. While it follows exactly (the
//! ramp, the locked helix) the set point is the chain point, bit for bit.
//!
//! It touches only its own fields: nothing allocates, nothing locks.

use crate::math::V2;
use crate::profile::brake_limit;

/// The share of an axis's acceleration that closes a lag; the rest is left
/// for the chain point's own speed changes. *Choice*: one half.
const CLOSE_SHARE: f64 = 0.5;

/// A lag this small (mm) is closed in the period: below the trace's
/// resolution (µm) by three orders of magnitude.
const SNAP_MM: f64 = 1e-9;

/// The set point of one axis following a moving point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct AxisFollow {
    /// Set point, slide units.
    p: f64,
    /// Its speed over the last period.
    v: f64,
    /// The followed point in the last period.
    t: f64,
}

impl AxisFollow {
    /// One period towards the point `t` with acceleration `a`.
    fn step(&mut self, t: f64, a: f64, dt: f64) {
        let vt = (t - self.t) / dt;
        // The lag before this period; the relative speed that closes it.
        let e0 = self.t - self.p;
        let close = brake_limit(e0.abs(), 0.0, CLOSE_SHARE * a, dt).copysign(e0);
        let v = (vt + close).clamp(self.v - a * dt, self.v + a * dt);
        let mut p = self.p + v * dt;
        if (t - p).abs() <= SNAP_MM {
            p = t;
        }
        self.v = (p - self.p) / dt;
        self.p = p;
        self.t = t;
    }
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
    /// accelerations `acc` (radial X, Z). Outside threads the set point is
    /// the target and the follower only keeps pace.
    pub fn step(&mut self, target: V2, thread: bool, acc: [f64; 2], dt: f64) -> V2 {
        let ts = [target.r, target.z];
        if !self.engaged && !thread {
            for (ax, &t) in self.axes.iter_mut().zip(&ts) {
                ax.v = (t - ax.p) / dt;
                ax.p = t;
                ax.t = t;
            }
            return target;
        }
        let mut exact = true;
        for ((ax, &t), &a) in self.axes.iter_mut().zip(&ts).zip(&acc) {
            let before = ax.t;
            ax.step(t, a, dt);
            exact &= ax.p == t && ax.v == (t - before) / dt;
        }
        self.engaged = thread || !exact;
        V2::new(self.axes[0].p, self.axes[1].p)
    }

    /// Drops any lag (a reset that re-seeds the machine position).
    pub fn snap(&mut self, at: V2) {
        for (ax, t) in self.axes.iter_mut().zip([at.r, at.z]) {
            *ax = AxisFollow { p: t, v: 0.0, t };
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
            f.step(t, a, DT);
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

    /// A point that moves within the limit is followed exactly.
    #[test]
    fn a_point_within_the_limit_is_followed_exactly() {
        let mut f = AxisFollow::default();
        for k in 0..50 {
            // 1000 mm/s², under the 1500 of the axis.
            let t = 0.5 * 1000.0 * ((k + 1) as f64 * DT).powi(2);
            f.step(t, 1500.0, DT);
            assert_eq!(f.p, t);
        }
    }
}
