//! `gbvm run --parts N`: parts in a row, with the part counter and tool
//! life carried on. The canon is counted by hand from the program.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Group 1: tools 101 and 202, two uses each; group 2: tool 303, one
/// minute of cutting.
const MACHINE: &str = "\
[[tool_life.group]]
number = 1
life = 2
unit = \"count\"
tools = [101, 202]
[[tool_life.group]]
number = 2
life = 1
unit = \"minutes\"
tools = [303]
";

/// One part: reads the counter, a tool of group 1, a 22 mm cut.
const PART: &str = "\
#100=#3901
T0199
G00 X40 Z2
G01 Z-20 F300
G00 X60 Z2
M30
";

/// The canon of one part on `tool` (its offset the same number).
fn part_canon(tool: u32) -> String {
    format!(
        "TOOL T={tool} D={tool}\nRAPID X=40 Z=2\nFEED F=300 MODE=MIN\n\
         LINE X=40 Z=-20\nRAPID X=60 Z=2\nSTOP KIND=M30\n"
    )
}

/// The machine file and `program` compiled for it, in a fresh folder.
fn compiled(tag: &str, program: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("gbc-parts-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let machine = dir.join("lathe.toml");
    std::fs::write(&machine, MACHINE).expect("written");
    let src = dir.join("part.nc");
    std::fs::write(&src, program).expect("written");
    let gbc = dir.join("part.gbc");
    let status = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .arg(&src)
        .arg("--machine")
        .arg(&machine)
        .arg("-o")
        .arg(&gbc)
        .status()
        .expect("gbcc runs");
    assert!(status.success());
    (gbc, machine)
}

fn gbvm(gbc: &Path, machine: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .arg("run")
        .arg(gbc)
        .arg("--machine")
        .arg(machine)
        .arg("-q")
        .args(args)
        .output()
        .expect("gbvm runs")
}

#[test]
fn three_parts_wear_out_the_first_tool_and_count_three() {
    let (gbc, machine) = compiled("three", PART);
    let out = gbvm(&gbc, &machine, &["--parts", "3"]);
    assert!(out.status.success(), "{out:?}");
    let canon = String::from_utf8_lossy(&out.stdout);
    // Tool 1 twice, worn out, then tool 2.
    let expected = [part_canon(1), part_canon(1), part_canon(2)].concat();
    assert_eq!(canon, expected);
    let notes = String::from_utf8_lossy(&out.stderr);
    assert!(
        notes.contains("parts machined (#3901) 3, required (#3902) 0"),
        "{notes}"
    );
    assert!(
        notes.contains("tool-life group 1 (uses, life 2): T0101 2 (worn out), T0202 1 (current)"),
        "{notes}"
    );
    assert!(
        notes.contains("tool-life group 2 (minutes, life 1): T0303 0.000"),
        "{notes}"
    );
}

#[test]
fn a_minutes_tool_adds_its_cutting_time_over_the_parts() {
    // 22 mm at 300 mm/min a part: 0.0733 min, 0.293 after four.
    let (gbc, machine) = compiled("minutes", &PART.replace("T0199", "T0299"));
    let out = gbvm(&gbc, &machine, &["--parts", "4", "--emit", "canon"]);
    assert!(out.status.success(), "{out:?}");
    let notes = String::from_utf8_lossy(&out.stderr);
    assert!(notes.contains("T0303 0.293 (current)"), "{notes}");
}

#[test]
fn without_parts_a_run_is_one_part_from_zero() {
    let (gbc, machine) = compiled("one", PART);
    let out = gbvm(&gbc, &machine, &[]);
    assert!(out.status.success(), "{out:?}");
    assert_eq!(String::from_utf8_lossy(&out.stdout), part_canon(1));
    assert!(out.stderr.is_empty(), "{out:?}");
}

#[test]
fn the_stats_count_every_part() {
    let (gbc, machine) = compiled("stats", PART);
    let one = gbvm(&gbc, &machine, &["--stats=json"]);
    let three = gbvm(&gbc, &machine, &["--parts", "3", "--stats=json"]);
    let json =
        |o: &Output| -> serde_json::Value { serde_json::from_slice(&o.stdout).expect("json") };
    let (one, three) = (json(&one), json(&three));
    assert_eq!(one["blocks"].as_u64(), Some(6));
    assert_eq!(three["blocks"].as_u64(), Some(18));
    // The 22 mm cut, three times (summed period by period).
    let cut = three["cut_mm"].as_f64().expect("cut_mm");
    assert!((cut - 66.0).abs() < 1e-6, "{cut}");
}

#[test]
fn zero_parts_is_a_usage_error() {
    let (gbc, machine) = compiled("zero", PART);
    let out = gbvm(&gbc, &machine, &["--parts", "0"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--parts"));
}
