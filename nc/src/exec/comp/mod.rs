//! Tool-nose-radius compensation G40/G41/G42 (comp.md).
//!
//! The nose centre runs R to the left (G41) or right (G42) of the
//! programmed contour and the canon prints the imaginary tip of the
//! compensated tool. Where an element ends depends on the next one, so
//! compensated moves wait in the contour queue (`contour::queue`) exactly
//! like moves with an L/D corner word: the queue asks `classify` what a
//! new move is, then joins the waiting element with it (`join`) or ends
//! it on its own normal (`close`), and prints it through `printed`.
//! Everything that only needs the modal state (errors, cancels, the count
//! of blocks without a move) happens around each block, in
//! `before_block` and `end_of_block`.

use alloc::format;

use crate::plan::offset;
pub(crate) use crate::plan::offset::Tool;

mod cancel;
pub(crate) mod conic;
#[cfg(test)]
mod conic_tests;
mod corner;
mod cycle;
mod print;
mod startup;
#[cfg(test)]
mod tests;

pub(crate) use cancel::close;
pub(crate) use corner::join;
pub(crate) use cycle::turning_cycle;
pub(crate) use print::printed;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{Comp, OneShot, Work, G};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Sink};
use crate::plan::elem::{shorter_than, EPS_LEN};

/// What a compensated move is in the chain of elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Role {
    /// The start-up move (§4): a straight move to the first element's
    /// start normal, not offset itself.
    Start,
    /// An element offset by R (§5).
    Body,
    /// A zero-length move: printed where the tool stands (§7).
    Zero,
}

/// The compensation of one queued move, filled in as the neighbours of
/// its element become known. Points are nose-centre points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Leg {
    pub(crate) role: Role,
    pub(crate) tool: Tool,
    /// Where the centre starts (a `Body`), set by the join with the
    /// element before.
    pub(crate) start: Option<Pt>,
    /// Where it ends, set by the join with the next element or by a close.
    pub(crate) end: Option<Pt>,
    /// The arc round an outside corner, printed before this element.
    pub(crate) corner: Option<Element>,
}

impl Leg {
    fn new(role: Role, tool: Tool) -> Leg {
        Leg {
            role,
            tool,
            start: None,
            end: None,
            corner: None,
        }
    }

    /// Whether move `e` must wait for the next element before it prints:
    /// a start-up always (its end needs the next direction), an element
    /// unless a corner word used it up (it then has no direction).
    pub(crate) fn open(&self, e: &Element) -> bool {
        self.end.is_none()
            && match self.role {
                Role::Start => true,
                Role::Body => !shorter_than(e, EPS_LEN),
                Role::Zero => false,
            }
    }

    /// The leg of an element that an L/D corner inserts after this one's:
    /// it runs under the same compensation.
    pub(crate) fn inserted(&self) -> Leg {
        Leg::new(Role::Body, self.tool)
    }
}

/// What the queue does with a new move (see `classify`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Step {
    /// No compensation is involved.
    Plain,
    /// A start-up with nothing waiting before it.
    Start,
    /// An element that joins the one waiting before it.
    Join,
    /// A cancel or a change of side: the waiting element ends on its own
    /// normal, and the new move does not join it.
    Close,
    /// A zero-length move: it waits behind the element before it.
    Behind,
}

/// Compensation between blocks: the tool while it runs, the count of
/// blocks without a move, where the compensated tool last stood.
#[derive(Debug, Clone, Default)]
pub struct CompState {
    /// The running compensation; `None` under G40 and, under G41/G42,
    /// before the start-up and after a suspension.
    pub(crate) running: Option<Tool>,
    /// Consecutive blocks without a move while compensating (E4034).
    idle: u32,
    /// The current block's move was a zero-length one, or moved only the
    /// axis outside a plane (no move for E4034).
    zero_move: bool,
    /// The last nose-centre point printed, for zero-length moves.
    pub(crate) stand: Pt,
}

impl CompState {
    /// A suspension or a cancel: the next G41/G42 move is a start-up.
    pub(crate) fn stop(&mut self) {
        self.running = None;
    }
}

