//! Backlash compensation: the lost motion between a slide's screw and its
//! nut, taken up in the drive's command where the axis turns back
//! (docs/machine.md, `backlash_mm`).
//!
//! When an axis reverses, the screw turns through the lost motion before
//! the nut, and the slide, follows. A control adds that travel to what it
//! commands the drive, so that the slide stands where the program says.
//! Here the set points stay the slide's (what the program, the limits and
//! `gbvm check` speak of) and the counts, the drive's command, carry the
//! compensation.
//!
//! The reference return and power-on state is the lost motion taken up
//! toward + (a lathe's reference point is approached in +): the command
//! equals the set point while the axis last moved in +, and lies
//! `backlash` below it once it moved in −. The change between the two is
//! not a step, which no drive could follow: it runs as a short move of
//! its own, accelerating at the axis's acceleration for half its time and
//! braking for the other half, in whole periods.

use crate::math::{sqrt, V2};

/// A set point step shorter than this (mm) is standing, not a direction:
/// rounding noise of a standing axis must not start a compensation.
const STANDING: f64 = 1e-9;

/// One axis's compensation, slide units.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Lash {
    /// The lost motion; 0 turns the compensation off.
    amount: f64,
    /// The acceleration of the compensation's move.
    accel: f64,
    /// The axis last moved in −.
    minus: bool,
    /// The compensation's move: from `from` to `to`, `n` periods long,
    /// `k` of them run.
    from: f64,
    to: f64,
    k: u32,
    n: u32,
}

impl Lash {
    fn new(amount: f64, accel: f64) -> Lash {
        Lash {
            amount,
            accel,
            minus: false,
            from: 0.0,
            to: 0.0,
            k: 0,
            n: 0,
        }
    }

    /// The compensation after a period in which the set point moved by
    /// `step` (`dt` long).
    fn period(&mut self, step: f64, dt: f64) -> f64 {
        if self.amount == 0.0 {
            return 0.0;
        }
        let minus = match step {
            s if s < -STANDING => true,
            s if s > STANDING => false,
            _ => self.minus,
        };
        if minus != self.minus {
            self.minus = minus;
            self.turn(dt);
        }
        self.k = (self.k + 1).min(self.n);
        self.offset()
    }

    /// Starts the move from where the compensation stands to the one the
    /// new direction needs.
    fn turn(&mut self, dt: f64) {
        let from = self.offset();
        let to = if self.minus { -self.amount } else { 0.0 };
        // Half the time accelerating, half braking: a distance d takes
        // 2·√(d/a), rounded up to whole periods (so the acceleration is
        // at most a).
        let time = 2.0 * sqrt((to - from).abs() / self.accel);
        self.n = libm::ceil(time / dt).max(1.0) as u32;
        (self.from, self.to, self.k) = (from, to, 0);
    }

    /// The compensation now: along the move's velocity triangle.
    fn offset(&self) -> f64 {
        if self.k >= self.n {
            return self.to;
        }
        let u = f64::from(self.k) / f64::from(self.n);
        let done = if u <= 0.5 {
            2.0 * u * u
        } else {
            1.0 - 2.0 * (1.0 - u) * (1.0 - u)
        };
        self.from + (self.to - self.from) * done
    }
}

/// The compensation of X, Z and C, following the machine set points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Backlash {
    r: Lash,
    z: Lash,
    c: Lash,
    /// The set points of the period before.
    last: Option<V2>,
    last_c: Option<f64>,
}

impl Backlash {
    /// X's and Z's lost motion and acceleration, slide units (X radial).
    pub(crate) fn new(lost: V2, accel: V2) -> Backlash {
        Backlash {
            r: Lash::new(lost.r, accel.r),
            z: Lash::new(lost.z, accel.z),
            c: Lash::new(0.0, 1.0),
            last: None,
            last_c: None,
        }
    }

    /// With a rotary C axis's lost motion and acceleration, degrees.
    pub(crate) fn with_c(mut self, lost: f64, accel: f64) -> Backlash {
        self.c = Lash::new(lost, accel);
        self
    }

    /// The compensation to add to this period's machine set point `at`
    /// for the drives' command, slide units.
    pub(crate) fn period(&mut self, at: V2, dt: f64) -> V2 {
        let step = self.last.map_or(V2::ZERO, |last| at.sub(last));
        self.last = Some(at);
        V2::new(self.r.period(step.r, dt), self.z.period(step.z, dt))
    }

