//! The program side of a controller: the VM run ahead of the motion, its
//! canon events translated into commands and handed to the motion through
//! a [`Link`].
//!
//! [`crate::Controller`] links it straight to its engine (one context
//! calls both sides); [`crate::split`] links it to an engine on another
//! thread through lock-free queues.

use crate::command::{Command, Ending, Feed, Move, MoveKind, Path, Tag};
use crate::controller::AlarmInfo;
use crate::interpolate::{Engine, SkipReport};
use crate::math::V2;
use crate::planner::{Full, Pushed};
use crate::plc::Plc;
use crate::translate::Translator;
use alloc::collections::VecDeque;
use alloc::string::String;
use alloc::vec::Vec;
use nc::counters::{Counters, Parts};
use nc::exec::switches::Switch;
use nc::machine_check::BadKey;
use nc::{Event, Machine, Placed, Sink};
use vm::restart::{RestartAt, RestartError, Restarted};
use vm::{Status, Vm};

/// Where the axes stand after a reset: X and Z in machine coordinates
/// (the power-on work system, no tool offset) and C, degrees.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Standing {
    pub at: V2,
    pub c: f64,
}

/// What the program side needs of the motion side.
pub(crate) trait Link {
    /// Queues a command for the motion; `Err(Full)` to try again later.
    fn push(&mut self, c: Command, t: Tag) -> Result<Pushed, Full>;
    /// Moves and seconds of motion queued ahead of the axes.
    fn horizon(&mut self) -> (usize, f64);
    /// The look-ahead to keep queued: (moves, seconds).
    fn lookahead(&self) -> (usize, f64);
    /// Every command pushed so far has been executed.
    fn idle(&self) -> bool;
    /// Once, after a reset has finished: where the axes stand.
    fn take_reset(&mut self) -> Option<Standing>;
    /// Once, after a G31 move has ended: how it ended.
    fn take_skip(&mut self) -> Option<SkipReport>;
    /// Once, after the motion reached the program's end (before the
    /// reset that may follow it).
    fn take_ended(&mut self) -> bool;
    /// Sets the display shift and the queue's tail for a restarted run.
    fn reseed(&mut self, origin: V2);
    /// The run about to start is another module's (another program, MDI
    /// blocks or the program after them), whose source files the
    /// motion's alarms are to name from now on. (A controller in one
    /// context reads them from the VM's module when asked.)
    fn files(&mut self, _files: &[isa::SourceFileInfo]) {}
    /// Hands over what `push` may have kept back (the program side is
    /// about to return).
    fn flush(&mut self) {}
}

/// The engine itself, as a controller in one context drives it.
impl<P: Plc> Link for Engine<P> {
    fn push(&mut self, c: Command, t: Tag) -> Result<Pushed, Full> {
        Engine::push(self, c, t)
    }

    fn horizon(&mut self) -> (usize, f64) {
        self.planner().horizon()
    }

    fn lookahead(&self) -> (usize, f64) {
        (self.config().lookahead_blocks, self.config().lookahead_s)
    }

    fn idle(&self) -> bool {
        self.planner().is_empty()
    }

    fn take_reset(&mut self) -> Option<Standing> {
        self.take_reset_done().then(|| Standing {
            at: self.position(),
            c: self.c(),
        })
    }

    fn take_skip(&mut self) -> Option<SkipReport> {
        self.take_skip_report()
    }

    fn take_ended(&mut self) -> bool {
        Engine::take_ended(self)
    }

