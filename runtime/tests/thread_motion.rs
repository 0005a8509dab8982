//! Threads and taps as a servo can cut them: the long axis ramps up to
//! thread speed after the index pulse and brakes at the end within its
//! acceleration, pull-outs and run-outs turn the short axis within its
//! acceleration, and every conformance program with a thread or tap keeps
//! every axis within its limits in every period.

mod common;

use common::*;
use nc::thread_room::{entry_length, exit_length};
use nc::Machine;
use runtime::{AutoAck, Controller, Motion, RunState, SetPoint};
use std::path::{Path, PathBuf};

/// Z of the thread periods (the set point moves and the motion is a
/// thread), with the spindle turns at the end of the period.
fn thread_periods(pts: &[SetPoint], line: u32) -> Vec<(usize, f64, f64)> {
    pts.iter()
        .enumerate()
        .filter(|(_, p)| p.motion == Motion::Thread && p.line == line)
        .map(|(k, p)| (k, p.z, p.spindle_turns))
        .collect()
}

/// G32 Z5 → Z-30, lead 1.5 at 600 rpm on the reference machine. Hand
/// figures: v = 1.5 mm × 600/60 rev/s = 15 mm/s. The ramp keeps back
/// lead × spindle acceleration = 1.5 × 1000/60 = 25 mm/s² of Z's 2000, so
/// it accelerates at 1975 mm/s² and reaches thread speed after
/// 15² / (2 × 1975) = 0.056962 mm: the incomplete lead at entry. From
/// there Z = start − lead × (turns since the index) + 0.056962, in every
/// period. At the end Z brakes at 2000 mm/s² over 15² / 4000 = 0.05625 mm
/// (the incomplete lead at exit), landing on Z-30 within a period's travel
/// (0.015 mm) of that.
#[test]
fn thread_entry_and_exit_lengths_at_600_rpm() {
    let src = "O0011\nG97 S600 M03\nG00 X30 Z5\nG32 Z-30 F1.5\nG00 X40\nM30\n";
    let r = run(src);
    check_end_points(&r);
    check_limits(&r, false);
    let entry = entry_length(1.5, 600.0, 2000.0, 1000.0);
    assert!((entry - 0.056962).abs() < 1e-6, "{entry}");
    let exit = exit_length(1.5, 600.0, 2000.0);
    assert!((exit - 0.05625).abs() < 1e-12);

    let th = thread_periods(&r.pts, 4);
    // The index pulse (Q0: a whole turn) falls in the first period that
    // moves Z (the thread waited for it standing).
    let (k0, _, _) = *th.iter().find(|p| p.1 < 5.0).unwrap();
    let theta0 = r.pts[k0].spindle_turns.floor();
    assert!(
        r.pts[k0 - 1].spindle_turns < theta0,
        "no index pulse before the ramp"
    );
    let mut locked = 0;
    let mut first_locked_z = None;
    let mut last_locked_z = 0.0;
    for w in th.windows(2) {
        let ((_, z0, t0), (_, z1, t1)) = (w[0], w[1]);
        if ((z0 - z1) - 1.5 * (t1 - t0)).abs() < 1e-9 {
            locked += 1;
            // On the helix shifted by the entry length.
            let offset = z1 + 1.5 * (t1 - theta0) - 5.0;
            assert!((offset - entry).abs() < 1e-6, "helix offset {offset}");
            first_locked_z.get_or_insert(z0);
            last_locked_z = z1;
        }
    }
    // 35 mm at 15 mm/s is 2333 periods, nearly all locked.
    assert!(locked > 2300, "{locked} locked periods");
    let ran_in = 5.0 - first_locked_z.unwrap();
    assert!(
        ran_in >= entry - 1e-9 && ran_in <= entry + 0.015,
        "locked after {ran_in} mm"
    );
    let ran_out = last_locked_z + 30.0;
    assert!(
        (ran_out - exit).abs() <= 0.015,
        "braked over {ran_out} mm, not {exit}"
    );
}

