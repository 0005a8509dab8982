//! The look-ahead planner: a bounded queue of what the program asked for,
//! and for every move the speed envelope the interpolator must stay under.
//!
//! The planner computes, per move, a hard speed cap (axis and path feed
//! limits, curvature, F at the highest override), the speed at which the
//! move may run into the next one (the corner speed: 0 for an exact stop)
//! and, by a backward pass, the highest speed at its end from which every
//! later point the queue knows can still be met — the last move in the
//! queue always ends in a stop. Acceleration *forwards* is not planned:
//! the interpolator accelerates in real time at the move's acceleration
//! towards the commanded feed (overrides and the spindle speed change it
//! at any moment) and only has to stay under the envelope, which does not
//! depend on either.
//!
//! Adding a move raises the exit speeds of the moves before it; the pass
//! stops at the first move whose exit does not change, and a move's exit
//! can only rise while it is within braking distance of the end of the
//! queue, so a push costs O(1) amortised (O(braking distance / segment
//! length) at worst, independent of the queue length).
//!
//! The C axis (a machine with `[axes.c]`): a line or rapid may turn C
//! from `c0` to `c1` degrees. A feed that turns C runs along the combined
//! vector with the degrees counted as mm, as Fanuc feeds a linear + rotary
//! G01: its path length is √(ΔXZ² + ΔC²) and F is the speed along it, so
//! a C-only G01 turns at F deg/min. C follows the path parameter in
//! proportion and arrives with X/Z; the caps and the acceleration of the
//! move take C's max feed and acceleration along that vector as they do
//! the linear axes'. A move that turns C ends in a stop (no G64 blending:
//! the corner rule knows only the XZ plane). A rapid turns C at its own
//! rapid rate, like every axis of a G00.

use crate::command::{Command, Ending, Feed, Move, MoveKind, PauseKind, Tag};
use crate::config::Config;
use crate::geom::Curve;
use crate::math::{sqrt, PI, V2};
use crate::plc::PlcFunction;
use crate::polar::PlaneMap;
use crate::profile::brake_limit_above;
use alloc::vec::Vec;
use nc::error::Alarm;
use nc::geom::Element;
use nc::thread_room::z_is_long;

/// A move ready for interpolation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Rapid, feed, skip, thread …
    pub kind: MoveKind,
    /// The exact curve.
    pub curve: Curve,
    /// Start (machine axes, slide units).
    pub from: V2,
    /// End.
    pub to: V2,
    /// The third coordinate at both ends (equal when it stays): C's angle
    /// in degrees; in a plane, where C follows the plane point, the axis
    /// outside the plane that a straight move takes along (polar Z,
    /// cylinder X as a radius, work coordinates, mm: `PlaneMap::held`).
    pub c0: f64,
    /// ... and at the end.
    pub c1: f64,
    /// Path length: XZ, or the combined XZ + C vector when C turns.
    pub len: f64,
    /// Machine axes minus the programmed point.
    pub shift: V2,
    /// Hard path speed cap, mm/s.
    pub v_max: f64,
    /// Path acceleration for speed changes, mm/s².
    pub a: f64,
    /// `a` is `a_scale · (1 − f_n − max(c_in, c_out))`: the share of the
    /// centripetal acceleration at `v_max` (curves) and of the corner
    /// velocity steps at both ends are kept back.
    a_scale: f64,
    f_n: f64,
    c_in: f64,
    c_out: f64,
    /// Jerk limiting: the velocity step of the G64 corner the move starts
    /// with (in seconds of its axes' accelerations, see `join`), and the
    /// corner's speed cap (0: the move starts from a stop, where the
    /// averages settle; `steps_before`).
    step_in: f64,
    v_in: f64,
    /// The speed at which the move may run into the next one; 0 = stop.
    pub v_junction: f64,
    /// Planned limit at the end of the move (≤ `v_junction`).
    pub v_exit: f64,
    /// Unit tangents at both ends.
    pub t0: V2,
    /// ... at the end.
    pub t1: V2,
    /// Threads: Z is the long axis, and the long axis's travel.
    pub long_z: bool,
    /// ... and the long axis's travel.
    pub long_len: f64,
    /// Estimated duration at 100 % (for the look-ahead horizon).
    pub est_s: f64,
    /// The move leaves the axes' travel (soft limits, E7002): the move
    /// before it stops at its start, where the interpolator raises the
    /// alarm.
    pub outside: bool,
}

impl Segment {
    /// Whether the move turns the C axis (in a plane: moves the axis
    /// outside it).
    pub fn turns_c(&self) -> bool {
        self.c1 != self.c0
    }

    /// How far the third coordinate moves a mm of the path.
    fn c_rate(&self) -> f64 {
        (self.c1 - self.c0) / self.len
    }

    /// The third coordinate at path parameter λ (0…1): in proportion,
    /// exactly `c1` at the end.
    pub fn c_at(&self, lam: f64) -> f64 {
        if lam >= 1.0 {
            self.c1
        } else {
            self.c0 + (self.c1 - self.c0) * lam
        }
    }

    /// The path speed on this move that runs the long axis as fast as a
    /// path speed of 1 on `next`, where both are legs of a thread chain
    /// (1 elsewhere). A chain's long axis keeps its speed (lead × spindle
    /// speed) through a corner while its path speed jumps: a 45° leg runs
    /// √2 times as fast along its path as the Z leg after it. Speeds,
    /// distances and accelerations of `next` times this are the same
    /// motion of the long axis seen from this move, so braking is planned
    /// along the chain as one move.
    pub fn chain_scale(&self, next: &Segment) -> f64 {
        let share = |s: &Segment| {
            if s.len > 0.0 && s.long_len > 0.0 {
                s.long_len / s.len
            } else {
                1.0
            }
        };
        match (self.kind, next.kind) {
            (MoveKind::Thread(_), MoveKind::Thread(_)) => share(next) / share(self),
            _ => 1.0,
        }
    }

    /// A placeholder (no move).
    pub const IDLE: Segment = Segment {
        kind: MoveKind::Rapid,
        curve: Curve::Line {
            p0: V2::ZERO,
            d: V2::ZERO,
        },
        from: V2::ZERO,
        to: V2::ZERO,
        c0: 0.0,
        c1: 0.0,
        len: 0.0,
        shift: V2::ZERO,
        v_max: 0.0,
        a: 0.0,
        a_scale: 0.0,
        f_n: 0.0,
        c_in: 0.0,
        c_out: 0.0,
        step_in: 0.0,
        v_in: 0.0,
        v_junction: 0.0,
        v_exit: 0.0,
        t0: V2::ZERO,
        t1: V2::ZERO,
        long_z: true,
        long_len: 0.0,
        est_s: 0.0,
        outside: false,
    };
}

/// Items live by value in the preallocated ring (no box, no allocation
/// per period), so the move variant's size is the price of the queue.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ItemKind {
    /// A move.
    Move(Segment),
    /// G04: seconds.
    Dwell(f64),
    /// An M, S or T function for the PLC.
    Plc(PlcFunction),
    /// A stop: M00, M01, a message, single block.
    Pause(PauseKind),
    /// G22/G23: the area the axes may not enter from here on.
    Stroke(Option<nc::stroke::Area>),
    /// Polar or cylindrical interpolation on or off (polar.rs).
    Plane(crate::polar::PlaneSwitch),
    /// The program ends.
    End(Ending),
    /// The program raised an alarm (its code).
    Alarm(u32),
}

#[derive(Debug, Clone, Copy, PartialEq)]
/// One queue entry with its source place.
pub struct Item {
    /// What it is.
    pub kind: ItemKind,
    /// Where it comes from.
    pub tag: Tag,
    /// Machine axes minus the programmed point while this item runs.
    pub shift: V2,
}

impl Item {
    /// The move, if the item is one.
    pub fn segment(&self) -> Option<&Segment> {
        match &self.kind {
            ItemKind::Move(s) => Some(s),
            _ => None,
        }
    }
}

/// The queue is full: push again after the interpolator has consumed some.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Full;

/// What a push did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pushed {
    /// Queued.
    Queued,
    /// A move of zero length: nothing to do.
    Empty,
}

