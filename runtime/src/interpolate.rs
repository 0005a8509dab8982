//! The interpolator: the per-period part of the runtime. [`Engine::tick`]
//! advances the machine by one interpolation period — the spindle, then
//! the item at the head of the planner queue — and returns the axis set
//! points. It allocates nothing, takes no lock and makes no system call:
//! everything it touches was allocated when the engine was built.
//!
//! Speeds follow the planner's envelope with the discrete braking limit of
//! [`crate::profile`]: a feed runs towards F × override (× the actual rpm
//! in G99) with the move's acceleration, never faster than what still lets
//! it meet the corner speed ahead or stop on the last planned point. A
//! stop lands exactly on the end point; the next move starts one period
//! later, so the velocity passes through zero and no axis sees more than
//! its acceleration.

use crate::backlash::Backlash;
use crate::command::{Ending, MoveKind, PauseKind, Tag};
use crate::config::{Config, RapidOverride};
use crate::counts::Counts;
use crate::follow::{Ahead, FollowAxes, Follower};
use crate::machine_lock::MachineLock;
use crate::math::{sqrt, V2};
use crate::pitch::PitchTable;
use crate::planner::{Full, Item, ItemKind, Planner, Pushed, Segment};
use crate::plc::{Plc, PlcFunction};
use crate::profile::{approach, brake_limit, brake_limit_above, stopping_distance};
use crate::smooth::{Cascade, Smoother, Turns};
use crate::spindle::Spindle;
use nc::error::Alarm;
use thread::{Phase, ThreadRun};

mod manual;
mod thread;

pub use manual::{JogRate, Manual, ManualAxis, ManualRefused, JOG_REACH};

/// What the machine is doing, as a controller's status line shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunState {
    /// Waiting for the first cycle start.
    Idle,
    /// A manual move (jog, step, handwheel, reference return) runs
    /// between programs (`Engine::manual`).
    Manual,
    /// Moving or executing.
    Running,
    /// Feed hold: stopped on the path, cycle start resumes.
    Held,
    /// M00, M01, a message or single block: cycle start goes on.
    Stopped(PauseKind),
    /// The queue ran empty before the program ended (the host did not run
    /// the program ahead); the axes stand.
    Starved,
    /// The program ended.
    Ended,
    /// A run-time alarm (the code of canon.md, e.g. 7003); reset clears it.
    Alarm(u32),
}

/// The kind of motion of a period, for plots and statistics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Motion {
    #[default]
    /// Standing.
    None,
    /// G00.
    Rapid,
    /// A cutting feed along a straight line (G01, G31).
    Feed,
    /// A spindle-synchronised thread.
    Thread,
    /// A cutting feed along a curve: G02/G03, G6.2/G6.3, G7.2/G7.3.
    Arc,
    /// A G04 dwell counting down (the axes stand).
    Dwell,
}

impl Motion {
    /// The word of the trace's `motion` column (docs/formats.md).
    pub fn word(self) -> &'static str {
        match self {
            Motion::None => "none",
            Motion::Rapid => "rapid",
            Motion::Feed => "feed",
            Motion::Thread => "thread",
            Motion::Arc => "arc",
            Motion::Dwell => "dwell",
        }
    }

    /// A cutting move: a feed, an arc or a thread.
    pub fn cuts(self) -> bool {
        matches!(self, Motion::Feed | Motion::Arc | Motion::Thread)
    }
}

/// One period's output.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SetPoint {
    /// Time at the end of the period, s.
    pub time_s: f64,
    /// The programmed point in work coordinates, X as a diameter (as the
    /// canon prints positions).
    pub x: f64,
    /// Programmed Z in work coordinates.
    pub z: f64,
    /// The axis set points in machine coordinates (X as a diameter), tool
    /// length offset included: what the drives get.
    pub axis_x: f64,
    /// The Z axis set point in machine coordinates.
    pub axis_z: f64,
    /// The machine set points in whole steps of the resolution (C in
    /// 0.001°), with the axis compensation of a machine file added (the
    /// lost motion of `backlash_mm` where an axis has turned back, the
    /// correction of `pitch_comp_mm` where it stands): what a
    /// position-command or pulse interface sends (the drive's command;
    /// `axis_x`/`axis_z` are where the slide is to be).
    pub counts: Counts,
    /// Signed actual spindle speed (+ for M03), rev/min.
    pub spindle_rpm: f64,
    /// Spindle turns since power-on.
    pub spindle_turns: f64,
    /// The C axis angle, degrees; `None` on a machine without one.
    pub c: Option<f64>,
    /// Path speed over the period, mm/min (with C counted as mm, the
    /// combined speed of planner.rs, while C turns).
    pub feed: f64,
    /// Source line of the block whose motion the period ran (a move that
    /// waited in the kernel for the next block keeps its own block's; a
    /// period that ends exactly on a corner, the block before it).
    pub line: u32,
    /// Its source file: an index into the module's file table
    /// (`isa::Module::files`; 0 is the main program's file).
    pub file: u16,
    /// The kind of motion of the period.
    pub motion: Motion,
    /// The active tool number.
    pub tool: u32,
}

/// W118 at run time: a thread chain whose first move is shorter than the
/// length its long axis needs to reach thread speed (`exit`: whose last
/// move is shorter than the length it needs to stop), at the spindle speed
/// the thread really starts with ([`nc::thread_room`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoomWarning {
    /// The thread move (its block).
    pub tag: Tag,
    /// The stopping length at the end, not the entry length.
    pub exit: bool,
    /// The long-axis travel of the move, mm.
    pub room_mm: f64,
    /// The length needed, mm.
    pub need_mm: f64,
    /// The spindle speed, rev/min.
    pub rpm: f64,
    /// The long axis is Z (else X).
    pub long_z: bool,
}

impl RoomWarning {
    /// The warning's text, worded as gbcc's W118.
    pub fn message(&self) -> alloc::string::String {
        let axis = if self.long_z { "Z" } else { "X" };
        let (what, after) = if self.exit {
            (
                "no room to stop at the thread's end",
                "to stop from thread speed",
            )
        } else {
            (
                "thread too short to reach its lead",
                "to reach thread speed",
            )
        };
        alloc::format!(
            "{what}: at {:.0} rpm {axis} needs {:.3} mm {after}, this block gives {:.3} mm",
            self.rpm,
            self.need_mm,
            self.room_mm
        )
    }
}

/// How a G31 move ended (axis positions, slide units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkipReport {
    /// Where the signal came, if it came.
    pub hit: Option<V2>,
    /// Where the axes stopped.
    pub stop: V2,
    /// Machine axes minus the programmed point during the move.
    pub shift: V2,
}

/// A copy of what the queue's head item asks (the queue is not held
/// borrowed while it runs).
enum Head {
    Move,
    Dwell(f64),
    Plc(PlcFunction),
    Pause(PauseKind),
    Stroke(Option<nc::stroke::Area>),
    Plane(crate::polar::PlaneSwitch),
    End(Ending),
    Alarm(u32),
}

/// Whether a period goes on to the next queued item or is over.
enum Flow {
    /// The item took no time: the next one runs in this period.
    Next,
    /// The period's work is done.
    Done,
}

/// One period of one axis in a rapid: from `p` at speed `v0` towards `t`
/// at the axis's rapid rate × `f` and acceleration, landing exactly on
/// `t`. Returns the new speed and position.
///
/// With jerk limiting, `guard` holds N (the rapid's window, periods) and
/// the sign of the axis's speed change N periods before (smooth.rs
/// `Turns`): the speed does not fall where it rose then, nor rise where it
/// fell. It speeds up only where it can still run N more periods at the
/// new speed before it must brake, so the landing never waits on the
/// guard; a hold or a lower override may (up to N periods at speed).
fn rapid_axis(
    v0: f64,
    p: f64,
    t: f64,
    ax: &crate::config::Axis,
    f: f64,
    dt: f64,
    guard: Option<(usize, i8)>,
) -> (f64, f64) {
    let dist = (t - p).abs();
    let top = ax.rapid * f;
    let lim = brake_limit_above(dist, 0.0, ax.accel, dt, (v0 + ax.accel * dt).min(top));
    let mut v = approach(v0, top.min(lim), ax.accel, dt);
    if let Some((n, before)) = guard {
        if v > v0 {
            v = match before < 0 {
                true => v0,
                false => v.min(cruise_limit(dist, n, ax.accel, dt)).max(v0),
            };
        } else if v < v0 && before > 0 {
            v = v0;
        }
    }
    let step = v * dt;
    let np = if step >= dist - 1e-12 {
        t
    } else {
        p + step.copysign(t - p)
    };
    (v, np)
}

