//! `gbvm check`, the motion certificate: every conformance program
//! (../shared/conformance) and every public corpus program
//! (../shared/corpus/public) that runs to its end is certified, except the
//! ones listed in [`FAILS_TODAY`], which exit 1 naming the place of the
//! violation; an origin change is no jump; `--frame machine` traces the
//! axes, `--frame counts` them in steps of the resolution; the trace names
//! the motion and the tool.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Programs `gbvm check` does not certify yet, with the first violation
/// it measures on the reference machine (none today: the run-out chains,
/// the 45° pull-outs and the corners a thread chain turns at speed are
/// certified, issue 15). A listed program that passes fails this test,
/// so that it leaves the list.
const FAILS_TODAY: &[(&str, &str)] = &[];

/// Simulated seconds a program may run in this test; one that does not
/// end within them (a dwell waiting for a spindle that never turns …)
/// does not run to its end and is not certified.
const MAX_TIME: &str = "1800";

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-check-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(bin: &str, args: &[&str]) -> Output {
    Command::new(bin).args(args).output().unwrap()
}

fn gbcc(args: &[&str]) -> Output {
    run(env!("CARGO_BIN_EXE_gbcc"), args)
}

fn gbvm(args: &[&str]) -> Output {
    run(env!("CARGO_BIN_EXE_gbvm"), args)
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// What `gbvm check` made of a program.
enum Verdict {
    /// Exit 0: the summary line.
    Certified(String),
    /// Exit 1: the violation line.
    Violation(String),
    /// It did not run to its end (an alarm, the time bound) or did not
    /// compile.
    NotRun,
}

fn check(src: &Path, machine: Option<&Path>, out: &Path) -> Verdict {
    let name = src.file_name().unwrap().to_string_lossy().into_owned();
    let gbc = out.join(format!("{name}.gbc"));
    let (src, gbc) = (src.to_str().unwrap(), gbc.to_str().unwrap());
    let mut args = vec![src, "-o", gbc];
    let m = machine.map(|m| m.to_str().unwrap());
    if let Some(m) = m {
        args.extend(["--machine", m]);
    }
    if !gbcc(&args).status.success() {
        return Verdict::NotRun;
    }
    let mut args = vec!["check", gbc, "--max-time", MAX_TIME];
    if let Some(m) = m {
        args.extend(["--machine", m]);
    }
    let o = gbvm(&args);
    match o.status.code() {
        Some(0) => {
            let summary = text(&o.stdout);
            assert!(summary.starts_with("certified: "), "{summary}");
            Verdict::Certified(summary)
        }
        Some(1) => Verdict::Violation(text(&o.stderr)),
        Some(2) => Verdict::NotRun,
        c => panic!("{name}: gbvm check exited {c:?}: {}", text(&o.stderr)),
    }
}

/// Compares the verdicts with [`FAILS_TODAY`].
fn judge(results: Vec<(String, Verdict)>) -> (usize, Vec<String>) {
    let mut wrong = Vec::new();
    let mut certified = 0;
    for (name, v) in results {
        let listed = FAILS_TODAY.iter().any(|(n, _)| *n == name);
        match (v, listed) {
            (Verdict::Certified(_), false) => certified += 1,
            (Verdict::Certified(_), true) => {
                wrong.push(format!("{name}: certified now; take it off FAILS_TODAY"))
            }
            (Verdict::Violation(e), false) => wrong.push(format!("{name}: {e}")),
            // Exit 1 names the place: `FILE:LINE: violation: at T s: …`.
            (Verdict::Violation(e), true) => {
                if !e.contains(": violation: at ") {
                    wrong.push(format!("{name}: the violation reads {e:?}"));
                }
            }
            (Verdict::NotRun, _) => {}
        }
    }
    (certified, wrong)
}

fn shared(dir: &str) -> Option<PathBuf> {
    let d = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared")
        .join(dir);
    d.is_dir().then_some(d)
}

/// The conformance programs that run to their end, each with its
/// machine file (the case's, if any) plus `extra` TOML.
fn conformance_verdicts(tag: &str, extra: &str) -> Option<Vec<(String, Verdict)>> {
    let Some(suite) = shared("conformance") else {
        eprintln!("../shared/conformance not found: skipped");
        return None;
    };
    let out = scratch(tag);
    let mut results = Vec::new();
    let mut names: Vec<PathBuf> = std::fs::read_dir(&suite)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "nc"))
        .filter(|p| p.with_extension("canon").exists())
        .collect();
    names.sort();
    for src in names {
        let canon = std::fs::read_to_string(src.with_extension("canon")).unwrap();
        if canon.contains("ALARM") {
            continue; // it does not run to its end
        }
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let toml = src.with_extension("toml");
        let case = std::fs::read_to_string(&toml).unwrap_or_default();
        let machine = out.join(format!("{name}.toml"));
        std::fs::write(&machine, format!("{case}\n{extra}")).unwrap();
        results.push((name, check(&src, Some(&machine), &out)));
    }
    let _ = std::fs::remove_dir_all(out);
    Some(results)
}

