//! What the tests that build C hosts share: where the workspace and the
//! profile's target directory are, and `cargo build` into that directory.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `target/<profile>`: the test binary is `target/<profile>/deps/<name>`.
pub fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>")
        .to_path_buf()
}

pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace")
        .to_path_buf()
}

/// The static and the shared library of the same profile (`cargo test`
/// builds the crate only as the tests' rlib), built now if need be.
pub fn build_libraries(profile: &Path) {
    cargo_build(profile, &["-p", "capi", "--lib"]);
}

/// `cargo build` of `what` in the profile and target directory this test
/// runs in, wherever they are.
pub fn cargo_build(profile: &Path, what: &[&str]) {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(repo())
        .args(["build", "--quiet"])
        .args(what);
    let name = profile.file_name().and_then(|n| n.to_str()).unwrap_or("");
    if name != "debug" {
        cmd.args(["--profile", name]);
    }
    if let Some(target) = profile.parent() {
        cmd.arg("--target-dir").arg(target);
    }
    let st = cmd.status().expect("cargo runs");
    assert!(st.success(), "cargo build {what:?} failed");
}
