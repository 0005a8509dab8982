//! A controller split in two for two threads (README, "Two threads"):
//! the interpreter half runs the VM (`gbc_run_ahead`, which allocates
//! and may take long on a macro loop) on an ordinary thread; the
//! real-time half (`gbc_tick` and the operator's signals) on the
//! real-time one, which then never waits for the VM. The halves talk
//! through the runtime's lock-free rings (`runtime::split`).
//!
//! The entry points of the motion side take either a whole controller or
//! a real-time half ([`with_motion`]); those of the program side a whole
//! controller or an interpreter half ([`Ctl::program`]).

use core::ffi::c_char;
use runtime::command::PauseKind;
use runtime::{
    AlarmInfo, BadKey, Controller, Counters, Engine, Interpreter, MeasureRefused, MeasuredAxis,
    OffsetLengths, Parts, Realtime, RunState, SelectRefused, SetPoint, VariableRefused, WorkOffset,
    Xz,
};

use crate::handle::{self, Kind, Object};
use crate::host::HostPlc;
use crate::{
    fail, give_text, guard, put, with_ctl, with_object, Ctl, Failure, GbcController, GbcStatus,
    Outcome, Panel, Poisonable,
};

/// What the motion side does, on a whole controller or a real-time half.
pub(crate) trait Motion {
    /// The engine, for the operator's signals and the screen.
    fn engine(&self) -> &Engine<HostPlc>;
    fn engine_mut(&mut self) -> &mut Engine<HostPlc>;
    /// One period.
    fn tick(&mut self) -> SetPoint;
    /// The blocks the VM has run (the interpreter's count: 0 on a
    /// real-time half, which has no VM).
    fn blocks(&self) -> u64;
    /// The alarm the machine stands in, with its place.
    fn alarm(&self) -> Option<AlarmInfo>;
}

impl Motion for Controller<HostPlc> {
    fn engine(&self) -> &Engine<HostPlc> {
        Controller::engine(self)
    }
    fn engine_mut(&mut self) -> &mut Engine<HostPlc> {
        Controller::engine_mut(self)
    }
    fn tick(&mut self) -> SetPoint {
        Controller::tick(self)
    }
    fn blocks(&self) -> u64 {
        Controller::blocks(self)
    }
    fn alarm(&self) -> Option<AlarmInfo> {
        Controller::alarm(self)
    }
}

impl Motion for Realtime<HostPlc> {
    fn engine(&self) -> &Engine<HostPlc> {
        Realtime::engine(self)
    }
    fn engine_mut(&mut self) -> &mut Engine<HostPlc> {
        Realtime::engine_mut(self)
    }
    fn tick(&mut self) -> SetPoint {
        Realtime::tick(self)
    }
    fn blocks(&self) -> u64 {
        0
    }
    fn alarm(&self) -> Option<AlarmInfo> {
        Realtime::alarm(self)
    }
}

/// A real-time half's handle object.
pub(crate) struct RtObj {
    rt: Realtime<HostPlc>,
    panel: Panel,
    reset_pending: bool,
    poisoned: bool,
}

impl Object for RtObj {
    const KIND: Kind = Kind::Realtime;
}

impl Poisonable for RtObj {
    fn poisoned(&mut self) -> &mut bool {
        &mut self.poisoned
    }
}

/// The motion side behind a handle, for one call.
pub(crate) struct MotionSide<'a> {
    /// The motion; while no program is loaded (never on a real-time
    /// half), the controller's machine instead.
    pub motion: Result<&'a mut dyn Motion, &'a nc::Machine>,
    pub panel: &'a mut Panel,
    /// A reset was asked for in an alarm: ticks are accepted again.
    pub reset_pending: &'a mut bool,
}

impl MotionSide<'_> {
    pub fn motion(&mut self) -> Result<&mut dyn Motion, Failure> {
        match &mut self.motion {
            Ok(m) => Ok(&mut **m),
            Err(_) => Err(GbcStatus::NoProgram.into()),
        }
    }
}

