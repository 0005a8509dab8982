//! The gbc loop JIT: a [`vm::Tier`] that compiles a module's hot macro
//! loops to machine code with Cranelift.
//!
//! The VM counts a loop's rounds at its backward jump and hands them to
//! the tier; past a threshold ([`Mode`]) the tier compiles the loop, from
//! its head to that jump, and from then on the round runs as machine code.
//! An NC block the code runs by a direct call into the kernel's executor
//! (the VM's [`vm::Kernel`]: the same code the interpreter runs it with);
//! it goes on after it where the VM's steps run past blocks
//! (`Vm::stop_at_blocks` off), and leaves after it where the VM must
//! finish the block or end its step there. What the code does not handle
//! (calls, system variables, a fault, a charge the block budget cannot
//! take) it leaves at, unexecuted, to the interpreter, which runs it and
//! hands back at the next instruction: every alarm is the interpreter's.
//! Compiled code changes nothing else the interpreter would not: the same
//! values bit for bit (`lower`'s module doc), the same block budget, the
//! same variables at every exit.
//!
//! A loop is compiled twice if it runs long: first quickly, as soon as it
//! is hot ([`Level`]: the loop waits for it), then, once its quick code has
//! run [`OPTIMIZE_AFTER`] instructions (unless it runs an NC block more
//! often than every [`OPTIMIZE_BLOCKS_EVERY`]: its time is the kernel's),
//! again with Cranelift's optimiser and register allocator, whose code then
//! takes over at the next entry.
//!
//! Compiling happens in the VM's thread, on the interpreter's side of a
//! controller (the real-time half only consumes set points); a loop that
//! fails to compile stays interpreted.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Duration;

use isa::Module;
use vm::{Entry, LoopState, Tier, TierStats};

mod helpers;
mod lower;
mod native;
mod region;

pub use native::Level;
use native::{Backend, Code};
use region::Region;

/// When loops are compiled (`gbvm run --jit`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    /// Never: everything is interpreted.
    Off,
    /// A loop is compiled once it has gone round [`AUTO_THRESHOLD`] times.
    #[default]
    Auto,
    /// A loop is compiled at its first backward jump (for tests: compiled
    /// code runs as much as it can).
    Always,
}

/// Rounds after which `auto` compiles a loop: compiling one takes about as
/// long as interpreting a few hundred rounds of it.
pub const AUTO_THRESHOLD: u32 = 500;

/// Bytecode instructions a loop runs in quick code before it is compiled
/// again at [`Level::Full`]: the full compile (0.3–0.4 ms for a loop of 20
/// to 40 instructions, up to 1 ms with the caches cold) is then paid back
/// within a few million instructions, at the third of a round the better
/// code saves.
pub const OPTIMIZE_AFTER: u64 = 1_000_000;

/// Instructions per NC block below which a loop is not compiled again: a
/// block is the kernel's work (the move executed, its canon), more than a
/// hundred compiled instructions take, which faster code does not shorten.
/// Issue #14's macro loop (a block every 15 instructions) lost 0.8 ms of
/// its 13 by the full compile at its millionth instruction.
pub const OPTIMIZE_BLOCKS_EVERY: u64 = 100;

/// A compiled loop.
struct Loop {
    region: Region,
    code: Code,
    level: Level,
    /// Instructions its code has run (the fuel it spent).
    work: u64,
    /// NC blocks its code has run.
    blocks: u64,
}

/// The JIT tier for one module's run (see the crate doc).
pub struct Jit {
    threshold: u32,
    optimize_after: u64,
    quick: Option<Backend>,
    full: Option<Backend>,
    /// Rounds per loop (head, back edge) not compiled yet.
    rounds: BTreeMap<(u32, u32), u32>,
    /// Loops tried and not compiled.
    rejected: BTreeSet<(u32, u32)>,
    loops: Vec<Loop>,
    /// By pc, the loop entered there plus one (0: none; the widest
    /// compiled): made at the first compile, as long as the code, so that
    /// the VM's question at every backward jump is one look.
    entries: Vec<u32>,
    stats: TierStats,
}