/// A 45° run-out at thread speed: G32 Z-20, then G32 to X33 Z-21.5
/// (1.5 mm radial over 1.5 mm of Z). Z goes on at 15 mm/s; X, standing,
/// must reach 15 mm/s: with 1500 mm/s² that takes 15 / 1.5 = 10 periods,
/// its speed rising 1.5 mm/s per period. Until then it falls behind the
/// programmed chamfer by 15·t − 750·t², 0.075 mm at t = 10 ms (v²/2a),
/// then closes the gap; it ends exactly on X33 Z-21.5.
#[test]
fn a_pull_out_turns_x_within_its_acceleration() {
    let src = "O0012\nG97 S600 M03\nG00 X30 Z5\nG32 Z-20 F1.5\nG32 X33 Z-21.5\nG00 X40\nM30\n";
    let r = run(src);
    check_end_points(&r);
    check_limits(&r, false);
    let dt = r.cfg.period_s;
    let xr: Vec<f64> = r.pts.iter().map(|p| p.axis_x / 2.0).collect();
    let start = r
        .pts
        .iter()
        .position(|p| p.line == 5 && p.axis_x > 30.0)
        .expect("X moves in the run-out");
    // Periods from X's first move until it runs at 15 mm/s: 10, or 11
    // when the corner falls inside a period (its first step is partial).
    let periods = (start..xr.len())
        .position(|k| (xr[k] - xr[k - 1]) / dt >= 15.0 - 1e-6)
        .expect("X reaches thread speed")
        + 1;
    assert!(periods == 10 || periods == 11, "{periods} periods");
    // The lag behind the chamfer (programmed radial X at the same Z).
    let corner_z = -20.0;
    let lag = r
        .pts
        .iter()
        .filter(|p| p.z < corner_z && p.z > -21.5)
        .map(|p| (15.0 + (corner_z - p.z)) - p.x / 2.0)
        .fold(0.0, f64::max);
    assert!(lag > 0.06 && lag < 0.08, "lag {lag}");
    let last_thread = r.pts.iter().rev().find(|p| p.line == 5).unwrap();
    assert_eq!((last_thread.x, last_thread.z), (33.0, -21.5));
}

/// Rigid tapping (M29, G84 Z-10 F1.5 P200 at 600 rpm) on the reference
/// machine with a spindle that could brake at 2000 rev/s² (120 000
/// rpm/s). Hand figures: Z may accelerate at 2000 mm/s², so the spindle's
/// rigid-tap acceleration is 2000 / 1.5 = 1333.33 rev/s² (80 000 rpm/s).
/// From 600 rpm = 10 rev/s it stops in 10 / 1333.33 = 7.5 ms and
/// 10² / (2 × 1333.33) = 0.0375 turns, Z with it in 1.5 × 0.0375 =
/// 0.05625 mm. Through the whole reversal Z = −10 + 1.5 × |turns − θb|
/// (θb: the turns at the bottom), the bottom reached exactly when the
/// spindle stands; the tap never turns while Z stands; Z and the spindle
/// start out at the same 1333.33 rev/s² (Z 2000 mm/s²).
#[test]
fn a_rigid_tapping_reversal_follows_the_spindle() {
    let src =
        "O0013\nG97 M03 S600\nG00 X0 Z5\nM29 S600\nG84 X0 Z-10 F1.5 P200\nG80\nG00 X50 Z50\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.spindle.accel_rpm_s = 120_000.0,
        |_, _| {},
        600.0,
    );
    check_end_points(&r);
    check_limits(&r, false);
    let dt = r.cfg.period_s;
    let bottom = r.pts.iter().map(|p| p.z).fold(f64::MAX, f64::min);
    assert_eq!(bottom, -10.0);
    // The bottom's turns: the first period standing there.
    let kb = r.pts.iter().position(|p| p.z == -10.0).unwrap();
    let theta_b = r.pts[kb].spindle_turns;
    // The tap never turns while Z stands at the bottom.
    for p in r.pts.iter().filter(|p| p.z == -10.0) {
        assert_eq!(p.spindle_turns, theta_b, "the tap turned at the bottom");
    }
    // The reversal: from the last period at full speed down to the
    // spindle's stop, and from its restart until it is at speed again.
    let mut k = kb;
    while r.pts[k - 1].spindle_rpm < 600.0 - 1e-9 {
        k -= 1;
    }
    let start = k - 1;
    let mut end = kb;
    while r.pts[end].spindle_rpm > -600.0 + 1e-9 {
        end += 1;
    }
    let mut decel = 0.0f64;
    for (i, p) in r.pts[start..=end].iter().enumerate() {
        let z = -10.0 + 1.5 * (p.spindle_turns - theta_b).abs();
        assert!((p.z - z).abs() < 1e-9, "period {i}: Z {} not {z}", p.z);
        if i > 0 {
            let dw = (p.spindle_rpm - r.pts[start + i - 1].spindle_rpm).abs() / 60.0 / dt;
            decel = decel.max(dw);
        }
    }
    // The spindle brakes and starts at its rigid-tap acceleration, no more.
    assert!(decel <= 2000.0 / 1.5 + 1e-6, "{decel} rev/s²");
    assert!(decel > 2000.0 / 1.5 - 1e-6, "{decel} rev/s²");
    // Braking took 0.0375 turns = 0.05625 mm (7.5 periods: 8).
    let braked = r.pts[start].z + 10.0;
    assert!((braked - 0.05625).abs() <= 0.015, "braked over {braked}");
    assert!(kb - start <= 9, "{} periods", kb - start);
}

