//! Pitch error compensation: the corrections a laser calibration measured
//! along an axis's stroke, which the drive's command adds where the slide
//! is to stand (docs/machine.md, `pitch_comp_mm`). A screw's lead is never
//! exact; the table says by how much the command must differ from the set
//! point at each measured position, and between two the correction is
//! read off the straight line through them. A rotary axis's table
//! (`pitch_comp_deg`) covers one turn and repeats every turn.

use alloc::vec::Vec;

/// One axis's table: (machine position, correction) pairs in slide units
/// (X radial), in ascending position; empty for none.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PitchTable {
    points: Vec<(f64, f64)>,
    /// The segment the last position fell in: a slide moves a few µm a
    /// period, so the next is nearly always there (no search then).
    hint: usize,
    /// A rotary axis's table: positions are read modulo a turn.
    turn: bool,
}

/// A turn of a rotary axis, degrees.
const TURN: f64 = 360.0;

impl PitchTable {
    /// The table of `points`, which a machine file gives in ascending
    /// position (machine_check: at least two, a gentle slope).
    pub fn new(points: Vec<(f64, f64)>) -> PitchTable {
        PitchTable {
            points,
            hint: 0,
            turn: false,
        }
    }

    /// A rotary axis's table of `points` over one turn (machine_check:
    /// angles 0 ≤ a < 360, ascending): read at the angle modulo a turn,
    /// and from the last point on to the first, one turn later, along
    /// the line between them (so the correction never jumps).
    pub fn turn(points: Vec<(f64, f64)>) -> PitchTable {
        let (Some(&(a0, c0)), Some(&(an, cn))) = (points.first(), points.last()) else {
            return PitchTable::default();
        };
        let mut round = Vec::with_capacity(points.len() + 2);
        round.push((an - TURN, cn));
        round.extend(points);
        round.push((a0 + TURN, c0));
        PitchTable {
            points: round,
            hint: 0,
            turn: true,
        }
    }

    /// No correction anywhere.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The correction at position `at`: along the line between the
    /// points about it; beyond the table, its end's.
    pub fn at(&mut self, at: f64) -> f64 {
        let at = match self.turn {
            // (The table reaches from its last angle less a turn to its
            // first plus a turn: every angle of [0, 360] is inside.)
            true => libm::fmod(at, TURN) + if at < 0.0 { TURN } else { 0.0 },
            false => at,
        };
        let p = &self.points;
        let (Some(&(lo, first)), Some(&(hi, last))) = (p.first(), p.last()) else {
            return 0.0;
        };
        if at <= lo {
            return first;
        }
        if at >= hi {
            return last;
        }
        let within = |i: usize| matches!((p.get(i), p.get(i + 1)), (Some(a), Some(b)) if a.0 <= at && at < b.0);
        if !within(self.hint) {
            // (The first point past `at`, and the one before it.)
            self.hint = p.partition_point(|q| q.0 <= at).saturating_sub(1);
        }
        match (p.get(self.hint), p.get(self.hint + 1)) {
            (Some(&(a, ca)), Some(&(b, cb))) => ca + (cb - ca) * (at - a) / (b - a),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    /// A Z screw measured at −300, −100 and 0: by hand, at −200 half way
    /// from −0.004 to −0.001, at −50 half way from −0.001 to 0; the ends
    /// held beyond the table.
    #[test]
    fn the_correction_is_read_off_the_line_between_two_points() {
        let mut t = PitchTable::new(vec![(-300.0, -0.004), (-100.0, -0.001), (0.0, 0.0)]);
        let near = |a: f64, b: f64| (a - b).abs() < 1e-15;
        assert!(near(t.at(-200.0), -0.0025));
        assert!(near(t.at(-50.0), -0.0005));
        assert!(near(t.at(-100.0), -0.001));
        assert_eq!(t.at(-400.0), -0.004);
        assert_eq!(t.at(2.0), 0.0);
        // From one segment to the other and back, as a slide moves.
        assert!(near(t.at(-250.0), -0.00325));
        assert!(near(t.at(-50.0), -0.0005));
        assert!(near(t.at(-200.0), -0.0025));
        assert_eq!(PitchTable::default().at(-200.0), 0.0);
    }

    /// A C table measured at 0°, 90° and 270°: by hand, at 45° half way
    /// from 0 to 0.004; at 315° half way from 270°'s −0.002 round to
    /// 360°'s 0; at 350° 8/9 of that way; the same a turn or two on and
    /// back.
    #[test]
    fn a_turns_table_repeats_every_turn() {
        let mut t = PitchTable::turn(vec![(0.0, 0.0), (90.0, 0.004), (270.0, -0.002)]);
        let near = |a: f64, b: f64| (a - b).abs() < 1e-15;
        assert!(near(t.at(45.0), 0.002));
        assert!(near(t.at(180.0), 0.001));
        assert!(near(t.at(315.0), -0.001));
        assert!(near(t.at(350.0), -0.002 / 9.0));
        assert!(near(t.at(360.0 + 45.0), 0.002));
        assert!(near(t.at(720.0 + 315.0), -0.001));
        assert!(near(t.at(-45.0), -0.001));
        assert!(near(t.at(-360.0 - 270.0), 0.004));
        assert_eq!(t.at(0.0), 0.0);
        // A table that starts past 0: below its first angle the line
        // comes from its last, a turn before (−150°): at 0°, 150/180 of
        // the way from −0.003 to 0.003.
        let mut t = PitchTable::turn(vec![(30.0, 0.003), (210.0, -0.003)]);
        assert!(near(t.at(0.0), 0.002));
        assert!(near(t.at(120.0), 0.0));
        assert_eq!(PitchTable::turn(vec![]).at(10.0), 0.0);
    }
}
