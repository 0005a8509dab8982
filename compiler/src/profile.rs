//! G70–G73 profiles at compile time (dialect.md §4.8, §8.2 E2020–E2022;
//! cycles.md §5): finding the ns…nf blocks of a cycle block, the checks
//! that need no run, handing the blocks to the cycle in the bytecode and
//! making the program go on after nf.
//!
//! The profile blocks stay where they are written (a GOTO may reach them)
//! and are also built, as `Profile` NC operations the VM hands to the
//! kernel, just before the cycle block; they carry their own source
//! lines, so a run-time error names them. After a G71/G72/G73 block a jump
//! skips to the block after nf; after G70 the program simply goes on.

use crate::build::Builder as Gen;
use crate::ir::{self, Handle};
use crate::link::{self, Program, Unit};
use crate::words::{self, Call, NcWord, WordValue};
use grammar::ast::{Block, Body};
use grammar::Span;
use nc::block::round_half_away;
use nc::gcode::{self, Drill, OneShot, G};
use nc::words::{addr, COMMA_A, COMMA_C, COMMA_R, LITERAL, NO_POINT};
use nc::Nc;
use smallvec::SmallVec;
use std::collections::{HashMap, HashSet};

/// `Exec` flag of a profile block (the VM's `vm::PROFILE`).
pub const PROFILE: u8 = 1;

/// At most this many blocks from ns to nf (E2020).
const MAX_BLOCKS: usize = 100;

/// Build state: where the blocks after numbered ones start and which
/// jumps wait for a target.
#[derive(Debug, Default)]
pub struct Profiles {
    /// The block being built: (unit, line).
    current: Option<(usize, usize)>,
    /// The lines a jump past nf may go to, in line order: in a program
    /// that names a cycle, every block after a numbered one (the IR starts
    /// a basic block there).
    targets: Vec<usize>,
    /// The IR block at which each of those lines starts, as (line, block)
    /// in line order: a cycle's jump past nf stays in its own program, and
    /// a vector is filled far faster than a map.
    starts: Vec<(usize, Handle<ir::Block>)>,
    /// Jumps after a cycle block, with the line of the block after nf
    /// (`None`: nf is the program's last block).
    pending: Vec<(Handle<ir::Block>, Option<usize>)>,
    /// Blocks of the program being lowered that name G70–G73 (skipped
    /// ones too): with fewer than two, no profile number can be shared.
    cycle_blocks: usize,
    /// The sequence numbers of the program being lowered, where it names
    /// a cycle (`program_start`).
    numbers: Numbers,
    /// Ignored corner words of profiles already told (W112), as (unit, line):
    /// a profile that G71 and G70 both read is told once.
    corners_told: HashSet<(usize, usize)>,
}

/// What follows a cycle block's `Exec`.
pub struct After {
    /// The line of the block after nf; `None` when nf ends the program.
    resume: Option<usize>,
}

/// A G70–G73 block's code and its P, Q words (`None`: absent; `Some(None)`:
/// computed).
struct CycleWords {
    code: OneShot,
    p: Option<Option<f64>>,
    q: Option<Option<f64>>,
}

fn letter(w: &NcWord<'_>, l: u8) -> bool {
    w.addr == addr(l)
}

/// A literal G word's code as the kernel types it (`None` for a computed
/// word or a code not of the dialect).
fn literal_g(w: &NcWord<'_>) -> Option<G> {
    match w.value {
        WordValue::Literal(v, _) if letter(w, b'G') => G::from_code(words::round_g(v)),
        _ => None,
    }
}

/// G70–G73: the cycles that take a profile.
fn profile_cycle(g: Option<G>) -> Option<OneShot> {
    match g? {
        G::OneShot(
            c @ (OneShot::Finish | OneShot::RoughTurn | OneShot::RoughFace | OneShot::Pattern),
        ) => Some(c),
        _ => None,
    }
}

/// Whether any word of a block is a literal G70–G73. Without one, the
/// block's NC words hold none either (they are a subset), so most blocks
/// need not be sorted to tell that they are no cycle block.
pub(crate) fn names_cycle(ws: &[grammar::ast::Word]) -> bool {
    ws.iter().any(|w| {
        let g = w.addr == grammar::ast::Addr::Letter('G');
        let code = words::value_of(w).literal();
        g && profile_cycle(code.and_then(|v| G::from_code(words::round_g(v)))).is_some()
    })
}

