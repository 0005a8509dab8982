//! Ellipses and parabolas in G71–G73 profiles (seed 000, G6.2 note 8,
//! G7.2 note 7). The roughing treats a conic as a curve: a level pass ends
//! where the level meets it, and the contour follows it with its own words.
//! Every expected figure comes from the conic's equation in the comment
//! above it, not from a run. The seed says only that conics may stand in
//! G70–G73 profiles; that a pass ends on the curve itself and that pieces
//! print with the block's own words is our decision (docs/language.md).

use alloc::string::String;
use alloc::string::ToString;
use alloc::vec::Vec;

use crate::base::event::Event;
use crate::base::machine::Machine;
use crate::exec::cycles::testing::{nums, words};
use crate::exec::Nc;

/// Runs the setup blocks, hands the profile over (tags 1, 2, …) and runs
/// the cycle block: its canon.
fn cycle(setup: &[&str], cyc: &str, profile: &[&str]) -> Vec<String> {
    let mut nc = Nc::new(Machine::reference());
    let mut ignored: Vec<Event> = Vec::new();
    for b in setup {
        nc.exec(&words(b), &mut ignored).expect("setup block");
    }
    for (i, b) in profile.iter().enumerate() {
        nc.push_profile(&words(b), i as u32 + 1);
    }
    let mut events: Vec<Event> = Vec::new();
    nc.exec(&words(cyc), &mut events).expect("the cycle runs");
    events.iter().map(|e| e.to_string()).collect()
}

/// The (X, Z) of every LINE that directly follows a RAPID infeed and runs
/// along Z: the level cuts of G71, then the infeed of the contour pass.
fn level_cuts(canon: &[String]) -> Vec<(f64, f64)> {
    let moves: Vec<&String> = canon.iter().filter(|l| !l.starts_with("FEED")).collect();
    moves
        .windows(2)
        .filter(|w| w[0].starts_with("RAPID") && w[1].starts_with("LINE"))
        .map(|w| (nums(w[0]), nums(w[1])))
        .filter(|(a, b)| (a[0] - b[0]).abs() < 1e-9)
        .map(|(_, b)| (b[0], b[1]))
        .collect()
}

#[test]
fn g71_cuts_each_level_where_it_meets_the_ellipse() {
    // The program. G6.3 from X0 Z0 to X30 Z-10, A15 B10, Q90°:
    // the major axis along X (−X from +Z in the G02 sense). Of the two
    // centres (r15 z0 and r0 z-10) the counter-clockwise arc ≤ 180° is the
    // one about r0 z-10: r = 15·sin θ, z = −10 + 10·cos θ, θ = 0…90°.
    // With U0.4 W0.1 the profile moves by r + 0.2, z + 0.1; Δd = 2 from
    // A′ (r21.2) gives levels r19.2, 17.2, …, 1.2. On the ellipse a level
    // r (below r15.2) ends at z = 0.1 − 10 + 10·√(1 − ((r − 0.2)/15)²);
    // r19.2 and r17.2 lie above it and end at the profile's end, Z-19.9.
    let canon = cycle(
        &["G98 G00 X42 Z2", "G71 U2 R0.5 F100"],
        "G71 P1 Q4 U0.4 W0.1",
        &[
            "G00 X0",
            "G01 Z0",
            "G6.3 X30 Z-10 A15 B10 Q90000",
            "G01 Z-20",
        ],
    );
    let cuts = level_cuts(&canon);
    assert_eq!(cuts.len(), 11, "{canon:?}");
    for (k, &(x, z)) in cuts.iter().take(10).enumerate() {
        let r = 21.2 - 2.0 * (k as f64 + 1.0);
        assert!((x - 2.0 * r).abs() < 1e-4, "{x} vs level r{r}");
        let expected = if r > 15.2 {
            -19.9
        } else {
            let t = (r - 0.2) / 15.0;
            0.1 - 10.0 + 10.0 * (1.0 - t * t).sqrt()
        };
        assert!(
            (z - expected).abs() < 1e-4,
            "level r{r}: Z{z} vs {expected}"
        );
    }
    // Spot checks by hand: r13.2 → sin θ = 13/15, cos θ = 0.49889,
    // Z = −10 + 4.9889 + 0.1 = −4.9111; r9.2 → sin θ = 0.6, Z = −1.9.
    assert!(canon.iter().any(|l| l == "LINE X=26.4 Z=-4.9111"));
    assert!(canon.iter().any(|l| l == "LINE X=18.4 Z=-1.9"));
    // The contour pass follows the ellipse moved by the allowance.
    let n = canon.len();
    assert_eq!(
        canon[n - 4..],
        [
            "LINE X=0.4 Z=0.1",
            "ELLIPSE DIR=CCW X=30.4 Z=-9.9 A=15 B=10 Q=90",
            "LINE X=30.4 Z=-19.9",
            "RAPID X=42 Z=2",
        ]
    );
}