    /// The compensation to add to this period's C angle `c`, degrees.
    pub(crate) fn period_c(&mut self, c: f64, dt: f64) -> f64 {
        let step = self.last_c.map_or(0.0, |last| c - last);
        self.last_c = Some(c);
        self.c.period(step, dt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    /// Z with 0.02 mm at 2000 mm/s², 1 ms periods: the move takes
    /// 2·√(0.02/2000) = 6.32 ms, so 7 periods; along the velocity
    /// triangle the share done after k of them is 2(k/7)² to half way,
    /// then 1 − 2(1 − k/7)²: 2/49, 8/49, 18/49, 31/49, 41/49, 47/49, 1.
    #[test]
    fn a_reversal_takes_up_the_lost_motion_in_seven_periods() {
        let mut b = Backlash::new(V2::new(0.0, 0.02), V2::new(1500.0, 2000.0));
        let mut z = 0.0;
        assert_eq!(b.period(V2::new(0.0, z), 0.001), V2::ZERO);
        // Moving in + (the power-on direction): nothing to take up.
        z += 0.1;
        assert_eq!(b.period(V2::new(0.0, z), 0.001), V2::ZERO);
        let shares = [2.0, 8.0, 18.0, 31.0, 41.0, 47.0, 49.0, 49.0, 49.0];
        for share in shares {
            z -= 0.1;
            let c = b.period(V2::new(0.0, z), 0.001);
            assert_eq!(c.r, 0.0);
            assert!((c.z + 0.02 * share / 49.0).abs() < 1e-15, "{share}: {c:?}");
        }
        // Standing keeps it; a step back in + returns it the same way.
        assert_eq!(b.period(V2::new(0.0, z), 0.001).z, -0.02);
        z += 0.1;
        let back = b.period(V2::new(0.0, z), 0.001).z;
        assert!((back - (-0.02 + 0.02 * 2.0 / 49.0)).abs() < 1e-15);
    }

    /// The acceleration of the compensation's move stays within the
    /// axis's: its second differences, over a period squared.
    #[test]
    fn the_compensation_accelerates_within_the_axis_limit() {
        let (lost, accel, dt) = (0.05, 1500.0, 0.001);
        let mut b = Backlash::new(V2::new(lost, 0.0), V2::new(accel, 2000.0));
        let mut offsets = vec![0.0, 0.0];
        let mut r = 0.0;
        for _ in 0..40 {
            r -= 0.01;
            offsets.push(b.period(V2::new(r, 0.0), dt).r);
        }
        assert_eq!(offsets.last(), Some(&-lost));
        for w in offsets.windows(3) {
            let a = (w[2] - 2.0 * w[1] + w[0]) / (dt * dt);
            assert!(a.abs() <= accel + 1e-6, "{a} mm/s² in {offsets:?}");
        }
    }

    /// C with 0.05° at 3600°/s², 1 ms periods: 2·√(0.05/3600) = 7.45 ms,
    /// so 8 periods, with shares 2/64, 8/64, 18/64, 32/64, 46/64, 56/64,
    /// 62/64 and 1 along the velocity triangle; X and Z, without lost
    /// motion, get none.
    #[test]
    fn a_rotary_axis_takes_up_its_lost_motion_in_degrees() {
        let mut b = Backlash::new(V2::ZERO, V2::new(1500.0, 2000.0)).with_c(0.05, 3600.0);
        let mut c = 10.0;
        assert_eq!(b.period_c(c, 0.001), 0.0);
        for share in [2.0, 8.0, 18.0, 32.0, 46.0, 56.0, 62.0, 64.0, 64.0] {
            c -= 0.5;
            let got = b.period_c(c, 0.001);
            assert!((got + 0.05 * share / 64.0).abs() < 1e-15, "{share}: {got}");
            assert_eq!(b.period(V2::new(5.0, -c), 0.001), V2::ZERO);
        }
    }

    /// Noise below a nanometre is not a reversal, and an axis without
    /// lost motion is never compensated.
    #[test]
    fn standing_noise_and_no_lost_motion_change_nothing() {
        let mut b = Backlash::new(V2::new(0.0, 0.02), V2::new(1500.0, 2000.0));
        let mut z = -5.0;
        b.period(V2::new(10.0, z), 0.001);
        for i in 0..10 {
            z += if i % 2 == 0 { -1e-12 } else { 1e-12 };
            let c = b.period(V2::new(10.0 - f64::from(i), z), 0.001);
            assert_eq!(c, V2::ZERO);
        }
    }
}
