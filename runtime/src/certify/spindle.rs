//! The checks that follow the spindle: a thread's lead per turn, and the
//! G96 spindle speed at the diameter cut.

use super::chain::long_is_z;
use super::pending::Pending;
use super::{incomplete_lead, Certifier, Figure, Kind, Subject, ENTRY_MARGIN};
use crate::interpolate::{Motion, SetPoint};
use crate::math::{PI, V2};

impl Certifier {
    /// The lead of a thread period, away from the incomplete leads.
    pub(super) fn thread_lead(&mut self, prev: &SetPoint, p: &SetPoint, m: &Pending) {
        let (Some((lead, dlead)), Some(start), Motion::Thread) = (m.thread, m.start, p.motion)
        else {
            return;
        };
        let turns = p.spindle_turns - prev.spindle_turns;
        if turns <= 1e-9 {
            return;
        }
        let d = m.end - start;
        let long_z = long_is_z(d);
        let long = |v: V2| if long_z { v.z } else { v.r };
        let (a, b) = (V2::from_xz(prev.x, prev.z), V2::from_xz(p.x, p.z));
        let q0 = (long(a) - long(start)).abs();
        let q1 = (long(b) - long(start)).abs();
        let rest = (long(m.end) - long(b)).abs();
        let want = if dlead == 0.0 {
            lead
        } else {
            libm::sqrt((lead * lead + dlead * (q0 + q1)).max(0.0))
        };
        let v = want * p.spindle_rpm.abs() / 60.0;
        let [ax, az, _] = self.axes;
        let (Some(ax), Some(az)) = (ax, az) else {
            return;
        };
        let (la, sa) = if long_z { (az, ax) } else { (ax, az) };
        let short = if long_z { d.r } else { d.z };
        let room = incomplete_lead(v, la.accel, sa.accel, long(d), short) * (1.0 + ENTRY_MARGIN)
            + v * self.dt;
        if q0 < room || rest < room {
            return;
        }
        let catching_up = v * self.catch_up[usize::from(long_z)].lead_s;
        if q0 < catching_up * (1.0 + ENTRY_MARGIN) + 2.0 * v * self.dt {
            return;
        }
        self.lead_periods += 1;
        let got = (long(b) - long(a)).abs() / turns;
        self.note(Figure::at(
            Kind::Lead,
            Subject::Path,
            p,
            got,
            want,
            (got - want).abs() / want,
        ));
    }

    /// G96 while cutting: the spindle at the surface speed's target.
    pub(super) fn surface_speed(&mut self, prev: &SetPoint, p: &SetPoint, m: &Pending) {
        let (Some(vc), true, Motion::Feed | Motion::Arc) = (m.spindle.css, m.spindle.on, p.motion)
        else {
            return;
        };
        // The spindle of a period follows the diameter it began at.
        let d = prev.x.abs();
        let lim = m.spindle.clamp.min(self.spindle.max_rpm);
        let n = if d < 1e-9 {
            lim
        } else {
            (1000.0 * vc / (PI * d) * self.spindle_ovr).min(lim)
        };
        let target = if n > 0.0 {
            n.max(self.spindle.min_rpm)
        } else {
            return;
        };
        let rpm = p.spindle_rpm.abs();
        let step = (p.spindle_rpm - prev.spindle_rpm).abs();
        if step >= self.spindle.accel_rpm_s * self.dt * (1.0 - 1e-9) {
            return; // still changing speed at full acceleration
        }
        self.css_periods += 1;
        self.note(Figure::at(
            Kind::SurfaceSpeed,
            Subject::Spindle,
            p,
            rpm,
            target,
            (rpm - target).abs() / target,
        ));
    }
}