    fn reseed(&mut self, origin: V2) {
        Engine::reseed(self, origin);
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum VmState {
    Running,
    /// Waiting for a G31 move to end.
    Skip,
    /// Waiting for all motion to end before a current-position read.
    Sync,
    Done,
    Alarm,
}

/// The VM and what turns its events into queued commands.
pub(crate) struct RunAhead {
    pub(crate) vm: Vm,
    pub(crate) machine: Machine,
    pub(crate) tr: Translator,
    staged: VecDeque<(Command, Tag)>,
    /// A step's events, and where an earlier block's begin (its pc:
    /// what waited in the kernel's contour queue).
    events: Placed,
    scratch: Vec<Command>,
    vm_state: VmState,
    vm_alarm: Option<vm::Alarm>,
    /// Blocks executed, as the block budget (E6005) counts them, over
    /// all runs since the load (a reset starts a new VM).
    pub(crate) blocks: u64,
    block: u32,
    max_blocks: u64,
    repeat: u32,
    /// The G22 area last handed to the motion.
    stroke: Option<nc::stroke::Area>,
    /// The kernel's programmed point after the last block (`None`: not
    /// seen yet, or re-seeded).
    kernel_seen: Option<V2>,
    /// The tag of a G32/G34 block the kernel holds back for its run-out:
    /// its thread legs come with the next block and carry this tag.
    wait_tag: Option<Tag>,
    /// A program restart for the next reset to begin with (a split
    /// controller's), and how the last one went.
    pending_restart: Option<RestartAt>,
    restart_result: Option<Result<Restarted, RestartError>>,
    /// The production counters as the finished runs and the operator
    /// left them, and what this run started counting from (counters.rs).
    pub(crate) counters: Counters,
    run_start: Counters,
    /// While MDI blocks are loaded or run: the program they replaced,
    /// which comes back when they end or at a reset.
    pub(crate) after_mdi: Option<isa::Module>,
    /// MDI blocks for the next reset to begin with (a split controller's).
    pending_mdi: Option<isa::Module>,
    /// A program selected for the next reset to begin with (a split
    /// controller's).
    pending_select: Option<isa::Module>,
}

impl RunAhead {
    pub(crate) fn new(module: isa::Module, machine: Machine) -> RunAhead {
        let mut vm = Vm::new(module, machine.clone());
        vm.sync_positions = true;
        let max_blocks = vm.max_blocks;
        let counters = vm.nc.counters();
        RunAhead {
            tr: Translator::new(origin_of(&vm)),
            vm,
            machine,
            staged: VecDeque::new(),
            events: Placed::default(),
            scratch: Vec::new(),
            vm_state: VmState::Running,
            vm_alarm: None,
            blocks: 0,
            block: 0,
            max_blocks,
            repeat: 1,
            stroke: None,
            kernel_seen: None,
            wait_tag: None,
            pending_restart: None,
            restart_result: None,
            run_start: counters.clone(),
            counters,
            after_mdi: None,
            pending_mdi: None,
            pending_select: None,
        }
    }

    /// The next reset begins a program restart at `at` instead of the
    /// program's start.
    pub(crate) fn restart_at_reset(&mut self, at: RestartAt) {
        self.pending_restart = Some(at);
        self.restart_result = None;
    }

    /// How the restart [`RunAhead::restart_at_reset`] asked for went,
    /// once, after the reset.
    pub(crate) fn take_restart_result(&mut self) -> Option<Result<Restarted, RestartError>> {
        self.restart_result.take()
    }

    /// The power-on work zero in machine coordinates.
    pub(crate) fn origin(&self) -> V2 {
        origin_of(&self.vm)
    }

    pub(crate) fn set_max_blocks(&mut self, n: u64) {
        self.max_blocks = n;
        self.vm.max_blocks = n;
    }

    pub(crate) fn set_repeat(&mut self, n: u32) {
        self.repeat = n.max(1);
        self.vm.repeat = self.repeat;
    }

    /// Block-skip switch `switch` (1–9), for the blocks the VM reads from
    /// now on; kept for the VM a reset starts afresh.
    pub(crate) fn set_block_skip(&mut self, switch: u8, on: bool) {
        self.vm.set_block_skip(switch, on);
        let index = usize::from(switch).wrapping_sub(1);
        if let Some(s) = self.machine.operator.block_skip.get_mut(index) {
            *s = on;
        }
    }

    /// The text of a `MESSAGE` stop.
    pub(crate) fn message(&self, n: u32) -> Option<&str> {
        self.tr.messages.get(n as usize).map(String::as_str)
    }

    /// The VM has ended or stopped on an alarm, and all it made is queued.
    pub(crate) fn finished(&self) -> bool {
        matches!(self.vm_state, VmState::Done | VmState::Alarm) && self.staged.is_empty()
    }

    /// The code of the alarm the VM raised, if it did.
    pub(crate) fn vm_alarm_code(&self) -> Option<u32> {
        self.vm_alarm.as_ref().map(|a| a.code)
    }

    /// MDI blocks wait for the next reset.
    pub(crate) fn mdi_pending(&self) -> bool {
        self.pending_mdi.is_some()
    }

    /// The VM's alarm, if `code` is the one it raised.
    pub(crate) fn vm_alarm(&self, code: u32) -> Option<AlarmInfo> {
        let a = self.vm_alarm.as_ref().filter(|a| a.code == code)?;
        Some(AlarmInfo {
            code,
            message: a.message.clone(),
            file: a.file.clone(),
            line: a.line,
            col: a.col,
        })
    }

    /// Runs the VM until the look-ahead is queued or it must wait.
    pub(crate) fn fill<L: Link>(&mut self, link: &mut L, tap: &mut dyn Sink) {
        self.queue(link, tap);
        link.flush();
    }

    fn queue<L: Link>(&mut self, link: &mut L, tap: &mut dyn Sink) {
        if link.take_ended() {
            self.run_ended();
        }
        if let Some(at) = link.take_reset() {
            if let Some(m) = self.pending_mdi.take() {
                self.start_mdi(m, at, link);
            } else {
                match self.pending_restart.take() {
                    Some(r) => self.restart_result = Some(self.restart_from(r, at, link, tap)),
                    None => self.restart(at, link),
                }
            }
        }
        if let Some(r) = link.take_skip() {
            self.after_skip(r);
        }
        if self.vm_state == VmState::Sync && self.staged.is_empty() && link.idle() {
            self.vm_state = VmState::Running;
        }
        let (cfg_blocks, cfg_secs) = link.lookahead();
        loop {
            while let Some(&(c, t)) = self.staged.front() {
                match link.push(c, t) {
                    Ok(pushed) => {
                        self.staged.pop_front();
                        if pushed == Pushed::Empty && is_skip(&c) {
                            // A G31 of zero length never runs, so no skip
                            // report will come: it ended where it began.
                            self.skip_done();
                        }
                    }
                    Err(Full) => return,
                }
            }
            if self.vm_state != VmState::Running {
                return;
            }
            let (moves, secs) = link.horizon();
            if moves >= cfg_blocks && secs >= cfg_secs {
                return;
            }
            self.step_vm(tap);
        }
    }

    /// The operator sets the part counters (counters.rs).
    pub(crate) fn set_parts(&mut self, parts: Parts) -> Result<(), BadKey> {
        parts.check()?;
        self.counters.parts = parts;
        Ok(())
    }

    /// Counters a host kept over a power-off (counters.rs), if they fit.
    pub(crate) fn restore_counters(&mut self, c: Counters) -> Result<(), BadKey> {
        c.check_fits(&self.counters)?;
        self.counters = c;
        Ok(())
    }

    /// The operator renews tool-life group `number` (counters.rs).
    pub(crate) fn renew_tool_life(&mut self, number: u32) -> Result<(), BadKey> {
        self.counters.renew_group(number)
    }

    /// The motion reached the end of the run: the counters keep what it
    /// counted (a run a reset or an alarm abandons counts nothing, so a
    /// restarted part counts once).
    pub(crate) fn run_ended(&mut self) {
        if self.vm_state != VmState::Done {
            return;
        }
        let end = self.vm.nc.counters();
        self.counters.add_run(&self.run_start, &end);
        self.run_start = end;
    }

    /// The blocks the VM has executed, as the block budget counts them;
    /// the block that passed the budget (E6005) did not run.
    fn charged(&self) -> u64 {
        self.vm.blocks_charged().min(self.vm.max_blocks)
    }

    /// Executes one block of the VM and stages its commands.
    fn step_vm(&mut self, tap: &mut dyn Sink) {
        self.events.clear();
        let charged = self.charged();
        let status = self.vm.step(1 << 16, &mut self.events);
        // Counted as the budget counts: a step that ends the run (M30,
        // M02) or stops it may have run a block too.
        self.blocks += self.charged().saturating_sub(charged);
        let tag = self.tag_at(self.vm.last_loc());
        self.tr.skip_queued = false;
        let held = self.held_legs(tag, status == Status::OutOfBudget);
        self.stage_events(tag, held, tap);
        match status {
            Status::Event => self.block_done(tag),
            Status::OutOfBudget => {}
            Status::Sync => self.vm_state = VmState::Sync,
            Status::Done => {
                if !matches!(self.staged.back(), Some((Command::End(_), _))) {
                    let end = Command::End(self.tr.ending(Ending::Stop));
                    self.staged.push_back((end, tag));
                }
                self.vm_state = VmState::Done;
            }
            Status::Alarm(a) => {
                // (The canon's ALARM event may have staged it already.)
                let at = self.alarm_tag(&a, tag);
                match self.staged.back_mut() {
                    Some((Command::Alarm(_), t)) => *t = at,
                    _ => self.staged.push_back((Command::Alarm(a.code), at)),
                }
                self.vm_alarm = Some(a);
                self.vm_state = VmState::Alarm;
            }
        }
    }

    /// The tag of the VM's alarm `a` for the motion: the alarm's own
    /// place (the block the VM stopped in, which may have made no
    /// command), so that the motion's alarm names what the VM's does.
    fn alarm_tag(&self, a: &vm::Alarm, tag: Tag) -> Tag {
        let files = &self.vm.module().files;
        let Some(file) = files.iter().position(|f| f.name == a.file) else {
            return tag;
        };
        Tag {
            file: u16::try_from(file).unwrap_or(tag.file),
            line: a.line,
            col: a.col,
            ..tag
        }
    }

    /// The tag of the commands of the block at `loc`, with the switches
    /// the program has set.
    fn tag_at(&self, loc: isa::SourceLoc) -> Tag {
        Tag {
            file: loc.file,
            line: loc.line,
            col: loc.col,
            block: self.block,
            block_end: false,
            no_hold: self.vm.nc.switch(Switch::NoFeedHold),
            no_fin: self.vm.nc.switch(Switch::NoFinWait),
            active: self.vm.nc.active_codes(),
        }
    }

    /// A block held back for its run-out is printed at the start of this
    /// one: one leg when this block continues its chain, else two (up to
    /// P1 and the run-out). They belong to the held block: how many legs,
    /// and its tag (`tag` when none is held).
    fn held_legs(&mut self, tag: Tag, out_of_budget: bool) -> (usize, Tag) {
        let Some(t) = self.wait_tag else {
            return (0, tag);
        };
        if self.events.events.is_empty() && out_of_budget {
            return (0, tag);
        }
        self.wait_tag = None;
        let legs = if self.vm.nc.thread_chain_open() { 1 } else { 2 };
        let held_tag = Tag {
            block_end: false,
            ..t
        };
        (legs, held_tag)
    }

    /// The step's events, translated into commands for the queue (the
    /// first `held.0` thread legs tagged as the held block's, those of an
    /// earlier block that waited in the kernel as that block's), and told
    /// to `tap`.
    fn stage_events(&mut self, tag: Tag, held: (usize, Tag), tap: &mut dyn Sink) {
        let (held, held_tag) = held;
        let mut legs = 0;
        let mut origins = 0;
        let mut own = tag;
        for (i, e) in self.events.events.drain(..).enumerate() {
            while let Some(&(at, pc)) = self.events.origins.get(origins) {
                if at > i {
                    break;
                }
                own = match pc {
                    nc::RUNNING => tag,
                    pc => {
                        let loc = self.vm.loc_at(pc);
                        Tag {
                            file: loc.file,
                            line: loc.line,
                            col: loc.col,
                            ..tag
                        }
                    }
                };
                origins += 1;
            }
            self.scratch.clear();
            self.tr
                .event(&e, &self.vm.nc, &self.machine, &mut self.scratch);
            let mut t = own;
            if legs < held && matches!(e, Event::Thread { .. }) {
                legs += 1;
                t = held_tag;
                // The held block ends with its last leg.
                t.block_end = legs == held;
            }
            for c in self.scratch.drain(..) {
                self.staged.push_back((c, t));
            }
            tap.emit(e);
        }
    }

    /// A block has run: what its end means for the runtime (an exact stop,
    /// a stroke area, the end of its commands, a skip move to wait for).
    fn block_done(&mut self, tag: Tag) {
        self.resync(tag);
        if self.vm.nc.thread_waiting() {
            self.wait_tag = Some(tag);
        }
        if self.vm.nc.exact_stop() {
            self.staged.push_back((Command::ExactStop, tag));
        }
        if self.vm.nc.stroke_area() != self.stroke {
            self.stroke = self.vm.nc.stroke_area();
            self.staged.push_back((Command::Stroke(self.stroke), tag));
        }
        // Under #3003 bit 0 single block runs on to a block without it.
        let stops = !self.vm.nc.switch(Switch::NoSingleBlock);
        if let Some((_, t)) = self.staged.back_mut() {
            if t.block == self.block && stops {
                t.block_end = true;
            }
        }
        self.block = self.block.wrapping_add(1);
        if self.tr.skip_queued {
            self.vm_state = VmState::Skip;
        }
    }

    /// A block moved the programmed point by an event this build does not
    /// know: reach the kernel's point by a line at the modal feed.
    ///
    /// Not where the kernel's point differs from the tool's on purpose: a
    /// G32/G34 block with run-out words waits for the next block (its
    /// point has moved, its legs come with the next block), and after a
    /// run-out the tool stands at the lifted end while the kernel's point
    /// is the programmed end (§16.5); a move with an L/D corner word or
    /// a compensated one waits in the contour queue, and tool-nose
    /// compensation offsets the tool from the programmed contour
    /// (`Nc::contour_held`: reaching for the kernel's point there cut the
    /// programmed corner instead of the chamfer or the compensated path,
    /// at a rapid where the feed was held back too). So only a block
    /// that moved the kernel's point, with nothing waiting, is
    /// resynchronised.
    fn resync(&mut self, tag: Tag) {
        if self.tr.in_plane() {
            // The kernel's point is the joints', the plane's moves are not.
            return;
        }
        let p = self.vm.nc.position();
        let kernel = V2::new(p.r, p.z);
        let moved = self
            .kernel_seen
            .is_none_or(|k| (kernel - k).max_abs() > 1e-9);
        self.kernel_seen = Some(kernel);
        let held = self.vm.nc.thread_waiting() || self.vm.nc.contour_held();
        if moved && !held && (kernel - self.tr.work).max_abs() > 1e-6 {
            let kind = if self.tr.feed.f > 0.0 {
                MoveKind::Feed(self.tr.feed)
            } else {
                MoveKind::Rapid
            };
            self.tr.work = kernel;
            let shift = self.tr.origin + self.tr.tool_off;
            let m = Move {
                kind,
                path: Path::Line { to: kernel + shift },
                shift,
                c: None,
            };
            self.staged.push_back((Command::Move(m), tag));
        }
    }

    /// A G31 move ended: the next block starts where the axes stopped, and
    /// the kernel learns the skip position (#5061/#5062, #995/#996).
    fn after_skip(&mut self, r: SkipReport) {
        self.skip_done();
        let Some(hit) = r.hit else { return };
        let stop_work = r.stop - r.shift;
        let hit_work = hit - r.shift;
        self.tr.work = stop_work;
        self.kernel_seen = None;
        self.vm.nc.skip_ended(
            nc::point::Pt::new(stop_work.r, stop_work.z),
            nc::point::Pt::new(hit_work.r, hit_work.z),
        );
        // (#995 as the program reads X: radius programming reads radii.)
        let x = self.vm.nc.machine.programmed_x(hit_work.r);
        let vars = self.vm.persistent_mut();
        vars[495] = x;
        vars[496] = hit_work.z;
    }

    /// The G31 move the VM waits for has ended.
    fn skip_done(&mut self) {
        if self.vm_state == VmState::Skip {
            self.vm_state = VmState::Running;
        }
    }

    /// Program restart: a fresh VM where the axes stand (`stand`), run in
    /// search mode up to `at`; the restored state and the approach are
    /// staged, and the run goes on from there. When the search fails the
    /// VM is fresh again, at the program's start, and `tap` has the
    /// `ALARM` of a search that stopped on one.
    pub(crate) fn restart_from<L: Link>(
        &mut self,
        at: RestartAt,
        stand: Standing,
        link: &mut L,
        tap: &mut dyn Sink,
    ) -> Result<Restarted, RestartError> {
        self.restart(stand, link);
        self.events.clear();
        let restarted = match vm::restart::search(&mut self.vm, at, &mut self.events) {
            Ok(r) => r,
            Err(e) => {
                // (What the search passes on is an alarm's event.)
                for event in self.events.events.drain(..) {
                    tap.emit(event);
                }
                self.events.clear();
                self.restart(stand, link);
                return Err(e);
            }
        };
        self.blocks += self.charged();
        let tag = self.tag_at(self.vm.loc_at(self.vm.pc()));
        self.stage_events(tag, (0, tag), tap);
        Ok(restarted)
    }

    /// After a reset: a fresh VM at the start of the program (the one MDI
    /// blocks replaced, if they did), its programmed point and C where
    /// the axes now stand.
    pub(crate) fn restart<L: Link>(&mut self, stand: Standing, link: &mut L) {
        let module = self.program_after_reset();
        self.start(module, stand, link);
    }

    /// The program a reset goes back to: one selected for it, else the
    /// one MDI blocks replaced, else the program loaded.
    fn program_after_reset(&mut self) -> isa::Module {
        if let Some(selected) = self.pending_select.take() {
            self.after_mdi = None;
            return selected;
        }
        match self.after_mdi.take() {
            Some(main) => main,
            None => self.vm.module().clone(),
        }
    }

    /// MDI blocks, compiled, in place of the program until they end (or
    /// a reset), where the axes stand.
    pub(crate) fn start_mdi<L: Link>(&mut self, mdi: isa::Module, stand: Standing, link: &mut L) {
        let main = self.program_after_reset();
        self.start(mdi, stand, link);
        self.tr.mdi = true;
        self.after_mdi = Some(main);
    }

    /// MDI blocks for the next reset to begin with, instead of the program.
    pub(crate) fn mdi_at_reset(&mut self, mdi: isa::Module) {
        self.pending_mdi = Some(mdi);
    }

    /// Another program for the next reset to begin with (MDI blocks
    /// given for that reset run first, then it). A program restart asked
    /// for the program it replaces is dropped.
    pub(crate) fn select_at_reset(&mut self, module: isa::Module) {
        self.pending_select = Some(module);
        self.pending_restart = None;
        self.restart_result = None;
    }

    /// A program waits for the next reset ([`RunAhead::select_at_reset`]).
    pub(crate) fn select_pending(&self) -> bool {
        self.pending_select.is_some()
    }

    /// A fresh VM for `module` at the start of the program, its
    /// programmed point and C where the axes now stand (a reset, or
    /// another program selected).
    pub(crate) fn start<L: Link>(&mut self, module: isa::Module, stand: Standing, link: &mut L) {
        let Standing { at, c } = stand;
        self.after_mdi = None;
        if module.files != self.vm.module().files {
            link.files(&module.files);
        }
        let mut vm = Vm::new(module, self.machine.clone());
        // #500–#999 and where they are kept survive the reset.
        *vm.persistent_mut() = *self.vm.persistent();
        if let Some(storage) = self.vm.take_storage() {
            vm.set_storage(storage);
        }
        // So does the loop tier (bound to the new VM's module, it keeps
        // no code made for another).
        if let Some(tier) = self.vm.take_tier() {
            vm.set_tier(tier);
        }
        vm.nc.set_counters(&self.counters);
        self.run_start = self.counters.clone();
        self.vm = vm;
        self.vm.sync_positions = true;
        self.vm.max_blocks = self.max_blocks;
        self.vm.repeat = self.repeat;
        let origin = origin_of(&self.vm);
        let work = at - origin;
        self.vm.nc.set_position(nc::point::Pt::new(work.r, work.z));
        self.vm.nc.set_c(c);
        self.kernel_seen = None;
        self.wait_tag = None;
        let messages = core::mem::take(&mut self.tr.messages);
        self.tr = Translator::new(origin);
        self.tr.messages = messages;
        self.tr.work = work;
        self.tr.set_c(c);
        self.tr.feed = Feed {
            f: 0.0,
            per_rev: false,
            fixed: false,
        };
        link.reseed(origin);
        self.staged.clear();
        self.vm_state = VmState::Running;
        self.vm_alarm = None;
        self.stroke = None;
        self.block = 0;
    }
}

pub(crate) fn is_skip(c: &Command) -> bool {
    matches!(c, Command::Move(m) if matches!(m.kind, MoveKind::Skip(_)))
}

/// The power-on work zero of a VM.
fn origin_of(vm: &Vm) -> V2 {
    let o = vm.nc.origin();
    V2::new(o.r, o.z)
}
