//! `gbvm run --from`: program restart from the command line, to the canon
//! alone and through the runtime (the trace), and its refusals.

use std::path::PathBuf;
use std::process::{Command, Output};

const TWO_TOOLS: &str = "\
G50 X200 Z100
T0101
G97 S1000 M03
M08
G00 X52 Z2
G99 G01 Z-30 F0.2
X60
G00 Z2
T0202
S800 M04
G00 X40 Z2
N100 G01 Z-20 F0.1
X50
M09
G00 X200 Z100
M30
";

/// `TWO_TOOLS` compiled into a fresh folder: the module's path.
fn module(tag: &str) -> PathBuf {
    compiled(tag, TWO_TOOLS)
}

/// `program` compiled into a fresh folder: the module's path.
fn compiled(tag: &str, program: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gbc-restart-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let src = dir.join("program.nc");
    std::fs::write(&src, program).expect("written");
    let gbc = dir.join("program.gbc");
    let status = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .arg(&src)
        .arg("-o")
        .arg(&gbc)
        .status()
        .expect("gbcc runs");
    assert!(status.success());
    gbc
}

fn gbvm(gbc: &PathBuf, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .arg("run")
        .arg(gbc)
        .args(["-q"])
        .args(args)
        .output()
        .expect("gbvm runs")
}

/// By hand (docs/manual.md, "Program restart"): the state the blocks
/// before N100 left (G50's zero, tool 2, 800 rpm reversed, coolant on,
/// the feed printed last), X from where the tool stands (work X200 Z100)
/// to N100's start point X40, then Z, then the program from N100 on.
const FROM_N100: &str = "\
ORIGIN X=-200 Z=-100
TOOL T=2 D=2
SPEED S=800 MODE=RPM
SPINDLE DIR=CCW
M CODE=8
FEED F=0.2 MODE=REV
RAPID X=40 Z=100
RAPID X=40 Z=2
FEED F=0.1 MODE=REV
LINE X=40 Z=-20
LINE X=50 Z=-20
M CODE=9
RAPID X=200 Z=100
STOP KIND=M30
";

#[test]
fn from_a_sequence_number_or_its_line_prints_the_restarted_canon() {
    let gbc = module("canon");
    for at in ["N100", "12", "n100@1"] {
        let out = gbvm(&gbc, &["--from", at]);
        assert!(out.status.success(), "{at}: {out:?}");
        assert_eq!(String::from_utf8_lossy(&out.stdout), FROM_N100, "{at}");
    }
    // Through the runtime (--stats keeps the canon on stdout with --emit):
    // the same canon.
    let out = gbvm(&gbc, &["--from", "N100", "--emit", "canon", "--stats"]);
    assert!(out.status.success(), "{out:?}");
    assert_eq!(String::from_utf8_lossy(&out.stdout), FROM_N100);
}

#[test]
fn the_trace_of_a_restart_starts_with_the_approach_of_the_block() {
    let gbc = module("trace");
    let out = gbvm(&gbc, &["--from", "N100", "--emit", "trace"]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    let mut rows = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>());
    // time_s,x,z,spindle_rpm,feed,line,motion,tool,file
    let first = rows.next().expect("a period");
    assert_eq!(
        (first[2], first[5], first[6], first[7]),
        ("100.000000", "12", "rapid", "2")
    );
    assert!(rows.all(|r| r[7] == "2" && r[2].parse::<f64>().is_ok_and(|z| z >= -20.0)));
}

#[test]
fn a_restart_that_cannot_begin_is_an_error() {
    let gbc = module("refused");
    let cases = [
        ("N7", "the main file has no block at N7"),
        (
            "12@2",
            "the run reaches line 12 1 time(s), so there is no pass 2",
        ),
        ("99", "the main file has no block at line 99"),
    ];
    for (at, msg) in cases {
        for extra in [&[][..], &["--stats"][..]] {
            let out = gbvm(&gbc, &[&["--from", at][..], extra].concat());
            assert_eq!(out.status.code(), Some(1), "{at} {extra:?}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(err.contains(&format!("--from: {msg}")), "{at}: {err}");
        }
    }
    let out = gbvm(&gbc, &["--from", "N12@0"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("give a line (120) or a sequence number"));
}

/// The M codes of the machine's own before the block are told on
/// standard error, not given again.
#[test]
fn a_restart_names_the_m_codes_it_does_not_give_again() {
    let gbc = compiled("m", "M10\nG00 X50 Z2\nM14\nN20 G00 X60\nM30\n");
    let out = gbvm(&gbc, &["--from", "N20"]);
    assert!(out.status.success(), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(
            "--from: the blocks before it gave M10, M14, which a restart does not give again"
        ),
        "{err}"
    );
    assert!(!String::from_utf8_lossy(&out.stdout).contains("M CODE="));
}

/// `gbvm check --from` certifies the restarted run, the approach
/// included: its two rapids and the three moves from N100 on are the five
/// end points.
#[test]
fn check_certifies_a_restarted_run() {
    let gbc = module("check");
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["check", "--from", "N100"])
        .arg(&gbc)
        .output()
        .expect("gbvm runs");
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("certified: "), "{text}");
    assert!(text.contains("end points: 5 of 5 reached"), "{text}");
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["check", "--from", "N7"])
        .arg(&gbc)
        .output()
        .expect("gbvm runs");
    assert_eq!(out.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("--from: the main file has no block at N7")
    );
}

/// Inside nose-radius compensation (G42, tool 1: R 0.8, tip 3): the
/// restart at the taper approaches the compensated point X20 Z-20.4686
/// (compiler/tests/restart.rs works it out by hand), and `gbvm check`
/// certifies the run: the two rapids, the taper, the corner's arc, the
/// last element and the cancel are its six end points.
#[test]
fn a_restart_inside_compensation_approaches_the_compensated_point() {
    let program =
        "T0101\nG00 X50 Z2\nG42 G01 X20 Z0 F100\nZ-20\nX40 Z-30\nZ-40\nG40 G00 X60\nM30\n";
    let dir = std::env::temp_dir().join(format!("gbc-restart-comp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let (src, machine, gbc) = (dir.join("p.nc"), dir.join("m.toml"), dir.join("p.gbc"));
    std::fs::write(&src, program).expect("written");
    std::fs::write(
        &machine,
        "[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n",
    )
    .expect("written");
    let status = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .arg(&src)
        .arg("--machine")
        .arg(&machine)
        .arg("-o")
        .arg(&gbc)
        .status()
        .expect("gbcc runs");
    assert!(status.success());
    let machine = machine.to_str().expect("a path");
    let out = gbvm(&gbc, &["--from", "5", "--machine", machine]);
    assert!(out.status.success(), "{out:?}");
    let canon = String::from_utf8_lossy(&out.stdout);
    let rapids: Vec<&str> = canon.lines().filter(|l| l.starts_with("RAPID")).collect();
    assert_eq!(rapids[..2], ["RAPID X=20 Z=0", "RAPID X=20 Z=-20.4686"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--from: the approach goes to X20 Z-20.4686 (work coordinates)"),
        "{err}"
    );
    // By hand: G01 and G42 from line 3, T0101 and F100 before; the rest
    // power-on (dialect.md §3).
    assert!(
        err.contains(
            "--from: the run resumes with G01 G97 G98 G21 G42 G23 G80 G67 G54 G64 G18 G15 G13.1 F100 S0 T0101\n"
        ),
        "{err}"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .args(["check", "--from", "5", "--machine", machine])
        .arg(&gbc)
        .output()
        .expect("gbvm runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("end points: 6 of 6 reached"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
