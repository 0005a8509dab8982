//! Compile-time checks through the NC kernel: the rules of a block with
//! literal words, and a dry run of a static program so that its geometry
//! errors are compile errors (dialect.md §0).

use crate::link::{self, Program, Unit};
use crate::thread_room::RoomCheck;
use crate::words::{self, Call, NcWord, WordValue};
use grammar::ast::{Block, Body, Value};
use grammar::{Diagnostic, Span};
use nc::base::nesting::Levels;
use nc::words::Word;
use nc::{Machine, Nc, NcError};
use smallvec::SmallVec;

/// Checks the literal words of a block (a computed word is checked when
/// it runs), parsing them into the scratch `p` (with the kernel's short
/// parse when they make a plain move: the same result).
pub fn literal_block(
    m: &Machine,
    ws: &[NcWord<'_>],
    p: &mut nc::block::Parsed,
) -> Result<(), NcError> {
    word_rules(m, &literal_words(ws), p)
}

/// The kernel's rules on the words of a block, which hold whatever state
/// it runs in (its parse, and a T's tool and offset numbers).
pub fn word_rules(m: &Machine, lits: &[Word], p: &mut nc::block::Parsed) -> Result<(), NcError> {
    nc::block::parse_move(lits, m, p)?;
    if let Some(t) = p.get(b'T') {
        let t = nc::block::round_half_away(t).max(0.0) as u32;
        nc::exec::check_tool(m, t / 100, t % 100)?;
    }
    Ok(())
}

/// The literal words of a block, as the kernel takes them (inline: one
/// block's worth, built for every block).
pub(crate) fn literal_words(ws: &[NcWord<'_>]) -> SmallVec<[Word; 8]> {
    ws.iter()
        .filter_map(|w| match w.value {
            WordValue::Literal(v, flags) => Some(Word {
                addr: w.addr,
                value: v,
                flags,
            }),
            WordValue::Expr(_) => None,
        })
        .collect()
}

/// The span of the word among `ws` (a block's NC words) that a kernel
/// error names (`NcError::word_among`): the kernel was given their
/// literal words, in this order.
pub fn named_word(e: &NcError, ws: &[NcWord<'_>]) -> Option<Span> {
    let literals = || ws.iter().filter(|w| w.value.literal().is_some());
    let i = e.word_among(literals().map(|w| w.addr))?;
    literals().nth(i).map(|w| w.span)
}

/// [`named_word`] for the words of a block as written: the NC words it
/// splits into (found again on an error only).
fn named_in_block(e: &NcError, ws: &[grammar::ast::Word]) -> Option<Span> {
    if e.word.is_none() && e.addr.is_none() {
        return None;
    }
    named_word(e, &words::classify(ws).ok()?.nc)
}

/// Tags from [`CARRIED`] on name a block of an earlier chunk of a chunked
/// run, kept in [`Lines::carried`]: an element of it still waits in the
/// kernel, and an error about it stands on that block, as it does when the
/// program is run whole.
const CARRIED: u32 = u32::MAX / 2;

/// Where the kernel's line tags point: lines of the running block's unit,
/// and the blocks an earlier chunk left waiting.
#[derive(Clone, Copy)]
struct Lines<'a> {
    unit: &'a Unit,
    carried: &'a [Block],
}

impl Lines<'_> {
    /// The block tagged `tag`.
    fn block(&self, tag: u32) -> Option<&Block> {
        match tag.checked_sub(CARRIED) {
            Some(k) => self.carried.get(k as usize),
            None => link::block(self.unit, tag as usize),
        }
    }

    /// The span of the block tagged `at`, else `block`.
    fn span(&self, at: Option<u32>, block: Span) -> Span {
        at.and_then(|l| self.block(l)).map_or(block, |b| b.span)
    }
}

/// The span an error of the dry run stands on: the word it names, in the
/// block it is about (the tagged one, `NcError::at`, else the running
/// block `ws`), else that block's span (`block`).
fn error_word_span(lines: Lines<'_>, e: &NcError, ws: &[grammar::ast::Word], block: Span) -> Span {
    let tagged = e.at.and_then(|l| lines.block(l));
    let (ws, span) = match tagged {
        Some(b) => match &b.body {
            Body::Words(ws) => (ws.as_slice(), b.span),
            Body::Stmt(_) => (&[][..], b.span),
        },
        None => (ws, block),
    };
    named_in_block(e, ws).unwrap_or(span)
}

/// The literal words of a block that calls nothing: what
/// `literal_words(&classify(ws).nc)` gives then, without sorting first.
fn plain_literals(ws: &[grammar::ast::Word]) -> SmallVec<[Word; 8]> {
    ws.iter()
        .filter_map(|w| match words::value_of(w) {
            WordValue::Literal(value, flags) => Some(Word {
                addr: words::addr_code(w.addr),
                value,
                flags,
            }),
            WordValue::Expr(_) => None,
        })
        .collect()
}

/// The NC words of a block as the modal warnings read them in a run of a
/// program with macros (`predict`), where the block's computed values are
/// gone: its literal words, and its computed ones with a NaN value, so
/// that a word written counts as given. (A computed G or M is left out:
/// its value decides what the warnings ask of it.)
pub(crate) fn watched_words(ws: &[grammar::ast::Word]) -> SmallVec<[Word; 8]> {
    // (Most blocks call nothing: every word is an NC word.)
    if !words::may_call(ws) {
        let each = |w: &grammar::ast::Word| watched(words::addr_code(w.addr), words::value_of(w));
        return ws.iter().filter_map(each).collect();
    }
    match words::classify(ws) {
        Ok(split) => split
            .nc
            .iter()
            .filter_map(|w| watched(w.addr, w.value))
            .collect(),
        Err(_) => SmallVec::new(),
    }
}

/// The word of [`watched_words`] for address `addr` and `value`.
fn watched(addr: u8, value: WordValue<'_>) -> Option<Word> {
    let (value, flags) = match value {
        WordValue::Literal(value, flags) => (value, flags),
        WordValue::Expr(_) if addr != b'G' - b'A' && addr != b'M' - b'A' => (f64::NAN, 0),
        WordValue::Expr(_) => return None,
    };
    Some(Word { addr, value, flags })
}

/// A static program: no macro statement and no computed word (§0).
pub fn is_static(units: &[Unit], programs: &[Program]) -> bool {
    programs.iter().all(|p| {
        p.blocks
            .iter()
            .filter_map(|&l| link::block(&units[p.unit], l))
            .all(|b| match &b.body {
                Body::Stmt(_) => false,
                Body::Words(ws) => ws.iter().all(|w| matches!(w.value, Value::Number(_))),
            })
    })
}

/// Errors a dry run reports at compile time: those of dialect.md §8.1–§8.3
/// (E1xxx–E4xxx) and a tool number past the table; the others (value and
/// machine faults) stay run-time alarms.
fn compile_time(code: u16) -> bool {
    (1000..5000).contains(&code) || code == nc::error::Alarm::ToolNumber.code()
}

/// A block as the dry run runs it: the kernel's literal words, its call,
/// and for a G71–G73 cycle the block after its profile (nf) to go on at.
struct Split<'w> {
    lits: SmallVec<[Word; 8]>,
    call: Option<Call<'w>>,
    resume: Option<usize>,
}

