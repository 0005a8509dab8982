//! Pass `build`: every block of every linked program into the IR.
//!
//! NC blocks become `Nc` operations (their words constants or
//! expressions); macro statements become assignments, branches and jumps;
//! M98/M99/G65/G66 become call and return terminators. The constant
//! folding and propagation of -O1 happen here, as the blocks are read
//! (`expr`); the diagnostics of the checks that need no run come out in
//! block order.

mod blocks;

use crate::ir::{self, Handle, Loc, Op, Terminator};
use crate::link::{self, Program, Unit};
use crate::words::{self, WordValue};
use grammar::ast::{Block, Body, Cond, Expr, Stmt};
use grammar::{Diagnostic, Span};
use nc::Machine;
use std::collections::HashMap;

/// A diagnostic with the index of its unit (source file).
pub type FileDiag = (usize, Diagnostic);

/// What the code of the program built so far ends with, as emitted (the
/// rule for the program's final `Halt`/`Ret` reads it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tail {
    /// Nothing yet.
    Nothing,
    /// An M99 without P.
    Ret,
    /// The join of a `/n` block's guard.
    Join,
    /// Anything else.
    Other,
}

pub struct Builder<'a> {
    pub units: &'a [Unit],
    pub programs: &'a [Program],
    pub machine: &'a Machine,
    pub optimize: bool,
    pub diags: Vec<FileDiag>,
    pub unit: usize,
    /// The number of the program being built.
    program_number: u32,
    /// G70–G73 profiles: block starts and jumps past nf.
    pub(crate) profiles: crate::profile::Profiles,
    /// Scratch for the literal check of each block (filled in place).
    parsed: nc::block::Parsed,
    /// The block being built is one the dry run has run (`crate::stream`):
    /// the kernel parsed its words there, the same words with the same
    /// machine, so they are not parsed twice.
    words_parsed: bool,
    module: ir::Module,
    strings: HashMap<String, u32>,
    /// The function being built and its open block.
    f: ir::Function,
    cur: Option<Handle<ir::Block>>,
    /// The source of what is added next, and whether it starts a statement.
    span: Span,
    fresh: bool,
    tail: Tail,
    /// The innermost DO loop open where the builder stands (0: none).
    pub(crate) in_loop: u32,
    /// G65 H80–H86 jumps to a written sequence number, checked against
    /// their target's loop at the program's end (E2015).
    pub(crate) literal_jumps: Vec<LiteralJump>,
}

/// An open DO loop of the program being built.
struct Loop {
    label: u32,
    id: u32,
    start: Handle<ir::Block>,
    /// Blocks whose branch leaves the loop (WHILE's test).
    exits: Vec<Handle<ir::Block>>,
    span: Span,
}

/// A G65 H80–H86 to a written sequence number `seq` at `span`, inside DO
/// loop `inside` (0: none).
pub(crate) struct LiteralJump {
    pub h: u32,
    pub seq: u32,
    pub span: Span,
    pub inside: u32,
}

/// Each N number of a program: the index in `ProgState::seqs` of its
/// first block, and whether another block carries it too.
type FirstNumbers = crate::hash::IntMap<u32, (usize, bool)>;

/// [`FirstNumbers`] of a program, found in one pass: a search of all
/// blocks per jump was quadratic in a long chain of GOTOs.
fn first_numbers(st: &ProgState) -> FirstNumbers {
    let mut first = FirstNumbers::default();
    for (i, (n, ..)) in st.seqs.iter().enumerate() {
        first
            .entry(*n)
            .and_modify(|(_, again)| *again = true)
            .or_insert((i, false));
    }
    first
}

/// W103's message for a jump to `N{seq}` (dialect.md §1.6).
fn recurs(seq: u32) -> String {
    format!("N{seq} occurs more than once: the first block is used")
}

/// A literal jump waiting for its target: the block it ends.
struct Pending {
    at: Handle<ir::Block>,
    seq: u32,
    span: Span,
    loops: Vec<u32>,
}

/// What building a program carries from block to block.
#[derive(Default)]
pub(crate) struct ProgBuild {
    state: ProgState,
    data_setting: crate::data_setting::Checker,
}

