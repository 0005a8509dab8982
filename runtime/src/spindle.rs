//! The spindle: it follows M03/M04/M05 and S with the machine's
//! acceleration, computes the rpm of constant surface speed from the
//! current diameter every period, and keeps the angle that threads
//! synchronise to (the index pulse is at whole turns).
//!
//! The speed and angle are simulated until the host feeds the measured
//! ones ([`Spindle::set_measured`], from its encoder): from then on each
//! period takes them as they come, so threads and feed per revolution
//! follow the real spindle, whatever its drive does.

use crate::config::SpindleConfig;
use crate::math::PI;
use crate::plc::SpindleDir;
use crate::profile::brake_limit;

#[derive(Debug, Clone)]
/// The spindle's state: direction, programmed speed, actual speed and angle.
pub struct Spindle {
    cfg: SpindleConfig,
    dir: SpindleDir,
    css: bool,
    /// G97 rpm and G96 surface speed (m/min) as programmed.
    s_rpm: f64,
    v_css: f64,
    /// `G50 S` limit (∞ before any).
    limit: f64,
    /// Signed actual rpm (+ for M03).
    rpm: f64,
    /// Turns made in the running direction, from power-on (monotone).
    turns: f64,
    /// Spindle override, 1.0 = 100 %.
    pub override_factor: f64,
    /// The host's encoder, once it feeds one.
    measured: Option<Measured>,
    /// Rigid tapping: the spindle in position control for a reversal.
    rigid: Option<Rigid>,
}

/// A rigid-tapping reversal: the spindle brakes at `accel` to stand
/// exactly at `at` turns (the bottom of the tap), stands until it is
/// reversed, and starts the other way at `accel` again.
#[derive(Debug, Clone, Copy)]
struct Rigid {
    /// rev/s².
    accel: f64,
    /// Turns at the bottom.
    at: f64,
    /// Still braking to (or standing at) the bottom: not reversed yet.
    holding: bool,
    /// The move out has started from the bottom.
    out: bool,
}

/// The measured spindle of the coming period.
#[derive(Debug, Clone, Copy)]
struct Measured {
    /// Encoder position (turns, signed as it counts) at the last period.
    last: f64,
    /// ... and now.
    now: f64,
    /// Signed measured speed, rev/min.
    rpm: f64,
}

impl Spindle {
    /// A stopped spindle with this override (percent).
    pub fn new(cfg: SpindleConfig, override_pct: f64) -> Spindle {
        Spindle {
            cfg,
            dir: SpindleDir::Stop,
            css: false,
            s_rpm: 0.0,
            v_css: 0.0,
            limit: f64::INFINITY,
            rpm: 0.0,
            turns: 0.0,
            override_factor: override_pct / 100.0,
            measured: None,
            rigid: None,
        }
    }

    /// The measured position (encoder turns, signed) and speed (rev/min,
    /// signed) for the coming period. The first call only takes the
    /// position as its reference; from then on the angle advances by what
    /// the encoder turned, in either direction (the angle counts turns in
    /// the running direction).
    pub fn set_measured(&mut self, position: f64, rpm: f64) {
        match &mut self.measured {
            Some(m) => {
                m.now = position;
                m.rpm = rpm;
            }
            None => {
                self.measured = Some(Measured {
                    last: position,
                    now: position,
                    rpm,
                })
            }
        }
    }

    /// Back to the simulated spindle, from the last measured state.
    pub fn set_simulated(&mut self) {
        self.measured = None;
    }

    /// Whether the speed and angle are the host's measured ones.
    pub fn is_measured(&self) -> bool {
        self.measured.is_some()
    }

    /// M03, M04 or M05. A reversal releases a rigid-tapping hold.
    pub fn set_dir(&mut self, d: SpindleDir) {
        if let Some(r) = &mut self.rigid {
            if d != self.dir {
                r.holding = false;
            }
        }
        self.dir = d;
    }

    /// M03, M04 or M05 as in force.
    pub fn dir(&self) -> SpindleDir {
        self.dir
    }

    /// Rigid tapping: brake at `accel` rev/s² so as to stand exactly at
    /// `at` turns, and reverse at that acceleration too.
    pub fn rigid_stop(&mut self, at: f64, accel: f64) {
        self.rigid = Some(Rigid {
            accel,
            at,
            holding: true,
            out: false,
        });
    }

    /// Whether a rigid-tapping stop is armed and not yet released.
    pub fn rigid_holding(&self) -> bool {
        self.rigid.is_some_and(|r| r.holding)
    }

    /// The bottom's turns of a rigid reversal released by the spindle's
    /// reversal (the move out starts from there), taken once.
    pub fn take_rigid_origin(&mut self) -> Option<f64> {
        match &mut self.rigid {
            Some(r) if !r.holding && !r.out => {
                r.out = true;
                Some(r.at)
            }
            _ => None,
        }
    }

    /// Whether the move out of a rigid reversal is running.
    pub fn rigid_out(&self) -> bool {
        self.rigid.is_some_and(|r| r.out)
    }

    /// The turns of an armed rigid stop.
    pub fn rigid_at(&self) -> Option<f64> {
        self.rigid.map(|r| r.at)
    }

    /// Ends a rigid-tapping reversal (its move out is done, or a reset).
    pub fn rigid_end(&mut self) {
        self.rigid = None;
    }

    /// A SPEED event: S in G97 (rpm) or G96 (m/min), and a `G50 S` limit.
    pub fn set_speed(&mut self, s: f64, css: bool, max: Option<f64>) {
        if let Some(m) = max {
            self.limit = if m > 0.0 { m } else { f64::INFINITY };
        }
        self.css = css;
        if css {
            self.v_css = s.max(0.0);
        } else {
            self.s_rpm = s.max(0.0);
        }
    }

