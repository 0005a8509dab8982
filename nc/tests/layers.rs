//! The layer order of the kernel (nc/src/lib.rs): every `crate::…`,
//! `super::…` and `self::…` path in a module of a layer must name a module
//! of the same layer or of a layer below. A circle between modules of
//! different layers needs an edge that points up, so this check also rules
//! out such circles.

use std::fs;
use std::path::{Path, PathBuf};

/// The layers from the bottom up.
const LAYERS: [&str; 5] = ["base", "block", "modal", "plan", "exec"];

fn rank(segment: &str) -> Option<usize> {
    LAYERS.iter().position(|&l| l == segment)
}

/// The source with comments, strings and character literals blanked out,
/// so that neither a path in a doc comment nor a brace in a format string
/// counts.
fn code_only(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let skip_to = |out: &mut String, from: usize, to: usize| {
        for &ch in &c[from..to] {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    while i < c.len() {
        let rest = &c[i..];
        let end = if rest.starts_with(&['/', '/']) {
            rest.iter()
                .position(|&ch| ch == '\n')
                .map_or(c.len(), |n| i + n)
        } else if rest.starts_with(&['/', '*']) {
            let close =
                (i + 2..c.len().saturating_sub(1)).find(|&j| c[j] == '*' && c[j + 1] == '/');
            close.map_or(c.len(), |j| j + 2)
        } else if rest.starts_with(&['r', '#']) || rest.starts_with(&['r', '"']) {
            let hashes = rest[1..].iter().take_while(|&&ch| ch == '#').count();
            let open = i + 1 + hashes;
            if c.get(open) != Some(&'"') {
                out.push(c[i]);
                i += 1;
                continue;
            }
            let closing: Vec<char> = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            (open + 1..c.len())
                .find(|&j| c[j..].starts_with(&closing))
                .map_or(c.len(), |j| j + closing.len())
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            j + 1
        } else if c[i] == '\'' && (c.get(i + 1) == Some(&'\\') || c.get(i + 2) == Some(&'\'')) {
            // A character literal; a lifetime (`'a`) has no closing quote.
            let mut j = i + 1;
            while j < c.len() && c[j] != '\'' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            j + 1
        } else {
            out.push(c[i]);
            i += 1;
            continue;
        };
        let end = end.min(c.len());
        skip_to(&mut out, i, end);
        i = end;
    }
    out
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    Punct(char),
    PathSep,
}

fn tokens(code: &str) -> Vec<Tok> {
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        if c[i].is_alphanumeric() || c[i] == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(c[start..i].iter().collect()));
        } else if c[i] == ':' && c.get(i + 1) == Some(&':') {
            out.push(Tok::PathSep);
            i += 2;
        } else {
            if !c[i].is_whitespace() {
                out.push(Tok::Punct(c[i]));
            }
            i += 1;
        }
    }
    out
}

fn ident(t: Option<&Tok>) -> Option<&str> {
    match t {
        Some(Tok::Ident(s)) => Some(s),
        _ => None,
    }
}

/// The first segment of each item of a `{…}` group starting at `toks[at]`.
fn group_heads(toks: &[Tok], at: usize) -> Vec<String> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut expect_head = true;
    for t in &toks[at..] {
        match t {
            Tok::Punct('{') => {
                depth += 1;
                expect_head = depth == 1;
            }
            Tok::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            Tok::Punct(',') if depth == 1 => expect_head = true,
            Tok::Ident(s) if expect_head && depth == 1 => {
                heads.push(s.clone());
                expect_head = false;
            }
            Tok::Punct('*') if expect_head && depth == 1 => {
                heads.push("*".into());
                expect_head = false;
            }
            _ => {}
        }
    }
    heads
}

/// The module path of a source file under `src`: `exec/comp/mod.rs` →
/// `[exec, comp]`, `base/geom.rs` → `[base, geom]`, `lib.rs` → `[]`.
fn module_of(rel: &Path) -> Vec<String> {
    let mut segs: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if matches!(segs.last().map(String::as_str), Some("mod" | "lib")) {
        segs.pop();
    }
    segs
}

