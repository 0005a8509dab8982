//! The trace checker: end points, axis limits, threads, constant surface
//! speed, feed hold, determinism, the PLC handshake, skip and alarms.

mod common;

use common::*;
use nc::{Event, Machine};
use runtime::{Controller, Motion, RunState};

#[test]
fn a_turned_shaft_reaches_every_end_point_within_limits() {
    let r = run(SHAFT);
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    check_limits(&r, false);
}

/// Short segments approximating a curve blend at speed (G64) and still
/// keep every axis within its acceleration.
#[test]
fn short_segments_blend_within_the_limits() {
    let mut src = String::from("O0002\nG00 X0 Z0\nG98 G01 F3000\n");
    for i in 1..=400 {
        let t = i as f64 * 0.01;
        src.push_str(&format!(
            "X{:.3} Z{:.3}\n",
            40.0 * (t * 2.0).sin().abs(),
            -10.0 * t
        ));
    }
    src.push_str("M30\n");
    let r = run(&src);
    check_end_points(&r);
    check_limits(&r, false);
    // Blending: the run is far shorter than stopping at each of 400 points.
    let stops = r
        .pts
        .windows(2)
        .filter(|w| w[0].feed > 0.0 && w[1].feed == 0.0)
        .count();
    assert!(stops < 20, "{stops} stops");
}

#[test]
fn arcs_stay_on_their_circle() {
    let r =
        run("O0003\nG00 X20 Z0\nG98 G01 F2000\nG03 X20 Z-20 R10\nG02 X20 Z-40 R10\nG01 X40\nM30\n");
    check_end_points(&r);
    check_limits(&r, false);
    let mut on_arc = 0;
    for p in &r.pts {
        let (rr, z) = (p.x / 2.0, p.z);
        let d1 = ((rr - 10.0).powi(2) + (z + 10.0).powi(2)).sqrt();
        let d2 = ((rr - 10.0).powi(2) + (z + 30.0).powi(2)).sqrt();
        if p.line >= 4 && p.line <= 5 && p.motion == Motion::Arc {
            on_arc += 1;
            let d = if p.line == 4 { d1 } else { d2 };
            assert!((d - 10.0).abs() < 1e-6, "off the circle by {}", d - 10.0);
        }
    }
    assert!(on_arc > 100);
}

#[test]
fn rapids_move_each_axis_at_its_own_rate() {
    let r = run("O0004\nG00 X-200 Z-400\nM30\n");
    check_end_points(&r);
    check_limits(&r, false);
    let dt = r.cfg.period_s;
    let vmax = |axis: usize| {
        r.pts
            .windows(2)
            .map(|w| if axis == 0 { (w[1].axis_x - w[0].axis_x).abs() / 2.0 } else { (w[1].axis_z - w[0].axis_z).abs() } / dt)
            .fold(0.0, f64::max)
    };
    assert!((vmax(0) - 100.0).abs() < 1e-6, "X at {}", vmax(0));
    assert!((vmax(1) - 10000.0 / 60.0).abs() < 1e-6, "Z at {}", vmax(1));
}

/// G32 twice over the same helix: after the ramp, Z = lead × turns, and
/// both passes sit on the same helix.
#[test]
fn threads_keep_lead_times_revolutions() {
    let src = "O0005\nG97 S600 M03\nG00 X30 Z5\nG32 Z-30 F1.5\nG00 X40\nZ5\nX29.5\nG32 Z-30 F1.5\nG00 X40\nM30\n";
    let r = run(src);
    check_end_points(&r);
    check_limits(&r, false);
    let lead = 1.5;
    let mut phases = Vec::new();
    let mut locked = 0;
    for w in r.pts.windows(2) {
        if w[0].motion == Motion::Thread && w[1].motion == Motion::Thread {
            let dz = w[1].z - w[0].z;
            let dturns = w[1].spindle_turns - w[0].spindle_turns;
            if (dz.abs() - lead * dturns).abs() < 1e-9 {
                locked += 1;
                // Where this pass's helix crosses Z = 0, in turns mod 1.
                let phase = (w[1].spindle_turns + w[1].z / lead).rem_euclid(1.0);
                phases.push(phase);
            }
        }
    }
    // 35 mm at 1.5 mm × 10 rev/s = 2.33 s per pass, nearly all locked.
    assert!(locked > 4000, "{locked} locked periods");
    let (lo, hi) = phases
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &p| (a.min(p), b.max(p)));
    assert!(
        (hi - lo) * lead < 0.001,
        "the passes differ by {} mm",
        (hi - lo) * lead
    );
}

