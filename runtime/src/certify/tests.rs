use super::chain::long_is_z;
use super::*;
use crate::math::PI;
use alloc::string::ToString;
use alloc::vec::Vec;
use nc::event::SpindleDir;
use nc::{Event, Sink};

/// A run on the reference machine (X 1500, Z 2000 mm/s², feeds
/// ≤ 4000/5000 mm/min, rapids 6000/10000 mm/min, period 1 ms),
/// starting at machine zero = work zero.
fn certifier() -> Certifier {
    Certifier::new(&Config::default(), 0.0, 0.0, 0.0)
}

/// A set point at period `k` (time k ms), work = machine + `shift`
/// (diameter, Z).
fn at(k: u32, axis: (f64, f64), shift: (f64, f64), motion: Motion) -> SetPoint {
    SetPoint {
        time_s: f64::from(k) * 0.001,
        x: axis.0 + shift.0,
        z: axis.1 + shift.1,
        axis_x: axis.0,
        axis_z: axis.1,
        line: 10 + k,
        motion,
        ..SetPoint::default()
    }
}

/// Z positions of a stop-to-stop feed at 2000 mm/s² (the limit):
/// z = −a·t²/2 for 10 periods, then braking symmetrically.
fn z_profile(a: f64) -> Vec<f64> {
    let dt = 0.001;
    let mut z = Vec::new();
    for k in 1..=10 {
        let t = f64::from(k) * dt;
        z.push(-a * t * t / 2.0);
    }
    let top = -a * (10.0 * dt) * (10.0 * dt) / 2.0;
    for k in 1..=10 {
        let t = f64::from(10 - k) * dt;
        z.push(2.0 * top + a * t * t / 2.0);
    }
    z
}

#[test]
fn a_move_at_the_limits_is_certified() {
    let mut c = certifier();
    let z = z_profile(2000.0);
    // The canon end point: Z = 2 × (−2000 × 0.01² / 2) = −0.2.
    c.emit(Event::Line {
        x: 0.0,
        z: -0.2,
        c: None,
    });
    for (k, &z) in z.iter().enumerate() {
        c.period(&at(k as u32 + 1, (0.0, z), (0.0, 0.0), Motion::Feed));
    }
    c.finish(true);
    assert_eq!(c.violation(), None);
    // Top speed 2000 × 0.01 = 20 mm/s, but the finite difference of
    // period 10 is (z10 − z9)/dt = 2000 × (0.1² − 0.09²)/2 … /dt
    // = 19 mm/s; the acceleration is exactly the limit.
    let v = c.worst(Kind::Velocity).unwrap();
    assert!((v.value.abs() - 19.0).abs() < 1e-6, "{v:?}");
    let a = c.worst(Kind::Acceleration).unwrap();
    assert!((a.ratio - 1.0).abs() < 1e-6, "{a:?}");
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 1 of 1 reached"));
}

#[test]
fn a_thread_start_in_one_period_is_caught() {
    // Z from rest to 1.5 mm/rev × 600 rev/min = 15 mm/s at once: the
    // second difference is 0.015 mm / (1 ms)² = 15 000 mm/s².
    let mut c = certifier();
    c.period(&at(1, (0.0, 0.0), (0.0, 0.0), Motion::Thread));
    c.period(&at(2, (0.0, -0.015), (0.0, 0.0), Motion::Thread));
    let v = *c.violation().expect("a violation");
    assert_eq!(
        (v.kind, v.subject, v.line),
        (Kind::Acceleration, Subject::Z, 12)
    );
    assert!((v.value.abs() - 15_000.0).abs() < 1e-6, "{v:?}");
    assert_eq!(v.limit, 2000.0);
    let text = v.to_string();
    assert!(
        text.contains(
            "at 0.002000 s: Z acceleration 15000.000 mm/s² exceeds its limit 2000.000 mm/s²"
        ),
        "{text}"
    );
}

#[test]
fn feeds_and_rapids_have_their_own_speed_limits() {
    // 0.07 mm of radius in 1 ms = 70 mm/s: above X's cutting feed
    // (4000 mm/min = 66.667 mm/s), below its rapid (100 mm/s). The
    // acceleration is measured too, so X builds the speed slowly:
    // 70 mm/s at 1500 mm/s² takes 47 periods (70/1.5).
    for (motion, bad) in [(Motion::Rapid, false), (Motion::Feed, true)] {
        let mut c = certifier();
        let (mut r, mut v, mut k) = (0.0f64, 0.0f64, 0);
        while k < 200 {
            v = (v + 1.5).min(70.0); // mm/s gained per period
            r += v * 0.001;
            k += 1;
            c.period(&at(k, (2.0 * r, 0.0), (0.0, 0.0), motion));
        }
        let f = c.worst(Kind::Velocity).unwrap();
        assert!((f.value - 70.0).abs() < 1e-6, "{f:?}");
        assert_eq!(c.violation().is_some(), bad, "{motion:?}");
        if bad {
            let f = c.violation().unwrap();
            assert_eq!(
                (f.kind, f.subject, f.limit),
                (Kind::Velocity, Subject::X, 4000.0 / 60.0)
            );
        }
    }
}

