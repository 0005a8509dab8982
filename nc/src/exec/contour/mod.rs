//! Contour geometry: chamfer L / rounding D corners, angle programming Q
//! and the comma words, ellipses G6.2/G6.3 and parabolas G7.2/G7.3
//! (dialect.md §4.1, §5; cycles.md §13).
//!
//! A block with a corner word cannot print its element before the next
//! move is known, and the first block of the two-block angle form cannot
//! print its line before the second block gives the intersection. Such an
//! element waits in [`ContourState`]; while it waits, every event the
//! kernel prints is held behind it, so that the canon stays in block
//! order: E1 (shortened), the inserted element, the events of the blocks
//! in between and of the next block's groups 0–1, then E2 (cycles.md §13).

use alloc::vec;

pub(crate) mod conic;
mod queue;
#[cfg(test)]
mod tests;

pub use crate::plan::angle::{angle_of, end_at_r, end_at_z};
pub use crate::plan::conic::{ellipse_centre, parabola_vertex};
pub use crate::plan::corner::{corner, Corner};
pub use queue::ContourState;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{Motion, OneShot};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::comp::compensating;
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::angle;
pub(crate) use queue::in_order;
use queue::AngleFirst;
pub(crate) use queue::{advance, Move};

/// G6.2, G6.3, G7.2, G7.3 blocks.
pub fn conic(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let ellipse = code.is_ellipse();
    let cw = code.is_cw_conic();
    if conic::run(nc, ellipse, cw, p, sink)? {
        out.moved = true;
    }
    Ok(())
}

/// The corner word of a block whose motion is `code` (plan::reader).
#[inline]
pub(crate) fn corner_word(nc: &Nc, code: Motion, p: &Parsed) -> Result<Option<Corner>, NcError> {
    nc.reader().corner_word(code, p)
}

/// Whether a G00/G01 block asks for angle programming.
pub(crate) fn has_angle(p: &Parsed) -> bool {
    angle::angle_of(p).is_some()
}

/// A G00 (`rapid`) or G01 block that moves or starts an angle pair: the
/// corner-aware entry of straight moves (cycle legs use `Nc::line`).
pub(crate) fn straight(
    nc: &mut Nc,
    rapid: bool,
    p: &Parsed,
    corner: Option<Corner>,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    if nc.st.c_block {
        return turn_c(nc, rapid, p, sink);
    }
    let from = nc.st.pos;
    // The usual line: no corner or angle word, nothing waits (so no angle
    // pair either) and nothing compensates, so `queue::advance` would
    // print it at once; printed here without the queue. (A short path,
    // off with the plain path: compiler/tests/plain_path.rs compares.)
    let usual = corner.is_none() && !nc.st.contour.is_holding() && !compensating(nc);
    if nc.plain_path && usual && !has_angle(p) {
        let to = nc.target(p);
        nc.st.pos = to;
        return queue::print_line(nc, from, to, rapid, sink);
    }
    let q = angle::angle_of(p);
    let x = p.has(b'X') || p.has(b'U');
    let z = p.has(b'Z') || p.has(b'W');
    if nc.st.contour.angle_waiting() {
        return second_block(nc, rapid, p, q, corner, sink);
    }
    let to = match q {
        None => nc.target(p),
        Some(q) if !x && !z => return first_block(nc, rapid, q, corner, sink),
        Some(q) if x && !z => angle::end_at_r(from, q, nc.target(p).r)?,
        Some(q) if z && !x => angle::end_at_z(from, q, nc.target(p).z)?,
        // X Z Q without a first block: an ordinary line, Q ignored (W104).
        Some(_) => nc.target(p),
    };
    nc.st.pos = to;
    let m = Move::new(nc, Element::Line { from, to }, rapid, corner);
    queue::advance(nc, m, sink)
}

/// A G00/G01 that turns C (caxis.rs: no corner, angle or compensation
/// here): what waits is printed first, as before a G00, and the line
/// carries C to its end.
fn turn_c(nc: &mut Nc, rapid: bool, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    flush(nc, sink)?;
    let from = nc.st.pos;
    let to = nc.target(p);
    nc.st.pos = to;
    nc.st.c = crate::exec::caxis::target_from(nc, p, nc.st.c);
    let mut m = Move::new(nc, Element::Line { from, to }, rapid, None);
    m.c = Some(nc.st.c);
    queue::advance(nc, m, sink)
}

/// `Q_` alone: the line's end waits for the next block.
fn first_block(
    nc: &mut Nc,
    rapid: bool,
    q: f64,
    corner: Option<Corner>,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    if rapid {
        // A G00 is not a move that can take a waiting corner.
        flush(nc, sink)?;
    }
    let feed = queue::feed_now(nc);
    nc.st.contour.wait_angle(AngleFirst::new(
        nc.st.pos, q, rapid, feed, corner, nc.origin,
    ));
    Ok(())
}

