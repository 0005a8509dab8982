//! `libgbc.so` carries the SONAME `libgbc.so.N`, N = `GBC_ABI_VERSION`
//! (build.rs): a C host linked with `-lgbc` records that name and runs
//! off a library installed under it, and a library of another ABI (another
//! N) is never loaded in its place.
#![cfg(target_os = "linux")]

mod support;

use std::path::Path;
use std::process::Command;

use gbc::GBC_ABI_VERSION;
use support::{build_libraries, profile_dir, repo};

/// A host that prints the library's ABI version and exits 0 when it is
/// the header's.
const HOST: &str = r#"
#include <stdio.h>
#include "gbc.h"

int main(void) {
    printf("%u\n", gbc_abi_version());
    return gbc_abi_version() == GBC_ABI_VERSION ? 0 : 1;
}
"#;

/// The `[...]` values of `readelf -d`'s lines of `tag` (SONAME, NEEDED).
fn dynamic(file: &Path, tag: &str) -> Vec<String> {
    let out = Command::new("readelf")
        .arg("-d")
        .arg(file)
        .output()
        .expect("readelf (binutils, beside the C compiler) runs");
    assert!(out.status.success(), "readelf -d {}", file.display());
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines()
        .filter(|l| l.contains(&format!("({tag})")))
        .filter_map(|l| Some(l.split_once('[')?.1.split_once(']')?.0.to_string()))
        .collect()
}

#[test]
fn the_shared_library_is_named_for_its_abi_version() {
    let profile = profile_dir();
    build_libraries(&profile);
    let lib = profile.join("libgbc.so");
    let soname = format!("libgbc.so.{GBC_ABI_VERSION}");
    assert_eq!(dynamic(&lib, "SONAME"), std::slice::from_ref(&soname));

    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("shared");
    let installed = out.join("lib");
    std::fs::create_dir_all(&installed).expect("a scratch directory");
    let src = out.join("abi.c");
    std::fs::write(&src, HOST).expect("write abi.c");
    let exe = out.join("abi");
    let cc = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let st = Command::new(cc)
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror"])
        .arg("-I")
        .arg(repo().join("capi/include"))
        .arg(&src)
        .arg("-L")
        .arg(&profile)
        .arg("-lgbc")
        .arg("-o")
        .arg(&exe)
        .status()
        .expect("the system C compiler (cc) runs");
    assert!(st.success(), "cc -lgbc failed");
    // The link recorded the SONAME, not the file name it found.
    assert!(dynamic(&exe, "NEEDED").contains(&soname));

    // Installed under its SONAME alone (no `libgbc.so` beside it), the
    // library is what the host loads.
    let link = installed.join(&soname);
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&lib, &link).expect("symlink libgbc.so.N");
    let run = Command::new(&exe)
        .env("LD_LIBRARY_PATH", &installed)
        .output()
        .expect("the host runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert_eq!(
        String::from_utf8_lossy(&run.stdout),
        format!("{GBC_ABI_VERSION}\n")
    );
}
