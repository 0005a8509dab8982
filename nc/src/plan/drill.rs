//! The drilling and tapping legs (cycles.md §20–§22): G83/G87 peck
//! drilling, G84/G88 rigid tapping holes and G33 tapping with a floating
//! holder, as paths from the holes and the cycle's data. The executor
//! (`exec::cycles`) reads the words, keeps the drilling data and the M29
//! rules, and prints.

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::SpindleDir;
use crate::base::point::Pt;
use crate::plan::legs::{before, sign, stops, thread, Leg, MAX_LEGS};

/// The pecking of G83/G87: the peck depth and the retract per peck (mm,
/// along the drilling axis), and J1 (deep-hole pecking: back to the start
/// level after each peck).
#[derive(Debug, Clone, Copy, Default)]
pub struct Pecks {
    pub peck: f64,
    pub retract: f64,
    pub deep: bool,
}

/// The holes of one block: along Z at an X (G83/G84) or along X at a Z
/// (G87/G88). `s` is the coordinate along the drilling axis (r for X).
pub struct Holes {
    pub along_z: bool,
    /// The hole position (r, or Z for G87/G88), and how far each repeat
    /// moves it (an incremental position is applied again, §21).
    pub pos: f64,
    pub step: f64,
    pub s0: f64,
    pub s1: f64,
    /// The C angle of the first hole and the turn per repeat (H).
    pub c: f64,
    pub c_step: f64,
    pub dwell_s: f64,
    pub clamp: Option<u32>,
}

impl Holes {
    /// The C angle of hole `n` (0 first).
    pub fn c_at(&self, n: i64) -> f64 {
        self.c + n as f64 * self.c_step
    }

    /// The point of hole `n` (0 first) at `s` along the drilling axis.
    pub fn at(&self, n: i64, s: f64) -> Pt {
        let pos = self.pos + n as f64 * self.step;
        if self.along_z {
            Pt::new(pos, s)
        } else {
            Pt::new(s, pos)
        }
    }
}

/// G83/G87: position, clamp, the pecks (§21 step 3), dwell, back to the
/// start level, unclamp; K times.
pub fn drill_path(h: &Holes, d: &Pecks, repeats: i64) -> Result<Vec<Leg>, NcError> {
    let mut out = Vec::new();
    for n in 0..repeats {
        if out.len() > MAX_LEGS {
            return fail(Alarm::ZeroStep, format!("K{repeats}: too many holes"));
        }
        out.push(Leg::RapidC(h.at(n, h.s0), h.c_at(n)));
        if let Some(m) = h.clamp {
            out.push(Leg::M(m));
        }
        for (rapid, s) in feed_to_bottom(h.s0, h.s1, d)? {
            let to = h.at(n, s);
            out.push(if rapid { Leg::Rapid(to) } else { Leg::Line(to) });
        }
        if h.dwell_s > 0.0 {
            out.push(Leg::Dwell(h.dwell_s));
        }
        out.push(Leg::Rapid(h.at(n, h.s0)));
        if let Some(m) = h.clamp {
            out.push(Leg::M(m.saturating_add(1)));
        }
    }
    Ok(out)
}

/// The feed to the bottom along the drilling axis: (rapid?, s) steps.
/// Without a peck (or J0 without a retract) one feed; otherwise a feed to
/// each peck depth, then J0: back R (never behind s0), J1: out to s0 and
/// in again to R short of the depth reached; the last feed reaches s1.
pub fn feed_to_bottom(s0: f64, s1: f64, d: &Pecks) -> Result<Vec<(bool, f64)>, NcError> {
    if d.peck <= 0.0 || (!d.deep && d.retract <= 0.0) {
        return Ok(vec![(false, s1)]);
    }
    let sd = sign(s1 - s0);
    // A retract point behind the start level is the start level.
    let back = |t: f64| {
        let p = t - sd * d.retract;
        if sd * (p - s0) < 0.0 {
            s0
        } else {
            p
        }
    };
    let mut out = Vec::new();
    for t in stops(s0, s1, d.peck, Alarm::ZeroStep)? {
        out.push((false, t));
        if !before(s0, s1, t) {
            break;
        }
        if d.deep {
            out.push((true, s0));
        }
        out.push((true, back(t)));
    }
    Ok(out)
}

/// The rigid tapping holes of G84/G88 (§22): K times a hole; the tap
/// turns CW for a right-hand (positive) lead, CCW for a left-hand one;
/// `spindle` is the spindle's direction before the first hole.
pub fn tap_holes(
    h: &Holes,
    lead: f64,
    spindle: SpindleDir,
    repeats: i64,
) -> Result<Vec<Leg>, NcError> {
    let dir = if lead < 0.0 {
        SpindleDir::Ccw
    } else {
        SpindleDir::Cw
    };
    let mut spindle = spindle;
    let mut out = Vec::new();
    for n in 0..repeats {
        if out.len() > MAX_LEGS {
            return fail(Alarm::ZeroStep, format!("K{repeats}: too many holes"));
        }
        let hole = Hole {
            top: h.at(n, h.s0),
            bottom: h.at(n, h.s1),
            c: h.c_at(n),
            lead: lead.abs(),
            dwell_s: h.dwell_s,
            clamp: h.clamp,
        };
        tap_hole(&hole, dir, &mut spindle, &mut out);
    }
    Ok(out)
}

