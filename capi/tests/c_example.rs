//! `examples/c/controller.c`, built by the system C compiler against the
//! checked-in header and the static library cargo just built, runs a
//! compiled program to its end; its set points (printed in the trace
//! format) are the same, line for line, as `gbvm run --emit trace`.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;

use support::{build_libraries, cargo_build, profile_dir, repo};

/// `gbvm` of the same profile, built now if need be (a no-op when the
/// workspace's tests already built it).
fn gbvm(profile: &Path) -> PathBuf {
    cargo_build(profile, &["-p", "cli", "--bin", "gbvm"]);
    profile.join("gbvm")
}

/// `libgbc.a` of the same profile.
fn static_lib(profile: &Path) -> PathBuf {
    build_libraries(profile);
    profile.join("libgbc.a")
}

/// Compiles the C example against `libgbc.a`; returns the executable.
fn build_example(profile: &Path, out: &Path) -> PathBuf {
    build_c(profile, &repo().join("examples/c/controller.c"), out)
}

/// Compiles a C host `src` against `libgbc.a` into `out`; returns the
/// executable.
fn build_c(profile: &Path, src: &Path, out: &Path) -> PathBuf {
    let lib = static_lib(profile);
    assert!(lib.exists(), "{} is missing", lib.display());
    let name = src.file_stem().expect("a C file name");
    let exe = out.join(name);
    let cc = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let st = Command::new(cc)
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-g"])
        .arg("-I")
        .arg(repo().join("capi/include"))
        .arg(src)
        .arg(&lib)
        // What a Rust static library needs of the system on Linux.
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lgcc_s", "-lc"])
        .arg("-o")
        .arg(&exe)
        .status()
        .expect("the system C compiler (cc) runs");
    assert!(st.success(), "cc failed on {}", src.display());
    exe
}

fn compile(src: &Path, out: &Path) -> PathBuf {
    let text = std::fs::read(src).expect("the example program");
    let c = compiler::compile("part.nc", &text, &compiler::Options::default());
    let rendered = c.render();
    let module = c.module.unwrap_or_else(|| panic!("{rendered}"));
    let path = out.join("part.gbc");
    std::fs::write(&path, module.to_bytes()).expect("write part.gbc");
    path
}

#[test]
fn the_c_controller_loop_gives_gbvms_trace() {
    let profile = profile_dir();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_example");
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let exe = build_example(&profile, &out);
    let gbc = compile(&repo().join("examples/c/part.nc"), &out);

    let c = Command::new(&exe)
        .arg(&gbc)
        .output()
        .expect("the example runs");
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert!(c.status.success(), "the C controller failed: {stderr}");
    // The host saw the PLC functions (T, M03, S, M08, M09, M05 of M30 …)
    // and the store of #500 (one block changes it).
    assert!(stderr.contains(" 1 stores of #500-#999"), "{stderr}");

    let g = Command::new(gbvm(&profile))
        .args(["run", "--emit", "trace"])
        .arg(&gbc)
        .output()
        .expect("gbvm runs");
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));

    let (c_out, g_out) = (
        String::from_utf8(c.stdout).expect("UTF-8"),
        String::from_utf8(g.stdout).expect("UTF-8"),
    );
    let (cl, gl): (Vec<&str>, Vec<&str>) = (c_out.lines().collect(), g_out.lines().collect());
    // Several seconds of motion: the rapids, the cut, the dwell, the thread.
    assert!(gl.len() > 2000, "gbvm's trace has {} lines", gl.len());
    assert_eq!(cl.len(), gl.len(), "trace lengths differ");
    for (i, (a, b)) in cl.iter().zip(&gl).enumerate() {
        assert_eq!(a, b, "line {} differs (C, gbvm)", i + 1);
    }
}

/// A thread whose S comes from a variable, 1 mm from its block's start
/// and end (the runtime's own test, thread_motion.rs, derives the
/// figures): the example prints W118 for both as gbvm's timed runs do,
/// in gbcc's wording.
#[test]
fn the_c_controller_reports_a_thread_without_room() {
    const SHORT: &str = "#1=1500\nG97 S#1 M03\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM30\n";
    let profile = profile_dir();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_room");
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let exe = build_example(&profile, &out);
    let src = out.join("short.nc");
    std::fs::write(&src, SHORT).expect("write short.nc");
    let gbc = compile(&src, &out);
    let c = Command::new(&exe)
        .arg(&gbc)
        .output()
        .expect("the example runs");
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert!(c.status.success(), "the C controller failed: {stderr}");
    let warned: Vec<&str> = stderr.lines().filter(|l| l.contains("W118")).collect();
    assert_eq!(
        warned,
        [
            "part.nc:4:1: warning[W118]: thread too short to reach its lead: at 1500 rpm Z needs 1.442 mm to reach thread speed, this block gives 1.000 mm",
            "part.nc:4:1: warning[W118]: no room to stop at the thread's end: at 1500 rpm Z needs 1.406 mm to stop from thread speed, this block gives 1.000 mm",
        ]
    );
    let g = Command::new(gbvm(&profile))
        .args(["run", "--emit", "trace"])
        .arg(&gbc)
        .output()
        .expect("gbvm runs");
    let g_err = String::from_utf8_lossy(&g.stderr);
    for w in warned {
        assert!(g_err.contains(w), "gbvm: {g_err}");
    }
}

