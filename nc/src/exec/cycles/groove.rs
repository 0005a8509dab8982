//! G74 face grooving / peck drilling along Z and G75 grooving along X
//! (cycles.md §9, §10): pecks along one axis, steps along the other.

use super::legs;
use super::words;
use crate::base::error::NcError;
use crate::base::gcode::OneShot;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::groove::{g74_path, g75_path, Groove};

/// The peck retract e of the last G74 and of the last G75 first block.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Retracts {
    g74: f64,
    g75: f64,
}

/// A G74 (740) or G75 (750) block: the first block (no axis word) sets e,
/// the second cuts.
pub(crate) fn run(
    nc: &mut Nc,
    code: OneShot,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let g74 = code == OneShot::PeckFace;
    if !p.has_axis() {
        if let Some(e) = nc.len_of(p, b'R') {
            let st = &mut nc.st.cycles.groove;
            *if g74 { &mut st.g74 } else { &mut st.g75 } = e.abs();
        }
        return Ok(());
    }
    let st = nc.st.cycles.groove;
    // P(Δi) steps or pecks in X, Q(Δk) in Z: both radius/Z amounts in
    // 0.001 mm, whichever axis pecks.
    let di = words::increments(nc, p, b'P').unwrap_or(0.0).abs();
    let dk = words::increments(nc, p, b'Q').unwrap_or(0.0).abs();
    let g = Groove {
        a: nc.st.pos,
        end: nc.target(p),
        step: if g74 { di } else { dk },
        peck: if g74 { dk } else { di },
        relief: words::length_or(nc, p, b'R', 0.0),
        retract: if g74 { st.g74 } else { st.g75 },
    };
    let path = if g74 { g74_path(&g)? } else { g75_path(&g)? };
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{run, run_err, Lathe};
    use alloc::format;
    use alloc::string::ToString;
    use alloc::vec;

    #[test]
    fn g74_last_column_is_partial_and_the_relief_goes_back() {
        // A = X20 Z1, end X31 Z-4, Δi 2.5 (radius), Δk 3, e 0.4, Δd 0.2:
        // columns r 10, 12.5, 15, then 17.5 passes 15.5 → 15.5 (X31);
        // pecks Z-2 then Z-5 passes Z-4 → Z-4; relief -0.2 radius (X
        // −0.4) against the step direction.
        let mut m = Lathe::new();
        m.run("G00 X20 Z1");
        m.run("G74 R0.4");
        let l = m.run("G74 X31 Z-4 P2500 Q3000 R0.2 F80");
        let column = |x: f64, next: &str| {
            vec![
                format!("LINE X={x} Z=-2"),
                format!("RAPID X={x} Z=-1.6"),
                format!("LINE X={x} Z=-4"),
                format!("RAPID X={} Z=-4", x - 0.4),
                format!("RAPID X={} Z=1", x - 0.4),
                next.to_string(),
            ]
        };
        let mut want = column(20.0, "RAPID X=25 Z=1");
        want.insert(0, "FEED F=80 MODE=MIN".into());
        want.extend(column(25.0, "RAPID X=30 Z=1"));
        want.extend(column(30.0, "RAPID X=31 Z=1"));
        want.extend(column(31.0, "RAPID X=20 Z=1"));
        // The first column's relief leg X19.6 … is printed as computed.
        assert_eq!(l, want);
    }

    #[test]
    fn g75_single_row_keeps_the_sign_of_its_relief() {
        // One row (no Z word): Δd = -0.3 moves -0.3 in Z; Δi 0: one feed.
        let l = run(&["G00 X50 Z-10", "G75 R1", "G75 X40 R-0.3 F30"]);
        assert_eq!(
            l[1..],
            [
                "FEED F=30 MODE=MIN",
                "LINE X=40 Z=-10",
                "RAPID X=40 Z=-10.3",
                "RAPID X=50 Z=-10.3",
                "RAPID X=50 Z=-10"
            ]
        );
    }

    #[test]
    fn g75_rows_towards_plus_z() {
        // A = X30 Z-20, end X26 Z-16: rows -20, -17.5, then -15 passes →
        // -16; relief +sz·|Δd| against: -0.5. Pecks r 15 → 13 (Δi 3 is
        // more than the depth): one feed per row. e from no first block: 0.
        let l = run(&["G00 X30 Z-20", "G75 X26 Z-16 P3000 Q2500 R0.5 F20"]);
        let row = |z: f64, next: &str| {
            vec![
                format!("LINE X=26 Z={z}"),
                format!("RAPID X=26 Z={}", z - 0.5),
                format!("RAPID X=30 Z={}", z - 0.5),
                next.to_string(),
            ]
        };
        let mut want = vec!["RAPID X=30 Z=-20".to_string(), "FEED F=20 MODE=MIN".into()];
        let mut r = row(-20.0, "RAPID X=30 Z=-17.5");
        // The first row's return to xA at its relief Z is then followed…
        want.append(&mut r);
        want.extend(row(-17.5, "RAPID X=30 Z=-16"));
        want.extend(row(-16.0, "RAPID X=30 Z=-20"));
        assert_eq!(l, want);
    }

    #[test]
    fn zero_steps() {
        assert_eq!(run_err(&["G00 X20 Z1", "G74 X30 Z-5 P0 Q1000 F1"]), 4011);
        assert_eq!(run_err(&["G00 X20 Z1", "G75 X10 Z-5 P1000 F1"]), 4011);
        // Δk = 0 for G74 is not an error: one feed to Z.
        assert_eq!(run(&["G00 X0 Z1", "G74 Z-5 F1"]).len(), 1 + 3);
    }
}
