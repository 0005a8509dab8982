//! The JIT against the interpreter on random macro programs
//! (harness/src/jit_diff.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::jit_diff::differential(data));
