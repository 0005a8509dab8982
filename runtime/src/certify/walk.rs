//! The walk along the canon's end points: which the path reached, in
//! order, and which it missed.

use super::pending::Pending;
use super::step::Step;
use super::{Certifier, Figure, Kind, Subject};
use crate::interpolate::SetPoint;

impl Certifier {
    /// Pops the end points this period's path reached, in order. One
    /// that the path cut by (it came within a period's travel of it and
    /// moves away) is a violation at its nearest approach, and the walk
    /// goes on from the next, so that one miss does not hide the rest.
    pub(super) fn end_points(&mut self, prev: &SetPoint, p: &SetPoint) {
        let step = Step::new(prev, p);
        // Where the walk stands on the step (a share of it, 0 at its
        // start): the next end point is reached after the last one (a
        // short move back may end within the tolerance of where this step
        // began).
        let mut from = 0.0;
        let mut first = true;
        while let Some(mut m) = self.pending.front().copied() {
            let way = step.way(&m);
            if m.away {
                if !way.returns(from, m.tol) {
                    self.waiting(p);
                    break;
                }
                m.away = false;
                if let Some(f) = self.pending.front_mut() {
                    f.away = false;
                }
            }
            // After an end point reached in this step, the next is due in
            // it only where the rest of the step runs past it. One the
            // step ends on or short of may be a µm move's the tool runs
            // after the ones it still has to run (it stands within a µm
            // of several): judged now, the tool going on to those would
            // look like leaving it, a miss.
            if !first && way.joined() {
                let t = way.param(from);
                if !(t > 0.0 && t < 1.0) {
                    break;
                }
            }
            m.tol = self.tol_of(&m, p.spindle_rpm);
            let d = way.dist(from);
            // The step ends where it is nearest to the end point: the tool
            // may still get nearer, and the end points after it are not
            // due yet (points a µm apart lie within the tolerance of one
            // step together).
            let closing = way.joined() && d > 0.0 && way.param(from) >= 1.0;
            if closing {
                self.nearer(d, p);
                break;
            }
            let within = m.tol + super::ROUNDING_MM;
            if d <= within || m.nearest <= within {
                if way.joined() {
                    from += (1.0 - from) * way.param(from).clamp(0.0, 1.0);
                }
                first = false;
                self.reached += 1;
                self.passed(m, p.spindle_rpm);
                continue;
            }
            // The period's travel is the axes' step: where the frame
            // jumped, b − a is the jump, not a way the tool went.
            if d > m.nearest && m.nearest <= way.travel {
                self.missed(&m);
                self.passed(m, p.spindle_rpm);
                continue;
            }
            self.nearer(d, p);
            break;
        }
    }

    /// The next end point is a full circle's, and the tool has not come
    /// back to it: where the walk began to wait, the place a miss is
    /// reported at if it never comes back.
    fn waiting(&mut self, p: &SetPoint) {
        if let Some(f) = self.pending.front_mut() {
            if f.at.0 == 0.0 {
                f.at = (p.time_s, p.file, p.line);
            }
        }
    }

    /// The next end point is `d` from this period's step: its nearest
    /// approach so far?
    fn nearer(&mut self, d: f64, p: &SetPoint) {
        if let Some(f) = self.pending.front_mut() {
            if d < f.nearest {
                f.nearest = d;
                f.at = (p.time_s, p.file, p.line);
            }
        }
    }

    /// The walk leaves end point `m`, the next pending, reached or missed.
    fn passed(&mut self, m: Pending, rpm: f64) {
        self.reach(m);
        self.pending.pop_front();
        self.turned(&m, rpm);
    }

    /// End point `m` is reached (or passed by): the move is done.
    fn reach(&mut self, m: Pending) {
        if let Some(d) = self.done {
            self.passed.rotate_right(1);
            self.passed[0] = Some(d);
        }
        self.done = Some(m);
    }

    /// End point `m` was not reached: a violation at its nearest
    /// approach.
    pub(super) fn missed(&mut self, m: &Pending) {
        let (time_s, file, line) = m.at;
        self.note(Figure {
            kind: Kind::EndPoint,
            subject: Subject::Path,
            time_s,
            file,
            line,
            value: m.nearest,
            limit: m.tol,
            ratio: m.nearest,
        });
    }
}
