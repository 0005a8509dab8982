//! G73 pattern repeating (cycles.md §7): the whole profile, ns included,
//! run d times, each time nearer to the allowance contour.

use super::{Path, Seg};
use crate::base::point::Pt;

/// The words of a G73 cycle: relief Δi (radius) and Δk, pass count d, and
/// the finishing allowance (Δu as a radius, Δw).
pub struct Pattern {
    pub di: f64,
    pub dk: f64,
    pub passes: u32,
    pub allowance: Pt,
}

pub fn run(out: &mut Path, segs: &[Seg], pat: &Pattern) {
    let a = out.pos();
    for n in 1..=pat.passes {
        // The first pass is Δi, Δk away from the allowance contour, the
        // last one on it.
        let f = if pat.passes > 1 {
            f64::from(pat.passes - n) / f64::from(pat.passes - 1)
        } else {
            0.0
        };
        let delta = pat.allowance.add(Pt::new(pat.di * f, pat.dk * f));
        out.rapid(a.add(delta));
        for s in segs {
            out.follow(&s.curve.shifted(delta), s.ns && s.rapid);
        }
    }
    out.rapid(a);
}