fn cycle_words(ws: &[NcWord<'_>]) -> Option<CycleWords> {
    let code = ws.iter().find_map(|w| profile_cycle(literal_g(w)))?;
    let value = |l: u8| ws.iter().find(|w| letter(w, l)).map(|w| w.value.literal());
    Some(CycleWords {
        code,
        p: value(b'P'),
        q: value(b'Q'),
    })
}

/// Every block-skip switch on: every `/n` block skipped.
pub(crate) const ALL_ON: [bool; 9] = [true; 9];

/// Whether the block-delete switch of a block is on (the block is skipped).
fn skipped(skip: &[bool; 9], block: &Block) -> bool {
    block.delete.is_some_and(|d| {
        skip.get(d.switch.saturating_sub(1) as usize)
            .copied()
            .unwrap_or(false)
    })
}

fn seq_of(unit: &Unit, line: usize) -> Option<u32> {
    link::block(unit, line)
        .and_then(|b| b.seq)
        .map(|s| s.number)
}

/// A program's blocks by sequence number: where each number stands, as
/// indices into `prog.blocks` in order. Built once a program that names a
/// cycle: a scan of the blocks for each cycle's P and Q made a program of
/// many cycles quadratic.
#[derive(Debug, Default)]
pub struct Numbers(HashMap<u32, SmallVec<[usize; 2]>>);

impl Numbers {
    pub fn of(unit: &Unit, prog: &Program) -> Numbers {
        let mut places: HashMap<u32, SmallVec<[usize; 2]>> = HashMap::new();
        for (i, &l) in prog.blocks.iter().enumerate() {
            if let Some(n) = seq_of(unit, l) {
                places.entry(n).or_default().push(i);
            }
        }
        Numbers(places)
    }

    /// Where `n` stands, first to last.
    fn places(&self, n: u32) -> &[usize] {
        self.0.get(&n).map_or(&[], |p| p.as_slice())
    }

    /// The first block numbered `n`, and whether another block carries
    /// the same number (W103).
    pub(crate) fn first(&self, n: u32) -> (Option<usize>, bool) {
        let places = self.places(n);
        (places.first().copied(), places.len() > 1)
    }
}

/// ns…nf as indices into `prog.blocks`, or the E2020 message.
fn resolve(numbers: &Numbers, ns: u32, nf: u32) -> Result<(usize, usize), String> {
    let (Some(i), _) = numbers.first(ns) else {
        return Err(format!("P{ns}: there is no block N{ns} in this program"));
    };
    let (Some(j), _) = numbers.first(nf) else {
        return Err(format!("Q{nf}: there is no block N{nf} in this program"));
    };
    if j < i {
        return Err(format!(
            "Q{nf}: the block N{nf} (nf) stands before N{ns} (ns)"
        ));
    }
    if j - i + 1 > MAX_BLOCKS {
        return Err(format!(
            "the profile N{ns}…N{nf} has {} blocks; at most {MAX_BLOCKS} are allowed",
            j - i + 1
        ));
    }
    Ok((i, j))
}

/// A sequence number as P/Q give it, or the E2020 message.
fn sequence(v: Option<Option<f64>>, l: char) -> Result<u32, String> {
    match v {
        Some(Some(n)) if (0.0..=99999.0).contains(&round_half_away(n)) => {
            Ok(round_half_away(n) as u32)
        }
        Some(Some(n)) => Err(format!("{l}{n} is not a sequence number")),
        Some(None) => Err(format!("{l} of G70–G73 must be a literal sequence number")),
        None => Err(format!(
            "{l} is missing: a G70–G73 cycle block needs P (ns) and Q (nf)"
        )),
    }
}

/// At the start of a program: the lines a jump past nf may go to.
pub fn program_start(gen: &mut Gen<'_>, prog: &Program) {
    let units: &[Unit] = gen.units;
    let unit = &units[prog.unit];
    let names = |&l: &usize| match link::block(unit, l).map(|b| &b.body) {
        Some(Body::Words(ws)) => names_cycle(ws),
        _ => false,
    };
    gen.profiles.targets.clear();
    gen.profiles.numbers = Numbers::default();
    if !prog.blocks.iter().any(names) {
        return;
    }
    gen.profiles.numbers = Numbers::of(unit, prog);
    let after_numbered = prog
        .blocks
        .windows(2)
        .filter(|w| seq_of(unit, w[0]).is_some())
        .map(|w| w[1]);
    gen.profiles.targets.extend(after_numbered);
}

/// At the start of every block of a program (before block delete).
pub fn block_start(gen: &mut Gen<'_>, line: usize) {
    let key = (gen.unit, line);
    gen.profiles.current = Some(key);
    if gen.profiles.targets.binary_search(&line).is_err() {
        return;
    }
    let here = gen.here();
    gen.profiles.starts.push((line, here));
    if gen.profiles.pending.is_empty() {
        return;
    }
    let pending = std::mem::take(&mut gen.profiles.pending);
    let (due, wait): (Vec<_>, Vec<_>) = pending.into_iter().partition(|&(_, t)| t == Some(line));
    gen.profiles.pending = wait;
    for (at, _) in due {
        gen.patch_jump(at, here);
    }
}

/// At the end of a program, before its final `Halt`/`Ret`: jumps past a
/// last nf land there; E2022 for the whole program.
pub fn program_end(gen: &mut Gen<'_>, prog: &Program) {
    let pending = std::mem::take(&mut gen.profiles.pending);
    if !pending.is_empty() {
        let here = gen.here();
        for (at, _) in pending {
            gen.patch_jump(at, here);
        }
    }
    gen.profiles.starts.clear();
    // (The check reads the whole program again: only where it can find
    // something.)
    if std::mem::take(&mut gen.profiles.cycle_blocks) >= 2 {
        shared_numbers(gen, prog);
    }
}

/// Counts the blocks that name a compound cycle, for `program_end`.
pub fn count_cycle(gen: &mut Gen<'_>, block: &Block) {
    if let Body::Words(ws) = &block.body {
        gen.profiles.cycle_blocks += usize::from(names_cycle(ws));
    }
}

/// The program being lowered and its unit.
fn current<'a>(gen: &Gen<'a>) -> Option<(&'a Unit, &'a Program, usize)> {
    let (unit, line) = gen.profiles.current?;
    let units: &'a [Unit] = gen.units;
    let programs: &'a [Program] = gen.programs;
    // (A program's lines ascend: `link::split` takes them in order.)
    let prog = programs
        .iter()
        .find(|p| p.unit == unit && p.blocks.binary_search(&line).is_ok())?;
    Some((&units[unit], prog, line))
}