/// The same rigid tap at 300 rpm on the reference spindle (1000 rpm/s =
/// 16.67 rev/s², below Z's 2000 / 1.5 = 1333.33): the spindle brakes at
/// its own acceleration, from 5 rev/s in 0.3 s and 5² / (2 × 16.67) =
/// 0.75 turn, so Z follows it over the last 1.5 × 0.75 = 1.125 mm at
/// 1.5 × 16.67 = 25 mm/s², Z = −10 + 1.5 × (θb − turns) in every period.
#[test]
fn a_rigid_tap_brakes_with_the_spindle_at_its_own_acceleration() {
    let src = "O0015\nG97 M03 S300\nG00 X0 Z5\nM29 S300\nG84 X0 Z-10 F1.5\nG80\nG00 X50 Z50\nM30\n";
    let r = run(src);
    check_end_points(&r);
    check_limits(&r, false);
    let kb = r.pts.iter().position(|p| p.z == -10.0).unwrap();
    let theta_b = r.pts[kb].spindle_turns;
    // 0.3 s of braking: 300 periods before the bottom, Z locked to the
    // spindle in each, the spindle never faster than 1000 rpm/s.
    for k in kb - 300..=kb {
        let p = &r.pts[k];
        let z = -10.0 + 1.5 * (theta_b - p.spindle_turns);
        assert!((p.z - z).abs() < 1e-9, "period {k}: Z {} not {z}", p.z);
        let dw = (p.spindle_rpm - r.pts[k - 1].spindle_rpm).abs();
        assert!(dw <= 1.0 + 1e-9, "{dw} rpm in a period");
    }
    let braked = r.pts[kb - 300].z + 10.0;
    assert!((braked - 1.125).abs() <= 0.0075, "braked over {braked}");
}

/// G33 taps with a floating holder (cycles.md §20: M05 at the bottom,
/// then the reverse): no rigid reversal. Z brakes to the bottom alone at
/// 2000 mm/s² (1.25 × 5 = 6.25 mm/s: 6.25² / 4000 = 0.0098 mm) while the
/// spindle still turns, and stands while the spindle stops and reverses.
#[test]
fn a_floating_tap_still_brakes_z_alone() {
    let r = run("O0014\nG97 M03 S300\nG00 X0 Z3\nG33 Z-15 F1.25\nG00 X50 Z50\nM30\n");
    check_end_points(&r);
    check_limits(&r, false);
    let at_bottom: Vec<&SetPoint> = r.pts.iter().filter(|p| p.z == -15.0).collect();
    let turned = at_bottom.last().unwrap().spindle_turns - at_bottom[0].spindle_turns;
    // The spindle stops from 300 rpm at 1000 rpm/s (0.3 s, 0.75 turn)
    // and restarts the other way while Z stands.
    assert!(turned > 0.75, "{turned} turns at the bottom");
    assert!(at_bottom.iter().any(|p| p.spindle_rpm < 0.0));
}

fn conformance() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/conformance");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("skipping: {} not found", dir.display());
        None
    }
}

/// Every conformance program that threads or taps, run period by period
/// on its machine (the reference one, X 1500 and Z 2000 mm/s² radial,
/// unless the case brings a machine file): no axis set point changes its
/// speed by more than its acceleration allows, to 1e-6 of the limit
/// (rounding), in any period. Checked on the machine axes, so that a work
/// origin change is no jump.
#[test]
fn conformance_threads_and_taps_stay_within_the_acceleration() {
    let Some(dir) = conformance() else { return };
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .filter(|p| !p.with_extension("err").exists())
        .collect();
    names.sort();
    let mut checked = Vec::new();
    for path in names {
        let src = std::fs::read_to_string(&path).unwrap();
        let machine = match std::fs::read_to_string(path.with_extension("toml")) {
            Ok(text) => Machine::from_toml(&text).unwrap(),
            Err(_) => Machine::reference(),
        };
        let opts = compiler::Options {
            machine: machine.clone(),
            ..compiler::Options::default()
        };
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if compiler::compile(&name, src.as_bytes(), &opts)
            .module
            .is_none()
        {
            continue;
        }
        let r = run_with(&src, machine, runtime::AutoAck, |_| {}, |_, _| {}, 3600.0);
        if !r.pts.iter().any(|p| p.motion == Motion::Thread) {
            continue;
        }
        let (_, a) = worst_ratios(&r, false);
        assert!(
            a <= 1.0 + 1e-6,
            "{name}: an axis reaches {a:.4} of its acceleration"
        );
        checked.push(name);
    }
    for must in [
        "g92_thread_m24",
        "g92_two_start",
        "g76_internal",
        "part_shaft_m30",
        "g32_runout_chain",
        "g76_m24x1_5",
        "g78_cut_in_modes",
        "g84_rigid_m29",
        "g33_tapping",
    ] {
        assert!(checked.iter().any(|n| n == must), "{must} not checked");
    }
}