#[test]
fn an_origin_change_is_no_jump_and_end_points_follow_it() {
    // G00 Z-0.2 in work = machine; then G50 moves work zero by 100 mm
    // (work Z = machine Z + 100): the next end point, Z = 99.8 in the
    // new work frame, is the machine's Z −0.2 again … back to 0.
    let mut c = certifier();
    c.emit(Event::Line {
        x: 0.0,
        z: -0.2,
        c: None,
    });
    let z = z_profile(2000.0);
    let mut k = 0;
    for &z in &z {
        k += 1;
        c.period(&at(k, (0.0, z), (0.0, 0.0), Motion::Feed));
    }
    c.emit(Event::Origin { x: 0.0, z: 100.0 });
    c.emit(Event::Line {
        x: 0.0,
        z: 100.0,
        c: None,
    });
    k += 1;
    c.period(&at(k, (0.0, -0.2), (0.0, 100.0), Motion::None));
    for &z in &z {
        k += 1;
        c.period(&at(k, (0.0, -0.2 - z), (0.0, 100.0), Motion::Feed));
    }
    c.finish(true);
    assert_eq!(c.violation(), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 2 of 2 reached"));
}

#[test]
fn a_shift_after_the_tool_settled_misses_no_end_point() {
    // Jerk limiting: the canon runs ahead of the set points, so the
    // next end point (work Z−0.1 after a shift of 0.3 mm, machine
    // Z−0.4) is queued while the tool settles on Z−0.2: its last
    // period, from Z−0.1995 (within the tolerance) to Z−0.2, goes
    // away from the next point in the old frame (0.0995 → 0.1 mm).
    // The shift then moves the tool's work point 0.3 mm without a
    // step: the tool did not cut by the point, which it reaches
    // 0.2 mm later.
    let mut c = certifier();
    c.emit(Event::Line {
        x: 0.0,
        z: -0.2,
        c: None,
    });
    let z = z_profile(2000.0);
    let mut k = 0;
    for &z in &z {
        k += 1;
        c.period(&at(k, (0.0, z * 0.9975), (0.0, 0.0), Motion::Feed));
    }
    c.emit(Event::Origin { x: 0.0, z: 0.3 });
    c.emit(Event::Line {
        x: 0.0,
        z: -0.1,
        c: None,
    });
    for shift in [0.0, 0.3] {
        k += 1;
        c.period(&at(k, (0.0, -0.2), (0.0, shift), Motion::Feed));
    }
    for &z in &z {
        k += 1;
        c.period(&at(k, (0.0, -0.2 + z), (0.0, 0.3), Motion::Feed));
    }
    c.finish(true);
    assert_eq!(c.violation(), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 2 of 2 reached"));
}

#[test]
fn a_shift_and_the_first_step_in_one_period() {
    // Standing at machine X40 Z10 = work X40 Z10; G55 moves work zero
    // so that the point is X35, and the same period steps 0.003 mm
    // (diameter) towards X30: the zero-length RAPID X35 is where the
    // step began in the new frame, so it is reached.
    let mut c = Certifier::new(&Config::default(), 40.0, 10.0, 0.0);
    c.emit(Event::Origin { x: 5.0, z: 0.0 });
    c.emit(Event::Rapid {
        x: 35.0,
        z: 10.0,
        c: None,
    });
    c.period(&at(1, (40.0, 10.0), (0.0, 0.0), Motion::None));
    c.period(&at(2, (39.997, 10.0), (-5.0, 0.0), Motion::Rapid));
    c.finish(true);
    assert_eq!(c.violation(), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 1 of 1 reached"));
}

#[test]
fn an_end_point_not_reached_is_reported_where_the_path_came_nearest() {
    // The path stops 0.002 mm short of Z−0.2: it came nearest on its
    // last period (line 30), 0.002 mm away.
    let mut c = certifier();
    c.emit(Event::Line {
        x: 0.0,
        z: -0.2,
        c: None,
    });
    for (k, &z) in z_profile(2000.0).iter().enumerate() {
        c.period(&at(k as u32 + 1, (0.0, z * 0.99), (0.0, 0.0), Motion::Feed));
    }
    assert_eq!(c.violation(), None); // not yet: the run goes on
    c.finish(true);
    let f = *c.violation().expect("the end point is missed");
    assert_eq!((f.kind, f.line), (Kind::EndPoint, 30));
    assert!((f.value - 0.002).abs() < 1e-9, "{f:?}");
    // A run that stopped early (an alarm) owes no end points.
    let mut c = certifier();
    c.emit(Event::Line {
        x: 0.0,
        z: -0.2,
        c: None,
    });
    c.finish(false);
    assert_eq!(c.violation(), None);
}

#[test]
fn a_reversal_after_an_end_point_reached_early_is_no_miss() {
    // G01 X0.004 (radius 0.002) then back to X−0.003 (radius −0.0015),
    // as a random contour ran them: the period to r 0.0015 comes
    // 0.0005 mm near the first end point and still closes on it, the
    // next one ends on it, the tool stands a period and comes back.
    // Had the first counted as reached at 0.0005 mm, the path would
    // have neared r −0.0015 no more than 0.0015 mm and then left it,
    // by as much as it moved: a cut corner to the walk, though the
    // tool was still going to the first end point. It reaches both.
    let mut c = certifier();
    for x in [0.004, -0.003] {
        c.emit(Event::Line { x, z: 0.0, c: None });
    }
    let radii = [0.0, 0.0015, 0.002, 0.002, 0.0005, -0.00125, -0.0015];
    for (k, &r) in radii.iter().enumerate() {
        c.period(&at(k as u32 + 1, (2.0 * r, 0.0), (0.0, 0.0), Motion::Feed));
    }
    c.finish(true);
    assert_eq!(c.violation(), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 2 of 2 reached"));
}

/// How the trace of `full_circle` runs the circle.
#[derive(Clone, Copy)]
enum Round {
    /// All the way round, back on its end point.
    Whole,
    /// Its last quarter spirals out to 0.002 mm beyond the end point
    /// on the radius; the last line then runs back to its own end.
    Wide,
    /// Not at all: the tool goes straight on.
    Skipped,
}

/// `G01 Z−10` from X20 Z0 (line 2), a full G03 circle about X16 Z−10
/// (radius 2, tangent to the line, line 3), `G01 Z−20` (line 4), at
/// 0.01 mm a period; the circle in 1257 periods (2π·2/1257 = 0.009997
/// mm of arc), run as `round` says.
fn full_circle(round: Round) -> Certifier {
    let mut c = Certifier::new(&Config::default(), 20.0, 0.0, 0.0);
    c.emit(Event::Line {
        x: 20.0,
        z: -10.0,
        c: None,
    });
    c.emit(Event::Arc {
        dir: nc::event::Dir::Ccw,
        x: 20.0,
        z: -10.0,
        cx: 16.0,
        cz: -10.0,
    });
    c.emit(Event::Line {
        x: 20.0,
        z: -20.0,
        c: None,
    });
    let mut k = 0;
    let mut step = |c: &mut Certifier, r: f64, z: f64, line: u32, motion: Motion| {
        k += 1;
        c.period(&SetPoint {
            line,
            ..at(k, (2.0 * r, z), (0.0, 0.0), motion)
        });
    };
    step(&mut c, 10.0, 0.0, 2, Motion::None);
    for i in 1..=1000 {
        step(&mut c, 10.0, -0.01 * f64::from(i), 2, Motion::Feed);
    }
    let n = 1257;
    let mut back = 0.0;
    for i in 1..=n {
        if let Round::Skipped = round {
            break;
        }
        let phi = 2.0 * PI * f64::from(i) / f64::from(n);
        // (Wide: the radius grows by 0.002 over the last quarter.)
        if let Round::Wide = round {
            back = (0.002 * (phi - 1.5 * PI) / (0.5 * PI)).max(0.0);
        }
        let rad = 2.0 + back;
        step(
            &mut c,
            8.0 + rad * phi.cos(),
            -10.0 - rad * phi.sin(),
            3,
            Motion::Arc,
        );
    }
    for i in 1..=1000 {
        let t = f64::from(i) / 1000.0;
        step(
            &mut c,
            10.0 + back * (1.0 - t),
            -10.0 - 10.0 * t,
            4,
            Motion::Feed,
        );
    }
    c.finish(true);
    c
}

/// A full circle starts on its end point, but that end point is due
/// when the tool comes back to it, not where it leaves it.
#[test]
fn a_full_circle_ends_where_it_comes_back() {
    let c = full_circle(Round::Whole);
    assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 3 of 3 reached"));
    // Coming back 0.002 mm wide of it is a miss, at the circle's last
    // period (line 3): its chord ends 0.002 mm out on the radius and
    // passes the end point at 0.002·cos(δ/2) ≈ 0.002 − 6e-9 mm (δ the
    // 0.005 rad a period turns).
    let c = full_circle(Round::Wide);
    let f = *c.worst(Kind::EndPoint).expect("the circle's end is missed");
    assert!(f.violates() && (f.value - 0.002).abs() < 1e-8, "{f:?}");
    assert_eq!(f.line, 3);
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 2 of 3 reached"));
    // A circle the tool never ran: its end point is not reached at its
    // start. The miss is placed where the walk began to wait for it:
    // the period that reached the circle's start (line 2's last).
    let c = full_circle(Round::Skipped);
    let f = *c
        .worst(Kind::EndPoint)
        .expect("the skipped circle is caught");
    let at_1001 = (f.time_s - 1.001).abs() < 1e-9;
    assert!(f.violates() && f.line == 2 && at_1001, "{f:?}");
    assert!(f.to_string().contains("does not come back to it"), "{f}");
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 1 of 3 reached"));
}

#[test]
fn end_points_are_reached_in_order_within_a_step() {
    // G01 W−0.003, back to Z0, then to (r 0.0015, Z −0.004), at 1–2 µm
    // a period. The step from Z −0.001 to −0.0026 ends 0.0004 mm short
    // of the first end point and began 0.001 mm from the second:
    // that one is only reached after the first, on the way back. Taken
    // at once, the walk judged the third from Z −0.003, where it came
    // 0.0018 mm near, and called the step that leaves Z0 for it, by
    // 0.002 mm, a miss.
    let mut c = certifier();
    for (x, z) in [(0.0, -0.003), (0.0, 0.0), (0.003, -0.004)] {
        c.emit(Event::Line { x, z, c: None });
    }
    let path = [
        (0.0, -0.001),
        (0.0, -0.0026),
        (0.0, -0.003),
        (0.0, -0.001),
        (0.0, 0.0),
        (0.000703, -0.001874),
        (0.0014, -0.00375),
        (0.0015, -0.004),
    ];
    for (k, &(r, z)) in path.iter().enumerate() {
        c.period(&at(k as u32 + 1, (2.0 * r, z), (0.0, 0.0), Motion::Feed));
    }
    c.finish(true);
    // (The made-up steps break the axes' acceleration: only the end
    // points are judged here.)
    assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 3 of 3 reached"));
}

#[test]
fn a_corner_cut_between_two_periods_is_a_miss_and_the_walk_goes_on() {
    // G01 Z−0.1 then X0.1 (radius 0.05) at 20 mm/s: the periods at Z
    // −0.095 and then (X 0.03, Z −0.1)… jump over the corner Z−0.1: the
    // chord from (r 0, Z −0.095) to (r 0.015, Z −0.1) passes it at
    // 0.005 × 0.015 / hypot(0.015, 0.005) = 0.0047434 mm, its nearest
    // (period 6, line 16). The next end point is reached.
    let mut c = certifier();
    c.emit(Event::Line {
        x: 0.0,
        z: -0.1,
        c: None,
    });
    c.emit(Event::Line {
        x: 0.1,
        z: -0.1,
        c: None,
    });
    let path = [
        (0.0, -0.02),
        (0.0, -0.04),
        (0.0, -0.06),
        (0.0, -0.08),
        (0.0, -0.095),
        (0.03, -0.1),
        (0.07, -0.1),
        (0.1, -0.1),
    ];
    for (k, &xz) in path.iter().enumerate() {
        c.period(&at(k as u32 + 1, xz, (0.0, 0.0), Motion::Feed));
    }
    c.finish(true);
    let f = *c.worst(Kind::EndPoint).expect("the corner is missed");
    assert_eq!(f.line, 16);
    let want = 0.005 * 0.015 / libm::hypot(0.015, 0.005);
    assert!(
        (f.value - want).abs() < 1e-12 && (want - 0.0047434).abs() < 1e-7,
        "{f:?}"
    );
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 1 of 2 reached"));
}

#[test]
fn incomplete_lead_lengths() {
    // 1.5 mm/rev at 600 rev/min: 15 mm/s; Z at 2000 mm/s² needs
    // 15² / (2 × 2000) = 0.05625 mm.
    assert!((incomplete_lead(15.0, 2000.0, 1500.0, 30.0, 0.0) - 0.05625).abs() < 1e-12);
    // A 45° taper: X (1500 mm/s²) must follow Z one to one, so Z may
    // accelerate at only 1500: 225 / 3000 = 0.075 mm.
    assert!((incomplete_lead(15.0, 2000.0, 1500.0, 10.0, -10.0) - 0.075).abs() < 1e-12);
    // A shallow taper (X 1 in Z 4): X allows 1500 × 4 = 6000 > 2000.
    assert!((incomplete_lead(15.0, 2000.0, 1500.0, -8.0, 2.0) - 0.05625).abs() < 1e-12);
}

/// A G32 Z−30 with lead 1.5 at 600 rev/min (0.01 rev per period):
/// Z ramps at 2000 mm/s² to 15 mm/s (7.5 periods: take 8 at the
/// limit, then exactly 0.015 mm per period), with one wrong period
/// at `bad` where Z moves 0.0151 mm.
fn thread(bad: Option<u32>) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Spindle(SpindleDir::Cw));
    c.emit(Event::Rapid {
        x: 0.0,
        z: 0.0,
        c: None,
    });
    c.emit(Event::Thread {
        x: 0.0,
        z: -30.0,
        c: None,
        lead: 1.5,
        dlead: None,
        q: None,
    });
    let (mut z, mut v, mut turns) = (0.0f64, 0.0f64, 0.0);
    // 1900 periods: Z ends at about −28.4, short of the run-out.
    for k in 1..=1900u32 {
        v = (v + 2.0).min(15.0); // mm/s: 2000 mm/s² × 1 ms
        let step = if Some(k) == bad { 0.0151 } else { v * 0.001 };
        z -= step;
        turns += 0.01;
        let p = SetPoint {
            spindle_rpm: 600.0,
            spindle_turns: turns,
            ..at(k, (0.0, z), (0.0, 0.0), Motion::Thread)
        };
        c.period(&p);
    }
    c
}

/// A feed along Z from X20 Z0 to Z−10, then a quarter arc about X20
/// Z−12 to X24 Z−12, every 10 µm of Z a period; the period `off`
/// strays `by` mm out on the radius.
fn along(off: u32, by: f64) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Rapid {
        x: 20.0,
        z: 0.0,
        c: None,
    });
    c.emit(Event::Line {
        x: 20.0,
        z: -10.0,
        c: None,
    });
    c.emit(Event::Arc {
        dir: nc::event::Dir::Ccw,
        x: 24.0,
        z: -12.0,
        cx: 20.0,
        cz: -12.0,
    });
    let mut k = 0;
    let mut step = |c: &mut Certifier, r: f64, z: f64, motion: Motion| {
        k += 1;
        let r = if k == off { r + by } else { r };
        c.period(&at(k, (2.0 * r, z), (0.0, 0.0), motion));
    };
    step(&mut c, 10.0, 0.0, Motion::None);
    for i in 1..=1000 {
        step(&mut c, 10.0, -0.01 * f64::from(i), Motion::Feed);
    }
    // The arc: r = 10 + 2·sin θ, z = −12 + 2·cos θ, θ from 0 to 90°.
    for i in 1..=300 {
        let t = core::f64::consts::FRAC_PI_2 * f64::from(i) / 300.0;
        step(
            &mut c,
            10.0 + 2.0 * t.sin(),
            -12.0 + 2.0 * t.cos(),
            Motion::Arc,
        );
    }
    c.finish(true);
    c
}

