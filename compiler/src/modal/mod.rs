//! Pass `modal` (issue #14): which G code is in force in each modal group
//! before every operation, as far as the compiler can know it.
//!
//! A forward data-flow analysis over each function's control-flow graph.
//! The fact of a group is the code in force on every path that reaches
//! the point, or `Unknown` when paths differ or a code is computed. A
//! join makes unknown only the groups whose codes really differ.
//!
//! Calls are analysed across programs, in two phases. First every
//! program gets a summary: the state at its returns as a function of the
//! state it was called in (a group it does not touch stays `Entry`, "as
//! the caller left it"); summaries are found by iteration, so recursion
//! is no special case. Then the states are found from the main program
//! down: a program starts in the join of the states of its call sites,
//! and a call site's state after the call is the callee's summary
//! applied to the state before it.
//!
//! The rules are the kernel's (`nc::modal` and `Nc::modal_settings`),
//! and where the compiler cannot follow the kernel it gives up the group
//! rather than guess:
//! - a computed G word can be any code: every group is unknown after it;
//! - any group-01 code cancels the drilling cycles (G80);
//! - G54–G59 in a block with G50 is ignored; G13.1 ends the polar
//!   command mode too;
//! - G28, G30, G71–G73 with P, and M02/M30 leave G40 in force;
//! - G70 runs its profile blocks as blocks, then puts the motion and the
//!   compensation back; G71–G73 only read theirs;
//! - between G10 and G11 blocks are data, not commands, except that a
//!   parameter may switch G20/G21: units are unknown there;
//! - under G66 any block may call the macro: its summary is joined in;
//! - M99 and its repeat count run a program again from its start, and
//!   `M99 P`, a computed GOTO and G65 H80–H86 may enter a program at any
//!   numbered block: those blocks join every such state.
//!
//! Decision: group 12 (G66/G67) is not a fact of its own here: the VM,
//! not the kernel, keeps the modal call (#4012 reads G67 always), so the
//! pass follows G66 as the calls it makes, in [`State::g66`].
//!
//! The position is followed too, where the kernel's reader gives it
//! (`position`): through plain moves, G50 and blocks that do not move.

pub mod position;

pub use position::Position;

use crate::ir::{
    Block, Call, CallKind, Callee, Count, Expr, Function, Handle, Module, NcBlock, NcKind, Op,
    Terminator, VarTarget, WordValue,
};
use nc::block::round_half_away;
use nc::gcode::{self, Code, Comp, Drill, OneShot, Polar, PolarCmd, G};
use nc::Machine;
use smallvec::SmallVec;

/// The modal groups the pass follows, in `#4001…` order.
pub const GROUPS: [u8; 12] = [
    gcode::MOTION,
    gcode::SPEED_MODE,
    gcode::FEED_MODE,
    gcode::UNITS,
    gcode::COMP,
    gcode::STROKE,
    gcode::DRILL,
    gcode::WORK,
    gcode::EXACT,
    gcode::PLANE,
    gcode::POLAR_CMD,
    gcode::POLAR,
];

/// A group's name for listings.
pub fn group_name(group: u8) -> &'static str {
    match group {
        gcode::MOTION => "motion",
        gcode::SPEED_MODE => "speed mode",
        gcode::FEED_MODE => "feed mode",
        gcode::UNITS => "units",
        gcode::COMP => "compensation",
        gcode::STROKE => "stroke check",
        gcode::DRILL => "drilling cycle",
        gcode::WORK => "work system",
        gcode::EXACT => "path mode",
        gcode::PLANE => "plane",
        gcode::POLAR_CMD => "polar command",
        gcode::POLAR => "polar interpolation",
        _ => "?",
    }
}

/// What is known of one modal value at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fact<T> {
    /// What the caller left in force (in a summary only).
    Entry,
    /// This value on every path.
    Is(T),
    /// Paths differ, or the value is set at run time.
    Unknown,
}

impl<T: Copy + PartialEq> Fact<T> {
    fn join(self, other: Fact<T>) -> Fact<T> {
        if self == other {
            self
        } else {
            Fact::Unknown
        }
    }

    /// This fact of a summary, applied where the call is made.
    fn at_call(self, before: Fact<T>) -> Fact<T> {
        match self {
            Fact::Entry => before,
            other => other,
        }
    }
}

/// The macro a G66 in force calls after a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModalCall {
    Off,
    /// A program of the module, by index.
    Program(u32),
}

