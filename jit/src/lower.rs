//! One loop's bytecode as a Cranelift function
//! `fn(ctx: *mut Ctx, entry: u32) -> u32`: it runs from `entry` and
//! returns the pc at which the interpreter goes on.
//!
//! Registers and the loop's locals and commons live in Cranelift variables
//! (`declare_var`/`def_var`/`use_var`), loaded from the VM once at the
//! entry. A variable's write also goes to the VM at once; a register is
//! written into the VM only where the code leaves or calls the kernel, and
//! only if the interpreter may read it from there (`store_live`: the
//! registers are an expression's temporaries, most of them dead by the
//! next statement). The block count and the fuel are variables too,
//! written into the context at the exit and before a call of the kernel's
//! executor. The arithmetic is the kernel's
//! (`nc::value`) written out: vacant counts as 0, a result that is not
//! finite faults, −0 becomes 0; the same IEEE operations in the same
//! order, none fused. The functions that round call the kernel's code
//! itself (`helpers`): SIN, COS, ATAN and EXP, which have no domain to
//! check, directly, the check of their result inline; TAN, ASIN, ACOS,
//! LN, ROUND, BIN and BCD, MOD and the bitwise operations through the
//! kernel's `value` functions, which check and raise.
//!
//! The code is written for a short compile (at `Level::Quick` the
//! optimiser is off): no `num` of a value known not to be vacant, a
//! variable's `num` kept beside it (`Cached`: tested where it is stored,
//! not in every round that reads it), no −0 made 0 where the value cannot
//! be −0, a comparison with a constant decided by the strict comparison
//! alone where the value is far from the constant (the tolerance of
//! `near` out of line), a comparison followed by its `jumpifnot` branches
//! on the truth value, the leaving paths out of line, and in a
//! restartable run (`Region::restart`) the finite checks summed and
//! tested once at its end.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::mem::offset_of;

use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::immediates::Ieee64;
use cranelift_codegen::ir::{
    types, Block, BlockArg, FuncRef, InstBuilder, MemFlags, SigRef, Type, Value,
};
use cranelift_frontend::{FunctionBuilder, Switch, Variable};
use isa::{Instr, Module};
use nc::value::{Bin, Func, Rel, VACANT};
use vm::Ran;

use crate::helpers::{self, binary_code};
use crate::native::Ctx;
use crate::region::{dead_at, is_block, is_native, is_pure, Place, Region};

/// Bounds around a finite constant `c` beyond which no finite value is
/// `near` it: c ∓ 4·10⁻⁹·max(1, |c|). `near(a, c)` needs
/// |a − c| ≤ 10⁻⁹·max(1, |a|, |c|): where |a| ≤ max(1, |c|) the distance
/// is at least four times that bound; where |a| is larger, a lies beyond
/// c on the side away from 0, and |a − c| ≥ |a| − |c| with
/// |a| ≥ |c|·(1 + 4·10⁻⁹), so |a − c| > 10⁻⁹·|a|. Both with a margin of
/// nearly 3·10⁻⁹ relative, far above the rounding of these few
/// operations (10⁻¹⁶).
/// (±∞ is `near` every finite value: the check excludes it.)
pub fn far_bounds(c: f64) -> (f64, f64) {
    let margin = 4e-9 * c.abs().max(1.0);
    (c - margin, c + margin)
}

/// The helpers, imported into the function being built.
pub struct Refs {
    /// `fn(f64) -> f64`, for the functions of `helpers::total`.
    pub unary: SigRef,
    pub binary: FuncRef,
    pub func: FuncRef,
    pub atan2: FuncRef,
    pub push_word: FuncRef,
    pub block: FuncRef,
}

/// The pointers the entry block loads from the context (they dominate
/// every other block).
struct Bases {
    regs: Value,
    locals: Value,
    common: Value,
    persistent: Value,
    words: Value,
    max_blocks: Value,
}

/// The arithmetic written out inline.
#[derive(Clone, Copy)]
enum Arith {
    Add,
    Sub,
    Mul,
    Div,
}

/// A local or common variable of the loop: its value, and its value as
/// `num` takes it (vacant as 0), kept beside it so that a round reads a
/// variable's number without testing it: the test is made where the
/// value is loaded or stored, and only there if it may be vacant.
#[derive(Clone, Copy)]
struct Cached {
    value: Variable,
    num: Variable,
}

/// An operand: a register or a constant-pool entry.
#[derive(Clone, Copy)]
enum Src {
    Reg(u8),
    Const(u32),
}

pub struct Lower<'a, 'f> {
    b: FunctionBuilder<'f>,
    module: &'a Module,
    region: &'a Region,
    refs: Refs,
    ctx: Value,
    ptr: Type,
    bases: Bases,
    /// A variable per register below `num_regs` that the loop uses.
    regs: Vec<Option<Variable>>,
    vars: BTreeMap<u32, Cached>,
    blocks: Variable,
    fuel: Variable,
    labels: BTreeMap<u32, Block>,
    exit: Block,
    /// Values known not to be vacant (constants, results that passed the
    /// finite check): `num` of one is itself.
    plain: HashSet<Value>,
    /// Values known not to be −0 (constants, results of `plain_zero`, a
    /// sum with one such term): `plain_zero` of one is itself.
    unsigned_zero: HashSet<Value>,
    /// Values known to be finite (finite constants, results that passed
    /// the finite check, truth values).
    finite: HashSet<Value>,
    /// A variable's value as read, its `num` as read beside it, and the
    /// block that read them: the `num` holds where that block dominates
    /// (a value the variable had on every path can have a `num` that
    /// differs by path, a block parameter).
    num_of: HashMap<Value, (Value, Block)>,
    /// The blocks entered only from one block (a guard's way on, a
    /// join of paths that split in it): that block, their immediate
    /// dominator.
    idom: HashMap<Block, Block>,
    /// The register the last instruction set to a comparison's result,
    /// with that result as a truth value (a `jumpifnot` right after it
    /// branches on the truth value).
    last_compare: Option<(u8, Value)>,
    /// A comparison's register not written (`Region::branches_on`): the
    /// `jumpifnot`'s pc, the register and the truth value, for an exit
    /// at that pc to write it.
    unwritten: Option<(u32, u8, Value)>,
    /// In a restartable run (`Region::restart`): its start, and its
    /// results so far, whose finite check is at its end (`check_run`).
    pending: Option<(u32, Vec<Value>)>,
}

