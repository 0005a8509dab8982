//! The interpreter loop.

use alloc::boxed::Box;
use alloc::format;
use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

use crate::block::{self, BlockRun, TierCall};
use crate::loc_cache::LocCache;
use crate::tier::{Entry, LoopState, Tier};
use crate::vars::{slot, Slot, Vars};
use isa::{Instr, Module};
use nc::base::nesting::Levels;
use nc::block::round_half_away;
use nc::error::Alarm as AlarmCode;
use nc::event::StopKind;
use nc::value::{self, is_vacant, Bin, Func, Rel, VACANT};
use nc::words::Words;
use nc::{Event, Machine, Nc, NcError, Sink};

/// A run-time alarm with the place of the block that raised it.
#[derive(Debug, Clone, PartialEq)]
pub struct Alarm {
    /// The canon's `CODE=`: 5001 for E5001, 3000 + n for `#3000 = n`.
    pub code: u32,
    /// The alarm text (the kernel's wording, or the `#3000` comment).
    pub message: String,
    /// The source file of the block, as compiled.
    pub file: String,
    /// Its line (1-based).
    pub line: u32,
    /// Its column (1-based).
    pub col: u32,
}

impl Alarm {
    /// `FILE:LINE:COL: alarm[E5001]: message` (`alarm[3005]` for user
    /// alarms, canon.md).
    pub fn header(&self) -> String {
        NcError::header(self.code, &self.message, &self.file, self.line, self.col)
    }
}

/// What one call of [`Vm::step`] ended with.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// The program ended (M02/M30, past its last block, or the M99 of the
    /// last pass).
    Done,
    /// A block executed; its events are in the sink.
    Event,
    /// The instruction budget is used up; call again to go on.
    OutOfBudget,
    /// A run-time alarm; the `ALARM` event is in the sink.
    Alarm(Alarm),
    /// The next instruction reads the current position (#5021–#5023,
    /// #5041–#5043), which on a real control waits for the motion before
    /// it: let that motion finish, then call again (the read then runs).
    /// Only returned when [`Vm::sync_positions`] is set.
    Sync,
}

/// Where #500–#999 persist: the VM hands the whole set over whenever a
/// block changed one of them (vacant values are NaN). `Send`, so that a
/// VM can move to an interpreter thread of its own.
pub trait Storage: Send {
    /// Keeps all of #500–#999; an `Err` stops the run with E5007.
    fn store(&mut self, persistent: &[f64; 500]) -> Result<(), String>;
}

/// A call in progress.
#[derive(Debug, Clone)]
struct Frame {
    return_pc: u32,
    /// The caller's program index.
    caller: u32,
    /// The called program's index.
    callee: u32,
    remaining: u32,
    macro_level: bool,
    modal: bool,
    args: Vec<(u8, f64)>,
}

/// `Exec` flag: hand the block to the kernel as a G70–G73 profile block
/// (its tag is its pc) instead of executing it.
pub const PROFILE: u8 = 1;

struct ModalCall {
    prog: u32,
    count: u32,
    args: Vec<(u8, f64)>,
}

/// The interpreter: one verified module, its registers and variables,
/// and the NC kernel that gives its blocks their meaning.
///
/// ```
/// /// Runs a verified module (`gbcc`'s output, read with
/// /// `isa::Module::from_bytes`) to its end and returns its canon.
/// fn canon(module: isa::Module) -> Result<Vec<nc::Event>, String> {
///     let mut vm = vm::Vm::new(module, nc::Machine::reference());
///     let mut events: Vec<nc::Event> = Vec::new();
///     match vm.run(&mut events) {
///         vm::Status::Alarm(a) => Err(a.header()),
///         _ => Ok(events),
///     }
/// }
/// ```
pub struct Vm {
    module: Module,
    /// The NC kernel: modal state, machine configuration, the meaning of
    /// a block (public so that a host can seed positions and settings).
    pub nc: Nc,
    regs: Vec<f64>,
    vars: Vars,
    pc: u32,
    prog: u32,
    frames: Vec<Frame>,
    words: Words,
    args: Vec<(u8, f64)>,
    msg: Option<u32>,
    modal: Option<ModalCall>,
    blocks: u64,
    /// Block budget: past this many executed blocks the run stops with
    /// E6005 (`gbvm run --max-blocks`).
    pub max_blocks: u64,
    pass: u32,
    /// Passes that a main program's M99 makes (`gbvm run --repeat`).
    pub repeat: u32,
    done: bool,
    /// The pc of the last `Exec` that ran.
    last_exec: u32,
    /// Locations of recent blocks (asked for after every block).
    locs: LocCache,
    /// Return [`Status::Sync`] before reading a current position; a
    /// controller whose motion lags the VM sets it.
    pub sync_positions: bool,
    /// End a step after every NC block with [`Status::Event`] (the
    /// default): a controller's runtime takes each block's events there.
    /// A host that only collects the events (`Vm::run`, `gbvm run --emit
    /// canon`) turns it off; steps then run on past blocks, and so does a
    /// tier's compiled loop, whose blocks no longer end its run.
    pub stop_at_blocks: bool,
    /// The motion was synchronised since the last NC block.
    synced: bool,
    storage: Option<Box<dyn Storage>>,
    /// Compiled code for hot loops, if the host gave a tier.
    tier: Option<Box<dyn Tier>>,
    /// The pc after the instruction at which the tier's code last left
    /// (it may be entered again there); `NO_PC` when none.
    resume_at: u32,
    /// Instructions the current `step` may still run.
    fuel: u64,
}

/// No pc (`resume_at` unset).
const NO_PC: u32 = u32::MAX;

type Fault = NcError;

fn fault<T>(alarm: AlarmCode, msg: impl Into<String>) -> Result<T, Fault> {
    Err(NcError::new(alarm, msg))
}

