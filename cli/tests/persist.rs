//! `gbvm run --vars FILE` under a crash: a run killed at any instant leaves
//! either the old or the new values in FILE, never a torn file.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gbc-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every line `#n=value`, #500 an integer counter and #501 the marker the
/// program wrote first; a torn file would lose a line or a digit.
fn check(text: &str) -> f64 {
    let mut counter = None;
    let mut marker = None;
    for line in text.lines() {
        let (n, v) = line
            .strip_prefix('#')
            .and_then(|l| l.split_once('='))
            .expect("a #n=value line");
        let v: f64 = v.parse().expect("a number");
        match n {
            "500" => counter = Some(v),
            "501" => marker = Some(v),
            other => panic!("unexpected variable #{other}"),
        }
    }
    // A run killed between its first two stores leaves #501 alone (the
    // program writes it before #500): a whole state, counted as 0.
    let c = counter.unwrap_or(0.0);
    assert_eq!(
        marker,
        Some(12345.678),
        "the marker line is damaged: {text:?}"
    );
    assert!(text.ends_with('\n'), "the file is cut short: {text:?}");
    c
}

#[test]
fn killed_runs_never_leave_a_torn_file() {
    let dir = temp_dir("persist");
    let src = dir.join("count.nc");
    // The VM stores whenever a block changes #500–#999; the file is
    // rewritten at most once per `cli::vars::SAVE_PERIOD` (100 ms).
    std::fs::write(
        &src,
        "#501=12345.678\n#500=0\nWHILE[#500LT1000000]DO1\n#500=#500+1\nEND1\nM30\n",
    )
    .unwrap();
    let gbc = dir.join("count.gbc");
    let status = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .arg(&src)
        .arg("-o")
        .arg(&gbc)
        .status()
        .unwrap();
    assert!(status.success());
    let vars = dir.join("vars.txt");
    let mut last = 0.0;
    let mut seen_progress = false;
    for i in 0..12u64 {
        let mut child = Command::new(env!("CARGO_BIN_EXE_gbvm"))
            .args(["run"])
            .arg(&gbc)
            .arg("--vars")
            .arg(&vars)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(20 + 40 * i));
        child.kill().unwrap();
        child.wait().unwrap();
        let Ok(text) = std::fs::read_to_string(&vars) else {
            continue; // killed before the first store
        };
        if text.is_empty() {
            // gbvm creates a missing FILE empty (all vacant) to lock it:
            // killed before the first store, it still holds that state.
            continue;
        }
        let c = check(&text);
        // Each run starts its count again from 0: only a whole count is valid.
        assert!(c >= 0.0 && c.fract() == 0.0, "#500 = {c}");
        seen_progress |= c > 0.0;
        last = c;
    }
    assert!(
        seen_progress,
        "no run got far enough to store anything (last {last})"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// G31 leaves its end point in #995/#996 (no skip signal in a plain run:
/// the move ends at its target, X10 Z-5), and those are persistent: they
/// reach the variables file as any store to #500–#999 does.
#[test]
fn a_skip_position_reaches_the_variables_file() {
    let dir = temp_dir("skip");
    let src = dir.join("skip.nc");
    std::fs::write(&src, "G98 G00 X20 Z2\nG31 X10 Z-5 F100\nM30\n").unwrap();
    let gbc = dir.join("skip.gbc");
    let vars = dir.join("skip.vars");
    let _ = std::fs::remove_file(&vars);
    let ok = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args([
            src.as_os_str(),
            "-q".as_ref(),
            "-o".as_ref(),
            gbc.as_os_str(),
        ])
        .status()
        .unwrap();
    assert!(ok.success());
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .arg("run")
        .arg(&gbc)
        .arg("--vars")
        .arg(&vars)
        .args(["--emit", "canon", "-q"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&vars).expect("the variables file");
    assert!(text.lines().any(|l| l == "#995=10"), "{text:?}");
    assert!(text.lines().any(|l| l == "#996=-5"), "{text:?}");
}
