//! An ellipse or parabola under compensation meets the element before it
//! (comp.md §5 with a conic for the second element). The conic runs as
//! chords (`contour::conic`); at an inside corner the chord at the start
//! may be shorter than the trim, so the chords start at the one that
//! reaches the crossing of the two offset curves, found here on the true
//! offset of the conic.

use super::Tool;
use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::plan::comp::{kind, Kind};
use crate::plan::curve::Curve;
use crate::plan::elem::{cross, tangent_at};
use crate::plan::offset::{self, normal};

/// Samples of the conic searched for the first crossing; the crossing is
/// then refined by bisection to the last bit that changes.
const SAMPLES: u32 = 256;

/// The parameter of the conic where its offset crosses the offset of
/// `prev` at an inside corner (0 at a tangent or outside corner, where
/// the conic's offset starts on the start's normal). E4036 when the
/// offsets do not meet.
pub(crate) fn start_param(prev: &Element, tool: &Tool, conic: &Curve) -> Result<f64, NcError> {
    let q = conic.start();
    let (Some(t1), Some(t2)) = (tangent_at(prev, q), conic.direction(0.0)) else {
        return Ok(0.0);
    };
    if kind(t1, t2, tool.side) != Kind::Inside {
        return Ok(0.0);
    }
    let off = offset::curve(prev, tool)?;
    // Which side of the offset curve of `prev` the conic's offset point
    // at s lies on: a sign change is a crossing.
    let side = |s: f64| {
        let o = conic.at(s).add(normal(conic.direction(s), tool));
        match off {
            offset::Curve::Line { p, t } => cross(t, o.sub(p)),
            offset::Curve::Circle { c, rad } => o.dist(c) - rad,
        }
    };
    let before = side(0.0).signum();
    let mut lo = 0.0;
    for i in 1..=SAMPLES {
        let hi = f64::from(i) / f64::from(SAMPLES);
        if side(hi).signum() != before {
            return Ok(bisect(&side, before, lo, hi));
        }
        lo = hi;
    }
    fail(
        Alarm::CompInterference,
        "compensation interference: the offset of the ellipse or parabola does not meet the offset of the element before it",
    )
}

/// The crossing of `side` in [lo, hi], where its sign changes from
/// `before`.
fn bisect(side: &dyn Fn(f64) -> f64, before: f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if side(mid).signum() == before {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}
