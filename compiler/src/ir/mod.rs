//! The compiler's intermediate representation (issue #14).
//!
//! One [`Function`] per linked `O` program: basic blocks laid out in the
//! order their code runs when no jump is taken, each a list of operations
//! and one terminator. Operations, expressions and the words of NC blocks
//! live in arenas of the function and are named by typed handles; where
//! each came from is kept in side vectors beside them (file and byte span),
//! as naga does, so that passes that do not care about sources never see
//! them. Analyses keep their facts in side tables keyed by handle too.
//!
//! Passes: `build` (syntax tree and linked programs → IR; with -O1 it
//! folds the expressions that read no variable), `fold` (-O1: constant
//! propagation over the control-flow graph, `crate::fold`), `resolve` (NC
//! blocks that are plain moves typed as such, `crate::resolve`),
//! `validate` (after them, on every compile: an invalid IR is the
//! internal error E0000), `modal` (the modal groups and the position known
//! before each operation, `crate::modal`; the `--emit=ir` printer and
//! W119 read it), `emit` (IR → bytecode), and the `--emit=ir` printer.
//!
//! Decisions:
//! - The IR is a module of the compiler, not a crate: only the compiler's
//!   passes make and read it, and its types need nothing but `grammar`'s
//!   spans and `nc`'s value operators. It can move into a crate of its own
//!   when something outside the compiler reads it.
//! - The layout is explicit and `emit` adds or removes no jump: an edge the
//!   code falls through (`Follow`, the `then` of `Branch`, the `next` of
//!   `Skip`, `Call` and `GotoIf`) goes to the next block of the layout, an
//!   edge that jumps is always a jump. So the bytecode is the one the
//!   lowering before the IR made, instruction for instruction.
//! - M02 and M30 stay words of their `Nc` operation (the kernel ends the
//!   run when it executes them), and the basic block ends after it with
//!   `Ended`, which adds no code: the bytecode is the lowering's, which
//!   went on with the next block's code.
//! - A G66 modal call is a `Call` terminator (the call is set up there);
//!   the calls it makes after each move happen inside `Nc` operations, as
//!   the VM makes them. The modal pass has to treat a move under G66 as a
//!   call.

mod handle;
pub mod print;
pub mod validate;

pub use handle::{Arena, Handle};
pub use validate::validate;

use grammar::Span;
use nc::gcode::Motion;
use nc::value::{Bin, Func, Rel};

/// A place in a source file: the unit (file) index and a byte span.
///
/// `fresh` marks the first operation or terminator of a source block (a
/// statement): values computed for one statement live until the next one,
/// and the emitter starts its register frame there (the bytecode's
/// registers are allocated per statement, as a stack).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Loc {
    pub file: u16,
    pub fresh: bool,
    pub span: Span,
}

/// A string of the module's table (comments that become messages).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StrId(pub u32);

/// The IR of a compilation: every linked program, main program first.
#[derive(Debug, Default)]
pub struct Module {
    pub functions: Vec<Function>,
    pub strings: Vec<String>,
}

/// One `O` program.
#[derive(Debug, Default)]
pub struct Function {
    /// The program number (`O0001` → 1).
    pub number: u32,
    /// The source file of the program's blocks.
    pub file: u16,
    /// The program's own span (its `O` line or its first block).
    pub span: Span,
    pub blocks: Arena<Block>,
    /// Where each block's terminator came from (by block handle).
    pub term_locs: Vec<Loc>,
    /// The order of the blocks in the code: `layout[0]` is the entry; a
    /// fall-through edge goes to the next block of the layout.
    pub layout: Vec<Handle<Block>>,
    pub ops: Arena<Op>,
    /// Where each operation came from (by op handle).
    pub op_locs: Vec<Loc>,
    pub exprs: Arena<Expr>,
    /// The words of every NC block, block after block ([`NcBlock::words`]
    /// names a range of it).
    pub words: Vec<Word>,
    /// Where each word came from (by index into `words`).
    pub word_spans: Vec<Span>,
    /// The DO loops, numbered from 1 in source order: `loops[i]` is the
    /// loop that holds loop i + 1 (0: none).
    pub loops: Vec<u32>,
}

