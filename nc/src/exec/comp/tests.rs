//! Hand-checked compensation through `Nc::exec`. Every expected point is
//! worked out in the comment above it, or by a formula written out in the
//! test from comp.md's definitions, not taken from the implementation.
//!
//! Points in the comments are (z, r), r = X/2; with R0.8 and tip 3 the
//! printed point is the nose centre + (−0.8, −0.8).

use alloc::format;
use alloc::string::String;
use alloc::string::ToString;
use alloc::vec;
use alloc::vec::Vec;

use crate::base::error::NcError;
use crate::base::event::Event;
use crate::base::machine::Machine;
use crate::base::words::{addr, Word, LITERAL, NO_POINT};
use crate::exec::Nc;

fn words(block: &str) -> Vec<Word> {
    block
        .split_whitespace()
        .map(|w| {
            let (letter, number) = w.split_at(1);
            Word {
                addr: addr(letter.as_bytes()[0]),
                value: number.parse().expect("a number"),
                // As the compiler marks a literal written without a point.
                flags: if number.contains('.') {
                    LITERAL
                } else {
                    LITERAL | NO_POINT
                },
            }
        })
        .collect()
}

fn tool(radius: f64, tip: u32) -> Machine {
    let toml = format!("[[tools.offset]]\nnumber = 1\nradius = {radius}\ntip = {tip}\n");
    Machine::from_toml(&toml).expect("a machine file")
}

/// Runs the blocks, flushes, and returns the canon lines.
fn run_on(m: Machine, blocks: &[&str]) -> Result<Vec<String>, NcError> {
    let mut nc = Nc::new(m);
    let mut events: Vec<Event> = Vec::new();
    for b in blocks {
        nc.exec(&words(b), &mut events)?;
    }
    nc.flush(&mut events)?;
    Ok(events.iter().map(|e| e.to_string()).collect())
}

fn run(blocks: &[&str]) -> Vec<String> {
    run_on(tool(0.8, 3), blocks).expect("the blocks run")
}

fn code_of(m: Machine, blocks: &[&str]) -> u16 {
    run_on(m, blocks).expect_err("an alarm").code
}

/// Same keywords and fields, numbers within 0.001 (canon.md).
fn assert_canon(got: &[String], want: &[String]) {
    let same_word = |a: &str, b: &str| match (a.split_once('='), b.split_once('=')) {
        (Some((ka, va)), Some((kb, vb))) => {
            ka == kb
                && match (va.parse::<f64>(), vb.parse::<f64>()) {
                    (Ok(x), Ok(y)) => (x - y).abs() <= 0.001,
                    _ => va == vb,
                }
        }
        _ => a == b,
    };
    let same = got.len() == want.len()
        && got.iter().zip(want).all(|(g, w)| {
            let (g, w): (Vec<&str>, Vec<&str>) = (g.split(' ').collect(), w.split(' ').collect());
            g.len() == w.len() && g.iter().zip(&w).all(|(a, b)| same_word(a, b))
        });
    assert!(same, "canon differs\n got: {got:#?}\nwant: {want:#?}");
}

fn lines(want: &[&str]) -> Vec<String> {
    want.iter().map(|s| s.to_string()).collect()
}

/// A printed point from a centre (z, r): X is the diameter.
fn rapid(z: f64, r: f64) -> String {
    format!("RAPID X={:.5} Z={z:.5}", 2.0 * r)
}

fn line(z: f64, r: f64) -> String {
    format!("LINE X={:.5} Z={z:.5}", 2.0 * r)
}

const FEED: &str = "FEED F=0.1 MODE=MIN";
const START: [&str; 3] = ["T0101", "G00 X60 Z5", "G42 G00 X20 Z2"];

fn program<'a>(rest: &[&'a str]) -> Vec<&'a str> {
    START.iter().copied().chain(rest.iter().copied()).collect()
}

