//! The plain C data of the interface: status codes, handles, set points,
//! states, alarms and PLC functions.

use core::ffi::c_void;

use runtime::command::PauseKind;
use runtime::plc::SpindleDir;
use runtime::{Motion, PlcFunction, RunState, SetPoint};

/// The version of the interface this header describes; `gbc_abi_version`
/// gives the library's. It changes with every change a host built
/// against an older header would get wrong (a function's parameters, a
/// struct's fields, a status's meaning), so a host checks at start-up
/// that `gbc_abi_version() == GBC_ABI_VERSION` and refuses to run
/// otherwise. On Linux it is also the N of the shared library's SONAME,
/// `libgbc.so.N` (build.rs reads it here: keep it a literal).
pub const GBC_ABI_VERSION: u32 = 4;

/// Handles alive at once in a process, machines and controllers
/// together; making one more is [`GbcStatus::Limit`] until one is freed.
pub const GBC_HANDLE_CAPACITY: usize = 256;

/// What every entry point but `gbc_abi_version` returns. On any status
/// but `GBC_STATUS_OK`, `gbc_last_error` gives a text about that failure.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GbcStatus {
    /// Done.
    Ok = 0,
    /// A required pointer argument (an output, a buffer) is null.
    NullPointer = 1,
    /// The handle is null (0), freed, or was never made by this library.
    InvalidHandle = 2,
    /// The handle is live but names another kind of object (a machine
    /// where a controller is expected, or the reverse), or the half of a
    /// split controller that does not take the call.
    WrongKind = 3,
    /// An argument is out of its range (a NaN override, a NaN or
    /// infinite encoder reading, machine file text that is not UTF-8, a
    /// tool offset number outside the table …).
    InvalidArgument = 4,
    /// The bytes are not a valid `.gbc` module (`gbc_last_error` says why).
    InvalidModule = 5,
    /// The module was compiled for a machine whose compile-time keys differ.
    MachineMismatch = 6,
    /// The machine file text is not valid (`gbc_last_error` says why).
    InvalidMachine = 7,
    /// A program is already loaded in this controller; make a new one.
    AlreadyLoaded = 8,
    /// No program is loaded yet.
    NoProgram = 9,
    /// The controller stands in an alarm: read it with `gbc_alarm`, clear
    /// it with `gbc_reset` (ticks are then accepted again).
    Alarm = 10,
    /// A host callback reported a failure (`vars_load` returned non-zero,
    /// or `vars_store` did for `gbc_set_variable`).
    HostFailure = 11,
    /// The library caught an internal panic; the controller is unusable
    /// from now on (free it).
    Panic = 12,
    /// All [`GBC_HANDLE_CAPACITY`] handle slots are in use.
    Limit = 13,
    /// A manual move, a program restart, another program selected or MDI
    /// while a program runs, stands stopped, ended or in an alarm (a
    /// restart, a select or MDI also while a manual move or a reset
    /// runs): `gbc_reset` first.
    NotIdle = 14,
    /// The motion queue is full: a manual step given faster than the axes
    /// follow.
    QueueFull = 15,
    /// A program restart found no block to begin at: the main file has
    /// none on that line or with that N, the line is a cycle's profile,
    /// or the run ends before reaching the block that many times. The
    /// program stays at its start.
    RestartNotFound = 16,
    /// A program restart reached its block, but what is in force there
    /// cannot be resumed (a thread chain open before the block, polar or
    /// cylindrical interpolation): restart at an earlier block. The
    /// program stays at its start.
    RestartHeld = 17,
    /// The program raised an alarm before reaching the restart block
    /// (`gbc_last_error` gives it). The controller does not stand in that
    /// alarm, unlike [`GbcStatus::Alarm`]: the program stays at its start.
    RestartAlarm = 18,
    /// The G-code text given to `gbc_mdi`, `gbc_controller_load_source` or
    /// `gbc_controller_select_source` does not compile (`gbc_last_error`
    /// gives the compiler's diagnostic of its first error). Nothing
    /// changed.
    CompileError = 19,
    /// `gbc_restart_result` on a split controller: the restart asked for
    /// waits for `gbc_reset` on the real-time half and the
    /// `gbc_run_ahead` after it, which runs its search.
    RestartPending = 20,
}