/// The highest speed at which an axis `dist` from its end may run `n` + 1
/// periods before it brakes, and still land (`rapid_axis`'s guard): the
/// root of v·(n + 3)·dt + v²/2a = `dist` (the stop itself takes v²/2a and
/// at most a period more), checked against the landing limit.
fn cruise_limit(dist: f64, n: usize, a: f64, dt: f64) -> f64 {
    let hold = (n as f64 + 3.0) * dt;
    let mut v = a * (sqrt(hold * hold + 2.0 * dist / a) - hold);
    for _ in 0..4 {
        let ahead = dist - v * (n as f64 + 1.0) * dt;
        if ahead >= 0.0 && brake_limit_above(ahead, 0.0, a, dt, v) >= v {
            return v;
        }
        v *= 0.5;
    }
    0.0
}

/// The sign of a speed change, for `Turns`.
fn turn(v0: f64, v: f64) -> i8 {
    if v > v0 {
        1
    } else if v < v0 {
        -1
    } else {
        0
    }
}

/// The runtime core: planner queue, interpolator, spindle and the
/// operator's signals, for one machine.
pub struct Engine<P: Plc> {
    cfg: Config,
    /// The drives' backlash compensation, following the set points (none
    /// on a machine without lost motion, the usual case, which then pays
    /// nothing for it).
    backlash: Option<Backlash>,
    /// The pitch error tables of X, Z and C (none on a machine without).
    pitch: Option<[PitchTable; 3]>,
    /// Machine lock: the switch, and where it holds the axes.
    lock: MachineLock,
    dt: f64,
    plc: P,
    q: Planner,
    spindle: Spindle,
    ticks: u64,
    /// The programmed point (on the path).
    pos: V2,
    /// The axis set point: `pos`, except where an axis follows a thread
    /// chain's corner within its acceleration ([`Follower`]).
    out: V2,
    follow: Follower,
    last_step: V2,
    /// The C angle (degrees) and its change over the last period; while
    /// a plane is on (C following the plane point) the axis outside the
    /// plane (the planner's third coordinate, `Segment::c0`).
    c: f64,
    last_step_c: f64,
    /// A plane switched in this period (`switch_plane`).
    switched: bool,
    /// Periods the axes have stood for, up to 2.
    still: u8,
    shift: V2,
    fixed_work: Option<V2>,
    /// The head item's block.
    tag: Tag,
    /// The block this period's motion ran where it is not the head's: a
    /// period that ends exactly on a corner ran the move before it, and
    /// the trace names that one (formats.md, `line`).
    ran: Option<Tag>,
    /// The codes shown before a block runs and after a reset: those a
    /// run starts with.
    power_on_codes: nc::ActiveCodes,
    tool: u32,
    state: RunState,
    /// The head item has begun.
    started: bool,
    /// A copy of the head move, made when it begins (the queue is not
    /// copied every period); its exit speed and acceleration are
    /// refreshed each period, since the planner may raise them.
    cur: Segment,
    /// Path parameter: `s` of the acceleration-limited profile, `s_out` of
    /// the set points (the same unless jerk limiting averages it, in a
    /// plane).
    s: f64,
    s_out: f64,
    /// Jerk limiting: the moving average of the path parameter in a
    /// plane.
    smooth: Smoother,
    jerk: bool,
    /// Jerk limiting: the unfiltered rapid point, its moving average and
    /// the turns of its axes' speeds (smooth.rs `Turns`).
    rapid_raw: V2,
    rapid_avg: Smoother,
    turns: Turns,
    /// The unfiltered rapid C angle and C's own moving average (jerk).
    rapid_raw_c: f64,
    rapid_avg_c: Smoother,
    /// Jerk limiting: the pairs of moving averages of a feed's set points
    /// (X/Z, and C), outside a plane (planner.rs `FeedSmoothing`).
    feed_avg: Cascade,
    feed_avg_c: Cascade,
    lam: f64,
    v: f64,
    /// Rapid speeds of X, Z and C.
    rapid_v: [f64; 3],
    thread: ThreadRun,
    dwell_left: u64,
    stall_s: f64,
    motion: Motion,
    feed_ovr: f64,
    rapid_ovr: RapidOverride,
    hold: bool,
    single_block: bool,
    optional_stop: bool,
    dry_run: bool,
    /// Auxiliary function lock: PLC functions pass unexecuted.
    aux_lock: bool,
    cycle_start: bool,
    /// A manual session: its moves are queued or running (manual.rs).
    manual: bool,
    reset_req: bool,
    reset_done: bool,
    /// The program ended on an M30 and the machine rewinds
    /// (`run.m30_rewinds`): cycle start runs it again.
    rewind: bool,
    /// A rewind's reset runs: cycle start when it has finished.
    start_after_reset: bool,
    /// The motion reached the program's end, until the run-ahead takes it
    /// (it then keeps what the run counted: counters.rs).
    ended: bool,
    skip_active: bool,
    skip_hit: Option<V2>,
    skip_report: Option<SkipReport>,
    /// The latest W118 of a thread start, until the host takes it.
    room_warning: [Option<RoomWarning>; 2],
    sb_block: Option<u32>,
    /// A period that ended on a corner (or crossed it by a rounding
    /// residue) faster than the corner speed: the next one must not
    /// exceed the corner speed, since the direction change falls between
    /// the two.
    cap_next: f64,
    /// ... and that period's speed change is charged to the move before
    /// the corner (its acceleration keeps the corner's share back).
    cap_accel: f64,
    alarm: Option<(u32, Tag)>,
    /// Stored stroke check 2 (G22): the area the axes may not enter.
    stroke: Option<nc::stroke::Area>,
    /// Polar or cylindrical interpolation: `pos` is a plane point and
    /// these are the joints (polar.rs).
    plane: Option<crate::polar::PlaneRun>,
}

