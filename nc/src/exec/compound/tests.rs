//! Hand-checked paths of G70–G73 through `Nc::exec`. Every expected point
//! is worked out in the comment above it (or by the formula in the test)
//! from cycles.md, not taken from a run.

use alloc::format;
use alloc::string::String;
use alloc::string::ToString;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::NcError;
use crate::base::event::Event;
use crate::base::gcode;
use crate::base::machine::Machine;
use crate::base::words::{addr, Word, LITERAL, NO_POINT};
use crate::exec::Nc;

/// "G01 X20 Z-5" as words (a literal without a point gets `NO_POINT`).
fn block(text: &str) -> Vec<Word> {
    text.split_whitespace()
        .map(|t| {
            let (letter, num) = t.split_at(1);
            let flags = LITERAL | if num.contains('.') { 0 } else { NO_POINT };
            Word {
                addr: addr(letter.as_bytes()[0]),
                value: num.parse().expect("a number"),
                flags,
            }
        })
        .collect()
}

/// Runs `setup`, then hands `profile` over (tags 1, 2, …) and runs `cycle`;
/// the canon of the cycle block.
fn cycle(
    nc: &mut Nc,
    setup: &[&str],
    cycle: &str,
    profile: &[&str],
) -> Result<Vec<String>, NcError> {
    let mut ignored: Vec<Event> = Vec::new();
    for b in setup {
        nc.exec(&block(b), &mut ignored)?;
    }
    for (i, b) in profile.iter().enumerate() {
        nc.push_profile(&block(b), i as u32 + 1);
    }
    let mut events: Vec<Event> = Vec::new();
    nc.exec(&block(cycle), &mut events)?;
    Ok(events.iter().map(|e| e.to_string()).collect())
}

fn run(setup: &[&str], cyc: &str, profile: &[&str]) -> Result<Vec<String>, NcError> {
    cycle(&mut Nc::new(Machine::reference()), setup, cyc, profile)
}

fn fmt(v: f64) -> String {
    crate::base::event::Num(v).to_string()
}

fn rapid(x: f64, z: f64) -> String {
    format!("RAPID X={} Z={}", fmt(x), fmt(z))
}

fn line(x: f64, z: f64) -> String {
    format!("LINE X={} Z={}", fmt(x), fmt(z))
}

/// The legs of one type I level pass (cycles.md §5 step 2) at diameter
/// `x`, cut end `z`, retract e with directions sx, sz, back at `z0`.
fn level_pass(x: f64, z: f64, e: f64, sx: f64, sz: f64, z0: f64) -> Vec<String> {
    let back = x - sx * 2.0 * e;
    vec![
        rapid(x, z0),
        line(x, z),
        line(back, z - sz * e),
        rapid(back, z0),
    ]
}

const START: &[&str] = &["G98 G00 X40 Z2", "G71 U3 R1"];
const TAPER: &[&str] = &["G00 X20", "G01 Z-10", "X40 Z-30"];

#[test]
fn g71_taper_with_a_partial_last_pass() {
    // A = X40 Z2 (r20), Δu = Δw = 0: A′ = A, B′ = X20 Z2 (r10). Radial
    // stock 10, Δd = 3: ⌈10/3⌉ − 1 = 3 level passes at r 17, 14, 11; the
    // last 1 mm goes with the allowance pass. The taper r10 z-10 → r20
    // z-30 has z = −10 − 2(r − 10).
    let got = run(START, "G71 P1 Q2 F0.2", TAPER).unwrap();
    let mut want = Vec::new();
    for k in 1..=3 {
        let r = 20.0 - 3.0 * f64::from(k);
        let mut pass = level_pass(2.0 * r, -10.0 - 2.0 * (r - 10.0), 1.0, -1.0, -1.0, 2.0);
        if k == 1 {
            pass.insert(1, "FEED F=0.2 MODE=MIN".into());
        }
        want.extend(pass);
    }
    // B′ by rapid (G00 ns), the allowance pass, back to A.
    want.extend([
        rapid(20.0, 2.0),
        line(20.0, -10.0),
        line(40.0, -30.0),
        rapid(40.0, 2.0),
    ]);
    assert_eq!(got, want);
    // First pass: X34 Z-24, retract X36 Z-23.
    assert_eq!(got[2..4], [line(34.0, -24.0), line(36.0, -23.0)]);
}