/// A basic block: operations run in order, then the terminator.
#[derive(Debug, Default)]
pub struct Block {
    pub ops: Vec<Handle<Op>>,
    /// `None` only while the block is being built.
    pub term: Option<Terminator>,
}

/// An operation.
#[derive(Debug, Clone)]
pub enum Op {
    /// The start of a block numbered `N` (the first field), a target of
    /// GOTO and M99 P, in DO loop `.1` of its function (0: none).
    Seq(u32, u32),
    /// An NC block in word form, handed to the kernel.
    Nc(NcBlock),
    /// `#var = value`. An assignment to #3000 (alarm) or #3006 (stop with
    /// message) carries its message: the store is what raises it.
    Assign {
        target: VarTarget,
        value: Handle<Expr>,
        msg: Option<StrId>,
    },
    /// A macro-A operation `G65 Hm P#dst Q j R k` (H01–H34): `value`, the
    /// operation written out as an expression of `j` and `k`
    /// ([`MacroAOp::value`]), is stored into `#dst`. Emit computes it and
    /// fold evaluates it as it does any expression. A store into #3000
    /// or #3006 carries its message (the block's comment), as an
    /// assignment does.
    MacroA {
        op: MacroAOp,
        dst: u32,
        j: Handle<Expr>,
        k: Handle<Expr>,
        value: Handle<Expr>,
        msg: Option<StrId>,
    },
    /// A user alarm (`G65 H99 Q n`: alarm 500 + n).
    Alarm { code: u16, msg: StrId },
    /// `G65 H99 Q…` with a computed Q: alarm 500 + Q when it runs.
    UserAlarm { q: Handle<Expr>, msg: StrId },
    /// G67: the modal call ends.
    ModalCancel,
    /// A macro statement block that nothing else it runs charges to the
    /// block budget (machine.md §4: every executed block counts): a WHILE
    /// or DO, an IF whose THEN or GOTO does not run.
    Charge,
}

/// Which variable an assignment writes.
#[derive(Debug, Clone, Copy)]
pub enum VarTarget {
    Direct(u32),
    Indirect(Handle<Expr>),
}

/// An NC block: its words and, for a block read in its own place, the
/// message its comment sets.
#[derive(Debug, Clone)]
pub struct NcBlock {
    /// A range of [`Function::words`].
    pub words: (u32, u32),
    pub kind: NcKind,
    pub msg: Option<StrId>,
}

/// How the kernel takes an NC block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NcKind {
    /// Executed where it stands.
    Run,
    /// A G70–G73 profile block, handed to the cycle block that follows.
    Profile,
    /// Executed where it stands, a plain move (pass `resolve`): its words
    /// are constants, X/Z/U/W (one at least), F, N and an arc's R or I/K,
    /// each once, and the G code, if any, is written as 0–3: the motion,
    /// or `None` for the one in force.
    Move(Option<Motion>),
}

impl NcKind {
    /// Whether the block is executed where it stands.
    pub fn runs_here(self) -> bool {
        self != NcKind::Profile
    }
}

/// One word of an NC block: its address (`A` = 0 … `Z` = 25, then the
/// comma addresses of `nc::words`) and its value ([`Word::value`]). Its
/// source is in [`Function::word_spans`].
///
/// A long program has millions of words: a word is 16 bytes, the value's
/// kind beside the address instead of an enum's tag (which would make it
/// 24 with the padding around the `f64`).
#[derive(Debug, Clone, Copy)]
pub struct Word {
    pub addr: u8,
    /// The `nc::words` flags of a constant.
    flags: u8,
    /// Whether `bits` is an expression's handle (else a constant's bits).
    computed: bool,
    bits: u64,
}

impl Word {
    /// The value of a constant word; `None` for a computed one.
    #[inline]
    pub fn constant(&self) -> Option<f64> {
        (!self.computed).then(|| f64::from_bits(self.bits))
    }

