//! The user's guide holds together: every relative link of README.md and
//! docs/*.md names a file in the repository, and nothing points outside it
//! (the README used to send readers to a spec folder beside the checkout).

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The targets of `[text](target)` links, anchors cut off.
fn links(md: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = md;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        let end = rest.find(')').unwrap_or(rest.len());
        let target = rest[..end].split('#').next().unwrap_or("");
        if !target.is_empty() && !target.contains("://") {
            out.push(target.to_string());
        }
        rest = &rest[end..];
    }
    out
}

fn check(file: &Path, broken: &mut Vec<String>) {
    let text = std::fs::read_to_string(file).unwrap();
    let base = file.parent().unwrap();
    for l in links(&text) {
        let target = base.join(&l);
        let inside = target
            .canonicalize()
            .is_ok_and(|t| t.starts_with(root().canonicalize().unwrap()));
        if !inside {
            broken.push(format!("{}: {l}", file.display()));
        }
    }
    assert!(
        !text.contains("../shared/spec"),
        "{} points to the spec folder outside the repository",
        file.display()
    );
}

#[test]
fn every_link_of_the_guide_resolves_inside_the_repository() {
    let mut broken = Vec::new();
    check(&root().join("README.md"), &mut broken);
    let mut n = 0;
    for e in std::fs::read_dir(root().join("docs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "md") {
            check(&p, &mut broken);
            n += 1;
        }
    }
    // getting-started, manual, language, formats, machine, embedding and
    // the index at least.
    assert!(n >= 7, "{n} documents");
    // diagnostics.md is written beside this guide; until it lands, the
    // index's link to it is the one allowed gap.
    broken.retain(|b| {
        !b.ends_with(": diagnostics.md") || root().join("docs/diagnostics.md").exists()
    });
    assert!(broken.is_empty(), "broken links: {broken:#?}");
}

#[test]
fn links_are_found_with_their_anchors_cut() {
    assert_eq!(
        links("see [a](x.md), [b](y.md#part) and [c](https://e.org)"),
        ["x.md", "y.md"]
    );
}
