//! Single thread moves: G32, G32.1 (rigid) and G34 (variable lead), their
//! chains and the run-out at a chain's end (cycles.md §16, §17).
//!
//! Only the last block of a chain runs out, and which block is the last is
//! known only when the next NC block arrives. A block with run-out words
//! in force therefore waits (`Chain::pending`, its checks already made and
//! the tool's point already moved) and is printed by `next_block`, at the
//! start of the next block's group 1, with or without its run-out.

use super::legs::Leg;
use super::{lead, Func};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::Motion;
use crate::block::{round_half_away, Parsed};
use crate::exec::{Nc, Outcome, Sink};
pub(crate) use crate::plan::thread::{runout, Move, Runout};

#[derive(Debug, Clone, Default)]
pub(crate) struct Chain {
    /// The last NC block was a G32/G34 move: the next one continues it.
    pub open: bool,
    /// The run-out words (J, K in mm) in force, the missing one derived.
    pub runout: Option<(f64, f64)>,
    /// The block that ends the chain if the next block does not continue
    /// it, with the run-out it then gets, and its block's tag.
    pub pending: Option<(Move, Runout, u32)>,
}

/// Before every block: a waiting block is printed, with its run-out when
/// this block does not continue the chain, and a block that is not a
/// G32/G34 move ends the chain.
pub(crate) fn next_block(nc: &mut Nc, f: Func, p: &Parsed, sink: &mut dyn Sink) {
    let continues = nc.st.cycles.chain.open
        && matches!(f, Func::Motion(Motion::Thread | Motion::VariableThread))
        && p.has_axis();
    if !continues {
        return flush(nc, sink);
    }
    if let Some((mv, _, tag)) = nc.st.cycles.chain.pending.take() {
        print_as(nc.origin, tag, &[mv.plain()], sink);
    }
}

/// The end of a run: a waiting block is the last of its chain.
pub(crate) fn flush(nc: &mut Nc, sink: &mut dyn Sink) {
    nc.st.cycles.chain.open = false;
    // (Most blocks end no chain: asked first, as taking the waiting block
    // copies its room whether it holds one or not.)
    if nc.st.cycles.chain.pending.is_none() {
        return;
    }
    if let Some((mv, ro, tag)) = nc.st.cycles.chain.pending.take() {
        print_as(nc.origin, tag, &mv.with_runout(ro), sink);
    }
}

/// Prints the legs of a block that waited (tagged `tag`) while block
/// `running` runs: the sink is told whose they are ([`Sink::origin`]), so
/// that what is said of them names their own block.
fn print_as(running: u32, tag: u32, legs: &[Leg], sink: &mut dyn Sink) {
    if tag == running {
        return print(legs, sink);
    }
    sink.origin(tag);
    print(legs, sink);
    sink.origin(running);
}

/// Prints thread legs without moving the programmed point: a thread ends
/// where the program put it (the lifted end of a run-out is not the
/// point the next block's U/W count from, §16.5).
fn print(legs: &[Leg], sink: &mut dyn Sink) {
    for leg in legs {
        if let Leg::Thread { to, lead, dlead, q } = *leg {
            // C never moves in a G32/G34 thread (caxis.rs).
            sink.emit(crate::base::event::Event::Thread {
                x: to.x(),
                z: to.z,
                c: None,
                lead,
                dlead,
                q,
            });
        }
    }
}

/// A G32 (320), G32.1 (321) or G34 (340) block.
pub(crate) fn run(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let rigid = code == Motion::RigidThread;
    let written = lead::written(nc, p, true).map(|l| if rigid { l.abs() } else { l });
    lead::remember(nc, written);
    remember_runout(nc, p)?;
    if !p.has_axis() {
        return Ok(());
    }
    let mv = Move {
        from: nc.st.pos,
        to: nc.target(p),
        lead: lead::resolve(nc, written)?,
        dlead: (code == Motion::VariableThread).then(|| nc.len_of(p, b'R').unwrap_or(0.0)),
        q: start_q(nc, code, p),
    };
    if code == Motion::VariableThread {
        check_variable_lead(nc, &mv)?;
    }
    let runout = runout(nc.st.cycles.chain.runout, &mv)?;
    if let Some(ro) = runout {
        lead::check_lift(nc, "run-out", mv.lead_at_runout(ro), (ro.j, ro.k))?;
    }
    nc.st.pos = mv.to;
    out.moved = true;
    match runout {
        // G32.1 does not chain: it is its own last block.
        Some(ro) if rigid => print(&mv.with_runout(ro), sink),
        Some(ro) => nc.st.cycles.chain.pending = Some((mv, ro, nc.origin)),
        None => print(&[mv.plain()], sink),
    }
    nc.st.cycles.chain.open = !rigid;
    Ok(())
}

/// J and K are modal: a block that gives one or both replaces them (the
/// other derived: K = |J|, or J = K) (§16.3). K must be positive.
fn remember_runout(nc: &mut Nc, p: &Parsed) -> Result<(), NcError> {
    let (j, k) = (nc.len_of(p, b'J'), nc.len_of(p, b'K'));
    if k.is_some_and(|k| k < 0.0) {
        return fail(Alarm::BadThread, "the run-out length K must be positive");
    }
    let pair = match (j, k) {
        (None, None) => return Ok(()),
        (Some(j), None) => (j, j.abs()),
        (j, Some(k)) => (j.unwrap_or(k), k),
    };
    nc.st.cycles.chain.runout = Some(pair);
    Ok(())
}

