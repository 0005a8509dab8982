//! The codes in force through the C interface: the screen follows the
//! motion, not the VM (which reads ahead), and shows the power-on codes
//! before a program is loaded, before it runs and after a reset. The
//! expected codes are read by hand from the program and dialect.md §3.

mod periods;

use gbc::*;
use periods::*;

const PROGRAM: &str = "\
G00 X60 Z5
T0101
G96 S150 M03
G99 G01 X40 Z2 F0.2
Z-30
G97 S800
G98 G01 X50 F100
G00 X60 Z5
M30
";

/// G00, G97, G98, G21, G40, G23, G80, G67, G54, G64, G18, G15, G13.1.
const POWER_ON: [u16; GBC_ACTIVE_GROUPS] = [
    0, 970, 980, 210, 400, 230, 800, 670, 540, 640, 180, 150, 131,
];

fn active(c: GbcController) -> GbcActiveCodes {
    let mut a = GbcActiveCodes {
        g: [9999; GBC_ACTIVE_GROUPS],
        f: -1.0,
        s: -1.0,
        t: 9999,
    };
    assert_eq!(unsafe { gbc_active_codes(c, &mut a) }, GbcStatus::Ok);
    a
}

/// A reset, ticked until idle: the power-on codes again.
fn reset_shows_power_on(c: GbcController) {
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    for _ in 0..10_000 {
        if period(c).1 == GbcRunState::Idle {
            break;
        }
    }
    assert_eq!(active(c).g, POWER_ON);
}

/// Periods until the motion runs `line`.
fn until_line(c: GbcController, line: u32) {
    for _ in 0..200_000 {
        if period(c).0.line == line {
            return;
        }
    }
    panic!("line {line} never ran");
}

#[test]
fn the_codes_in_force_follow_the_motion() {
    let (m, c) = controller_on("");
    let unloaded = active(c);
    assert_eq!(
        (unloaded.g, unloaded.f, unloaded.s, unloaded.t),
        (POWER_ON, 0.0, 0.0, 0)
    );
    load(c, PROGRAM);
    assert_eq!(active(c).g, POWER_ON);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    until_line(c, 5);
    // G01, G96, G99 (groups 1–3), F0.2 S150 T0101: line 5's, though the
    // VM has read G97 S800 and G98 F100 by now.
    let cut = active(c);
    assert_eq!((cut.g[0], cut.g[1], cut.g[2]), (10, 960, 990));
    assert_eq!((cut.f, cut.s, cut.t), (0.2, 150.0, 101));
    // Line 5 runs from Z2 to Z-30 at X40: -30 less where Z is to go.
    let (sp, _) = period(c);
    let (mut x, mut z) = (f64::NAN, f64::NAN);
    assert_eq!(
        unsafe { gbc_distance_to_go(c, &mut x, &mut z) },
        GbcStatus::Ok
    );
    assert_eq!(sp.line, 5);
    assert!(
        x == 0.0 && (z - (-30.0 - sp.z)).abs() < 1e-9,
        "{x} {z} at Z{}",
        sp.z
    );
    assert_eq!(
        unsafe { gbc_distance_to_go(c, std::ptr::null_mut(), &mut z) },
        GbcStatus::NullPointer
    );
    until_line(c, 7);
    let face = active(c);
    assert_eq!(
        (face.g[1], face.g[2], face.f, face.s),
        (970, 980, 100.0, 800.0)
    );
    reset_shows_power_on(c);
    free(m, c);
}

/// After a program restart's search, before the cycle start, the screen
/// shows the codes the run resumes with (a control's restart page): at
/// line 5, line 4's G01 G96 G99 F0.2 S150 and line 2's T0101; after a
/// reset, the power-on codes again.
#[test]
fn a_restart_shows_the_codes_it_resumes_with() {
    let (m, c) = controller_on("");
    load(c, PROGRAM);
    assert_eq!(gbc_restart_from(c, 5, 1), GbcStatus::Ok);
    let resumed = active(c);
    let mut g = POWER_ON;
    (g[0], g[1], g[2]) = (10, 960, 990);
    assert_eq!(
        (resumed.g, resumed.f, resumed.s, resumed.t),
        (g, 0.2, 150.0, 101)
    );
    reset_shows_power_on(c);
    free(m, c);
}
