//! What `gbvm run` writes for people to look at: the trace with file and
//! line, the statistics (text on stdout or stderr, JSON), the plot, no
//! progress bar off a terminal, and Ctrl-C keeping what the run made.

use cli::stats_json::Report;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-outputs-{tag}-{}", std::process::id()));
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

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    tool(env!("CARGO_BIN_EXE_gbcc"), args, cwd)
}

fn gbvm(args: &[&str], cwd: &Path) -> Output {
    tool(env!("CARGO_BIN_EXE_gbvm"), args, cwd)
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Two tools, each feeding along Z at 600 mm/min, with rapids between.
const TWO_TOOLS: &str = "O0042 (TWO TOOLS)\n[BILLET X50 Z70\nG98 T0101\nG00 X40 Z2\nG01 Z-60 F600\nG00 X100 Z100\nT0202\nG00 X30 Z2\nG01 Z-28 F600\nG00 X100 Z100\nM30\n";

fn compiled(tag: &str, src: &str) -> PathBuf {
    let d = dir(tag);
    std::fs::write(d.join("part.nc"), src).unwrap();
    let out = gbcc(&["part.nc", "-q"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    d
}

#[test]
fn the_trace_names_file_and_line() {
    let d = compiled("trace", TWO_TOOLS);
    let out = gbvm(&["run", "part.gbc", "--emit", "trace"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let t = text(&out.stdout);
    let mut lines = t.lines();
    assert_eq!(
        lines.next(),
        Some("time_s,x,z,spindle_rpm,feed,line,motion,tool,file")
    );
    // Every period names part.nc; the feed of line 5 (tool 1) is among them.
    assert!(lines.clone().all(|l| l.ends_with(",part.nc")), "{t:.400}");
    assert!(lines.any(|l| l.ends_with(",5,feed,1,part.nc")));
    let out = gbvm(
        &["run", "part.gbc", "--emit", "trace", "--format", "json"],
        &d,
    );
    let first = text(&out.stdout);
    let first = first.lines().next().unwrap_or_default();
    let v: serde_json::Value = serde_json::from_str(first).unwrap();
    assert_eq!(v["file"], "part.nc");
    assert!(v["line"].as_u64().is_some());
}

#[test]
fn stats_alone_go_to_stdout_and_beside_the_canon_to_stderr() {
    let d = compiled("stats", TWO_TOOLS);
    let out = gbvm(&["run", "part.gbc", "--stats"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let s = text(&out.stdout);
    assert!(s.starts_with("cycle time: 0:00:"), "{s}");
    assert!(!s.contains("RAPID"), "no canon with --stats alone: {s}");
    assert!(s.contains("  T01: 0:00:0"), "{s}");
    assert!(s.contains("    2. T02 from line 7: "), "{s}");
    let out = gbvm(&["run", "part.gbc", "--emit", "canon", "--stats"], &d);
    assert!(
        text(&out.stdout).starts_with("TOOL T=1 D=1\n"),
        "{}",
        text(&out.stdout)
    );
    assert!(text(&out.stderr).starts_with("cycle time: "));
}

/// `blocks` counts as the block budget does, the final M30 included: the
/// assignment 1, the G00 1, the G90 from outside the stock its 4 moves,
/// the M98 1, O1001's two blocks (its M99 too) 2, M30 1: 10 blocks. The
/// run fits `--max-blocks 10` and not 9.
#[test]
fn stats_count_the_blocks_the_budget_counts() {
    let src =
        "O0043\n#1=2\nG98 G00 X50 Z2\nG90 X40 Z-20 F600\nM98 P1001\nM30\nO1001\nG00 X60\nM99\n";
    let d = compiled("blocks", src);
    let out = gbvm(&["run", "part.gbc", "--stats"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let s = text(&out.stdout);
    assert!(s.ends_with("blocks: 10\n"), "{s}");
    let out = gbvm(&["run", "part.gbc", "--stats=json"], &d);
    let r: Report = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r.blocks, 10);
    let out = gbvm(&["run", "part.gbc", "--max-blocks", "10"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let out = gbvm(&["run", "part.gbc", "--max-blocks", "9", "--stats"], &d);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    // At the M30 (line 6), the tenth block: it did not run, 9 did.
    assert!(
        text(&out.stderr).contains("part.nc:6:1: alarm[E6005]"),
        "{}",
        text(&out.stderr)
    );
    assert!(
        text(&out.stdout).ends_with("blocks: 9\n"),
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn stats_as_json_read_back() {
    let d = compiled("json", TWO_TOOLS);
    let out = gbvm(&["run", "part.gbc", "--stats=json"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r: Report = serde_json::from_slice(&out.stdout).unwrap();
    // T01 cuts from Z2 to Z−60 (62 mm) and T02 from Z2 to Z−28 (30 mm),
    // each in one operation. An operation
    // begins at its first period: T0202 (line 7) has one, as the motion
    // stops for the change; T0101 at the start takes none, so the first
    // operation begins on the first move (line 4).
    let ops: Vec<(u32, u32)> = r.operations.iter().map(|o| (o.tool, o.line)).collect();
    assert_eq!(ops, [(1, 4), (2, 7)]);
    assert!((r.operations[0].cut_mm - 62.0).abs() < 1e-6, "{r:?}");
    assert!((r.operations[1].cut_mm - 30.0).abs() < 1e-6, "{r:?}");
    assert!((r.cut_mm - 92.0).abs() < 1e-6);
    // 92 mm at 10 mm/s is 9.2 s at feed; the rapids and ramps add to it.
    let t = r.cycle_time.s;
    assert!(t > 9.2 && t < 30.0, "{t}");
    let whole = t.round() as u64;
    assert_eq!(r.cycle_time.hms, format!("0:00:{whole:02}"));
    let per_tool: f64 = r.per_tool.iter().map(|p| p.time.s).sum();
    assert!((per_tool - t).abs() < 0.01, "{per_tool} vs {t}");
    assert!(r.interrupted_at.is_none());
}

#[test]
fn the_plot_is_small_titled_and_shows_stock_and_tools() {
    let d = compiled("plot", TWO_TOOLS);
    let out = gbvm(&["run", "part.gbc", "--plot", "p.svg"], &d);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // Without --stats the canon still goes to stdout.
    assert!(text(&out.stdout).contains("STOP KIND=M30"));
    let svg = std::fs::read_to_string(d.join("p.svg")).unwrap();
    assert!(
        svg.contains(">part.gbc  O0042 (TWO TOOLS)</text>"),
        "{svg:.600}"
    );
    assert!(svg.contains(">T01</text>") && svg.contains(">T02</text>"));
    // The [BILLET X50 Z70 line: a bar of radius 25 from Z0 to Z−70.
    assert!(svg.contains("fill=\"#f1e6c8\""));
    // The rapids to X100 Z100 leave the frame: an arrow at each crossing
    // (out, in, out).
    assert_eq!(svg.matches("class=\"leaves\"").count(), 3, "{svg}");
    assert!(svg.len() < 20_000, "{} bytes", svg.len());
    // A --stock that does not parse is refused.
    let out = gbvm(
        &["run", "part.gbc", "--plot", "q.svg", "--stock", "X50"],
        &d,
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("X<diameter> Z<length>"));
}

/// The canon of many moves (written on a thread of its own, in batches)
/// comes out whole and in order, and an alarm's line is still the last.
#[test]
fn a_long_canon_is_whole_and_in_order_to_its_alarm() {
    const MOVES: usize = 9000;
    // X an integer, Z a quarter: both print exactly as `f64`'s Display.
    let point = |i: usize| ((i % 50) as f64, -(((i % 70) + 1) as f64) / 4.0);
    let mut src = String::from("G98 G01 X1 Z-1 F600\n");
    for i in 0..MOVES {
        let (x, z) = point(i);
        src.push_str(&format!("X{x:.0} Z{z}\n"));
    }
    src.push_str("#3000=1(STOP HERE)\nX1 Z-2\nM30\n");
    let d = compiled("long", &src);
    let out = gbvm(&["run", "part.gbc", "--emit", "canon"], &d);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    let mut want = vec!["FEED F=600 MODE=MIN".to_string(), "LINE X=1 Z=-1".into()];
    want.extend((0..MOVES).map(|i| {
        let (x, z) = point(i);
        format!("LINE X={x} Z={z}")
    }));
    want.push("ALARM CODE=3001 MSG=\"STOP HERE\"".into());
    let got = text(&out.stdout);
    assert_eq!(got.lines().collect::<Vec<_>>(), want);
}

#[test]
fn no_progress_bar_off_a_terminal() {
    // The tests' stderr is a pipe: nothing but the statistics appear.
    let d = compiled("quiet", TWO_TOOLS);
    let out = gbvm(&["run", "part.gbc", "--emit", "canon", "--stats"], &d);
    let err = text(&out.stderr);
    assert!(!err.contains('\u{1b}') && !err.contains('\r'), "{err:?}");
    let out = gbvm(&["run", "part.gbc", "--quiet", "--stats"], &d);
    assert_eq!(out.status.code(), Some(0));
    assert!(out.stderr.is_empty(), "{}", text(&out.stderr));
}

#[test]
fn ctrl_c_keeps_the_plot_and_the_statistics() {
    // 1000 mm at 1 mm/min: 60 000 s of cycle time, far longer than the
    // test waits (a release build simulates the default bound of an hour,
    // run.max_time_s, within the wait, so the bound is raised).
    let d = compiled(
        "sigint",
        "O0007\nG98 T0101\nG00 X40 Z2\nG01 Z-1000 F1\nM30\n",
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["run", "part.gbc", "--plot", "p.svg", "--stats"])
        .args(["--max-time", "1000000"])
        .current_dir(&d)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("gbvm did not stop on SIGINT");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("gbvm: interrupted at part.nc:4 after "),
        "{err}"
    );
    assert!(err.contains("hold the run so far"), "{err}");
    let stats = text(&out.stdout);
    assert!(stats.starts_with("cycle time: "), "{stats}");
    assert!(stats.contains("interrupted at: part.nc:4"), "{stats}");
    let svg = std::fs::read_to_string(d.join("p.svg")).unwrap();
    assert!(svg.ends_with("</svg>\n"));
    assert!(svg.contains("#1f4e9c"), "the feed so far is drawn");
}
