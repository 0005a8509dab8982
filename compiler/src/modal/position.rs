//! The position the tool stands at, as pass `modal` follows it: the
//! kernel's programmed point (work coordinates, X as a radius,
//! `nc::point::Pt`), an axis at a time.
//!
//! The end point of a move is read by the kernel's own reader
//! (`nc::plan::reader::Reader`, the code the executor reads blocks with),
//! from words the kernel's block parse took, so a known coordinate is the
//! very `f64` the kernel will hold. The pass knows the position only
//! through blocks whose effect on it is plain:
//! - a plain move (pass `resolve`: X/Z/U/W, F, N and an arc's R or I/K,
//!   at most a G00–G03) with the motion, drilling, compensation, plane,
//!   polar and unit groups known and none of them in a mode that bends
//!   the path (G41/G42, G12.1, G7.1, a drilling cycle, another plane);
//! - G50, whose axis words make the point those coordinates (its S, the
//!   spindle clamp, moves nothing);
//! - a block that does not move: no axis word, and only G04 (whose X
//!   is a time), G00–G03 set for later, the feed and speed modes and the
//!   path modes;
//! - an assignment to a plain variable (#1–#999).
//!
//! A program starts with the position unknown: it runs from wherever the
//! tool stands (`gbvm` starts at the machine's power-on point, a
//! controller wherever the last program ended).
//!
//! Anything else — a cycle, a return to the reference point, a change of
//! work system or local origin, an assignment to a system variable (a
//! work or tool offset moves the zero), a computed axis word — makes the
//! axes it may change unknown.

use super::{Fact, State};
use crate::ir::{Function, NcBlock, NcKind, WordValue};
use nc::gcode::{
    self, Code, Comp, Drill, FeedMode, Motion, OneShot, PathMode, Plane, Polar, PolarCmd,
    SpeedMode, Stroke, Units, G,
};
use nc::plan::reader::Reader;
use nc::point::Pt;
use nc::words::{addr, Word};
use nc::Machine;
use smallvec::SmallVec;

/// The position: the bits of the radius and of Z.
pub type Position = [Fact<u64>; 2];

fn known(p: Pt) -> Position {
    [p.r, p.z].map(|v| match v.is_nan() {
        true => Fact::Unknown,
        false => Fact::Is(v.to_bits()),
    })
}

/// The known coordinates of `pos` as a point, NaN where unknown.
fn point(pos: &Position) -> Pt {
    let [r, z] = pos.map(|f| match f {
        Fact::Is(bits) => f64::from_bits(bits),
        Fact::Entry | Fact::Unknown => f64::NAN,
    });
    Pt::new(r, z)
}

/// Codes that, in a block without axis words, move nothing: they set a
/// mode for later blocks (G00–G03 too).
const STILL: [Code; 18] = [
    Motion::Rapid.code(),
    Motion::Line.code(),
    Motion::ArcCw.code(),
    Motion::ArcCcw.code(),
    PolarCmd::Off.code(),
    Plane::Zx.code(),
    Units::Inch.code(),
    Units::Metric.code(),
    Stroke::On.code(),
    Stroke::Off.code(),
    Comp::Off.code(),
    PathMode::ExactStop.code(),
    PathMode::Continuous.code(),
    Drill::Off.code(),
    SpeedMode::SurfaceSpeed.code(),
    SpeedMode::Rpm.code(),
    FeedMode::PerMinute.code(),
    FeedMode::PerRev.code(),
];

/// The position after an NC block the kernel runs as commands (`codes`
/// its G codes), from the state `before` it.
pub(super) fn after_block(
    f: &Function,
    nc: &NcBlock,
    codes: &[Code],
    before: &State,
    m: &Machine,
) -> Position {
    let words = f.words_of(nc);
    let axis = |w: &crate::ir::Word| b"XZUWCH".iter().any(|&l| w.addr == addr(l));
    if codes.contains(&OneShot::Dwell.code()) && codes.len() == 1 {
        return before.pos;
    }
    if !words.iter().any(axis) && codes.iter().all(|c| STILL.contains(c)) {
        return before.pos;
    }
    let g50 = codes == [OneShot::SetCoordinates.code()];
    let plain = matches!(nc.kind, NcKind::Move(_)) && motion_plain(codes, before);
    if !(plain
        || g50
            && words
                .iter()
                .all(|w| b"GXZUWNS".iter().any(|&l| w.addr == addr(l))))
    {
        return [Fact::Unknown; 2];
    }
    let Some(inch) = units(before) else {
        return [Fact::Unknown; 2];
    };
    read_end(words, before, inch, m)
}

