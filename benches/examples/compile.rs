//! Parses or compiles one generated program, for profiling the compiler
//! under callgrind or perf:
//! `compile [short|arcs|moves] [blocks] [parse|compile]`.

use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let kind = args.first().map_or("short", String::as_str);
    let blocks = args.get(1).and_then(|n| n.parse().ok()).unwrap_or(20_000);
    let what = args.get(2).map_or("compile", String::as_str);
    let src = match kind {
        "arcs" => benches::arcs(blocks),
        "moves" => benches::moves(blocks),
        _ => benches::short_segments(blocks),
    };
    if what == "parse" {
        let (ast, diags) = grammar::parse(black_box(src.as_bytes()));
        println!("{} lines, {} diagnostics", ast.lines.len(), diags.len());
    } else {
        let m = benches::build(black_box(&src));
        println!("{} instructions", m.code.len());
    }
}
