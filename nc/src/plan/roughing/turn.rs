//! E4009 when a G71/G72 profile turns back: the block that does it, the
//! coordinate it reaches and the way out, so that the diagnostic points at
//! the culprit rather than only at the cycle block.

use alloc::format;
use alloc::string::String;

use super::{Job, Seg};
use crate::base::error::{Alarm, NcError};
use crate::base::event::Num;
use crate::base::point::Pt;
use crate::plan::curve::{coord, Axis, SLACK};

/// How frame coordinates go back to the program's: the finishing
/// allowance taken off, the G72 mirror undone.
pub struct Frame {
    shift: Pt,
    mirrored: bool,
}

impl Frame {
    pub fn of(job: &Job, mirrored: bool) -> Frame {
        Frame {
            shift: job.a1.sub(job.a),
            mirrored,
        }
    }

    /// The program's name of a frame axis (G72 computes with X and Z
    /// exchanged).
    fn name(&self, axis: Axis) -> char {
        match (axis, self.mirrored) {
            (Axis::Z, false) | (Axis::R, true) => 'Z',
            _ => 'X',
        }
    }

    /// A frame coordinate on `axis` as the program writes it (X a
    /// diameter), the allowance taken off.
    fn value(&self, axis: Axis, v: f64) -> f64 {
        let v = v - coord(self.shift, axis);
        if self.name(axis) == 'X' {
            2.0 * v
        } else {
            v
        }
    }

    fn cycle(&self) -> &'static str {
        if self.mirrored {
            "G72"
        } else {
            "G71"
        }
    }
}

/// E4009 pointing to `seg`'s block: over [s0, s1] it moves against `dir` on `axis`
/// (the cut direction when `axis` is Z, out of the material when it is R).
pub fn turns_back(frame: &Frame, seg: &Seg, axis: Axis, dir: f64, s0: f64, s1: f64) -> NcError {
    let c = &seg.curve;
    let name = frame.name(axis);
    let at = |s: f64| coord(c.at(s), axis);
    let show = |v: f64| Num(frame.value(axis, v));
    let gap = |a: f64, b: f64| (frame.value(axis, a) - frame.value(axis, b)).abs();
    let (v0, v1) = (at(s0), at(s1));
    // The furthest point along `dir` and the furthest back, among the
    // end and the extremes inside the range.
    let (mut far, mut back) = (v1, v1);
    for s in c.extremes(axis).into_iter().filter(|&s| s > s0 && s < s1) {
        let v = at(s);
        if dir * (v - far) > 0.0 {
            far = v;
        }
        if dir * (v - back) < 0.0 {
            back = v;
        }
    }
    let where_ = if dir * (v1 - v0) < 0.0 {
        format!(
            "runs back along {name} from {name}{} to {name}{}",
            show(v0),
            show(v1)
        )
    } else if dir * (far - v1) > SLACK {
        format!(
            "reaches {name}{}, {:.3} mm past its end point {name}{}",
            show(far),
            gap(far, v1),
            show(v1)
        )
    } else {
        format!(
            "comes back to {name}{}, {:.3} mm behind its start point {name}{}",
            show(back),
            gap(back, v0),
            show(v0)
        )
    };
    let message = format!(
        "the {} profile is not monotonic: a profile block {where_}",
        frame.cycle()
    );
    NcError::new(Alarm::BadRoughing, message)
        .pointing_to(seg.tag)
        .with_help(fix(frame, axis))
}

fn fix(frame: &Frame, axis: Axis) -> String {
    let cut = frame.name(Axis::Z);
    let infeed = frame.name(Axis::R);
    if axis == Axis::R {
        format!(
            "this is a pocket: name both X and Z in the ns block to rough it as type II, or make the profile monotonic in {infeed}"
        )
    } else {
        format!(
            "{} cuts along {cut}, in type II too: make the profile run one way along {cut} (end this element where it turns), or leave that part to G70",
            frame.cycle()
        )
    }
}
