//! Diagnostics as data: rustc's JSON shape read back with serde, a SARIF
//! 2.1.0 log checked for the properties the standard requires, and
//! `--explain` for every code the tools can emit.

use cli::report::json::Diag;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-data-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// "G00 X10\nG01 X1.2.3\n": the malformed number "1.2.3" is bytes 13..18
/// (line 2 starts at 8; "G01 X" is 5 bytes), columns 6..11.
const BAD: &str = "G00 X10\nG01 X1.2.3\n";

/// A diagnostic on a line of 10 MB (a binary file with no line end) shows
/// a window of the line around the fault, marked `...` where it is cut,
/// in the text form and in JSON alike: not the line and a caret run as
/// long (30 MB on stderr). Its place is the file's.
#[test]
fn a_huge_line_is_clipped_around_the_fault() {
    let d = dir("huge");
    let mut src = vec![b'X'; 10_000_000];
    // A malformed number in the middle: "X1.2.3" at byte 5 000 000.
    src.splice(5_000_000..5_000_006, *b"X1.2.3");
    std::fs::write(d.join("huge.nc"), &src).unwrap();
    let out = gbcc(&["huge.nc"], &d);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.len() < 4000, "{} bytes of stderr", err.len());
    let json = gbcc(&["huge.nc", "-fdiagnostics-format=json"], &d);
    let all: Vec<Diag> = text(&json.stderr)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert!(json.stderr.len() < 40_000, "{} bytes", json.stderr.len());
    let number = all
        .iter()
        .flat_map(|d| &d.spans)
        .find(|s| s.byte_start == 5_000_001)
        .expect("a diagnostic at the malformed number");
    assert_eq!((number.line_start, number.column_start), (1, 5_000_002));
    let line = &number.text[0];
    assert!(line.text.starts_with("...X") && line.text.ends_with("X..."));
    let (from, to) = (line.highlight_start - 1, line.highlight_end - 1);
    assert_eq!(&line.text[from..to], "1.2.3", "{}", line.text);
    // The text form shows the same window.
    assert!(err.contains(&line.text), "{err}");
    assert!(err.contains("┌─ huge.nc:1:5000002"), "{err}");
    // The alarm message W124 quotes is the program's text: clipped too.
    let message = "A".repeat(1_000_000);
    std::fs::write(d.join("alarm.nc"), format!("#3000=1 ({message})\nM30\n")).unwrap();
    let err = text(&gbcc(&["alarm.nc"], &d).stderr);
    assert!(
        err.contains("W124") && err.len() < 4000,
        "{} bytes",
        err.len()
    );
    assert!(err.contains(&format!("{}...", &message[..60])), "{err}");
}

#[test]
fn json_has_rustc_shape_and_loses_nothing() {
    let d = dir("json");
    std::fs::write(d.join("bad.nc"), BAD).unwrap();
    let out = gbcc(&["bad.nc", "-fdiagnostics-format=json"], &d);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    let first = err.lines().next().unwrap();
    let diag: Diag = serde_json::from_str(first).unwrap();
    assert_eq!(diag.level, "error");
    let code = diag.code.as_ref().unwrap();
    assert_eq!(code.code, "E1007");
    assert!(code
        .explanation
        .as_deref()
        .unwrap_or("")
        .starts_with("E1007: "));
    let span = &diag.spans[0];
    assert_eq!(span.file_name, "bad.nc");
    assert_eq!((span.byte_start, span.byte_end), (13, 18));
    assert_eq!((span.line_start, span.line_end), (2, 2));
    assert_eq!((span.column_start, span.column_end), (6, 11));
    assert!(span.is_primary);
    assert_eq!(span.text[0].text, "G01 X1.2.3");
    assert_eq!(
        (span.text[0].highlight_start, span.text[0].highlight_end),
        (6, 11)
    );
    // The text form is there whole, and matches what text mode prints.
    let plain = text(&gbcc(&["bad.nc"], &d).stderr);
    let rendered = diag.rendered.as_deref().unwrap();
    assert!(plain.starts_with(rendered), "{plain}\n---\n{rendered}");
    // Notes and help become children.
    std::fs::write(d.join("help.nc"), "G00 X1 ;junk\n").unwrap();
    let out = gbcc(
        &["help.nc", "-fdiagnostics-format=json", "-fsyntax-only"],
        &d,
    );
    let all: Vec<Diag> = text(&out.stderr)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let plain = text(&gbcc(&["help.nc", "-fsyntax-only"], &d).stderr);
    for diag in &all {
        for c in &diag.children {
            assert!(["note", "help"].contains(&c.level.as_str()));
            assert!(plain.contains(&c.message), "{} not in {plain}", c.message);
        }
    }
}