/// An alarm the program raises itself (`#3000 = n`, `G65 H99`): its
/// number is the program's, not one of dialect.md §8's.
fn program_alarm<T>(code: u16, msg: impl Into<String>) -> Result<T, Fault> {
    Err(NcError::numbered(code, msg))
}

#[derive(PartialEq)]
enum Next {
    Go,
    Event,
    Done,
    /// The instruction at `pc` waits for the motion (not executed yet).
    Sync,
}

impl Vm {
    /// A VM for a verified module on a machine.
    pub fn new(module: Module, machine: Machine) -> Vm {
        let regs = vec![VACANT; module.num_regs.max(1) as usize];
        let max_blocks = machine.run.max_blocks;
        let pc = module.programs.first().map_or(0, |p| p.entry);
        Vm {
            module,
            nc: Nc::new(machine),
            regs,
            vars: Vars::default(),
            pc,
            prog: 0,
            frames: Vec::new(),
            words: Words::default(),
            args: Vec::new(),
            msg: None,
            modal: None,
            blocks: 0,
            max_blocks,
            pass: 1,
            repeat: 1,
            done: false,
            last_exec: 0,
            locs: LocCache::default(),
            sync_positions: false,
            stop_at_blocks: true,
            synced: false,
            storage: None,
            tier: None,
            resume_at: NO_PC,
            fuel: 0,
        }
    }

    /// The module being run.
    pub fn module(&self) -> &Module {
        &self.module
    }

    /// The index of the instruction that runs next (for a debugger or a
    /// test that steps one instruction at a time).
    pub fn pc(&self) -> u32 {
        self.pc
    }

    /// The pc of the instruction that executed the last block (a typed
    /// `block` or `move`, or `exec`/`execmove` after the block's words).
    pub fn last_block_pc(&self) -> u32 {
        self.last_exec
    }

    /// The blocks charged to the block budget so far (a cycle counts as
    /// its moves, a call as one block): a host that steps block by block
    /// tells by it whether a step that ended the run ran a block.
    pub fn blocks_charged(&self) -> u64 {
        self.blocks
    }

    /// The instructions the last [`step`](Self::step) left of its budget
    /// (a step that ends at a block leaves the rest: a host that watches
    /// each block goes on with it).
    pub fn fuel_left(&self) -> u64 {
        self.fuel
    }

    /// The source place of the block executed last (for traces).
    pub fn last_loc(&self) -> isa::SourceLoc {
        self.locs.get(&self.module.lines, self.last_exec)
    }

    /// The source place of the block instruction at `pc`: events told to
    /// a sink under `Sink::origin(pc)` belong to it.
    pub fn loc_at(&self, pc: u32) -> isa::SourceLoc {
        self.locs.get(&self.module.lines, pc)
    }

    /// Whether block-skip switch `switch` (1–9; `/` is 1) is on: a `/n`
    /// block read from now on is skipped. It starts as the machine file's
    /// `operator.block_skip`; a number outside 1–9 names no switch (off).
    pub fn block_skip(&self, switch: u8) -> bool {
        let switches = &self.nc.machine.operator.block_skip;
        let index = usize::from(switch).wrapping_sub(1);
        switches.get(index).copied().unwrap_or(false)
    }

    /// Turns block-skip switch `switch` (1–9) on or off, as the operator's
    /// key does: it decides for the blocks the VM reads from now on (the
    /// ones it has read, ahead of the motion, keep their decision). A
    /// number outside 1–9 changes nothing.
    pub fn set_block_skip(&mut self, switch: u8, on: bool) {
        let index = usize::from(switch).wrapping_sub(1);
        if let Some(s) = self.nc.machine.operator.block_skip.get_mut(index) {
            *s = on;
        }
    }

    /// Persists #500–#999 through `storage` from now on.
    pub fn set_storage(&mut self, storage: Box<dyn Storage>) {
        self.storage = Some(storage);
    }

    /// The storage of #500–#999, taken out (a host that replaces the VM
    /// after a reset hands it to the new one).
    pub fn take_storage(&mut self) -> Option<Box<dyn Storage>> {
        self.storage.take()
    }

    /// Runs hot loops through `tier` from now on (the `jit` crate's).
    pub fn set_tier(&mut self, mut tier: Box<dyn Tier>) {
        tier.bind(&self.module);
        self.resume_at = NO_PC;
        self.tier = Some(tier);
    }

    /// What the tier has done, if there is one.
    pub fn tier_stats(&self) -> Option<crate::tier::TierStats> {
        self.tier.as_ref().map(|t| t.stats())
    }

    /// The tier, taken out (a host that replaces the VM after a reset
    /// hands it to the new one).
    pub fn take_tier(&mut self) -> Option<Box<dyn Tier>> {
        self.resume_at = NO_PC;
        self.tier.take()
    }

    /// Runs at most `budget` instructions (those a tier ran included).
    pub fn step(&mut self, budget: u64, sink: &mut dyn Sink) -> Status {
        if self.done {
            return Status::Done;
        }
        self.fuel = budget;
        while self.fuel > 0 {
            self.fuel -= 1;
            if self.pc == self.resume_at {
                if let Some(status) = self.resume(sink) {
                    return status;
                }
            }
            let pc = self.pc;
            let result = self.exec_one(sink);
            if let Some(status) = self.settle(pc, result, sink) {
                return status;
            }
        }
        Status::OutOfBudget
    }

    /// The tier's code runs on from the pc, up to a block it runs (the
    /// step ends there, as that block's instruction would end it), or up
    /// to an instruction it leaves to the interpreter (`None`). (Cold,
    /// as `enter_tier`: out of the interpreter's loop, which without a
    /// tier never comes here; inline it cost 2–3 % of an interpreted
    /// program's instructions.)
    #[cold]
    fn resume(&mut self, sink: &mut dyn Sink) -> Option<Status> {
        let ran = self.enter_tier(Entry::Resume, sink)?;
        self.settle(self.pc, ran, sink)
    }