#[test]
fn a_thread_too_fast_for_the_axis_is_e4010() {
    let r = run("O0006\nG97 S1000 M03\nG00 X30 Z5\nG32 Z-30 F6\nM30\n");
    assert_eq!(r.state, RunState::Alarm(4010));
    assert_eq!(r.alarm.unwrap().line, 4);
}

/// A slow G96 face cut: rpm × π × X stays at the surface speed while the
/// rpm is below the limits.
#[test]
fn constant_surface_speed_holds() {
    let src = "O0007\nG50 S2500\nG96 S150 M03\nG00 X80 Z0\nG04 X3\nG98 G01 X20 F30\nM30\n";
    let r = run(src);
    check_end_points(&r);
    let mut checked = 0;
    for p in r
        .pts
        .iter()
        .filter(|p| p.motion == Motion::Feed && p.x > 20.5)
    {
        let v = p.spindle_rpm * std::f64::consts::PI * p.x / 1000.0;
        assert!((v - 150.0).abs() < 0.05, "surface speed {v} at X{}", p.x);
        checked += 1;
    }
    assert!(checked > 10_000);
}

#[test]
fn feed_hold_stops_within_the_deceleration_distance_and_resumes_on_the_path() {
    let src = "O0008\nG98 G01 X40 Z-60 F3000\nM30\n";
    let mut held_at = None;
    let mut stopped_at = None;
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, sp| {
            if held_at.is_none() && sp.time_s >= 0.5 {
                held_at = Some(*sp);
                ctl.feed_hold();
            }
            if ctl.state() == RunState::Held && stopped_at.is_none() {
                stopped_at = Some(*sp);
            }
            if let Some(s) = stopped_at {
                if sp.time_s >= s.time_s + 0.3 {
                    ctl.cycle_start();
                }
            }
        },
        60.0,
    );
    check_end_points(&r);
    check_limits(&r, false);
    let (h, s) = (held_at.unwrap(), stopped_at.unwrap());
    let v = h.feed / 60.0;
    let (dir_r, dir_z) = (20.0 / (20f64.hypot(60.0)), -60.0 / (20f64.hypot(60.0)));
    // A path speed of v at acceleration a (the line's: Z limits it).
    let a = (r.cfg.x.accel / dir_r.abs()).min(r.cfg.z.accel / dir_z.abs())
        * (1.0 - r.cfg.corner_budget);
    let dist = ((s.x - h.x) / 2.0).hypot(s.z - h.z);
    let limit = v * v / (2.0 * a) + v * r.cfg.period_s;
    assert!(
        dist <= limit + 1e-9,
        "stopped after {dist} mm, more than {limit}"
    );
    assert!(
        dist > 0.5 * v * v / (2.0 * a),
        "stopped too early ({dist} mm)"
    );
    for p in &r.pts {
        let off = (p.x / 2.0) * dir_z - p.z * dir_r;
        assert!(off.abs() < 1e-9, "left the path by {off}");
    }
    assert_eq!(r.state, RunState::Ended);
}

#[test]
fn feed_override_scales_the_feed() {
    let src = "O0009\nG98 G01 Z-100 F1200\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.feed_override_pct = 50.0,
        |_, _| {},
        60.0,
    );
    let top = r.pts.iter().map(|p| p.feed).fold(0.0, f64::max);
    assert!((top - 600.0).abs() < 1e-6, "{top}");
}

