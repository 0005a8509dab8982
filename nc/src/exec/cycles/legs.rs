//! The legs a cycle is made of, the pull-out at a thread's end, and
//! printing a path.

use alloc::format;
use alloc::vec::Vec;

use super::words::{sign, EPS};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Event, SpindleDir};
use crate::base::point::Pt;
use crate::exec::{Nc, Sink};

/// One step of a cycle's path (cycles.md §0 "Legs"), plus the spindle,
/// dwell and clamp events that tapping and drilling print among them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Leg {
    Rapid(Pt),
    /// A rapid that also turns C to its angle (a drilling hole's
    /// positioning, caxis.rs).
    RapidC(Pt, f64),
    Line(Pt),
    Thread {
        to: Pt,
        lead: f64,
        dlead: Option<f64>,
        q: Option<f64>,
    },
    Spindle(SpindleDir),
    Dwell(f64),
    M(u32),
}

/// A thread leg at a constant lead; `q` in degrees, printed when not 0.
pub(crate) fn thread(to: Pt, lead: f64, q: f64) -> Leg {
    Leg::Thread {
        to,
        lead,
        dlead: None,
        q: (q.abs() > EPS).then_some(q),
    }
}

/// The same point as printed (X a diameter), within 1e-6 mm.
pub(crate) fn same(a: Pt, b: Pt) -> bool {
    (a.x() - b.x()).abs() <= EPS && (a.z - b.z).abs() <= EPS
}

/// Prints a path from the current point. With `skip_zero` a move that ends
/// where the tool already is, is left out: a leg the cycle generates
/// (cycles.md §0); G33 prints its programmed moves whatever their length.
pub(crate) fn emit(nc: &mut Nc, legs: &[Leg], skip_zero: bool, sink: &mut dyn Sink) {
    for &leg in legs {
        let to = match leg {
            Leg::Rapid(to) | Leg::Line(to) | Leg::Thread { to, .. } => Some(to),
            Leg::RapidC(to, c) if (c - nc.st.c).abs() <= EPS => Some(to),
            _ => None,
        };
        if skip_zero && to.is_some_and(|to| same(to, nc.st.pos)) {
            continue;
        }
        emit_one(nc, leg, sink);
    }
}

fn emit_one(nc: &mut Nc, leg: Leg, sink: &mut dyn Sink) {
    match leg {
        Leg::Rapid(to) => nc.rapid(to, sink),
        Leg::RapidC(to, c) => {
            let from = core::mem::replace(&mut nc.st.c, c);
            nc.rapid_c(to, from, sink);
        }
        Leg::Line(to) => {
            nc.feed_due(sink);
            nc.st.pos = to;
            sink.emit(Event::Line {
                x: to.x(),
                z: to.z,
                c: nc.c_field(nc.st.c),
            });
        }
        Leg::Thread { to, lead, dlead, q } => {
            nc.st.pos = to;
            sink.emit(Event::Thread {
                x: to.x(),
                z: to.z,
                c: nc.c_field(nc.st.c),
                lead,
                dlead,
                q,
            });
        }
        Leg::Spindle(dir) => {
            nc.st.spindle = dir;
            sink.emit(Event::Spindle(dir));
        }
        Leg::Dwell(s) => {
            // The virtual clock (#3001) counts dwells, as G04 does.
            nc.st.clock_ms += s * 1000.0;
            sink.emit(Event::Dwell { s });
        }
        Leg::M(code) => sink.emit(Event::M(code)),
    }
}

/// A thread pull-out (cycles.md §12): the last `z` mm of a pass along Z
/// lift `x` mm (radius) out of the cut, still synchronised.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PullOut {
    pub x: f64,
    pub z: f64,
}

impl PullOut {
    /// From a J/K pair (radial lift, length along Z); none when either is 0.
    pub fn from_pair((x, z): (f64, f64)) -> Option<PullOut> {
        let (x, z) = (x.abs(), z.abs());
        (x > EPS && z > EPS).then_some(PullOut { x, z })
    }