    /// What the step does after the instruction at `pc` gave `result`:
    /// goes on (`None`) or returns a status. (Inline: it follows every
    /// instruction.)
    #[inline(always)]
    fn settle(
        &mut self,
        pc: u32,
        result: Result<Next, Fault>,
        sink: &mut dyn Sink,
    ) -> Option<Status> {
        match result.and_then(|next| self.persist().map(|()| next)) {
            Ok(Next::Go) => None,
            Ok(Next::Event) => self.stop_at_blocks.then_some(Status::Event),
            Ok(Next::Sync) => Some(Status::Sync),
            Ok(Next::Done) => {
                self.done = true;
                Some(Status::Done)
            }
            Err(e) => {
                self.done = true;
                let _ = self.persist();
                Some(Status::Alarm(self.alarm(pc, e, sink)))
            }
        }
    }

    /// Hands changed persistent variables to the storage. (Asked after
    /// every instruction: the question is inline, the storing is not.)
    #[inline]
    fn persist(&mut self) -> Result<(), Fault> {
        match self.vars.persistent_dirty {
            false => Ok(()),
            true => self.store_persistent(),
        }
    }

    #[cold]
    fn store_persistent(&mut self) -> Result<(), Fault> {
        let Some(storage) = self.storage.as_mut() else {
            return Ok(());
        };
        self.vars.persistent_dirty = false;
        storage.store(&self.vars.persistent).map_err(|e| {
            NcError::new(
                nc::error::Alarm::VariableAccess,
                format!("cannot store #500–#999: {e}"),
            )
        })
    }

    /// Runs to the end; the final status (never `Event`/`OutOfBudget`).
    pub fn run(&mut self, sink: &mut dyn Sink) -> Status {
        // Nothing is done between blocks here: they need not end a step.
        let stop_at_blocks = core::mem::replace(&mut self.stop_at_blocks, false);
        let status = loop {
            match self.step(1 << 16, sink) {
                Status::Event | Status::OutOfBudget | Status::Sync => continue,
                other => break other,
            }
        };
        self.stop_at_blocks = stop_at_blocks;
        status
    }

    fn alarm(&mut self, pc: u32, e: Fault, sink: &mut dyn Sink) -> Alarm {
        // What was programmed before the faulty block still prints; a
        // second fault while flushing changes nothing about the first.
        let _ = self.nc.flush(sink);
        // An error about a profile block names that block.
        let pc = e.at.unwrap_or(pc);
        let loc = self.module.lines.get(pc as usize).unwrap_or_default();
        let file = self
            .module
            .files
            .get(loc.file as usize)
            .map_or_else(String::new, |f| f.name.clone());
        let msg = if NcError::is_program_alarm(e.code as u32) {
            self.msg_text()
        } else if let Some(tag) = e.culprit {
            // (The alarm stands on the cycle block: the message says which
            // profile block it is about.)
            let line = self.module.lines.get(tag as usize).unwrap_or_default().line;
            nc::event::ascii(&format!("{} (line {line})", e.message))
        } else {
            // The canon is ASCII (canon.md): our own messages are written
            // so; a program's text prints as it is (other bytes as `?`).
            nc::event::ascii(&e.message)
        };
        sink.emit(Event::Alarm {
            code: e.code as u32,
            msg: msg.clone(),
        });
        Alarm {
            code: e.code as u32,
            message: if msg.is_empty() { e.message } else { msg },
            file,
            line: loc.line,
            col: loc.col,
        }
    }

    fn msg_text(&self) -> String {
        self.msg
            .and_then(|s| self.module.strings.get(s as usize))
            .cloned()
            .unwrap_or_default()
    }

    fn count_block(&mut self) -> Result<(), Fault> {
        block::charge(&mut self.blocks, self.max_blocks, 1)
    }

    /// Continues at `target`. A transfer backwards may close a loop, so it
    /// is charged to the block budget like a block, whichever instruction
    /// makes it: every loop of any module, compiled or crafted, then ends
    /// with E6005 at the latest. (GOTO, calls and M99 are charged where
    /// they run.)
    ///
    /// A tier may take over at a backward jump; if its code runs a block,
    /// the jump ends as that block's instruction would.
    fn jump(&mut self, target: u32, sink: &mut dyn Sink) -> Result<Next, Fault> {
        if target < self.pc {
            self.count_block()?;
        }
        self.transfer(target, sink)
    }

    /// Continues at `target`, already charged: a tier may take over at a
    /// backward transfer.
    fn transfer(&mut self, target: u32, sink: &mut dyn Sink) -> Result<Next, Fault> {
        let from = self.pc - 1;
        self.pc = target;
        if target <= from && self.tier.is_some() {
            if let Some(ran) = self.enter_tier(Entry::BackEdge { from }, sink) {
                return ran;
            }
        }
        Ok(Next::Go)
    }

    /// Lets the tier run from the pc, if it has code there. If its code
    /// ran a block (and left after it), that block's end, finished here:
    /// an alarm names the block.
    #[cold]
    fn enter_tier(&mut self, entry: Entry, sink: &mut dyn Sink) -> Option<Result<Next, Fault>> {
        let tier = self.tier.as_mut()?;
        let (locals, common, persistent) = self.vars.split();
        // (The tier, the registers and the variables are borrowed beside
        // the block's part, and the words and block count go to the tier.)
        let mut call = TierCall {
            run: BlockRun {
                module: &self.module,
                nc: &mut self.nc,
                sink: &mut *sink,
                max_blocks: self.max_blocks,
                last_exec: &mut self.last_exec,
                msg: &mut self.msg,
                synced: &mut self.synced,
            },
            ran: None,
            // A block may be run through (its outcome needing nothing of
            // the VM) where steps run on past blocks and no G66 call
            // follows a move.
            go_on: !self.stop_at_blocks && self.modal.is_none(),
        };
        let state = LoopState {
            regs: &mut self.regs,
            locals,
            common,
            persistent,
            words: &mut self.words,
            blocks: &mut self.blocks,
            max_blocks: self.max_blocks,
            fuel: &mut self.fuel,
            kernel: &mut call,
        };
        self.resume_at = NO_PC;
        let next = tier.enter(&self.module, self.pc, entry, state);
        let TierCall { ran, .. } = call;
        if let Some(pc) = next {
            self.pc = pc;
            self.resume_at = pc.saturating_add(1);
        }
        // (Read in place: moving the outcome whole, just written field by
        // field, stalled the processor's store forwarding.)
        let at = ran.as_ref()?.0;
        // The code left after the block: it may go on from there.
        self.pc = at.saturating_add(1);
        self.resume_at = self.pc;
        let result = match ran {
            Some((_, Ok(ref out))) => self.finish_block(out, sink),
            Some((_, Err(e))) => Err(e),
            None => return None,
        };
        Some(result.map_err(|e| about_block(e, at)))
    }