impl<P: Plc> Engine<P> {
    /// An engine at machine zero, spindle stopped, waiting for cycle
    /// start. This is the only allocation (the queue).
    pub fn new(cfg: Config, plc: P) -> Engine<P> {
        let q = Planner::new(&cfg);
        let spindle = Spindle::new(cfg.spindle, cfg.spindle_override_pct);
        let lost = V2::new(cfg.x.backlash, cfg.z.backlash);
        let (lost_c, accel_c) = cfg.c.as_ref().map_or((0.0, 1.0), |c| (c.backlash, c.accel));
        let backlash = (lost != V2::ZERO || lost_c != 0.0).then(|| {
            Backlash::new(lost, V2::new(cfg.x.accel, cfg.z.accel)).with_c(lost_c, accel_c)
        });
        let pitch = cfg
            .pitch
            .iter()
            .any(|t| !t.is_empty())
            .then(|| cfg.pitch.clone());
        Engine {
            backlash,
            pitch,
            lock: MachineLock::new(cfg.machine_lock),
            dt: cfg.period_s,
            plc,
            q,
            spindle,
            ticks: 0,
            pos: V2::ZERO,
            out: V2::ZERO,
            follow: Follower::default(),
            last_step: V2::ZERO,
            still: 2,
            c: 0.0,
            last_step_c: 0.0,
            switched: false,
            shift: V2::ZERO,
            fixed_work: None,
            tag: Tag::default(),
            ran: None,
            power_on_codes: nc::ActiveCodes::NONE,
            tool: 1,
            state: RunState::Idle,
            started: false,
            cur: Segment::IDLE,
            s: 0.0,
            s_out: 0.0,
            smooth: Smoother::new(cfg.jerk_taps()),
            jerk: cfg.jerk_taps() > 1,
            rapid_raw: V2::ZERO,
            rapid_avg: Smoother::new(cfg.rapid_taps()),
            turns: Turns::new(cfg.rapid_taps()),
            rapid_raw_c: 0.0,
            rapid_avg_c: Smoother::new(if cfg.c.is_some() { cfg.rapid_taps() } else { 1 }),
            feed_avg: Cascade::new(cfg.feed_taps(), cfg.feed_spread_taps()),
            feed_avg_c: match cfg.c {
                Some(_) => Cascade::new(cfg.feed_taps(), cfg.feed_spread_taps()),
                None => Cascade::new(1, 1),
            },
            lam: 0.0,
            v: 0.0,
            rapid_v: [0.0; 3],
            thread: ThreadRun::OFF,
            dwell_left: 0,
            stall_s: 0.0,
            motion: Motion::None,
            feed_ovr: cfg.feed_override_pct / 100.0,
            rapid_ovr: cfg.rapid_override,
            hold: false,
            single_block: cfg.single_block,
            optional_stop: cfg.optional_stop,
            dry_run: cfg.dry_run,
            aux_lock: cfg.aux_lock,
            cycle_start: false,
            manual: false,
            reset_req: false,
            reset_done: false,
            rewind: false,
            start_after_reset: false,
            ended: false,
            skip_active: false,
            skip_hit: None,
            skip_report: None,
            room_warning: [None; 2],
            sb_block: None,
            cap_next: f64::INFINITY,
            cap_accel: 0.0,
            alarm: None,
            stroke: None,
            plane: None,
            cfg,
        }
    }

    /// The settings the engine runs with.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// The planner queue.
    pub fn planner(&self) -> &Planner {
        &self.q
    }

    /// The queue itself, for a host that plans without interpolating (a
    /// bench of the planning, an estimate): it may pop planned moves, but
    /// not while the interpolator is on one.
    pub fn planner_mut(&mut self) -> &mut Planner {
        &mut self.q
    }

    /// Queues a command (the non-real-time side; allocates nothing).
    pub fn push(&mut self, cmd: crate::command::Command, tag: Tag) -> Result<Pushed, Full> {
        if self.manual {
            // The program side waits, as at a full queue: the reset that
            // ends a manual session restarts it anyway.
            return Err(Full);
        }
        self.q.push(cmd, tag)
    }

    /// Completes the planning of what was pushed (the backward pass);
    /// call it after a batch of pushes, before the next tick.
    pub fn replan(&mut self) {
        self.q.replan();
    }

    /// Marks the end of NC block `block` in the queue (single block stops there).
    pub fn mark_block_end(&mut self, block: u32) {
        self.q.mark_block_end(block);
    }

    /// The host's PLC.
    pub fn plc(&self) -> &P {
        &self.plc
    }

    /// The host's PLC, mutable.
    pub fn plc_mut(&mut self) -> &mut P {
        &mut self.plc
    }

    /// The spindle (simulated or measured).
    pub fn spindle(&self) -> &Spindle {
        &self.spindle
    }

    /// What the machine is doing.
    pub fn state(&self) -> RunState {
        match self.manual {
            true => RunState::Manual,
            false => self.state,
        }
    }

    /// The code and place of the alarm that stopped the run.
    pub fn alarm(&self) -> Option<(u32, Tag)> {
        self.alarm
    }

    /// The codes in force for the block whose motion runs (or last ran),
    /// for the operator's screen: the G code of each modal group, F, S
    /// and the T word, as they stood after that block. The VM reads
    /// ahead of the motion; these go with the commands, so that the
    /// screen follows the motion. A move that waited in the kernel for
    /// the next block (nose-radius compensation, a corner word) shows
    /// the codes after that block. Before the first block and after a
    /// reset: those of [`set_power_on_codes`](Engine::set_power_on_codes).
    pub fn active_codes(&self) -> nc::ActiveCodes {
        self.ran_tag().active
    }

    /// How far the move that runs still has to go along X (on the
    /// diameter, as positions are shown) and Z, mm: its end point less
    /// the programmed point the axes are at; in a plane of polar or
    /// cylindrical interpolation, the joints at its end less the joints
    /// now. Zero while no program move runs: idle, at a stop or the end,
    /// in an alarm, in a dwell or a PLC function, during a reset or a
    /// manual move.
    pub fn distance_to_go(&self) -> nc::machine::Xz {
        let moving = matches!(
            self.state,
            RunState::Running | RunState::Held | RunState::Starved
        );
        if !moving || self.reset_req {
            return nc::machine::Xz { x: 0.0, z: 0.0 };
        }
        let d = match &self.plane {
            Some(run) => run.joints_at(self.cur.to, self.cur.c1).sub(run.work()),
            None => self.cur.to.sub(self.pos),
        };
        nc::machine::Xz { x: d.x(), z: d.z }
    }

    /// The tag of the block this period's motion ran (`ran`, else the
    /// head item's).
    fn ran_tag(&self) -> &Tag {
        self.ran.as_ref().unwrap_or(&self.tag)
    }

    /// The codes a run starts with (the controller gives
    /// [`nc::ActiveCodes::power_on`] of its machine), shown until a
    /// block runs and again after every reset.
    pub fn set_power_on_codes(&mut self, codes: nc::ActiveCodes) {
        self.power_on_codes = codes;
        if self.ticks == 0 {
            self.tag.active = codes;
        }
    }

    /// While idle, the screen shows `codes` until a block runs: those a
    /// program restart's search found ([`crate::Restarted::codes`]), or
    /// a new program's power-on codes. Ignored while a run is under way.
    pub fn show_codes(&mut self, codes: nc::ActiveCodes) {
        if self.state == RunState::Idle && !self.reset_req {
            self.tag.active = codes;
        }
    }

    /// The programmed point the axes are at, slide units. The set points
    /// differ from it only while an axis still follows a thread chain's
    /// corner ([`crate::follow`]), a new move waiting until they meet,
    /// and under machine lock, which holds them
    /// ([`machine_point`](Engine::machine_point) is where they stand).
    pub fn position(&self) -> V2 {
        self.pos
    }

    /// Time since power-on: periods × the period, s.
    pub fn time_s(&self) -> f64 {
        self.ticks as f64 * self.dt
    }

    /// Feed override, 0–150 %.
    pub fn set_feed_override(&mut self, pct: f64) {
        self.feed_ovr = pct.clamp(0.0, 150.0) / 100.0;
    }

    /// Rapid override position.
    pub fn set_rapid_override(&mut self, r: RapidOverride) {
        self.rapid_ovr = r;
    }

    /// Spindle override, percent (0–200).
    pub fn set_spindle_override(&mut self, pct: f64) {
        self.spindle.override_factor = pct.clamp(0.0, 200.0) / 100.0;
    }

    /// The host's measured spindle for the coming period (encoder
    /// position in turns, signed; speed in rev/min, signed): from the
    /// first call on, threads and feed per revolution follow it instead
    /// of the simulated spindle ([`Spindle::set_measured`]).
    pub fn set_spindle_feedback(&mut self, position_turns: f64, rpm: f64) {
        self.spindle.set_measured(position_turns, rpm);
    }

    /// Back to the simulated spindle.
    pub fn set_spindle_simulated(&mut self) {
        self.spindle.set_simulated();
    }

    /// Feed hold: the motion decelerates on its path and stands; cycle
    /// start resumes. Threads finish their chain first (dialect.md §4.3).
    pub fn feed_hold(&mut self) {
        self.hold = true;
    }

    /// A feed hold requested holds the head item, unless the program set
    /// `#3004` bit 0 for its block: then it waits for a block without.
    fn holding(&self) -> bool {
        self.hold && !self.tag.no_hold
    }