/// W118 at run time, where S comes from a variable: lead 3 at 1500 rpm is
/// v = 75 mm/s; Z keeps back 3 × 1000/60 = 50 of its 2000 mm/s² for the
/// spindle, so it needs 75² / 3900 = 1.442 mm to reach thread speed and
/// 75² / 4000 = 1.406 mm to stop; the G32 from Z1 to Z0 gives 1 mm.
#[test]
fn a_thread_that_starts_too_close_is_warned_at_run_time() {
    let src = "O0014\n#1=1500\nG97 S#1 M03\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM30\n";
    let mut got = Vec::new();
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, _| {
            while let Some(w) = ctl.engine_mut().take_room_warning() {
                got.push(w);
            }
        },
        60.0,
    );
    check_limits(&r, false);
    assert_eq!(got.len(), 2, "{got:?}");
    let (entry, exit) = (got[0], got[1]);
    assert!(!entry.exit && exit.exit);
    assert_eq!((entry.tag.line, exit.tag.line), (5, 5));
    assert!(
        (entry.need_mm - 5625.0 / 3900.0).abs() < 1e-9,
        "{}",
        entry.need_mm
    );
    assert!(
        (exit.need_mm - 5625.0 / 4000.0).abs() < 1e-9,
        "{}",
        exit.need_mm
    );
    assert_eq!((entry.room_mm, exit.room_mm), (1.0, 1.0));
    assert_eq!(
        entry.message(),
        "thread too short to reach its lead: at 1500 rpm Z needs 1.442 mm to reach thread speed, this block gives 1.000 mm"
    );
    // From Z3 it fits: no warning.
    let mut none = true;
    run_with(
        &src.replace("Z1\n", "Z3\n"),
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, _| none &= ctl.engine_mut().take_room_warning().is_none(),
        60.0,
    );
    assert!(none);
}

/// A G32 chain whose last block runs out (G32 Z-30 J1 K3): the kernel
/// holds that block back until the next one says the chain ends, having
/// moved its programmed point to X29 Z-30 already; the runtime must not
/// take that for a move of its own (it used to rapid to Z-30, then cut
/// the thread back up to Z-27). Hand figures: lead 2 at 400 rpm is
/// 13.333 mm/s; the chain runs from Z5 without a stop through Z-20 to
/// P1 = X29 Z-27 at lead 2 and runs out to X31 Z-30 (3 mm of Z for 1 mm
/// of radius, lead 2 along Z): Z only ever goes down, at
/// 2 × 400/60 / 1000 = 0.013333 mm per period while locked, and no
/// rapid comes between the thread periods. The periods carry the line of
/// the block they cut.
#[test]
fn a_run_out_chain_is_cut_in_one_go() {
    let src =
        "O0012\nG97 S400 M03\nG00 X40 Z5\nX29\nG32 Z-20 F2\nG32 Z-30 J1 K3\nM05\nG00 X40\nM30\n";
    let r = run(src);
    check_end_points(&r);
    check_limits(&r, false);
    let th: Vec<usize> = (0..r.pts.len())
        .filter(|&k| r.pts[k].motion == Motion::Thread)
        .collect();
    let (first, last) = (th[0], *th.last().unwrap());
    assert!(
        r.pts[first..=last]
            .iter()
            .all(|p| p.motion == Motion::Thread),
        "a move between the thread periods"
    );
    for w in r.pts[first..=last].windows(2) {
        assert!(w[1].z <= w[0].z, "Z goes back up at {}", w[1].time_s);
    }
    // Through Z-20 at thread speed, locked at lead 2 from Z-1 to Z-26.9:
    // 25.9 mm at 0.013333 mm per period is 1942.5 periods.
    let locked: Vec<&[SetPoint]> = r.pts[first..=last]
        .windows(2)
        .filter(|w| w[0].z < -1.0 && w[1].z > -26.9)
        .collect();
    assert!((1942..=1944).contains(&locked.len()), "{}", locked.len());
    for w in locked {
        let lead = (w[0].z - w[1].z) / (w[1].spindle_turns - w[0].spindle_turns);
        assert!((lead - 2.0).abs() < 1e-9, "lead {lead} at {}", w[1].time_s);
        assert!((w[0].z - w[1].z - 2.0 * 400.0 / 60.0 * 0.001).abs() < 1e-6);
    }
    let end = r.pts[last];
    assert!(
        (end.x - 31.0).abs() < 1e-9 && (end.z + 30.0).abs() < 1e-9,
        "{end:?}"
    ); // The held block's legs come with the next block (M05, line 7) but
       // are its own: line 5 up to Z-20, line 6 (the G32 Z-30 J1 K3) after.
    for p in &r.pts[first..=last] {
        let want = if p.z > -20.0 + 0.014 {
            5
        } else if p.z < -20.0 - 0.014 {
            6
        } else {
            p.line
        };
        assert_eq!(p.line, want, "at Z{}", p.z);
    }
}

