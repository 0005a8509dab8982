//! Pass `emit`: the IR into bytecode.
//!
//! Blocks are laid out in the IR's layout order; a fall-through edge adds
//! no code, every jump is a `Jump` (the IR says which edges jump). NC
//! blocks become `word`/`wordk` instructions and `exec` (the VM hands the
//! words to the kernel); expressions become register arithmetic. Registers
//! are a stack per statement: a statement's first operation or terminator
//! (`Loc::fresh`) starts again at register 0, and the values computed
//! within a statement stay in their registers until it ends.

use crate::build::FileDiag;
use crate::consts::ConstIndex;
use crate::ir::{self, CallKind, Callee, Count, Expr, Function, Handle, Loc, Op, Terminator};
use crate::profile::PROFILE;
use grammar::diag::LineHint;
use grammar::{Diagnostic, SourceFile, Span};
use isa::block::Records;
use isa::{Instr, SourceLoc};
use nc::value::Bin;
use std::collections::HashMap;

/// Emits a validated module.
pub fn emit(
    ir: &ir::Module,
    files: &[SourceFile],
    machine: &nc::Machine,
) -> (isa::Module, Vec<FileDiag>) {
    let (constants, instrs) = sizes(ir);
    let room = Room {
        constants,
        instrs,
        records: 0,
    };
    let mut e = Emitter::new(files, machine, room);
    e.sync_strings(&ir.strings);
    for f in &ir.functions {
        e.function(f);
    }
    e.finish()
}

/// About the constants and instructions of a module: two constants per
/// operation (most are NC blocks: a new coordinate or two), an
/// instruction per word, operation and terminator.
fn sizes(ir: &ir::Module) -> (usize, usize) {
    ir.functions.iter().fold((0, 0), |(k, n), f| {
        (
            k + 2 * f.ops.len(),
            n + f.words.len() + f.ops.len() + f.blocks.len(),
        )
    })
}

/// A typed word as a key: address, value bits, flags.
type RecordKey = (u8, u64, u8);

/// The register stack of the statement being emitted.
#[derive(Default)]
struct Regs {
    next: u16,
    max: u16,
    overflow: bool,
}

impl Regs {
    fn alloc(&mut self) -> u8 {
        if self.next >= 255 {
            self.overflow = true;
            return 254;
        }
        let r = self.next as u8;
        self.next += 1;
        self.max = self.max.max(self.next);
        r
    }

    fn free_to(&mut self, r: u8) {
        self.next = r as u16 + 1;
    }
}

pub(crate) struct Emitter<'a> {
    /// The IR's strings (copied: a module built in chunks adds to them).
    ir_strings: Vec<String>,
    files: &'a [SourceFile],
    module: isa::Module,
    /// The module's `blocks`, apart from it until it is finished: a chunk
    /// at a time, the stream walks them as they come (`walk_records`).
    records: Records,
    consts: ConstIndex,
    /// IR string → module string.
    strings: HashMap<u32, u32>,
    /// The records of the typed profile blocks by their words: the block
    /// where a profile block stands shares its record.
    profile_recs: HashMap<Vec<RecordKey>, u32>,
    loc: SourceLoc,
    /// The line of the last location, where the next one is looked for
    /// first (see `SourceFile::line_col_near`), and the file it is in.
    hint: (usize, LineHint),
    regs: Regs,
    diags: Vec<FileDiag>,
    /// The source of what is being emitted (for E1014).
    file: usize,
    span: Span,
}

/// What the module is expected to hold: room made for it up front spares
/// copying a large table as it grows (and holding it twice meanwhile).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Room {
    pub constants: usize,
    pub instrs: usize,
    /// Bytes of typed-block records.
    pub records: usize,
}

/// A program being emitted: where it starts, its sequence numbers (each
/// with its pc and DO loop) and its loops (`ir::Function::loops`).
pub(crate) struct OpenProgram {
    entry: u32,
    seqs: Vec<(u32, u32, u32)>,
    loops: Vec<u32>,
}

