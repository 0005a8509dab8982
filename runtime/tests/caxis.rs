//! The C axis through the runtime: C end points are reached, C stays
//! within its own velocity, acceleration and jerk limits, feeds along the
//! combined XZ + C vector run at F, and a machine without C prints no `c`.

mod common;

use common::{check_limits, run_with, Run};
use nc::{Event, Machine};
use runtime::Motion;

fn c_machine() -> Machine {
    let mut m = Machine::reference();
    m.axes.c.enabled = true;
    m
}

/// A rapid with C, a combined Z + C feed, a C-only feed too fast for C and
/// a combined X + C feed.
const PROGRAM: &str = "G98\nG00 X20 Z5 C90\nG01 Z0 H-45 F600\nC0 F3000\nG01 X30 C30 F2400\nM30\n";

fn run_c(jerk: bool) -> Run {
    run_with(
        PROGRAM,
        c_machine(),
        runtime::AutoAck,
        |cfg| cfg.jerk_limited = jerk,
        |_, _| {},
        60.0,
    )
}

/// The C angle of every period, starting at 0 (power-on).
fn angles(r: &Run) -> Vec<f64> {
    std::iter::once(0.0)
        .chain(r.pts.iter().map(|p| p.c.expect("a C column")))
        .collect()
}

/// Every canon move with a `C=` field ends at a period whose X, Z and C
/// are its end point within 0.001 (mm, °), in order.
fn check_c_end_points(r: &Run) {
    let ends: Vec<(f64, f64, f64)> = r
        .canon
        .iter()
        .filter_map(|e| match e {
            Event::Rapid { x, z, c: Some(c) } | Event::Line { x, z, c: Some(c) } => {
                Some((*x, *z, *c))
            }
            _ => None,
        })
        .collect();
    assert_eq!(ends.len(), 4, "{:?}", r.canon);
    let mut k = 0;
    for (i, &(x, z, c)) in ends.iter().enumerate() {
        let hit = r.pts[k..].iter().position(|p| {
            (p.x - x).abs() <= 0.001
                && (p.z - z).abs() <= 0.001
                && (p.c.unwrap_or(f64::NAN) - c).abs() <= 0.001
        });
        match hit {
            Some(j) => k += j,
            None => panic!("end point {i} (X{x} Z{z} C{c}) not reached after period {k}"),
        }
    }
}

/// The worst |C velocity| / limit, |C acceleration| / limit and |C jerk| /
/// limit over the run (finite differences of the set points).
fn c_ratios(r: &Run) -> (f64, f64, f64) {
    let c = r.cfg.c.expect("a C axis");
    let dt = r.cfg.period_s;
    let a = angles(r);
    let (mut wv, mut wa, mut wj) = (0.0f64, 0.0f64, 0.0f64);
    for k in 1..a.len() {
        let lim = if r.pts[k - 1].motion == Motion::Rapid {
            c.rapid
        } else {
            c.max_feed
        };
        wv = wv.max(((a[k] - a[k - 1]) / dt).abs() / lim);
        if k + 1 < a.len() {
            let acc = (a[k + 1] - 2.0 * a[k] + a[k - 1]) / (dt * dt);
            wa = wa.max(acc.abs() / c.accel);
        }
        if k + 2 < a.len() {
            let jerk = (a[k + 2] - 3.0 * a[k + 1] + 3.0 * a[k] - a[k - 1]) / (dt * dt * dt);
            wj = wj.max(jerk.abs() / c.jerk);
        }
    }
    (wv, wa, wj)
}

/// The highest C speed (°/s) while source line `line` runs.
fn peak_c_speed(r: &Run, line: u32) -> f64 {
    let a = angles(r);
    let dt = r.cfg.period_s;
    (1..a.len())
        .filter(|&k| r.pts[k - 1].line == line)
        .map(|k| ((a[k] - a[k - 1]) / dt).abs())
        .fold(0.0, f64::max)
}

#[test]
fn c_reaches_its_end_points_within_its_limits() {
    let r = run_c(false);
    assert_eq!(r.state, runtime::RunState::Ended);
    check_c_end_points(&r);
    let (v, a, _) = c_ratios(&r);
    assert!(
        v <= 1.0 + 1e-6,
        "C exceeds its velocity limit: {v:.6} of it"
    );
    assert!(
        a <= 1.0 + 1e-6,
        "C exceeds its acceleration limit: {a:.6} of it"
    );
    check_limits(&r, false);
    // The program ends at C30.
    let last = r.pts.last().and_then(|p| p.c);
    assert!((last.unwrap_or(f64::NAN) - 30.0).abs() < 1e-9);
}

#[test]
fn feeds_with_c_run_along_the_combined_vector() {
    let r = run_c(false);
    // Line 3: Z 5 → 0 while C turns 90 → 45: 10 mm/s along a vector of
    // √(5² + 45²) = 45.27693 "mm", so C turns at 10·45/45.27693 = 9.93884 °/s.
    let v3 = peak_c_speed(&r, 3);
    assert!((v3 - 9.93884).abs() < 1e-3, "{v3}");
    // Line 4: C alone at F3000 = 50 °/s, above C's 1800 °/min = 30 °/s:
    // it turns at the axis's maximum.
    let v4 = peak_c_speed(&r, 4);
    assert!((v4 - 30.0).abs() < 1e-6, "{v4}");
    // Line 5: X20 → 30 is 5 mm radial with 30° of C: 40 mm/s along
    // √(5² + 30²) = 30.41381 would turn C at 39.456 °/s, over 30 °/s; so C
    // caps the path at 30·30.41381/30 = 30.41381 mm/s and C turns at 30.
    let v5 = peak_c_speed(&r, 5);
    assert!((v5 - 30.0).abs() < 1e-6, "{v5}");
}