    /// Cycle start: starts the program, resumes after feed hold or a stop.
    /// After an M30 on a machine whose M30 rewinds (`run.m30_rewinds`):
    /// a reset, then the program from its start, period for period as
    /// the operator's reset and cycle start would make them.
    pub fn cycle_start(&mut self) {
        if self.state == RunState::Ended && self.rewind && !self.reset_req {
            self.reset_req = true;
            self.start_after_reset = true;
        } else {
            self.cycle_start = true;
        }
    }

    /// Single block: stop at the end of every block.
    pub fn set_single_block(&mut self, on: bool) {
        self.single_block = on;
    }

    /// The optional stop switch, read when the motion reaches an M01:
    /// off, the M01 passes without a stop. (The VM must hand every M01
    /// over for this to work both ways: see
    /// [`crate::Controller::set_optional_stop`].)
    pub fn set_optional_stop(&mut self, on: bool) {
        self.optional_stop = on;
    }

    /// Dry run: cutting feeds (not G31 skips, not threads, which stay on
    /// the spindle) run at [`Config::dry_run_feed`] × the feed override,
    /// feed per revolution included, so the spindle need not turn. The
    /// rate applies at once, up to the speed each queued move was planned
    /// for: moves queued after the switch are planned for the path limit
    /// ([`Planner::set_dry_run`]), those queued before for their F.
    pub fn set_dry_run(&mut self, on: bool) {
        self.dry_run = on;
        self.q.set_dry_run(on);
    }

    /// Machine lock (docs/machine.md): the program runs, the axes stand.
    /// The switch is read when a run or a manual move starts from idle,
    /// and holds the axes until the reset that ends it, which brings the
    /// programmed point back to where they stand; switched mid-run, it
    /// waits for the next start.
    pub fn set_machine_lock(&mut self, on: bool) {
        self.lock.switch = on;
    }

    /// Auxiliary function lock (docs/machine.md, "Machine lock"): the M,
    /// S and T functions the motion reaches pass without being executed:
    /// the PLC is not asked, the simulated spindle and the tool stay as
    /// they are. Read as the motion reaches each function.
    pub fn set_aux_lock(&mut self, on: bool) {
        self.aux_lock = on;
    }

    /// Machine lock holds the axes for the run or manual move under way.
    pub fn axes_locked(&self) -> bool {
        self.lock.holds()
    }

    /// A run or a manual move starts: machine lock, if on, holds the
    /// axes where they stand.
    fn lock_axes(&mut self) {
        let (_, axes, c) = self.frames();
        self.lock.start(axes, c);
    }

    /// Reset: the motion decelerates to a stop, the queue is dropped, the
    /// spindle stops, an alarm is cleared; the engine waits for cycle start.
    pub fn reset(&mut self) {
        self.reset_req = true;
        self.start_after_reset = false;
    }

    /// Drops what the program queued ahead while the machine is idle, for
    /// a run that starts afresh where the axes stand (a program restart).
    /// `false`, and nothing changes, unless idle.
    pub fn clear_idle(&mut self) -> bool {
        if self.state() != RunState::Idle || self.reset_req {
            return false;
        }
        self.q.clear();
        self.q.set_tail(self.pos);
        self.q.set_tail_c(self.c);
        true
    }

    /// The level of the host input wired to the skip signal (№148).
    pub fn set_skip_input(&mut self, level: bool) {
        self.skip_active = level != self.cfg.skip_active_low;
    }

    /// How the last G31 move ended, once.
    pub fn take_skip_report(&mut self) -> Option<SkipReport> {
        self.skip_report.take()
    }

    /// The room checks of the last thread start (W118), entry first, each
    /// once: a host polls them every period (a later start replaces those
    /// not taken).
    pub fn take_room_warning(&mut self) -> Option<RoomWarning> {
        let [entry, exit] = &mut self.room_warning;
        entry.take().or_else(|| exit.take())
    }

    /// Whether a reset finished since the last call.
    pub fn take_reset_done(&mut self) -> bool {
        core::mem::take(&mut self.reset_done)
    }

    /// Whether the motion reached the program's end (M02, M30, the last
    /// M99 or the last block) since the last call; a reset keeps the
    /// report until it is taken.
    pub fn take_ended(&mut self) -> bool {
        core::mem::take(&mut self.ended)
    }

    /// Display shift and tail at power-on and after a reset (the host
    /// re-seeds them). The queue takes the shift too: an item that is no
    /// move (a dwell, an M code, a T) carries the queue's shift, which the
    /// work frame is shown in while it runs.
    pub fn reseed(&mut self, shift: V2) {
        self.shift = shift;
        self.q.set_shift(shift);
        self.q.set_tail(self.pos);
    }

    /// One interpolation period.
    pub fn tick(&mut self) -> SetPoint {
        self.ticks += 1;
        let before = self.out;
        let before_c = self.c;
        // Only constant surface speed needs the diameter.
        let x = if self.spindle.css() {
            self.css_diameter()
        } else {
            0.0
        };
        self.spindle.update(self.dt, x);
        self.motion = Motion::None;
        self.ran = None;
        if self.reset_req {
            self.reset_step();
        } else if self.manual {
            self.manual_period();
        } else {
            self.run_state();
        }
        self.follow_point();
        self.last_step = self.out - before;
        self.last_step_c = self.c - before_c;
        if let Some(run) = &mut self.plane {
            // The path is the plane's (`c` is the third coordinate: the
            // axis outside the plane, which a move may take along).
            run.follow(self.pos, self.c);
        }
        if core::mem::take(&mut self.switched) {
            // The point changed coordinates: no step of the path.
            (self.last_step, self.last_step_c) = (V2::ZERO, 0.0);
        }
        self.still = match self.last_step == V2::ZERO && self.last_step_c == 0.0 {
            true => (self.still + 1).min(2),
            false => 0,
        };
        self.check_stroke();
        let (work, axes, c) = self.frames();
        let drive = self.drive_command(axes, c);
        self.setpoint(work, axes, c, drive)
    }

    /// Cycle start and feed hold against the run state, and this
    /// period's motion if the program runs.
    fn run_state(&mut self) {
        match self.state {
            // (Manual is only reported, `state`: a manual move runs as
            // Running, `manual_period`.)
            RunState::Ended | RunState::Alarm(_) | RunState::Manual => self.cycle_start = false,
            RunState::Idle => {
                if core::mem::take(&mut self.cycle_start) {
                    self.lock_axes();
                    self.state = RunState::Running;
                    self.run();
                }
            }
            RunState::Stopped(kind) => {
                if core::mem::take(&mut self.cycle_start) {
                    // Cycle start passes the pause that stopped the run
                    // (after a single block's stop, a pause at the head
                    // is still to come).
                    if !matches!(kind, PauseKind::SingleBlock) {
                        if let Some(Item {
                            kind: ItemKind::Pause(_),
                            ..
                        }) = self.q.get(0)
                        {
                            self.q.pop();
                            self.started = false;
                        }
                    }
                    self.state = RunState::Running;
                    self.run();
                }
            }
            RunState::Held | RunState::Running | RunState::Starved => {
                if core::mem::take(&mut self.cycle_start) {
                    self.hold = false;
                }
                if self.state == RunState::Held && !self.hold {
                    self.state = RunState::Running;
                }
                self.run();
            }
        }
    }

    /// The axes follow the point: at once, or in a thread chain (and
    /// until they have closed their lag after it) each within its
    /// acceleration (follow.rs).
    fn follow_point(&mut self) {
        let thread = self.motion == Motion::Thread;
        let acc = [self.cfg.x.accel, self.cfg.z.accel];
        let vmax = [self.cfg.x.max_feed, self.cfg.z.max_feed];
        let ahead = if thread {
            [0, 1].map(|i| self.chain_runs_on(i, stopping_distance(vmax[i], acc[i], self.dt)))
        } else {
            [Ahead::UNKNOWN; 2]
        };
        let axes = FollowAxes { acc, vmax, ahead };
        self.out = self.follow.step(self.pos, thread, axes, self.dt);
        if !thread && self.follow.engaged() {
            self.motion = Motion::Thread;
        }
    }