#[test]
fn the_tool_is_held_to_its_lines_and_arcs() {
    let c = along(0, 0.0);
    let w = c.worst(Kind::Path).unwrap();
    assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
    // (The first period jumps from machine zero: only the path and
    // the end points matter here.)
    assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("path: worst 0.0000 mm off (1300 periods"));
    // 1.5 µm out on the radius in period 500 (Z −4.99), off the line
    // by as much, or in period 1290 (86.7° round the arc), off the
    // circle by √((2·sin 86.7° + 0.0015)² + (2·cos 86.7°)²) − 2 =
    // 1.49751 µm: caught; 0.5 µm is within the resolution.
    for (off, by) in [(500, 0.0015), (1290, 0.00149751)] {
        let w = *along(off, 0.0015).worst(Kind::Path).unwrap();
        assert!(w.violates() && (w.value - by).abs() < 1e-8, "{w:?}");
        assert_eq!(w.line, 10 + off);
        assert!(!along(off, 0.0005).worst(Kind::Path).unwrap().violates());
    }
}

/// A rapid from X20 Z0 to X40 Z−10 as a dog-leg: X (10 → 20 on the
/// radius) at 0.1 a period, Z at 0.05, so X arrives first; the period
/// `off` strays `by` mm beyond Z0.
fn dog_leg(off: u32, by: f64) -> Certifier {
    let mut c = certifier();
    for (x, z) in [(20.0, 0.0), (40.0, -10.0)] {
        c.emit(Event::Rapid { x, z, c: None });
    }
    c.period(&at(1, (20.0, 0.0), (0.0, 0.0), Motion::None));
    for k in 2..=201u32 {
        let i = f64::from(k - 1);
        let (r, mut z) = ((10.0 + 0.1 * i).min(20.0), -0.05 * i);
        if k == off {
            z = by;
        }
        c.period(&at(k, (2.0 * r, z), (0.0, 0.0), Motion::Rapid));
    }
    c
}

