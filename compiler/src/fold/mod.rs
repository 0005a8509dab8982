//! Pass `fold` (-O1): constant propagation over the control-flow graph.
//!
//! A forward data-flow analysis finds, before each operation, the plain
//! variables whose value is the same on every path that reaches it; then
//! every expression (assignment values, word values, conditions, call
//! operands) whose variables are all known there becomes a constant, and
//! every subexpression of one that is not. A word whose value is known to
//! be vacant is left out of its block, as the VM leaves it out.
//!
//! Build folds the expressions that read no variable (and warns of those
//! that always fault, W116); this pass adds what the variables bring. It
//! replaces the propagation `build` made as it read the blocks, which
//! forgot everything at a numbered block, a loop or a conditional, and
//! did not see that a move under G66 calls the macro, which may change a
//! common variable.
//!
//! Decisions (what is known where):
//! - The main program starts knowing nothing (it runs from wherever the
//!   last program left the memory), and so does a program called from
//!   nowhere; a called program knows what every call of it passes
//!   (`entries`).
//! - Only #1–#33, #100–#199 and #500–#999 are followed; system variables
//!   change behind the program's back.
//! - A numbered block can be entered by a computed GOTO or by a
//!   subprogram's `M99 P`: there it joins what such jumps carry (nothing,
//!   for `M99 P`). Static GOTOs are edges of the graph.
//! - After a call, what its program may write (`writes`) stops being
//!   known: a macro's common variables only (its locals are its own), a
//!   subprogram's locals too (it shares the caller's). G66 changes nothing
//!   where it stands; under it, every NC block may call the macro: the
//!   common variables are forgotten after each one. Whether G66 may be in
//!   force is followed as well; the main program starts with it in force
//!   when the module has a G66.
//! - An NC block writes #995–#999 (G31's skip position) and, for a G10 L52
//!   read (N and R words), the variable R names.
//! - A program whose blocks would between them hold more known values
//!   than `STORED_PER_OP` per operation is not folded (memory stays
//!   proportional to the code); blocks that know the same share one map.
//! - A value whose computation faults stays in the code: the alarm is the
//!   run's, with its line. Where a variable's known value proves it, the
//!   pass warns (W116, as build does for a fault of constants alone); so
//!   it does for a block whose computed words all became constants and
//!   break one of the kernel's rules on words (a G, M or T value, words
//!   that cannot stand together), and for a computed GOTO to a number no
//!   block of the program has.

use crate::build::FileDiag;
use crate::ir::{
    Block, Call, CallKind, Callee, Count, Expr, Function, Handle, Module, NcBlock, Op, Terminator,
    VarTarget, Word, WordValue,
};
use grammar::{Diagnostic, Span};
use nc::error::Alarm;
use nc::value::{self, Bin};
use nc::words::addr;
use nc::{Machine, NcError};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::rc::Rc;

mod entries;
mod writes;

/// Rounds over the layout before the analysis gives up (and folds
/// nothing): far more than the loops of a real program nest.
const MAX_ROUNDS: usize = 64;

/// The analysis of a function may hold this many values per operation,
/// and this many in any case (a few megabytes at most for a long program;
/// a real one holds far fewer: most blocks share their maps).
const STORED_PER_OP: usize = 8;
const STORED_MIN: usize = 1 << 16;

/// Plain variables a program can hold constants in.
fn followed(n: u32) -> bool {
    matches!(n, 1..=33 | 100..=199 | 500..=999)
}

fn common(n: u32) -> bool {
    matches!(n, 100..=199 | 500..=999)
}

/// What is known at a point of the program.
///
/// The map is shared between the points that know the same (most of a
/// program's blocks): it is copied only where something changes.
#[derive(Debug, Clone, PartialEq, Default)]
struct Facts {
    /// Variable → the bits of its value (NaN bits: known vacant).
    vars: Rc<BTreeMap<u32, u64>>,
    /// Whether a G66 modal call may be in force.
    g66: bool,
}

