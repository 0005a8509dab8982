//! W127: a loop that never ends once it goes round. gbc's own warning,
//! for a program with macros (a static one's dry run finds its endless
//! loops, W120), on the IR before fold (which makes a test that is always
//! true a jump, and the message would lose it):
//!
//! - a loop with no way out (`DO 1` … `END 1` with no GOTO out of it);
//! - a loop whose one way out is a test, met on every round, of
//!   variables that nothing in the loop writes (`WHILE [#1 LT 10] DO 1`
//!   with no `#1 = …` inside): the test gives the same answer every
//!   time, so a loop that goes round once goes round for ever.
//!
//! Either way only an alarm stops the run: E6005 when the block budget is
//! used up, at the latest. The analysis stays silent wherever it cannot
//! be sure: a test that reads a system variable (an input, a position) or
//! a variable by a computed number, a second way out, a loop with a call,
//! an alarm, a block-skip switch or a write to a computed number inside,
//! a program with a computed GOTO, a module with G66 (every move may call
//! a macro).

use crate::build::FileDiag;
use crate::fold::{has_modal_call, nc_writes};
use crate::ir::{Block, Expr, Function, Handle, Module, Op, Terminator, VarTarget, Word};
use grammar::{Diagnostic, Span};
use nc::words::addr;
use std::collections::BTreeSet;

/// The warnings of every program of `m`.
pub fn module(m: &Module) -> Vec<FileDiag> {
    if m.functions.iter().any(has_modal_call) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for f in &m.functions {
        let file = usize::from(f.file);
        out.extend(function(f).into_iter().map(|d| (file, d)));
    }
    out
}

/// Why a loop never ends.
enum Endless {
    /// No edge leaves it.
    NoWayOut,
    /// Its one way out is a test of these variables, which it never
    /// writes.
    Unchanged(BTreeSet<u32>),
}

/// The warnings of one program: one per loop head at most.
fn function(f: &Function) -> Vec<Diagnostic> {
    if f.blocks.iter().any(|(_, b)| jumps_at_run_time(b)) {
        return Vec::new();
    }
    let order = layout_order(f);
    let place = |b: Handle<Block>| order.get(b.index()).copied();
    // A back edge of the layout: a loop's last block to its head. (Most
    // programs have none, and need no more than this.)
    let back_edges: Vec<_> = (f.layout.iter())
        .flat_map(|&from| successors(f, from).map(move |head| (head, from)))
        .filter(|&(head, from)| place(head) <= place(from))
        .collect();
    if back_edges.is_empty() {
        return Vec::new();
    }
    let preds = Preds::of(f);
    let heads: BTreeSet<_> = back_edges.iter().map(|&(head, _)| head).collect();
    let mut out = Vec::new();
    for head in heads {
        // The loop at `head`: every cycle through it (a DO's END, and a
        // GOTO back to it from a branch of its body).
        let tails: Vec<_> = (back_edges.iter())
            .filter(|&&(h, _)| h == head)
            .map(|&(_, tail)| tail)
            .collect();
        let loops = tails
            .iter()
            .filter_map(|&t| natural_loop(f, head, t, &preds));
        let body: BTreeSet<_> = loops.flatten().collect();
        if body.is_empty() {
            continue;
        }
        let round = Round {
            head,
            tails: &tails,
            body: &body,
        };
        if let Some((why, span)) = endless(f, &round) {
            out.push(warning(why, span));
        }
    }
    out
}

/// A loop: its head, the blocks that jump back to it, and its blocks.
struct Round<'a> {
    head: Handle<Block>,
    tails: &'a [Handle<Block>],
    body: &'a BTreeSet<Handle<Block>>,
}

impl Round<'_> {
    /// Whether every round passes block `b`: without it, the head
    /// reaches none of the blocks that jump back.
    fn passes(&self, f: &Function, b: Handle<Block>) -> bool {
        if b == self.head {
            return true;
        }
        // (A head that jumps back to itself goes round alone.)
        if self.tails.contains(&self.head) {
            return false;
        }
        let mut seen = BTreeSet::from([self.head, b]);
        let mut work = vec![self.head];
        while let Some(at) = work.pop() {
            if self.tails.contains(&at) {
                return false;
            }
            for next in successors(f, at) {
                if self.body.contains(&next) && seen.insert(next) {
                    work.push(next);
                }
            }
        }
        true
    }
}

