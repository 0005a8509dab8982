//! Criterion group `vm`: compile throughput and run-to-canon throughput on
//! a generated 1M-block program.

use benches::{build, moves, Count};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use vm::Vm;

const BLOCKS: usize = 1_000_000;

fn vm(c: &mut Criterion) {
    let src = moves(BLOCKS);
    let module = build(&src);
    let mut g = c.benchmark_group("vm");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(10))
        .warm_up_time(Duration::from_secs(1));
    g.throughput(Throughput::Elements(BLOCKS as u64));
    g.bench_function("compile_1M_blocks", |b| b.iter(|| build(&src)));
    g.bench_function("run_to_canon_1M_blocks", |b| {
        b.iter(|| {
            let mut vm = Vm::new(module.clone(), nc::Machine::reference());
            let mut sink = Count::default();
            vm.run(&mut sink);
            sink.0
        })
    });
    g.bench_function("run_to_canon_text_1M_blocks", |b| {
        b.iter(|| {
            let mut vm = Vm::new(module.clone(), nc::Machine::reference());
            let mut text: Vec<nc::Event> = Vec::with_capacity(BLOCKS + 8);
            vm.run(&mut text);
            text.iter().map(|e| e.to_string().len()).sum::<usize>()
        })
    });
    g.finish();
}

criterion_group!(benches, vm);
criterion_main!(benches);
