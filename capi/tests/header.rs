//! `include/gbc.h` is what cbindgen makes of the crate today: a change to
//! the interface that forgot to regenerate the header fails here.
//! `GBC_BLESS=1 cargo test -p capi --test header` rewrites it.

use std::path::Path;

#[test]
fn the_checked_in_header_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut fresh = Vec::new();
    cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen parses the crate")
        .write(&mut fresh);
    let fresh = String::from_utf8(fresh).expect("UTF-8 header");
    let path = dir.join("include/gbc.h");
    if std::env::var_os("GBC_BLESS").is_some() {
        std::fs::write(&path, &fresh).expect("write include/gbc.h");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == fresh,
        "capi/include/gbc.h is stale: run `GBC_BLESS=1 cargo test -p capi --test header`"
    );
}