const TRUSTED: MemFlags = MemFlags::trusted();

impl<'a, 'f> Lower<'a, 'f> {
    /// Builds the whole function into `b` (whose signature is set).
    pub fn build(
        mut b: FunctionBuilder<'f>,
        module: &'a Module,
        region: &'a Region,
        refs: Refs,
        ptr: Type,
        num_regs: usize,
    ) {
        let start = b.create_block();
        b.append_block_params_for_function_params(start);
        b.switch_to_block(start);
        let (ctx, entry) = (b.block_params(start)[0], b.block_params(start)[1]);
        let field = |b: &mut FunctionBuilder, ty: Type, offset: usize| {
            b.ins().load(ty, TRUSTED, ctx, offset as i32)
        };
        let bases = Bases {
            regs: field(&mut b, ptr, offset_of!(Ctx, regs)),
            locals: field(&mut b, ptr, offset_of!(Ctx, locals)),
            common: field(&mut b, ptr, offset_of!(Ctx, common)),
            persistent: field(&mut b, ptr, offset_of!(Ctx, persistent)),
            words: field(&mut b, ptr, offset_of!(Ctx, words)),
            max_blocks: field(&mut b, types::I64, offset_of!(Ctx, max_blocks)),
        };
        let blocks = b.declare_var(types::I64);
        let fuel = b.declare_var(types::I64);
        let exit = b.create_block();
        b.append_block_param(exit, types::I32);
        let mut regs = vec![None; num_regs];
        for &r in &region.regs {
            if let Some(slot) = regs.get_mut(r as usize) {
                *slot = Some(b.declare_var(types::F64));
            }
        }
        let vars = region
            .vars
            .iter()
            .map(|&n| {
                let value = b.declare_var(types::F64);
                let num = b.declare_var(types::F64);
                (n, Cached { value, num })
            })
            .collect();
        let labels = region
            .leaders
            .iter()
            .map(|&pc| (pc, b.create_block()))
            .collect();
        let mut lower = Lower {
            b,
            module,
            region,
            refs,
            ctx,
            ptr,
            bases,
            regs,
            vars,
            blocks,
            fuel,
            labels,
            exit,
            plain: HashSet::new(),
            unsigned_zero: HashSet::new(),
            finite: HashSet::new(),
            num_of: HashMap::new(),
            idom: HashMap::new(),
            last_compare: None,
            unwritten: None,
            pending: None,
        };
        lower.load_state(entry);
        lower.body();
        lower.exit_block();
        lower.b.seal_all_blocks();
        lower.b.finalize();
    }

    /// The entry: the state into variables, then on to the entry's block.
    fn load_state(&mut self, entry: Value) {
        for (r, var) in self.cached_regs() {
            let v = self
                .b
                .ins()
                .load(types::F64, TRUSTED, self.bases.regs, 8 * r);
            self.b.def_var(var, v);
        }
        for (base, offset, var) in self.cached_vars() {
            let v = self.b.ins().load(types::F64, TRUSTED, base, offset);
            self.def_cached(var, v);
        }
        let blocks = self.load_ctx(types::I64, offset_of!(Ctx, blocks));
        self.b.def_var(self.blocks, blocks);
        let fuel = self.load_ctx(types::I64, offset_of!(Ctx, fuel));
        self.b.def_var(self.fuel, fuel);
        let mut switch = Switch::new();
        for &pc in &self.region.entries {
            if let Some(&block) = self.labels.get(&pc) {
                switch.set_entry(u128::from(pc), block);
            }
        }
        // An entry the loop does not have runs nothing.
        let nowhere = self.b.create_block();
        switch.emit(&mut self.b, entry, nowhere);
        self.b.switch_to_block(nowhere);
        self.b.ins().jump(self.exit, &[BlockArg::Value(entry)]);
    }

    /// The exit: the counters written, the pc returned (the rest of the
    /// state is in the VM already).
    fn exit_block(&mut self) {
        self.b.switch_to_block(self.exit);
        let pc = self.b.block_params(self.exit)[0];
        self.store_counters();
        self.b.ins().return_(&[pc]);
    }

    fn cached_regs(&self) -> Vec<(i32, Variable)> {
        (0..)
            .zip(&self.regs)
            .filter_map(|(r, v)| v.map(|v| (r, v)))
            .collect()
    }

    fn cached_vars(&self) -> Vec<(Value, i32, Cached)> {
        self.vars
            .iter()
            .filter_map(|(&n, &var)| match Place::of(n) {
                Place::Local(i) => Some((self.bases.locals, 8 * i as i32, var)),
                Place::Common(i) => Some((self.bases.common, 8 * i as i32, var)),
                _ => None,
            })
            .collect()
    }

