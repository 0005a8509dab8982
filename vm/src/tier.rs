//! A second execution tier for hot loops (the `jit` crate is one). The VM
//! stays the only owner of its state: it lends a tier the part of it that
//! compiled code may read and write ([`LoopState`]) and goes on at the pc
//! the tier hands back. Whatever a tier runs must leave that state exactly
//! as interpreting the same instructions would have; everything it does
//! not handle it leaves to the interpreter, at the instruction not yet
//! executed. An NC block it may run itself, by a direct call into the
//! kernel's executor ([`Kernel`]); it then leaves at the instruction after
//! it, for the VM to finish the block and end its step, or, where steps
//! run past blocks and the block needs nothing more of the VM, goes on
//! ([`Ran`]).

use isa::Module;
use nc::words::Words;

/// How the VM came to a pc where a tier may take over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Entry {
    /// A backward jump from `from` landed here (already charged to the
    /// block budget): a loop went round once more.
    BackEdge {
        /// The pc of the jump.
        from: u32,
    },
    /// The interpreter ran the instruction the tier's code left at last
    /// and has come to the one after it.
    Resume,
}

/// The VM state compiled code works on, lent for one entry.
pub struct LoopState<'a> {
    /// The registers.
    pub regs: &'a mut [f64],
    /// #1–#33 of the current call level (no call happens in compiled code).
    pub locals: &'a mut [f64; 33],
    /// #100–#199.
    pub common: &'a mut [f64; 100],
    /// #500–#999, read only: a write goes through the interpreter, which
    /// hands it to the storage.
    pub persistent: &'a [f64; 500],
    /// The words of the block being built.
    pub words: &'a mut Words,
    /// Blocks charged to the budget so far.
    pub blocks: &'a mut u64,
    /// The budget: a charge past it is the interpreter's (E6005).
    pub max_blocks: u64,
    /// Instructions the current [`crate::Vm::step`] may still run; a tier
    /// takes off what it ran, and leaves before it runs out.
    pub fuel: &'a mut u64,
    /// The kernel's executor, for a block the code has built.
    pub kernel: &'a mut dyn Kernel,
}

/// The kernel's executor as a tier calls it: the block instruction at a pc
/// (`exec`, `execmove`, `move`, `block`) run with the words built so far,
/// exactly as the interpreter runs it, its block charged to `blocks`.
pub trait Kernel {
    /// Runs the block instruction at `pc`; see [`Ran`] for what the tier
    /// does next.
    fn run_block(&mut self, pc: u32, words: &mut Words, blocks: &mut u64) -> Ran;
}

/// What became of a block a tier handed to the [`Kernel`] (as `u32`, for
/// compiled code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum Ran {
    /// Nothing ran: `pc` is not a block instruction, or the VM has a
    /// block of this entry to finish first. The tier leaves at `pc`.
    Not = 0,
    /// The block ran; the tier must leave at once, at `pc + 1`, without
    /// touching the state again: the VM finishes the block (its outcome,
    /// an alarm at `pc`) and ends its step.
    Leave = 1,
    /// The block ran and is done ([`crate::Vm::stop_at_blocks`] is off and
    /// its outcome needs nothing of the VM): the tier goes on at `pc + 1`,
    /// the block count read again (the block was charged to it), every
    /// variable as it was.
    GoOn = 2,
}

/// What a tier has done (`gbvm --stats`, the benches).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TierStats {
    /// Loops compiled.
    pub compiled: u32,
    /// Loops compiled again, optimised, after running long (each is also
    /// counted in `compiled`).
    pub optimized: u32,
    /// Loops that could not be compiled (they stay interpreted).
    pub failed: u32,
    /// Time spent compiling, in all, in nanoseconds.
    pub compile_ns: u64,
    /// Times compiled code was entered.
    pub entries: u64,
    /// NC blocks compiled code ran by a direct call ([`Kernel`]).
    pub blocks: u64,
}

/// A tier: compiled code for some of a module's loops.
pub trait Tier: Send {
    /// What it has done so far.
    fn stats(&self) -> TierStats;

    /// The tier now serves a VM running `module` ([`crate::Vm::set_tier`]
    /// says so): code made for any other module must go.
    fn bind(&mut self, module: &Module);

    /// Runs compiled code from `pc`, if the tier has some that may be
    /// entered there (compiling the loop first if it has become hot), and
    /// returns the pc at which the interpreter goes on; `None` when nothing
    /// ran.
    fn enter(
        &mut self,
        module: &Module,
        pc: u32,
        entry: Entry,
        state: LoopState<'_>,
    ) -> Option<u32>;
}