/// A jump whose target block's pc is not known yet.
struct Fixup {
    at: usize,
    target: Handle<ir::Block>,
}

impl<'a> Emitter<'a> {
    pub(crate) fn new(files: &'a [SourceFile], machine: &nc::Machine, room: Room) -> Self {
        Emitter {
            ir_strings: Vec::new(),
            files,
            module: isa::Module {
                machine: machine.compile_keys(),
                code: Vec::with_capacity(room.instrs),
                consts: Vec::with_capacity(room.constants),
                ..isa::Module::default()
            },
            records: Records::with_capacity(room.records),
            consts: ConstIndex::default(),
            strings: HashMap::new(),
            profile_recs: HashMap::new(),
            loc: SourceLoc::default(),
            hint: (usize::MAX, LineHint::default()),
            regs: Regs::default(),
            diags: Vec::new(),
            file: 0,
            span: Span::default(),
        }
    }

    /// Takes the IR strings added since the last call.
    pub(crate) fn sync_strings(&mut self, strings: &[String]) {
        let new = strings.get(self.ir_strings.len()..).unwrap_or_default();
        self.ir_strings.extend_from_slice(new);
    }

    /// The module, and the diagnostics found on the way.
    pub(crate) fn finish(self) -> (isa::Module, Vec<FileDiag>) {
        let (mut module, records, diags) = self.finish_walked();
        module.blocks = records.into_bytes();
        (module, diags)
    }

    /// The module without its `blocks`, which are in the records, with
    /// the walk of them done so far (for `isa::Module::verify_with`), and
    /// the diagnostics found on the way.
    pub(crate) fn finish_walked(mut self) -> (isa::Module, Records, Vec<FileDiag>) {
        self.module.num_regs = self.regs.max.max(1);
        (self.module, self.records, self.diags)
    }

    /// Checks the records emitted since the last call, as the verifier
    /// would; `None` on a bad one (the compiler's own fault).
    pub(crate) fn walk_records(&mut self) -> Option<()> {
        self.records.walk().ok()
    }

    fn emit(&mut self, instr: Instr) -> usize {
        self.module.code.push(instr);
        self.module.lines.push(self.loc);
        self.module.code.len() - 1
    }

    fn pc(&self) -> u32 {
        self.module.code.len() as u32
    }

    fn konst(&mut self, v: f64) -> u32 {
        self.consts.index(&mut self.module.consts, v)
    }

    fn string(&mut self, id: ir::StrId) -> u32 {
        if let Some(&s) = self.strings.get(&id.0) {
            return s;
        }
        let text = self
            .ir_strings
            .get(id.0 as usize)
            .cloned()
            .unwrap_or_default();
        let s = self.module.strings.len() as u32;
        self.module.strings.push(text);
        self.strings.insert(id.0, s);
        s
    }

    fn set_loc(&mut self, file: u16, span: Span) {
        let file = file as usize;
        if self.hint.0 != file {
            self.hint = (file, LineHint::default());
        }
        let (line, col) = match self.files.get(file) {
            Some(f) => f.line_col_near(span.start, &mut self.hint.1),
            None => (0, 0),
        };
        self.loc = SourceLoc {
            file: file as u16,
            line: line as u32,
            col: col as u32,
        };
        self.file = file;
        self.span = span;
    }

    /// Where an operation or terminator comes from; a new statement starts
    /// its registers afresh.
    fn at(&mut self, loc: Loc) {
        if loc.fresh {
            self.regs.next = 0;
        }
        self.set_loc(loc.file, loc.span);
    }

    fn function(&mut self, f: &Function) {
        let mut program = self.open_program();
        self.part(f, &mut program);
        self.close_program(f.number, program);
    }

    /// A program starts here.
    pub(crate) fn open_program(&self) -> OpenProgram {
        OpenProgram {
            entry: self.pc(),
            seqs: Vec::new(),
            loops: Vec::new(),
        }
    }