enum Flow {
    Go,
    End,
    /// A called program's `M99 P n`: its caller goes on at its first
    /// block numbered n.
    Back(Return),
}

/// An `M99 P n`: the sequence number, and the M99 block's unit and span.
struct Return {
    seq: u32,
    at: (usize, Span),
}

struct DryRun<'a> {
    units: &'a [Unit],
    programs: &'a [Program],
    skip: [bool; 9],
    run: Runner,
    /// Each program's sequence numbers, made when first needed: by a
    /// cycle's profile, or an `M99 P` returning to the program.
    numbers: Vec<Option<crate::profile::Numbers>>,
    /// Each program's blocks the run has passed, a bit each (made when
    /// the program first runs).
    seen: Vec<Vec<u64>>,
    /// The unit whose line indices tag the kernel's blocks (`Nc::origin`).
    tagged_unit: usize,
}

/// The kernel a dry run drives, and what watches it.
struct Runner {
    nc: Nc,
    /// Blocks run beyond each block's first pass (and a cycle's legs
    /// beyond its first), against [`EXTRA_STEPS`].
    extra: u64,
    /// Blocks the kernel ran, a cycle counted as its legs: what the VM
    /// charges to its block budget at the least.
    executed: u64,
    /// The block past which `executed` first exceeded the machine's
    /// block budget (`run.max_blocks`), and its unit (W122).
    over: Option<(usize, Span)>,
    /// W118 on the canon events.
    room: RoomCheck,
    /// W105–W112, W114 on what each block did.
    warner: crate::dry_warn::Warner,
    /// The last block ran without a fault (its words parsed).
    ran_clean: bool,
    /// The blocks of earlier chunks whose elements wait (tags from
    /// [`CARRIED`] on); none when the program runs whole.
    carried: Vec<Block>,
}