/// The other turning direction (a stopped spindle stays stopped).
pub fn reverse(dir: SpindleDir) -> SpindleDir {
    match dir {
        SpindleDir::Cw => SpindleDir::Ccw,
        SpindleDir::Ccw => SpindleDir::Cw,
        SpindleDir::Stop => SpindleDir::Stop,
    }
}

/// For each start: (restart), tap to the bottom, stop, reverse, back out,
/// stop (§20).
pub fn g33_path(
    a: Pt,
    bottom: Pt,
    lead: f64,
    starts: i64,
    dir: SpindleDir,
) -> Result<Vec<Leg>, NcError> {
    let mut out = Vec::new();
    for j in 0..starts {
        if out.len() > MAX_LEGS {
            return fail(Alarm::BadThread, format!("G33 L{starts}: too many starts"));
        }
        if j > 0 {
            out.push(Leg::Spindle(dir));
        }
        out.push(thread(bottom, lead, j as f64 * 360.0 / starts as f64));
        out.push(Leg::Spindle(SpindleDir::Stop));
        out.push(Leg::Spindle(reverse(dir)));
        out.push(thread(a, lead, 0.0));
        out.push(Leg::Spindle(SpindleDir::Stop));
    }
    Ok(out)
}

/// One rigid tapping hole: its top (at the start level) and bottom.
pub struct Hole {
    pub top: Pt,
    pub bottom: Pt,
    /// The hole's C angle (degrees).
    pub c: f64,
    pub lead: f64,
    pub dwell_s: f64,
    pub clamp: Option<u32>,
}

/// The legs of a rigid tapping hole (§22): the tap turns `dir` (CW for a
/// right-hand lead); `spindle`, the spindle's direction before the hole,
/// is `dir` after it.
pub fn tap_hole(h: &Hole, dir: SpindleDir, spindle: &mut SpindleDir, out: &mut Vec<Leg>) {
    out.push(Leg::RapidC(h.top, h.c));
    if let Some(m) = h.clamp {
        out.push(Leg::M(m));
    }
    if *spindle != dir {
        out.push(Leg::Spindle(dir));
    }
    out.push(thread(h.bottom, h.lead, 0.0));
    if h.dwell_s > 0.0 {
        out.push(Leg::Dwell(h.dwell_s));
    }
    out.push(Leg::Spindle(reverse(dir)));
    out.push(thread(h.top, h.lead, 0.0));
    // Turning the tapping way again, ready for the next hole.
    out.push(Leg::Spindle(dir));
    *spindle = dir;
    if let Some(m) = h.clamp {
        out.push(Leg::M(m.saturating_add(1)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One hole along Z at r 5 from z 2 down to z -7.
    fn hole() -> Holes {
        Holes {
            along_z: true,
            pos: 5.0,
            step: 0.0,
            s0: 2.0,
            s1: -7.0,
            c: 0.0,
            c_step: 0.0,
            dwell_s: 0.0,
            clamp: None,
        }
    }

    #[test]
    fn g83_pecks_back_off_by_the_retract() {
        // Pecks of 4 from z 2: -2, -6, then the bottom -7 (cycles.md §21);
        // after each peck short of the bottom a rapid back by R1.
        let at = |z| Pt::new(5.0, z);
        let pecks = Pecks {
            peck: 4.0,
            retract: 1.0,
            deep: false,
        };
        assert_eq!(
            drill_path(&hole(), &pecks, 1).unwrap(),
            [
                Leg::RapidC(at(2.0), 0.0),
                Leg::Line(at(-2.0)),
                Leg::Rapid(at(-1.0)),
                Leg::Line(at(-6.0)),
                Leg::Rapid(at(-5.0)),
                Leg::Line(at(-7.0)),
                Leg::Rapid(at(2.0)),
            ]
        );
    }

    #[test]
    fn a_left_hand_tap_turns_ccw_in_and_cw_out() {
        // F-1.5: the tap turns CCW to the bottom, CW back to the top, and
        // CCW again ready for the next hole (§22); the lead printed is |F|.
        let legs = tap_holes(&hole(), -1.5, SpindleDir::Stop, 1).unwrap();
        assert_eq!(
            legs,
            [
                Leg::RapidC(Pt::new(5.0, 2.0), 0.0),
                Leg::Spindle(SpindleDir::Ccw),
                thread(Pt::new(5.0, -7.0), 1.5, 0.0),
                Leg::Spindle(SpindleDir::Cw),
                thread(Pt::new(5.0, 2.0), 1.5, 0.0),
                Leg::Spindle(SpindleDir::Ccw),
            ]
        );
    }
}
