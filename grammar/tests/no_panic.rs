//! `parse` must never panic: random bytes, random G-code-like text, and
//! random mutations of the corpus and conformance programs. Every span it
//! returns must lie inside the input, and every diagnostic must render.

use proptest::prelude::*;
use std::path::Path;

/// Parses and checks what can be checked of any result.
fn check(src: &[u8]) {
    let (ast, diags) = grammar::parse(src);
    let len = src.len() as u32;
    for line in &ast.lines {
        let span = line.span();
        assert!(
            span.start <= span.end && span.end <= len,
            "{span:?} outside {len}"
        );
    }
    let file = grammar::SourceFile::new("fuzz.nc", src);
    for d in &diags {
        assert!(d.span.start <= d.span.end && d.span.end <= len, "{d:?}");
        assert!(!file.render(d).is_empty());
    }
}

/// The corpus and conformance programs (empty when the folders are absent).
fn seeds() -> Vec<Vec<u8>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared");
    let mut seeds = Vec::new();
    for dir in ["corpus/public", "conformance"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<_> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        for p in paths {
            let keep = p.extension().is_some_and(|x| x == "nc") || dir == "corpus/public";
            if keep && p.file_name().is_some_and(|n| n != "MANIFEST.tsv") {
                if let Ok(bytes) = std::fs::read(&p) {
                    seeds.push(bytes);
                }
            }
        }
    }
    if seeds.is_empty() {
        seeds.push(
            b"O0001\nN10 G01 X10 Z-5 F0.2\n#1=[#2+1]*SIN[30]\nIF[#1GT0]GOTO10\nM30\n".to_vec(),
        );
    }
    seeds
}

/// Bytes that G-code is made of, so that random text gets past the lexer.
const ALPHABET: &[u8] = b"GXZUWNOFMSTPQRIKD#[]=+-*/.,:;()% \t\r\n0123456789EQNTLGAORXODIFTHENWHILEENDGOTOSINATAN\x1a\xe9";

#[derive(Debug, Clone)]
enum Mutation {
    Insert(usize, u8),
    Delete(usize),
    Replace(usize, u8),
    SwapLines(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let byte = prop_oneof![any::<u8>(), prop::sample::select(ALPHABET)];
    prop_oneof![
        (any::<usize>(), byte.clone()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        any::<usize>().prop_map(Mutation::Delete),
        (any::<usize>(), byte).prop_map(|(i, b)| Mutation::Replace(i, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Mutation::SwapLines(i, j)),
    ]
}

fn apply(mut src: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let n = src.len();
        match *m {
            Mutation::Insert(i, b) => src.insert(i % (n + 1), b),
            Mutation::Delete(i) if n > 0 => {
                src.remove(i % n);
            }
            Mutation::Replace(i, b) if n > 0 => src[i % n] = b,
            Mutation::SwapLines(i, j) => {
                let mut lines: Vec<Vec<u8>> =
                    src.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
                let k = lines.len();
                lines.swap(i % k, j % k);
                src = lines.join(&b'\n');
            }
            _ => {}
        }
    }
    src
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_bytes(src in prop::collection::vec(any::<u8>(), 0..400)) {
        check(&src);
    }

    #[test]
    fn random_gcode_text(src in prop::collection::vec(prop::sample::select(ALPHABET), 0..400)) {
        check(&src);
    }

    #[test]
    fn mutated_programs(pick in any::<usize>(), mutations in prop::collection::vec(mutation(), 1..12)) {
        let seeds = seeds();
        let src = apply(seeds[pick % seeds.len()].clone(), &mutations);
        check(&src);
    }
}

#[test]
fn hostile_shapes() {
    // Deep or long constructs that could exhaust the stack of a recursive
    // walk: rejected (or bounded) by the limits of the lexer.
    let deep = format!("#1={}1{}", "[".repeat(5000), "]".repeat(5000));
    check(deep.as_bytes());
    let unary = format!("#1={}1", "-".repeat(100_000));
    check(unary.as_bytes());
    let chain = format!("#1=1{}", "+1".repeat(100_000));
    check(chain.as_bytes());
    let hashes = format!("#1={}1", "#".repeat(100_000));
    check(hashes.as_bytes());
    let words = "X1 ".repeat(100_000);
    check(words.as_bytes());
    check(&[b'('; 10_000]);
    check(&[b';'; 10_000]);
    check(&[0x1a; 3]);
    check(b"");
}