#[test]
fn identical_runs_are_bit_identical() {
    let a = run(SHAFT);
    let b = run(SHAFT);
    assert_eq!(a.pts.len(), b.pts.len());
    assert_eq!(hash(&a), hash(&b));
}

/// The PLC acknowledges M08 only after 100 periods: the next cut waits.
#[test]
fn the_next_block_waits_for_the_plc() {
    #[derive(Default)]
    struct Slow {
        left: u32,
        acked_at: Option<u64>,
        n: u64,
    }
    impl runtime::Plc for Slow {
        fn request(&mut self, f: runtime::PlcFunction) {
            if f == runtime::PlcFunction::M(8) {
                self.left = 100;
            }
        }
        fn done(&mut self, f: runtime::PlcFunction) -> bool {
            self.n += 1;
            if self.left > 0 {
                self.left -= 1;
                if self.left == 0 && f == runtime::PlcFunction::M(8) {
                    self.acked_at = Some(self.n);
                }
            }
            self.left == 0
        }
    }
    let src = "O0010\nG98 G01 Z-1 F600\nM08\nG01 Z-2\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        Slow::default(),
        |_| {},
        |_, _| {},
        60.0,
    );
    check_end_points(&r);
    // Z stands at -1 for the 100 periods of the handshake.
    let standing = r.pts.iter().filter(|p| (p.z + 1.0).abs() < 1e-12).count();
    assert!(standing >= 100, "{standing}");
}

#[test]
fn a_feed_per_revolution_with_the_spindle_stopped_is_e7003() {
    let m = Machine::from_toml("[spindle]\nstall_timeout_s = 0.5\n").unwrap();
    let r = run_with(
        "O0011\nG99 G01 Z-10 F0.1\nM30\n",
        m,
        runtime::AutoAck,
        |_| {},
        |_, _| {},
        60.0,
    );
    assert_eq!(r.state, RunState::Alarm(7003));
    let t = r.pts.last().unwrap().time_s;
    assert!((0.5..0.51).contains(&t), "after {t} s");
}

/// G31 with the skip signal: the move stops, #5062 holds the skip point,
/// the next block starts from where the axes stopped.
#[test]
fn the_skip_signal_ends_a_g31_move() {
    let src = "O0012\nG98 G31 Z-50 F600\n#100 = #5062\nG01 Z[#100 + 2]\nM30\n";
    let mut hit_z = None;
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, sp| {
            if sp.z <= -20.0 && hit_z.is_none() {
                hit_z = Some(sp.z);
                ctl.set_skip_input(true);
            }
        },
        60.0,
    );
    assert_eq!(r.state, RunState::Ended);
    let hit = hit_z.unwrap();
    let last = r.pts.last().unwrap();
    assert!(
        (last.z - (hit + 2.0)).abs() < 1e-9,
        "ended at {} (skip at {hit})",
        last.z
    );
    check_limits(&r, false);
}

/// G31 along X in radius programming: #995 reads the skip point as a
/// radius, as the program writes X (docs/language.md).
#[test]
fn the_skip_point_is_a_radius_in_radius_programming() {
    let src = "O0015\nG98 G00 X30 Z0\nG31 X0 F600\n#100 = #995\nG01 X[#100 + 2]\nM30\n";
    let mut m = Machine::reference();
    m.axes.x.diameter = false;
    // (The signal comes on the way in from X60, the G00's end.)
    let (mut out, mut hit_x) = (false, None);
    let r = run_with(
        src,
        m,
        runtime::AutoAck,
        |_| {},
        |ctl, sp| {
            out |= sp.x >= 60.0;
            if out && sp.x <= 40.0 && hit_x.is_none() {
                hit_x = Some(sp.x);
                ctl.set_skip_input(true);
            }
        },
        60.0,
    );
    assert_eq!(r.state, RunState::Ended);
    // The trace's X is a diameter: the hit at diameter d is the radius
    // d/2, and X[d/2 + 2] ends 4 mm of diameter further out.
    let hit = hit_x.unwrap();
    let last = r.pts.last().unwrap();
    assert!(
        (last.x - (hit + 4.0)).abs() < 1e-9,
        "ended at {} (skip at {hit})",
        last.x
    );
}