#[test]
fn a_rapid_is_held_to_the_rectangle_of_its_ends() {
    let w = *dog_leg(0, 0.0).worst(Kind::Path).unwrap();
    assert!(w.value == 0.0 && !w.violates(), "{w:?}");
    // Z at +0.002 in period 50 (X at 14.9, inside): 0.002 mm out.
    let w = *dog_leg(50, 0.002).worst(Kind::Path).unwrap();
    assert!(w.violates() && (w.value - 0.002).abs() < 1e-12, "{w:?}");
    assert_eq!(w.line, 60);
}

/// `G00 X20 Z5 C0 / G12.1 / G01 X10 C0 / G13.1 / G01 Z−5` by hand:
/// the plane's line in 50 periods from the radius 10 to `to` at Z5
/// and C0 (the canon's end: 5), the line after it in 100 periods from
/// Z5 to Z−5 at the radius `to`, `by` mm beyond in period `off`.
fn after_polar(to: f64, off: u32, by: f64) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Rapid {
        x: 20.0,
        z: 5.0,
        c: Some(0.0),
    });
    c.emit(Event::PolarOn);
    c.emit(Event::PlaneMove {
        plane: nc::event::Plane::Polar,
        motion: nc::event::PlaneMotion::Line,
        a: 10.0,
        b: 0.0,
        off: None,
    });
    c.emit(Event::PolarOff { x: 10.0, c: 0.0 });
    c.emit(Event::Line {
        x: 10.0,
        z: -5.0,
        c: None,
    });
    c.period(&at(1, (20.0, 5.0), (0.0, 0.0), Motion::None));
    let mut k = 1;
    for i in 1..=50 {
        k += 1;
        let r = 10.0 + (to - 10.0) * f64::from(i) / 50.0;
        c.period(&at(k, (2.0 * r, 5.0), (0.0, 0.0), Motion::Feed));
    }
    for i in 1..=100 {
        k += 1;
        let r = if k == off { to + by } else { to };
        let z = 5.0 - 10.0 * f64::from(i) / 100.0;
        c.period(&at(k, (2.0 * r, z), (0.0, 0.0), Motion::Feed));
    }
    c.finish(true);
    c
}

