//! `gbcc -E` is equivalent to the program it expands: for every
//! conformance program (../shared/conformance, with its machine file) and
//! every public corpus program (../shared/corpus/public, on the machines of
//! compiler/tests/corpus.rs) that compiles, the `-E` output compiles on the
//! same machine and `gbvm run --emit canon` prints the same lines for both,
//! byte for byte.
//!
//! One normalisation: a run that stops on a run-time alarm other than a
//! `#3000` one (a check of the dialect such as E5001, the block budget) has
//! no G-code that raises it, so `-E` ends with a comment naming the alarm
//! where the run stopped. For such a program the canons must agree on every
//! line before the `ALARM` line, the `-E` program's canon must end there,
//! and the `-E` output's last line must be that comment. A `#3000` alarm is
//! written as the `#3000` write and compared like any other line.

mod cases;

use cases::{conformance_cases, corpus_cases, Case};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Programs whose `-E` output does not compile again, each with the reason
/// the output itself gives in a comment (the text the test looks for).
/// None today.
const EXEMPT: &[(&str, &str, &str)] = &[];

fn run(bin: &str, args: &[&str]) -> Output {
    Command::new(bin).args(args).output().unwrap()
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-expand-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn with_machine<'a>(mut args: Vec<&'a str>, machine: &'a Option<PathBuf>) -> Vec<&'a str> {
    if let Some(m) = machine {
        args.push("--machine");
        args.push(m.to_str().unwrap());
    }
    args
}

fn compile(src: &Path, gbc: &Path, machine: &Option<PathBuf>) -> Output {
    let args = vec![src.to_str().unwrap(), "-q", "-o", gbc.to_str().unwrap()];
    run(env!("CARGO_BIN_EXE_gbcc"), &with_machine(args, machine))
}

fn canon(gbc: &Path, machine: &Option<PathBuf>) -> String {
    let args = vec!["run", gbc.to_str().unwrap(), "--emit", "canon"];
    let out = run(env!("CARGO_BIN_EXE_gbvm"), &with_machine(args, machine));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// What became of one program.
enum Verdict {
    /// It does not compile: not part of the claim.
    NotCompiled,
    Equivalent,
    /// The `-E` output does not compile; the output's text.
    ExpandedNotCompiled(String, String),
    Different(String),
}

fn check(case: &Case, dir: &Path) -> Verdict {
    let stem = case.name.replace('/', "_");
    let gbc = dir.join(format!("{stem}.gbc"));
    if !compile(&case.src, &gbc, &case.machine).status.success() {
        return Verdict::NotCompiled;
    }
    let first = canon(&gbc, &case.machine);
    let expanded = dir.join(format!("{stem}.E.nc"));
    let args = vec![
        case.src.to_str().unwrap(),
        "-E",
        "-q",
        "-o",
        expanded.to_str().unwrap(),
    ];
    // A run that ends on an alarm exits non-zero, the text written all the same.
    run(
        env!("CARGO_BIN_EXE_gbcc"),
        &with_machine(args, &case.machine),
    );
    let text = std::fs::read_to_string(&expanded).unwrap_or_default();
    let gbc2 = dir.join(format!("{stem}.E.gbc"));
    let out = compile(&expanded, &gbc2, &case.machine);
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        return Verdict::ExpandedNotCompiled(text, err);
    }
    let second = canon(&gbc2, &case.machine);
    match compare(&first, &second, &text) {
        None => Verdict::Equivalent,
        Some(why) => Verdict::Different(why),
    }
}

/// Why the canons differ, or None (the normalisation of the module's doc).
fn compare(first: &str, second: &str, text: &str) -> Option<String> {
    if first == second {
        // Also a run whose -E output raises the same alarm by itself
        // (a feed move at F = 0 stops both with E7001).
        return None;
    }
    let lines: Vec<&str> = first.lines().collect();
    let other_alarm = lines
        .last()
        .and_then(|l| l.strip_prefix("ALARM CODE="))
        .and_then(|r| {
            let code: u32 = r.split(' ').next()?.parse().ok()?;
            (!(3000..4000).contains(&code)).then_some(code)
        });
    let Some(code) = other_alarm else {
        return Some(first_difference(first, second));
    };
    let before = lines[..lines.len() - 1].join("\n");
    if before != second.trim_end_matches('\n') {
        return Some(first_difference(&before, second));
    }
    let last = text.lines().last().unwrap_or("");
    if !last.starts_with(&format!("(ALARM {code}: ")) {
        return Some(format!("-E does not end naming alarm {code}: {last:?}"));
    }
    None
}

fn first_difference(a: &str, b: &str) -> String {
    let mut n = 0;
    let (mut la, mut lb) = (a.lines(), b.lines());
    loop {
        n += 1;
        match (la.next(), lb.next()) {
            (None, None) => return "equal lines, different ends".into(),
            (x, y) if x != y => return format!("line {n}: {x:?} against {y:?}"),
            _ => {}
        }
    }
}

#[test]
fn every_program_that_compiles_expands_to_the_same_canon() {
    let dir = scratch("all");
    let mut cases = conformance_cases();
    cases.extend(corpus_cases(&dir));
    if cases.is_empty() {
        eprintln!("../shared not found: skipped");
        return;
    }
    let (mut equivalent, mut wrong) = (0, Vec::new());
    for case in &cases {
        let exempt = EXEMPT.iter().find(|(name, _, _)| *name == case.name);
        match (check(case, &dir), exempt) {
            (Verdict::NotCompiled, None) => {}
            (Verdict::Equivalent, None) => equivalent += 1,
            (Verdict::ExpandedNotCompiled(text, _), Some((_, _, says))) if text.contains(says) => {}
            (Verdict::ExpandedNotCompiled(_, err), None) => {
                wrong.push(format!("{}: -E output does not compile: {err}", case.name))
            }
            (Verdict::Different(why), None) => wrong.push(format!("{}: {why}", case.name)),
            (_, Some(_)) => wrong.push(format!(
                "{}: exempt, but its -E output is not the one the list expects",
                case.name
            )),
        }
    }
    eprintln!("{equivalent} programs equivalent");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // 2026-12: 112 programs compile (90 conformance cases less 14 compile
    // errors, 82 corpus programs less 46 the compiler rejects): all are
    // equivalent (before -E wrote zero shifts, reference
    // returns and messages as G-code: 82).
    assert!(equivalent >= 112, "only {equivalent} equivalent");
    let _ = std::fs::remove_dir_all(dir);
}

/// An arc after a chamfer (L) ends its block where the chamfer begins, not
/// where the block's words say: its I/K must be taken from the point the
/// last printed move ended (the old `-E` took the kernel's programmed
/// point, and the arc it wrote did not close: E4002).
#[test]
fn an_arc_after_a_chamfer_is_written_from_where_the_chamfer_ends() {
    let dir = scratch("chamfer");
    let src = dir.join("ld.nc");
    std::fs::write(
        &src,
        "G00 X20 Z2\nG01 Z0 F100\nG01 Z-20\nG01 X60 L1\nG02 X60 Z-40 R12 L2\nG01 X80\nM30\n",
    )
    .unwrap();
    let case = Case {
        name: "chamfer".into(),
        src,
        machine: None,
    };
    match check(&case, &dir) {
        Verdict::Equivalent => {}
        Verdict::NotCompiled => panic!("the program itself does not compile"),
        Verdict::ExpandedNotCompiled(text, err) => panic!("{err}\n{text}"),
        Verdict::Different(why) => panic!("{why}"),
    }
    let _ = std::fs::remove_dir_all(dir);
}
