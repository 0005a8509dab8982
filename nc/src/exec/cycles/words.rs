//! Reading cycle words and the small numeric rules of cycles.md §0.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::block::{round_half_away, Parsed};
use crate::exec::Nc;

/// Coordinates closer than this are the same (cycles.md §0).
pub(crate) const EPS: f64 = 1e-6;

/// No cycle generates more legs than this: a step so small that the path
/// would never end (or fill the memory) is an alarm instead.
pub(crate) const MAX_LEGS: usize = 1_000_000;

/// sign(v): +1, −1, or 0 when |v| ≤ 1e-6.
pub(crate) fn sign(v: f64) -> f64 {
    if v > EPS {
        1.0
    } else if v < -EPS {
        -1.0
    } else {
        0.0
    }
}

/// Whether `p`, on the way from `a` to `b`, is strictly before `b`.
pub(crate) fn before(a: f64, b: f64, p: f64) -> bool {
    sign(b - a) * (b - p) > EPS
}

/// The stops on the way from `from` to `to` by `step`: from + sd·j·step for
/// j = 1, 2, … while strictly before `to`, then `to` itself (the step that
/// would reach or pass `to` goes to `to`). A zero step goes straight to
/// `to`. More than `MAX_LEGS` stops: alarm `code`.
pub(crate) fn stops(from: f64, to: f64, step: f64, code: Alarm) -> Result<Vec<f64>, NcError> {
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
                return fail(
                    code,
                    format!("the step {step} mm is too small for this cycle"),
                );
            }
            out.push(t);
        }
    }
    out.push(to);
    Ok(out)
}

/// mm per increment (0.001 mm, or 0.0001 inch under G20).
fn increment(nc: &Nc) -> f64 {
    if nc.st.inch() {
        0.0001 * 25.4
    } else {
        0.001
    }
}

/// A P or Q amount in increments, in mm (an integer word: a computed
/// value is rounded).
pub(crate) fn increments(nc: &Nc, p: &Parsed, letter: u8) -> Option<f64> {
    p.get(letter).map(|v| round_half_away(v) * increment(nc))
}

/// A count word (L, K, D …), rounded half away from zero. A literal with a
/// decimal point is E1009 also where block.rs cannot see that the word is
/// a count (a modal repeat that does not name the code).
pub(crate) fn count(p: &Parsed, letter: u8) -> Result<Option<i64>, NcError> {
    let Some(w) = p.word(letter) else {
        return Ok(None);
    };
    if w.literal_with_point() {
        return fail(
            Alarm::DecimalPointNotAllowed,
            format!(
                "{} is a count here; a decimal point is not allowed",
                letter as char
            ),
        );
    }
    // `as` saturates: an absurd count stays an absurd (checked) count.
    Ok(Some(round_half_away(w.value) as i64))
}

/// A length word in mm, or `default`.
pub(crate) fn length_or(nc: &Nc, p: &Parsed, letter: u8, default: f64) -> f64 {
    nc.len_of(p, letter).unwrap_or(default)
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

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
    }
}
