//! G64 under jerk limiting: feeds blend at their corners and the axes'
//! set points are averaged twice after interpolation (planner.rs
//! `FeedSmoothing`), so a polyline runs through its corners at speed
//! instead of stopping at every block, within every axis's jerk and
//! within half the resolution of the path.

mod common;

use common::{certify, run_with, Run};
use nc::Machine;
use runtime::{AutoAck, Controller, SetPoint};

/// A quarter circle of R 20 as 180 G01 chords of 0.5° (0.1745 mm) at
/// `feed` mm/min; `mode` is G61 or G64.
fn polyline(mode: &str, feed: u32) -> String {
    let mut s = format!("G00 X40 Z2\nM03 S1000\n{mode}\nG98 G01 X40 Z0 F{feed}\n");
    for i in 1..=180 {
        let a = (f64::from(i) * 0.5).to_radians();
        let (x, z) = (40.0 + 40.0 * (1.0 - a.cos()), -20.0 * a.sin());
        s += &format!("G01 X{x:.4} Z{z:.4}\n");
    }
    s + "G00 X100 Z50\nM30\n"
}

/// Runs the polyline on the reference machine; `host` is called after
/// every period.
fn run_polyline(
    mode: &str,
    feed: u32,
    jerk: bool,
    host: impl FnMut(&mut Controller<AutoAck>, &SetPoint),
) -> Run {
    run_with(
        &polyline(mode, feed),
        Machine::reference(),
        AutoAck,
        |c| c.jerk_limited = jerk,
        host,
        120.0,
    )
}

/// The set points' path speeds (mm/s) of the periods on the chords
/// (lines 5 to 184), in order.
fn chord_speeds(jerk: bool, mode: &str, feed: u32) -> Vec<f64> {
    run_polyline(mode, feed, jerk, |_, _| {})
        .pts
        .iter()
        .filter(|p| (5..=184).contains(&p.line))
        .map(|p| p.feed / 60.0)
        .collect()
}

/// The speeds on the chords of lines 30 to 159 (the first and last 25
/// chords, 4.4 mm, take the speed up and down), and the time on all of
/// them, s.
fn inner_speeds(feed: u32) -> (Vec<f64>, f64) {
    let r = run_polyline("G64", feed, true, |_, _| {});
    let on = |lines: core::ops::RangeInclusive<u32>| {
        r.pts
            .iter()
            .filter(|p| lines.contains(&p.line))
            .map(|p| p.feed / 60.0)
            .collect::<Vec<f64>>()
    };
    let inner = on(30..=159);
    // 22.7 mm, at 25 mm/s or less: 900 periods at least.
    assert!(inner.len() > 900, "{} periods", inner.len());
    (inner, on(5..=184).len() as f64 * 0.001)
}

#[test]
fn a_polyline_under_jerk_limiting_runs_through_its_corners_at_its_feed() {
    // The reference machine with jerk limiting averages feeds over
    // T = 11 ms, then T₂ = 6 ms, and plans them at 110 (X) and 137.5
    // mm/s² (Z), a quarter of which the moves keep back for corners. A
    // 0.5° corner changes the direction by |Δu| = 2·sin 0.25° = 0.008 727.
    // Its velocity step, v·|Δu| on X where the path runs along Z (the
    // first corners), may take that quarter of X's acceleration over T₂,
    // 0.25·110·0.006 = 0.165 mm/s: v ≤ 18.9 mm/s. With the corners that
    // may follow in a window, v·T₂/0.174 53 of them, v·|Δu|·(1 +
    // v·0.006/0.174 53) ≤ 0.165: v ≤ 13.05 mm/s. The averages' cut
    // allows (0.0005/|Δu| − 137.5·(T² + T₂²)/48)/(T/8 + T₂²/24T) = 37.6
    // mm/s, the curve of R 20 the chords make √(24·20·0.0005/(T² + T₂²))
    // = 39.1 mm/s. So F600 (10 mm/s) runs through every corner at its
    // feed: 31.4 mm in 3.14 s and the first and last chords' ramps.
    let (inner, secs) = inner_speeds(600);
    let slowest = inner.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(slowest > 9.99, "the speed falls to {slowest} mm/s");
    assert!(inner.iter().all(|&s| s <= 10.0 + 1e-6));
    assert!(secs < 3.3, "the chords take {secs} s");
}

#[test]
fn a_faster_polyline_under_jerk_limiting_runs_at_its_corners_speed() {
    // F1500 (25 mm/s): the corners' steps bind, at 13.05 mm/s where the
    // path runs along Z and more where it turns to X (the step then falls
    // on Z, which accelerates faster). The raw speed never falls below
    // that, and neither does its average. (Taking all of the window's
    // share would stop the corner after it.)
    let (inner, secs) = inner_speeds(1500);
    let slowest = inner.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(slowest > 13.0, "the speed falls to {slowest} mm/s");
    assert!(inner.iter().all(|&s| s <= 25.0 + 1e-6));
    // 31.4 mm at 13.05 mm/s or more: 2.41 s and the ramps.
    assert!(secs < 2.6, "the chords take {secs} s");
}

#[test]
fn g61_under_jerk_limiting_still_stops_at_every_block() {
    // Exact stop: each chord ends at rest, the average settled on its end
    // point, before the next starts.
    let v = chord_speeds(true, "G61", 600);
    let stops = v.windows(2).filter(|w| w[0] > 0.0 && w[1] == 0.0).count();
    assert!(stops >= 180, "{stops} stops on 181 blocks");
}