    fn reg(&self, r: u8) -> f64 {
        self.regs.get(r as usize).copied().unwrap_or(VACANT)
    }

    fn set(&mut self, r: u8, v: f64) {
        if let Some(slot) = self.regs.get_mut(r as usize) {
            *slot = v;
        }
    }

    fn konst(&self, k: u32) -> f64 {
        self.module
            .consts
            .get(k as usize)
            .copied()
            .unwrap_or(VACANT)
    }

    fn exec_one(&mut self, sink: &mut dyn Sink) -> Result<Next, Fault> {
        let Some(&instr) = self.module.code.get(self.pc as usize) else {
            return fault(
                AlarmCode::JumpTargetMissing,
                "execution ran outside the program",
            );
        };
        self.pc += 1;
        match instr {
            Instr::LoadK { dst, k } => self.set(dst, self.konst(k)),
            Instr::LoadNull { dst } => self.set(dst, VACANT),
            Instr::Mov { dst, src } => self.set(dst, self.reg(src)),
            Instr::LoadVar { dst, var } => {
                if self.must_sync(var) {
                    return Ok(self.wait_for_motion());
                }
                let v = self.read_var(var)?;
                self.set(dst, v);
            }
            Instr::LoadVarInd { dst, idx } => {
                let n = var_number(self.reg(idx))?;
                if self.must_sync(n) {
                    return Ok(self.wait_for_motion());
                }
                let v = self.read_var(n)?;
                self.set(dst, v);
            }
            Instr::StoreVar { var, src } => {
                self.count_block()?;
                self.write_var(var, self.reg(src), sink)?;
            }
            Instr::StoreVarInd { idx, src } => {
                self.count_block()?;
                let n = var_number(self.reg(idx))?;
                self.write_var(n, self.reg(src), sink)?;
            }
            Instr::Neg { dst, a } => self.set(dst, value::neg(self.reg(a))),
            Instr::Add { dst, a, b } => self.bin(Bin::Add, dst, a, b)?,
            Instr::Sub { dst, a, b } => self.bin(Bin::Sub, dst, a, b)?,
            Instr::Mul { dst, a, b } => self.bin(Bin::Mul, dst, a, b)?,
            Instr::Div { dst, a, b } => self.bin(Bin::Div, dst, a, b)?,
            Instr::Mod { dst, a, b } => self.bin(Bin::Mod, dst, a, b)?,
            Instr::BitAnd { dst, a, b } => self.bin(Bin::And, dst, a, b)?,
            Instr::BitOr { dst, a, b } => self.bin(Bin::Or, dst, a, b)?,
            Instr::BitXor { dst, a, b } => self.bin(Bin::Xor, dst, a, b)?,
            Instr::Func { dst, a, f } => {
                let Some(f) = Func::from_code(f) else {
                    return fault(AlarmCode::NotSupportedYet, "unknown function code");
                };
                let v = value::func(f, self.reg(a))?;
                self.set(dst, v);
            }
            Instr::Atan2 { dst, y, x } => {
                let v = value::atan2(self.reg(y), self.reg(x))?;
                self.set(dst, v);
            }
            Instr::Cmp { dst, a, b, op } => self.compare(op, dst, self.reg(a), self.reg(b))?,
            Instr::AddK { dst, a, k } => self.bin_k(Bin::Add, dst, a, k)?,
            Instr::SubK { dst, a, k } => self.bin_k(Bin::Sub, dst, a, k)?,
            Instr::MulK { dst, a, k } => self.bin_k(Bin::Mul, dst, a, k)?,
            Instr::DivK { dst, a, k } => self.bin_k(Bin::Div, dst, a, k)?,
            Instr::CmpK { dst, a, k, op } => self.compare(op, dst, self.reg(a), self.konst(k))?,
            Instr::Jump { target } => return self.jump(target, sink),
            Instr::Goto { target } => {
                // Charged here as the GOTO block, so a backward one is not
                // charged again as closing a loop.
                self.count_block()?;
                return self.transfer(target, sink);
            }
            Instr::Charge => self.count_block()?,
            Instr::JumpIfNot { cond, target } => {
                if value::compare(Rel::Eq, self.reg(cond), 0.0) == 1.0 || is_vacant(self.reg(cond))
                {
                    return self.jump(target, sink);
                }
            }
            Instr::SkipBlock { switch, target } => {
                // The switch as the block is read: the VM reads blocks
                // ahead of the motion, so a change reaches the blocks not
                // yet read (forward only: nothing to charge).
                if self.block_skip(switch) {
                    self.pc = target;
                }
            }
            Instr::GotoSeq { seq } => self.goto_seq(seq, 0)?,
            Instr::GotoSeqIn { seq, inside } => self.goto_seq(seq, inside)?,
            Instr::Word { addr, src } => {
                let v = self.reg(src);
                // A word whose value is vacant is left out (§7.5).
                if !is_vacant(v) {
                    self.words.push(addr, v, 0);
                }
            }
            Instr::WordK { addr, k, flags } => {
                self.words.push(addr, self.konst(k), flags);
                // A block's literal words come in a run: take the rest of
                // it here rather than one dispatch each (they cannot fail,
                // wait or write a variable).
                while let Some(&Instr::WordK { addr, k, flags }) =
                    self.module.code.get(self.pc as usize)
                {
                    self.pc += 1;
                    self.words.push(addr, self.konst(k), flags);
                }
            }
            Instr::SetMsg { s } => self.msg = Some(s),
            Instr::Exec { flags } if flags & PROFILE != 0 => {
                self.nc.push_profile(&self.words.list, self.pc - 1);
                self.words.clear();
                self.msg = None;
            }
            // The NC blocks (`block::BlockRun`), then what follows them.
            Instr::Exec { .. } => return self.run_block(sink, |r, pc, w, b| r.words(pc, w, b)),
            Instr::Block { rec } => {
                return self.run_block(sink, |r, pc, w, b| r.typed(pc, rec, w, b));
            }
            Instr::Move { rec } => {
                return self.run_block(sink, |r, pc, w, b| r.typed_move(pc, rec, w, b));
            }
            Instr::ExecMove => return self.run_block(sink, |r, pc, w, b| r.plain_move(pc, w, b)),
            Instr::Profile { rec } => {
                // A typed profile block: as `wordk… exec` with PROFILE.
                block::load_record(&self.module, rec, &mut self.words)?;
                self.nc.push_profile(&self.words.list, self.pc - 1);
                self.words.clear();
            }
            Instr::CallSub { prog, count } => {
                self.nc.check_call()?;
                let n = count_of(self.reg(count))?;
                self.call(prog, n, false, false, Vec::new())?;
            }
            Instr::CallSubDyn { num, count } => {
                self.nc.check_call()?;
                let prog = self.program_by_number(self.reg(num))?;
                let n = count_of(self.reg(count))?;
                self.call(prog, n, false, false, Vec::new())?;
            }
            Instr::CallSubPacked { num } => {
                self.nc.check_call()?;
                let (prog, n) = self.packed(self.reg(num))?;
                self.call(prog, n, false, false, Vec::new())?;
            }
            Instr::CallMacro { prog, count } => {
                let n = count_of(self.reg(count))?;
                let args = core::mem::take(&mut self.args);
                self.modal = None;
                self.call(prog, n, true, false, args)?;
            }
            Instr::CallMacroDyn { num, count } => {
                let prog = self.program_by_number(self.reg(num))?;
                let n = count_of(self.reg(count))?;
                let args = core::mem::take(&mut self.args);
                self.modal = None;
                self.call(prog, n, true, false, args)?;
            }
            Instr::Arg { var, src } => {
                let v = self.reg(src);
                if !is_vacant(v) {
                    self.args.retain(|(a, _)| *a != var);
                    self.args.push((var, v));
                }
            }
            Instr::ModalCall { prog, count } => {
                let count = count_of(self.reg(count))?;
                let args = core::mem::take(&mut self.args);
                self.modal = Some(ModalCall { prog, count, args });
            }
            Instr::ModalCallDyn { num, count } => {
                let prog = self.program_by_number(self.reg(num))?;
                let count = count_of(self.reg(count))?;
                let args = core::mem::take(&mut self.args);
                self.modal = Some(ModalCall { prog, count, args });
            }
            Instr::ModalCancel => self.modal = None,
            Instr::Ret => return self.ret(None, sink),
            Instr::RetSeq { seq } => {
                let n = target_number(self.reg(seq))?;
                return self.ret(Some(n), sink);
            }
            Instr::Alarm { code, msg } => {
                self.msg = Some(msg);
                return program_alarm(code, self.msg_text());
            }
            Instr::UserAlarm { q, msg } => {
                // A vacant Q is no Q: 0 (dialect.md §7.5).
                let q = self.reg(q);
                let n = if is_vacant(q) {
                    0.0
                } else {
                    nc::block::round_half_away(q)
                };
                if !(0.0..=99.0).contains(&n) {
                    let msg = format!(
                        "G65 H99: Q{} is outside 0…99 (alarms 500…599)",
                        nc::event::Num(n)
                    );
                    return fault(AlarmCode::ValueOutOfRange, msg);
                }
                self.msg = Some(msg);
                return program_alarm(500 + n as u16, self.msg_text());
            }
            Instr::Halt => {
                // Running past the last block: a waiting corner element is
                // printed whole.
                self.nc.flush(sink)?;
                return Ok(Next::Done);
            }
        }
        Ok(Next::Go)
    }