#[test]
fn g71_arc_profile_meets_the_arc_on_every_level() {
    // A = X30 Z2 (r15). N1 G00 X10; G01 Z0; G03 X30 Z-10 R10: a quarter
    // from r5 z0 to r15 z-10 about r5 z-10 (CCW). Δd = 2: levels r 13, 11,
    // 9, 7 (r5 = B′ is not strictly before B′). On the arc a level r
    // meets it at z = −10 + √(100 − (r − 5)²): −4, −2, −0.834849, −0.202041.
    let setup = ["G98 G00 X30 Z2", "G71 U2 R0.5"];
    let got = run(
        &setup,
        "G71 P1 Q2 F0.2",
        &["G00 X10", "G01 Z0", "G03 X30 Z-10 R10"],
    )
    .unwrap();
    let z_at = |r: f64| -10.0 + (100.0 - (r - 5.0) * (r - 5.0)).sqrt();
    let mut want = Vec::new();
    for r in [13.0, 11.0, 9.0, 7.0] {
        want.extend(level_pass(2.0 * r, z_at(r), 0.5, -1.0, -1.0, 2.0));
    }
    want.insert(1, "FEED F=0.2 MODE=MIN".into());
    want.extend([
        rapid(10.0, 2.0),
        line(10.0, 0.0),
        "ARC DIR=CCW X=30 Z=-10 CX=10 CZ=-10".into(),
        rapid(30.0, 2.0),
    ]);
    assert_eq!(got, want);
    assert_eq!(got[2], "LINE X=26 Z=-4");
    assert_eq!(got[14], "LINE X=14 Z=-0.202");
}

#[test]
fn g71_bore_with_negative_allowance() {
    // A = X20 Z1 (r10). Δu = −0.5 (r −0.25), Δw = 0.1: A′ = r9.75 z1.1
    // (X19.5), B′ = r17.75 (X35.5). sx = +1, sz = −1. Stock 8, Δd = 1.5:
    // ⌈8/1.5⌉ − 1 = 5 levels r 11.25 … 17.25. P′: r17.75 z1.1 → z-9.9 →
    // r11.75 z-19.9 (taper, z = −9.9 + (r − 17.75)/0.6) → r9.75 z-19.9.
    // Level r11.25 lies past the taper: it meets the last element at z-19.9.
    let setup = ["G98 G00 X20 Z1", "G71 U1.5 R0.5"];
    let profile = ["G00 X36", "G01 Z-10", "X24 Z-20", "X20"];
    let got = run(&setup, "G71 P1 Q2 U-0.5 W0.1 F0.2", &profile).unwrap();
    let taper = |r: f64| -9.9 + (r - 17.75) / 0.6;
    let mut want = vec![rapid(19.5, 1.1)];
    for k in 1..=5 {
        let r = 9.75 + 1.5 * f64::from(k);
        let z = if r <= 11.75 { -19.9 } else { taper(r) };
        want.extend(level_pass(2.0 * r, z, 0.5, 1.0, -1.0, 1.1));
    }
    want.insert(2, "FEED F=0.2 MODE=MIN".into());
    want.extend([
        rapid(35.5, 1.1),
        line(35.5, -9.9),
        line(23.5, -19.9),
        line(19.5, -19.9),
        rapid(20.0, 1.0),
    ]);
    assert_eq!(got, want);
    // First pass X22.5 to Z-19.9, retract X21.5 Z-19.4; last X34.5 Z-10.7333.
    assert_eq!(got[3..5], [line(22.5, -19.9), line(21.5, -19.4)]);
    assert_eq!(got[19], "LINE X=34.5 Z=-10.7333");
}

#[test]
fn g72_facing_cuts_along_x() {
    // A = X50 Z1. Δu 0.2 (r +0.1), Δw 0.1: A′ = X50.2 Z1.1, B′ = X50.2
    // Z-5.9. P′: r25.1 z-5.9 → r15.1 → r10.1 z-1.9 → z1.1. sz = −1 (infeed),
    // sx = −1 (cut). Stock 7, Δd 2: 3 levels Z-0.9, -2.9, -4.9. The taper
    // r = 15.1 − 5(z + 5.9)/4: Z-2.9 → X22.7, Z-4.9 → X27.7; Z-0.9 meets
    // the last element at X20.2. Retract: X + 1, Z + 0.5.
    let setup = ["G98 G00 X50 Z1", "G72 W2 R0.5"];
    let profile = ["G00 Z-6", "G01 X30", "X20 Z-2", "Z1"];
    let got = run(&setup, "G72 P1 Q2 U0.2 W0.1 F0.15", &profile).unwrap();
    let mut want = vec![rapid(50.2, 1.1)];
    for (z, x) in [(-0.9, 20.2), (-2.9, 22.7), (-4.9, 27.7)] {
        want.extend([
            rapid(50.2, z),
            line(x, z),
            line(x + 1.0, z + 0.5),
            rapid(50.2, z + 0.5),
        ]);
    }
    want.insert(2, "FEED F=0.15 MODE=MIN".into());
    want.extend([
        rapid(50.2, -5.9),
        line(30.2, -5.9),
        line(20.2, -1.9),
        line(20.2, 1.1),
        rapid(50.0, 1.0),
    ]);
    assert_eq!(got, want);
}