/// Before the words of an NC block: for a G70–G73 cycle block, the checks
/// and the profile blocks. `Some` for a cycle block whose program goes on
/// after nf (G71–G73).
pub fn before_exec(gen: &mut Gen<'_>, block: &Block, split: &words::Split<'_>) -> Option<After> {
    let cw = cycle_words(&split.nc)?;
    integer_flags(gen, &cw, &split.nc, block.span);
    if cw.p.is_none() && cw.q.is_none() {
        if cw.code == OneShot::Finish {
            gen.error("E2006", block.span, "G70 needs P (ns) and Q (nf)");
        }
        return None;
    }
    let (unit, prog, _) = current(gen)?;
    let (ns, nf) = match sequence(cw.p, 'P').and_then(|ns| Ok((ns, sequence(cw.q, 'Q')?))) {
        Ok(v) => v,
        Err(msg) => {
            gen.error("E2020", block.span, msg);
            return None;
        }
    };
    let numbers = &gen.profiles.numbers;
    let repeated = [ns, nf].map(|n| (n, numbers.first(n).1));
    let (i, j) = match resolve(numbers, ns, nf) {
        Ok(r) => r,
        Err(msg) => {
            gen.error("E2020", block.span, msg);
            return None;
        }
    };
    for (n, repeated) in repeated {
        if repeated {
            gen.warn(
                "W103",
                block.span,
                format!("N{n} occurs more than once: the first block is used"),
            );
        }
    }
    // The profile as the switches leave it: every block (all off) and
    // none of the `/n` ones (all on); both must be sound.
    let lines: Vec<usize> = prog.blocks[i..=j]
        .iter()
        .copied()
        .filter(|&l| link::block(unit, l).is_some())
        .collect();
    let kept: Vec<usize> = lines
        .iter()
        .copied()
        .filter(|&l| link::block(unit, l).is_some_and(|b| !skipped(&ALL_ON, b)))
        .collect();
    if !check_blocks(gen, unit, cw.code, &lines, block.span)
        || (kept != lines && !check_blocks(gen, unit, cw.code, &kept, block.span))
    {
        return None;
    }
    if let Some(&ns) = lines.first() {
        ignored_j(gen, unit, &cw, &split.nc, ns);
    }
    ignored_corners(gen, unit, &lines);
    build_profile(gen, unit, &lines);
    gen.set_loc(block.span);
    (cw.code != OneShot::Finish).then(|| After {
        resume: prog.blocks.get(j + 1).copied(),
    })
}

