//! The example machine file of the user's guide (docs/machine.md) loads,
//! and a program runs on it within its limits.

use std::path::PathBuf;
use std::process::{Command, Output};

fn machine() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/gsk980tdi-slant-bed.toml")
}

fn run(bin: &str, args: &[&str], cwd: &std::path::Path) -> Output {
    Command::new(bin)
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Roughing and finishing a Ø24 × 30 spigot with a taper, in G54.
const PART: &str = "O0100 (SPIGOT)\nG54 G99 T0101\nG50 S3000\nG96 S180 M03\nG00 X42 Z2\nG71 U1.5 R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\nN10 G00 X20\nG01 Z0 F0.1\nX24 Z-2\nZ-30\nX40 Z-40\nN20 X42\nG00 X100 Z50 T0202\nG70 P10 Q20\nG00 X100 Z50\nM30\n";

#[test]
fn the_example_machine_loads_and_runs_a_part() {
    let m = machine();
    let loaded = cli::load_machine(Some(&m));
    assert!(loaded.is_ok(), "{:?}", loaded.err());
    let d = std::env::temp_dir().join(format!("gbc-example-machine-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("part.nc"), PART).unwrap();
    let m = m.to_string_lossy().into_owned();
    let out = run(
        env!("CARGO_BIN_EXE_gbcc"),
        &["part.nc", "--machine", &m],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // Through the runtime, soft limits on: no E7002, two tools.
    let out = run(
        env!("CARGO_BIN_EXE_gbvm"),
        &["run", "part.gbc", "--machine", &m, "--stats"],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stats = text(&out.stdout);
    assert!(
        stats.contains("  T01: ") && stats.contains("  T02: "),
        "{stats}"
    );
    // The reference machine is another machine: the module is refused.
    let out = run(env!("CARGO_BIN_EXE_gbvm"), &["run", "part.gbc"], &d);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
}

#[test]
fn the_example_machine_has_eight_stations() {
    // tools.count = 8: T0909 is outside the turret (E7004 at compile time).
    let d = std::env::temp_dir().join(format!("gbc-example-t9-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("t9.nc"), "T0909\nM30\n").unwrap();
    let m = machine().to_string_lossy().into_owned();
    let out = run(env!("CARGO_BIN_EXE_gbcc"), &["t9.nc", "--machine", &m], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("E7004"), "{}", text(&out.stderr));
}

/// Finishing a profile under nose-radius compensation near the − end of
/// X's travel: G54 puts work X0 at machine X−320, T0202's offset (X−1.8)
/// the slide 1.8 lower, so the travel (−330) ends at work X−8.2. The
/// profile starts at X−1.6, inside; its corner arcs print a block late
/// (compensation looks ahead) and inside G70, and are checked from where
/// the tool was printed, not from the programmed point.
const FINISH: &str = "G54 G99 T0202\nG96 S180 M03\nG00 X40 Z2\nG70 P10 Q20\nG00 X100 Z50\nM30\nN10 G00 G42 X-1.6 Z2\nG01 Z0 F0.1\nX20\nX21.6 Z-0.4\nZ-24\nG02 X24 Z-25.2 R1.2\nG01 X30\nG03 X33 Z-26.7 R1.5\nG01 Z-52\nX40\nN20 G00 G40 Z2\n";

#[test]
fn a_compensated_profile_inside_the_travel_passes_the_soft_limits() {
    let d = std::env::temp_dir().join(format!("gbc-example-finish-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("finish.nc"), FINISH).unwrap();
    let m = machine().to_string_lossy().into_owned();
    let out = run(
        env!("CARGO_BIN_EXE_gbcc"),
        &["finish.nc", "--machine", &m],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(!text(&out.stderr).contains("W124"), "{}", text(&out.stderr));
    let out = run(
        env!("CARGO_BIN_EXE_gbvm"),
        &["run", "finish.gbc", "--machine", &m, "--stats"],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
}

#[test]
fn a_move_past_the_travel_ends_the_canon_before_it() {
    // Z−70 in G54 with T0101 (Z+1.2) puts the slide at machine
    // Z −245 − 70 + 1.2 = −313.8, past Z's end at −310; X40 at
    // −320 + 40 − 2.5 = −282.5.
    let d = std::env::temp_dir().join(format!("gbc-example-travel-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let prog = "G54 G99 T0101\nG00 X40 Z2\nG01 Z-70 F0.2\nG00 X100\nM30\n";
    std::fs::write(d.join("travel.nc"), prog).unwrap();
    let m = machine().to_string_lossy().into_owned();
    let out = run(
        env!("CARGO_BIN_EXE_gbcc"),
        &["travel.nc", "--machine", &m],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("travel.nc:3:1: warning[W124]"),
        "{}",
        text(&out.stderr)
    );
    // A timed run prints the same canon as a plain one.
    for timed in [false, true] {
        let mut args = vec!["run", "travel.gbc", "--machine", &m, "--emit", "canon"];
        if timed {
            args.push("--stats");
        }
        let out = run(env!("CARGO_BIN_EXE_gbvm"), &args, &d);
        assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
        let canon = text(&out.stdout);
        let lines: Vec<&str> = canon.lines().collect();
        assert_eq!(lines.len(), 3, "{canon}");
        assert_eq!(lines[1], "RAPID X=40 Z=2");
        assert_eq!(
            lines[2],
            "ALARM CODE=7002 MSG=\"the move takes the slide to machine X-282.5 Z-313.8, past Z's soft limit -310\""
        );
        assert!(text(&out.stderr).contains("travel.nc:3:1: alarm[E7002]"));
    }
}

/// `PART` on a lathe programmed on the radius: every X value halved (the
/// G71 allowance U0.4 too; U1.5 is a depth of cut, a radius already).
const PART_ON_RADIUS: &str = "O0100 (SPIGOT)\nG54 G99 T0101\nG50 S3000\nG96 S180 M03\nG00 X21 Z2\nG71 U1.5 R0.5\nG71 P10 Q20 U0.2 W0.1 F0.25\nN10 G00 X10\nG01 Z0 F0.1\nX12 Z-2\nZ-30\nX20 Z-40\nN20 X21\nG00 X50 Z50 T0202\nG70 P10 Q20\nG00 X50 Z50\nM30\n";

#[test]
fn a_lathe_programmed_on_the_radius_cuts_the_same_part() {
    let d = std::env::temp_dir().join(format!("gbc-radius-machine-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("part.nc"), PART).unwrap();
    std::fs::write(d.join("radius.nc"), PART_ON_RADIUS).unwrap();
    std::fs::write(d.join("radius.toml"), "[axes.x]\ndiameter = false\n").unwrap();
    let canon = |args: &[&str]| {
        let out = run(env!("CARGO_BIN_EXE_gbvm"), args, &d);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        text(&out.stdout)
    };
    for (src, machine) in [("part.nc", None), ("radius.nc", Some("radius.toml"))] {
        let mut args = vec![src];
        args.extend(machine.iter().flat_map(|m| ["--machine", m]));
        let out = run(env!("CARGO_BIN_EXE_gbcc"), &args, &d);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    }
    // The canon prints diameters either way: the same moves.
    let diameter = canon(&["run", "part.gbc", "--emit", "canon"]);
    let radius = canon(&[
        "run",
        "radius.gbc",
        "--emit",
        "canon",
        "--machine",
        "radius.toml",
    ]);
    assert!(diameter.contains("LINE X=24 Z=-30"), "{diameter}");
    assert_eq!(radius, diameter);
    // Compiled for the radius, the module runs on no diameter machine.
    let out = run(env!("CARGO_BIN_EXE_gbvm"), &["run", "radius.gbc"], &d);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("x_diameter"),
        "{}",
        text(&out.stderr)
    );
    std::fs::remove_dir_all(&d).ok();
}
