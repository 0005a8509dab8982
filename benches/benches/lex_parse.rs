//! Lexing + parsing throughput (`grammar::parse`), next to the `gcode`
//! crate on the same generated text so the ratio shows in one run.
//!
//! Inputs: a generated program of 1M blocks (numbered `G01 X.. Z.. F..`
//! moves with a few rapids and M/S/T words), the same program with a macro
//! statement every few blocks, and the concatenated public corpus.

use benches::Lcg;
use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use std::fmt::Write;
use std::hint::black_box;
use std::time::Duration;

const BLOCKS: usize = 1_000_000;

/// A coordinate with three decimals, as a CAM system writes it.
fn coord(rng: &mut Lcg, max: u64) -> String {
    let v = rng.next_u64() % (max * 1000);
    let sign = if rng.next_u64().is_multiple_of(4) {
        "-"
    } else {
        ""
    };
    format!("{sign}{}.{:03}", v / 1000, v % 1000)
}

/// Mostly feed moves; with `macros`, every fifth block is a macro statement.
fn generate(macros: bool) -> String {
    let mut rng = Lcg(0x9e37_79b9_7f4a_7c15);
    let mut out = String::with_capacity(BLOCKS * 32);
    out.push_str("%\nO0001 (GENERATED)\n");
    for i in 0..BLOCKS {
        let n = (i % 99_999) + 1;
        if macros && i % 5 == 4 {
            match (i / 5) % 4 {
                0 => writeln!(
                    out,
                    "N{n} #{} = #{} + {} * 2",
                    100 + i % 50,
                    101 + i % 40,
                    coord(&mut rng, 10)
                ),
                1 => writeln!(
                    out,
                    "N{n} IF [#{} GT {}] GOTO {}",
                    100 + i % 50,
                    coord(&mut rng, 100),
                    n + 1
                ),
                2 => writeln!(out, "N{n} #1 = SIN[#2 * 3.] + [#3 - #4] / 2"),
                _ => writeln!(
                    out,
                    "N{n} G01 X[#100 + {}] Z-#101 F0.2",
                    coord(&mut rng, 50)
                ),
            }
        } else {
            match i % 50 {
                0 => writeln!(
                    out,
                    "N{n} G00 X{} Z{} T0101 M08",
                    coord(&mut rng, 100),
                    coord(&mut rng, 5)
                ),
                25 => writeln!(out, "N{n} G97 S1200 M03"),
                _ => writeln!(
                    out,
                    "N{n} G01 X{} Z{} F0.{}",
                    coord(&mut rng, 100),
                    coord(&mut rng, 200),
                    1 + rng.next_u64() % 3
                ),
            }
        }
        .expect("writing to a String cannot fail");
    }
    out.push_str("M30\n%\n");
    out
}

/// Every public corpus file, one after the other.
fn corpus() -> Vec<u8> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/corpus/public");
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    paths.sort();
    let mut all = Vec::new();
    for p in paths {
        if p.file_name().is_some_and(|n| n != "MANIFEST.tsv") {
            if let Ok(bytes) = std::fs::read(&p) {
                all.extend_from_slice(&bytes);
                all.push(b'\n');
            }
        }
    }
    all
}

fn lex_parse(c: &mut Criterion) {
    let plain = generate(false);
    let mixed = generate(true);
    let corpus = corpus();
    eprintln!(
        "lex_parse inputs: moves {} bytes / {} blocks, macros {} bytes / {} blocks, corpus {} bytes / {} lines",
        plain.len(),
        plain.lines().count(),
        mixed.len(),
        mixed.lines().count(),
        corpus.len(),
        corpus.split(|&b| b == b'\n').count(),
    );

    // Both parsers must accept the generated text, or the race means nothing.
    for (name, src) in [("moves", &plain), ("macros", &mixed)] {
        let (ast, diags) = grammar::parse(src.as_bytes());
        assert!(diags.is_empty(), "{name}: {:?}", diags.first());
        assert_eq!(ast.lines.len(), BLOCKS + 4, "{name}");
    }
    let program = gcode::parse(&plain).expect("gcode accepts the generated moves");
    assert!(program.blocks.len() >= BLOCKS);

    let mut group = c.benchmark_group("lex_parse");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));

    group.throughput(Throughput::Bytes(plain.len() as u64));
    group.bench_with_input(BenchmarkId::new("grammar", "moves_1M"), &plain, |b, src| {
        b.iter(|| grammar::parse(black_box(src.as_bytes())))
    });
    group.bench_with_input(BenchmarkId::new("gcode", "moves_1M"), &plain, |b, src| {
        b.iter(|| gcode::parse(black_box(src)).map(|p| p.blocks.len()))
    });

    group.throughput(Throughput::Bytes(mixed.len() as u64));
    group.bench_with_input(
        BenchmarkId::new("grammar", "macros_1M"),
        &mixed,
        |b, src| b.iter(|| grammar::parse(black_box(src.as_bytes()))),
    );

    if corpus.is_empty() {
        eprintln!("lex_parse: corpus folder not found, skipping the corpus bench");
    } else {
        group.throughput(Throughput::Bytes(corpus.len() as u64));
        group.bench_with_input(BenchmarkId::new("grammar", "corpus"), &corpus, |b, src| {
            b.iter(|| grammar::parse(black_box(src)))
        });
    }
    group.finish();
}

criterion_group!(benches, lex_parse);
criterion_main!(benches);