    /// A computed GOTO to the number in register `seq`, from inside DO
    /// loop `inside` of the program (0: outside every loop).
    fn goto_seq(&mut self, seq: u8, inside: u32) -> Result<(), Fault> {
        self.count_block()?;
        let n = target_number(self.reg(seq))?;
        if n == 0 {
            return fault(
                AlarmCode::ValueOutOfRange,
                "GOTO 0: sequence numbers to jump to are 1…99999",
            );
        }
        let prog = self.prog as usize;
        let Some((pc, target_loop)) = self.module.seq_target(prog, n) else {
            return fault(
                AlarmCode::JumpTargetMissing,
                format!("GOTO {n}: there is no block N{n} in this program"),
            );
        };
        // Into a loop only from inside it (dialect.md §7.7).
        if !self.module.loop_holds(prog, target_loop, inside) {
            return fault(
                AlarmCode::ComputedJumpIntoLoop,
                format!("GOTO {n} jumps into a DO loop from outside it"),
            );
        }
        self.pc = pc;
        Ok(())
    }

    fn bin(&mut self, op: Bin, dst: u8, a: u8, b: u8) -> Result<(), Fault> {
        let v = value::binary(op, self.reg(a), self.reg(b))?;
        self.set(dst, v);
        Ok(())
    }

    /// `a op consts[k]`, as `bin` with the constant in a register.
    fn bin_k(&mut self, op: Bin, dst: u8, a: u8, k: u32) -> Result<(), Fault> {
        let v = value::binary(op, self.reg(a), self.konst(k))?;
        self.set(dst, v);
        Ok(())
    }