impl Facts {
    fn join(&self, other: &Facts) -> Facts {
        let g66 = self.g66 || other.g66;
        if Rc::ptr_eq(&self.vars, &other.vars) {
            return Facts {
                vars: self.vars.clone(),
                g66,
            };
        }
        let both: BTreeMap<u32, u64> = self
            .vars
            .iter()
            .filter(|(k, v)| other.vars.get(k) == Some(v))
            .map(|(k, v)| (*k, *v))
            .collect();
        // (Where one side knows no more than the join, its map serves.)
        let vars = if both.len() == self.vars.len() {
            self.vars.clone()
        } else if both.len() == other.vars.len() {
            other.vars.clone()
        } else {
            Rc::new(both)
        };
        Facts { vars, g66 }
    }

    fn get(&self, n: u32) -> Option<f64> {
        match n {
            // #0 is always vacant (it cannot be written).
            0 => Some(value::VACANT),
            _ => self.vars.get(&n).map(|b| f64::from_bits(*b)),
        }
    }

    fn set(&mut self, n: u32, v: Option<f64>) {
        match v {
            Some(v) if followed(n) => {
                if self.vars.get(&n) != Some(&v.to_bits()) {
                    Rc::make_mut(&mut self.vars).insert(n, v.to_bits());
                }
            }
            _ => self.forget(n),
        }
    }

    fn forget(&mut self, n: u32) {
        if self.vars.contains_key(&n) {
            Rc::make_mut(&mut self.vars).remove(&n);
        }
    }

    fn forget_all(&mut self) {
        if !self.vars.is_empty() {
            self.vars = Rc::default();
        }
    }

    fn forget_commons(&mut self) {
        if self.vars.keys().any(|n| common(*n)) {
            Rc::make_mut(&mut self.vars).retain(|n, _| !common(*n));
        }
    }
}

fn join(slot: &Option<Facts>, f: &Facts) -> Facts {
    match slot {
        Some(s) => s.join(f),
        None => f.clone(),
    }
}

/// Folds every function of `m`; the W116 warnings of what the values
/// known prove (a fault of constant operands alone is build's to warn of).
pub fn module(m: &mut Module, machine: &Machine) -> Vec<FileDiag> {
    if !m.functions.iter().any(reads_variables) {
        return Vec::new(); // Nothing to fold (a plain program).
    }
    let g66 = m.functions.iter().any(has_modal_call);
    let m99_p = m.functions.iter().skip(1).any(|f| {
        f.blocks
            .iter()
            .any(|(_, b)| matches!(b.term, Some(Terminator::Return { seq: Some(_) })))
    });
    let scope = Scope {
        g66,
        m99_p,
        writes: writes::of(m),
    };
    let starts = entries::of(m, &scope);
    let mut diags = Vec::new();
    for (f, entry) in m.functions.iter_mut().zip(starts) {
        if reads_variables(f) {
            let file = usize::from(f.file);
            let warnings = function(f, machine, entry, &scope);
            diags.extend(warnings.into_iter().map(|d| (file, d)));
        }
    }
    diags
}

/// What the module tells the analysis of each of its programs.
struct Scope {
    /// Whether the module has a G66.
    g66: bool,
    /// Whether a subprogram may return into a numbered block (`M99 P`).
    m99_p: bool,
    /// What each program may write, its callees included.
    writes: Vec<writes::Writes>,
}

impl Scope {
    /// Knowing nothing.
    fn unknown(&self) -> Facts {
        Facts {
            vars: Rc::default(),
            g66: self.g66,
        }
    }
}

/// Whether `f` sets a G66 modal call.
pub(crate) fn has_modal_call(f: &Function) -> bool {
    writes::calls(f).any(|(_, kind)| kind == CallKind::Modal)
}

/// Whether anything in `f` reads a variable (most long programs do not).
fn reads_variables(f: &Function) -> bool {
    f.exprs
        .iter()
        .any(|(_, e)| matches!(e, Expr::Var(_) | Expr::VarInd(_)))
}

/// Folds `f`, which starts knowing `entry`; its warnings.
fn function(f: &mut Function, machine: &Machine, entry: Facts, scope: &Scope) -> Vec<Diagnostic> {
    let Some(flow) = Flow::solve(f, entry, scope) else {
        return Vec::new();
    };
    let mut r = Rewrite::new(f, machine);
    for b in r.f.layout.clone() {
        // (An unreached block has nothing to fold with.)
        if let Some(facts) = flow.block_in.get(b.index()).cloned().flatten() {
            r.block(b, facts, flow.seq_in.as_ref());
        }
    }
    r.warnings
}

