//! Shared pieces of the runtime tests: compile a G-code string, run it
//! period by period with a scripted host, and check the trace.
#![allow(dead_code)]

use nc::{Event, Machine};
use runtime::{AlarmInfo, AutoAck, Config, Controller, Motion, Plc, Realtime, RunState, SetPoint};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A turned shaft: rapids, feed per revolution, both arc forms, coolant.
pub const SHAFT: &str = "O0001
G50 X100 Z50
T0101 M03 S800
G00 X40 Z2 M08
G99 G01 Z-20 F0.2
X50 Z-30
G02 X60 Z-35 R5
G01 Z-50
G03 X70 Z-55 K-5
G01 X80
G00 X100 Z50 M09
M30
";

pub fn module(src: &str, machine: &Machine) -> isa::Module {
    let opts = compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    };
    let out = compiler::compile("test.nc", src.as_bytes(), &opts);
    match out.module {
        Some(m) => m,
        None => panic!("compile error:\n{}", out.render()),
    }
}

pub struct Run {
    pub pts: Vec<SetPoint>,
    pub canon: Vec<Event>,
    pub state: RunState,
    pub alarm: Option<AlarmInfo>,
    pub cfg: Config,
}

/// Runs `src` to its end (at most `max_s` simulated seconds); `host` is
/// called after every period and may press buttons.
pub fn run_with<P: Plc>(
    src: &str,
    machine: Machine,
    plc: P,
    tweak: impl FnOnce(&mut Config),
    mut host: impl FnMut(&mut Controller<P>, &SetPoint),
    max_s: f64,
) -> Run {
    let m = module(src, &machine);
    let mut cfg = Config::from_machine(&machine);
    tweak(&mut cfg);
    let mut ctl = Controller::with_config(m, machine, cfg.clone(), plc).expect("loads");
    ctl.cycle_start();
    let mut canon = Vec::new();
    let mut pts = Vec::new();
    loop {
        ctl.run_ahead_tap(&mut canon);
        let sp = ctl.tick();
        pts.push(sp);
        host(&mut ctl, &sp);
        match ctl.state() {
            RunState::Stopped(_) => ctl.cycle_start(),
            RunState::Ended | RunState::Alarm(_) => break,
            _ => {}
        }
        if sp.time_s > max_s {
            panic!(
                "the run did not end within {max_s} s (state {:?})",
                ctl.state()
            );
        }
    }
    Run {
        pts,
        canon,
        state: ctl.state(),
        alarm: ctl.alarm(),
        cfg,
    }
}

/// As [`run_with`] with the controller split: the interpreter runs on a
/// thread of its own, as fast as it likes, while this one ticks the
/// real-time half without waiting for it. Periods pass while the queue
/// is starved, as on a machine; only, the loop gives the interpreter's
/// thread the core then (the ticks run far faster than real time), and
/// the run must end within a minute of wall time. The alarm is the VM's
/// when the VM raised it, else the engine's.
pub fn run_split_with<P: Plc>(
    src: &str,
    machine: Machine,
    plc: P,
    mut host: impl FnMut(&mut Realtime<P>, &SetPoint),
) -> Run {
    let m = module(src, &machine);
    let cfg = Config::from_machine(&machine);
    let ctl = Controller::with_config(m, machine, cfg.clone(), plc).expect("loads");
    let (mut interp, mut rt) = ctl.split();
    rt.cycle_start();
    let stop = AtomicBool::new(false);
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut pts = Vec::new();
    let (canon, interp) = std::thread::scope(|s| {
        let vm_side = s.spawn(|| {
            let mut canon: Vec<Event> = Vec::new();
            while !stop.load(Ordering::Acquire) {
                interp.run_ahead_tap(&mut canon);
                std::thread::yield_now();
            }
            (canon, interp)
        });
        loop {
            let sp = rt.tick();
            pts.push(sp);
            host(&mut rt, &sp);
            match rt.state() {
                RunState::Stopped(_) => rt.cycle_start(),
                RunState::Ended | RunState::Alarm(_) => break,
                RunState::Starved => std::thread::yield_now(),
                _ => {}
            }
            if Instant::now() > deadline {
                stop.store(true, Ordering::Release);
                panic!(
                    "the split run did not end within a minute ({:?})",
                    rt.state()
                );
            }
        }
        stop.store(true, Ordering::Release);
        vm_side.join().expect("the interpreter thread")
    });
    let alarm = match rt.state() {
        RunState::Alarm(code) => interp.alarm(code).or_else(|| rt.alarm()),
        _ => None,
    };
    Run {
        pts,
        canon,
        state: rt.state(),
        alarm,
        cfg,
    }
}

