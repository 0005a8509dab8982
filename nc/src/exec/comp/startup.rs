//! The tool data a start-up reads (comp.md §1, §3) and the end of the
//! start-up move (§4).

use alloc::format;

use super::Tool;
use crate::base::error::{fail, Alarm, NcError};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::exec::Nc;
use crate::plan::elem::{scale, tangent_at};
use crate::plan::offset::normal;

/// v(T): the imaginary tip seen from the nose centre, per unit radius
/// (Fanuc numbering: 1–4 the quadrants counter-clockwise from (+Z, +X),
/// 5–8 the axis directions from +Z; 0, 9 and anything else the centre).
pub fn tip_vector(t: f64) -> Pt {
    // (Δr, Δz): `Pt::new` takes r first.
    let (dr, dz) = match crate::block::round_half_away(t) as i64 {
        1 => (1.0, 1.0),
        2 => (1.0, -1.0),
        3 => (-1.0, -1.0),
        4 => (-1.0, 1.0),
        5 => (0.0, 1.0),
        6 => (1.0, 0.0),
        7 => (0.0, -1.0),
        8 => (-1.0, 0.0),
        _ => (0.0, 0.0),
    };
    Pt::new(dr, dz)
}

/// The radius R (geometry + wear) and tip of the active offset, on
/// `side`. Offset 0, or a number past the table (88, 99), has none.
/// E4036 for a negative radius (wear larger than the geometry).
pub fn read_tool(nc: &Nc, side: f64) -> Result<Tool, NcError> {
    let i = (nc.st.offset as usize).checked_sub(1);
    let geom = i.and_then(|i| nc.st.geom.get(i));
    let wear = i.and_then(|i| nc.st.wear.get(i));
    let radius = geom.map_or(0.0, |g| g[2]) + wear.map_or(0.0, |w| w[2]);
    let tip = wear.map_or(0.0, |w| w[3]);
    if radius.is_nan() || radius < 0.0 {
        return fail(
            Alarm::CompInterference,
            format!(
                "the nose radius of offset {} is negative ({radius:.4}): the wear is larger than the geometry",
                nc.st.offset
            ),
        );
    }
    Ok(Tool {
        side,
        radius,
        tip: scale(tip_vector(tip), radius),
    })
}

/// Where the start-up move `e` ends when the next element starts in
/// direction `t2` (`None`: no compensated element follows, so the
/// start-up's own direction counts): C = Q + R·n(t2).
pub fn end(e: &Element, t2: Option<Pt>, tool: &Tool) -> Pt {
    let q = e.end();
    let t = t2.or_else(|| tangent_at(e, q));
    q.add(normal(t, tool))
}