#[test]
fn g73_with_one_pass_runs_on_the_allowance_contour() {
    // d = 1: f = 0, so the only pass is moved by the allowance alone:
    // δX = 0.4, δZ = 0.2. The G02 R5 from r10 z-10 to r15 z-15 has its
    // centre at r15 z-10 (X30 Z-10), moved to X30.4 Z-9.8.
    let setup = ["G98 G00 X40 Z3", "G73 U5 W2 R1"];
    let profile = ["G00 X20 Z1", "G01 Z-10", "G02 X30 Z-15 R5", "G01 X40"];
    let got = run(&setup, "G73 P1 Q2 U0.4 W0.2 F0.2", &profile).unwrap();
    let want = [
        rapid(40.4, 3.2),
        rapid(20.4, 1.2),
        "FEED F=0.2 MODE=MIN".into(),
        line(20.4, -9.8),
        "ARC DIR=CW X=30.4 Z=-14.8 CX=30.4 CZ=-9.8".into(),
        line(40.4, -14.8),
        rapid(40.0, 3.0),
    ];
    assert_eq!(got, want);
}

#[test]
fn g73_passes_come_nearer_by_equal_steps() {
    // d = 4, Δi = 3, Δk = 1.5, no allowance: pass n is moved by
    // 2·3·(4 − n)/3 in X and 1.5·(4 − n)/3 in Z: X +6, +4, +2, 0.
    let setup = ["G98 G00 X40 Z3", "G73 U3 W1.5 R4"];
    let got = run(&setup, "G73 P1 Q2 F0.2", &["G01 X20 Z0", "X40 Z-10"]).unwrap();
    let rapids: Vec<String> = got
        .iter()
        .filter(|l| l.starts_with("RAPID"))
        .cloned()
        .collect();
    let mut want: Vec<String> = (1..=4)
        .map(|n| {
            let f = f64::from(4 - n) / 3.0;
            rapid(40.0 + 6.0 * f, 3.0 + 1.5 * f)
        })
        .collect();
    // The last pass starts at A itself, then the return to A.
    want.push(rapid(40.0, 3.0));
    assert_eq!(rapids, want);
    assert_eq!(got.iter().filter(|l| l.starts_with("LINE")).count(), 8);
}

#[test]
fn g71_type2_follows_the_pocket_between_levels() {
    // A = X50 Z2 (r25), depth d = 25 − r, position u = −z. K′: ns G01 to
    // r20 z0 (depth 5), z-10, r15 z-15 (10), z-20, r22 (3), z-30, r25 (0).
    // D = 10, Δd = 3: levels 3, 6, 9 (r22, r19, r16), e = 1.
    // Pass 1: the ns element reaches depth 3 at z0.8; one deep run to
    // z-20; the floor at depth 3 and the climb are band pieces.
    // Pass 2: travel h = 3, τ = −1 (X52); the taper meets r19 at z-11, the
    // wall at z-20. Pass 3: travel h = 6 (the taper at z-11), τ = min(2, 5);
    // the taper meets r16 at z-14. Travel to A′: h → 0 near z2, τ = −1.
    let setup = ["G98 G00 X50 Z2", "G71 U3 R1"];
    let profile = [
        "G01 X40 Z0",
        "Z-10",
        "X30 Z-15",
        "Z-20",
        "X44",
        "Z-30",
        "X50",
    ];
    let got = run(&setup, "G71 P1 Q2 F0.2", &profile).unwrap();
    let contour = [
        line(40.0, 0.0),
        line(40.0, -10.0),
        line(30.0, -15.0),
        line(30.0, -20.0),
        line(44.0, -20.0),
        line(44.0, -30.0),
        line(50.0, -30.0),
    ];
    let mut want = vec![
        "FEED F=0.2 MODE=MIN".to_string(),
        line(44.0, 0.8),
        line(44.0, -20.0),
        line(44.0, -30.0),
        line(50.0, -30.0),
        line(52.0, -29.0),
        rapid(52.0, 0.8),
        rapid(44.0, 0.8),
        line(40.0, 0.0),
        line(40.0, -10.0),
        line(38.0, -11.0),
        line(38.0, -20.0),
        line(44.0, -20.0),
        line(46.0, -19.0),
        rapid(46.0, -11.0),
        rapid(38.0, -11.0),
        line(32.0, -14.0),
        line(32.0, -20.0),
        line(38.0, -20.0),
        line(40.0, -19.0),
        rapid(52.0, -19.0),
        rapid(52.0, 2.0),
        rapid(50.0, 2.0),
    ];
    want.extend(contour.iter().cloned());
    want.push(rapid(50.0, 2.0));
    assert_eq!(got, want);

    // J1: once more along the contour from A′ (the RAPID C′ → A′ equals
    // the final return, which then comes after the second run).
    let again = run(&setup, "G71 P1 Q2 J1 F0.2", &profile).unwrap();
    let mut want_j1 = want.clone();
    want_j1.extend(contour.iter().cloned());
    want_j1.push(rapid(50.0, 2.0));
    assert_eq!(again, want_j1);
}

