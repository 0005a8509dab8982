//! A controller in two halves, for a host with two contexts: the
//! [`Interpreter`] runs the VM on an ordinary thread, the [`Realtime`]
//! half plans and interpolates in the period loop. This is how a real
//! control divides its work (the interpreter runs ahead, motion runs on
//! time), and it lets the two run at once on two cores.
//!
//! `Controller::split` makes the pair. They share no lock: commands go
//! to the real-time half through a wait-free ring (`rtrb`), reports
//! (a reset finished, a G31 move ended) come back through another, and
//! the queue's horizon and idleness are published in atomics. Neither
//! half ever waits for the other: the interpreter returns when the ring
//! is full or the look-ahead is queued, the real-time half takes what
//! the ring holds (at most [`DRAIN`] commands a period) and ticks.
//!
//! What the VM waits for, it waits for here too: after a G31 block for the
//! skip report, before a current-position read until every command it
//! has sent has run. A reset on the real-time half drops the commands
//! still in flight (each carries the epoch it was sent in) and restarts
//! the interpreter's program where the axes stopped.
//!
//! The set points of a split run follow the same rules as a
//! [`crate::Controller`]'s, but not always the same bits: how much
//! look-ahead is queued at a given period depends on the two threads'
//! timing. For bit-identical output, use the one-context controller.

use crate::command::{Command, Tag};
use crate::config::RapidOverride;
use crate::controller::measure::{set_measured, standing_point, MeasureRefused, MeasuredAxis};
use crate::controller::{engine_alarm, AlarmInfo, SelectRefused};
use crate::interpolate::{Engine, Manual, ManualRefused, RunState, SetPoint, SkipReport};
use crate::math::V2;
use crate::planner::{Full, Pushed};
use crate::plc::Plc;
use crate::runahead::{is_skip, Link, RunAhead, Standing};
use alloc::sync::Arc;
use alloc::vec::Vec;
use core::sync::atomic::{AtomicU32, Ordering};
use nc::counters::{Counters, Parts};
use nc::machine::Xz;
use nc::machine_check::BadKey;
use nc::offset_page::{OffsetLengths, WorkOffset};
use nc::{Machine, Sink};
use rtrb::{Consumer, Producer, RingBuffer};
use standing::StandingCell;
use vm::restart::{RestartAt, RestartError, Restarted};
use vm::Vm;

mod standing;

/// Commands the real-time half takes from the ring in one period: bounds
/// the planning a period can do.
pub const DRAIN: usize = 256;

/// Commands in flight between the halves.
const RING: usize = 1024;

/// File tables in flight to the real-time half, and back to be freed
/// (it frees none: that would call the allocator).
const FILES: usize = 4;

/// The source files of a module, which the motion's alarms name.
type Files = Vec<isa::SourceFileInfo>;

/// A command on its way to the motion, with the epoch it was sent in.
#[derive(Clone, Copy)]
struct Msg {
    cmd: Command,
    tag: Tag,
    epoch: u8,
}

/// What the real-time half tells the interpreter.
#[derive(Clone, Copy)]
enum Report {
    /// A reset finished with the axes at `at`; commands from now on carry
    /// `epoch`.
    Reset { epoch: u8, at: Standing },
    /// A G31 move sent in `epoch` ended.
    Skip { epoch: u8, report: SkipReport },
    /// The motion reached the end of the program sent in `epoch`.
    Ended { epoch: u8 },
}

/// Published by the real-time half, read by the interpreter.
struct Shared {
    /// Moves in the planner's queue.
    moves: AtomicU32,
    /// Seconds of motion in the queue, as `f32` bits.
    secs: AtomicU32,
    /// [`mark`] of the epoch and the commands taken from the ring when the
    /// queue was last seen empty.
    idle: AtomicU32,
    /// Where the axes stand, for a measured cut.
    standing: StandingCell,
}

/// The epoch in the high byte, a count of commands (mod 2^24) below: the
/// count only has to tell "all sent" from "fewer", and the ring holds far
/// fewer than 2^24.
fn mark(epoch: u8, count: u32) -> u32 {
    (u32::from(epoch) << 24) | (count & 0x00FF_FFFF)
}

