//! G74 face grooving / peck drilling along Z and G75 grooving along X
//! (cycles.md §9, §10) as paths: pecks along one axis, steps along the
//! other. The executor (`exec::cycles`) reads the words and prints.

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::plan::legs::{sign, stops, Leg, MAX_LEGS};

/// A cycle block's words, the axes not yet exchanged: `peck` along the
/// pecking axis, `step` between columns/rows, `relief` at the bottom.
pub struct Groove {
    pub a: Pt,
    pub end: Pt,
    pub step: f64,
    pub peck: f64,
    pub relief: f64,
    pub retract: f64,
}

/// Which coordinate pecks and which one steps.
#[derive(Clone, Copy)]
struct Axes {
    /// G74 pecks along Z and steps in r; G75 the other way round.
    peck_z: bool,
}

impl Axes {
    /// (peck coordinate, step coordinate) of a point.
    fn split(self, p: Pt) -> (f64, f64) {
        if self.peck_z {
            (p.z, p.r)
        } else {
            (p.r, p.z)
        }
    }

    fn pt(self, peck: f64, step: f64) -> Pt {
        if self.peck_z {
            Pt::new(step, peck)
        } else {
            Pt::new(peck, step)
        }
    }
}

/// G74: columns in r, pecks along Z.
pub fn g74_path(g: &Groove) -> Result<Vec<Leg>, NcError> {
    path(
        g,
        Axes { peck_z: true },
        "G74 with P0 while X differs from the start X: no X step",
    )
}

/// G75: rows in Z, pecks along r.
pub fn g75_path(g: &Groove) -> Result<Vec<Leg>, NcError> {
    path(
        g,
        Axes { peck_z: false },
        "G75 with Q0 while Z differs from the start Z: no Z step",
    )
}

/// Both cycles in the (peck, step) coordinates of `ax`.
fn path(g: &Groove, ax: Axes, zero_step: &str) -> Result<Vec<Leg>, NcError> {
    let (a_peck, a_step) = ax.split(g.a);
    let (e_peck, e_step) = ax.split(g.end);
    let ss = sign(e_step - a_step);
    if ss != 0.0 && g.step <= 0.0 {
        return fail(Alarm::ZeroStep, zero_step);
    }
    let mut lines = vec![a_step];
    if ss != 0.0 {
        lines.extend(stops(a_step, e_step, g.step, Alarm::ZeroStep)?);
    }
    // The relief moves against the step direction; with a single column
    // (row) Δd keeps its own sign.
    let relief = if lines.len() == 1 {
        g.relief
    } else {
        -ss * g.relief.abs()
    };
    let sp = sign(e_peck - a_peck);
    let pecks = stops(a_peck, e_peck, g.peck, Alarm::ZeroStep)?;
    let mut out = Vec::new();
    for (n, &line) in lines.iter().enumerate() {
        if out.len() > MAX_LEGS {
            let msg = format!("the cycle would make more than {MAX_LEGS} moves, the most a cycle may make: take larger steps");
            return fail(Alarm::ZeroStep, msg);
        }
        for (j, &t) in pecks.iter().enumerate() {
            out.push(Leg::Line(ax.pt(t, line)));
            if j + 1 < pecks.len() {
                out.push(Leg::Rapid(ax.pt(t - sp * g.retract, line)));
            }
        }
        out.push(Leg::Rapid(ax.pt(e_peck, line + relief)));
        out.push(Leg::Rapid(ax.pt(a_peck, line + relief)));
        out.push(Leg::Rapid(match lines.get(n + 1) {
            Some(&next) => ax.pt(a_peck, next),
            None => g.a,
        }));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_column_g74_pecks_and_backs_off() {
        // From z 2 to z -5 at r 0, pecks of 3, retract 1: the stops are
        // -1, -4 and the bottom -5 (cycles.md §0); after each peck but the
        // last the tool backs off 1 towards the start, then returns to A.
        let a = Pt::new(0.0, 2.0);
        let g = Groove {
            a,
            end: Pt::new(0.0, -5.0),
            step: 0.0,
            peck: 3.0,
            relief: 0.0,
            retract: 1.0,
        };
        let at = |z| Pt::new(0.0, z);
        assert_eq!(
            g74_path(&g).unwrap(),
            [
                Leg::Line(at(-1.0)),
                Leg::Rapid(at(0.0)),
                Leg::Line(at(-4.0)),
                Leg::Rapid(at(-3.0)),
                Leg::Line(at(-5.0)),
                Leg::Rapid(at(-5.0)),
                Leg::Rapid(at(2.0)),
                Leg::Rapid(a),
            ]
        );
        // Columns without a step: E4011.
        let wide = Groove {
            end: Pt::new(5.0, -5.0),
            ..g
        };
        assert_eq!(g74_path(&wide).unwrap_err().code, 4011);
    }
}