impl Runner {
    fn new(m: &Machine) -> Self {
        Runner {
            nc: Nc::new(m.clone()),
            extra: 0,
            executed: 0,
            over: None,
            room: RoomCheck::new(m),
            warner: Default::default(),
            ran_clean: false,
            carried: Vec::new(),
        }
    }

    /// The warnings found, after the last block.
    fn warnings(mut self) -> Vec<(usize, Diagnostic)> {
        if let Some((unit, span)) = self.over {
            let max = self.nc.machine.run.max_blocks;
            (self.warner).over_budget(unit, span, max, self.executed);
        }
        self.room.finish();
        let mut found = self.warner.diags;
        found.append(&mut self.room.warnings);
        found
    }

    /// Counts a block about to run, `again` when the run has passed it
    /// before: whether the run goes on. Past the budget it warns (W120)
    /// at the block, and the run ends there.
    fn step(&mut self, again: bool, unit: usize, span: Span) -> bool {
        self.extra += u64::from(again);
        if self.extra <= EXTRA_STEPS {
            return true;
        }
        self.warner.budget_spent(unit, span, EXTRA_STEPS);
        false
    }
}

/// Blocks a dry run may run beyond its first pass over each block: a
/// loop's rounds, a repeated call's passes, a cycle's legs. The first
/// pass is free, so a straight program is dry-run whole however long
/// (compile time stays linear in it); a program that loops for ever
/// stops after this many more, with W120.
const EXTRA_STEPS: u64 = 200_000;

/// Runs a static program through the kernel: the warnings it finds
/// (dry_warn, W118), then the first compile-time error, each with its unit.
///
/// Block skip is the operator's switch, read as each block is, so a
/// program with `/n` blocks runs once per state that matters: as the
/// machine file sets the switches (the state a run starts in; its warnings
/// are the ones reported), with every switch off (a diagnostic in a `/n`
/// block is found) and with every switch on (the modal state without those
/// blocks).
pub fn dry_run(units: &[Unit], programs: &[Program], m: &Machine) -> Vec<(usize, Diagnostic)> {
    let mut states = vec![*m.operator.block_skip];
    if has_deleted_blocks(units, programs) {
        for state in [[false; 9], crate::profile::ALL_ON] {
            if !states.contains(&state) {
                states.push(state);
            }
        }
    }
    let first = states[0];
    let mut found = Vec::new();
    for skip in states {
        let mut run = DryRun {
            units,
            programs,
            skip,
            run: Runner::new(m),
            numbers: programs.iter().map(|_| None).collect(),
            seen: programs.iter().map(|_| Vec::new()).collect(),
            tagged_unit: programs.first().map_or(0, |p| p.unit),
        };
        let error = run.program(0, Levels::default()).err();
        if skip == first {
            found.append(&mut run.run.warnings());
        }
        if let Some((unit, d)) = error {
            let d = if skip == first {
                d
            } else {
                d.with_note(state_note(&skip))
            };
            found.push((unit, d));
            break;
        }
    }
    found
}