/// The text of a motion call on an interpreter half.
const TO_REALTIME: &str =
    "this is the interpreter half of a split controller: the real-time half takes this call";

/// Runs `f` on the motion side of a whole controller or of a real-time
/// half; an interpreter half is [`GbcStatus::WrongKind`].
pub(crate) fn with_motion(
    h: GbcController,
    f: impl FnOnce(MotionSide<'_>) -> Outcome,
) -> GbcStatus {
    if handle::kind_of(h) == Ok(Kind::Realtime) {
        return with_object(h, |r: &mut RtObj| {
            f(MotionSide {
                motion: Ok(&mut r.rt),
                panel: &mut r.panel,
                reset_pending: &mut r.reset_pending,
            })
        });
    }
    with_ctl(h, |c| {
        if c.interp.is_some() {
            return Err(fail(GbcStatus::WrongKind, TO_REALTIME));
        }
        f(MotionSide {
            motion: match c.run.as_mut() {
                Some(r) => Ok(r),
                None => Err(&c.machine),
            },
            panel: &mut c.panel,
            reset_pending: &mut c.reset_pending,
        })
    })
}

/// Splits a controller with a program loaded into two halves for two
/// threads: `controller` becomes the interpreter half (call
/// `gbc_run_ahead` on it from an ordinary thread, as often as it likes:
/// it never waits for the other half), and `*realtime` names the
/// real-time half (call `gbc_tick` on it once a period from the
/// real-time thread: it allocates, locks and blocks on nothing, and
/// never waits for the VM). The rule "one call at a time per handle"
/// holds for each half on its own: calls on the two halves may run at
/// the same time. Which half takes which call is in the README ("Two
/// threads"); a call on the other half is [`GbcStatus::WrongKind`].
/// Free both; either may be freed first. Without a program:
/// [`GbcStatus::NoProgram`]; a second split: [`GbcStatus::WrongKind`].
///
/// # Safety
/// `realtime` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_controller_split(
    controller: GbcController,
    realtime: *mut GbcController,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if c.interp.is_some() {
            return Err(fail(
                GbcStatus::WrongKind,
                "the controller is split already",
            ));
        }
        if realtime.is_null() {
            return Err(fail(GbcStatus::NullPointer, "the output pointer is null"));
        }
        let run = c.run.take().ok_or(GbcStatus::NoProgram)?;
        let (interp, rt) = run.split();
        let obj = RtObj {
            rt,
            panel: c.panel,
            reset_pending: c.reset_pending,
            poisoned: false,
        };
        c.interp = Some(interp);
        let h = handle::insert(obj)?;
        // SAFETY: checked non-null; the caller's promise.
        unsafe { put(realtime, h) }
    })
}

/// Frees the real-time half of a split controller (the interpreter half
/// is freed with `gbc_controller_free`).
#[no_mangle]
pub extern "C" fn gbc_realtime_free(realtime: GbcController) -> GbcStatus {
    guard(|| Ok(handle::remove::<RtObj>(realtime)?))
}

/// The interpreter half of a split controller, or the whole controller.
pub(crate) enum ProgramSide<'a> {
    Whole(&'a mut Controller<HostPlc>),
    Split(&'a mut Interpreter),
}

impl Ctl {
    /// The program side: the whole controller, or its interpreter half.
    pub(crate) fn program(&mut self) -> Result<ProgramSide<'_>, Failure> {
        if let Some(i) = self.interp.as_mut() {
            return Ok(ProgramSide::Split(i));
        }
        let run = self.run.as_mut().ok_or(GbcStatus::NoProgram)?;
        Ok(ProgramSide::Whole(run))
    }
}

/// One delegation per call of the program side, to whichever half has
/// it (the names and meanings are the runtime's).
macro_rules! both {
    ($self:ident, $p:ident => $e:expr) => {
        match $self {
            ProgramSide::Whole($p) => $e,
            ProgramSide::Split($p) => $e,
        }
    };
}

