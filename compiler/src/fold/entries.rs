//! What each program of the module knows where it starts: the join of
//! what every call of it passes.
//!
//! - G65, a G-code macro and G66 give the macro a local level of its own:
//!   its arguments, every other local vacant. A G65 passes the common
//!   variables as the caller has them; a G66 macro runs after later moves,
//!   when they may differ, so it starts without them.
//! - M98 (and an M code that calls) shares the caller's locals: the
//!   subprogram starts with all the caller knows.
//! - A call that may run its program more than once (a count other than
//!   a constant 0 or 1) passes only a macro's arguments: a second run
//!   starts with what the first left.
//! - The main program and a program no call reaches start knowing nothing;
//!   so does every called program when the module has a call of a
//!   computed program number, or when the callers' facts do not settle
//!   within a few rounds (recursion with values that keep changing).

use super::{common, eval, Facts, Flow, Scope};
use crate::ir::{Call, CallKind, Callee, Count, Expr, Function, Module, Terminator};
use nc::value;
use std::collections::BTreeMap;
use std::rc::Rc;

/// Rounds of the callers' analyses before the entries are given up.
const MAX_ROUNDS: usize = 8;

/// The facts each function of `m` starts with.
pub(super) fn of(m: &Module, scope: &Scope) -> Vec<Facts> {
    let unknown = &scope.unknown();
    let n = m.functions.len();
    let mut entries = vec![unknown.clone(); n];
    if n == 1 || m.functions.iter().any(calls_computed_program) {
        return entries;
    }
    for _ in 0..MAX_ROUNDS {
        let mut next: Vec<Option<Facts>> = vec![None; n];
        for (f, entry) in m.functions.iter().zip(&entries) {
            calls(f, entry, scope, |callee, passed| {
                if let Some(slot) = next.get_mut(callee) {
                    *slot = Some(super::join(slot, &passed));
                }
            });
        }
        // (The main program also starts the run, knowing nothing.) The
        // rounds start from entries that know nothing and can only come
        // to know more; they stop where each entry is what its calls pass.
        let next: Vec<Facts> = next
            .into_iter()
            .enumerate()
            .map(|(i, e)| e.filter(|_| i > 0).unwrap_or_else(|| unknown.clone()))
            .collect();
        if next == entries {
            return entries;
        }
        entries = next;
    }
    vec![unknown.clone(); n]
}

fn calls_computed_program(f: &Function) -> bool {
    super::writes::calls(f).any(|(callee, _)| callee.is_none())
}

/// Gives `each` the calls `f` makes where it starts with `entry`, each
/// with what it passes, in turn: a caller joins each as it comes, so a
/// program of many macro calls (each passing its 33 locals) does not hold
/// them all. Where `f`'s analysis gives up, its calls pass nothing known.
fn calls(f: &Function, entry: &Facts, scope: &Scope, mut each: impl FnMut(usize, Facts)) {
    let flow = Flow::solve(f, entry.clone(), scope);
    for &b in &f.layout {
        let Some(Terminator::Call { call, .. }) = f.blocks.get(b).and_then(|k| k.term.as_ref())
        else {
            continue;
        };
        let Callee::Program(callee) = call.callee else {
            continue;
        };
        let passed = match &flow {
            // (A block no path reaches makes no call.)
            Some(flow) => match flow.block_out(f, b) {
                Some(before) => passed(f, call, &before),
                None => continue,
            },
            None => scope.unknown(),
        };
        each(callee as usize, passed);
    }
}

/// What `call` passes to its program, made where `before` holds.
fn passed(f: &Function, call: &Call, before: &Facts) -> Facts {
    let once = once(f, call.count);
    match call.kind {
        CallKind::Sub if once => before.clone(),
        CallKind::Sub => Facts {
            vars: Rc::default(),
            g66: before.g66,
        },
        CallKind::Macro | CallKind::Modal => {
            let mut vars: BTreeMap<u32, u64> =
                (1..=33).map(|n| (n, value::VACANT.to_bits())).collect();
            for &(local, h) in &call.args {
                match eval(f, h, before) {
                    Some(Ok(v)) => vars.insert(u32::from(local), v.to_bits()),
                    _ => vars.remove(&u32::from(local)),
                };
            }
            if call.kind == CallKind::Macro && once {
                vars.extend(before.vars.iter().filter(|(n, _)| common(**n)));
            }
            Facts {
                vars: Rc::new(vars),
                g66: before.g66 || call.kind == CallKind::Modal,
            }
        }
    }
}

/// Whether a call runs its program once: a count of a constant 0 or 1.
fn once(f: &Function, count: Count) -> bool {
    match count {
        Count::Expr(h) => matches!(f.exprs.get(h), Some(Expr::Const(c)) if *c == 0.0 || *c == 1.0),
        Count::Packed => false,
    }
}
