//! The JIT against the interpreter on random macro programs (the
//! generator is `harness::jit_diff`): a fixed seed, a bounded count.
//! `JIT_CASES=n` runs more, `JIT_SEED=n` from another seed (the stop's
//! note gives a long run); the fuzz target `jit` runs the same comparison
//! on a fuzzer's bytes.

use harness::jit_diff::{compare, program, Choices};

#[test]
fn random_macro_programs_run_the_same_compiled_and_interpreted() {
    let cases: u64 = std::env::var("JIT_CASES").map_or(1000, |n| n.parse().unwrap_or(1000));
    let seed = std::env::var("JIT_SEED").map_or(0x1175_c0de, |n| n.parse().unwrap_or(1));
    let mut c = Choices::Seed(seed.max(1));
    let (mut compiled, mut optimized, mut entries, mut blocks) = (0u64, 0u64, 0u64, 0u64);
    for i in 0..cases {
        let src = program(&mut c);
        // Budgets and steps vary, so that runs end on E6005 inside
        // compiled loops and steps end inside them too.
        let max_blocks = [60, 400, 5_000][(i % 3) as usize];
        let step = [1, 100, 1 << 16][((i / 3) % 3) as usize];
        let stats = compare(&src, max_blocks, step);
        compiled += u64::from(stats.compiled);
        optimized += u64::from(stats.optimized);
        entries += stats.entries;
        blocks += stats.blocks;
    }
    // The comparison is not empty: loops were compiled, and again with the
    // optimiser, their code ran, and ran blocks itself.
    eprintln!(
        "{cases} programs: {compiled} loops compiled ({optimized} again, optimised), \
         code entered {entries} times, {blocks} blocks run from it"
    );
    assert!(compiled >= cases, "{compiled} loops compiled");
    assert!(optimized >= cases / 2, "{optimized} loops optimised");
    assert!(entries >= 10 * cases, "code entered {entries} times");
    assert!(blocks >= cases, "{blocks} blocks run from compiled code");
}
