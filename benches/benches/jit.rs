//! Criterion group `jit` (issue #17): the macro programs run with the loop
//! JIT off and on (compiled at a loop's first round), and the time to
//! compile one loop.
//!
//! - `numeric_1M_*`: the numeric loop of `whole::numeric_loop`, 10⁶
//!   rounds, one move at the end; compile + run to canon in one process.
//! - `macro_loop_100k_*`: issue #14's loop (4 assignments and a G01 per
//!   round), compile + run to canon.
//! - `ellipse_*`: an ellipse of 3 601 points by a macro (`macro.rs`'s).
//! - `compile_*`: Cranelift compiling one loop of the ellipse program and
//!   of the numeric loop (the module made once), quickly as a loop that has
//!   just become hot is, and `_optimised` as one that has run long.

use benches::build;
use benches::whole::{canon_lines, macro_loop, numeric_loop, ELLIPSE};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use std::time::Duration;

const NUMERIC_ROUNDS: usize = 1_000_000;
const LOOP_ROUNDS: usize = 100_000;

fn runs(c: &mut Criterion) {
    let mut g = c.benchmark_group("jit");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(5))
        .warm_up_time(Duration::from_secs(1));
    let modes = [("off", jit::Mode::Off), ("on", jit::Mode::Always)];
    let programs = [
        ("numeric_1M", numeric_loop(NUMERIC_ROUNDS), NUMERIC_ROUNDS),
        ("macro_loop_100k", macro_loop(LOOP_ROUNDS), LOOP_ROUNDS),
        ("ellipse_3601", ELLIPSE.to_string(), 3601),
    ];
    for (name, src, rounds) in &programs {
        g.throughput(Throughput::Elements(*rounds as u64));
        for (mode_name, mode) in modes {
            g.bench_function(format!("{name}_{mode_name}"), |b| {
                b.iter(|| canon_lines(src, mode))
            });
        }
    }
    g.finish();
}

/// Compile time of one loop, as a run pays it: into a JIT module of its
/// own (made, and dropped, outside the timing; one module that took every
/// iteration's code would grow to thousands of functions, which no run
/// has).
fn compile(c: &mut Criterion) {
    let mut g = c.benchmark_group("jit");
    g.sample_size(50).measurement_time(Duration::from_secs(5));
    for (name, src) in [
        ("ellipse", ELLIPSE.to_string()),
        ("numeric", numeric_loop(10)),
    ] {
        let module = build(&src);
        let Some(&(head, tail)) = jit::loops(&module).first() else {
            panic!("the {name} program has no loop");
        };
        for (level, suffix) in [(jit::Level::Quick, ""), (jit::Level::Full, "_optimised")] {
            let fresh = || match jit::Compiler::new(level) {
                Ok(c) => c,
                Err(e) => panic!("no JIT here: {e}"),
            };
            g.bench_function(format!("compile_{name}_loop{suffix}"), |b| {
                b.iter_batched_ref(
                    fresh,
                    |compiler| compiler.compile(&module, head, tail),
                    BatchSize::PerIteration,
                )
            });
        }
    }
    g.finish();
}

criterion_group!(benches, runs, compile);
criterion_main!(benches);
