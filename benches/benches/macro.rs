//! Criterion group `macro`: a 1M-iteration WHILE loop with arithmetic and a
//! move per iteration, a pure arithmetic loop (macro operations per
//! second), an ellipse drawn point by point by a macro, and the compile of
//! a long macro program (the passes' cost where they have work: pass
//! `fold` follows 300 known variables through 20 000 statements).

use benches::whole::ELLIPSE;
use benches::{build, Count};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use vm::Vm;

const ITER: u64 = 1_000_000;

/// Per iteration: the test (2 loads, cmp, branch), 5 arithmetic
/// statements of 2–3 operations each, one move.
fn loop_with_moves() -> String {
    format!(
        "#1=0\n#2=0\nWHILE[#1LT{ITER}]DO1\n#2=#2+0.001\n#3=#1*2-#2\n#4=[#3+1]/2\n#5=#4 MOD 7\n#1=#1+1\nG01 X[40-#5] Z[-#2] F0.2\nEND1\nM30\n"
    )
}

/// Only macro arithmetic: no block reaches the NC kernel.
fn pure_arithmetic() -> String {
    format!("#1=0\n#2=0\nWHILE[#1LT{ITER}]DO1\n#2=#2+#1*3-1\n#1=#1+1\nEND1\nM30\n")
}

/// The 300 common variables #100–#199 and #500–#699 set, then 5 000
/// rounds of a conditional assignment, a numbered move with computed
/// words, an arithmetic statement and a dwell: 20 000 statements.
fn long_macro_program() -> String {
    let vars: Vec<u32> = (100..200).chain(500..700).collect();
    let mut s: String = vars.iter().map(|v| format!("#{v}={v}\n")).collect();
    for (i, v) in (0..5_000).zip(vars.iter().cycle()) {
        s += &format!(
            "IF[#1GT{i}]THEN#2=#2+1\nN{} G01 X[#{v}*0.1] Z-#2 F0.2\n#3=#{v}*2+#3\nG04 X[#{v}*0.001]\n",
            i + 1
        );
    }
    s + "M30\n"
}

fn run(module: &isa::Module) -> u64 {
    let mut vm = Vm::new(module.clone(), nc::Machine::reference());
    vm.max_blocks = u64::MAX;
    let mut sink = Count::default();
    vm.run(&mut sink);
    sink.0
}

fn macros(c: &mut Criterion) {
    let mut g = c.benchmark_group("macro");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(8))
        .warm_up_time(Duration::from_secs(1));
    let with_moves = build(&loop_with_moves());
    g.throughput(Throughput::Elements(ITER));
    g.bench_function("while_1M_iterations_with_moves", |b| {
        b.iter(|| run(&with_moves))
    });
    let pure = build(&pure_arithmetic());
    // Instructions of one pure iteration, counted from the listing.
    let per_iter = pure.code.len() as u64 - 5;
    g.throughput(Throughput::Elements(ITER * per_iter));
    g.bench_function("arithmetic_instructions", |b| b.iter(|| run(&pure)));
    let ellipse = build(ELLIPSE);
    g.throughput(Throughput::Elements(3601));
    g.bench_function("ellipse_by_points_3601_blocks", |b| {
        b.iter(|| run(&ellipse))
    });
    let long = long_macro_program();
    g.throughput(Throughput::Elements(20_000));
    g.bench_function("compile_20k_macro_statements", |b| {
        b.iter(|| build(&long).code.len())
    });
    g.finish();
}

criterion_group!(benches, macros);
criterion_main!(benches);