    fn compare(&mut self, op: u8, dst: u8, a: f64, b: f64) -> Result<(), Fault> {
        let Some(op) = Rel::from_code(op) else {
            return fault(AlarmCode::NotSupportedYet, "unknown comparison code");
        };
        self.set(dst, value::compare(op, a, b));
        Ok(())
    }

    /// Runs the block instruction just read with `run` (one of
    /// [`BlockRun`]'s), then finishes it.
    #[inline(always)]
    fn run_block(
        &mut self,
        sink: &mut dyn Sink,
        run: impl FnOnce(&mut BlockRun<'_>, u32, &mut Words, &mut u64) -> Result<nc::Outcome, Fault>,
    ) -> Result<Next, Fault> {
        let pc = self.pc - 1;
        // (As `BlockRun::instr` does for a tier's call.)
        self.nc.origin = pc;
        let mut kernel = BlockRun {
            module: &self.module,
            nc: &mut self.nc,
            sink: &mut *sink,
            max_blocks: self.max_blocks,
            last_exec: &mut self.last_exec,
            msg: &mut self.msg,
            synced: &mut self.synced,
        };
        let out = run(&mut kernel, pc, &mut self.words, &mut self.blocks)?;
        self.finish_block(&out, sink)
    }

    /// What follows a block in the VM: G31's skip position, G10 L52's
    /// variable, the program's end, a G66 call after a move. (Inline: it
    /// follows every block.)
    #[inline(always)]
    fn finish_block(&mut self, out: &nc::Outcome, sink: &mut dyn Sink) -> Result<Next, Fault> {
        if let Some(p) = out.skip {
            // #995–#999 are persistent: set as a store would, so that
            // the storage gets them.
            let x = self.nc.machine.programmed_x(p.r);
            let values = [x, p.z, VACANT, VACANT, VACANT];
            for (i, v) in (495..).zip(values) {
                self.vars.set(&Slot::Persistent(i), v);
            }
        }
        // G10 L52 `N… R#var`: the kernel read the parameter, the variable
        // is ours to write.
        if let Some((var, value)) = out.store {
            self.write_var(var, value, sink)?;
        }
        if out.end.is_some() {
            return Ok(Next::Done);
        }
        if let Some(call) = out.call {
            return self.word_call(call, sink);
        }
        if out.modal_call && !self.frames.iter().any(|f| f.modal) {
            if let Some(m) = &self.modal {
                let (prog, count, args) = (m.prog, m.count, m.args.clone());
                self.call(prog, count, true, true, args)?;
            }
        }
        Ok(Next::Event)
    }

    /// The call or return of a block's computed M code (`nc::WordCall`),
    /// after the block, as a written one's `callsub…` or `ret`.
    fn word_call(&mut self, call: nc::WordCall, sink: &mut dyn Sink) -> Result<Next, Fault> {
        match call {
            nc::WordCall::Sub { p: None, .. } => {
                return fault(AlarmCode::MissingWord, "M98 needs P, the program to call");
            }
            nc::WordCall::Sub { p: Some(p), l } => {
                self.nc.check_call()?;
                let (prog, count) = match l {
                    Some(l) => (self.program_by_number(p)?, count_of(l)?),
                    None => self.packed(p)?,
                };
                self.call(prog, count, false, false, Vec::new())?;
            }
            nc::WordCall::Macro(n) => {
                self.nc.check_call()?;
                let prog = self.program_by_number(f64::from(n))?;
                self.call(prog, 1, false, false, Vec::new())?;
            }
            nc::WordCall::Return { seq } => {
                let seq = seq.map(target_number).transpose()?;
                if self.ret(seq, sink)? == Next::Done {
                    return Ok(Next::Done);
                }
            }
        }
        Ok(Next::Event)
    }

    /// The program and count of `M98 P<count:4><program:4>` (dialect.md
    /// §7.11): count 0 is once; a vacant P is E5009.
    fn packed(&self, p: f64) -> Result<(u32, u32), Fault> {
        let packed = target_number(p)?;
        let prog = self.program_by_number(f64::from(packed % 10_000))?;
        Ok((prog, (packed / 10_000).max(1)))
    }

    fn program_by_number(&self, v: f64) -> Result<u32, Fault> {
        let n = target_number(v)?;
        self.module
            .programs
            .iter()
            .position(|p| p.number == n)
            .map(|i| i as u32)
            .ok_or_else(|| {
                NcError::new(
                    nc::error::Alarm::CalledProgramMissing,
                    format!("the called program O{n:04} does not exist"),
                )
            })
    }

    fn call(
        &mut self,
        callee: u32,
        count: u32,
        macro_level: bool,
        modal: bool,
        args: Vec<(u8, f64)>,
    ) -> Result<(), Fault> {
        self.count_block()?;
        self.nc.break_thread_chain();
        let macros = self.frames.iter().filter(|f| f.macro_level).count();
        let levels = Levels {
            macros,
            subs: self.frames.len() - macros,
        };
        if levels.enter(macro_level).is_none() {
            return fault(
                AlarmCode::CallsTooDeep,
                "calls nested too deep (4 macro levels, 4 subprogram levels, 8 in all)",
            );
        }
        let Some(entry) = self.module.programs.get(callee as usize).map(|p| p.entry) else {
            return fault(
                AlarmCode::CalledProgramMissing,
                "the called program does not exist",
            );
        };
        if macro_level {
            self.vars.push_level(&args);
        }
        self.frames.push(Frame {
            return_pc: self.pc,
            caller: self.prog,
            callee,
            remaining: count.saturating_sub(1),
            macro_level,
            modal,
            args,
        });
        self.prog = callee;
        self.pc = entry;
        Ok(())
    }

    /// M99 (with `seq`: M99 P n).
    fn ret(&mut self, seq: Option<u32>, sink: &mut dyn Sink) -> Result<Next, Fault> {
        self.count_block()?;
        self.nc.break_thread_chain();
        let Some(frame) = self.frames.last_mut() else {
            return self.end_pass(seq, sink);
        };
        if frame.remaining > 0 {
            frame.remaining -= 1;
            let (callee, macro_level, args) = (frame.callee, frame.macro_level, frame.args.clone());
            if macro_level {
                self.vars.refresh_level(&args);
            }
            self.pc = self
                .module
                .programs
                .get(callee as usize)
                .map_or(self.pc, |p| p.entry);
            return Ok(Next::Go);
        }
        let Some(frame) = self.frames.pop() else {
            return Ok(Next::Done);
        };
        if frame.macro_level {
            self.vars.pop_level();
        }
        self.prog = frame.caller;
        self.pc = frame.return_pc;
        if let Some(n) = seq {
            match self.module.pc_of_seq(frame.caller as usize, n) {
                Some(pc) => self.pc = pc,
                None => {
                    return fault(
                        AlarmCode::ReturnTargetMissing,
                        format!("M99 P{n}: the calling program has no block N{n}"),
                    )
                }
            }
        }
        Ok(Next::Go)
    }

    /// A main-program M99: the pass ends; the last one ends the run.
    fn end_pass(&mut self, seq: Option<u32>, sink: &mut dyn Sink) -> Result<Next, Fault> {
        if self.pass >= self.repeat {
            self.nc.flush(sink)?;
            sink.emit(Event::Stop(StopKind::M99));
            return Ok(Next::Done);
        }
        self.pass += 1;
        self.pc = self.module.programs.first().map_or(0, |p| p.entry);
        if let Some(n) = seq {
            match self.module.pc_of_seq(0, n) {
                Some(pc) => self.pc = pc,
                None => {
                    return fault(
                        AlarmCode::ReturnTargetMissing,
                        format!("M99 P{n}: the main program has no block N{n}"),
                    )
                }
            }
        }
        Ok(Next::Go)
    }

    /// Whether reading #`n` must first wait for the motion before it.
    fn must_sync(&self, n: u32) -> bool {
        self.sync_positions && !self.synced && nc::sysvar::is_current_position(n)
    }

    /// Stops before the current instruction until the caller has let the
    /// motion finish; reads after it, up to the next NC block, need no wait.
    fn wait_for_motion(&mut self) -> Next {
        self.pc -= 1;
        self.synced = true;
        Next::Sync
    }

    /// (Inline: the common and local variables, the rest out of line.)
    #[inline]
    fn read_var(&self, n: u32) -> Result<f64, Fault> {
        match slot(n) {
            Some(s) => Ok(self.vars.get(&s)),
            None => self.read_other_var(n),
        }
    }

    fn read_other_var(&self, n: u32) -> Result<f64, Fault> {
        if n == 0 {
            return Ok(VACANT);
        }
        match n {
            4114 => return Ok(self.last_sequence().map_or(VACANT, f64::from)),
            4115 => return Ok(self.program_number().map_or(VACANT, f64::from)),
            // Group 12 is the VM's: G66 in force (also inside the macro
            // it calls) or G67 (dialect.md §7.2).
            4012 => return Ok(if self.modal.is_some() { 66.0 } else { 67.0 }),
            _ => {}
        }
        if nc::sysvar::is_system(n) {
            return Ok(self.nc.read_var(n)?.unwrap_or(VACANT));
        }
        fault(AlarmCode::NoSuchVariable, format!("#{n} names no variable"))
    }

    /// #4115: the number of the running program.
    fn program_number(&self) -> Option<u32> {
        self.module
            .programs
            .get(self.prog as usize)
            .map(|p| p.number)
    }

    /// #4114, the last N passed: the nearest N block at or before the
    /// running instruction in the running program, else at or before the
    /// call in each caller (a subprogram without N keeps its caller's).
    fn last_sequence(&self) -> Option<u32> {
        let here = (self.prog, self.pc.saturating_sub(1));
        let callers = self
            .frames
            .iter()
            .rev()
            .map(|f| (f.caller, f.return_pc.saturating_sub(1)));
        core::iter::once(here)
            .chain(callers)
            .find_map(|(prog, pc)| self.sequence_before(prog, pc))
    }

    fn sequence_before(&self, prog: u32, pc: u32) -> Option<u32> {
        let p = self.module.programs.get(prog as usize)?;
        p.seqs
            .iter()
            .filter(|&&(_, at)| at <= pc)
            .max_by_key(|&&(_, at)| at)
            .map(|&(n, _)| n)
    }

    #[inline]
    fn write_var(&mut self, n: u32, v: f64, sink: &mut dyn Sink) -> Result<(), Fault> {
        match slot(n) {
            Some(s) => {
                self.vars.set(&s, v);
                Ok(())
            }
            None => self.write_other_var(n, v, sink),
        }
    }

    fn write_other_var(&mut self, n: u32, v: f64, sink: &mut dyn Sink) -> Result<(), Fault> {
        match n {
            0 => fault(
                AlarmCode::VariableAccess,
                "#0 is always vacant and cannot be written",
            ),
            3000 => {
                let code = whole_number(v);
                if !(0.0..=999.0).contains(&code) {
                    return fault(
                        AlarmCode::ValueOutOfRange,
                        format!("#3000 = {code}: the alarm number must be 0…999"),
                    );
                }
                program_alarm(3000 + code as u16, self.msg_text())
            }
            3006 => {
                let text = self.msg_text();
                let number = message_number(v);
                let message = Event::Message { number, text };
                self.between(sink, |nc, sink| nc.emit_in_order(message, sink));
                self.msg = None;
                Ok(())
            }
            n if nc::sysvar::is_system(n) => {
                let value = (!is_vacant(v)).then_some(v);
                self.between(sink, |nc, sink| nc.write_var(n, value, sink))
            }
            _ => fault(AlarmCode::NoSuchVariable, format!("#{n} names no variable")),
        }
    }

    /// Runs `f`: a statement between blocks that may print (`#3006 = n`,
    /// a work offset's write). What it prints is the statement's own,
    /// tagged with its pc ([`Sink::origin`]), not the next block's, which
    /// ends the step: so `gbcc -E` and the runtime name its line.
    fn between<R>(
        &mut self,
        sink: &mut dyn Sink,
        f: impl FnOnce(&mut Nc, &mut dyn Sink) -> R,
    ) -> R {
        let at = self.pc.wrapping_sub(1);
        // (What waits for a corner holds it with this tag too.)
        self.nc.origin = at;
        let mut own = Statement {
            sink: &mut *sink,
            at,
            told: false,
        };
        let result = f(&mut self.nc, &mut own);
        if own.told {
            sink.origin(nc::RUNNING);
        }
        result
    }

    /// The value of variable `n` as the program would read it (vacant as
    /// NaN), for hosts and tests.
    pub fn variable(&self, n: u32) -> Result<f64, NcError> {
        self.read_var(n)
    }

    /// The persistent variables #500–#999 (vacant as NaN).
    pub fn persistent(&self) -> &[f64; 500] {
        &self.vars.persistent
    }

    /// The persistent variables, for a host that loads them at the start
    /// (changes made here are not handed to the storage).
    pub fn persistent_mut(&mut self) -> &mut [f64; 500] {
        &mut self.vars.persistent
    }

    /// Sets #500–#999 variable `n` as the operator's macro-variable page
    /// does: NaN makes it vacant; the storage gets the set at once. The
    /// VM reads ahead of the motion, so the value counts for the blocks
    /// it reads from now on. Other variables are refused: #1–#33 and
    /// #100–#199 belong to the run (and start vacant in each), system
    /// variables act on the machine (the offset page has its own calls).
    pub fn set_persistent(&mut self, n: u32, value: f64) -> Result<(), VariableRefused> {
        let Some(crate::vars::Slot::Persistent(i)) = crate::vars::slot(n) else {
            return Err(VariableRefused::NotPersistent(n));
        };
        if value.is_infinite() {
            return Err(VariableRefused::NotFinite(n));
        }
        self.vars.persistent[i] = value;
        self.vars.persistent_dirty = true;
        self.store_persistent()
            .map_err(|e| VariableRefused::Storage(e.message))
    }
}

/// Why [`Vm::set_persistent`] refused a value.
#[derive(Debug, Clone, PartialEq)]
pub enum VariableRefused {
    /// The variable is not one of #500–#999.
    NotPersistent(u32),
    /// The value is infinite.
    NotFinite(u32),
    /// The storage failed (the value is set nonetheless, as a run's
    /// would be before its E5007).
    Storage(String),
}

impl core::fmt::Display for VariableRefused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            VariableRefused::NotPersistent(n) => write!(
                f,
                "#{n}: only #500–#999 can be set from outside the program (#1–#33 and #100–#199 belong to the run, system variables act on the machine)"
            ),
            VariableRefused::NotFinite(n) => write!(f, "#{n}: the value is infinite"),
            VariableRefused::Storage(e) => write!(f, "{e}"),
        }
    }
}

