//! Polar and cylindrical interpolation: where the plane's moves leave
//! the joints, as end points the walk holds the tool to in space.

use super::pending::{Pending, PlaneEnd, Shape};
use super::{Certifier, END_POINT_MM};
use crate::math::V2;
use crate::polar::PlaneMap;

/// Polar or cylindrical interpolation while it is on, as the translator
/// follows it (translate.rs): the map, and where its moves leave the
/// joints X (a radius) and Z, work coordinates (`None`: not known).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PlaneTrack {
    map: PlaneMap,
    pub(super) r: Option<f64>,
    pub(super) z: Option<f64>,
    /// C where the plane's last end point stands (`None` before one).
    c: Option<f64>,
}

impl PlaneTrack {
    /// Whether joints at `r`, `z`, `c` are where the last end point left
    /// them: a move that goes nowhere (a `LINE Z=` to the Z the tool
    /// stands at) runs no period, so its end point is not waited for.
    fn stands_at(&self, r: Option<f64>, z: Option<f64>, c: f64) -> bool {
        let same = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-9,
            (None, None) => true,
            _ => false,
        };
        // (C counts in whole turns where the kernel unwinds it, the
        // joints' map does not: the same place.)
        let turn = |d: f64| libm::fabs(d - 360.0 * libm::round(d / 360.0)) <= 1e-9;
        same(self.r, r) && same(self.z, z) && self.c.is_some_and(|p| turn(p - c))
    }
}

impl Certifier {
    /// A move of the plane ends with the joints at X (a radius) `r`, Z
    /// `z` (`None`: not known) and C `c`: not held to a way (as
    /// [`Shape::Free`]), its end held in space ([`PlaneEnd`]). The next
    /// move starts there where X and Z are known.
    fn push_plane(&mut self, r: Option<f64>, z: Option<f64>, c: f64) {
        self.end_points += 1;
        self.pending.push_back(Pending {
            end: V2::new(r.unwrap_or(0.0), z.unwrap_or(0.0)),
            start: self.last_end,
            thread: None,
            tol: END_POINT_MM,
            enter: V2::ZERO,
            corner: false,
            shape: Shape::Free,
            spindle: self.cmd,
            nearest: f64::INFINITY,
            at: (0.0, 0, 0),
            plane: Some(PlaneEnd {
                c,
                free_r: r.is_none(),
                free_z: z.is_none(),
            }),
            away: false,
        });
        self.last_end = r.zip(z).map(|(r, z)| V2::new(r, z));
    }

    /// Polar or cylindrical interpolation starts with `map` where the last
    /// move ended (the plane's start moves no joint).
    pub(super) fn plane_on(&mut self, map: PlaneMap) {
        self.plane = Some(PlaneTrack {
            map,
            r: self.last_end.map(|e| e.r),
            z: self.last_end.map(|e| e.z),
            c: None,
        });
    }

    /// A move in the plane to its point (`a`, `b`) as the canon prints it
    /// (polar X a diameter and C mm, cylinder Z and C degrees); `off`:
    /// where it takes the axis outside the plane along (polar Z, cylinder
    /// X a diameter). The joints as the translator turns the plane point
    /// into them ([`PlaneMap::joints`]).
    pub(super) fn plane_move(&mut self, a: f64, b: f64, off: Option<f64>) {
        let Some(mut t) = self.plane else {
            return;
        };
        let (w, c) = t.map.joints(t.map.point(a, b));
        match t.map {
            PlaneMap::Polar { .. } => {
                t.r = Some(w.r);
                t.z = off.or(t.z);
            }
            PlaneMap::Cylinder { .. } => {
                t.r = off.map(|x| x * 0.5).or(t.r);
                t.z = Some(w.z);
            }
        }
        self.plane_end(t, c);
    }

    /// The plane's joints after a move, with C at `c`: an end point to
    /// reach, unless the move went nowhere.
    fn plane_end(&mut self, mut t: PlaneTrack, c: f64) {
        let moved = self
            .plane
            .is_none_or(|before| !before.stands_at(t.r, t.z, c));
        t.c = Some(c);
        self.plane = Some(t);
        if moved {
            self.push_plane(t.r, t.z, c);
        }
    }

    /// The axis outside the plane moves alone to `to` (polar Z, cylinder
    /// X a diameter), the joints of the plane standing at C `c`.
    pub(super) fn plane_axis(&mut self, to: f64, c: f64) {
        let Some(mut t) = self.plane else {
            return;
        };
        match t.map {
            PlaneMap::Polar { .. } => t.z = Some(to),
            PlaneMap::Cylinder { .. } => t.r = Some(to * 0.5),
        }
        self.plane_end(t, c);
    }

    /// The plane ends (`POLAR MODE=OFF` gives X, a diameter, as the
    /// joints stand): the next move starts where its moves left X and Z,
    /// not where the plane started.
    pub(super) fn plane_off(&mut self, x: Option<f64>) {
        let Some(mut t) = self.plane.take() else {
            return;
        };
        if let Some(x) = x {
            t.r = Some(x * 0.5);
        }
        self.last_end = t.r.zip(t.z).map(|(r, z)| V2::new(r, z));
    }
}
