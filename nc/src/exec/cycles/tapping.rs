//! Tapping: G33 with a floating holder (cycles.md §20) and the rigid
//! tapping hole of G84/G88 (§22).

use alloc::format;

use super::legs;
use super::{lead, words};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::SpindleDir;
use crate::base::point::Pt;
use crate::base::words::addr;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::drill::g33_path;

/// A G33 block: taps along Z at the current X, once per start.
pub(crate) fn g33(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    if p.has(b'X') || p.has(b'U') {
        let msg = "G33 taps along Z at the current X: X/U cannot stand in a G33 block";
        let e = NcError::new(Alarm::IncompatibleWords, msg);
        return Err(e.on_pair(addr(b'X'), addr(b'U')));
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
    legs::emit(nc, &path, false, sink)?;
    out.moved = true;
    Ok(())
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
