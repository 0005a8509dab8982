//! Contour geometry: chamfer L / rounding D corners, angle programming Q
//! and the comma words, ellipses G6.2/G6.3 and parabolas G7.2/G7.3
//! (dialect.md §4.1, §5; cycles.md §13).

use crate::block::Parsed;
use crate::error::{fail, NcError};
use crate::exec::{Nc, Outcome, Sink};
use crate::gcode::{self, Code};

/// Pending corners and angle-programming pairs.
#[derive(Debug, Clone, Default)]
pub struct ContourState {}

/// G6.2, G6.3, G7.2, G7.3 blocks.
pub fn conic(
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