/// The look-ahead queue: commands in, planned speed envelopes out; allocated once.
pub struct Planner {
    items: Vec<Item>,
    head: usize,
    len: usize,
    dt: f64,
    ax: [f64; 2],
    /// 1/acceleration and 1/max feed of each axis (divisions are the
    /// slow part of a push).
    iax: [f64; 2],
    ivfeed: [f64; 2],
    vfeed: [f64; 2],
    vrapid: [f64; 2],
    /// The C axis, if the machine has one (deg/s, deg/s²).
    c_axis: Option<crate::config::Axis>,
    /// X and Z (for the axis outside a plane).
    axes: [crate::config::Axis; 2],
    path_max: f64,
    budget: f64,
    /// G64 blends within this (machine.resolution_mm).
    tolerance: f64,
    exact_stop: bool,
    /// Jerk limiting is on. In a plane feeds stop between blocks there
    /// (the joints' map is not linear: the interpolator averages the path
    /// parameter of each move on its own).
    jerk: bool,
    /// X's and Z's jerk, mm/s³, and the window a plane's path parameter
    /// is averaged over, s (used only with jerk limiting).
    jerks: [f64; 2],
    jerk_window: f64,
    /// With jerk limiting, feeds outside a plane are averaged after
    /// interpolation: what that asks of them (see [`FeedSmoothing`]).
    smoothing: Option<FeedSmoothing>,
    /// End of the last queued move (machine axes, slide units), and its
    /// C angle.
    tail: V2,
    tail_c: f64,
    shift: V2,
    /// rpm used to estimate feed-per-revolution durations.
    rpm_hint: f64,
    css_hint: Option<f64>,
    queued_s: f64,
    queued_moves: usize,
    /// Moves queued since the last backward pass.
    pending: usize,
    /// Dry run: feeds queued now may run up to the path limit, whatever
    /// their F (the interpolator sets their speed).
    dry_run: bool,
    /// Polar or cylindrical interpolation for the moves queued now, and
    /// the machine axes' shift from its joints.
    plane: Option<PlaneMap>,
    plane_shift: V2,
    /// The soft limits of X (a radius) and Z, machine coordinates.
    travel: [Option<(f64, f64)>; 2],
}

const PLACEHOLDER: Item = Item {
    kind: ItemKind::End(Ending::Stop),
    tag: Tag {
        file: 0,
        line: 0,
        col: 0,
        block: 0,
        block_end: false,
        no_hold: false,
        no_fin: false,
        active: nc::ActiveCodes::NONE,
    },
    shift: V2::ZERO,
};

/// Moves queued between two backward passes at most. One pass per batch
/// instead of one per move: a move that has not been through a pass yet
/// ends in a stop, which is a valid (if slow) envelope, so the batch only
/// delays speed that the interpolator would not reach before the pass.
pub const REPLAN_BATCH: usize = 32;

/// Moves `Planner::steps_before` follows back at most.
const STEP_WALK: usize = 256;

/// Highest feed override: the envelope must allow it.
const MAX_OVERRIDE: f64 = 1.5;

/// Feeds under jerk limiting (outside a plane): the interpolator runs
/// them as without it, blending at G64 corners, and averages each axis's
/// set points twice in a row, over T and then T₂ (config.rs `feed_taps`
/// and `feed_spread_taps`, smooth.rs `Cascade`). The pair keeps every
/// axis within the speed it is given, and bounds its acceleration by
/// W/T₂ and its jerk by 2·W/(T·T₂), W the largest change of the axis's
/// unaveraged speed over T₂. Feeds plan with accelerations of at most
/// a = j·T/2, which alone give W ≤ a·T₂; they keep a share of it back
/// (`Config::corner_budget`) for the velocity steps of the G64 corners,
/// which the corners within any T₂ share (`Planner::steps_before`). What
/// the averages cost is the path: they cut a corner and the inside of a
/// curve, which the speed caps here keep within half the resolution.
#[derive(Debug, Clone, Copy)]
struct FeedSmoothing {
    /// T and T₂, s.
    window: f64,
    spread: f64,
    /// The axes' feed accelerations and their inverses.
    ax: [f64; 2],
    iax: [f64; 2],
    /// C's feed acceleration, deg/s².
    c_accel: f64,
    /// What the averages may cut, mm: half the resolution.
    tol: f64,
}

impl FeedSmoothing {
    fn new(cfg: &Config) -> Option<FeedSmoothing> {
        if cfg.jerk_taps() <= 1 {
            return None;
        }
        let ax = [cfg.feed_accel(&cfg.x), cfg.feed_accel(&cfg.z)];
        Some(FeedSmoothing {
            window: cfg.feed_taps() as f64 * cfg.period_s,
            spread: cfg.feed_spread_taps() as f64 * cfg.period_s,
            ax,
            iax: ax.map(|a| 1.0 / a),
            c_accel: cfg.c.map_or(0.0, |c| cfg.feed_accel(&c)),
            tol: 0.5 * cfg.resolution_mm.max(1e-6),
        })
    }

    /// T² + T₂²: twelve times the variance of the averages' weights over
    /// time (a box of T, then one of T₂).
    fn spread2(&self) -> f64 {
        self.window * self.window + self.spread * self.spread
    }

    /// The speed cap on a curve of radius `r`: the weighted mean of
    /// points a path length v·t apart on a circle lies v²·σ²/2R inside
    /// it, σ² the weights' variance: v²·(T² + T₂²)/24R.
    fn curve_speed(&self, r: f64) -> f64 {
        sqrt(24.0 * r * self.tol / self.spread2())
    }

    /// The corner speed where the direction changes by `du` (|Δu|)
    /// between moves whose shorter one is `short` long. The averages of a
    /// path through a corner at speed v pass v·m₁·|Δu| from it, m₁ the
    /// weights' mean distance from their middle on one side, T/8 +
    /// T₂²/24T (T/8 for one box of T); braking into the corner and
    /// accelerating out of it at a adds a·m₂/2·|Δu|, m₂ = (T² + T₂²)/24
    /// the weights' second moment on one side. Where the moves are
    /// shorter than the window, their corners add up to a curve of
    /// radius `short`/|Δu|.
    fn corner_speed(&self, du: f64, short: f64) -> f64 {
        if du <= 1e-15 {
            return f64::INFINITY;
        }
        let t = self.window;
        let a = self.ax[0].max(self.ax[1]);
        let m1 = t / 8.0 + self.spread * self.spread / (24.0 * t);
        let corner = (self.tol / du - a * self.spread2() / 48.0) / m1;
        corner.max(0.0).min(self.curve_speed(short / du))
    }
}

/// What caps a segment's speed and acceleration, whatever its kind.
struct Limits {
    /// The path speed cap, mm/s.
    cap: f64,
    /// The acceleration along a line's direction.
    a_line: f64,
    /// The smaller axis acceleration.
    amin: f64,
    /// The curve's smallest radius (infinite for a line).
    rmin: f64,
    is_line: bool,
    /// The axis of the third coordinate (C, or in a plane the axis
    /// outside it), when the move moves it.
    c: Option<crate::config::Axis>,
}

impl Planner {
    /// A queue for these settings (its only allocation).
    pub fn new(cfg: &Config) -> Planner {
        let cap = cfg.queue_capacity.max(cfg.lookahead_blocks).max(2);
        let mut items = Vec::with_capacity(cap);
        items.resize(cap, PLACEHOLDER);
        Planner {
            items,
            head: 0,
            len: 0,
            dt: cfg.period_s,
            ax: [cfg.x.accel, cfg.z.accel],
            iax: [1.0 / cfg.x.accel, 1.0 / cfg.z.accel],
            ivfeed: [1.0 / cfg.x.max_feed, 1.0 / cfg.z.max_feed],
            vfeed: [cfg.x.max_feed, cfg.z.max_feed],
            vrapid: [cfg.x.rapid, cfg.z.rapid],
            c_axis: cfg.c,
            axes: [cfg.x, cfg.z],
            path_max: cfg.path_max_feed,
            budget: cfg.corner_budget.clamp(0.0, 0.5),
            tolerance: cfg.resolution_mm.max(1e-6),
            exact_stop: cfg.always_exact_stop,
            jerk: cfg.jerk_taps() > 1,
            jerks: [cfg.x.jerk, cfg.z.jerk],
            jerk_window: cfg.jerk_taps() as f64 * cfg.period_s,
            smoothing: FeedSmoothing::new(cfg),
            tail: V2::ZERO,
            tail_c: 0.0,
            shift: V2::ZERO,
            rpm_hint: 0.0,
            css_hint: None,
            queued_s: 0.0,
            queued_moves: 0,
            pending: 0,
            dry_run: cfg.dry_run,
            plane: None,
            plane_shift: V2::ZERO,
            travel: [&cfg.x, &cfg.z].map(|a| a.travel()),
        }
    }

