//! Lowering: every block of every linked program into bytecode.
//!
//! NC blocks become `word`/`wordk` instructions followed by `exec` (the VM
//! hands the words to the NC kernel); macro statements become register
//! arithmetic and jumps; M98/M99/G65/G66 become calls and returns.

use crate::expr::ExprGen;
use crate::link::{self, Program, Unit};
use crate::words::{self, Call, WordValue};
use grammar::ast::{Block, Body, Cond, Expr, Stmt};
use grammar::diag::LineHint;
use grammar::{Diagnostic, SourceFile, Span};
use isa::{Instr, Module, SourceLoc};
use nc::Machine;

/// A diagnostic with the index of its unit (source file).
pub type FileDiag = (usize, Diagnostic);

pub struct Gen<'a> {
    pub units: &'a [Unit],
    pub files: &'a [SourceFile],
    pub programs: &'a [Program],
    pub machine: &'a Machine,
    pub optimize: bool,
    pub module: Module,
    consts: crate::consts::ConstIndex,
    pub diags: Vec<FileDiag>,
    pub unit: usize,
    loc: SourceLoc,
    /// The line of the last location, where the next one is looked for
    /// first (see `SourceFile::line_col_near`), and the unit it is in.
    line_hint: (usize, LineHint),
    pub expr: ExprGen,
    /// The number of the program being lowered.
    program_number: u32,
    /// G70–G73 profiles: block starts and jumps past nf.
    pub(crate) profiles: crate::profile::Profiles,
    /// Scratch for the literal check of each block (filled in place).
    parsed: nc::block::Parsed,
}

/// An open DO loop of the program being lowered.
struct Loop {
    label: u32,
    id: u32,
    start: u32,
    exits: Vec<usize>,
    span: Span,
}

/// A literal jump waiting for its target.
struct Pending {
    at: usize,
    seq: u32,
    span: Span,
    loops: Vec<u32>,
}

/// Per-program lowering state.
#[derive(Default)]
struct ProgState {
    loops: Vec<Loop>,
    next_loop: u32,
    gotos: Vec<Pending>,
    /// (sequence number, pc, loop ids open at that block).
    seqs: Vec<(u32, u32, Vec<u32>, Span)>,
    /// Where the last `/n` block's guard goes on.
    join: Option<u32>,
}

