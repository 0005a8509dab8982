//! The embedding API for a controller: a verified `.gbc` module, the VM
//! that runs it, and the [`Engine`] that interpolates it.
//!
//! A host calls two things:
//!
//! - [`Controller::tick`] once per interpolation period, from its
//!   real-time context: it returns the axis set points and allocates,
//!   locks and calls the system for nothing;
//! - [`Controller::run_ahead`] from its ordinary context whenever it likes
//!   (between ticks is fine): it runs the VM ahead of the motion and fills
//!   the planner queue up to the look-ahead horizon. It allocates (the VM
//!   does), so it must not run in the period loop.
//!
//! Signals (overrides, feed hold, cycle start, reset, single block, skip)
//! go through the methods of [`Controller`]; M, S and T functions through
//! the host's [`Plc`].
//!
//! The VM runs ahead of the motion: the block-end positions (#5001…) are
//! the kernel's programmed state, known when a block executes. It waits,
//! as a real control does, where a value depends on the motion: after a
//! G31 block until the move has ended (the skip position, #5061, #995),
//! and before a read of the current position (#5021…, #5041…) until all
//! motion queued before it has ended ([`vm::Status::Sync`]). The planner
//! always plans its last queued move to a stop, so the wait cannot
//! deadlock.

use crate::command::{Command, Feed, Move, MoveKind, Path, Tag};
use crate::config::{Config, RapidOverride};
use crate::interpolate::{Engine, RunState, SetPoint};
use crate::math::V2;
use crate::planner::{Full, Pushed};
use crate::plc::{AutoAck, Plc};
use crate::translate::Translator;
use alloc::collections::VecDeque;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use nc::{Event, Machine, Sink};
use vm::{Status, Vm};

/// Why a module cannot be run.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadError {
    /// Not a valid `.gbc` (the verifier's message).
    Invalid(String),
    /// Compiled for a machine whose compile-time keys differ.
    Machine,
}

impl core::fmt::Display for LoadError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LoadError::Invalid(m) => write!(f, "not a valid .gbc module: {m}"),
            LoadError::Machine => f.write_str(
                "compiled for another machine configuration (its compile-time keys differ)",
            ),
        }
    }
}

impl core::error::Error for LoadError {}

/// An alarm with its place, as `gbvm` reports it.
#[derive(Debug, Clone, PartialEq)]
pub struct AlarmInfo {
    pub code: u32,
    pub message: String,
    pub file: String,
    pub line: u32,
    pub col: u32,
}

impl AlarmInfo {
    /// `FILE:LINE:COL: alarm[E7003]: message` (canon.md).
    pub fn header(&self) -> String {
        let code = if (500..1000).contains(&self.code) || (3000..4000).contains(&self.code) {
            format!("{}", self.code)
        } else {
            format!("E{:04}", self.code)
        };
        format!(
            "{}:{}:{}: alarm[{}]: {}",
            self.file, self.line, self.col, code, self.message
        )
    }
}