/// How a program ends: its last block's span, and whether that block
/// ends it (M02, M30, M99 or a GOTO).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ProgEnd {
    pub span: Span,
    pub explicit: bool,
}

/// Per-program state.
#[derive(Default)]
struct ProgState {
    loops: Vec<Loop>,
    /// Labels of loops a crossing END closed (see `close_loop`).
    crossed: Vec<u32>,
    gotos: Vec<Pending>,
    /// (sequence number, its block, loop ids open at that block).
    seqs: Vec<(u32, Handle<ir::Block>, Vec<u32>, Span)>,
}

/// Builds the IR of every program; `presets` are `-D` assignments run
/// first.
pub fn build(
    units: &[Unit],
    programs: &[Program],
    machine: &Machine,
    optimize: bool,
    presets: &[(u32, f64)],
) -> (ir::Module, Vec<FileDiag>) {
    let mut b = Builder::new(units, programs, machine, optimize);
    for (i, prog) in programs.iter().enumerate() {
        b.build_program(i, prog, presets);
    }
    (b.module, b.diags)
}

impl<'a> Builder<'a> {
    pub(crate) fn new(
        units: &'a [Unit],
        programs: &'a [Program],
        machine: &'a Machine,
        optimize: bool,
    ) -> Self {
        Builder {
            units,
            programs,
            machine,
            optimize,
            diags: Vec::new(),
            unit: 0,
            program_number: 0,
            profiles: Default::default(),
            parsed: Default::default(),
            words_parsed: false,
            module: ir::Module::default(),
            strings: HashMap::new(),
            f: ir::Function::default(),
            cur: None,
            span: Span::default(),
            fresh: false,
            tail: Tail::Nothing,
            in_loop: 0,
            literal_jumps: Vec::new(),
        }
    }

    pub fn error(&mut self, code: &'static str, span: Span, msg: impl Into<String>) {
        self.diags
            .push((self.unit, Diagnostic::error(code, span, msg)));
    }

    pub fn warn(&mut self, code: &'static str, span: Span, msg: impl Into<String>) {
        self.diags
            .push((self.unit, Diagnostic::warning(code, span, msg)));
    }

    /// The source of the operations and terminators added next.
    pub(crate) fn set_loc(&mut self, span: Span) {
        self.span = span;
    }

    /// A new statement starts: what follows computes its values afresh.
    pub fn reset(&mut self) {
        self.fresh = true;
    }

    fn loc(&mut self) -> Loc {
        Loc {
            file: self.unit as u16,
            fresh: std::mem::take(&mut self.fresh),
            span: self.span,
        }
    }

    pub fn string(&mut self, s: &str) -> ir::StrId {
        if let Some(&i) = self.strings.get(s) {
            return ir::StrId(i);
        }
        let i = self.module.strings.len() as u32;
        self.module.strings.push(s.to_string());
        self.strings.insert(s.to_string(), i);
        ir::StrId(i)
    }

    /// The program table index of program `number`.
    pub fn program_index(&self, number: u32) -> Option<u32> {
        self.programs
            .iter()
            .position(|p| p.number == number)
            .map(|i| i as u32)
    }

    // --- A program in chunks (`crate::stream`) ----------------------------