/// One random thread cycle from X`d`+5 Z5: a G92 pass pair with a J/K
/// pull-out (45° or J ≠ K), a G76 with a 45° pull-out of 0–3 leads, a
/// G32 into a run-out that turns the long axis to X, or a taper G92, at
/// a lead and spindle speed that may ask an axis for more than its
/// maximum cutting feed.
fn thread_cycle(rng: &mut Lcg) -> String {
    let s = rng.pick(&[200, 500, 1000, 1500, 2500]);
    let lead = rng.pick(&[0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0]);
    let (d, l) = (rng.range(10.0, 60.0), rng.range(8.0, 40.0));
    let mut p = format!("G97 S{s} M03\nG99\nG00 X{:.3} Z5\n", d + 5.0);
    match rng.pick(&[0, 1, 2, 3]) {
        0 => {
            let j = rng.range(0.2, 4.0);
            let k = if rng.unit() < 0.5 {
                j
            } else {
                rng.range(0.2, 4.0)
            };
            p += &format!(
                "G92 X{:.3} Z-{l:.3} F{lead} J{j:.3} K{k:.3}\nX{:.3}\n",
                d - 0.3,
                d - 0.6
            );
        }
        1 => {
            let h = lead * 0.6;
            p += &format!(
                "G76 P01{:02}60 Q50 R0.02\nG76 X{:.3} Z-{l:.3} P{} Q{} F{lead}\n",
                rng.pick(&[0, 5, 10, 20, 30]),
                d - 2.0 * h,
                (h * 1000.0).round(),
                (h * 300.0).max(60.0).round()
            );
        }
        2 => {
            p += &format!(
                "G32 Z-{l:.3} F{lead}\nG32 X{:.3} W-{:.3}\nG00 X{:.3}\nZ5\n",
                d + 5.0 + rng.range(0.0, 6.0),
                rng.range(0.5, 5.0),
                d + 12.0
            );
        }
        _ => {
            let j = rng.range(0.2, 4.0);
            p += &format!(
                "G92 X{:.3} Z-{l:.3} R-{:.3} F{lead} J{j:.3} K{j:.3}\n",
                d - 0.3,
                rng.range(0.5, 3.0)
            );
        }
    }
    p + "G00 X80 Z20\nM30\n"
}

/// Random thread cycles (a fixed seed) are certified period by period,
/// their leads kept through pull-outs and run-outs, or stop with E4010
/// before the thread exactly where `gbcc` warned W126 (a block of the
/// chain asks an axis for more than its maximum cutting feed). Programs
/// like these found a pull-out braked out of step with the spindle
/// (its path above the path limit of programmed feeds), run-outs whose
/// long axis, X, closed its lag ever slower, and pull-outs too fast for
/// X that ran with a spoilt lead instead of stopping.
#[test]
fn random_thread_cycles_are_certified_or_stop_where_warned() {
    let mut rng = Lcg(43);
    let machine = Machine::reference();
    let (mut certified, mut stopped) = (0, 0);
    for _ in 0..120 {
        let src = thread_cycle(&mut rng);
        let compiled = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
        let warned = compiled.diags.iter().any(|(_, d)| d.code == "W126");
        let Some(module) = compiled.module else {
            continue;
        };
        let mut ctl = Controller::new(module, machine.clone(), AutoAck).expect("loads");
        let (cert, _) = ctl.run_certified(600_000);
        match ctl.state() {
            RunState::Alarm(code) => {
                assert!(
                    code == 4010 && warned,
                    "alarm {code}, W126 {warned}:\n{src}"
                );
                stopped += 1;
            }
            state => {
                assert_eq!(state, RunState::Ended, "{src}");
                assert!(!warned, "W126 but no alarm:\n{src}");
                if let Some(v) = cert.violation() {
                    panic!("line {}: {v}\n{src}", v.line);
                }
                certified += 1;
            }
        }
    }
    // Both kinds are there in numbers.
    assert!(
        certified >= 80 && stopped >= 20,
        "{certified} certified, {stopped} stopped"
    );
}