/// Line 3 is skipped while switch 1 is on; line 4 reads the current
/// position, so the program is read no further until the motion before it
/// has ended; line 5 is read after that.
const SKIPS: &str = "O0001\nG00 X10 Z0\n/G00 X12\n#100=#5021\n/G00 X16\nG00 X18\nM30\n";

#[test]
fn block_skip_turned_off_from_c_decides_for_the_blocks_read_after_it() {
    let profile = profile_dir();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_block_skip");
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let exe = build_c(&profile, &repo().join("capi/tests/c/block_skip.c"), &out);
    let src = out.join("skips.nc");
    std::fs::write(&src, SKIPS).expect("write skips.nc");
    let gbc = compile(&src, &out);

    // The host turns switch 1 off after the first run-ahead, which read
    // lines 2 and 3 (switch on: skipped) and stopped at line 4.
    let c = Command::new(&exe)
        .arg(&gbc)
        .output()
        .expect("block_skip runs");
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert!(c.status.success(), "the C host failed: {stderr}");
    let text = String::from_utf8(c.stdout).expect("UTF-8");
    let mut lines: Vec<u32> = text.lines().filter_map(|l| l.parse().ok()).collect();
    lines.dedup();
    // The axes ran line 2, then (the skipped line 3 never moves them, the
    // read at line 4 moves nothing) line 5, read with the switch off, and
    // line 6; M30 at line 7.
    let moved: Vec<u32> = lines.into_iter().filter(|&l| l != 7).collect();
    assert_eq!(moved, [2, 5, 6], "{text}");
}

/// 100 000 rounds of a macro loop, then two moves; the last ends at X40
/// Z-30 (40 000 and −30 000 steps of 0.001 mm).
const LOOP_THEN_MOVES: &str =
    "#1=0\nWHILE[#1LT100000]DO1\n#1=#1+1\nEND1\nG00 X40 Z-20\nG98 G01 Z-30 F300\nM30\n";

#[test]
fn a_c_host_runs_a_split_controller_on_two_threads() {
    let profile = profile_dir();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_split");
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let exe = build_c(&profile, &repo().join("capi/tests/c/split.c"), &out);
    let src = out.join("loop.nc");
    std::fs::write(&src, LOOP_THEN_MOVES).expect("write loop.nc");
    let gbc = compile(&src, &out);
    let c = Command::new(&exe).arg(&gbc).output().expect("split runs");
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert!(c.status.success(), "the C host failed: {stderr}");
    let text = String::from_utf8(c.stdout).expect("UTF-8");
    assert_eq!(text, "40.000000 -30.000000 40000 -30000\n", "{stderr}");
}

/// The first C code block of `capi/README.md`.
fn readme_loop() -> String {
    let readme = std::fs::read_to_string(repo().join("capi/README.md")).expect("capi/README.md");
    let start = readme.find("```c\n").expect("a C block in the README") + "```c\n".len();
    let len = readme[start..].find("```").expect("the block's end");
    readme[start..start + len].to_string()
}

/// A `main` around the README's `run()`: reads the `.gbc` named by its
/// argument and returns what `run` returns.
const README_MAIN: &str = r#"
#include <stdio.h>

int main(int argc, char **argv) {
    static unsigned char program[1 << 20];
    FILE *f = argc == 2 ? fopen(argv[1], "rb") : NULL;
    if (!f)
        return 2;
    size_t len = fread(program, 1, sizeof program, f);
    fclose(f);
    return run(program, len);
}
"#;

/// The README's minimal loop, compiled as it stands with the warnings
/// the project uses, runs examples/c/part.nc — which stops at its M01 on
/// the reference machine — to its end.
#[test]
fn the_readme_loop_runs_the_example_part_to_its_end() {
    let profile = profile_dir();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_readme");
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let src = out.join("readme_loop.c");
    std::fs::write(&src, readme_loop() + README_MAIN).expect("write readme_loop.c");
    let exe = build_c(&profile, &src, &out);
    let gbc = compile(&repo().join("examples/c/part.nc"), &out);

    // A loop that misses the stop never ends: give it a deadline.
    let mut child = Command::new(&exe)
        .arg(&gbc)
        .spawn()
        .expect("the README loop runs");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    let status = loop {
        if let Some(st) = child.try_wait().expect("wait for the README loop") {
            break st;
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the README loop did not end within 120 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    assert_eq!(status.code(), Some(0), "run() did not reach the end");
}
