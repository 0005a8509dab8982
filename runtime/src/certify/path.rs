//! The path check: each set point on the canon move it belongs to (a
//! feed's line or arc, a rapid's rectangle, a thread chain's box).

use super::pending::{Pending, Shape};
use super::shape::off_shape;
use super::step::frame_kept;
use super::{Certifier, Figure, Kind, Subject, MAX_AHEAD, PASSED, PATH_MM};
use crate::config::Axis;
use crate::interpolate::{Motion, SetPoint};
use crate::math::V2;

impl Certifier {
    /// A straight or circular feed's set point on its canon move, a
    /// rapid's within its rectangle: on the move whose end point is next,
    /// or on one of the [`PASSED`] moves before or after it. (Set points lie on
    /// the path; only the chord between two of them cuts a corner or an
    /// arc.) Not in a period whose work frame changed, nor for a move not
    /// checked ([`Shape::Free`]).
    pub(super) fn on_path(&mut self, prev: &SetPoint, p: &SetPoint) {
        if !frame_kept(prev, p) {
            return;
        }
        let rapid = match p.motion {
            Motion::Feed | Motion::Arc => false,
            Motion::Rapid => true,
            Motion::Thread => return self.in_chain(prev, p),
            _ => return,
        };
        let here = V2::from_xz(p.x, p.z);
        let kind = |m: &Pending| (m.shape == Shape::Rapid) == rapid;
        // The move running must be one of the period's kind and known
        // (not one that starts where the tool came home, say).
        let front = self.pending.front().copied().filter(kind);
        let Some(on_front) = front.and_then(|m| off_shape(&m, here)) else {
            return;
        };
        // (A period may pass the end points of many µm moves before the
        // walk counts them: the moves ahead within the period's travel
        // count, at least PASSED of them; and the walk may count some
        // ahead of the tool.)
        let travel = (here - V2::from_xz(prev.x, prev.z)).norm() + PATH_MM;
        let mut run = 0.0;
        let ahead = self.pending.iter().skip(1).take(MAX_AHEAD).take_while(|m| {
            let counted = run <= travel;
            run += m.start.map_or(f64::INFINITY, |a| (m.end - a).norm());
            counted
        });
        let d = ahead
            .copied()
            .chain(self.pending.iter().skip(1).take(PASSED).copied())
            .chain(self.done)
            .chain(self.passed.iter().flatten().copied())
            .filter(|m| kind(m))
            .filter_map(|m| off_shape(&m, here))
            .fold(on_front, f64::min);
        self.path_periods += 1;
        self.note(Figure::at(Kind::Path, Subject::Path, p, d, PATH_MM, d));
    }

    /// A thread period's set point within the box of the chain's legs
    /// around it: the legs done before the one running ([`PASSED`] of
    /// them), that one, and those ahead within the period's travel and
    /// the farthest an axis may lag behind the chain's point (v²/2a at
    /// its top speed). Each axis runs between where it was and the
    /// chain's point, so a set point outside that box ran past the chain
    /// (the root of a thread, a corner). Only while a thread leg of known
    /// start runs.
    fn in_chain(&mut self, prev: &SetPoint, p: &SetPoint) {
        let thread = |m: &&Pending| m.shape == Shape::Thread;
        let Some((front, start)) = self
            .pending
            .front()
            .filter(thread)
            .and_then(|m| Some((m, m.start?)))
        else {
            return;
        };
        let here = V2::from_xz(p.x, p.z);
        let lag = |a: &Option<Axis>| a.map_or(0.0, |a| a.max_feed * a.max_feed / (2.0 * a.accel));
        let reach = (here - V2::from_xz(prev.x, prev.z)).norm()
            + lag(&self.axes[0]).max(lag(&self.axes[1]));
        let (mut lo, mut hi) = (start, start);
        let mut widen = |m: &Pending| {
            for q in m.start.into_iter().chain([m.end]) {
                lo = V2::new(lo.r.min(q.r), lo.z.min(q.z));
                hi = V2::new(hi.r.max(q.r), hi.z.max(q.z));
            }
        };
        widen(front);
        let mut run = 0.0;
        for m in self.pending.iter().skip(1).take(MAX_AHEAD).filter(thread) {
            if run > reach {
                break;
            }
            widen(m);
            run += m.start.map_or(f64::INFINITY, |a| (m.end - a).norm());
        }
        for m in self
            .done
            .iter()
            .chain(self.passed.iter().flatten())
            .filter(thread)
        {
            widen(m);
        }
        let out = |v: f64, a: f64, b: f64| (a - v).max(v - b).max(0.0);
        let d = libm::hypot(out(here.r, lo.r, hi.r), out(here.z, lo.z, hi.z));
        self.path_periods += 1;
        self.note(Figure::at(Kind::Path, Subject::Path, p, d, PATH_MM, d));
    }
}
