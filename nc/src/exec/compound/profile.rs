//! The ns…nf blocks handed over for a roughing cycle, read as contour
//! elements (cycles.md §5, §7, §15). The blocks are not executed: only
//! their geometry and their G00/G01 mode count; F, S, T and M words are
//! ignored (cycles.md §5 "Decision (errors)").

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{Drill, Motion, G};
use crate::base::geom::{self, Element};
use crate::base::point::Pt;
use crate::base::words::Word;
use crate::block::{self, Parsed};
use crate::exec::contour::{self, Corner};
use crate::exec::Nc;
use crate::plan::curve::Curve;
use crate::plan::roughing::Seg;

/// The two types of G71/G72 (cycles.md §15): read from the ns block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The ns block names only the infeed axis.
    Plain,
    /// The ns block names both axes: profiles with pockets.
    Pockets,
}

/// A handed-over block, or E2020 when the compiler handed none.
fn first(blocks: &[(Vec<Word>, u32)]) -> Result<&(Vec<Word>, u32), NcError> {
    blocks.first().ok_or_else(|| {
        NcError::new(
            Alarm::BadProfile,
            "the cycle has no profile: P(ns) and Q(nf) name no blocks",
        )
    })
}

fn parse_at(nc: &Nc, words: &[Word], tag: u32) -> Result<Parsed, NcError> {
    block::parse(words, &nc.machine).map_err(|e| e.at(tag))
}

/// E2021, checked before anything else about the ns block of G71/G72
/// (dialect.md §4.8): its motion code, its own or the one in force, must be
/// G00/G01, and it must name the infeed axis. Returns the cycle type.
pub fn ns_kind(nc: &Nc, blocks: &[(Vec<Word>, u32)], facing: bool) -> Result<Kind, NcError> {
    let (words, tag) = first(blocks)?;
    let p = parse_at(nc, words, *tag)?;
    let code = p.motion().unwrap_or(nc.st.modal.motion);
    let name = if facing { "G72" } else { "G71" };
    if !code.is_straight() {
        let msg = format!(
            "the first profile block (ns) of {name} must move with G00 or G01, not {}",
            code.name()
        );
        return Err(NcError::new(Alarm::BadProfileStart, msg).at(*tag));
    }
    let has_x = p.has(b'X') || p.has(b'U');
    let has_z = p.has(b'Z') || p.has(b'W');
    let (infeed, other, axis) = if facing {
        (has_z, has_x, "Z(W)")
    } else {
        (has_x, has_z, "X(U)")
    };
    if !infeed {
        let msg = format!("the first profile block (ns) of {name} must name {axis}");
        return Err(NcError::new(Alarm::BadProfileStart, msg).at(*tag));
    }
    Ok(if other { Kind::Pockets } else { Kind::Plain })
}

/// E2020 for the codes a profile may not hold: group 00 and the drilling
/// cycles (dialect.md §4.8); E2007 for C/H, since the cycles move X and Z
/// only (without a C axis, block.rs has refused them already).
pub fn check_codes(nc: &Nc, p: &Parsed, tag: u32) -> Result<(), NcError> {
    if nc.machine.axes.c.enabled && (p.has(b'C') || p.has(b'H')) {
        let msg = "C/H may not stand in a G70–G73 profile: the cycles move X and Z only";
        return Err(NcError::new(Alarm::IncompatibleWords, msg).at(tag));
    }
    if let Some(code) = p.one_shot() {
        let msg = format!(
            "{} (group 00) may not stand in a G70–G73 profile",
            code.name()
        );
        return Err(NcError::new(Alarm::BadProfile, msg).at(tag));
    }
    for g in p.gs() {
        if let G::Drill(
            code @ (Drill::FaceDrill | Drill::FaceTap | Drill::SideDrill | Drill::SideTap),
        ) = g
        {
            let msg = format!("{} may not stand in a G70–G73 profile", code.name());
            return Err(NcError::new(Alarm::BadProfile, msg).at(tag));
        }
    }
    Ok(())
}

/// The profile of a roughing cycle (G71, G72, G73) from the tool position.
/// Chamfers and roundings (L, D, ,C, ,R) join an element and the next
/// moving block's one with the contour module's corner geometry, as in
/// ordinary blocks (cycles.md §13 "the same rules apply inside profiles").
pub fn build(nc: &Nc, blocks: &[(Vec<Word>, u32)]) -> Result<Vec<Seg>, NcError> {
    first(blocks)?;
    let mut pos = nc.st.pos;
    let mut code = nc.st.modal.motion;
    let mut segs: Vec<Seg> = Vec::with_capacity(blocks.len());
    // The element waiting for its corner: its index and the corner.
    let mut waiting: Option<(usize, Corner)> = None;
    for (i, (words, tag)) in blocks.iter().enumerate() {
        let p = parse_at(nc, words, *tag)?;
        check_codes(nc, &p, *tag)?;
        if let Some(c) = p.motion() {
            code = c;
        }
        let corner = contour::corner_word(nc, code, &p).map_err(|e| e.at(*tag))?;
        let Some(curve) = element(nc, code, &p, pos).map_err(|e| e.at(*tag))? else {
            continue;
        };
        pos = curve.end();
        let seg = Seg {
            curve,
            rapid: code == Motion::Rapid,
            ns: i == 0,
            tag: *tag,
        };
        match waiting.take() {
            // A G00 takes no corner (W112): the waiting one is dropped.
            Some((at, c)) if code != Motion::Rapid => {
                join(&mut segs, at, seg, c).map_err(|e| e.at(*tag))?
            }
            _ => segs.push(seg),
        }
        waiting = corner.map(|c| (segs.len() - 1, c));
    }
    // A corner word on the nf block is ignored (W112).
    Ok(segs)
}

