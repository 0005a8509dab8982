//! The plain move: a block of axis words, F and N (and an arc's R or I/K),
//! with at most a G00–G03, run where no mode acts on it: no plane mode
//! (G12.1, G7.1), nothing held behind a waiting element, no drilling cycle
//! left in force.
//! It is the usual block of CAM output, and this is `Nc::exec_parsed` for
//! it without the steps that do nothing then:
//! - `comp::before_block` acts on group-00 codes and G54–G59 only;
//! - `plane::before_block` on a plane mode, group-00 codes and G12.1;
//! - `contour::in_order` holds events only while an element waits;
//! - `caxis` on C and H words;
//! - the group-1 and group-4 steps on M, S and T words;
//! - `Nc::motion`'s other branches on a plane mode, a group-00 code, G22,
//!   a drilling cycle or another motion code.
//!
//! The steps it keeps are the same functions `exec_parsed` calls, in the
//! same order (the cycle rules through `cycles::before_plain_block`, those
//! of them that can act on a plain move), outside `contour::in_order`: so it is not taken while an
//! element waits (the one step here that can print, the end of a thread
//! chain, would then have to be held). `compiler/tests/plain_path.rs`
//! runs every suite program and random macro programs both ways
//! (`Nc::set_plain_path`) and compares events and state after each
//! instruction.

use crate::base::error::NcError;
use crate::base::gcode::{Drill, Motion, PathMode};
use crate::block::Parsed;
use crate::exec::{contour, Nc, Outcome, Sink};

/// Whether block `p` takes the plain path in the kernel's state.
#[inline]
pub(crate) fn takes(nc: &Nc, p: &Parsed) -> bool {
    let st = &nc.st;
    nc.plain_path
        && p.is_plain_move()
        && st.plane.is_none()
        && !st.contour.is_holding()
        && (p.motion().is_some() || st.modal.drill == Drill::Off)
        && match p.motion().unwrap_or(st.modal.motion) {
            // (R, I or K on a line: the general path, which ignores them.)
            Motion::Rapid | Motion::Line => !p.has(b'R') && !p.has(b'I') && !p.has(b'K'),
            Motion::ArcCw | Motion::ArcCcw => true,
            _ => false,
        }
}

