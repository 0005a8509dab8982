//! The corners a thread chain turns at speed, as the queue of end points
//! meets them: the tolerance of an end point at one, and the catch-ups
//! they open (the law itself is [`super::chain`]'s).

use super::chain::{long_len, per_turn, CatchUp};
use super::pending::Pending;
use super::{Certifier, ENTRY_MARGIN};
use crate::config::Axis;
use crate::math::V2;

impl Certifier {
    /// The distance within which the path reaches end point `m` with the
    /// spindle at `rpm`: its own ([`END_POINT_MM`], [`chain_corner_mm`]),
    /// and at a corner of a thread chain that the chain reaches before an
    /// axis has caught up with the corners before it ([`CatchUp`]), that
    /// axis's lag too: at most c²/2a for steps c in its speed (the lag it
    /// builds while reaching its new speed).
    ///
    /// [`END_POINT_MM`]: super::END_POINT_MM
    /// [`chain_corner_mm`]: super::chain_corner_mm
    pub(super) fn tol_of(&self, m: &Pending, rpm: f64) -> f64 {
        let Some(leg_s) = leg_time(m, rpm).filter(|_| m.corner) else {
            return m.tol;
        };
        let stops = self.stops_at(m, rpm);
        let mut lag2 = 0.0;
        for ((axis, up), stop) in self.axes.iter().zip(&self.catch_up).zip(stops) {
            // (The margin of the lead's check: the follower is discrete.)
            let open = up.lag_s * (1.0 + ENTRY_MARGIN) + 2.0 * self.dt > leg_s;
            if let (Some(ax), true) = (axis, open || stop > 0.0) {
                let c = if open { up.c + stop } else { stop };
                let lag = c * c / (2.0 * ax.accel);
                lag2 += lag * lag;
            }
        }
        m.tol + libm::sqrt(lag2)
    }

    /// The speed (mm/s, radial X and Z) each axis sheds running into the
    /// corner at the end of leg `m`, where the chain stops, turns or slows
    /// it there or within its stopping distance after: the follower slows
    /// it ahead so as never to pass the chain's point, at most down to
    /// where it would pass each such corner no faster than the chain runs
    /// on from there, and the corner is cut by up to the lag that builds,
    /// at most Δv²/2a.
    fn stops_at(&self, m: &Pending, rpm: f64) -> [f64; 2] {
        let (Some((lead, _)), Some(start)) = (m.thread, m.start) else {
            return [0.0; 2];
        };
        let rps = rpm.abs() / 60.0;
        let u = per_turn(m.end - start, lead);
        let later = || self.pending.iter().skip_while(|p| p.end != m.end).skip(1);
        [0, 1].map(|i| {
            let along = |d: V2| if i == 0 { d.r } else { d.z };
            let (Some(ax), dir) = (self.axes[i], along(u)) else {
                return 0.0;
            };
            let (v, a) = (dir.abs() * rps, ax.accel);
            // The fastest the axis may pass m's end, and how far on the
            // axis the leg after it starts from there.
            let (mut here, mut dist, mut on) = (v, 0.0, m.corner);
            for n in later() {
                let (Some((next_lead, _)), Some(from), true) = (n.thread, n.start, on) else {
                    break;
                };
                let w = along(per_turn(n.end - from, next_lead));
                let run_on = if w * dir > 0.0 { w.abs() * rps } else { 0.0 };
                here = here.min(libm::sqrt(run_on * run_on + 2.0 * a * dist));
                if run_on == 0.0 || 2.0 * a * dist > v * v {
                    break;
                }
                (dist, on) = (dist + along(n.end - from).abs(), n.corner);
            }
            (v - here).max(0.0)
        })
    }

    /// The chain turned from leg `m` into the next pending one (or `m`
    /// ended a move off a chain): the catch-ups still open lose the leg's
    /// time, and the corner adds its own steps in the axes' speeds.
    pub(super) fn turned(&mut self, m: &Pending, rpm: f64) {
        let next = self.pending.front().copied();
        let (Some(leg_s), Some(n)) = (leg_time(m, rpm).filter(|_| m.corner), next) else {
            self.catch_up = [CatchUp::NONE; 2];
            return;
        };
        let (Some((lead, _)), Some(start)) = (n.thread, n.start) else {
            self.catch_up = [CatchUp::NONE; 2];
            return;
        };
        let rps = rpm.abs() / 60.0;
        let u = per_turn(n.end - start, lead);
        let steps = [(n.enter.r, u.r), (n.enter.z, u.z)];
        let runs = [self.axis_run(0), self.axis_run(1)];
        for (i, (du, ui)) in steps.into_iter().enumerate() {
            let up = &mut self.catch_up[i];
            up.lead_s = (up.lead_s - leg_s).max(0.0);
            up.lag_s = (up.lag_s - leg_s).max(0.0);
            if up.lag_s == 0.0 {
                up.c = 0.0;
            }
            let Some(ax) = self.axes[i].filter(|_| du != 0.0) else {
                continue;
            };
            // Faster in the leg's direction on this axis, or slower.
            let w0 = if ui != 0.0 {
                du * ui.signum()
            } else {
                -du.abs()
            } * rps;
            up.add(&ax, ui.abs() * rps, w0, runs[i]);
        }
    }

    /// How far the chain runs on axis `i` (0: radial X, 1: Z) from the
    /// start of the next pending move in the direction it moves there, up
    /// to where that axis stops or turns, or the chain queued so far ends.
    fn axis_run(&self, i: usize) -> f64 {
        let along = |d: V2| if i == 0 { d.r } else { d.z };
        let (mut run, mut dir) = (0.0, 0.0);
        for m in &self.pending {
            let (Some(_), Some(start)) = (m.thread, m.start) else {
                break;
            };
            let d = along(m.end - start);
            if d == 0.0 || d * dir < 0.0 {
                break;
            }
            (run, dir) = (run + d.abs(), d);
            if !m.corner {
                break;
            }
        }
        run
    }

    /// The end points of the thread legs that end less than a period's
    /// travel before the corner the last pending leg ends at (legs of a
    /// few µm): the chain may pass them and the corner in one period, so
    /// that period's chord is bent by the corner as much as the corner's
    /// own; they take its tolerance.
    pub(super) fn widen_before_corner(&mut self) {
        let top = |a: &Option<Axis>| a.map_or(0.0, |a| a.max_feed);
        let reach = libm::hypot(top(&self.axes[0]), top(&self.axes[1])) * self.dt;
        let mut legs = self.pending.iter_mut().rev();
        let Some(corner) = legs.next().filter(|m| m.corner) else {
            return;
        };
        let (tol, mut run) = (
            corner.tol,
            corner
                .start
                .map_or(f64::INFINITY, |a| (corner.end - a).norm()),
        );
        for m in legs {
            let Some(start) = m.start.filter(|_| m.thread.is_some() && run <= reach) else {
                break;
            };
            m.tol = m.tol.max(tol);
            run += (m.end - start).norm();
        }
    }
}

/// The time a thread leg takes at `rpm` (its long-axis travel at lead
/// × speed); `None` off a thread or with the spindle standing.
fn leg_time(m: &Pending, rpm: f64) -> Option<f64> {
    let (Some((lead, _)), Some(start)) = (m.thread, m.start) else {
        return None;
    };
    let v = lead * rpm.abs() / 60.0;
    (v > 0.0).then(|| long_len(m.end - start) / v)
}