impl GbcStatus {
    /// The last-error text of a failure that has none more precise.
    pub(crate) fn text(self) -> &'static str {
        match self {
            GbcStatus::Ok => "no error",
            GbcStatus::NullPointer => "a required pointer argument is null",
            GbcStatus::InvalidHandle => "the handle is 0, freed, or was not made by this library",
            GbcStatus::WrongKind => {
                "the handle names another kind of object than this call takes \
                 (a machine, a controller, or a split controller's real-time half)"
            }
            GbcStatus::InvalidArgument => "an argument is out of its range",
            GbcStatus::InvalidModule => "not a valid .gbc module",
            GbcStatus::MachineMismatch => "the module was compiled for another machine",
            GbcStatus::InvalidMachine => "the machine file is not valid",
            GbcStatus::AlreadyLoaded => "a program is already loaded in this controller",
            GbcStatus::NoProgram => "no program is loaded in this controller",
            GbcStatus::Alarm => "the controller stands in an alarm; reset it first",
            GbcStatus::HostFailure => "a host callback reported a failure",
            GbcStatus::Panic => {
                "internal error (panic) in the gbc library: the controller is unusable, free it"
            }
            GbcStatus::Limit => {
                "all GBC_HANDLE_CAPACITY handle slots are in use \
                 (machines and controllers together): free one first"
            }
            GbcStatus::NotIdle => {
                "manual moves, program restarts and MDI are made while no program runs"
            }
            GbcStatus::QueueFull => "the motion queue is full",
            GbcStatus::RestartNotFound => "the program has no block to restart at there",
            GbcStatus::RestartHeld => "the program cannot be restarted at that block",
            GbcStatus::RestartAlarm => {
                "the program raised an alarm before reaching the restart block"
            }
            GbcStatus::CompileError => "the G-code text does not compile",
            GbcStatus::RestartPending => {
                "the restart waits for gbc_reset on the real-time half and the \
                 gbc_run_ahead after it"
            }
        }
    }
}

/// A machine configuration (from a machine file or the reference machine).
/// 0 is never a valid handle.
pub type GbcMachine = u64;

/// A controller: one program running on one machine. 0 is never a valid
/// handle.
pub type GbcController = u64;

/// Number of persistent variables (#500–#999) in the arrays of
/// [`GbcHost::vars_load`] and [`GbcHost::vars_store`].
pub const GBC_PERSISTENT_COUNT: usize = 500;

/// `gbc_set_jit`: every macro loop interpreted.
pub const GBC_JIT_OFF: u8 = 0;
/// `gbc_set_jit`: a macro loop compiled to machine code once it has gone
/// round 500 times (the default).
pub const GBC_JIT_AUTO: u8 = 1;
/// `gbc_set_jit`: every macro loop compiled at its first round.
pub const GBC_JIT_ALWAYS: u8 = 2;

/// What the machine is doing.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GbcRunState {
    /// No program, or waiting for the first cycle start.
    Idle = 0,
    /// Moving or executing.
    Running = 1,
    /// Feed hold: stopped on the path; cycle start resumes.
    Held = 2,
    /// M00, M01, a message or single block (see [`GbcStopKind`]); cycle
    /// start goes on.
    Stopped = 3,
    /// The host did not run the program ahead in time; the axes stand.
    Starved = 4,
    /// The program ended.
    Ended = 5,
    /// A run-time alarm; `gbc_alarm` tells which, `gbc_reset` clears it.
    Alarm = 6,
    /// A manual move runs (`gbc_jog`, `gbc_jog_step`, `gbc_home`).
    Manual = 7,
}

/// Why a [`GbcRunState::Stopped`] controller stopped.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GbcStopKind {
    /// Not stopped.
    None = 0,
    /// M00.
    M00 = 1,
    /// M01 with optional stop on.
    M01 = 2,
    /// A `#3006` message stop.
    Message = 3,
    /// Single block: the end of a block.
    SingleBlock = 4,
}