#[test]
fn the_move_after_polar_interpolation_starts_where_the_plane_ended() {
    // The line after G13.1 runs from X10 (the radius 5), where the
    // plane's line ended, not from X20, where the plane began (the
    // plane's periods at Z5, X 20 → 10, lie 1.4 mm and more off the
    // line from X20 Z5 to X10 Z−5 but are held to no line).
    let c = after_polar(5.0, 0, 0.0);
    let w = c.worst(Kind::Path).unwrap();
    assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
    assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 3 of 3 reached"));
    // 2 µm out on the radius in period 100 of the run (Z0.1): caught.
    let w = *after_polar(5.0, 100, 0.002).worst(Kind::Path).unwrap();
    assert!(w.violates() && (w.value - 0.002).abs() < 1e-9, "{w:?}");
    assert_eq!(w.line, 110);
    // A plane that stops at X12: its end point, X10, is missed by 1 mm
    // on the radius (where the tool stood at the nearest), and the
    // walk waits there (the line after it is not the move running).
    let c = after_polar(6.0, 0, 0.0);
    let e = c.worst(Kind::EndPoint).unwrap();
    assert!(e.violates() && (e.value - 1.0).abs() < 1e-9, "{e:?}");
    assert_eq!(e.line, 61);
}

/// `G00 X20 Z0 C0 / G7.1 C10. / G01 Z−10 C90 / G7.1 C0 / G01 X30` by
/// hand: the plane's line in 100 periods from Z0 C0 to Z−10 and C
/// `to` (the canon's end: 90°) at X20, then the line along X to X30
/// at Z−10 in 50 periods.
fn after_cylinder(to: f64) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Rapid {
        x: 20.0,
        z: 0.0,
        c: Some(0.0),
    });
    c.emit(Event::Cylinder(Some(10.0)));
    c.emit(Event::PlaneMove {
        plane: nc::event::Plane::Cylinder,
        motion: nc::event::PlaneMotion::Line,
        a: -10.0,
        b: 90.0,
        off: None,
    });
    c.emit(Event::Cylinder(None));
    c.emit(Event::Line {
        x: 30.0,
        z: -10.0,
        c: None,
    });
    let with_c = |p: SetPoint, deg: f64| SetPoint { c: Some(deg), ..p };
    c.period(&with_c(at(1, (20.0, 0.0), (0.0, 0.0), Motion::None), 0.0));
    let mut k = 1;
    for i in 1..=100 {
        k += 1;
        let f = f64::from(i) / 100.0;
        let p = at(k, (20.0, -10.0 * f), (0.0, 0.0), Motion::Feed);
        c.period(&with_c(p, to * f));
    }
    for i in 1..=50 {
        k += 1;
        let x = 20.0 + 10.0 * f64::from(i) / 50.0;
        c.period(&with_c(at(k, (x, -10.0), (0.0, 0.0), Motion::Feed), to));
    }
    c.finish(true);
    c
}

#[test]
fn the_move_after_cylindrical_interpolation_starts_where_the_plane_ended() {
    // From X20 Z−10 (not Z0, where G7.1 began).
    let c = after_cylinder(90.0);
    let w = c.worst(Kind::Path).unwrap();
    assert!(w.value < 1e-12 && !w.violates(), "{w:?}");
    assert_eq!(c.worst(Kind::EndPoint), None, "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 3 of 3 reached"));
    // The plane ends at C80, not C90: X and Z as programmed, but the
    // tool stands 2 · 10 · sin 5° = 1.74311 mm from the plane's end
    // about the spindle's axis.
    let e = *after_cylinder(80.0).worst(Kind::EndPoint).unwrap();
    let chord = 20.0 * 5f64.to_radians().sin();
    assert!(e.violates() && (e.value - chord).abs() < 1e-9, "{e:?}");
}

/// A G78 pass: a run-in from X25 Z5 to X23 Z4, the thread to Z−13, a
/// pull-out to X25 Z−15, 20 + 340 + 40 periods along the legs; in
/// period `off` of the thread X stands `by` mm (radius) below its
/// root, X23, as an axis that ran past the run-in's corner did.
fn g78_pass(off: u32, by: f64) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Rapid {
        x: 25.0,
        z: 5.0,
        c: None,
    });
    for (x, z) in [(23.0, 4.0), (23.0, -13.0), (25.0, -15.0)] {
        c.emit(Event::Thread {
            x,
            z,
            c: None,
            lead: 2.0,
            dlead: None,
            q: None,
        });
    }
    c.period(&at(1, (25.0, 5.0), (0.0, 0.0), Motion::None));
    let legs = [
        ((25.0, 5.0), (23.0, 4.0), 20),
        ((23.0, 4.0), (23.0, -13.0), 340),
    ];
    let mut k = 1;
    for ((x0, z0), (x1, z1), n) in legs.into_iter().chain([((23.0, -13.0), (25.0, -15.0), 40)]) {
        for i in 1..=n {
            let f = f64::from(i) / f64::from(n);
            let mut x = x0 + (x1 - x0) * f;
            k += 1;
            if k == off {
                x -= 2.0 * by;
            }
            c.period(&at(k, (x, z0 + (z1 - z0) * f), (0.0, 0.0), Motion::Thread));
        }
    }
    c
}

#[test]
fn a_thread_is_held_to_the_box_of_its_chain() {
    let w = *g78_pass(0, 0.0).worst(Kind::Path).unwrap();
    assert!(w.value == 0.0 && !w.violates(), "{w:?}");
    // 0.05 mm below the root in the thread's 5th period (period 26).
    let w = *g78_pass(26, 0.05).worst(Kind::Path).unwrap();
    assert!(w.violates() && (w.value - 0.05).abs() < 1e-9, "{w:?}");
    assert_eq!(w.line, 36);
    // Half a resolution below is within it.
    assert!(!g78_pass(26, 0.0005).worst(Kind::Path).unwrap().violates());
}

