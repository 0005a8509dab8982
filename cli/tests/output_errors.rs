//! `gbvm` when its output cannot be written: a full device or a closed pipe
//! never panics (exit 101) and never passes for success (exit 0); the
//! exit code is 3 (README) and the error is named on stderr.

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The code `gbvm` exits with when its output failed (README).
const EXIT_OUTPUT: i32 = 3;

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-outerr-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A module whose canon and listing are each well over a pipe's 64 KiB
/// buffer, so a closed pipe is certain to fail a write.
fn big_module(d: &Path) -> PathBuf {
    let mut src = String::new();
    for i in 0..6000 {
        src.push_str(&format!("G01 X{} Z-{} F4000\n", i % 50, i % 70));
    }
    src.push_str("M30\n");
    std::fs::write(d.join("big.nc"), src).unwrap();
    let st = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(["big.nc", "-o", "big.gbc"])
        .current_dir(d)
        .status()
        .unwrap();
    assert!(st.success());
    d.join("big.gbc")
}

fn dev_full() -> Option<File> {
    // Linux has it; elsewhere these cases are skipped.
    std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .ok()
}

fn gbvm_to_full(args: &[&str], module: &Path) -> Option<Output> {
    let full = dev_full()?;
    Some(
        Command::new(env!("CARGO_BIN_EXE_gbvm"))
            .args(args)
            .arg(module)
            .stdout(full)
            .output()
            .unwrap(),
    )
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_full_device_is_an_error_for_every_command() {
    let d = dir("full");
    let m = big_module(&d);
    for args in [
        &["run"][..],
        &["run", "--emit", "trace"],
        &["run", "--stats"],
        &["disasm"],
        &["verify"],
    ] {
        let Some(out) = gbvm_to_full(args, &m) else {
            return;
        };
        assert_eq!(out.status.code(), Some(EXIT_OUTPUT), "gbvm {args:?}");
        let err = stderr(&out);
        assert!(
            err.contains("gbvm: error: standard output:") && !err.contains("panicked"),
            "gbvm {args:?}: {err}"
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// `check`'s line and `run`'s plot are outputs too: exit 3 when they
/// cannot be written.
#[test]
fn the_check_line_and_the_plot_on_a_full_device() {
    let d = dir("fullplot");
    std::fs::write(d.join("p.nc"), "G98 G00 X20 Z2\nG01 Z-10 F100\nM30\n").unwrap();
    let st = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(["p.nc", "-o", "p.gbc"])
        .current_dir(&d)
        .status()
        .unwrap();
    assert!(st.success());
    let Some(out) = gbvm_to_full(&["check"], &d.join("p.gbc")) else {
        return;
    };
    assert_eq!(out.status.code(), Some(EXIT_OUTPUT), "{}", stderr(&out));
    assert!(stderr(&out).contains("gbvm: error: standard output:"));
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["run", "p.gbc", "--plot", "/dev/full"])
        .current_dir(&d)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(EXIT_OUTPUT), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("gbvm: error: /dev/full:"),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_full_stderr_does_not_panic() {
    let d = dir("fullerr");
    let Some(full) = dev_full() else { return };
    // A missing file: the error message itself cannot be written.
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["verify", "no-such.gbc"])
        .current_dir(&d)
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_closed_pipe_ends_the_command_without_a_panic_or_success() {
    let d = dir("pipe");
    let m = big_module(&d);
    for args in [&["run"][..], &["run", "--emit", "trace"], &["disasm"]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_gbvm"))
            .args(args)
            .arg(&m)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Read a little, as `| head -c 10` would, then hang up.
        let mut first = [0u8; 10];
        let mut pipe = child.stdout.take().unwrap();
        pipe.read_exact(&mut first).unwrap();
        drop(pipe);
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(EXIT_OUTPUT), "gbvm {args:?}");
        // The reader chose to stop: nothing to report.
        assert_eq!(stderr(&out), "", "gbvm {args:?}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}
