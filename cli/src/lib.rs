//! Shared pieces of the gbc command-line tools.

pub mod allocator;
pub mod canon;
pub mod depfile;
pub mod exit;
pub mod expand;
pub mod explain;
pub mod io;
pub mod jit;
pub mod program_info;
pub mod progress;
pub mod report;
pub mod stats_json;
pub mod vars;
pub mod warnings;

use nc::Machine;
use std::path::Path;

/// Loads `--machine FILE`, or the reference machine.
pub fn load_machine(path: Option<&Path>) -> Result<Machine, String> {
    let Some(path) = path else {
        return Ok(Machine::reference());
    };
    let text = io::read_text(path)?;
    Machine::from_toml(&text).map_err(|e| match e {
        // A value out of range: gcc-style, at the key.
        nc::machine::MachineError::Range {
            bad,
            at: Some((line, col)),
        } => format!("{}:{line}:{col}: {}: {}", path.display(), bad.key, bad.msg),
        e => format!("{}: {e}", path.display()),
    })
}