#[test]
fn start_up_outside_corner_and_cancel() {
    // Start-up to Q (2, 10), next −Z: right(−Z) = +r, C = (2, 10.8),
    // printed (1.2, 10). Z-10 then down the face X10: a left turn, outside
    // for G42. The line ends on its normal (−10, 10.8) → printed (−10.8,
    // 10); the arc about Q (−10, 10) runs CCW to Q + 0.8·right(−r) =
    // (−10.8, 10) → printed (−11.6, 9.2), centre printed (−10.8, 9.2). The
    // face ends before the cancel on its own normal (−10.8, 5) → printed
    // (−11.6, 4.2); the cancel prints its programmed end.
    let got = run(&program(&["G01 Z-10 F0.1", "X10", "G40 G00 X30 Z20"]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
        "ARC DIR=CCW X=18.4 Z=-11.6 CX=18.4 CZ=-10.8",
        "LINE X=8.4 Z=-11.6",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn inside_corner_between_lines() {
    // Z-10 then up the face X40: a right turn, inside for G42. The offset
    // lines r = 10.8 and z = −10 + 0.8 meet at (−9.2, 10.8) → printed
    // (−10, 10): with tip 3 the corner of two axis-parallel lines prints
    // as programmed. The face ends on its normal (−9.2, 20) → (−10, 19.2).
    let got = run(&program(&["G01 Z-10 F0.1", "X40", "G40 G00 X50 Z5"]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10",
        "LINE X=38.4 Z=-10",
        "RAPID X=50 Z=5",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn inside_corner_between_a_line_and_an_arc() {
    // G03 X20 Z-20 R5 from (−10, 10): the half circle about (−15, 10)
    // leaves Q going +r, a right turn from −Z: inside for G42. G42 on a
    // G03 keeps the tool away from the centre: radius 5.8. r = 10.8 meets
    // (z + 15)² + 0.8² = 5.8² at z = −15 + √33 (the root nearer Q).
    let z = -15.0 + 33f64.sqrt();
    // The arc ends before the cancel on its normal: (−20.8, 10) →
    // printed (−21.6, 9.2); its centre prints at (−15.8, 9.2).
    let got = run(&program(&[
        "G01 Z-10 F0.1",
        "G03 X20 Z-20 R5",
        "G40 G00 X40 Z5",
    ]));
    let want = vec![
        "TOOL T=1 D=1".to_string(),
        "RAPID X=60 Z=5".into(),
        "RAPID X=20 Z=1.2".into(),
        FEED.into(),
        line(z - 0.8, 10.0),
        "ARC DIR=CCW X=18.4 Z=-21.6 CX=18.4 CZ=-15.8".into(),
        "RAPID X=40 Z=5".into(),
    ];
    assert_canon(&got, &want);
}

#[test]
fn a_start_up_followed_by_a_cancel_uses_its_own_direction() {
    // From (5, 30) to Q (2, 10): t = (−3, −20)/√409; right(t) for G42 is
    // (t_r, −t_z) = (−20, 3)/√409. C = Q + 0.8·right(t), printed − 0.8.
    let n = 409f64.sqrt();
    let (cz, cr) = (2.0 - 0.8 * 20.0 / n, 10.0 + 0.8 * 3.0 / n);
    let got = run(&[
        "T0101",
        "G00 X60 Z5",
        "G42 G01 X20 Z2 F0.1",
        "G40 G00 X60 Z5",
    ]);
    let want = vec![
        "TOOL T=1 D=1".to_string(),
        "RAPID X=60 Z=5".into(),
        FEED.into(),
        line(cz - 0.8, cr - 0.8),
        "RAPID X=60 Z=5".into(),
    ];
    assert_canon(&got, &want);
}

#[test]
fn each_tip_direction_moves_the_printed_point() {
    // The start-up centre is (2, 10.8) (see above); v(T) as comp.md §3
    // tabulates it, (ΔZ, Δr) for T = 0…9.
    let v = [
        (0.0, 0.0),
        (1.0, 1.0),
        (-1.0, 1.0),
        (-1.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (-1.0, 0.0),
        (0.0, -1.0),
        (0.0, 0.0),
    ];
    for (t, (dz, dr)) in v.iter().enumerate() {
        let got = run_on(tool(0.8, t as u32), &program(&["G01 Z-10 F0.1"])).expect("runs");
        let start_up = got.get(2).cloned().unwrap_or_default();
        assert_canon(&[start_up], &[rapid(2.0 + 0.8 * dz, 10.8 + 0.8 * dr)]);
    }
}

#[test]
fn a_zero_length_move_prints_where_the_tool_stands() {
    // As in the outside corner: Z-10 ends printed at (−10.8, 10) before
    // the corner arc, which belongs to the face; the repeated Z-10 prints
    // there, after the line and before the arc.
    let got = run(&program(&[
        "G01 Z-10 F0.1",
        "Z-10",
        "X10",
        "G40 G00 X30 Z20",
    ]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
        "LINE X=20 Z=-10.8",
        "ARC DIR=CCW X=18.4 Z=-11.6 CX=18.4 CZ=-10.8",
        "LINE X=8.4 Z=-11.6",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn blocks_without_a_move_print_between_the_elements() {
    // The dwell and M08 stand between Z-10 and the face: they print after
    // Z-10's line (its end needs the face) and before the corner arc.
    let got = run(&program(&[
        "G01 Z-10 F0.1",
        "G04 P500",
        "M08",
        "X10",
        "G40 G00 X30 Z20",
    ]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
        "DWELL S=0.5",
        "M CODE=8",
        "ARC DIR=CCW X=18.4 Z=-11.6 CX=18.4 CZ=-10.8",
        "LINE X=8.4 Z=-11.6",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn the_end_of_the_run_ends_the_last_element_on_its_normal() {
    // No cancel: the flush at the end prints Z-10 on its normal
    // (−10, 10.8) → printed (−10.8, 10).
    let got = run(&program(&["G01 Z-10 F0.1"]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn g90_taper_moves_the_cut_towards_the_start_point() {
    // A = (2, 26), G90 X40 Z-20 R-2: cut ℓ2 from S (2, 18) to E (−20, 20),
    // retract ℓ3 from E to F (−20, 26). ℓ2's unit normal towards A is
    // n = (2, 22)/√488; moved ℓ2 passes S + 0.8·n + (−0.8, −0.8) with the
    // slope Δr/Δz = 2/(−22). ℓ3's normal towards A is +z: moved by 0.8 and
    // back by the tip, it stays at z = −20.
    let k = 488f64.sqrt();
    let p = (2.0 + 0.8 * 2.0 / k - 0.8, 18.0 + 0.8 * 22.0 / k - 0.8);
    let r_at = |z: f64| p.1 + (z - p.0) * (2.0 / -22.0);
    let got = run(&["T0101", "G00 X52 Z2", "G42", "G90 X40 Z-20 R-2 F0.1"]);
    let want = vec![
        "TOOL T=1 D=1".to_string(),
        "RAPID X=52 Z=2".into(),
        rapid(2.0, r_at(2.0)),
        FEED.into(),
        line(-20.0, r_at(-20.0)),
        "LINE X=52 Z=-20".into(),
        "RAPID X=52 Z=2".into(),
    ];
    assert_canon(&got, &want);
}

#[test]
fn the_seventh_block_without_a_move_is_e4034() {
    // From the G42 block on: G42, M08, M09, S100, G04, F0.2 are six.
    let six = [
        "T0101",
        "G00 X60 Z5",
        "G42",
        "M08",
        "M09",
        "S100",
        "G04 P10",
        "F0.2",
    ];
    assert!(run_on(tool(0.8, 3), &six).is_ok());
    let mut seven = six.to_vec();
    seven.push("M08");
    assert_eq!(code_of(tool(0.8, 3), &seven), 4034);
    // A move resets the count; a zero-length move does not.
    let mut moved = six.to_vec();
    moved.extend(["G01 X20 Z2", "M08", "M09"]);
    assert!(run_on(tool(0.8, 3), &moved).is_ok());
    let mut zero = six.to_vec();
    zero.push("G01 X60 Z5");
    assert_eq!(code_of(tool(0.8, 3), &zero), 4034);
    // Under G40 nothing is counted.
    let plain = ["M08", "M09", "M08", "M09", "M08", "M09", "M08", "M09"];
    assert!(run_on(tool(0.8, 3), &plain).is_ok());
}

#[test]
fn starting_or_cancelling_on_an_arc_is_e4031() {
    let m = || tool(0.8, 3);
    assert_eq!(
        code_of(m(), &["T0101", "G00 X30 Z2", "G42 G02 X40 Z-3 R5 F0.1"]),
        4031
    );
    let cancel = program(&["G01 Z-10 F0.1", "G40 G02 X30 Z-15 R5"]);
    assert_eq!(code_of(m(), &cancel), 4031);
    // G31 and G53 need compensation off; G40 alone is not enough.
    assert_eq!(code_of(m(), &program(&["G31 X30 F0.1"])), 4031);
    assert_eq!(code_of(m(), &program(&["G40", "G53 X0 Z0"])), 4031);
}

#[test]
fn interference_is_e4036() {
    // G42 on a G02 puts the tool on the centre side: R5 arc, R6 tool.
    let small = program(&["G01 Z-10 F0.1", "G02 X30 Z-15 R5", "G40 G00 X60"]);
    assert_eq!(code_of(tool(6.0, 3), &small), 4036);
    // Wear larger than the geometry: a negative radius at the start-up.
    let toml = "[[tools.offset]]\nnumber = 1\nradius = 0.4\nwear_radius = -0.5\ntip = 3\n";
    let m = Machine::from_toml(toml).expect("a machine file");
    assert_eq!(code_of(m, &START), 4036);
    // A 0.5 mm step inside a 0.8 mm nose: after the inside corner the
    // face X21 would run backwards.
    let step = program(&["G01 Z-10 F0.1", "X21", "Z-20", "G40 G00 X60"]);
    assert_eq!(code_of(tool(0.8, 3), &step), 4036);
}

#[test]
fn m98_is_refused_while_compensating() {
    let mut nc = Nc::new(tool(0.8, 3));
    let mut events: Vec<Event> = Vec::new();
    assert!(nc.check_call().is_ok());
    nc.exec(&words("G42"), &mut events).expect("runs");
    assert_eq!(nc.check_call().map_err(|e| e.code), Err(4035));
    // Once running, G40 alone leaves the cancel move to come.
    nc.exec(&words("G00 X20 Z2"), &mut events).expect("runs");
    nc.exec(&words("G40"), &mut events).expect("runs");
    assert_eq!(nc.check_call().map_err(|e| e.code), Err(4035));
    nc.exec(&words("G00 X60 Z5"), &mut events).expect("runs");
    assert!(nc.check_call().is_ok());
}

#[test]
fn a_zero_radius_changes_nothing() {
    // The reference machine: offsets are 0, so the path is as programmed
    // and no corner arc appears.
    let got = run_on(
        Machine::reference(),
        &program(&["G01 Z-10 F0.1", "X10", "G40 G00 X30 Z20"]),
    )
    .expect("runs");
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=2",
        FEED,
        "LINE X=20 Z=-10",
        "LINE X=10 Z=-10",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn a_zero_length_start_up_still_goes_to_the_first_normal() {
    // Already at Q (2, 10): the start-up still moves the centre to
    // Q + 0.8·right(−Z) = (2, 10.8), printed (1.2, 10).
    let got = run(&[
        "T0101",
        "G00 X20 Z2",
        "G42 G00 X20 Z2",
        "G01 Z-10 F0.1",
        "G40 G00 X30 Z20",
    ]);
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=20 Z=2",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}

#[test]
fn a_change_of_side_cancels_and_starts_again() {
    // G42 Z-10 ends on its own normal (−10, 10.8) → printed (−10.8, 10).
    // The G41 move starts up to Q (−10, 5) + 0.8·left(−Z) = (−10, 4.2) →
    // printed (−10.8, 3.4); Z-20 ends on its normal (−20, 4.2) → (−20.8,
    // 3.4) before the cancel.
    let got = run(&program(&[
        "G01 Z-10 F0.1",
        "G41 X10",
        "Z-20",
        "G40 G00 X30 Z20",
    ]));
    let want = lines(&[
        "TOOL T=1 D=1",
        "RAPID X=60 Z=5",
        "RAPID X=20 Z=1.2",
        FEED,
        "LINE X=20 Z=-10.8",
        "LINE X=6.8 Z=-10.8",
        "LINE X=6.8 Z=-20.8",
        "RAPID X=30 Z=20",
    ]);
    assert_canon(&got, &want);
}
