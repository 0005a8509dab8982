//! The host's encoder instead of the simulated spindle: a thread follows
//! the measured angle, so its lead stays exact while the spindle slows
//! down under the cut; feed per revolution follows the measured speed.

mod common;

use common::run_with;
use nc::Machine;
use runtime::{Controller, Motion, SetPoint};

/// What the "encoder" of these tests reports: 600 rev/min, slowing down
/// linearly to 300 rev/min between 1.0 s and 1.5 s, then 300 rev/min.
fn rpm_at(t: f64) -> f64 {
    if t < 1.0 {
        600.0
    } else if t < 1.5 {
        600.0 - 600.0 * (t - 1.0)
    } else {
        300.0
    }
}

/// The encoder positions a host fed, one per period.
type Fed = std::rc::Rc<std::cell::RefCell<Vec<f64>>>;

/// A host that integrates `rpm_at` itself and feeds position and speed
/// before every period; returns the positions it fed, one per period.
fn encoder_host() -> (
    impl FnMut(&mut Controller<runtime::AutoAck>, &SetPoint),
    Fed,
) {
    let fed = std::rc::Rc::new(std::cell::RefCell::new(vec![0.0]));
    let log = fed.clone();
    let host = move |ctl: &mut Controller<runtime::AutoAck>, sp: &SetPoint| {
        // For the period that follows the one just ticked.
        let rpm = rpm_at(sp.time_s);
        let mut f = log.borrow_mut();
        let pos = f.last().copied().unwrap_or(0.0) + rpm / 60.0 * 0.001;
        f.push(pos);
        ctl.set_spindle_feedback(pos, rpm);
    };
    (host, fed)
}

#[test]
fn the_lead_stays_exact_while_the_spindle_slows_down() {
    // A 50 mm thread of lead 1.5: at 600 rev/min it runs at 15 mm/s, so
    // it is still cutting when the spindle slows down at 1.0–1.5 s.
    let src = "O0001\nG00 X40 Z5 M03 S600\nG32 Z-45 F1.5\nG00 X60\nM30\n";
    let (host, fed) = encoder_host();
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        host,
        60.0,
    );
    assert_eq!(r.state, runtime::RunState::Ended);
    let fed = fed.borrow();
    // pts[i] is the period that ran with fed[i] (fed[0] = 0 is the
    // reference reading the first host call compares with).
    let thread: Vec<usize> = (0..r.pts.len())
        .filter(|&i| r.pts[i].motion == Motion::Thread)
        .collect();
    let (first, last) = (thread[0], *thread.last().unwrap());
    // Locked from 0.1 s after the start (the ramp to 15 mm/s at 2000
    // mm/s² takes 7.5 ms) until 0.1 s before the run-out brakes.
    let a = first + 100;
    let b = last - 100;
    assert!(
        r.pts[a].time_s < 1.0 && r.pts[b].time_s > 1.6,
        "spans the slow-down"
    );
    for i in a + 1..=b {
        let dz = r.pts[i - 1].z - r.pts[i].z;
        let turns = fed[i] - fed[i - 1];
        assert!(
            (dz - 1.5 * turns).abs() < 1e-9,
            "period {i} at {:.3} s: Z moved {dz}, the spindle {turns} turns",
            r.pts[i].time_s
        );
    }
    // By hand: 600 rev/min = 10 rev/s = 0.01 rev per 1 ms period, so
    // 0.015 mm of Z; at 300 rev/min half of it.
    let step = |i: usize| r.pts[i - 1].z - r.pts[i].z;
    let fast = (a + 1..b).find(|&i| r.pts[i].time_s < 0.9).unwrap();
    let slow = (a + 1..=b).rev().find(|&i| r.pts[i].time_s > 1.55).unwrap();
    assert!((step(fast) - 0.015).abs() < 1e-9, "{}", step(fast));
    assert!((step(slow) - 0.0075).abs() < 1e-9, "{}", step(slow));
    // The whole locked stretch: Z advance = lead × measured revolutions.
    let dz = r.pts[a].z - r.pts[b].z;
    assert!((dz - 1.5 * (fed[b] - fed[a])).abs() < 1e-9);
    // The set points report the measured spindle.
    assert_eq!(r.pts[slow].spindle_rpm, 300.0);
}

#[test]
fn feed_per_revolution_follows_the_measured_speed() {
    // G99 F0.1 at a measured 300 rev/min: 0.1 × 5 rev/s = 0.5 mm/s =
    // 30 mm/min, whatever S says (the simulation would give 0.1 × 600 =
    // 60 mm/min).
    let src = "O0001\nM03 S600\nG99 G01 W-2 F0.1\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, sp| ctl.set_spindle_feedback(sp.time_s * 5.0, 300.0),
        60.0,
    );
    assert_eq!(r.state, runtime::RunState::Ended);
    let top = r.pts.iter().map(|p| p.feed).fold(0.0, f64::max);
    assert!((top - 30.0).abs() < 1e-6, "top feed {top}");
}
