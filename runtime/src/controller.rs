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
//! A host whose real-time context is a thread (or an interrupt) of its own
//! splits the controller instead ([`Controller::split`]): the
//! [`crate::split::Interpreter`] runs the VM on an ordinary thread, the
//! [`crate::split::Realtime`] half is ticked in the period loop, and they
//! share no lock.
//!
//! Signals (overrides, feed hold, cycle start, reset, single block, block
//! skip, skip) go through the methods of [`Controller`]; M, S and T functions through
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

use crate::certify::Certifier;
use crate::config::{Config, RapidOverride};
use crate::interpolate::{Engine, Manual, ManualRefused, RunState, SetPoint};
use crate::plc::{AutoAck, Plc};
use crate::runahead::RunAhead;
use crate::split::{Interpreter, Realtime};
use alloc::format;
use alloc::string::String;
use nc::{Machine, Sink};
use vm::Vm;

pub(crate) mod between;
pub(crate) mod measure;
pub use between::{RestartRefused, SelectRefused};
pub use measure::{MeasureRefused, MeasuredAxis};
use vm::restart::RestartAt;

/// Why a module cannot be run.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadError {
    /// Not a valid `.gbc` (the verifier's message).
    Invalid(String),
    /// Compiled for a machine whose compile-time keys differ: the first
    /// that does, with both values.
    Machine(String),
}

impl core::fmt::Display for LoadError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LoadError::Invalid(m) => write!(f, "not a valid .gbc module: {m}"),
            LoadError::Machine(key) => write!(
                f,
                "compiled for another machine configuration (its compile-time keys differ: {key})"
            ),
        }
    }
}

impl core::error::Error for LoadError {}

/// An alarm with its place, as `gbvm` reports it.
#[derive(Debug, Clone, PartialEq)]
pub struct AlarmInfo {
    /// The canon's alarm code (7003 for E7003, 3005 for `#3000 = 5`).
    pub code: u32,
    /// The alarm text.
    pub message: String,
    /// The source file of the block that raised it.
    pub file: String,
    /// Its line (1-based).
    pub line: u32,
    /// Its column (1-based).
    pub col: u32,
}

impl AlarmInfo {
    /// `FILE:LINE:COL: alarm[E7003]: message` (canon.md).
    pub fn header(&self) -> String {
        nc::NcError::header(self.code, &self.message, &self.file, self.line, self.col)
    }
}

/// The wording of the runtime's own alarms.
pub fn runtime_alarm_message(code: u32) -> &'static str {
    use nc::error::Alarm;
    let alarm = u16::try_from(code).ok().and_then(Alarm::from_code);
    match alarm {
        Some(Alarm::ZeroFeed) => "a feed move with F = 0 cannot run",
        Some(Alarm::StrokeLimit) => {
            "the axes leave their travel (soft limit) or enter the area G22 forbids"
        }
        Some(Alarm::SpindleStopped) => {
            "a feed-per-revolution move waited too long for the stopped spindle"
        }
        Some(Alarm::BadThread) => {
            "the thread needs a feed above the axis's maximum cutting feed at this spindle speed"
        }
        _ => "run-time alarm",
    }
}