    /// The same builder over other units and programs: the next chunk's.
    pub(crate) fn rebind<'b>(
        self,
        units: &'b [Unit],
        programs: &'b [Program],
        machine: &'b Machine,
    ) -> Builder<'b> {
        Builder {
            units,
            programs,
            machine,
            optimize: self.optimize,
            diags: self.diags,
            unit: self.unit,
            program_number: self.program_number,
            profiles: self.profiles,
            parsed: self.parsed,
            words_parsed: false,
            module: self.module,
            strings: self.strings,
            f: self.f,
            cur: self.cur,
            span: self.span,
            fresh: self.fresh,
            tail: self.tail,
            in_loop: self.in_loop,
            literal_jumps: self.literal_jumps,
        }
    }

    /// Starts the main program (`prog`: its first chunk's blocks).
    pub(crate) fn start_chunks(&mut self, prog: &Program) {
        let (blocks, words) = sizes(self.units, prog);
        self.start_program(prog, blocks, words);
        self.start_blocks(prog);
    }

    /// Builds one chunk's blocks, the first `ran_ahead` of which the dry
    /// run has run, and hands them over as a part of the function: its
    /// last block stays open and goes on in the next part.
    pub(crate) fn build_chunk(
        &mut self,
        prog: &Program,
        pb: &mut ProgBuild,
        ran_ahead: usize,
    ) -> ir::Function {
        self.build_blocks(prog, pb, ran_ahead);
        self.take_part()
    }

    /// Ends the program after its last chunk; the last part.
    pub(crate) fn end_chunks(
        &mut self,
        prog: &Program,
        pb: ProgBuild,
        end: ProgEnd,
    ) -> ir::Function {
        self.end_program(prog, true, pb, end);
        self.take_part()
    }

    /// The function built so far; the next part starts empty, with no
    /// open block.
    fn take_part(&mut self) -> ir::Function {
        // The next chunk is about as large as this one: its tables start
        // at this one's sizes rather than grow (and copy) from empty.
        let f = &self.f;
        let next = ir::Function {
            number: f.number,
            file: f.file,
            span: f.span,
            ops: ir::Arena::with_capacity(f.ops.len()),
            op_locs: Vec::with_capacity(f.op_locs.len()),
            words: Vec::with_capacity(f.words.len()),
            word_spans: Vec::with_capacity(f.word_spans.len()),
            ..Default::default()
        };
        self.cur = None;
        std::mem::replace(&mut self.f, next)
    }

    /// The module being built: its strings (its functions stay empty).
    pub(crate) fn module(&self) -> &ir::Module {
        &self.module
    }

    pub(crate) fn take_diags(&mut self) -> Vec<FileDiag> {
        std::mem::take(&mut self.diags)
    }

    // --- Programs --------------------------------------------------------

    fn build_program(&mut self, index: usize, prog: &Program, presets: &[(u32, f64)]) {
        let (blocks, words) = sizes(self.units, prog);
        self.start_program(prog, blocks, words);
        if index == 0 {
            for &(var, value) in presets {
                self.reset();
                let value = self.add_expr(ir::Expr::Const(value));
                self.push(Op::Assign {
                    target: ir::VarTarget::Direct(var),
                    value,
                    msg: None,
                });
            }
        }
        let mut pb = ProgBuild::default();
        self.start_blocks(prog);
        self.build_blocks(prog, &mut pb, 0);
        let unit = &self.units[prog.unit];
        let end = ProgEnd {
            span: (prog.blocks.last())
                .and_then(|&l| link::block(unit, l))
                .map_or(prog.span, |b| b.span),
            explicit: ends_explicitly(unit, prog),
        };
        self.end_program(prog, index == 0, pb, end);
        let f = std::mem::take(&mut self.f);
        self.module.functions.push(f);
    }

    /// A new function for `prog`, with room for `blocks` operations and
    /// `words` words.
    fn start_program(&mut self, prog: &Program, blocks: usize, words: usize) {
        self.unit = prog.unit;
        self.program_number = prog.number;
        self.set_loc(prog.span);
        self.f = ir::Function {
            number: prog.number,
            file: prog.unit as u16,
            span: prog.span,
            ops: ir::Arena::with_capacity(blocks),
            op_locs: Vec::with_capacity(blocks),
            words: Vec::with_capacity(words),
            word_spans: Vec::with_capacity(words),
            ..Default::default()
        };
        self.cur = None;
        self.tail = Tail::Nothing;
        self.in_loop = 0;
        self.literal_jumps.clear();
    }

    /// What comes before a program's first block is built.
    fn start_blocks(&mut self, prog: &Program) {
        crate::profile::program_start(self, prog);
    }

    /// Builds the blocks of `prog` (all of them, or those of one chunk),
    /// the first `ran_ahead` of which the dry run has run.
    fn build_blocks(&mut self, prog: &Program, pb: &mut ProgBuild, ran_ahead: usize) {
        let units: &'a [Unit] = self.units;
        let unit = &units[prog.unit];
        let st = &mut pb.state;
        for (i, &line) in prog.blocks.iter().enumerate() {
            self.words_parsed = i < ran_ahead;
            crate::profile::block_start(self, line);
            let Some(block) = link::block(unit, line) else {
                continue;
            };
            self.set_loc(block.span);
            crate::profile::count_cycle(self, block);
            pb.data_setting.block(self, block);
            if let Some(seq) = block.seq {
                let at = self.here();
                let loc = self.loc_peek();
                self.push_at(
                    Op::Seq(seq.number, self.in_loop),
                    Loc {
                        fresh: false,
                        ..loc
                    },
                );
                let loops = st.loops.iter().map(|l| l.id).collect();
                st.seqs.push((seq.number, at, loops, block.span));
            }
            // A `/n` block is kept behind a guard: the switch is the
            // operator's, read when the block is (docs/language.md).
            let guard = block.delete.map(|d| self.skip_guard(d.switch));
            self.reset();
            match &block.body {
                Body::Words(_) => self.build_words(block),
                Body::Stmt(s) => self.build_stmt(s, block, st),
            }
            if let Some(at) = guard {
                self.end_guard(at);
            }
        }
        self.words_parsed = false;
    }

    /// After the last block: the end of the program (W101 when it runs
    /// off its last block), open loops, and the GOTOs' targets.
    fn end_program(&mut self, prog: &Program, main: bool, pb: ProgBuild, end: ProgEnd) {
        let mut st = pb.state;
        self.set_loc(end.span);
        crate::profile::program_end(self, prog);
        // A program that ends in M99 needs no end of its own, unless a jump
        // may land past it (a skipped last block goes on past its code).
        let ends = self.tail == Tail::Ret;
        let mut off_the_end = None;
        if !ends || !st.gotos.is_empty() || !st.seqs.is_empty() || self.cur.is_some() {
            self.reset();
            off_the_end = Some(self.open());
            self.terminate(if main {
                Terminator::Halt
            } else {
                Terminator::Return { seq: None }
            });
        }
        for open in std::mem::take(&mut st.loops) {
            self.error(
                "E2014",
                open.span,
                format!("DO {} has no END {}", open.label, open.label),
            );
        }
        let first = first_numbers(&st);
        self.check_literal_jumps(&st, &first);
        self.resolve_gotos(&mut st, &first);
        // Running off the end (W101): the main program halts, a
        // subprogram returns as if M99. Not when no path gets there, such
        // as G70's profile after M30 (a profile is not run through).
        if !end.explicit && off_the_end.is_some_and(|b| self.reaches(b)) {
            let what = if main {
                "the main program ends"
            } else {
                "the subprogram returns as if M99"
            };
            let msg = format!(
                "O{:04} runs off its last block without M02, M30 or M99: {what}",
                prog.number
            );
            let mut d = Diagnostic::warning("W101", end.span, msg);
            if let Some(next) = self.leading_blocks_before(prog) {
                d = d.with_help(format!(
                    "the blocks before the first O line are a main program of their own, O0000, and O{next:04} after them is a subprogram that runs only when called: if they belong to O{next:04}, write them after its O line"
                ));
            }
            self.diags.push((self.unit, d));
        }
    }

    /// The number of the file's first O program when `prog` is the main
    /// program made of the blocks before it (docs/language.md §1).
    fn leading_blocks_before(&self, prog: &Program) -> Option<u32> {
        let no_o_line = prog.number == 0 && prog.span == Span::default();
        let mut same_file = self.programs.iter().filter(|p| p.unit == prog.unit);
        let next = same_file.nth(1)?;
        no_o_line.then_some(next.number)
    }

    /// Whether control may get to block `to` of the function being
    /// built: from its entry along the edges, and from every numbered
    /// block where a jump is computed (GOTO, G65 H80–H86) or a callee
    /// may return to one (M99 P).
    fn reaches(&self, to: Handle<ir::Block>) -> bool {
        let f = &self.f;
        let computed = (f.blocks.iter()).any(|(_, b)| {
            matches!(
                b.term,
                Some(Terminator::Goto { .. } | Terminator::GotoIf { .. } | Terminator::Call { .. })
            )
        });
        let numbered = |b: &ir::Block| (b.ops.iter()).any(|&op| matches!(f.ops[op], Op::Seq(..)));
        let mut seen = vec![false; f.blocks.len()];
        let mut stack: Vec<Handle<ir::Block>> = f.layout.first().copied().into_iter().collect();
        if computed {
            stack.extend(f.blocks.iter().filter(|(_, b)| numbered(b)).map(|(h, _)| h));
        }
        while let Some(b) = stack.pop() {
            if std::mem::replace(&mut seen[b.index()], true) {
                continue;
            }
            if b == to {
                return true;
            }
            let term = f.blocks.get(b).and_then(|blk| blk.term.as_ref());
            stack.extend(term.into_iter().flat_map(|t| t.successors()));
        }
        false
    }

    /// E2015 for a G65 H80–H86 to a written number whose block lies in a
    /// loop that does not hold the jump. A number no block has is the
    /// run's E6001 (dialect.md §7.8), so is passed over here.
    /// The written targets of G65 H80–H86: W103 where the number recurs
    /// (the first block is used, as for GOTO), E2015 into a loop. (One
    /// that names no block is E6001 when the jump runs, dialect.md §7.8.)
    fn check_literal_jumps(&mut self, st: &ProgState, first: &FirstNumbers) {
        for j in std::mem::take(&mut self.literal_jumps) {
            let Some(&(i, again)) = first.get(&j.seq) else {
                continue;
            };
            if again {
                self.warn("W103", j.span, recurs(j.seq));
            }
            let Some((.., loops, _)) = st.seqs.get(i) else {
                continue;
            };
            if !self
                .f
                .loop_holds(loops.last().copied().unwrap_or(0), j.inside)
            {
                let msg = format!(
                    "G65 H{} P{} jumps into a DO loop from outside it",
                    j.h, j.seq
                );
                self.error("E2015", j.span, msg);
            }
        }
    }

    fn resolve_gotos(&mut self, st: &mut ProgState, first: &FirstNumbers) {
        for g in std::mem::take(&mut st.gotos) {
            let found = first.get(&g.seq).map(|&(i, again)| (&st.seqs[i], again));
            let Some(((_, target, loops, _), again)) = found else {
                self.error(
                    "E2010",
                    g.span,
                    format!(
                        "GOTO {}: there is no block N{} in this program",
                        g.seq, g.seq
                    ),
                );
                continue;
            };
            if again {
                self.warn("W103", g.span, recurs(g.seq));
            }
            if !loops.iter().all(|id| g.loops.contains(id)) {
                self.error(
                    "E2015",
                    g.span,
                    format!("GOTO {} jumps into a DO loop from outside it", g.seq),
                );
                continue;
            }
            let target = *target;
            self.patch_jump(g.at, target);
        }
    }

    // --- Statements ------------------------------------------------------

    fn build_stmt(&mut self, s: &Stmt, block: &Block, st: &mut ProgState) {
        match s {
            Stmt::Assign { target, value, .. } => self.assign(target, value, block),
            Stmt::Goto { target, .. } => self.goto(target, None, st),
            Stmt::IfGoto { cond, target, .. } => {
                let c = self.cond(cond);
                self.goto(target, Some(c), st);
            }
            Stmt::IfThen { cond, then, .. } => {
                let c = self.cond(cond);
                let at = self.branch(c);
                self.build_stmt(then, block, st);
                let over = self.jump_later();
                self.charge_otherwise(at);
                let here = self.here();
                self.patch_jump(over, here);
            }
            Stmt::While { cond, label, span } => {
                let start = self.here();
                self.push(Op::Charge);
                let c = self.cond(cond);
                let exit = self.branch(c);
                self.open_loop(label.value, start, vec![exit], *span, label.span, st);
            }
            Stmt::Do { label, span } => {
                let start = self.here();
                self.push(Op::Charge);
                self.open_loop(label.value, start, Vec::new(), *span, label.span, st);
            }
            Stmt::End { label, span } => {
                self.close_loop(label.value, *span, st);
            }
        }
    }

    fn open_loop(
        &mut self,
        label: u32,
        start: Handle<ir::Block>,
        exits: Vec<Handle<ir::Block>>,
        span: Span,
        label_span: Span,
        st: &mut ProgState,
    ) {
        if !(1..=3).contains(&label) {
            self.error(
                "E2013",
                label_span,
                format!("DO/END label {label}: labels are 1, 2 or 3"),
            );
            return;
        }
        // (Opened even so: its END then closes it, not an outer loop,
        // which would cascade into errors about crossed loops.)
        if st.loops.iter().any(|l| l.label == label) {
            self.error(
                "E2014",
                span,
                format!("DO {label} is already open: nested loops need different labels"),
            );
        } else if st.loops.len() >= 3 {
            self.error("E2014", span, "loops nest at most three deep");
        }
        // Numbered as the IR numbers them, each with the loop around it.
        self.f.loops.push(self.in_loop);
        self.in_loop = self.f.loops.len() as u32;
        st.loops.push(Loop {
            label,
            id: self.in_loop,
            start,
            exits,
            span,
        });
    }

    fn close_loop(&mut self, label: u32, span: Span, st: &mut ProgState) {
        if !(1..=3).contains(&label) {
            self.error(
                "E2013",
                span,
                format!("DO/END label {label}: labels are 1, 2 or 3"),
            );
            return;
        }
        let Some(depth) = st.loops.iter().rposition(|l| l.label == label) else {
            // The END of a loop an earlier END crossed was reported there.
            if let Some(i) = st.crossed.iter().position(|&l| l == label) {
                st.crossed.swap_remove(i);
            } else {
                self.error("E2014", span, format!("END {label} without a DO {label}"));
            }
            return;
        };
        // Loops opened inside this one and still open are crossed by it:
        // reported once, here, and their own ENDs later are let pass.
        if let Some(inner) = st.loops.last().filter(|l| l.label != label) {
            let msg = format!("END {label} closes DO {}: loops are crossed", inner.label);
            self.error("E2014", span, msg);
            st.crossed
                .extend(st.loops.drain(depth + 1..).map(|l| l.label));
        }
        let Some(open) = st.loops.pop() else {
            return;
        };
        self.in_loop = st.loops.last().map_or(0, |l| l.id);
        self.terminate(Terminator::Jump(open.start));
        let here = self.here();
        for at in open.exits {
            self.patch_branch(at, here);
        }
    }

    /// `GOTO n` (conditional when `cond` is the test).
    fn goto(&mut self, target: &Expr, cond: Option<Handle<ir::Expr>>, st: &mut ProgState) {
        let skip = cond.map(|c| self.branch(c));
        if let Expr::Num(n) = target {
            if n.has_point {
                let msg = "a GOTO's sequence number is an integer: a decimal point is not allowed";
                self.error("E1009", target.span(), msg);
            }
        }
        match crate::expr::fold(target) {
            Some(Ok(n)) => {
                let n = nc::block::round_half_away(n);
                if !(1.0..=99999.0).contains(&n) {
                    self.error(
                        "E2010",
                        target.span(),
                        format!("GOTO {n}: sequence numbers are 1…99999"),
                    );
                } else {
                    let at = self.goto_later();
                    let loops = st.loops.iter().map(|l| l.id).collect();
                    st.gotos.push(Pending {
                        at,
                        seq: n as u32,
                        span: target.span(),
                        loops,
                    });
                }
            }
            _ => {
                let seq = self.expr(target);
                let inside = self.in_loop;
                self.terminate(Terminator::Goto { seq, inside });
            }
        }
        if let Some(at) = skip {
            self.charge_otherwise(at);
        }
    }

    fn assign(&mut self, target: &grammar::ast::VarRef, value: &Expr, block: &Block) {
        let src = self.expr(value);
        let index = crate::expr::fold(&target.index.expr());
        let msg = if let Some(c) = block.comments.first() {
            Some(self.string(&c.text))
        } else if matches!(index, Some(Ok(v)) if v == 3000.0 || v == 3006.0) {
            Some(self.string(""))
        } else {
            None
        };
        match index {
            // (`#0 = …` too: a value error is the run's, E5007 when it is
            // reached, dialect.md §0; the compile-time run tells W124 when
            // it always is.)
            Some(Ok(n)) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => {
                self.push(Op::Assign {
                    target: ir::VarTarget::Direct(n as u32),
                    value: src,
                    msg,
                });
            }
            _ => {
                let idx = self.expr(&target.index.expr());
                self.push(Op::Assign {
                    target: ir::VarTarget::Indirect(idx),
                    value: src,
                    msg,
                });
            }
        }
    }

    /// An expression of the program, folded as far as -O1 allows.
    pub fn expr(&mut self, e: &Expr) -> Handle<ir::Expr> {
        crate::expr::build(self, e)
    }

    fn cond(&mut self, c: &Cond) -> Handle<ir::Expr> {
        crate::expr::build_cond(self, c)
    }

    /// A word's value as an expression (a literal is a constant).
    pub fn value(&mut self, v: &WordValue<'_>) -> Handle<ir::Expr> {
        match v {
            WordValue::Literal(x, _) => self.add_expr(ir::Expr::Const(*x)),
            WordValue::Expr(e) => self.expr(e),
        }
    }

    // --- NC blocks -------------------------------------------------------

    fn build_words(&mut self, block: &Block) {
        let Body::Words(ws) = &block.body else { return };
        let table = &self.machine.r#macro.g_code_macros;
        if let Some(call) = words::g_code_macro(ws, table, self.program_number) {
            match call {
                Ok(split) => self.build_split(block, &split),
                Err(d) => self.diags.push((self.unit, d)),
            }
            return;
        }
        let mut plain = words::Split {
            nc: words::NcWords::new(),
            call: None,
        };
        if words::classify_plain(ws, &mut plain) {
            self.build_split(block, &plain);
            return;
        }
        match words::classify(ws) {
            Ok(split) => self.build_split(block, &split),
            Err(d) => self.diags.push((self.unit, d)),
        }
    }

    fn build_split(&mut self, block: &Block, split: &words::Split<'_>) {
        if !self.literals_hold(block, split) {
            return;
        }
        let after = crate::profile::before_exec(self, block, split);
        let start = self.words_len();
        let last_motion = split.nc.iter().rposition(written_motion);
        for (i, w) in split.nc.iter().enumerate() {
            // (Only a word before the last motion can be one to skip.)
            if last_motion.is_some_and(|last| i < last) && written_motion(w) {
                // (W106: a later G00–G03 replaces it. Without it the
                // block can be a plain move, and pass `modal` follows
                // the position through it.)
                continue;
            }
            match w.value {
                WordValue::Literal(v, flags) => {
                    self.push_word(w.addr, ir::WordValue::Const(v, flags), w.span)
                }
                WordValue::Expr(e) => match crate::expr::fold(e).filter(|_| self.optimize) {
                    // Folded: a computed value (no decimal-point rule);
                    // a vacant one leaves the word out.
                    Some(Ok(v)) if v.is_nan() => {}
                    Some(Ok(v)) => self.push_word(w.addr, ir::WordValue::Const(v, 0), w.span),
                    _ => {
                        let h = self.expr(e);
                        self.push_word(w.addr, ir::WordValue::Expr(h), w.span);
                    }
                },
            }
        }
        self.warn_unlisted_m(split);
        crate::lint::block(self, split);
        self.set_loc(block.span);
        if !split.nc.is_empty() {
            let msg = block.comments.first().map(|c| c.text.clone());
            let msg = msg.map(|m| self.string(&m));
            self.nc_op(start, ir::NcKind::Run, msg);
            if ends_program(split) {
                self.terminate(Terminator::Ended);
            }
        }
        crate::profile::after_exec(self, after);
        if let Some(call) = &split.call {
            let comment = block.comments.first().map(|c| c.text.as_str());
            crate::calls::build_call(self, call.clone(), block.span, comment);
        }
    }

    /// Whether the literal words of a block pass the kernel's rules (an
    /// error where they do not). A block the dry run ran has passed its
    /// parse there; a T word's tool and offset numbers are checked here
    /// all the same.
    fn literals_hold(&mut self, block: &Block, split: &words::Split<'_>) -> bool {
        const T: u8 = b'T' - b'A';
        if self.words_parsed && split.nc.iter().all(|w| w.addr != T) {
            return true;
        }
        let Err(e) = crate::check::literal_block(self.machine, &split.nc, &mut self.parsed) else {
            return true;
        };
        // The kernel names the word among the literals it was given
        // (`check::literal_words`).
        let word = crate::check::named_word(&e, &split.nc);
        self.error(code_name(e.code), word.unwrap_or(block.span), e.message);
        false
    }

    /// W113: an M code that neither the reference PLC table nor the
    /// machine file's `[plc] m_codes` lists.
    fn warn_unlisted_m(&mut self, split: &words::Split<'_>) {
        const LISTED: &[u32] = &[
            0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13, 14, 15, 20, 21, 24, 25, 29, 30, 32, 33, 41, 42,
            43, 44, 50, 51, 52, 53, 54, 55, 56, 57, 58, 63, 64, 65,
        ];
        for w in &split.nc {
            let (true, WordValue::Literal(v, _)) = (w.addr == b'M' - b'A', w.value) else {
                continue;
            };
            let m = nc::block::round_half_away(v);
            let listed = LISTED.contains(&(m as u32)) || self.machine.plc.lists_m(m as u32);
            if (0.0..9000.0).contains(&m) && !listed {
                self.warn(
                    "W113",
                    w.span,
                    format!(
                        "M{m} is not in the reference PLC table; it is handed to the PLC as it is"
                    ),
                );
            }
        }
    }
}