impl Jit {
    /// A tier for `mode`; `None` for [`Mode::Off`].
    pub fn new(mode: Mode) -> Option<Jit> {
        let threshold = match mode {
            Mode::Off => return None,
            Mode::Auto => AUTO_THRESHOLD,
            Mode::Always => 1,
        };
        Some(Jit {
            threshold,
            optimize_after: OPTIMIZE_AFTER,
            quick: None,
            full: None,
            rounds: BTreeMap::new(),
            rejected: BTreeSet::new(),
            loops: Vec::new(),
            entries: Vec::new(),
            stats: TierStats::default(),
        })
    }

    /// Compiles a loop again with the optimiser once its quick code has
    /// run `work` instructions (default [`OPTIMIZE_AFTER`]) and no more
    /// than one NC block per [`OPTIMIZE_BLOCKS_EVERY`]; 0 compiles every
    /// loop at [`Level::Full`] at once (for tests).
    pub fn optimize_after(mut self, work: u64) -> Jit {
        self.optimize_after = work;
        self
    }

    /// The index of the compiled loop that may be entered at `pc`.
    fn loop_at(&self, pc: u32) -> Option<usize> {
        let number = *self.entries.get(pc as usize)? as usize;
        number
            .checked_sub(1)
            .filter(|&index| index < self.loops.len())
    }

    /// The backend of `level`, made at its first use.
    fn backend(&mut self, level: Level) -> Option<&mut Backend> {
        let slot = match level {
            Level::Quick => &mut self.quick,
            Level::Full => &mut self.full,
        };
        if slot.is_none() {
            *slot = Some(Backend::new(level, false).ok()?);
        }
        slot.as_mut()
    }

    /// Compiles loop `index` again at [`Level::Full`]; its quick code stays
    /// if that fails (tried once either way).
    fn optimize(&mut self, module: &Module, index: usize) {
        let Some(quick) = self.loops.get_mut(index) else {
            return;
        };
        quick.level = Level::Full;
        let num_regs = quick.code.num_regs();
        let region = quick.region.clone();
        let Some(backend) = self.backend(Level::Full) else {
            return;
        };
        let Ok((code, took)) = backend.compile(module, &region, num_regs) else {
            return;
        };
        if let Some(compiled) = self.loops.get_mut(index) {
            compiled.code = code;
        }
        self.stats.optimized += 1;
        self.add_compile_time(took);
    }

    fn add_compile_time(&mut self, took: Duration) {
        let ns = u64::try_from(took.as_nanos()).unwrap_or(u64::MAX);
        self.stats.compile_ns = self.stats.compile_ns.saturating_add(ns);
    }

    /// Counts a round of the loop `head..=from`, compiling it when hot.
    fn count_round(&mut self, module: &Module, head: u32, from: u32, num_regs: usize) {
        let key = (head, from);
        if self.rejected.contains(&key) {
            return;
        }
        let rounds = self.rounds.entry(key).or_insert(0);
        *rounds += 1;
        if *rounds < self.threshold {
            return;
        }
        self.rounds.remove(&key);
        if self.compile(module, head, from, num_regs).is_none() {
            self.stats.failed += 1;
            self.rejected.insert(key);
        }
    }

    fn compile(&mut self, module: &Module, head: u32, tail: u32, num_regs: usize) -> Option<()> {
        let region = Region::find(module, head, tail)?;
        let level = match self.optimize_after {
            0 => Level::Full,
            _ => Level::Quick,
        };
        let backend = self.backend(level)?;
        let (code, took) = backend.compile(module, &region, num_regs).ok()?;
        self.stats.compiled += 1;
        self.add_compile_time(took);
        if self.entries.is_empty() {
            self.entries = vec![0; module.code.len()];
        }
        let number = u32::try_from(self.loops.len() + 1).ok()?;
        // The widest loop's code takes over the entries it shares with
        // the loops inside it (the earliest head, then the latest back
        // edge).
        let width = |r: &Region| (std::cmp::Reverse(r.head), r.tail);
        for &pc in &region.entries {
            let Some(slot) = self.entries.get_mut(pc as usize) else {
                continue;
            };
            let other = (*slot as usize).checked_sub(1);
            let narrower = match other.and_then(|i| self.loops.get(i)) {
                Some(other) => width(&other.region) < width(&region),
                None => true,
            };
            if narrower {
                *slot = number;
            }
        }
        self.loops.push(Loop {
            region,
            code,
            level,
            work: 0,
            blocks: 0,
        });
        Some(())
    }
}

