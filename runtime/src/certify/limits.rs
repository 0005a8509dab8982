//! The machine's limits, period by period: each axis's velocity,
//! acceleration, jerk and travel, and the spindle's speed and
//! acceleration.

use super::{Certifier, Figure, Kind, Subject};
use crate::config::Axis;
use crate::interpolate::{Motion, SetPoint};

impl Certifier {
    /// Velocity, acceleration and jerk of X, Z and C.
    pub(super) fn axis_limits(&mut self, p: &SetPoint) {
        let (dt, [p0, p1, p2, p3]) = (self.dt, self.pos);
        let subjects = [Subject::X, Subject::Z, Subject::C];
        for (i, ax) in self.axes.into_iter().enumerate() {
            let Some(ax) = ax else { continue };
            let at = |kind, value: f64, limit: f64| {
                Figure::at(kind, subjects[i], p, value, limit, value.abs() / limit)
            };
            let vlim = if p.motion == Motion::Rapid {
                ax.rapid
            } else {
                ax.max_feed
            };
            if ax.soft_limits {
                self.note(travel(at(Kind::Travel, p3[i], 0.0), ax, i == 0));
            }
            self.note(at(Kind::Velocity, (p3[i] - p2[i]) / dt, vlim));
            let a = (p3[i] - 2.0 * p2[i] + p1[i]) / (dt * dt);
            self.note(at(Kind::Acceleration, a, ax.accel));
            let thread = self.motion.contains(&Motion::Thread);
            if self.jerk && !thread {
                let j = (p3[i] - 3.0 * p2[i] + 3.0 * p1[i] - p0[i]) / (dt * dt * dt);
                self.note(at(Kind::Jerk, j, ax.jerk));
            }
        }
    }

    /// The spindle's speed and acceleration.
    pub(super) fn spindle_limits(&mut self, p: &SetPoint) {
        let at = |kind, value: f64, limit: f64| {
            Figure::at(kind, Subject::Spindle, p, value, limit, value.abs() / limit)
        };
        let top = self.spindle.max_rpm;
        let accel = self.spindle.accel_rpm_s;
        self.note(at(Kind::SpindleSpeed, p.spindle_rpm, top));
        let a = (p.spindle_rpm - self.prev_rpm) / self.dt;
        self.note(at(Kind::SpindleAccel, a, accel));
    }
}

/// A travel figure of `ax` at `fig.value` (machine coordinates; X a
/// radius, given as a diameter as the machine file writes it): against
/// the nearer limit.
fn travel(mut fig: Figure, ax: Axis, diameter: bool) -> Figure {
    let v = fig.value;
    let (limit, beyond) = if v - ax.min < ax.max - v {
        (ax.min, ax.min - v)
    } else {
        (ax.max, v - ax.max)
    };
    let k = if diameter { 2.0 } else { 1.0 };
    (fig.value, fig.limit, fig.ratio) = (v * k, limit * k, beyond * k);
    fig
}
