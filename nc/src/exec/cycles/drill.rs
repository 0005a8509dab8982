//! The drilling and rigid tapping cycles of group 10: G83/G87 peck
//! drilling, G84/G88 rigid tapping with the M29 rules, G80 (cycles.md §21,
//! §22).

use alloc::vec::Vec;

use super::legs::{self, Leg};
use super::words;
use super::{lead, Func};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{Drill, G};
use crate::base::mcode::M;
use crate::base::words::addr;
use crate::block::{round_half_away, Parsed};
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::drill::{drill_path, tap_holes, Holes, Pecks};

/// The data of the drilling cycle in force, and the rigid tapping mode.
#[derive(Debug, Clone, Default)]
pub(crate) struct DrillState {
    /// The group-10 code the data belongs to (`None`: none yet).
    code: Option<Drill>,
    data: Data,
    /// An M29 waits for its G84/G88 block.
    m29: bool,
    /// A G84/G88 has tapped: later holes of the run tap without M29.
    rigid: bool,
    /// The clamp code of the block being executed.
    clamp: Option<M>,
}

/// What a block that names the cycle starts afresh and later blocks may
/// change (§21 "Which block drills").
#[derive(Debug, Clone, Copy, Default)]
struct Data {
    /// The bottom along the drilling axis (Z, or r for G87/G88).
    bottom: Option<f64>,
    /// Peck depth and retract per peck (mm, along the drilling axis).
    peck: f64,
    retract: f64,
    dwell_ms: f64,
    /// J1: deep-hole pecking (back to the start level after each peck).
    deep: bool,
    /// G84/G88: the lead of the run, signed (F < 0 left-hand).
    lead: Option<f64>,
}

/// Before the block's group 1: the M29 rules (§22) and the clamp code of a
/// drilling block, which `before_motion` must not print as a PLC M code.
/// M codes with their own meaning keep it in a drilling block; any other
/// (PLC) code there is the cycle's clamp code α (canon.md block order,
/// `M::can_clamp`).
pub(crate) fn before_block(nc: &mut Nc, f: Func, p: &Parsed) -> Result<Option<M>, NcError> {
    // C/H count as axis words on a machine with a C axis.
    let moves = nc.axis_words(p);
    let st = &mut nc.st.cycles.drill;
    // (Only M29 or a rigid cycle leaves something to clear.)
    if st.m29 || st.rigid {
        if p.has_g(Drill::Off) || p.ends_program() {
            st.m29 = false;
            st.rigid = false;
        }
        if p.has_g(Drill::FaceDrill) || p.has_g(Drill::SideDrill) || p.motion().is_some() {
            st.rigid = false;
        }
    }
    let drills = matches!(f, Func::Drill(_)) && moves;
    let taps = drills && matches!(f, Func::Drill(d) if d.taps());
    if let Some(n) = p.ms().iter().position(|&m| m == M::RigidTapping) {
        if st.m29 {
            let msg = "a second M29 before the G84/G88 block";
            return Err(NcError::new(Alarm::IncompatibleWords, msg).on_nth(addr(b'M'), n));
        }
        st.m29 = true;
    }
    if st.m29 && moves && !taps {
        return fail(
            Alarm::IncompatibleWords,
            "no move may come between M29 and its G84/G88 tapping block",
        );
    }
    st.clamp = None;
    if drills {
        if p.ms().len() > 1 {
            let msg = "a drilling block takes one M word (the clamp code)";
            return Err(NcError::new(Alarm::IncompatibleWords, msg).on_nth(addr(b'M'), 1));
        }
        st.clamp = p.ms().first().copied().filter(|m| m.can_clamp());
    }
    Ok(st.clamp)
}