    /// What the drives are commanded for the machine set point `axes`
    /// and C angle `c`: they, plus the backlash and pitch error
    /// compensation of a machine that has them.
    fn drive_command(&mut self, axes: V2, c: f64) -> (V2, f64) {
        let (mut drive, mut drive_c) = (axes, c);
        if let Some(b) = &mut self.backlash {
            drive = drive + b.period(axes, self.dt);
            drive_c += b.period_c(c, self.dt);
        }
        if let Some([x, z, c_table]) = &mut self.pitch {
            drive = drive + V2::new(x.at(axes.r), z.at(axes.z));
            drive_c += c_table.at(c);
        }
        (drive, drive_c)
    }

    /// The machine set point the axes stand at, X on the diameter, tool
    /// offset included (the last period's `axis_x`, `axis_z`); `None` in
    /// a plane of polar or cylindrical interpolation, whose joints are
    /// not X and Z.
    pub fn machine_point(&self) -> Option<nc::machine::Xz> {
        if self.plane.is_some() {
            return None;
        }
        let (_, axes, _) = self.frames();
        Some(nc::machine::Xz {
            x: axes.x(),
            z: axes.z,
        })
    }

    /// This period's point in work coordinates, the machine set point
    /// and C (where machine lock holds them, while it does).
    fn frames(&self) -> (V2, V2, f64) {
        let (work, axes, c) = match &self.plane {
            Some(run) => (run.work(), run.axes(), run.c()),
            None => (
                self.fixed_work.unwrap_or(self.out - self.shift),
                self.out,
                self.c,
            ),
        };
        let (axes, c) = self.lock.axes(axes, c);
        (work, axes, c)
    }

    /// The period's set point; `drive` is the machine set point and C
    /// with the backlash and pitch error compensation added, which the
    /// counts command.
    fn setpoint(&self, work: V2, axes: V2, c: f64, (drive, drive_c): (V2, f64)) -> SetPoint {
        let ran = self.ran_tag();
        SetPoint {
            time_s: self.ticks as f64 * self.dt,
            x: work.x(),
            z: work.z,
            axis_x: axes.x(),
            axis_z: axes.z,
            counts: Counts::of(drive.x(), drive.z, drive_c, self.cfg.resolution_mm),
            spindle_rpm: self.spindle.rpm(),
            spindle_turns: self.spindle.turns(),
            c: self.cfg.c.map(|_| c),
            feed: self.path_step() / self.dt * 60.0,
            line: ran.line,
            file: ran.file,
            motion: self.motion,
            tool: self.tool,
        }
    }

    /// The distance the last period moved along the path: XZ, combined
    /// with C (degrees as mm) while C turns; in a plane, along the plane
    /// combined with the axis outside it.
    fn path_step(&self) -> f64 {
        if self.last_step_c == 0.0 {
            self.last_step.norm()
        } else {
            crate::math::sqrt(
                self.last_step.r * self.last_step.r
                    + self.last_step.z * self.last_step.z
                    + self.last_step_c * self.last_step_c,
            )
        }
    }

    /// The current C angle, degrees (0 without a C axis).
    pub fn c(&self) -> f64 {
        self.plane.as_ref().map_or(self.c, |run| run.c())
    }

    /// The diameter G96 computes the rpm from: the programmed point, or a
    /// rapid's end point (dialect.md §4.10).
    fn css_diameter(&self) -> f64 {
        if self.started {
            if let Some(s) = self.q.seg(0) {
                if matches!(s.kind, MoveKind::Rapid) {
                    return (s.to - s.shift).x();
                }
            }
        }
        self.fixed_work.unwrap_or(self.pos - self.shift).x()
    }

    /// G22 on the path: the first period whose set point (the machine
    /// axes, X as a diameter) lies in the forbidden area stops the motion
    /// with E7002, as a real control stops on entering it. The kernel has
    /// already refused every programmed end point there; this catches what
    /// runs between them (dog-leg rapids, arcs, cycle legs) and what tool
    /// offsets move.
    fn check_stroke(&mut self) {
        let Some(area) = self.stroke else { return };
        // (In a plane the point is no axis position; the kernel checked
        // the plane's end points.)
        if self.plane.is_some() {
            return;
        }
        if matches!(self.state, RunState::Alarm(_)) {
            return;
        }
        if area.forbids(self.out.x(), self.out.z) {
            self.raise(Alarm::StrokeLimit.into(), self.tag);
        }
    }

    fn raise(&mut self, code: u32, tag: Tag) {
        self.state = RunState::Alarm(code);
        self.alarm = Some((code, tag));
        self.v = 0.0;
        self.rapid_v = [0.0; 3];
    }

    /// Polar or cylindrical interpolation on or off: the motion stands
    /// (the move before ended at rest); the point changes coordinates.
    fn switch_plane(&mut self, sw: &crate::polar::PlaneSwitch) {
        self.plane = sw.map.map(|m| crate::polar::PlaneRun::start(m, sw));
        self.switched = true;
        self.pos = sw.at;
        self.c = sw.third();
        self.rapid_raw = sw.at;
        self.rapid_raw_c = self.c;
        self.smooth.reset(sw.at);
        self.rapid_avg.reset(sw.at);
        self.rapid_avg_c.reset(V2::new(self.c, 0.0));
    }

    /// Done with the head item; `landed`: the motion stands at its end.
    fn finish_item(&mut self) {
        let block_end = self.q.get(0).is_some_and(|i| i.tag.block_end);
        if let Some(Segment {
            kind: MoveKind::Offset,
            shift,
            ..
        }) = self.q.seg(0)
        {
            self.shift = *shift;
            self.fixed_work = None;
        }
        self.q.pop();
        self.started = false;
        self.thread.phase = Phase::Off;
        if self.spindle.rigid_out() {
            // The move out of a rigid reversal is done.
            self.spindle.rigid_end();
        }
        if block_end && self.single_block && self.state == RunState::Running {
            self.state = RunState::Stopped(PauseKind::SingleBlock);
        }
    }

    /// Executes head items until one takes the rest of the period.
    fn run(&mut self) {
        for _ in 0..64 {
            if self.state != RunState::Running
                && self.state != RunState::Starved
                && self.state != RunState::Held
            {
                return;
            }
            let Some((head, tag, shift)) = self.head() else {
                if self.state == RunState::Running {
                    self.state = RunState::Starved;
                }
                return;
            };
            if self.state == RunState::Starved {
                self.state = RunState::Running;
            }
            if !self.started && !matches!(head, Head::Move) {
                self.shift = shift;
                self.tag = tag;
                self.fixed_work = None;
            }
            let flow = match head {
                Head::Move => {
                    self.step_move();
                    Flow::Done
                }
                Head::Dwell(secs) => self.step_dwell(secs),
                Head::Plc(f) => self.step_plc(f),
                Head::Pause(PauseKind::M01) if !self.optional_stop => self.finish_item_now(),
                Head::Pause(k) => {
                    self.state = RunState::Stopped(k);
                    Flow::Done
                }
                Head::Stroke(a) => {
                    self.stroke = a;
                    self.finish_item_now()
                }
                Head::Plane(sw) => {
                    self.switch_plane(&sw);
                    self.finish_item_now()
                }
                Head::End(ending) => {
                    self.ended = true;
                    match ending {
                        Ending::Mdi => self.back_from_mdi(),
                        _ => {
                            self.state = RunState::Ended;
                            self.rewind = ending == Ending::M30 && self.cfg.m30_rewinds;
                        }
                    }
                    Flow::Done
                }
                Head::Alarm(c) => {
                    self.raise(c, tag);
                    Flow::Done
                }
            };
            if let Flow::Done = flow {
                return;
            }
        }
    }

    /// The queue's head item (a copy of what it asks), its tag and shift.
    fn head(&self) -> Option<(Head, Tag, V2)> {
        let item = self.q.get(0)?;
        let head = match &item.kind {
            ItemKind::Move(_) => Head::Move,
            ItemKind::Dwell(s) => Head::Dwell(*s),
            ItemKind::Plc(f) => Head::Plc(*f),
            ItemKind::Pause(k) => Head::Pause(*k),
            ItemKind::Stroke(a) => Head::Stroke(*a),
            ItemKind::Plane(sw) => Head::Plane(*sw),
            ItemKind::End(e) => Head::End(*e),
            ItemKind::Alarm(c) => Head::Alarm(*c),
        };
        Some((head, item.tag, item.shift))
    }