#[test]
fn single_block_stops_at_every_block() {
    let src = "O0013\nG98 G01 Z-1 F600\nZ-2\nZ-3\nM30\n";
    let mut stops = 0;
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.single_block = true,
        |ctl, _| {
            if let RunState::Stopped(runtime::command::PauseKind::SingleBlock) = ctl.state() {
                stops += 1;
            }
        },
        60.0,
    );
    check_end_points(&r);
    assert_eq!(stops, 3);
}

#[test]
fn a_program_alarm_ends_the_motion_where_it_stands() {
    let r = run("O0014\nG98 G01 Z-5 F600\n#3000 = 12 (STOP HERE)\nG01 Z-10\nM30\n");
    assert_eq!(r.state, RunState::Alarm(3012));
    assert!((r.pts.last().unwrap().z + 5.0).abs() < 1e-9);
    assert_eq!(r.alarm.unwrap().message, "STOP HERE");
}

/// Jerk limiting (an option): every axis also keeps its jerk, every end
/// point is still reached exactly.
#[test]
fn jerk_limiting_bounds_the_jerk() {
    let src = "O0015\nG00 X40 Z2\nG98 G01 Z-20 F1500\nX50 Z-30\nG02 X60 Z-35 R5\nG01 Z-50\nG00 X100 Z50\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.jerk_limited = true,
        |_, _| {},
        120.0,
    );
    assert_eq!(r.state, RunState::Ended);
    check_end_points(&r);
    check_limits(&r, false);
    let worst = worst_jerk(&r);
    eprintln!("jerk: worst {worst:.4} of the limit");
    assert!(worst <= 1.0 + 1e-6, "jerk at {worst:.4} of the limit");
    // The S-curve costs time against linear acceleration, but not much.
    let plain = run(src);
    assert!(r.pts.len() > plain.pts.len());
}

#[test]
fn reset_stops_on_the_path_and_cycle_start_runs_the_program_again() {
    let mut resets = 0;
    let mut idle_seen = false;
    let r = run_with(
        SHAFT,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, sp| {
            if resets == 0 && sp.time_s >= 3.0 {
                ctl.reset();
                resets += 1;
            }
            if ctl.state() == RunState::Idle && !idle_seen {
                idle_seen = true;
                assert!(sp.feed == 0.0, "reset left the axes moving");
                ctl.cycle_start();
            }
        },
        120.0,
    );
    assert!(idle_seen);
    assert_eq!(r.state, RunState::Ended);
    check_limits(&r, false);
}

#[test]
fn a_move_beyond_the_travel_is_e7002() {
    let m = Machine::from_toml("[axes.z]\nsoft_limits = true\n").unwrap();
    let r = run_with(
        "O0016\nG00 Z-100\nG00 Z-600\nM30\n",
        m,
        runtime::AutoAck,
        |_| {},
        |_, _| {},
        60.0,
    );
    assert_eq!(r.state, RunState::Alarm(7002));
    assert!((r.pts.last().unwrap().z + 100.0).abs() < 1e-9);
    assert_eq!(r.alarm.unwrap().line, 3);
}

/// A feed that would blend into the next one (the same direction) stops
/// at its end when the next one leaves the travel: the alarm comes at the
/// start of that move, and no period leaves the travel. (The check once
/// looked only at moves started from rest, and let this one run to Z−600.)
#[test]
fn a_blended_move_beyond_the_travel_is_e7002_before_it() {
    let m = Machine::from_toml("[axes.z]\nsoft_limits = true\n").unwrap();
    let r = run_with(
        "O0016\nG98 G01 Z-100 F3000\nG01 Z-600\nM30\n",
        m,
        runtime::AutoAck,
        |_| {},
        |_, _| {},
        60.0,
    );
    assert_eq!(r.state, RunState::Alarm(7002));
    assert_eq!(r.alarm.unwrap().line, 3);
    // Z's travel is −510…2 (machine.md); the tool stands at Z−100.
    assert!(r.pts.iter().all(|p| p.axis_z >= -510.0 - 1e-9));
    assert!((r.pts.last().unwrap().z + 100.0).abs() < 1e-9);
}

