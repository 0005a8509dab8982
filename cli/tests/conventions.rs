//! gcc's driver conventions in gbcc and gbvm: `-` for standard input and
//! output, warnings by name, dependency files, the error cap and summary,
//! colour, exit codes, outputs that cannot be written, the source that an
//! output must not replace.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-conv-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn cmd(bin: &str, args: &[&str], cwd: &Path) -> Command {
    let mut c = Command::new(bin);
    c.args(args).current_dir(cwd).env_remove("NO_COLOR");
    c
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    cmd(env!("CARGO_BIN_EXE_gbcc"), args, cwd).output().unwrap()
}

fn gbvm(args: &[&str], cwd: &Path) -> Output {
    cmd(env!("CARGO_BIN_EXE_gbvm"), args, cwd).output().unwrap()
}

/// Runs with `input` on standard input.
fn piped(bin: &str, args: &[&str], cwd: &Path, input: &[u8]) -> Output {
    let mut child = cmd(bin, args, cwd)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

const PART: &str = "G00 X10 Z2\nG01 Z-5 F100\nM30\n";
const CANON: &str = "RAPID X=10 Z=2\nFEED F=100 MODE=MIN\nLINE X=10 Z=-5\nSTOP KIND=M30\n";

#[test]
fn dash_is_standard_input_and_output() {
    let d = dir("dash");
    let out = piped(
        env!("CARGO_BIN_EXE_gbcc"),
        &["-", "-o", "x.gbc"],
        &d,
        PART.as_bytes(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let module = std::fs::read(d.join("x.gbc")).unwrap();
    // -o - writes the module itself to standard output, and no file "-".
    std::fs::write(d.join("part.nc"), PART).unwrap();
    let out = gbcc(&["part.nc", "-o", "-"], &d);
    assert_eq!(out.status.code(), Some(0));
    assert!(out.stdout.starts_with(b"GBC\0"));
    assert!(!d.join("-").exists());
    // Same program, same module, whichever way it came in (the name of
    // the source differs: compare the run instead).
    let run = piped(env!("CARGO_BIN_EXE_gbvm"), &["run", "-"], &d, &out.stdout);
    assert_eq!(text(&run.stdout), CANON, "{}", text(&run.stderr));
    let run = piped(env!("CARGO_BIN_EXE_gbvm"), &["run", "-"], &d, &module);
    assert_eq!(text(&run.stdout), CANON);
    // -S -o - prints the listing; -E -o FILE writes the expansion there.
    let s = gbcc(&["part.nc", "-S", "-o", "-"], &d);
    assert!(
        text(&s.stdout).contains("move b0 (G0 X10 Z2)"),
        "{}",
        text(&s.stdout)
    );
    let e = gbcc(&["part.nc", "-E", "-o", "part.e.nc"], &d);
    assert_eq!(e.status.code(), Some(0));
    assert!(e.stdout.is_empty());
    let expanded = std::fs::read_to_string(d.join("part.e.nc")).unwrap();
    assert!(expanded.starts_with("G00 X10 Z2"), "{expanded}");
    // A diagnostic from standard input names it <stdin>.
    let bad = piped(
        env!("CARGO_BIN_EXE_gbcc"),
        &["-", "-fsyntax-only"],
        &d,
        b"G00 X1.2.3\n",
    );
    assert!(
        text(&bad.stderr).starts_with("<stdin>:1:6: error[E1007]"),
        "{}",
        text(&bad.stderr)
    );
}

#[test]
fn warnings_by_name() {
    let d = dir("warn");
    // M51 is listed, M77 is not (W113); no M30 (W101).
    std::fs::write(d.join("w.nc"), "G00 X10\nM77\n").unwrap();
    let all = text(&gbcc(&["w.nc", "-o", "w.gbc"], &d).stderr);
    assert!(
        all.contains("warning[W113]") && all.contains("warning[W101]"),
        "{all}"
    );
    assert!(all.ends_with("gbcc: 0 errors, 2 warnings\n"), "{all}");
    let out = gbcc(&["w.nc", "-Wno-W113", "-o", "w.gbc"], &d);
    let err = text(&out.stderr);
    assert!(
        !err.contains("W113") && err.contains("warning[W101]"),
        "{err}"
    );
    // -Werror=W101 fails the build and says which warning did it.
    let out = gbcc(&["w.nc", "-Werror=W101", "-o", "w.gbc"], &d);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(
        err.contains("error[W101]: ") && err.contains("[-Werror=W101]"),
        "{err}"
    );
    assert!(err.contains("warning[W113]"), "{err}");
    assert!(
        err.ends_with("gbcc: 1 error, 1 warning (1 warning treated as error by -Werror)\n"),
        "{err}"
    );
    // -Wall, -Wextra and -w are accepted; -w silences everything.
    assert_eq!(
        gbcc(&["w.nc", "-Wall", "-Wextra", "-o", "w.gbc"], &d)
            .status
            .code(),
        Some(0)
    );
    let quiet = gbcc(&["w.nc", "-w", "-Werror", "-o", "w.gbc"], &d);
    assert_eq!(quiet.status.code(), Some(0));
    assert!(quiet.stderr.is_empty(), "{}", text(&quiet.stderr));
    // An unknown -W is a usage error that says what exists.
    for bad in ["-Wfoo", "-Wno-W999", "-Werror=E1001"] {
        let out = gbcc(&["w.nc", bad], &d);
        assert_eq!(out.status.code(), Some(1), "{bad}");
        assert!(
            text(&out.stderr).contains(&format!("unknown warning option '{bad}'")),
            "{bad}"
        );
    }
}

/// A machine file that lists the machine's own M codes: no W113 for them.
#[test]
fn machine_m_codes_are_not_w113() {
    let d = dir("mcodes");
    std::fs::write(d.join("m.nc"), "M77\nM78\nM30\n").unwrap();
    std::fs::write(d.join("lathe.toml"), "[plc]\nm_codes = [77]\n").unwrap();
    let out = gbcc(&["m.nc", "--machine", "lathe.toml", "-o", "m.gbc"], &d);
    let err = text(&out.stderr);
    assert!(!err.contains("M77") && err.contains("M78 is not"), "{err}");
}

#[test]
fn make_dependencies_name_the_library_programs() {
    let d = dir("deps");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    std::fs::write(d.join("lib/O1234.nc"), "O1234\nG00 U1\nM99\n").unwrap();
    std::fs::write(d.join("lib/O5678.nc"), "O5678\nM99\n").unwrap();
    std::fs::write(d.join("main.nc"), "M98 P1234\nM30\n").unwrap();
    let out = gbcc(&["main.nc", "-I", "lib", "-MD"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // The rule beside the output, naming the one library program used.
    let rule = std::fs::read_to_string(d.join("main.d")).unwrap();
    assert_eq!(rule, "main.gbc: main.nc lib/O1234.nc\n");
    let out = gbcc(
        &["main.nc", "-I", "lib", "-o", "out.gbc", "-MF", "deps.mk"],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let rule = std::fs::read_to_string(d.join("deps.mk")).unwrap();
    assert_eq!(rule, "out.gbc: main.nc lib/O1234.nc\n");
}

/// `-MF`, the default dependency name and `-o` never replace a file the
/// compile read (by any name, link or hard link), nor the dependency file
/// the output; a refused compile writes nothing and exits 1.
#[test]
fn a_dependency_file_replaces_nothing_the_compile_read() {
    let d = dir("depguard");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    let lib = "O1234\nG00 U1\nM99\n";
    std::fs::write(d.join("lib/O1234.nc"), lib).unwrap();
    let main = "M98 P1234\nM30\n";
    for name in ["main.nc", "part.d"] {
        std::fs::write(d.join(name), main).unwrap();
    }
    std::fs::write(d.join("lathe.toml"), "").unwrap();
    std::os::unix::fs::symlink("main.nc", d.join("link.d")).unwrap();
    std::fs::hard_link(d.join("main.nc"), d.join("hard.d")).unwrap();
    // A link to the output, which is not there yet.
    std::os::unix::fs::symlink("out.gbc", d.join("ahead.d")).unwrap();
    let with_lib = |extra: &[&str]| {
        let mut args = vec!["main.nc", "-I", "lib", "-o", "out.gbc"];
        args.extend_from_slice(extra);
        gbcc(&args, &d)
    };
    let cases: [(Output, &str); 9] = [
        (with_lib(&["-MF", "main.nc"]), "is the input main.nc"),
        (
            with_lib(&["-MF", "./lib/../main.nc"]),
            "is the input main.nc",
        ),
        (with_lib(&["-MF", "link.d"]), "is the input main.nc"),
        (with_lib(&["-MF", "hard.d"]), "is the input main.nc"),
        (with_lib(&["-MFlib/O1234.nc"]), "is the library program"),
        (
            with_lib(&["-MD", "-MF", "out.gbc"]),
            "is the output out.gbc",
        ),
        (with_lib(&["-MF", "ahead.d"]), "is the output out.gbc"),
        (
            with_lib(&["--machine", "lathe.toml", "-MF", "lathe.toml"]),
            "is the machine file lathe.toml",
        ),
        // The default name, the output's stem with `.d`, is the source.
        (
            gbcc(&["part.d", "-I", "lib", "-o", "part.gbc", "-MD"], &d),
            "is the input part.d",
        ),
    ];
    for (out, why) in cases {
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains(why) && err.contains("refusing to overwrite"),
            "{why}: {err}"
        );
        assert!(
            !d.join("out.gbc").exists() && !d.join("part.gbc").exists(),
            "{err}"
        );
    }
    for name in ["main.nc", "part.d", "link.d", "hard.d"] {
        assert_eq!(
            std::fs::read_to_string(d.join(name)).unwrap(),
            main,
            "{name}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(d.join("lib/O1234.nc")).unwrap(),
        lib
    );
    assert_eq!(std::fs::read_to_string(d.join("lathe.toml")).unwrap(), "");
    // `-o` may not replace a library program either.
    let out = gbcc(&["main.nc", "-I", "lib", "-o", "lib/O1234.nc"], &d);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert_eq!(
        std::fs::read_to_string(d.join("lib/O1234.nc")).unwrap(),
        lib
    );
    // A device replaces nothing: both may go to /dev/null.
    let out = gbcc(
        &[
            "main.nc",
            "-I",
            "lib",
            "-o",
            "/dev/null",
            "-MF",
            "/dev/null",
        ],
        &d,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
}

#[test]
fn the_error_cap_and_the_summary() {
    let d = dir("cap");
    let src: String = (0..30).map(|_| "G01 X1.2.3\n").collect();
    std::fs::write(d.join("many.nc"), src).unwrap();
    let count = |o: &Output| text(&o.stderr).matches("error[E1007]").count();
    let out = gbcc(&["many.nc"], &d);
    assert_eq!(out.status.code(), Some(1));
    // The default cap is 20; the ten others are counted.
    assert_eq!(count(&out), 20);
    let err = text(&out.stderr);
    assert!(
        err.contains("gbcc: note: 10 more diagnostics not shown (-fmax-errors=20"),
        "{err}"
    );
    assert!(err.ends_with("gbcc: 30 errors, 0 warnings\n"), "{err}");
    assert_eq!(count(&gbcc(&["many.nc", "-fmax-errors=3"], &d)), 3);
    assert_eq!(count(&gbcc(&["many.nc", "-fmax-errors=0"], &d)), 30);
    assert_eq!(
        gbcc(&["many.nc", "-fmax-errors=x"], &d).status.code(),
        Some(1)
    );
}

#[test]
fn wrong_kinds_of_file_are_refused() {
    let d = dir("kinds");
    std::fs::write(d.join("part.nc"), PART).unwrap();
    assert_eq!(gbcc(&["part.nc"], &d).status.code(), Some(0));
    let out = gbcc(&["part.gbc", "-o", "again.gbc"], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("part.gbc is a compiled .gbc module"),
        "{}",
        text(&out.stderr)
    );
    let run = gbvm(&["run", "part.nc"], &d);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("compile it first"),
        "{}",
        text(&run.stderr)
    );
    // The output may not replace the source, even through another name.
    let out = gbcc(&["part.nc", "-o", "./part.nc"], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("refusing to overwrite the source"));
    assert_eq!(std::fs::read_to_string(d.join("part.nc")).unwrap(), PART);
    // Nor may the default output name: a source called `prog.gbc`.
    std::fs::write(d.join("prog.gbc"), PART).unwrap();
    let out = gbcc(&["prog.gbc"], &d);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert_eq!(std::fs::read_to_string(d.join("prog.gbc")).unwrap(), PART);
}

/// An input that is no regular file: a device (an endless /dev/zero was
/// read until memory ran out) or a folder is refused at once, by both
/// tools and for the machine and `--vars` files too; a pipe is read.
#[test]
fn devices_are_refused_and_pipes_read() {
    let d = dir("devices");
    std::fs::write(d.join("part.nc"), PART).unwrap();
    let refused = |out: Output, what: &str| {
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains(&format!("not a regular file ({what})")),
            "{err}"
        );
    };
    for dev in ["/dev/zero", "/dev/urandom"] {
        refused(gbcc(&[dev, "-o", "z.gbc"], &d), "a device");
        for sub in ["verify", "run", "check", "disasm"] {
            refused(gbvm(&[sub, dev], &d), "a device");
        }
        refused(gbcc(&["part.nc", "--machine", dev], &d), "a device");
        refused(gbcc(&["part.nc", "--vars", dev], &d), "a device");
    }
    refused(gbcc(&["."], &d), "a folder");
    assert!(!d.join("z.gbc").exists());
    // A named pipe, as `gbcc <(…)` gives one, is read as standard input.
    let fifo = d.join("pipe.nc");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        return;
    }
    let writer = std::thread::spawn(move || std::fs::write(fifo, PART));
    let out = gbcc(&["pipe.nc", "-o", "pipe.gbc"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(writer.join().unwrap().is_ok());
    assert_eq!(text(&gbvm(&["run", "pipe.gbc"], &d).stdout), CANON);
}

#[test]
fn colour_on_request_only() {
    let d = dir("colour");
    std::fs::write(d.join("c.nc"), "G01 X1.2.3\n").unwrap();
    let esc = |o: Output| text(&o.stderr).contains("\x1b[");
    // Not a terminal: auto is plain.
    assert!(!esc(gbcc(&["c.nc"], &d)));
    assert!(esc(gbcc(&["c.nc", "-fdiagnostics-color=always"], &d)));
    assert!(!esc(gbcc(&["c.nc", "-fdiagnostics-color=never"], &d)));
    let mut c = cmd(
        env!("CARGO_BIN_EXE_gbcc"),
        &["c.nc", "-fdiagnostics-color=auto"],
        &d,
    );
    assert!(!esc(c.env("NO_COLOR", "1").output().unwrap()));
    // An explicit request wins over NO_COLOR, as in gcc.
    let mut c = cmd(
        env!("CARGO_BIN_EXE_gbcc"),
        &["c.nc", "-fdiagnostics-color=always"],
        &d,
    );
    assert!(esc(c.env("NO_COLOR", "1").output().unwrap()));
    let plain = text(&gbcc(&["c.nc"], &d).stderr);
    assert!(plain.starts_with("c.nc:1:6: error[E1007]: "), "{plain}");
}

#[test]
fn exit_codes_tell_the_cases_apart() {
    let d = dir("exit");
    std::fs::write(d.join("a.nc"), "#1=SQRT[-4]\nM30\n").unwrap();
    assert_eq!(gbcc(&["a.nc"], &d).status.code(), Some(0));
    assert_eq!(gbvm(&["run", "a.gbc"], &d).status.code(), Some(2));
    assert_eq!(
        gbvm(&["run", "a.gbc", "--no-such"], &d).status.code(),
        Some(1)
    );
    assert_eq!(gbvm(&["run", "missing.gbc"], &d).status.code(), Some(1));
    assert_eq!(gbcc(&["--explain", "E4009"], &d).status.code(), Some(0));
    assert_eq!(gbcc(&["--help"], &d).status.code(), Some(0));
}

/// Writes into a full device end with exit 3 and a message, not a panic
/// (101). Linux only: it needs /dev/full.
#[test]
fn outputs_that_cannot_be_written() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        return;
    }
    let d = dir("full");
    std::fs::write(d.join("part.nc"), PART).unwrap();
    std::fs::write(d.join("bad.nc"), "G01 X1.2.3\n").unwrap();
    let to_full = |args: &[&str], stderr_full: bool| {
        let mut c = cmd(env!("CARGO_BIN_EXE_gbcc"), args, &d);
        let dev = || std::fs::OpenOptions::new().write(true).open(full).unwrap();
        if stderr_full {
            c.stderr(dev());
        } else {
            c.stdout(dev());
        }
        c.output().unwrap()
    };
    for args in [
        &["part.nc", "-E"][..],
        &["part.nc", "-S", "-o", "-"],
        &["part.nc", "-o", "-"],
    ] {
        let out = to_full(args, false);
        assert_eq!(out.status.code(), Some(3), "{args:?}");
        assert!(
            text(&out.stderr).contains("cannot write <stdout>"),
            "{}",
            text(&out.stderr)
        );
    }
    assert_eq!(to_full(&["bad.nc"], true).status.code(), Some(3));
    assert_eq!(
        to_full(&["part.nc", "-o", "/dev/full"], false)
            .status
            .code(),
        Some(3)
    );
    // gbvm's listings and its canon too.
    assert_eq!(gbcc(&["part.nc"], &d).status.code(), Some(0));
    for sub in ["disasm", "verify", "run"] {
        let out = cmd(env!("CARGO_BIN_EXE_gbvm"), &[sub, "part.gbc"], &d)
            .stdout(std::fs::OpenOptions::new().write(true).open(full).unwrap())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(3), "{sub}");
    }
}

/// Standard error closed (`2>&-`): a diagnostic that cannot be shown is
/// lost, and the exit code says so (3), as with a full one; a compile
/// with nothing to say still succeeds.
#[test]
fn a_closed_standard_error_is_a_lost_one() {
    let d = dir("closed");
    std::fs::write(d.join("part.nc"), PART).unwrap();
    std::fs::write(d.join("warn.nc"), "G00 X10 Z2\nM444\nM30\n").unwrap();
    std::fs::write(d.join("bad.nc"), "G01 X1.2.3\n").unwrap();
    let closed = |file: &str| {
        let script = "exec \"$0\" \"$1\" -o out.gbc 2>&-";
        cmd("sh", &["-c", script, env!("CARGO_BIN_EXE_gbcc"), file], &d)
            .output()
            .unwrap()
            .status
            .code()
    };
    assert_eq!(closed("warn.nc"), Some(3));
    assert_eq!(closed("bad.nc"), Some(3));
    assert_eq!(closed("part.nc"), Some(0));
    // Discarded on purpose is not lost.
    let mut c = cmd(
        env!("CARGO_BIN_EXE_gbcc"),
        &["warn.nc", "-o", "out.gbc"],
        &d,
    );
    assert_eq!(c.stderr(Stdio::null()).status().unwrap().code(), Some(0));
}

/// Lone-CR line ends: the header and the snippet name the same line.
#[test]
fn lone_cr_files_agree_in_header_and_snippet() {
    let d = dir("cr");
    std::fs::write(d.join("cr.nc"), "G00 X1\rG01 X1.2.3\rM30\r").unwrap();
    let err = text(&gbcc(&["cr.nc"], &d).stderr);
    // "G01 X1.2.3" is line 2; its number starts at column 6.
    assert!(err.starts_with("cr.nc:2:6: error[E1007]"), "{err}");
    assert!(
        err.contains("┌─ cr.nc:2:6") && err.contains("2 │ G01 X1.2.3\n"),
        "{err}"
    );
}