    /// A dwell counts down a period at a time (not while held).
    fn step_dwell(&mut self, secs: f64) -> Flow {
        if !self.started {
            self.started = true;
            let n = libm::round(secs.max(0.0) / self.dt);
            self.dwell_left = if n.is_finite() { n as u64 } else { u64::MAX };
        }
        if self.dwell_left == 0 {
            return self.finish_item_now();
        }
        if self.holding() {
            self.state = RunState::Held;
        } else {
            self.motion = Motion::Dwell;
            self.dwell_left -= 1;
            if self.dwell_left == 0 {
                self.finish_item();
            }
        }
        Flow::Done
    }

    /// A PLC function is requested once, then waited for (not under
    /// `#3003` bit 1: the host is not polled for its FIN).
    fn step_plc(&mut self, f: PlcFunction) -> Flow {
        if self.aux_lock && !self.started {
            return self.finish_item_now();
        }
        if !self.started {
            self.started = true;
            self.apply_plc(f);
            self.plc.request(f);
        }
        if !self.tag.no_fin && !self.plc.done(f) {
            return Flow::Done;
        }
        self.finish_item_now()
    }

    /// Finishes the head item, which took no time: the next one may run
    /// in this period.
    fn finish_item_now(&mut self) -> Flow {
        self.finish_item();
        Flow::Next
    }

    /// What the simulation itself does for a PLC function.
    fn apply_plc(&mut self, f: PlcFunction) {
        match f {
            PlcFunction::Spindle(d) => self.spindle.set_dir(d),
            PlcFunction::Speed { s, css, max } => self.spindle.set_speed(s, css, max),
            PlcFunction::Tool { t, .. } => self.tool = t,
            PlcFunction::M(_) | PlcFunction::Gear(_) => {}
        }
    }

    /// Checks made when a move starts: F = 0 (E7001), travel (E7002).
    fn check_move(&self, seg: &Segment) -> Option<u32> {
        if let MoveKind::Feed(f) | MoveKind::Skip(f) = seg.kind {
            if !crate::math::is_pos(f.f) {
                return Some(Alarm::ZeroFeed.into());
            }
        }
        if seg.outside {
            return Some(Alarm::StrokeLimit.into());
        }
        None
    }

    fn step_move(&mut self) {
        if !self.started {
            if !self.start_move() {
                return;
            }
        } else if let Some(s) = self.q.seg(0) {
            self.cur.v_exit = s.v_exit;
            self.cur.a = s.a;
        }
        match self.cur.kind {
            _ if self.axis_rapid() => self.step_rapid(),
            MoveKind::Thread(_) => self.step_thread(),
            _ => self.step_path(),
        }
    }

    /// Starts the head move if it may start in this period; false where
    /// it waits (for the axes to stand, for cycle start after a hold) or
    /// raised an alarm.
    fn start_move(&mut self) -> bool {
        let Some(item) = self.q.get(0) else {
            return false;
        };
        let ItemKind::Move(seg) = &item.kind else {
            return false;
        };
        // Start from rest only: a landing period is followed by one
        // standing period, so the velocity passes through zero. With jerk
        // limiting, two: the acceleration too, so the jerk of the start
        // does not add to that of the last move's end (each may take the
        // whole limit: a rapid's window is a/j).
        let need = if self.jerk { 2 } else { 1 };
        if self.still < need || self.follow.engaged() {
            return false;
        }
        if self.hold && !item.tag.no_hold && !matches!(seg.kind, MoveKind::Thread(_)) {
            self.state = RunState::Held;
            return false;
        }
        let (seg, tag) = (*seg, item.tag);
        if let Some(code) = self.check_move(&seg) {
            self.raise(code, tag);
            return false;
        }
        self.begin_move(seg, tag);
        true
    }

    /// The run's state for `seg`, which starts from rest where the axes
    /// stand.
    fn begin_move(&mut self, seg: Segment, tag: Tag) {
        self.cur = seg;
        self.started = true;
        self.cap_next = f64::INFINITY;
        self.s = 0.0;
        self.lam = 0.0;
        self.v = 0.0;
        self.rapid_v = [0.0; 3];
        self.stall_s = 0.0;
        self.skip_hit = None;
        self.tag = tag;
        if let MoveKind::Offset = self.cur.kind {
            self.fixed_work = Some(self.pos - self.shift);
        } else {
            self.shift = self.cur.shift;
            self.fixed_work = None;
        }
        if let MoveKind::Thread(_) = self.cur.kind {
            self.thread = ThreadRun::STARTING;
        }
        self.s_out = 0.0;
        self.rapid_raw = self.pos;
        self.rapid_raw_c = self.c;
        if self.jerk {
            let at = if self.axis_rapid() {
                self.pos
            } else {
                V2::ZERO
            };
            self.smooth.reset(at);
            self.rapid_avg.reset(self.pos);
            self.rapid_avg_c.reset(V2::new(self.c, 0.0));
            self.turns.clear();
            self.feed_avg.reset(self.pos);
            self.feed_avg_c.reset(V2::new(self.c, 0.0));
        }
    }

    /// The head move is a rapid of each axis on its own: a G00 (or an
    /// offset's move) outside polar and cylindrical interpolation. In a
    /// plane a G00 follows the straight line of the plane, as a feed at
    /// the rapid rate does, within the joints' caps (planner.rs).
    fn axis_rapid(&self) -> bool {
        matches!(self.cur.kind, MoveKind::Rapid | MoveKind::Offset) && self.plane.is_none()
    }

    /// G00: each axis on its own, at its rapid rate and acceleration.
    fn step_rapid(&mut self) {
        self.motion = Motion::Rapid;
        let f = if self.holding() || self.reset_req {
            0.0
        } else {
            self.rapid_ovr.factor(self.cfg.rapid_f0)
        };
        let to = self.cur.to;
        let mut raw = if self.jerk { self.rapid_raw } else { self.pos };
        let (lag, n, jerk) = (self.turns.lagged(), self.turns_len(), self.jerk);
        let guard = |k: usize| jerk.then_some((n, lag[k]));
        let (vx, rx) = rapid_axis(
            self.rapid_v[0],
            raw.r,
            to.r,
            &self.cfg.x,
            f,
            self.dt,
            guard(0),
        );
        let (vz, rz) = rapid_axis(
            self.rapid_v[1],
            raw.z,
            to.z,
            &self.cfg.z,
            f,
            self.dt,
            guard(1),
        );
        let turn = [turn(self.rapid_v[0], vx), turn(self.rapid_v[1], vz)];
        self.rapid_v[0] = vx;
        self.rapid_v[1] = vz;
        let mut arrived = rx == to.r && rz == to.z;
        raw = V2::new(rx, rz);
        if self.jerk {
            self.rapid_raw = raw;
            self.pos = self.rapid_avg.push(raw);
            arrived &= self.rapid_avg.settled();
        } else {
            self.pos = raw;
        }
        let (c_arrived, turn_c) = self.rapid_c(f, guard(2));
        arrived &= c_arrived;
        self.turns.push([turn[0], turn[1], turn_c]);
        if arrived {
            self.pos = to;
            self.c = self.cur.c1;
            self.finish_item();
        } else if self.holding()
            && self.rapid_v == [0.0; 3]
            && (!self.jerk || self.rapid_avg.settled())
        {
            self.state = RunState::Held;
        }
    }