/// The modal state at a point of the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct State {
    pub groups: Groups,
    pub g66: Fact<ModalCall>,
    /// Between G10 and G11.
    pub data: Fact<bool>,
    /// Where the tool stands (`position`).
    pub pos: Position,
    /// What the profile blocks waiting for their G70–G73 set, in the
    /// order they run (`Entry`: a group they leave alone).
    profile: Groups,
}

/// A fact per group, by index into [`GROUPS`].
pub type Groups = [Fact<Code>; GROUPS.len()];

/// Puts `code` in force in `group`.
fn set(groups: &mut Groups, group: u8, code: Code) {
    if let Some(i) = GROUPS.iter().position(|&g| g == group) {
        groups[i] = Fact::Is(code);
    }
}

impl State {
    /// Power-on: the machine's codes (machine.md §1), no G66, no G10.
    pub fn power_on(m: &Machine) -> State {
        let modal = nc::modal::Modal::power_on(m);
        State {
            groups: GROUPS.map(|g| Fact::Is(modal.group(g))),
            g66: Fact::Is(ModalCall::Off),
            data: Fact::Is(false),
            // (A program starts wherever the last one left the tool.)
            pos: [Fact::Unknown; 2],
            profile: [Fact::Entry; GROUPS.len()],
        }
    }

    /// As the caller left it (the start of a summary). Summaries are
    /// made with G66 and G10 off: a call made under either knows nothing
    /// after it.
    fn entry() -> State {
        State {
            groups: [Fact::Entry; GROUPS.len()],
            g66: Fact::Is(ModalCall::Off),
            data: Fact::Is(false),
            pos: [Fact::Entry; 2],
            profile: [Fact::Entry; GROUPS.len()],
        }
    }

    /// Nothing known.
    fn unknown() -> State {
        State {
            groups: [Fact::Unknown; GROUPS.len()],
            g66: Fact::Unknown,
            data: Fact::Unknown,
            pos: [Fact::Unknown; 2],
            profile: [Fact::Unknown; GROUPS.len()],
        }
    }

    /// Whether a summary made from [`State::entry`] applies here.
    fn summarised(&self) -> bool {
        self.g66 == Fact::Is(ModalCall::Off) && self.data == Fact::Is(false)
    }

    /// The code in force in `group`, when it is known.
    pub fn code(&self, group: u8) -> Option<Code> {
        let i = GROUPS.iter().position(|&g| g == group)?;
        match self.groups[i] {
            Fact::Is(c) => Some(c),
            _ => None,
        }
    }

    /// The coordinates of the position that are known here: the radius
    /// (X / 2) and Z, in mm, as the kernel holds them.
    pub fn position(&self) -> [Option<f64>; 2] {
        self.pos.map(|f| match f {
            Fact::Is(bits) => Some(f64::from_bits(bits)),
            Fact::Entry | Fact::Unknown => None,
        })
    }

    /// The groups whose code is not known here.
    pub fn unknown_groups(&self) -> impl Iterator<Item = u8> + '_ {
        GROUPS
            .iter()
            .zip(&self.groups)
            .filter(|(_, f)| !matches!(f, Fact::Is(_)))
            .map(|(&g, _)| g)
    }

    fn join(&self, other: &State) -> State {
        let join = |a: &Groups, b: &Groups| {
            let mut out = *a;
            for (x, y) in out.iter_mut().zip(b) {
                *x = x.join(*y);
            }
            out
        };
        State {
            groups: join(&self.groups, &other.groups),
            g66: self.g66.join(other.g66),
            data: self.data.join(other.data),
            pos: [0, 1].map(|i| self.pos[i].join(other.pos[i])),
            profile: join(&self.profile, &other.profile),
        }
    }

    /// The state after a call whose callee returns in `summary`.
    fn after_call(&self, summary: &State) -> State {
        let mut groups = summary.groups;
        for (a, b) in groups.iter_mut().zip(&self.groups) {
            *a = a.at_call(*b);
        }
        State {
            groups,
            g66: summary.g66.at_call(self.g66),
            data: summary.data.at_call(self.data),
            pos: [0, 1].map(|i| summary.pos[i].at_call(self.pos[i])),
            // (Profile blocks waiting across a call: the callee may run
            // them, or add its own.)
            profile: core::array::from_fn(|i| match (self.profile[i], summary.profile[i]) {
                (Fact::Entry, Fact::Entry) => Fact::Entry,
                _ => Fact::Unknown,
            }),
        }
    }

    fn set(&mut self, group: u8, code: Code) {
        set(&mut self.groups, group, code);
    }

    fn forget(&mut self, group: u8) {
        if let Some(i) = GROUPS.iter().position(|&g| g == group) {
            self.groups[i] = Fact::Unknown;
        }
    }
}