#[test]
fn a_tail_over_the_start_level_only_joins_the_allowance_pass() {
    // The nf block goes back over the stock at X40 (the start level): the
    // tail. Without the rule the cut direction would be 0 (Z2 → Z2). The
    // levels are those of the taper test; the allowance pass ends with the
    // tail at feed and the return to A is then of zero length.
    let mut profile = TAPER.to_vec();
    profile.push("G00 Z2");
    let got = run(START, "G71 P1 Q2 K1 F0.2", &profile).unwrap();
    assert_eq!(
        got.iter().filter(|l| l.starts_with("LINE")).count(),
        3 * 2 + 3
    );
    assert_eq!(got[got.len() - 2..], [line(40.0, -30.0), line(40.0, 2.0)]);
}

#[test]
fn the_one_block_form_takes_d_and_the_machine_retract() {
    // `G71 P Q D3`: Δd = 3, e = cycles.g71_retract_mm = 0.5. First pass at
    // X34 (r17) to Z-24, retract X35 Z-23.5.
    let got = run(&["G98 G00 X40 Z2"], "G71 P1 Q2 D3 F0.2", TAPER).unwrap();
    assert_eq!(
        got[..5],
        [
            rapid(34.0, 2.0),
            "FEED F=0.2 MODE=MIN".into(),
            line(34.0, -24.0),
            line(35.0, -23.5),
            rapid(35.0, 2.0)
        ]
    );
}

#[test]
fn roughing_ignores_f_s_t_and_m_of_the_profile() {
    let profile = ["G00 X20 S500 T0202 M08", "G01 Z-10 F0.05", "X40 Z-30"];
    let mut nc = Nc::new(Machine::reference());
    let got = cycle(&mut nc, START, "G71 P1 Q2 F0.2", &profile).unwrap();
    assert!(got
        .iter()
        .all(|l| l.starts_with("RAPID") || l.starts_with("LINE") || l == "FEED F=0.2 MODE=MIN"));
    assert_eq!(nc.st.feed, 0.2);
    assert_eq!((nc.st.tool, nc.st.offset), (1, 0));
}

#[test]
fn a_pocket_in_type_i_stops_the_roughing() {
    // Level r17 (X34): walking P′ it meets X24 going back into the
    // material (r15 → r12) before it comes back to the level: E4009 after
    // the infeed has been printed. With K1 the check comes before anything
    // moves.
    let profile = ["G00 X20", "G01 Z-10", "X30", "Z-20", "X24", "Z-30", "X40"];
    let mut nc = Nc::new(Machine::reference());
    let mut events: Vec<Event> = Vec::new();
    for b in START {
        nc.exec(&block(b), &mut events).unwrap();
    }
    events.clear();
    for (i, b) in profile.iter().enumerate() {
        nc.push_profile(&block(b), i as u32);
    }
    let e = nc
        .exec(&block("G71 P1 Q2 U0 F0.2"), &mut events)
        .unwrap_err();
    // The culprit is the X24 block (tag 4): it runs from X30 down to X24,
    // and the way out is type II.
    // It stands on the cycle block and points to the culprit.
    assert_eq!((e.code, e.at, e.culprit), (4009, None, Some(4)));
    assert!(
        e.message
            .ends_with("a profile block runs back along X from X30 to X24"),
        "{}",
        e.message
    );
    assert!(e.help.as_deref().is_some_and(|h| h.contains("type II")));
    assert_eq!(
        events,
        vec![Event::Rapid {
            x: 34.0,
            z: 2.0,
            c: None
        }]
    );
    let e = run(START, "G71 P1 Q2 K1 F0.2", &profile).unwrap_err();
    assert_eq!(e.code, 4009);
}

