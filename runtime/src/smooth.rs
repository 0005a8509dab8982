//! Jerk limiting: a moving average over the last N set points of the
//! acceleration-limited profile. Averaging N samples of a speed that
//! changes by at most `a·dt` per period changes the acceleration by at
//! most `2·a / (N·dt)` per second (the jerk), keeps every speed below the
//! largest one averaged and every acceleration below `a`, and ends on the
//! very point the unfiltered motion ends on, N periods later. The
//! interpolator applies it to each axis of a rapid, to each axis of a feed
//! after interpolation (where it cuts G64 corners and the inside of
//! curves, which the planner's caps keep within the tolerance:
//! planner.rs `FeedSmoothing`), and in a plane to the path parameter of
//! each move on its own, which leaves the point on the path.

use crate::math::V2;
use alloc::vec::Vec;

#[derive(Debug, Clone)]
/// The moving average of the last N values of a profile (jerk limiting).
pub struct Smoother {
    buf: Vec<V2>,
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
            *b = v;
        }
        self.sum = v * self.buf.len() as f64;
        self.next = 0;
        self.same = self.buf.len();
        self.last = v;
    }

    /// Adds a sample; the average of the last N.
    pub fn push(&mut self, v: V2) -> V2 {
        let n = self.buf.len();
        let old = core::mem::replace(&mut self.buf[self.next], v);
        self.next = if self.next + 1 == n { 0 } else { self.next + 1 };
        self.same = if v == self.last {
            (self.same + 1).min(n)
        } else {
            1
        };
        self.last = v;
        if self.same == n {
            // Settled: exactly the value, whatever the running sum drifted.
            self.sum = v * n as f64;
            return v;
        }
        self.sum = self.sum + v - old;
        self.sum * (1.0 / n as f64)
    }

    /// Every sample in the window equals the last one.
    pub fn settled(&self) -> bool {
        self.same == self.buf.len()
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
}
