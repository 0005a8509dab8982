//! What `gbvm check` allows a thread chain: the incomplete leads at both
//! ends of a thread, the bound within which a corner taken at speed is
//! passed, and the time an axis takes to catch up with the chain after a
//! corner changed its speed (`runtime::follow`'s law, worked out by
//! hand).

use super::{LEAD_TOL, PATH_MM};
use crate::config::Axis;
use crate::follow::CLOSE_SHARE;
use crate::math::V2;
use nc::thread_room::z_is_long;

/// An axis catching up with a thread chain after corners that changed
/// its speed ([`catch_up_time`]), counted from the start of the leg the
/// chain is on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct CatchUp {
    /// Seconds until the axis keeps the lead again (within [`LEAD_TOL`]).
    pub(super) lead_s: f64,
    /// Seconds until it is back on the chain's point (infinite for an
    /// axis at its top speed, which keeps its lag).
    pub(super) lag_s: f64,
    /// The steps in its speed not caught up with yet, mm/s: the lag is at
    /// most c²/2a.
    pub(super) c: f64,
}

impl CatchUp {
    pub(super) const NONE: CatchUp = CatchUp {
        lead_s: 0.0,
        lag_s: 0.0,
        c: 0.0,
    };

    /// A corner's step: the axis `ax` must run `w0` mm/s faster (negative:
    /// slower) to keep to the chain at `v` mm/s, with `runs` mm of the
    /// chain ahead on it in the direction it moves. The follower closes
    /// the lag on its closing curve ([`catch_up_time`]) where the point
    /// runs on far enough for the axis to stop behind it, (v + c_p)²/2a
    /// beyond the catch-up's own travel; else at least on the slower tail
    /// ([`tail_time`]).
    pub(super) fn add(&mut self, ax: &Axis, v: f64, w0: f64, runs: f64) {
        let span = |w| catch_up_span(ax, v, w, runs);
        let (lead, lag) = span(w0);
        // A lag still open from corners before closes at this leg's
        // speed now, which may leave less room below the top speed: at
        // most as slowly as one step of all of them.
        let (lead_all, lag_all) = if self.c > 0.0 {
            span((self.c + w0.abs()).copysign(w0))
        } else {
            (0.0, 0.0)
        };
        self.lead_s = (self.lead_s + lead).max(lead_all);
        self.lag_s = (self.lag_s + lag).max(lag_all);
        self.c += w0.abs();
    }
}

/// The times (s) an axis `ax` takes to keep the lead again and to close
/// its lag after a step `w` in its speed, keeping to the chain at `v`
/// with `runs` mm of the chain ahead on it ([`CatchUp::add`]).
fn catch_up_span(ax: &Axis, v: f64, w: f64, runs: f64) -> (f64, f64) {
    let (a, vmax) = (ax.accel, ax.max_feed);
    let curve = |tol| catch_up_time(v, w, a, vmax, tol);
    let peak = w.abs() / libm::sqrt(1.0 + 1.0 / CLOSE_SHARE);
    let free = runs >= v * curve(0.0) + (v + peak) * (v + peak) / (2.0 * a);
    let time = |tol, eps| {
        let t = curve(tol);
        if free {
            t
        } else {
            t.max(tail_time(v, w, a, vmax, eps))
        }
    };
    let lag = if v < vmax {
        time(0.0, 0.5 * PATH_MM)
    } else {
        f64::INFINITY
    };
    (time(LEAD_TOL, LEAD_TOL * v * v / a), lag)
}

/// The distance the long axis of a thread needs to reach speed `v` from
/// rest (or to stop from it): v²/(2a) at the highest long-axis
/// acceleration that keeps both axes within their limits, `a_long`, and
/// `a_short` × long/short travel for a taper (`long`, `short`: the
/// travels of the two axes, slide units).
pub fn incomplete_lead(v: f64, a_long: f64, a_short: f64, long: f64, short: f64) -> f64 {
    let a = if short.abs() > 1e-12 {
        a_long.min(a_short * (long / short).abs())
    } else {
        a_long
    };
    v * v / (2.0 * a)
}

/// Long-axis travel of a thread leg of travel `d` (radius, Z).
pub(super) fn long_len(d: V2) -> f64 {
    if long_is_z(d) {
        d.z.abs()
    } else {
        d.r.abs()
    }
}

/// The travel per spindle turn (radius, Z) of a thread leg of travel `d`
/// at lead `lead` along its long axis.
pub(super) fn per_turn(d: V2, lead: f64) -> V2 {
    let l = long_len(d);
    if l > 0.0 {
        V2::new(d.r / l * lead, d.z / l * lead)
    } else {
        V2::ZERO
    }
}