#[test]
fn the_catch_up_of_a_long_axis_that_a_corner_turns() {
    // A Z thread of lead 1.5 into a run-out 2 mm out on the radius and
    // 1 along Z: X is long there, at lead 1.5 × 2 = 3 along X, 1.5 of
    // Z a turn as before; X ran at 0 before, so it must run 3 mm per
    // turn faster. A 45° pull-out keeps Z long at Z's speed, and X
    // steps by 1.5.
    let z_thread = (V2::new(0.0, -20.0), (1.5, 0.0));
    let run_out = (V2::new(2.0, -1.0), (3.0, 0.0));
    assert_eq!(axis_steps([z_thread, run_out]), V2::new(3.0, 0.0));
    let pull_out = (V2::new(2.0, -2.0), (1.5, 0.0));
    assert_eq!(axis_steps([z_thread, pull_out]), V2::new(1.5, 0.0));
    // From rest to 15 mm/s at 1500 mm/s²: 15/1500 s to reach it, then
    // up 15/√3 at a and down at a/2: (0.01 + 0.0057735 + 0.011547) s
    // × 15 mm/s = 0.40981 mm.
    let d = catch_up_lead(15.0, 15.0, 1500.0, 66.667, LEAD_TOL);
    assert!((d - 0.409808).abs() < 1e-6, "{d}");
    // At 60 mm/s the peak (34.6 mm/s over the point) is cut to 6.667 by
    // the top speed: 0.04 s to reach 60, a lag of 1.2 mm; 0.004444 s up,
    // 0.008889 s down, which close 6.667²·3/3000 = 0.04444 mm, and
    // (1.2 − 0.04444)/6.667 = 0.17333 s at the top speed between:
    // 0.226667 s × 60 = 13.6 mm.
    let d = catch_up_lead(60.0, 60.0, 1500.0, 200.0 / 3.0, LEAD_TOL);
    assert!((d - 13.6).abs() < 1e-9, "{d}");
    // A thread at the axis's top speed: the lag stays, the lead is
    // kept once the axis runs at it (2/1500·... = 0.04444 s × 66.667).
    let v = 200.0 / 3.0;
    let d = catch_up_lead(v, v, 1500.0, v, LEAD_TOL);
    assert!((d - v * v / 1500.0).abs() < 1e-9, "{d}");
    assert_eq!(catch_up_lead(15.0, 0.0, 1500.0, 66.667, LEAD_TOL), 0.0);
}

/// A Z thread of lead 2 (X 20, Z 0 to −10, 500 periods at 0.02 mm)
/// into a run-out to X 36 Z −12 at lead 4 along X (X 0.04 mm and Z
/// 0.01 mm a period, 200 periods), the spindle at 600 rev/min, every
/// period on the programmed chain except one 0.0401 mm step of X at
/// `bad` periods into the run-out.
fn run_out(bad: u32) -> Certifier {
    let mut c = certifier();
    c.emit(Event::Spindle(SpindleDir::Cw));
    c.emit(Event::Rapid {
        x: 20.0,
        z: 0.0,
        c: None,
    });
    for (x, z, lead) in [(20.0, -10.0, 2.0), (36.0, -12.0, 4.0)] {
        c.emit(Event::Thread {
            x,
            z,
            c: None,
            lead,
            dlead: None,
            q: None,
        });
    }
    let (mut r, mut z, mut turns) = (10.0, 0.0, 0.0);
    for k in 1..=700u32 {
        if k <= 500 {
            z -= 0.02;
        } else {
            r += if k - 500 == bad { 0.0401 } else { 0.04 };
            z -= 0.01;
        }
        turns += 0.01;
        let p = SetPoint {
            spindle_rpm: 600.0,
            spindle_turns: turns,
            ..at(k, (2.0 * r, z), (0.0, 0.0), Motion::Thread)
        };
        c.period(&p);
    }
    c
}

#[test]
fn a_run_out_whose_long_axis_is_x_is_checked_after_the_catch_up() {
    // X must start at 40 mm/s: 40/1500 × (1 + 3/√3) = 0.072855 s,
    // 2.914 mm of X, + 10 % + 2 periods: 3.286 mm, 82 periods. A
    // wrong step in period 60 (X 2.4 mm out) is left out, one in
    // period 120 (4.8 mm) is caught: 0.25 % off. (Without the
    // catch-up only the incomplete lead, 40²/3000 × 1.1 + 0.04 =
    // 0.627 mm, would be left out.)
    let c = run_out(60);
    let w = c.worst(Kind::Lead).unwrap();
    assert!(!w.violates(), "{w:?}");
    let c = run_out(120);
    let w = *c.worst(Kind::Lead).unwrap();
    assert!(w.violates(), "{w:?}");
    assert_eq!(w.line, 10 + 620);
    assert!((w.value - 4.01).abs() < 1e-6 && w.limit == 4.0, "{w:?}");
}

#[test]
fn the_lead_is_checked_after_the_incomplete_lead() {
    // The ramp (lead below 1.5) is within the incomplete lead:
    // 0.05625 × 1.1 + 0.015 = 0.0769 mm; period 8 ends at
    // 2+4+…+14 µm + 15 = 0.071 mm, so period 9, which starts there,
    // is left out too; from period 10 on (Z −0.086 at its start) the
    // lead is 1.5.
    // Periods 10 to 1900 are checked: 1891. (The spindle is at 600
    // from the first period, a jump the spindle check reports; only
    // the lead matters here.)
    let c = thread(None);
    let w = c.worst(Kind::Lead).unwrap();
    assert!(w.ratio < 1e-9 && !w.violates(), "{w:?}");
    assert!(
        c.summary().to_string().contains("(1891 periods"),
        "{}",
        c.summary()
    );
    // A period of 0.0151 mm in a turn of 0.01: lead 1.51, 0.667 % off.
    let c = thread(Some(500));
    let f = *c.worst(Kind::Lead).unwrap();
    assert!(f.violates());
    assert_eq!(f.line, 510);
    assert!((f.value - 1.51).abs() < 1e-9 && f.limit == 1.5, "{f:?}");
}