/// Found by the `thread` fuzz target. A G32 chain whose second leg asks
/// X for 4002 mm/min at the commanded 1500 rev/min (3 × 1500 × 3.5155 /
/// 3.953): the chain was checked at the speed the spindle had reached
/// when it counted as at speed (0.5 % below, 3983 mm/min) and ran with X
/// beyond its feed; it is checked at the commanded speed now, as W126 is.
/// And a chain whose corner comes while X, long on the leg before it,
/// still closes the lag of the corner before that (it must slow from
/// 50 mm/s almost to a stand there): certified, the corner counted within
/// the lag X may still have.
#[test]
fn thread_chains_the_fuzz_target_found() {
    let too_fast = "G97 S1500 M03\nG99\nG00 X50.490 Z5\nG32 Z-12.769 F3\nG32 X57.521 W-3.953\nG32 X58.084 W-3.203\nG00 X65.084\nZ5\nG00 X80 Z20\nM30\n";
    let machine = Machine::reference();
    let mut ctl =
        Controller::new(module(too_fast, &machine), machine.clone(), AutoAck).expect("loads");
    let _ = ctl.run_certified(600_000);
    assert_eq!(ctl.state(), RunState::Alarm(4010));
    let lagging = "G97 S1000 M03\nG99\nG00 X64.804 Z5\nG32 Z-39.373 F3\nG32 X67.491 W-2.969\nG32 X73.429 W-1.844\nG32 X73.523 W-3.375\nG00 X80.523\nZ5\nG00 X80 Z20\nM30\n";
    assert_eq!(certify(lagging, &machine, false), Some(Ok(())));
}

/// A chain whose 45° leg (lead 4 at 1000 rev/min: X long at 66.667
/// mm/s, the path at 93.7) runs into a Z leg of 0.281 mm (its path at
/// 66.667): braking along the path, that leg is too short to slow the
/// path by 27 mm/s, so the planner held the 45° leg's exit down, the
/// chain began to brake there, 8 mm before its end, and ran the legs
/// after it at Z's top feed, lead 5 where 4 is programmed. The long axis
/// keeps its speed through the corner; the chain now brakes only for its
/// end, and is certified.
#[test]
fn a_short_slower_leg_does_not_brake_the_chain() {
    let src = "G97 S1000 M03\nG99\nG00 X64.804 Z5\nG32 Z-40.000 F4\nG32 X72.773 W-3.938\nG32 X72.773 W-0.281\nG32 X73.866 W-3.828\nG32 X76.085 W-3.984\nG00 X83.085\nZ5\nG00 X80 Z20\nM30\n";
    assert_eq!(certify(src, &Machine::reference(), false), Some(Ok(())));
}

/// The thread periods of a run from the index pulse (Z leaves 5) to the
/// last one.
fn chain_periods(r: &Run) -> Vec<&SetPoint> {
    r.pts
        .iter()
        .filter(|p| p.motion == Motion::Thread && p.z < 5.0)
        .collect()
}

/// Asserts that set points of a chain that runs out on X and along −Z
/// never turn back on either axis.
fn assert_outward(th: &[&SetPoint], src: &str) {
    for w in th.windows(2) {
        let (a, b) = (w[0], w[1]);
        assert!(
            b.x >= a.x,
            "X turns back at {} s: {} after {}\n{src}",
            b.time_s,
            b.x,
            a.x
        );
        assert!(
            b.z <= a.z,
            "Z turns back at {} s: {} after {}\n{src}",
            b.time_s,
            b.z,
            a.z
        );
    }
}

