//! The programs the whole-tool equivalence tests run: the conformance
//! suite (with each case's machine file), the public corpus (on the
//! machines of compiler/tests/corpus.rs), when ../shared is beside the
//! repository, and the examples.

// Each test binary uses a different subset.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// One program: its name in reports, its source, its machine file.
pub struct Case {
    pub name: String,
    pub src: PathBuf,
    pub machine: Option<PathBuf>,
}

fn shared(dir: &str) -> Option<PathBuf> {
    let d = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared")
        .join(dir);
    d.is_dir().then_some(d)
}

/// The `.nc` files of a folder, sorted.
fn nc_files(dir: &Path) -> Vec<PathBuf> {
    let mut srcs: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "nc"))
        .collect();
    srcs.sort();
    srcs
}

/// The programs of `examples/`, on the reference machine.
pub fn example_cases() -> Vec<Case> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    nc_files(&dir)
        .into_iter()
        .map(|src| Case {
            name: format!("examples/{}", src.file_stem().unwrap().to_string_lossy()),
            src,
            machine: None,
        })
        .collect()
}

pub fn conformance_cases() -> Vec<Case> {
    let Some(suite) = shared("conformance") else {
        return Vec::new();
    };
    nc_files(&suite)
        .into_iter()
        .map(|src| {
            let toml = src.with_extension("toml");
            Case {
                name: format!("conformance/{}", src.file_stem().unwrap().to_string_lossy()),
                machine: toml.exists().then_some(toml),
                src,
            }
        })
        .collect()
}

/// The corpus on the machines of compiler/tests/corpus.rs: integer
/// coordinates in increments where the manifest says so; the Doosan's
/// arcs without a centre as lines.
pub fn corpus_cases(dir: &Path) -> Vec<Case> {
    let Some(corpus) = shared("corpus/public") else {
        return Vec::new();
    };
    let manifest = std::fs::read_to_string(corpus.join("MANIFEST.tsv")).unwrap();
    let mut cases = Vec::new();
    for line in manifest.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        let (file, features) = (cols[0], cols.get(6).copied().unwrap_or(""));
        let increment = features.contains("int-units-no-decimal");
        let doosan = file.starts_with("doosan-lynx300__");
        let mut toml = String::from("[machine]\n");
        if increment {
            toml.push_str("decimal_point = \"increment\"\n");
        }
        if doosan {
            toml.push_str("arc_without_center = \"line\"\n");
        }
        let path = dir.join(format!("m-{increment}-{doosan}.toml"));
        std::fs::write(&path, toml).unwrap();
        cases.push(Case {
            name: format!("corpus/{file}"),
            src: corpus.join(file),
            machine: Some(path),
        });
    }
    cases
}