    /// Dry run on or off for the feeds queued from now on: on, a feed is
    /// planned for the path limit instead of its F, so the interpolator
    /// may run it at the dry-run rate; moves queued before keep the
    /// envelope of their F.
    pub fn set_dry_run(&mut self, on: bool) {
        self.dry_run = on;
    }

    /// Items the queue can hold.
    pub fn capacity(&self) -> usize {
        self.items.len()
    }

    /// Items queued.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Nothing is queued.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// No room for another item.
    pub fn is_full(&self) -> bool {
        self.len == self.items.len()
    }

    /// Moves queued and their estimated duration at 100 %.
    pub fn horizon(&self) -> (usize, f64) {
        (self.queued_moves, self.queued_s)
    }

    fn slot(&self, k: usize) -> usize {
        let i = self.head + k;
        if i >= self.items.len() {
            i - self.items.len()
        } else {
            i
        }
    }

    /// The k-th item from the head.
    pub fn get(&self, k: usize) -> Option<&Item> {
        (k < self.len).then(|| &self.items[self.slot(k)])
    }

    /// The k-th queued item, mutable.
    pub fn get_mut(&mut self, k: usize) -> Option<&mut Item> {
        if k < self.len {
            let i = self.slot(k);
            Some(&mut self.items[i])
        } else {
            None
        }
    }

    /// The k-th item's move, if it is one.
    pub fn seg(&self, k: usize) -> Option<&Segment> {
        self.get(k).and_then(Item::segment)
    }

    /// Drops the head (the interpolator is done with it).
    pub fn pop(&mut self) {
        if self.len == 0 {
            return;
        }
        if let ItemKind::Move(s) = &self.items[self.head].kind {
            self.queued_s = (self.queued_s - s.est_s).max(0.0);
            self.queued_moves -= 1;
        }
        self.head = self.slot(1);
        self.len -= 1;
        if self.len == 0 {
            self.queued_s = 0.0;
        }
    }

