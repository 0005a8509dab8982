//! Jerk limiting: a moving average over the last N set points of the
//! acceleration-limited profile. Averaging N samples of a speed that
//! changes by at most `a·dt` per period changes the acceleration by at
//! most `2·a / (N·dt)` per second (the jerk), keeps every speed below the
//! largest one averaged and every acceleration below `a`, and ends on the
//! very point the unfiltered motion ends on, N periods later. The
//! interpolator applies it to each axis of a rapid (whose speed does not
//! turn within the window: [`Turns`], which halves the bound), twice in a
//! row to each axis of a feed after interpolation ([`Cascade`]: where it
//! cuts G64 corners and the inside of curves, which the planner's caps
//! keep within the tolerance: planner.rs `FeedSmoothing`), and in a plane
//! to the path parameter of each move on its own, which leaves the point
//! on the path.

use crate::math::V2;
use alloc::vec::Vec;

#[derive(Debug, Clone)]
/// The moving average of the last N values of a profile (jerk limiting).
pub struct Smoother {
    /// The samples less `origin`, the point the filter last stood on: the
    /// running sum of a move's offsets from its start drifts by their
    /// rounding, not by that of coordinates some metres out (whose drift,
    /// snapped off where the filter settles, was a jerk of 0.1 mm/s³).
    buf: Vec<V2>,
    origin: V2,
    sum: V2,
    next: usize,
    /// Consecutive pushes of the same value.
    same: usize,
    last: V2,
}

impl Smoother {
    /// A filter of `n` taps (1: no filtering), allocated once.
    pub fn new(n: usize) -> Smoother {
        let n = n.max(1);
        let mut buf = Vec::with_capacity(n);
        buf.resize(n, V2::ZERO);
        Smoother {
            buf,
            origin: V2::ZERO,
            sum: V2::ZERO,
            next: 0,
            same: n,
            last: V2::ZERO,
        }
    }

    /// Periods averaged.
    pub fn taps(&self) -> usize {
        self.buf.len()
    }

    /// At rest at `v`.
    pub fn reset(&mut self, v: V2) {
        for b in self.buf.iter_mut() {
            *b = V2::ZERO;
        }
        self.origin = v;
        self.sum = V2::ZERO;
        self.next = 0;
        self.same = self.buf.len();
        self.last = v;
    }

    /// Adds a sample; the average of the last N.
    pub fn push(&mut self, v: V2) -> V2 {
        let n = self.buf.len();
        let off = v - self.origin;
        let old = core::mem::replace(&mut self.buf[self.next], off);
        self.next = if self.next + 1 == n { 0 } else { self.next + 1 };
        self.same = if v == self.last {
            (self.same + 1).min(n)
        } else {
            1
        };
        self.last = v;
        if self.same == n {
            // Settled: exactly the value, whatever the running sum drifted.
            self.sum = off * n as f64;
            return v;
        }
        self.sum = self.sum + off - old;
        self.origin + self.sum * (1.0 / n as f64)
    }

    /// Every sample in the window equals the last one.
    pub fn settled(&self) -> bool {
        self.same == self.buf.len()
    }
}

/// Two moving averages in a row (a feed's set points under jerk
/// limiting): N taps, then M. With v the unaveraged speed per period, the
/// pair's acceleration per period is the mean of v_k − v_(k−M) over N
/// periods, divided by M·dt, and its jerk is
/// ((v_k − v_(k−M)) − (v_(k−N) − v_(k−N−M))) / (N·M·dt²): both are
/// bounded by W, the largest change of v over M periods (W/(M·dt) and
/// 2·W/(N·M·dt²)). A velocity step inside a window of M periods counts
/// once in W, where one average alone would turn it into a jump of
/// acceleration within a period.
#[derive(Debug, Clone)]
pub struct Cascade {
    first: Smoother,
    second: Smoother,
}

impl Cascade {
    /// `n` taps, then `m` (1 and 1: no filtering), allocated once.
    pub fn new(n: usize, m: usize) -> Cascade {
        Cascade {
            first: Smoother::new(n),
            second: Smoother::new(m),
        }
    }

    /// At rest at `v`.
    pub fn reset(&mut self, v: V2) {
        self.first.reset(v);
        self.second.reset(v);
    }

