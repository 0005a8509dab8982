//! Reading cycle words and the small numeric rules of cycles.md §0.

use alloc::format;

use crate::base::error::{Alarm, NcError};
use crate::block::{round_half_away, Parsed};
use crate::exec::Nc;

pub(crate) use crate::plan::legs::EPS;

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
        let msg = format!(
            "{} is a count here; a decimal point is not allowed",
            letter as char
        );
        return Err(NcError::new(Alarm::DecimalPointNotAllowed, msg).on_addr(w.addr));
    }
    // `as` saturates: an absurd count stays an absurd (checked) count.
    Ok(Some(round_half_away(w.value) as i64))
}

/// A length word in mm, or `default`.
pub(crate) fn length_or(nc: &Nc, p: &Parsed, letter: u8, default: f64) -> f64 {
    nc.len_of(p, letter).unwrap_or(default)
}
