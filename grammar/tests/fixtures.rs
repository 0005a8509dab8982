//! One snapshot per fixture: the syntax tree of every `data/ok/*.nc` (plus
//! any warning), the rendered diagnostics of every `data/err/*.nc`. Also
//! checks that every parent span encloses the spans of its children.

use grammar::ast::*;
use grammar::{Severity, SourceFile, Span};
use std::path::{Path, PathBuf};

fn fixtures(kind: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(kind);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no fixtures in {}", dir.display());
    files
}

fn name(path: &Path) -> String {
    path.file_stem().unwrap().to_string_lossy().into_owned()
}

/// The diagnostics as `gbcc` prints them, without colour.
fn rendered(kind: &str, path: &Path, bytes: &[u8], diags: &[grammar::Diagnostic]) -> String {
    let file = SourceFile::new(format!("{kind}/{}.nc", name(path)), bytes);
    diags
        .iter()
        .map(|d| file.render(d))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn ok_fixtures() {
    for path in fixtures("ok") {
        let bytes = std::fs::read(&path).unwrap();
        let (ast, diags) = grammar::parse(&bytes);
        let errors: Vec<_> = diags.iter().filter(|d| d.is_error()).collect();
        assert!(errors.is_empty(), "{}: {errors:#?}", path.display());
        assert!(!ast.lines.is_empty(), "{}: empty tree", path.display());
        let mut snap = format!("{ast:#?}");
        if !diags.is_empty() {
            snap.push_str("\n\n");
            snap.push_str(&rendered("ok", &path, &bytes, &diags));
        }
        insta::assert_snapshot!(format!("ok__{}", name(&path)), snap);
    }
}

#[test]
fn err_fixtures() {
    for path in fixtures("err") {
        let bytes = std::fs::read(&path).unwrap();
        let (_, diags) = grammar::parse(&bytes);
        assert!(
            diags.iter().any(|d| d.severity == Severity::Error),
            "{}: no error",
            path.display()
        );
        // The file name says the code every error of the file has.
        let stem = name(&path);
        if let Some(code) = stem.split('_').next().filter(|c| c.starts_with('e')) {
            for d in &diags {
                assert_eq!(d.code.to_lowercase(), code, "{}: {d:?}", path.display());
            }
        }
        insta::assert_snapshot!(
            format!("err__{stem}"),
            rendered("err", &path, &bytes, &diags)
        );
    }
}

/// Asserts that `outer` encloses `inner`, naming what they are.
fn encloses(outer: Span, inner: Span, what: &str, path: &Path) {
    assert!(
        outer.contains(inner),
        "{}: {what}: {inner:?} not inside {outer:?}",
        path.display()
    );
}

fn check_expr(e: &Expr, p: &Path) {
    let s = e.span();
    assert!(s.start < s.end, "{}: empty span {e:?}", p.display());
    let index;
    let children: Vec<&Expr> = match e {
        Expr::Num(_) => vec![],
        Expr::Var(v) => {
            index = v.index.expr();
            vec![&*index]
        }
        Expr::Paren { inner, .. } => vec![inner],
        Expr::Unary { operand, .. } => vec![operand],
        Expr::Binary { lhs, rhs, .. } => vec![lhs, rhs],
        Expr::Call { arg, .. } => vec![arg],
        Expr::Atan2 { y, x, .. } => vec![y, x],
    };
    for c in children {
        encloses(s, c.span(), "expression", p);
        check_expr(c, p);
    }
}

fn check_cond(c: &Cond, p: &Path) {
    match c {
        Cond::Rel { lhs, rhs, span, .. } => {
            for e in [lhs, rhs] {
                encloses(*span, e.span(), "condition operand", p);
                check_expr(e, p);
            }
        }
        Cond::Logic { lhs, rhs, span, .. } => {
            for c in [lhs, rhs] {
                encloses(*span, c.span(), "combined condition", p);
                check_cond(c, p);
            }
        }
    }
}

fn check_stmt(s: &Stmt, p: &Path) {
    let span = s.span();
    match s {
        Stmt::Assign { target, value, .. } => {
            encloses(span, target.span, "assignment target", p);
            let index = target.index.expr();
            encloses(target.span, index.span(), "variable index", p);
            check_expr(&index, p);
            encloses(span, value.span(), "assigned value", p);
            check_expr(value, p);
        }
        Stmt::Goto { target, .. } => {
            encloses(span, target.span(), "GOTO target", p);
            check_expr(target, p);
        }
        Stmt::IfGoto { cond, target, .. } => {
            encloses(span, cond.span(), "IF condition", p);
            check_cond(cond, p);
            encloses(span, target.span(), "GOTO target", p);
            check_expr(target, p);
        }
        Stmt::IfThen { cond, then, .. } => {
            encloses(span, cond.span(), "IF condition", p);
            check_cond(cond, p);
            encloses(span, then.span(), "THEN statement", p);
            check_stmt(then, p);
        }
        Stmt::While { cond, label, .. } => {
            encloses(span, cond.span(), "WHILE condition", p);
            check_cond(cond, p);
            encloses(span, label.span, "DO label", p);
        }
        Stmt::Do { label, .. } | Stmt::End { label, .. } => encloses(span, label.span, "label", p),
    }
}

fn check_block(b: &Block, p: &Path) {
    if let Some(d) = &b.delete {
        encloses(b.span, d.span, "block delete", p);
    }
    if let Some(s) = &b.seq {
        encloses(b.span, s.span, "sequence number", p);
    }
    for c in &b.comments {
        encloses(b.span, c.span, "comment", p);
    }
    match &b.body {
        Body::Words(words) => {
            for w in words {
                encloses(b.span, w.span, "word", p);
                match &w.value {
                    Value::Number(n) => encloses(w.span, n.span, "word value", p),
                    Value::Expr(e) => {
                        encloses(w.span, e.span(), "word value", p);
                        check_expr(e, p);
                    }
                }
            }
        }
        Body::Stmt(s) => {
            encloses(b.span, s.span(), "statement", p);
            check_stmt(s, p);
        }
    }
}

#[test]
fn parent_spans_enclose_children() {
    for path in fixtures("ok") {
        let bytes = std::fs::read(&path).unwrap();
        let (ast, _) = grammar::parse(&bytes);
        let mut last_end = 0;
        for line in &ast.lines {
            let span = match line {
                Line::Percent(s) => *s,
                Line::ProgramStart(ps) => {
                    for c in &ps.comments {
                        encloses(ps.span, c.span, "O-line comment", &path);
                    }
                    ps.span
                }
                Line::Block(b) => {
                    check_block(b, &path);
                    b.span
                }
            };
            assert!(
                span.end as usize <= bytes.len(),
                "{}: {span:?}",
                path.display()
            );
            assert!(
                span.start >= last_end,
                "{}: lines out of order",
                path.display()
            );
            last_end = span.end;
        }
    }
}
