//! The optional C axis (dialect.md §2.1, machine.md `[axes.c]`): C is the
//! absolute angle, H the incremental one, in degrees. Without a C axis
//! nothing here acts (block.rs gives E2005 for C and H as axis words).
//!
//! Where C may move — decided as a GSK/Fanuc lathe with a Cs/C axis does:
//!
//! - G00 and G01 (C alone, or with X/Z): the C axis moves with the line.
//!   A G01 that turns C feeds along the combined vector, the degrees
//!   counted as mm (Fanuc's rule for a linear + rotary move); a C-only G01
//!   runs at F deg/min (the runtime's planner, runtime/src/planner.rs).
//!   Such a block cannot take a chamfer, a corner rounding or angle
//!   programming (their geometry is in the ZX plane only) and cannot run
//!   under nose-radius compensation (E2007); a corner still waiting from
//!   the block before is printed whole first, as before a G00.
//! - The drilling/tapping cycles G83/G84/G87/G88: C/H is the hole angle,
//!   reached by the positioning rapid; H is applied again at each K repeat
//!   (as U/W are, cycles.md §21), so `H90 K4` drills four holes 90° apart.
//!   A block with only C/H in a drilling mode drills another hole.
//! - G28/G30: a C/H word names C: it goes to the intermediate angle with
//!   the rapid, then to its reference point, 0° (the machine file has no C
//!   reference angles); `HOME` lists it as `AXES=…C`.
//! - Nowhere else: G02/G03 (the canon's `ARC` has no C, so a helical C
//!   could not be printed; a real lathe has no helical option either),
//!   threads (G32, G33, G34, G92, G76, G78: the spindle *is* the C axis on
//!   a Cs lathe, it cannot turn at cutting speed and be positioned at
//!   once), canned and compound cycles, G04, G31, G50, G52, G53: E2007.
//!   G32.1 keeps C/H as its start angle.
//!
//! Canon (canon.md): `RAPID`, `LINE` and `THREAD` print `C=` when the block
//! programs C/H (every leg of a drilling block, the hole angle included)
//! or when the event turns C.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{self, Motion, OneShot};
use crate::base::machine::DecimalPoint;
use crate::base::words::{addr, Word, NO_POINT};
use crate::block::Parsed;
use crate::exec::cycles::{func, Func};
use crate::exec::Nc;
use crate::modal::Comp;

/// Whether the block programs the C axis (C or H as axis words).
pub(crate) fn programs_c(nc: &Nc, p: &Parsed) -> bool {
    if !nc.machine.axes.c.enabled || !(p.has(b'C') || p.has(b'H')) {
        return false;
    }
    // Inside G12.1 and G7.1 C/H are coordinates of the plane (plane.rs).
    if nc.st.plane.is_some() {
        return false;
    }
    // G32.1's C is its start angle, G7.1's the cylinder radius, G65's
    // arguments are the macro's.
    !matches!(
        func(nc, p),
        Func::Motion(Motion::RigidThread)
            | Func::OneShot(OneShot::Cylindrical)
            | Func::OneShot(OneShot::MacroCall)
    )
}

/// E2007 for C/H where the C axis cannot move (module comment).
pub(crate) fn check(nc: &Nc, p: &Parsed) -> Result<(), NcError> {
    if !programs_c(nc, p) {
        return Ok(());
    }
    // (An error names the C or H word, of both the later, unless it
    // names another.)
    let on_c = |e: NcError| match e.addr {
        Some(_) => e,
        None => e.on_pair(addr(b'C'), addr(b'H')),
    };
    if p.has(b'C') && p.has(b'H') {
        return fail(
            Alarm::IncompatibleWords,
            "C and H in one block: write the C angle either absolute or incremental",
        )
        .map_err(on_c);
    }
    match func(nc, p) {
        Func::OneShot(OneShot::Home | OneShot::HomeN) | Func::Drill(_) => Ok(()),
        Func::Motion(code) if code.is_straight() => check_line(nc, p),
        Func::Motion(code) if code.is_contour() => fail(
            Alarm::IncompatibleWords,
            "C/H cannot stand in a circular move: helical interpolation with C is not supported",
        ),
        Func::Motion(code) if code.is_thread() => fail(
            Alarm::IncompatibleWords,
            format!(
                "C/H cannot stand in a {} thread block: the spindle cannot turn as C while it cuts",
                code.name()
            ),
        ),
        Func::Motion(code) => not_here(code.code()),
        Func::OneShot(code) => not_here(code.code()),
    }
    .map_err(on_c)
}