/// The compiler alone, for the benches (compile time per loop) and tools:
/// it compiles a loop and keeps the code without running it.
pub struct Compiler {
    backend: Backend,
}

impl Compiler {
    /// A compiler for this host at `level`; an error where Cranelift has no
    /// backend.
    pub fn new(level: Level) -> Result<Compiler, String> {
        Backend::new(level, false).map(|backend| Compiler { backend })
    }

    /// The same, with Cranelift's verifier checking each function built
    /// (which a run leaves off): a function it rejects is an error of
    /// `compile`. For the tests.
    pub fn verifying(level: Level) -> Result<Compiler, String> {
        Backend::new(level, true).map(|backend| Compiler { backend })
    }

    /// Compiles the loop of `module` from `head` to the backward jump at
    /// `tail`; how long it took.
    pub fn compile(&mut self, module: &Module, head: u32, tail: u32) -> Result<Duration, String> {
        let region = Region::find(module, head, tail)
            .ok_or_else(|| format!("no loop the JIT compiles at {head}..={tail}"))?;
        let num_regs = usize::from(module.num_regs.max(1));
        self.backend
            .compile(module, &region, num_regs)
            .map(|(_, took)| took)
    }
}

/// Whether the JIT compiles the loop of `module` from `head` to the
/// backward jump at `tail` (one it does not stays interpreted).
pub fn takes(module: &Module, head: u32, tail: u32) -> bool {
    Region::find(module, head, tail).is_some()
}

/// The loops of `module`, innermost first: (head, backward jump) of every
/// backward `jump`.
pub fn loops(module: &Module) -> Vec<(u32, u32)> {
    let mut loops: Vec<(u32, u32)> = (0..)
        .zip(&module.code)
        .filter_map(|(pc, instr)| match *instr {
            isa::Instr::Jump { target } | isa::Instr::Goto { target } if target <= pc => {
                Some((target, pc))
            }
            _ => None,
        })
        .collect();
    loops.sort_by_key(|&(head, tail)| tail - head);
    loops
}

impl Tier for Jit {
    fn stats(&self) -> TierStats {
        self.stats
    }

    fn bind(&mut self, _: &Module) {
        // Code made for another module goes, and its memory with it.
        self.rounds.clear();
        self.rejected.clear();
        self.entries.clear();
        self.loops.clear();
        self.quick = None;
        self.full = None;
    }

    fn enter(
        &mut self,
        module: &Module,
        pc: u32,
        entry: Entry,
        state: LoopState<'_>,
    ) -> Option<u32> {
        if self.loop_at(pc).is_none() {
            if let Entry::BackEdge { from } = entry {
                self.count_round(module, pc, from, state.regs.len());
            }
        }
        let index = self.loop_at(pc)?;
        let compiled = self.loops.get_mut(index)?;
        // The code checks the fuel at its backward jumps; no path from an
        // entry to one is longer than the loop, so with this much it runs
        // no instruction the step has not allowed.
        if *state.fuel < compiled.region.len() {
            return None;
        }
        self.stats.entries += 1;
        let run = compiled.code.run(pc, state)?;
        compiled.work = compiled.work.saturating_add(run.work);
        compiled.blocks = compiled.blocks.saturating_add(run.blocks);
        let optimize = compiled.level == Level::Quick
            && compiled.work >= self.optimize_after
            && compiled.blocks.saturating_mul(OPTIMIZE_BLOCKS_EVERY) <= compiled.work;
        self.stats.blocks += run.blocks;
        if optimize {
            self.optimize(module, index);
        }
        Some(run.next)
    }
}