/// `a ⊔ b`, where `None` is a point no path reaches.
fn join(a: Option<State>, b: &State) -> State {
    a.map_or(*b, |a| a.join(b))
}

/// The facts of a module: for each function, the state before each
/// operation (by op handle; `None` where no path from the main program
/// reaches it).
#[derive(Debug, Default)]
pub struct Facts {
    pub functions: Vec<Vec<Option<State>>>,
}

impl Facts {
    /// The state before operation `op` of function `f`.
    pub fn before(&self, f: usize, op: Handle<Op>) -> Option<&State> {
        self.functions.get(f)?.get(op.index())?.as_ref()
    }
}

/// How many rounds of the two phases run before the pass gives up (and
/// knows nothing): the facts only climb a lattice of height 2 per group,
/// so real programs settle in a few.
const MAX_ROUNDS: usize = 64;

/// Runs the pass over a module built for `machine`.
pub fn analyze(m: &Module, machine: &Machine) -> Facts {
    let module = ModuleFacts::of(m, machine);
    let summaries = summaries(m, &module);
    let mut entries: Vec<Option<State>> = vec![None; m.functions.len()];
    if let Some(e) = entries.first_mut() {
        *e = Some(State::power_on(machine));
    }
    for _ in 0..MAX_ROUNDS {
        let mut next = entries.clone();
        let mut facts = Facts::default();
        for (i, f) in m.functions.iter().enumerate() {
            let run = Walk::new(f, &summaries, &module, i).run(entries[i]);
            for (callee, at) in &run.calls {
                if let Some(slot) = next.get_mut(*callee as usize) {
                    *slot = Some(join(*slot, at));
                }
            }
            facts.functions.push(run.before);
        }
        if next == entries {
            return facts;
        }
        entries = next;
    }
    Facts {
        functions: m.functions.iter().map(unknown_facts).collect(),
    }
}

fn unknown_facts(f: &Function) -> Vec<Option<State>> {
    vec![Some(State::unknown()); f.ops.len()]
}

/// Phase one: each program's state at its returns, from [`State::entry`];
/// `None` for a program that never returns.
fn summaries(m: &Module, module: &ModuleFacts) -> Vec<Option<State>> {
    let mut sums: Vec<Option<State>> = vec![None; m.functions.len()];
    // (Only a call reads a summary: a program nothing calls, the main
    // one mostly, needs none, and its walks were most of the pass.)
    let called = module.called(m);
    for _ in 0..MAX_ROUNDS {
        let next: Vec<Option<State>> = m
            .functions
            .iter()
            .enumerate()
            .map(|(i, f)| match called.get(i) {
                Some(true) => {
                    Walk::new(f, &sums, module, i)
                        .run(Some(State::entry()))
                        .exit
                }
                _ => None,
            })
            .collect();
        if next == sums {
            return sums;
        }
        sums = next;
    }
    vec![Some(State::unknown()); m.functions.len()]
}

/// The analysis of one function, from a given entry state.
struct Walk<'a> {
    f: &'a Function,
    summaries: &'a [Option<State>],
    module: &'a ModuleFacts,
    /// The state at the start of each block (by handle).
    block_in: Vec<Option<State>>,
    /// The states that may enter at a numbered block (`Op::Seq`).
    seq_in: Option<State>,
    /// The function may run again from its start when it returns.
    repeats: bool,
}

/// What the walks of every function need to know of the whole module.
struct ModuleFacts {
    /// A subprogram returns with M99 P, into its caller at a numbered
    /// block the pass does not follow.
    m99_p: bool,
    /// By function: whether it may run more than once per call. The main
    /// program's M99 starts it again (`gbvm run --repeat`); a call's count
    /// other than a constant 0 or 1 repeats the callee; a call whose
    /// program is computed may repeat any.
    repeats: Vec<bool>,
    /// By function: its program number.
    numbers: Vec<u32>,
    /// The machine, whose reader the position is read with.
    machine: Machine,
    /// A block has G7.1 (cylindrical interpolation): the position is not
    /// followed.
    cylindrical: bool,
}

