//! The one-line summary of a run: the worst figure of each kind.

use super::{Certifier, Kind};
use core::fmt;

impl Certifier {
    /// The one-line summary: the worst figure of each kind.
    pub fn summary(&self) -> Summary<'_> {
        Summary(self)
    }
}

/// The summary line (see [`Certifier::summary`]).
pub struct Summary<'a>(&'a Certifier);

impl fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.0;
        write!(
            f,
            "{} periods ({:.3} s)",
            c.periods,
            c.periods as f64 * c.dt
        )?;
        for kind in Kind::ALL {
            let w = c.worst(kind);
            match (kind, w) {
                (Kind::Jerk, None) if !c.jerk => write!(f, "; jerk: not limited")?,
                (Kind::Travel, None) => write!(f, "; travel: not limited")?,
                (Kind::Travel, Some(w)) => write!(
                    f,
                    "; travel: {} {:.3} mm {} its limit ({} at {:.3} mm, line {})",
                    if w.ratio > 0.0 { "worst" } else { "nearest" },
                    w.ratio.abs(),
                    if w.ratio > 0.0 { "beyond" } else { "inside" },
                    w.subject.name(),
                    w.value,
                    w.line
                )?,
                (Kind::EndPoint, _) => {
                    write!(f, "; end points: {} of {} reached", c.reached, c.end_points)?
                }
                (Kind::Path, Some(w)) => write!(
                    f,
                    "; path: worst {:.4} mm off ({} periods, line {})",
                    w.value, c.path_periods, w.line
                )?,
                (Kind::Lead, Some(w)) => write!(
                    f,
                    "; thread lead: worst {:.4} % off ({} periods, line {})",
                    w.ratio * 100.0,
                    c.lead_periods,
                    w.line
                )?,
                (Kind::SurfaceSpeed, Some(w)) => write!(
                    f,
                    "; surface speed: worst {:.4} % off the G96 target ({} periods, line {})",
                    w.ratio * 100.0,
                    c.css_periods,
                    w.line
                )?,
                (_, Some(w)) => write!(
                    f,
                    "; {}: worst {:.1} % of the limit ({} {:.3} {}, line {})",
                    kind.name(),
                    w.ratio * 100.0,
                    w.subject.name(),
                    w.value.abs(),
                    w.subject.unit(kind),
                    w.line
                )?,
                (_, None) => write!(f, "; {}: none", kind.name())?,
            }
        }
        Ok(())
    }
}