/// Whether the block jumps to a block found at run time (a computed
/// GOTO, M99 P): a loop can then be left where the IR shows no edge.
fn jumps_at_run_time(b: &Block) -> bool {
    matches!(
        b.term,
        Some(Terminator::Goto { .. } | Terminator::GotoIf { .. })
            | Some(Terminator::Return { seq: Some(_) })
    )
}

/// Each block's place in the layout (blocks off the layout last).
fn layout_order(f: &Function) -> Vec<usize> {
    let mut order = vec![usize::MAX; f.blocks.len()];
    for (i, b) in f.layout.iter().enumerate() {
        if let Some(slot) = order.get_mut(b.index()) {
            *slot = i;
        }
    }
    order
}

fn successors(f: &Function, b: Handle<Block>) -> impl Iterator<Item = Handle<Block>> + '_ {
    let term = f.blocks.get(b).and_then(|b| b.term.as_ref());
    term.into_iter().flat_map(|t| t.successors())
}

/// Every edge, to its block's index and from its block, sorted: each
/// block's predecessors in one list (a program may have a block per
/// numbered line: no list of its own for each).
struct Preds(Vec<(usize, Handle<Block>)>);

impl Preds {
    fn of(f: &Function) -> Preds {
        let edges = f
            .blocks
            .iter()
            .flat_map(|(b, _)| successors(f, b).map(move |s| (s.index(), b)));
        let mut edges: Vec<_> = edges.collect();
        edges.sort_unstable();
        Preds(edges)
    }

    fn of_block(&self, b: Handle<Block>) -> impl Iterator<Item = Handle<Block>> + '_ {
        let from = self.0.partition_point(|e| e.0 < b.index());
        let edges = self.0.get(from..).unwrap_or(&[]);
        edges
            .iter()
            .take_while(move |e| e.0 == b.index())
            .map(|e| e.1)
    }
}

/// The loop of back edge `tail` → `head`: the blocks on a path from the
/// head to the tail (that reach the tail without passing the head, and
/// that the head reaches); `None` when the head does not reach the tail
/// (the tail is dead code: an END after a GOTO out of its loop).
fn natural_loop(
    f: &Function,
    head: Handle<Block>,
    tail: Handle<Block>,
    preds: &Preds,
) -> Option<BTreeSet<Handle<Block>>> {
    let mut reach_tail = BTreeSet::from([head]);
    let mut work = vec![tail];
    while let Some(b) = work.pop() {
        if reach_tail.insert(b) {
            work.extend(preds.of_block(b));
        }
    }
    let mut body = BTreeSet::from([head]);
    let mut work: Vec<_> = successors(f, head).collect();
    while let Some(b) = work.pop() {
        if reach_tail.contains(&b) && body.insert(b) {
            work.extend(successors(f, b));
        }
    }
    body.contains(&tail).then_some(body)
}

/// Whether the loop never ends once it goes round, and where to say so:
/// its test that never changes, or its head. Its one way out must be
/// met on every round: a test met only on some (behind a branch of the
/// body) may be met for the first time late, and leave.
fn endless(f: &Function, round: &Round<'_>) -> Option<(Endless, Span)> {
    let body = round.body;
    let mut written = BTreeSet::new();
    let mut tests = Vec::new();
    for &h in body {
        let b = f.blocks.get(h)?;
        for &op in &b.ops {
            writes(f, f.ops.get(op)?, &mut written)?;
        }
        match b.term.as_ref()? {
            Terminator::Follow(_) | Terminator::Jump(_) | Terminator::GotoKnown(_) => {}
            Terminator::Branch {
                cond,
                then,
                otherwise,
            } => {
                if !(body.contains(then) && body.contains(otherwise)) {
                    if !round.passes(f, h) {
                        return None;
                    }
                    tests.push((*cond, f.term_locs.get(h.index())?.span));
                }
            }
            Terminator::Skip { skip, next, .. } => {
                // (The operator may turn the switch at any time.)
                if !(body.contains(skip) && body.contains(next)) {
                    return None;
                }
            }
            _ => return None,
        }
    }
    let (cond, span) = match tests[..] {
        [] => return Some((Endless::NoWayOut, head_span(f, round.head)?)),
        [test] => test,
        // (Several ways out: one that holds at once leaves the loop on
        // every pass, and the others' variables may change around it.)
        _ => return None,
    };
    let mut read = BTreeSet::new();
    reads(f, cond, &mut read)?;
    match read.is_disjoint(&written) {
        true => Some((Endless::Unchanged(read), span)),
        false => None,
    }
}