impl ModuleFacts {
    fn of(m: &Module, machine: &Machine) -> ModuleFacts {
        let numbers: Vec<u32> = m.functions.iter().map(|f| f.number).collect();
        let mut repeats = vec![false; m.functions.len()];
        if let Some(main) = repeats.first_mut() {
            *main = true;
        }
        for f in &m.functions {
            for (_, b) in f.blocks.iter() {
                let Some(Terminator::Call { call, .. }) = &b.term else {
                    continue;
                };
                match callee_in(&numbers, f, call.callee) {
                    Some(i) if !once(f, call.count) => {
                        if let Some(r) = repeats.get_mut(i as usize) {
                            *r = true;
                        }
                    }
                    Some(_) => {}
                    None => repeats.iter_mut().for_each(|r| *r = true),
                }
            }
        }
        ModuleFacts {
            m99_p: returns_to_seq(m),
            repeats,
            numbers,
            machine: machine.clone(),
            cylindrical: uses_cylindrical(m),
        }
    }

    /// The functions a call may run: one, or (its program computed) any.
    /// By function: whether a call (M98, G65, G66) may run it.
    fn called(&self, m: &Module) -> Vec<bool> {
        let mut called = vec![false; m.functions.len()];
        for f in &m.functions {
            for (_, b) in f.blocks.iter() {
                let Some(Terminator::Call { call, .. }) = &b.term else {
                    continue;
                };
                for i in self.callees(f, call.callee) {
                    if let Some(c) = called.get_mut(i as usize) {
                        *c = true;
                    }
                }
            }
        }
        called
    }

    fn callees(&self, f: &Function, callee: Callee) -> Vec<u32> {
        match callee_in(&self.numbers, f, callee) {
            Some(i) => vec![i],
            None => (0..self.numbers.len() as u32).collect(),
        }
    }
}

/// The function a call runs (by index), when it is known: a program of
/// the module, or a computed number that folded to one of `numbers`.
fn callee_in(numbers: &[u32], f: &Function, callee: Callee) -> Option<u32> {
    match callee {
        Callee::Program(i) => Some(i),
        Callee::Dynamic(h) => match f.exprs.get(h) {
            Some(Expr::Const(v)) => numbers
                .iter()
                .position(|&n| f64::from(n) == *v)
                .map(|i| i as u32),
            _ => None,
        },
    }
}

/// Whether a call's count runs its callee once: a constant 0 or 1.
fn once(f: &Function, count: Count) -> bool {
    match count {
        Count::Expr(h) => matches!(f.exprs.get(h), Some(Expr::Const(v)) if *v == 0.0 || *v == 1.0),
        Count::Packed => false,
    }
}

/// What a walk finds.
struct Run {
    before: Vec<Option<State>>,
    exit: Option<State>,
    /// Each call made, with the state before it.
    calls: Vec<(u32, State)>,
}