    fn load_ctx(&mut self, ty: Type, offset: usize) -> Value {
        self.b.ins().load(ty, TRUSTED, self.ctx, offset as i32)
    }

    /// Every instruction of the loop, in order; a leader starts a block.
    fn body(&mut self) {
        let mut open = false;
        for pc in self.region.head..=self.region.tail {
            let instr = self.module.code[pc as usize];
            let leader = self.labels.get(&pc).copied();
            if open && (leader.is_some() || !is_pure(&instr)) {
                self.check_run();
            }
            if let Some(block) = leader {
                if open {
                    self.b.ins().jump(block, &[]);
                }
                self.b.switch_to_block(block);
                self.last_compare = None;
            }
            let compare = self.last_compare.take();
            if let Instr::JumpIfNot { cond, target } = instr {
                self.last_compare = compare.filter(|&(r, _)| r == cond);
                self.jump_if_not(pc, cond, target);
                open = false;
                continue;
            }
            open = self.instr(pc, instr);
        }
        if open {
            self.check_run();
            self.exit_at(self.region.tail + 1);
        }
        // The blocks of leaders past the loop leave at their pc.
        let outside: Vec<(u32, Block)> = self
            .labels
            .range(self.region.tail + 1..)
            .map(|(&pc, &b)| (pc, b))
            .collect();
        for (pc, block) in outside {
            self.b.switch_to_block(block);
            self.exit_at(pc);
        }
    }

    /// One instruction; whether the block goes on after it.
    fn instr(&mut self, pc: u32, instr: Instr) -> bool {
        use Instr::*;
        if is_block(&instr) {
            // The code goes on after it where the kernel says so.
            self.block(pc);
            return true;
        }
        if !is_native(&instr) {
            self.exit_at(pc);
            return false;
        }
        match instr {
            LoadK { dst, k } => {
                let v = self.konst(k);
                self.set(dst, v);
            }
            LoadNull { dst } => {
                let v = self.f64(VACANT);
                self.set(dst, v);
            }
            Mov { dst, src } => {
                let v = self.reg(src);
                self.set(dst, v);
            }
            Neg { dst, a } => {
                let a = self.reg(a);
                let x = self.num(a);
                let v = self.b.ins().fneg(x);
                let v = self.plain_zero(v);
                self.set(dst, v);
            }
            Add { dst, a, b } => self.arith(pc, Arith::Add, dst, a, Src::Reg(b)),
            Sub { dst, a, b } => self.arith(pc, Arith::Sub, dst, a, Src::Reg(b)),
            Mul { dst, a, b } => self.arith(pc, Arith::Mul, dst, a, Src::Reg(b)),
            Div { dst, a, b } => self.arith(pc, Arith::Div, dst, a, Src::Reg(b)),
            AddK { dst, a, k } => self.arith(pc, Arith::Add, dst, a, Src::Const(k)),
            SubK { dst, a, k } => self.arith(pc, Arith::Sub, dst, a, Src::Const(k)),
            MulK { dst, a, k } => self.arith(pc, Arith::Mul, dst, a, Src::Const(k)),
            DivK { dst, a, k } => self.arith(pc, Arith::Div, dst, a, Src::Const(k)),
            Mod { dst, a, b } => self.binary_call(pc, Bin::Mod, dst, a, b),
            BitAnd { dst, a, b } => self.binary_call(pc, Bin::And, dst, a, b),
            BitOr { dst, a, b } => self.binary_call(pc, Bin::Or, dst, a, b),
            BitXor { dst, a, b } => self.binary_call(pc, Bin::Xor, dst, a, b),
            Func { dst, a, f } => self.func(pc, dst, a, f),
            Atan2 { dst, y, x } => {
                let (y, x) = (self.reg(y), self.reg(x));
                self.call_checked(pc, dst, self.refs.atan2, &[y, x]);
            }
            Cmp { dst, a, b, op } => self.compare(pc, dst, a, Src::Reg(b), op),
            CmpK { dst, a, k, op } => self.compare(pc, dst, a, Src::Const(k), op),
            LoadVar { dst, var } => {
                let v = self.load_var(var);
                self.set(dst, v);
            }
            StoreVar { var, src } => {
                self.charge(pc);
                let v = self.reg(src);
                self.store_var(var, v);
            }
            Word { addr, src } => self.word(addr, src),
            WordK { addr, k, flags } => {
                let v = self.konst(k);
                self.push_word(addr, v, flags);
            }
            Jump { target } => {
                self.jump(pc, target);
                return false;
            }
            Goto { target } => {
                // The GOTO block; a backward one is charged as the loop's
                // round, one that leaves the loop by the interpreter.
                if target > pc && self.region.contains(target) {
                    self.charge(pc);
                }
                self.jump(pc, target);
                return false;
            }
            Charge => self.charge(pc),
            _ => {
                self.exit_at(pc);
                return false;
            }
        }
        true
    }

    fn f64(&mut self, v: f64) -> Value {
        let value = self.b.ins().f64const(Ieee64::with_bits(v.to_bits()));
        if !v.is_nan() {
            self.plain.insert(value);
        }
        if v.to_bits() != (-0.0f64).to_bits() {
            self.unsigned_zero.insert(value);
        }
        if v.is_finite() {
            self.finite.insert(value);
        }
        value
    }

    fn konst(&mut self, k: u32) -> Value {
        let v = self
            .module
            .consts
            .get(k as usize)
            .copied()
            .unwrap_or(VACANT);
        self.f64(v)
    }