fn not_here(code: gcode::Code) -> Result<(), NcError> {
    fail(
        Alarm::IncompatibleWords,
        format!("C/H cannot stand in a {} block", gcode::name(code)),
    )
}

fn check_line(nc: &Nc, p: &Parsed) -> Result<(), NcError> {
    use crate::base::words::{COMMA_A, COMMA_C, COMMA_R};
    let corner = [
        addr(b'L'),
        addr(b'D'),
        addr(b'Q'),
        COMMA_C,
        COMMA_R,
        COMMA_A,
    ];
    if let Some(&a) = corner.iter().find(|&&a| p.has_at(a)) {
        let msg =
            "a block that turns C takes no chamfer, corner rounding or angle (L, D, Q, ,C, ,R, ,A)";
        return Err(NcError::new(Alarm::IncompatibleWords, msg).on_addr(a));
    }
    if nc.st.modal.comp() != Comp::Off || crate::exec::comp::running(nc) {
        return fail(
            Alarm::IncompatibleWords,
            "C cannot move under nose-radius compensation: cancel it with G40 first",
        );
    }
    Ok(())
}

/// An angle word in degrees: no unit conversion (G20 changes lengths
/// only), but the increment-mode rule for literals without a point.
pub(crate) fn degrees(nc: &Nc, w: Word) -> f64 {
    if w.flags & NO_POINT != 0 && nc.machine.machine.decimal_point == DecimalPoint::Increment {
        w.value * 0.001
    } else {
        w.value
    }
}

/// The C angle a block moves to from `from`: C absolute, H incremental,
/// `from` when neither is written.
pub(crate) fn target_from(nc: &Nc, p: &Parsed, from: f64) -> f64 {
    if let Some(c) = p.word(b'C') {
        degrees(nc, c)
    } else if let Some(h) = p.word(b'H') {
        from + degrees(nc, h)
    } else {
        from
    }
}

/// The incremental C of a block (H), 0 without one: a drilling repeat
/// turns by it again.
pub(crate) fn step(nc: &Nc, p: &Parsed) -> f64 {
    p.word(b'H').map_or(0.0, |h| degrees(nc, h))
}

impl Nc {
    /// The `C=` field of a `RAPID`, `LINE` or `THREAD` that ends at the
    /// current C angle: printed when the block programs C/H or the move
    /// turned C (`from` is the angle it started at).
    pub(crate) fn c_field(&self, from: f64) -> Option<f64> {
        (self.st.c_block || (self.st.c - from).abs() > 1e-9).then_some(self.st.c)
    }
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::Lathe;
    use alloc::vec::Vec;

    /// The canon lines of blocks run one after another on `m`.
    fn lines(m: &mut Lathe, blocks: &[&str]) -> Vec<alloc::string::String> {
        blocks.iter().flat_map(|b| m.run(b)).collect()
    }

    #[test]
    fn absolute_incremental_and_c_only_moves() {
        let mut m = Lathe::with_c();
        let l = lines(
            &mut m,
            &[
                "G00 X20 Z5 C90",
                // 90 − 45.5 = 44.5
                "G01 W-5 H-45.5 F100",
                // modal G01, C alone
                "C10",
                // no C word, C does not move: no field
                "X30",
                // 10 − 20 = −10
                "H-20",
                // programmed but not moved: still printed
                "G00 X40 H0",
            ],
        );
        assert_eq!(
            l,
            [
                "RAPID X=20 Z=5 C=90",
                "FEED F=100 MODE=MIN",
                "LINE X=20 Z=0 C=44.5",
                "LINE X=20 Z=0 C=10",
                "LINE X=30 Z=0",
                "LINE X=30 Z=0 C=-10",
                "RAPID X=40 Z=0 C=-10",
            ]
        );
        // Block end and current C (no C offsets: machine = local).
        for n in [5003, 5023, 5043] {
            assert_eq!(m.nc.read_var(n).ok().flatten(), Some(-10.0), "#{n}");
        }
        assert!(crate::exec::sysvar::is_current_position(5023));
        assert!(crate::exec::sysvar::is_current_position(5043));
        // Without a C axis the C variables do not exist.
        assert_eq!(
            Lathe::new().nc.read_var(5003).map_err(|e| e.code),
            Err(5007)
        );
    }