/// The facts at the start of each block, at the fixed point.
struct Flow<'s> {
    scope: &'s Scope,
    block_in: Vec<Option<Facts>>,
    /// What a jump to a number carries (`None`: no such jump).
    seq_in: Option<Facts>,
    /// The maps the slots hold: how many slots hold each, and its size.
    held: HashMap<*const BTreeMap<u32, u64>, (usize, usize)>,
    /// Entries of the distinct maps held, and how many may be: the
    /// analysis of a program where many blocks know many different values
    /// stops there (its memory stays proportional to the code).
    entries: usize,
    budget: usize,
}

impl<'s> Flow<'s> {
    /// Iterates to the fixed point; `None` when it takes too many rounds
    /// or stores more than its budget.
    fn solve(f: &Function, entry: Facts, scope: &'s Scope) -> Option<Flow<'s>> {
        let start = *f.layout.first()?;
        let mut flow = Flow {
            scope,
            block_in: vec![None; f.blocks.len()],
            seq_in: scope.m99_p.then(|| scope.unknown()),
            held: HashMap::new(),
            entries: 0,
            budget: STORED_PER_OP * f.ops.len() + STORED_MIN,
        };
        flow.hold(&entry, 1);
        *flow.block_in.get_mut(start.index())? = Some(entry);
        for _ in 0..MAX_ROUNDS {
            if !flow.round(f)? {
                return Some(flow);
            }
        }
        None
    }

    /// One pass over the layout; whether anything changed (`None`: over
    /// the budget).
    fn round(&mut self, f: &Function) -> Option<bool> {
        let mut changed = false;
        for &b in &f.layout {
            let Some(out) = self.block_out(f, b) else {
                continue;
            };
            let Some(term) = f.blocks.get(b).and_then(|k| k.term.as_ref()) else {
                continue;
            };
            for (target, facts) in edges(term, out, self.scope) {
                let slot = match target {
                    Some(t) => match self.block_in.get_mut(t.index()) {
                        Some(slot) => slot,
                        None => continue,
                    },
                    None => &mut self.seq_in,
                };
                let new = join(slot, &facts);
                if slot.as_ref() == Some(&new) {
                    continue;
                }
                changed = true;
                let old = slot.replace(new.clone());
                self.hold(&new, 1);
                if let Some(old) = old {
                    self.hold(&old, -1);
                }
            }
            if self.entries > self.budget {
                return None;
            }
        }
        Some(changed)
    }

    /// Counts a slot's hold (`by` = 1) or release (-1) of `facts`' map.
    fn hold(&mut self, facts: &Facts, by: isize) {
        let key = Rc::as_ptr(&facts.vars);
        let (slots, len) = self.held.entry(key).or_insert((0, facts.vars.len()));
        *slots = slots.saturating_add_signed(by);
        match (*slots, by > 0) {
            (1, true) => self.entries += *len,
            (0, false) => {
                self.entries -= *len;
                self.held.remove(&key);
            }
            _ => {}
        }
    }

    /// The facts after the operations of block `b` (`None`: unreached).
    fn block_out(&self, f: &Function, b: Handle<Block>) -> Option<Facts> {
        let mut facts = self.block_in.get(b.index())?.clone()?;
        for &op in &f.blocks.get(b)?.ops {
            let o = f.ops.get(op)?;
            facts = entering(o, facts, self.seq_in.as_ref());
            transfer(f, o, &mut facts);
        }
        Some(facts)
    }
}

/// Where control goes after a terminator, with what it knows; `None` as
/// the target: every numbered block.
fn edges(term: &Terminator, out: Facts, scope: &Scope) -> Vec<(Option<Handle<Block>>, Facts)> {
    match term {
        Terminator::Call { call, next } => vec![(Some(*next), after_call(call, out, scope))],
        Terminator::Goto { .. } | Terminator::Return { seq: Some(_) } => vec![(None, out)],
        Terminator::GotoIf { next, .. } => vec![(Some(*next), out.clone()), (None, out)],
        // (M99 running the main program again starts it knowing nothing,
        // as its entry does; a call's count that runs its program again
        // is `entries`' to follow.)
        t => t.successors().map(|s| (Some(s), out.clone())).collect(),
    }
}

/// What a call leaves known: all but what its program may write (only
/// its common variables, for a macro). The callee may set or cancel a G66.
fn after_call(call: &Call, mut facts: Facts, scope: &Scope) -> Facts {
    if call.kind == CallKind::Modal {
        facts.g66 = true;
        return facts;
    }
    let commons_only = call.kind == CallKind::Macro;
    let writes = match call.callee {
        Callee::Program(i) => scope.writes.get(i as usize),
        Callee::Dynamic(_) => None,
    };
    match writes {
        Some(w) => w.forget_in(&mut facts, commons_only),
        None if commons_only => facts.forget_commons(),
        None => facts.forget_all(),
    }
    facts.g66 = scope.g66;
    facts
}

/// The facts before `o`: a numbered block also joins what a jump to a
/// number brings (`seq_in`).
fn entering(o: &Op, facts: Facts, seq_in: Option<&Facts>) -> Facts {
    match (o, seq_in) {
        (Op::Seq(..), Some(seq)) => facts.join(seq),
        _ => facts,
    }
}

/// What one operation changes.
fn transfer(f: &Function, op: &Op, facts: &mut Facts) {
    match op {
        Op::Assign { target, value, .. } => match target_var(f, *target, facts) {
            Some(n) => {
                let v = eval(f, *value, facts).and_then(Result::ok);
                facts.set(n, v);
            }
            None => facts.forget_all(),
        },
        Op::MacroA { dst, value, .. } => {
            let v = eval(f, *value, facts).and_then(Result::ok);
            facts.set(*dst, v);
        }
        Op::Nc(nc) => nc_block(f, nc, facts),
        Op::ModalCancel => facts.g66 = false,
        Op::Seq(..) | Op::Alarm { .. } | Op::UserAlarm { .. } | Op::Charge => {}
    }
}

/// The variable an assignment writes, when it is known.
fn target_var(f: &Function, target: VarTarget, facts: &Facts) -> Option<u32> {
    match target {
        VarTarget::Direct(n) => Some(n),
        VarTarget::Indirect(i) => match eval(f, i, facts)? {
            Ok(n) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => Some(n as u32),
            _ => None,
        },
    }
}

/// What an NC block writes: G31's skip position, a G10 L52 read's
/// variable and, under G66, whatever the macro it calls writes.
fn nc_block(f: &Function, nc: &NcBlock, facts: &mut Facts) {
    if facts.vars.is_empty() {
        return; // Nothing to forget (most blocks of a long program).
    }
    match nc_writes(f, nc) {
        Some(vars) => vars.for_each(|n| facts.forget(n)),
        None => facts.forget_all(),
    }
    if facts.g66 {
        facts.forget_commons();
    }
}

/// The variables an NC block itself writes: #995–#999 (G31's skip
/// position) and, for a G10 L52 read (N and R words), the one R names;
/// `None`: any (a computed R).
pub(crate) fn nc_writes(f: &Function, nc: &NcBlock) -> Option<impl Iterator<Item = u32>> {
    let words = f.words_of(nc);
    let has = |c: u8| words.iter().find(|w| w.addr == addr(c));
    let read = match (has(b'N'), has(b'R')) {
        (Some(_), Some(r)) => match r.constant() {
            Some(v) if v >= 0.0 => Some(nc::block::round_half_away(v) as u32),
            _ => return None,
        },
        _ => None,
    };
    Some((995..=999).chain(read))
}

/// The value of expression `h` where `facts` hold: `None` when it reads a
/// variable not known there.
fn eval(f: &Function, h: Handle<Expr>, facts: &Facts) -> Option<Result<f64, nc::NcError>> {
    let e = |h| eval(f, h, facts);
    Some(match f.exprs.get(h)? {
        Expr::Const(v) => Ok(*v),
        Expr::Var(n) => Ok(facts.get(*n)?),
        Expr::VarInd(i) => match e(*i)? {
            Ok(n) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => {
                Ok(facts.get(n as u32)?)
            }
            _ => return None,
        },
        Expr::Neg(a) => e(*a)?.map(value::neg),
        Expr::Binary { op, a, b } => {
            let (a, b) = (e(*a)?, e(*b)?);
            a.and_then(|a| b.and_then(|b| value::binary(*op, a, b)))
        }
        Expr::Func { f: func, a } => e(*a)?.and_then(|a| value::func(*func, a)),
        Expr::Atan2 { y, x } => {
            let (y, x) = (e(*y)?, e(*x)?);
            y.and_then(|y| x.and_then(|x| value::atan2(y, x)))
        }
        Expr::Compare { op, a, b } => {
            let (a, b) = (e(*a)?, e(*b)?);
            a.and_then(|a| b.map(|b| value::compare(*op, a, b)))
        }
    })
}

/// The rewriting of one function, with what it finds to warn of.
struct Rewrite<'a> {
    f: &'a mut Function,
    machine: &'a Machine,
    /// The numbers of the function's blocks (computed GOTO targets).
    seqs: BTreeSet<u32>,
    warnings: Vec<Diagnostic>,
    /// Scratch for the kernel's parse of a block made constant.
    parsed: nc::block::Parsed,
}

