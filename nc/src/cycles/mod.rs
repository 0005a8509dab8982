//! Single canned cycles, threading, grooving and drilling (cycles.md §1–§4,
//! §9–§12, §16–§22): G90 G92 G94, G32 G32.1 G32.2 G32.3 G33 G34 G92.1,
//! G74 G75 G76 G78, G83 G84 G87 G88.

use crate::block::Parsed;
use crate::error::{fail, NcError};
use crate::exec::{Nc, Outcome, Sink};
use crate::gcode::{self, Code};

/// Modal state of these cycles (first-block values, modal lead, J/K …).
#[derive(Debug, Clone, Default)]
pub struct CycleState {}

/// A block whose group-01 code is one of this module's.
pub fn motion(
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

/// G74, G75, G76, G78 blocks (group 00).
pub fn one_shot(
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

/// A block while a drilling/tapping cycle (group 10) is in force, or the
/// block that selects it.
pub fn drill(
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
