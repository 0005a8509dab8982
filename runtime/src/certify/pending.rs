//! What the certifier keeps of each canon move whose end point the path
//! has still to reach.

use crate::math::V2;

/// The spindle state the canon set before a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SpindleCmd {
    pub(super) on: bool,
    /// G96 surface speed, m/min (`None` in G97).
    pub(super) css: Option<f64>,
    /// G50 S (infinite when none).
    pub(super) clamp: f64,
}

/// A canon move whose end point the path has not reached yet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Pending {
    /// End point, work coordinates (radius, Z).
    pub(super) end: V2,
    /// Start: the previous end point (`None` when unknown).
    pub(super) start: Option<V2>,
    /// Lead and lead change of a straight thread.
    pub(super) thread: Option<(f64, f64)>,
    /// The distance within which the path reaches it: [`END_POINT_MM`],
    /// or at a corner a thread chain turns at speed the bound of
    /// [`chain_corner_mm`].
    ///
    /// [`END_POINT_MM`]: super::END_POINT_MM
    /// [`chain_corner_mm`]: super::chain_corner_mm
    pub(super) tol: f64,
    /// A thread leg that continues its chain at speed: how each axis's
    /// speed (mm per turn, radial X and Z) changes at the corner where
    /// it starts; 0 otherwise.
    pub(super) enter: V2,
    /// Whether the end point is a corner a thread chain turns at speed.
    pub(super) corner: bool,
    /// The way to it the tool must keep.
    pub(super) shape: Shape,
    pub(super) spindle: SpindleCmd,
    /// The nearest approach so far: distance and place.
    pub(super) nearest: f64,
    pub(super) at: (f64, u16, u32),
    /// A full circle ([`comes_back`]) whose end point the tool has not
    /// come back to yet: it starts on it, so there it is not due.
    ///
    /// [`comes_back`]: super::shape::comes_back
    pub(super) away: bool,
    /// A move of polar or cylindrical interpolation (`end` its joints X
    /// and Z): the walk holds the tool to its end in space.
    pub(super) plane: Option<PlaneEnd>,
}

/// Where a move in the plane of polar or cylindrical interpolation leaves
/// the joints, beyond X and Z: as the tool about the spindle's axis,
/// (r cos C, r sin C, Z) in space, the end of each of the plane's moves is
/// a point of its own (in X and Z alone a polar contour passes its end
/// radius many times, a cylinder's C moves none), and the walk holds the
/// tool to them in order; the set points of the plane are held to no move
/// after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PlaneEnd {
    /// C at the end, degrees.
    pub(super) c: f64,
    /// X (Z) at the end is not known: the plane started where the tool
    /// came by a way of its own (home) and its moves did not set it; the
    /// walk takes the tool's own.
    pub(super) free_r: bool,
    pub(super) free_z: bool,
}

/// The way a canon move goes to its end point, as far as the path check
/// holds the tool to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shape {
    /// A straight feed (G01, G31): the segment from the start.
    Line,
    /// A circular feed: the circle about `centre` through the end point,
    /// counter-clockwise (G03) or not.
    Arc { centre: V2, ccw: bool },
    /// A rapid: each axis runs at its own rate (a dog-leg), so the tool
    /// stays within the rectangle of the start and the end.
    Rapid,
    /// A thread leg: its axes follow the chain's corners within their
    /// acceleration, never past the chain's point, so the tool stays
    /// within the box of the legs around it.
    Thread,
    /// Not checked: a conic, a circular thread.
    Free,
}