/// A program's blocks and words: room for the IR (a count costs little
/// beside the copies of growing arenas).
fn sizes(units: &[Unit], prog: &Program) -> (usize, usize) {
    let Some(unit) = units.get(prog.unit) else {
        return (0, 0);
    };
    let words = prog
        .blocks
        .iter()
        .filter_map(|&l| link::block(unit, l))
        .map(|b| match &b.body {
            Body::Words(ws) => ws.len(),
            Body::Stmt(_) => 0,
        })
        .sum();
    (prog.blocks.len(), words)
}

/// Whether an NC block ends the program: M02 or M30 written as a literal
/// (the kernel ends the run when it executes them).
/// Whether `w` is a G00–G03 written as a literal 0–3.
fn written_motion(w: &words::NcWord<'_>) -> bool {
    // (The address first: most words are not G.)
    w.addr == b'G' - b'A'
        && matches!(w.value, WordValue::Literal(v, _) if nc::block::written_motion(v).is_some())
}

fn ends_program(split: &words::Split<'_>) -> bool {
    split.nc.iter().any(|w| {
        w.addr == b'M' - b'A' && matches!(w.value.literal(), Some(m) if m == 2.0 || m == 30.0)
    })
}

/// Does the program's last block end it (M02, M30, M99 or a GOTO)?
fn ends_explicitly(unit: &Unit, prog: &Program) -> bool {
    (prog.blocks.iter().rev())
        .filter_map(|&l| link::block(unit, l))
        .find_map(block_ends)
        .unwrap_or(false)
}

/// Whether a block ends its program (M02, M30, M99 or a GOTO); `None`
/// for a block of no words, which the rule passes over.
pub(crate) fn block_ends(block: &Block) -> Option<bool> {
    match &block.body {
        Body::Stmt(s) => Some(matches!(**s, Stmt::Goto { .. })),
        Body::Words(ws) if ws.is_empty() => None,
        Body::Words(ws) => Some(ws.iter().any(|w| {
            w.addr == grammar::ast::Addr::Letter('M')
                && matches!(words::value_of(w).literal(), Some(m) if [2.0, 30.0, 99.0].contains(&m))
        })),
    }
}

/// `E4001` from 4001 (codes are static strings in diagnostics).
pub fn code_name(code: u16) -> &'static str {
    crate::codes::name(code)
}
