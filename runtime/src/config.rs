//! The numbers the runtime plans with, in its own units (mm, s, mm/s,
//! rev/min), taken from a machine file (machine.md §3–§4) plus a few
//! runtime choices that have no key there.

use crate::pitch::PitchTable;

/// One linear axis, in slide units: X values are radial (machine.md §1:
/// "an X rate is the radial speed"), so a diameter travel is halved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    /// Rapid rate, mm/s.
    pub rapid: f64,
    /// Maximum cutting feed of the axis, mm/s.
    pub max_feed: f64,
    /// Acceleration, mm/s².
    pub accel: f64,
    /// Jerk, mm/s³ (used only when [`Config::jerk_limited`] is on).
    pub jerk: f64,
    /// Travel check (E7002) on machine positions, slide units.
    pub soft_limits: bool,
    /// Lower travel limit, slide units.
    pub min: f64,
    /// Upper travel limit, slide units.
    pub max: f64,
    /// The lost motion of the screw and nut, slide units: what the
    /// drive's command takes up where the axis turns back (backlash.rs);
    /// 0 on a machine without compensation.
    pub backlash: f64,
}

/// The simulated spindle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpindleConfig {
    /// Lowest speed of a turning analog spindle, rev/min.
    pub min_rpm: f64,
    /// Highest speed, rev/min.
    pub max_rpm: f64,
    /// rev/min per second.
    pub accel_rpm_s: f64,
    /// Encoder pulses per turn.
    pub encoder_ppr: u32,
    /// A feed-per-revolution move that waits this long for a stopped
    /// spindle raises E7003.
    pub stall_timeout_s: f64,
}

/// The rapid override positions of the operator panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RapidOverride {
    /// F0: a fixed creep rate, [`Config::rapid_f0`] of each axis's rapid.
    F0,
    /// 25 %.
    P25,
    /// 50 %.
    P50,
    /// 100 %.
    P100,
}

impl RapidOverride {
    /// The nearest switch position for a percentage (machine files give
    /// `operator.rapid_override_pct` as a number).
    pub fn from_pct(p: f64) -> RapidOverride {
        if p >= 75.0 {
            RapidOverride::P100
        } else if p >= 37.5 {
            RapidOverride::P50
        } else if p >= 12.5 {
            RapidOverride::P25
        } else {
            RapidOverride::F0
        }
    }

