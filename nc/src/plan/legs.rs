//! The legs a cycle's path is made of (cycles.md §0), the thread pass
//! with its pull-out (§12) and the numeric rules of the cycles: pure
//! functions, which the executor's cycles call and print.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::SpindleDir;
use crate::base::point::Pt;

/// Coordinates closer than this are the same (cycles.md §0).
pub const EPS: f64 = 1e-6;

/// No cycle generates more legs than this: a step so small that the path
/// would never end (or fill the memory) is an alarm instead.
pub const MAX_LEGS: usize = 1_000_000;

/// sign(v): +1, −1, or 0 when |v| ≤ 1e-6.
pub fn sign(v: f64) -> f64 {
    if v > EPS {
        1.0
    } else if v < -EPS {
        -1.0
    } else {
        0.0
    }
}

/// Whether `p`, on the way from `a` to `b`, is strictly before `b`.
pub fn before(a: f64, b: f64, p: f64) -> bool {
    sign(b - a) * (b - p) > EPS
}

/// The stops on the way from `from` to `to` by `step`: from + sd·j·step for
/// j = 1, 2, … while strictly before `to`, then `to` itself (the step that
/// would reach or pass `to` goes to `to`). A zero step goes straight to
/// `to`. More than `MAX_LEGS` stops: alarm `code`.
pub fn stops(from: f64, to: f64, step: f64, code: Alarm) -> Result<Vec<f64>, NcError> {
    let sd = sign(to - from);
    let step = step.abs();
    let mut out = Vec::new();
    if step > 0.0 {
        for j in 1.. {
            let t = from + sd * j as f64 * step;
            if !before(from, to, t) {
                break;
            }
            if j > MAX_LEGS {
                let length = (to - from).abs();
                return fail(
                    code,
                    format!("the step {step} mm over {length} mm makes more than {MAX_LEGS} stops, the most a cycle may make: take a larger step"),
                );
            }
            out.push(t);
        }
    }
    out.push(to);
    Ok(out)
}

/// One step of a cycle's path (cycles.md §0 "Legs"), plus the spindle,
/// dwell and clamp events that tapping and drilling print among them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Leg {
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
pub fn thread(to: Pt, lead: f64, q: f64) -> Leg {
    Leg::Thread {
        to,
        lead,
        dlead: None,
        q: (q.abs() > EPS).then_some(q),
    }
}

/// The same point as printed (X a diameter), within 1e-6 mm.
pub fn same(a: Pt, b: Pt) -> bool {
    (a.x() - b.x()).abs() <= EPS && (a.z - b.z).abs() <= EPS
}

/// A thread pull-out (cycles.md §12): the last `z` mm of a pass along Z
/// lift `x` mm (radius) out of the cut, still synchronised.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOut {
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
pub fn jk_pair(j: Option<f64>, k: Option<f64>) -> Option<(f64, f64)> {
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
pub fn pass(
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
    use alloc::vec;

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

    #[test]
    fn signs_have_a_dead_band() {
        assert_eq!(sign(2.0), 1.0);
        assert_eq!(sign(-0.5), -1.0);
        assert_eq!(sign(1e-7), 0.0);
    }

    #[test]
    fn stops_end_exactly_at_the_target() {
        // 3 → -25 by 5: -2 -7 -12 -17 -22, then -25.
        assert_eq!(
            stops(3.0, -25.0, 5.0, Alarm::ZeroStep).unwrap(),
            vec![-2.0, -7.0, -12.0, -17.0, -22.0, -25.0]
        );
        // An exact multiple is not a separate stop: 0 → 10 by 2.5.
        assert_eq!(
            stops(0.0, 10.0, 2.5, Alarm::ZeroStep).unwrap(),
            vec![2.5, 5.0, 7.5, 10.0]
        );
        // No step, or no way to go: straight to the target.
        assert_eq!(stops(0.0, 10.0, 0.0, Alarm::ZeroStep).unwrap(), vec![10.0]);
        assert_eq!(stops(4.0, 4.0, 1.0, Alarm::ZeroStep).unwrap(), vec![4.0]);
    }

    #[test]
    fn a_step_lost_in_rounding_is_an_alarm_not_a_hang() {
        let e = stops(1e20, 0.0, 1e-3, Alarm::ZeroStep).unwrap_err();
        assert_eq!(e.code, 4011);
        assert!(
            e.message.contains("more than 1000000 stops"),
            "{}",
            e.message
        );
    }
}
