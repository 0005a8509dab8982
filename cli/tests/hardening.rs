//! Bad input gets a clean, located answer (issue 20): overflowing
//! literals, `-D` presets, `G65 H99 Q`, the `--vars` file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-harden-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(bin: &str, args: &[&str], cwd: &Path) -> Output {
    Command::new(bin)
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    run(env!("CARGO_BIN_EXE_gbcc"), args, cwd)
}

fn gbvm(args: &[&str], cwd: &Path) -> Output {
    run(env!("CARGO_BIN_EXE_gbvm"), args, cwd)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn a_literal_beyond_the_largest_double_is_a_located_error() {
    let d = dir("lit");
    // 400 nines read as infinity; each is E1010 at the first digit.
    let nines = "9".repeat(400);
    let src = format!("G00 X10 Z2\nG00 X{nines}\nG04 X{nines}\nS{nines}\nM30\n");
    std::fs::write(d.join("inf.nc"), src).unwrap();
    let out = gbcc(&["inf.nc"], &d);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    for at in [
        "inf.nc:2:6: error[E1010]",
        "inf.nc:3:6: error[E1010]",
        "inf.nc:4:2: error[E1010]",
    ] {
        assert!(err.contains(at), "{at} missing in {err}");
    }
    assert!(!d.join("inf.gbc").exists());
    // 20 digits is large but finite: the program compiles.
    std::fs::write(d.join("big.nc"), "G00 X99999999999999999999\nM30\n").unwrap();
    assert_eq!(gbcc(&["big.nc"], &d).status.code(), Some(0));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn defines_must_name_a_user_variable_and_a_finite_value() {
    let d = dir("def");
    std::fs::write(d.join("d.nc"), "G00 X#100 Z2\nM30\n").unwrap();
    for bad in [
        "#0=1",
        "#5001=1",
        "#34=1",
        "#1000=1",
        "#100=inf",
        "#100=nan",
        "#100=1e999",
    ] {
        let out = gbcc(&["d.nc", "-D", bad], &d);
        // A usage error (README, exit codes).
        assert_eq!(out.status.code(), Some(1), "-D {bad}");
        assert!(stderr(&out).contains(bad), "-D {bad}: {}", stderr(&out));
    }
    for good in ["#1=1", "#33=1", "#100=5", "#199=-2.5", "#500=1", "#999=0"] {
        let out = gbcc(&["d.nc", "-D", good], &d);
        assert_eq!(out.status.code(), Some(0), "-D {good}: {}", stderr(&out));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn g65_h99_takes_q_0_to_99_only_and_a_variable_q() {
    let d = dir("h99");
    std::fs::write(d.join("ok.nc"), "G65 H99 Q7\nM30\n").unwrap();
    assert_eq!(gbcc(&["ok.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "ok.gbc"], &d);
    assert_eq!(run.status.code(), Some(2));
    // 500 + Q (dialect.md §8).
    assert!(stdout(&run).contains("ALARM CODE=507"), "{}", stdout(&run));
    for (q, code) in [("Q500", "E1010"), ("Q99999999", "E1010"), ("Q-1", "E1010")] {
        std::fs::write(d.join("bad.nc"), format!("#1=3\nG65 H99 {q}\nM30\n")).unwrap();
        let out = gbcc(&["bad.nc"], &d);
        assert_eq!(out.status.code(), Some(1), "{q}");
        let err = stderr(&out);
        assert!(
            err.starts_with(&format!("bad.nc:2:1: error[{code}]")),
            "{q}: {err}"
        );
    }
    // A variable Q (§7.8) is read when the block runs: 500 + 3.
    std::fs::write(d.join("var.nc"), "#1=3\nG65 H99 Q#1\nM30\n").unwrap();
    assert_eq!(gbcc(&["var.nc"], &d).status.code(), Some(0));
    let run = gbvm(&["run", "var.gbc"], &d);
    assert!(stdout(&run).contains("ALARM CODE=503"), "{}", stdout(&run));
    std::fs::remove_dir_all(&d).unwrap();
}

/// A module that sets #500 to 1, 2, … 50 and ends.
fn counter(d: &Path) {
    std::fs::write(
        d.join("count.nc"),
        "#500=0\nWHILE[#500LT50]DO1\n#500=#500+1\nEND1\nM30\n",
    )
    .unwrap();
    assert_eq!(gbcc(&["count.nc"], d).status.code(), Some(0));
}

#[test]
fn vars_keep_a_link_and_write_through_it() {
    let d = dir("link");
    counter(&d);
    std::fs::create_dir_all(d.join("store")).unwrap();
    std::fs::write(d.join("store/real.txt"), "#501=7\n").unwrap();
    std::os::unix::fs::symlink("store/real.txt", d.join("v.txt")).unwrap();
    let out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let meta = std::fs::symlink_metadata(d.join("v.txt")).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
    assert_eq!(
        std::fs::read_to_string(d.join("store/real.txt")).unwrap(),
        "#500=50\n#501=7\n"
    );
    // No temporary file is left behind.
    let left: Vec<_> = std::fs::read_dir(d.join("store")).unwrap().collect();
    assert_eq!(left.len(), 1);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_planted_temporary_link_is_not_followed() {
    let d = dir("plant");
    counter(&d);
    std::fs::write(d.join("victim.txt"), "precious\n").unwrap();
    // The names the old implementation used, and a few guesses.
    for name in ["v.txt.tmp", ".v.txt.tmp", "v.tmp"] {
        std::os::unix::fs::symlink("victim.txt", d.join(name)).unwrap();
    }
    let out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        std::fs::read_to_string(d.join("victim.txt")).unwrap(),
        "precious\n"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("v.txt")).unwrap(),
        "#500=50\n"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn vars_keep_their_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir("perm");
    counter(&d);
    let v = d.join("v.txt");
    std::fs::write(&v, "").unwrap();
    std::fs::set_permissions(&v, std::fs::Permissions::from_mode(0o640)).unwrap();
    let out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mode = std::fs::metadata(&v).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640);
    assert_eq!(std::fs::read_to_string(&v).unwrap(), "#500=50\n");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn vars_refuse_what_is_not_a_writable_regular_file() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir("refuse");
    counter(&d);
    let ro = d.join("ro.txt");
    std::fs::write(&ro, "#500=1\n").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    std::fs::create_dir(d.join("folder")).unwrap();
    for (name, why) in [
        ("ro.txt", "read-only"),
        ("folder", "not a regular file"),
        ("/dev/null", "not a regular file"),
    ] {
        let out = gbvm(&["run", "count.gbc", "--vars", name], &d);
        assert_eq!(out.status.code(), Some(1), "{name}");
        assert!(stderr(&out).contains(why), "{name}: {}", stderr(&out));
        assert_eq!(stdout(&out), "", "{name}: nothing may run");
    }
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "#500=1\n");
    std::fs::remove_dir_all(&d).unwrap();
}

/// `gbvm run count.gbc --vars v.txt` once the test's own lock is gone.
///
/// A lock lasts while any copy of its descriptor is open, and a process
/// that another test of this binary forks in the meantime holds a copy
/// until it executes its program: on a loaded machine that can outlast the
/// drop by a moment. So a refusal "in use" is retried for up to 2 s; any
/// other outcome is returned at once.
fn run_once_unlocked(d: &Path) -> Output {
    let mut out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], d);
    for _ in 0..100 {
        if !stderr(&out).contains("in use by another run") {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
        out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], d);
    }
    out
}

#[test]
fn a_vars_file_in_use_by_another_run_is_refused() {
    let d = dir("lock");
    counter(&d);
    let v = d.join("v.txt");
    std::fs::write(&v, "#500=3\n").unwrap();
    // Another run holds the file (as gbvm itself does for a whole run).
    let held = std::fs::File::open(&v).unwrap();
    held.lock().unwrap();
    let out = gbvm(&["run", "count.gbc", "--vars", "v.txt"], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("in use by another run"),
        "{}",
        stderr(&out)
    );
    assert_eq!(std::fs::read_to_string(&v).unwrap(), "#500=3\n");
    drop(held);
    let out = run_once_unlocked(&d);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&v).unwrap(), "#500=50\n");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn machine_values_out_of_range_are_refused_at_their_key() {
    let d = dir("machine");
    std::fs::write(d.join("a.nc"), "G00 X10 Z2\nM30\n").unwrap();
    assert_eq!(gbcc(&["a.nc"], &d).status.code(), Some(0));
    // (file text, where the bad key stands, the key named)
    let cases = [
        (
            "[machine]\nlookahead_blocks = 4294967295\n",
            "2:1",
            "machine.lookahead_blocks",
        ),
        (
            "[machine]\nlookahead_blocks = 0\n",
            "2:1",
            "machine.lookahead_blocks",
        ),
        ("\n[axes.z]\nmin_mm = nan\n", "3:1", "axes.z.min_mm"),
        (
            "[axes.x]\nmin_mm = 5.0\nmax_mm = 1.0\n",
            "2:1",
            "axes.x.min_mm",
        ),
        ("[spindle]\nmin_rpm = -1\n", "2:1", "spindle.min_rpm"),
        ("[spindle]\nencoder_ppr = 0\n", "2:1", "spindle.encoder_ppr"),
        (
            "[spindle]\nstall_timeout_s = inf\n",
            "2:1",
            "spindle.stall_timeout_s",
        ),
        (
            "[cycles]\ng71_retract_mm = -0.5\n",
            "2:1",
            "cycles.g71_retract_mm",
        ),
        // Columns counted by hand: the `z` of `second = { x = 1.0, z = nan }`
        // is the 21st character, the `x` of `g54 = { x = inf }` the 9th.
        (
            "[reference_points]\nsecond = { x = 1.0, z = nan }\n",
            "2:21",
            "reference_points.second.z",
        ),
        ("[coords]\ng54 = { x = inf }\n", "2:9", "coords.g54.x"),
        ("[measure]\ngamma_x_mm = -2\n", "2:1", "measure.gamma_x_mm"),
        (
            "[operator]\nfeed_override_pct = nan\n",
            "2:1",
            "operator.feed_override_pct",
        ),
        (
            "[stroke_check_2]\nplus = { x = 0.0, z = -inf }\n",
            "2:19",
            "stroke_check_2.plus.z",
        ),
        ("[tools]\ncount = 4294967295\n", "2:1", "tools.count"),
        ("[tools]\noffsets = 1000\n", "2:1", "tools.offsets"),
        (
            "[[tools.offset]]\nnumber = 1\n[[tools.offset]]\nnumber = 1\n",
            "4:1",
            "tools.offset[1].number",
        ),
        (
            "[[tools.offset]]\nnumber = 2\nradius = inf\n",
            "3:1",
            "tools.offset[0].radius",
        ),
        ("[run]\nmax_time_s = 0\n", "2:1", "run.max_time_s"),
        ("[host]\ndate = 20001301\n", "2:1", "host.date"),
    ];
    for (text, at, key) in cases {
        std::fs::write(d.join("m.toml"), text).unwrap();
        for out in [
            gbvm(&["run", "a.gbc", "--machine", "m.toml"], &d),
            gbcc(&["a.nc", "--machine", "m.toml"], &d),
        ] {
            assert_eq!(out.status.code(), Some(1), "{text}");
            let err = stderr(&out);
            assert!(
                err.contains(&format!("m.toml:{at}: {key}: ")),
                "{text}: {err}"
            );
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn timed_runs_that_cannot_end_stop_with_e6006() {
    let d = dir("time");
    std::fs::write(d.join("dwell.nc"), "G00 X10 Z2\nG04 X99999999\nM30\n").unwrap();
    std::fs::write(d.join("far.nc"), "G00 X99999999999999999999\nM30\n").unwrap();
    std::fs::write(d.join("a.nc"), "G00 X10 Z2\nG01 Z-5 F100\nM30\n").unwrap();
    std::fs::write(d.join("stuck.toml"), "[operator]\nfeed_override_pct = 0\n").unwrap();
    std::fs::write(d.join("short.toml"), "[run]\nmax_time_s = 0.5\n").unwrap();
    for f in ["dwell.nc", "far.nc", "a.nc"] {
        assert_eq!(gbcc(&[f], &d).status.code(), Some(0), "{f}");
    }
    // (arguments, the line running when the time ran out, seconds allowed)
    let cases: [(&[&str], &str); 5] = [
        (
            &["run", "dwell.gbc", "--stats", "--max-time", "3"],
            "dwell.nc:2:1",
        ),
        (
            &["run", "far.gbc", "--emit", "trace", "--max-time", "2"],
            "far.nc:1:1",
        ),
        (
            &[
                "run",
                "a.gbc",
                "--plot",
                "p.svg",
                "--machine",
                "stuck.toml",
                "--max-time",
                "2",
            ],
            "a.nc:2:1",
        ),
        (
            &[
                "run",
                "a.gbc",
                "--stats",
                "--machine",
                "stuck.toml",
                "--max-time",
                "2",
            ],
            "a.nc:2:1",
        ),
        // The machine key bounds a run without the option.
        (
            &[
                "run",
                "dwell.gbc",
                "--emit",
                "trace",
                "--machine",
                "short.toml",
            ],
            "dwell.nc:2:1",
        ),
    ];
    for (args, at) in cases {
        let out = gbvm(args, &d);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains(&format!("{at}: alarm[E6006]")),
            "{args:?}: {err}"
        );
    }
    // The trace stops at the bound: 2 s at 1 ms is 2000 lines and a header.
    let out = gbvm(
        &["run", "far.gbc", "--emit", "trace", "--max-time", "2"],
        &d,
    );
    let trace = stdout(&out);
    assert_eq!(trace.lines().count(), 2001);
    assert!(
        trace.lines().last().unwrap().starts_with("2.000000,"),
        "{trace}"
    );
    // The canon of a timed run ends with the alarm.
    let out = gbvm(
        &[
            "run",
            "dwell.gbc",
            "--emit",
            "canon",
            "--stats",
            "--max-time",
            "1",
        ],
        &d,
    );
    assert!(stdout(&out).ends_with("ALARM CODE=6006 MSG=\"the run did not end within 1 s of simulated time (run.max_time_s, --max-time)\"\n"), "{}", stdout(&out));
    // A run that ends in time is not touched by the bound.
    let out = gbvm(&["run", "a.gbc", "--stats", "--max-time", "10"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for bad in ["0", "-1", "nan", "inf", "1e300"] {
        let arg = format!("--max-time={bad}");
        let out = gbvm(&["run", "a.gbc", "--stats", &arg], &d);
        // A usage error (README, exit codes).
        assert_eq!(out.status.code(), Some(1), "--max-time {bad}");
    }
    // The value as given, not written out in 301 digits.
    let out = gbvm(&["run", "a.gbc", "--stats", "--max-time", "1e300"], &d);
    let err = stderr(&out);
    assert!(
        err.starts_with("gbvm: error: --max-time 1e300: ") && err.len() < 100,
        "{err}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}