    fn reg(&mut self, r: u8) -> Value {
        match self.regs.get(r as usize).copied().flatten() {
            Some(var) => self.b.use_var(var),
            None => self.f64(VACANT),
        }
    }

    /// Sets a register: its variable. The VM's register is written where
    /// the code leaves or calls the kernel (`store_live`).
    fn set(&mut self, r: u8, v: Value) {
        if let Some(var) = self.regs.get(r as usize).copied().flatten() {
            self.b.def_var(var, v);
        }
    }

    /// Writes into the VM the registers the interpreter may read from
    /// `pc` on (`region::dead_at` says which it will not).
    fn store_live(&mut self, pc: u32) {
        for (r, var) in self.cached_regs() {
            let r8 = u8::try_from(r).unwrap_or(u8::MAX);
            if dead_at(&self.module.code, pc, r8) {
                continue;
            }
            let v = self.b.use_var(var);
            self.b.ins().store(TRUSTED, v, self.bases.regs, 8 * r);
        }
    }

    fn src(&mut self, s: Src) -> Value {
        match s {
            Src::Reg(r) => self.reg(r),
            Src::Const(k) => self.konst(k),
        }
    }

    fn load_var(&mut self, n: u32) -> Value {
        match Place::of(n) {
            Place::Local(_) | Place::Common(_) => match self.vars.get(&n).copied() {
                Some(var) => {
                    let v = self.b.use_var(var.value);
                    let num = self.b.use_var(var.num);
                    if let Some(here) = self.b.current_block() {
                        self.num_of.insert(v, (num, here));
                    }
                    v
                }
                None => self.f64(VACANT),
            },
            Place::Persistent(i) => {
                let base = self.bases.persistent;
                self.b.ins().load(types::F64, TRUSTED, base, 8 * i as i32)
            }
            Place::Null | Place::Other => self.f64(VACANT),
        }
    }

    /// A local or common variable: its variable, and the VM's (as `set`).
    fn store_var(&mut self, n: u32, v: Value) {
        let Some(&var) = self.vars.get(&n) else {
            return;
        };
        self.def_cached(var, v);
        let (base, offset) = match Place::of(n) {
            Place::Local(i) => (self.bases.locals, 8 * i as i32),
            Place::Common(i) => (self.bases.common, 8 * i as i32),
            _ => return,
        };
        self.b.ins().store(TRUSTED, v, base, offset);
    }

    fn def_cached(&mut self, var: Cached, v: Value) {
        self.b.def_var(var.value, v);
        let num = self.num(v);
        self.b.def_var(var.num, num);
    }

    /// The counters' variables into the context, whose fields the kernel
    /// and the caller read.
    fn store_counters(&mut self) {
        for (var, offset) in [
            (self.blocks, offset_of!(Ctx, blocks)),
            (self.fuel, offset_of!(Ctx, fuel)),
        ] {
            let v = self.b.use_var(var);
            self.b.ins().store(TRUSTED, v, self.ctx, offset as i32);
        }
    }

    /// Leaves for the interpreter, which goes on at `pc`.
    fn exit_at(&mut self, pc: u32) {
        if let Some((at, dst, truth)) = self.unwritten.filter(|u| u.0 == pc) {
            // The interpreter runs the `jumpifnot` at `at`, which reads
            // the register.
            debug_assert_eq!(at, pc);
            self.write_truth(dst, truth);
        }
        self.store_live(pc);
        let pc = self.b.ins().iconst(types::I32, i64::from(pc));
        self.b.ins().jump(self.exit, &[BlockArg::Value(pc)]);
    }

    /// Switches to `block`, entered only from `from` (or from paths that
    /// split there).
    fn continue_in(&mut self, block: Block, from: Option<Block>) {
        if let Some(from) = from {
            self.idom.insert(block, from);
        }
        self.b.switch_to_block(block);
    }

    /// Whether `block` is the current block or dominates it by the chain
    /// `continue_in` recorded.
    fn dominates(&self, block: Block) -> bool {
        let mut at = self.b.current_block();
        // (The chain has no cycle: each block is entered once.)
        for _ in 0..=self.idom.len() {
            match at {
                Some(b) if b == block => return true,
                Some(b) => at = self.idom.get(&b).copied(),
                None => return false,
            }
        }
        false
    }

    /// Goes on only where `ok`; elsewhere leaves at `pc` (unexecuted).
    fn guard(&mut self, ok: Value, pc: u32) {
        let here = self.b.current_block();
        let (go_on, leave) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(ok, go_on, &[], leave, &[]);
        // Each has its one predecessor now: sealed, their variables are
        // the values here (no block parameters to build and remove).
        self.b.seal_block(go_on);
        self.b.seal_block(leave);
        // The leaving path out of line, its pc made there: the hot path
        // keeps its registers.
        self.b.set_cold_block(leave);
        self.b.switch_to_block(leave);
        self.exit_at(pc);
        self.continue_in(go_on, here);
    }

    /// `num`: vacant (NaN) counts as 0.
    fn num(&mut self, v: Value) -> Value {
        if self.plain.contains(&v) {
            return v;
        }
        if let Some(&(n, at)) = self.num_of.get(&v) {
            if self.dominates(at) {
                self.plain.insert(n);
                return n;
            }
        }
        let vacant = self.b.ins().fcmp(FloatCC::Unordered, v, v);
        let zero = self.f64(0.0);
        let n = self.b.ins().select(vacant, zero, v);
        self.plain.insert(n);
        if self.unsigned_zero.contains(&v) {
            self.unsigned_zero.insert(n);
        }
        if self.finite.contains(&v) {
            self.finite.insert(n);
        }
        n
    }

