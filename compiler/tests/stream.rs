//! A long plain program compiled a chunk at a time (`compiler::stream`)
//! gives the module and the diagnostics of the whole-file path, byte for
//! byte; a program that is not plain, or has an error, goes the
//! whole-file way.

use compiler::{compile, Options};
use std::path::Path;
use std::sync::Arc;

/// Options whose chunks are `chunk` bytes.
fn chunked(chunk: usize) -> Options {
    Options {
        chunk_bytes: chunk,
        ..Options::default()
    }
}

/// The whole-file path's result, as bytes and rendered diagnostics.
fn whole(name: &str, src: &[u8]) -> (Option<Vec<u8>>, String) {
    let c = compile(name, src, &chunked(usize::MAX));
    (c.module.as_ref().map(|m| m.to_bytes()), c.render())
}

/// The chunked path's result, when the program takes it.
fn in_chunks(name: &str, src: &[u8], chunk: usize) -> Option<(Option<Vec<u8>>, String)> {
    let c = compiler::stream::compile(name, &Arc::from(src), &chunked(chunk))?;
    Some((c.module.as_ref().map(|m| m.to_bytes()), c.render()))
}

/// Compares both ways on `src`; whether it took the chunked path.
fn same_both_ways(name: &str, src: &[u8], chunk: usize) -> bool {
    let Some(chunks) = in_chunks(name, src, chunk) else {
        return false;
    };
    let whole = whole(name, src);
    assert!(
        chunks.0.is_some(),
        "{name}: a chunked compile without a module"
    );
    assert_eq!(chunks.1, whole.1, "{name}: the diagnostics differ");
    assert!(chunks.0 == whole.0, "{name}: the modules differ");
    true
}

#[test]
fn every_plain_program_of_the_suites_compiles_the_same_in_chunks() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        root.join("../../shared/conformance"),
        root.join("../../shared/corpus/public"),
        root.join("../examples"),
    ];
    let (mut programs, mut chunked) = (0, 0);
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for path in entries.flatten().map(|e| e.path()) {
            let ext = path.extension().and_then(|e| e.to_str());
            if !matches!(ext, Some("nc" | "NC" | "txt" | "TXT")) {
                continue;
            }
            let src = std::fs::read(&path).expect("readable");
            let name = path.display().to_string();
            programs += 1;
            // Chunks of a line, and of a few lines (a file shorter than
            // its first chunk goes the whole-file way).
            let taken = [16, 100].map(|chunk| same_both_ways(&name, &src, chunk));
            chunked += usize::from(taken[0]);
        }
    }
    assert!(programs >= 130, "only {programs} programs found");
    // (Counted when written: the plain ones among conformance, corpus and
    // examples; a fall means programs stopped taking the path.)
    eprintln!("{chunked} of {programs} in chunks");
    assert!(
        chunked >= 40,
        "only {chunked} programs took the chunked path"
    );
}

/// A long program of moves, numbers, comments, feeds and M codes.
fn long_program(blocks: usize, last: &str) -> String {
    let mut src = String::from("%\nO0042 (LONG)\nG98 G00 X50 Z2 M03 S800\n");
    for i in 0..blocks {
        let z = -(i as f64) * 0.01;
        match i % 5 {
            0 => src.push_str(&format!(
                "N{} G01 X{:.3} Z{z:.3} F{}\n",
                i + 1,
                40.0 - z / 10.0,
                100 + i % 7
            )),
            1 => src.push_str(&format!("X{:.2} (STEP {i})\n", 39.0 + (i % 3) as f64)),
            2 => src.push_str(&format!("G02 X{:.1} Z{:.2} R20\n", 40.0, z - 1.0)),
            3 => src.push_str("M08\n"),
            _ => src.push_str(&format!("G00 Z{z:.3}\n")),
        }
    }
    src.push_str(last);
    src
}

#[test]
fn a_long_program_compiles_the_same_in_chunks() {
    // (The third: blocks after M30 never run, so no W101 either way.)
    for last in ["M30\n%\n", "G00 X60\n", "M30\nN70 G00 X99 Z9\n"] {
        let src = long_program(3_000, last);
        assert!(same_both_ways("long.nc", src.as_bytes(), 4_096), "{last:?}");
    }
    // Without an M30 it ends as the whole-file path ends it, with W101.
    let src = long_program(3_000, "G00 X60\n");
    let (_, text) = whole("long.nc", src.as_bytes());
    assert!(text.contains("W101"), "{text}");
    let src = long_program(3_000, "M30\nN70 G00 X99 Z9\n");
    let (_, text) = whole("long.nc", src.as_bytes());
    assert!(!text.contains("W101"), "{text}");
}