pub(crate) fn split<P: Plc>(ra: RunAhead, engine: Engine<P>) -> (Interpreter, Realtime<P>) {
    let (cmd_tx, cmd_rx) = RingBuffer::new(RING);
    let (rep_tx, rep_rx) = RingBuffer::new(16);
    let (moves, secs) = engine.planner().horizon();
    let idle = if engine.planner().is_empty() {
        mark(0, 0)
    } else {
        u32::MAX
    };
    let stand = standing_point(&engine);
    let shared = Arc::new(Shared {
        moves: AtomicU32::new(moves as u32),
        secs: AtomicU32::new((secs as f32).to_bits()),
        idle: AtomicU32::new(idle),
        standing: StandingCell::new(stand),
    });
    let files = ra.vm.module().files.clone();
    let (files_tx, files_rx) = RingBuffer::new(FILES);
    let (old_tx, old_rx) = RingBuffer::new(FILES);
    let origin = ra.origin();
    let cfg = engine.config();
    let link = RingLink {
        tx: cmd_tx,
        rx: rep_rx,
        shared: shared.clone(),
        epoch: 0,
        sent: 0,
        batch: Vec::with_capacity(BATCH),
        seen: (0, 0.0),
        // (Read them at the first call.)
        since: BATCH,
        lookahead: (cfg.lookahead_blocks, cfg.lookahead_s),
        reset: None,
        skip: None,
        ended: false,
        files_tx,
        old_rx,
    };
    let rt = Realtime {
        engine,
        rx: cmd_rx,
        tx: rep_tx,
        shared,
        epoch: 0,
        taken: 0,
        origin,
        reset: None,
        skip: None,
        ended: None,
        files,
        files_rx,
        old_tx,
        published: (moves as u32, (secs as f32).to_bits()),
        idle,
        stand,
    };
    (Interpreter { ra, link }, rt)
}

/// Commands the interpreter collects before it writes them to the ring:
/// each write is seen by the other core, so it writes in batches.
const BATCH: usize = 32;

/// The interpreter's end of the rings.
struct RingLink {
    tx: Producer<Msg>,
    rx: Consumer<Report>,
    shared: Arc<Shared>,
    epoch: u8,
    /// Commands sent in this epoch (the batch included).
    sent: u32,
    /// Commands not yet written to the ring.
    batch: Vec<Msg>,
    /// The horizon last read from `shared`, and the pushes since: the
    /// interpreter asks at every block, reading the other core's values
    /// only every [`BATCH`] pushes.
    seen: (usize, f64),
    since: usize,
    lookahead: (usize, f64),
    reset: Option<Standing>,
    skip: Option<SkipReport>,
    ended: bool,
    /// The file tables of the modules started, to the real-time half,
    /// and those it no longer names, back.
    files_tx: Producer<Files>,
    old_rx: Consumer<Files>,
}

impl RingLink {
    /// Writes what the ring has room for of the batch.
    fn write(&mut self) {
        let n = self.batch.len().min(self.tx.slots());
        if n == 0 {
            return;
        }
        if let Ok(chunk) = self.tx.write_chunk_uninit(n) {
            chunk.fill_from_iter(self.batch.drain(..n));
        }
    }

    fn poll(&mut self) {
        // (Dropped here, on this side.)
        while self.old_rx.pop().is_ok() {}
        while let Ok(r) = self.rx.pop() {
            match r {
                Report::Reset { epoch, at } => {
                    self.epoch = epoch;
                    self.sent = 0;
                    self.batch.clear();
                    self.reset = Some(at);
                    self.skip = None;
                }
                Report::Skip { epoch, report } if epoch == self.epoch => self.skip = Some(report),
                Report::Skip { .. } => {}
                Report::Ended { epoch } => self.ended |= epoch == self.epoch,
            }
        }
    }
}

impl Link for RingLink {
    fn push(&mut self, cmd: Command, tag: Tag) -> Result<Pushed, Full> {
        if self.batch.len() == BATCH {
            self.write();
            if self.batch.len() == BATCH {
                return Err(Full);
            }
        }
        let epoch = self.epoch;
        self.batch.push(Msg { cmd, tag, epoch });
        self.sent = self.sent.wrapping_add(1);
        self.since += 1;
        Ok(Pushed::Queued)
    }

    fn horizon(&mut self) -> (usize, f64) {
        if self.since >= BATCH {
            let in_ring = RING - self.tx.slots() + self.batch.len();
            let moves = self.shared.moves.load(Ordering::Acquire) as usize;
            let secs = f32::from_bits(self.shared.secs.load(Ordering::Acquire));
            self.seen = (moves + in_ring, f64::from(secs));
            self.since = 0;
        }
        (self.seen.0 + self.since, self.seen.1)
    }