impl<'a> Rewrite<'a> {
    fn new(f: &'a mut Function, machine: &'a Machine) -> Rewrite<'a> {
        let seqs = f
            .ops
            .iter()
            .filter_map(|(_, o)| match o {
                Op::Seq(n, _) => Some(*n),
                _ => None,
            })
            .collect();
        Rewrite {
            f,
            machine,
            seqs,
            warnings: Vec::new(),
            parsed: nc::block::Parsed::default(),
        }
    }

    /// Folds block `b`, entered with `facts`; `seq_in`: what a jump to a
    /// number brings.
    fn block(&mut self, b: Handle<Block>, mut facts: Facts, seq_in: Option<&Facts>) {
        let ops = self
            .f
            .blocks
            .get(b)
            .map(|k| k.ops.clone())
            .unwrap_or_default();
        for op in ops {
            if let Some(o) = self.f.ops.get(op) {
                facts = entering(o, facts, seq_in);
            }
            self.op(op, &facts);
            if let Some(o) = self.f.ops.get(op) {
                transfer(self.f, o, &mut facts);
            }
        }
        if let Some(term) = self.f.blocks.get(b).and_then(|k| k.term.clone()) {
            let span = self
                .f
                .term_locs
                .get(b.index())
                .map_or(self.f.span, |l| l.span);
            self.term(&term, &facts, span);
        }
    }

    /// W116 at `span`: `e` happens whenever the program gets there.
    fn warn(&mut self, span: Span, e: &NcError) {
        let msg = crate::expr::always_fails(e);
        self.warnings.push(Diagnostic::warning("W116", span, msg));
    }

    /// Folds the tree of `h`: the whole of it when its value is known,
    /// else each largest subtree whose value is. The value of `h`, when
    /// known. A fault proven with a variable's value is W116 at `span`.
    fn fold(&mut self, h: Handle<Expr>, facts: &Facts, span: Span) -> Option<f64> {
        match eval(self.f, h, facts) {
            Some(Ok(v)) => {
                if let Some(e) = self.f.exprs.get_mut(h) {
                    *e = Expr::Const(v);
                }
                return Some(v);
            }
            // The fault stays where it happens, with its line.
            Some(Err(_)) => {
                self.warn_fault(h, facts, span);
                return None;
            }
            None => self.check_division(h, facts, span),
        }
        for child in children(self.f, h) {
            self.fold(child, facts, span);
        }
        None
    }

    /// A division by a value known to be zero (or vacant) faults whatever
    /// the dividend, a variable not known here: W116.
    fn check_division(&mut self, h: Handle<Expr>, facts: &Facts, span: Span) {
        let Some(&Expr::Binary { op: Bin::Div, a, b }) = self.f.exprs.get(h) else {
            return;
        };
        if !matches!(self.f.exprs.get(a), Some(Expr::Var(_))) {
            return;
        }
        if let Some(Ok(divisor)) = eval(self.f, b, facts) {
            if let Err(e) = value::binary(Bin::Div, 0.0, divisor) {
                self.warn(span, &e);
            }
        }
    }

    /// W116 for the operation of the tree of `h` that faults, when a
    /// variable's value is what proves it (build warns of an operation
    /// whose operands are constants).
    fn warn_fault(&mut self, h: Handle<Expr>, facts: &Facts, span: Span) {
        let kids = children(self.f, h);
        for &c in &kids {
            if let Some(Err(_)) = eval(self.f, c, facts) {
                return self.warn_fault(c, facts, span);
            }
        }
        let proven_by_variable = kids.iter().any(|&c| reads_variable(self.f, c));
        if let (true, Some(Err(e))) = (proven_by_variable, eval(self.f, h, facts)) {
            self.warn(span, &e);
        }
    }

    /// Folds the expressions of one operation, with what is known before
    /// it.
    fn op(&mut self, op: Handle<Op>, facts: &Facts) {
        let span = self
            .f
            .op_locs
            .get(op.index())
            .map_or(self.f.span, |l| l.span);
        match self.f.ops.get(op).cloned() {
            Some(Op::Assign { target, value, .. }) => {
                if let VarTarget::Indirect(i) = target {
                    self.fold(i, facts, span);
                }
                self.fold(value, facts, span);
            }
            Some(Op::MacroA { value, .. }) => {
                self.fold(value, facts, span);
            }
            Some(Op::Nc(nc)) => {
                let computed = self.f.words_of(&nc).iter().any(|w| w.constant().is_none());
                let kept = self.words(&nc, facts);
                let Some(Op::Nc(nc)) = self.f.ops.get_mut(op) else {
                    return;
                };
                nc.words.1 = nc.words.0 + kept;
                let nc = nc.clone();
                if computed && nc.kind.runs_here() {
                    self.check_words(&nc, span);
                }
            }
            _ => {}
        }
    }

    /// Folds the words of an NC block and moves those left (a vacant one
    /// is left out) to the front of its range; how many are left. (The
    /// words past the new end of the range belong to no block.)
    fn words(&mut self, nc: &NcBlock, facts: &Facts) -> u32 {
        let (a, b) = (nc.words.0 as usize, nc.words.1 as usize);
        let mut kept = a;
        for i in a..b {
            let (Some(&w), Some(&span)) = (self.f.words.get(i), self.f.word_spans.get(i)) else {
                break;
            };
            let w = match w.value() {
                WordValue::Expr(h) => match self.fold(h, facts, span) {
                    Some(v) if value::is_vacant(v) => continue,
                    Some(v) => Word::new(w.addr, WordValue::Const(v, 0)),
                    None => w,
                },
                WordValue::Const(..) => w,
            };
            // (`kept` ≤ `i`, which is in range.)
            if let (Some(dw), Some(ds)) =
                (self.f.words.get_mut(kept), self.f.word_spans.get_mut(kept))
            {
                (*dw, *ds) = (w, span);
            }
            kept += 1;
        }
        (kept - a) as u32
    }

    /// A block whose computed words all became constants: the kernel's
    /// rules on words (a G, M or T value, words that cannot stand
    /// together) decide now what they will decide whenever it runs.
    fn check_words(&mut self, nc: &NcBlock, span: Span) {
        let words = self.f.words_of(nc);
        let lits: Option<Vec<nc::words::Word>> = words
            .iter()
            .map(|w| match w.value() {
                WordValue::Const(value, flags) => Some(nc::words::Word {
                    addr: w.addr,
                    value,
                    flags,
                }),
                WordValue::Expr(_) => None,
            })
            .collect();
        let Some(lits) = lits else { return };
        if let Err(e) = crate::check::word_rules(self.machine, &lits, &mut self.parsed) {
            // At the word the kernel names, when it names one (every word
            // is one of `lits` here, in order).
            let addrs = lits.iter().map(|w| w.addr);
            let word = e
                .word_among(addrs)
                .and_then(|i| self.f.word_spans_of(nc).get(i));
            self.warn(word.copied().unwrap_or(span), &e);
        }
    }

    /// Folds the operands of a terminator, with what is known at the end
    /// of its block.
    fn term(&mut self, term: &Terminator, facts: &Facts, span: Span) {
        match term {
            Terminator::Branch { cond, .. } => {
                self.fold(*cond, facts, span);
            }
            Terminator::Goto { seq, .. } => {
                if let Some(n) = self.fold(*seq, facts, span) {
                    self.check_goto(n, span);
                }
            }
            Terminator::Return { seq: Some(seq) } => {
                self.fold(*seq, facts, span);
            }
            Terminator::GotoIf { seq, j, k, .. } => {
                for h in [*seq, *j, *k] {
                    self.fold(h, facts, span);
                }
            }
            Terminator::Call { call, .. } => {
                if let Callee::Dynamic(h) = call.callee {
                    self.fold(h, facts, span);
                }
                if let Count::Expr(h) = call.count {
                    self.fold(h, facts, span);
                }
                for &(_, h) in &call.args {
                    self.fold(h, facts, span);
                }
            }
            _ => {}
        }
    }

    /// A computed GOTO whose target is known: W116 when it is 0 (the VM's
    /// E5010) or no block of the program has that number (E6001).
    fn check_goto(&mut self, v: f64, span: Span) {
        let n = nc::block::round_half_away(v);
        let valid = !value::is_vacant(v) && (0.0..=99_999_999.0).contains(&n);
        if valid && n == 0.0 {
            let msg = "GOTO 0: sequence numbers to jump to are 1…99999";
            self.warn(span, &NcError::new(Alarm::ValueOutOfRange, msg));
        } else if valid && !self.seqs.contains(&(n as u32)) {
            let msg = format!("GOTO {n}: there is no block N{n} in this program");
            self.warn(span, &NcError::new(Alarm::JumpTargetMissing, msg));
        }
    }
}