impl ProgramSide<'_> {
    pub fn run_ahead(&mut self) {
        both!(self, p => p.run_ahead())
    }
    pub fn machine(&self) -> &nc::Machine {
        both!(self, p => p.machine())
    }
    pub fn vm_mut(&mut self) -> &mut vm::Vm {
        both!(self, p => p.vm_mut())
    }
    pub fn message(&self, index: u32) -> Option<&str> {
        both!(self, p => p.message(index))
    }
    pub fn file_name(&self, index: u16) -> Option<&str> {
        both!(self, p => p.file_name(index))
    }
    pub fn tool_offset(&self, n: u32) -> Option<OffsetLengths> {
        both!(self, p => p.tool_offset(n))
    }
    pub fn set_tool_offset(&mut self, n: u32, l: OffsetLengths) -> Result<(), BadKey> {
        both!(self, p => p.set_tool_offset(n, l))
    }
    pub fn work_offset(&self, w: WorkOffset) -> Xz {
        both!(self, p => p.work_offset(w))
    }
    pub fn set_work_offset(&mut self, w: WorkOffset, at: Xz) -> Result<(), BadKey> {
        both!(self, p => p.set_work_offset(w, at))
    }
    pub fn set_parts(&mut self, parts: Parts) -> Result<(), BadKey> {
        both!(self, p => p.set_parts(parts))
    }
    pub fn restore_counters(&mut self, c: Counters) -> Result<(), BadKey> {
        both!(self, p => p.restore_counters(c))
    }
    pub fn renew_tool_life(&mut self, number: u32) -> Result<(), BadKey> {
        both!(self, p => p.renew_tool_life(number))
    }
    pub fn mdi(&mut self, blocks: isa::Module) -> Result<(), SelectRefused> {
        both!(self, p => p.mdi(blocks))
    }
    pub fn select_program(&mut self, module: isa::Module) -> Result<(), SelectRefused> {
        both!(self, p => p.select_program(module))
    }
    pub fn measure_tool_offset(
        &mut self,
        number: u32,
        axis: MeasuredAxis,
        measured: f64,
    ) -> Result<OffsetLengths, MeasureRefused> {
        both!(self, p => p.measure_tool_offset(number, axis, measured))
    }
    pub fn in_mdi(&self) -> bool {
        both!(self, p => p.in_mdi())
    }
    pub fn set_block_skip(&mut self, switch: u8, on: bool) {
        both!(self, p => p.set_block_skip(switch, on))
    }
    pub fn variable(&self, n: u32) -> Result<f64, nc::NcError> {
        both!(self, p => p.variable(n))
    }
    pub fn set_variable(&mut self, n: u32, value: f64) -> Result<(), VariableRefused> {
        both!(self, p => p.set_variable(n, value))
    }
}

/// The message stop the motion stands at, for a split controller's
/// screen: its index in the run (counted from 0), which
/// `gbc_message_at` on the interpreter half turns into its text;
/// `UINT32_MAX` when the motion stands at none. (`GbcStateInfo::message`
/// is the program's number, `#3006 = n`, not this index; on a whole
/// controller `gbc_message` gives the text at once.)
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_message_index(controller: GbcController, out: *mut u32) -> GbcStatus {
    with_motion(controller, |s| {
        let state = s.motion.ok().map(|m| m.engine().state());
        let index = match state {
            Some(RunState::Stopped(PauseKind::Message { index, .. })) => index,
            _ => u32::MAX,
        };
        // SAFETY: the caller's promise.
        unsafe { put(out, index) }
    })
}

/// The text of message stop `index` of the run (`gbc_message_index`)
/// into `buf`, as `gbc_message` gives it; on the interpreter half of a
/// split controller or a whole one. An empty text for an index the run
/// has not reached.
///
/// # Safety
/// `buf` is null or writable for `cap` bytes; `len` null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_message_at(
    controller: GbcController,
    index: u32,
    buf: *mut c_char,
    cap: usize,
    len: *mut usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let p = c.program()?;
        // SAFETY: the caller's promise.
        unsafe { give_text(p.message(index).unwrap_or(""), buf, cap, len) }
    })
}