    fn flush(&mut self) {
        self.write();
        // The next call reads the other core's values afresh.
        self.since = BATCH;
    }

    fn lookahead(&self) -> (usize, f64) {
        self.lookahead
    }

    fn idle(&self) -> bool {
        self.shared.idle.load(Ordering::Acquire) == mark(self.epoch, self.sent)
    }

    fn take_reset(&mut self) -> Option<Standing> {
        self.poll();
        self.reset.take()
    }

    fn take_skip(&mut self) -> Option<SkipReport> {
        self.poll();
        self.skip.take()
    }

    fn take_ended(&mut self) -> bool {
        self.poll();
        core::mem::take(&mut self.ended)
    }

    /// The real-time half re-seeded its engine when the reset finished.
    fn reseed(&mut self, _: V2) {}

    /// Sent before the run's first command, which the real-time half
    /// takes after it. Four tables in flight are far more than resets
    /// come; were the ring full, the alarms would name the older files.
    fn files(&mut self, files: &[isa::SourceFileInfo]) {
        // (Room for it: the tables handed back are freed first; the
        // reports wait for the run-ahead's own poll.)
        while self.old_rx.pop().is_ok() {}
        let _ = self.files_tx.push(files.to_vec());
    }
}

/// The half of a split controller that runs the VM: call
/// [`Interpreter::run_ahead`] from an ordinary thread, as often as it
/// likes. It allocates (the VM does) and never blocks.
pub struct Interpreter {
    ra: RunAhead,
    link: RingLink,
}

impl Interpreter {
    /// Runs the VM until the look-ahead is queued, the ring is full, or
    /// the program must wait for the motion.
    pub fn run_ahead(&mut self) {
        self.run_ahead_tap(&mut nc::Discard);
    }

    /// As [`Interpreter::run_ahead`], handing every canon event to `tap`.
    pub fn run_ahead_tap(&mut self, tap: &mut dyn Sink) {
        self.ra.fill(&mut self.link, tap);
    }

    /// The program has ended (or stopped on an alarm) and everything it
    /// made is on its way to the motion. A reset starts it again.
    pub fn finished(&self) -> bool {
        self.ra.finished()
    }

    /// The VM's alarm, if `code` (from [`Realtime::state`]) is the VM's.
    pub fn alarm(&self, code: u32) -> Option<AlarmInfo> {
        self.ra.vm_alarm(code)
    }

    /// The text of a `MESSAGE` stop ([`RunState::Stopped`]): `index` is
    /// its [`PauseKind::Message`](crate::command::PauseKind::Message)'s.
    pub fn message(&self, index: u32) -> Option<&str> {
        self.ra.message(index)
    }

    /// Blocks the VM has executed, as the block budget counts them
    /// ([`crate::Controller::blocks`]).
    pub fn blocks(&self) -> u64 {
        self.ra.blocks
    }

    /// The VM running the program.
    pub fn vm(&self) -> &Vm {
        &self.ra.vm
    }

    /// The VM, for its settings (the loop tier, its storage).
    pub fn vm_mut(&mut self) -> &mut Vm {
        &mut self.ra.vm
    }

    /// The VM's alarm, if it stopped on one: it runs ahead of the motion,
    /// so the machine stands in it once [`Realtime::state`] says
    /// `Alarm` with its code.
    pub fn vm_alarm(&self) -> Option<AlarmInfo> {
        self.ra.vm_alarm(self.ra.vm_alarm_code()?)
    }

    /// The name of source file `index` ([`crate::Controller::file_name`]).
    pub fn file_name(&self, index: u16) -> Option<&str> {
        let files = &self.ra.vm.module().files;
        files.get(usize::from(index)).map(|f| f.name.as_str())
    }

    /// MDI blocks run, or wait for the reset that starts them, in the
    /// program's place ([`crate::Controller::in_mdi`]).
    pub fn in_mdi(&self) -> bool {
        self.ra.after_mdi.is_some() || self.ra.mdi_pending()
    }

    /// The lengths of tool offset `number` ([`crate::Controller::tool_offset`]).
    pub fn tool_offset(&self, number: u32) -> Option<OffsetLengths> {
        self.ra.machine.offset_lengths(number)
    }

    /// A work offset ([`crate::Controller::work_offset`]).
    pub fn work_offset(&self, w: WorkOffset) -> Xz {
        self.ra.machine.work_offset_of(w)
    }