/// After the cycle block: G71–G73 go on after nf.
pub fn after_exec(gen: &mut Gen<'_>, after: Option<After>) {
    let Some(after) = after else { return };
    let at = gen.jump_later();
    match after.resume.and_then(|l| block_at(&gen.profiles, l)) {
        Some(b) => gen.patch_jump(at, b),
        None => gen.profiles.pending.push((at, after.resume)),
    }
}

/// The IR block where `line`, a block of this program built already,
/// starts.
fn block_at(profiles: &Profiles, line: usize) -> Option<Handle<ir::Block>> {
    let starts = &profiles.starts;
    let i = starts.binary_search_by_key(&line, |&(l, _)| l).ok()?;
    Some(starts[i].1)
}

/// The profile blocks as `Profile` NC operations.
fn build_profile(gen: &mut Gen<'_>, unit: &Unit, lines: &[usize]) {
    for &l in lines {
        let Some(b) = link::block(unit, l) else {
            continue;
        };
        let Body::Words(ws) = &b.body else { continue };
        let Ok(split) = words::classify(ws) else {
            continue;
        };
        if split.nc.is_empty() {
            continue;
        }
        gen.set_loc(b.span);
        // A `/n` profile block is left out of the profile when its switch
        // is on as the cycle block is read.
        let guard = b.delete.map(|d| gen.skip_guard(d.switch));
        gen.reset();
        let start = gen.words_len();
        build_words(gen, &split.nc);
        gen.set_loc(b.span);
        gen.nc_op(start, ir::NcKind::Profile, None);
        if let Some(at) = guard {
            gen.end_guard(at);
        }
    }
    gen.reset();
}

/// A profile block's words, each with its own source. Computed words are
/// evaluated when the cycle runs, like the cycle block's own.
fn build_words(gen: &mut Gen<'_>, ws: &[NcWord<'_>]) {
    for w in ws {
        let value = match w.value {
            WordValue::Literal(v, flags) => ir::WordValue::Const(v, flags),
            WordValue::Expr(e) => ir::WordValue::Expr(gen.expr(e)),
        };
        gen.push_word(w.addr, value, w.span);
    }
}

/// W112 for a corner word of a profile that is ignored (dialect.md §5.1):
/// its next profile block that moves is a conic (a literal G6.2/G6.3/
/// G7.2/G7.3, not G01–G03, as outside a profile), or there is none (the
/// word stands on the last block that moves, the nf block as a rule).
fn ignored_corners(gen: &mut Gen<'_>, unit: &Unit, lines: &[usize]) {
    let Some((unit_index, _)) = gen.profiles.current else {
        return;
    };
    let is_corner = |w: &&NcWord<'_>| {
        letter(w, b'L') || letter(w, b'D') || w.addr == COMMA_C || w.addr == COMMA_R
    };
    let mut waiting: Option<(usize, Span)> = None;
    for &l in lines {
        let Some(Body::Words(ws)) = link::block(unit, l).map(|b| &b.body) else {
            continue;
        };
        let Ok(split) = words::classify(ws) else {
            continue;
        };
        if !split
            .nc
            .iter()
            .any(|w| b"XZUW".iter().any(|&a| letter(w, a)))
        {
            continue;
        }
        let conic = |w: &NcWord<'_>| matches!(literal_g(w), Some(G::Motion(m)) if m.is_conic());
        if let Some((at, span)) = waiting.take() {
            if split.nc.iter().any(conic) && gen.profiles.corners_told.insert((unit_index, at)) {
                let msg = "this chamfer or rounding is ignored: the next move of the profile is an ellipse or parabola, not G01–G03";
                gen.warn("W112", span, msg.to_string());
            }
        }
        waiting = split.nc.iter().find(is_corner).map(|w| (l, w.span));
    }
    if let Some((at, span)) = waiting {
        if gen.profiles.corners_told.insert((unit_index, at)) {
            let msg = "this chamfer or rounding is ignored: it stands on the last move of the profile (its nf block), which has no next element";
            gen.warn("W112", span, msg.to_string());
        }
    }
}