/// The wording of the runtime's own alarms.
pub fn runtime_alarm_message(code: u32) -> &'static str {
    match code {
        7001 => "a feed move with F = 0 cannot run",
        7002 => "the axes leave their travel (soft limit) or enter the area G22 forbids",
        7003 => "a feed-per-revolution move waited too long for the stopped spindle",
        4010 => {
            "the thread needs a feed above the axis's maximum cutting feed at this spindle speed"
        }
        _ => "run-time alarm",
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

/// A program running on a machine.
pub struct Controller<P: Plc = AutoAck> {
    engine: Engine<P>,
    vm: Vm,
    machine: Machine,
    tr: Translator,
    staged: VecDeque<(Command, Tag)>,
    events: Vec<Event>,
    scratch: Vec<Command>,
    vm_state: VmState,
    vm_alarm: Option<vm::Alarm>,
    blocks: u64,
    block: u32,
    max_blocks: u64,
    repeat: u32,
    /// The G22 area last handed to the engine.
    stroke: Option<nc::stroke::Area>,
}

impl Controller<AutoAck> {
    /// Loads and verifies a `.gbc` for the reference host (every PLC
    /// function completes at once).
    pub fn load(bytes: &[u8], machine: Machine) -> Result<Controller<AutoAck>, LoadError> {
        let module =
            isa::Module::from_bytes(bytes).map_err(|e| LoadError::Invalid(format!("{e}")))?;
        Controller::new(module, machine, AutoAck)
    }
}

impl<P: Plc> Controller<P> {
    /// A controller for a verified module, with the runtime settings of
    /// the machine file.
    pub fn new(module: isa::Module, machine: Machine, plc: P) -> Result<Controller<P>, LoadError> {
        let cfg = Config::from_machine(&machine);
        Controller::with_config(module, machine, cfg, plc)
    }

    /// As [`Controller::new`] with runtime settings of the host's choosing
    /// (jerk limiting, queue size, corner budget …).
    pub fn with_config(
        module: isa::Module,
        machine: Machine,
        cfg: Config,
        plc: P,
    ) -> Result<Controller<P>, LoadError> {
        if module.machine != machine.compile_keys() {
            return Err(LoadError::Machine);
        }
        let mut vm = Vm::new(module, machine.clone());
        vm.sync_positions = true;
        let origin = origin_of(&vm);
        let mut engine = Engine::new(cfg, plc);
        engine.reseed(origin);
        let max_blocks = vm.max_blocks;
        Ok(Controller {
            engine,
            vm,
            machine,
            tr: Translator::new(origin),
            staged: VecDeque::new(),
            events: Vec::new(),
            scratch: Vec::new(),
            vm_state: VmState::Running,
            vm_alarm: None,
            blocks: 0,
            block: 0,
            max_blocks,
            repeat: 1,
            stroke: None,
        })
    }

    /// Block budget (E6005), as `gbvm run --max-blocks`.
    pub fn set_max_blocks(&mut self, n: u64) {
        self.max_blocks = n;
        self.vm.max_blocks = n;
    }

    /// Passes a main-program M99 makes, as `gbvm run --repeat`.
    pub fn set_repeat(&mut self, n: u32) {
        self.repeat = n.max(1);
        self.vm.repeat = self.repeat;
    }

    pub fn engine(&self) -> &Engine<P> {
        &self.engine
    }

    /// The engine, for its signals and settings.
    pub fn engine_mut(&mut self) -> &mut Engine<P> {
        &mut self.engine
    }

    pub fn vm(&self) -> &Vm {
        &self.vm
    }

    pub fn vm_mut(&mut self) -> &mut Vm {
        &mut self.vm
    }

    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// NC blocks the VM has executed.
    pub fn blocks(&self) -> u64 {
        self.blocks
    }

    pub fn state(&self) -> RunState {
        self.engine.state()
    }

    /// The text of a `MESSAGE` stop.
    pub fn message(&self, n: u32) -> Option<&str> {
        self.tr.messages.get(n as usize).map(String::as_str)
    }

    pub fn set_feed_override(&mut self, pct: f64) {
        self.engine.set_feed_override(pct);
    }

    pub fn set_rapid_override(&mut self, r: RapidOverride) {
        self.engine.set_rapid_override(r);
    }

    pub fn feed_hold(&mut self) {
        self.engine.feed_hold();
    }

    pub fn cycle_start(&mut self) {
        self.engine.cycle_start();
    }

    pub fn reset(&mut self) {
        self.engine.reset();
    }

    pub fn set_single_block(&mut self, on: bool) {
        self.engine.set_single_block(on);
    }

    pub fn set_skip_input(&mut self, level: bool) {
        self.engine.set_skip_input(level);
    }

    /// One interpolation period (real-time safe).
    pub fn tick(&mut self) -> SetPoint {
        self.engine.tick()
    }

    /// The alarm that stopped the run, with its place.
    pub fn alarm(&self) -> Option<AlarmInfo> {
        let RunState::Alarm(code) = self.engine.state() else {
            return None;
        };
        if let Some(a) = &self.vm_alarm {
            if a.code == code {
                return Some(AlarmInfo {
                    code,
                    message: a.message.clone(),
                    file: a.file.clone(),
                    line: a.line,
                    col: a.col,
                });
            }
        }
        let tag = self.engine.alarm().map(|(_, t)| t).unwrap_or_default();
        let file = self
            .vm
            .module()
            .files
            .get(tag.file as usize)
            .map_or_else(String::new, |f| f.name.clone());
        Some(AlarmInfo {
            code,
            message: runtime_alarm_message(code).into(),
            file,
            line: tag.line,
            col: tag.col,
        })
    }

    /// Runs the VM ahead of the motion (not real-time: it allocates).
    pub fn run_ahead(&mut self) {
        struct Nothing;
        impl Sink for Nothing {
            fn emit(&mut self, _: Event) {}
        }
        self.run_ahead_tap(&mut Nothing);
    }

    /// As [`Controller::run_ahead`], handing every canon event the VM
    /// produces to `tap` too (in program order, ahead of the motion).
    pub fn run_ahead_tap(&mut self, tap: &mut dyn Sink) {
        self.fill(tap);
        self.engine.replan();
    }

    fn fill(&mut self, tap: &mut dyn Sink) {
        if self.engine.take_reset_done() {
            self.restart();
        }
        if let Some(r) = self.engine.take_skip_report() {
            self.after_skip(r);
        }
        if self.vm_state == VmState::Sync
            && self.staged.is_empty()
            && self.engine.planner().is_empty()
        {
            self.vm_state = VmState::Running;
        }
        let cfg_blocks = self.engine.config().lookahead_blocks;
        let cfg_secs = self.engine.config().lookahead_s;
        loop {
            while let Some(&(c, t)) = self.staged.front() {
                match self.engine.push(c, t) {
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
            let (moves, secs) = self.engine.planner().horizon();
            if moves >= cfg_blocks && secs >= cfg_secs {
                return;
            }
            self.step_vm(tap);
        }
    }

    /// Executes one block of the VM and stages its commands.
    fn step_vm(&mut self, tap: &mut dyn Sink) {
        self.events.clear();
        let status = self.vm.step(1 << 16, &mut self.events);
        let loc = self.vm.last_loc();
        let tag = Tag {
            file: loc.file,
            line: loc.line,
            col: loc.col,
            block: self.block,
            block_end: false,
        };
        self.tr.skip_queued = false;
        for e in self.events.drain(..) {
            self.scratch.clear();
            self.tr
                .event(&e, &self.vm.nc.st, &self.machine, &mut self.scratch);
            for c in self.scratch.drain(..) {
                self.staged.push_back((c, tag));
            }
            tap.emit(e);
        }
        match status {
            Status::Event => {
                self.blocks += 1;
                self.resync(tag);
                if self.vm.nc.st.exact_stop {
                    self.staged.push_back((Command::ExactStop, tag));
                }
                if self.vm.nc.st.stroke2 != self.stroke {
                    self.stroke = self.vm.nc.st.stroke2;
                    self.staged.push_back((Command::Stroke(self.stroke), tag));
                }
                if let Some((_, t)) = self.staged.back_mut() {
                    if t.block == self.block {
                        t.block_end = true;
                    }
                }
                self.block = self.block.wrapping_add(1);
                if self.tr.skip_queued {
                    self.vm_state = VmState::Skip;
                }
            }
            Status::OutOfBudget => {}
            Status::Sync => self.vm_state = VmState::Sync,
            Status::Done => {
                if !matches!(self.staged.back(), Some((Command::End, _))) {
                    self.staged.push_back((Command::End, tag));
                }
                self.vm_state = VmState::Done;
            }
            Status::Alarm(a) => {
                if !matches!(self.staged.back(), Some((Command::Alarm(_), _))) {
                    self.staged.push_back((Command::Alarm(a.code), tag));
                }
                self.vm_alarm = Some(a);
                self.vm_state = VmState::Alarm;
            }
        }
    }

    /// A block moved the programmed point by an event this build does not
    /// know: reach the kernel's point by a line at the modal feed.
    fn resync(&mut self, tag: Tag) {
        let p = self.vm.nc.st.pos;
        let kernel = V2::new(p.r, p.z);
        if (kernel - self.tr.work).max_abs() > 1e-6 {
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
    fn after_skip(&mut self, r: crate::interpolate::SkipReport) {
        self.skip_done();
        let Some(hit) = r.hit else { return };
        let stop_work = r.stop - r.shift;
        let hit_work = hit - r.shift;
        self.tr.work = stop_work;
        let st = &mut self.vm.nc.st;
        st.pos = nc::state::Pt::new(stop_work.r, stop_work.z);
        st.skip = Some(nc::state::Pt::new(hit_work.r, hit_work.z));
        let vars = self.vm.persistent_mut();
        vars[495] = hit_work.x();
        vars[496] = hit_work.z;
    }

    /// The G31 move the VM waits for has ended.
    fn skip_done(&mut self) {
        if self.vm_state == VmState::Skip {
            self.vm_state = VmState::Running;
        }
    }

    /// After a reset: a fresh VM at the start of the program, its
    /// programmed point where the axes now stand (power-on work system,
    /// no tool offset).
    fn restart(&mut self) {
        let module = self.vm.module().clone();
        self.vm = Vm::new(module, self.machine.clone());
        self.vm.sync_positions = true;
        self.vm.max_blocks = self.max_blocks;
        self.vm.repeat = self.repeat;
        let origin = origin_of(&self.vm);
        let work = self.engine.position() - origin;
        self.vm.nc.st.pos = nc::state::Pt::new(work.r, work.z);
        let messages = core::mem::take(&mut self.tr.messages);
        self.tr = Translator::new(origin);
        self.tr.messages = messages;
        self.tr.work = work;
        self.tr.feed = Feed {
            f: 0.0,
            per_rev: false,
        };
        self.engine.reseed(origin);
        self.staged.clear();
        self.vm_state = VmState::Running;
        self.vm_alarm = None;
        self.stroke = None;
        self.block = 0;
    }
}

fn is_skip(c: &Command) -> bool {
    matches!(c, Command::Move(m) if matches!(m.kind, MoveKind::Skip(_)))
}

/// The power-on work zero of a VM.
fn origin_of(vm: &Vm) -> V2 {
    let o = vm.nc.st.origin();
    V2::new(o.r, o.z)
}
