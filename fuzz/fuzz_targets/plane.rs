//! `harness::plane::certified` under libFuzzer (see harness/src/plane.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::plane::certified(data));