/// Whether the compensation is running (an element may be waiting).
pub(crate) fn running(nc: &Nc) -> bool {
    nc.st.comp.running.is_some()
}

/// The current block moves only the axis outside the plane of polar or
/// cylindrical interpolation: no move in the plane, for E4034.
pub(crate) fn moved_off_plane(nc: &mut Nc) {
    nc.st.comp.zero_move = true;
}

/// "While compensating" (comp.md §7, §10): G41/G42 in force, or a cancel
/// still to come.
pub(crate) fn compensating(nc: &Nc) -> bool {
    running(nc) || nc.st.modal.comp().side().is_some()
}

fn on_arc(code: Alarm, what: &str) -> NcError {
    NcError::new(
        code,
        format!("nose-radius compensation cannot {what} on a G02/G03 arc: use a G00 or G01 move"),
    )
}

/// The role of a new move of the current block, from the group-07 mode
/// and whether compensation runs; starts or ends the running compensation.
/// E4031 for a start-up or cancel on an arc, E4036 for a negative radius
/// or an arc too small for the tool on its centre side.
pub(crate) fn classify(nc: &mut Nc, e: &Element) -> Result<(Step, Option<Leg>), NcError> {
    if !compensating(nc) {
        // Nothing compensates: no role needs the move's length (and the
        // block cannot end compensating, so E4034 does not count it).
        return Ok((Step::Plain, None));
    }
    let mode = nc.st.modal.comp().side();
    let zero = shorter_than(e, EPS_LEN);
    if zero {
        nc.st.comp.zero_move = true;
    }
    let arc = matches!(e, Element::Arc { .. });
    match (nc.st.comp.running, mode) {
        (None, None) => Ok((Step::Plain, None)),
        (None, Some(side)) => {
            if arc {
                return Err(on_arc(Alarm::CompOnArc, "start"));
            }
            let tool = startup::read_tool(nc, side)?;
            nc.st.comp.running = Some(tool);
            Ok((Step::Start, Some(Leg::new(Role::Start, tool))))
        }
        (Some(tool), Some(side)) if tool.side == side => {
            if zero {
                return Ok((Step::Behind, Some(Leg::new(Role::Zero, tool))));
            }
            offset::check_arc(e, &tool)?;
            Ok((Step::Join, Some(Leg::new(Role::Body, tool))))
        }
        (Some(_), Some(side)) => {
            // G41 ↔ G42: a cancel of the old side and a start-up on the
            // new one in the same move (§6).
            if arc {
                return Err(on_arc(Alarm::CompOnArc, "change sides"));
            }
            let tool = startup::read_tool(nc, side)?;
            nc.st.comp.running = Some(tool);
            Ok((Step::Close, Some(Leg::new(Role::Start, tool))))
        }
        (Some(_), None) => {
            if arc {
                return Err(on_arc(Alarm::CompOnArc, "be cancelled"));
            }
            nc.st.comp.stop();
            Ok((Step::Close, None))
        }
    }
}

/// Whether a conic block (G6.2/G6.3, G7.2/G7.3) runs compensated. Like an
/// arc it cannot start, cancel or change the compensation (E4031).
pub(crate) fn conic_compensated(nc: &Nc) -> Result<bool, NcError> {
    let mode = nc.st.modal.comp().side();
    let what = match (nc.st.comp.running, mode) {
        (None, None) => return Ok(false),
        (Some(tool), Some(side)) if tool.side == side => return Ok(true),
        (None, Some(_)) => "start",
        (Some(_), Some(_)) => "change sides",
        (Some(_), None) => "be cancelled",
    };
    Err(NcError::new(
        Alarm::CompOnArc,
        format!("nose-radius compensation cannot {what} on an ellipse or parabola: use a G00 or G01 move"),
    ))
}

/// The last group-07 code the block writes.
fn last_comp(p: &Parsed) -> Option<Comp> {
    p.gs().rev().find_map(|g| match g {
        G::Comp(c) => Some(c),
        _ => None,
    })
}

