//! What a compensated move prints (comp.md §3): every point is a nose
//! centre point plus v(T)·R, an arc's centre included.

use alloc::vec;
use alloc::vec::Vec;

use super::{CompState, Leg, Role};
use crate::base::geom::Element;
use crate::plan::offset::over;

/// The printed elements of move `e` with leg `l`, in order, each with
/// whether it is a rapid: an outside corner's arc first (a feed move even
/// next to a G00), then the move itself. Remembers where the nose centre
/// stands afterwards, for the zero-length moves that follow.
pub fn printed(st: &mut CompState, e: &Element, l: &Leg, rapid: bool) -> Vec<(Element, bool)> {
    let tip = l.tool.tip;
    match l.role {
        Role::Zero => {
            let at = st.stand.add(tip);
            vec![(Element::Line { from: at, to: at }, rapid)]
        }
        Role::Start => {
            // Not resolved only if the queue lost its neighbour: the
            // programmed end is the safest guess.
            let end = l.end.unwrap_or(e.end());
            st.stand = end;
            let line = Element::Line {
                from: e.start(),
                to: end,
            };
            vec![(line.shifted(tip), rapid)]
        }
        Role::Body => {
            let start = l.start.unwrap_or_else(|| over(e, e.start(), &l.tool));
            let end = l.end.unwrap_or_else(|| over(e, e.end(), &l.tool));
            st.stand = end;
            let body = match *e {
                Element::Line { .. } => Element::Line {
                    from: start,
                    to: end,
                },
                Element::Arc { centre, cw, .. } => Element::Arc {
                    from: start,
                    to: end,
                    centre,
                    cw,
                },
            };
            let mut out = Vec::with_capacity(2);
            if let Some(arc) = l.corner {
                out.push((arc.shifted(tip), false));
            }
            out.push((body.shifted(tip), rapid));
            out
        }
    }
}