    /// The machine the program runs on.
    pub fn machine(&self) -> &Machine {
        &self.ra.machine
    }

    /// Program restart on a split controller ([`crate::Controller::restart_from`]):
    /// the next reset of the [`Realtime`] half (press it after this call;
    /// it is one in every state, so a running program stops) starts the
    /// program at `at` instead of its start. The search runs in
    /// [`Interpreter::run_ahead`] when the reset has reached this half;
    /// [`Interpreter::take_restart_result`] tells how it went. A refused
    /// restart leaves the program at its start, as a plain reset does.
    pub fn restart_from(&mut self, at: RestartAt) {
        self.ra.restart_at_reset(at);
    }

    /// How the restart asked for went, once it has run: `None` until the
    /// reset has reached this half.
    pub fn take_restart_result(&mut self) -> Option<Result<Restarted, RestartError>> {
        self.ra.take_restart_result()
    }

    /// The offset page ([`crate::Controller::set_tool_offset`]): the
    /// lengths of tool offset `number` from the next reset on.
    pub fn set_tool_offset(&mut self, number: u32, l: OffsetLengths) -> Result<(), BadKey> {
        self.ra.machine.set_offset_lengths(number, l)
    }

    /// A work offset from the next reset on.
    pub fn set_work_offset(&mut self, w: WorkOffset, at: Xz) -> Result<(), BadKey> {
        self.ra.machine.set_work_offset(w, at)
    }

    /// The production counters ([`crate::Controller::counters`]): this
    /// half runs the program, so it keeps them. A run's end counts at the
    /// `run_ahead` after the motion reached it.
    pub fn counters(&self) -> &Counters {
        &self.ra.counters
    }

    /// Sets the part counters ([`crate::Controller::set_parts`]) for the
    /// runs from the next reset on; the running one adds what it counts.
    pub fn set_parts(&mut self, parts: Parts) -> Result<(), BadKey> {
        self.ra.set_parts(parts)
    }

    /// MDI blocks ([`crate::Controller::mdi`]) for the next reset of the
    /// [`Realtime`] half to begin with (press it after this call); they
    /// run at the cycle start after it, and when they end the program is
    /// back at its start. Refused for blocks compiled for another machine.
    pub fn mdi(&mut self, blocks: isa::Module) -> Result<(), SelectRefused> {
        crate::controller::between::compiled_for(&self.ra.machine, &blocks)?;
        self.ra.mdi_at_reset(blocks);
        Ok(())
    }

    /// Another program ([`crate::Controller::select_program`]) for the
    /// next reset of the [`Realtime`] half to begin with (press it after
    /// this call; it is one in every state, so a running program stops):
    /// from then on it is the program, started where the axes stand,
    /// with the power-on modes, at the cycle start after the reset. MDI
    /// blocks given for that reset run first; a program restart asked
    /// before this call is dropped (ask it again for the new program).
    /// Refused for a program compiled for another machine.
    pub fn select_program(&mut self, module: isa::Module) -> Result<(), SelectRefused> {
        crate::controller::between::compiled_for(&self.ra.machine, &module)?;
        self.ra.select_at_reset(module);
        Ok(())
    }

    /// A program selected waits for the next reset.
    pub fn select_pending(&self) -> bool {
        self.ra.select_pending()
    }

    /// Tool setting by a measured cut
    /// ([`crate::Controller::measure_tool_offset`]), with the slide where
    /// the [`Realtime`] half last published it standing (idle or at the
    /// program's end, outside polar and cylindrical interpolation: else
    /// [`MeasureRefused::NotStanding`]). As every edit of the page here,
    /// it holds from the next reset.
    pub fn measure_tool_offset(
        &mut self,
        number: u32,
        axis: MeasuredAxis,
        measured: f64,
    ) -> Result<OffsetLengths, MeasureRefused> {
        let slide = self.link.shared.standing.load();
        let slide = slide.ok_or(MeasureRefused::NotStanding)?;
        set_measured(&mut self.ra.machine, number, axis, measured, slide)
    }

    /// Restores counters the host kept
    /// ([`crate::Controller::restore_counters`]) from the next reset on.
    pub fn restore_counters(&mut self, c: Counters) -> Result<(), BadKey> {
        self.ra.restore_counters(c)
    }