#[test]
fn a_program_that_is_not_plain_goes_the_whole_file_way() {
    let tails = [
        "#1=5\nG01 X#1\nM30\n",
        "M98 P1234\nM30\n",
        "G71 U1 R0.5\nG71 P1 Q2 U0.2 W0.1 F0.2\nN1 G00 X20\nN2 G01 Z-10\nG70 P1 Q2\nM30\n",
        "/ G00 X10\nM30\n",
        "O0043\nG00 X10\nM30\n",
        "G10 P1 X1 Z1\nM30\n",
    ];
    for tail in tails {
        let src = long_program(2_000, tail);
        assert!(
            in_chunks("t.nc", src.as_bytes(), 4_096).is_none(),
            "{tail:?}"
        );
        // Compiled the whole-file way, as before.
        let c = compile("t.nc", src.as_bytes(), &chunked(4_096));
        let reference = whole("t.nc", src.as_bytes());
        assert_eq!(c.render(), reference.1, "{tail:?}");
        assert!(c.module.map(|m| m.to_bytes()) == reference.0, "{tail:?}");
    }
}

#[test]
fn an_error_in_a_late_chunk_is_reported_as_the_whole_file_path_reports_it() {
    // A syntax error, a block rule (two X words), and a geometry error the
    // dry run finds (an arc of too small a radius).
    for (tail, code) in [
        ("G01 X10 Z=\nM30\n", "E"),
        ("G01 X10 X20\nM30\n", "E1011"),
        ("G02 X30 Z-40 R1\nM30\n", "E4001"),
    ] {
        let src = long_program(2_000, tail);
        assert!(
            in_chunks("e.nc", src.as_bytes(), 4_096).is_none(),
            "{tail:?}"
        );
        let last_line = src.lines().count() - 1;
        assert_eq!(first_error_line(&src, code), last_line, "{tail:?}");
    }
}

/// Compiles `src` (chunks allowed): no module, the whole-file path's
/// diagnostics, a first error whose code starts with `code`; its line.
fn first_error_line(src: &str, code: &str) -> usize {
    let c = compile("e.nc", src.as_bytes(), &chunked(4_096));
    let (_, reference) = whole("e.nc", src.as_bytes());
    assert!(c.module.is_none());
    assert_eq!(c.render(), reference);
    let (f, d) = c
        .diags
        .iter()
        .find(|(_, d)| d.is_error())
        .expect("an error");
    assert!(d.code.starts_with(code), "{}", d.code);
    c.files[*f].line_col(d.span.start).0
}

/// The chunked path parses a block's words once, in the dry run, and the
/// builder checks only those of the blocks the run did not reach: a block
/// after M30 is still checked, a T word's numbers too.
#[test]
fn a_block_the_dry_run_does_not_reach_is_checked_all_the_same() {
    for (tail, code) in [
        ("M30\nG01 X10 X20\n", "E1011"),
        ("M30\nG00 X10 Z5\nG01 X10 X20\nG00 X1\n", "E1011"),
        ("T9999\nM30\n", "E"),
    ] {
        first_error_line(&long_program(2_000, tail), code);
    }
}

/// Under nose-radius compensation an element waits for the next block,
/// across a chunk boundary where chunks are small (one or two lines of
/// 16 bytes): a warning about it names its own block in chunks as whole.
/// With `F0` no feed is in force; whole, W107 names the arc's line 9.
#[test]
fn a_warning_about_an_element_of_an_earlier_chunk_names_its_own_block() {
    let src = "O0091\nG99 M03 S1000\nT0101\nG00 X60 Z5\nG42 G00 X20 Z2\nG01 Z-10 F0\n\
               X30 Z-20\nZ-30\nG02 X40 Z-35 R5\nG01 X50\nZ-45\nX60\nG40 G00 X70 Z5\nM30\n";
    let (_, reference) = whole("c.nc", src.as_bytes());
    assert!(reference.contains("c.nc:9:1: warning[W107]"), "{reference}");
    for chunk in [16, 24, 40] {
        assert!(
            same_both_ways("c.nc", src.as_bytes(), chunk),
            "chunks of {chunk} bytes: not the chunked path"
        );
    }
}
