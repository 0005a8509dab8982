//! The work frame of the trace: the programmed point, machine position
//! minus the shift (work zero and tool offset), from the first period on.

mod common;

use common::*;
use nc::Machine;
use runtime::{Motion, RunState};

/// G54 at machine X−100 Z−50 (X a diameter); tool 1's offset X−2.5
/// (diameter) Z+1.2.
const MACHINE: &str = "[coords]
g54 = { x = -100.0, z = -50.0 }
[[tools.offset]]
number = 1
x = -2.5
z = 1.2
";

fn machine() -> Machine {
    match Machine::from_toml(MACHINE) {
        Ok(m) => m,
        Err(e) => panic!("the test's machine file: {e}"),
    }
}

fn run_g54(src: &str) -> Run {
    run_with(src, machine(), runtime::AutoAck, |_| {}, |_, _| {}, 60.0)
}

/// Work minus machine of a set point, (X diameter, Z).
fn work_minus_axes(p: &runtime::SetPoint) -> (f64, f64) {
    (p.x - p.axis_x, p.z - p.axis_z)
}

/// The tool starts at machine zero, so under G54 (X−100, Z−50) it stands
/// at work X100 Z50 (0 − (−100), 0 − (−50)). A dwell before the first
/// move shows that point, not X0 Z0, and no period jumps.
#[test]
fn a_dwell_before_the_first_move_shows_the_work_position() {
    let r = run_g54("O0001\nG04 X0.003\nM03 S100\nG00 X20 Z5\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    let dwell: Vec<_> = r.pts.iter().filter(|p| p.motion == Motion::Dwell).collect();
    // 0.003 s at 1 ms periods.
    assert_eq!(dwell.len(), 3);
    for p in &dwell {
        assert_eq!((p.x, p.z), (100.0, 50.0), "at {} s", p.time_s);
        assert_eq!((p.axis_x, p.axis_z), (0.0, 0.0), "at {} s", p.time_s);
    }
    // No origin change in the program: work − machine is G54's −shift
    // (X +100, Z +50) in every period.
    for p in &r.pts {
        let (dx, dz) = work_minus_axes(p);
        assert!(
            (dx - 100.0).abs() < 1e-9 && (dz - 50.0).abs() < 1e-9,
            "at {} s work − machine is X{dx} Z{dz}",
            p.time_s
        );
    }
    let last = r.pts.last().map(|p| (p.x, p.z));
    assert_eq!(last, Some((20.0, 5.0)));
}

/// T0101 first: the axes move by the offset (X −2.5 diameter, Z +1.2)
/// while the programmed point stays at work X100 Z50; the G00 then ends
/// at work X20 Z5, machine X20 − 100 − 2.5 = −82.5, Z5 − 50 + 1.2 = −43.8.
#[test]
fn a_tool_offset_before_the_first_move_keeps_the_work_position() {
    let r = run_g54("O0002\nT0101\nG00 X20 Z5\nM30\n");
    assert_eq!(r.state, RunState::Ended);
    let offset: Vec<_> = r.pts.iter().filter(|p| p.line == 2).collect();
    assert!(offset.len() > 10, "{} periods of the offset", offset.len());
    for p in &offset {
        assert_eq!((p.x, p.z), (100.0, 50.0), "at {} s", p.time_s);
    }
    // The offset move ends with the axes at the offset.
    let end = offset.last().map(|p| (p.axis_x, p.axis_z));
    assert!(
        end.is_some_and(|(x, z)| (x + 2.5).abs() < 1e-9 && (z - 1.2).abs() < 1e-9),
        "{end:?}"
    );
    let last = r.pts.last().map(|p| (p.x, p.z, p.axis_x, p.axis_z));
    let Some((x, z, ax, az)) = last else {
        panic!("no periods")
    };
    assert!(
        (x - 20.0).abs() < 1e-9 && (z - 5.0).abs() < 1e-9,
        "X{x} Z{z}"
    );
    assert!(
        (ax + 82.5).abs() < 1e-9 && (az + 43.8).abs() < 1e-9,
        "X{ax} Z{az}"
    );
}