    fn is_vacant(&mut self, v: Value) -> Value {
        self.b.ins().fcmp(FloatCC::Unordered, v, v)
    }

    /// −0 as 0: `v + 0` is `v` for every other value (NaN and ±∞
    /// included) and +0 for −0, in IEEE arithmetic.
    fn plain_zero(&mut self, v: Value) -> Value {
        if self.unsigned_zero.contains(&v) {
            self.plain.insert(v);
            return v;
        }
        let zero = self.f64(0.0);
        let z = self.b.ins().fadd(v, zero);
        self.plain.insert(z);
        self.unsigned_zero.insert(z);
        z
    }

    /// `finite`: a result that is not finite leaves for the interpreter,
    /// which raises the alarm (E5006, or E5001 for x/0, E5002 for the root
    /// of a negative value: the result is ±∞ or NaN then); −0 becomes 0.
    fn finite(&mut self, pc: u32, v: Value) -> Value {
        self.check_finite(pc, v);
        let z = self.plain_zero(v);
        self.finite.insert(z);
        z
    }

    /// Leaves at `pc` unless `v` is finite: at once, or, in a restartable
    /// run, at the run's end (and then at the run's start).
    fn check_finite(&mut self, pc: u32, v: Value) {
        match self.region.restart.get(&pc) {
            Some(&start) => match &mut self.pending {
                Some((_, results)) => results.push(v),
                None => self.pending = Some((start, vec![v])),
            },
            None => {
                let magnitude = self.b.ins().fabs(v);
                let inf = self.f64(f64::INFINITY);
                let ok = self.b.ins().fcmp(FloatCC::LessThan, magnitude, inf);
                self.guard(ok, pc);
            }
        }
    }

    /// The end of a restartable run: where one of its results was not
    /// finite, back to its start.
    ///
    /// The test is on the sum of the results, added pairwise (a tree, not
    /// a chain): one addition a result. The sum is finite when every
    /// result is; a result that is not (±∞, NaN) makes it ±∞ or NaN, and
    /// `s − s` is NaN exactly then. Finite results whose sum overflows
    /// (beyond 10³⁰⁸) only send the run back to the interpreter, which
    /// runs it again and finds nothing.
    fn check_run(&mut self) {
        if let Some((start, mut results)) = self.pending.take() {
            while results.len() > 1 {
                results = results
                    .chunks(2)
                    .map(|pair| match *pair {
                        [a, b] => self.b.ins().fadd(a, b),
                        _ => pair[0],
                    })
                    .collect();
            }
            let Some(&sum) = results.first() else {
                return;
            };
            let d = self.b.ins().fsub(sum, sum);
            let ok = self.b.ins().fcmp(FloatCC::Ordered, d, d);
            self.guard(ok, start);
        }
    }

    fn arith(&mut self, pc: u32, op: Arith, dst: u8, a: u8, b: Src) {
        let a = self.reg(a);
        let b = self.src(b);
        let (x, y) = (self.num(a), self.num(b));
        let (r, unsigned) = match op {
            // In IEEE arithmetic (round to nearest) a sum is −0 only when
            // both terms are, a difference x − y only when x is −0 and y +0.
            Arith::Add => (self.b.ins().fadd(x, y), self.unsigned_either(x, y)),
            Arith::Sub => (self.b.ins().fsub(x, y), self.unsigned_zero.contains(&x)),
            // A product or quotient is −0 from an underflow too.
            Arith::Mul => (self.b.ins().fmul(x, y), false),
            // x/0 is ±∞ or NaN: `finite` leaves for the interpreter's E5001.
            Arith::Div => (self.b.ins().fdiv(x, y), false),
        };
        if unsigned {
            self.unsigned_zero.insert(r);
        }
        let v = self.finite(pc, r);
        self.set(dst, v);
    }

    fn unsigned_either(&self, x: Value, y: Value) -> bool {
        self.unsigned_zero.contains(&x) || self.unsigned_zero.contains(&y)
    }

    /// A helper's result, or a leave at `pc` where it reports a fault.
    fn call_checked(&mut self, pc: u32, dst: u8, f: FuncRef, args: &[Value]) {
        let call = self.b.ins().call(f, args);
        let v = self.b.inst_results(call)[0];
        self.check_finite(pc, v);
        self.plain.insert(v);
        self.finite.insert(v);
        self.set(dst, v);
    }

    fn binary_call(&mut self, pc: u32, op: Bin, dst: u8, a: u8, b: u8) {
        let code = binary_code(op).map_or(u32::MAX, |c| c);
        let code = self.b.ins().iconst(types::I32, i64::from(code));
        let (a, b) = (self.reg(a), self.reg(b));
        self.call_checked(pc, dst, self.refs.binary, &[code, a, b]);
    }

    /// A comparison, as `value::compare` computes it: EQ and NE tell
    /// vacant from 0, the others count it as 0; equality is relative.
    fn compare(&mut self, pc: u32, dst: u8, a: u8, b: Src, op: u8) {
        let Some(rel) = Rel::from_code(op) else {
            // An unknown comparison is the interpreter's alarm (what
            // follows is then never reached).
            let never = self.b.ins().iconst(types::I8, 0);
            self.guard(never, pc);
            return;
        };
        let constant = match b {
            Src::Const(k) => self.module.consts.get(k as usize).copied(),
            Src::Reg(_) => None,
        }
        .filter(|c| c.is_finite());
        let a = self.reg(a);
        let b = self.src(b);
        let result = match constant {
            Some(c) => self.compare_with_constant(rel, a, b, c),
            None => self.full_compare(rel, a, b, None),
        };
        self.last_compare = Some((dst, result));
        if self.region.branches_on(&self.module.code, pc, dst) {
            // Only the `jumpifnot` reads it: the value is made where the
            // code leaves at that instruction (`exit_at`).
            self.unwritten = Some((pc + 1, dst, result));
            return;
        }
        self.write_truth(dst, result);
    }