/// The sink of a statement between blocks ([`Vm::between`]): told its
/// tag before the first event it prints.
struct Statement<'a> {
    sink: &'a mut dyn Sink,
    at: u32,
    /// Whether the sink was told a tag.
    told: bool,
}

impl Sink for Statement<'_> {
    fn emit(&mut self, event: Event) {
        if !self.told {
            self.sink.origin(self.at);
            self.told = true;
        }
        self.sink.emit(event);
    }

    fn origin(&mut self, block: u32) {
        self.sink.origin(block);
        self.told = true;
    }
}

/// The number of a `#3006 = n` message stop, for the host: any value is
/// allowed (dialect.md §7.3), so it is made whole as `#3000` makes its
/// alarm number and held in `u32` (`as` saturates: below 0 is 0, beyond
/// the range `u32::MAX`).
fn message_number(v: f64) -> u32 {
    whole_number(v) as u32
}

/// The number `#3000` and `#3006` take from a value: rounded half away
/// from zero, vacant 0.
fn whole_number(v: f64) -> f64 {
    if is_vacant(v) {
        0.0
    } else {
        round_half_away(v)
    }
}

/// A fault of the block at `pc` that a tier's code ran: the alarm names
/// that block (unless it names a profile block already).
fn about_block(mut e: Fault, pc: u32) -> Fault {
    e.at.get_or_insert(pc);
    e
}