#[test]
fn a_45_degree_pull_out_is_measured_along_z() {
    // The kernel's rule: Z is long when it moves at least as far as
    // X; a travel rounded 1.8e-15 mm the other way is still a tie.
    assert!(long_is_z(V2::new(2.0000000000000018, -2.0)));
    assert!(long_is_z(V2::new(2.0, -2.0)));
    assert!(!long_is_z(V2::new(2.001, -2.0)));
    // G32 Z−30 at lead 1.5, 600 rev/min (Z ramped to 15 mm/s as in
    // `thread`), then a 45° pull-out to r 2.0000000000000018 Z−32.
    // Z stays locked at 0.015 mm per 0.01 turn; X starts from rest at
    // the corner and, lagging, gains 1.5 mm/s per period (its
    // 1500 mm/s²) up to 20 mm/s to catch up: measured along X the
    // lead would reach 0.020 / 0.01 = 2.0, 33 % off. Along Z it is
    // 1.5 in every period checked, the chamfer's too: from
    // 15²/(2 × 1500) × 1.1 + 0.015 = 0.0975 mm past the corner.
    let mut c = certifier();
    c.emit(Event::Spindle(SpindleDir::Cw));
    c.emit(Event::Rapid {
        x: 0.0,
        z: 0.0,
        c: None,
    });
    for (x, z) in [(0.0, -30.0), (4.0000000000000036, -32.0)] {
        c.emit(Event::Thread {
            x,
            z,
            c: None,
            lead: 1.5,
            dlead: None,
            q: None,
        });
    }
    let (mut r, mut z, mut vz, mut vx, mut turns) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0);
    let mut k = 0;
    let mut chamfer = 0;
    while z > -31.8 {
        k += 1;
        vz = (vz + 2.0).min(15.0);
        z -= vz * 0.001;
        if z < -30.0 {
            vx = (vx + 1.5).min(20.0);
            r += vx * 0.001;
            chamfer += 1;
        }
        turns += 0.01;
        c.period(&SetPoint {
            spindle_rpm: 600.0,
            spindle_turns: turns,
            ..at(k, (2.0 * r, z), (0.0, 0.0), Motion::Thread)
        });
    }
    assert!(vx == 20.0 && chamfer > 100, "{vx} {chamfer}");
    let w = c.worst(Kind::Lead).unwrap();
    assert!(w.ratio < 1e-9 && !w.violates(), "{w:?}");
}

#[test]
fn the_bound_of_a_chain_corner() {
    let (acc, dt) = ([1500.0, 2000.0], 0.001);
    let b = |d0: (f64, f64), l0: f64, d1: (f64, f64), l1: f64| {
        let legs = [
            (V2::new(d0.0, d0.1), (l0, 0.0)),
            (V2::new(d1.0, d1.1), (l1, 0.0)),
        ];
        chain_corner_mm(legs, acc, dt)
    };
    let near = |a: f64, b: f64| (a - b).abs() < 1e-15;
    // Z thread into a 45° pull-out, lead 1.5: per turn (0, −1.5) then
    // (1.5, −1.5); Z keeps its speed, X changes: 1500 × 0.001² mm.
    assert!(near(b((0.0, -30.0), 1.5, (2.0, -2.0), 1.5), 0.0015));
    // A taper (r 1 in Z 35) into its pull-out: still only X.
    assert!(near(b((1.0, -35.0), 2.0, (1.0, -2.0), 2.0), 0.0015));
    // A face thread (X long) into a run-out along Z: Z changes.
    assert!(near(b((-10.0, 0.0), 1.5, (-2.0, -1.0), 1.5), 0.002));
    // A run-out with J > K at lead × J/K keeps Z at 2 per turn (the
    // kernel's rule): (0, −2) then X-long (3, −1) at lead 6, (6, −2).
    assert!(near(b((0.0, -10.0), 2.0, (3.0, -1.0), 6.0), 0.0015));
    // At the bare lead 2 Z would slow to 0.667 per turn: both axes,
    // √(1500² + 2000²) × 0.001² = 0.0025 mm.
    assert!(near(b((0.0, -10.0), 2.0, (3.0, -1.0), 2.0), 0.0025));
    // A straight chain: nothing turns.
    assert_eq!(b((0.0, -10.0), 2.0, (0.0, -5.0), 2.0), 0.0);
    // G34: the lead at the end of the first leg, √(2² + 2 × 0.1 × 10)
    // = √6, is the second leg's start: nothing turns.
    let legs = [
        (V2::new(0.0, -10.0), (2.0, 0.1)),
        (V2::new(0.0, -5.0), (libm::sqrt(6.0), 0.1)),
    ];
    assert_eq!(chain_corner_mm(legs, acc, dt), 0.0);
}

/// Lead 1.5 at 600 rev/min (0.015 mm of Z a period) from Z−29.9551
/// into a 45° pull-out at Z−30: the period that turns ends 0.0149 mm
/// into the corner, 0.0001 mm past it, with X `x1` mm (radius) out.
/// Returns the certifier after six periods.
fn corner(x1: f64, thread: bool) -> Certifier {
    let mut c = Certifier::new(&Config::default(), 0.0, -29.9551, 0.0);
    c.emit(Event::Rapid {
        x: 0.0,
        z: -29.9551,
        c: None,
    });
    for (x, z) in [(0.0, -30.0), (4.0, -32.0)] {
        c.emit(if thread {
            Event::Thread {
                x,
                z,
                c: None,
                lead: 1.5,
                dlead: None,
                q: None,
            }
        } else {
            Event::Line { x, z, c: None }
        });
    }
    let path = [
        (0.0, -29.9701),
        (0.0, -29.9851),
        (x1, -30.0001),
        (x1 + 0.003, -30.0151),
        (x1 + 0.0075, -30.0301),
        (x1 + 0.0135, -30.0451),
    ];
    for (k, &(r, z)) in path.iter().enumerate() {
        c.period(&at(k as u32 + 1, (2.0 * r, z), (0.0, 0.0), Motion::Thread));
    }
    c
}

#[test]
fn a_chain_corner_at_speed_is_reached_within_one_period_of_acceleration() {
    // X from rest at its full 1500 mm/s² moves a·dt² = 0.0015 mm in
    // the period that turns: the chord from (r 0, Z −29.9851) to
    // (0.0015, −30.0001) passes the corner (0, −30) at
    // 0.0149 × 0.0015 / hypot(0.0015, 0.015) = 0.0014826 mm: more than
    // 0.001, within the corner's bound of 0.0015 mm.
    let want = 0.0149 * 0.0015 / libm::hypot(0.0015, 0.015);
    assert!((want - 0.0014826).abs() < 1e-7);
    let c = corner(0.0015, true);
    assert!(c.worst(Kind::EndPoint).is_none(), "{}", c.summary());
    assert!(c
        .summary()
        .to_string()
        .contains("end points: 2 of 3 reached"));
    // The same path programmed as feeds is no thread chain: 0.001 mm.
    let c = corner(0.0015, false);
    let f = *c.worst(Kind::EndPoint).expect("missed");
    assert!(f.violates() && f.limit == END_POINT_MM, "{f:?}");
    assert!((f.value - want).abs() < 1e-9, "{f:?}");
    // An X that jumps twice a·dt² (0.003 mm) misses the corner by
    // 0.0149 × 0.003 / hypot(0.003, 0.015) = 0.0029221 mm > 0.0015.
    let c = corner(0.003, true);
    let f = *c.worst(Kind::EndPoint).expect("missed");
    assert!(f.violates() && (f.limit - 0.0015).abs() < 1e-15, "{f:?}");
    let want = 0.0149 * 0.003 / libm::hypot(0.003, 0.015);
    assert!((f.value - want).abs() < 1e-9 && (want - 0.0029221).abs() < 1e-7);
    assert!(f.to_string().contains("(tolerance 0.0015 mm)"), "{f}");
}