    /// Emits a function, or a part of one (`crate::stream`): its jumps
    /// stay within the part, and an open last block goes on in the code
    /// of the next part.
    pub(crate) fn part(&mut self, f: &Function, program: &mut OpenProgram) {
        program.loops.clone_from(&f.loops);
        let seqs = &mut program.seqs;
        let mut starts = vec![0u32; f.blocks.len()];
        let mut fixups: Vec<Fixup> = Vec::new();
        for &b in &f.layout {
            if let Some(s) = starts.get_mut(b.index()) {
                *s = self.pc();
            }
            let block = &f.blocks[b];
            for &op in &block.ops {
                if let Some(&loc) = f.op_locs.get(op.index()) {
                    self.at(loc);
                }
                self.op(f, &f.ops[op], seqs);
            }
            match &block.term {
                Some(Terminator::Follow(_) | Terminator::Ended) | None => {}
                Some(t) => {
                    if let Some(&loc) = f.term_locs.get(b.index()) {
                        self.at(loc);
                    }
                    self.terminator(f, t, &mut fixups);
                }
            }
        }
        for Fixup { at, target } in fixups {
            let pc = starts.get(target.index()).copied().unwrap_or(0);
            if let Some(
                Instr::Jump { target: t }
                | Instr::Goto { target: t }
                | Instr::JumpIfNot { target: t, .. }
                | Instr::SkipBlock { target: t, .. },
            ) = self.module.code.get_mut(at)
            {
                *t = pc;
            }
        }
    }

    /// The program ends here: into the program table.
    pub(crate) fn close_program(&mut self, number: u32, program: OpenProgram) {
        let OpenProgram {
            entry,
            mut seqs,
            loops,
        } = program;
        seqs.sort();
        // A number repeated on a block of no code of its own (`N5` alone,
        // then `N5 G00 X2`) names one pc twice: one entry says it.
        seqs.dedup_by_key(|&mut (n, pc, _)| (n, pc));
        let mut seq_loops: Vec<u32> = seqs.iter().map(|s| s.2).collect();
        if seq_loops.iter().all(|&l| l == 0) {
            seq_loops.clear();
        }
        let end = self.pc();
        self.module.programs.push(isa::Program {
            number,
            entry,
            end,
            seqs: seqs.iter().map(|&(n, pc, _)| (n, pc)).collect(),
            loops,
            seq_loops,
        });
    }

    fn op(&mut self, f: &Function, op: &Op, seqs: &mut Vec<(u32, u32, u32)>) {
        match op {
            Op::Seq(n, in_loop) => seqs.push((*n, self.pc(), *in_loop)),
            Op::Nc(nc) => self.nc_block(f, nc),
            Op::Assign { target, value, msg } => {
                let src = self.expr(f, *value);
                if let Some(m) = msg {
                    let s = self.string(*m);
                    self.emit(Instr::SetMsg { s });
                }
                match target {
                    ir::VarTarget::Direct(var) => {
                        self.emit(Instr::StoreVar { var: *var, src });
                    }
                    ir::VarTarget::Indirect(i) => {
                        let idx = self.expr(f, *i);
                        self.emit(Instr::StoreVarInd { idx, src });
                    }
                }
            }
            Op::MacroA {
                op,
                dst,
                j,
                k,
                value,
                msg,
            } => {
                // R is read even where the operation ignores it, after Q,
                // as the control reads every address of the block: a
                // fault there (`R#[0-1]`) is the block's alarm.
                let ignored = !op.reads_r() && !matches!(f.exprs.get(*k), Some(Expr::Const(_)));
                if ignored {
                    self.expr(f, *j);
                    self.expr(f, *k);
                }
                let src = self.expr(f, *value);
                if let Some(m) = msg {
                    let s = self.string(*m);
                    self.emit(Instr::SetMsg { s });
                }
                self.emit(Instr::StoreVar { var: *dst, src });
            }
            Op::Alarm { code, msg } => {
                let msg = self.string(*msg);
                self.emit(Instr::Alarm { code: *code, msg });
            }
            Op::UserAlarm { q, msg } => {
                let q = self.expr(f, *q);
                let msg = self.string(*msg);
                self.emit(Instr::UserAlarm { q, msg });
            }
            Op::ModalCancel => {
                self.emit(Instr::ModalCancel);
            }
            Op::Charge => {
                self.emit(Instr::Charge);
            }
        }
    }