/// The start angle: G32's Q (0.001°) on the first block of a chain only,
/// G32.1's C (degrees); G34 has none.
fn start_q(nc: &Nc, code: Motion, p: &Parsed) -> f64 {
    match code {
        Motion::Thread if !nc.st.cycles.chain.open => {
            p.get(b'Q').map_or(0.0, |q| round_half_away(q) / 1000.0)
        }
        Motion::RigidThread => p.get(b'C').unwrap_or(0.0),
        _ => 0.0,
    }
}

/// G34 (§17.2): the lead √(F² + 2·R·s) must stay above 0 and within the
/// machine's maximum over the whole move; it is monotonic, so the end is
/// enough once F itself is checked.
fn check_variable_lead(nc: &Nc, mv: &Move) -> Result<(), NcError> {
    let r = mv.dlead.unwrap_or(0.0);
    let end = mv.lead * mv.lead + 2.0 * r * mv.long_length();
    if end <= 0.0 {
        return fail(
            Alarm::BadThread,
            "G34: the lead falls to zero or below during the move",
        );
    }
    lead::check(nc, libm::sqrt(end))
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{assert_line, run_err, Lathe};

    fn lathe() -> Lathe {
        let mut m = Lathe::new();
        m.run("M03 S300");
        m
    }

    #[test]
    fn run_out_goes_to_the_last_block_of_a_chain_only() {
        // J/K given on the first block stay modal: the first block is not
        // the last, so it has no run-out; the second ends the chain.
        let mut m = lathe();
        m.run("G00 X30 Z5");
        assert!(m.run("G32 Z-10 F1.5 J0.8 K2 Q45000").is_empty());
        // The first block waits until the second shows it continues.
        assert_eq!(m.run("G32 Z-20"), ["THREAD X=30 Z=-10 LEAD=1.5 Q=45"]);
        // The G00 ends the chain: Z-20 runs out from Z-18, lifted 0.8.
        let l = m.run("G00 X40");
        assert_eq!(l[0], "THREAD X=30 Z=-18 LEAD=1.5");
        assert_eq!(l[1], "THREAD X=31.6 Z=-20 LEAD=1.5");
        // The programmed end (X30 Z-20) stays the point of the block.
        assert_eq!(l[2], "RAPID X=40 Z=-20");
    }

    #[test]
    fn a_taper_thread_runs_out_along_its_line() {
        // X30 Z5 → X34 Z-15 (Z long, 20 mm, r +2): K4 J-1 → P1 at 16/20:
        // r 15 + 1.6 = 16.6, Z-11; then Z-15 at r 15.6. |j|/k < 1.
        let mut m = lathe();
        m.run("G00 X30 Z5");
        m.run("G32 X34 Z-15 F2 J-1 K4");
        let l = m.run("M09");
        assert_line(&l[0], "THREAD", &[33.2, -11.0, 2.0]);
        assert_line(&l[1], "THREAD", &[31.2, -15.0, 2.0]);
    }

    #[test]
    fn a_steep_run_out_scales_the_lead() {
        // J3 K1.5 → f = 2: LEAD 1·2 on the run-out leg.
        let mut m = lathe();
        m.run("G00 X20 Z0");
        m.run("G32 Z-10 F1 J3 K1.5");
        let l = m.run("G00 X50");
        assert_line(&l[1], "THREAD", &[26.0, -10.0, 2.0]);
    }

    #[test]
    fn g34_run_out_lead_follows_the_continuous_model() {
        // F3 from Z0 to Z-20 (L 20), K2 J2: ℓ(18) = √(9 − 3.6).
        let mut m = lathe();
        m.run("G00 X20 Z0");
        m.run("G34 Z-20 F3 R-0.1 J2 K2");
        let l = m.run("G00 X40");
        assert_eq!(l[0], "THREAD X=20 Z=-18 LEAD=3 DLEAD=-0.1");
        let lead = (9.0f64 - 3.6).sqrt();
        assert_line(&l[1], "THREAD", &[24.0, -20.0, lead, -0.1]);
        // Without run-out DLEAD prints even when R is 0.
        assert_eq!(m.run("G34 W-5 F2")[0], "THREAD X=40 Z=-25 LEAD=2 DLEAD=0");
    }

    #[test]
    fn g32_1_prints_c_as_q_and_takes_a_left_hand_lead() {
        let mut m = lathe();
        m.run("G00 X20 Z2");
        assert_eq!(
            m.run("G32.1 Z-10 F-1.25 C90."),
            ["THREAD X=20 Z=-10 LEAD=1.25 Q=90"]
        );
    }

    #[test]
    fn thread_move_errors() {
        // The lead falls below 0: F1 over 10 mm: 1 − 2 < 0.
        assert_eq!(run_err(&["G00 X20 Z0", "G34 Z-10 F1 R-0.1"]), 4010);
        // The lead grows past 500 mm.
        assert_eq!(run_err(&["G00 X20 Z0", "G34 Z-10 F1 R20000"]), 4010);
        // A run-out as long as the move.
        assert_eq!(run_err(&["G00 X20 Z0", "G32 Z-3 F1 K3"]), 4010);
        assert_eq!(run_err(&["G00 X20 Z0", "G32 Z-30 F1 K-3"]), 4010);
        // A run-out of J10 over K1 cuts at lead × 10 (§16.5): 1000 mm.
        assert_eq!(run_err(&["G00 X20 Z0", "G32 Z-30 F100 J10 K1"]), 4010);
        // No lead yet.
        assert_eq!(run_err(&["G00 X20 Z0", "G32 Z-3"]), 2006);
        // A programmed zero-length thread is printed.
        let mut m = lathe();
        m.run("G00 X20 Z0");
        assert_eq!(m.run("G32 W0 F1"), ["THREAD X=20 Z=0 LEAD=1"]);
    }
}
