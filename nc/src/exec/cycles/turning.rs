//! G90 turning and G94 facing (cycles.md §1, §2), and the run values that
//! G90, G92 and G94 keep from one modal repetition to the next (§4).

use alloc::format;

use super::legs::{self, Leg};
use super::words;
use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::Motion;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};
pub(crate) use crate::plan::single::{g90_legs, g94_legs, Cycle};

/// What a block leaves out keeps the value of the previous cycle of the
/// same run: the end point, R and (G92) L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Run {
    pub code: Motion,
    /// The end point's r and Z; `None` until a cycle of the run gives them
    /// (they then default to the start point A).
    pub r: Option<f64>,
    pub z: Option<f64>,
    pub taper: f64,
    pub starts: i64,
}

impl Run {
    fn new(code: Motion) -> Run {
        Run {
            code,
            r: None,
            z: None,
            taper: 0.0,
            starts: 1,
        }
    }
}

/// The values of this block's cycle of the `code` run, from its words and
/// the previous cycle's; a new run starts when the block wrote the code or
/// a run of another code was in force. The run keeps them.
pub(crate) fn next_cycle(nc: &mut Nc, code: Motion, p: &Parsed) -> Result<Cycle, NcError> {
    let a = nc.st.pos;
    let mut run = match nc.st.cycles.run {
        Some(run) if run.code == code => run,
        _ => Run::new(code),
    };
    let r = if let Some(r) = nc.radial_of(p, b'X') {
        r
    } else if let Some(u) = nc.radial_of(p, b'U') {
        a.r + u
    } else {
        run.r.unwrap_or(a.r)
    };
    let z = if let Some(z) = nc.len_of(p, b'Z') {
        z
    } else if let Some(w) = nc.len_of(p, b'W') {
        a.z + w
    } else {
        run.z.unwrap_or(a.z)
    };
    let taper = words::length_or(nc, p, b'R', run.taper);
    let mut starts = run.starts;
    if matches!(code, Motion::ThreadCycle | Motion::RigidThreadCycle) {
        starts = words::count(p, b'L')?.unwrap_or(starts);
        if starts < 1 {
            return fail(
                Alarm::BadThread,
                format!("L{starts}: a thread has at least one start"),
            );
        }
    }
    run = Run {
        code,
        r: Some(r),
        z: Some(z),
        taper,
        starts,
    };
    nc.st.cycles.run = Some(run);
    Ok(Cycle {
        a,
        end: Pt::new(r, z),
        taper,
        starts,
    })
}

/// A G90 or G94 block: a block without an axis word does not cut (§4).
pub(crate) fn run(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    if !p.has_axis() {
        return Ok(());
    }
    let c = next_cycle(nc, code, p)?;
    let mut path = if code == Motion::TurningCycle {
        g90_legs(&c)
    } else {
        g94_legs(&c)
    };
    if let [Leg::Rapid(s), Leg::Line(e), Leg::Line(f), _] = &mut path {
        // Under G41/G42 the cut and the retract are moved (comp.md §9).
        crate::exec::comp::turning_cycle(nc, code == Motion::FacingCycle, c.a, [s, e, f])?;
    }
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{run, run_err, Lathe};

    #[test]
    fn g90_taper_with_r_and_its_modal_repetition() {
        // From X60 Z3: G90 X50 Z-30 R-4: the cut starts at X50 + 2·(-4) =
        // X42, ends at X50 Z-30, X back at feed to X60, rapid to A.
        let mut m = Lathe::new();
        m.run("G98 G00 X60 Z3");
        let legs = m.run("G90 X50 Z-30 R-4 F150");
        assert_eq!(
            legs,
            [
                "RAPID X=42 Z=3",
                "FEED F=150 MODE=MIN",
                "LINE X=50 Z=-30",
                "LINE X=60 Z=-30",
                "RAPID X=60 Z=3"
            ]
        );
        // W-10 from A (Z3) is Z-7; X and R kept: start X42 again.
        let legs = m.run("W-10");
        assert_eq!(
            legs,
            [
                "RAPID X=42 Z=3",
                "LINE X=50 Z=-7",
                "LINE X=60 Z=-7",
                "RAPID X=60 Z=3"
            ]
        );
        // A block without an axis word does not cut.
        assert!(m.run("R-1").is_empty());
        // Writing G90 again starts a new run: R back to 0, Z back to A's.
        // (The cut to Z3 and the return to A have zero length: left out.)
        let legs = m.run("G90 X56");
        assert_eq!(legs, ["RAPID X=56 Z=3", "LINE X=60 Z=3"]);
    }

    #[test]
    fn g94_taper_face_cuts_from_z_plus_r() {
        // From X80 Z5: G94 X30 Z-3 R-6: start at Z-3-6 = Z-9 on X80.
        let mut m = Lathe::new();
        m.run("G00 X80 Z5");
        let legs = m.run("G94 X30 Z-3 R-6 F100");
        assert_eq!(
            legs,
            [
                "RAPID X=80 Z=-9",
                "FEED F=100 MODE=MIN",
                "LINE X=30 Z=-3",
                "LINE X=30 Z=5",
                "RAPID X=80 Z=5"
            ]
        );
        // A one-shot code ends the run: the next block's Z defaults to A.
        m.run("G04 P10");
        let legs = m.run("X20");
        assert_eq!(legs[0], "RAPID X=80 Z=-9");
        m.run("G28 U0");
        // G28 took X home (X0): A = X0 Z5, a new run from there.
        let legs = m.run("X20");
        assert_eq!(legs, ["LINE X=20 Z=5", "RAPID X=0 Z=5"]);
    }

    #[test]
    fn g90_under_g20_converts_r() {
        let legs = run(&["G20 G00 X2. Z0.1", "G90 X1.5 Z-1. R-0.1 F10."]);
        assert_eq!(legs[1], "RAPID X=33.02 Z=2.54");
        assert!(run_err(&["G00 X10", "G90 X5 Z-5 F-1"]) == 1010);
    }
}
