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