/// Whether the tree of `h` reads a variable.
fn reads_variable(f: &Function, h: Handle<Expr>) -> bool {
    matches!(f.exprs.get(h), Some(Expr::Var(_) | Expr::VarInd(_)))
        || children(f, h).into_iter().any(|c| reads_variable(f, c))
}

fn children(f: &Function, h: Handle<Expr>) -> Vec<Handle<Expr>> {
    match f.exprs.get(h) {
        Some(Expr::VarInd(a) | Expr::Neg(a) | Expr::Func { a, .. }) => vec![*a],
        Some(Expr::Binary { a, b, .. } | Expr::Compare { a, b, .. }) => vec![*a, *b],
        Some(Expr::Atan2 { y, x }) => vec![*y, *x],
        Some(Expr::Const(_) | Expr::Var(_)) | None => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{compile_ir, Options};

    /// 300 common variables set, then `ifs` IF blocks; `changes`: whether
    /// each sets #2 to a value of its own first (so that every block after
    /// it knows the 300 and a different #2, then joins without it).
    fn wide(ifs: usize, changes: bool) -> String {
        let mut s: String = (100..400).map(|v| format!("#{v}={v}\n")).collect();
        for i in 0..ifs {
            if changes {
                s += &format!("#2={i}\n");
            }
            s += &format!("IF[#1GT{i}]THEN#2=#2+1\n");
        }
        s + "G01 X#100 Z#399 F100\nM30\n"
    }

    /// The values the main program's analysis holds at its fixed point;
    /// `None` when it gives up.
    fn held(src: &str) -> Option<usize> {
        let (c, ir) = compile_ir("t.nc", src.as_bytes(), &Options::default());
        assert!(!c.has_errors(), "{}", c.render());
        let ir = ir.expect("IR");
        let f = ir.functions.first().expect("a main program");
        let scope = Scope {
            g66: false,
            m99_p: false,
            writes: writes::of(&ir),
        };
        Flow::solve(f, scope.unknown(), &scope).map(|flow| flow.entries)
    }

    #[test]
    fn blocks_that_know_the_same_share_one_map() {
        // Every block knows the 300 commons: one map of 300 and few more
        // (the THEN blocks' #2 is not known after the first join).
        let entries = held(&wide(2000, false)).expect("solved");
        assert!(entries <= 3 * 300, "{entries} entries held");
    }

    #[test]
    fn a_program_past_the_budget_is_not_folded() {
        // Each join makes a map of its own (#2 differs on its two paths):
        // 2 000 maps of 300 would be 600 000 entries, over the budget of
        // 8 per operation (about 4 300 operations) and 65 536.
        assert!(held(&wide(2000, true)).is_none());
        // A twentieth of that fits.
        assert!(held(&wide(100, true)).is_some());
    }
}