impl<'a> Walk<'a> {
    fn new(
        f: &'a Function,
        summaries: &'a [Option<State>],
        module: &'a ModuleFacts,
        index: usize,
    ) -> Walk<'a> {
        Walk {
            f,
            summaries,
            module,
            block_in: vec![None; f.blocks.len()],
            seq_in: module.m99_p.then(State::unknown),
            repeats: module.repeats.get(index).copied().unwrap_or(true),
        }
    }

    /// Iterates to the fixed point, then records it.
    fn run(mut self, entry: Option<State>) -> Run {
        let Some(start) = self.f.layout.first().copied() else {
            return self.record();
        };
        let Some(entry) = entry else {
            return self.record();
        };
        self.block_in[start.index()] = Some(entry);
        for _ in 0..MAX_ROUNDS {
            if !self.round(start) {
                return self.record();
            }
        }
        self.block_in = vec![Some(State::unknown()); self.f.blocks.len()];
        self.record()
    }

    /// One pass over the layout; whether any state changed.
    fn round(&mut self, start: Handle<Block>) -> bool {
        let mut changed = false;
        for &b in &self.f.layout {
            let Some(out) = self.block(b, self.block_in[b.index()], None) else {
                continue;
            };
            for (target, state) in self.edges(b, start, out) {
                changed |= self.flow_into(target, &state);
            }
        }
        changed
    }

    /// Joins `state` into where `target` says.
    fn flow_into(&mut self, target: Target, state: &State) -> bool {
        let slot = match target {
            Target::Block(b) => match self.block_in.get_mut(b.index()) {
                Some(slot) => slot,
                None => return false,
            },
            Target::Numbered => &mut self.seq_in,
        };
        let new = join(*slot, state);
        let changed = *slot != Some(new);
        *slot = Some(new);
        changed
    }

    /// Runs the operations of block `b` from `s` (`None`: unreached, but
    /// a numbered block may be entered by a jump to its number); the
    /// state after them and, with `record`, the state before each.
    fn block(
        &self,
        b: Handle<Block>,
        mut s: Option<State>,
        mut record: Option<&mut Vec<Option<State>>>,
    ) -> Option<State> {
        let block = self.f.blocks.get(b)?;
        for &op in &block.ops {
            let o = self.f.ops.get(op);
            if let (Some(Op::Seq(..)), Some(seq)) = (o, &self.seq_in) {
                s = Some(join(s, seq));
            }
            if let Some(before) = record.as_deref_mut().and_then(|r| r.get_mut(op.index())) {
                *before = s;
            }
            if let (Some(o), Some(now)) = (o, s) {
                s = Some(self.op(o, now));
            }
        }
        s
    }

    /// Where control goes after block `b`, in state `out`.
    fn edges(&self, b: Handle<Block>, start: Handle<Block>, out: State) -> Vec<(Target, State)> {
        let Some(term) = self.f.blocks.get(b).and_then(|k| k.term.as_ref()) else {
            return Vec::new();
        };
        match term {
            Terminator::Call { call, next } => match self.after_call(call, &out) {
                Some(after) => vec![(Target::Block(*next), after)],
                None => Vec::new(),
            },
            // Run again from the start (M99, a count), or from a number.
            Terminator::Return { seq: None } if self.repeats => {
                vec![(Target::Block(start), out)]
            }
            Terminator::Return { seq: None } => Vec::new(),
            Terminator::Return { seq: Some(_) } | Terminator::Goto { .. } => {
                vec![(Target::Numbered, out)]
            }
            Terminator::GotoIf { next, .. } => {
                vec![(Target::Block(*next), out), (Target::Numbered, out)]
            }
            t => t.successors().map(|s| (Target::Block(s), out)).collect(),
        }
    }

    /// The state after a call, `None` when the callee never returns.
    fn after_call(&self, call: &Call, before: &State) -> Option<State> {
        let callee = callee_in(&self.module.numbers, self.f, call.callee);
        if call.kind == CallKind::Modal {
            let mut s = *before;
            s.g66 = callee.map_or(Fact::Unknown, |i| Fact::Is(ModalCall::Program(i)));
            return Some(s);
        }
        // (A count of 0 runs the callee once, as 1 does.)
        match callee {
            Some(_) if !before.summarised() => Some(State::unknown()),
            Some(i) => Some(before.after_call(self.summaries.get(i as usize)?.as_ref()?)),
            None => Some(State::unknown()),
        }
    }

    /// The state after one operation.
    fn op(&self, op: &Op, s: State) -> State {
        match op {
            Op::Nc(nc) if nc.kind == NcKind::Profile => profile_block(self.f, nc, s),
            Op::Nc(nc) => {
                let after = nc_block(self.f, nc, s, self.module);
                self.modal_call_after(after)
            }
            Op::ModalCancel => State {
                g66: Fact::Is(ModalCall::Off),
                ..s
            },
            // A system variable may be a work or tool offset: the zero,
            // and so the tool's coordinates, may move.
            Op::Assign {
                target: VarTarget::Direct(n),
                ..
            }
            | Op::MacroA { dst: n, .. }
                if *n < 1000 =>
            {
                s
            }
            Op::Assign { .. } | Op::MacroA { .. } => State {
                pos: [Fact::Unknown; 2],
                ..s
            },
            Op::Seq(..) | Op::Alarm { .. } | Op::UserAlarm { .. } | Op::Charge => s,
        }
    }

    /// Under G66 the block may have called the macro (a move does).
    fn modal_call_after(&self, s: State) -> State {
        match s.g66 {
            Fact::Is(ModalCall::Off) => s,
            Fact::Is(ModalCall::Program(i)) => match self.summaries.get(i as usize) {
                Some(Some(sum)) => s.join(&s.after_call(sum)),
                // A macro that never returns: after the call nothing runs.
                _ => s,
            },
            Fact::Entry | Fact::Unknown => s.join(&State::unknown()),
        }
    }

    /// Runs the fixed point once more, keeping the state before each op,
    /// the exit state and the call sites.
    fn record(&self) -> Run {
        let mut before = vec![None; self.f.ops.len()];
        let mut exit = None;
        let mut calls = Vec::new();
        for &b in &self.f.layout {
            let Some(out) = self.block(b, self.block_in[b.index()], Some(&mut before)) else {
                continue;
            };
            match self.f.blocks.get(b).and_then(|k| k.term.as_ref()) {
                Some(Terminator::Return { .. }) => exit = Some(join(exit, &out)),
                Some(Terminator::Call { call, .. }) => {
                    for i in self.module.callees(self.f, call.callee) {
                        calls.push((i, out));
                    }
                }
                _ => {}
            }
            self.g66_calls(b, &before, &mut calls);
        }
        Run {
            before,
            exit,
            calls,
        }
    }

    /// The macro calls G66 makes from the NC blocks of block `b`.
    fn g66_calls(&self, b: Handle<Block>, before: &[Option<State>], calls: &mut Vec<(u32, State)>) {
        let Some(block) = self.f.blocks.get(b) else {
            return;
        };
        for &op in &block.ops {
            let Some(Some(s)) = before.get(op.index()) else {
                continue;
            };
            let Some(Op::Nc(nc)) = self.f.ops.get(op) else {
                continue;
            };
            let after = nc_block(self.f, nc, *s, self.module);
            match (nc.kind, s.g66) {
                (NcKind::Profile, _) | (_, Fact::Is(ModalCall::Off)) => {}
                (_, Fact::Is(ModalCall::Program(i))) => calls.push((i, after)),
                // (Under a G66 of a computed program, any.)
                _ => calls.extend((0..self.module.numbers.len() as u32).map(|i| (i, after))),
            }
        }
    }
}