pub fn run_split(src: &str) -> Run {
    run_split_with(src, Machine::reference(), runtime::AutoAck, |_, _| {})
}

pub fn run(src: &str) -> Run {
    run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |_, _| {},
        600.0,
    )
}

/// Distance from p to the segment a–b.
fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dz) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dz * dz;
    let t = if l2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dz) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = (a.0 + t * dx, a.1 + t * dz);
    ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt()
}

/// The end points of the canon's moves, in order (radius, Z).
/// Cycle start, then every period to the end (at most 400 simulated
/// s); the last set point. An alarm fails the test.
pub fn run_to_end(ctl: &mut Controller) -> SetPoint {
    ctl.cycle_start();
    let mut last = SetPoint::default();
    for _ in 0..400_000 {
        ctl.run_ahead();
        last = ctl.tick();
        match ctl.state() {
            RunState::Ended => return last,
            RunState::Alarm(a) => panic!("alarm {a}"),
            _ => {}
        }
    }
    panic!("not done: {:?} at {last:?}", ctl.state());
}

/// Reset, ticked until it has finished.
pub fn reset_to_idle(ctl: &mut Controller) {
    ctl.reset();
    while ctl.state() != RunState::Idle {
        ctl.run_ahead();
        ctl.tick();
    }
}

pub fn end_points(canon: &[Event]) -> Vec<(f64, f64)> {
    canon
        .iter()
        .filter_map(|e| match e {
            Event::Rapid { x, z, .. } | Event::Line { x, z, .. } | Event::Skip { x, z } => {
                Some((x / 2.0, *z))
            }
            Event::Arc { x, z, .. }
            | Event::Thread { x, z, .. }
            | Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. } => Some((x / 2.0, *z)),
            _ => None,
        })
        .collect()
}

/// Every canon end point is on the interpolated path, in order, within
/// 0.001 mm (a stop lands on it; a blended corner is passed through
/// between two periods).
pub fn check_end_points(r: &Run) {
    // The reference start: the tool at machine zero, work zero there too.
    let pts: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain(r.pts.iter().map(|p| (p.x / 2.0, p.z)))
        .collect();
    let mut k = 0;
    'next: for (i, e) in end_points(&r.canon).into_iter().enumerate() {
        let start = k;
        while k + 1 < pts.len() {
            if seg_dist(e, pts[k], pts[k + 1]) <= 0.001 {
                continue 'next;
            }
            k += 1;
        }
        panic!("end point {i} {e:?} not reached after period {start}");
    }
    let last = pts.last().copied().unwrap_or_default();
    if let Some(e) = end_points(&r.canon).last() {
        assert!(
            ((last.0 - e.0).powi(2) + (last.1 - e.1).powi(2)).sqrt() <= 0.001,
            "ends at {last:?}, not {e:?}"
        );
    }
}

/// The worst ratio of |axis velocity| to its limit and of |axis
/// acceleration| to its limit over the whole run (slide units, finite
/// differences of the axis set points). Thread periods are measured
/// against the cutting feed limit; `skip_threads` leaves out the
/// accelerations of thread periods (the helix follows the spindle).
pub fn worst_ratios(r: &Run, skip_threads: bool) -> (f64, f64) {
    let dt = r.cfg.period_s;
    let ax = [r.cfg.x, r.cfg.z];
    let pos: Vec<[f64; 2]> = std::iter::once([0.0, 0.0])
        .chain(r.pts.iter().map(|p| [p.axis_x / 2.0, p.axis_z]))
        .collect();
    let (mut wv, mut wa) = (0.0f64, 0.0f64);
    for k in 1..pos.len() {
        let m = r.pts[k - 1].motion;
        for a in 0..2 {
            let v = (pos[k][a] - pos[k - 1][a]) / dt;
            let lim = if m == Motion::Rapid {
                ax[a].rapid
            } else {
                ax[a].max_feed
            };
            wv = wv.max(v.abs() / lim);
            if k + 1 < pos.len() {
                let acc = (pos[k + 1][a] - 2.0 * pos[k][a] + pos[k - 1][a]) / (dt * dt);
                let thread =
                    r.pts[k - 1].motion == Motion::Thread || r.pts[k].motion == Motion::Thread;
                if !(skip_threads && thread) {
                    if std::env::var("TRACE_WORST").is_ok() && acc.abs() / ax[a].accel > 1.0 + 1e-6
                    {
                        eprintln!(
                            "period {k} axis {a} ratio {:.4} motion {:?} line {} p={:?}",
                            acc.abs() / ax[a].accel,
                            m,
                            r.pts[k - 1].line,
                            &r.pts[k.saturating_sub(3)..(k + 2).min(r.pts.len())]
                                .iter()
                                .map(|p| (p.axis_x / 2.0, p.axis_z, p.feed))
                                .collect::<Vec<_>>()
                        );
                    }
                    wa = wa.max(acc.abs() / ax[a].accel);
                }
            }
        }
    }
    (wv, wa)
}