/// Chains whose every leg runs out on X and along −Z (the thread fuzz
/// target's shape) whose axes had to stop or slow at corners while they
/// still closed the lag of a corner before: a square step at 2500
/// rev/min (a radial leg of 4 mm at 62.5 mm/s, then a Z leg), where Z
/// ran 0.94 mm past the step's corner and came back, and X ran 1.2 mm
/// past the Z leg's and came back; and a 45° leg into an X leg of
/// 0.047 mm over 3.4 mm of Z, where X, still catching up at 28.6 mm/s,
/// ran 8 µm past the chain's end and came back. Such a chain never turns
/// back on either axis, so neither may its set points: the follower
/// brakes an axis ahead of a corner that stops or slows it, and keeps
/// that corner's speed until the axis is past it. Both are certified,
/// with jerk limiting too.
#[test]
fn a_chain_that_never_turns_back_is_followed_without_turning_back() {
    let step = "G97 S2500 M03\nG99\nG00 X16.765 Z5\nG32 Z-40.000 F1.5\nG32 X21.171 W-2.984\nG32 X29.140 W-0.000\nG32 X29.140 W-3.984\nG32 X37.108 W-3.984\nG32 X45.077 W-3.984\nG00 X52.077\nZ5\nG00 X80 Z20\nM30\n";
    let slow_x = "G97 S1000 M03\nG99\nG00 X64.804 Z5\nG32 Z-39.373 F3\nG32 X67.491 W-2.969\nG32 X73.429 W-1.844\nG32 X73.523 W-3.375\nG00 X80.523\nZ5\nG00 X80 Z20\nM30\n";
    for src in [step, slow_x] {
        let r = run(src);
        assert_eq!(r.state, RunState::Ended);
        let th = chain_periods(&r);
        assert!(th.len() > 500, "{} thread periods", th.len());
        assert_outward(&th, src);
        for jerk in [false, true] {
            assert_eq!(certify(src, &Machine::reference(), jerk), Some(Ok(())));
        }
    }
}

/// Found by the `thread` fuzz target: lead 4 at 1000 rev/min into legs
/// of 16 µm along Z. Z slows from 66.667 mm/s to 22.7 (0.047 mm of X
/// over 0.016 of Z), then to 0.27 (3.98 mm of X), and runs on at 66.667
/// after that. The chain's point passes both corners in one period; Z,
/// told in that period only of the first, sped up by a·dt and ran 0.06 mm
/// past the point (to Z−20.184, the corner being at Z−20.107 and the
/// leg after it ending at Z−20.123) and came back. And X, closing a lag
/// of 1.2 mm onto the last leg (1.04 mm/s on X), caught the point as it
/// braked for the chain's end and turned back by 1.7 µm (on the
/// diameter). Neither axis now turns back, Z never passes Z−20.123
/// before the last leg, and the run is certified with and without jerk
/// limiting.
#[test]
fn an_axis_whose_chain_point_passes_two_corners_in_a_period_never_passes_it() {
    let src = "G97 S1000 M03\nG99\nG00 X21.471 Z5\nG32 Z-19.294 F4\nG32 X21.502 W-0.109\nG32 X22.533 W-0.688\nG32 X22.627 W-0.016\nG32 X30.596 W-0.016\nG32 X30.689 W-2.984\nG00 X37.689\nZ5\nG00 X80 Z20\nM30\n";
    let r = run(src);
    assert_eq!(r.state, RunState::Ended);
    let th = chain_periods(&r);
    assert_outward(&th, src);
    // Until the point reaches the last leg (line 9), Z stays on or behind
    // the leg that ends at Z−20.123.
    for p in th.iter().filter(|p| p.line < 9) {
        assert!(p.z >= -20.123 - 1e-9, "Z at {} at {} s", p.z, p.time_s);
    }
    for jerk in [false, true] {
        assert_eq!(certify(src, &Machine::reference(), jerk), Some(Ok(())));
    }
}

/// A random G32 chain of the thread target's shape: a Z thread, then up
/// to five legs out on X and along −Z, each of 0–7.97 mm on the diameter
/// and 0–3.98 mm of Z, at the target's speeds and leads.
fn outward_chain(rng: &mut Lcg) -> String {
    let rpm = rng.pick(&[200, 500, 1000, 1500, 2500]);
    let lead = rng.pick(&[0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0]);
    let (d, l) = (rng.range(15.0, 65.0), rng.range(8.0, 40.0));
    let mut s = format!("G97 S{rpm} M03\nG99\nG00 X{d:.3} Z5\nG32 Z-{l:.3} F{lead}\n");
    let mut x = d;
    for _ in 0..rng.pick(&[1, 2, 3, 4, 5]) {
        let (dx, dz) = (rng.range(0.0, 7.97), rng.range(0.0, 3.98));
        if dx == 0.0 && dz == 0.0 {
            continue;
        }
        x += dx;
        s += &format!("G32 X{x:.3} W-{dz:.3}\n");
    }
    s + &format!("G00 X{:.3}\nZ5\nG00 X80 Z20\nM30\n", x + 7.0)
}