    /// Drops everything queued (reset).
    pub fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
        // A reset ends a plane (interpolate.rs).
        self.plane = None;
        self.queued_s = 0.0;
        self.queued_moves = 0;
    }

    /// Where the next move starts.
    pub fn tail(&self) -> V2 {
        self.tail
    }

    /// After a skip or a reset the axes stand somewhere else than planned.
    pub fn set_tail(&mut self, p: V2) {
        self.tail = p;
    }

    /// Where the last queued move leaves C, degrees.
    pub fn tail_c(&self) -> f64 {
        self.tail_c
    }

    /// After a reset C stands somewhere else than planned.
    pub fn set_tail_c(&mut self, c: f64) {
        self.tail_c = c;
    }

    /// The shift (machine axes minus programmed point) that items queued now get.
    pub fn shift(&self) -> V2 {
        self.shift
    }

    /// Sets the shift items queued from now on get: the power-on work
    /// zero, or the one a restarted run begins with (until a move or an
    /// origin change sets another).
    pub fn set_shift(&mut self, shift: V2) {
        self.shift = shift;
    }

    /// Marks the last queued item as the end of an NC block.
    pub fn mark_block_end(&mut self, block: u32) {
        if let Some(k) = self.len.checked_sub(1) {
            if let Some(it) = self.get_mut(k) {
                if it.tag.block == block {
                    it.tag.block_end = true;
                }
            }
        }
    }

    /// Queues one command. Allocates nothing.
    pub fn push(&mut self, cmd: Command, tag: Tag) -> Result<Pushed, Full> {
        let Some(kind) = self.item_of(cmd) else {
            return Ok(Pushed::Empty);
        };
        if self.is_full() {
            return Err(Full);
        }
        let shift = match &kind {
            ItemKind::Move(s) => s.shift,
            _ => self.shift,
        };
        let i = self.slot(self.len);
        self.items[i] = Item { kind, tag, shift };
        self.len += 1;
        if let ItemKind::Move(s) = &self.items[i].kind {
            self.queued_s += s.est_s;
            self.queued_moves += 1;
            self.tail = s.to;
            self.tail_c = s.c1;
            self.shift = s.shift;
            self.join();
        } else {
            self.release_corner(self.len - 1);
        }
        self.pending += 1;
        if self.pending >= REPLAN_BATCH {
            self.replan();
        }
        Ok(Pushed::Queued)
    }

    /// The queue item of a command, taking what it sets (a shift, the
    /// plane, the spindle hints); `None` when it queues nothing. A command
    /// the full queue refuses is pushed again: what it sets is the same.
    fn item_of(&mut self, cmd: Command) -> Option<ItemKind> {
        Some(match cmd {
            Command::Shift(s) => {
                self.shift = s;
                return None;
            }
            Command::Move(m) => match self.curve(&m) {
                Ok(curve) => match self.segment(&m, curve) {
                    Some(seg) => ItemKind::Move(seg),
                    None => {
                        self.tail = m.path.to();
                        return None;
                    }
                },
                // A conic that cannot be drawn is an alarm at its line,
                // never a chord in its place.
                Err(code) => ItemKind::Alarm(code),
            },
            Command::Dwell(s) => ItemKind::Dwell(s),
            // A zero dwell: the moves on both sides cannot join, so the
            // one before ends at rest.
            Command::ExactStop => ItemKind::Dwell(0.0),
            Command::Plc(f) => {
                self.speed_hint(&f);
                ItemKind::Plc(f)
            }
            Command::Pause(p) => ItemKind::Pause(p),
            Command::Stroke(a) => ItemKind::Stroke(a),
            Command::Plane(sw) => {
                // Moves from here on start in the new coordinates
                // (plane points have no shift: polar.rs) and follow the
                // plane's caps.
                self.plane = sw.map;
                self.plane_shift = sw.shift;
                self.tail = sw.at;
                self.tail_c = sw.third();
                self.shift = if sw.map.is_some() { V2::ZERO } else { sw.shift };
                ItemKind::Plane(sw)
            }
            Command::End(e) => ItemKind::End(e),
            Command::Alarm(c) => ItemKind::Alarm(c),
        })
    }

    /// The spindle speed the moves queued after an S word will see.
    fn speed_hint(&mut self, f: &PlcFunction) {
        if let PlcFunction::Speed { s, css, .. } = *f {
            if css {
                self.css_hint = Some(s);
            } else {
                self.css_hint = None;
                self.rpm_hint = s;
            }
        }
    }

    /// The exact curve of a move from the current tail; the alarm code
    /// (E4005, E4006) of an ellipse or parabola that does not join its
    /// end points (the kernel has checked it, so only a crafted module
    /// gets here).
    fn curve(&self, m: &Move) -> Result<Curve, u32> {
        let from = self.tail;
        if !m.path.to().is_finite() {
            // (`segment` drops the move.)
            return Ok(Curve::line(from, m.path.to()));
        }
        Ok(match (m.kind, m.path) {
            (MoveKind::Rapid | MoveKind::Offset, _) => Curve::line(from, m.path.to()),
            (_, crate::command::Path::Line { to }) => Curve::of(Element::Line { from, to }),
            // An arc whose radius is below the resolution strays less than
            // two resolutions from its chord, and would turn the direction
            // within a period: it runs as its chord, its turn taken at the
            // corners at both ends.
            (_, crate::command::Path::Arc { to, centre, .. })
                if (from - centre).norm() < self.tolerance =>
            {
                Curve::line(from, to)
            }
            (_, crate::command::Path::Arc { to, centre, ccw }) => Curve::of(Element::Arc {
                from,
                to,
                centre,
                cw: !ccw,
            }),
            (_, crate::command::Path::Ellipse { to, a, b, q, ccw }) => {
                Curve::ellipse(from, to, a, b, q, ccw).ok_or(u32::from(Alarm::BadEllipse))?
            }
            (_, crate::command::Path::Parabola { to, p, q, ccw }) => {
                Curve::parabola(from, to, p, q, ccw).ok_or(u32::from(Alarm::BadParabola))?
            }
        })
    }

    /// Builds the segment of a move along `curve` from the current tail.
    fn segment(&self, m: &Move, curve: Curve) -> Option<Segment> {
        let (from, to) = (self.tail, m.path.to());
        if !to.is_finite() {
            return None;
        }
        let (c0, c1) = (self.tail_c, self.c_target(m));
        if !c1.is_finite() {
            return None;
        }
        let dc = c1 - c0;
        let len = if dc != 0.0 {
            sqrt(curve.length() * curve.length() + dc * dc)
        } else {
            curve.length()
        };
        if !crate::math::is_pos(len - 1e-9) {
            return None;
        }
        let (t0, t1) = match curve {
            Curve::Line { d, .. } => {
                let u = d * (1.0 / len);
                (u, u)
            }
            _ => curve.end_tangents(),
        };
        let mut seg = Segment {
            kind: m.kind,
            curve,
            from,
            to,
            c0,
            c1,
            len,
            shift: m.shift,
            v_max: 0.0,
            a: 0.0,
            a_scale: 0.0,
            f_n: 0.0,
            c_in: 0.0,
            c_out: 0.0,
            step_in: 0.0,
            v_in: 0.0,
            v_junction: 0.0,
            v_exit: 0.0,
            t0,
            t1,
            long_z: true,
            long_len: 0.0,
            est_s: 0.0,
            outside: false,
        };
        seg.outside = self.leaves_travel(&seg);
        let lim = self.limits(&seg, dc);
        match m.kind {
            // In a plane a G00 is a straight line of it at the rapid rate
            // (interpolate.rs, `axis_rapid`).
            MoveKind::Rapid if self.plane.is_some() => {
                let f = self.vrapid[0].min(self.vrapid[1]);
                self.feed_segment(
                    &mut seg,
                    &lim,
                    Feed {
                        f,
                        per_rev: false,
                        fixed: false,
                    },
                )
            }
            MoveKind::Rapid | MoveKind::Offset => self.rapid_segment(&mut seg, &lim, dc),
            MoveKind::Feed(f) | MoveKind::Skip(f) => self.feed_segment(&mut seg, &lim, f),
            MoveKind::Thread(t) => self.thread_segment(&mut seg, &lim, t),
        }
        seg.a = seg.a_scale * (1.0 - seg.f_n - seg.c_in.max(seg.c_out));
        if !crate::math::is_pos(seg.a) {
            seg.a = seg.a_scale * 0.25;
        }
        Some(seg)
    }

    /// Whether the move leaves the soft limits: its ends (a rapid of each
    /// axis on its own), or 17 points along it; in a plane, the joints'
    /// (polar.rs).
    fn leaves_travel(&self, seg: &Segment) -> bool {
        if self.travel == [None, None] {
            return false;
        }
        let axis_rapid = matches!(seg.kind, MoveKind::Rapid | MoveKind::Offset);
        let n = if axis_rapid && self.plane.is_none() {
            1
        } else {
            16
        };
        let outside = |v: f64, lim: Option<(f64, f64)>| {
            lim.is_some_and(|(lo, hi)| v < lo - 1e-9 || v > hi + 1e-9)
        };
        (0..=n).any(|i| {
            let lam = f64::from(i) / f64::from(n);
            let p = seg.curve.point(lam);
            let p = match self.plane {
                Some(map) => map.with_held(seg.c_at(lam)).joints(p).0 + self.plane_shift,
                None => p,
            };
            outside(p.r, self.travel[0]) || outside(p.z, self.travel[1])
        })
    }

    /// The hard caps of a segment's path (`dc`: the third coordinate's move).
    fn limits(&self, seg: &Segment, dc: f64) -> Limits {
        let (curve, len) = (seg.curve, seg.len);
        let smoothing = self.smoothing_of(seg.kind);
        let (ax, iax) = smoothing.map_or((self.ax, self.iax), |s| (s.ax, s.iax));
        let amin = ax[0].min(ax[1]);
        // Per-axis feed limits (a curve sweeps its direction, so both
        // count fully), the path limit, curvature.
        let is_line = matches!(curve, Curve::Line { .. });
        let dir = if is_line {
            seg.t0
        } else {
            (seg.to - seg.from).unit()
        };
        let (ur, uz) = (dir.r.abs(), dir.z.abs());
        // The third coordinate's share of the direction (only lines move
        // it): C's, or in a plane the axis's outside it.
        let third = match self.plane {
            None => self.c_axis,
            Some(PlaneMap::Polar { .. }) => Some(self.axes[1]),
            Some(PlaneMap::Cylinder { .. }) => Some(self.axes[0]),
        };
        let c = third.filter(|_| dc != 0.0);
        let uc = dc.abs() / len;
        let mut cap = if is_line {
            1.0 / (ur * self.ivfeed[0]).max(uz * self.ivfeed[1])
        } else {
            self.vfeed[0].min(self.vfeed[1])
        };
        if let Some(c) = &c {
            cap = cap.min(c.max_feed / uc);
        }
        // The path limit clamps a programmed F. A thread's speed is the
        // spindle's (lead × rpm), bound only by each axis's feed, as its
        // start checks (E4010): clamping a 45° pull-out to the path limit
        // would pull the chain out of step with the spindle.
        if !matches!(seg.kind, MoveKind::Thread(_)) {
            cap = cap.min(self.path_max);
        }
        let rmin = curve.min_radius();
        if rmin.is_finite() {
            // Half of the smaller acceleration for the centripetal part,
            // and chords between set points within the tolerance of the
            // curve (sagitta ℓ²/8R).
            cap = cap.min(sqrt(0.5 * amin * rmin));
            cap = cap.min(sqrt(8.0 * rmin * self.tolerance) / self.dt);
            if let Some(s) = smoothing {
                cap = cap.min(s.curve_speed(rmin));
            }
        }
        // Line acceleration: the moving axes' limits along the direction.
        let mut a_line = 1.0 / (ur * iax[0]).max(uz * iax[1]);
        if let Some(c) = &c {
            let a = smoothing.map_or(c.accel, |s| s.c_accel);
            a_line = a_line.min(a / uc);
        }
        let mut lim = Limits {
            cap,
            a_line,
            amin,
            rmin,
            is_line,
            c,
        };
        if let Some(map) = self.plane {
            self.plane_limits(map, seg, &mut lim);
        }
        lim
    }

    /// The joints' caps while a plane is on: the queue holds plane points
    /// (polar.rs), whose speed and acceleration the joints turn into
    /// their own, which must stay within their limits.
    fn plane_limits(&self, map: PlaneMap, seg: &Segment, lim: &mut Limits) {
        let Some(c) = self.c_axis else {
            return;
        };
        // A G00 in the plane moves the joints at up to their rapid rates.
        let rapid = matches!(seg.kind, MoveKind::Rapid);
        let (w, vfeed) = match rapid {
            true => (c.rapid.to_radians(), self.vrapid),
            false => (c.max_feed.to_radians(), self.vfeed),
        };
        let alpha = c.accel.to_radians();
        // A curve sweeps its direction: each axis may take all of it.
        let dir = |u: f64| if lim.is_line { u.abs() } else { 1.0 };
        match map {
            PlaneMap::Cylinder { radius, .. } => {
                // The first axis (`z`) is C developed on the cylinder, the
                // second (`r`) is Z.
                let (us, uz) = (dir(seg.t0.z), dir(seg.t0.r));
                let axes = [(w * radius, alpha * radius, us), (vfeed[1], self.ax[1], uz)];
                for (v, a, u) in axes {
                    if u > 0.0 {
                        lim.cap = lim.cap.min(v / u);
                        lim.a_line = lim.a_line.min(a / u);
                    }
                    lim.amin = lim.amin.min(a);
                }
            }
            PlaneMap::Polar { .. } => {
                // C is the angle of the plane point p (ρ = |p|): at path
                // speed v it turns at |p × t|·v/ρ², and its acceleration
                // is at most a·h/ρ² + v²(κ/ρ + 2h/ρ³) (t the direction,
                // h the curve's lever about the centre, a along the path,
                // κ the curvature): half of C's limit for each part, with
                // h/ρ² and the rest bounded over the piece (polar.rs
                // `CentreBounds`; translate.rs cuts a line or an arc that
                // passes near the centre). ρ at least the resolution: a
                // path through the centre is an alarm (nc plane.rs). X
                // is ρ: its speed at most v, its acceleration at most
                // a + v²κ + v²h²/ρ³: a quarter of X's limit for the last
                // part, the rest for the path's (and its curvature's).
                let b = crate::polar::CentreBounds::of(&seg.curve, self.tolerance);
                let mut cap = vfeed[0];
                let mut a = (0.75 * self.ax[0]).min(lim.amin);
                if b.turn > 0.0 {
                    cap = cap.min(w / b.turn);
                    cap = cap.min(sqrt(0.25 * self.ax[0] / b.bend));
                    a = a.min(0.5 * alpha / b.turn);
                }
                cap = cap.min(sqrt(0.5 * alpha / b.spin));
                lim.cap = lim.cap.min(cap);
                lim.a_line = lim.a_line.min(a);
                lim.amin = lim.amin.min(a);
            }
        }
    }

    /// Under jerk limiting in a plane, the smaller jerk of the plane's two
    /// axes as the joints allow it (on the cylinder Z's and C's along its
    /// surface; in the polar plane X's and C's at the move's least
    /// distance from the centre); `None` otherwise.
    fn plane_jerk(&self, seg: &Segment) -> Option<f64> {
        let (map, c) = (self.plane?, self.c_axis?);
        if !self.jerk {
            return None;
        }
        let jc = c.jerk.to_radians();
        Some(match map {
            PlaneMap::Cylinder { radius, .. } => self.jerks[1].min(jc * radius),
            PlaneMap::Polar { .. } => {
                let rho = seg.curve.min_distance_to(V2::ZERO).max(self.tolerance);
                self.jerks[0].min(jc * rho)
            }
        })
    }

    /// An arc of radius `rho` in a plane under jerk limiting, `j` the
    /// plane's jerk. Averaging the path parameter over the window T bounds
    /// the jerk along the path by 2·a/T (a the acceleration along it); the
    /// curvature κ = 1/ρ adds up to 3κ·v·a + κ²·v³ to an axis's (the
    /// normal's κ·v² changing, and the direction turning). So the speed
    /// is at most ∛(j·ρ²/2), which leaves half of `j` at least, and a ≤
    /// (j − κ²·v³)/(2/T + 3κ·v), v the move's top speed: the larger the
    /// arc, the less it takes (on a cylinder of radius 10 at 7.5 mm/s, an
    /// arc of 50 mm keeps 96 % of C's acceleration there, one of 5 mm 69
    /// %). (Without it a 0.5 mm arc there took C to 100.4 % of its jerk.)
    /// An ellipse's or a parabola's curvature changes along it, by up to
    /// κ′ a mm (geom.rs, `max_curvature_rate`), which adds κ′·v³: it
    /// counts beside κ² (a flat ellipse at F3000 took X to 1.9 times its
    /// jerk without it).
    fn curve_jerk_limits(&self, seg: &mut Segment, rho: f64, j: f64) {
        if !crate::math::is_pos(rho) {
            return;
        }
        let k = 1.0 / rho;
        let bend = k * k + seg.curve.max_curvature_rate();
        seg.v_max = seg.v_max.min(libm::cbrt(0.5 * j / bend));
        let v = seg.v_max;
        let a = (j - bend * v * v * v) / (2.0 / self.jerk_window + 3.0 * k * v);
        seg.a_scale = seg.a_scale.min(a);
    }

    /// A rapid: each axis at its own rate, the path at the smaller
    /// acceleration.
    fn rapid_segment(&self, seg: &mut Segment, lim: &Limits, dc: f64) {
        let d = seg.to - seg.from;
        seg.v_max = f64::INFINITY;
        seg.a = lim.amin;
        seg.a_scale = lim.amin;
        seg.est_s = (d.r.abs() / self.vrapid[0]).max(d.z.abs() / self.vrapid[1]);
        if let Some(c) = &lim.c {
            seg.est_s = seg.est_s.max(dc.abs() / c.rapid);
        }
    }

    /// A feed (or a skip move): F up to the caps, with room for the
    /// override above it.
    fn feed_segment(&self, seg: &mut Segment, lim: &Limits, f: Feed) {
        let kind = seg.kind;
        let dry = self.dry_run && matches!(kind, MoveKind::Feed(_));
        let top = if f.per_rev || dry {
            lim.cap
        } else {
            let over = if let MoveKind::Skip(_) = kind {
                1.0
            } else {
                MAX_OVERRIDE
            };
            lim.cap.min(f.f * over)
        };
        seg.v_max = top.max(0.0);
        if lim.is_line {
            seg.a_scale = lim.a_line;
        } else {
            seg.a_scale = lim.amin;
            if let Some(j) = self.plane_jerk(seg) {
                self.curve_jerk_limits(seg, lim.rmin, j);
            }
            seg.f_n = (seg.v_max * seg.v_max / (lim.rmin * lim.amin)).min(0.5);
        }
        // Keep the corner share at the end until the next move is known;
        // the real corner can only need less.
        let blends = lim.c.is_none() && !self.exact_stop && !(self.jerk && self.plane.is_some());
        seg.c_out = if matches!(kind, MoveKind::Feed(_)) && blends {
            self.budget
        } else {
            0.0
        };
        seg.est_s = seg.len / self.nominal(f, seg.to).min(seg.v_max).max(1e-3);
    }

    /// A thread: its long axis (the one the lead is along) and the caps.
    fn thread_segment(&self, seg: &mut Segment, lim: &Limits, t: crate::command::Thread) {
        let d = seg.to - seg.from;
        seg.long_z = z_is_long(d.r, d.z);
        let along = |p: V2| if seg.long_z { p.z.abs() } else { p.r.abs() };
        seg.long_len = match seg.curve {
            Curve::Arc { .. } => along(seg.curve.point(1.0) - seg.curve.point(0.0)),
            _ => along(d),
        };
        seg.v_max = lim.cap;
        seg.a_scale = if lim.is_line { lim.a_line } else { lim.amin };
        seg.f_n = if lim.is_line { 0.0 } else { 0.5 };
        let rps = self.rpm_hint.max(1.0) / 60.0;
        seg.est_s = seg.long_len / (t.lead.max(1e-6) * rps);
    }

    /// What the average after interpolation asks of a move of this kind
    /// queued now: feeds outside a plane, with jerk limiting.
    fn smoothing_of(&self, kind: MoveKind) -> Option<&FeedSmoothing> {
        match kind {
            MoveKind::Feed(_) | MoveKind::Skip(_) if self.plane.is_none() => {
                self.smoothing.as_ref()
            }
            _ => None,
        }
    }

    /// The C angle a move ends at: lines and rapids may turn C, nothing
    /// else does; without a C axis C stays at 0.
    fn c_target(&self, m: &Move) -> f64 {
        let line = matches!(m.path, crate::command::Path::Line { .. });
        match m.c {
            Some(c) if self.c_axis.is_some() && line && !matches!(m.kind, MoveKind::Thread(_)) => c,
            _ => self.tail_c,
        }
    }

    /// The feed at 100 %, mm/s, for the horizon estimate.
    fn nominal(&self, f: Feed, at: V2) -> f64 {
        if !f.per_rev {
            return f.f;
        }
        let rpm = match self.css_hint {
            Some(v) => {
                let x = (at - self.shift).x().abs().max(1.0);
                1000.0 * v / (PI * x)
            }
            None => self.rpm_hint,
        };
        f.f * rpm.min(3000.0) / 60.0
    }

    /// The item after move `k - 1` is not a move: that move ends in a stop
    /// and needs no corner share at its end.
    fn release_corner(&mut self, k: usize) {
        let Some(k) = k.checked_sub(1) else { return };
        let i = self.slot(k);
        if let ItemKind::Move(s) = &mut self.items[i].kind {
            if matches!(s.kind, MoveKind::Feed(_)) && s.c_out > 0.0 {
                s.c_out = 0.0;
                s.v_junction = 0.0;
                s.a = s.a.max(s.a_scale * (1.0 - s.f_n - s.c_in));
            }
        }
    }

    /// Whether two moves may blend (G64) at their junction.
    fn joinable(&self, a: &Segment, b: &Segment) -> bool {
        // A move that turns C stops at both ends; in a plane the pieces
        // of a move that takes the axis outside it along run on (the same
        // rate along the path; the tangents are checked below).
        let third = match self.plane {
            None => a.turns_c() || b.turns_c(),
            Some(_) => (a.c_rate() - b.c_rate()).abs() > 1e-9,
        };
        if third || b.outside {
            return false;
        }
        match (a.kind, b.kind) {
            // Consecutive thread blocks run on without a stop (§4.3).
            (MoveKind::Thread(_), MoveKind::Thread(_)) => true,
            // (In a plane a corner's step would be the joints' to take,
            // which the corner budget does not know: only the pieces of a
            // move and tangent joints run on.)
            (MoveKind::Feed(_), MoveKind::Feed(_)) => {
                !self.exact_stop
                    && match self.plane {
                        None => true,
                        Some(_) => !self.jerk && (b.t0 - a.t1).norm() < 1e-9,
                    }
            }
            // The pieces of a G00 in a plane (polar.rs `cuts`) run on,
            // straight through.
            (MoveKind::Rapid, MoveKind::Rapid) => {
                self.plane.is_some()
                    && !self.exact_stop
                    && !self.jerk
                    && (b.t0 - a.t1).norm() < 1e-9
            }
            _ => false,
        }
    }

    /// The new tail move was just queued: set the corner with the move
    /// before it.
    fn join(&mut self) {
        let n = self.len - 1;
        if n == 0 {
            return;
        }
        let (ip, it) = (self.slot(n - 1), self.slot(n));
        let (prev, cur) = match (&self.items[ip].kind, &self.items[it].kind) {
            (ItemKind::Move(p), ItemKind::Move(c)) => (p, c),
            // A non-move before: its own move (if any) ends in a stop.
            _ => return,
        };
        let corner = if !self.joinable(prev, cur) {
            Corner::default()
        } else if matches!(cur.kind, MoveKind::Thread(_)) {
            // A chain's speed along the path jumps at a corner (the lead
            // stays along the long axis, the short axes follow:
            // follow.rs): each leg's cap binds its own path speed, and
            // the joint lets the faster leg's through, seen from the move
            // before. (Their smaller one turned a 45° pull-out after a Z
            // thread at Z's top feed into a brake and broke the lead.)
            Corner {
                v: prev.v_max.max(cur.v_max * prev.chain_scale(cur)),
                ..Corner::default()
            }
        } else {
            self.feed_corner(prev, cur, n)
        };
        // Only ever raised: the interpolator may already run on them.
        let raise = |s: &mut Segment| {
            if !matches!(s.kind, MoveKind::Rapid | MoveKind::Offset) {
                let a = s.a_scale * (1.0 - s.f_n - s.c_in.max(s.c_out));
                s.a = s.a.max(a);
            }
        };
        if let ItemKind::Move(p) = &mut self.items[ip].kind {
            p.v_junction = corner.v;
            p.c_out = corner.out;
            raise(p);
        }
        if let ItemKind::Move(c) = &mut self.items[it].kind {
            c.c_in = corner.into;
            c.step_in = corner.step;
            c.v_in = corner.v;
            raise(c);
        }
    }

    /// The corner where two feed moves blend, `prev` ending move `n` − 1
    /// and `cur` move `n`.
    fn feed_corner(&self, prev: &Segment, cur: &Segment, n: usize) -> Corner {
        let du = cur.t0 - prev.t1;
        let smoothing = self.smoothing_of(cur.kind);
        let iax = match (smoothing, self.plane) {
            (Some(s), _) => s.iax,
            (None, Some(map)) => self.plane_iax(map, prev, cur),
            (None, None) => self.iax,
        };
        // The velocity step of the corner within its share of each axis's
        // acceleration ...
        let share = (du.r.abs() * iax[0]).max(du.z.abs() * iax[1]);
        // ... and the chord of the period through the corner off a
        // curve's tangent by half the angle v·dt/R the curve turns in it:
        // a velocity error up to v²·dt/2R, which the other move's period
        // takes (a curve of a few µm turns tens of degrees in a period;
        // the curve's own centripetal share covers its own periods).
        let bend = |c: &Curve| 0.5 * self.dt / c.min_radius() * iax[0].max(iax[1]);
        let (bend_prev, bend_cur) = (bend(&prev.curve), bend(&cur.curve));
        let turn = Turn {
            du: du.norm(),
            share,
            bend: bend_prev.max(bend_cur),
            short: prev.len.min(cur.len),
        };
        let vj = self
            .feed_corner_speed(smoothing, &turn, n)
            .min(prev.v_max.min(cur.v_max))
            .max(0.0);
        let mut corner = Corner {
            v: vj,
            out: (vj * share + vj * vj * bend_cur) / self.dt,
            into: (vj * share + vj * vj * bend_prev) / self.dt,
            step: vj * share + vj * vj * bend_prev.max(bend_cur),
        };
        if smoothing.is_some() && vj > 0.0 {
            // Under jerk limiting both moves keep the whole share back: a
            // window of T₂ may hold any of their periods and the corners
            // next to them (`spread_corner_speed`). (The averages settle
            // in a stop: a move that stops at both ends keeps nothing
            // back.)
            (corner.out, corner.into) = (self.budget, self.budget);
        } else if prev.len < vj * self.dt {
            // A period may run through the whole move before (a µm along
            // a tangent): what that move kept back for the corner before
            // it, this one keeps too.
            corner.into = corner.into.max(prev.c_in);
        }
        corner
    }

    /// `iax` for a joint of two moves in a plane (only tangent ones run
    /// on there): the inverse accelerations the plane's two axes may
    /// take, as `plane_limits` derives them from the joints. On the
    /// cylinder, Z's and C's on its surface; in the polar plane, the
    /// smaller of X's and C's at the moves' least distance from the
    /// centre, in every direction. (X's and Z's own, which the joint took
    /// before, let a period through a tangent joint onto a small arc take
    /// C past its limit.)
    fn plane_iax(&self, map: PlaneMap, prev: &Segment, cur: &Segment) -> [f64; 2] {
        let Some(c) = self.c_axis else {
            return self.iax;
        };
        let alpha = c.accel.to_radians();
        match map {
            // (`r` is Z, `z` is C developed.)
            PlaneMap::Cylinder { radius, .. } => [self.iax[1], 1.0 / (alpha * radius)],
            PlaneMap::Polar { .. } => {
                let near = |s: &Segment| s.curve.min_distance_to(V2::ZERO);
                let rho = near(prev).min(near(cur)).max(self.tolerance);
                let a = self.ax[0].min(alpha * rho);
                [1.0 / a, 1.0 / a]
            }
        }
    }

    /// The speed of a feed corner (`feed_corner`) at the end of move
    /// `n` − 1, not yet capped by the moves' own top speeds.
    fn feed_corner_speed(&self, smoothing: Option<&FeedSmoothing>, t: &Turn, n: usize) -> f64 {
        let Turn {
            du,
            share,
            bend,
            short,
        } = *t;
        let mut vj = match smoothing {
            Some(s) => self.spread_corner_speed(s, share, bend, short, n - 1),
            None => corner_speed(share, bend, self.budget * self.dt),
        };
        if share > 1e-18 {
            // A period runs through one such corner at most: it starts on
            // the move before and ends on the move after. (One that ran on
            // through a move of a µm would take the corner's step out of
            // the share of a move that did not keep it.)
            vj = vj.min(short / self.dt);
        }
        // ... and the chord of the period that runs through the corner
        // within the tolerance of it: (v·dt/2)·sin(θ/2), |Δu| = 2·sin(θ/2).
        if du > 1e-15 {
            vj = vj.min(4.0 * self.tolerance / (self.dt * du));
        }
        // ... and the averages after interpolation within their tolerance
        // of the corner.
        if let Some(s) = smoothing {
            vj = vj.min(s.corner_speed(du, short));
        }
        vj
    }

    /// Under jerk limiting: the speed of the corner at the end of move
    /// `k`, whose velocity step (`share`, `bend`: see `join`) the second
    /// average spreads over T₂. The steps of the corners that one such
    /// window may hold share what the moves keep back, `budget`·T₂. Those
    /// before this one are known (`steps_before`); at speed v on moves of
    /// `short`, up to v·T₂/`short` more may follow, so the corner takes no
    /// more than its share as if its neighbours were like it (one that
    /// took all that is left would stop the next).
    fn spread_corner_speed(
        &self,
        s: &FeedSmoothing,
        share: f64,
        bend: f64,
        short: f64,
        k: usize,
    ) -> f64 {
        let window = self.budget * s.spread;
        let left = (window - self.steps_before(k, s.spread + self.dt)).max(0.0);
        let neighbours = share * s.spread / short.max(1e-12);
        corner_speed(share, bend, left).min(corner_speed(share, bend + neighbours, window))
    }

    /// The velocity steps of the G64 corners before the one at the end of
    /// move `k` (`Segment::step_in`) that one window of the second average
    /// may hold together with it, under jerk limiting. A corner's step
    /// falls on the speed changes of the period it is crossed in and the
    /// one after, so two corners are in one window of T₂ only if the path
    /// between them takes less than `horizon`, T₂ + dt: it is then shorter
    /// than `horizon` times the fastest speed between them. On a move of ℓ
    /// that starts at v₀ at most and accelerates at a, that is at most
    /// √(v₀² + 2·a·ℓ), and where it also ends at v₁ at most (the moves
    /// before move `k`, whose corners are set and whose accelerations no
    /// longer change), √((v₀² + v₁²)/2 + a·ℓ). A move that starts from a
    /// stop ends the walk: the averages settle in a stop. ∞ when the walk
    /// is too long to follow (the corner then stops).
    fn steps_before(&self, k: usize, horizon: f64) -> f64 {
        let (mut dist, mut fastest, mut sum) = (0.0_f64, 0.0_f64, 0.0);
        let (first, mut k) = (k, k);
        for _ in 0..STEP_WALK {
            let Some(ItemKind::Move(m)) = self.get(k).map(|item| &item.kind) else {
                return sum;
            };
            dist += m.len;
            let top = match k == first {
                true => sqrt(m.v_in * m.v_in + 2.0 * m.a * m.len),
                false => sqrt(0.5 * (m.v_in * m.v_in + m.v_junction * m.v_junction) + m.a * m.len),
            };
            fastest = fastest.max(m.v_max.min(top));
            if m.v_in <= 0.0 || dist >= fastest * horizon {
                return sum;
            }
            sum += m.step_in;
            let Some(before) = k.checked_sub(1) else {
                return sum;
            };
            k = before;
        }
        f64::INFINITY
    }

    /// The backward pass over what was queued since the last one: each
    /// move's exit rises to what the move after it can still brake from;
    /// before the new items, the pass ends at the first move whose exit
    /// does not change. Callers that push one by one call it before the
    /// next period (the controller does at the end of `run_ahead`);
    /// `push` also runs it every [`REPLAN_BATCH`] items.
    pub fn replan(&mut self) {
        let dirty = core::mem::take(&mut self.pending);
        if self.len == 0 || dirty == 0 {
            return;
        }
        let first_dirty = self.len.saturating_sub(dirty);
        let cap = self.items.len();
        let dt = self.dt;
        // The move after the current one.
        let mut carry: Option<Segment> = None;
        let mut k = self.len - 1;
        let mut i = self.slot(k);
        loop {
            let settled = k < first_dirty;
            match &mut self.items[i].kind {
                ItemKind::Move(p) => {
                    let mut rose = false;
                    if let Some(n) = carry {
                        // At its corner speed already, nothing can rise.
                        if p.v_junction > 0.0 && p.v_exit < p.v_junction {
                            // (The exact limit only matters below it.)
                            let k = p.chain_scale(&n);
                            let (cl, ce, ca) = (n.len * k, n.v_exit * k, n.a * k);
                            let lim = brake_limit_above(cl, ce, ca, dt, p.v_junction);
                            let exit = p.v_junction.min(lim);
                            if exit > p.v_exit {
                                p.v_exit = exit;
                                rose = true;
                            }
                        }
                    }
                    if settled && !rose {
                        break;
                    }
                    carry = Some(*p);
                }
                _ => {
                    if settled {
                        break;
                    }
                    carry = None;
                }
            }
            if k == 0 {
                break;
            }
            k -= 1;
            i = if i == 0 { cap - 1 } else { i - 1 };
        }
    }
}

