//! Pitch error compensation: the corrections a laser calibration measured
//! along an axis's stroke, which the drive's command adds where the slide
//! is to stand (docs/machine.md, `pitch_comp_mm`). A screw's lead is never
//! exact; the table says by how much the command must differ from the set
//! point at each measured position, and between two the correction is
//! read off the straight line through them.

use alloc::vec::Vec;

/// One axis's table: (machine position, correction) pairs in slide units
/// (X radial), in ascending position; empty for none.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PitchTable {
    points: Vec<(f64, f64)>,
    /// The segment the last position fell in: a slide moves a few µm a
    /// period, so the next is nearly always there (no search then).
    hint: usize,
}

impl PitchTable {
    /// The table of `points`, which a machine file gives in ascending
    /// position (machine_check: at least two, a gentle slope).
    pub fn new(points: Vec<(f64, f64)>) -> PitchTable {
        PitchTable { points, hint: 0 }
    }

    /// No correction anywhere.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The correction at position `at`: along the line between the
    /// points about it; beyond the table, its end's.
    pub fn at(&mut self, at: f64) -> f64 {
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
}