    pub fn new(addr: u8, value: WordValue) -> Word {
        let (flags, computed, bits) = match value {
            WordValue::Const(v, flags) => (flags, false, v.to_bits()),
            WordValue::Expr(h) => (0, true, h.index() as u64),
        };
        Word {
            addr,
            flags,
            computed,
            bits,
        }
    }

    pub fn value(&self) -> WordValue {
        match self.computed {
            false => WordValue::Const(f64::from_bits(self.bits), self.flags),
            true => match Handle::from_index(self.bits as usize) {
                Some(h) => WordValue::Expr(h),
                // (`new` stored a handle's index, which has a handle.)
                None => WordValue::Const(f64::NAN, 0),
            },
        }
    }
}

/// A word's value.
#[derive(Debug, Clone, Copy)]
pub enum WordValue {
    /// A value known at compile time, with its `nc::words` flags (how it
    /// was written: a literal, with or without a decimal point).
    Const(f64, u8),
    /// A value computed at run time.
    Expr(Handle<Expr>),
}

/// An expression of macro B. Children always have smaller handles than
/// their parents (the arena is in evaluation order).
#[derive(Debug, Clone, Copy)]
pub enum Expr {
    Const(f64),
    /// `#n`.
    Var(u32),
    /// `#[e]`.
    VarInd(Handle<Expr>),
    Neg(Handle<Expr>),
    /// Arithmetic and the bitwise AND/OR/XOR (of values and of conditions).
    Binary {
        op: Bin,
        a: Handle<Expr>,
        b: Handle<Expr>,
    },
    Func {
        f: Func,
        a: Handle<Expr>,
    },
    Atan2 {
        y: Handle<Expr>,
        x: Handle<Expr>,
    },
    /// A comparison: 1 when it holds, 0 when not.
    Compare {
        op: Rel,
        a: Handle<Expr>,
        b: Handle<Expr>,
    },
}

/// The macro-A arithmetic of `G65 Hm` (dialect.md §7.11).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MacroAOp {
    /// H01: `#i = j`.
    Set,
    /// H02–H05.
    Add,
    Sub,
    Mul,
    Div,
    /// H11–H13.
    Or,
    And,
    Xor,
    /// H21, H22.
    Sqrt,
    Abs,
    /// H23: `j - fix(j / k) * k`.
    Rem,
    /// H26: `#i * j / k`.
    MulDiv,
    /// H27, H28: `sqrt(j² ± k²)`.
    Hypot,
    HypotDiff,
    /// H31–H33: `j * f(k)`.
    Sin,
    Cos,
    Tan,
    /// H34: `atan2(j, k)`.
    Atan2,
}

impl MacroAOp {
    /// The operation of `G65 H<h>`.
    pub fn of(h: u32) -> Option<MacroAOp> {
        use MacroAOp::*;
        Some(match h {
            1 => Set,
            2 => Add,
            3 => Sub,
            4 => Mul,
            5 => Div,
            11 => Or,
            12 => And,
            13 => Xor,
            21 => Sqrt,
            22 => Abs,
            23 => Rem,
            26 => MulDiv,
            27 => Hypot,
            28 => HypotDiff,
            31 => Sin,
            32 => Cos,
            33 => Tan,
            34 => Atan2,
            _ => return None,
        })
    }

