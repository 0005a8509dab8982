//! The interpolation runtime (`runtime` crate): planning throughput
//! alone (`plan`), parse + VM + plan end to end (`parse_vm_plan`), the
//! same from a compiled module (`vm_plan`), both again with the controller
//! split in two threads (`…_split`: the interpreter on one, the planning
//! on the other), and the cost of one
//! interpolation period (`period`), on generated short-segment and
//! arc-heavy programs, and for the period a thread-heavy one (G92
//! passes: spindle-synchronised periods, run-outs, rapids back); and the
//! trace's CSV lines (`trace_csv`, in work coordinates and in counts).
//!
//! Targets: plan ≥ 5 M blocks/s, end to end ≥ 1 M blocks/s, one period
//! ≤ 100 ns mean. The distribution of single periods (worst included)
//! is printed on stderr.

use benches::pipeline::{
    commands, end_to_end, end_to_end_split, plan_all, spindle_commands, vm_plan, vm_plan_split,
    Ticker,
};
use benches::{arcs, build as module, short_segments, threads};
use criterion::{
    criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use runtime::planner::Planner;
use runtime::Config;
use std::hint::black_box;
use std::time::{Duration, Instant};

const BLOCKS: usize = 200_000;

fn runtime_benches(c: &mut Criterion) {
    let short = short_segments(BLOCKS);
    let arc = arcs(BLOCKS);
    let short_cmds = commands(&short);
    let arc_cmds = commands(&arc);
    eprintln!(
        "runtime inputs: short segments {} moves, arcs {} moves",
        short_cmds.len(),
        arc_cmds.len()
    );

    let mut group = c.benchmark_group("runtime");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));

    let mut planner = Planner::new(&Config::default());
    for (name, cmds) in [("short_segments", &short_cmds), ("arcs", &arc_cmds)] {
        group.throughput(Throughput::Elements(cmds.len() as u64));
        group.bench_with_input(BenchmarkId::new("plan", name), cmds, |b, cmds| {
            b.iter(|| plan_all(&mut planner, black_box(cmds)))
        });
    }
    for (name, src, n) in [
        ("short_segments", &short, short_cmds.len()),
        ("arcs", &arc, arc_cmds.len()),
    ] {
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("parse_vm_plan", name), src, |b, src| {
            b.iter(|| end_to_end(black_box(src), &mut planner))
        });
        group.bench_with_input(
            BenchmarkId::new("parse_vm_plan_split", name),
            src,
            |b, src| b.iter(|| end_to_end_split(black_box(src))),
        );
    }

    for (name, src, n) in [
        ("short_segments", &short, short_cmds.len()),
        ("arcs", &arc, arc_cmds.len()),
    ] {
        let m = module(src);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("vm_plan", name), &m, |b, m| {
            b.iter_batched(
                || m.clone(),
                |m| vm_plan(m, &mut planner),
                BatchSize::LargeInput,
            )
        });
        group.bench_with_input(BenchmarkId::new("vm_plan_split", name), &m, |b, m| {
            b.iter_batched(|| m.clone(), vm_plan_split, BatchSize::LargeInput)
        });
    }

    group.throughput(Throughput::Elements(1));
    let thread_cmds = spindle_commands(&threads(400));
    for (name, cmds) in [
        ("short_segments", &short_cmds),
        ("arcs", &arc_cmds),
        ("threads", &thread_cmds),
    ] {
        let mut t = Ticker::new(cmds.clone());
        group.bench_function(BenchmarkId::new("period", name), |b| {
            b.iter_custom(|iters| {
                let mut spent = Duration::ZERO;
                let mut left = iters;
                while left > 0 {
                    let n = left.min(500);
                    let t0 = Instant::now();
                    for _ in 0..n {
                        black_box(t.e.tick());
                    }
                    spent += t0.elapsed();
                    left -= n;
                    if t.low() {
                        t.refill();
                    }
                }
                spent
            })
        });
        // Single periods, timed one by one (timer overhead included), over
        // 100 s of machine time: the distribution and the worst one.
        let mut each = Vec::with_capacity(100_000);
        for _ in 0..200 {
            for _ in 0..500 {
                let t0 = Instant::now();
                black_box(t.e.tick());
                each.push(t0.elapsed());
            }
            t.refill();
        }
        each.sort();
        let at = |q: f64| each[((each.len() - 1) as f64 * q) as usize];
        eprintln!(
            "runtime/period/{name}: single periods p50 {:?}, p99 {:?}, p99.9 {:?}, p99.99 {:?}, worst {:?} (state {:?})",
            at(0.5),
            at(0.99),
            at(0.999),
            at(0.9999),
            each[each.len() - 1],
            t.e.state()
        );
    }
    trace_lines(&mut group, &short_cmds);
    group.finish();
}

/// Formatting the trace (`gbvm run --emit trace`): 20 000 periods of the
/// short segments as CSV lines, in work coordinates and in counts.
fn trace_lines(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    cmds: &[runtime::Command],
) {
    use runtime::trace::{write_csv, Frame};
    let mut t = Ticker::new(cmds.to_vec());
    let mut points = Vec::with_capacity(20_000);
    while points.len() < 20_000 {
        points.push(t.e.tick());
        if t.low() {
            t.refill();
        }
    }
    group.throughput(Throughput::Elements(points.len() as u64));
    for (name, frame) in [("work", Frame::Work), ("counts", Frame::Counts)] {
        let mut out = String::with_capacity(points.len() * 80);
        group.bench_function(BenchmarkId::new("trace_csv", name), |b| {
            b.iter(|| {
                out.clear();
                for p in &points {
                    let _ = write_csv(&mut out, black_box(p), frame, "part.nc");
                }
                out.len()
            })
        });
    }
}

criterion_group!(benches, runtime_benches);
criterion_main!(benches);
