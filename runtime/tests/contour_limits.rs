//! Contours of micro-moves keep every axis within its limits and reach
//! every end point: random ZX programs of lines and arcs from 0.5 µm to
//! 10 mm (a fixed seed), with reversals, tight arcs, G61 and G64, feeds
//! per minute and per revolution, are certified period by period
//! (`runtime::certify`, as `gbvm check` does), with jerk limiting off and
//! on. Programs like these found an arc of a few µm that broke X's
//! acceleration at a corner, a period that ran through two corners, the
//! turning's jerk on arcs and a false miss in the certifier.

mod common;

use common::{certify, Lcg};
use core::f64::consts::{FRAC_PI_2, TAU};
use nc::Machine;

/// A coordinate as a program writes it: 3 decimals.
fn mm(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// One contour: 20–60 moves from X60 Z2, each 10^(−3.3…1) mm long (a
/// third along an axis), 45 % of them arcs of 1.0001–20 × half the chord.
fn contour(rng: &mut Lcg) -> String {
    let mut s = format!(
        "G00 X60 Z2\nM03 S{}\n{}\n{}\n",
        rng.pick(&[300, 1000, 2500]),
        rng.pick(&["G61", "G64", "G64"]),
        rng.pick(&["G98 F100", "G98 F800", "G98 F3000", "G99 F0.05", "G99 F0.5"]),
    );
    // X as a diameter, as the program writes it.
    let (mut x, mut z) = (60.0f64, 2.0f64);
    for _ in 0..20 + (rng.unit() * 40.0) as usize {
        let len = 10f64.powf(-3.3 + 4.3 * rng.unit());
        let along = rng.unit() < 0.3;
        let turn = rng.unit();
        let a = if along {
            FRAC_PI_2 * (turn * 4.0).floor()
        } else {
            TAU * turn
        };
        let nx = mm((x + 2.0 * len * a.cos()).clamp(0.0, 120.0));
        let nz = mm((z + len * a.sin()).clamp(-80.0, 10.0));
        if (nx, nz) == (x, z) {
            continue;
        }
        if rng.unit() < 0.45 {
            let half = ((nx - x) / 2.0).hypot(nz - z) / 2.0;
            let r = half * rng.pick(&[1.0001, 1.01, 1.5, 3.0, 20.0]);
            let g = rng.pick(&["G02", "G03"]);
            s += &format!("{g} X{nx:.3} Z{nz:.3} R{r:.4}\n");
        } else {
            s += &format!("G01 X{nx:.3} Z{nz:.3}\n");
        }
        (x, z) = (nx, nz);
    }
    s + "G00 X80 Z5\nM30\n"
}

#[test]
fn random_micro_move_contours_are_certified() {
    let mut rng = Lcg(42);
    let machine = Machine::reference();
    let mut certified = 0;
    for _ in 0..200 {
        let src = contour(&mut rng);
        for jerk in [false, true] {
            match certify(&src, &machine, jerk) {
                Some(Ok(())) => certified += 1,
                Some(Err(v)) => panic!("jerk {jerk}: {v}\n{src}"),
                None => {}
            }
        }
    }
    // Most of them run (an R rounded to 4 decimals may not reach).
    assert!(certified >= 380, "{certified} of 400 runs certified");
}