/// Ellipses and parabolas (pushed as commands: the kernel prints them only
/// in newer builds) follow their exact curve within the resolution.
#[test]
fn ellipse_and_parabola_follow_the_exact_curve() {
    use runtime::command::{Command, Feed, Move, MoveKind, Path, Tag};
    use runtime::math::V2;
    let mut e = runtime::Engine::new(runtime::Config::default(), runtime::AutoAck);
    let feed = MoveKind::Feed(Feed {
        f: 20.0,
        per_rev: false,
        fixed: false,
    });
    let mv = |path| {
        Command::Move(Move {
            kind: feed,
            path,
            shift: V2::ZERO,
            c: None,
        })
    };
    e.push(
        mv(Path::Line {
            to: V2::new(5.0, 0.0),
        }),
        Tag::default(),
    )
    .unwrap();
    let (a, b, q) = (10.0, 6.0, 0.3f64);
    e.push(
        mv(Path::Ellipse {
            to: V2::new(10.0, -12.0),
            a,
            b,
            q,
            ccw: false,
        }),
        Tag {
            line: 2,
            ..Tag::default()
        },
    )
    .unwrap();
    e.push(
        mv(Path::Parabola {
            to: V2::new(16.0, -20.0),
            p: 3.0,
            q: 0.0,
            ccw: true,
        }),
        Tag {
            line: 3,
            ..Tag::default()
        },
    )
    .unwrap();
    e.push(Command::End(runtime::command::Ending::Stop), Tag::default())
        .unwrap();
    e.replan();
    let ellipse = *e.planner().seg(1).unwrap();
    let parabola = e.planner().seg(2).unwrap().curve;
    e.cycle_start();
    let mut on_e = 0;
    let mut on_p = 0;
    let mut last = V2::ZERO;
    for _ in 0..200_000 {
        let sp = e.tick();
        let p = V2::from_xz(sp.axis_x, sp.axis_z);
        last = p;
        if let runtime::geom::Curve::Ellipse { c, u, a, b, .. } = ellipse.curve {
            if sp.line == 2 && sp.motion == runtime::Motion::Arc {
                let d = p - c;
                let (x, y) = (d.dot(u), d.dot(u.perp()));
                let f = (x / a).powi(2) + (y / b).powi(2);
                assert!((f - 1.0).abs() < 1e-6, "off the ellipse: {f}");
                on_e += 1;
            }
        }
        if let runtime::geom::Curve::Parabola {
            o, u, p: pp, y0, ..
        } = parabola
        {
            if sp.line == 3 && sp.motion == runtime::Motion::Arc {
                let d = p - o;
                let (x, y) = (d.dot(u), d.dot(u.perp()));
                // The vertex at local (−y0²/2p, y0) from the start.
                let err = x - ((y - y0).powi(2) - y0 * y0) / (2.0 * pp);
                assert!(err.abs() < 1e-6, "off the parabola by {err}");
                on_p += 1;
            }
        }
        if e.state() == RunState::Ended {
            break;
        }
    }
    assert_eq!(e.state(), RunState::Ended);
    assert!(on_e > 100 && on_p > 100, "{on_e} {on_p}");
    assert!((last - V2::new(16.0, -20.0)).norm() < 1e-9);
}

