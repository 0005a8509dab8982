//! The figures a certificate measures: what each is of, its unit, and
//! how it reads in a message.

use super::{CSS_TOL, LEAD_TOL, LIMIT_TOL, TRAVEL_MM};
use crate::interpolate::SetPoint;
use core::fmt;

/// What a figure measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Axis velocity.
    Velocity,
    /// Axis acceleration.
    Acceleration,
    /// Axis jerk.
    Jerk,
    /// Axis position against its travel (soft limits): the distance
    /// beyond the nearer limit (negative inside).
    Travel,
    /// A canon end point not reached (distance of the nearest approach).
    EndPoint,
    /// A set point of a feed off its canon line or arc (the distance; an
    /// arc of a radius below [`MICRO_ARC_MM`] may run along its chord), of
    /// a rapid outside the rectangle of its ends, or of a thread outside
    /// the box of the chain's legs around it.
    ///
    /// [`MICRO_ARC_MM`]: super::MICRO_ARC_MM
    Path,
    /// Thread lead.
    Lead,
    /// G96 surface speed (the spindle speed against its target).
    SurfaceSpeed,
    /// Spindle speed.
    SpindleSpeed,
    /// Spindle acceleration.
    SpindleAccel,
}

impl Kind {
    /// Every kind, in the order of the summary.
    pub const ALL: [Kind; 10] = [
        Kind::Velocity,
        Kind::Acceleration,
        Kind::Jerk,
        Kind::Travel,
        Kind::EndPoint,
        Kind::Path,
        Kind::Lead,
        Kind::SurfaceSpeed,
        Kind::SpindleSpeed,
        Kind::SpindleAccel,
    ];

    pub(super) fn index(self) -> usize {
        self as usize
    }

    /// The name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Velocity => "velocity",
            Kind::Acceleration => "acceleration",
            Kind::Jerk => "jerk",
            Kind::Travel => "travel",
            Kind::EndPoint => "end point",
            Kind::Path => "path",
            Kind::Lead => "thread lead",
            Kind::SurfaceSpeed => "surface speed",
            Kind::SpindleSpeed => "spindle speed",
            Kind::SpindleAccel => "spindle acceleration",
        }
    }
}

/// What a figure is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Subject {
    /// The X slide (radial).
    X,
    /// The Z slide.
    Z,
    /// The C axis (degrees).
    C,
    /// The spindle.
    Spindle,
    /// The tool's path.
    Path,
}

impl Subject {
    pub(super) fn name(self) -> &'static str {
        match self {
            Subject::X => "X",
            Subject::Z => "Z",
            Subject::C => "C",
            Subject::Spindle => "spindle",
            Subject::Path => "path",
        }
    }

    /// The unit of a figure of this kind.
    pub(super) fn unit(self, kind: Kind) -> &'static str {
        let deg = self == Subject::C;
        match kind {
            Kind::Velocity if deg => "deg/s",
            Kind::Acceleration if deg => "deg/s²",
            Kind::Jerk if deg => "deg/s³",
            Kind::Velocity => "mm/s",
            Kind::Acceleration => "mm/s²",
            Kind::Jerk => "mm/s³",
            Kind::EndPoint | Kind::Path | Kind::Travel => "mm",
            Kind::Lead => "mm/rev",
            Kind::SurfaceSpeed | Kind::SpindleSpeed => "rev/min",
            Kind::SpindleAccel => "rev/min/s",
        }
    }
}

/// One figure at its place: a violation, or the worst of its kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figure {
    /// What it measures.
    pub kind: Kind,
    /// Of which axis (or the spindle, or the path).
    pub subject: Subject,
    /// Time at the end of the period, s.
    pub time_s: f64,
    /// Source file index of the block running (as [`SetPoint::file`]).
    ///
    /// [`SetPoint::file`]: crate::interpolate::SetPoint::file
    pub file: u16,
    /// Its source line.
    pub line: u32,
    /// The measured value (velocity, acceleration …; for a lead or a G96
    /// speed, the measured lead or rpm).
    pub value: f64,
    /// Its limit (for a lead or a G96 speed: the programmed lead, the
    /// target rpm).
    pub limit: f64,
    /// How far it is from holding: |value| / limit for limits, the
    /// relative (or, for end points, absolute) deviation otherwise.
    pub ratio: f64,
}

impl Figure {
    /// A figure of `kind` about `subject`, measured at the period of `p`
    /// (its time and the block running).
    pub(super) fn at(
        kind: Kind,
        subject: Subject,
        p: &SetPoint,
        value: f64,
        limit: f64,
        ratio: f64,
    ) -> Figure {
        Figure {
            kind,
            subject,
            time_s: p.time_s,
            file: p.file,
            line: p.line,
            value,
            limit,
            ratio,
        }
    }

    /// Whether the figure breaks its bound.
    pub fn violates(&self) -> bool {
        match self.kind {
            Kind::EndPoint | Kind::Path => self.ratio > self.limit,
            Kind::Travel => self.ratio > TRAVEL_MM,
            Kind::Lead => self.ratio > LEAD_TOL,
            Kind::SurfaceSpeed => self.ratio > CSS_TOL,
            _ => self.ratio > 1.0 + LIMIT_TOL,
        }
    }
}

impl fmt::Display for Figure {
    /// `at 1.234000 s: Z acceleration 15000.000 mm/s² exceeds its limit 2000.000 mm/s²`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = self.subject.unit(self.kind);
        write!(f, "at {:.6} s: ", self.time_s)?;
        match self.kind {
            // (A full circle's end point the tool never came back to.)
            Kind::EndPoint if self.value.is_infinite() => write!(
                f,
                "a canon end point is not reached: the path does not come back to it (the end of a full circle, where it began)"
            ),
            Kind::EndPoint => write!(
                f,
                "a canon end point is not reached: the path passes {:.4} mm from it at the nearest (tolerance {} mm)",
                self.value, self.limit
            ),
            Kind::Path => write!(
                f,
                "the tool leaves the programmed path by {:.4} mm (tolerance {} mm)",
                self.value, self.limit
            ),
            Kind::Lead => write!(
                f,
                "thread lead {:.6} {unit} where {:.6} is programmed ({:.4} % off, tolerance {} %)",
                self.value,
                self.limit,
                self.ratio * 100.0,
                LEAD_TOL * 100.0
            ),
            Kind::SurfaceSpeed => write!(
                f,
                "G96 spindle speed {:.3} {unit} where the surface speed asks {:.3} ({:.4} % off)",
                self.value,
                self.limit,
                self.ratio * 100.0
            ),
            Kind::Travel => write!(
                f,
                "{} at {:.3} {unit} leaves its travel: the limit is {:.3} {unit}",
                self.subject.name(),
                self.value,
                self.limit
            ),
            _ => write!(
                f,
                "{} {} {:.3} {unit} exceeds its limit {:.3} {unit}",
                self.subject.name(),
                self.kind.name(),
                self.value.abs(),
                self.limit
            ),
        }
    }
}