    /// The factor on the rapid rate (`f0`: the F0 share, [`Config::rapid_f0`]).
    pub fn factor(self, f0: f64) -> f64 {
        match self {
            RapidOverride::F0 => f0,
            RapidOverride::P25 => 0.25,
            RapidOverride::P50 => 0.5,
            RapidOverride::P100 => 1.0,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
/// The runtime's settings: axes, spindle, look-ahead and the operator panel's power-on positions.
pub struct Config {
    /// Interpolation period, s (machine.interpolation_period_ms).
    pub period_s: f64,
    /// The X slide (radial units).
    pub x: Axis,
    /// The Z slide.
    pub z: Axis,
    /// The pitch error tables of X (radial units), Z and C (one turn's
    /// angular table), which the drive's command adds ([`crate::pitch`]);
    /// empty for none.
    pub pitch: [PitchTable; 3],
    /// The optional C axis in degrees (deg/s, deg/s², deg/s³); `None`
    /// on a machine without one.
    pub c: Option<Axis>,
    /// Path limit of cutting feeds (№027), mm/s.
    pub path_max_feed: f64,
    /// The spindle.
    pub spindle: SpindleConfig,
    /// Look-ahead: at least this many blocks and this much motion are kept
    /// planned when the program allows (machine.md §3).
    pub lookahead_blocks: usize,
    /// ... and this many seconds of motion.
    pub lookahead_s: f64,
    /// Items the queue holds at most (allocated once).
    pub queue_capacity: usize,
    /// №007.5: every block ends in an exact stop.
    pub always_exact_stop: bool,
    /// S-curve (jerk-limited) speed changes instead of linear
    /// acceleration: a moving average of the acceleration-limited motion
    /// (see `smooth`): over [`Config::rapid_taps`] for rapids, over
    /// [`Config::feed_taps`] and then [`Config::feed_spread_taps`] for
    /// feeds, over [`Config::jerk_taps`] for the path parameter in a
    /// plane. Off on the reference machine; never for threads.
    pub jerk_limited: bool,
    /// The share of an axis's acceleration that a G64 corner may use as a
    /// one-period velocity step (under jerk limiting: that the corners
    /// within the second average's window share, as steps spread over
    /// it); the segments next to the corner keep the rest for their own
    /// speed changes, so the sum never exceeds the limit. *Choice*: 0.25.
    pub corner_budget: f64,
    /// Rapid rate at the F0 override position, as a share of each axis's
    /// rapid. *Choice*: 5 %.
    pub rapid_f0: f64,
    /// Power-on positions of the operator panel.
    pub feed_override_pct: f64,
    /// Rapid override at power-on.
    pub rapid_override: RapidOverride,
    /// Spindle override at power-on, percent.
    pub spindle_override_pct: f64,
    /// Single block at power-on.
    pub single_block: bool,
    /// M01 stops (the optional stop switch; the host may turn it at any
    /// time, [`crate::Engine::set_optional_stop`]).
    pub optional_stop: bool,
    /// Dry run: cutting feeds run at [`Config::dry_run_feed`] × the feed
    /// override instead of F (a live switch,
    /// [`crate::Engine::set_dry_run`]).
    pub dry_run: bool,
    /// Machine lock: the program runs, the axes stand (read when a run
    /// starts, [`crate::Engine::set_machine_lock`]).
    pub machine_lock: bool,
    /// Auxiliary function lock: M, S and T functions are not executed
    /// (live, [`crate::Engine::set_aux_lock`]).
    pub aux_lock: bool,
    /// The dry-run rate, mm/s. The machine file has no key for it; it is
    /// the path limit of cutting feeds (№027), so that the override knob
    /// sets the speed of an air cut as the GSK's manual rate does.
    pub dry_run_feed: f64,
    /// Cycle start after an M30 runs the program again from its start
    /// (`run.m30_rewinds`); else a reset must come first.
    pub m30_rewinds: bool,
    /// The skip signal is active at 0 (№185.7).
    pub skip_active_low: bool,
    /// Positions are commanded in these steps (machine.resolution_mm):
    /// each set point's [`crate::Counts`].
    pub resolution_mm: f64,
    /// The feed of a manual reference return, mm/s (№113,
    /// `reference_points.return_feed_mm_min`).
    pub home_feed: f64,
}

impl Axis {
    /// The travel (min, max) the soft limits allow, where they are on.
    pub fn travel(&self) -> Option<(f64, f64)> {
        self.soft_limits.then_some((self.min, self.max))
    }
}

impl Default for Config {
    /// The reference machine of machine.md.
    fn default() -> Config {
        let min = |v: f64| v / 60.0;
        Config {
            period_s: 0.001,
            x: Axis {
                rapid: min(6000.0),
                max_feed: min(4000.0),
                accel: 1500.0,
                jerk: 20000.0,
                soft_limits: false,
                min: -130.0,
                max: 1.0,
                backlash: 0.0,
            },
            z: Axis {
                rapid: min(10000.0),
                max_feed: min(5000.0),
                accel: 2000.0,
                jerk: 25000.0,
                soft_limits: false,
                min: -510.0,
                max: 2.0,
                backlash: 0.0,
            },
            pitch: Default::default(),
            c: None,
            path_max_feed: min(5000.0),
            spindle: SpindleConfig {
                min_rpm: 30.0,
                max_rpm: 3000.0,
                accel_rpm_s: 1000.0,
                encoder_ppr: 1024,
                stall_timeout_s: 5.0,
            },
            lookahead_blocks: 1024,
            lookahead_s: 0.2,
            queue_capacity: 4096,
            always_exact_stop: false,
            jerk_limited: false,
            corner_budget: 0.25,
            rapid_f0: 0.05,
            feed_override_pct: 100.0,
            rapid_override: RapidOverride::P100,
            spindle_override_pct: 100.0,
            single_block: false,
            optional_stop: true,
            dry_run: false,
            machine_lock: false,
            aux_lock: false,
            dry_run_feed: min(5000.0),
            m30_rewinds: false,
            skip_active_low: false,
            resolution_mm: 0.001,
            home_feed: min(4000.0),
        }
    }
}

impl Config {
    /// The axes as an array, X first.
    pub fn axes(&self) -> [&Axis; 2] {
        [&self.x, &self.z]
    }

    /// The smaller of the two axis accelerations: what a curve, whose
    /// direction sweeps over both axes, may use.
    pub fn min_accel(&self) -> f64 {
        self.x.accel.min(self.z.accel)
    }

    /// Periods of the moving-average filter that turns linear
    /// acceleration into an S-curve with jerk within every axis's limit
    /// (a box filter of width T bounds the jerk by 2·a/T).
    pub fn jerk_taps(&self) -> usize {
        if !self.jerk_limited {
            return 1;
        }
        let mut t = (2.0 * self.x.accel / self.x.jerk).max(2.0 * self.z.accel / self.z.jerk);
        if let Some(c) = &self.c {
            t = t.max(2.0 * c.accel / c.jerk);
        }
        let n = libm::ceil(t / self.period_s);
        if n.is_finite() && n >= 1.0 {
            (n as usize).min(1 << 16)
        } else {
            1
        }
    }

    /// Periods of the moving average over a rapid's axes, with jerk
    /// limiting (1 without): a/j, the largest over the axes. A rapid's
    /// axis never turns from speeding up to slowing down, or back, within
    /// that window (smooth.rs `Turns`), which halves what one average
    /// needs for any profile (`jerk_taps`, 2·a/j): the end of a rapid is
    /// about a/j later than without jerk limiting, as with an S-curve.
    pub fn rapid_taps(&self) -> usize {
        // Half a period over a/j at least: the jerk stays a little below
        // the limit, whatever the averages' rounding.
        match self.jerk_taps() {
            n if n > 1 => n / 2 + 1,
            _ => 1,
        }
    }

    /// Periods of the first moving average over each axis's set points
    /// of a feed, with jerk limiting (1 without; the second:
    /// [`Config::feed_spread_taps`]). The average of N periods turns an
    /// axis acceleration `a` into jerk within 2·a/(N·dt), so feeds
    /// accelerate at [`Config::feed_accel`], at most j·T/2 (T = N·dt).
    /// Alone, it would cut a G64 corner, where the direction changes by
    /// Δu, by up to (v·T/8 + a·T²/48)·|Δu| at speed v (planner.rs
    /// `FeedSmoothing`): the window is the longest whose braking term,
    /// J·T³/96 with J the smaller axis jerk, stays within a quarter of
    /// the resolution at |Δu| = 1, T = ∛(24·tol/J) (11 ms on the
    /// reference machine). A longer one would stop every corner of more
    /// than a few degrees and slow every curve (the cut of a curve grows
    /// with T²); a shorter one would slow every speed change. Never
    /// longer than 2·a/j (`jerk_taps`).
    pub fn feed_taps(&self) -> usize {
        let most = self.jerk_taps();
        if most <= 1 {
            return 1;
        }
        let j = self.x.jerk.min(self.z.jerk);
        let t = libm::cbrt(24.0 * self.resolution_mm.max(1e-6) / j);
        let n = libm::round(t / self.period_s);
        if n.is_nan() || n < 1.0 {
            1
        } else if n < most as f64 {
            n as usize
        } else {
            most
        }
    }

    /// Periods of the second moving average over a feed's set points,
    /// after the first ([`Config::feed_taps`]; 1 without jerk limiting).
    /// The pair bounds each axis's jerk by 2·W/(T·T₂), W the largest
    /// change of the unaveraged axis speed over T₂ (smooth.rs `Cascade`):
    /// a G64 corner's velocity step, which one average turns into a jump
    /// of acceleration, becomes a ramp over T₂, so corners may step T₂/dt
    /// times as much. The second window also cuts corners and curves a
    /// little more (planner.rs `FeedSmoothing`): half the first is the
    /// balance (6 periods on the reference machine).
    pub fn feed_spread_taps(&self) -> usize {
        self.feed_taps().div_ceil(2)
    }

    /// An axis's acceleration for feeds: its own, and with jerk limiting
    /// at most j·T/2 over the feeds' window T ([`Config::feed_taps`]).
    pub fn feed_accel(&self, axis: &Axis) -> f64 {
        if self.jerk_taps() <= 1 {
            return axis.accel;
        }
        let t = self.feed_taps() as f64 * self.period_s;
        axis.accel.min(0.5 * axis.jerk * t)
    }
}

/// An axis's pitch error table in slide units (`k` 0.5 for X, which the
/// machine file gives on the diameter).
fn table(a: &nc::machine::LinearAxis, k: f64) -> PitchTable {
    // (machine_check has made each point a pair.)
    let pairs = a.pitch_comp_mm.iter().filter_map(|p| match p.as_slice() {
        &[at, add] => Some((at * k, add * k)),
        _ => None,
    });
    PitchTable::new(pairs.collect())
}

/// C's angular table (degrees; none without a C axis).
fn turn_table(c: &nc::machine::RotaryAxis) -> PitchTable {
    let pairs = c.pitch_comp_deg.iter().filter_map(|p| match p.as_slice() {
        &[at, add] if c.enabled => Some((at, add)),
        _ => None,
    });
    PitchTable::turn(pairs.collect())
}

/// The C axis of a machine file, per second; it turns without limits.
fn rotary(c: &nc::machine::RotaryAxis) -> Axis {
    Axis {
        rapid: c.rapid_deg_min / 60.0,
        max_feed: c.max_feed_deg_min / 60.0,
        accel: c.accel_deg_s2,
        jerk: c.jerk_deg_s3,
        soft_limits: false,
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
        backlash: c.backlash_deg,
    }
}

impl Config {
    /// The runtime's view of a machine file.
    pub fn from_machine(m: &nc::Machine) -> Config {
        let per_s = |v: f64| v / 60.0;
        let axis = |a: &nc::machine::LinearAxis, radial: bool| {
            let k = if radial { 0.5 } else { 1.0 };
            Axis {
                rapid: per_s(a.rapid_mm_min),
                max_feed: per_s(a.max_feed_mm_min),
                accel: a.accel_mm_s2,
                jerk: a.jerk_mm_s3,
                soft_limits: a.soft_limits,
                min: a.min_mm * k,
                max: a.max_mm * k,
                backlash: a.backlash_mm * k,
            }
        };
        let d = Config::default();
        Config {
            period_s: m.machine.interpolation_period_ms / 1000.0,
            // (The machine file writes X's travel on the diameter, in
            // radius programming too: machine.md.)
            x: axis(&m.axes.x, true),
            z: axis(&m.axes.z, false),
            pitch: [
                table(&m.axes.x, 0.5),
                table(&m.axes.z, 1.0),
                turn_table(&m.axes.c),
            ],
            c: m.axes.c.enabled.then(|| rotary(&m.axes.c)),
            path_max_feed: per_s(m.feed.max_mm_min),
            spindle: SpindleConfig {
                min_rpm: m.spindle.min_rpm.max(0.0),
                max_rpm: m.spindle.max_rpm,
                accel_rpm_s: m.spindle.accel_rpm_s,
                encoder_ppr: m.spindle.encoder_ppr,
                stall_timeout_s: m.spindle.stall_timeout_s.max(0.0),
            },
            lookahead_blocks: (m.machine.lookahead_blocks as usize).max(1024),
            queue_capacity: ((m.machine.lookahead_blocks as usize).max(1024) * 4).min(1 << 20),
            always_exact_stop: m.motion.always_exact_stop,
            jerk_limited: m.motion.jerk_limiting,
            feed_override_pct: m.operator.feed_override_pct.clamp(0.0, 150.0),
            rapid_override: RapidOverride::from_pct(m.operator.rapid_override_pct),
            spindle_override_pct: m.operator.spindle_override_pct.clamp(0.0, 200.0),
            single_block: m.operator.single_block,
            optional_stop: m.operator.optional_stop,
            dry_run: m.operator.dry_run,
            machine_lock: m.operator.machine_lock,
            aux_lock: m.operator.aux_lock,
            dry_run_feed: per_s(m.feed.max_mm_min),
            m30_rewinds: m.run.m30_rewinds,
            skip_active_low: m.measure.signal_active_low,
            resolution_mm: m.machine.resolution_mm,
            home_feed: per_s(m.reference_points.return_feed_mm_min),
            ..d
        }
    }
}