    /// The lead of the pull-out leg, measured along its long axis: X when
    /// it lifts more than it advances (§12).
    pub fn lead(&self, lead: f64) -> f64 {
        if self.x <= self.z {
            lead
        } else {
            lead * self.x / self.z
        }
    }
}

/// J/K as written in a block (mm): only one given means both the same
/// (cycles.md §3, §11).
pub(crate) fn jk_pair(j: Option<f64>, k: Option<f64>) -> Option<(f64, f64)> {
    match (j, k) {
        (None, None) => None,
        (j, k) => {
            let j = j.or(k).unwrap_or(0.0);
            Some((j, k.unwrap_or(j)))
        }
    }
}

/// The thread legs of one pass along the straight line `from` → `to`
/// (Z the long axis, `from` the current point), with an optional pull-out
/// lifting towards `so` (+1 outwards for an outside thread). The first leg
/// prints the start angle `q`; the pull-out leg never does.
pub(crate) fn pass(
    from: Pt,
    to: Pt,
    lead: f64,
    q: f64,
    pull: Option<PullOut>,
    so: f64,
    legs: &mut Vec<Leg>,
) -> Result<(), NcError> {
    let Some(pull) = pull else {
        legs.push(thread(to, lead, q));
        return Ok(());
    };
    let length = (to.z - from.z).abs();
    if pull.z >= length - EPS {
        return fail(
            Alarm::BadThread,
            format!(
                "the pull-out ({:.4} mm along Z) is not shorter than the thread pass ({length:.4} mm)",
                pull.z
            ),
        );
    }
    let z1 = to.z - sign(to.z - from.z) * pull.z;
    let t = (z1 - from.z) / (to.z - from.z);
    let r1 = from.r + t * (to.r - from.r);
    legs.push(thread(Pt::new(r1, z1), lead, q));
    legs.push(thread(
        Pt::new(r1 + so * pull.x, to.z),
        pull.lead(lead),
        0.0,
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_of_j_k_gives_both() {
        assert_eq!(jk_pair(Some(1.0), None), Some((1.0, 1.0)));
        assert_eq!(jk_pair(None, Some(2.0)), Some((2.0, 2.0)));
        assert_eq!(jk_pair(None, None), None);
        assert_eq!(PullOut::from_pair((0.0, 2.0)), None);
    }

    #[test]
    fn a_steep_pull_out_measures_its_lead_along_x() {
        let p = PullOut { x: 2.0, z: 1.0 };
        assert!((p.lead(1.5) - 3.0).abs() < 1e-12);
        let p = PullOut { x: 1.0, z: 2.0 };
        assert!((p.lead(1.5) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn a_pass_with_pull_out_bends_at_the_line() {
        // Taper from r14 at Z5 to r15 at Z-30, pull-out 1 × 2: the bend is
        // 33/35 of the way, at r 14 + 33/35.
        let mut legs = Vec::new();
        let pull = PullOut::from_pair((1.0, 2.0));
        pass(
            Pt::new(14.0, 5.0),
            Pt::new(15.0, -30.0),
            2.0,
            0.0,
            pull,
            1.0,
            &mut legs,
        )
        .unwrap();
        let Leg::Thread { to, .. } = legs[0] else {
            panic!()
        };
        assert!((to.r - (14.0 + 33.0 / 35.0)).abs() < 1e-9 && (to.z + 28.0).abs() < 1e-9);
        let Leg::Thread { to, lead, .. } = legs[1] else {
            panic!()
        };
        assert!((to.r - (15.0 + 33.0 / 35.0)).abs() < 1e-9 && (to.z + 30.0).abs() < 1e-9);
        assert_eq!(lead, 2.0);
    }

    #[test]
    fn a_pull_out_as_long_as_the_pass_is_e4010() {
        let pull = PullOut::from_pair((1.0, 10.0));
        let e = pass(
            Pt::new(10.0, 0.0),
            Pt::new(10.0, -10.0),
            1.0,
            0.0,
            pull,
            1.0,
            &mut Vec::new(),
        );
        assert_eq!(e.unwrap_err().code, 4010);
    }
}