/// Where a state flows.
#[derive(Debug, Clone, Copy)]
enum Target {
    Block(Handle<Block>),
    /// Every numbered block of the function.
    Numbered,
}

/// Whether a block of the module has G7.1, written or computed.
fn uses_cylindrical(m: &Module) -> bool {
    m.functions.iter().any(|f| {
        f.ops.iter().any(|(_, op)| match op {
            Op::Nc(nc) => {
                g_codes(f, nc).is_none_or(|codes| codes.contains(&OneShot::Cylindrical.code()))
            }
            _ => false,
        })
    })
}

/// Whether a subprogram returns with `M99 P` somewhere in the module.
fn returns_to_seq(m: &Module) -> bool {
    m.functions.iter().skip(1).any(|f| {
        f.blocks
            .iter()
            .any(|(_, b)| matches!(b.term, Some(Terminator::Return { seq: Some(_) })))
    })
}

/// A block's G codes, or `None` when one of them is computed.
fn g_codes(f: &Function, nc: &NcBlock) -> Option<SmallVec<[Code; 4]>> {
    let mut codes = SmallVec::new();
    for w in f.words_of(nc) {
        if w.addr != b'G' - b'A' {
            continue;
        }
        match w.value() {
            WordValue::Const(v, _) if (0.0..=9999.0).contains(&v) => {
                codes.push(round_half_away(v * 10.0) as Code)
            }
            // Out of range: the kernel's alarm, nothing runs after it.
            WordValue::Const(..) => {}
            WordValue::Expr(_) => return None,
        }
    }
    Some(codes)
}

/// Whether the block has a literal M02 or M30, or a P word.
fn has_word(f: &Function, nc: &NcBlock, letter: u8, values: &[f64]) -> bool {
    f.words_of(nc).iter().any(|w| {
        w.addr == letter - b'A'
            && match w.value() {
                WordValue::Const(v, _) => values.is_empty() || values.contains(&v),
                WordValue::Expr(_) => values.is_empty(),
            }
    })
}

/// The state after an NC block the kernel runs.
fn nc_block(f: &Function, nc: &NcBlock, s: State, module: &ModuleFacts) -> State {
    let Some(codes) = g_codes(f, nc) else {
        // Any code, G10 included.
        return s.join(&State::unknown());
    };
    let has = |c: OneShot| codes.contains(&c.code());
    if has(OneShot::DataSetting) {
        return State {
            data: Fact::Is(true),
            ..s
        };
    }
    if has(OneShot::DataSettingEnd) {
        return State {
            data: Fact::Is(false),
            ..s
        };
    }
    let mut data = s;
    data.forget(gcode::UNITS);
    // (A G10 L52 block's R#var may write a work offset.)
    if has_word(f, nc, b'R', &[]) {
        data.pos = [Fact::Unknown; 2];
    }
    match s.data {
        Fact::Is(false) => commands(f, nc, &codes, s, module),
        Fact::Is(true) => data,
        Fact::Entry | Fact::Unknown => data.join(&commands(f, nc, &codes, s, module)),
    }
}

