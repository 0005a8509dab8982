//! The shared library's SONAME on Linux: `libgbc.so.N`, N being
//! `GBC_ABI_VERSION` (src/types.rs). An executable linked against
//! `libgbc.so` records that name, so the dynamic loader never hands it a
//! libgbc of another ABI (that one is `libgbc.so.M`); the start-up check
//! `gbc_abi_version() == GBC_ABI_VERSION` then only catches a library
//! loaded by hand (`dlopen`) or installed under the wrong name.

use std::env;
use std::fs;

fn main() {
    println!("cargo:rerun-if-changed=src/types.rs");
    // GNU ld and lld spell it this way on Linux; Mach-O (install names)
    // and PE (no SONAME) work otherwise.
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("linux") {
        return;
    }
    let src = fs::read_to_string("src/types.rs").unwrap_or_default();
    let Some(abi) = abi_version(&src) else {
        panic!("capi/src/types.rs must define `pub const GBC_ABI_VERSION: u32 = <number>;`");
    };
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libgbc.so.{abi}");
}

/// N of `pub const GBC_ABI_VERSION: u32 = N;`: the constant stays a
/// literal in the source, as cbindgen must read it to write its `#define`.
fn abi_version(src: &str) -> Option<u32> {
    let (_, rest) = src.split_once("pub const GBC_ABI_VERSION: u32 =")?;
    let (value, _) = rest.split_once(';')?;
    value.trim().parse().ok()
}