#[test]
fn g72_cuts_each_level_where_it_meets_the_ellipse() {
    // G6.2 from X30 Z-20 to X20 Z-10, A10 (along Z) B5: the clockwise arc
    // ≤ 180° is the quarter about r10 z-20, r = 10 + 5·sin θ,
    // z = −20 + 10·cos θ (θ = 90° → 0°). G72 W2 from Z2 with W0.1, U0.4:
    // levels z = 2.1 − 2k; a level z (−20 < z − 0.1 < −10) ends at
    // r = 0.2 + 10 + 5·√(1 − ((z − 0.1 + 20)/10)²). By hand: Z-15.9 →
    // cos θ = 0.4, r = 10 + 5·0.91652 = 14.5826 → X29.5652 (with 0.4).
    let canon = cycle(
        &["G98 G00 X42 Z2", "G72 W2 R0.5 F100"],
        "G72 P1 Q4 U0.4 W0.1",
        &["G00 Z-20", "G01 X30", "G6.2 X20 Z-10 A10 B5 Q0", "G01 Z0"],
    );
    assert!(canon.iter().any(|l| l == "LINE X=29.5652 Z=-15.9"));
    let mut seen = 0;
    for w in canon.windows(2) {
        let (a, b) = (nums(&w[0]), nums(&w[1]));
        // A level cut: a rapid to X42.4 then a feed along X at the same Z.
        if !(w[0].starts_with("RAPID") && w[1].starts_with("LINE")) || a[0] != 42.4 {
            continue;
        }
        assert!((a[1] - b[1]).abs() < 1e-9, "{w:?}");
        let dz = b[1] - 0.1 + 20.0;
        if dz > 0.0 && dz < 10.0 {
            let r = 0.2 + 10.0 + 5.0 * (1.0 - (dz / 10.0).powi(2)).sqrt();
            assert!((b[0] - 2.0 * r).abs() < 1e-4, "{w:?} vs X{}", 2.0 * r);
            seen += 1;
        }
    }
    // Levels Z-11.9, -13.9, -15.9, -17.9 cross the ellipse.
    assert_eq!(seen, 4, "{canon:?}");
    assert!(canon
        .iter()
        .any(|l| l == "ELLIPSE DIR=CW X=20.4 Z=-9.9 A=10 B=5 Q=0"));
}

#[test]
fn g73_repeats_the_parabola_moved() {
    // G73 U4 W2 R2 with U0.4 W0.1: pass 1 is moved by X+8.4 Z+2.1, pass 2
    // by X+0.4 Z+0.1; the parabola keeps P and Q, its end moves along.
    let canon = cycle(
        &["G98 G00 X42 Z2", "G73 U4 W2 R2 F100"],
        "G73 P1 Q4 U0.4 W0.1",
        &[
            "G00 X0 Z2",
            "G01 Z0",
            "G7.3 X20 Z-10 P5000 Q90000",
            "G01 Z-20",
        ],
    );
    let parabolas: Vec<&String> = canon.iter().filter(|l| l.starts_with("PARABOLA")).collect();
    assert_eq!(
        parabolas,
        [
            "PARABOLA DIR=CCW X=28.4 Z=-7.9 P=5 Q=90",
            "PARABOLA DIR=CCW X=20.4 Z=-9.9 P=5 Q=90",
        ]
    );
}

