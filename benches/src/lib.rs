//! Shared helpers of the criterion benches (and of the profiling example):
//! generated programs and a sink that only counts.

pub mod pipeline;
pub mod whole;

/// The benches measure with the allocator `gbcc` and `gbvm` use.
#[global_allocator]
static ALLOCATOR: cli::allocator::Mimalloc = cli::allocator::Mimalloc;

use nc::{Event, Sink};
use std::fmt::Write;

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

/// A small deterministic generator, so every run makes the same program.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() % 1_000_000) as f64 / 1_000_000.0
    }
}

/// A CAM-style contour: 0.05–0.25 mm segments turning a few degrees at
/// a time, at F2000 mm/min (G98).
pub fn short_segments(n: usize) -> String {
    let mut g = Lcg(7);
    let mut s = String::with_capacity(n * 24);
    s.push_str("O0001\nG98 G01 F2000\n");
    let (mut r, mut z, mut a) = (20.0f64, 0.0f64, -1.6f64);
    for _ in 0..n {
        a += (g.unit() - 0.5) * 0.2;
        a = a.clamp(-2.8, -0.3);
        let l = 0.05 + 0.2 * g.unit();
        r = (r + l * a.sin()).clamp(1.0, 60.0);
        z += l * a.cos() - 0.01;
        let _ = writeln!(s, "X{:.3} Z{:.3}", 2.0 * r, z);
    }
    s.push_str("M30\n");
    s
}

/// Thread-heavy: `n` G92 passes of an M24×1.5 thread 30 mm long at
/// 800 rev/min, each 0.05 mm deeper, back to the first depth every 12
/// passes (about 0.4 s of spindle-synchronised motion each).
pub fn threads(n: usize) -> String {
    let mut s = String::with_capacity(n * 24);
    s.push_str("O0003\nG97 S800 M03\nG00 X26 Z5\n");
    for i in 0..n {
        let x = 23.6 - 0.05 * (i % 12) as f64;
        let _ = writeln!(s, "G92 X{x:.3} Z-30 F1.5");
    }
    s.push_str("M30\n");
    s
}

/// Quarter arcs of 1–6 mm radius, alternating G02/G03, at F1500.
pub fn arcs(n: usize) -> String {
    let mut g = Lcg(11);
    let mut s = String::with_capacity(n * 28);
    s.push_str("O0002\nG98 G01 X40 Z0 F1500\n");
    let (r, mut z) = (20.0f64, 0.0f64);
    let mut up = true;
    let mut rad = 1.0;
    for _ in 0..n {
        // Out by the radius in X and back, Z down by it each time: a
        // pair of tangent quarter arcs.
        if up {
            rad = 1.0 + 5.0 * g.unit();
        }
        let nr = if up { r + rad } else { r };
        z -= rad;
        let code = if up { "G02" } else { "G03" };
        let _ = writeln!(s, "{code} X{:.3} Z{:.3} R{rad:.3}", 2.0 * nr, z);
        up = !up;
    }
    s.push_str("M30\n");
    s
}