/// The dry run's sink: the warnings' counts and the thread-room check
/// each see every event.
struct Watchers<'a> {
    counts: &'a mut crate::dry_warn::Counts,
    room: &'a mut RoomCheck,
    /// The running block's lines and span: the events of a block that
    /// waited (a thread block before its run-out) name their own line.
    lines: Lines<'a>,
    block: Span,
}

impl nc::Sink for Watchers<'_> {
    fn emit(&mut self, e: nc::Event) {
        self.room.event(&e);
        self.counts.emit(e);
    }

    fn origin(&mut self, tag: u32) {
        self.room.span = self.lines.span(Some(tag), self.block);
    }
}

/// Which switch state an error of a later dry run belongs to.
fn state_note(skip: &[bool; 9]) -> &'static str {
    if skip.contains(&true) {
        "with the block-skip switches on (the `/` blocks skipped)"
    } else {
        "with the block-skip switches off (the `/` blocks run)"
    }
}

/// Whether any block of the programs carries `/` or `/n`.
fn has_deleted_blocks(units: &[Unit], programs: &[Program]) -> bool {
    programs.iter().any(|p| {
        p.blocks
            .iter()
            .filter_map(|&l| link::block(&units[p.unit], l))
            .any(|b| b.delete.is_some())
    })
}

