//! `gbvm` against crafted `.gbc` files (issue 20): a module that loops
//! without a block must still end with the budget alarm, and text from a
//! module's tables must not reach the terminal raw.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-crafted-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a tool, killing it (and failing the test) if it has not ended
/// after a generous limit: the point of these tests is that it ends.
fn run_bounded(exe: &str, args: &[&str], cwd: &Path) -> Output {
    let mut child = Command::new(exe)
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("{exe} {args:?} did not end within 60 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    run_bounded(env!("CARGO_BIN_EXE_gbcc"), args, cwd)
}

fn gbvm(args: &[&str], cwd: &Path) -> Output {
    run_bounded(env!("CARGO_BIN_EXE_gbvm"), args, cwd)
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Recomputes the CRC32 trailer after a forged change.
fn reseal(bytes: &mut [u8]) {
    let body = bytes.len() - 4;
    let crc = crc32fast::hash(&bytes[..body]);
    bytes[body..].copy_from_slice(&crc.to_le_bytes());
}

#[test]
fn a_crafted_conditional_loop_ends_with_the_budget_alarm() {
    let d = dir("loop");
    std::fs::write(d.join("small.nc"), "#1=5\nM30\n").unwrap();
    let out = gbcc(&["small.nc", "-o", "small.gbc"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let mut bytes = std::fs::read(d.join("small.gbc")).unwrap();
    // Byte 11 is the first opcode (magic 4, version 2, code tag 1, code
    // length 4): `loadk r0, k0`. Flipping bit 5 makes it `jumpifnot r0,
    // @0`, a loop on itself that r0 (vacant) never leaves.
    assert_eq!(bytes[11..17], [0x01, 0, 0, 0, 0, 0], "loadk r0, k0");
    bytes[11] ^= 0x20;
    reseal(&mut bytes);
    std::fs::write(d.join("loop.gbc"), &bytes).unwrap();

    let verify = gbvm(&["verify", "loop.gbc"], &d);
    assert_eq!(verify.status.code(), Some(0), "{}", text(&verify.stderr));
    let listing = text(&gbvm(&["disasm", "loop.gbc"], &d).stdout);
    assert!(listing.contains("jumpifnot r0, @0000"), "{listing}");

    for emit in [&["--emit", "canon"][..], &["--stats"][..]] {
        let mut args = vec!["run", "loop.gbc", "--max-blocks", "1"];
        args.extend_from_slice(emit);
        let run = gbvm(&args, &d);
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        let err = text(&run.stderr);
        assert!(
            err.contains("small.nc:1:1: alarm[E6005]: "),
            "{args:?}: {err}"
        );
    }
    let run = gbvm(&["run", "loop.gbc", "--max-blocks", "1"], &d);
    assert!(text(&run.stdout).starts_with("ALARM CODE=6005 "));
}

#[test]
fn text_from_a_crafted_module_reaches_stderr_sanitised() {
    let d = dir("text");
    std::fs::write(d.join("part.nc"), "G00 X1\n#3000=1 (BAD)\nM30\n").unwrap();
    let out = gbcc(&["part.nc", "-o", "part.gbc"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let bytes = std::fs::read(d.join("part.gbc")).unwrap();
    let mut m = isa::Module::from_bytes(&bytes).unwrap();
    assert_eq!(m.strings, ["BAD"]);
    // A file name and a message that try to draw on the terminal and to
    // pass off a line of their own as a diagnostic.
    m.files[0].name = "x.nc:9:9: error[E1001]: fake\n\x1b[31mred".into();
    m.strings[0] = "BAD\x1b]0;title\x07\nfake.nc:1:1: error[E2012]: \"forged\"".into();
    std::fs::write(d.join("evil.gbc"), m.to_bytes()).unwrap();

    // Each character outside printable ASCII, and `"`, becomes `?`
    // (canon.md's rule for strings): one line, no escape byte.
    let header = "x.nc:9:9: error[E1001]: fake??[31mred:2:1: alarm[3001]: \
                  BAD?]0;title??fake.nc:1:1: error[E2012]: ?forged?\n";
    for extra in [&[][..], &["--stats"][..]] {
        let mut args = vec!["run", "evil.gbc"];
        args.extend_from_slice(extra);
        let run = gbvm(&args, &d);
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        let err = text(&run.stderr);
        let last = err.lines().last().unwrap_or_default();
        assert_eq!(format!("{last}\n"), header, "{args:?}: {err:?}");
        assert!(!err.contains(['\x1b', '\x07']), "{args:?}: {err:?}");
    }
    // The canon's MSG already follows the rule.
    let run = gbvm(&["run", "evil.gbc"], &d);
    assert_eq!(
        text(&run.stdout),
        "RAPID X=1 Z=0\nALARM CODE=3001 MSG=\"BAD?]0;title??fake.nc:1:1: error[E2012]: ?forged?\"\n"
    );

    // The listing escapes control characters in the file name; no line
    // of it starts with the forged text.
    let listing = text(&gbvm(&["disasm", "evil.gbc"], &d).stdout);
    assert!(!listing.contains(['\x1b', '\x07']), "{listing}");
    assert!(
        listing.contains("; file 0: x.nc:9:9: error[E1001]: fake\\n\\u{1b}[31mred (crc32"),
        "{listing}"
    );
    assert!(
        listing
            .lines()
            .all(|l| !l.starts_with("fake") && !l.starts_with("\\")),
        "{listing}"
    );
}