/// The end point of a plain move or a G50 from its constant words, the
/// kernel's way; an axis with a computed word is unknown, and an axis
/// without a word keeps what it was (in a summary, the caller's).
fn read_end(words: &[crate::ir::Word], before: &State, inch: bool, m: &Machine) -> Position {
    let mut written = [Written::No; 2];
    for w in words {
        let axis = match w.addr {
            a if a == addr(b'X') || a == addr(b'U') => 0,
            a if a == addr(b'Z') || a == addr(b'W') => 1,
            _ => continue,
        };
        let how = match w.constant() {
            Some(_) => Written::Constant,
            None => Written::Computed,
        };
        written[axis] = written[axis].max(how);
    }
    let lits = constant_words(words);
    let mut p = nc::block::Parsed::default();
    if nc::block::parse_move(&lits, m, &mut p).is_err() {
        // (The kernel's alarm: nothing runs after the block.)
        return [Fact::Unknown; 2];
    }
    let from = point(&before.pos);
    let reader = Reader {
        machine: m,
        inch,
        at: from,
        motion: p.motion().unwrap_or(Motion::Line),
    };
    let to = known(reader.target_from(&p, from));
    [0, 1].map(|i| match written[i] {
        Written::No => before.pos[i],
        Written::Constant => to[i],
        Written::Computed => Fact::Unknown,
    })
}

/// The kernel's alarm for a plain arc (G02/G03 with constant words) that
/// cannot be drawn from where the tool stands, when that point and the
/// modes are known before the block (`s`): the alarm it raises whenever
/// it is reached.
pub fn arc_fault(f: &Function, nc: &NcBlock, s: &State, m: &Machine) -> Option<nc::NcError> {
    let NcKind::Move(written) = nc.kind else {
        return None;
    };
    let motion = written.or_else(|| match G::from_code(s.code(gcode::MOTION)?) {
        Some(G::Motion(c)) => Some(c),
        _ => None,
    })?;
    let codes: SmallVec<[Code; 1]> = written.map(Motion::code).into_iter().collect();
    if !motion.is_arc() || !motion_plain(&codes, s) || s.data != Fact::Is(false) {
        return None;
    }
    let [Fact::Is(r), Fact::Is(z)] = s.pos else {
        return None;
    };
    let words = f.words_of(nc);
    if words.iter().any(|w| w.constant().is_none()) {
        return None;
    }
    let lits = constant_words(words);
    let mut p = nc::block::Parsed::default();
    // (A fault of the words themselves is a compile error already.)
    nc::block::parse_move(&lits, m, &mut p).ok()?;
    let from = Pt::new(f64::from_bits(r), f64::from_bits(z));
    let reader = Reader {
        machine: m,
        inch: units(s)?,
        at: from,
        motion,
    };
    let to = reader.target_from(&p, from);
    reader
        .arc_element(from, motion == Motion::ArcCw, to, &p)
        .err()
}

/// The constant words of a block, as the kernel takes them.
fn constant_words(words: &[crate::ir::Word]) -> SmallVec<[Word; 8]> {
    words
        .iter()
        .filter_map(|w| match w.value() {
            WordValue::Const(value, flags) => Some(Word {
                addr: w.addr,
                value,
                flags,
            }),
            WordValue::Expr(_) => None,
        })
        .collect()
}

/// How a block writes an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Written {
    No,
    Constant,
    /// (A vacant value leaves the word out, so the axis may keep its
    /// coordinate or not.)
    Computed,
}

/// Whether a plain move's path is the straight line or arc it names: its
/// motion is G00–G03 and no mode bends or moves it.
fn motion_plain(codes: &[Code], s: &State) -> bool {
    let is = |group, code: Code| s.code(group) == Some(code);
    let motion = codes.first().copied().or(s.code(gcode::MOTION));
    let straight_or_arc = motion.is_some_and(|c| {
        matches!(
            G::from_code(c),
            Some(G::Motion(
                Motion::Rapid | Motion::Line | Motion::ArcCw | Motion::ArcCcw
            ))
        )
    });
    straight_or_arc
        && (!codes.is_empty() || is(gcode::DRILL, Drill::Off.code()))
        && is(gcode::COMP, Comp::Off.code())
        && is(gcode::PLANE, Plane::Zx.code())
        && is(gcode::POLAR, Polar::Off.code())
        && is(gcode::POLAR_CMD, PolarCmd::Off.code())
}

/// G20 in force, when the units are known.
fn units(s: &State) -> Option<bool> {
    match s.code(gcode::UNITS)? {
        c if c == Units::Inch.code() => Some(true),
        c if c == Units::Metric.code() => Some(false),
        _ => None,
    }
}