/// G61 ends every block at rest, G09 only its own block; G64 blends.
#[test]
fn g61_and_g09_stop_exactly_where_g64_blends() {
    let program = |mode: &str, g09_at: Option<usize>| {
        let mut src = format!("O0003\nG00 X0 Z0\nG98 {mode} G01 F2000\n");
        for i in 1..=20 {
            let g09 = if g09_at == Some(i) { "G09 " } else { "" };
            src.push_str(&format!(
                "{g09}X{} Z{}\n",
                if i % 2 == 0 { 0 } else { 4 },
                -2 * i as i64
            ));
        }
        src.push_str("M30\n");
        src
    };
    let stops = |r: &Run| {
        r.pts
            .windows(2)
            .filter(|w| w[0].feed > 0.0 && w[1].feed == 0.0)
            .count()
    };
    let blended = run(&program("G64", None));
    let exact = run(&program("G61", None));
    let one = run(&program("G64", Some(10)));
    for r in [&blended, &exact, &one] {
        check_end_points(r);
        check_limits(r, false);
    }
    // 20 blocks, each ending at rest under G61; only the last under G64.
    assert_eq!(stops(&exact), 20, "G61");
    assert_eq!(stops(&blended), 1, "G64");
    assert_eq!(stops(&one), 2, "G09 on one block");
}

/// The tick at which the VM has produced `n` LINE events, with the Z the
/// axes stood at in the period before.
fn tick_of_line(src: &str, n: usize) -> (u64, f64) {
    let machine = Machine::reference();
    let m = module(src, &machine);
    let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
    ctl.cycle_start();
    let mut canon: Vec<Event> = Vec::new();
    let mut z = 0.0;
    for tick in 0..20_000u64 {
        ctl.run_ahead_tap(&mut canon);
        let lines = canon
            .iter()
            .filter(|e| matches!(e, Event::Line { .. }))
            .count();
        if lines >= n {
            return (tick, z);
        }
        z = ctl.tick().z;
    }
    panic!("the VM never produced {n} LINE events");
}

/// #5042 (current Z) waits for the motion before it, as on a real control;
/// #5002 (block-end Z) is known ahead and lets the VM run on at once.
#[test]
fn a_current_position_read_waits_for_the_motion() {
    // Z-30 at 600 mm/min: 3 s of motion before the read.
    let waits = "O0015\nG98 G01 Z-30 F600\n#100 = #5042\nG01 Z[#100 - 5]\nM30\n";
    let (tick, z) = tick_of_line(waits, 2);
    assert!(
        tick >= 3000,
        "the second block ran at tick {tick}, before the move ended"
    );
    assert!(
        (z + 30.0).abs() < 1e-9,
        "the axes stood at Z{z} when #5042 was read"
    );
    let ahead = "O0016\nG98 G01 Z-30 F600\n#100 = #5002\nG01 Z[#100 - 5]\nM30\n";
    assert_eq!(tick_of_line(ahead, 2).0, 0, "#5002 needs no wait");
    // And the run ends where the program says, without deadlock.
    let r = run(waits);
    assert_eq!(r.state, RunState::Ended);
    assert!((r.pts.last().unwrap().z + 35.0).abs() < 1e-9);
}

/// G22 on the path: both end points of the diagonal lie outside the box
/// X −10…100, Z −20…50, but the line from X50 Z-30 to X150 Z10 runs
/// through it (at Z-18 it is at X80). The kernel refuses the line (E7002
/// naming it) before it is printed, so the axes never enter the area.
#[test]
fn g22_refuses_a_line_whose_path_runs_through_the_area() {
    let enters = "O0017\nG98 G00 X150 Z10\nG22 X100. Z50. I-10. K-20.\nG00 Z-30\nX50\n\
                  G01 X150 Z10 F3000\nG23\nM30\n";
    let r = run(enters);
    assert_eq!(r.state, RunState::Alarm(7002));
    let alarm = r.alarm.as_ref().expect("an alarm");
    assert_eq!(alarm.line, 6, "{alarm:?}");
    let inside = |p: &runtime::SetPoint| p.x > -10.0 && p.x < 100.0 && p.z > -20.0 && p.z < 50.0;
    assert_eq!(r.pts.iter().filter(|p| p.line >= 4 && inside(p)).count(), 0);
    let last = r.pts.last().unwrap();
    assert!((last.x - 50.0).abs() < 1e-6 && (last.z + 30.0).abs() < 1e-6);
    // The same program with G23 before the diagonal runs to its end.
    let off = enters.replace("G22 X100. Z50. I-10. K-20.", "G23");
    assert_eq!(run(&off).state, RunState::Ended);
}