/// The last group-14 code the block writes.
fn last_work(p: &Parsed) -> Option<Work> {
    p.gs().rev().find_map(|g| match g {
        G::Work(c) => Some(c),
        _ => None,
    })
}

/// The error of a function that needs compensation off: G31/G53 E4031,
/// G36/G37 E4032 (dialect.md §4.7).
fn needs_off(p: &Parsed) -> Option<Alarm> {
    match p.one_shot() {
        Some(OneShot::Skip | OneShot::MachineCoords) => Some(Alarm::CompOnArc),
        Some(OneShot::MeasureX | OneShot::MeasureZ) => Some(Alarm::MeasureInComp),
        _ => None,
    }
}

/// The checks and suspensions a block needs before its first event: the
/// functions that need compensation off (also when this block writes
/// G41/G42), and a G54–G59 that moves the zero suspends it (comp.md §8).
pub(crate) fn before_block(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    let mode = last_comp(p).unwrap_or(nc.st.modal.comp);
    if running(nc) || mode.side().is_some() {
        if let (Some(code), Some(g)) = (needs_off(p), p.one_shot()) {
            return fail(
                code,
                format!(
                    "{} needs nose-radius compensation off (G40 and a cancel move first)",
                    g.name()
                ),
            );
        }
    }
    if running(nc) && moves_origin(nc, p) {
        crate::exec::contour::flush(nc, sink)?;
    }
    Ok(())
}

/// Whether the block's G54–G59 selects a system with another zero.
fn moves_origin(nc: &Nc, p: &Parsed) -> bool {
    let Some(code) = last_work(p) else {
        return false;
    };
    if p.one_shot() == Some(OneShot::SetCoordinates) {
        // G50 wins over G54–G59 in one block; the selection is ignored.
        return false;
    }
    let index = code.index();
    let now = nc.st.work.get(nc.st.work_index());
    nc.st.work.get(index) != now
}

/// Blocks whose function cancels compensation (comp.md §8): the waiting
/// element was already printed by the flush the function makes.
fn cancels(p: &Parsed) -> bool {
    let cycle = matches!(
        p.one_shot(),
        Some(OneShot::RoughTurn | OneShot::RoughFace | OneShot::Pattern)
    ) && p.has(b'P');
    matches!(p.one_shot(), Some(OneShot::Home | OneShot::HomeN)) || cycle || p.ends_program()
}

/// After each block: the cancelling functions leave G40 in force, and the
/// 7th consecutive block without a move while compensating is E4034.
pub(crate) fn end_of_block(nc: &mut Nc, p: &Parsed, moved: bool) -> Result<(), NcError> {
    if cancels(p) {
        nc.st.modal.comp = Comp::Off;
        nc.st.comp.stop();
    }
    let zero = core::mem::take(&mut nc.st.comp.zero_move);
    if !compensating(nc) || (moved && !zero) {
        nc.st.comp.idle = 0;
        return Ok(());
    }
    nc.st.comp.idle = nc.st.comp.idle.saturating_add(1);
    if nc.st.comp.idle >= 7 {
        return fail(
            Alarm::CompWithoutMoves,
            "seven consecutive blocks without a move while nose-radius compensation is on",
        );
    }
    Ok(())
}

/// An offset write that moves the zero suspends a running compensation
/// (comp.md §8): what waits is printed before the zero moves.
pub(crate) fn suspend(nc: &mut Nc, sink: &mut dyn Sink) -> Result<(), NcError> {
    if running(nc) {
        crate::exec::contour::flush(nc, sink)?;
    }
    Ok(())
}

impl Nc {
    /// E4035: M98 may not run while nose-radius compensation is on
    /// (dialect.md §4.7). The compiler and VM handle M98, so they ask here
    /// before the call.
    pub fn check_call(&self) -> Result<(), NcError> {
        if compensating(self) {
            return fail(
                Alarm::CallInComp,
                "M98 while nose-radius compensation is on: cancel it (G40 and a move) before the call",
            );
        }
        Ok(())
    }
}