#[test]
fn every_conformance_program_that_runs_is_certified() {
    let Some(results) = conformance_verdicts("conformance", "") else {
        return;
    };
    let (certified, wrong) = judge(results);
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // 72 cases with a canon, none in FAILS_TODAY (2026-12).
    assert!(certified >= 60, "only {certified} certified");
}

/// `motion.jerk_limiting` in the machine file turns the S-curve on: the
/// same programs are certified with each axis within its jerk too (a
/// work shift while the set points lag the canon, as in g54_g59_offsets,
/// was once a missed end point).
#[test]
fn every_conformance_program_that_runs_is_certified_with_jerk_limiting() {
    let extra = "[motion]\njerk_limiting = true\n";
    let Some(results) = conformance_verdicts("jerk", extra) else {
        return;
    };
    let moving = results.iter().filter(|(_, v)| match v {
        Verdict::Certified(s) => !s.contains("end points: 0 of 0"),
        _ => false,
    });
    for (name, v) in moving {
        if let Verdict::Certified(s) = v {
            assert!(s.contains("; jerk: worst "), "{name}: {s}");
        }
    }
    let (certified, wrong) = judge(results);
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    assert!(certified >= 60, "only {certified} certified");
}

#[test]
fn every_corpus_program_that_runs_is_certified() {
    let Some(corpus) = shared("corpus/public") else {
        eprintln!("../shared/corpus/public not found: skipped");
        return;
    };
    let out = scratch("corpus");
    // The machines of compiler/tests/corpus.rs: integer coordinates in
    // increments where the manifest says so; the Doosan's CIR = 0.
    let machine = |increment: bool, doosan: bool| -> Option<PathBuf> {
        let mut toml = String::from("[machine]\n");
        if increment {
            toml.push_str("decimal_point = \"increment\"\n");
        }
        if doosan {
            toml.push_str("arc_without_center = \"line\"\n");
        }
        let path = out.join(format!("m-{increment}-{doosan}.toml"));
        std::fs::write(&path, toml).unwrap();
        Some(path)
    };
    let manifest = std::fs::read_to_string(corpus.join("MANIFEST.tsv")).unwrap();
    let mut results = Vec::new();
    for line in manifest.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        let (file, features) = (cols[0], cols.get(6).copied().unwrap_or(""));
        let m = machine(
            features.contains("int-units-no-decimal"),
            file.starts_with("doosan-lynx300__"),
        );
        results.push((
            file.to_string(),
            check(&corpus.join(file), m.as_deref(), &out),
        ));
    }
    let (certified, wrong) = judge(results);
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // 18 corpus programs are certified today (2026-12).
    assert!(certified >= 15, "only {certified} certified");
    let _ = std::fs::remove_dir_all(out);
}