    /// Renews tool-life group `number`
    /// ([`crate::Controller::renew_tool_life`]) from the next reset on.
    pub fn renew_tool_life(&mut self, number: u32) -> Result<(), BadKey> {
        self.ra.renew_tool_life(number)
    }

    /// Block-skip switch `switch` (1–9), for the blocks this half reads
    /// from now on ([`crate::Controller::set_block_skip`]): the switch
    /// belongs to the interpreter, which reads the blocks.
    pub fn set_block_skip(&mut self, switch: u8, on: bool) {
        self.ra.set_block_skip(switch, on);
    }

    /// The value of variable `n` as the program would read it now (vacant
    /// as NaN), for the operator's macro-variable page. The VM reads
    /// ahead of the motion: it is the value after the blocks read so far.
    /// A number the dialect does not have: the error the program would
    /// get.
    pub fn variable(&self, n: u32) -> Result<f64, nc::NcError> {
        self.ra.vm.variable(n)
    }

    /// Sets #500–#999 variable `n` (NaN: vacant) as the macro-variable
    /// page does: kept over resets, handed to the storage at once, read
    /// by the blocks the VM reads from now on ([`crate::Controller::set_variable`]).
    pub fn set_variable(&mut self, n: u32, value: f64) -> Result<(), vm::VariableRefused> {
        self.ra.vm.set_persistent(n, value)
    }
}

/// The half of a split controller that moves the axes: call
/// [`Realtime::tick`] once per period from the real-time context. It
/// allocates, locks and calls the system for nothing.
pub struct Realtime<P: Plc> {
    engine: Engine<P>,
    rx: Consumer<Msg>,
    tx: Producer<Report>,
    shared: Arc<Shared>,
    epoch: u8,
    /// Commands taken from the ring in this epoch.
    taken: u32,
    /// The program's power-on work zero (for the engine after a reset).
    origin: V2,
    /// Reports the ring had no room for yet.
    reset: Option<Standing>,
    skip: Option<SkipReport>,
    /// The epoch whose program the motion finished, to report.
    ended: Option<u8>,
    /// The source files of the module whose commands run, which the
    /// alarms name; the tables of modules started since, and the
    /// replaced ones on their way back.
    files: Files,
    files_rx: Consumer<Files>,
    old_tx: Producer<Files>,
    /// What `shared` holds: (moves, seconds' bits), the idle mark and
    /// the standing point.
    published: (u32, u32),
    idle: u32,
    stand: Option<Xz>,
}

impl<P: Plc> Realtime<P> {
    /// One interpolation period: takes new commands into the plan, moves.
    pub fn tick(&mut self) -> SetPoint {
        self.plan_pending();
        let sp = self.engine.tick();
        self.after_tick();
        sp
    }

    /// Plans up to [`DRAIN`] commands from the ring; returns how many it
    /// took. `tick` calls it; a host that plans without moving (a cycle
    /// time estimate, a bench) may call it alone.
    pub fn plan_pending(&mut self) -> usize {
        self.take_files();
        let mut took = 0;
        while took < DRAIN {
            let Ok(&m) = self.rx.peek() else { break };
            if m.epoch == self.epoch {
                match self.engine.push(m.cmd, m.tag) {
                    Ok(pushed) => {
                        if pushed == Pushed::Empty && is_skip(&m.cmd) {
                            // It never runs, so the engine will not report it.
                            self.skip = Some(SkipReport {
                                hit: None,
                                stop: self.engine.position(),
                                shift: V2::ZERO,
                            });
                        }
                        self.taken = self.taken.wrapping_add(1);
                    }
                    Err(Full) => break,
                }
            }
            // A command from before a reset is dropped.
            let _ = self.rx.pop();
            took += 1;
        }
        if took > 0 {
            self.engine.replan();
        }
        self.publish();
        took
    }

    /// The file tables of modules started since the last period (each
    /// sent before the module's first command), the replaced ones handed
    /// back to be freed.
    fn take_files(&mut self) {
        while self.old_tx.slots() > 0 {
            let Ok(files) = self.files_rx.pop() else {
                return;
            };
            let old = core::mem::replace(&mut self.files, files);
            // (It has room: this half is its only writer.)
            let _ = self.old_tx.push(old);
        }
    }

