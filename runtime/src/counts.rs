//! Set points in counts: the axis positions quantized to the machine's
//! resolution, as a position-command or pulse interface sends them.
//!
//! The runtime plans and interpolates in IEEE doubles; a drive takes whole
//! steps. Each period's machine set point is rounded to the nearest step
//! on its own (half away from zero), never by adding up rounded
//! increments, so the counts never drift from the set points: every count
//! lies within half a step of its set point, and the step from one period
//! to the next is the set points' own step to within one count. On a
//! machine with backlash or pitch error compensation (`backlash_mm`,
//! `pitch_comp_mm`, C's `backlash_deg`, `pitch_comp_deg`) the point
//! rounded is the set point plus the compensation: the drive's command.
//!
//! X is a diameter, so one X count is `resolution_mm` of diameter, half of
//! it on the slide: the least command increment of a diameter-programmed
//! X, as a Fanuc control of increment system B has it (0.0005 mm of radius
//! on the reference machine). C counts are [`C_STEP_DEG`], the dialect's
//! angular increment.

/// One C count, degrees.
pub const C_STEP_DEG: f64 = 0.001;

/// A set point's machine position in counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Counts {
    /// X (a diameter) in steps of the resolution.
    pub x: i64,
    /// Z in steps of the resolution.
    pub z: i64,
    /// C in steps of [`C_STEP_DEG`]; 0 on a machine without C.
    pub c: i64,
}

impl Counts {
    /// The counts of machine position (`x` a diameter, `z`, `c` degrees)
    /// at `resolution_mm` per count.
    pub fn of(x: f64, z: f64, c: f64, resolution_mm: f64) -> Counts {
        Counts {
            x: quantize(x, resolution_mm),
            z: quantize(z, resolution_mm),
            c: quantize(c, C_STEP_DEG),
        }
    }
}

/// `v` in whole steps of `step`: the nearest, halves away from zero (as
/// the dialect rounds). The quotient is one correctly rounded division, so
/// the result is the same on every host. Out of range it saturates (a
/// position of 10¹⁶ steps is no machine's) and NaN, which no set point
/// holds, gives 0.
pub fn quantize(v: f64, step: f64) -> i64 {
    libm::round(v / step) as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halves_round_away_from_zero() {
        // Steps and values exact in binary, so the halves are exact too.
        assert_eq!(quantize(1.25, 0.5), 3);
        assert_eq!(quantize(-1.25, 0.5), -3);
        assert_eq!(quantize(1.2, 0.5), 2);
        assert_eq!(quantize(-0.2, 0.5), 0);
        assert_eq!(quantize(0.0, 0.001), 0);
    }

    #[test]
    fn millimetres_become_micrometre_steps() {
        // 25.0004 mm and −12.3456 mm at 0.001 mm: 25 000.4 and −12 345.6
        // steps.
        let c = Counts::of(25.0004, -12.3456, 90.0, 0.001);
        assert_eq!(
            c,
            Counts {
                x: 25_000,
                z: -12_346,
                c: 90_000
            }
        );
    }

    #[test]
    fn out_of_range_saturates_and_nan_is_zero() {
        assert_eq!(quantize(1e300, 0.001), i64::MAX);
        assert_eq!(quantize(-1e300, 0.001), i64::MIN);
        assert_eq!(quantize(f64::NAN, 0.001), 0);
    }
}