impl DryRun<'_> {
    /// Marks block `at` (an index into its `blocks`) of program `index`
    /// as passed: whether the run had passed it before.
    fn passed(&mut self, index: usize, at: usize) -> bool {
        let (Some(bits), Some(prog)) = (self.seen.get_mut(index), self.programs.get(index)) else {
            return true;
        };
        if bits.is_empty() {
            bits.resize(prog.blocks.len().div_ceil(64), 0);
        }
        let Some(word) = bits.get_mut(at / 64) else {
            return true;
        };
        let bit = 1 << (at % 64);
        let again = *word & bit != 0;
        *word |= bit;
        again
    }

    fn program(&mut self, index: usize, levels: Levels) -> Result<Flow, (usize, Diagnostic)> {
        let Some(prog) = self.programs.get(index) else {
            return Ok(Flow::End);
        };
        let unit = &self.units[prog.unit];
        let mut next = 0;
        while let Some(&line) = prog.blocks.get(next) {
            next += 1;
            let Some(block) = link::block(unit, line) else {
                continue;
            };
            let Body::Words(ws) = &block.body else {
                continue;
            };
            if self.skipped(block) {
                continue;
            }
            let again = self.passed(index, next - 1);
            if !self.run.step(again, prog.unit, block.span) {
                return Ok(Flow::End);
            }
            let Some(Split { lits, call, resume }) = self.split(index, ws) else {
                return Ok(Flow::End);
            };
            if !lits.is_empty() {
                // The tag of the block's events and of errors about it
                // (`NcError::at`, `Lines::span`): its line. What
                // waits from a program of another file has no line here:
                // an error about it stands on this block.
                if self.tagged_unit != prog.unit {
                    self.run.nc.retag_waiting(u32::MAX);
                    self.tagged_unit = prog.unit;
                }
                self.run.nc.origin = line as u32;
                let at = (prog.unit, unit, block, ws.as_slice());
                if let Flow::End = self.run.exec(at, &lits)? {
                    return Ok(Flow::End);
                }
            }
            next = resume.unwrap_or(next);
            match call {
                None => {}
                // M99 in a called program: back to the caller.
                Some(Call::Ret { p }) if index != 0 => {
                    self.run.nc.break_thread_chain();
                    return Ok(returned(p, (prog.unit, block.span)));
                }
                Some(call) => match self.follow(index, levels, (prog, block), &call)? {
                    Some(at) => next = at.unwrap_or(next),
                    None => return Ok(Flow::End),
                },
            }
        }
        Ok(if index == 0 { Flow::End } else { Flow::Go })
    }

    /// Whether block delete skips the block: its switch is on.
    fn skipped(&self, block: &grammar::ast::Block) -> bool {
        block.delete.is_some_and(|d| {
            self.skip
                .get(d.switch.saturating_sub(1) as usize)
                .copied()
                .unwrap_or(false)
        })
    }

    /// A block of program `index` as the dry run runs it; `None` where the
    /// words do not split (the run ends there).
    fn split<'w>(&mut self, index: usize, ws: &'w [grammar::ast::Word]) -> Option<Split<'w>> {
        if !words::may_call(ws) && !crate::profile::names_cycle(ws) {
            // Most blocks: no call, no cycle, every word an NC word.
            return Some(Split {
                lits: plain_literals(ws),
                call: None,
                resume: None,
            });
        }
        let split = words::classify(ws).ok()?;
        let prog = self.programs.get(index)?;
        let unit = &self.units[prog.unit];
        // A G70–G73 cycle gets its profile.
        let numbers = self.numbers.get_mut(index)?;
        let numbers = numbers.get_or_insert_with(|| crate::profile::Numbers::of(unit, prog));
        let resume = crate::profile::hand_over(
            &mut self.run.nc,
            (unit, prog, numbers),
            &split.nc,
            &self.skip,
        );
        Some(Split {
            lits: literal_words(&split.nc),
            call: split.call,
            resume,
        })
    }

    /// Follows the call of a block of program `index` (not an M99 of a
    /// called program): `None` ends the run, `Some(None)` goes on after the
    /// block, `Some(Some(i))` at block i (an `M99 P n` back from the called
    /// program).
    fn follow(
        &mut self,
        index: usize,
        levels: Levels,
        at: (&Program, &grammar::ast::Block),
        call: &Call<'_>,
    ) -> Result<Option<Option<usize>>, (usize, Diagnostic)> {
        let (prog, block) = at;
        Ok(match self.called(call, levels, (prog.unit, block))? {
            Flow::Go => Some(None),
            Flow::End => None,
            Flow::Back(back) => match self.block_numbered(index, back.seq) {
                Some(at) => Some(Some(at)),
                // The run stops with E6002 at the M99.
                None => {
                    let caller = (index != 0).then_some(prog.number);
                    (self.run.warner).return_missing(back.at, back.seq, caller);
                    None
                }
            },
        })
    }

    /// Runs the program a block of a program at `levels` calls, when the
    /// dry run follows the call; `at` is the calling block's unit and span.
    fn called(
        &mut self,
        call: &Call<'_>,
        levels: Levels,
        at: (usize, &grammar::ast::Block),
    ) -> Result<Flow, (usize, Diagnostic)> {
        let (unit, block) = at;
        let at = (unit, block.span);
        let Some(target) = target(call) else {
            // W124 for a `G65 H99`: the run stops there.
            if let Some(code) = crate::calls::user_alarm_code(call) {
                let comment = block.comments.first().map(|c| c.text.as_str());
                let msg = crate::calls::user_alarm_message(comment);
                self.run.warner.user_alarm(at, code, msg);
            }
            return Ok(Flow::End);
        };
        // E4035: M98 while nose-radius compensation is on.
        if !target.macro_level {
            if let Err(e) = self.run.nc.check_call() {
                return Err((at.0, error_at(&e, at.1)));
            }
        }
        self.call(target, levels)
    }

    /// The index in program `index`'s blocks of its first block numbered
    /// `n`, where `M99 P n` returns to (as the VM finds it).
    fn block_numbered(&mut self, index: usize, n: u32) -> Option<usize> {
        let prog = self.programs.get(index)?;
        let numbers = self.numbers.get_mut(index)?;
        let unit = &self.units[prog.unit];
        let numbers = numbers.get_or_insert_with(|| crate::profile::Numbers::of(unit, prog));
        numbers.first(n).0
    }

    /// Runs the called program `t.count` times from a program at `levels`.
    fn call(&mut self, t: Target, levels: Levels) -> Result<Flow, (usize, Diagnostic)> {
        self.run.nc.break_thread_chain();
        let Some(sub) = self.programs.iter().position(|q| q.number == t.number) else {
            return Ok(Flow::End);
        };
        // (Past a limit the run ends with E6004, which W121 names where
        // every run gets there.)
        let Some(inner) = levels.enter(t.macro_level) else {
            return Ok(Flow::End);
        };
        // (An `M99 P` returns to the caller only from the last pass; the
        // passes before it run the program again, as in the VM.)
        let mut flow = Flow::Go;
        for _ in 0..t.count {
            flow = self.program(sub, inner)?;
            if let Flow::End = flow {
                return Ok(Flow::End);
            }
        }
        Ok(flow)
    }
}