impl<'a> Gen<'a> {
    pub fn new(
        units: &'a [Unit],
        files: &'a [SourceFile],
        programs: &'a [Program],
        machine: &'a Machine,
        optimize: bool,
    ) -> Gen<'a> {
        // A block of words is an instruction per word and one to run it,
        // and a few new constants: room for that spares the copies of
        // growing tables (and a count of the words costs little beside).
        let (blocks, instrs) = sizes(units, programs);
        let module = Module {
            machine: machine.compile_keys(),
            code: Vec::with_capacity(instrs),
            consts: Vec::with_capacity(2 * blocks),
            ..Module::default()
        };
        Gen {
            units,
            files,
            programs,
            machine,
            optimize,
            module,
            consts: Default::default(),
            diags: Vec::new(),
            unit: 0,
            loc: SourceLoc::default(),
            line_hint: (0, LineHint::default()),
            expr: ExprGen::default(),
            program_number: 0,
            profiles: Default::default(),
            parsed: Default::default(),
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

    pub fn emit(&mut self, instr: Instr) -> usize {
        self.module.code.push(instr);
        self.module.lines.push(self.loc);
        self.module.code.len() - 1
    }

    pub fn pc(&self) -> u32 {
        self.module.code.len() as u32
    }

    pub fn konst(&mut self, v: f64) -> u32 {
        self.consts.index(&mut self.module.consts, v)
    }

    pub fn string(&mut self, s: &str) -> u32 {
        if let Some(i) = self.module.strings.iter().position(|t| t == s) {
            return i as u32;
        }
        self.module.strings.push(s.to_string());
        (self.module.strings.len() - 1) as u32
    }

    pub(crate) fn set_loc(&mut self, span: Span) {
        if self.line_hint.0 != self.unit {
            self.line_hint = (self.unit, LineHint::default());
        }
        let (line, col) = self.files[self.unit].line_col_near(span.start, &mut self.line_hint.1);
        self.loc = SourceLoc {
            file: self.unit as u16,
            line: line as u32,
            col: col as u32,
        };
    }

    /// The program table index of program `number`.
    pub fn program_index(&self, number: u32) -> Option<u32> {
        self.programs
            .iter()
            .position(|p| p.number == number)
            .map(|i| i as u32)
    }

    /// Lowers every program; `presets` are `-D` assignments run first.
    pub fn lower_all(&mut self, presets: &[(u32, f64)]) {
        for (i, prog) in self.programs.iter().enumerate() {
            self.unit = prog.unit;
            self.program_number = prog.number;
            self.set_loc(prog.span);
            let entry = self.pc();
            if i == 0 {
                for &(var, value) in presets {
                    let k = self.konst(value);
                    self.emit(Instr::LoadK { dst: 0, k });
                    self.emit(Instr::StoreVar { var, src: 0 });
                    self.expr.touch(1);
                }
            }
            let seqs = self.lower_program(prog, i == 0);
            let end = self.pc();
            self.module.programs.push(isa::Program {
                number: prog.number,
                entry,
                end,
                seqs,
            });
        }
        self.module.num_regs = self.expr.max_regs().max(1);
    }

    fn lower_program(&mut self, prog: &Program, main: bool) -> Vec<(u32, u32)> {
        let mut st = ProgState::default();
        self.expr.forget_all();
        let entry_pc = self.pc();
        let unit = &self.units[prog.unit];
        let mut data_setting = crate::data_setting::Checker::default();
        for &line in &prog.blocks {
            crate::profile::block_start(self, line);
            let Some(block) = link::block(unit, line) else {
                continue;
            };
            self.set_loc(block.span);
            crate::profile::count_cycle(self, block);
            data_setting.block(self, block);
            if let Some(seq) = block.seq {
                // A block with a number may be a jump target.
                self.expr.forget_all();
                let loops = st.loops.iter().map(|l| l.id).collect();
                st.seqs.push((seq.number, self.pc(), loops, block.span));
            }
            // A `/n` block is kept behind a guard: the switch is the
            // operator's, read when the block is (docs/language.md).
            let guard = block.delete.map(|d| {
                self.emit(Instr::SkipBlock {
                    switch: d.switch,
                    target: 0,
                })
            });
            self.expr.reset();
            match &block.body {
                Body::Words(_) => self.lower_words(block, &mut st),
                Body::Stmt(s) => self.lower_stmt(s, block, &mut st),
            }
            if let Some(at) = guard {
                st.join = Some(self.end_guard(at));
            }
        }
        // Running off the end: the main program halts, a subprogram
        // returns as if M99 (W101).
        let end_span = prog
            .blocks
            .last()
            .and_then(|&l| link::block(unit, l))
            .map_or(prog.span, |b| b.span);
        self.set_loc(end_span);
        if !ends_explicitly(unit, prog) {
            let what = if main {
                "the main program ends"
            } else {
                "the subprogram returns as if M99"
            };
            self.warn(
                "W101",
                end_span,
                format!(
                    "O{:04} runs off its last block without M02, M30 or M99: {what}",
                    prog.number
                ),
            );
        }
        crate::profile::program_end(self, prog);
        // (A skipped last block goes on past its code: something must be
        // there.)
        let ends = matches!(self.module.code.last(), Some(Instr::Ret | Instr::Halt))
            && self.pc() > entry_pc
            && st.join != Some(self.pc());
        if !ends || !st.gotos.is_empty() || !st.seqs.is_empty() {
            self.emit(if main { Instr::Halt } else { Instr::Ret });
        }
        for open in std::mem::take(&mut st.loops) {
            self.error(
                "E2014",
                open.span,
                format!("DO {} has no END {}", open.label, open.label),
            );
        }
        self.resolve_gotos(&mut st);
        let mut seqs: Vec<(u32, u32)> = st.seqs.iter().map(|(n, pc, _, _)| (*n, *pc)).collect();
        seqs.sort();
        seqs
    }

    fn resolve_gotos(&mut self, st: &mut ProgState) {
        // Each N number's first block and whether it recurs, found in one
        // pass: a search of all blocks per GOTO was quadratic in a long
        // chain of GOTOs.
        let mut first: crate::hash::IntMap<u32, (usize, bool)> = Default::default();
        for (i, (n, ..)) in st.seqs.iter().enumerate() {
            first
                .entry(*n)
                .and_modify(|(_, again)| *again = true)
                .or_insert((i, false));
        }
        for g in std::mem::take(&mut st.gotos) {
            let found = first.get(&g.seq).map(|&(i, again)| (&st.seqs[i], again));
            let Some(((_, pc, loops, _), again)) = found else {
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
                self.warn(
                    "W103",
                    g.span,
                    format!("N{} occurs more than once: the first block is used", g.seq),
                );
            }
            if !loops.iter().all(|id| g.loops.contains(id)) {
                self.error(
                    "E2015",
                    g.span,
                    format!("GOTO {} jumps into a DO loop from outside it", g.seq),
                );
                continue;
            }
            let target = *pc;
            match &mut self.module.code[g.at] {
                Instr::Jump { target: t } | Instr::JumpIfNot { target: t, .. } => *t = target,
                _ => {}
            }
        }
    }

    /// Points the block-skip guard at `at` past the block just lowered;
    /// returns that pc. Both ways meet there, so nothing the block set is
    /// known after it.
    pub(crate) fn end_guard(&mut self, at: usize) -> u32 {
        let pc = self.pc();
        if let Some(Instr::SkipBlock { target, .. }) = self.module.code.get_mut(at) {
            *target = pc;
        }
        self.expr.forget_all();
        pc
    }

    fn lower_stmt(&mut self, s: &Stmt, block: &Block, st: &mut ProgState) {
        match s {
            Stmt::Assign { target, value, .. } => self.assign(target, value, block),
            Stmt::Goto { target, .. } => self.goto(target, None, st),
            Stmt::IfGoto { cond, target, .. } => {
                let c = self.cond(cond);
                self.goto(target, c, st);
            }
            Stmt::IfThen { cond, then, .. } => {
                let Some(c) = self.cond(cond) else { return };
                let skip = self.emit(Instr::JumpIfNot { cond: c, target: 0 });
                let before = self.expr.snapshot();
                self.lower_stmt(then, block, st);
                // The assignment may not have happened.
                self.expr.restore_minus_changes(before);
                let here = self.pc();
                if let Instr::JumpIfNot { target, .. } = &mut self.module.code[skip] {
                    *target = here;
                }
            }
            Stmt::While { cond, label, span } => {
                self.expr.forget_all();
                let start = self.pc();
                let Some(c) = self.cond(cond) else { return };
                let exit = self.emit(Instr::JumpIfNot { cond: c, target: 0 });
                self.open_loop(label.value, start, vec![exit], *span, label.span, st);
            }
            Stmt::Do { label, span } => {
                self.expr.forget_all();
                let start = self.pc();
                self.open_loop(label.value, start, Vec::new(), *span, label.span, st);
            }
            Stmt::End { label, span } => {
                self.close_loop(label.value, *span, st);
                self.expr.forget_all();
            }
        }
    }

    fn open_loop(
        &mut self,
        label: u32,
        start: u32,
        exits: Vec<usize>,
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
        if st.loops.iter().any(|l| l.label == label) {
            self.error(
                "E2014",
                span,
                format!("DO {label} is already open: nested loops need different labels"),
            );
            return;
        }
        if st.loops.len() == 3 {
            self.error("E2014", span, "loops nest at most three deep");
            return;
        }
        st.next_loop += 1;
        st.loops.push(Loop {
            label,
            id: st.next_loop,
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
        let Some(open) = st.loops.pop() else {
            self.error("E2014", span, format!("END {label} without a DO {label}"));
            return;
        };
        if open.label != label {
            self.error(
                "E2014",
                span,
                format!("END {label} closes DO {}: loops are crossed", open.label),
            );
            return;
        }
        self.emit(Instr::Jump { target: open.start });
        let here = self.pc();
        for at in open.exits {
            if let Instr::JumpIfNot { target, .. } = &mut self.module.code[at] {
                *target = here;
            }
        }
    }

    /// `GOTO n` (conditional when `cond` holds the register of the test).
    fn goto(&mut self, target: &Expr, cond: Option<u8>, st: &mut ProgState) {
        let skip = cond.map(|c| self.emit(Instr::JumpIfNot { cond: c, target: 0 }));
        match self.expr.constant(target) {
            Some(Ok(n)) => {
                let n = nc::block::round_half_away(n);
                if !(0.0..=99999.0).contains(&n) {
                    self.error(
                        "E2010",
                        target.span(),
                        format!("GOTO {n}: sequence numbers are 1…99999"),
                    );
                } else {
                    let at = self.emit(Instr::Jump { target: 0 });
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
                if let Some(r) = self.expr_reg(target) {
                    self.emit(Instr::GotoSeq { seq: r });
                }
            }
        }
        if let Some(at) = skip {
            let here = self.pc();
            if let Instr::JumpIfNot { target, .. } = &mut self.module.code[at] {
                *target = here;
            }
        }
    }

    fn assign(&mut self, target: &grammar::ast::VarRef, value: &Expr, block: &Block) {
        let Some(src) = self.expr_reg(value) else {
            return;
        };
        if let Some(c) = block.comments.first() {
            let s = self.string(&c.text);
            self.emit(Instr::SetMsg { s });
        } else if matches!(self.expr.constant(&target.index), Some(Ok(v)) if v == 3000.0 || v == 3006.0)
        {
            let s = self.string("");
            self.emit(Instr::SetMsg { s });
        }
        match self.expr.constant(&target.index) {
            Some(Ok(n)) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => {
                if n == 0.0 {
                    self.error(
                        "E5007",
                        target.span,
                        "#0 is always vacant and cannot be written",
                    );
                    return;
                }
                self.emit(Instr::StoreVar { var: n as u32, src });
                self.expr.assigned(n as u32, value, self.optimize);
            }
            _ => {
                let Some(idx) = self.expr_reg(&target.index) else {
                    return;
                };
                self.emit(Instr::StoreVarInd { idx, src });
                self.expr.forget_all();
            }
        }
    }

    /// Compiles an expression into a register, reporting folding findings.
    pub fn expr_reg(&mut self, e: &Expr) -> Option<u8> {
        let mut expr = std::mem::take(&mut self.expr);
        let r = expr.compile(self, e);
        self.expr = expr;
        r
    }

    fn cond(&mut self, c: &Cond) -> Option<u8> {
        let mut expr = std::mem::take(&mut self.expr);
        let r = expr.cond(self, c);
        self.expr = expr;
        r
    }

    fn lower_words(&mut self, block: &Block, st: &mut ProgState) {
        let _ = st;
        let Body::Words(ws) = &block.body else { return };
        let table = self.machine.r#macro.g_code_macros;
        if let Some(call) = words::g_code_macro(ws, &table, self.program_number) {
            match call {
                Ok(split) => self.lower_split(block, &split),
                Err(d) => self.diags.push((self.unit, d)),
            }
            return;
        }
        match words::classify(ws) {
            Ok(split) => self.lower_split(block, &split),
            Err(d) => self.diags.push((self.unit, d)),
        }
    }

    fn lower_split(&mut self, block: &Block, split: &words::Split<'_>) {
        if let Err(e) = crate::check::literal_block(self.machine, &split.nc, &mut self.parsed) {
            self.error(code_name(e.code), block.span, e.message);
            return;
        }
        let after = crate::profile::before_exec(self, block, split);
        // A block whose words are all known now (literals, or folded
        // values) is one typed block: a record of its words, in order,
        // and one `block` instruction at the block's place.
        let mut known: smallvec::SmallVec<[isa::BlockWord; 8]> = smallvec::SmallVec::new();
        let all_known = split.nc.iter().all(|w| match w.value {
            WordValue::Literal(value, flags) => {
                known.push(isa::BlockWord {
                    addr: w.addr,
                    value,
                    flags,
                });
                true
            }
            WordValue::Expr(e) => match self.expr.known_value(e).filter(|_| self.optimize) {
                // A vacant value leaves the word out.
                Some(v) if v.is_nan() => true,
                Some(value) => {
                    known.push(isa::BlockWord {
                        addr: w.addr,
                        value,
                        flags: 0,
                    });
                    true
                }
                None => false,
            },
        });
        let typed = all_known.then(|| self.module.push_block(&known)).flatten();
        for w in split.nc.iter().filter(|_| typed.is_none()) {
            self.set_loc(w.span);
            match w.value {
                WordValue::Literal(v, flags) => {
                    let k = self.konst(v);
                    self.emit(Instr::WordK {
                        addr: w.addr,
                        k,
                        flags,
                    });
                }
                WordValue::Expr(e) => match self.expr.known_value(e).filter(|_| self.optimize) {
                    // Folded: a computed value (no decimal-point rule);
                    // a vacant one leaves the word out.
                    Some(v) if v.is_nan() => {}
                    Some(v) => {
                        let k = self.konst(v);
                        self.emit(Instr::WordK {
                            addr: w.addr,
                            k,
                            flags: 0,
                        });
                    }
                    None => {
                        if let Some(src) = self.expr_reg(e) {
                            self.emit(Instr::Word { addr: w.addr, src });
                        }
                    }
                },
            }
        }
        self.warn_unlisted_m(split);
        crate::lint::block(self, split);
        self.set_loc(block.span);
        if !split.nc.is_empty() {
            if let Some(c) = block.comments.first() {
                let s = self.string(&c.text);
                self.emit(Instr::SetMsg { s });
            }
            self.emit(match typed {
                Some(rec) => Instr::Block { rec },
                None => Instr::Exec { flags: 0 },
            });
            // G31 writes the skip position into #995–#999.
            for var in 995..=999 {
                self.expr.forget(var);
            }
            // A G10 L52 read writes its variable.
            crate::data_setting::forget_read(&mut self.expr, split);
        }
        crate::profile::after_exec(self, after);
        if let Some(call) = &split.call {
            crate::calls::lower_call(self, call.clone(), block.span);
            // The called program may change any variable.
            self.expr.forget_all();
        }
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

    pub fn value_reg(&mut self, v: &WordValue<'_>) -> Option<u8> {
        match v {
            WordValue::Literal(x, _) => {
                let k = self.konst(*x);
                let r = self.expr.alloc();
                self.emit(Instr::LoadK { dst: r, k });
                Some(r)
            }
            WordValue::Expr(e) => self.expr_reg(e),
        }
    }

    pub fn call_kind(&self, c: &Call<'_>) -> &'static str {
        c.kind_name()
    }
}

/// The programs' blocks, and about the instructions they lower to: one
/// per word and one to run the block (statements take a few more, and
/// are rare).
fn sizes(units: &[Unit], programs: &[Program]) -> (usize, usize) {
    let mut instrs = 0;
    let mut blocks = 0;
    for prog in programs {
        blocks += prog.blocks.len();
        let Some(unit) = units.get(prog.unit) else {
            continue;
        };
        for b in prog.blocks.iter().filter_map(|&l| link::block(unit, l)) {
            instrs += match &b.body {
                Body::Words(ws) => ws.len() + 1,
                Body::Stmt(_) => 4,
            };
        }
    }
    (blocks, instrs + 2 * programs.len())
}

/// Does the program's last block end it (M02, M30, M99 or a GOTO)?
fn ends_explicitly(unit: &Unit, prog: &Program) -> bool {
    let Some(last) = prog
        .blocks
        .iter()
        .rev()
        .filter_map(|&l| link::block(unit, l))
        .find(|b| match &b.body {
            Body::Words(ws) => !ws.is_empty(),
            Body::Stmt(_) => true,
        })
    else {
        return false;
    };
    match &last.body {
        Body::Stmt(s) => matches!(**s, Stmt::Goto { .. }),
        Body::Words(ws) => ws.iter().any(|w| {
            w.addr == grammar::ast::Addr::Letter('M')
                && matches!(words::value_of(w).literal(), Some(m) if [2.0, 30.0, 99.0].contains(&m))
        }),
    }
}

/// `E4001` from 4001 (codes are static strings in diagnostics).
pub fn code_name(code: u16) -> &'static str {
    crate::codes::name(code)
}