    /// A comparison with the finite constant `c` (`b`): where `a` is
    /// finite and outside `far_bounds(c)` it is not `near` c, and the
    /// strict comparison is the result; elsewhere the whole comparison,
    /// out of line.
    fn compare_with_constant(&mut self, rel: Rel, a: Value, b: Value, c: f64) -> Value {
        let x = match rel {
            Rel::Eq | Rel::Ne => a,
            _ => self.num(a),
        };
        let (lo, hi) = far_bounds(c);
        let (lo, hi) = (self.f64(lo), self.f64(hi));
        let below = self.b.ins().fcmp(FloatCC::LessThan, x, lo);
        let above = self.b.ins().fcmp(FloatCC::GreaterThan, x, hi);
        let outside = self.b.ins().bor(below, above);
        let far = if self.finite.contains(&x) {
            outside
        } else {
            let magnitude = self.b.ins().fabs(x);
            let inf = self.f64(f64::INFINITY);
            let finite = self.b.ins().fcmp(FloatCC::LessThan, magnitude, inf);
            self.b.ins().band(outside, finite)
        };
        let truth = match rel {
            Rel::Lt | Rel::Le => below,
            Rel::Gt | Rel::Ge => above,
            Rel::Eq => self.b.ins().iconst(types::I8, 0),
            Rel::Ne => self.b.ins().iconst(types::I8, 1),
        };
        let here = self.b.current_block();
        let (slow, join) = (self.b.create_block(), self.b.create_block());
        let result = self.b.append_block_param(join, types::I8);
        self.b
            .ins()
            .brif(far, join, &[BlockArg::Value(truth)], slow, &[]);
        self.b.seal_block(slow);
        self.b.set_cold_block(slow);
        self.continue_in(slow, here);
        let scale = c.abs().max(1.0);
        let truth = self.full_compare(rel, a, b, Some(scale));
        self.b.ins().jump(join, &[BlockArg::Value(truth)]);
        self.b.seal_block(join);
        self.continue_in(join, here);
        result
    }

    /// `value::compare` written out; `scale` is max(1, |b|) where `b` is
    /// a constant.
    fn full_compare(&mut self, rel: Rel, a: Value, b: Value, scale: Option<f64>) -> Value {
        match rel {
            Rel::Eq | Rel::Ne => {
                // `near` is false when either is vacant (NaN), so "both
                // vacant, or near" is the kernel's three cases.
                let (va, vb) = (self.is_vacant(a), self.is_vacant(b));
                let both = self.b.ins().band(va, vb);
                let near = self.near(a, b, scale);
                let same = self.b.ins().bor(both, near);
                match rel {
                    Rel::Eq => same,
                    _ => self.b.ins().bxor_imm(same, 1),
                }
            }
            _ => {
                let (x, y) = (self.num(a), self.num(b));
                let eq = self.near(x, y, scale);
                let (cc, join_eq) = match rel {
                    Rel::Gt => (FloatCC::GreaterThan, false),
                    Rel::Lt => (FloatCC::LessThan, false),
                    Rel::Ge => (FloatCC::GreaterThan, true),
                    _ => (FloatCC::LessThan, true),
                };
                let strict = self.b.ins().fcmp(cc, x, y);
                if join_eq {
                    self.b.ins().bor(strict, eq)
                } else {
                    let not_eq = self.b.ins().bxor_imm(eq, 1);
                    self.b.ins().band(strict, not_eq)
                }
            }
        }
    }

    /// A comparison's result, as a value (1 or 0), into register `dst`.
    fn write_truth(&mut self, dst: u8, truth: Value) {
        let (one, zero) = (self.f64(1.0), self.f64(0.0));
        let v = self.b.ins().select(truth, one, zero);
        self.plain.insert(v);
        self.unsigned_zero.insert(v);
        self.finite.insert(v);
        self.set(dst, v);
    }

    /// `near`: |a − b| ≤ 10⁻⁹·max(1, |a|, |b|) (false when either is NaN);
    /// `b_scale` is max(1, |b|) where `b` is a constant (the same maximum:
    /// a maximum is one of its operands, in any order).
    fn near(&mut self, a: Value, b: Value, b_scale: Option<f64>) -> Value {
        let diff = self.b.ins().fsub(a, b);
        let diff = self.b.ins().fabs(diff);
        let ma = self.b.ins().fabs(a);
        let scale = match b_scale {
            Some(s) => {
                let s = self.f64(s);
                self.max(s, ma)
            }
            None => {
                let one = self.f64(1.0);
                let mb = self.b.ins().fabs(b);
                let scale = self.max(one, ma);
                self.max(scale, mb)
            }
        };
        let tolerance = self.f64(1e-9);
        let bound = self.b.ins().fmul(tolerance, scale);
        self.b.ins().fcmp(FloatCC::LessThanOrEqual, diff, bound)
    }