/// The point of an ellipse about (cr, cz) with semi-axes a along Z and b
/// along r: how far (x, z) is from it, as |(dz/a)² + (dr/b)² − 1|.
fn off_ellipse(x: f64, z: f64, cr: f64, cz: f64, a: f64, b: f64) -> f64 {
    let (dz, dr) = ((z - cz) / a, (x / 2.0 - cr) / b);
    (dz * dz + dr * dr - 1.0).abs()
}

#[test]
fn type_ii_roughs_a_pocket_shaped_by_a_half_ellipse() {
    // G6.2 from X20 Z-5 to X20 Z-25, A10 B4: the half ellipse about r10
    // z-15 dipping to r6. Levels from r22 by Δd 1.5: the pocket levels
    // r8.5 and r7 meet it at z = −15 ± 10·√(1 − ((10 − r)/4)²):
    // r8.5 → ±9.2702 → Z-5.7298, Z-24.2702; r7 → ±6.6144 → Z-8.3856,
    // Z-21.6144. Each piece cut off the ellipse prints with its words.
    let canon = cycle(
        &["G98 G00 X44 Z2", "G71 U1.5 R0.5 F100"],
        "G71 P1 Q5 U0 W0",
        &[
            "G00 X20 Z2",
            "G01 Z-5",
            "G6.2 X20 Z-25 A10 B4",
            "G01 Z-30",
            "X44",
        ],
    );
    for l in [
        "ELLIPSE DIR=CW X=17 Z=-5.7298 A=10 B=4 Q=0",
        "LINE X=17 Z=-24.2702",
        "ELLIPSE DIR=CW X=14 Z=-8.3856 A=10 B=4 Q=0",
        "LINE X=14 Z=-21.6144",
    ] {
        assert!(canon.iter().any(|c| c == l), "{l} missing from {canon:?}");
    }
    // Every ELLIPSE starts and ends on the programmed ellipse.
    let mut at = (0.0, 0.0);
    for l in &canon {
        let v = nums(l);
        if l.starts_with("ELLIPSE") {
            assert!(
                off_ellipse(at.0, at.1, 10.0, -15.0, 10.0, 4.0) < 1e-4,
                "{l}"
            );
            assert!(
                off_ellipse(v[0], v[1], 10.0, -15.0, 10.0, 4.0) < 1e-4,
                "{l}"
            );
        }
        if v.len() >= 2 && !l.starts_with("FEED") {
            at = (v[0], v[1]);
        }
    }
}

#[test]
fn a_corner_word_next_to_a_conic_is_ignored() {
    // dialect.md §5.1: a chamfer or rounding applies only when the next
    // move is G01–G03; a conic is not, so the word is ignored (W112, from
    // the compiler), and L or D on the conic itself is no corner word of
    // it (W104): the cycle runs as the profile without them.
    let profile = [
        "G00 X0",
        "G01 Z0",
        "G6.3 X30 Z-10 A15 B10 Q90000",
        "G01 Z-20",
    ];
    let run = |p: &[&str]| {
        cycle(
            &["G98 G00 X42 Z2", "G71 U2 R0.5 F100"],
            "G71 P1 Q4 U0.4 W0.1",
            p,
        )
    };
    let plain = run(&profile);
    let before = ["G00 X0", "G01 Z0 L1", profile[2], profile[3]];
    assert_eq!(run(&before), plain);
    let on = [
        "G00 X0",
        "G01 Z0",
        "G6.3 X30 Z-10 A15 B10 Q90000 D1",
        profile[3],
    ];
    assert_eq!(run(&on), plain);
}
