//! Parses or compiles one generated program, for profiling the compiler
//! under callgrind or perf, and prints the fastest of `runs` timings:
//! `compile [short|arcs|moves|file:PATH] [blocks] [parse|compile] [runs]`.

use std::hint::black_box;
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let kind = args.first().map_or("short", String::as_str);
    let blocks = args.get(1).and_then(|n| n.parse().ok()).unwrap_or(20_000);
    let what = args.get(2).map_or("compile", String::as_str);
    let runs = args.get(3).and_then(|n| n.parse().ok()).unwrap_or(1);
    let src = match kind {
        "arcs" => benches::arcs(blocks),
        "moves" => benches::moves(blocks),
        path if path.starts_with("file:") => {
            std::fs::read_to_string(&path[5..]).unwrap_or_default()
        }
        _ => benches::short_segments(blocks),
    };
    let mut best = Duration::MAX;
    for _ in 0..runs {
        let t0 = Instant::now();
        if what == "parse" {
            let (ast, diags) = grammar::parse(black_box(src.as_bytes()));
            black_box((ast.lines.len(), diags.len()));
        } else {
            black_box(benches::build(black_box(&src)).code.len());
        }
        best = best.min(t0.elapsed());
    }
    let per_block = best.as_secs_f64() * 1e9 / blocks as f64;
    println!("{kind} {what}: best of {runs} {best:?}, {per_block:.0} ns/block");
}
