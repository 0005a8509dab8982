//! The codes in force on the operator's screen follow the motion, not
//! the VM, which reads ahead: while the cut of line 5 runs, the screen
//! shows G96 G99 F0.2 although the VM has already read the G97 and G98
//! of lines 6 and 7 (docs/embedding.md, "Operator and PLC").

mod common;

use common::module;
use nc::Machine;
use runtime::{ActiveCodes, Controller, RunState, ACTIVE_GROUPS};

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

/// The code of group `g` (its number, as #4001–#4021 count them), in
/// tenths.
fn group(a: &ActiveCodes, g: u8) -> u16 {
    let i = ACTIVE_GROUPS.iter().position(|&x| x == g).expect("a group");
    a.g[i]
}

/// Ticks until the motion runs line `line`.
fn until_line(ctl: &mut Controller, line: u32) {
    for _ in 0..200_000 {
        ctl.run_ahead();
        if ctl.tick().line == line {
            return;
        }
    }
    panic!("line {line} never ran: {:?}", ctl.state());
}

/// By hand from dialect.md §3's power-on codes: G00, G97, G98, G21, G40,
/// G23, G80, G67, G54, G64, G18, G15 (group 17), G13.1 (group 21).
const POWER_ON: [u16; 13] = [
    0, 970, 980, 210, 400, 230, 800, 670, 540, 640, 180, 150, 131,
];

#[test]
fn the_screen_shows_the_codes_of_the_block_the_motion_runs() {
    let machine = Machine::reference();
    let mut ctl =
        Controller::new(module(PROGRAM, &machine), machine, runtime::AutoAck).expect("loads");
    let idle = ctl.active_codes();
    assert_eq!((idle.g, idle.f, idle.s, idle.t), (POWER_ON, 0.0, 0.0, 0));
    ctl.cycle_start();
    until_line(&mut ctl, 5);
    let cut = ctl.active_codes();
    assert_eq!(
        (group(&cut, 1), group(&cut, 2), group(&cut, 3)),
        (10, 960, 990)
    );
    assert_eq!((cut.f, cut.s, cut.t), (0.2, 150.0, 101));
    // The VM is past lines 6 and 7 already.
    let read = ctl.vm().nc.active_codes();
    assert_eq!(
        (group(&read, 2), group(&read, 3), read.f),
        (970, 980, 100.0)
    );
    until_line(&mut ctl, 7);
    let face = ctl.active_codes();
    assert_eq!(
        (group(&face, 1), group(&face, 2), group(&face, 3)),
        (10, 970, 980)
    );
    assert_eq!((face.f, face.s), (100.0, 800.0));
    until_line(&mut ctl, 8);
    assert_eq!(group(&ctl.active_codes(), 1), 0);
    ctl.reset();
    for _ in 0..10_000 {
        ctl.tick();
        if ctl.state() == RunState::Idle {
            break;
        }
    }
    assert_eq!(ctl.active_codes().g, POWER_ON);
}

/// The split controller: the real-time half shows the same, the
/// interpreter's VM ahead of it.
#[test]
fn the_real_time_half_shows_the_codes_of_its_motion() {
    let machine = Machine::reference();
    let ctl = Controller::new(module(PROGRAM, &machine), machine, runtime::AutoAck).expect("loads");
    let (mut interp, mut rt) = ctl.split();
    assert_eq!(rt.active_codes().g, POWER_ON);
    rt.cycle_start();
    let mut line = 0;
    for _ in 0..200_000 {
        interp.run_ahead();
        line = rt.tick().line;
        if line == 5 {
            break;
        }
    }
    assert_eq!(line, 5);
    let cut = rt.active_codes();
    assert_eq!(
        (group(&cut, 2), group(&cut, 3), cut.f, cut.s),
        (960, 990, 0.2, 150.0)
    );
}

/// Distance to go: the cut of line 5 (Z2 to Z-30 at X40) has -30 less
/// where Z is to go, and none in X; the move of line 7 (X40 to X50 at
/// Z-30) has 50 less where X is, on the diameter. None while idle, in a
/// feed hold it stays as it was, none after the end.
#[test]
fn the_screen_shows_the_distance_the_move_has_to_go() {
    let machine = Machine::reference();
    let mut ctl =
        Controller::new(module(PROGRAM, &machine), machine, runtime::AutoAck).expect("loads");
    let none = runtime::Xz { x: 0.0, z: 0.0 };
    assert_eq!(ctl.distance_to_go(), none);
    ctl.cycle_start();
    until_line(&mut ctl, 5);
    let mut cut = Vec::new();
    for _ in 0..200 {
        ctl.run_ahead();
        let sp = ctl.tick();
        let d = ctl.distance_to_go();
        assert_eq!(d.x, 0.0);
        assert!((d.z - (-30.0 - sp.z)).abs() < 1e-9, "{d:?} at Z{}", sp.z);
        cut.push(d.z);
    }
    assert!(cut.windows(2).all(|w| w[1] > w[0]), "it shrinks as Z goes");
    ctl.feed_hold();
    for _ in 0..2_000 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.state(), RunState::Held);
    let held = ctl.distance_to_go();
    assert!(held.z < -1.0, "{held:?}");
    ctl.run_ahead();
    ctl.tick();
    assert_eq!(ctl.distance_to_go(), held);
    ctl.cycle_start();
    until_line(&mut ctl, 7);
    ctl.run_ahead();
    let sp = ctl.tick();
    let d = ctl.distance_to_go();
    assert!(
        (d.x - (50.0 - sp.x)).abs() < 1e-9 && d.x > 0.0,
        "{d:?} at X{}",
        sp.x
    );
    assert!(d.z.abs() < 1e-9, "{d:?}");
    while ctl.state() != RunState::Ended {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.distance_to_go(), none);
}

/// In polar interpolation the distance is in the joints: the line of
/// line 4 ends at plane point (10, 10), X = 2·√(10² + 10²) = 28.2843 on
/// the diameter, Z staying at -2.
#[test]
fn in_polar_interpolation_the_distance_to_go_is_the_joints() {
    let src = "G98\nG00 X40 Z-2 C0\nG12.1\nG01 X20 C10 F300\nG01 X40 C0\nG13.1\nM30\n";
    let mut machine = Machine::reference();
    machine.axes.c.enabled = true;
    let mut ctl = Controller::new(module(src, &machine), machine, runtime::AutoAck).expect("loads");
    ctl.cycle_start();
    until_line(&mut ctl, 4);
    let end_x = 2.0 * 200f64.sqrt();
    for _ in 0..100 {
        ctl.run_ahead();
        let sp = ctl.tick();
        let d = ctl.distance_to_go();
        assert!((d.x - (end_x - sp.x)).abs() < 1e-9, "{d:?} at X{}", sp.x);
        assert!(d.z.abs() < 1e-12, "{d:?}");
    }
}