#[test]
fn e2021_comes_from_the_ns_block_and_its_modal_code() {
    // N1 writes no G code: the G02 in force counts.
    let setup = ["G98 G00 X40 Z2", "G02", "G71 U3 R1"];
    let e = run(&setup, "G71 P1 Q2 F0.2", &["X20", "G01 Z-10"]).unwrap_err();
    assert_eq!((e.code, e.at), (2021, Some(1)));
    // Checked first: before the missing Δd (E4009).
    let e = run(&["G00 X40 Z2"], "G72 P1 Q2 F0.2", &["G01 X20", "Z-10"]).unwrap_err();
    assert_eq!((e.code, e.at), (2021, Some(1)));
    let e = run(&["G00 X40 Z2"], "G71 P1 Q2 F0.2", TAPER).unwrap_err();
    assert_eq!((e.code, e.at), (4009, None));
}

#[test]
fn profile_blocks_with_group_00_codes_are_e2020_at_that_block() {
    let e = run(
        START,
        "G71 P1 Q2 F0.2",
        &["G00 X20", "G04 P100", "G01 Z-10"],
    )
    .unwrap_err();
    assert_eq!((e.code, e.at), (2020, Some(2)));
    let e = run(START, "G70 P1 Q2", &["G00 X20", "G28 U0"]).unwrap_err();
    assert_eq!((e.code, e.at), (2020, Some(2)));
    let e = run(START, "G70", &[]).unwrap_err();
    assert_eq!(e.code, 2006);
}

#[test]
fn g73_needs_a_pass_and_an_integer_count() {
    let e = run(&["G00 X40 Z2", "G73 U1 W1 R0"], "G73 P1 Q2", TAPER).unwrap_err();
    assert_eq!(e.code, 4009);
    let e = run(&["G00 X40 Z2"], "G73 U1 W1 R3.", &[]).unwrap_err();
    assert_eq!(e.code, 1009);
}

#[test]
fn g70_runs_the_profile_and_returns_to_a() {
    // F, S, T in the profile act; M08 prints nothing; the last G00 block
    // leaves G00 modal inside, but G01 is back after G70 and F stays 50.
    let setup = ["G98 G01 X40 Z2 F100"];
    let profile = ["G00 X20 Z2", "G01 Z-10 F50 S900 M08", "X40 Z-20", "G00 X44"];
    let mut nc = Nc::new(Machine::reference());
    let got = cycle(&mut nc, &setup, "G70 P1 Q2", &profile).unwrap();
    let want = [
        rapid(20.0, 2.0),
        "SPEED S=900 MODE=RPM".into(),
        "FEED F=50 MODE=MIN".into(),
        line(20.0, -10.0),
        line(40.0, -20.0),
        rapid(44.0, -20.0),
        rapid(40.0, 2.0),
    ];
    assert_eq!(got, want);
    assert_eq!(nc.st.modal.motion, gcode::Motion::Line);
    assert_eq!(nc.st.feed, 50.0);
}

#[test]
fn the_two_block_angle_form_shapes_a_profile() {
    // Q135000 from X20 Z0 (r 10) and X40 Z-30 Q180000 meet where
    // r = 10 − z reaches r = 20: X40 Z-10. L2 on the first block is a
    // type II chamfer 2 mm from that corner on each line: along 135°
    // back, X(40 − 2√2) Z(−10 + √2); along 180° on, X40 Z-12.
    let setup = ["G98 G00 X60 Z3", "G73 U0 W0 R1"];
    let profile = [
        "G00 X20 Z2",
        "G01 Z0",
        "Q135000 L2",
        "X40 Z-30 Q180000",
        "X60",
    ];
    let got = run(&setup, "G73 P1 Q5 F0.2", &profile).unwrap();
    let r2 = core::f64::consts::SQRT_2;
    let want = [
        rapid(20.0, 2.0),
        "FEED F=0.2 MODE=MIN".into(),
        line(20.0, 0.0),
        line(40.0 - 2.0 * r2, -10.0 + r2),
        line(40.0, -12.0),
        line(40.0, -30.0),
        line(60.0, -30.0),
        rapid(60.0, 3.0),
    ];
    assert_eq!(got, want);
}