/// The kind of motion of a period.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GbcMotion {
    /// Standing (PLC wait, stop, end).
    None = 0,
    /// G00.
    Rapid = 1,
    /// A cutting feed along a straight line.
    Feed = 2,
    /// A spindle-synchronised thread.
    Thread = 3,
    /// A cutting feed along a curve (G02/G03, G6.2/G6.3, G7.2/G7.3).
    Arc = 4,
    /// A G04 dwell counting down.
    Dwell = 5,
}

/// One period's output of `gbc_tick`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcSetPoint {
    /// Time at the end of the period, s.
    pub time_s: f64,
    /// The programmed point in work coordinates, X as a diameter, mm.
    pub x: f64,
    /// The programmed Z in work coordinates, mm.
    pub z: f64,
    /// The X axis set point in machine coordinates (a diameter), tool
    /// offset included: what the drive gets.
    pub axis_x: f64,
    /// The Z axis set point in machine coordinates.
    pub axis_z: f64,
    /// `axis_x` in whole steps of the machine's resolution (a diameter:
    /// one count moves the slide half a step), rounded to the nearest,
    /// halves away from zero, with the machine file's axis compensation
    /// added (`backlash_mm` where the axis has turned back, the correction
    /// of `pitch_comp_mm` where it stands): what a position-command or
    /// pulse interface sends. Each period is rounded on its own, so the
    /// counts never drift.
    pub count_x: i64,
    /// `axis_z` in whole steps of the resolution, as `count_x`.
    pub count_z: i64,
    /// `c` in steps of 0.001° (0 without a C axis), with the machine
    /// file's `backlash_deg` where C has turned back and the correction
    /// of `pitch_comp_deg` at its angle, as `count_x`.
    pub count_c: i64,
    /// The C axis angle, degrees (0 without a C axis; see `has_c`).
    pub c: f64,
    /// Whether the machine has a C axis.
    pub has_c: bool,
    /// Signed spindle speed (+ for M03), rev/min: simulated, or the
    /// measured one while the host feeds the encoder.
    pub spindle_rpm: f64,
    /// Spindle turns since power-on, in the running direction.
    pub spindle_turns: f64,
    /// Path speed over the period, mm/min.
    pub feed: f64,
    /// Source line of the block being executed.
    pub line: u32,
    /// Its source file, an index for `gbc_file_name` (0: the main program).
    pub file: u16,
    /// The active tool number.
    pub tool: u32,
    /// The kind of motion.
    pub motion: GbcMotion,
}

impl From<&SetPoint> for GbcSetPoint {
    fn from(p: &SetPoint) -> GbcSetPoint {
        GbcSetPoint {
            time_s: p.time_s,
            x: p.x,
            z: p.z,
            axis_x: p.axis_x,
            axis_z: p.axis_z,
            count_x: p.counts.x,
            count_z: p.counts.z,
            count_c: p.counts.c,
            c: p.c.unwrap_or(0.0),
            has_c: p.c.is_some(),
            spindle_rpm: p.spindle_rpm,
            spindle_turns: p.spindle_turns,
            feed: p.feed,
            line: p.line,
            file: p.file,
            tool: p.tool,
            motion: match p.motion {
                Motion::None => GbcMotion::None,
                Motion::Rapid => GbcMotion::Rapid,
                Motion::Feed => GbcMotion::Feed,
                Motion::Thread => GbcMotion::Thread,
                Motion::Arc => GbcMotion::Arc,
                Motion::Dwell => GbcMotion::Dwell,
            },
        }
    }
}

/// The controller's status, from `gbc_state`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GbcStateInfo {
    /// What the machine is doing.
    pub state: GbcRunState,
    /// Why it stopped, when `state` is [`GbcRunState::Stopped`].
    pub stop: GbcStopKind,
    /// At a message stop (`stop` is [`GbcStopKind::Message`]): the value
    /// the program wrote to `#3006` (`#3006 = 7 (TEXT)` gives 7), made a
    /// whole number as `#3000` makes its alarm number — rounded half away
    /// from zero, vacant 0 — and held in 32 bits: below 0 gives 0, above
    /// `UINT32_MAX` gives `UINT32_MAX`. Its text is `gbc_message`'s.
    /// 0 at any other time; as `#3006 = 0` gives 0 too, `stop` tells a
    /// message stop from none.
    pub message: u32,
    /// The alarm code when `state` is [`GbcRunState::Alarm`], else 0.
    pub alarm_code: u32,
    /// Blocks the VM has executed, as the block budget counts them (it
    /// runs ahead of the motion).
    pub blocks: u64,
}