/// Every path of `src` (the file of module `module`) that leaves its layer
/// upwards or goes through the crate root, as messages.
fn violations(module: &[String], src: &str) -> Vec<String> {
    let Some(own) = module.first().and_then(|m| rank(m)) else {
        return Vec::new(); // lib.rs: the root may re-export any layer
    };
    let toks = tokens(&code_only(src));
    // Inline modules (`mod tests { … }`) with the depth of their brace.
    let mut stack: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut bad = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth = depth.saturating_sub(1);
                if stack.last().is_some_and(|&(_, d)| d == depth) {
                    stack.pop();
                }
            }
            Tok::Ident(m) if m == "mod" => {
                if let (Some(name), Some(Tok::Punct('{'))) =
                    (ident(toks.get(i + 1)), toks.get(i + 2))
                {
                    stack.push((name.to_string(), depth));
                }
            }
            Tok::Ident(root)
                if matches!(root.as_str(), "crate" | "super" | "self")
                    && toks.get(i + 1) == Some(&Tok::PathSep) =>
            {
                let mut here: Vec<String> = module.to_vec();
                here.extend(stack.iter().map(|(n, _)| n.clone()));
                let mut base = if root == "crate" {
                    Vec::new()
                } else {
                    here.clone()
                };
                if root == "super" {
                    base.pop();
                }
                let mut j = i + 2;
                // Further `super::` steps.
                while ident(toks.get(j)) == Some("super") && toks.get(j + 1) == Some(&Tok::PathSep)
                {
                    base.pop();
                    j += 2;
                }
                let heads = match (base.first(), toks.get(j)) {
                    (Some(first), _) => vec![first.clone()],
                    (None, Some(Tok::Punct('{'))) => group_heads(&toks, j),
                    (None, Some(Tok::Ident(s))) => vec![s.clone()],
                    (None, _) => vec!["*".into()],
                };
                for h in heads {
                    match rank(&h) {
                        Some(r) if r <= own => {}
                        Some(_) => bad.push(format!(
                            "{}: `{root}::` path into the higher layer `{h}`",
                            module.join("::")
                        )),
                        None => bad.push(format!(
                            "{}: `{root}::{h}` reaches past the layers through the crate root",
                            module.join("::")
                        )),
                    }
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    bad
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("the nc sources are readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_import_points_to_the_same_or_a_lower_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    files.sort();
    let mut bad = Vec::new();
    let mut seen_layers = [false; LAYERS.len()];
    for f in &files {
        let rel = f.strip_prefix(&src).expect("under src");
        let module = module_of(rel);
        match module.first().map(|m| rank(m)) {
            Some(Some(r)) => seen_layers[r] = true,
            Some(None) => bad.push(format!("{} is in no layer", rel.display())),
            None => {}
        }
        let text = fs::read_to_string(f).expect("a source file is UTF-8");
        bad.extend(violations(&module, &text));
    }
    assert!(files.len() > 40, "found only {} source files", files.len());
    assert_eq!(seen_layers, [true; 5], "every layer has a module");
    assert!(bad.is_empty(), "layer order broken:\n{}", bad.join("\n"));
}

fn m(path: &str) -> Vec<String> {
    path.split("::").map(String::from).collect()
}

#[test]
fn an_upward_import_is_found() {
    let v = violations(&m("base::geom"), "use crate::exec::state::State;\n");
    assert_eq!(v.len(), 1, "{v:?}");
    let v = violations(&m("plan::elem"), "use crate::{base::point::Pt, exec::Nc};");
    assert_eq!(
        v,
        ["plan::elem: `crate::` path into the higher layer `exec`"]
    );
    // `super::super` from modal::x climbs to the root, then into exec.
    let v = violations(&m("modal::x"), "fn f() { super::super::exec::run() }");
    assert_eq!(v.len(), 1, "{v:?}");
    // A path through the root's re-exports bypasses the layers.
    let v = violations(&m("block"), "use crate::state::State;");
    assert_eq!(v.len(), 1, "{v:?}");
}

#[test]
fn downward_and_local_paths_pass() {
    let src = r#"
        //! See `crate::exec::Nc` in the docs: not an import.
        use crate::base::geom::Element;
        use super::elem::dot;
        const S: &str = "crate::exec::Nc {";
        fn f<'a>(x: &'a str) -> char { let _ = '{'; 'x' }
        #[cfg(test)]
        mod tests {
            use super::*;
            use crate::block::Parsed;
        }
    "#;
    assert_eq!(violations(&m("plan::corner"), src), Vec::<String>::new());
    // `super::*` of a test module inside block/mod.rs is the block module.
    let v = violations(&m("block"), "mod tests { use super::*; }");
    assert!(v.is_empty(), "{v:?}");
    // The same from the layer module itself would name the root.
    let v = violations(&m("block"), "use super::*;");
    assert_eq!(v.len(), 1, "{v:?}");
}