/// A corner's speed, and the shares of acceleration the two moves keep
/// back for it: the move before for the period through the corner
/// (`out`), the move after for the period after it (`into`); `step` is
/// its velocity step. All zero where the moves do not blend.
#[derive(Default)]
struct Corner {
    v: f64,
    out: f64,
    into: f64,
    step: f64,
}

/// How a feed corner turns (`Planner::feed_corner`): |Δu| between the
/// moves' directions, the share of acceleration its velocity step takes
/// at unit speed, the bend of the chords next to it (× v²), and the
/// shorter of the two moves.
#[derive(Clone, Copy)]
struct Turn {
    du: f64,
    share: f64,
    bend: f64,
    short: f64,
}

/// The highest corner speed v whose velocity step v·`share` + v²·`bend`
/// (in units of the axes' acceleration) stays within `budget`; ∞ for a
/// tangent joint of lines.
fn corner_speed(share: f64, bend: f64, budget: f64) -> f64 {
    if bend > 0.0 {
        // The root of bend·v² + share·v − budget, in the form that does
        // not cancel.
        2.0 * budget / (share + sqrt(share * share + 4.0 * bend * budget))
    } else if share > 1e-18 {
        budget / share
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn feeds_under_jerk_limiting_plan_for_the_average_after_interpolation() {
        // The reference machine with jerk limiting: J = 20 000 mm/s³ (X),
        // resolution 1 µm: T = ∛(24·0.001/20 000) = 10.63 ms, 11 periods,
        // then T₂ = 6 periods; feed accelerations X min(1500, 20 000 ·
        // 0.0055) = 110, Z min(2000, 25 000·0.0055) = 137.5 mm/s².
        let cfg = Config {
            jerk_limited: true,
            ..Config::default()
        };
        assert_eq!((cfg.feed_taps(), cfg.feed_spread_taps()), (11, 6));
        let s = FeedSmoothing::new(&cfg).unwrap();
        assert_eq!(s.ax, [110.0, 137.5]);
        // T² + T₂² = 0.000 121 + 0.000 036 = 0.000 157 s².
        // A curve of R 1: √(24·1·0.0005 / 0.000 157) = 8.742 60 mm/s.
        assert!((s.curve_speed(1.0) - 8.742_60).abs() < 1e-5);
        // A corner of |Δu| 0.01 between long moves: m₁ = 0.011/8 +
        // 0.006²/(24·0.011) = 0.001 511 36 s, braking 137.5·0.000 157/48
        // = 0.000 449 74 mm; (0.0005/0.01 − 0.000 449 74)/0.001 511 36
        // = 32.785 mm/s.
        assert!((s.corner_speed(0.01, 10.0) - 32.785).abs() < 1e-3);
        // ... between moves of 10 µm: the curve of R 1 they make.
        assert!((s.corner_speed(0.01, 0.01) - 8.742_60).abs() < 1e-5);
        // A corner whose braking term alone takes the tolerance (|Δu| >
        // 0.0005/0.000 449 74 = 1.112, a turn of more than 67°): a stop.
        assert_eq!(s.corner_speed(1.2, 10.0), 0.0);
        assert!(s.corner_speed(1.1, 10.0) > 0.0);
        // Without jerk limiting, no average.
        assert!(FeedSmoothing::new(&Config::default()).is_none());
        assert_eq!(Config::default().feed_taps(), 1);
        assert_eq!(Config::default().feed_spread_taps(), 1);
    }

    #[test]
    fn corners_within_the_second_window_share_it() {
        // Jerk limiting on the reference machine: the corners within T₂ =
        // 6 ms share 0.25·0.006 = 0.0015 s of their axes' acceleration.
        // F3000 along −Z, a 0.5° turn towards +X, 0.05 mm on, a 5° turn.
        let cfg = Config {
            jerk_limited: true,
            ..Config::default()
        };
        let mut p = Planner::new(&cfg);
        let deg = |a: f64| V2::new(a.to_radians().sin(), -a.to_radians().cos());
        let a = V2::new(0.0, -10.0);
        let b = a + deg(0.5) * 0.05;
        let c = b + deg(5.5) * 10.0;
        for to in [a, b, c] {
            p.push(feed(to, 50.0), Tag::default()).unwrap();
        }
        p.replan();
        let (s0, s1, s2) = (p.seg(0).unwrap(), p.seg(1).unwrap(), p.seg(2).unwrap());
        // The first corner's step, in seconds of X's 110 mm/s²: v·|Δu_x|
        // /110 = v·7.9332e-5. Up to v·T₂/0.05 corners like it may follow
        // in a window: v·7.9332e-5·(1 + 0.12·v) ≤ 0.0015, v = 9.0593 mm/s
        // (the cut allows 20.9 mm/s there; the curve the moves make).
        assert!((s0.v_junction - 9.0593).abs() < 1e-3, "{}", s0.v_junction);
        // The second is within the window (0.05 mm at most √(9.06² +
        // 2·103.13·0.05) = 9.61 mm/s takes 5.2 ms, less than T₂ + dt) and
        // takes what is left: (0.0015 − 9.0593·7.9332e-5)/7.9199e-4 =
        // 0.9865 mm/s (on its own 1.59 mm/s).
        assert!((s1.v_junction - 0.9865).abs() < 1e-3, "{}", s1.v_junction);
        assert!((s1.step_in + s2.step_in - 0.0015).abs() < 1e-9);
    }

    /// A batch pass gives the same envelope as a pass after every push.
    #[test]
    fn batched_and_single_passes_agree() {
        let cfg = Config::default();
        let (mut a, mut b) = (Planner::new(&cfg), Planner::new(&cfg));
        let mut r: f64 = 10.0;
        for i in 0..300 {
            r += if i % 7 == 0 { 0.3 } else { -0.02 };
            let c = if i % 50 == 25 {
                Command::Plc(PlcFunction::M(8))
            } else {
                feed(V2::new(r, -(i as f64) * 0.2), 30.0)
            };
            a.push(c, Tag::default()).unwrap();
            a.replan();
            b.push(c, Tag::default()).unwrap();
        }
        b.replan();
        for k in 0..a.len() {
            // The batch sees the final accelerations, so it may only be
            // closer to the limit, never above it.
            let (ea, eb) = (
                a.seg(k).map_or(0.0, |s| s.v_exit),
                b.seg(k).map_or(0.0, |s| s.v_exit),
            );
            assert!(eb >= ea - 1e-12, "item {k}: {eb} < {ea}");
            for p in [&a, &b] {
                if let (Some(s), Some(n)) = (p.seg(k), p.seg(k + 1)) {
                    let room = s
                        .v_junction
                        .min(crate::profile::brake_limit(n.len, n.v_exit, n.a, p.dt));
                    assert!(
                        s.v_exit <= room + 1e-12,
                        "item {k}: exit {} above {room}",
                        s.v_exit
                    );
                }
            }
        }
        assert_eq!(b.seg(b.len() - 1).unwrap().v_exit, 0.0);
    }

    use super::*;
    use crate::command::Path;

    fn feed(to: V2, f: f64) -> Command {
        Command::Move(Move {
            kind: MoveKind::Feed(Feed {
                f,
                per_rev: false,
                fixed: false,
            }),
            path: Path::Line { to },
            shift: V2::ZERO,
            c: None,
        })
    }

    #[test]
    fn collinear_moves_blend_and_the_last_stops() {
        let mut p = Planner::new(&Config::default());
        for i in 1..=10 {
            p.push(feed(V2::new(0.0, -(i as f64)), 10.0), Tag::default())
                .unwrap();
        }
        p.replan();
        for k in 0..9 {
            let s = p.seg(k).unwrap();
            assert!(s.v_exit > 9.9, "{k}: {}", s.v_exit);
        }
        assert_eq!(p.seg(9).unwrap().v_exit, 0.0);
    }

    #[test]
    fn a_right_angle_slows_to_the_corner_speed() {
        let mut p = Planner::new(&Config::default());
        p.push(feed(V2::new(0.0, -10.0), 50.0), Tag::default())
            .unwrap();
        p.push(feed(V2::new(5.0, -10.0), 50.0), Tag::default())
            .unwrap();
        p.replan();
        let s = p.seg(0).unwrap();
        // Z loses its whole speed in one period, so 0.25·2000·0.001 mm/s at most.
        assert!(s.v_exit <= 0.5 + 1e-12 && s.v_exit > 0.0, "{}", s.v_exit);
    }

    fn thread(to: V2, lead: f64) -> Command {
        Command::Move(Move {
            kind: MoveKind::Thread(crate::command::Thread {
                lead,
                dlead: 0.0,
                q_deg: 0.0,
            }),
            path: Path::Line { to },
            shift: V2::ZERO,
            c: None,
        })
    }

    /// A Z thread into a 45° pull-out (lead 4 at 1000 rev/min: Z at
    /// 66.667 mm/s, X as fast in the pull-out). The pull-out's path runs
    /// at 94.28 mm/s, which the axes allow (X 4000, Z 5000 mm/min: the
    /// cap is 66.667·√2) but the path limit of programmed feeds (5000
    /// mm/min, 83.333 mm/s) would not; and the joint lets the faster
    /// leg's speed through: the Z thread's own cap, Z's 83.333, against
    /// the pull-out's 94.28 seen from the Z leg (× 1/√2, the same Z
    /// speed: 66.667). (Capped at the pull-out's path limit, the chain
    /// braked out of step with the spindle: 2.83 mm a turn along Z where
    /// 4 is programmed.)
    #[test]
    fn a_thread_chain_is_capped_by_the_axes_and_its_joint_by_the_faster_leg() {
        let mut p = Planner::new(&Config::default());
        p.push(thread(V2::new(0.0, -20.0), 4.0), Tag::default())
            .unwrap();
        p.push(thread(V2::new(8.0, -28.0), 4.0), Tag::default())
            .unwrap();
        p.replan();
        let (z_leg, pull_out) = (p.seg(0).unwrap(), p.seg(1).unwrap());
        let axes = 4000.0 / 60.0 * 2f64.sqrt();
        assert!((pull_out.v_max - axes).abs() < 1e-9, "{}", pull_out.v_max);
        assert!(
            (z_leg.v_max - 5000.0 / 60.0).abs() < 1e-9,
            "{}",
            z_leg.v_max
        );
        assert!((z_leg.chain_scale(pull_out) - 0.5f64.sqrt()).abs() < 1e-12);
        assert!(
            (z_leg.v_junction - 5000.0 / 60.0).abs() < 1e-9,
            "{}",
            z_leg.v_junction
        );
        assert!(z_leg.long_z && pull_out.long_z);
    }

    /// A 45° leg, then a Z leg of 0.281 mm, at lead 4 and 1000 rev/min:
    /// the long axis runs at 66.667 mm/s throughout, the 45° leg's path
    /// at 94.28, the Z leg's at 66.667. Braking along the path, the Z leg
    /// is too short to slow from 94.28 to 66.667 (it needs 0.8 mm at
    /// 2000 mm/s²), and the 45° leg's exit was held to 90.18 (the fuzz
    /// target's chain braked there, 8 mm before its end, and ran on at Z's
    /// top feed: lead 5 where 4 is programmed). Seen from the 45° leg, the
    /// Z leg's speeds are √2 times as fast: the 45° leg exits at the
    /// faster cap, the Z leg's 83.333 seen from it, and so does the Z leg
    /// (nothing slows it before the last leg).
    #[test]
    fn a_chain_leg_brakes_only_for_the_chain_s_end_not_for_a_slower_leg() {
        let mut p = Planner::new(&Config::default());
        for to in [(0.0, -20.0), (4.0, -24.0), (4.0, -24.281), (4.0, -40.0)] {
            p.push(thread(V2::new(to.0, to.1), 4.0), Tag::default())
                .unwrap();
        }
        p.replan();
        let (diag, short) = (p.seg(1).unwrap(), p.seg(2).unwrap());
        assert!((diag.chain_scale(short) - 2f64.sqrt()).abs() < 1e-12);
        let z_cap = 5000.0 / 60.0;
        assert!(
            (diag.v_exit - z_cap * 2f64.sqrt()).abs() < 1e-9,
            "{}",
            diag.v_exit
        );
        assert!((short.v_exit - z_cap).abs() < 1e-9, "{}", short.v_exit);
        assert_eq!(p.seg(3).unwrap().v_exit, 0.0);
    }

    #[test]
    fn rapids_and_feeds_stop_between() {
        let mut p = Planner::new(&Config::default());
        p.push(
            Command::Move(Move {
                kind: MoveKind::Rapid,
                path: Path::Line {
                    to: V2::new(5.0, 5.0),
                },
                shift: V2::ZERO,
                c: None,
            }),
            Tag::default(),
        )
        .unwrap();
        p.push(feed(V2::new(5.0, -10.0), 10.0), Tag::default())
            .unwrap();
        p.replan();
        assert_eq!(p.seg(0).unwrap().v_exit, 0.0);
    }
}