impl GbcStateInfo {
    /// The state of a controller with no program.
    pub(crate) const EMPTY: GbcStateInfo = GbcStateInfo {
        state: GbcRunState::Idle,
        stop: GbcStopKind::None,
        message: 0,
        alarm_code: 0,
        blocks: 0,
    };

    pub(crate) fn new(s: RunState, blocks: u64) -> GbcStateInfo {
        let mut info = GbcStateInfo {
            blocks,
            ..GbcStateInfo::EMPTY
        };
        info.state = match s {
            RunState::Idle => GbcRunState::Idle,
            RunState::Running => GbcRunState::Running,
            RunState::Held => GbcRunState::Held,
            RunState::Starved => GbcRunState::Starved,
            RunState::Ended => GbcRunState::Ended,
            RunState::Manual => GbcRunState::Manual,
            RunState::Alarm(code) => {
                info.alarm_code = code;
                GbcRunState::Alarm
            }
            RunState::Stopped(k) => {
                info.stop = match k {
                    PauseKind::M00 => GbcStopKind::M00,
                    PauseKind::M01 => GbcStopKind::M01,
                    PauseKind::Message { number, .. } => {
                        info.message = number;
                        GbcStopKind::Message
                    }
                    PauseKind::SingleBlock => GbcStopKind::SingleBlock,
                };
                GbcRunState::Stopped
            }
        };
        info
    }
}

/// Bytes of the text fields of [`GbcAlarm`], the terminating NUL included.
pub const GBC_TEXT_CAPACITY: usize = 256;

/// An alarm with its place, from `gbc_alarm`. Texts are UTF-8, NUL
/// terminated, cut at a character boundary when longer than the buffer:
/// `message_len`/`file_len` give the full lengths, so a length of
/// [`GBC_TEXT_CAPACITY`] or more tells of a cut.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct GbcAlarm {
    /// The canon's alarm code (e.g. 7003 for E7003, 3005 for `#3000=5`);
    /// 0: no alarm.
    pub code: u32,
    /// Source line of the block that raised it (1-based).
    pub line: u32,
    /// Source column.
    pub column: u32,
    /// The alarm text: for an alarm the program raised (`#3000 = n
    /// (TEXT)`, `G65 H99`) its comment as `gbc_message` gives a message's,
    /// else the library's wording.
    pub message: [u8; GBC_TEXT_CAPACITY],
    /// The source file's name as compiled.
    pub file: [u8; GBC_TEXT_CAPACITY],
    /// The full length of the alarm text in bytes (without the NUL).
    pub message_len: usize,
    /// The full length of the file name in bytes (without the NUL).
    pub file_len: usize,
}

/// Copies `s` into `buf` as a NUL-terminated string, cut at a character
/// boundary; returns the length written (without the NUL).
pub(crate) fn copy_text(s: &str, buf: &mut [u8]) -> usize {
    let Some(room) = buf.len().checked_sub(1) else {
        return 0;
    };
    let mut n = s.len().min(room);
    while !s.is_char_boundary(n) {
        n -= 1;
    }
    buf[..n].copy_from_slice(&s.as_bytes()[..n]);
    buf[n] = 0;
    n
}

/// The kinds of [`GbcPlcFunction`].
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GbcPlcKind {
    /// An M code for the PLC (M08, M09, M10 …): `code`.
    M = 0,
    /// M03.
    SpindleCw = 1,
    /// M04.
    SpindleCcw = 2,
    /// M05.
    SpindleStop = 3,
    /// S: `s` in rev/min (G97) or m/min (G96, `css`); `max_rpm` the `G50 S`
    /// limit of a G50 block, else NaN.
    Speed = 4,
    /// S00…S04 of a gear spindle: `code`.
    Gear = 5,
    /// T: tool `code`, offset `offset`.
    Tool = 6,
}

