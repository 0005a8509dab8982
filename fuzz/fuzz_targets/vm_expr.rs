//! The VM against the reference evaluator (harness/src/expr.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::expr::vm_against_reference(data));
