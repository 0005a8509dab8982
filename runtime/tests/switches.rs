//! The operator's live switches through the embedding API: optional stop,
//! dry run and the spindle override.

mod common;

use common::{module, run_with};
use nc::Machine;
use runtime::command::PauseKind;
use runtime::{Config, Controller, RunState};

const M01: &str = "O0001\nG00 W-1\nM01\nG00 W-1\nM30\n";

/// Runs `src` pressing cycle start at every stop; returns the stops seen.
fn stops(
    machine: Machine,
    setup: impl FnOnce(&mut Controller),
    mid: Option<bool>,
) -> Vec<PauseKind> {
    let m = module(M01, &machine);
    let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
    setup(&mut ctl);
    ctl.cycle_start();
    let mut seen = Vec::new();
    for i in 0..100_000 {
        ctl.run_ahead();
        ctl.tick();
        if i == 2 {
            // Flipped while the first move runs: the VM has long passed
            // the M01, the motion has not.
            if let Some(on) = mid {
                ctl.set_optional_stop(on);
            }
        }
        match ctl.state() {
            RunState::Stopped(k) => {
                seen.push(k);
                ctl.cycle_start();
            }
            RunState::Ended => return seen,
            s => assert!(!matches!(s, RunState::Alarm(_)), "{s:?}"),
        }
    }
    panic!("did not end");
}

#[test]
fn optional_stop_is_read_when_the_motion_reaches_the_m01() {
    let r = Machine::reference;
    // Machine file default (on), untouched: the M01 stops.
    assert_eq!(stops(r(), |_| {}, None), vec![PauseKind::M01]);
    // Turned off before the start, and off while the first move runs.
    assert_eq!(stops(r(), |c| c.set_optional_stop(false), None), vec![]);
    assert_eq!(
        stops(r(), |c| c.set_optional_stop(true), Some(false)),
        vec![]
    );
    // A machine file that has it off, switched on live: it stops.
    let mut off = r();
    off.operator.optional_stop = false;
    assert_eq!(stops(off.clone(), |_| {}, None), vec![]);
    assert_eq!(
        stops(off, |c| c.set_optional_stop(false), Some(true)),
        vec![PauseKind::M01]
    );
}

/// The top path speed of a run (mm/min): `power_on` sets the panel
/// before the run, `live` is called once, after the first period (the
/// program has been run ahead and its moves planned by then).
fn top_feed(
    src: &str,
    power_on: impl FnOnce(&mut Config),
    live: impl Fn(&mut Controller) + Copy,
) -> (f64, RunState) {
    let mut first = true;
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        power_on,
        |c, _| {
            if first {
                live(c);
                first = false;
            }
        },
        60.0,
    );
    (r.pts.iter().map(|p| p.feed).fold(0.0, f64::max), r.state)
}

#[test]
fn dry_run_runs_feeds_at_the_dry_run_rate() {
    // 50 mm at F100 mm/min; the dry-run rate of the reference machine is
    // its path limit, feed.max_mm_min = 5000 mm/min (machine.md), which
    // 50 mm reach: accelerating to 83.3 mm/s at 2000 mm/s² takes
    // 83.3² / 4000 = 1.7 mm.
    let src = "O0001\nG98 G01 W-50 F100\nM30\n";
    let (plain, _) = top_feed(src, |_| {}, |_| {});
    assert!((plain - 100.0).abs() < 1e-6, "{plain}");
    let (dry, _) = top_feed(src, |c| c.dry_run = true, |_| {});
    assert!((dry - 5000.0).abs() < 1e-6, "{dry}");
    // The feed override scales the dry-run rate.
    let (half, _) = top_feed(src, |c| c.dry_run = true, |c| c.set_feed_override(50.0));
    assert!((half - 2500.0).abs() < 1e-6, "{half}");
    // Switched on while the move is already planned for F100: it speeds
    // up to what that plan allows, F × the top override 150 % = 150.
    let (late, _) = top_feed(src, |_| {}, |c| c.set_dry_run(true));
    assert!((late - 150.0).abs() < 1e-6, "{late}");
    // ... and a move planned after the switch runs at the full rate (the
    // read of the current position, #5042, holds the VM back until the
    // first move has ended).
    let two = "O0001\nG98 G01 W-1 F100\n#1 = #5042\nG01 W-50\nM30\n";
    let mut first = true;
    let r = run_with(
        two,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |c, _| {
            if first {
                c.set_dry_run(true);
                first = false;
            }
        },
        60.0,
    );
    let top = r.pts.iter().map(|p| p.feed).fold(0.0, f64::max);
    assert!((top - 5000.0).abs() < 1e-6, "{top}");
    // Feed per revolution with the spindle standing: in dry run it moves
    // at the dry-run rate instead of waiting (and alarming, E7003).
    let (g99, state) = top_feed(
        "O0001\nG99 G01 W-50 F0.1\nM30\n",
        |c| c.dry_run = true,
        |_| {},
    );
    assert_eq!(state, RunState::Ended);
    assert!((g99 - 5000.0).abs() < 1e-6, "{g99}");
}

