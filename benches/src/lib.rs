//! Shared helpers of the criterion benches: generated programs and a sink
//! that only counts.

use nc::{Event, Sink};

/// A generated program of `n` G01 blocks zig-zagging over a shaft.
pub fn moves(n: usize) -> String {
    let mut s = String::with_capacity(n * 24);
    s.push_str("G99 M03 S800\nG00 X40 Z2\n");
    for i in 0..n {
        let x = 30.0 + (i % 100) as f64 * 0.1;
        let z = -((i % 500) as f64) * 0.05;
        s.push_str(&format!("G01 X{x:.3} Z{z:.3} F0.2\n"));
    }
    s.push_str("M30\n");
    s
}

/// Counts events without keeping them.
#[derive(Default)]
pub struct Count(pub u64);

impl Sink for Count {
    fn emit(&mut self, _: Event) {
        self.0 += 1;
    }
}

/// Compiles a program, panicking on errors (benches use valid programs).
pub fn build(src: &str) -> isa::Module {
    let c = compiler::compile("bench.nc", src.as_bytes(), &compiler::Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    c.module.expect("a module")
}