#[test]
fn the_spindle_keeps_its_acceleration() {
    // 1000 rev/min/s is 1 rev/min per period: a step of 2 is twice it.
    let mut c = certifier();
    let p = |k, rpm| SetPoint {
        spindle_rpm: rpm,
        ..at(k, (0.0, 0.0), (0.0, 0.0), Motion::None)
    };
    c.period(&p(1, 1.0));
    c.period(&p(2, 2.0));
    assert_eq!(c.violation(), None);
    c.period(&p(3, 4.0));
    let f = *c.violation().unwrap();
    assert_eq!(
        (f.kind, f.value, f.limit),
        (Kind::SpindleAccel, 2000.0, 1000.0)
    );
}

#[test]
fn g96_holds_the_surface_speed() {
    // G96 S150 at X50: 1000 × 150 / (π × 50) = 954.93 rev/min.
    let target = 1000.0 * 150.0 / (PI * 50.0);
    let run = |rpm: [f64; 3]| {
        let mut c = Certifier::new(&Config::default(), 50.0, 0.0, 0.0);
        c.emit(Event::Speed {
            s: 150.0,
            css: true,
            max: None,
        });
        c.emit(Event::Spindle(SpindleDir::Cw));
        c.emit(Event::Line {
            x: 50.0,
            z: -10.0,
            c: None,
        });
        // Feeding at X50 (it stays: a face would change the target).
        for (k, rpm) in rpm.into_iter().enumerate() {
            c.period(&SetPoint {
                spindle_rpm: rpm,
                ..at(
                    k as u32 + 1,
                    (50.0, -0.001 * k as f64),
                    (0.0, 0.0),
                    Motion::Feed,
                )
            });
        }
        c.worst(Kind::SurfaceSpeed).copied()
    };
    let held = run([target; 3]).unwrap();
    assert!(held.ratio < 1e-12 && !held.violates(), "{held:?}");
    // 900 rev/min steady: (954.93 − 900) / 954.93 = 5.75 % off.
    let off = run([900.0; 3]).unwrap();
    assert!(off.violates());
    assert!((off.ratio - (target - 900.0) / target).abs() < 1e-12);
    assert!((off.ratio - 0.0575).abs() < 1e-4);
    // Still speeding up at the spindle's 1 rev/min per period: exempt.
    let chasing = run([898.0, 899.0, 900.0]).unwrap();
    assert_eq!(chasing.time_s, 0.001, "only the first period counts");
}

#[test]
fn travel_is_checked_where_the_machine_has_soft_limits() {
    // Z's travel −5…2: standing at Z−4.999 (0.001 mm inside), then a
    // step of 0.002 mm to Z−5.001 (0.001 mm beyond: a violation).
    // X at X4 (radius 2) against −260…2 as a diameter (the
    // reference): 1 mm inside its upper limit, as a diameter.
    let mut cfg = Config::default();
    (cfg.x.soft_limits, cfg.x.min, cfg.x.max) = (true, -130.0, 1.0);
    (cfg.z.soft_limits, cfg.z.min, cfg.z.max) = (true, -5.0, 2.0);
    let mut c = Certifier::new(&cfg, 0.0, -4.999, 0.0);
    for k in 1..=3 {
        c.period(&at(k, (0.0, -4.999), (0.0, 0.0), Motion::None));
    }
    let w = *c.worst(Kind::Travel).unwrap();
    assert!((w.ratio + 0.001).abs() < 1e-9 && w.limit == -5.0, "{w:?}");
    assert!(c.violation().is_none());
    assert!(c
        .summary()
        .to_string()
        .contains("travel: nearest 0.001 mm inside its limit (Z at -4.999 mm, line 11)"));
    c.period(&at(4, (0.0, -5.001), (0.0, 0.0), Motion::Feed));
    let v = *c.violation().unwrap();
    assert_eq!((v.kind, v.subject, v.line), (Kind::Travel, Subject::Z, 14));
    assert!((v.ratio - 0.001).abs() < 1e-9, "{v:?}");
    assert!(v
        .to_string()
        .ends_with("Z at -5.001 mm leaves its travel: the limit is -5.000 mm"));
    // X as a diameter: radius 0.5 against the upper limit 1 (X2).
    let mut c = Certifier::new(&cfg, 1.0, 0.0, 0.0);
    c.period(&at(1, (1.0, 0.0), (0.0, 0.0), Motion::None));
    let w = *c.worst(Kind::Travel).unwrap();
    assert_eq!(
        (w.subject, w.value, w.limit, w.ratio),
        (Subject::X, 1.0, 2.0, -1.0)
    );
    // Without soft limits: not limited (standing at Z−900).
    let mut c = Certifier::new(&Config::default(), 0.0, -900.0, 0.0);
    c.period(&at(1, (0.0, -900.0), (0.0, 0.0), Motion::None));
    assert!(c.worst(Kind::Travel).is_none() && c.violation().is_none());
    assert!(c.summary().to_string().contains("travel: not limited"));
}

#[test]
fn jerk_is_checked_where_the_machine_limits_it() {
    // Z starts at 2000 mm/s² at once: the third difference of
    // 0, 0, 0, −0.001 mm (a·dt²/2) is 0.001 mm / 1e-9 s³ = 1e6 mm/s³,
    // 40 × the 25 000 mm/s³ limit. Without jerk limiting it is not
    // checked.
    for jerk in [false, true] {
        let cfg = Config {
            jerk_limited: jerk,
            ..Config::default()
        };
        let mut c = Certifier::new(&cfg, 0.0, 0.0, 0.0);
        for (k, z) in [0.0, 0.0, 0.0, -0.001].into_iter().enumerate() {
            c.period(&at(k as u32 + 1, (0.0, z), (0.0, 0.0), Motion::Feed));
        }
        let w = c.worst(Kind::Jerk);
        if jerk {
            let w = w.unwrap();
            assert!(
                (w.value + 1.0e6).abs() < 1e-3 && w.limit == 25_000.0,
                "{w:?}"
            );
            assert_eq!(c.violation().map(|f| f.kind), Some(Kind::Jerk));
        } else {
            assert!(w.is_none());
            assert!(c.summary().to_string().contains("jerk: not limited"));
        }
    }
}