    /// Constant surface speed (G96) is on.
    pub fn css(&self) -> bool {
        self.css
    }

    /// The G96 surface speed, m/min.
    pub fn surface_speed(&self) -> f64 {
        self.v_css
    }

    /// The commanded rpm (unsigned) at diameter `x`: G96 from the
    /// diameter, limited by `G50 S` and the machine; G97 by the machine;
    /// never below the analog spindle's minimum while it turns.
    pub fn commanded(&self, x: f64) -> f64 {
        if self.dir == SpindleDir::Stop {
            return 0.0;
        }
        let top = self.cfg.max_rpm;
        let n = if self.css {
            let lim = self.limit.min(top);
            let x = x.abs();
            if x < 1e-9 {
                lim
            } else {
                (1000.0 * self.v_css / (PI * x) * self.override_factor).min(lim)
            }
        } else {
            (self.s_rpm * self.override_factor).min(top)
        };
        if n > 0.0 {
            n.max(self.cfg.min_rpm)
        } else {
            0.0
        }
    }

    fn sign(&self) -> f64 {
        match self.dir {
            SpindleDir::Ccw => -1.0,
            _ => 1.0,
        }
    }

    /// One period at diameter `x`.
    pub fn update(&mut self, dt: f64, x: f64) {
        if let Some(m) = &mut self.measured {
            self.turns += (m.now - m.last).abs();
            m.last = m.now;
            self.rpm = m.rpm;
            return;
        }
        if let Some(r) = self.rigid {
            // Position control: at most `accel`, braking to land exactly
            // on the bottom's turns while holding.
            let w = self.rpm * self.sign() / 60.0;
            let mut target = self.commanded(x) / 60.0;
            let rem = (r.at - self.turns).max(0.0);
            if r.holding {
                target = target.min(brake_limit(rem, 0.0, r.accel, dt));
            }
            let step = r.accel * dt;
            let w = target.clamp(w - step, w + step);
            if r.holding && w * dt >= rem - 1e-12 {
                self.turns = r.at;
            } else {
                self.turns += w.abs() * dt;
            }
            self.rpm = w * 60.0 * self.sign();
            return;
        }
        let target = self.commanded(x) * self.sign();
        let step = self.cfg.accel_rpm_s * dt;
        self.rpm = target.clamp(self.rpm - step, self.rpm + step);
        self.turns += self.rpm.abs() / 60.0 * dt;
    }

    /// Signed actual rpm.
    pub fn rpm(&self) -> f64 {
        self.rpm
    }

    /// Turns made so far (continuous; the index pulse at whole turns of
    /// the physical angle, which this follows in the running direction).
    pub fn turns(&self) -> f64 {
        self.turns
    }

    /// Encoder count of the current angle.
    pub fn encoder(&self) -> u64 {
        (self.turns * self.cfg.encoder_ppr as f64) as u64
    }

    /// The spindle runs at its commanded speed (within 0.5 % or 1 rpm).
    pub fn at_speed(&self, x: f64) -> bool {
        let target = self.commanded(x);
        target > 0.0
            && (self.rpm * self.sign() - target).abs() <= (0.005 * target).max(1.0)
            && self.rpm * self.sign() > 0.0
    }

    /// The spindle is, for practical purposes, standing.
    pub fn stopped(&self) -> bool {
        self.rpm.abs() < 0.5
    }

    /// Back to stopped with no speed programmed (reset).
    pub fn reset(&mut self) {
        self.dir = SpindleDir::Stop;
        self.rigid = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    #[test]
    fn spins_up_with_the_machine_acceleration() {
        let mut s = Spindle::new(Config::default().spindle, 100.0);
        s.set_speed(800.0, false, None);
        s.set_dir(SpindleDir::Cw);
        for _ in 0..400 {
            s.update(0.001, 50.0);
        }
        assert!((s.rpm() - 400.0).abs() < 1e-6);
        for _ in 0..1000 {
            s.update(0.001, 50.0);
        }
        assert!((s.rpm() - 800.0).abs() < 1e-9);
        assert!(s.at_speed(50.0));
    }

    #[test]
    fn a_measured_spindle_replaces_the_simulation() {
        let mut s = Spindle::new(Config::default().spindle, 100.0);
        s.set_speed(800.0, false, None);
        s.set_dir(SpindleDir::Ccw);
        // The first reading is the reference: no turn is counted.
        s.set_measured(10.0, -600.0);
        s.update(0.001, 50.0);
        assert_eq!((s.turns(), s.rpm()), (0.0, -600.0));
        // M04 counts down: 0.25 turn backwards is 0.25 turn run.
        s.set_measured(9.75, -590.0);
        s.update(0.001, 50.0);
        assert_eq!((s.turns(), s.rpm()), (0.25, -590.0));
        // A period without a reading: the angle stands.
        s.update(0.001, 50.0);
        assert_eq!(s.turns(), 0.25);
        // Simulated again: it accelerates from the measured speed towards
        // -800 at 1000 rpm/s, i.e. 1 rpm per period.
        s.set_simulated();
        s.update(0.001, 50.0);
        assert!((s.rpm() + 591.0).abs() < 1e-9);
    }

    #[test]
    fn constant_surface_speed_is_clamped() {
        let mut s = Spindle::new(Config::default().spindle, 100.0);
        s.set_dir(SpindleDir::Cw);
        s.set_speed(200.0, true, None);
        assert!((s.commanded(100.0) - 1000.0 * 200.0 / (PI * 100.0)).abs() < 1e-9);
        assert_eq!(s.commanded(0.0), 3000.0);
        s.set_speed(200.0, true, Some(1500.0));
        assert_eq!(s.commanded(10.0), 1500.0);
    }
}
