//! One program has one outcome whatever `gbvm run` is asked to draw: a
//! plain canon run, `--plot`, `--stats` and `--emit trace` give the same
//! exit code and the same alarm, the alarm once, on stderr once, and (where
//! the canon is printed) as its last line.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-outcome-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn tool(bin: &str, args: &[&str], cwd: &Path) -> Output {
    Command::new(bin)
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Compiles `src` and runs it every way; checks that each run ends with
/// exit `code` and, when `alarm` is given, with that alarm printed once.
fn same_outcome(tag: &str, src: &str, code: i32, alarm: Option<&str>) {
    let d = dir(tag);
    std::fs::write(d.join("p.nc"), src).unwrap();
    let out = tool(env!("CARGO_BIN_EXE_gbcc"), &["p.nc", "-q"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let runs: [&[&str]; 5] = [
        &["run", "p.gbc", "--emit", "canon"],
        &["run", "p.gbc", "--plot", "p.svg"],
        &["run", "p.gbc", "--stats"],
        &["run", "p.gbc", "--emit", "trace"],
        &["run", "p.gbc", "--stats=json", "--plot", "p.svg"],
    ];
    for args in runs {
        let out = tool(env!("CARGO_BIN_EXE_gbvm"), args, &d);
        let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
        assert_eq!(
            out.status.code(),
            Some(code),
            "{args:?}\n{stdout}\n{stderr}"
        );
        let Some(alarm) = alarm else { continue };
        let tag = format!("alarm[{alarm}]");
        assert_eq!(stderr.matches(&tag).count(), 1, "{args:?}: {stderr}");
        let canon_lines: Vec<&str> = stdout
            .lines()
            .filter(|l| l.starts_with(char::is_alphabetic) && l.contains('='))
            .collect();
        let alarms = canon_lines
            .iter()
            .filter(|l| l.starts_with("ALARM"))
            .count();
        if canon_lines.is_empty() {
            continue; // trace and statistics only
        }
        assert_eq!(alarms, 1, "{args:?}:\n{stdout}");
        let last = canon_lines.last().copied().unwrap_or_default();
        let number = alarm.trim_start_matches('E');
        assert!(
            last.starts_with(&format!("ALARM CODE={number}")),
            "{args:?}: the last line is {last:?}\n{stdout}"
        );
    }
}

#[test]
fn a_feed_move_without_f_alarms_in_every_run() {
    // `G01 X10` with no F in force: E7001 at the move (dialect.md §4.1).
    same_outcome("f0", "O0001\nG01 X10\nM30\n", 2, Some("E7001"));
}

#[test]
fn a_line_across_the_g22_area_alarms_in_every_run() {
    // From X50 Z10 to X-10 Z-30: x = 50 − 60t, z = 10 − 40t meets
    // Z−15 at t = 0.625, x = 12.5, inside the box X 0…20, Z −20…−10,
    // while both end points lie outside it.
    let src = "O0002\nG00 X50 Z10\nG22 X20. Z-10. I0 K-20.\nG98 G01 X-10 Z-30 F1000\nM30\n";
    same_outcome("g22-path", src, 2, Some("E7002"));
}

#[test]
fn a_move_ending_in_the_g22_area_alarms_once() {
    // With --plot the alarm used to be printed twice.
    let src = "O0003\nG00 X50 Z10\nG22 X20. Z-10. I0 K-20.\nG98 G01 X10 Z-15 F1000\nM30\n";
    same_outcome("g22-end", src, 2, Some("E7002"));
}

#[test]
fn a_clean_program_ends_in_every_run() {
    let src = "O0004\nG98 G00 X40 Z2\nG01 Z-20 F600\nG00 X60 Z10\nM30\n";
    same_outcome("clean", src, 0, None);
}
