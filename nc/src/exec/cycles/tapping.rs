//! Tapping: G33 with a floating holder (cycles.md §20) and the rigid
//! tapping hole of G84/G88 (§22).

use alloc::format;
use alloc::vec::Vec;

use super::legs::{self, thread, Leg};
use super::{lead, words};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::SpindleDir;
use crate::base::point::Pt;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};

fn reverse(dir: SpindleDir) -> SpindleDir {
    match dir {
        SpindleDir::Cw => SpindleDir::Ccw,
        SpindleDir::Ccw => SpindleDir::Cw,
        SpindleDir::Stop => SpindleDir::Stop,
    }
}

/// A G33 block: taps along Z at the current X, once per start.
pub(crate) fn g33(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    if p.has(b'X') || p.has(b'U') {
        return fail(
            Alarm::IncompatibleWords,
            "G33 taps along Z at the current X: X/U cannot stand in a G33 block",
        );
    }
    let written = lead::written(nc, p, true);
    lead::remember(nc, written);
    let starts = words::count(p, b'L')?.unwrap_or(1);
    if !p.has(b'Z') && !p.has(b'W') {
        return Ok(());
    }
    let lead = lead::resolve(nc, written)?;
    if starts < 1 {
        return fail(
            Alarm::BadThread,
            format!("G33 L{starts}: a thread has at least one start"),
        );
    }
    let dir = nc.st.spindle;
    if dir == SpindleDir::Stop {
        return fail(
            Alarm::SpindleStopped,
            "G33 needs the spindle turning (M03 or M04): its reverse is undefined",
        );
    }
    let a = nc.st.pos;
    let bottom = Pt::new(a.r, nc.target(p).z);
    let path = g33_path(a, bottom, lead, starts, dir)?;
    // The moves of G33 are programmed: printed even when of zero length.
    legs::emit(nc, &path, false, sink);
    out.moved = true;
    Ok(())
}

/// For each start: (restart), tap to the bottom, stop, reverse, back out,
/// stop (§20).
fn g33_path(
    a: Pt,
    bottom: Pt,
    lead: f64,
    starts: i64,
    dir: SpindleDir,
) -> Result<Vec<Leg>, NcError> {
    let mut out = Vec::new();
    for j in 0..starts {
        if out.len() > words::MAX_LEGS {
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
pub(crate) struct Hole {
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
pub(crate) fn tap_hole(h: &Hole, dir: SpindleDir, spindle: &mut SpindleDir, out: &mut Vec<Leg>) {
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
    use crate::exec::cycles::testing::{run, run_err, Lathe};
    use alloc::format;
    use alloc::string::String;
    use alloc::vec;
    use alloc::vec::Vec;

    #[test]
    fn g33_three_starts_from_a_ccw_spindle() {
        // M04: S = CCW, S' = CW. Q 0, 120, 240; restart before starts 2, 3.
        let l = run(&["M04 S100", "G00 X0 Z5", "G33 Z-10 F1 L3"]);
        let cycle: Vec<&str> = l[3..].iter().map(String::as_str).collect();
        let one = |q: &str| {
            vec![
                format!("THREAD X=0 Z=-10 LEAD=1{q}"),
                "SPINDLE DIR=STOP".into(),
                "SPINDLE DIR=CW".into(),
                "THREAD X=0 Z=5 LEAD=1".into(),
                "SPINDLE DIR=STOP".into(),
            ]
        };
        let mut want = one("");
        want.push("SPINDLE DIR=CCW".into());
        want.extend(one(" Q=120"));
        want.push("SPINDLE DIR=CCW".into());
        want.extend(one(" Q=240"));
        assert_eq!(cycle, want);
    }

    #[test]
    fn g33_rules() {
        // Modal: the next Z block taps again (the spindle stopped: E7003).
        let mut m = Lathe::new();
        m.run("M03 S100");
        m.run("G00 X0 Z5");
        m.run("G33 Z-10 F1.5");
        assert_eq!(m.try_run("W-1"), Err(7003));
        m.run("M03");
        let l = m.run("W-12");
        assert_eq!(l[0], "THREAD X=0 Z=-7 LEAD=1.5");
        // X in a G33 block, and L0.
        assert_eq!(run_err(&["M03", "G33 X10 Z-10 F1"]), 2007);
        assert_eq!(run_err(&["M03", "G33 Z-10 F1 L0"]), 4010);
    }
}
