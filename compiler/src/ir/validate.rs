//! The IR's validator: what `emit` and every later pass rely on.
//!
//! - every handle names an item of its arena, and an expression's
//!   operands come before it (no cycles);
//! - every block is laid out once and ends in one terminator;
//! - jump targets are blocks of the function's layout, and an edge taken
//!   without a jump goes to the next block of the layout;
//! - an operation stands in one block only;
//! - calls name a function of the module or a number looked up at run
//!   time;
//! - NC word ranges and strings are in their tables, and every operation
//!   and block has its source location.

use super::{
    Block, Call, CallKind, Callee, Count, Expr, Function, Handle, Loc, Module, NcBlock, NcKind, Op,
    Terminator, VarTarget, Word, WordValue,
};

/// A fault of the IR, where it was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error {
    pub loc: Loc,
    pub message: String,
}

/// Checks a module; every fault found.
pub fn validate(m: &Module) -> Result<(), Vec<Error>> {
    let mut errors = Vec::new();
    for (i, f) in m.functions.iter().enumerate() {
        let name = format!("O{:04} (function {i})", f.number);
        check(m, f, name, false, &mut errors);
    }
    faults(errors)
}

/// Checks a part of a function built a chunk at a time (`crate::stream`)
/// against the module `m` (its strings). The rules are a function's, but
/// for the end: a part may have no block, and its last block may be open
/// (it goes on into the next part's first one).
pub fn validate_part(m: &Module, f: &Function) -> Result<(), Vec<Error>> {
    let mut errors = Vec::new();
    check(
        m,
        f,
        format!("O{:04} (a part)", f.number),
        true,
        &mut errors,
    );
    faults(errors)
}

fn check(m: &Module, f: &Function, name: String, part: bool, errors: &mut Vec<Error>) {
    Checker {
        m,
        f,
        name,
        errors,
        part,
    }
    .function();
}

fn faults(errors: Vec<Error>) -> Result<(), Vec<Error>> {
    match errors.is_empty() {
        true => Ok(()),
        false => Err(errors),
    }
}

struct Checker<'a> {
    m: &'a Module,
    f: &'a Function,
    name: String,
    errors: &'a mut Vec<Error>,
    /// A part of a function: see [`validate_part`].
    part: bool,
}

