//! The ns…nf blocks handed over for a roughing cycle, read as contour
//! elements (cycles.md §5, §7, §15). The blocks are not executed: only
//! their geometry and their G00/G01 mode count; F, S, T and M words are
//! ignored (cycles.md §5 "Decision (errors)"). A pure function of the
//! blocks and a [`Reader`] (the machine, the units, the point and the
//! motion code the cycle starts from): the executor calls it at run time,
//! and the compiler could at compile time.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{Drill, Motion, G};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::base::words::addr;
use crate::base::words::Word;
use crate::block::{self, Parsed};
use crate::plan::angle::{angle_of, end_at_r, end_at_z, intersection};
use crate::plan::corner::{corner, Corner};
use crate::plan::curve::Curve;
use crate::plan::reader::Reader;
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

fn parse_at(r: &Reader, words: &[Word], tag: u32) -> Result<Parsed, NcError> {
    block::parse(words, r.machine).map_err(|e| e.at(tag))
}

/// E2021, checked before anything else about the ns block of G71/G72
/// (dialect.md §4.8): its motion code, its own or the one in force, must be
/// G00/G01, and it must name the infeed axis. Returns the cycle type.
pub fn ns_kind(r: &Reader, blocks: &[(Vec<Word>, u32)], facing: bool) -> Result<Kind, NcError> {
    let (words, tag) = first(blocks)?;
    let p = parse_at(r, words, *tag)?;
    let code = p.motion().unwrap_or(r.motion);
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
pub fn check_codes(r: &Reader, p: &Parsed, tag: u32) -> Result<(), NcError> {
    if r.machine.axes.c.enabled && (p.has(b'C') || p.has(b'H')) {
        let msg = "C/H may not stand in a G70–G73 profile: the cycles move X and Z only";
        let e = NcError::new(Alarm::IncompatibleWords, msg);
        return Err(e.on_pair(addr(b'C'), addr(b'H')).at(tag));
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
/// ordinary blocks (cycles.md §13 "the same rules apply inside profiles");
/// so does the two-block angle form (`Q_` then `X_ Z_ Q_`, dialect.md §5.2).
pub fn build(r: &Reader, blocks: &[(Vec<Word>, u32)]) -> Result<Vec<Seg>, NcError> {
    first(blocks)?;
    let mut b = Builder {
        r,
        pos: r.at,
        code: r.motion,
        chain: Chain {
            segs: Vec::with_capacity(blocks.len()),
            waiting: None,
        },
        pair: None,
    };
    for (i, (words, tag)) in blocks.iter().enumerate() {
        let p = parse_at(r, words, *tag)?;
        check_codes(r, &p, *tag)?;
        b.block(i == 0, &p, *tag).map_err(|e| e.or_at(*tag))?;
    }
    if let Some(first) = b.pair {
        let msg = "angle programming: the block after a Q_ block must be X_ Z_ Q_";
        return Err(NcError::new(Alarm::BadAngle, msg).at(first.tag));
    }
    // A corner word on the nf block is ignored (W112).
    Ok(b.chain.segs)
}

/// The profile read so far: where it stands, the motion code in force,
/// its elements and an angle pair's first block waiting for its second.
struct Builder<'a> {
    r: &'a Reader<'a>,
    pos: Pt,
    code: Motion,
    chain: Chain,
    pair: Option<AnglePair>,
}

impl Builder<'_> {
    /// Reads one block (`ns`: the first).
    fn block(&mut self, ns: bool, p: &Parsed, tag: u32) -> Result<(), NcError> {
        if let Some(c) = p.motion() {
            self.code = c;
        }
        let corner = self.r.corner_word(self.code, p)?;
        if let Some(first) = self.pair.take() {
            return self.after_angle(first, p, corner, tag);
        }
        if let Some(angle) = angle_alone(self.code, p) {
            self.pair = Some(AnglePair {
                from: self.pos,
                angle,
                code: self.code,
                corner,
                ns,
                tag,
                between: 0,
            });
            return Ok(());
        }
        let Some(curve) = element(self.r, self.code, p, self.pos)? else {
            return Ok(());
        };
        self.pos = curve.end();
        let seg = Seg {
            curve,
            rapid: self.code == Motion::Rapid,
            ns,
            tag,
        };
        self.chain.add(seg, corner)
    }

    /// A block after an angle pair's first: one that moves nothing (G04,
    /// M, S, T) may stand between, as outside a profile; else it is the
    /// second, and both lines join the profile.
    fn after_angle(
        &mut self,
        mut first: AnglePair,
        p: &Parsed,
        corner: Option<Corner>,
        tag: u32,
    ) -> Result<(), NcError> {
        if !p.has_axis() && angle_of(p).is_none() {
            first.between += 1;
            if first.between > 1 {
                return fail(
                    Alarm::BadAngle,
                    "angle programming: at most one block may stand between its two blocks",
                );
            }
            self.pair = Some(first);
            return Ok(());
        }
        let (meet, end) = first.second(self.r, self.code, p, &mut self.chain)?;
        self.pos = end;
        let seg = Seg::line(meet, end, self.code, false, tag);
        self.chain.add(seg, corner)
    }
}

/// The profile's elements so far, and the element waiting for its corner
/// (its index and the corner).
struct Chain {
    segs: Vec<Seg>,
    waiting: Option<(usize, Corner)>,
}

impl Chain {
    /// Adds `seg`, joined to the waiting element by its corner; `corner`
    /// (the block's own corner word) waits for the next.
    fn add(&mut self, seg: Seg, corner: Option<Corner>) -> Result<(), NcError> {
        match self.waiting.take() {
            // A G00 takes no corner (W112): the waiting one is dropped.
            Some((at, c)) if !seg.rapid => join(&mut self.segs, at, seg, c)?,
            _ => self.segs.push(seg),
        }
        self.waiting = corner.map(|c| (self.segs.len() - 1, c));
        Ok(())
    }
}

impl Seg {
    fn line(from: Pt, to: Pt, code: Motion, ns: bool, tag: u32) -> Seg {
        Seg {
            curve: Curve::new(Element::Line { from, to }),
            rapid: code == Motion::Rapid,
            ns,
            tag,
        }
    }
}

/// The angle of a G00/G01 block that names it and no end point: the
/// first block of the two-block form.
fn angle_alone(code: Motion, p: &Parsed) -> Option<f64> {
    let ends = [b'X', b'U', b'Z', b'W'].iter().any(|&l| p.has(l));
    angle_of(p).filter(|_| code.is_straight() && !ends)
}

/// The first block of an angle pair, waiting for its second.
struct AnglePair {
    from: Pt,
    angle: f64,
    code: Motion,
    corner: Option<Corner>,
    ns: bool,
    tag: u32,
    /// Blocks that moved nothing since.
    between: u32,
}

impl AnglePair {
    /// The second block (`p`, G00/G01 with absolute X, Z and its angle):
    /// adds the first block's line, to where the two lines meet; that
    /// point and the second block's end.
    fn second(
        self,
        r: &Reader,
        code: Motion,
        p: &Parsed,
        chain: &mut Chain,
    ) -> Result<(Pt, Pt), NcError> {
        if !code.is_straight() {
            return fail(
                Alarm::BadAngle,
                "the second block of angle programming must be a G01 (or G00) X_ Z_ Q_ block",
            );
        }
        let (Some(q2), true, true) = (angle_of(p), p.has(b'X'), p.has(b'Z')) else {
            return fail(
                Alarm::BadAngle,
                "the second block of angle programming needs absolute X, Z and an angle Q (or ,A)",
            );
        };
        let end = r.target_from(p, self.from);
        let meet = intersection(self.from, self.angle, end, q2)?;
        let seg = Seg::line(self.from, meet, self.code, self.ns, self.tag);
        chain.add(seg, self.corner)?;
        Ok((meet, end))
    }
}

/// Puts `next` after the element at `at`, joined by corner `c`.
fn join(segs: &mut Vec<Seg>, at: usize, next: Seg, c: Corner) -> Result<(), NcError> {
    let Some(prev) = segs.get_mut(at) else {
        segs.push(next);
        return Ok(());
    };
    let (Some(e1), Some(e2)) = (prev.curve.element(), next.curve.element()) else {
        // A conic is not G01–G03: the word is ignored (dialect.md §5.1;
        // W112 from the compiler), as outside a profile.
        segs.push(next);
        return Ok(());
    };
    // (An error is about the corner word of the earlier block.)
    match corner(&e1, &e2, c).map_err(|e| e.at(prev.tag))? {
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
fn element(r: &Reader, code: Motion, p: &Parsed, from: Pt) -> Result<Option<Curve>, NcError> {
    let to = r.target_from(p, from);
    match code {
        Motion::Rapid | Motion::Line => {
            let Some(deg) = angle_of(p) else {
                let line = Element::Line { from, to };
                return Ok(p.has_axis().then_some(Curve::new(line)));
            };
            // The one-block angle forms (dialect.md §5.2), the same
            // geometry as outside a profile.
            let x = p.has(b'X') || p.has(b'U');
            let z = p.has(b'Z') || p.has(b'W');
            let end = match (x, z) {
                (true, false) => end_at_r(from, deg, to.r)?,
                (false, true) => end_at_z(from, deg, to.z)?,
                // X, Z and Q: an ordinary line, Q ignored (W104).
                (true, true) => to,
                // The first block of the two-block form: `build` reads
                // the pair (AnglePair).
                (false, false) => return Ok(None),
            };
            Ok(Some(Curve::new(Element::Line { from, to: end })))
        }
        Motion::ArcCw | Motion::ArcCcw => {
            Ok(r.arc_element(from, code == Motion::ArcCw, to, p)?.map(Curve::new))
        }
        Motion::ThreePoint | Motion::ThreePointAbs => {
            let arc = r.three_point(code == Motion::ThreePointAbs, p, from, to)?;
            Ok(Some(Curve::new(arc)))
        }
        // Seed 000, G6.2 note 8 and G7.2 note 7: conics may shape a profile.
        c if c.is_conic() && p.has_axis() => {
            let ellipse = c.is_ellipse();
            let cw = c.is_cw_conic();
            r.conic_curve(ellipse, cw, p, from, to)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::machine::Machine;
    use crate::base::words::{addr, LITERAL, NO_POINT};

    /// A block of literal words with decimal points (no increment rule),
    /// but Q and M, written without.
    fn block(ws: &[(u8, f64)], tag: u32) -> (Vec<Word>, u32) {
        let words = ws
            .iter()
            .map(|&(l, value)| Word {
                addr: addr(l),
                value,
                flags: if b"QM".contains(&l) {
                    LITERAL | NO_POINT
                } else {
                    LITERAL
                },
            })
            .collect();
        (words, tag)
    }

    fn ends(segs: &[Seg]) -> Vec<(f64, f64)> {
        segs.iter()
            .map(|s| (s.curve.end().x(), s.curve.end().z))
            .collect()
    }

    /// The profile is read from the reader alone: no kernel runs.
    #[test]
    fn a_profile_reads_from_the_start_point_and_the_motion_in_force() {
        let machine = Machine::reference();
        let r = Reader {
            machine: &machine,
            inch: false,
            at: Pt::xz(130.0, 2.0),
            motion: Motion::Line,
        };
        let blocks = [
            block(&[(b'G', 0.0), (b'X', 20.0)], 10),
            block(&[(b'G', 1.0), (b'Z', -10.0)], 11),
            block(&[(b'U', 20.0), (b'W', -5.0)], 12),
        ];
        let segs = build(&r, &blocks).unwrap();
        // Ends worked out by hand: X20 Z2 (the ns rapid), then Z-10, then
        // U20 W-5 from there: X40 Z-15.
        assert_eq!(ends(&segs), [(20.0, 2.0), (20.0, -10.0), (40.0, -15.0)]);
        assert_eq!(segs[0].curve.start(), Pt::xz(130.0, 2.0));
        let flags: Vec<_> = segs.iter().map(|s| (s.rapid, s.ns, s.tag)).collect();
        assert_eq!(
            flags,
            [(true, true, 10), (false, false, 11), (false, false, 12)]
        );
        assert_eq!(ns_kind(&r, &blocks, false).unwrap(), Kind::Plain);
    }

    #[test]
    fn the_reader_gives_the_units_and_the_modal_motion() {
        let machine = Machine::reference();
        let r = Reader {
            machine: &machine,
            inch: true,
            at: Pt::xz(50.8, 0.0),
            motion: Motion::Line,
        };
        // No G code: G01 in force; inches: X1 is 25.4 mm (diameter), Z-1
        // is -25.4 mm. X and Z in the ns block: the pocket type.
        let blocks = [block(&[(b'X', 1.0), (b'Z', -1.0)], 7)];
        let segs = build(&r, &blocks).unwrap();
        assert_eq!(ends(&segs), [(25.4, -25.4)]);
        assert!(!segs[0].rapid);
        assert_eq!(ns_kind(&r, &blocks, false).unwrap(), Kind::Pockets);
        // G02 in force at the ns block of G71: E2021, tagged with it.
        let arc = Reader {
            motion: Motion::ArcCw,
            ..r
        };
        let e = ns_kind(&arc, &blocks, false).unwrap_err();
        assert_eq!((e.code, e.at), (Alarm::BadProfileStart.code(), Some(7)));
        assert!(build(&r, &[]).is_err());
    }

    /// The profile of `blocks` from X60 Z2 in G01 on the reference machine.
    fn from_x60(blocks: &[(Vec<Word>, u32)]) -> Result<Vec<Seg>, NcError> {
        let machine = Machine::reference();
        let r = Reader {
            machine: &machine,
            inch: false,
            at: Pt::xz(60.0, 2.0),
            motion: Motion::Line,
        };
        build(&r, blocks)
    }

    fn angle_profile(second: &[(u8, f64)], between: usize) -> Result<Vec<Seg>, NcError> {
        let mut blocks = alloc::vec![
            block(&[(b'G', 0.0), (b'X', 20.0)], 10),
            block(&[(b'G', 1.0), (b'Z', 0.0)], 11),
            block(&[(b'Q', 135_000.0)], 12),
        ];
        for k in 0..between {
            blocks.push(block(&[(b'M', 8.0)], 20 + k as u32));
        }
        blocks.push(block(second, 13));
        blocks.push(block(&[(b'X', 60.0)], 14));
        from_x60(&blocks)
    }

    #[test]
    fn the_two_block_angle_form_meets_at_the_corner() {
        // From X20 Z0 (radius 10) at 135°: r = 10 + t/√2, Z = −t/√2; the
        // line through X40 Z−30 at 180° is r = 20: they meet at t/√2 = 10,
        // X40 Z−10. One block (M08) may stand between the two.
        for between in [0, 1] {
            let segs =
                angle_profile(&[(b'X', 40.0), (b'Z', -30.0), (b'Q', 180_000.0)], between).unwrap();
            let got: Vec<_> = ends(&segs)
                .iter()
                .map(|&(x, z)| ((x * 1e9).round() / 1e9, (z * 1e9).round() / 1e9))
                .collect();
            assert_eq!(
                got,
                [
                    (20.0, 2.0),
                    (20.0, 0.0),
                    (40.0, -10.0),
                    (40.0, -30.0),
                    (60.0, -30.0)
                ]
            );
            let tags: Vec<_> = segs.iter().map(|s| s.tag).collect();
            assert_eq!(tags, [10, 11, 12, 13, 14]);
        }
    }

    #[test]
    fn an_angle_pair_without_its_second_block_is_e4008() {
        let e4008 = Alarm::BadAngle.code();
        // U instead of X; an arc; two blocks between; no second block.
        let u = angle_profile(&[(b'U', 20.0), (b'Z', -30.0), (b'Q', 180_000.0)], 0);
        assert_eq!(
            u.map_err(|e| (e.code, e.at)).unwrap_err(),
            (e4008, Some(13))
        );
        let arc = angle_profile(&[(b'G', 2.0), (b'X', 40.0), (b'Z', -30.0), (b'R', 5.0)], 0);
        assert_eq!(
            arc.map_err(|e| (e.code, e.at)).unwrap_err(),
            (e4008, Some(13))
        );
        let two = angle_profile(&[(b'X', 40.0), (b'Z', -30.0), (b'Q', 180_000.0)], 2);
        assert_eq!(
            two.map_err(|e| (e.code, e.at)).unwrap_err(),
            (e4008, Some(21))
        );
        let blocks = [
            block(&[(b'G', 0.0), (b'X', 20.0)], 10),
            block(&[(b'G', 1.0), (b'Q', 135_000.0)], 11),
        ];
        let e = from_x60(&blocks).unwrap_err();
        assert_eq!((e.code, e.at), (e4008, Some(11)));
    }
}