    /// `f64::max` of two values that are not NaN (a select: `fmax`'s NaN
    /// rules cost a longer sequence, and no NaN comes here).
    fn max(&mut self, a: Value, b: Value) -> Value {
        let greater = self.b.ins().fcmp(FloatCC::GreaterThan, a, b);
        self.b.ins().select(greater, a, b)
    }

    /// A function: the exact ones (ABS, SQRT, FIX, FUP) inline, whose IEEE
    /// results are the same bits as `libm`'s; those without a domain a
    /// direct call of the kernel's computation (`helpers::total`: the same
    /// `libm` call), whose result is checked here; the others through the
    /// kernel's `value::func`, which checks and raises.
    fn func(&mut self, pc: u32, dst: u8, a: u8, f: u8) {
        let a = self.reg(a);
        let inline = match Func::from_code(f) {
            Some(Func::Abs) => {
                let x = self.num(a);
                let v = self.b.ins().fabs(x);
                self.unsigned_zero.insert(v);
                Some(v)
            }
            Some(Func::Sqrt) => {
                // The root of a negative value is NaN: `finite` leaves for
                // the interpreter's E5002. The root of −0 is −0.
                let x = self.num(a);
                let v = self.b.ins().sqrt(x);
                if self.unsigned_zero.contains(&x) {
                    self.unsigned_zero.insert(v);
                }
                Some(v)
            }
            Some(Func::Fix) => {
                let x = self.num(a);
                Some(self.b.ins().trunc(x))
            }
            Some(Func::Fup) => {
                let x = self.num(a);
                let up = self.b.ins().ceil(x);
                let minus = self.b.ins().fneg(x);
                let down = self.b.ins().ceil(minus);
                let down = self.b.ins().fneg(down);
                let zero = self.f64(0.0);
                let negative = self.b.ins().fcmp(FloatCC::LessThan, x, zero);
                Some(self.b.ins().select(negative, down, up))
            }
            Some(g) => match helpers::total(g) {
                Some(total) => {
                    let x = self.num(a);
                    let at = self.b.ins().iconst(self.ptr, total as usize as i64);
                    let call = self.b.ins().call_indirect(self.refs.unary, at, &[x]);
                    Some(self.b.inst_results(call)[0])
                }
                None => None,
            },
            None => None,
        };
        match inline {
            Some(v) => {
                let v = self.finite(pc, v);
                self.set(dst, v);
            }
            None => {
                let code = self.b.ins().iconst(types::I32, i64::from(f));
                self.call_checked(pc, dst, self.refs.func, &[code, a]);
            }
        }
    }

    fn word(&mut self, addr: u8, src: u8) {
        // A vacant word is left out of the block (§7.5).
        let v = self.reg(src);
        let vacant = self.is_vacant(v);
        let here = self.b.current_block();
        let (push, after) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(vacant, after, &[], push, &[]);
        self.b.seal_block(push);
        self.continue_in(push, here);
        self.push_word(addr, v, 0);
        self.b.ins().jump(after, &[]);
        self.b.seal_block(after);
        self.continue_in(after, here);
    }

    fn push_word(&mut self, addr: u8, v: Value, flags: u8) {
        let addr = self.b.ins().iconst(types::I32, i64::from(addr));
        let flags = self.b.ins().iconst(types::I32, i64::from(flags));
        let words = self.bases.words;
        self.b
            .ins()
            .call(self.refs.push_word, &[words, addr, v, flags]);
    }

    /// An NC block, its words built: a direct call into the kernel's
    /// executor (`vm::Ran` says what became of it), the counters written
    /// for it. `GoOn`: the code goes on, the block count read again (the
    /// kernel charged the block);
    /// `Leave`: it leaves at the next pc, for the VM to finish the block
    /// and end its step; `Not`: it leaves at `pc` itself, unrun.
    fn block(&mut self, pc: u32) {
        self.store_live(pc);
        self.store_counters();
        let at = self.b.ins().iconst(types::I32, i64::from(pc));
        let call = self.b.ins().call(self.refs.block, &[self.ctx, at]);
        let ran = self.b.inst_results(call)[0];
        let blocks = self.load_ctx(types::I64, offset_of!(Ctx, blocks));
        self.b.def_var(self.blocks, blocks);
        let go_on = self
            .b
            .ins()
            .icmp_imm(IntCC::Equal, ran, i64::from(Ran::GoOn as u32));
        let here = self.b.current_block();
        let (on, leave) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(go_on, on, &[], leave, &[]);
        self.b.seal_block(on);
        self.b.seal_block(leave);
        self.b.switch_to_block(leave);
        // Not (0) or Leave (1): at pc or after it.
        let next = self.b.ins().iadd(at, ran);
        self.b.ins().jump(self.exit, &[BlockArg::Value(next)]);
        self.continue_in(on, here);
    }

    /// Charges a block to the budget; one the budget cannot take leaves
    /// at `pc`, where the interpreter charges it and raises E6005.
    fn charge(&mut self, pc: u32) {
        let blocks = self.b.use_var(self.blocks);
        let ok = self
            .b
            .ins()
            .icmp(IntCC::UnsignedLessThan, blocks, self.bases.max_blocks);
        self.guard(ok, pc);
        let blocks = self.b.ins().iadd_imm(blocks, 1);
        self.b.def_var(self.blocks, blocks);
    }

    /// A jump, taken: within the loop a backward one is a round (fuel and a
    /// block); out of the loop it leaves, unexecuted, for the interpreter.
    fn jump(&mut self, pc: u32, target: u32) {
        let Some(&block) = self
            .labels
            .get(&target)
            .filter(|_| self.region.contains(target))
        else {
            self.exit_at(pc);
            return;
        };
        if target <= pc {
            self.round(pc);
        }
        self.b.ins().jump(block, &[]);
    }

