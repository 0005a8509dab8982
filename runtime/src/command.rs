//! What a program asks of the runtime, already in slide coordinates of the
//! machine axes. The controller makes these from the canon events; a host
//! without the VM can push them itself.

use crate::math::V2;
use crate::plc::PlcFunction;

/// Where a command comes from: its source place, and whether it is the
/// last command of its NC block (single block stops there).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tag {
    /// Index of the source file in the module's file table.
    pub file: u16,
    /// Source line (1-based).
    pub line: u32,
    /// Source column (1-based).
    pub col: u32,
    /// Running number of the NC block.
    pub block: u32,
    /// The last command of its NC block (single block stops after it;
    /// never set under `#3003` bit 0).
    pub block_end: bool,
    /// Its block ran under `#3004` bit 0: feed hold does not stop it.
    pub no_hold: bool,
    /// Its block ran under `#3003` bit 1: its M, S or T function is
    /// requested and the program goes on without waiting for FIN.
    pub no_fin: bool,
    /// The codes in force after its block, for the operator's screen
    /// ([`crate::Engine::active_codes`]).
    pub active: nc::ActiveCodes,
}

/// The shape of a move; its start is where the previous move ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Path {
    /// A straight line.
    Line {
        /// End point (machine axes, slide units).
        to: V2,
    },
    /// A circular arc (G02/G03).
    Arc {
        /// End point.
        to: V2,
        /// Centre point.
        centre: V2,
        /// Counter-clockwise (G03).
        ccw: bool,
    },
    /// G6.2/G6.3 (semi-axes in mm, axis angle in radians from +Z).
    Ellipse {
        /// End point.
        to: V2,
        /// Semi-axis along the ellipse's axis, mm.
        a: f64,
        /// The other semi-axis, mm.
        b: f64,
        /// Axis angle, radians from +Z.
        q: f64,
        /// Counter-clockwise (G6.3).
        ccw: bool,
    },
    /// G7.2/G7.3 (p in mm, axis angle in radians from +Z).
    Parabola {
        /// End point.
        to: V2,
        /// Parameter p (focal distance × 2), mm.
        p: f64,
        /// Axis angle, radians from +Z.
        q: f64,
        /// Counter-clockwise (G7.3).
        ccw: bool,
    },
}

impl Path {
    /// The end point of the path.
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
    /// F is per spindle revolution (G99), else per minute (G98).
    pub per_rev: bool,
    /// `#3004` bit 1 was set: the feed override does not apply.
    pub fixed: bool,
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
/// How a move runs.
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
/// A move: how it runs and its shape.
pub struct Move {
    /// Rapid, feed, skip, thread …
    pub kind: MoveKind,
    /// The shape and end point.
    pub path: Path,
    /// Machine axes minus the programmed point (work zero + tool offset),
    /// to print work coordinates.
    pub shift: V2,
    /// The C axis angle at the end, degrees (`None`: C stays). Only lines
    /// and rapids turn C; the kernel never asks it of a curve or thread.
    /// While a plane is on ([`Command::Plane`]), where C follows the plane
    /// point, it is instead where a line or rapid takes the axis outside
    /// the plane (polar Z, cylinder X as a radius; work coordinates, mm;
    /// `None`: it stays), in proportion along the move.
    pub c: Option<f64>,
}

/// Why the program waits for cycle start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PauseKind {
    /// M00: program stop.
    M00,
    /// M01: optional stop (stops only with the switch on).
    M01,
    /// `#3006 = number` message: the host shows the text,
    /// `Controller::message(index)`.
    Message {
        /// The value written to #3006, made whole (nc `Event::Message`).
        number: u32,
        /// Which message stop of the run it is, counted from 0: the key of
        /// its text.
        index: u32,
    },
    /// Single block: the end of a block.
    SingleBlock,
}

#[derive(Debug, Clone, Copy, PartialEq)]
/// What the program side hands to the motion, in program order.
pub enum Command {
    /// A move.
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
    /// Polar or cylindrical interpolation on or off (polar.rs).
    Plane(crate::polar::PlaneSwitch),
    /// The program ends (M02, M30, last M99, past the last block).
    End(Ending),
    /// The program raised an alarm; motion stops here.
    Alarm(u32),
}

/// How a run ends, for what the machine does next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// M02, the last M99 or the last block: the program stands ended
    /// until a reset.
    Stop,
    /// M30: as `Stop`, except that on a machine whose M30 rewinds
    /// (`run.m30_rewinds`) cycle start runs the program again.
    M30,
    /// The end of MDI blocks: the machine is idle again at once, the
    /// spindle and coolant as the blocks left them, and the program
    /// comes back at its start (docs/embedding.md, "MDI").
    Mdi,
}