/// How far the set points may pass from the corner where a thread chain
/// turns at speed from leg `legs[0]` into `legs[1]` (travel, (lead, lead
/// change)), on axes of accelerations `acc` (radial X, Z) at period `dt`.
///
/// Up to the corner the axes follow the chain's point exactly; in the
/// period in which the chain turns, an axis whose speed the corner
/// changes may change its own by at most a·dt (it follows the new leg
/// within its acceleration, `runtime::follow`), so its set point lies at
/// most a·dt² from where the old leg's straight run would have put it,
/// and an axis whose speed stays (the long axis, locked to the spindle)
/// lies on it. The chord of that period runs from a point of the old leg
/// towards that point: it passes the corner, which lies on the old leg's
/// run within the period, at most √(Σ a²)·dt² away (over the axes whose
/// speed changes: a continuous servo following the same law passes
/// through the corner itself; the chord is the period's discretisation).
/// 0.0015 mm for a pull-out that turns X (1500 mm/s²) at 1 ms. A corner
/// where no axis changes speed gives 0.
pub fn chain_corner_mm(legs: [(V2, (f64, f64)); 2], acc: [f64; 2], dt: f64) -> f64 {
    let [(d0, (l0, dl0)), (d1, (l1, _))] = legs;
    // The lead at the end of the incoming leg (G34: ℓ² + 2·R·L).
    let l_end = libm::sqrt((l0 * l0 + 2.0 * dl0 * long_len(d0)).max(0.0));
    let (u0, u1) = (per_turn(d0, l_end), per_turn(d1, l1));
    let mut a2 = 0.0;
    if (u0.r - u1.r).abs() > 1e-9 {
        a2 += acc[0] * acc[0];
    }
    if (u0.z - u1.z).abs() > 1e-9 {
        a2 += acc[1] * acc[1];
    }
    libm::sqrt(a2) * dt * dt
}

/// The long-axis travel over which a thread leg that its chain enters at
/// speed may miss its lead: the leg's long axis has to run `w0` mm/s
/// faster than it did (negative: slower) and follows the chain's point
/// within its acceleration `a` and top speed `vmax` (`runtime::follow`),
/// so it falls behind and then closes the lag at [`CLOSE_SHARE`] of `a`.
/// The lead is the chain's (`v` mm/s) again once the axis runs at `v`
/// on the point, or within `tol` of `v` behind it (an axis whose top speed
/// is the thread's own never closes the lag, but keeps the lead). 0 when
/// the axis keeps its speed.
///
/// In the follower's relative speed c (the axis's speed less `v`) from
/// c₀ = −w0: c reaches 0 at `a` (time |c₀|/a) while a lag c₀²/2a builds
/// up, rises at `a` to a peak c_p and falls to 0 on the closing curve
/// c = √(2·s·a·e) (s = CLOSE_SHARE); the two close the lag when
/// c_p²·(1 + 1/s)/2a = c₀²/2a. A peak the top speed cuts to c_m runs at
/// c_m until the lag left is the curve's.
pub fn catch_up_lead(v: f64, w0: f64, a: f64, vmax: f64, tol: f64) -> f64 {
    v * catch_up_time(v, w0, a, vmax, tol)
}

/// The time [`catch_up_lead`] takes: until the axis runs on the point at
/// `v`, or within `tol` of `v` behind it.
pub fn catch_up_time(v: f64, w0: f64, a: f64, vmax: f64, tol: f64) -> f64 {
    if w0 == 0.0 || a <= 0.0 {
        return 0.0;
    }
    let s = CLOSE_SHARE;
    let c0 = w0.abs();
    let lag = c0 * c0 / (2.0 * a);
    let peak = c0 / libm::sqrt(1.0 + 1.0 / s);
    // (Slower: the axis may run backwards down to −vmax.)
    let room = if w0 > 0.0 { vmax - v } else { vmax + v };
    let mut t = c0 / a;
    if peak <= room {
        t += peak / a + peak / (s * a);
    } else if room > tol * v {
        let rise = room * room * (1.0 + 1.0 / s) / (2.0 * a);
        t += room / a + (lag - rise) / room + room / (s * a);
    } else {
        // The peak is within the tolerance of the lead: only reaching it counts.
        t += room.max(0.0) / a;
    }
    t
}

/// The time an axis following a thread chain takes to close the lag a
/// step `w0` in its speed gave it to within `eps` mm, when the chain point
/// is about to stop or turn on that axis, so that the follower keeps a
/// speed from which it could stop where the point would if the point
/// braked at the axis's whole acceleration (`runtime::follow`): the axis
/// reaches its new speed `v` in |w0|/a with a lag w0²/2a, gains at most
/// vmax − v on the point while that binds, and then at least a·lag/v,
/// so that the lag falls as e^(−a·t/v). (Slower than
/// [`catch_up_time`]'s closing curve, which holds where the point runs
/// on.)
pub fn tail_time(v: f64, w0: f64, a: f64, vmax: f64, eps: f64) -> f64 {
    if w0 == 0.0 || a <= 0.0 || v <= 0.0 {
        return 0.0;
    }
    let c0 = w0.abs();
    let lag = c0 * c0 / (2.0 * a);
    let mut t = c0 / a;
    // Where the top speed binds: a·lag/v above vmax − v.
    let bound = (vmax - v).max(0.0) * v / a;
    let exp_from = if lag > bound && vmax > v {
        t += (lag - bound) / (vmax - v);
        bound
    } else {
        lag
    };
    if exp_from > eps {
        t += v / a * libm::log(exp_from / eps);
    }
    t
}

/// How each axis's speed (mm per turn, radial X and Z) changes where a
/// chain turns from leg `legs[0]` into `legs[1]` at speed (travel,
/// (lead, lead change)).
pub fn axis_steps(legs: [(V2, (f64, f64)); 2]) -> V2 {
    let [(d0, (l0, dl0)), (d1, (l1, _))] = legs;
    let l_end = libm::sqrt((l0 * l0 + 2.0 * dl0 * long_len(d0)).max(0.0));
    per_turn(d1, l1) - per_turn(d0, l_end)
}

/// Whether Z is the long axis of a thread move of travel `d` (radius, Z):
/// the kernel's rule, ties within rounding going to Z.
pub(super) fn long_is_z(d: V2) -> bool {
    z_is_long(d.r, d.z)
}
