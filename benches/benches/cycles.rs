//! Criterion group `cycles`: expansion throughput of a G71 over a
//! 100-block profile and of a G76 with 50 passes, through the NC kernel
//! (the code the compiler's dry run and the VM both call).

use benches::Count;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use nc::words::{addr, Word, LITERAL, NO_POINT};
use nc::{Machine, Nc};
use std::time::Duration;

fn words(list: &[(u8, f64)]) -> Vec<Word> {
    list.iter()
        .map(|&(l, v)| Word {
            addr: addr(l),
            value: v,
            flags: LITERAL | if v.fract() == 0.0 { NO_POINT } else { 0 },
        })
        .collect()
}

/// A 100-block OD profile from X20 Z0 stepping out to X120 Z-200: 50
/// shoulders of a face and a cylinder each.
fn profile() -> Vec<Vec<Word>> {
    let mut blocks = vec![words(&[(b'G', 0.0), (b'X', 20.0)])];
    for i in 0..99 {
        let step = (i / 2) as f64;
        let block = if i % 2 == 0 {
            words(&[(b'G', 1.0), (b'Z', -4.0 * (step + 1.0))])
        } else {
            words(&[(b'X', 22.0 + 2.0 * step)])
        };
        blocks.push(block);
    }
    blocks
}

fn run_g71(profile: &[Vec<Word>]) -> u64 {
    let mut nc = Nc::new(Machine::reference());
    let mut sink = Count::default();
    let setup = [
        words(&[(b'G', 99.0), (b'M', 3.0), (b'S', 800.0)]),
        words(&[(b'G', 0.0), (b'X', 130.0), (b'Z', 2.0)]),
        words(&[(b'G', 71.0), (b'U', 1.0), (b'R', 0.5)]),
    ];
    for b in &setup {
        nc.exec(b, &mut sink).expect("setup runs");
    }
    for (i, b) in profile.iter().enumerate() {
        nc.push_profile(b, i as u32);
    }
    let cycle = words(&[
        (b'G', 71.0),
        (b'P', 10.0),
        (b'Q', 20.0),
        (b'U', 0.4),
        (b'W', 0.1),
        (b'F', 0.25),
    ]);
    nc.exec(&cycle, &mut sink).expect("G71 runs");
    sink.0
}

fn run_g76() -> u64 {
    let mut nc = Nc::new(Machine::reference());
    let mut sink = Count::default();
    let blocks = [
        words(&[(b'M', 3.0), (b'S', 500.0)]),
        words(&[(b'G', 0.0), (b'X', 32.0), (b'Z', 5.0)]),
        // m = 2 finishing passes, 45° angle at 0 pull-out … Δdmin 20 µm.
        words(&[(b'G', 76.0), (b'P', 20060.0), (b'Q', 20.0), (b'R', 0.02)]),
        // k = 2.45 mm, Δd = 0.35 mm: (2.45 − 0.02)/0.35 squared ≈ 48 rough passes.
        words(&[
            (b'G', 76.0),
            (b'X', 25.1),
            (b'Z', -40.0),
            (b'P', 2450.0),
            (b'Q', 350.0),
            (b'F', 4.0),
        ]),
    ];
    for b in &blocks {
        nc.exec(b, &mut sink).expect("G76 runs");
    }
    sink.0
}

fn cycles(c: &mut Criterion) {
    let profile = profile();
    let legs = run_g71(&profile);
    let threads = run_g76();
    let mut g = c.benchmark_group("cycles");
    g.sample_size(20)
        .measurement_time(Duration::from_secs(5))
        .warm_up_time(Duration::from_secs(1));
    g.throughput(Throughput::Elements(legs));
    g.bench_function("g71_100_block_profile_legs", |b| {
        b.iter(|| run_g71(&profile))
    });
    g.throughput(Throughput::Elements(threads));
    g.bench_function("g76_about_50_passes_events", |b| b.iter(run_g76));
    g.finish();
    println!("g71: {legs} events per expansion; g76: {threads} events per expansion");
}

criterion_group!(benches, cycles);
criterion_main!(benches);
