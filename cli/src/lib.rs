//! Shared pieces of the gbc command-line tools.

pub mod expand;
pub mod vars;

/// The tools' allocator. A large program's compile makes and frees one
/// small allocation per block (its words), which mimalloc does faster than
/// the system allocator (about 5 % of a compile and run of 200 000 arc
/// blocks); the libraries leave the choice to whoever links them.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use nc::Machine;
use std::path::Path;

/// Loads `--machine FILE`, or the reference machine.
pub fn load_machine(path: Option<&Path>) -> Result<Machine, String> {
    let Some(path) = path else {
        return Ok(Machine::reference());
    };
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Machine::from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))
}
