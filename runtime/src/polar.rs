//! Polar (G12.1) and cylindrical (G7.1) interpolation in the runtime: the
//! programmed path lies in a plane of its own, the axes that move are X
//! and C (polar) or Z and C (cylinder).
//!
//! While a plane is on, the planner and the interpolator work in it as
//! they do in the ZX plane: the moves' points are plane points (`V2` with
//! the plane's first axis as `z` and its second as `r`, as the kernel's
//! plane.rs orients arcs), so lines, arcs, the look-ahead, the corners
//! and the acceleration all act on the programmed path and F is the
//! tangential feed along it. Each period the interpolator's plane point is
//! turned into joint positions here ([`PlaneRun::follow`]):
//!
//! - polar: X = 2·√(x² + c²), C = the angle of (x, c) from +X, followed
//!   continuously (a circle about the centre is a whole turn of C); Z
//!   stays where the map says;
//! - cylinder: Z = the plane's Z, C = s / r in degrees (s the developed
//!   length, r the cylinder's radius); X stays where the map says.
//!
//! The axis the map holds moves alone between two switches: the plane
//! ends, the axis moves as an ordinary move, the plane starts again at the
//! same plane point with the new Z or X (translate.rs, `PlaneAxis`).
//!
//! Joint speeds are not limited by the planner: near the centre C turns
//! fast, and the program keeps F < L·R·π/180 (seed 000; docs/language.md).
//! A switch ([`PlaneSwitch`]) is a queue item: the move before it ends at
//! rest, and the interpolator's point changes from machine axes to plane
//! point (or back) there.

use crate::math::V2;

/// How plane points map to joints while a plane is on (work coordinates,
/// the joint that stays included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneMap {
    /// G12.1: Z (work) stays here while the plane is on.
    Polar {
        /// Z, work coordinates.
        z: f64,
    },
    /// G7.1: the cylinder's radius; X (work radius) stays.
    Cylinder {
        /// The cylinder's radius, mm.
        radius: f64,
        /// X as a radius, work coordinates.
        r: f64,
    },
}

impl PlaneMap {
    /// The plane point of a canon plane move's two numbers (event.rs:
    /// polar X diameter and C mm, cylinder Z and C degrees).
    pub fn point(&self, a: f64, b: f64) -> V2 {
        match *self {
            PlaneMap::Polar { .. } => V2::new(b, a * 0.5),
            PlaneMap::Cylinder { radius, .. } => V2::new(a, radius * b.to_radians()),
        }
    }

    /// The joints (work coordinates) at plane point `p`; C in degrees,
    /// for the polar plane its angle in (−180°, 180°].
    pub fn joints(&self, p: V2) -> (V2, f64) {
        match *self {
            PlaneMap::Polar { z } => (
                V2::new(libm::hypot(p.z, p.r), z),
                libm::atan2(p.r, p.z).to_degrees(),
            ),
            PlaneMap::Cylinder { radius, r } => (V2::new(r, p.r), (p.z / radius).to_degrees()),
        }
    }
}

/// A switch of the plane: a queue item.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSwitch {
    /// The mapping from here on; `None`: joint motion again.
    pub map: Option<PlaneMap>,
    /// The interpolator's point after the switch: the plane point at the
    /// start, the machine axes at the end.
    pub at: V2,
    /// The C angle at the switch, degrees.
    pub c: f64,
    /// Machine axes minus programmed joints while the plane is on (work
    /// zero + tool offset), and the queue's shift after it ends.
    pub shift: V2,
}

/// The interpolator's state while a plane is on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneRun {
    map: PlaneMap,
    shift: V2,
    /// The joints of the last period (work coordinates) and C, followed
    /// continuously.
    work: V2,
    c: f64,
    /// The polar angle of the last period, to unwrap C.
    angle: f64,
}

impl PlaneRun {
    /// The state at a switch that turns a plane on, from its start point.
    pub fn start(map: PlaneMap, sw: &PlaneSwitch) -> PlaneRun {
        let (work, angle) = map.joints(sw.at);
        let mut run = PlaneRun {
            map,
            shift: sw.shift,
            work,
            c: sw.c,
            angle,
        };
        if let PlaneMap::Cylinder { .. } = map {
            run.c = angle;
        }
        run
    }

    /// Moves the joints to plane point `p`.
    pub fn follow(&mut self, p: V2) {
        let (work, angle) = self.map.joints(p);
        self.work = work;
        match self.map {
            PlaneMap::Polar { .. } => {
                // The change of angle the shorter way round: a period
                // turns C by far less than half a turn.
                let mut d = angle - self.angle;
                if d > 180.0 {
                    d -= 360.0;
                } else if d < -180.0 {
                    d += 360.0;
                }
                self.c += d;
                self.angle = angle;
            }
            PlaneMap::Cylinder { .. } => self.c = angle,
        }
    }

    /// The joints in work coordinates (X as a radius).
    pub fn work(&self) -> V2 {
        self.work
    }

    /// The joints in machine coordinates.
    pub fn axes(&self) -> V2 {
        self.work + self.shift
    }

    /// The C angle, degrees.
    pub fn c(&self) -> f64 {
        self.c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polar_joints_and_unwrapping() {
        let map = PlaneMap::Polar { z: -2.0 };
        // X20 C0 is the plane point (x 10, c 0).
        let at = map.point(20.0, 0.0);
        assert_eq!(at, V2::new(0.0, 10.0));
        let sw = PlaneSwitch {
            map: Some(map),
            at,
            c: 360.0,
            shift: V2::new(1.0, 5.0),
        };
        let mut run = PlaneRun::start(map, &sw);
        assert_eq!(run.axes(), V2::new(11.0, 3.0));
        // Around the centre counter-clockwise in quarter steps, (r, z) =
        // (c, x): 90°, 180°, −90° (= 270°), 0° (= 360°): C gains a whole
        // turn from where it started (360°).
        for (r, z) in [(10.0, 0.0), (0.0, -10.0), (-10.0, 0.0), (0.0, 10.0)] {
            run.follow(V2::new(r, z));
        }
        assert!((run.c() - 720.0).abs() < 1e-9, "{}", run.c());
        // (x 3, c 4): radius 5, angle atan2(4, 3) = 53.1301°.
        run.follow(V2::new(4.0, 3.0));
        assert!((run.work().r - 5.0).abs() < 1e-12);
        assert!((run.c() - 720.0 - 53.130_102_354).abs() < 1e-6);
    }

    #[test]
    fn cylinder_joints() {
        let map = PlaneMap::Cylinder {
            radius: 20.0,
            r: 15.0,
        };
        // Z−10 C90 on radius 20: s = 20·π/2.
        let p = map.point(-10.0, 90.0);
        assert!((p.z - 31.415_926_536).abs() < 1e-6 && p.r == -10.0);
        let (work, c) = map.joints(p);
        assert_eq!(work, V2::new(15.0, -10.0));
        assert!((c - 90.0).abs() < 1e-9);
    }
}