fn compiled(tag: &str, src: &str) -> (PathBuf, PathBuf) {
    let d = scratch(tag);
    let nc = d.join("p.nc");
    std::fs::write(&nc, src).unwrap();
    let gbc = d.join("p.gbc");
    let o = gbcc(&[nc.to_str().unwrap(), "-o", gbc.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    (d, gbc)
}

/// Compiles `src` and runs `gbvm check` on it, which must certify the
/// run; its summary line.
fn certified(tag: &str, src: &str) -> String {
    let (d, gbc) = compiled(tag, src);
    let o = gbvm(&["check", gbc.to_str().unwrap()]);
    assert!(
        o.status.success(),
        "{src}{}{}",
        text(&o.stdout),
        text(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(d);
    text(&o.stdout)
}

/// G50 moves work zero by 100 mm in Z between two feeds: in work
/// coordinates Z jumps by 100 mm in one period, the machine axes do not
/// move, and the check (on machine coordinates) certifies the run.
#[test]
fn an_origin_change_is_certified_and_the_machine_frame_shows_no_jump() {
    let src = "O0001\nG98 G01 X20 Z-5 F600\nG50 X20 Z95\nG01 Z90\nM30\n";
    let (d, gbc) = compiled("origin", src);
    let gbc = gbc.to_str().unwrap();
    let o = gbvm(&["check", gbc]);
    assert!(o.status.success(), "{}{}", text(&o.stdout), text(&o.stderr));
    assert!(
        text(&o.stdout).contains("end points: 2 of 2 reached"),
        "{}",
        text(&o.stdout)
    );
    let zs = |frame: &str| -> Vec<f64> {
        let o = gbvm(&["run", gbc, "--emit", "trace", "--frame", frame]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        let t = text(&o.stdout);
        assert_eq!(
            t.lines().next(),
            Some("time_s,x,z,spindle_rpm,feed,line,motion,tool,file")
        );
        t.lines()
            .skip(1)
            .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
            .collect()
    };
    let jump = |z: &[f64]| {
        z.windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max)
    };
    // Work: Z −5 becomes 95 at once. Machine: never more than a period's
    // travel at 600 mm/min (0.01 mm).
    assert!((jump(&zs("work")) - 100.0).abs() < 0.02);
    assert!(jump(&zs("machine")) <= 0.01 + 1e-9);
    let _ = std::fs::remove_dir_all(d);
}

/// `--frame counts` gives the machine set points in whole steps of the
/// resolution: each within half a step of the machine frame's set point,
/// and the end point X20.0004 Z-5.0006 as 20 000 and −5 001 µm steps
/// (20 000.4 and −5 000.6 rounded to the nearest).
#[test]
fn the_counts_frame_quantizes_the_machine_set_points() {
    let src = "O0001\nG98 G01 X20.0004 Z-5.0006 F600\nM30\n";
    let (d, gbc) = compiled("counts", src);
    let gbc = gbc.to_str().unwrap();
    let trace = |frame: &str| -> Vec<(f64, f64)> {
        let o = gbvm(&["run", gbc, "--emit", "trace", "--frame", frame]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        let t = text(&o.stdout);
        t.lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[1].parse().unwrap(), f[2].parse().unwrap())
            })
            .collect()
    };
    let (mm, counts) = (trace("machine"), trace("counts"));
    assert_eq!(mm.len(), counts.len());
    assert!(mm.len() > 100, "{} periods", mm.len());
    for (m, n) in mm.iter().zip(&counts) {
        assert_eq!(n.0.fract(), 0.0, "{n:?} is not a whole count");
        // Half a step, and the machine frame's own 6-decimal rounding.
        assert!((n.0 * 0.001 - m.0).abs() <= 0.0005 + 1e-6, "{m:?} {n:?}");
        assert!((n.1 * 0.001 - m.1).abs() <= 0.0005 + 1e-6, "{m:?} {n:?}");
    }
    assert_eq!(counts.last(), Some(&(20_000.0, -5_001.0)));
    let _ = std::fs::remove_dir_all(d);
}

/// With `backlash_mm` the counts are the drive's command: Z has moved
/// in −, so its 0.03 mm of lost motion is taken up below the set point
/// (−5 000.6 − 30 = −5 030.6 steps, rounded to −5 031); X has moved in +,
/// the power-on direction, and keeps its count. The set points, which
/// `gbvm check` certifies, are the slide's and unchanged.
#[test]
fn the_counts_frame_carries_the_backlash_compensation() {
    let src = "O0001\nG98 G01 X20.0004 Z-5.0006 F600\nM30\n";
    let (d, gbc) = compiled("lash", src);
    let machine = d.join("m.toml");
    std::fs::write(
        &machine,
        "[axes.x]\nbacklash_mm = 0.02\n[axes.z]\nbacklash_mm = 0.03\n",
    )
    .unwrap();
    let (gbc, machine) = (gbc.to_str().unwrap(), machine.to_str().unwrap());
    let last = |frame: &str| -> String {
        let o = gbvm(&[
            "run",
            gbc,
            "--emit",
            "trace",
            "--frame",
            frame,
            "--machine",
            machine,
        ]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        let t = text(&o.stdout);
        let l = t.lines().last().unwrap_or_default();
        l.split(',').skip(1).take(2).collect::<Vec<_>>().join(",")
    };
    assert_eq!(last("counts"), "20000,-5031");
    assert_eq!(last("machine"), "20.000400,-5.000600");
    let o = gbvm(&["check", gbc, "--machine", machine]);
    assert!(o.status.success(), "{}", text(&o.stdout));
    let _ = std::fs::remove_dir_all(d);
}

/// A machine file with `operator.machine_lock`: the work frame runs the
/// program to X20 Z-5, the machine and counts frames stand at the
/// power-on point, machine zero, every period.
#[test]
fn machine_lock_holds_the_machine_frame_and_the_counts() {
    let src = "O0001\nG98 G01 X20 Z-5 F600\nM30\n";
    let (d, gbc) = compiled("lock", src);
    let machine = d.join("m.toml");
    std::fs::write(&machine, "[operator]\nmachine_lock = true\n").unwrap();
    let (gbc, machine) = (gbc.to_str().unwrap(), machine.to_str().unwrap());
    let xz = |frame: &str| -> Vec<String> {
        let args = ["run", gbc, "--emit", "trace", "--frame", frame];
        let o = gbvm(&[&args[..], &["--machine", machine]].concat());
        assert!(o.status.success(), "{}", text(&o.stderr));
        let t = text(&o.stdout);
        let xz = |l: &str| l.split(',').skip(1).take(2).collect::<Vec<_>>().join(",");
        t.lines().skip(1).map(xz).collect()
    };
    let work = xz("work");
    assert!(work.len() > 100, "{} periods", work.len());
    assert_eq!(work.last().map(String::as_str), Some("20.000000,-5.000000"));
    assert!(xz("machine").iter().all(|p| p == "0.000000,0.000000"));
    assert!(xz("counts").iter().all(|p| p == "0,0"));
    let _ = std::fs::remove_dir_all(d);
}

/// The trace names the motion of each period and the tool.
#[test]
fn the_trace_has_motion_words_and_the_tool() {
    let src = "O0001\nT0202\nG00 X20 Z2\nG98 G01 Z0 F600\nG02 X24 Z-2 R2\nG04 X0.05\nM30\n";
    let (d, gbc) = compiled("words", src);
    let o = gbvm(&[
        "run",
        gbc.to_str().unwrap(),
        "--emit",
        "trace",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let t = text(&o.stdout);
    let words: Vec<(String, u64, u64)> = t
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            (
                v["motion"].as_str().unwrap().to_string(),
                v["line"].as_u64().unwrap(),
                v["tool"].as_u64().unwrap(),
            )
        })
        .collect();
    for (word, line) in [("rapid", 3), ("feed", 4), ("arc", 5), ("dwell", 6)] {
        assert!(
            words
                .iter()
                .any(|(w, l, t)| w == word && *l == line && *t == 2),
            "no {word} on line {line} with T2"
        );
    }
    // G04 X0.05: 50 dwell periods of 1 ms.
    assert_eq!(words.iter().filter(|(w, ..)| w == "dwell").count(), 50);
    let o = gbvm(&["run", gbc.to_str().unwrap(), "--frame", "machine"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "--frame without a trace is a usage error"
    );
    let _ = std::fs::remove_dir_all(d);
}

/// Polar and cylindrical interpolation keep the joints within their
/// limits (before, C ran at up to 50 times its speed near the centre):
/// a contour round the centre with a plunge, G00 in the plane, a line 0.5
/// mm from the centre; a groove on a cylinder with an infeed and a G00.
/// The line past the centre slows near it only: 20 mm at F300 take 4 s;
/// C turns from atan2(0.5, 10) = 2.862° to 177.138° at most at its
/// maximum feed, 30°/s (1800°/min), which no run can beat: 5.81 s; the
/// whole line at the speed the centre allows (0.5236 rad/s · 0.5 mm,
/// 0.26 mm/s) would take 76 s. Planned in pieces on which the distance
/// from the centre grows by a tenth, it takes 8.7 s (12.1 s when they
/// doubled it).
#[test]
fn polar_and_cylindrical_interpolation_are_certified() {
    let d = scratch("planes");
    let machine = d.join("c.toml");
    std::fs::write(&machine, "[axes.c]\nenabled = true\n").unwrap();
    let programs = [
        ("polar.nc", "G98 G00 X40 Z-2 C0\nG12.1\nG01 X20 C10 F300\nG03 X-20 C10 R10\nG01 Z-4 F50\nG01 C-10 F300\nG03 X20 C-10 R10\nG00 X20 C0.5\nG01 X-20 C0.5\nG00 X40 C0\nG13.1\nM30\n"),
        ("cylinder.nc", "G98 G00 X40 Z0 C0\nG7.1 C20.\nG01 X36 F20\nG01 Z-10 C90 F200\nG02 Z-30 R10\nG00 Z-40 C0\nG00 X40\nG7.1 C0\nM30\n"),
        // The axis outside the plane taken along: a ramp past the centre
        // (planned in pieces), a rapid back up; on the cylinder an infeed
        // along the groove.
        ("ramps.nc", "G98 G00 X40 Z2 C0\nG12.1\nG01 X-20 C0.5 Z-3 F300\nG00 X40 C0 Z2\nG13.1\nM30\n"),
        ("cylinder_ramps.nc", "G98 G00 X40 Z0 C0\nG7.1 C20.\nG01 Z-10 C90 X36 F200\nG00 Z0 C0 X40\nG7.1 C0\nM30\n"),
    ];
    for (name, src) in programs {
        let nc = d.join(name);
        std::fs::write(&nc, src).unwrap();
        assert!(
            matches!(check(&nc, Some(&machine), &d), Verdict::Certified(_)),
            "{name} is not certified"
        );
    }
    // Under nose-radius compensation (a tool of radius 2): the corner arcs
    // about the square's corners, a plunge where the tool stands.
    let tool = d.join("tool.toml");
    std::fs::write(
        &tool,
        "[axes.c]\nenabled = true\n[[tools.offset]]\nnumber = 1\nradius = 2\n",
    )
    .unwrap();
    let nc = d.join("polar_comp.nc");
    std::fs::write(&nc, "G98 G00 X40 Z-2 C0 T0101\nG12.1\nG42 G01 X20 C-10 F300\nC10\nG01 Z-5 F50\nG01 X-20 F300\nC-10\nX20\nG40 X40 C0\nG00 Z2\nG13.1\nM30\n").unwrap();
    assert!(
        matches!(check(&nc, Some(&tool), &d), Verdict::Certified(_)),
        "polar_comp.nc is not certified"
    );
    let gbc = d.join("polar.nc.gbc");
    let (gbc, m) = (gbc.to_str().unwrap(), machine.to_str().unwrap());
    let o = gbvm(&["run", gbc, "--machine", m, "--emit", "trace"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    // The trace's periods (1 ms) of line 9.
    let t = text(&o.stdout);
    let periods = t
        .lines()
        .filter(|l| l.split(',').nth(6) == Some("9"))
        .count();
    let s = periods as f64 * 0.001;
    assert!((5.81..10.0).contains(&s), "line 9 takes {s} s");
    let _ = std::fs::remove_dir_all(d);
}

/// An arc (its acceleration shared by both axes: 750 mm/s² along the
/// path) runs tangentially into a short Z move that ends the program: the
/// arc brakes onto the speed the short move can stop from at Z's own
/// 2000 mm/s². A period that landed on that speed a rounding residue
/// above it once charged the next period to the arc's acceleration, so
/// the short move fell behind its braking and stopped at up to 4 633
/// mm/s² (27 of these 381 lengths). Every length is certified.
#[test]
fn a_short_move_after_an_arc_stops_within_the_axes_acceleration() {
    let d = scratch("short");
    let mut wrong = Vec::new();
    for k in 0..381 {
        let w = 0.010 + 0.0005 * f64::from(k);
        let src = format!("G98 G00 X2 Z0\nG01 X10 F3000\nG03 X20 Z-5 R5\nG01 W-{w:.4}\nM30\n");
        let nc = d.join(format!("w{k}.nc"));
        std::fs::write(&nc, src).unwrap();
        if let v @ (Verdict::Violation(_) | Verdict::NotRun) = check(&nc, None, &d) {
            let why = match v {
                Verdict::Violation(e) => e,
                _ => "did not run".into(),
            };
            wrong.push(format!("W-{w:.4}: {why}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    let _ = std::fs::remove_dir_all(d);
}

/// An arc of 0.6 µm radius, below the resolution (1 µm), turned the
/// direction within one period and took X to 108 % of its acceleration
/// (found by random contours); it runs as its chord, its turn taken at
/// the corners at both ends.
#[test]
fn an_arc_below_the_resolution_runs_as_its_chord() {
    let src = "G98 G00 X30.9245 Z4.9996\nG03 X33.3079 Z4.1573 R2.7155 F500\nG01 X33.2826 Z4.2165\nG01 X33.2806 Z4.2154\nG01 X33.1052 Z4.1107\nG02 X33.1059 Z4.11 R0.0006\nG01 X33.791 Z5.0\nM30\n";
    certified("micro-arc", src);
}

/// A corner next to an arc of a few µm (R 0.0016): the arc turns some 40°
/// in the period that runs through the corner, so that period's chord
/// leaves the arc's end tangent by half of it, and the line after took X
/// to 104.6 % of its acceleration (found by random contours). The corner
/// speed now keeps that error within the corner's share.
#[test]
fn a_corner_after_an_arc_of_a_few_microns_keeps_the_axes_acceleration() {
    let src = "G98 G00 X86.091 Z-5.212\nG64 F800\nG02 X86.087 Z-5.211 R0.0027\nG02 X86.088 Z-5.210 R0.0015\nG03 X86.086 Z-5.208 R0.0016\nG01 X86.175 Z-5.178\nG01 X85.258 Z-5.178\nM30\n";
    certified("micro-corner", src);
}

/// G61 moves of 2 µm out and 3.5 µm back (radius): the period that ends
/// 0.5 µm before the first end point counts it reached, and the tool goes
/// on to it before it turns. `gbvm check` took the turn for a corner cut
/// past the second end point, which the tool reaches two periods later.
#[test]
fn a_reversal_of_a_few_microns_reaches_both_end_points() {
    let src = "G98 G00 X56 Z9.174\nG61 F800\nG01 X55.118 Z9.174\nG01 X55.118 Z10.000\nG01 X55.122 Z10.000\nG01 X55.115 Z10.000\nG01 X55.141 Z9.982\nM30\n";
    let summary = certified("micro-reversal", src);
    assert!(summary.contains("end points: 6 of 6 reached"), "{summary}");
}

/// An arc of 14 µm, then one of 0.5 µm that runs as its chord, then a
/// line on: the period through the arc's end corner ran on through the
/// 0.5 µm move into the line, whose first period had not kept back the
/// corner's step (X at 101 %). A period now runs through one corner at
/// most.
#[test]
fn a_period_runs_through_one_corner_at_most() {
    let src = "G98 G00 X56.855 Z10\nG64 F800\nG01 X56.839 Z10.000\nG01 X56.738 Z10.000\nG03 X56.717 Z10.000 R0.0144\nG02 X56.716 Z10.000 R0.0005\nG01 X56.593 Z10.000\nG01 X56.589 Z10.000\nM30\n";
    certified("one-corner", src);
}

/// A half circle of 21 µm radius runs tangentially into a 15 µm line:
/// the period through the joint follows the arc's chord, which turns
/// X's velocity away from the tangent by v²·dt/2R, and the line's first
/// period, accelerating at X's full limit, took X to 100.9 %. The line
/// now keeps that share back.
#[test]
fn a_line_after_a_tight_arc_keeps_back_the_arcs_share() {
    let src = "G98 G00 X28.993 Z-0.872\nG64 F800\nG03 X28.900 Z-0.933 R0.0384\nG01 X28.897 Z-0.935\nG03 X28.897 Z-0.893 R0.0210\nG01 X28.928 Z-0.893\nM30\n";
    certified("tight-arc", src);
}

/// With jerk limiting, an arc of 2.45 mm radius at F3000: when the
/// moving average ran along the path, it bounded the jerk along it but
/// not the turning's (v³/R² and 3·v·a/R on the axes), and X reached
/// 105.8 % of its jerk. Now each axis's set points are averaged, which
/// bounds every axis's jerk whatever the path does.
#[test]
fn an_arc_under_jerk_limiting_keeps_the_axes_jerk() {
    let d = scratch("jerk-arc");
    let machine = d.join("jerk.toml");
    std::fs::write(&machine, "[motion]\njerk_limiting = true\n").unwrap();
    let nc = d.join("arc.nc");
    let src = "G98 G00 X55.570 Z0.756\nG61 F3000\nG03 X61.994 Z-2.945 R2.4505\nG01 X61.504 Z-3.953\nM30\n";
    std::fs::write(&nc, src).unwrap();
    match check(&nc, Some(&machine), &d) {
        Verdict::Certified(s) => assert!(!s.contains("jerk: not limited"), "{s}"),
        Verdict::Violation(e) => panic!("{e}"),
        Verdict::NotRun => panic!("did not run"),
    }
    let _ = std::fs::remove_dir_all(d);
}

/// G76 pull-outs at 45° and thread speed (found by random thread cycles):
/// X, which follows the corner within its acceleration, closed its lag at
/// up to 67.5 mm/s (X's top cutting feed is 66.667), and where the chain
/// braked at X's whole acceleration it ran 0.095 mm past the pull-out's
/// end before coming back. Both are certified now.
#[test]
fn a_thread_pull_out_is_followed_within_the_top_speed_and_not_past_its_end() {
    let programs = [
        "G97 S1500 M03\nG99\nG00 X47.874 Z5\nG76 P012060 Q100 R0.02\nG76 X40.474 Z-27.657 P1200 Q360 F2\nG00 X80 Z20\nM30\n",
        "G97 S2500 M03\nG99\nG00 X36.444 Z5\nG76 P021060 Q100 R0.02\nG76 X30.844 Z-24.389 P300 Q90 F0.5\nG00 X80 Z20\nM30\n",
    ];
    for (k, src) in programs.iter().enumerate() {
        certified(&format!("pull-out-{k}"), src);
    }
}

/// Thread chains whose pull-out or run-out the runtime braked out of
/// step with the spindle (found by random thread cycles): a 45° G76
/// pull-out at Z's thread speed of 66.667 mm/s, whose path (94.3 mm/s)
/// is above the path limit of programmed feeds but within both axes'
/// (2.83 mm a turn along Z where 4 is programmed); a G32 run-out and a
/// G92 pull-out (J twice K) whose long axis is X, which must start from
/// rest at the corner (27 % and 25 % off). Each lead is kept now, the
/// run-out's and the pull-out's once X has closed its lag.
#[test]
fn a_thread_chain_keeps_its_lead_through_pull_outs_and_run_outs() {
    let programs = [
        "G97 S1000 M03\nG99\nG00 X20.078 Z5\nG76 P012060 Q50 R0.02\nG76 X10.278 Z-22.659 P2400 Q720 F4\nG00 X80 Z20\nM30\n",
        "G97 S1000 M03\nG99\nG00 X64.161 Z5\nG32 Z-38.696 F0.5\nG32 X69.411 W-0.502\nG00 X71.161\nZ5\nG00 X80 Z20\nM30\n",
        "G97 S200 M03\nG99\nG00 X28.556 Z5\nG92 X23.256 Z-16.185 F1.5 J2.702 K1.351\nX22.956\nX22.756\nG00 X80 Z20\nM30\n",
    ];
    for (k, src) in programs.iter().enumerate() {
        let summary = certified(&format!("chain-{k}"), src);
        assert!(
            summary.contains("thread lead: worst 0.0000 % off"),
            "{summary}"
        );
    }
}

/// A 45° G92 pull-out at lead 4.5 and 1000 rev/min asks X for 4500
/// mm/min, above its 4000, though the thread itself (Z at 4500 of its
/// 5000) does not: the run stops with E4010 before the thread starts,
/// and `gbcc` says so (W126). The run went on before and braked the
/// pull-out out of step with the spindle.
#[test]
fn a_pull_out_too_fast_for_x_stops_the_run_before_the_thread() {
    let src = "G97 S1000 M03\nG00 X30 Z5\nG92 X20 Z-20 F4.5 J3 K3\nG00 X60 Z20\nM30\n";
    let d = scratch("pull-out-e4010");
    let nc = d.join("p.nc");
    std::fs::write(&nc, src).unwrap();
    let gbc = d.join("p.gbc");
    let o = gbcc(&[nc.to_str().unwrap(), "-o", gbc.to_str().unwrap()]);
    let err = text(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("warning[W126]") && err.contains("asks X for 4500 mm/min"),
        "{err}"
    );
    let o = gbvm(&["run", gbc.to_str().unwrap(), "--emit", "trace"]);
    let err = text(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("p.nc:3:1: alarm[E4010]"), "{err}");
    // The tool waited at the thread's start for the spindle, and never
    // moved in the thread.
    let trace = text(&o.stdout);
    let threads: Vec<&str> = trace.lines().filter(|l| l.contains(",thread,")).collect();
    assert!(!threads.is_empty());
    for l in threads {
        assert!(l.contains(",20.000000,5.000000,"), "{l}");
    }
    let _ = std::fs::remove_dir_all(d);
}

/// Chamfers (L), roundings (D) and tool-nose compensation hold a move
/// back until the next block, so the kernel's programmed point runs ahead
/// of the printed moves. The runtime took that for a move it had missed
/// and reached for the programmed point: it cut the sharp corner instead
/// of the chamfer and the rounding, ran the compensated contour through
/// the uncompensated corners, and ran the first compensated feed (its
/// FEED held back too) at rapid speed. `gbvm check` now holds every feed
/// period to its canon line or arc ("path").
#[test]
fn chamfers_roundings_and_compensation_are_cut_as_printed() {
    let chamfer = "G99 G00 X0 Z2 M03 S800\nG01 Z0 F0.1\nX20 L1\nZ-20 D0.5\nX40\nG00 X60 Z10\nM30\n";
    let summary = certified("chamfer", chamfer);
    assert!(summary.contains("path: worst 0.0000 mm off"), "{summary}");
    // The comp_od_profile case: G42 with a 0.8 nose radius, tip 3.
    let comp = "G99 M03 S1000\nT0101\nG00 X60 Z5\nG42 G00 X20 Z2\nG01 Z-10 F0.2\nX30 Z-20\nZ-30\nG02 X40 Z-35 R5\nG01 X50\nZ-45\nX60\nG40 G00 X70 Z5\nM30\n";
    let d = scratch("comp-path");
    let (nc, gbc, toml) = (d.join("p.nc"), d.join("p.gbc"), d.join("m.toml"));
    std::fs::write(&nc, comp).unwrap();
    std::fs::write(
        &toml,
        "[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n",
    )
    .unwrap();
    let (gbc, toml) = (gbc.to_str().unwrap(), toml.to_str().unwrap());
    let o = gbcc(&[nc.to_str().unwrap(), "--machine", toml, "-o", gbc]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let o = gbvm(&["check", gbc, "--machine", toml]);
    let summary = text(&o.stdout);
    assert!(o.status.success(), "{summary}{}", text(&o.stderr));
    assert!(summary.contains("path: worst 0.0000 mm off"), "{summary}");
    // No rapid from the start-up (line 4) to the cancel (line 12) goes
    // below the start-up's Z1.2 into the part (the first feed ran as a
    // rapid to Z−10).
    let o = gbvm(&["run", gbc, "--machine", toml, "--emit", "trace"]);
    let trace = text(&o.stdout);
    for l in trace.lines().skip(1) {
        let f: Vec<&str> = l.split(',').collect();
        let (z, line): (f64, u32) = (f[2].parse().unwrap(), f[5].parse().unwrap());
        if (4..12).contains(&line) && f[6] == "rapid" {
            assert!(z >= 1.2 - 1e-9, "{l}");
        }
    }
    let _ = std::fs::remove_dir_all(d);
}