/// The state after a block of commands (not data) with these G codes.
fn commands(
    f: &Function,
    nc: &NcBlock,
    codes: &[Code],
    mut s: State,
    module: &ModuleFacts,
) -> State {
    s.pos = match module.cylindrical {
        // (The pass does not follow G7.1's mode, in which moves are
        // taken on the unrolled cylinder.)
        true => [Fact::Unknown; 2],
        false => position::after_block(f, nc, codes, &s, &module.machine),
    };
    let g50 = codes.contains(&OneShot::SetCoordinates.code());
    for &code in codes {
        set_code(&mut s.groups, code, g50);
    }
    let has = |c: OneShot| codes.contains(&c.code());
    let roughing = has(OneShot::RoughTurn) || has(OneShot::RoughFace) || has(OneShot::Pattern);
    if has(OneShot::Home)
        || has(OneShot::HomeN)
        || (roughing && has_word(f, nc, b'P', &[]))
        || has_word(f, nc, b'M', &[2.0, 30.0])
    {
        s.set(gcode::COMP, Comp::Off.code());
    }
    if has(OneShot::Finish) {
        finish(&mut s);
    }
    if roughing || has(OneShot::Finish) {
        s.profile = [Fact::Entry; GROUPS.len()];
    }
    s
}

/// G70 runs its profile blocks as blocks, then puts the motion and the
/// compensation back as they were (`compound::finish`); G71–G73 only read
/// theirs.
fn finish(s: &mut State) {
    for (i, (now, profile)) in s.groups.iter_mut().zip(&s.profile).enumerate() {
        let restored = matches!(GROUPS[i], gcode::MOTION | gcode::COMP);
        if *profile != Fact::Entry && !restored {
            *now = *profile;
        }
    }
}

/// One G code of a block, as `Nc::modal_settings` puts it in force.
fn set_code(s: &mut Groups, code: Code, g50: bool) {
    let Some(g) = G::from_code(code) else {
        // Not of the dialect: the kernel's alarm.
        return;
    };
    match g {
        G::OneShot(_) | G::ModalCall(_) => {}
        G::Motion(_) => {
            set(s, gcode::MOTION, code);
            set(s, gcode::DRILL, Drill::Off.code());
        }
        G::Work(_) if g50 => {}
        G::Polar(Polar::Off) => {
            set(s, gcode::POLAR, code);
            set(s, gcode::POLAR_CMD, PolarCmd::Off.code());
        }
        _ => {
            if let Some(group) = gcode::group(code) {
                set(s, group, code);
            }
        }
    }
}

/// A profile block waits for its cycle: what it would set is added to
/// what the profile blocks before it set.
fn profile_block(f: &Function, nc: &NcBlock, mut s: State) -> State {
    let Some(codes) = g_codes(f, nc) else {
        s.profile = [Fact::Unknown; GROUPS.len()];
        return s;
    };
    let g50 = codes.contains(&OneShot::SetCoordinates.code());
    for &code in &codes {
        set_code(&mut s.profile, code, g50);
    }
    s
}

impl Facts {
    /// The `--emit=ir` note of an NC block: the groups whose code is not
    /// known before it and the coordinates of the position that are not,
    /// or that no path from the main program reaches it.
    pub fn note(&self, m: &Module, f: usize, op: Handle<Op>) -> Option<String> {
        let function = m.functions.get(f)?;
        if !matches!(function.ops.get(op), Some(Op::Nc(_))) {
            return None;
        }
        let Some(s) = self.before(f, op) else {
            return Some("modal: not reached".into());
        };
        let mut unknown: Vec<&str> = s.unknown_groups().map(group_name).collect();
        for (known, axis) in s.position().iter().zip(["position X", "position Z"]) {
            if known.is_none() {
                unknown.push(axis);
            }
        }
        (!unknown.is_empty()).then(|| format!("modal unknown: {}", unknown.join(", ")))
    }
}