    /// A backward jump costs a round of the loop's instructions from the
    /// step's fuel (leaving while some are left), then a block.
    fn round(&mut self, pc: u32) {
        let cost = self.region.len() as i64;
        let fuel = self.b.use_var(self.fuel);
        let ok = self
            .b
            .ins()
            .icmp_imm(IntCC::UnsignedGreaterThanOrEqual, fuel, cost);
        self.guard(ok, pc);
        self.charge(pc);
        let fuel = self.b.use_var(self.fuel);
        let fuel = self.b.ins().iadd_imm(fuel, -cost);
        self.b.def_var(self.fuel, fuel);
    }

    /// Whether register `r` holds vacant or what EQ takes for 0.
    fn is_zero_or_vacant(&mut self, r: u8) -> Value {
        let c = self.reg(r);
        let vacant = self.is_vacant(c);
        let magnitude = self.b.ins().fabs(c);
        let tiny = self.f64(1e-9);
        let small = self.b.ins().fcmp(FloatCC::LessThanOrEqual, magnitude, tiny);
        let inf = self.f64(f64::INFINITY);
        let infinite = self.b.ins().fcmp(FloatCC::Equal, magnitude, inf);
        let take = self.b.ins().bor(vacant, small);
        self.b.ins().bor(take, infinite)
    }

    /// `jumpifnot`: taken when the condition is vacant or equal to 0 as
    /// the kernel's EQ compares (|c| ≤ 10⁻⁹, and ±∞, whose relative
    /// distance to 0 is no more than itself).
    fn jump_if_not(&mut self, pc: u32, cond: u8, target: u32) {
        let take = match self.last_compare.take() {
            // Right after the comparison that set it: its truth value.
            Some((_, truth)) => self.b.ins().bxor_imm(truth, 1),
            None => self.is_zero_or_vacant(cond),
        };
        let taken = self.b.create_block();
        // The next pc is a leader (`Region` makes every jump's one).
        let next = match self.labels.get(&(pc + 1)) {
            Some(&block) => block,
            None => {
                let block = self.b.create_block();
                self.labels.insert(pc + 1, block);
                block
            }
        };
        self.b.ins().brif(take, taken, &[], next, &[]);
        self.b.seal_block(taken);
        self.b.switch_to_block(taken);
        self.jump(pc, target);
        self.unwritten = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nc::value::compare;

    /// `n` steps of one unit in the last place from `x`, towards +∞
    /// (`n` > 0) or −∞.
    fn ulps(x: f64, n: i64) -> f64 {
        let mut y = x;
        for _ in 0..n.unsigned_abs() {
            y = if n > 0 { y.next_up() } else { y.next_down() };
        }
        y
    }

    /// Beyond `far_bounds`, the kernel's every comparison with the constant
    /// is the strict one: checked on the values next to each bound, around
    /// ±max(1, |c|) (where the larger magnitude takes over the scale), and
    /// spread over the far ranges.
    #[test]
    fn beyond_the_far_bounds_no_value_is_near() {
        let constants = [
            0.0,
            1.0,
            -1.0,
            0.999_999_999_9,
            -0.999_999_999_9,
            1e-9,
            -100.0,
            1e6,
            -1e6,
            0.001,
            123.456,
            1e300,
            -1e300,
            1.7e308,
            5e-324,
        ];
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        for c in constants {
            let (lo, hi) = far_bounds(c);
            let s = c.abs().max(1.0);
            let mut probes = Vec::new();
            for base in [lo, hi, -s, s, -2.0 * s, 2.0 * s, f64::MAX, -f64::MAX] {
                for n in -300..=300 {
                    probes.push(ulps(base, n));
                }
            }
            for _ in 0..20_000 {
                seed = seed
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let magnitude = 10f64.powf((seed >> 11) as f64 / (1u64 << 53) as f64 * 40.0 - 20.0);
                let sign = if seed & 1 == 0 { 1.0 } else { -1.0 };
                probes.push(c + sign * magnitude * s);
            }
            for a in probes.into_iter().filter(|a| a.is_finite()) {
                let (below, above) = (a < lo, a > hi);
                if !(below || above) {
                    continue;
                }
                let truth = |b: bool| if b { 1.0 } else { 0.0 };
                let expect = [
                    (Rel::Eq, 0.0),
                    (Rel::Ne, 1.0),
                    (Rel::Lt, truth(below)),
                    (Rel::Le, truth(below)),
                    (Rel::Gt, truth(above)),
                    (Rel::Ge, truth(above)),
                ];
                for (rel, want) in expect {
                    assert_eq!(compare(rel, a, c), want, "{a:e} {rel:?} {c:e}");
                }
            }
        }
    }

    /// The bounds are close: the values just inside them are the slow
    /// path's, and a value near c is found near there.
    #[test]
    fn far_bounds_are_a_few_tolerances_wide() {
        for c in [0.0, 1e6, -100.0, 0.5] {
            let (lo, hi) = far_bounds(c);
            let tolerance = 1e-9 * c.abs().max(1.0);
            assert!(c - lo < 5.0 * tolerance && hi - c < 5.0 * tolerance);
            assert_eq!(compare(Rel::Eq, c + 0.9 * tolerance, c), 1.0);
            assert_eq!(compare(Rel::Eq, c + 1.1 * tolerance, c), 0.0);
        }
    }
}