/// Adds what `op` writes to `written`; `None` where it may end the run
/// (an alarm) or write any variable.
fn writes(f: &Function, op: &Op, written: &mut BTreeSet<u32>) -> Option<()> {
    match op {
        Op::Assign {
            target: VarTarget::Direct(n),
            ..
        }
        | Op::MacroA { dst: n, .. } => {
            // (#3000 raises an alarm.)
            if *n == 3000 {
                return None;
            }
            written.insert(*n);
        }
        Op::Assign { .. } | Op::Alarm { .. } | Op::UserAlarm { .. } => return None,
        Op::Nc(nc) => {
            // A computed G, M or T code may call a macro, return or end
            // the program.
            let calls = |w: &Word| CODES.contains(&w.addr) && w.constant().is_none();
            if f.words_of(nc).iter().any(calls) {
                return None;
            }
            written.extend(nc_writes(f, nc)?);
        }
        Op::Seq(..) | Op::ModalCancel | Op::Charge => {}
    }
    Some(())
}

/// The addresses of the codes that may call: G, M, T.
const CODES: [u8; 3] = [addr(b'G'), addr(b'M'), addr(b'T')];

/// Adds the variables `e` reads to `read`; `None` where it reads one that
/// changes by itself (a system variable) or by a computed number.
fn reads(f: &Function, e: Handle<Expr>, read: &mut BTreeSet<u32>) -> Option<()> {
    match *f.exprs.get(e)? {
        Expr::Const(_) => {}
        Expr::Var(n) if (1..=999).contains(&n) => {
            read.insert(n);
        }
        Expr::Var(_) | Expr::VarInd(_) => return None,
        Expr::Neg(a) | Expr::Func { a, .. } => reads(f, a, read)?,
        Expr::Binary { a, b, .. } | Expr::Compare { a, b, .. } => {
            reads(f, a, read)?;
            reads(f, b, read)?;
        }
        Expr::Atan2 { y, x } => {
            reads(f, y, read)?;
            reads(f, x, read)?;
        }
    }
    Some(())
}

/// Where a loop starts: its head's first statement (the DO).
fn head_span(f: &Function, head: Handle<Block>) -> Option<Span> {
    let b = f.blocks.get(head)?;
    match b.ops.first() {
        Some(op) => Some(f.op_locs.get(op.index())?.span),
        None => Some(f.term_locs.get(head.index())?.span),
    }
}

fn warning(why: Endless, span: Span) -> Diagnostic {
    const BUDGET: &str = "only an alarm stops the run: the block budget's (E6005) at the latest";
    match why {
        Endless::NoWayOut => Diagnostic::warning(
            "W127",
            span,
            format!("this loop never ends: nothing leaves it, so {BUDGET}"),
        )
        .with_help("leave it with IF [...] GOTO n, or make it a WHILE [...] DO loop"),
        Endless::Unchanged(vars) => {
            let names: Vec<String> = vars.iter().map(|n| format!("#{n}")).collect();
            let test = match names.is_empty() {
                true => "its test gives the same answer every time".to_string(),
                false => format!(
                    "its test reads only {}, which nothing in the loop changes",
                    names.join(", ")
                ),
            };
            Diagnostic::warning(
                "W127",
                span,
                format!("this loop never ends once it goes round: {test}, so {BUDGET}"),
            )
            .with_help("change a variable of the test inside the loop (as #1 = #1 + 1)")
        }
    }
}