/// A program running on a machine.
///
/// ```
/// use runtime::{Controller, RunState};
///
/// let src = "O0001\nG00 X10 Z-5\nM30\n";
/// let out = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
/// let bytes = out.module.expect("compiles").to_bytes();
/// let mut ctl = Controller::load(&bytes, nc::Machine::reference()).expect("verifies");
/// ctl.cycle_start();
/// let mut last = None;
/// while !matches!(ctl.state(), RunState::Ended | RunState::Alarm(_)) {
///     ctl.run_ahead(); // ordinary context: the VM, ahead of the motion
///     last = Some(ctl.tick()); // real-time context: one period
/// }
/// let sp = last.expect("ticked");
/// assert_eq!((sp.x, sp.z), (10.0, -5.0)); // a stop lands on its end point
/// ```
pub struct Controller<P: Plc = AutoAck> {
    engine: Engine<P>,
    ra: RunAhead,
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
        if let Some(key) = Machine::compile_keys_differ(&module.machine, &machine.compile_keys()) {
            return Err(LoadError::Machine(key));
        }
        let power_on = nc::ActiveCodes::power_on(&machine);
        let ra = RunAhead::new(module, machine);
        let mut engine = Engine::new(cfg, plc);
        engine.reseed(ra.origin());
        engine.set_power_on_codes(power_on);
        Ok(Controller { engine, ra })
    }

    /// The two halves of this controller, for a host that runs the VM on
    /// a thread of its own and ticks the motion from its real-time one
    /// ([`crate::split`]).
    pub fn split(self) -> (Interpreter, Realtime<P>) {
        crate::split::split(self.ra, self.engine)
    }

    /// Block budget (E6005), as `gbvm run --max-blocks`.
    pub fn set_max_blocks(&mut self, n: u64) {
        self.ra.set_max_blocks(n);
    }

    /// Passes a main-program M99 makes, as `gbvm run --repeat`.
    pub fn set_repeat(&mut self, n: u32) {
        self.ra.set_repeat(n);
    }

    /// The engine (planner, interpolator, spindle).
    pub fn engine(&self) -> &Engine<P> {
        &self.engine
    }

    /// The engine, for its signals and settings.
    pub fn engine_mut(&mut self) -> &mut Engine<P> {
        &mut self.engine
    }

    /// The VM running the program.
    pub fn vm(&self) -> &Vm {
        &self.ra.vm
    }

    /// The VM, for its variables and settings (e.g. loading #500–#999).
    pub fn vm_mut(&mut self) -> &mut Vm {
        &mut self.ra.vm
    }

    /// The machine the program runs on.
    pub fn machine(&self) -> &Machine {
        &self.ra.machine
    }

    /// Blocks the VM has executed, as the block budget counts them
    /// ([`Controller::set_max_blocks`]): each block each time it runs,
    /// macro statements, calls, M99 and the final M30 included, a canned
    /// cycle as the moves it makes.
    pub fn blocks(&self) -> u64 {
        self.ra.blocks
    }

    /// What the machine is doing.
    pub fn state(&self) -> RunState {
        self.engine.state()
    }

    /// The codes in force for the block the motion runs, for the
    /// operator's screen ([`Engine::active_codes`]); after a program
    /// restart's search, until a block runs, the codes the run resumes
    /// with ([`Restarted::codes`](crate::Restarted::codes)).
    pub fn active_codes(&self) -> nc::ActiveCodes {
        self.engine.active_codes()
    }

    /// How far the move that runs still has to go, X on the diameter
    /// and Z, for the operator's screen ([`Engine::distance_to_go`]).
    pub fn distance_to_go(&self) -> nc::machine::Xz {
        self.engine.distance_to_go()
    }

    /// The text of a `MESSAGE` stop: `index` is its
    /// [`PauseKind::Message`](crate::command::PauseKind::Message)'s.
    pub fn message(&self, index: u32) -> Option<&str> {
        self.ra.message(index)
    }

    /// The name of source file `index` of the loaded module (the index of
    /// [`SetPoint::file`](crate::SetPoint::file)), as given to the compiler.
    pub fn file_name(&self, index: u16) -> Option<&str> {
        let files = &self.ra.vm.module().files;
        files.get(usize::from(index)).map(|f| f.name.as_str())
    }

    /// Feed override, percent (0–150).
    pub fn set_feed_override(&mut self, pct: f64) {
        self.engine.set_feed_override(pct);
    }

    /// Rapid override position.
    pub fn set_rapid_override(&mut self, r: RapidOverride) {
        self.engine.set_rapid_override(r);
    }

    /// Feed hold: the motion decelerates on its path and stands.
    pub fn feed_hold(&mut self) {
        self.engine.feed_hold();
    }

    /// Cycle start: starts the program, resumes after feed hold or a stop.
    pub fn cycle_start(&mut self) {
        self.engine.cycle_start();
    }

    /// Reset: the motion stops, the spindle stops, an alarm clears and the program goes back to its start.
    pub fn reset(&mut self) {
        self.engine.reset();
    }

    /// A manual move (jog, step, handwheel, reference return) while no
    /// program runs; when it has run, the program starts again from where
    /// the axes stand ([`Engine::manual`]).
    pub fn manual(&mut self, m: Manual) -> Result<(), ManualRefused> {
        self.engine.manual(m)
    }

    /// Stops a manual move: the axes decelerate and stand.
    pub fn manual_stop(&mut self) {
        self.engine.manual_stop();
    }

    /// Single block: stop at the end of every block.
    pub fn set_single_block(&mut self, on: bool) {
        self.engine.set_single_block(on);
    }

    /// Spindle override, percent (0–200).
    pub fn set_spindle_override(&mut self, pct: f64) {
        self.engine.set_spindle_override(pct);
    }

    /// The optional stop switch, live: M01 stops when the motion reaches
    /// it with the switch on. From the first call on the VM hands every
    /// M01 to the motion (a machine file with `optional_stop = false`
    /// makes the VM drop them otherwise), so a host that wants the switch
    /// live from the start calls this before the first
    /// [`Controller::run_ahead`].
    pub fn set_optional_stop(&mut self, on: bool) {
        self.ra.machine.operator.optional_stop = true;
        self.ra.vm.nc.machine.operator.optional_stop = true;
        self.engine.set_optional_stop(on);
    }

    /// Block-skip switch `switch` (1–9; `/` is 1), live, as the panel's
    /// key: a `/n` block is skipped when its switch is on as the VM reads
    /// it. The VM reads ahead of the motion (the look-ahead), so a change
    /// decides for the blocks not yet read; those already read keep their
    /// decision, as on a real control that has them in its buffer. The
    /// machine file's `operator.block_skip` is the state at load; a reset
    /// keeps the switches; a number outside 1–9 changes nothing.
    pub fn set_block_skip(&mut self, switch: u8, on: bool) {
        self.ra.set_block_skip(switch, on);
    }

    /// Whether block-skip switch `switch` (1–9) is on.
    pub fn block_skip(&self, switch: u8) -> bool {
        self.ra.vm.block_skip(switch)
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
    /// by the blocks the VM reads from now on ([`vm::Vm::set_persistent`]).
    pub fn set_variable(&mut self, n: u32, value: f64) -> Result<(), vm::VariableRefused> {
        self.ra.vm.set_persistent(n, value)
    }

    /// Dry run, live ([`Engine::set_dry_run`]).
    pub fn set_dry_run(&mut self, on: bool) {
        self.engine.set_dry_run(on);
    }

    /// Auxiliary function lock: M, S and T functions pass unexecuted
    /// ([`Engine::set_aux_lock`]).
    pub fn set_aux_lock(&mut self, on: bool) {
        self.engine.set_aux_lock(on);
    }

    /// Machine lock: the program runs, the axes stand; read when a run
    /// or a manual move starts ([`Engine::set_machine_lock`]).
    pub fn set_machine_lock(&mut self, on: bool) {
        self.engine.set_machine_lock(on);
    }

    /// The measured spindle for the coming period, from the host's
    /// encoder ([`Engine::set_spindle_feedback`]).
    pub fn set_spindle_feedback(&mut self, position_turns: f64, rpm: f64) {
        self.engine.set_spindle_feedback(position_turns, rpm);
    }

    /// Back to the simulated spindle.
    pub fn set_spindle_simulated(&mut self) {
        self.engine.set_spindle_simulated();
    }

    /// The level of the host input wired to the skip signal (G31).
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
        let files = &self.ra.vm.module().files;
        Some(
            self.ra
                .vm_alarm(code)
                .unwrap_or_else(|| engine_alarm(&self.engine, code, files)),
        )
    }

    /// Runs the VM ahead of the motion (not real-time: it allocates).
    pub fn run_ahead(&mut self) {
        self.run_ahead_tap(&mut nc::Discard);
    }

    /// As [`Controller::run_ahead`], handing every canon event the VM
    /// produces to `tap` too (in program order, ahead of the motion).
    pub fn run_ahead_tap(&mut self, tap: &mut dyn Sink) {
        self.ra.fill(&mut self.engine, tap);
        self.engine.replan();
    }

    /// Runs the program from cycle start with every period checked by a
    /// [`Certifier`] (`gbvm check`), until it ends, an alarm stops it or
    /// `max_ticks` periods pass; a stop that waits for the operator (M00,
    /// M01, single block) is answered with cycle start. Gives the
    /// certifier, finished, and the last set point; [`Controller::state`]
    /// tells how the run ended (only a run that ended owes every end
    /// point).
    pub fn run_certified(&mut self, max_ticks: u64) -> (Certifier, SetPoint) {
        let cert = self.certifier();
        self.certify(cert, max_ticks)
    }

    /// As [`Controller::run_certified`], the program restarted at `at`
    /// ([`Controller::restart_from`]): the certifier follows the restored
    /// state and the approach too.
    pub fn run_certified_from(
        &mut self,
        at: RestartAt,
        max_ticks: u64,
    ) -> Result<(Certifier, SetPoint), RestartRefused> {
        let mut cert = self.certifier();
        self.restart_from_tap(at, &mut cert)?;
        Ok(self.certify(cert, max_ticks))
    }

    /// A certifier that starts where the axes stand.
    fn certifier(&self) -> Certifier {
        let start = self.engine.position();
        Certifier::new(self.engine.config(), start.x(), start.z, self.engine.c())
    }

    fn certify(&mut self, mut cert: Certifier, max_ticks: u64) -> (Certifier, SetPoint) {
        let mut last = SetPoint::default();
        self.cycle_start();
        for _ in 0..max_ticks {
            self.run_ahead_tap(&mut cert);
            last = self.tick();
            cert.period(&last);
            match self.state() {
                RunState::Stopped(_) | RunState::Idle => self.cycle_start(),
                RunState::Ended | RunState::Alarm(_) => break,
                _ => {}
            }
        }
        cert.finish(self.state() == RunState::Ended);
        (cert, last)
    }
}

/// An alarm of the engine's own (not the VM's), placed by the tag of the
/// command that raised it.
pub(crate) fn engine_alarm<P: Plc>(
    engine: &Engine<P>,
    code: u32,
    files: &[isa::SourceFileInfo],
) -> AlarmInfo {
    let tag = engine.alarm().map(|(_, t)| t).unwrap_or_default();
    let file = files
        .get(tag.file as usize)
        .map_or_else(String::new, |f| f.name.clone());
    AlarmInfo {
        code,
        message: runtime_alarm_message(code).into(),
        file,
        line: tag.line,
        col: tag.col,
    }
}