/// How a called program's M99 at `at` returns: to the block after the
/// call, to the block its literal P numbers (`M99 P n`), or, P computed,
/// the dry run ends.
fn returned(p: Option<WordValue<'_>>, at: (usize, Span)) -> Flow {
    match p.map(|p| p.literal()) {
        None => Flow::Go,
        Some(Some(n)) => match nc::block::round_half_away(n) {
            n if (0.0..=99_999_999.0).contains(&n) => Flow::Back(Return { seq: n as u32, at }),
            // (The run stops with an alarm there.)
            _ => Flow::End,
        },
        Some(None) => Flow::End,
    }
}

/// A call the dry run follows: the called program's number, how many
/// times it runs, and whether it opens a macro level (G65) or a
/// subprogram level (M98, an M-code call).
struct Target {
    number: u32,
    count: u32,
    macro_level: bool,
}

/// The target of a call of literal words that the dry run follows (any
/// other ends it: G66, a G65 H operation, the main program's M99).
fn target(call: &Call<'_>) -> Option<Target> {
    match call {
        Call::Sub { p: Some(p), l, .. } => {
            let l = l.and_then(|l| l.literal());
            let (number, count) = crate::calls::m98_target(p.literal()?, l);
            // (More, and the run stops with an alarm at the call.)
            (count <= MAX_REPEAT).then_some(Target {
                number,
                count,
                macro_level: false,
            })
        }
        &Call::SubM { number, .. } => Some(Target {
            number,
            count: 1,
            macro_level: false,
        }),
        Call::Macro {
            modal: false,
            p: Some(p),
            l,
            ..
        } => {
            let count = match l {
                Some(l) => repeat_count(l.literal()?)?,
                None => 1,
            };
            Some(Target {
                number: nc::block::round_half_away(p.literal()?).max(0.0) as u32,
                count,
                macro_level: true,
            })
        }
        _ => None,
    }
}

/// The most times a call repeats its program (dialect.md §7.9, §7.11).
const MAX_REPEAT: u32 = 9999;

/// A G65's L as the VM takes it: `None` outside 0…9999 (the run stops
/// with an alarm there), at least one run.
fn repeat_count(l: f64) -> Option<u32> {
    let n = nc::block::round_half_away(l);
    (0.0..=f64::from(MAX_REPEAT))
        .contains(&n)
        .then(|| (n as u32).max(1))
}

/// A block where the dry run stands: its unit's index, the unit, the
/// block and its words.
type At<'u> = (
    usize,
    &'u Unit,
    &'u grammar::ast::Block,
    &'u [grammar::ast::Word],
);

impl Runner {
    /// Counts a block the kernel ran, `legs` the moves it generated (a
    /// cycle: the VM charges them, at least one), and notes where the
    /// count first passes the machine's block budget.
    fn count_executed(&mut self, legs: u64, unit: usize, span: Span) {
        self.executed = self.executed.saturating_add(legs.max(1));
        if self.executed > self.nc.machine.run.max_blocks && self.over.is_none() {
            self.over = Some((unit, span));
        }
    }

