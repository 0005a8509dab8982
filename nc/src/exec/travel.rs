//! Soft limits (machine.md §3): with `axes.<a>.soft_limits = true` the
//! slide may not leave the axis's travel (E7002).
//!
//! The runtime checks the slide's path every period. The kernel checks
//! each motion event before it leaves the block as well (stroke.rs's
//! [`Guard`](crate::exec::stroke::Guard)), so that a faulty move is not
//! printed and the canon ends at the alarm as canon.md's ALARM section
//! says, in a plain canon run as in a timed one, and the compiler's dry
//! run can tell of it (W124). Where the slide stands is worked out as the
//! runtime's translator does: the printed point, plus the work origin,
//! plus the tool length offset the last `TOOL` event took (none after a
//! `HOME`: G28/G30 cancel it).

use alloc::format;

use crate::base::error::{Alarm, NcError};
use crate::base::event::Num;
use crate::base::machine::{LinearAxis, Machine};
use crate::base::point::Pt;
use crate::exec::state::State;
use crate::exec::Nc;

/// How far past an end of travel a point may lie and still count as on
/// it: float noise from adding the origin and the offset (the runtime
/// allows the same).
const TOLERANCE: f64 = 1e-9;

/// The travel of X (diameter) and Z in machine coordinates; an axis
/// without soft limits is endless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Travel {
    x: (f64, f64),
    z: (f64, f64),
}

impl Travel {
    /// The machine's soft limits, if any axis has them.
    pub fn of(m: &Machine) -> Option<Travel> {
        let (x, z) = (&m.axes.x, &m.axes.z);
        if !x.soft_limits && !z.soft_limits {
            return None;
        }
        let range = |a: &LinearAxis| {
            if a.soft_limits {
                (a.min_mm.min(a.max_mm), a.min_mm.max(a.max_mm))
            } else {
                (f64::NEG_INFINITY, f64::INFINITY)
            }
        };
        Some(Travel {
            x: range(x),
            z: range(z),
        })
    }

    /// Whether the slide point (machine X as a diameter, Z) lies outside
    /// the travel. The travel is a box, so a straight path (or a rapid,
    /// each axis on its own) between two points inside stays inside.
    pub fn leaves(&self, x: f64, z: f64) -> bool {
        self.past(x, z).is_some()
    }

    /// The axis whose travel the slide point is past, and that end of it.
    fn past(&self, x: f64, z: f64) -> Option<(char, f64)> {
        let end = |v: f64, (lo, hi): (f64, f64)| {
            if v < lo - TOLERANCE {
                Some(lo)
            } else if v > hi + TOLERANCE {
                Some(hi)
            } else {
                None
            }
        };
        (end(x, self.x).map(|l| ('X', l))).or_else(|| end(z, self.z).map(|l| ('Z', l)))
    }
}

/// The soft limits while a block runs: the travel, and what sets the
/// slide apart from the printed point.
#[derive(Debug, Clone)]
pub struct Slide {
    travel: Travel,
    offsets: Offsets,
    /// The tool length offset the axes carry.
    off: Pt,
}

impl Slide {
    /// The slide as the block about to run finds it, on a machine with
    /// soft limits.
    pub fn of(nc: &Nc) -> Option<Slide> {
        let travel = Travel::of(&nc.machine)?;
        Some(Slide {
            travel,
            offsets: Offsets::of(&nc.st),
            off: nc.st.slide_off,
        })
    }

    /// The tool length offset the axes carry after the block.
    pub fn offset(&self) -> Pt {
        self.off
    }

    /// A `TOOL` event: the axes take offset `d` at once.
    pub fn tool(&mut self, d: u32) {
        self.off = self.offsets.get(d);
    }

    /// A `HOME` event: G28/G30 cancel the offset.
    pub fn home(&mut self) {
        self.off = Pt::ZERO;
    }

    /// E7002 when the slide, for programmed machine point `m`, stands
    /// outside the travel; `what` says which move takes it there.
    pub fn check(&self, m: Pt, what: &str) -> Result<(), NcError> {
        let s = m.add(self.off);
        let Some((axis, limit)) = self.travel.past(s.x(), s.z) else {
            return Ok(());
        };
        Err(NcError::new(
            Alarm::StrokeLimit,
            format!(
                "{what} takes the slide to machine X{} Z{}, past {axis}'s soft limit {}",
                Num(s.x()),
                Num(s.z),
                Num(limit)
            ),
        ))
    }
}

/// The tool length offsets (geometry + wear; X as a diameter) by offset
/// number, as the axes take them at a `TOOL` event. A copy, because the
/// guard that reads them lives while the block runs.
#[derive(Debug, Clone)]
pub struct Offsets([Pt; 32]);

impl Offsets {
    pub fn of(st: &State) -> Offsets {
        Offsets(core::array::from_fn(|i| {
            let (g, w) = (st.geom[i], st.wear[i]);
            Pt::xz(g[0] + w[0], g[1] + w[1])
        }))
    }

    /// Offset `d`: none for D0 or a number the table does not have, as
    /// the runtime reads it.
    pub fn get(&self, d: u32) -> Pt {
        (d as usize)
            .checked_sub(1)
            .and_then(|i| self.0.get(i))
            .copied()
            .unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn machine(toml: &str) -> Machine {
        Machine::from_toml(toml).unwrap()
    }

    #[test]
    fn no_soft_limits_no_travel() {
        assert_eq!(Travel::of(&machine("")), None);
    }

    #[test]
    fn an_axis_without_soft_limits_is_endless() {
        // Z: −510 … +2 (machine.md §3); X unchecked.
        let t = Travel::of(&machine("[axes.z]\nsoft_limits = true\n")).unwrap();
        assert!(!t.leaves(-5000.0, -510.0));
        assert!(!t.leaves(5000.0, 2.0));
        assert!(t.leaves(0.0, -510.001));
        assert!(t.leaves(0.0, 2.001));
    }

    #[test]
    fn the_ends_of_travel_are_inside() {
        let t = Travel::of(&machine(
            "[axes.x]\nsoft_limits = true\nmin_mm = -100.0\nmax_mm = 4.0\n",
        ))
        .unwrap();
        assert!(!t.leaves(-100.0, 1e9));
        assert!(!t.leaves(4.0 + 1e-10, 0.0));
        assert!(t.leaves(4.0 + 1e-6, 0.0));
        assert!(t.leaves(-100.5, 0.0));
    }

    #[test]
    fn offsets_add_geometry_and_wear() {
        let m = machine(
            "[[tools.offset]]\nnumber = 2\nx = -10.0\nz = 5.0\nwear_x = 0.2\nwear_z = -0.1\n",
        );
        let o = Offsets::of(&State::power_on(&m));
        let p = o.get(2);
        assert!((p.x() + 9.8).abs() < 1e-12 && (p.z - 4.9).abs() < 1e-12);
        assert_eq!(o.get(0), Pt::default());
        assert_eq!(o.get(99), Pt::default());
    }
}