/// W104 for the J of G71/G72 where the cycle ignores it (cycles.md
/// §15.5): in type I (its ns block names one axis), and in type II any J
/// but J1.
fn ignored_j(gen: &mut Gen<'_>, unit: &Unit, cw: &CycleWords, ws: &[NcWord<'_>], ns: usize) {
    if !matches!(cw.code, OneShot::RoughTurn | OneShot::RoughFace) {
        return;
    }
    let Some(j) = ws.iter().find(|w| letter(w, b'J')) else {
        return;
    };
    let Some(Body::Words(ns_words)) = link::block(unit, ns).map(|b| &b.body) else {
        return;
    };
    let Ok(split) = words::classify(ns_words) else {
        return;
    };
    let names = |a, b| split.nc.iter().any(|w| letter(w, a) || letter(w, b));
    let why = match j.value {
        _ if !(names(b'X', b'U') && names(b'Z', b'W')) => {
            "the cycle is type I (its ns block names one axis), and only type II repeats its allowance pass (J1)"
        }
        WordValue::Literal(v, _) if v != 1.0 => "only J1 repeats the allowance pass of type II",
        _ => return,
    };
    gen.warn("W104", j.span, format!("J is ignored: {why}"));
}

/// E1009 for a decimal point on the integer-only J/K flags of G71/G72 and
/// the pass count R of a G73 first block (dialect.md §1.9).
fn integer_flags(gen: &mut Gen<'_>, cw: &CycleWords, ws: &[NcWord<'_>], span: Span) {
    let cycle = cw.p.is_some() || cw.q.is_some();
    let letters: &[u8] = match cw.code {
        OneShot::RoughTurn | OneShot::RoughFace if cycle => b"JK",
        OneShot::Pattern if !cycle => b"R",
        _ => b"",
    };
    for w in ws.iter().filter(|w| letters.iter().any(|&l| letter(w, l))) {
        if let WordValue::Literal(_, flags) = w.value {
            if flags & LITERAL != 0 && flags & NO_POINT == 0 {
                let l = (b'A' + w.addr) as char;
                gen.error(
                    "E1009",
                    span,
                    format!("{l} takes an integer here; a decimal point is not allowed"),
                );
            }
        }
    }
}

/// The static checks of the profile blocks; false after an error.
fn check_blocks(
    gen: &mut Gen<'_>,
    unit: &Unit,
    code: OneShot,
    lines: &[usize],
    span: Span,
) -> bool {
    let Some(&ns) = lines.first() else {
        gen.error(
            "E2020",
            span,
            "every block of the profile is skipped (block delete)",
        );
        return false;
    };
    if let Some((at, msg)) = ns_fault(unit, ns, code) {
        gen.error("E2021", at, msg);
        return false;
    }
    for (k, &l) in lines.iter().enumerate() {
        let Some(b) = link::block(unit, l) else {
            continue;
        };
        if let Some(msg) = block_fault(b, k + 1 == lines.len()) {
            gen.error("E2020", b.span, msg);
            return false;
        }
    }
    true
}