    /// One NC block: its words, each located at its own source, then the
    /// comment's message and `exec` at the block (`execmove` for a typed
    /// move). A block whose words are all known is one typed block
    /// instead: a record of its words, in order, and one `block`
    /// instruction (`move` for a typed move, `profile` for a G70–G73
    /// profile block, which has no use for the message).
    fn nc_block(&mut self, f: &Function, nc: &ir::NcBlock) {
        let (file, span) = (self.loc.file, self.span);
        let typed = self.typed_block(f.words_of(nc), nc.kind);
        // (A typed block's words are in its record: none is emitted.)
        let words = match typed {
            None => f.words_of(nc),
            Some(_) => &[],
        };
        for (w, &at) in words.iter().zip(f.word_spans_of(nc)) {
            self.set_loc(file, at);
            match w.value() {
                ir::WordValue::Const(v, flags) => {
                    let k = self.konst(v);
                    self.emit(Instr::WordK {
                        addr: w.addr,
                        k,
                        flags,
                    });
                }
                ir::WordValue::Expr(e) => {
                    let src = self.expr(f, e);
                    self.emit(Instr::Word { addr: w.addr, src });
                }
            }
        }
        self.set_loc(file, span);
        let profile = nc.kind == ir::NcKind::Profile;
        if let Some(m) = nc.msg.filter(|_| !profile || typed.is_none()) {
            let s = self.string(m);
            self.emit(Instr::SetMsg { s });
        }
        self.emit(match (typed, nc.kind) {
            (Some(rec), ir::NcKind::Run) => Instr::Block { rec },
            (Some(rec), ir::NcKind::Move(_)) => Instr::Move { rec },
            (Some(rec), ir::NcKind::Profile) => Instr::Profile { rec },
            (None, ir::NcKind::Run) => Instr::Exec { flags: 0 },
            (None, ir::NcKind::Move(_)) => Instr::ExecMove,
            (None, ir::NcKind::Profile) => Instr::Exec { flags: PROFILE },
        });
    }

    /// The record of a block whose words are all constants, if they fit
    /// one (`isa::block`); `None` leaves the block in word form. A profile
    /// block's record is remembered, and a block with the same words
    /// (the profile block where it stands) names it again.
    fn typed_block(&mut self, words: &[ir::Word], kind: ir::NcKind) -> Option<u32> {
        let known = words
            .iter()
            .map(|w| match w.value() {
                ir::WordValue::Const(value, flags) => Some(isa::BlockWord {
                    addr: w.addr,
                    value,
                    flags,
                }),
                _ => None,
            })
            .collect::<Option<smallvec::SmallVec<[isa::BlockWord; 8]>>>()?;
        let known = &known[..];
        if kind.runs_here() && self.profile_recs.is_empty() {
            return self.records.push(known);
        }
        let key: Vec<RecordKey> = known
            .iter()
            .map(|w| (w.addr, w.value.to_bits(), w.flags))
            .collect();
        if let Some(&rec) = self.profile_recs.get(&key) {
            return Some(rec);
        }
        let rec = self.records.push(known)?;
        if kind == ir::NcKind::Profile {
            self.profile_recs.insert(key, rec);
        }
        Some(rec)
    }

    /// A computed GOTO to the number in `seq`, from inside DO loop
    /// `inside` (0: none; the VM then needs no loop to check against).
    fn goto_seq(&mut self, seq: u8, inside: u32) {
        self.emit(match inside {
            0 => Instr::GotoSeq { seq },
            _ => Instr::GotoSeqIn { seq, inside },
        });
    }