    /// Runs a block's literal words `lits` through the kernel: whether the
    /// run goes on, or the compile-time error it found.
    fn exec(&mut self, at: At<'_>, lits: &[Word]) -> Result<Flow, (usize, Diagnostic)> {
        let (index, unit, block, ws) = at;
        self.room.unit = index;
        self.room.span = block.span;
        let before = self.warner.before(&self.nc);
        let mut counts = crate::dry_warn::Counts::default();
        let mut sink = Watchers {
            counts: &mut counts,
            room: &mut self.room,
            lines: Lines {
                unit,
                carried: &self.carried,
            },
            block: block.span,
        };
        // A cycle's legs after its first count against the extra steps,
        // as they count as blocks in the VM's budget: a cycle with a tiny
        // step against a huge depth does not hold up the compiler.
        (self.nc).set_allowance(EXTRA_STEPS.saturating_sub(self.extra));
        // `exec_move` is `exec` with the short parse of a plain move (any
        // other block goes the general way): most blocks of a long
        // program are plain moves.
        let result = self.nc.exec_move(lits, &mut sink);
        self.ran_clean = result.is_ok();
        let legs = self.nc.take_generated();
        self.extra = self.extra.saturating_add(legs);
        self.count_executed(legs, index, block.span);
        if result.is_ok() {
            (self.warner).after(index, &self.nc, (ws, block.span), lits, &counts, before);
        }
        let lines = Lines {
            unit,
            carried: &self.carried,
        };
        match result {
            Ok(out) if out.end.is_some() => Ok(Flow::End),
            Ok(_) => Ok(Flow::Go),
            // A feed move at F = 0 (E7001 when run): W107, and the run
            // goes on, the block done.
            Err(e) if e.code == nc::error::Alarm::ZeroFeed.code() => {
                // (A corner's arc faults at the block it is printed with.)
                let span = lines.span(e.at, block.span);
                self.warner.zero_feed(index, span);
                Ok(Flow::Go)
            }
            // A cycle with more legs than the budget has left.
            Err(e) if e.code == nc::error::Alarm::BlockBudget.code() => {
                self.warner.budget_spent(index, block.span, EXTRA_STEPS);
                Ok(Flow::End)
            }
            Err(e) if compile_time(e.code) => {
                Err((index, compile_error(lines, &e, ws, block.span)))
            }
            // A run-time fault: every run of this static program stops
            // there (W124).
            Err(e) => {
                let span = lines.span(e.at, block.span);
                self.warner.run_stops((index, span), &e);
                Ok(Flow::End)
            }
        }
    }
}

/// The diagnostic of a compile-time error of the dry run, found when the
/// block `ws` at `block` ran: at the word it names, in the block it is
/// about. That may be a profile block of the running cycle (a note says
/// which cycle), or an earlier block whose element waited for this one's
/// (a chamfer too large for the next move): this block is then labelled.
fn compile_error(
    lines: Lines<'_>,
    e: &NcError,
    ws: &[grammar::ast::Word],
    block: Span,
) -> Diagnostic {
    let (unit, span) = (lines.unit, lines.span(e.at, block));
    let mut d = error_at(e, error_word_span(lines, e, ws, block));
    if let Some(culprit) = e.culprit {
        let there = lines.span(Some(culprit), span);
        d = d.with_related(there, "this block");
    }
    if span == block {
        return d;
    }
    if crate::profile::names_cycle(ws) {
        let line = line_of(unit, block);
        d.with_note(format!("in the profile of the cycle at line {line}"))
    } else {
        d.with_related(block, "the next move")
    }
}

/// The dry run of a static program compiled a chunk at a time
/// (`crate::stream`). Its blocks are plain: no call, no G70–G73 cycle and
/// no `/` (so one switch state), so each chunk runs as it is parsed, the
/// kernel's state carried from one to the next; what it finds is what
/// [`dry_run`] finds on the whole program.
pub struct ChunkedRun {
    run: Runner,
    /// The run has ended (M02/M30, its budget of extra blocks, a run-time fault).
    ended: bool,
    error: Option<(usize, Diagnostic)>,
}

