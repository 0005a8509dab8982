//! `harness::thread::certified_or_warned` under libFuzzer (see harness/src/thread.rs).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::thread::certified_or_warned(data));