#[test]
fn a_chamfer_in_a_profile_is_cut_by_the_cycle() {
    // G01 Z-10 L2 then X40: a type II chamfer 2 mm from the corner r10
    // z-10 on each element: T1 = X20 Z-8, T2 = X24 Z-10.
    let setup = ["G98 G00 X40 Z3", "G73 U0 W0 R1"];
    let got = run(
        &setup,
        "G73 P1 Q2 F0.2",
        &["G00 X20 Z2", "G01 Z-10 L2", "X40"],
    )
    .unwrap();
    let want = [
        rapid(20.0, 2.0),
        "FEED F=0.2 MODE=MIN".into(),
        line(20.0, -8.0),
        line(24.0, -10.0),
        line(40.0, -10.0),
        rapid(40.0, 3.0),
    ];
    assert_eq!(got, want);
}

#[test]
fn random_profiles_never_panic() {
    // A small LCG: the same cases on every run.
    let mut seed: u64 = 0x5eed;
    let mut next = move |n: u64| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) % n
    };
    let codes = ["G00", "G01", "G02", "G03"];
    let mut ran = 0;
    for _ in 0..400 {
        let first = [
            "G71 U1.5 R0.5",
            "G72 W1.5 R0.5",
            "G73 U2 W1 R3",
            "G71 U0.1 R0",
        ][next(4) as usize];
        let cyc = ["G71", "G72", "G73", "G70"][next(4) as usize];
        let mut profile = Vec::new();
        for i in 0..1 + next(8) {
            let code = codes[next(4) as usize];
            let x = format!("X{}", next(80) as i64 - 10);
            let z = format!("Z{}", 5 - next(40) as i64);
            let mut b = match (i, next(3)) {
                (_, 0) => format!("{code} {x}"),
                (_, 1) => format!("{code} {z}"),
                _ => format!("{code} {x} {z}"),
            };
            if code == "G02" || code == "G03" {
                b.push_str(&format!(" R{}", next(30) as i64 - 5));
            }
            // Angle programming: the first block of a pair, or an angle
            // on a block with an end point (one form or the pair's second).
            match next(6) {
                0 => b = format!("{code} Q{}", next(360_000)),
                1 => b.push_str(&format!(" Q{}", next(360_000))),
                _ => {}
            }
            profile.push(b);
        }
        let refs: Vec<&str> = profile.iter().map(String::as_str).collect();
        let setup = ["G98 G00 X50 Z3", first];
        let text = format!(
            "{cyc} P1 Q2 U{} W{} F0.2 K{} J{}",
            next(3),
            next(2),
            next(2),
            next(2)
        );
        ran += usize::from(run(&setup, &text, &refs).is_ok());
    }
    // Most random shapes are rejected, but enough run to cover the paths.
    assert!(ran > 40, "only {ran} of 400 ran");
}

#[test]
fn g70_applies_corners_and_ignores_one_on_the_nf_block() {
    // As the G73 case: T1 = X20 Z-8, T2 = X24 Z-10. The L1 of the nf block
    // has no next move: the last line is printed whole before the return.
    let setup = ["G98 G00 X40 Z3 F0.2"];
    let got = run(
        &setup,
        "G70 P1 Q2",
        &["G00 X20 Z2", "G01 Z-10 L2", "X40 L1"],
    )
    .unwrap();
    let want = [
        rapid(20.0, 2.0),
        "FEED F=0.2 MODE=MIN".into(),
        line(20.0, -8.0),
        line(24.0, -10.0),
        line(40.0, -10.0),
        rapid(40.0, 3.0),
    ];
    assert_eq!(got, want);
}

#[test]
fn c_words_in_a_profile_are_refused_where_c_exists() {
    // The cycles move X and Z only: C/H in a profile block is E2007 at that
    // block (tag 2), for roughing and finishing alike.
    let profile = ["G00 X20", "G01 Z-10 C90", "X40"];
    let mut m = Machine::reference();
    m.axes.c.enabled = true;
    for cyc in ["G71 P1 Q3 U0.5 W0.1 F0.2", "G70 P1 Q3"] {
        let e = cycle(&mut Nc::new(m.clone()), START, cyc, &profile).unwrap_err();
        assert_eq!((e.code, e.at), (2007, Some(2)), "{cyc}");
    }
}
