//! Machine lock through the C interface: switched on before a program is
//! loaded (the panel keeps it), the run's programmed point reaches the
//! program's end while the axes and their counts stand at power-on; after
//! the reset, unlocked, the same program moves the slide from there.

mod periods;

use gbc::*;
use periods::{controller_on, free, load, period};

/// From machine zero (the reference machine's power-on point, work zero
/// there too) to X40 Z-20.
const PROGRAM: &str = "G00 X40 Z-20\nM30\n";

/// Cycle start and every period to the end: the last set point, and
/// whether the slide (set point and counts) ever left machine zero.
fn run(c: GbcController) -> (GbcSetPoint, bool) {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut moved = false;
    for _ in 0..100_000 {
        let (sp, state) = period(c);
        moved |= (sp.axis_x, sp.axis_z, sp.count_x, sp.count_z) != (0.0, 0.0, 0, 0);
        if state == GbcRunState::Ended {
            return (sp, moved);
        }
        assert_ne!(state, GbcRunState::Alarm);
    }
    panic!("did not end");
}

#[test]
fn a_locked_run_leaves_the_axes_at_power_on() {
    let (m, c) = controller_on("");
    assert_eq!(gbc_set_machine_lock(c, true), GbcStatus::Ok);
    load(c, PROGRAM);
    let (end, moved) = run(c);
    assert_eq!((end.x, end.z), (40.0, -20.0));
    assert!(!moved, "{end:?}");
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    while period(c).1 != GbcRunState::Idle {}
    assert_eq!(gbc_set_machine_lock(c, false), GbcStatus::Ok);
    let (end, moved) = run(c);
    assert!(moved);
    // From machine zero again: the same end, and the slide there.
    assert_eq!(
        (end.x, end.z, end.axis_x, end.axis_z),
        (40.0, -20.0, 40.0, -20.0)
    );
    assert_eq!((end.count_x, end.count_z), (40_000, -20_000));
    free(m, c);
}