    #[test]
    fn drilling_holes_at_angles() {
        let mut m = Lathe::with_c();
        m.run("G00 X0 Z3");
        // The hole at X20, C30 from Z3 to Z-5: every leg prints the angle.
        let l = m.run("G83 X20 C30 Z-5 F50");
        assert_eq!(
            l,
            [
                "RAPID X=20 Z=3 C=30",
                "FEED F=50 MODE=MIN",
                "LINE X=20 Z=-5 C=30",
                "RAPID X=20 Z=3 C=30",
            ]
        );
        // H90 K2: each repeat turns by 90 again: 120°, then 210°.
        let hole = |c: &str| {
            [
                alloc::format!("RAPID X=20 Z=3 C={c}"),
                alloc::format!("LINE X=20 Z=-5 C={c}"),
                alloc::format!("RAPID X=20 Z=3 C={c}"),
            ]
        };
        let mut want: Vec<_> = hole("120").into();
        want.extend(hole("210"));
        assert_eq!(m.run("H90 K2"), want);
        // C alone drills again; after G80 a move without C prints none.
        assert_eq!(m.run("C0"), hole("0"));
        m.run("G80");
        assert_eq!(m.run("G00 X30"), ["RAPID X=30 Z=3"]);
    }

    #[test]
    fn tapping_at_an_angle() {
        let mut m = Lathe::with_c();
        m.run("M03 S300");
        m.run("G00 X20 Z3");
        m.run("M29 S300");
        let l = m.run("G84 C45 Z-5 F1");
        assert_eq!(
            l,
            [
                "RAPID X=20 Z=3 C=45",
                "THREAD X=20 Z=-5 C=45 LEAD=1",
                "SPINDLE DIR=CCW",
                "THREAD X=20 Z=3 C=45 LEAD=1",
                "SPINDLE DIR=CW",
            ]
        );
    }

    #[test]
    fn reference_return_of_c() {
        let mut m = Lathe::with_c();
        m.run("G00 X10 Z2 C-10");
        // H0: the intermediate angle is the current one, no rapid.
        assert_eq!(m.run("G28 U0 W0 H0"), ["HOME N=1 AXES=XZC"]);
        assert_eq!(m.nc.read_var(5003).ok().flatten(), Some(0.0));
        // Through 90° to the reference (0°).
        assert_eq!(m.run("G28 C90"), ["RAPID X=0 Z=0 C=90", "HOME N=1 AXES=C"]);
        assert_eq!(m.nc.read_var(5043).ok().flatten(), Some(0.0));
    }

    #[test]
    fn where_c_cannot_move() {
        let e = |blocks: &[&str]| {
            let mut m = Lathe::with_c();
            blocks.iter().find_map(|b| m.try_run(b).err()).unwrap_or(0)
        };
        assert_eq!(e(&["G02 X10 Z-5 R5 C30 F1"]), 2007);
        assert_eq!(e(&["G32 Z-10 C30 F1"]), 2007);
        assert_eq!(e(&["G92 X20 Z-10 H30 F1"]), 2007);
        assert_eq!(e(&["G01 X10 C10 L1 F1"]), 2007);
        assert_eq!(e(&["G42 G01 X10 C10 F1"]), 2007);
        assert_eq!(e(&["G00 C10 H10"]), 2007);
        assert_eq!(e(&["G04 P100 C10"]), 2007);
        // G32.1 keeps C as its start angle.
        assert_eq!(e(&["M03 S100", "G32.1 Z-10 C30 F1"]), 0);
        // Polar and cylindrical interpolation: impossible without C
        // (plane.rs has the rest).
        assert_eq!(crate::exec::cycles::testing::run_err(&["G12.1"]), 2003);
        assert_eq!(crate::exec::cycles::testing::run_err(&["G00 C10"]), 2005);
        // H, the incremental C, is no more an axis word there than C is.
        assert_eq!(
            crate::exec::cycles::testing::run_err(&["G01 W-5 H10 F100"]),
            2005
        );
        assert_eq!(
            crate::exec::cycles::testing::run_err(&["G00 X10", "H10"]),
            2005
        );
    }

    #[test]
    fn a_waiting_corner_is_printed_before_c_turns() {
        // The chamfer of the first block finds a C move next: the line is
        // printed whole (as before a G00), then the C move.
        let mut m = Lathe::with_c();
        let l = lines(&mut m, &["G01 X20 Z0 F1", "Z-10 L1", "X30 C90"]);
        assert_eq!(
            l,
            [
                "FEED F=1 MODE=MIN",
                "LINE X=20 Z=0",
                "LINE X=20 Z=-10",
                "LINE X=30 Z=-10 C=90",
            ]
        );
    }
}
