//! Rapids under jerk limiting: each axis's acceleration-limited motion is
//! averaged over a/j (config.rs `rapid_taps`), and an axis never turns
//! from speeding up to slowing down, or back, within that window
//! (smooth.rs `Turns`), which keeps its jerk within the limit where any
//! profile would need 2·a/j. A rapid ends a/j later than without jerk
//! limiting, as with an S-curve.

mod common;

use common::{check_end_points, run_with, worst_jerk, Run};
use nc::Machine;
use runtime::{AutoAck, RunState};

/// Runs `src` on the reference machine with jerk limiting on or off;
/// `host` is called after every period.
fn run_rapids(
    src: &str,
    jerk: bool,
    host: impl FnMut(&mut runtime::Controller<AutoAck>, &runtime::SetPoint),
) -> Run {
    run_with(
        src,
        Machine::reference(),
        AutoAck,
        |c| c.jerk_limited = jerk,
        host,
        60.0,
    )
}

/// The run ended on every end point, each axis's jerk within 80/81 of
/// its limit (1e-6 for rounding, as `gbvm check` allows): a rapid's
/// window of 81 periods where a/j is 80.
fn check_ended_within_rapid_jerk(r: &Run) {
    assert_eq!(r.state, RunState::Ended);
    check_end_points(r);
    let worst = worst_jerk(r);
    assert!(worst <= 80.0 / 81.0 + 1e-6, "jerk {worst}");
}

/// Periods on line `line`.
fn periods_on(r: &Run, line: u32) -> usize {
    r.pts.iter().filter(|p| p.line == line).count()
}

const LONG: &str = "G00 X0 Z0\nG00 Z-100\nM30\n";

#[test]
fn a_long_rapid_ends_a_over_j_later() {
    // Z: 166.67 mm/s, 2000 mm/s², 25 000 mm/s³ (X: 1500 and 20 000), so
    // the window is a/j = 80 ms, the larger of 75 and 80, and a period
    // more for rounding: 81 (it was 160, 2·a/j). Without jerk limiting
    // the 100 mm take 83.3 ms up, 83.3 ms down and 86.1 mm at 166.67 mm/s:
    // 683 periods. The move is long, so its profile is the same with
    // jerk limiting; the average lands on the end 80 periods after it
    // (the first of its 81 samples is the landing one).
    let on = run_rapids(LONG, true, |_, _| {});
    let off = run_rapids(LONG, false, |_, _| {});
    assert_eq!(on.cfg.rapid_taps(), 81);
    assert_eq!(periods_on(&off, 2), 683);
    assert_eq!(periods_on(&on, 2), 683 + 80);
    let worst = worst_jerk(&on);
    assert!(worst <= 80.0 / 81.0 + 1e-6, "jerk {worst}");
    check_end_points(&on);
}

#[test]
fn short_rapids_under_jerk_limiting_land() {
    // Moves shorter than what the window runs at the first speed step
    // (33 µm: 2 mm/s for 82 periods would be 164 µm) creep at the speed
    // they can hold for a window before braking, and land exactly.
    let src = "G00 X0 Z0\nG00 Z-0.033\nG00 X0.05\nW0.001\nM30\n";
    let r = run_rapids(src, true, |_, _| {});
    check_ended_within_rapid_jerk(&r);
}

#[test]
fn a_hold_while_a_rapid_speeds_up_brakes_within_the_jerk_limit() {
    // Feed hold once Z's set point is 0.5 mm out (about 50 ms into the
    // rapid: the average lags the profile, which is 2.5 mm out), while Z
    // speeds up: Z keeps its speed until a window after its last speed
    // step, then brakes; the axes stand while held, and cycle start runs
    // the rapid to its end.
    let mut held_at = None;
    let r = run_rapids(LONG, true, |ctl, p| {
        let running = ctl.state() == RunState::Running;
        if p.line == 2 && held_at.is_none() && running && p.axis_z < -0.5 {
            ctl.feed_hold();
        }
        if ctl.state() == RunState::Held && held_at.is_none() {
            held_at = Some((p.time_s, p.axis_z));
        }
        if let Some((t, _)) = held_at {
            if p.time_s > t + 0.5 {
                ctl.cycle_start();
            }
        }
    });
    let (t, z) = held_at.expect("the hold took");
    let still = r
        .pts
        .iter()
        .filter(|p| p.time_s > t && p.time_s < t + 0.5)
        .all(|p| p.axis_z == z);
    assert!(still, "Z moved while held");
    assert!(z > -100.0 && z < -0.5, "held at Z{z}");
    check_ended_within_rapid_jerk(&r);
}
