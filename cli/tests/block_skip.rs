//! `gbvm run --block-skip on|off`: one `.gbc` runs with the `/` blocks
//! skipped or not; the machine file's `operator.block_skip` is the default.

use std::path::Path;
use std::process::Command;

/// `#1 = 10`; the `/` blocks move to X20, set #1 = 99 and (`/2`) feed to
/// Z-5; the last move goes to X#1.
const PART: &str = "O0001\n#1=10\nG00 X40 Z2\n/G00 X20\n/#1=99\n/2 G01 Z-5 F100\nG00 X#1\nM30\n";

/// Hand check: the three `/` blocks skipped, #1 stays 10.
const ON: &str = "RAPID X=40 Z=2\nRAPID X=10 Z=2\nSTOP KIND=M30\n";

/// Hand check: X20, #1 = 99, the feed at F100 mm/min (G98 at power-on)
/// to Z-5, then X99.
const OFF: &str = "RAPID X=40 Z=2\nRAPID X=20 Z=2\nFEED F=100 MODE=MIN\nLINE X=20 Z=-5\n\
                   RAPID X=99 Z=-5\nSTOP KIND=M30\n";

fn gbvm(dir: &Path, args: &[&str]) -> (String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("gbvm runs");
    let code = out.status.code().unwrap_or(-1);
    (String::from_utf8_lossy(&out.stdout).into_owned(), code)
}

#[test]
fn one_module_runs_with_the_switch_on_and_off() {
    let dir = tempfile::tempdir().expect("a scratch directory");
    let d = dir.path();
    std::fs::write(d.join("part.nc"), PART).expect("write part.nc");
    let st = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(["part.nc", "-o", "part.gbc"])
        .current_dir(d)
        .status()
        .expect("gbcc runs");
    assert!(st.success());
    // The reference machine has every switch on.
    assert_eq!(gbvm(d, &["run", "part.gbc"]), (ON.to_string(), 0));
    assert_eq!(
        gbvm(d, &["run", "part.gbc", "--block-skip", "on"]),
        (ON.to_string(), 0)
    );
    assert_eq!(
        gbvm(d, &["run", "part.gbc", "--block-skip", "off"]),
        (OFF.to_string(), 0)
    );
    // A machine file with the switches off sets the default; the option
    // overrides it. (operator.block_skip is no compile-time key: the
    // module compiled for the reference machine runs on this one.)
    let toml = "[operator]\nblock_skip = [false, false, false, false, false, false, false, false, false]\n";
    std::fs::write(d.join("off.toml"), toml).expect("write off.toml");
    assert_eq!(
        gbvm(d, &["run", "part.gbc", "--machine", "off.toml"]),
        (OFF.to_string(), 0)
    );
    assert_eq!(
        gbvm(
            d,
            &[
                "run",
                "part.gbc",
                "--machine",
                "off.toml",
                "--block-skip=on"
            ]
        ),
        (ON.to_string(), 0)
    );
    // The timed run (trace) reads the switch the same way: its last
    // period stands on X99 (a diameter) with the switch off.
    let (trace, code) = gbvm(
        d,
        &["run", "part.gbc", "--emit", "trace", "--block-skip", "off"],
    );
    assert_eq!(code, 0);
    let last = trace.lines().last().unwrap_or_default();
    assert!(last.split(',').nth(1) == Some("99.000000"), "{last}");
    // Anything but on or off is a usage error.
    assert_eq!(gbvm(d, &["run", "part.gbc", "--block-skip", "2"]).1, 1);
}