impl Checker<'_> {
    fn fail(&mut self, loc: Loc, message: String) {
        self.errors.push(Error {
            loc,
            message: format!("{}: {message}", self.name),
        });
    }

    fn function_loc(&self) -> Loc {
        Loc {
            file: self.f.file,
            fresh: false,
            span: self.f.span,
        }
    }

    fn function(&mut self) {
        let f = self.f;
        let here = self.function_loc();
        if f.op_locs.len() != f.ops.len() {
            self.fail(here, "not every operation has a location".into());
        }
        if f.term_locs.len() != f.blocks.len() {
            self.fail(here, "not every block has a location".into());
        }
        if f.layout.is_empty() && !self.part {
            self.fail(here, "the function has no block".into());
        }
        // Where each block stands in the layout.
        let mut position = vec![None; f.blocks.len()];
        for (i, &b) in f.layout.iter().enumerate() {
            match position.get_mut(b.index()) {
                None => self.fail(
                    here,
                    format!("the layout names block {b:?}, which is not one"),
                ),
                Some(Some(_)) => self.fail(here, format!("block {b:?} is laid out twice")),
                Some(p) => *p = Some(i),
            }
        }
        for (b, p) in f.blocks.iter().zip(&position) {
            if p.is_none() {
                self.fail(here, format!("block {:?} is not laid out", b.0));
            }
        }
        let mut owner = vec![false; f.ops.len()];
        for (i, &b) in f.layout.iter().enumerate() {
            let Some(block) = f.blocks.get(b) else {
                continue;
            };
            let loc = f.term_locs.get(b.index()).copied().unwrap_or(here);
            for &op in &block.ops {
                match owner.get_mut(op.index()) {
                    None => self.fail(
                        loc,
                        format!("block {b:?} names operation {op:?}, which is not one"),
                    ),
                    Some(true) => self.fail(loc, format!("operation {op:?} stands in two blocks")),
                    Some(o) => {
                        *o = true;
                        let op_loc = f.op_locs.get(op.index()).copied().unwrap_or(loc);
                        self.op(&f.ops[op], op_loc);
                    }
                }
            }
            self.terminator(b, block, f.layout.get(i + 1).copied(), &position, loc);
        }
        self.exprs();
    }

    fn expr(&mut self, e: Handle<Expr>, loc: Loc) {
        if !self.f.exprs.contains(e) {
            self.fail(loc, format!("expression {e:?} is not one"));
        }
    }

    /// Operands stand before the expressions that use them.
    fn exprs(&mut self) {
        let f = self.f;
        let here = self.function_loc();
        for (h, e) in f.exprs.iter() {
            let operands: &[Handle<Expr>] = match e {
                Expr::Const(_) | Expr::Var(_) => &[],
                Expr::VarInd(a) | Expr::Neg(a) | Expr::Func { a, .. } => std::slice::from_ref(a),
                Expr::Binary { a, b, .. } | Expr::Compare { a, b, .. } => &[*a, *b],
                Expr::Atan2 { y, x } => &[*y, *x],
            };
            for &o in operands {
                if o >= h {
                    self.fail(
                        here,
                        format!("expression {h:?} uses {o:?}, which does not come before it"),
                    );
                }
            }
        }
    }

    fn op(&mut self, op: &Op, loc: Loc) {
        match op {
            Op::Seq(..) | Op::ModalCancel | Op::Charge => {}
            Op::Nc(nc) => self.nc(nc, loc),
            Op::Assign { target, value, msg } => {
                self.expr(*value, loc);
                if let VarTarget::Indirect(i) = target {
                    self.expr(*i, loc);
                }
                if let Some(s) = msg {
                    self.string(s.0, loc);
                }
            }
            Op::MacroA { j, k, value, .. } => {
                self.expr(*j, loc);
                self.expr(*k, loc);
                self.expr(*value, loc);
            }
            Op::Alarm { msg, .. } => self.string(msg.0, loc),
            Op::UserAlarm { q, msg } => {
                self.expr(*q, loc);
                self.string(msg.0, loc);
            }
        }
    }

    fn string(&mut self, s: u32, loc: Loc) {
        if s as usize >= self.m.strings.len() {
            self.fail(loc, format!("string {s} is not in the table"));
        }
    }

    fn nc(&mut self, nc: &NcBlock, loc: Loc) {
        let (a, b) = nc.words;
        if a > b || b as usize > self.f.words.len() || b as usize > self.f.word_spans.len() {
            self.fail(loc, format!("the words {a}..{b} are not in the table"));
            return;
        }
        for w in &self.f.words[a as usize..b as usize] {
            if let WordValue::Expr(e) = w.value() {
                self.expr(e, loc);
            }
        }
        if let Some(s) = nc.msg {
            self.string(s.0, loc);
        }
        // A move's G code is a constant: computed, it could be any code.
        // (That a move of constants makes a plain move, the module's
        // verifier checks on every compile, at less cost than here, where
        // it held up the chunked path's back end; a move with a computed
        // word the kernel checks as it runs.)
        let words = &self.f.words[a as usize..b as usize];
        let computed_g = |w: &Word| w.addr == nc::words::addr(b'G') && w.constant().is_none();
        if matches!(nc.kind, NcKind::Move(_)) && words.iter().any(computed_g) {
            self.fail(loc, "a typed move with a computed G code".into());
        }
    }

    fn terminator(
        &mut self,
        b: Handle<Block>,
        block: &Block,
        next: Option<Handle<Block>>,
        position: &[Option<usize>],
        loc: Loc,
    ) {
        let Some(t) = &block.term else {
            if !(self.part && next.is_none()) {
                self.fail(loc, format!("block {b:?} has no terminator"));
            }
            return;
        };
        for s in t.successors() {
            if position.get(s.index()).copied().flatten().is_none() {
                self.fail(
                    loc,
                    format!("block {b:?} goes to {s:?}, which is not laid out"),
                );
            }
        }
        if let Some(fall) = t.fall_through() {
            if Some(fall) != next {
                self.fail(
                    loc,
                    format!("block {b:?} goes on into {fall:?}, which is not the next block"),
                );
            }
        }
        match t {
            Terminator::Branch { cond, .. } => self.expr(*cond, loc),
            Terminator::Goto { seq, .. } => self.expr(*seq, loc),
            Terminator::GotoIf { seq, j, k, .. } => {
                for e in [seq, j, k] {
                    self.expr(*e, loc);
                }
            }
            Terminator::Return { seq: Some(s) } => self.expr(*s, loc),
            Terminator::Call { call, .. } => self.call(call, loc),
            Terminator::Follow(_)
            | Terminator::Jump(_)
            | Terminator::GotoKnown(_)
            | Terminator::Skip { .. }
            | Terminator::Return { seq: None }
            | Terminator::Halt
            | Terminator::Ended => {}
        }
    }

    fn call(&mut self, call: &Call, loc: Loc) {
        match call.callee {
            Callee::Program(p) if p as usize >= self.m.functions.len() => {
                self.fail(loc, format!("a call names function {p}, which is not one"))
            }
            Callee::Program(_) => {}
            Callee::Dynamic(e) => self.expr(e, loc),
        }
        match (call.count, call.kind, call.callee) {
            (Count::Expr(e), ..) => self.expr(e, loc),
            (Count::Packed, CallKind::Sub, Callee::Dynamic(_)) => {}
            (Count::Packed, ..) => {
                self.fail(loc, "only a computed M98 P packs its count into P".into())
            }
        }
        if call.kind == CallKind::Sub && !call.args.is_empty() {
            self.fail(loc, "a subprogram call passes no arguments".into());
        }
        for &(_, v) in &call.args {
            self.expr(v, loc);
        }
    }
}
