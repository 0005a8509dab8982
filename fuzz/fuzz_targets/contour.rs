//! `harness::contour::certified` under libFuzzer (see harness/src/contour.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::contour::certified(data));
