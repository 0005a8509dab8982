//! What a compensated move prints (comp.md §3): every point is a nose
//! centre point plus v(T)·R, an arc's centre included.

use super::offset::over;
use super::{CompState, Leg, Role};
use crate::geom::Element;
use crate::state::Pt;

/// `e` moved by `d`, end points and centre alike.
fn shifted(e: &Element, d: Pt) -> Element {
    match *e {
        Element::Line { from, to } => Element::Line {
            from: from.add(d),
            to: to.add(d),
        },
        Element::Arc {
            from,
            to,
            centre,
            cw,
        } => Element::Arc {
            from: from.add(d),
            to: to.add(d),
            centre: centre.add(d),
            cw,
        },
    }
}

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
            vec![(shifted(&line, tip), rapid)]
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
                out.push((shifted(&arc, tip), false));
            }
            out.push((shifted(&body, tip), rapid));
            out
        }
    }
}
