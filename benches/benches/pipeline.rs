//! Criterion group `pipeline`: issue #14's whole-pipeline measurements in
//! one process — source text compiled, the module written and loaded
//! again, run on the reference machine with its canon printed (to a
//! writer that discards it, as `gbvm run --emit canon > /dev/null`).
//! `peer/compare.sh` times the same programs as whole processes against
//! LinuxCNC's `rs274 -g`.

use benches::whole::{canon_lines, g1_blocks, macro_loop};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;

const G1_BLOCKS: usize = 200_000;
const LOOP_ITERATIONS: usize = 100_000;
/// The loop JIT as `gbvm run` has it by default.
const MODE: jit::Mode = jit::Mode::Auto;

fn pipeline(c: &mut Criterion) {
    let mut g = c.benchmark_group("pipeline");
    // About 0.7 s an iteration on a shared 2-core machine: 10 samples of
    // one iteration each.
    g.sample_size(10)
        .measurement_time(Duration::from_secs(12))
        .warm_up_time(Duration::from_secs(1));
    let g1 = g1_blocks(G1_BLOCKS);
    g.throughput(Throughput::Elements(G1_BLOCKS as u64));
    g.bench_function("g1_200k_compile_and_run_to_canon", |b| {
        b.iter(|| canon_lines(&g1, MODE))
    });
    let looped = macro_loop(LOOP_ITERATIONS);
    g.measurement_time(Duration::from_secs(8));
    g.throughput(Throughput::Elements(LOOP_ITERATIONS as u64));
    g.bench_function("macro_loop_100k_compile_and_run_to_canon", |b| {
        b.iter(|| canon_lines(&looped, MODE))
    });
    g.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