/// Puts `next` after the element at `at`, joined by corner `c`.
fn join(segs: &mut Vec<Seg>, at: usize, next: Seg, c: Corner) -> Result<(), NcError> {
    let Some(prev) = segs.get_mut(at) else {
        segs.push(next);
        return Ok(());
    };
    let (Some(e1), Some(e2)) = (prev.curve.element(), next.curve.element()) else {
        return fail(
            Alarm::NotSupportedYet,
            "a chamfer or rounding next to an ellipse or parabola in a G71–G73 profile is not supported yet",
        );
    };
    match contour::corner(&e1, &e2, c)? {
        Some((e1, inserted, e2)) => {
            prev.curve = Curve::new(e1);
            // The corner word stands on the earlier block.
            let tag = prev.tag;
            segs.push(Seg {
                curve: Curve::new(inserted),
                rapid: false,
                ns: false,
                tag,
            });
            segs.push(Seg {
                curve: Curve::new(e2),
                ..next
            });
        }
        // Same direction, or a zero-length element: no corner (W112).
        None => segs.push(next),
    }
    Ok(())
}

/// The curve one profile block describes, `None` when it does not move.
fn element(nc: &Nc, code: Motion, p: &Parsed, from: Pt) -> Result<Option<Curve>, NcError> {
    let to = nc.target_from(p, from);
    match code {
        Motion::Rapid | Motion::Line => {
            let Some(deg) = contour::angle_of(p) else {
                let line = Element::Line { from, to };
                return Ok(p.has_axis().then_some(Curve::new(line)));
            };
            // The one-block angle forms (dialect.md §5.2), the same
            // geometry as outside a profile.
            let x = p.has(b'X') || p.has(b'U');
            let z = p.has(b'Z') || p.has(b'W');
            let end = match (x, z) {
                (true, false) => contour::end_at_r(from, deg, to.r)?,
                (false, true) => contour::end_at_z(from, deg, to.z)?,
                // X, Z and Q: an ordinary line, Q ignored (W104).
                (true, true) => to,
                (false, false) => {
                    return fail(
                        Alarm::NotSupportedYet,
                        "the two-block angle form in a G71–G73 profile is not supported yet",
                    )
                }
            };
            Ok(Some(Curve::new(Element::Line { from, to: end })))
        }
        Motion::ArcCw | Motion::ArcCcw => {
            Ok(nc.arc_element(from, code == Motion::ArcCw, to, p)?.map(Curve::new))
        }
        Motion::ThreePoint | Motion::ThreePointAbs => {
            three_point(nc, code == Motion::ThreePointAbs, p, from, to).map(|e| Some(Curve::new(e)))
        }
        // Seed 000, G6.2 note 8 and G7.2 note 7: conics may shape a profile.
        c if c.is_conic() && p.has_axis() => {
            let ellipse = matches!(c, Motion::EllipseCw | Motion::EllipseCcw);
            let cw = matches!(c, Motion::EllipseCw | Motion::ParabolaCw);
            contour::conic::profile_curve(nc, ellipse, cw, p, from, to)
        }
        c if c.is_conic() => Ok(None),
        _ => fail(
            Alarm::BadProfile,
            format!(
                "{} may not stand in a G71–G73 profile: only G00, G01, G02, G03, G05, G6.2/G6.3 and G7.2/G7.3 describe it",
                code.name()
            ),
        ),
    }
}

/// G05 (mid point relative to the start) and G05.1 (absolute mid point).
fn three_point(nc: &Nc, absolute: bool, p: &Parsed, from: Pt, to: Pt) -> Result<Element, NcError> {
    if !p.has(b'I') && !p.has(b'K') {
        return fail(Alarm::MissingWord, "G05 needs the mid point I/K");
    }
    let i = nc.len_of(p, b'I');
    let k = nc.len_of(p, b'K');
    let mid = if absolute {
        Pt::new(i.map_or(from.r, |x| x / 2.0), k.unwrap_or(from.z))
    } else {
        Pt::new(from.r + i.unwrap_or(0.0), from.z + k.unwrap_or(0.0))
    };
    let (centre, cw) = geom::circle_through(from, mid, to)?;
    Ok(Element::Arc {
        from,
        to,
        centre,
        cw,
    })
}
