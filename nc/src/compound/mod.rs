//! The compound cycles G70, G71, G72, G73 over an ns…nf profile
//! (cycles.md §5–§8, §15).

use crate::block::Parsed;
use crate::error::{fail, NcError};
use crate::exec::{Nc, Outcome, Sink};
use crate::gcode::{self, Code};

/// Modal first-block values of G71/G72/G73.
#[derive(Debug, Clone, Default)]
pub struct CompoundState {}

/// A G70–G73 block; `nc.profile` holds the ns…nf blocks for a cycle block.
pub fn run(
    nc: &mut Nc,
    code: Code,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let _ = (nc, p, sink, out);
    fail(
        2099,
        format!("{} is not implemented yet", gcode::name(code)),
    )
}
