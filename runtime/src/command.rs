//! What a program asks of the runtime, already in slide coordinates of the
//! machine axes. The controller makes these from the canon events; a host
//! without the VM can push them itself.

use crate::math::V2;
use crate::plc::PlcFunction;

/// Where a command comes from: its source place, and whether it is the
/// last command of its NC block (single block stops there).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tag {
    pub file: u16,
    pub line: u32,
    pub col: u32,
    /// Running number of the NC block.
    pub block: u32,
    pub block_end: bool,
}

/// The shape of a move; its start is where the previous move ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Path {
    Line {
        to: V2,
    },
    Arc {
        to: V2,
        centre: V2,
        ccw: bool,
    },
    /// G6.2/G6.3 (semi-axes in mm, axis angle in radians from +Z).
    Ellipse {
        to: V2,
        a: f64,
        b: f64,
        q: f64,
        ccw: bool,
    },
    /// G7.2/G7.3 (p in mm, axis angle in radians from +Z).
    Parabola {
        to: V2,
        p: f64,
        q: f64,
        ccw: bool,
    },
}

impl Path {
    pub fn to(&self) -> V2 {
        match *self {
            Path::Line { to }
            | Path::Arc { to, .. }
            | Path::Ellipse { to, .. }
            | Path::Parabola { to, .. } => to,
        }
    }
}

/// A feed: mm/min (converted to mm/s here) or mm/rev.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feed {
    /// mm/s, or mm/rev with `per_rev`.
    pub f: f64,
    pub per_rev: bool,
}

/// A spindle-synchronised move (dialect.md §4.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thread {
    /// mm per revolution along the long axis.
    pub lead: f64,
    /// Lead change per revolution (G34), mm/rev².
    pub dlead: f64,
    /// Start angle after the index pulse, degrees.
    pub q_deg: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MoveKind {
    /// G00: each axis at its own rapid rate (a dog-leg).
    Rapid,
    /// A cutting feed along the exact path.
    Feed(Feed),
    /// G31: a feed that the skip signal ends.
    Skip(Feed),
    /// Spindle-synchronised (never blended with other kinds).
    Thread(Thread),
    /// The axes move while the programmed point stays: a tool length
    /// offset taking effect (at rapid, as the T block of the GSK980TDi).
    Offset,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    pub kind: MoveKind,
    pub path: Path,
    /// Machine axes minus the programmed point (work zero + tool offset),
    /// to print work coordinates.
    pub shift: V2,
    /// The C axis angle at the end, degrees (`None`: C stays). Only lines
    /// and rapids turn C; the kernel never asks it of a curve or thread.
    pub c: Option<f64>,
}

/// Why the program waits for cycle start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PauseKind {
    M00,
    M01,
    /// `#3006` message (the host shows the text).
    Message(u32),
    /// Single block: the end of a block.
    SingleBlock,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Command {
    Move(Move),
    /// G04, seconds.
    Dwell(f64),
    /// Handed to the PLC; the next command waits for its completion.
    Plc(PlcFunction),
    /// Display shift change (G50, G52, G54…, an offset write): no motion.
    Shift(V2),
    /// Stops until cycle start.
    Pause(PauseKind),
    /// The block before ends in an exact stop (G09, G61): no blending
    /// into what follows.
    ExactStop,
    /// Stored stroke check 2 from here on (G22 with its area, G23 `None`).
    Stroke(Option<nc::stroke::Area>),
    /// The program ends (M02, M30, last M99, past the last block).
    End,
    /// The program raised an alarm; motion stops here.
    Alarm(u32),
}