    /// The value the operation stores, as an expression of `j`, `k` and
    /// (H26) `#dst`, its nodes made by `add`. Operands are evaluated in the
    /// order the operation reads them, `j` before `k`.
    pub fn value(
        self,
        dst: u32,
        j: Handle<Expr>,
        k: Handle<Expr>,
        add: &mut impl FnMut(Expr) -> Handle<Expr>,
    ) -> Handle<Expr> {
        use MacroAOp::*;
        fn bin<F: FnMut(Expr) -> Handle<Expr>>(
            op: Bin,
            a: Handle<Expr>,
            b: Handle<Expr>,
            add: &mut F,
        ) -> Handle<Expr> {
            add(Expr::Binary { op, a, b })
        }
        match self {
            // `j + 0`: a vacant j stores 0, as an addition does.
            Set => {
                let zero = add(Expr::Const(0.0));
                bin(Bin::Add, j, zero, add)
            }
            Add => bin(Bin::Add, j, k, add),
            Sub => bin(Bin::Sub, j, k, add),
            Mul => bin(Bin::Mul, j, k, add),
            Div => bin(Bin::Div, j, k, add),
            Or => bin(Bin::Or, j, k, add),
            And => bin(Bin::And, j, k, add),
            Xor => bin(Bin::Xor, j, k, add),
            Sqrt => add(Expr::Func {
                f: Func::Sqrt,
                a: j,
            }),
            Abs => add(Expr::Func { f: Func::Abs, a: j }),
            Rem => {
                let q = bin(Bin::Div, j, k, add);
                let fix = add(Expr::Func { f: Func::Fix, a: q });
                let whole = bin(Bin::Mul, fix, k, add);
                bin(Bin::Sub, j, whole, add)
            }
            MulDiv => {
                let old = add(Expr::Var(dst));
                let product = bin(Bin::Mul, old, j, add);
                bin(Bin::Div, product, k, add)
            }
            Hypot | HypotDiff => {
                let jj = bin(Bin::Mul, j, j, add);
                let kk = bin(Bin::Mul, k, k, add);
                let op = if self == Hypot { Bin::Add } else { Bin::Sub };
                let sum = bin(op, jj, kk, add);
                add(Expr::Func {
                    f: Func::Sqrt,
                    a: sum,
                })
            }
            Sin | Cos | Tan => {
                let f = match self {
                    Sin => Func::Sin,
                    Cos => Func::Cos,
                    _ => Func::Tan,
                };
                let t = add(Expr::Func { f, a: k });
                bin(Bin::Mul, j, t, add)
            }
            Atan2 => add(Expr::Atan2 { y: j, x: k }),
        }
    }

    /// Whether the value depends on R (`k`): H01, H21 and H22 ignore it.
    pub fn reads_r(self) -> bool {
        !matches!(self, MacroAOp::Set | MacroAOp::Sqrt | MacroAOp::Abs)
    }

    /// The H number.
    pub fn h(self) -> u32 {
        use MacroAOp::*;
        match self {
            Set => 1,
            Add => 2,
            Sub => 3,
            Mul => 4,
            Div => 5,
            Or => 11,
            And => 12,
            Xor => 13,
            Sqrt => 21,
            Abs => 22,
            Rem => 23,
            MulDiv => 26,
            Hypot => 27,
            HypotDiff => 28,
            Sin => 31,
            Cos => 32,
            Tan => 33,
            Atan2 => 34,
        }
    }
}

/// How a block ends.
#[derive(Debug, Clone)]
pub enum Terminator {
    /// Goes on into `next`, the next block of the layout (a join point
    /// starts there).
    Follow(Handle<Block>),
    /// An unconditional jump.
    Jump(Handle<Block>),
    /// `GOTO n` to a block known at compile time: a jump that is a block
    /// of its own, charged to the budget once whichever way it goes.
    GotoKnown(Handle<Block>),
    /// Goes on into `then` (the next block of the layout) when `cond` is
    /// non-zero, else jumps to `otherwise`.
    Branch {
        cond: Handle<Expr>,
        then: Handle<Block>,
        otherwise: Handle<Block>,
    },
    /// A `/n` block-skip guard: jumps to `skip` when the operator's switch
    /// `n` is on as the block is read, else goes on into `next` (the next
    /// block of the layout).
    Skip {
        switch: u8,
        skip: Handle<Block>,
        next: Handle<Block>,
    },
    /// A computed GOTO (and G65 H80): to the first block numbered `seq`
    /// when it runs, from inside DO loop `inside` (0: none), which must
    /// hold the target's loop (E6008).
    Goto { seq: Handle<Expr>, inside: u32 },
    /// G65 H81–H86: a computed GOTO to block `seq` when `j op k` holds,
    /// else on into `next` (the next block of the layout).
    GotoIf {
        seq: Handle<Expr>,
        inside: u32,
        op: Rel,
        j: Handle<Expr>,
        k: Handle<Expr>,
        next: Handle<Block>,
    },
    /// A call; the program goes on into `next` (the next block of the
    /// layout) when the callee returns.
    Call { call: Call, next: Handle<Block> },
    /// M99, or M99 P (back to block `seq` of the caller); running off the
    /// end of a subprogram.
    Return { seq: Option<Handle<Expr>> },
    /// The end of the main program.
    Halt,
    /// The block's last operation, an NC block with M02 or M30, ends the
    /// program when the kernel executes it: nothing follows (the code of
    /// the next block of the layout is not reached from here).
    Ended,
}