/// Velocity and acceleration limits hold in every period (tolerance: 1e-6
/// of the limit, rounding).
pub fn check_limits(r: &Run, skip_threads: bool) {
    let (v, a) = worst_ratios(r, skip_threads);
    assert!(
        v <= 1.0 + 1e-6,
        "an axis exceeds its velocity limit: {v:.6} of it"
    );
    assert!(
        a <= 1.0 + 1e-6,
        "an axis exceeds its acceleration limit: {a:.6} of it"
    );
}

/// The largest |jerk| / limit over X and Z, from the axis set points'
/// third differences (the machine starts at rest at zero).
pub fn worst_jerk(r: &Run) -> f64 {
    let dt = r.cfg.period_s;
    let pos: Vec<[f64; 2]> = std::iter::once([0.0, 0.0])
        .chain(r.pts.iter().map(|p| [p.axis_x / 2.0, p.axis_z]))
        .collect();
    let mut worst = 0.0f64;
    for k in 1..pos.len().saturating_sub(2) {
        for (a, ax) in [r.cfg.x, r.cfg.z].iter().enumerate() {
            let j = (pos[k + 2][a] - 3.0 * pos[k + 1][a] + 3.0 * pos[k][a] - pos[k - 1][a])
                / (dt * dt * dt);
            worst = worst.max(j.abs() / ax.jerk);
        }
    }
    worst
}

/// FNV-1a over every field of every set point.
pub fn hash(r: &Run) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |v: u64| {
        for b in v.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in &r.pts {
        for f in [
            p.time_s,
            p.x,
            p.z,
            p.axis_x,
            p.axis_z,
            p.spindle_rpm,
            p.spindle_turns,
            p.feed,
        ] {
            eat(f.to_bits());
        }
        if let Some(c) = p.c {
            eat(c.to_bits());
        }
        eat(p.line as u64);
        eat(p.tool as u64);
    }
    h
}

/// A small deterministic generator (64-bit LCG, Knuth's constants).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        ((lo + (hi - lo) * self.unit()) * 1000.0).round() / 1000.0
    }

    pub fn pick<T: Copy>(&mut self, of: &[T]) -> T {
        of[((self.unit() * of.len() as f64) as usize).min(of.len() - 1)]
    }
}

/// `Some(verdict)` of a run of `src` to its end: `Ok` certified, `Err`
/// the violation; `None` where it does not compile or stops with an
/// alarm (an arc that cannot be drawn, a path through the centre), on
/// `machine` with jerk limiting on or off.
pub fn certify(src: &str, machine: &Machine, jerk: bool) -> Option<Result<(), String>> {
    let opts = compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    };
    let module = compiler::compile("random.nc", src.as_bytes(), &opts).module?;
    let mut cfg = Config::from_machine(machine);
    cfg.jerk_limited = jerk;
    let mut ctl = Controller::with_config(module, machine.clone(), cfg, AutoAck).expect("loads");
    // (600 s of simulated time at 1 ms periods.)
    let (cert, _) = ctl.run_certified(600_000);
    if let RunState::Alarm(_) = ctl.state() {
        return None;
    }
    assert_eq!(
        ctl.state(),
        RunState::Ended,
        "{src}: the run did not end in 600 s"
    );
    Some(match cert.violation() {
        None => Ok(()),
        Some(v) => Err(format!("line {}: {v}", v.line)),
    })
}
