//! The single cycles G90, G94 (cycles.md §1, §2) and G92 (§3, §18) as
//! paths: one cycle's values in, its legs out. The executor
//! (`exec::cycles`) reads the words, keeps the run and prints the legs.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::plan::legs::{self, sign, Leg, PullOut, MAX_LEGS};

/// One cycle of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    pub a: Pt,
    pub end: Pt,
    /// R: G90/G92 cut start radius minus end radius, G94 start Z minus end Z.
    pub taper: f64,
    pub starts: i64,
}

/// G90 (§1): rapid to the cut start X + 2R, cut to the end, X back at
/// feed, rapid to A.
pub fn g90_legs(c: &Cycle) -> [Leg; 4] {
    [
        Leg::Rapid(Pt::new(c.end.r + c.taper, c.a.z)),
        Leg::Line(c.end),
        Leg::Line(Pt::new(c.a.r, c.end.z)),
        Leg::Rapid(c.a),
    ]
}

/// G94 (§2): rapid to the cut start Z + R, face to the end, Z back at
/// feed, rapid to A.
pub fn g94_legs(c: &Cycle) -> [Leg; 4] {
    [
        Leg::Rapid(Pt::new(c.a.r, c.end.z + c.taper)),
        Leg::Line(c.end),
        Leg::Line(Pt::new(c.end.r, c.a.z)),
        Leg::Rapid(c.a),
    ]
}

/// The legs of one G92 cycle: for each start j, rapid to the cut start
/// (X + 2R, zA), thread to the end (with the pull-out), X back at rapid,
/// rapid to A. Start j > 1 begins at (j − 1)·360/L degrees (§18).
pub fn g92_path(c: &Cycle, lead: f64, pull: Option<PullOut>) -> Result<Vec<Leg>, NcError> {
    let start = Pt::new(c.end.r + c.taper, c.a.z);
    let so = sign(c.a.r - c.end.r);
    let mut out = Vec::new();
    for j in 0..c.starts {
        if out.len() > MAX_LEGS {
            return fail(Alarm::BadThread, format!("L{}: too many starts", c.starts));
        }
        let q = j as f64 * 360.0 / c.starts as f64;
        out.push(Leg::Rapid(start));
        legs::pass(start, c.end, lead, q, pull, so, &mut out)?;
        out.push(Leg::Rapid(Pt::new(c.a.r, c.end.z)));
        out.push(Leg::Rapid(c.a));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cycle(a: Pt, end: Pt, taper: f64, starts: i64) -> Cycle {
        Cycle {
            a,
            end,
            taper,
            starts,
        }
    }

    #[test]
    fn g90_and_g94_are_four_legs_back_to_the_start() {
        // From A (r 25, z 2) to the end (r 20, z -30), R -1: G90 rapids to
        // r 20 - 1 = 19 at z 2, cuts to the end, feeds out to r 25, rapids
        // to A; G94 with R -1 rapids to z -30 - 1 at r 25 and faces.
        let a = Pt::new(25.0, 2.0);
        let c = cycle(a, Pt::new(20.0, -30.0), -1.0, 1);
        assert_eq!(
            g90_legs(&c),
            [
                Leg::Rapid(Pt::new(19.0, 2.0)),
                Leg::Line(Pt::new(20.0, -30.0)),
                Leg::Line(Pt::new(25.0, -30.0)),
                Leg::Rapid(a),
            ]
        );
        assert_eq!(
            g94_legs(&c),
            [
                Leg::Rapid(Pt::new(25.0, -31.0)),
                Leg::Line(Pt::new(20.0, -30.0)),
                Leg::Line(Pt::new(20.0, 2.0)),
                Leg::Rapid(a),
            ]
        );
    }

    #[test]
    fn g92_starts_are_spread_over_the_turn() {
        // Three starts: 4 legs each (no pull-out), the thread legs at
        // 0°, 120°, 240° (360/3 apart, cycles.md §18).
        let a = Pt::new(15.0, 5.0);
        let c = cycle(a, Pt::new(14.0, -20.0), 0.0, 3);
        let path = g92_path(&c, 2.0, None).unwrap();
        assert_eq!(path.len(), 12);
        let qs: Vec<Option<f64>> = path
            .iter()
            .filter_map(|l| match *l {
                Leg::Thread { q, .. } => Some(q),
                _ => None,
            })
            .collect();
        assert_eq!(qs, [None, Some(120.0), Some(240.0)]);
        assert_eq!(path[11], Leg::Rapid(a));
    }
}
