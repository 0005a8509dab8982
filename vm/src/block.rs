//! The kernel's part of running an NC block instruction (`exec`,
//! `execmove`, `move`, `block`): its words to the kernel's executor, the
//! block charged to the budget. It borrows only what that takes, so that
//! the interpreter and a tier's compiled code (a direct call through
//! [`crate::tier::Kernel`], while the tier holds the registers and
//! variables) run a block with the same code. What follows in the VM
//! (G31's #995–#999, G10 L52's variable, the end, a G66 call) is
//! `Vm::finish_block`'s.

use isa::{Instr, Module};
use nc::error::Alarm as AlarmCode;
use nc::words::{Word, Words};
use nc::{Nc, NcError, Outcome, Sink};

use crate::interp::PROFILE;
use crate::tier::{Kernel, Ran};

/// The VM's fields that running a block touches, borrowed.
pub(crate) struct BlockRun<'a> {
    pub module: &'a Module,
    pub nc: &'a mut Nc,
    pub sink: &'a mut dyn Sink,
    pub max_blocks: u64,
    /// The VM's `last_exec`: the pc of the last block run.
    pub last_exec: &'a mut u32,
    /// The VM's `msg` (a block's message goes with it).
    pub msg: &'a mut Option<u32>,
    /// The VM's `synced` (a block makes the motion lag again).
    pub synced: &'a mut bool,
}

/// Charges `n` blocks to the budget (E6005 past `max`).
pub(crate) fn charge(blocks: &mut u64, max: u64, n: u64) -> Result<(), NcError> {
    *blocks = blocks.saturating_add(n);
    if *blocks > max {
        return Err(NcError::new(
            AlarmCode::BlockBudget,
            alloc::format!(
                "the block budget of {max} blocks is used up: a loop that does not end, or a program longer than run.max_blocks of the machine file or `gbvm run --max-blocks` allow"
            ),
        ));
    }
    Ok(())
}

/// The words of the typed block at `rec`, from its record into `words`.
/// (The one copy of the record decoder in the VM: with a second one the
/// inliner left its varint reader out of line, 3 % more instructions on a
/// long straight program.)
#[inline]
pub(crate) fn load_record(module: &Module, rec: u32, words: &mut Words) -> Result<(), NcError> {
    match module.block_words(rec, |w| words.push(w.addr, w.value, w.flags)) {
        Some(()) => Ok(()),
        None => Err(NcError::new(
            AlarmCode::JumpTargetMissing,
            "a typed block is missing",
        )),
    }
}

impl BlockRun<'_> {
    /// Runs the block instruction at `pc` with `words` (its words so far);
    /// `None` when that instruction is not one (a tier's call).
    pub fn instr(
        &mut self,
        pc: u32,
        words: &mut Words,
        blocks: &mut u64,
    ) -> Option<Result<Outcome, NcError>> {
        let instr = *self.module.code.get(pc as usize)?;
        // What the block leaves waiting in the kernel is told by this pc
        // when it prints (`Sink::origin`, `Vm::loc_at`).
        self.nc.origin = pc;
        Some(match instr {
            Instr::Exec { flags } if flags & PROFILE == 0 => self.words(pc, words, blocks),
            Instr::ExecMove => self.plain_move(pc, words, blocks),
            Instr::Block { rec } => self.typed(pc, rec, words, blocks),
            Instr::Move { rec } => self.typed_move(pc, rec, words, blocks),
            _ => return None,
        })
    }

    /// `exec`: the block built so far.
    #[inline(always)]
    pub fn words(
        &mut self,
        pc: u32,
        words: &mut Words,
        blocks: &mut u64,
    ) -> Result<Outcome, NcError> {
        self.exec(pc, words, blocks, Nc::exec)
    }

    /// `execmove`: a plain move with computed words (the kernel's short
    /// parse).
    #[inline(always)]
    pub fn plain_move(
        &mut self,
        pc: u32,
        words: &mut Words,
        blocks: &mut u64,
    ) -> Result<Outcome, NcError> {
        self.exec(pc, words, blocks, Nc::exec_move)
    }

    /// `block`: a typed block, as `wordk… exec` would.
    #[inline(always)]
    pub fn typed(
        &mut self,
        pc: u32,
        rec: u32,
        words: &mut Words,
        blocks: &mut u64,
    ) -> Result<Outcome, NcError> {
        load_record(self.module, rec, words)?;
        self.words(pc, words, blocks)
    }

    /// `move`: a typed plain move (the short parse too).
    #[inline(always)]
    pub fn typed_move(
        &mut self,
        pc: u32,
        rec: u32,
        words: &mut Words,
        blocks: &mut u64,
    ) -> Result<Outcome, NcError> {
        load_record(self.module, rec, words)?;
        self.plain_move(pc, words, blocks)
    }

    /// Executes the block built so far with one of the kernel's executors.
    #[inline(always)]
    fn exec(
        &mut self,
        pc: u32,
        words: &mut Words,
        blocks: &mut u64,
        exec: impl FnOnce(&mut Nc, &[Word], &mut dyn Sink) -> Result<Outcome, NcError>,
    ) -> Result<Outcome, NcError> {
        // A block makes the motion lag the VM again.
        *self.synced = false;
        charge(blocks, self.max_blocks, 1)?;
        *self.last_exec = pc;
        self.nc
            .set_allowance(self.max_blocks.saturating_sub(*blocks));
        let result = exec(self.nc, &words.list, self.sink);
        words.clear();
        *self.msg = None;
        // A canned cycle counts as the blocks it generates, the first
        // being its own (all passes counted).
        let generated = self.nc.take_generated();
        charge(blocks, self.max_blocks, generated.saturating_sub(1))?;
        result
    }
}

/// A block run from a tier's code: the run, and what it gave, kept for the
/// VM to finish once the code has left.
pub(crate) struct TierCall<'a> {
    pub run: BlockRun<'a>,
    /// The pc of the block and its outcome, once one ran that the VM
    /// must finish.
    pub ran: Option<(u32, Result<Outcome, NcError>)>,
    /// Whether a block whose outcome needs nothing of the VM is done once
    /// run (`Vm::stop_at_blocks` off, no G66 call armed): the code goes on.
    pub go_on: bool,
}

impl Kernel for TierCall<'_> {
    fn run_block(&mut self, pc: u32, words: &mut Words, blocks: &mut u64) -> Ran {
        if self.ran.is_some() {
            // The VM finishes a block before the next runs.
            return Ran::Not;
        }
        match self.run.instr(pc, words, blocks) {
            // No end, no G31 position, no G10 L52 variable, no call: what
            // `Vm::finish_block` would do is nothing.
            Some(Ok(out))
                if self.go_on
                    && out.end.is_none()
                    && out.skip.is_none()
                    && out.store.is_none()
                    && out.call.is_none() =>
            {
                Ran::GoOn
            }
            Some(result) => {
                self.ran = Some((pc, result));
                Ran::Leave
            }
            None => Ran::Not,
        }
    }
}