/// G22 on a path only the runtime follows: the kernel checks an ellipse
/// at its end point only. The half ellipse G6.2 from X120 Z40 to X120
/// Z-10 (A25 along Z, B15 across) runs clockwise towards −Z, so it bulges
/// towards −X to r 60 − 15 = 45 (X90) at Z15, inside the box X −10…100,
/// Z −20…50, while both ends (X120) lie outside it. The runtime stops in
/// the first period inside, with E7002 naming the line.
#[test]
fn g22_stops_the_axes_where_the_path_enters_the_area() {
    let enters = "O0019\nG98 G00 X120 Z40\nG22 X100. Z50. I-10. K-20.\n\
                  G6.2 X120 Z-10 A25 B15 F3000\nG23\nM30\n";
    let r = run(enters);
    assert_eq!(r.state, RunState::Alarm(7002));
    let alarm = r.alarm.as_ref().expect("an alarm");
    assert_eq!(alarm.line, 4, "{alarm:?}");
    let inside = |p: &runtime::SetPoint| p.x > -10.0 && p.x < 100.0 && p.z > -20.0 && p.z < 50.0;
    let last = r.pts.last().unwrap();
    assert!(inside(last), "stopped at X{} Z{}", last.x, last.z);
    // Only the last period after the G22 is inside (the first rapid starts
    // from machine zero, inside the box, before G22): the axes stopped on
    // entering.
    let after = r.pts.iter().filter(|p| p.line >= 3 && inside(p)).count();
    assert_eq!(after, 1);
    let off = enters.replace("G22 X100. Z50. I-10. K-20.", "G23");
    assert_eq!(run(&off).state, RunState::Ended);
}

