//! W119: a geometry alarm the compiler can prove in a program with
//! macros.
//!
//! A static program is dry-run, and its geometry errors (E4xxx) are
//! compile errors. A program with macros is not: it may reach a block with
//! other values, so it must compile (dialect.md §0). Where pass `modal`
//! knows the tool's position and the modes before a plain arc of constant
//! words on every path that reaches it, the arc is the same whenever it
//! runs; if the kernel's reader cannot draw it (a radius too small for
//! the chord, an end point off the circle of I/K, no centre at all), the
//! alarm will happen whenever the block is reached (a test runs random
//! programs to every block W119 names and finds that alarm there). The compiler says so, as W116 does for
//! value errors, and the alarm itself stays at run time.

use crate::ir::{Module, Op};
use crate::modal::{position, Facts};
use grammar::Diagnostic;
use nc::Machine;

/// Operations past which a program is not searched: the analysis W119
/// needs costs about half as much again as the rest of the compile (on
/// 20 000 blocks of lines and arcs after one macro line, 145 M
/// instructions without it, 232 M with it), which a long program that
/// merely has a macro line should not pay. Hand-written macro programs
/// are far shorter.
pub const MAX_OPS: usize = 20_000;

/// Whether W119 is looked for in `ir`: a program with an arc (G02 or
/// G03 written), not longer than [`MAX_OPS`].
pub fn wanted(ir: &Module) -> bool {
    let arc = |w: &crate::ir::Word| {
        w.addr == nc::words::addr(b'G') && matches!(w.constant(), Some(v) if v == 2.0 || v == 3.0)
    };
    let ops: usize = ir.functions.iter().map(|f| f.ops.len()).sum();
    ops <= MAX_OPS && ir.functions.iter().any(|f| f.words.iter().any(arc))
}

/// W119 for each plain arc of `ir` that `facts` prove cannot be drawn.
pub fn arcs(ir: &Module, facts: &Facts, m: &Machine) -> Vec<(usize, Diagnostic)> {
    let mut found = Vec::new();
    for (fi, f) in ir.functions.iter().enumerate() {
        for (op, o) in f.ops.iter() {
            let Op::Nc(nc) = o else {
                continue;
            };
            let Some(e) = facts
                .before(fi, op)
                .and_then(|s| position::arc_fault(f, nc, s, m))
            else {
                continue;
            };
            let Some(loc) = f.op_locs.get(op.index()) else {
                continue;
            };
            let d = Diagnostic::warning(
                "W119",
                loc.span,
                format!(
                    "this arc raises E{} whenever it is reached: {}",
                    e.code, e.message
                ),
            )
            .with_label("the start point and the modes are known here")
            .with_help(
                "the program has macros, so the alarm stays at run time; correct the arc's end point, R or I/K",
            );
            found.push((usize::from(loc.file), d));
        }
    }
    found
}
