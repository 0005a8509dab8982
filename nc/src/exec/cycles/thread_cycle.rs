//! G92 threading cycle and G92.1 rigid threading cycle (cycles.md §3, §4,
//! §12, §18).

use super::legs::{self, jk_pair, PullOut};
use super::turning;
use super::{lead, words};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::Motion;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::single::g92_path;

/// A G92 (920) or G92.1 (921) block.
pub(crate) fn run(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let rigid = code == Motion::RigidThreadCycle;
    // The rigid cycle's F < 0 is a left-hand lead; the canon prints |F|.
    let written = lead::written(nc, p, true).map(|l| if rigid { l.abs() } else { l });
    lead::remember(nc, written);
    if !rigid {
        remember_pull(nc, p);
    }
    if !p.has_axis() {
        return Ok(());
    }
    let lead = lead::resolve(nc, written)?;
    let cycle = turning::next_cycle(nc, code, p)?;
    check_repair(nc, p)?;
    let pull = if rigid { None } else { pull_out(nc, lead) };
    lead::check_pull_out(nc, lead, pull)?;
    let path = g92_path(&cycle, lead, pull)?;
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

/// J and K stay in force until a G92 block gives new ones (§3).
fn remember_pull(nc: &mut Nc, p: &Parsed) {
    if let Some(pair) = jk_pair(nc.len_of(p, b'J'), nc.len_of(p, b'K')) {
        nc.st.cycles.g92_pull = Some(pair);
    }
}

/// The pull-out of J/K; without them parameter №019 (0.1 lead, 45°),
/// which is 0 on the reference machine.
fn pull_out(nc: &Nc, lead: f64) -> Option<PullOut> {
    match nc.st.cycles.g92_pull {
        Some(pair) => PullOut::from_pair(pair),
        None => {
            let g = f64::from(nc.machine.threads.pullout_tenths) * lead / 10.0;
            PullOut::from_pair((g, g))
        }
    }
}

/// P1 asks for thread repair, which needs a recorded position (№174.4);
/// without the option P is ignored (dialect.md §4.8).
fn check_repair(nc: &Nc, p: &Parsed) -> Result<(), NcError> {
    let repair = words::count(p, b'P')? == Some(1);
    if repair && nc.machine.threads.repair_enabled {
        return fail(
            Alarm::NoRepairPosition,
            "thread repair: no repair position has been recorded",
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{assert_line, run, run_err, Lathe};

    #[test]
    fn taper_thread_with_j_k_pull_out() {
        // A = X50 Z2, G92 X40 Z-20 F2.5 J2 K3: the cut starts at
        // X40 - 3 = X37 (r 18.5) and runs to r 20 at Z-20 (22 mm). The
        // pull-out starts at Z-17, 19/22 of the way: r 18.5 + 1.5·19/22;
        // it lifts J = 2 (radius) outwards at the end Z. J < K: LEAD 2.5.
        let mut m = Lathe::new();
        m.run("M03 S300");
        m.run("G00 X50 Z2");
        let l = m.run("G92 X40 Z-20 R-1.5 F2.5 J2 K3");
        let r1 = 18.5 + 1.5 * 19.0 / 22.0;
        assert_eq!(l.len(), 5);
        assert_line(&l[0], "RAPID", &[37.0, 2.0]);
        assert_line(&l[1], "THREAD", &[2.0 * r1, -17.0, 2.5]);
        assert_line(&l[2], "THREAD", &[2.0 * (r1 + 2.0), -20.0, 2.5]);
        assert_line(&l[3], "RAPID", &[50.0, -20.0]);
        assert_line(&l[4], "RAPID", &[50.0, 2.0]);
        // The next pass keeps R, the lead and J/K; only X changes.
        let l = m.run("X39");
        assert_line(&l[0], "RAPID", &[36.0, 2.0]);
        assert_line(
            &l[2],
            "THREAD",
            &[2.0 * (18.0 + 1.5 * 19.0 / 22.0 + 2.0), -20.0, 2.5],
        );
    }

    #[test]
    fn a_steep_pull_out_prints_its_lead_along_x() {
        // J3 K1 lifts 3 over 1: LEAD = 2·3/1 = 6 on the pull-out leg.
        let l = run(&["M03 S300", "G00 X40 Z5", "G92 X30 Z-20 F2 J3 K1"]);
        assert_line(&l[4], "THREAD", &[30.0, -19.0, 2.0]);
        assert_line(&l[5], "THREAD", &[36.0, -20.0, 6.0]);
    }

    #[test]
    fn inside_thread_pulls_out_inwards_and_g00_clears_j_k() {
        // A = X20 Z3, G92 X24 Z-15 F1.5 K1: so = -1, lift 1 inwards.
        let mut m = Lathe::new();
        m.run("G00 X20 Z3");
        let l = m.run("G92 X24 Z-15 F1.5 K1");
        assert_line(&l[1], "THREAD", &[24.0, -14.0, 1.5]);
        assert_line(&l[2], "THREAD", &[22.0, -15.0, 1.5]);
        m.run("G00 X20 Z3");
        let l = m.run("G92 X24 Z-15");
        assert_eq!(l.len(), 4);
        assert_line(&l[1], "THREAD", &[24.0, -15.0, 1.5]);
    }

    #[test]
    fn three_starts_and_g92_1() {
        // L3: Q 0, 120, 240; 12 legs.
        let l = run(&["G00 X30 Z5", "G92 X27 Z-10 F4.5 L3"]);
        assert_eq!(l.len(), 1 + 12);
        assert_eq!(l[2], "THREAD X=27 Z=-10 LEAD=4.5");
        assert_eq!(l[6], "THREAD X=27 Z=-10 LEAD=4.5 Q=120");
        assert_eq!(l[10], "THREAD X=27 Z=-10 LEAD=4.5 Q=240");
        // G92.1 with a left-hand lead prints |F| and has no pull-out.
        let l = run(&["G00 X30 Z5", "G92.1 X27 Z-10 F-2 K2 J2"]);
        assert_eq!(l[2], "THREAD X=27 Z=-10 LEAD=2");
        assert_eq!(l.len(), 1 + 4);
    }

    #[test]
    fn thread_errors() {
        // No lead ever given.
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X27 Z-10"]), 2006);
        // Lead 0, L0, a pull-out as long as the thread.
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X27 Z-10 F0"]), 4010);
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X27 Z-10 F1 L0"]), 4010);
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X27 Z-10 F1 K15"]), 4010);
        // A pull-out that lifts J10 over K1 cuts at lead × 10 (§12): F100
        // asks 1000 mm, above the 500 mm maximum; F50 is 500, the most.
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X28 Z-20 F100 J10 K1"]), 4010);
        let l = run(&["G00 X30 Z5", "G92 X28 Z-20 F50 J10 K1"]);
        assert_eq!(l[3], "THREAD X=48 Z=-20 LEAD=500");
        // A negative F is a right-hand G92's E1010.
        assert_eq!(run_err(&["G00 X30 Z5", "G92 X27 Z-10 F-1"]), 1010);
        // Threads per inch: I8 is 3.175 mm.
        let l = run(&["G00 X30 Z5", "G92 X27 Z-10 I8"]);
        assert_eq!(l[2], "THREAD X=27 Z=-10 LEAD=3.175");
    }
}