#[test]
fn jerk_limiting_covers_c() {
    let r = run_c(true);
    check_c_end_points(&r);
    let (v, a, j) = c_ratios(&r);
    assert!(v <= 1.0 + 1e-6, "C velocity: {v:.6} of the limit");
    assert!(a <= 1.0 + 1e-6, "C acceleration: {a:.6} of the limit");
    assert!(j <= 1.0 + 1e-6, "C jerk: {j:.6} of the limit");
}

#[test]
fn the_trace_has_a_c_column_only_with_a_c_axis() {
    let with = run_c(false);
    assert!(with.pts.iter().all(|p| p.c.is_some()));
    assert_eq!(
        runtime::trace::csv_header(with.cfg.c.is_some()),
        "time_s,x,z,c,spindle_rpm,feed,line,motion,tool,file"
    );
    let without = common::run("G00 X20 Z5\nG01 Z0 F600\nM30\n");
    assert!(without.pts.iter().all(|p| p.c.is_none()));
    assert!(without.cfg.c.is_none());
    assert_eq!(
        runtime::trace::csv_header(without.cfg.c.is_some()),
        "time_s,x,z,spindle_rpm,feed,line,motion,tool,file"
    );
    let mut line = String::new();
    runtime::trace::write_csv(
        &mut line,
        &without.pts[0],
        runtime::trace::Frame::Work,
        "p.nc",
    )
    .unwrap();
    assert_eq!(line.split(',').count(), 9, "{line}");
}

#[test]
fn c_runs_are_bit_identical() {
    assert_eq!(common::hash(&run_c(false)), common::hash(&run_c(false)));
}

/// C's counts are 0.001° steps: within half a step of the angle every
/// period, and a rapid to C12.3456 ends at 12 346 (12 345.6 rounded).
#[test]
fn c_counts_are_thousandths_of_a_degree() {
    let r = run_with(
        "G00 X20.0004 C12.3456\nM30\n",
        c_machine(),
        runtime::AutoAck,
        |_| {},
        |_, _| {},
        60.0,
    );
    for p in &r.pts {
        let c = p.c.expect("a C column");
        assert!(
            (p.counts.c as f64 * 0.001 - c).abs() <= 0.0005 + 1e-12,
            "{p:?}"
        );
    }
    let end = r.pts.last().unwrap().counts;
    assert_eq!((end.x, end.c), (20_000, 12_346));
}

/// After a reset the program starts where the axes stand, C included: an
/// incremental `H30` run again from C30 ends at C60 (the kernel's C is the
/// axis's, not power-on's 0°), and #5003 reads 30 before it.
#[test]
fn a_reset_hands_the_c_angle_to_the_restarted_program() {
    let src = "O1\n#100=#5003\nG00 H30\nM30\n";
    let m = c_machine();
    let module = common::module(src, &m);
    let mut ctl = runtime::Controller::new(module, m, runtime::AutoAck).expect("loads");
    let mut last = None;
    for round in 0..2 {
        ctl.cycle_start();
        for _ in 0..100_000 {
            ctl.run_ahead();
            last = Some(ctl.tick());
            if ctl.state() == runtime::RunState::Ended {
                break;
            }
        }
        assert_eq!(ctl.state(), runtime::RunState::Ended);
        let read = ctl.vm().variable(100).expect("#100");
        assert_eq!(read, 30.0 * f64::from(round), "round {round}");
        ctl.reset();
        for _ in 0..10 {
            ctl.run_ahead();
            ctl.tick();
        }
    }
    assert_eq!(last.and_then(|p| p.c), Some(60.0));
}

/// The same through a split controller: the reset's report carries C.
#[test]
fn a_reset_hands_the_c_angle_across_the_split() {
    let src = "O1\n#100=#5003\nG00 H30\nM30\n";
    let m = c_machine();
    let module = common::module(src, &m);
    let ctl = runtime::Controller::new(module, m, runtime::AutoAck).expect("loads");
    let (mut interp, mut rt) = ctl.split();
    let mut last = None;
    for round in 0..2 {
        rt.cycle_start();
        for _ in 0..100_000 {
            interp.run_ahead();
            last = Some(rt.tick());
            if rt.state() == runtime::RunState::Ended {
                break;
            }
        }
        assert_eq!(rt.state(), runtime::RunState::Ended);
        let read = interp.vm().variable(100).ok();
        assert_eq!(read, Some(30.0 * f64::from(round)), "round {round}");
        rt.reset();
        for _ in 0..10 {
            interp.run_ahead();
            rt.tick();
        }
    }
    assert_eq!(last.and_then(|p| p.c), Some(60.0));
}