/// `X_ Z_ Q_` after a `Q_` block: both lines meet at the intersection.
fn second_block(
    nc: &mut Nc,
    rapid: bool,
    p: &Parsed,
    q: Option<f64>,
    corner: Option<Corner>,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let (Some(q2), Some(r), Some(z)) = (q, nc.radial_of(p, b'X'), nc.len_of(p, b'Z')) else {
        return fail(
            Alarm::BadAngle,
            "the second block of angle programming needs absolute X, Z and an angle Q (or ,A)",
        );
    };
    let end = Pt::new(r, z);
    let template = Move::new(nc, Element::Line { from: end, to: end }, rapid, corner);
    nc.st.pos = end;
    queue::finish_angle(nc, end, q2, template, sink)
}

/// A G02/G03 block's element (an arc, or a line where
/// `arc_without_center = "line"`), corner-aware.
pub(crate) fn feed_element(
    nc: &mut Nc,
    e: Element,
    corner: Option<Corner>,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    if nc.st.contour.angle_waiting() {
        return fail(
            Alarm::BadAngle,
            "the second block of angle programming must be a G01 (or G00) X_ Z_ Q_ block",
        );
    }
    nc.st.pos = e.end();
    let m = Move::new(nc, e, false, corner);
    queue::advance(nc, m, sink)
}

/// A move that cannot take a corner (G00, cycles, threads, conics,
/// group-00 functions), the end of the program, or the end of a run:
/// prints what waits, each waiting element whole (its corner ignored,
/// W112). E4008 when an angle pair waits for its second block (after
/// printing everything else).
pub fn flush(nc: &mut Nc, sink: &mut dyn Sink) -> Result<(), NcError> {
    queue::flush(nc, sink)
}

/// Before a block's group-00 function: G09 lets its move decide; G04 may
/// stand between the two blocks of an angle pair (its corner word is then
/// ignored, a group-00 code came first); any other flushes.
pub(crate) fn before_one_shot(
    nc: &mut Nc,
    code: OneShot,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    match code {
        OneShot::ExactStop => Ok(()),
        OneShot::Dwell if nc.st.contour.angle_waiting() => {
            nc.st.contour.drop_angle_corner();
            Ok(())
        }
        // Under compensation G04 is a block without a move (comp.md §7):
        // the element keeps waiting; its corner word is ignored (W112).
        OneShot::Dwell if crate::exec::comp::running(nc) => {
            nc.st.contour.drop_corners();
            Ok(())
        }
        _ => flush(nc, sink),
    }
}

/// After each block: at most one block (G04, M, S, T) may stand between
/// the two blocks of an angle pair (E4008 at the second one).
pub(crate) fn end_of_block(nc: &mut Nc) -> Result<(), NcError> {
    if nc.st.contour.count_block_between() > 1 {
        return fail(
            Alarm::BadAngle,
            "angle programming: at most one block may stand between its two blocks",
        );
    }
    Ok(())
}

impl Nc {
    /// Prints what still waits for a next move (an element whose corner
    /// word found no next G01–G03, and the events held behind it), so that
    /// nothing is lost. The VM calls it when a run ends past its last
    /// block, before the `STOP KIND=M99` of the last pass, and before it
    /// prints an `ALARM`; the kernel itself flushes at M02/M30, group-00
    /// functions and every move that cannot take a corner. E4008 (after
    /// printing the rest) when the first block of an angle pair is still
    /// waiting for its second block.
    pub fn flush(&mut self, sink: &mut dyn Sink) -> Result<(), NcError> {
        // A thread block that waits to know whether it ends its chain
        // does: nothing follows.
        crate::exec::cycles::flush(self, sink);
        flush(self, sink)
    }

    /// Gives what waits for a next move (a corner, a thread block before
    /// its run-out) the block tag `tag` (for errors about it and its
    /// events): for a host whose tags of earlier blocks no longer name
    /// them, as the compiler's dry run when it enters another file.
    pub fn retag_waiting(&mut self, tag: u32) {
        self.map_waiting_tags(&mut |_| tag);
    }

    /// The tag of the block whose element waits last for a next move (a
    /// compensated element, a corner word, the first block of an angle
    /// pair), if one waits: the block an error at its join names.
    pub fn waiting_block(&self) -> Option<u32> {
        queue::last_waiting_tag(self)
    }

    /// Gives what waits for a next move the tag `f` makes of its own: for
    /// a host that keeps the blocks it still names under new tags (the
    /// compiler's dry run of a program in chunks).
    pub fn map_waiting_tags(&mut self, f: &mut dyn FnMut(u32) -> u32) {
        queue::retag(self, f);
        if let Some((_, _, waiting)) = &mut self.st.cycles.chain.pending {
            *waiting = f(*waiting);
        }
    }

    /// Prints an event of the caller's own (the VM's `MESSAGE`) in block
    /// order: behind an element that waits for its corner, if one does.
    pub fn emit_in_order(&mut self, event: crate::base::event::Event, sink: &mut dyn Sink) {
        if self.st.contour.is_holding() {
            self.st.contour.hold(vec![event], self.origin);
        } else {
            sink.emit(event);
        }
    }
}