    fn terminator(&mut self, f: &Function, t: &Terminator, fixups: &mut Vec<Fixup>) {
        let mut jump = |e: &mut Self, instr: Instr, target: Handle<ir::Block>| {
            let at = e.emit(instr);
            fixups.push(Fixup { at, target });
        };
        match t {
            Terminator::Follow(_) | Terminator::Ended => {}
            Terminator::Jump(b) => jump(self, Instr::Jump { target: 0 }, *b),
            Terminator::GotoKnown(b) => jump(self, Instr::Goto { target: 0 }, *b),
            Terminator::Branch {
                cond, otherwise, ..
            } => {
                let c = self.expr(f, *cond);
                jump(self, Instr::JumpIfNot { cond: c, target: 0 }, *otherwise);
            }
            Terminator::Skip { switch, skip, .. } => jump(
                self,
                Instr::SkipBlock {
                    switch: *switch,
                    target: 0,
                },
                *skip,
            ),
            Terminator::Goto { seq, inside } => {
                let seq = self.expr(f, *seq);
                self.goto_seq(seq, *inside);
            }
            Terminator::GotoIf {
                seq,
                inside,
                op,
                j,
                k,
                ..
            } => {
                let seq = self.expr(f, *seq);
                let (j, k) = (self.expr(f, *j), self.expr(f, *k));
                let c = self.regs.alloc();
                self.emit(Instr::Cmp {
                    dst: c,
                    a: j,
                    b: k,
                    op: *op as u8,
                });
                // Past the GOTO, the block charged (the GOTO charges itself
                // when it jumps), then the next block.
                let past = self.pc() + 2;
                self.emit(Instr::JumpIfNot {
                    cond: c,
                    target: past,
                });
                self.goto_seq(seq, *inside);
                self.emit(Instr::Charge);
            }
            Terminator::Call { call, .. } => self.call(f, call),
            Terminator::Return { seq: None } => {
                self.emit(Instr::Ret);
            }
            Terminator::Return { seq: Some(s) } => {
                let seq = self.expr(f, *s);
                self.emit(Instr::RetSeq { seq });
            }
            Terminator::Halt => {
                self.emit(Instr::Halt);
            }
        }
    }

    fn call(&mut self, f: &Function, call: &ir::Call) {
        match (call.kind, call.callee) {
            (CallKind::Sub, Callee::Program(prog)) => {
                let count = self.count(f, call.count);
                self.emit(Instr::CallSub { prog, count });
            }
            // A computed `P<count:4><program:4>`: the VM splits it (a
            // vacant P is E5009, which arithmetic here would turn into 0).
            (CallKind::Sub, Callee::Dynamic(p)) if call.count == Count::Packed => {
                let num = self.expr(f, p);
                self.emit(Instr::CallSubPacked { num });
            }
            (CallKind::Sub, Callee::Dynamic(p)) => {
                let num = self.expr(f, p);
                let count = self.count(f, call.count);
                self.emit(Instr::CallSubDyn { num, count });
            }
            (kind, callee) => {
                let count = self.count(f, call.count);
                for &(var, v) in &call.args {
                    let src = self.expr(f, v);
                    self.emit(Instr::Arg { var, src });
                }
                let modal = kind == CallKind::Modal;
                match callee {
                    Callee::Program(prog) if modal => self.emit(Instr::ModalCall { prog, count }),
                    Callee::Program(prog) => self.emit(Instr::CallMacro { prog, count }),
                    Callee::Dynamic(p) => {
                        let num = self.expr(f, p);
                        match modal {
                            true => self.emit(Instr::ModalCallDyn { num, count }),
                            false => self.emit(Instr::CallMacroDyn { num, count }),
                        }
                    }
                };
            }
        }
    }

    /// The register of a call's count. (`Count::Packed` stands only on a
    /// computed M98, whose `callsubpacked` takes none; the validator
    /// checks: here it would count once.)
    fn count(&mut self, f: &Function, count: Count) -> u8 {
        match count {
            Count::Expr(e) => self.expr(f, e),
            Count::Packed => {
                let one = self.regs.alloc();
                let k = self.konst(1.0);
                self.emit(Instr::LoadK { dst: one, k });
                one
            }
        }
    }