#[test]
fn polylines_under_jerk_limiting_are_certified() {
    // Every axis within its speed, acceleration and jerk, every end
    // point reached within 1 µm and every set point within 1 µm of the
    // path, for G64 and G61, with jerk limiting on and off.
    let machine = Machine::reference();
    for (mode, feed) in [("G64", 600), ("G64", 1500), ("G61", 600)] {
        for jerk in [false, true] {
            let r = certify(&polyline(mode, feed), &machine, jerk);
            assert_eq!(r, Some(Ok(())), "{mode} F{feed}, jerk {jerk}");
        }
    }
}

/// A full circle after a blended line: the averaged path passes the
/// line's end (the circle's start and end) within 0.0002 mm on the way
/// in and again on the way round, and the certificate holds both to it
/// in order (the circle's at its end, not where it begins). Also a
/// full circle closing a chain of arcs, and one at the program's end.
#[test]
fn full_circles_after_blended_moves_are_certified() {
    let machine = Machine::reference();
    let programs = [
        "O0030\nG98 G00 X-20 Z0\nG01 Z-10 F2000\nG02 X-20 Z-10 I10 K0\nG01 Z-20\nM30\n",
        "O0031\nG98 G00 X-20 Z0\nG01 Z-10 F2000\nG02 X-20 Z-10 I10 K0\nM30\n",
        "O0006\nG98 G00 X-20 Z0\nG01 Z-10 F3000\nG02 X-60 Z-30 R20\nG03 X-100 Z-50 R20\n\
         G02 X-100 Z-50.002 R0.5\nG01 Z-60\nG02 X-104 Z-62 I-2 K0 F4000\nG03 X-104 Z-62 I0 K-3\nM30\n",
        "O0007\nG98 G00 X-10 Z-2\nG01 Z-5 F5000\nG03 X-14 Z-7 R2\nG01 X-60 F5000\nG02 X-100 Z-27 R20\n\
         G01 Z-60 F5000\nG02 X-100 Z-60 I20 K0 F5000\nM30\n",
    ];
    for src in programs {
        for jerk in [false, true] {
            let r = certify(src, &machine, jerk);
            assert_eq!(r, Some(Ok(())), "jerk {jerk}:\n{src}");
        }
    }
}

#[test]
fn a_feed_hold_in_a_blended_polyline_stands_and_goes_on() {
    // Feed hold at 2 s, in the middle of the chords: the path brakes, the
    // average settles, the axes stand; cycle start at 3 s runs on. Every
    // end point is still passed within 1 µm, in order.
    let mut held_at = None;
    let r = run_polyline("G64", 600, true, |ctl, p| {
        if (p.time_s - 2.0).abs() < 1e-9 {
            ctl.feed_hold();
        }
        if ctl.state() == runtime::RunState::Held && held_at.is_none() {
            assert_eq!(p.feed, 0.0, "held while moving");
            held_at = Some((p.time_s, p.x, p.z));
        }
        if (p.time_s - 3.0).abs() < 1e-9 {
            ctl.cycle_start();
        }
    });
    let (t, x, z) = held_at.expect("the hold took");
    assert!(t > 2.0 && t < 2.2, "held at {t} s");
    // Standing from there until the cycle start.
    let still = r
        .pts
        .iter()
        .filter(|p| p.time_s > t && p.time_s < 3.0)
        .all(|p| p.x == x && p.z == z);
    assert!(still, "the axes moved while held");
    common::check_end_points(&r);
    assert_eq!(r.state, runtime::RunState::Ended);
}

#[test]
fn single_block_stops_a_blended_chain_on_every_block_end() {
    // Three collinear blocks blend in G64; single block stops each on its
    // end point, in the period the average settles there.
    let src = "O0013\nG98 G01 Z-1 F600\nZ-2\nZ-3\nM30\n";
    let mut stops = Vec::new();
    run_with(
        src,
        Machine::reference(),
        AutoAck,
        |c| {
            c.jerk_limited = true;
            c.single_block = true;
        },
        |ctl, p| {
            if let runtime::RunState::Stopped(runtime::command::PauseKind::SingleBlock) =
                ctl.state()
            {
                stops.push(p.z);
            }
        },
        60.0,
    );
    assert_eq!(stops, vec![-1.0, -2.0, -3.0]);
}

#[test]
fn a_reset_in_a_blended_chain_stops_on_the_path() {
    // Reset at 2 s: the path brakes, the average settles, the engine is
    // idle with the axes standing on the polyline; cycle start runs the
    // program again to its end.
    let mut idle_at = None;
    let r = run_polyline("G64", 600, true, |ctl, p| {
        if (p.time_s - 2.0).abs() < 1e-9 {
            ctl.reset();
        }
        if ctl.state() == runtime::RunState::Idle && idle_at.is_none() {
            assert_eq!(p.feed, 0.0, "reset left the axes moving");
            idle_at = Some((p.x, p.z));
            ctl.cycle_start();
        }
    });
    let (x, z) = idle_at.expect("the reset took");
    // On the quarter circle of R 20 about (X80, Z0), within 1 µm of a chord
    // (the sagitta of a 0.5° chord is 0.19 µm).
    let off = ((x / 2.0 - 40.0).hypot(z) - 20.0).abs();
    assert!(off < 0.001, "stopped {off} mm off the arc");
    assert_eq!(r.state, runtime::RunState::Ended);
}
