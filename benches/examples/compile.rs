//! Parses, compiles or runs one generated program, for profiling under
//! callgrind or perf, and prints the fastest, the median and the slowest
//! of `runs` timings:
//! `compile [short|arcs|moves|file:PATH] [blocks] [parse|compile|vm|plan|vm_plan[_split]|e2e[_split]|ticks] [runs]`
//! (`vm` compiles, then runs the VM to a sink that counts; `plan`,
//! `vm_plan` and `e2e` are the `runtime` bench's pipelines, `_split` with
//! the interpreter and the planning on two threads; `ticks` runs
//! 100 000 interpolation periods of the program's moves).

use benches::pipeline;
use runtime::planner::Planner;
use runtime::Config;
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
    let mut planner = Planner::new(&Config::default());
    let cmds = match what {
        "plan" | "ticks" => pipeline::commands(&src),
        _ => Vec::new(),
    };
    let mut ticker = (what == "ticks").then(|| pipeline::Ticker::new(cmds.clone()));
    let module = match what {
        "vm_plan" | "vm_plan_split" => Some(benches::build(&src)),
        _ => None,
    };
    let mut times: Vec<Duration> = Vec::new();
    for _ in 0..runs {
        let m = module.clone();
        let t0 = Instant::now();
        match (what, m) {
            ("vm", _) => {
                let m = benches::build(&src);
                let mut vm = vm::Vm::new(m, nc::Machine::reference());
                let mut c = benches::Count::default();
                black_box(vm.run(&mut c));
                black_box(c.0);
            }
            ("parse", _) => {
                let (ast, diags) = grammar::parse(black_box(src.as_bytes()));
                black_box((ast.lines.len(), diags.len()));
            }
            ("plan", _) => {
                black_box(pipeline::plan_all(&mut planner, black_box(&cmds)));
            }
            ("ticks", _) => {
                if let Some(t) = ticker.as_mut() {
                    ticks(t);
                }
            }
            ("vm_plan", Some(m)) => {
                black_box(pipeline::vm_plan(m, &mut planner));
            }
            ("vm_plan_split", Some(m)) => {
                black_box(pipeline::vm_plan_split(m));
            }
            ("e2e_split", _) => {
                black_box(pipeline::end_to_end_split(black_box(&src)));
            }
            ("e2e", _) => {
                black_box(pipeline::end_to_end(black_box(&src), &mut planner));
            }
            _ => {
                black_box(benches::build(black_box(&src)).code.len());
            }
        }
        times.push(t0.elapsed());
    }
    times.sort();
    let per_block = |t: Option<&Duration>| t.map_or(0.0, |t| t.as_secs_f64() * 1e9 / blocks as f64);
    let best = times.first().copied().unwrap_or_default();
    println!(
        "{kind} {what}: best of {runs} {best:?}, {:.0} ns/block (median {:.0}, slowest {:.0})",
        per_block(times.first()),
        per_block(times.get(times.len() / 2)),
        per_block(times.last()),
    );
}

/// 100 000 periods, the queue refilled between batches as in the bench.
fn ticks(t: &mut pipeline::Ticker) {
    for _ in 0..200 {
        for _ in 0..500 {
            black_box(t.e.tick());
        }
        if t.low() {
            t.refill();
        }
    }
}
