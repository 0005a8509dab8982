//! G90 and G94 under G41/G42 (comp.md §9): the cut and the feed retract
//! are moved towards the start point A, the four legs kept.

use super::{startup, Tool};
use crate::base::error::NcError;
use crate::base::point::Pt;
use crate::exec::Nc;
use crate::plan::elem::{dot, left, scale, unit};
use crate::plan::offset::{meet, Curve};

/// Unit directions along r (X) and along Z.
const ALONG_R: Pt = Pt::new(1.0, 0.0);
const ALONG_Z: Pt = Pt::new(0.0, 1.0);

/// The line `from` → `to` moved R along its unit normal towards `a`, then
/// by v(T)·R; `None` for a zero-length line, which has no normal.
fn moved(from: Pt, to: Pt, a: Pt, tool: &Tool) -> Option<Curve> {
    let t = unit(to.sub(from))?;
    let n = left(t);
    let towards_a = if dot(a.sub(from), n) < 0.0 { -1.0 } else { 1.0 };
    let shift = scale(n, towards_a * tool.radius).add(tool.tip);
    Some(Curve::Line {
        p: from.add(shift),
        t,
    })
}

fn cross_point(a: &Curve, b: &Curve) -> Option<Pt> {
    meet(a, b).first().copied()
}

/// Moves the ends of a G90 (`facing` false) or G94 cycle's legs 1–3
/// (cut start S, cut end E, retract end F; A the start point) when
/// G41/G42 is in force: leg 1 to moved ℓ2 on its own line, leg 2 to the
/// meeting of moved ℓ2 and ℓ3, leg 3 to moved ℓ3 on the line of leg 4.
/// Leg 4 returns to A uncompensated. R and T are read now (§1). A cut or
/// retract of zero length has no side: the cycle then runs as programmed.
pub fn turning_cycle(nc: &Nc, facing: bool, a: Pt, legs: [&mut Pt; 3]) -> Result<(), NcError> {
    let Some(side) = nc.st.modal.comp().side() else {
        return Ok(());
    };
    let tool = startup::read_tool(nc, side)?;
    let [s, e, f] = legs;
    let (Some(cut), Some(back)) = (moved(*s, *e, a, &tool), moved(*e, *f, a, &tool)) else {
        return Ok(());
    };
    // G90: leg 1 runs along X at Z = zA, leg 4 along Z at X = xA; G94
    // the other way round.
    let (leg1, leg4) = if facing {
        (ALONG_Z, ALONG_R)
    } else {
        (ALONG_R, ALONG_Z)
    };
    let line1 = Curve::Line { p: a, t: leg1 };
    let line4 = Curve::Line { p: a, t: leg4 };
    let ends = (
        cross_point(&cut, &line1),
        cross_point(&cut, &back),
        cross_point(&back, &line4),
    );
    if let (Some(p1), Some(p2), Some(p3)) = ends {
        (*s, *e, *f) = (p1, p2, p3);
    }
    Ok(())
}