/// One auxiliary function handed to the host's PLC.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcPlcFunction {
    /// Which function.
    pub kind: GbcPlcKind,
    /// M code, gear number or tool number.
    pub code: u32,
    /// Tool offset number (T only).
    pub offset: u32,
    /// Spindle speed (S only).
    pub s: f64,
    /// Constant surface speed (S only).
    pub css: bool,
    /// The `G50 S` limit (S only), NaN when the block sets none.
    pub max_rpm: f64,
}

impl From<PlcFunction> for GbcPlcFunction {
    fn from(f: PlcFunction) -> GbcPlcFunction {
        let mut g = GbcPlcFunction {
            kind: GbcPlcKind::M,
            code: 0,
            offset: 0,
            s: 0.0,
            css: false,
            max_rpm: f64::NAN,
        };
        match f {
            PlcFunction::M(m) => g.code = m,
            PlcFunction::Spindle(SpindleDir::Cw) => g.kind = GbcPlcKind::SpindleCw,
            PlcFunction::Spindle(SpindleDir::Ccw) => g.kind = GbcPlcKind::SpindleCcw,
            PlcFunction::Spindle(SpindleDir::Stop) => g.kind = GbcPlcKind::SpindleStop,
            PlcFunction::Speed { s, css, max } => {
                g.kind = GbcPlcKind::Speed;
                g.s = s;
                g.css = css;
                g.max_rpm = max.unwrap_or(f64::NAN);
            }
            PlcFunction::Gear(n) => {
                g.kind = GbcPlcKind::Gear;
                g.code = n;
            }
            PlcFunction::Tool { t, d } => {
                g.kind = GbcPlcKind::Tool;
                g.code = t;
                g.offset = d;
            }
        }
        g
    }
}

/// The host's side: PLC functions and persistent variables. Every
/// callback may be null: a null `plc_done` completes every function at
/// once, null `vars_load`/`vars_store` keep #500–#999 in memory only.
/// The callbacks are called from `gbc_tick` (PLC; they must return at
/// once) and `gbc_run_ahead`/`gbc_controller_load` (variables; also
/// `gbc_restart_from`/`gbc_restart_from_seq`, whose search runs the
/// blocks before the restart block), on the thread that makes those
/// calls. The `GbcHost` itself is copied by `gbc_controller_new`; the
/// functions and `user` must stay valid until the controller is freed.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct GbcHost {
    /// Passed back to every callback.
    pub user: *mut c_void,
    /// A function starts (strobe on). `f` points to a copy that lives
    /// only during the call: copy what you keep. Each call gets a fresh
    /// copy, so match a request to its `plc_done` polls by content (one
    /// function is pending at a time), never by address.
    pub plc_request: Option<unsafe extern "C" fn(user: *mut c_void, f: *const GbcPlcFunction)>,
    /// Polled once a period after the request until it returns true: the
    /// function is complete (FIN). `f` (the pending function) lives only
    /// during the call, as for `plc_request`.
    pub plc_done: Option<unsafe extern "C" fn(user: *mut c_void, f: *const GbcPlcFunction) -> bool>,
    /// Fills `vars[0..500]` with #500–#999 when a program is loaded (NaN:
    /// vacant; the array holds NaN on entry). Returns 0, or non-zero to
    /// refuse the load ([`GbcStatus::HostFailure`]).
    pub vars_load: Option<unsafe extern "C" fn(user: *mut c_void, vars: *mut f64) -> i32>,
    /// Called with all of #500–#999 after a block changed one of them.
    /// Returns 0, or non-zero: the program stops with alarm 5007.
    pub vars_store: Option<unsafe extern "C" fn(user: *mut c_void, vars: *const f64) -> i32>,
}

impl GbcHost {
    /// No callbacks: the reference host.
    pub const NONE: GbcHost = GbcHost {
        user: core::ptr::null_mut(),
        plc_request: None,
        plc_done: None,
        vars_load: None,
        vars_store: None,
    };
}