/// A G31 without axis words is a skip move of zero length: nothing runs,
/// so no skip report comes, and the VM must not wait for one.
#[test]
fn a_zero_length_g31_does_not_hold_the_program() {
    let r = run("O0018\nG98 G00 X10 Z5\nG31 F100\nG01 Z0\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    let last = r.pts.last().unwrap();
    assert!((last.z - 0.0).abs() < 1e-9 && (last.x - 10.0).abs() < 1e-9);
}

/// A compensated contour with a chamfer: each element waits in the kernel
/// for the next block and prints while that block runs, yet its periods
/// carry its own block's line (they carried the next one's).
#[test]
fn a_waiting_element_runs_under_its_own_line() {
    let machine = Machine::from_toml("[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n")
        .expect("a machine file");
    let src = "G98 G00 X20 Z2 T0101\nG42 G01 Z0 F300\nG01 Z-10\nX30 Z-15\nZ-25 L2\nX40\nG40 G00 X50 Z5\nM30\n";
    let r = run_with(src, machine, runtime::AutoAck, |_| {}, |_, _| {}, 600.0);
    assert_eq!(r.state, RunState::Ended);
    let on = |line: u32| -> Vec<(f64, f64)> {
        r.pts
            .iter()
            .filter(|p| p.line == line && p.motion != Motion::None)
            .map(|p| (p.x, p.z))
            .collect()
    };
    for line in 2..=7 {
        assert!(
            on(line).len() > 10,
            "line {line}: {} periods",
            on(line).len()
        );
    }
    // Tip 3 prints the imaginary tip on the programmed OD: the start-up
    // (line 2) ends where the next element starts, the nose centre 0.8
    // above Z0, printed 0.8 lower and 0.8 towards −Z: X20 Z−0.8; line 3
    // runs along X20 from there.
    assert!(on(2).iter().all(|&(x, z)| x == 20.0 && z >= -0.8 - 1e-9));
    assert!(on(3).iter().all(|&(x, z)| x == 20.0 && z <= -0.8 + 1e-9));
    // Line 5 is Z−15 … Z−25 with its chamfer L2 to X34 at Z−25 (the
    // tip printed 0.8 inside of it); line 6 runs out along Z−25.
    assert!(on(5)
        .iter()
        .all(|&(x, z)| (29.5..=34.0).contains(&x) && z <= -15.0));
    assert!(on(6).iter().all(|&(x, z)| z == -25.0 && x >= 33.0));
}

/// Periods whose set point is exactly the end point `(x, z)` (X a
/// diameter) of the move of line `line`, and the line each names.
fn labels_at_end_points(r: &Run, ends: &[(f64, f64, u32)]) -> Vec<(u32, u32)> {
    let at =
        |p: &runtime::SetPoint, x: f64, z: f64| (p.x - x).abs() < 1e-9 && (p.z - z).abs() < 1e-9;
    let mut out = Vec::new();
    for p in r.pts.iter().filter(|p| p.motion == Motion::Feed) {
        for &(x, z, line) in ends {
            if at(p, x, z) {
                out.push((line, p.line));
            }
        }
    }
    out
}

/// G64 corners: a period whose motion ends exactly on a corner ran the
/// move before it, and the trace's `line` names that move's block; the
/// period after it runs the next move and names the next block.
#[test]
fn a_period_ending_on_a_g64_corner_names_the_block_it_ran() {
    let r = run("O0003\nG98 G64 G01 X-20 F2000\nZ-20\nX-40 Z-30\nZ-50\nX-30 Z-55\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    let ends = [
        (-20.0, 0.0, 2),
        (-20.0, -20.0, 3),
        (-40.0, -30.0, 4),
        (-40.0, -50.0, 5),
    ];
    let seen = labels_at_end_points(&r, &ends);
    // Each corner is the end of exactly one period (the motion runs on).
    assert_eq!(seen.len(), 4, "{seen:?}");
    for (own, named) in seen {
        assert_eq!(
            named, own,
            "the period ending on line {own}'s end names {named}"
        );
    }
    // The period after the first corner runs Z−20 (line 3).
    let corner = |p: &runtime::SetPoint| (p.x + 20.0).abs() < 1e-9 && p.z.abs() < 1e-9;
    let k = r.pts.iter().position(corner);
    let next = k.and_then(|k| r.pts.get(k + 1));
    assert!(next.is_some_and(|p| p.line == 3 && p.z < 0.0), "{next:?}");
}

/// µm moves blended at their corners (a zero-length one among them): each
/// period that ends exactly on a move's end names that move's block, not
/// the next one (and never the zero-length line 4, which has no motion).
#[test]
fn a_period_ending_on_a_short_move_names_its_block() {
    let r = run(
        "O0024\nG98 G00 X-20 Z0\nG01 X-20.0004 F1000\nG01 X-20.0004\nG01 Z-0.0003\n\
                 G01 Z-0.0006\nG01 X-20.001 Z-0.001\nG01 X-20 Z-0.002\nG01 Z-0.052 F5000\nM30\n",
    );
    assert_eq!(r.state, RunState::Ended);
    let ends = [
        (-20.0004, 0.0, 3),
        (-20.0004, -0.0003, 5),
        (-20.0004, -0.0006, 6),
        (-20.001, -0.001, 7),
    ];
    let seen = labels_at_end_points(&r, &ends);
    assert!(seen.len() >= 3, "{seen:?}");
    for (own, named) in seen {
        assert_eq!(
            named, own,
            "the period ending on line {own}'s end names {named}"
        );
    }
}

/// Moves of a µm or two that turn back (a 0.001 mm line, a 0.002 mm one
/// back, an arc of R0.0011 to a point 0.001 mm from where the first
/// began): the tool stands within the 0.001 mm tolerance of several end
/// points at once, one of them exactly at it. Found by the bounded fuzz
/// target `contours_on_random_bytes`: the distance came out 1.2e-15 mm
/// over the tolerance, and the end point was reported missed.
#[test]
fn end_points_a_micrometre_apart_are_reached_at_the_tolerance() {
    let src = "G00 X60 Z2\nM03 S1000\nG64\nG98 F100\nG01 X60.000 Z1.999\nG01 X60.000 Z2.001\nG03 X59.998 Z1.999 R0.0011\nG01 X60.424 Z2.318\nM30\n";
    assert_eq!(certify(src, &Machine::reference(), false), Some(Ok(())));
}