#[test]
fn the_spindle_override_goes_through_the_controller() {
    // S1000 at 50 %: 500 rev/min once the spindle has run up.
    let src = "O0001\nM03 S1000\nG04 X2\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |c, _| c.set_spindle_override(50.0),
        60.0,
    );
    let last = r.pts.last().unwrap();
    assert!(
        (last.spindle_rpm - 500.0).abs() < 1e-9,
        "{}",
        last.spindle_rpm
    );
}

/// Every other block on the block-skip switch `/`.
const SKIPS: &str = "O0001\nG00 X10 Z0\n/G00 X12\nG00 X14\n/G00 X16\nG00 X18\n/G00 X20\nM30\n";

/// The canon lines of a tap.
fn lines(events: &[nc::Event]) -> Vec<String> {
    events.iter().map(|e| e.to_string()).collect()
}

#[test]
fn block_skip_is_read_when_the_block_is_read() {
    let machine = Machine::reference(); // every switch on
    let mut cfg = Config::from_machine(&machine);
    // A look-ahead of two moves: the first run-ahead reads up to the
    // second move and stops.
    cfg.lookahead_blocks = 2;
    cfg.lookahead_s = 0.0;
    let m = module(SKIPS, &machine);
    let mut ctl = Controller::with_config(m, machine, cfg, runtime::AutoAck).expect("loads");
    ctl.cycle_start();
    let mut read: Vec<nc::Event> = Vec::new();
    ctl.run_ahead_tap(&mut read);
    // Read with the switch on: X12 skipped.
    assert_eq!(lines(&read), ["RAPID X=10 Z=0", "RAPID X=14 Z=0"]);
    // Off now, before the axes have moved: the blocks read from here on
    // run, the X12 block read before stays skipped.
    ctl.set_block_skip(1, false);
    assert!(!ctl.block_skip(1) && ctl.block_skip(2));
    let mut last = None;
    for _ in 0..1_000_000 {
        ctl.run_ahead_tap(&mut read);
        last = Some(ctl.tick());
        if matches!(ctl.state(), RunState::Ended | RunState::Alarm(_)) {
            break;
        }
    }
    assert_eq!(ctl.state(), RunState::Ended);
    assert_eq!(
        lines(&read),
        [
            "RAPID X=10 Z=0",
            "RAPID X=14 Z=0",
            "RAPID X=16 Z=0",
            "RAPID X=18 Z=0",
            "RAPID X=20 Z=0",
            "STOP KIND=M30"
        ]
    );
    // The motion ran what was read: it ends on X20 (a diameter).
    assert_eq!(last.map(|sp| sp.x), Some(20.0));
}

#[test]
fn the_machine_file_sets_block_skip_at_load_and_a_reset_keeps_it() {
    let mut machine = Machine::reference();
    *machine.operator.block_skip = [false; 9];
    let m = module(SKIPS, &machine);
    let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
    assert!(!ctl.block_skip(1));
    // Turned on, the program runs; a reset brings it back to its start
    // and the switch stays on for the second run.
    ctl.set_block_skip(1, true);
    let mut runs = Vec::new();
    for _ in 0..2 {
        ctl.cycle_start();
        let mut read: Vec<nc::Event> = Vec::new();
        for _ in 0..1_000_000 {
            ctl.run_ahead_tap(&mut read);
            ctl.tick();
            if ctl.state() == RunState::Ended {
                break;
            }
        }
        runs.push(lines(&read));
        ctl.reset();
        for _ in 0..100_000 {
            ctl.run_ahead();
            ctl.tick();
            if ctl.state() == RunState::Idle {
                break;
            }
        }
    }
    let want = [
        "RAPID X=10 Z=0",
        "RAPID X=14 Z=0",
        "RAPID X=18 Z=0",
        "STOP KIND=M30",
    ];
    assert_eq!(runs, [want, want]);
}

/// A `#3006` message stop is the statement's own: the set points while
/// it stands name its line, not the next block's, and so does the
/// listing's tag, with a move waiting for its corner before it or not.
#[test]
fn a_message_stop_names_its_own_line() {
    for (src, line) in [
        ("O0001\nG00 W-1\n#3006=1 (CHECK)\nG00 W-1\nM30\n", 3),
        (
            "O0001\nG01 U-2 W-1 F100 ,C0.5\n#3006=2 (CHECK)\nG01 W-3\nM30\n",
            3,
        ),
    ] {
        let machine = Machine::reference();
        let m = module(src, &machine);
        let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
        ctl.cycle_start();
        let mut stood = None;
        for _ in 0..100_000 {
            ctl.run_ahead();
            let p = ctl.tick();
            match ctl.state() {
                RunState::Stopped(PauseKind::Message { .. }) => {
                    stood = Some(p.line);
                    ctl.cycle_start();
                }
                RunState::Stopped(_) => ctl.cycle_start(),
                RunState::Ended => break,
                s => assert!(!matches!(s, RunState::Alarm(_)), "{s:?}"),
            }
        }
        assert_eq!(stood, Some(line), "{src}");
    }
}
