//! The real programs of `shared/corpus/public` and the conformance programs
//! of `shared/conformance`: each must parse, or fail with the expected
//! first error at the expected line.

use grammar::{Diagnostic, SourceFile};
use std::path::{Path, PathBuf};

/// What the grammar must say about a corpus file.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    /// No error (warnings allowed; semantic faults such as G91, M97 or G81
    /// are the compiler's).
    Ok,
    /// The first error: its code and line.
    First(&'static str, usize),
}
use Expect::*;

/// The corpus files that are not valid GSK980TDi / Fanuc lathe programs,
/// each with the reason. Every other file must parse without error.
const REJECTED: &[(&str, Expect)] = &[
    // Citizen multi-path syntax: `$1` path header, later `S1=500`, `!L1` (§4.13).
    ("citizen-syntax__sample-citizen.cnc", First("E1001", 1)),
    // `TO303`: the letter O typed for the digit 0 (help: did you mean T0303?).
    ("cnclearn__215.txt", First("E1008", 4)),
    // Typo `G1Z-0.5.F0.03`: a second decimal point.
    ("cnclearn__Izolyator095-1000.NC", First("E1007", 41)),
    // `GO Y0.`: the letter O for the digit 0 (help: did you mean G0?).
    ("cnclearn__Kolco-dc8-061-1003.NC", First("E1008", 55)),
    // Typo `X-12.8.`: a second decimal point.
    ("cnclearn__Vtulka-dc8-210-1004.NC", First("E1007", 27)),
    // `:(Solve for B …)`: `:` starts a program number (like O) but none follows.
    ("donpayne-cnc__advanced_arcs_o2001.cnc", First("E1004", 23)),
    // `N200 G00 3.7347`: an address letter is missing; blanks are ignored, so
    // this reads `G003.7347`, a G value with four decimals.
    ("doosan-lynx300__O0024", First("E1010", 72)),
    // Commas between comments: `(F-mm/rot), (S-m/min)`; later `)` without `(`.
    ("icnc__T2019-1-S42-Luiz-LUIZ2.txt", First("E1008", 12)),
    // `(DESBASTE INTERNO` is never closed.
    (
        "icnc__T2019-2-S42-Andrey-e-Fabio-TORNO1.txt",
        First("E1002", 69),
    ),
    // `N55 G00 X45s`: a stray `s` without value.
    (
        "icnc__T2019-2-S43-Alexandre-e-Alexandre-TORNFASE2.txt",
        First("E1007", 20),
    ),
    // Text after `;`: `T0505 ;bedame de 3mm` (help: put comments in ( )).
    ("projetocnc1__programa-completo.gcode", First("E1008", 38)),
    // `IF [#1 EQ #2] S900. F500.`: IF without GOTO or THEN.
    (
        "rcod2__SHABLON2-SHABLON2-1-VERH-O00025.nc",
        First("E1014", 42),
    ),
    // `IF […] THEN M31`: only an assignment may follow THEN.
    (
        "rcod2__SHABLON3-RAZNOE-shabloNi-0000-O00044.nc",
        First("E1013", 3),
    ),
    // `N230IF[#609GT0]#712=#609`: IF without THEN (§4.13, help: write THEN).
    ("sk7420__O8000", First("E1014", 32)),
];

fn shared(dir: &str) -> Option<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared")
        .join(dir);
    if path.is_dir() {
        Some(path)
    } else {
        println!("skipping: {} not found", path.display());
        None
    }
}

fn files(dir: &Path, keep: impl Fn(&Path) -> bool) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && keep(p))
        .collect();
    files.sort();
    files
}

/// What the grammar said: `Ok`, or the first error's code and line.
fn outcome(bytes: &[u8], diags: &[Diagnostic]) -> Expect {
    match diags.iter().find(|d| d.is_error()) {
        None => Ok,
        Some(d) => First(d.code, SourceFile::new("", bytes).line_col(d.span.start).0),
    }
}

fn report(path: &Path, bytes: &[u8], diags: &[Diagnostic]) -> String {
    let file = SourceFile::new(path.display().to_string(), bytes);
    diags
        .iter()
        .map(|d| file.render(d))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn public_corpus() {
    let Some(dir) = shared("corpus/public") else {
        return;
    };
    let all = files(&dir, |p| p.file_name().is_some_and(|n| n != "MANIFEST.tsv"));
    assert!(all.len() >= 80, "only {} corpus files", all.len());
    let mut failures = Vec::new();
    let mut seen = 0;
    for path in &all {
        let name = path.file_name().unwrap().to_string_lossy();
        let expect = REJECTED
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(Ok, |(_, e)| *e);
        seen += usize::from(expect != Ok);
        let bytes = std::fs::read(path).unwrap();
        let (ast, diags) = grammar::parse(&bytes);
        let got = outcome(&bytes, &diags);
        if got != expect {
            failures.push(format!(
                "{name}: expected {expect:?}, got {got:?}\n{}",
                report(path, &bytes, &diags)
            ));
        }
        if expect == Ok {
            assert!(!ast.lines.is_empty(), "{name}: empty tree");
        }
    }
    assert_eq!(
        seen,
        REJECTED.len(),
        "a rejected file is missing from the corpus"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Codes of §8.1 that need the meaning of the words, not their syntax: the
/// compiler reports them (E1005 duplicate program, E1009 decimal point on
/// an integer address, E1010 out-of-range values, E1011 repeated address,
/// E1012 M-code count). G with two decimals (also E1010) is the grammar's.
const COMPILER_CODES: &[&str] = &["E1005", "E1009", "E1011", "E1012"];

#[test]
fn conformance_programs() {
    let Some(dir) = shared("conformance") else {
        return;
    };
    let programs = files(&dir, |p| p.extension().is_some_and(|x| x == "nc"));
    assert!(!programs.is_empty());
    let mut failures = Vec::new();
    for path in &programs {
        let bytes = std::fs::read(path).unwrap();
        let (_, diags) = grammar::parse(&bytes);
        let got = outcome(&bytes, &diags);
        // `compile line=N code=1xxx` names a syntax error the grammar must find.
        let err = std::fs::read_to_string(path.with_extension("err")).unwrap_or_default();
        let mut expect: Option<(String, usize)> = None;
        if let Some(rest) = err.trim().strip_prefix("compile ") {
            let field = |key: &str| rest.split_whitespace().find_map(|f| f.strip_prefix(key));
            let code = field("code=").map(|c| format!("E{c}"));
            let line = field("line=").and_then(|l| l.parse::<usize>().ok());
            if let (Some(code), Some(line)) = (code, line) {
                if code.starts_with("E1") && !COMPILER_CODES.contains(&code.as_str()) {
                    expect = Some((code, line));
                }
            }
        }
        let matches = match (&expect, got) {
            (None, Ok) => true,
            (Some((code, line)), First(c, l)) => code == c && *line == l,
            _ => false,
        };
        if !matches {
            failures.push(format!(
                "{}: expected {expect:?}, got {got:?}\n{}",
                path.display(),
                report(path, &bytes, &diags)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
