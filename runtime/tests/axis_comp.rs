//! Backlash and pitch error compensation through the controller: the
//! counts, the drives' command, take up a slide's lost motion once its
//! axis has turned back and add the pitch table's correction where it
//! stands; the set points stay the slide's. The expected counts are by
//! hand.

mod common;

use common::{run_with, Run};
use nc::Machine;
use runtime::counts::quantize;

/// From the power-on point X0 Z0 (work and machine coordinates are one):
/// X goes + to 40 (the power-on direction: nothing to take up) while Z
/// goes − to -5 (0.03 mm taken up); Z back + to -2 (given back); X − to
/// 20 (0.02 mm of diameter taken up); a dwell standing there.
const PROGRAM: &str = "G00 X40 Z-5\nG01 Z-2 F200\nG00 X20\nG04 X0.1\nM30\n";

fn run_on(toml: &str) -> Run {
    run_program(PROGRAM, toml)
}

fn run_program(src: &str, toml: &str) -> Run {
    let machine = Machine::from_toml(toml).expect("a machine file");
    run_with(src, machine, runtime::AutoAck, |_| {}, |_, _| {}, 60.0)
}

/// The counts of the periods of `line` standing at X`x` Z`z`.
fn standing(run: &Run, line: u32, x: f64, z: f64) -> Vec<(i64, i64)> {
    let at = run
        .pts
        .iter()
        .filter(|p| p.line == line && p.axis_x == x && p.axis_z == z);
    at.map(|p| (p.counts.x, p.counts.z)).collect()
}

#[test]
fn the_counts_take_up_the_lost_motion_where_an_axis_turns_back() {
    let run = run_on("[axes.x]\nbacklash_mm = 0.02\n[axes.z]\nbacklash_mm = 0.03\n");
    assert_eq!(run.alarm, None);
    let first = standing(&run, 1, 40.0, -5.0);
    assert!(!first.is_empty());
    assert!(first.iter().all(|&c| c == (40_000, -5_030)), "{first:?}");
    let back = standing(&run, 2, 40.0, -2.0);
    assert!(back.iter().all(|&c| c == (40_000, -2_000)), "{back:?}");
    let dwell = standing(&run, 4, 20.0, -2.0);
    assert!(dwell.len() >= 100, "{}", dwell.len());
    assert!(dwell.iter().all(|&c| c == (19_980, -2_000)), "{dwell:?}");
    // On the way, the command is never further from the set point than
    // the lost motion and half a count.
    for p in &run.pts {
        let dx = p.counts.x as f64 * 0.001 - p.axis_x;
        let dz = p.counts.z as f64 * 0.001 - p.axis_z;
        assert!((-0.0205..=0.0005).contains(&dx), "{dx} at {p:?}");
        assert!((-0.0305..=0.0005).contains(&dz), "{dz} at {p:?}");
    }
}

/// Without `backlash_mm` (the default), every count is its set point's.
#[test]
fn without_lost_motion_the_counts_are_the_set_points() {
    let run = run_on("");
    assert!(run.pts.iter().all(|p| {
        p.counts.x == quantize(p.axis_x, 0.001) && p.counts.z == quantize(p.axis_z, 0.001)
    }));
    assert_eq!(standing(&run, 4, 20.0, -2.0)[0], (20_000, -2_000));
}

/// X's table gives +0.02 of diameter at X100, so +0.008 at X40; Z's gives
/// −0.004 at −300, so −0.002 at −150 and −0.0013 at −100; Z's lost motion
/// 0.03 is taken up at −150 (Z came in −) and given back at −100 (in +).
/// By hand: standing at X40 Z-150, 40 008 and −150 000 − 30 − 2 steps;
/// at X40 Z-100, 40 008 and −100 001.33 rounded to −100 001.
#[test]
fn the_counts_add_the_pitch_correction_where_the_slide_stands() {
    let toml = "[axes.x]\npitch_comp_mm = [[0.0, 0.0], [100.0, 0.02]]\n\
        [axes.z]\nbacklash_mm = 0.03\npitch_comp_mm = [[-300.0, -0.004], [0.0, 0.0]]\n";
    let src = "G00 X40 Z-150\nG04 X0.1\nG01 Z-100 F500\nG04 X0.1\nM30\n";
    let run = run_program(src, toml);
    assert_eq!(run.alarm, None);
    let far = standing(&run, 2, 40.0, -150.0);
    assert!(
        far.len() >= 100 && far.iter().all(|&c| c == (40_008, -150_032)),
        "{far:?}"
    );
    let near = standing(&run, 4, 40.0, -100.0);
    assert!(
        near.len() >= 100 && near.iter().all(|&c| c == (40_008, -100_001)),
        "{near:?}"
    );
}

/// A rotary C with 0.05° of lost motion (`[axes.c] backlash_deg`): C
/// turns − to −90 and stands (the command 0.05° below: −90 050 steps of
/// 0.001°), then + to −30 (given back: −30 000); the set point stays
/// the table's angle throughout.
#[test]
fn a_rotary_axis_s_counts_take_up_its_lost_motion() {
    let toml = "[axes.c]\nenabled = true\nbacklash_deg = 0.05\n";
    let src = "G00 C-90\nG04 X0.1\nG00 C-30\nG04 X0.1\nM30\n";
    let run = run_program(src, toml);
    assert_eq!(run.alarm, None);
    let at = |line: u32, c: f64| -> Vec<i64> {
        let pts = run.pts.iter().filter(|p| p.line == line && p.c == Some(c));
        pts.map(|p| p.counts.c).collect()
    };
    let minus = at(2, -90.0);
    assert!(
        minus.len() >= 100 && minus.iter().all(|&n| n == -90_050),
        "{minus:?}"
    );
    let plus = at(4, -30.0);
    assert!(
        plus.len() >= 100 && plus.iter().all(|&n| n == -30_000),
        "{plus:?}"
    );
}

/// C's angular table (`pitch_comp_deg`): −0.009° at 270°, 0 at 0°,
/// +0.009° at 90°. By hand: at C−60 (300°, a third of the way from 270°
/// round to 360°) −0.006: −60 006 steps of 0.001°; at C30, 30/90 of the
/// way to 90°, +0.003: 30 003; at C390, a turn on, the same +0.003:
/// 390 003. The set point stays the programmed angle.
#[test]
fn a_rotary_axis_s_counts_add_its_angular_correction() {
    let toml = "[axes.c]\nenabled = true\n\
                pitch_comp_deg = [[0.0, 0.0], [90.0, 0.009], [270.0, -0.009]]\n";
    let src = "G00 C-60\nG04 X0.1\nG00 C30\nG04 X0.1\nG00 C390\nG04 X0.1\nM30\n";
    let run = run_program(src, toml);
    assert_eq!(run.alarm, None);
    for (line, c, count) in [(2, -60.0, -60_006), (4, 30.0, 30_003), (6, 390.0, 390_003)] {
        let pts = run.pts.iter().filter(|p| p.line == line && p.c == Some(c));
        let counts: Vec<i64> = pts.map(|p| p.counts.c).collect();
        assert!(
            counts.len() >= 100 && counts.iter().all(|&n| n == count),
            "line {line}: {counts:?}"
        );
    }
}