/// Chains that never turn back on an axis are followed without turning
/// back (docs/language.md, thread motion), up to where the last leg is
/// too short to stop in (W118) or a leg asks an axis for more than its
/// feed (W126). Of these 1 200 random chains 954 run; on the stop-46
/// follower 6 of them turned back, two by more than rounding (X by 2.0
/// µm, Z by 0.17 µm).
#[test]
fn random_outward_chains_never_turn_back() {
    let mut rng = Lcg(99);
    let mut ran = 0;
    for _ in 0..1200 {
        let src = outward_chain(&mut rng);
        let compiled = compiler::compile("t.nc", src.as_bytes(), &compiler::Options::default());
        if compiled
            .diags
            .iter()
            .any(|(_, d)| d.code == "W118" || d.code == "W126")
        {
            continue;
        }
        let r = run(&src);
        assert_eq!(r.state, RunState::Ended, "{src}");
        ran += 1;
        assert_outward(&chain_periods(&r), &src);
    }
    assert!(ran > 900, "{ran} chains ran");
}

/// Found by the `thread` target (stop 47), a false alarm of `gbvm check`
/// older than that stop: a Z thread at lead 4, 1000 rev/min, a leg of
/// 16 µm along Z and then a 45° leg. The chain passes the short leg and
/// the corner in one period; X starts in that period at a·dt, and the
/// period's chord passes the short leg's start (Z−9.129) 1.0 µm off,
/// where only the corner itself had the tolerance of the chord's bend
/// (2.5 µm: `chain_corner_mm`). The end points less than a period's
/// travel before a corner now share it, and the run is certified.
#[test]
fn an_end_point_a_period_before_a_corner_shares_its_tolerance() {
    let src = "G97 S1000 M03\nG99\nG00 X15.196 Z5\nG32 Z-9.129 F4\nG32 X15.196 W-0.016\nG32 X23.165 W-3.984\nG00 X30.165\nZ5\nG00 X80 Z20\nM30\n";
    assert_eq!(certify(src, &Machine::reference(), false), Some(Ok(())));
}

/// Chains that the first versions of the follower's end braking got
/// wrong (the bounded `thread` run): a last leg of 16 µm along Z, too
/// short to brake in (W118), taken to brake from the start so that Z
/// never closed its lag (3.9 mm off the path); and two radial legs after
/// a Z thread, where X, the long axis, was held to match the point
/// before the point braked at X's own rate, and never closed its lag
/// (lead 1.84 where 4 is programmed). Both are certified.
#[test]
fn chains_that_end_on_a_short_leg_or_a_long_axis_lag_are_certified() {
    let short_last = "G97 S1000 M03\nG99\nG00 X15.000 Z5\nG32 Z-8.000 F2\nG32 X19.594 W-0.672\nG32 X27.375 W-0.016\nG32 X27.375 W-0.016\nG00 X34.375\nZ5\nG00 X80 Z20\nM30\n";
    let radial = "G97 S1000 M03\nG99\nG00 X15.000 Z5\nG32 Z-8.000 F4\nG32 X21.688 W-0.000\nG32 X28.594 W-0.000\nG00 X35.594\nZ5\nG00 X80 Z20\nM30\n";
    let machine = Machine::reference();
    for src in [short_last, radial] {
        assert_eq!(certify(src, &machine, false), Some(Ok(())), "{src}");
    }
}

/// A straight thread chained to a radial exit (`G32 Z-20 F2`, then `G32
/// X30`): Z, at 33.3 mm/s, stops for good at the corner. The follower
/// tracked the chain up to the corner and ran Z on to −20.248 (its
/// stopping distance past the thread's end, where a shoulder may be); it
/// now brakes Z ahead of the corner and never passes Z−20, and the run
/// is certified (the corner is cut by the lag that builds). And the fuzz
/// target's chain of short legs whose X ran 0.047 mm past where the
/// chain left it.
#[test]
fn an_axis_a_chain_stops_never_runs_past_the_corner() {
    let src = "G97 S1000 M03\nG99\nG00 X20 Z5\nG32 Z-20 F2\nG32 X30\nG00 X40\nZ5\nM30\n";
    let r = run(src);
    assert_eq!(r.state, RunState::Ended);
    let deepest = r
        .pts
        .iter()
        .filter(|p| p.motion == Motion::Thread)
        .map(|p| p.z)
        .fold(f64::INFINITY, f64::min);
    assert!(deepest >= -20.0 - 1e-9, "Z reached {deepest}");
    let machine = Machine::reference();
    assert_eq!(certify(src, &machine, false), Some(Ok(())));
    let short_legs = "G97 S1000 M03\nG99\nG00 X33.235 Z5\nG32 Z-9.255 F3\nG32 X35.548 W-0.156\nG32 X35.860 W-3.984\nG32 X38.767 W-0.141\nG32 X38.892 W-0.000\nG32 X38.892 W-0.656\nG00 X45.892\nZ5\nG00 X80 Z20\nM30\n";
    assert_eq!(certify(short_legs, &machine, false), Some(Ok(())));
}
