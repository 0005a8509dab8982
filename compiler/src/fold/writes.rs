//! The variables each program may write, with the programs it calls: after
//! a call, only those stop being known.
//!
//! - A program writes the targets of its assignments and macro-A
//!   operations (any variable, for an assignment to a computed number),
//!   #995–#999 in an NC block (G31), and a G10 L52 read's variable.
//! - A subprogram's writes (M98) are its caller's, locals included: it
//!   shares the caller's local level. A macro's (G65) are its caller's
//!   common variables only: its locals are a level of its own.
//! - In a module with a G66, any NC block may call the modal macro: every
//!   program with an NC block writes what those macros write.
//! - A call of a computed program number may write anything.

use super::{common, nc_writes, Facts};
use crate::ir::{CallKind, Callee, Function, Module, Op, Terminator, VarTarget};
use std::collections::BTreeSet;

/// What a program may write.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Writes {
    /// Any variable (a computed target, a computed callee).
    any: bool,
    vars: BTreeSet<u32>,
}

impl Writes {
    /// Adds what `other` writes; only its common variables with
    /// `commons_only` (a macro's locals are its own).
    fn add(&mut self, other: &Writes, commons_only: bool) {
        self.any |= other.any;
        let new = other.vars.iter().filter(|n| !commons_only || common(**n));
        self.vars.extend(new);
    }

    /// Forgets in `facts` what a call of this program changes: its common
    /// variables only with `commons_only` (a macro call).
    pub(super) fn forget_in(&self, facts: &mut Facts, commons_only: bool) {
        match (self.any, commons_only) {
            (true, true) => facts.forget_commons(),
            (true, false) => facts.forget_all(),
            (false, _) => {
                for &n in self.vars.iter().filter(|n| !commons_only || common(**n)) {
                    facts.forget(n);
                }
            }
        }
    }
}

/// What each function of `m` may write, its callees' writes included.
pub(super) fn of(m: &Module) -> Vec<Writes> {
    let own: Vec<Writes> = m.functions.iter().map(own_writes).collect();
    let mut all = own.clone();
    // Sets only grow: as many rounds as the longest chain of calls.
    for _ in 0..=m.functions.len() {
        let modal = modal_writes(m, &all);
        let mut next = own.clone();
        for (f, w) in m.functions.iter().zip(&mut next) {
            for (callee, kind) in calls(f) {
                let callee = callee.and_then(|i| all.get(i)).unwrap_or(&ANYTHING);
                match kind {
                    CallKind::Sub => w.add(callee, false),
                    CallKind::Macro => w.add(callee, true),
                    // (Setting G66 calls nothing; its calls are `modal`'s.)
                    CallKind::Modal => {}
                }
            }
            if has_nc(f) {
                w.add(&modal, true);
            }
        }
        if next == all {
            return all;
        }
        all = next;
    }
    // (Not settled: cannot happen, as the sets only grow; be safe.)
    vec![ANYTHING.clone(); m.functions.len()]
}

/// What a call of a computed program may write.
static ANYTHING: Writes = Writes {
    any: true,
    vars: BTreeSet::new(),
};

/// The writes of `f`'s own operations.
fn own_writes(f: &Function) -> Writes {
    let mut w = Writes::default();
    for (_, op) in f.ops.iter() {
        match op {
            Op::Assign {
                target: VarTarget::Direct(n),
                ..
            }
            | Op::MacroA { dst: n, .. } => {
                w.vars.insert(*n);
            }
            Op::Assign { .. } => w.any = true,
            Op::Nc(nc) => match nc_writes(f, nc) {
                Some(vars) => w.vars.extend(vars),
                None => w.any = true,
            },
            Op::Seq(..)
            | Op::Alarm { .. }
            | Op::UserAlarm { .. }
            | Op::ModalCancel
            | Op::Charge => {}
        }
    }
    w
}

/// What the macros G66 calls may write (their common variables count).
fn modal_writes(m: &Module, all: &[Writes]) -> Writes {
    let mut w = Writes::default();
    for f in &m.functions {
        for (callee, kind) in calls(f) {
            if kind == CallKind::Modal {
                w.add(callee.and_then(|i| all.get(i)).unwrap_or(&ANYTHING), true);
            }
        }
    }
    w
}

/// `f`'s calls, G66's setting included: the callee (`None`: computed)
/// and the kind.
pub(super) fn calls(f: &Function) -> impl Iterator<Item = (Option<usize>, CallKind)> + '_ {
    f.blocks.iter().filter_map(|(_, b)| match &b.term {
        Some(Terminator::Call { call, .. }) => {
            let callee = match call.callee {
                Callee::Program(i) => Some(i as usize),
                Callee::Dynamic(_) => None,
            };
            Some((callee, call.kind))
        }
        _ => None,
    })
}

fn has_nc(f: &Function) -> bool {
    f.ops.iter().any(|(_, op)| matches!(op, Op::Nc(_)))
}
