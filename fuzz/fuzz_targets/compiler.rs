//! `harness::compiler` under libFuzzer (see harness/src/lib.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::compiler(data));