    fn after_tick(&mut self) {
        if let Some(r) = self.engine.take_skip_report() {
            self.skip = Some(r);
        }
        if self.engine.take_ended() {
            self.ended = Some(self.epoch);
        }
        if self.engine.take_reset_done() {
            self.epoch = self.epoch.wrapping_add(1);
            self.taken = 0;
            self.engine.reseed(self.origin);
            self.reset = Some(Standing {
                at: self.engine.position(),
                c: self.engine.c(),
            });
            self.skip = None;
        }
        self.publish();
        let stand = standing_point(&self.engine);
        if stand != self.stand {
            self.stand = stand;
            self.shared.standing.store(stand);
        }
        self.send_reports();
    }

    /// Publishes the horizon and idleness, writing only what changed: the
    /// interpreter's core sees every write.
    fn publish(&mut self) {
        let (moves, secs) = self.engine.planner().horizon();
        let now = (moves as u32, (secs as f32).to_bits());
        if now != self.published {
            self.published = now;
            self.shared.moves.store(now.0, Ordering::Release);
            self.shared.secs.store(now.1, Ordering::Release);
        }
        let idle = mark(self.epoch, self.taken);
        if self.engine.planner().is_empty() && idle != self.idle {
            self.idle = idle;
            self.shared.idle.store(idle, Ordering::Release);
        }
    }

    /// Sends what is pending: the end of a run first (the interpreter
    /// keeps what it counted before the reset restarts it), then the
    /// reset, which makes older reports moot.
    fn send_reports(&mut self) {
        if let Some(epoch) = self.ended {
            if self.tx.push(Report::Ended { epoch }).is_err() {
                return;
            }
            self.ended = None;
        }
        let epoch = self.epoch;
        if let Some(at) = self.reset {
            if self.tx.push(Report::Reset { epoch, at }).is_err() {
                return;
            }
            self.reset = None;
        }
        if let Some(report) = self.skip {
            if self.tx.push(Report::Skip { epoch, report }).is_ok() {
                self.skip = None;
            }
        }
    }

    /// What the machine is doing.
    pub fn state(&self) -> RunState {
        self.engine.state()
    }

    /// The codes in force for the block the motion runs, for the
    /// operator's screen ([`crate::Engine::active_codes`]). After a
    /// program restart, the power-on codes until the approach runs: the
    /// codes the run resumes with are the interpreter's
    /// ([`Interpreter::take_restart_result`]'s `Restarted::codes`).
    pub fn active_codes(&self) -> nc::ActiveCodes {
        self.engine.active_codes()
    }

    /// How far the move that runs still has to go, X on the diameter
    /// and Z, for the operator's screen ([`crate::Engine::distance_to_go`]).
    pub fn distance_to_go(&self) -> nc::machine::Xz {
        self.engine.distance_to_go()
    }

    /// The engine's alarm with its place; for the VM's own alarms ask
    /// [`Interpreter::alarm`].
    pub fn alarm(&self) -> Option<AlarmInfo> {
        let RunState::Alarm(code) = self.engine.state() else {
            return None;
        };
        Some(engine_alarm(&self.engine, code, &self.files))
    }

    /// Commands waiting in the ring.
    pub fn pending(&self) -> usize {
        self.rx.slots()
    }

    /// The engine.
    pub fn engine(&self) -> &Engine<P> {
        &self.engine
    }

    /// The engine, for its signals and settings.
    pub fn engine_mut(&mut self) -> &mut Engine<P> {
        &mut self.engine
    }

    /// Feed override, percent (0–150).
    pub fn set_feed_override(&mut self, pct: f64) {
        self.engine.set_feed_override(pct);
    }

    /// Rapid override position.
    pub fn set_rapid_override(&mut self, r: RapidOverride) {
        self.engine.set_rapid_override(r);
    }

    /// Feed hold.
    pub fn feed_hold(&mut self) {
        self.engine.feed_hold();
    }

    /// Cycle start.
    pub fn cycle_start(&mut self) {
        self.engine.cycle_start();
    }

    /// Reset.
    pub fn reset(&mut self) {
        self.engine.reset();
    }

    /// A manual move ([`Engine::manual`]).
    pub fn manual(&mut self, m: Manual) -> Result<(), ManualRefused> {
        self.engine.manual(m)
    }

    /// Stops a manual move ([`Engine::manual_stop`]).
    pub fn manual_stop(&mut self) {
        self.engine.manual_stop();
    }

    /// Single block.
    pub fn set_single_block(&mut self, on: bool) {
        self.engine.set_single_block(on);
    }

    /// The level of the skip input (G31).
    pub fn set_skip_input(&mut self, level: bool) {
        self.engine.set_skip_input(level);
    }
}