    /// Adds a sample; the average of the averages.
    pub fn push(&mut self, v: V2) -> V2 {
        let a = self.first.push(v);
        self.second.push(a)
    }

    /// Both averages stand on the last sample.
    pub fn settled(&self) -> bool {
        self.first.settled() && self.second.settled()
    }
}

/// The sign of each rapid axis's speed change (X, Z, C) in each of the
/// last N periods, under jerk limiting. A rapid's axis may not turn from
/// speeding up to slowing down, or back, within N periods: the speed
/// changes of two periods N apart then differ by at most a·dt, and one
/// average of N periods bounds the jerk by a/(N·dt), half of what any
/// profile within `a` gets (`Smoother`). So a rapid's window is a/j, not
/// 2·a/j (config.rs `rapid_taps`).
#[derive(Debug, Clone)]
pub struct Turns {
    buf: Vec<[i8; 3]>,
    next: usize,
}

impl Turns {
    /// N periods of history (at least 1), allocated once.
    pub fn new(n: usize) -> Turns {
        let mut buf = Vec::with_capacity(n.max(1));
        buf.resize(n.max(1), [0; 3]);
        Turns { buf, next: 0 }
    }

    /// The axes have stood for N periods.
    pub fn clear(&mut self) {
        self.buf.iter_mut().for_each(|s| *s = [0; 3]);
        self.next = 0;
    }

    /// The signs of the speed changes N periods before the one to come.
    pub fn lagged(&self) -> [i8; 3] {
        self.buf[self.next]
    }

    /// Records this period's signs.
    pub fn push(&mut self, signs: [i8; 3]) {
        self.buf[self.next] = signs;
        self.next = if self.next + 1 == self.buf.len() {
            0
        } else {
            self.next + 1
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settles_exactly_on_the_last_value() {
        let mut f = Smoother::new(7);
        f.reset(V2::ZERO);
        let mut out = V2::ZERO;
        for i in 0..20 {
            out = f.push(V2::new(0.0, (i.min(10) as f64) * 0.1));
        }
        assert!(f.settled());
        assert_eq!(out, V2::new(0.0, 1.0));
    }

    #[test]
    fn a_cascade_spreads_a_step_of_speed_over_its_second_window() {
        // At rest at 0, then a speed of 1 per period (a velocity step of
        // 1). One average of 4 taps turns it into an acceleration of 1/4
        // per period at once (a jerk of 1/4); with a second average of 2
        // taps the acceleration rises in two steps of 1/8. By hand: the
        // first average's points are 0, 1/4, 3/4, 3/2, 5/2, 7/2; the
        // second's the mean of two of them: 0, 1/8, 1/2, 9/8, 2, 3, 4.
        let mut c = Cascade::new(4, 2);
        c.reset(V2::ZERO);
        let mut pos = alloc::vec![0.0];
        for k in 0..8 {
            pos.push(c.push(V2::new(k as f64, 0.0)).r);
        }
        let speed: Vec<f64> = pos.windows(2).map(|w| w[1] - w[0]).collect();
        let accel: Vec<f64> = speed.windows(2).map(|w| w[1] - w[0]).collect();
        let want = [0.125, 0.25, 0.25, 0.25, 0.125, 0.0, 0.0];
        assert_eq!(accel.len(), want.len());
        for (got, w) in accel.iter().zip(want) {
            assert!((got - w).abs() < 1e-12, "{accel:?}");
        }
        assert!(!c.settled());
        c.reset(V2::new(3.0, 0.0));
        assert!(c.settled());
        assert_eq!(c.push(V2::new(3.0, 0.0)), V2::new(3.0, 0.0));
    }

    #[test]
    fn turns_are_seen_n_periods_later() {
        let mut t = Turns::new(3);
        t.push([1, 0, 0]);
        t.push([0, -1, 0]);
        assert_eq!(t.lagged(), [0; 3]);
        t.push([0, 0, 1]);
        // Three periods after the first: its signs.
        assert_eq!(t.lagged(), [1, 0, 0]);
        t.push([0; 3]);
        assert_eq!(t.lagged(), [0, -1, 0]);
        t.clear();
        assert_eq!(t.lagged(), [0; 3]);
    }
}
