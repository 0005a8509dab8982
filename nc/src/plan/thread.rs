//! Single thread moves G32, G32.1, G34 as legs (cycles.md §16, §17): the
//! move, its run-out at the end of a chain and the variable lead; the
//! long-axis rule of the arc threads G32.2/G32.3 (dialect.md §4.3). The
//! executor (`exec::cycles`) keeps the chain and prints.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::base::thread_room::z_is_long;
use crate::plan::legs::{sign, Leg, EPS};
use core::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

/// One thread block's move and how it prints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    pub from: Pt,
    pub to: Pt,
    pub lead: f64,
    /// G34: the lead change per revolution.
    pub dlead: Option<f64>,
    /// The start angle in degrees (0: not printed).
    pub q: f64,
}

/// A run-out: `j` on the short axis (signed), `k` along the long axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Runout {
    pub j: f64,
    pub k: f64,
}

impl Move {
    /// Z is the long axis when it moves at least as far as X (a radius).
    pub fn z_long(&self) -> bool {
        z_is_long(self.to.r - self.from.r, self.to.z - self.from.z)
    }

    pub fn long_length(&self) -> f64 {
        if self.z_long() {
            (self.to.z - self.from.z).abs()
        } else {
            (self.to.r - self.from.r).abs()
        }
    }

    /// The lead after `s` mm along the long axis (§17: ℓ = √(F² + 2Rs)).
    pub fn lead_at(&self, s: f64) -> f64 {
        let r = self.dlead.unwrap_or(0.0);
        libm::sqrt((self.lead * self.lead + 2.0 * r * s).max(0.0))
    }

    /// The lead where the run-out `ro` begins, k before the end.
    pub fn lead_at_runout(&self, ro: Runout) -> f64 {
        self.lead_at(self.long_length() - ro.k)
    }

    /// The move as one leg.
    pub fn plain(&self) -> Leg {
        Leg::Thread {
            to: self.to,
            lead: self.lead,
            dlead: self.dlead,
            q: start_angle(self.q),
        }
    }

    /// The move with its run-out (§16.5): up to P1, k before the end along
    /// the long axis, then to the end's long-axis coordinate, lifted j on
    /// the short axis, at lead·max(1, |j|/k).
    pub fn with_runout(&self, ro: Runout) -> [Leg; 2] {
        let (dr, dz) = (self.to.r - self.from.r, self.to.z - self.from.z);
        let (p1, lifted) = if self.z_long() {
            let z1 = self.to.z - sign(dz) * ro.k;
            let r1 = self.from.r + (z1 - self.from.z) / dz * dr;
            (Pt::new(r1, z1), Pt::new(r1 + ro.j, self.to.z))
        } else {
            let r1 = self.to.r - sign(dr) * ro.k;
            let z1 = self.from.z + (r1 - self.from.r) / dr * dz;
            (Pt::new(r1, z1), Pt::new(self.to.r, z1 + ro.j))
        };
        let f = (ro.j.abs() / ro.k).max(1.0);
        let first = Leg::Thread {
            to: p1,
            lead: self.lead,
            dlead: self.dlead,
            q: start_angle(self.q),
        };
        let second = Leg::Thread {
            to: lifted,
            lead: self.lead_at_runout(ro) * f,
            dlead: self.dlead.map(|d| d * f),
            q: None,
        };
        [first, second]
    }
}

pub fn start_angle(q: f64) -> Option<f64> {
    (q.abs() > EPS).then_some(q)
}

/// The run-out this move gets if it ends its chain, from the J/K words
/// in force; J = 0 or K = 0 is none, and k must be shorter than the move (E4010).
pub fn runout(words: Option<(f64, f64)>, mv: &Move) -> Result<Option<Runout>, NcError> {
    let Some((j, k)) = words else {
        return Ok(None);
    };
    if j.abs() <= EPS || k <= EPS {
        return Ok(None);
    }
    let length = mv.long_length();
    if k >= length - EPS {
        return fail(
            Alarm::BadThread,
            format!("the run-out K{k:.4} is not shorter than the thread move ({length:.4} mm)"),
        );
    }
    Ok(Some(Runout { j, k }))
}

/// Angles closer than this (radians) are the same.
const ANGLE_EPS: f64 = 1e-9;

/// The lead is measured along one axis for the whole arc: Z if its
/// tangent has |dZ| ≥ |dr| everywhere, X if |dr| ≥ |dZ| everywhere; an arc
/// that crosses a 45° direction has neither (E4010).
///
/// At the angle θ of a point about the centre (from +Z towards +r) the
/// tangent's |dZ| : |dr| is |sin θ| : |cos θ|, so the classes change only
/// at θ = 45° + n·90°: the arc must not pass one strictly inside.
pub fn check_long_axis(from: Pt, to: Pt, c: Pt, cw: bool) -> Result<(), NcError> {
    let a0 = libm::atan2(from.r - c.r, from.z - c.z);
    let a1 = libm::atan2(to.r - c.r, to.z - c.z);
    // The sweep in the arc's direction; end = start is a full circle.
    let mut sweep = crate::base::geom::rem_euclid(if cw { a0 - a1 } else { a1 - a0 }, TAU);
    if sweep < ANGLE_EPS {
        sweep = TAU;
    }
    let dir = if cw { -1.0 } else { 1.0 };
    for n in 0..4 {
        let boundary = FRAC_PI_4 + f64::from(n) * FRAC_PI_2;
        // How far along the arc the boundary lies.
        let at = crate::base::geom::rem_euclid(dir * (boundary - a0), TAU);
        if at > ANGLE_EPS && at < sweep - ANGLE_EPS {
            return fail(
                Alarm::BadThread,
                "G32.2/G32.3: the arc has no single long axis (its tangent crosses 45°)",
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_out_lifts_at_k_before_the_end() {
        // Along Z from z 0 to z -20 at r 10, J 1 K 2: thread to z -18,
        // then to z -20 lifted 1 (r 11) at lead·max(1, 1/2) = the lead.
        let mv = Move {
            from: Pt::new(10.0, 0.0),
            to: Pt::new(10.0, -20.0),
            lead: 1.5,
            dlead: None,
            q: 0.0,
        };
        let ro = runout(Some((1.0, 2.0)), &mv).unwrap().unwrap();
        let [a, b] = mv.with_runout(ro);
        assert_eq!(
            a,
            Leg::Thread {
                to: Pt::new(10.0, -18.0),
                lead: 1.5,
                dlead: None,
                q: None
            }
        );
        assert_eq!(
            b,
            Leg::Thread {
                to: Pt::new(11.0, -20.0),
                lead: 1.5,
                dlead: None,
                q: None
            }
        );
        // J0 is no run-out; K as long as the move is E4010.
        assert_eq!(runout(Some((0.0, 2.0)), &mv).unwrap(), None);
        assert_eq!(runout(Some((1.0, 20.0)), &mv).unwrap_err().code, 4010);
    }
}
