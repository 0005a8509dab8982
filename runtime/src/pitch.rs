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
}

impl PitchTable {
    /// The table of `points`, which a machine file gives in ascending
    /// position (machine_check: at least two, a gentle slope).
    pub fn new(points: Vec<(f64, f64)>) -> PitchTable {
        PitchTable { points }
    }

    /// No correction anywhere.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The correction at position `at`: along the line between the
    /// points about it; beyond the table, its end's.
    pub fn at(&self, at: f64) -> f64 {
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
        // (The first point past `at`, and the one before it.)
        let i = p.partition_point(|q| q.0 <= at);
        match (p.get(i.wrapping_sub(1)), p.get(i)) {
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
        let t = PitchTable::new(vec![(-300.0, -0.004), (-100.0, -0.001), (0.0, 0.0)]);
        let near = |a: f64, b: f64| (a - b).abs() < 1e-15;
        assert!(near(t.at(-200.0), -0.0025));
        assert!(near(t.at(-50.0), -0.0005));
        assert!(near(t.at(-100.0), -0.001));
        assert_eq!(t.at(-400.0), -0.004);
        assert_eq!(t.at(2.0), 0.0);
        assert_eq!(PitchTable::default().at(-200.0), 0.0);
    }
}