/// E2021 of the ns block of G71/G72 as far as its own words tell: a
/// group-01 code other than G00/G01, or no word of the infeed axis. The
/// modal code it inherits is checked by the kernel (at compile time in a
/// static program, by the dry run).
fn ns_fault(unit: &Unit, line: usize, code: OneShot) -> Option<(Span, String)> {
    if !matches!(code, OneShot::RoughTurn | OneShot::RoughFace) {
        return None;
    }
    let b = link::block(unit, line)?;
    let Body::Words(ws) = &b.body else {
        return None;
    };
    let split = words::classify(ws).ok()?;
    let name = code.name();
    let motion = split.nc.iter().rev().find_map(|w| match literal_g(w) {
        Some(G::Motion(m)) => Some(m),
        _ => None,
    });
    if let Some(m) = motion.filter(|m| !m.is_straight()) {
        let msg = format!(
            "the first profile block (ns) of {name} must move with G00 or G01, not {}",
            m.name()
        );
        return Some((b.span, msg));
    }
    let (axis, a, b2) = if code == OneShot::RoughTurn {
        ("X(U)", b'X', b'U')
    } else {
        ("Z(W)", b'Z', b'W')
    };
    if !split.nc.iter().any(|w| letter(w, a) || letter(w, b2)) {
        return Some((
            b.span,
            format!("the first profile block (ns) of {name} must name {axis}"),
        ));
    }
    None
}

/// E2020 for a profile block: a macro statement, a call, a group-00 code
/// or a drilling cycle; the first block of an angle pair as nf.
fn block_fault(b: &Block, last: bool) -> Option<String> {
    let Body::Words(ws) = &b.body else {
        return Some("a macro statement may not stand in a G70–G73 profile".into());
    };
    let split = words::classify(ws).ok()?;
    match split.call {
        None | Some(Call::ModalCancel) => {}
        Some(c) => {
            return Some(format!(
                "{} may not stand in a G70–G73 profile",
                c.kind_name()
            ))
        }
    }
    for g in split.nc.iter().filter_map(literal_g) {
        if matches!(g, G::OneShot(_)) || matches!(g, G::Drill(d) if d != Drill::Off) {
            return Some(format!(
                "{} may not stand in a G70–G73 profile",
                gcode::name(g.code())
            ));
        }
    }
    let axis = split
        .nc
        .iter()
        .any(|w| [b'X', b'U', b'Z', b'W'].iter().any(|&l| letter(w, l)));
    let angle = split
        .nc
        .iter()
        .any(|w| letter(w, b'Q') || w.addr == COMMA_A);
    if last && angle && !axis {
        return Some("the nf block may not be the first block of an angle-programming pair".into());
    }
    None
}

/// E2022: in a program with more than one G71/G72/G73 cycle block, a
/// sequence number of a profile block that stands on another block too,
/// reported at the later of the two.
fn shared_numbers(gen: &mut Gen<'_>, prog: &Program) {
    let units: &[Unit] = gen.units;
    let unit = &units[prog.unit];
    let numbers = Numbers::of(unit, prog);
    let cycles = cycle_ranges(unit, prog, &numbers);
    if cycles
        .iter()
        .filter(|(code, _)| *code != OneShot::Finish)
        .count()
        < 2
    {
        return;
    }
    let mut reported = HashSet::new();
    for (_, (i, j)) in cycles {
        for k in i..=j {
            let Some(n) = seq_of(unit, prog.blocks[k]) else {
                continue;
            };
            let twins = numbers.places(n).iter().filter(|&&m| m != k);
            for &m in twins {
                let later = k.max(m);
                let Some(b) =
                    link::block(unit, prog.blocks[later]).filter(|_| reported.insert(later))
                else {
                    continue;
                };
                gen.error(
                    "E2022",
                    b.span,
                    format!(
                        "N{n} stands in a compound-cycle profile and on another block: with several G71/G72/G73 cycles in a program, profile numbers may not repeat"
                    ),
                );
            }
        }
    }
}

/// Every cycle block of a program with its resolved ns…nf.
fn cycle_ranges(unit: &Unit, prog: &Program, numbers: &Numbers) -> Vec<(OneShot, (usize, usize))> {
    let mut out = Vec::new();
    for &l in &prog.blocks {
        let Some(b) = link::block(unit, l) else {
            continue;
        };
        let Body::Words(ws) = &b.body else { continue };
        if !names_cycle(ws) {
            continue;
        }
        let Ok(split) = words::classify(ws) else {
            continue;
        };
        let Some(cw) = cycle_words(&split.nc) else {
            continue;
        };
        let (Ok(ns), Ok(nf)) = (sequence(cw.p, 'P'), sequence(cw.q, 'Q')) else {
            continue;
        };
        if let Ok(r) = resolve(numbers, ns, nf) {
            out.push((cw.code, r));
        }
    }
    out
}