/// Runs a block [`takes`] accepted.
pub(crate) fn run(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<Outcome, NcError> {
    nc.st.c_block = false;
    if let Some(code) = p.motion() {
        // (`Nc::modal_settings`: a group-01 code cancels drilling.)
        nc.st.modal.motion = code;
        nc.st.modal.drill = Drill::Off;
    }
    crate::exec::cycles::before_plain_block(nc, p, sink)?;
    nc.remember(p);
    nc.st.exact_stop = nc.st.modal.path_mode() == PathMode::ExactStop;
    let code = nc.st.modal.motion;
    let corner = contour::corner_word(nc, code, p)?;
    if code.is_arc() {
        let target = nc.target(p);
        if let Some(e) = nc.arc_element(nc.st.pos, code == Motion::ArcCw, target, p)? {
            contour::feed_element(nc, e, corner, sink)?;
        }
    } else {
        contour::straight(nc, code == Motion::Rapid, p, corner, sink)?;
    }
    contour::end_of_block(nc)?;
    crate::exec::comp::end_of_block(nc, p, true)?;
    Ok(Outcome {
        moved: true,
        modal_call: true,
        ..Outcome::default()
    })
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::Lathe;
    use alloc::format;

    /// Runs `blocks` from `a` with the short path on and off: the same
    /// canon or alarm, and the same kernel state, after every block.
    fn both_ways(a: &mut Lathe, blocks: &[&str]) {
        let mut b = Lathe { nc: a.nc.clone() };
        b.nc.set_plain_path(false);
        for block in blocks {
            assert_eq!(a.try_run(block), b.try_run(block), "{block}");
            let (sa, sb) = (format!("{:?}", a.nc.st), format!("{:?}", b.nc.st));
            assert!(sa == sb, "{block}: the states differ");
        }
    }

    #[test]
    fn in_polar_interpolation_a_plain_block_moves_in_the_plane() {
        let blocks = [
            "G00 X40 Z-2 C0",
            "G98 G12.1",
            "G01 X20 C10 F100",
            "X10",
            "G01 X30",
            "G13.1",
            "X40",
        ];
        both_ways(&mut Lathe::with_c(), &blocks);
    }

    #[test]
    fn behind_a_waiting_chamfer_and_in_a_drilling_cycle() {
        let blocks = [
            "G98 G01 X20 Z0 F100",
            "G01 X26 Z-8 L1",
            "Z-20",
            "X30 Z-25 L2",
            "W-5",
            "G00 X0 Z5",
            "G83 X0 Z-5 Q1000 F50",
            "Z-8",
            "G80",
            "Z2",
        ];
        both_ways(&mut Lathe::new(), &blocks);
    }

    #[test]
    fn arcs_by_radius_and_centre_with_corners() {
        let blocks = [
            "G98 G00 X20 Z2",
            "G01 Z0 F100",
            "G02 X30 Z-5 R5",
            "G03 X40 Z-10 I10 K0",
            "Z-15 R5",
            "G02 W-5 R5 L1",
            "G01 Z-30",
            "G02 X50 Z-30 I-5 K-5",
            "G00 X60",
        ];
        both_ways(&mut Lathe::new(), &blocks);
    }

    /// The cycle rules a plain move meets, both ways: it ends a thread
    /// chain (the waiting block gets its run-out) and a G90 run, F < 0 is
    /// refused, and so is a move between M29 and its tapping block.
    #[test]
    fn a_plain_move_meets_the_cycle_rules() {
        let mut a = Lathe::new();
        let blocks = [
            "G99 M03 S500",
            "G00 X30 Z5",
            "G32 Z-10 F1.5",
            "G01 X40 F0.2",
            "G90 X20 Z-20 F0.2",
            "G00 X50",
            "X30 Z2",
            "G01 X20 F-1",
            "M29 S300",
            "G00 X20",
        ];
        both_ways(&mut a, &blocks);
        // (The alarms, which `both_ways` only compares.)
        assert!(a.try_run("G01 X20 F-1").is_err());
        assert_eq!(a.try_run("G00 X20"), Err(2007));
    }

    /// Runs every block of `blocks` through `Nc::exec_move` on one kernel
    /// and `Nc::exec` on another: the same canon or alarm, and the same
    /// state, after each (`exec_move` takes any words; it is only faster
    /// for a plain move's).
    fn move_both_ways(blocks: &[&str]) {
        use crate::exec::cycles::testing::words;
        use alloc::vec::Vec;
        let mut a = Lathe::new();
        let mut b = Lathe { nc: a.nc.clone() };
        for block in blocks {
            let mut events: Vec<crate::base::event::Event> = Vec::new();
            let moved =
                a.nc.exec_move(&words(block), &mut events)
                    .map_err(|e| e.code);
            let moved = moved.map(|_| events.iter().map(|e| format!("{e}")).collect());
            assert_eq!(moved, b.try_run(block), "{block}");
            let (sa, sb) = (format!("{:?}", a.nc.st), format!("{:?}", b.nc.st));
            assert!(sa == sb, "{block}: the states differ");
        }
    }

    #[test]
    fn a_typed_move_runs_as_its_block_in_every_mode() {
        move_both_ways(&[
            "G98 G00 X40 Z2",
            "G01 X30 Z-5 F100",
            "U2 W-1",
            // Data: a parameter block that looks like a move.
            "G10 L52",
            "N181 W0",
            "G11",
            // Tool life by minutes times the moves.
            "G10 L3",
            "P1 L1 Q2",
            "G11",
            "T0101",
            "G01 X20 Z-10 F50",
            // F 0, the stroke limit, a plane mode's and a chamfer's moves.
            "G01 X25 F0",
            "G01 X25 Z-12 F80",
            "G22 X100. Z50. I-10. K-20.",
            "G00 X120 Z0",
            "G01 X26 Z-8 L1",
            "Z-20",
            "G02 X30 Z-22 R2",
            "G01 X30 Z-25 F-1",
            "X30 U1",
            "G04 X1",
            "M30",
        ]);
    }

    #[test]
    fn after_threads_and_under_compensation() {
        let blocks = [
            "G00 X20 Z2",
            "G32 W-10 F1.5",
            "Z-20",
            // The G01 ends the chain: its last thread is printed first.
            "G01 U2 F100",
            "G32 W-5 F1.5",
            "G00 U2",
            "T0101",
            "G42 G01 X20 Z0 F1",
            "Z-10",
            "G02 X30 Z-15 R5",
            "X30",
            "G40 X40",
            "M30",
        ];
        both_ways(&mut Lathe::new(), &blocks);
    }
}