#[test]
fn sarif_log_has_the_required_structure() {
    let d = dir("sarif");
    std::fs::write(d.join("bad.nc"), BAD).unwrap();
    std::fs::write(d.join("warn.nc"), "G00 X1\n").unwrap();
    let out = gbcc(
        &[
            "bad.nc",
            "warn.nc",
            "-fsyntax-only",
            "-fdiagnostics-format=sarif",
        ],
        &d,
    );
    let out2 = gbcc(
        &["warn.nc", "-fdiagnostics-format=sarif", "-o", "w.gbc"],
        &d,
    );
    assert_eq!(out.status.code(), Some(1));
    for o in [out, out2] {
        let log: Value = serde_json::from_slice(&o.stderr).unwrap();
        check_sarif(&log);
    }
    let out = gbcc(&["bad.nc", "-fdiagnostics-format=sarif"], &d);
    let log: Value = serde_json::from_slice(&out.stderr).unwrap();
    let result = &log["runs"][0]["results"][0];
    assert_eq!(result["ruleId"], "E1007");
    assert_eq!(result["level"], "error");
    let region = &result["locations"][0]["physicalLocation"]["region"];
    assert_eq!(region["startLine"], 2);
    assert_eq!(region["startColumn"], 6);
    assert_eq!(region["endColumn"], 11);
    assert_eq!(
        result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
        "bad.nc"
    );
}

/// The properties SARIF 2.1.0 requires (sarif-schema-2.1.0.json: log
/// `version`, `runs`; run `tool`; tool `driver`; driver `name`; result
/// `message`; message `text`; rule `id`), the types it gives them, and the
/// values it allows for `level`.
fn check_sarif(log: &Value) {
    assert_eq!(log["version"], "2.1.0");
    assert!(log["$schema"]
        .as_str()
        .unwrap()
        .ends_with("sarif-schema-2.1.0.json"));
    let runs = log["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1);
    let driver = &runs[0]["tool"]["driver"];
    assert_eq!(driver["name"], "gbcc");
    let rules = driver["rules"].as_array().unwrap();
    for rule in rules {
        assert!(rule["id"].is_string());
        assert!(rule["shortDescription"]["text"].is_string());
    }
    for r in runs[0]["results"].as_array().unwrap() {
        assert!(r["message"]["text"].is_string());
        let level = r["level"].as_str().unwrap();
        assert!(["none", "note", "warning", "error"].contains(&level));
        let index = r["ruleIndex"].as_u64().unwrap() as usize;
        assert_eq!(rules[index]["id"], r["ruleId"]);
        for loc in r["locations"].as_array().unwrap() {
            let p = &loc["physicalLocation"];
            assert!(p["artifactLocation"]["uri"].is_string());
            let region = &p["region"];
            for k in ["startLine", "startColumn", "endLine", "endColumn"] {
                assert!(region[k].as_u64().unwrap() >= 1, "{k}");
            }
        }
    }
    for inv in runs[0]["invocations"].as_array().unwrap() {
        assert!(inv["executionSuccessful"].is_boolean());
    }
}

#[test]
fn explain_prints_an_example_of_each_code() {
    let d = dir("explain");
    let out = gbcc(&["--explain", "E4009"], &d);
    assert_eq!(out.status.code(), Some(0));
    let t = text(&out.stdout);
    assert!(t.starts_with("E4009: "), "{t}");
    assert!(has_examples(&t), "{t}");
    let out = gbcc(&["--explain", "E9999"], &d);
    assert_eq!(out.status.code(), Some(1));
}

/// Every code written in the sources of the crates that report (a string
/// such as "E4009" or "W113"), and every code of the run-time alarm table,
/// has its entry in docs/diagnostics.md, which `--explain` prints; every
/// entry has a wrong and a right example.
#[test]
fn every_code_has_its_explanation() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut codes = std::collections::BTreeSet::new();
    // (cli reports no code of its own.)
    for krate in ["grammar", "compiler", "nc", "vm", "runtime", "isa"] {
        scan(&root.join(krate).join("src"), &mut codes);
    }
    // The kernel's alarm table (nc::base::alarm) names its codes through a
    // macro, not as string literals: every one of them is reported.
    codes.extend(
        nc::base::alarm::Alarm::ALL
            .iter()
            .map(|a| a.name().to_string()),
    );
    // The placeholder of compiler::codes for a number it does not list.
    codes.remove("E0000");
    assert!(codes.len() > 80, "{codes:?}");
    let docs = std::fs::read_to_string(root.join("docs/diagnostics.md")).unwrap();
    for code in &codes {
        assert!(
            docs.contains(&format!("\n### {code}: ")),
            "{code} has no entry in docs/"
        );
        let e = cli::explain::find(code).unwrap_or_else(|| panic!("{code}: no --explain"));
        assert_eq!(e.code, code);
    }
    for e in cli::explain::entries() {
        assert!(has_examples(e.body), "{} lacks an example", e.code);
    }
}

/// A "Wrong" and a "Right" paragraph, each followed by a code block.
fn has_examples(body: &str) -> bool {
    let body = format!("\n{body}");
    ["\nWrong", "\nRight"].iter().all(|p| {
        body.split(p)
            .nth(1)
            .and_then(|rest| rest.split_once('\n'))
            .is_some_and(|(_, next)| next.starts_with("```"))
    })
}

/// Collects "E1234" and "W123" string literals of the .rs files under `dir`.
fn scan(dir: &Path, codes: &mut std::collections::BTreeSet<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            scan(&path, codes);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let src = std::fs::read_to_string(&path).unwrap();
            for piece in src.split('"').skip(1) {
                let b = piece.as_bytes();
                let digits = |n: usize| b.len() == n + 1 && b[1..].iter().all(u8::is_ascii_digit);
                if (b.first() == Some(&b'E') && digits(4))
                    || (b.first() == Some(&b'W') && digits(3))
                {
                    codes.insert(piece.to_string());
                }
            }
        }
    }
}