/// A call of a program.
#[derive(Debug, Clone)]
pub struct Call {
    pub kind: CallKind,
    pub callee: Callee,
    pub count: Count,
    /// Macro arguments: the local variable each sets, and its value.
    pub args: Vec<(u8, Handle<Expr>)>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CallKind {
    /// M98 and M9000–M9999: a subprogram (no arguments, no new locals).
    Sub,
    /// G65 and the G codes that call macros: a macro call.
    Macro,
    /// G66: a modal macro call, made after every move block until G67.
    Modal,
}

#[derive(Debug, Clone, Copy)]
pub enum Callee {
    /// A program of the module, by index into [`Module::functions`].
    Program(u32),
    /// A program number computed at run time, looked up when the call runs.
    Dynamic(Handle<Expr>),
}

/// How many times the callee runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Count {
    Expr(Handle<Expr>),
    /// Packed in a computed M98 P as `P<count:4><program:4>`, split when
    /// the call runs.
    Packed,
}

impl Function {
    /// Whether DO loop `outer` holds loop `inner` (a loop holds itself;
    /// 0, outside every loop, holds all).
    pub fn loop_holds(&self, outer: u32, inner: u32) -> bool {
        isa::loop_holds(&self.loops, outer, inner)
    }

    /// The words of an NC block.
    pub fn words_of(&self, nc: &NcBlock) -> &[Word] {
        self.words.get(range(nc)).unwrap_or(&[])
    }

    /// The sources of the words of an NC block.
    pub fn word_spans_of(&self, nc: &NcBlock) -> &[Span] {
        self.word_spans.get(range(nc)).unwrap_or(&[])
    }
}

fn range(nc: &NcBlock) -> std::ops::Range<usize> {
    nc.words.0 as usize..nc.words.1 as usize
}

impl Terminator {
    /// The blocks control may go to from here (a computed GOTO and a return
    /// go to blocks found at run time), the fall-through edge first.
    pub fn successors(&self) -> impl Iterator<Item = Handle<Block>> {
        let (a, b) = match self {
            Terminator::Follow(b) | Terminator::Jump(b) | Terminator::GotoKnown(b) => {
                (Some(*b), None)
            }
            Terminator::Branch {
                then, otherwise, ..
            } => (Some(*then), Some(*otherwise)),
            Terminator::Skip { skip, next, .. } => (Some(*next), Some(*skip)),
            Terminator::Call { next, .. } | Terminator::GotoIf { next, .. } => (Some(*next), None),
            Terminator::Goto { .. }
            | Terminator::Return { .. }
            | Terminator::Halt
            | Terminator::Ended => (None, None),
        };
        a.into_iter().chain(b)
    }

    /// The block the terminator goes on into without a jump, which must be
    /// the next one of the layout.
    pub fn fall_through(&self) -> Option<Handle<Block>> {
        match self {
            Terminator::Follow(b) => Some(*b),
            Terminator::Branch { then, .. } => Some(*then),
            Terminator::Skip { next, .. } => Some(*next),
            Terminator::Call { next, .. } | Terminator::GotoIf { next, .. } => Some(*next),
            _ => None,
        }
    }
}
