//! The thread lead: the F or I a block writes, the one modal lead, and its
//! range (cycles.md §0, dialect.md §4.3).

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::Num;
use crate::block::Parsed;
use crate::exec::Nc;
use crate::plan::legs::PullOut;

/// The lead a block writes, in mm: F (a length per revolution in the
/// program unit) or, with `tpi`, I in threads per inch (25.4/I). F wins
/// when both are written. The sign is kept: a left-hand lead is F < 0.
pub(crate) fn written(nc: &Nc, p: &Parsed, tpi: bool) -> Option<f64> {
    if let Some(f) = p.get(b'F') {
        return Some(f * nc.st.unit());
    }
    if tpi {
        // I0 gives an infinite lead, which `check` rejects.
        return p.get(b'I').map(|i| 25.4 / i);
    }
    None
}

/// A group-01 thread block's written lead becomes the modal lead, even in
/// a block that does not cut.
pub(crate) fn remember(nc: &mut Nc, written: Option<f64>) {
    if let Some(lead) = written {
        nc.st.cycles.lead = Some(lead.abs());
    }
}

/// The lead a thread block cuts with: its own, else the modal one (E2006
/// when there is none yet), in 0 < lead ≤ `threads.max_lead_mm` (E4010).
pub(crate) fn resolve(nc: &Nc, written: Option<f64>) -> Result<f64, NcError> {
    let Some(lead) = written.or(nc.st.cycles.lead) else {
        return fail(
            Alarm::MissingWord,
            "thread without a lead: give F (or I) in this or an earlier thread block",
        );
    };
    check(nc, lead)?;
    Ok(lead)
}

/// A pull-out or run-out leg (`leg`) that lifts |j| over k, cut at `lead`
/// before it: when it lifts more than it advances its lead is measured
/// along the lift, lead·|j|/k (cycles.md §12, §16.5), and that lead too
/// must stay ≤ `threads.max_lead_mm` (E4010), or the axis would be asked
/// for a lead the machine cannot cut.
pub(crate) fn check_lift(nc: &Nc, leg: &str, lead: f64, (j, k): (f64, f64)) -> Result<(), NcError> {
    let (j, k) = (j.abs(), k.abs());
    let derived = PullOut { x: j, z: k }.lead(lead);
    let max = nc.machine.threads.max_lead_mm;
    if derived <= max {
        return Ok(());
    }
    fail(
        Alarm::BadThread,
        format!(
            "the {leg} leg's lead {} mm ({} × J{} / K{}: it lifts more than it advances) is above the maximum lead of {} mm",
            Num(derived),
            Num(lead),
            Num(j),
            Num(k),
            Num(max)
        ),
    )
}

/// [`check_lift`] for a cycle's pull-out, if it has one.
pub(crate) fn check_pull_out(nc: &Nc, lead: f64, pull: Option<PullOut>) -> Result<(), NcError> {
    match pull {
        Some(p) => check_lift(nc, "pull-out", lead, (p.x, p.z)),
        None => Ok(()),
    }
}

pub(crate) fn check(nc: &Nc, lead: f64) -> Result<(), NcError> {
    let max = nc.machine.threads.max_lead_mm;
    if lead > 0.0 && lead <= max {
        return Ok(());
    }
    if lead.is_infinite() {
        // (25.4 / I with I0.)
        return fail(
            Alarm::BadThread,
            "I0 threads per inch gives no lead: I must be above 0",
        );
    }
    fail(
        Alarm::BadThread,
        format!("thread lead {lead:.4} mm is outside 0 < lead ≤ {max} mm"),
    )
}