impl ChunkedRun {
    pub fn new(m: &Machine) -> Self {
        ChunkedRun {
            run: Runner::new(m),
            ended: false,
            error: None,
        }
    }

    /// Runs the blocks of one chunk (`prog`'s, in `unit`); how many of
    /// its leading blocks ran without a fault, so that the kernel parsed
    /// their words (with `literal_block`'s result: a block that calls
    /// nothing has its words in order, as `plain_literals` takes them).
    pub fn chunk(&mut self, unit: &Unit, prog: &Program) -> usize {
        let ran = self.run_blocks(unit, prog);
        self.carry(unit);
        ran
    }

    /// Keeps the blocks whose elements still wait in the kernel, under
    /// tags from [`CARRIED`] on: the next chunk's lines are not theirs,
    /// and an error about such an element stands on its own block, as when
    /// the program runs whole. A tag no block answers to (`u32::MAX`)
    /// stands on the running block.
    fn carry(&mut self, unit: &Unit) {
        let earlier = std::mem::take(&mut self.run.carried);
        let mut kept: Vec<Block> = Vec::new();
        let lines = Lines {
            unit,
            carried: &earlier,
        };
        self.run.nc.map_waiting_tags(&mut |tag| {
            let Some(block) = lines.block(tag) else {
                return u32::MAX;
            };
            // Elements of one block share its entry.
            let k = match kept.iter().position(|b| b.span == block.span) {
                Some(k) => k,
                None => {
                    kept.push(block.clone());
                    kept.len() - 1
                }
            };
            CARRIED.saturating_add(k as u32)
        });
        self.run.carried = kept;
    }

    /// Runs the blocks of one chunk: how many of its leading blocks ran
    /// without a fault.
    fn run_blocks(&mut self, unit: &Unit, prog: &Program) -> usize {
        let mut ran = 0;
        for (i, &line) in prog.blocks.iter().enumerate() {
            let words = link::block(unit, line).and_then(|b| match &b.body {
                Body::Words(ws) => Some((b, ws)),
                Body::Stmt(_) => None,
            });
            // (A line without words has none to parse.)
            let parsed = match words {
                Some((block, ws)) => {
                    self.run.nc.origin = line as u32;
                    if self.ended {
                        break;
                    }
                    self.block((prog.unit, unit, block, ws))
                }
                None => true,
            };
            if parsed && ran == i {
                ran = i + 1;
            }
        }
        ran
    }

    /// Runs one block of a chunk: whether the kernel ran it without a
    /// fault.
    fn block(&mut self, at: At<'_>) -> bool {
        let (index, _, block, ws) = at;
        // (A plain program runs each block once.)
        if !self.run.step(false, index, block.span) {
            self.ended = true;
            return false;
        }
        let lits = plain_literals(ws);
        if lits.is_empty() {
            return false;
        }
        match self.run.exec(at, &lits) {
            Ok(Flow::Go) => {}
            Ok(_) => self.ended = true,
            Err(found) => {
                self.error = Some(found);
                self.ended = true;
            }
        }
        self.run.ran_clean
    }

    /// Whether it has found a compile-time error.
    pub fn failed(&self) -> bool {
        self.error.is_some()
    }

    /// What it found, in [`dry_run`]'s order.
    pub fn finish(self) -> Vec<(usize, Diagnostic)> {
        let mut found = self.run.warnings();
        found.extend(self.error);
        found
    }
}

pub fn error_at(e: &NcError, span: Span) -> Diagnostic {
    let d = Diagnostic::error(crate::codes::name(e.code), span, e.message.clone());
    match &e.help {
        Some(help) => d.with_help(help.clone()),
        None => d,
    }
}

/// The 1-based line of a span's start.
fn line_of(unit: &Unit, span: Span) -> usize {
    let end = (span.start as usize).min(unit.bytes.len());
    1 + unit.bytes[..end].iter().filter(|&&b| b == b'\n').count()
}