/// [`before_block`] for a plain move (`cycles::before_plain_block`): it
/// moves, has no M word and is no drilling block. Its group-1 code ends a
/// rigid run; a move after M29 is an alarm.
pub(crate) fn before_plain_block(nc: &mut Nc, p: &Parsed) -> Result<(), NcError> {
    let st = &mut nc.st.cycles.drill;
    if p.motion().is_some() {
        st.rigid = false;
    }
    if st.m29 {
        return fail(
            Alarm::IncompatibleWords,
            "no move may come between M29 and its G84/G88 tapping block",
        );
    }
    st.clamp = None;
    Ok(())
}

/// A block while G83, G84, G87 or G88 is in force.
pub(crate) fn run(
    nc: &mut Nc,
    code: Drill,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    // block.rs sees H only in a block that names the cycle.
    if !nc.machine.axes.c.enabled && p.has(b'H') {
        let msg = "this machine has no C axis (H is the incremental hole angle)";
        return Err(NcError::new(Alarm::AxisNotConfigured, msg).on_addr(addr(b'H')));
    }
    take_data(nc, code, p)?;
    // A block with only C/H drills the same hole at another angle.
    if !nc.axis_words(p) {
        return Ok(());
    }
    let repeats = words::count(p, b'K')?.unwrap_or(1);
    let holes = holes_of_block(nc, code, p)?;
    let path = if code.taps() {
        tap_path(nc, &holes, repeats).map_err(|e| on_the_code(e, p))?
    } else {
        let d = nc.st.cycles.drill.data;
        let pecks = Pecks {
            peck: d.peck,
            retract: d.retract,
            deep: d.deep,
        };
        drill_path(&holes, &pecks, repeats)?
    };
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

/// E2007 of a tapping block (no M29 before it) stands on its G84/G88
/// where it names one, else on the block (a repeat).
fn on_the_code(e: NcError, p: &Parsed) -> NcError {
    let code = p.gs().position(|g| matches!(g, G::Drill(d) if d.taps()));
    match code {
        Some(n) if e.alarm() == Some(Alarm::IncompatibleWords) => e.on_nth(addr(b'G'), n),
        _ => e,
    }
}

/// A block naming the code starts new data; every block may change it.
fn take_data(nc: &mut Nc, code: Drill, p: &Parsed) -> Result<(), NcError> {
    let mut d = nc.st.cycles.drill.data;
    if p.has_g(code) || nc.st.cycles.drill.code != Some(code) {
        d = Data::default();
    }
    let tapping = code.taps();
    if tapping {
        if let Some(l) = lead::written(nc, p, true) {
            d.lead = Some(l);
        }
    } else {
        if let Some(q) = words::increments(nc, p, b'Q') {
            d.peck = q.abs();
        }
        if let Some(r) = nc.len_of(p, b'R') {
            d.retract = r.abs();
        }
        if let Some(j) = p.get(b'J') {
            // J1 is deep-hole pecking; anything else the high-speed one.
            d.deep = round_half_away(j) == 1.0;
        }
    }
    if let Some(ms) = p.get(b'P') {
        d.dwell_ms = round_half_away(ms).max(0.0);
    }
    nc.st.cycles.drill.code = Some(code);
    nc.st.cycles.drill.data = d;
    Ok(())
}

/// The holes of a block from its words and the drilling data.
fn holes_of_block(nc: &mut Nc, code: Drill, p: &Parsed) -> Result<Holes, NcError> {
    let along_z = code.along_z();
    let here = nc.st.pos;
    let (abs_pos, inc_pos, abs_s, inc_s) = if along_z {
        (b'X', b'U', b'Z', b'W')
    } else {
        (b'Z', b'W', b'X', b'U')
    };
    // X and U are X values; the drilling coordinate of G87 is r.
    let word = |letter: u8| match letter {
        b'X' | b'U' => nc.radial_of(p, letter),
        _ => nc.len_of(p, letter),
    };
    let (at_pos, at_s) = if along_z {
        (here.r, here.z)
    } else {
        (here.z, here.r)
    };
    let step = word(inc_pos).unwrap_or(0.0);
    let pos = word(abs_pos).unwrap_or(at_pos + step);
    let s1 = if let Some(v) = word(abs_s) {
        v
    } else if let Some(v) = word(inc_s) {
        at_s + v
    } else {
        match nc.st.cycles.drill.data.bottom {
            Some(b) => b,
            None => {
                return fail(
                    Alarm::MissingWord,
                    "the first drilling block needs the hole's bottom",
                )
            }
        }
    };
    nc.st.cycles.drill.data.bottom = Some(s1);
    Ok(Holes {
        along_z,
        pos,
        step,
        s0: at_s,
        s1,
        c: crate::exec::caxis::target_from(nc, p, nc.st.c),
        c_step: crate::exec::caxis::step(nc, p),
        dwell_s: nc.st.cycles.drill.data.dwell_ms / 1000.0,
        clamp: nc.st.cycles.drill.clamp.map(|m| m.code().into()),
    })
}

/// G84/G88: the M29 rule and the lead, then the tapping holes (§22); the
/// hand is the lead's sign.
fn tap_path(nc: &mut Nc, h: &Holes, repeats: i64) -> Result<Vec<Leg>, NcError> {
    if repeats < 1 {
        return Ok(Vec::new());
    }
    let st = &nc.st.cycles.drill;
    if !st.m29 && !st.rigid {
        return fail(
            Alarm::IncompatibleWords,
            "rigid tapping G84/G88 needs M29 S… before it",
        );
    }
    let lead = match st.data.lead {
        Some(l) => l,
        None => lead::resolve(nc, None)?,
    };
    lead::check(nc, lead.abs())?;
    let out = tap_holes(h, lead, nc.st.spindle, repeats)?;
    let st = &mut nc.st.cycles.drill;
    st.m29 = false;
    st.rigid = true;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{run, run_err, Lathe};
    use alloc::format;
    use alloc::string::ToString;
    use alloc::vec;
    use alloc::vec::Vec;

    #[test]
    fn g83_last_partial_peck_and_repeats_with_u() {
        // From X10 Z2: G83 U10 Z-9 Q4000 R0.5 K2 M12 F0.1: holes at X20
        // and X30 (U applied per repeat); pecks at -2, -6, then -10 passes
        // -9 → -9; J0 retracts 0.5.
        let mut m = Lathe::new();
        m.run("M03 S500");
        m.run("G99 G00 X10 Z2");
        let l = m.run("G83 U10 Z-9 Q4000 R0.5 K2 M12 F0.1");
        let hole = |x: &str| {
            vec![
                format!("RAPID X={x} Z=2"),
                "M CODE=12".to_string(),
                format!("LINE X={x} Z=-2"),
                format!("RAPID X={x} Z=-1.5"),
                format!("LINE X={x} Z=-6"),
                format!("RAPID X={x} Z=-5.5"),
                format!("LINE X={x} Z=-9"),
                format!("RAPID X={x} Z=2"),
                "M CODE=13".to_string(),
            ]
        };
        let mut want = hole("20");
        want.insert(2, "FEED F=0.1 MODE=REV".into());
        want.extend(hole("30"));
        assert_eq!(l, want);
    }

    #[test]
    fn g83_deep_pecks_clamp_their_retract_at_the_start() {
        // Z0 → Z-7, Q3000 R5 J1: the first re-entry 5 short of -3 would be
        // +2, behind the start level Z0: it is Z0 (left out, the tool is
        // there); the second 5 short of -6 is -1.
        let l = run(&["G00 X0 Z0", "G83 Z-7 Q3000 R5 J1 F50"]);
        assert_eq!(
            l[1..],
            [
                "FEED F=50 MODE=MIN",
                "LINE X=0 Z=-3",
                "RAPID X=0 Z=0",
                "LINE X=0 Z=-6",
                "RAPID X=0 Z=0",
                "RAPID X=0 Z=-1",
                "LINE X=0 Z=-7",
                "RAPID X=0 Z=0"
            ]
        );
    }

    #[test]
    fn g87_drills_along_x_in_radius() {
        // Side drilling at Z-10 from X40 to X30: Q2000 pecks 2 mm in
        // radius: r 20 → 18 → 16 → 15, J0 R0.5 back in radius.
        let l = run(&["G00 X40 Z0", "G87 Z-10 X30 Q2000 R0.5 F60 P1500"]);
        assert_eq!(
            l[1..],
            [
                "RAPID X=40 Z=-10",
                "FEED F=60 MODE=MIN",
                "LINE X=36 Z=-10",
                "RAPID X=37 Z=-10",
                "LINE X=32 Z=-10",
                "RAPID X=33 Z=-10",
                "LINE X=30 Z=-10",
                "DWELL S=1.5",
                "RAPID X=40 Z=-10"
            ]
        );
    }

    #[test]
    fn drilling_data_and_errors() {
        // The first drilling block needs its bottom.
        assert_eq!(run_err(&["G00 X0 Z2", "G83 X0 F0.1"]), 2006);
        // Two M words in a drilling block.
        assert_eq!(run_err(&["G00 X0 Z2", "G83 Z-5 M12 M08 F1"]), 2007);
        // A block without axis words sets data only; naming G83 again
        // starts new data (no pecks).
        let mut m = Lathe::new();
        m.run("G00 X0 Z2");
        m.run("G83 Z-5 Q1000 R0.2 F100");
        assert!(m.run("Q2000").is_empty());
        // Pecks at 0 and -2 with their retracts, the bottom, the return.
        assert_eq!(m.run("Z-3").len(), 2 + 2 + 1 + 1);
        assert_eq!(m.run("G83 Z-3"), ["LINE X=0 Z=-3", "RAPID X=0 Z=2"]);
        // A PLC code that is not in a drilling block is printed.
        assert_eq!(m.run("M08"), ["M CODE=8"]);
    }

    #[test]
    fn m29_rules() {
        let e = |b: &[&str]| run_err(b);
        // A move between M29 and G84.
        assert_eq!(e(&["M03", "M29 S300", "G00 X0 Z5", "G84 Z-10 F1"]), 2007);
        // A second M29.
        assert_eq!(e(&["M03", "M29 S300", "M29 S300"]), 2007);
        // G80 forgets the M29; a group-01 code alone does not.
        assert_eq!(e(&["M29 S300", "G80", "G84 Z-10 F1"]), 2007);
        assert_eq!(e(&["M29 S300", "G00", "G84 Z-10 F1"]), 0);
        // Rigid mode lasts through the run, and ends with G80.
        let mut m = Lathe::new();
        m.run("M03 S300");
        m.run("M29 S300");
        m.run("G84 Z-10 F1 K2");
        m.run("Z-12");
        m.run("G80");
        assert_eq!(m.try_run("G84 Z-10 F1"), Err(2007));
    }

    #[test]
    fn tapping_holes_and_the_spindle() {
        // Spindle stopped: the first hole starts it CW; K2 taps twice,
        // the second hole finds the spindle CW already. M12 clamps.
        let l = run(&["G00 X0 Z3", "M29 S200", "G84 Z-8 F1.25 K2 M12"]);
        let hole = |first: bool| {
            let mut v = vec!["RAPID X=0 Z=3", "M CODE=12"];
            if first {
                v.push("SPINDLE DIR=CW");
            }
            v.extend([
                "THREAD X=0 Z=-8 LEAD=1.25",
                "SPINDLE DIR=CCW",
                "THREAD X=0 Z=3 LEAD=1.25",
                "SPINDLE DIR=CW",
                "M CODE=13",
            ]);
            v
        };
        let mut want: Vec<&str> = vec!["RAPID X=0 Z=3", "M CODE=29", "SPEED S=200 MODE=RPM"];
        // Both holes are at the tool's point: their positioning rapids are
        // zero-length cycle legs, left out.
        want.extend(hole(true).into_iter().skip(1));
        want.extend(hole(false).into_iter().skip(1));
        assert_eq!(l, want);
    }
}