    /// An expression into the next free register; E1014 when the register
    /// file is too small for it.
    fn expr(&mut self, f: &Function, e: Handle<Expr>) -> u8 {
        let r = self.node(f, e);
        if std::mem::take(&mut self.regs.overflow) {
            self.diags.push((
                self.file,
                Diagnostic::error(
                    "E1014",
                    self.span,
                    "expression too deep for the register file",
                ),
            ));
        }
        r
    }

    fn node(&mut self, f: &Function, e: Handle<Expr>) -> u8 {
        match f.exprs[e] {
            Expr::Const(v) => {
                let r = self.regs.alloc();
                let k = self.konst(v);
                self.emit(Instr::LoadK { dst: r, k });
                r
            }
            Expr::Var(var) => {
                let r = self.regs.alloc();
                self.emit(Instr::LoadVar { dst: r, var });
                r
            }
            Expr::VarInd(i) => {
                let idx = self.node(f, i);
                self.emit(Instr::LoadVarInd { dst: idx, idx });
                idx
            }
            Expr::Neg(a) => {
                let a = self.node(f, a);
                self.emit(Instr::Neg { dst: a, a });
                a
            }
            Expr::Binary { op, a, b } => {
                if let Some(r) = self.binary_k(f, op, a, b) {
                    return r;
                }
                let a = self.node(f, a);
                let b = self.node(f, b);
                let dst = a;
                self.emit(match op {
                    Bin::Add => Instr::Add { dst, a, b },
                    Bin::Sub => Instr::Sub { dst, a, b },
                    Bin::Mul => Instr::Mul { dst, a, b },
                    Bin::Div => Instr::Div { dst, a, b },
                    Bin::Mod => Instr::Mod { dst, a, b },
                    Bin::And => Instr::BitAnd { dst, a, b },
                    Bin::Or => Instr::BitOr { dst, a, b },
                    Bin::Xor => Instr::BitXor { dst, a, b },
                });
                self.regs.free_to(dst);
                dst
            }
            Expr::Func { f: func, a } => {
                let a = self.node(f, a);
                self.emit(Instr::Func {
                    dst: a,
                    a,
                    f: func as u8,
                });
                a
            }
            Expr::Atan2 { y, x } => {
                let a = self.node(f, y);
                let b = self.node(f, x);
                self.emit(Instr::Atan2 { dst: a, y: a, x: b });
                self.regs.free_to(a);
                a
            }
            Expr::Compare { op, a, b } => {
                if let Some(&Expr::Const(v)) = f.exprs.get(b) {
                    let a = self.node(f, a);
                    let k = self.konst(v);
                    let op = op as u8;
                    self.emit(Instr::CmpK { dst: a, a, k, op });
                    return a;
                }
                let a = self.node(f, a);
                let b = self.node(f, b);
                self.emit(Instr::Cmp {
                    dst: a,
                    a,
                    b,
                    op: op as u8,
                });
                self.regs.free_to(a);
                a
            }
        }
    }

    /// `a + k`, `a - k`, `a * k`, `a / k` (and `k + a`, `k * a`, which are
    /// the same numbers: IEEE addition and multiplication commute) with
    /// the constant read from the pool; `None` for other operations.
    fn binary_k(&mut self, f: &Function, op: Bin, a: Handle<Expr>, b: Handle<Expr>) -> Option<u8> {
        let konst = |h: Handle<Expr>| match f.exprs.get(h) {
            Some(&Expr::Const(v)) => Some(v),
            _ => None,
        };
        let (reg, v) = match (op, konst(a), konst(b)) {
            (Bin::Add | Bin::Sub | Bin::Mul | Bin::Div, _, Some(v)) => (a, v),
            (Bin::Add | Bin::Mul, Some(v), None) => (b, v),
            _ => return None,
        };
        let a = self.node(f, reg);
        let k = self.konst(v);
        self.emit(match op {
            Bin::Add => Instr::AddK { dst: a, a, k },
            Bin::Sub => Instr::SubK { dst: a, a, k },
            Bin::Mul => Instr::MulK { dst: a, a, k },
            _ => Instr::DivK { dst: a, a, k },
        });
        Some(a)
    }
}