    /// One period of C in a rapid, on its own like X and Z (a dog-leg);
    /// whether C has arrived (settled, with jerk limiting), and the turn
    /// of its speed (`rapid_axis`'s `guard`).
    fn rapid_c(&mut self, f: f64, guard: Option<(usize, i8)>) -> (bool, i8) {
        let Some(ax) = self.cfg.c.filter(|_| self.cur.turns_c()) else {
            return (true, 0);
        };
        let raw = if self.jerk { self.rapid_raw_c } else { self.c };
        let (v, c) = rapid_axis(self.rapid_v[2], raw, self.cur.c1, &ax, f, self.dt, guard);
        let turned = turn(self.rapid_v[2], v);
        self.rapid_v[2] = v;
        let mut arrived = c == self.cur.c1;
        if self.jerk {
            self.rapid_raw_c = c;
            self.c = self.rapid_avg_c.push(V2::new(c, 0.0)).r;
            arrived &= self.rapid_avg_c.settled();
        } else {
            self.c = c;
        }
        (arrived, turned)
    }

    /// Periods a rapid's axis keeps the sign of a speed change for.
    fn turns_len(&self) -> usize {
        self.rapid_avg.taps()
    }

    /// The commanded path speed of the head feed, mm/s; 0 while held,
    /// after a skip signal or during a reset. Counts the stall of G99
    /// moves.
    fn v_cmd(&mut self) -> f64 {
        let f = match self.cur.kind {
            MoveKind::Feed(f) | MoveKind::Skip(f) => f,
            MoveKind::Thread(_) => {
                return if self.reset_req {
                    0.0
                } else {
                    self.thread.v_sync
                }
            }
            // A G00 in a plane (`axis_rapid`): the slower axis's rapid
            // rate along the path, under the rapid override.
            MoveKind::Rapid if !self.holding() && !self.reset_req => {
                let rate = self.cfg.x.rapid.min(self.cfg.z.rapid);
                return (rate * self.rapid_ovr.factor(self.cfg.rapid_f0)).min(self.cur.v_max);
            }
            _ => return 0.0,
        };
        let skip = matches!(self.cur.kind, MoveKind::Skip(_));
        let mut v = f.f;
        if self.dry_run && !skip {
            v = self.cfg.dry_run_feed;
            self.stall_s = 0.0;
        } else if f.per_rev {
            if self.spindle.stopped() {
                self.stall_s += self.dt;
                if self.stall_s >= self.cfg.spindle.stall_timeout_s && self.v == 0.0 {
                    let tag = self.tag;
                    self.raise(Alarm::SpindleStopped.into(), tag);
                    return 0.0;
                }
            } else {
                self.stall_s = 0.0;
            }
            v *= self.spindle.rpm().abs() / 60.0;
        }
        if self.holding() || self.reset_req || self.skip_hit.is_some() {
            return 0.0;
        }
        let ovr = if skip || f.fixed { 1.0 } else { self.feed_ovr };
        (v * ovr).min(self.cur.v_max)
    }

    /// The commanded speed of the k-th queued move if it is a feed.
    fn feed_of(&self, k: usize) -> Option<f64> {
        let n = self.q.seg(k)?;
        match n.kind {
            MoveKind::Feed(_) if self.dry_run => {
                Some((self.cfg.dry_run_feed * self.feed_ovr).min(n.v_max))
            }
            MoveKind::Feed(f) => {
                let ovr = if f.fixed { 1.0 } else { self.feed_ovr };
                let rate = if f.per_rev {
                    self.spindle.rpm().abs() / 60.0
                } else {
                    1.0
                };
                Some((f.f * rate * ovr).min(n.v_max))
            }
            _ => None,
        }
    }

    /// This period's path speed on the head move.
    fn path_speed(&mut self, vc: f64) -> f64 {
        let dt = self.dt;
        let a = self.cur.a;
        let d = self.cur.len - self.s;
        let top = self.v + a * dt;
        let mut u = self.cur.v_exit;
        if u > 0.0 && matches!(self.cur.kind, MoveKind::Feed(_)) {
            // A lower feed ahead is met at the corner, not after it.
            if let Some(f) = self.feed_of(1) {
                u = u.min(f.max(0.0));
            }
        }
        // The highest speed this period can take: limits above it do not
        // need computing.
        let want = top.min(vc).min(self.cur.v_max);
        let mut lim = brake_limit_above(d, u, a, dt, want);
        // Junctions this period could reach beyond the first.
        let reach = top * dt;
        let mut dist = d;
        let mut k = 0;
        // The later moves seen from the head (thread chains:
        // `Segment::chain_scale`).
        let mut scale = 1.0;
        while dist < reach && k < 8 {
            let (Some(sk), Some(n)) = (self.q.seg(k), self.q.seg(k + 1)) else {
                break;
            };
            if sk.v_exit <= 0.0 {
                break;
            }
            scale *= sk.chain_scale(n);
            dist += n.len * scale;
            let (exit, an) = (n.v_exit * scale, n.a * scale);
            lim = lim.min(brake_limit_above(dist, exit, a.min(an), dt, want));
            k += 1;
        }
        if self.single_block && !matches!(self.cur.kind, MoveKind::Thread(_)) {
            lim = lim.min(self.single_block_limit(a));
        }
        let cap = core::mem::replace(&mut self.cap_next, f64::INFINITY);
        let a_step = if cap.is_finite() { self.cap_accel } else { a };
        approach(self.v, vc.min(lim).min(self.cur.v_max).min(cap), a_step, dt)
    }

    /// Single block: the first end of a block the motion can still stop on.
    fn single_block_limit(&mut self, a: f64) -> f64 {
        self.sb_block = None;
        let mut dist = 0.0;
        for k in 0..32 {
            let Some(it) = self.q.get(k) else { break };
            let Some(sk) = it.segment() else { break };
            dist += if k == 0 { sk.len - self.s } else { sk.len };
            if it.tag.block_end {
                let lim = brake_limit(dist, 0.0, a, self.dt);
                if lim >= self.v - a * self.dt - 1e-9 {
                    self.sb_block = Some(it.tag.block);
                    return lim;
                }
            }
            if sk.v_exit <= 0.0 {
                break;
            }
        }
        f64::INFINITY
    }

    /// Whether the motion may run from the head move into the next.
    fn may_cross(&self) -> bool {
        let c = &self.cur;
        if c.v_exit <= 0.0 || matches!(c.kind, MoveKind::Skip(_)) {
            return false;
        }
        let t = &self.tag;
        if self.single_block
            && t.block_end
            && self.sb_block == Some(t.block)
            && !matches!(c.kind, MoveKind::Thread(_))
        {
            return false;
        }
        self.q.seg(1).is_some()
    }

    /// A feed (or a braking thread) along the exact path.
    fn step_path(&mut self) {
        self.motion = match (self.cur.kind, self.cur.curve) {
            (MoveKind::Thread(_), _) => Motion::Thread,
            (MoveKind::Rapid, _) => Motion::Rapid,
            (_, crate::geom::Curve::Line { .. }) => Motion::Feed,
            _ => Motion::Arc,
        };
        if let MoveKind::Skip(_) = self.cur.kind {
            if self.skip_hit.is_none() && self.skip_active {
                self.skip_hit = Some(self.pos);
            }
        }
        let vc = self.v_cmd();
        if let RunState::Alarm(_) = self.state {
            return;
        }
        // The period's speed change is charged to the move it starts on:
        // that move keeps back the share its end corner needs, so the
        // period that runs through the corner stays within the axes'
        // acceleration (and the next period belongs to the next move).
        let v = self.path_speed(vc);
        if self.jerk && !matches!(self.cur.kind, MoveKind::Thread(_)) {
            match self.plane {
                Some(_) => self.smoothed_path(v),
                None => self.averaged_path(v),
            }
            return;
        }
        if self.travel(v) {
            self.land();
        } else if self.v == 0.0 {
            self.standing();
        }
    }

    /// One period of a feed with jerk limiting outside a plane: the path
    /// runs as without it (G64 corners blend), the set point is the
    /// average of its points: two moving averages in a row (smooth.rs
    /// `Cascade`, planner.rs `FeedSmoothing`). The move ends once the
    /// averages have caught up, on the very point the path stands on; it
    /// holds or stops at a skip in the period after (as without jerk
    /// limiting, a standing period).
    fn averaged_path(&mut self, v: f64) {
        let was_settled = self.feed_avg_settled();
        let landed = self.travel(v);
        self.pos = self.feed_avg.push(self.pos);
        self.c = self.feed_avg_c.push(V2::new(self.c, 0.0)).r;
        if !self.feed_avg_settled() {
            return;
        }
        if landed {
            self.land();
        } else if self.v == 0.0 && was_settled {
            self.standing();
        }
    }