/// Dry run (check.rs): for a cycle block at `index` of `prog`, hands its
/// profile to the kernel, each block tagged with its line, and returns the
/// index of `prog.blocks` where the program goes on (G71–G73: after nf).
pub fn hand_over(
    nc: &mut Nc,
    (unit, prog, numbers): (&Unit, &Program, &Numbers),
    ws: &[NcWord<'_>],
    skip: &[bool; 9],
) -> Option<usize> {
    let cw = cycle_words(ws)?;
    let (ns, nf) = (sequence(cw.p, 'P').ok()?, sequence(cw.q, 'Q').ok()?);
    let (i, j) = resolve(numbers, ns, nf).ok()?;
    for &l in &prog.blocks[i..=j] {
        let Some(b) = link::block(unit, l).filter(|b| !skipped(skip, b)) else {
            continue;
        };
        let Body::Words(bw) = &b.body else { continue };
        let Ok(split) = words::classify(bw) else {
            continue;
        };
        let lits = crate::check::literal_words(&split.nc);
        if !lits.is_empty() {
            nc.push_profile(&lits, l as u32);
        }
    }
    (cw.code != OneShot::Finish).then_some(j + 1)
}

#[cfg(test)]
mod tests {
    use crate::{compile, Options};
    use nc::{Event, Machine};
    use vm::{Status, Vm};

    /// The rendered diagnostics of a program that must not compile.
    fn errors(src: &str) -> String {
        let c = compile("t.nc", src.as_bytes(), &Options::default());
        assert!(c.has_errors(), "expected an error:\n{src}");
        c.render()
    }

    fn canon(src: &str) -> (Vec<String>, Status) {
        let c = compile("t.nc", src.as_bytes(), &Options::default());
        assert!(!c.has_errors(), "{}", c.render());
        let mut vm = Vm::new(c.module.expect("a module"), Machine::reference());
        let mut events: Vec<Event> = Vec::new();
        let status = vm.run(&mut events);
        (events.iter().map(|e| e.to_string()).collect(), status)
    }

    fn assert_error(src: &str, line: u32, code: &str) {
        let out = errors(src);
        assert!(
            out.contains(&format!("t.nc:{line}:")) && out.contains(code),
            "want {code} at line {line}:\n{out}"
        );
    }

    const HEAD: &str = "G98 G00 X40 Z2\nG71 U3 R1\n";

    #[test]
    fn missing_and_reversed_numbers_are_e2020_at_the_cycle_block() {
        assert_error(
            &format!("{HEAD}G71 P1 Q9 F0.2\nN1 G00 X20\nN2 G01 Z-10\nM30\n"),
            3,
            "E2020",
        );
        assert_error(
            &format!("{HEAD}G71 P2 Q1 F0.2\nN1 G00 X20\nN2 G01 Z-10\nM30\n"),
            3,
            "E2020",
        );
        assert_error(
            &format!("{HEAD}G71 P1 F0.2\nN1 G00 X20\nN2 G01 Z-10\nM30\n"),
            3,
            "E2020",
        );
        assert_error("G00 X40 Z2\nG70\nM30\n", 2, "E2006");
    }

    #[test]
    fn more_than_100_profile_blocks_is_e2020_at_the_cycle_block() {
        let mut src = format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\n");
        for i in 0..99 {
            src.push_str(&format!("G01 Z-{}\n", i + 1));
        }
        src.push_str("N2 X40\nM30\n");
        assert_error(&src, 3, "E2020");
    }

    #[test]
    fn calls_macros_and_group_00_in_a_profile_are_e2020_at_that_block() {
        let body = |bad: &str| {
            format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\n{bad}\nN2 G01 Z-10\nM30\nO0010\nM99\n")
        };
        assert_error(&body("M98 P10"), 5, "E2020");
        assert_error(&body("#1 = 5"), 5, "E2020");
        assert_error(&body("G04 P100"), 5, "E2020");
        // The nf block may not open an angle pair.
        assert_error(
            &format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\nN2 G01 Q135000\nM30\n"),
            5,
            "E2020",
        );
    }

    #[test]
    fn e2021_at_the_ns_block() {
        assert_error(
            &format!("{HEAD}G71 P1 Q2 F0.2\nN1 G03 X20 Z0 R10\nN2 G01 Z-10\nM30\n"),
            4,
            "E2021",
        );
        assert_error(
            &format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 Z0\nN2 G01 X20\nM30\n"),
            4,
            "E2021",
        );
        // In a program with macros the compiler cannot tell which code the
        // ns block inherits (control flow is computed): the kernel finds
        // the G02 when the cycle runs, still at the ns block.
        let src =
            "#1 = 20\nG98 G00 X40 Z2\nG02\nG71 U3 R1\nG71 P1 Q2 F0.2\nN1 X#1\nN2 G01 Z-10\nM30\n";
        let (_, status) = canon(src);
        let Status::Alarm(a) = status else {
            panic!("an alarm")
        };
        assert_eq!((a.code, a.line), (2021, 6));
    }

    #[test]
    fn shared_profile_numbers_with_two_roughing_cycles_are_e2022_at_the_later_block() {
        let src = format!(
            "{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\nN2 G01 Z-10\nG72 W2 R1\nG72 P5 Q6 F0.2\nN5 G00 Z-2\nN1 G01 X20\nN6 Z2\nM30\n"
        );
        // N1 of the first profile stands on line 9 too.
        assert_error(&src, 9, "E2022");
        // One roughing cycle and a G70: the numbers may repeat (W103).
        let ok =
            format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\nN2 G01 Z-10\nG70 P1 Q2\nN1 G00 X50\nM30\n");
        let c = compile("t.nc", ok.as_bytes(), &Options::default());
        assert!(!c.has_errors(), "{}", c.render());
    }

    #[test]
    fn the_program_goes_on_after_nf_and_after_g70() {
        // G71 from X40 Z2 over N1 X30 / N2 Z-5 (Δd 3 > stock 5 → one level
        // at X34): the profile blocks do not run again, the block after nf
        // does. G70 then runs them and goes on after its own block.
        let src = "#1 = 30\nG98 G00 X40 Z2\nG71 U3 R1\nG71 P1 Q2 F0.2\nN1 G00 X#1\nN2 G01 Z-5\nG00 X60\nG70 P1 Q2\nM30\n";
        let (got, status) = canon(src);
        assert_eq!(status, Status::Done);
        let want = [
            "RAPID X=40 Z=2",
            "RAPID X=34 Z=2",
            "FEED F=0.2 MODE=MIN",
            "LINE X=34 Z=-5",
            "LINE X=36 Z=-4",
            "RAPID X=36 Z=2",
            "RAPID X=30 Z=2",
            "LINE X=30 Z=-5",
            "RAPID X=40 Z=2",
            "RAPID X=60 Z=2",
            "RAPID X=30 Z=2",
            "LINE X=30 Z=-5",
            "RAPID X=60 Z=2",
            "STOP KIND=M30",
        ];
        assert_eq!(got, want);
    }

    #[test]
    fn a_geometry_error_in_a_profile_names_the_profile_block() {
        // Static: the dry run makes it a compile error at line 5.
        let src = format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\nG02 X30 Z-20 R1\nN2 G01 Z-30\nM30\n");
        assert_error(&src, 5, "E4001");
        // With a macro: a run-time alarm, still at line 6.
        let src = format!(
            "#1 = 1\n{HEAD}G71 P1 Q2 F0.2\nN1 G00 X20\nG02 X30 Z-20 R#1\nN2 G01 Z-30\nM30\n"
        );
        let (_, status) = canon(&src);
        let Status::Alarm(a) = status else {
            panic!("an alarm")
        };
        assert_eq!((a.code, a.line), (4001, 6));
    }

    #[test]
    fn skipped_blocks_leave_the_profile() {
        // From X40 Z2 (Δd 3, stock 6): one level pass at X34. With the
        // deleted taper /X34 Z-3 the profile is X28 → Z-10 and the pass
        // never meets it again: it ends at C′, Z-10 (not Z-3).
        let src = format!("{HEAD}G71 P1 Q2 F0.2\nN1 G00 X28\n/G01 X34 Z-3\nN2 G01 Z-10\nM30\n");
        let (got, _) = canon(&src);
        assert_eq!(
            got[1..4],
            ["RAPID X=34 Z=2", "FEED F=0.2 MODE=MIN", "LINE X=34 Z=-10"]
        );
    }
}