/// A variable number from a value: rounded; vacant E5009, negative E5008.
fn var_number(v: f64) -> Result<u32, Fault> {
    if is_vacant(v) {
        return fault(
            AlarmCode::NullValue,
            "a vacant value cannot name a variable",
        );
    }
    let n = round_half_away(v);
    if !(0.0..=u32::MAX as f64).contains(&n) {
        return fault(AlarmCode::NoSuchVariable, format!("#{n} names no variable"));
    }
    Ok(n as u32)
}

/// A jump or call target: vacant is E5009.
fn target_number(v: f64) -> Result<u32, Fault> {
    if is_vacant(v) {
        return fault(
            AlarmCode::NullValue,
            "a vacant value cannot be a jump or call target",
        );
    }
    let n = round_half_away(v);
    if !(0.0..=99_999_999.0).contains(&n) {
        return fault(
            AlarmCode::ValueOutOfRange,
            format!("{n} is not a valid sequence or program number"),
        );
    }
    Ok(n as u32)
}

/// A repeat count L: vacant is once (the word is left out, §7.5); 1…9999
/// (§7.6: below 1 is E5010).
fn count_of(v: f64) -> Result<u32, Fault> {
    if is_vacant(v) {
        return Ok(1);
    }
    let n = round_half_away(v);
    if !(1.0..=9999.0).contains(&n) {
        return fault(
            AlarmCode::ValueOutOfRange,
            format!("the repeat count {n} is outside 1…9999"),
        );
    }
    Ok(n as u32)
}