    /// The path stands on the head move's end point: the move is done.
    fn land(&mut self) {
        if let MoveKind::Skip(_) = self.cur.kind {
            self.report_skip();
        }
        self.finish_item();
    }

    /// Moves `v · dt` along the path, on into the queued moves where the
    /// corner allows; whether it landed on the head move's end point
    /// (where it stays: the caller ends the move). Sets the path speed
    /// `v`, which a thread chain's corner scales (`Segment::chain_scale`).
    #[inline]
    fn travel(&mut self, mut v: f64) -> bool {
        let mut ds = v * self.dt;
        loop {
            let rem = self.cur.len - self.s;
            if ds < rem {
                self.s += ds;
                self.lam = self.cur.curve.advance(self.lam, self.s, ds, self.cur.len);
                self.pos = self.cur.curve.point(self.lam);
                self.c = self.cur.c_at(self.lam);
                self.v = v;
                return false;
            }
            if v > 0.0 && self.may_cross() {
                // Faster than the corner by more than a rounding residue:
                // a period that braked onto the corner speed may land a
                // hair above it, and charging the next period to this
                // move's acceleration would leave a short move after it
                // behind its braking, to stop at its end harder than the
                // axes may.
                if v > self.cur.v_exit * (1.0 + 1e-9)
                    && !matches!(self.cur.kind, MoveKind::Thread(_))
                {
                    self.cap_next = self.cap_next.min(self.cur.v_exit);
                    self.cap_accel = self.cur.a;
                }
                ds -= rem;
                self.ran_to_corner(ds);
                self.pos = self.cur.to;
                self.c = self.cur.c1;
                self.q.pop();
                let Some(next) = self.q.get(0) else {
                    self.v = v;
                    return false;
                };
                let ItemKind::Move(n) = &next.kind else {
                    self.v = v;
                    return false;
                };
                let scale = self.cur.chain_scale(n);
                if scale != 1.0 {
                    // The same long-axis speed on the next leg.
                    (v, ds) = (v / scale, ds / scale);
                    self.thread.v_sync /= scale;
                }
                self.cur = *n;
                self.tag = next.tag;
                self.shift = n.shift;
                self.s = 0.0;
                self.lam = 0.0;
                continue;
            }
            // Lands on the end point.
            self.s = self.cur.len;
            self.lam = 1.0;
            self.pos = self.cur.to;
            self.c = self.cur.c1;
            self.v = v;
            return true;
        }
    }

    /// The period crosses the head move's end with `ds` mm of its travel
    /// left: with none (but a rounding residue), its motion ends on the
    /// corner and it ran the head move, whatever zero-length moves it
    /// crosses after it; with some, it runs on into the next.
    fn ran_to_corner(&mut self, ds: f64) {
        if ds > 1e-12 {
            self.ran = None;
        } else if self.ran.is_none() {
            self.ran = Some(self.tag);
        }
    }

    /// The path speed is 0: a skip move the signal ended finishes where
    /// it stands; a feed hold holds.
    fn standing(&mut self) {
        if self.skip_hit.is_some() {
            // The skip signal ended the move: the next block starts here.
            self.report_skip();
            self.q.set_tail(self.pos);
            self.finish_item();
        } else if self.holding() {
            self.state = RunState::Held;
        }
    }

    /// A skip move ends where the axes stand: where the signal came (if
    /// it came) and where they stopped, for the host.
    fn report_skip(&mut self) {
        self.skip_report = Some(SkipReport {
            hit: self.skip_hit,
            stop: self.pos,
            shift: self.cur.shift,
        });
    }

    /// One period of a feed with jerk limiting in a plane: the profile
    /// runs to the end point (each feed ends in a stop there), the set
    /// point follows its moving average along the path.
    fn smoothed_path(&mut self, v: f64) {
        let len = self.cur.len;
        let mut s = self.s + v * self.dt;
        if s >= len - 1e-12 {
            s = len;
        }
        self.s = s;
        self.v = v;
        let sf = self.smooth.push(V2::new(s, 0.0)).r;
        let ds = sf - self.s_out;
        self.s_out = sf;
        self.lam = self.cur.curve.advance(self.lam, sf, ds, len);
        self.pos = self.cur.curve.point(self.lam);
        self.c = self.cur.c_at(self.lam);
        let still = v == 0.0 && self.smooth.settled();
        if s == len && still {
            self.pos = self.cur.to;
            self.c = self.cur.c1;
            if let MoveKind::Skip(_) = self.cur.kind {
                self.report_skip();
            }
            self.finish_item();
        } else if still && self.skip_hit.is_some() {
            self.report_skip();
            self.q.set_tail(self.pos);
            self.finish_item();
        } else if still && self.holding() {
            self.state = RunState::Held;
        }
    }

    /// The averages of a feed's set points stand on their last point.
    fn feed_avg_settled(&self) -> bool {
        self.feed_avg.settled() && self.feed_avg_c.settled()
    }

    /// Every moving average of jerk limiting stands on its last point.
    fn averages_settled(&self) -> bool {
        self.smooth.settled()
            && self.rapid_avg.settled()
            && self.rapid_avg_c.settled()
            && self.feed_avg_settled()
    }

    /// A reset in progress: brake, then drop everything (in a period
    /// where the axes stand: one whose step settled the averages of jerk
    /// limiting still moved them).
    fn reset_step(&mut self) {
        let averaging = self.jerk && self.started && !self.averages_settled();
        let moving = self.v > 0.0
            || self.rapid_v != [0.0; 3]
            || matches!(self.thread.phase, Phase::Ramp | Phase::Locked)
            || averaging;
        if moving && self.started {
            if self.q.seg(0).is_some() {
                match self.cur.kind {
                    _ if self.axis_rapid() => self.step_rapid(),
                    MoveKind::Thread(_) => self.step_thread(),
                    _ => self.step_path(),
                }
            }
            let busy = self.v > 0.0
                || self.rapid_v != [0.0; 3]
                || averaging
                || (self.jerk && !self.averages_settled());
            if busy && self.started {
                return;
            }
        }
        self.spindle.reset();
        self.alarm = None;
        self.run_dropped();
        self.reset_req = false;
        self.cycle_start |= core::mem::take(&mut self.start_after_reset);
    }

    /// The end of MDI blocks: idle at once where the axes stand, the
    /// spindle and coolant as the blocks left them; reported as a reset
    /// is, so the program comes back at its start from here.
    fn back_from_mdi(&mut self) {
        self.run_dropped();
    }

    /// What a reset drops, the spindle aside: the queue, the motion's
    /// state, a plane's mapping; the engine is idle and says so.
    fn run_dropped(&mut self) {
        self.q.clear();
        if let Some(run) = self.plane.take() {
            // A reset ends polar and cylindrical interpolation: the point
            // is the axes' again.
            self.switched = true;
            self.pos = run.axes();
            self.c = run.c();
            self.smooth.reset(self.pos);
            self.rapid_avg.reset(self.pos);
            self.rapid_avg_c.reset(V2::new(self.c, 0.0));
        }
        if let Some((axes, c)) = self.lock.release() {
            // Machine lock held the axes: the point is theirs again.
            self.switched = true;
            (self.pos, self.out, self.c) = (axes, axes, c);
            self.follow.snap(axes);
        }
        self.q.set_tail(self.pos);
        self.q.set_tail_c(self.c);
        self.started = false;
        self.thread = ThreadRun::OFF;
        self.hold = false;
        self.v = 0.0;
        self.rapid_v = [0.0; 3];
        self.skip_hit = None;
        self.fixed_work = None;
        // Reset is power-on for group 09: G23.
        self.stroke = None;
        self.state = RunState::Idle;
        self.manual = false;
        self.tag.active = self.power_on_codes;
        self.reset_done = true;
        self.rewind = false;
    }
}
