//! `#3003` and `#3004`: the program's own switches over the operator's
//! controls (dialect.md §7, "runtime only"), which the runtime reads as
//! each block's commands leave the kernel.

mod common;

use common::run_with;
use nc::Machine;
use runtime::command::PauseKind;
use runtime::RunState;

/// The top path speed (mm/min) of the periods that run source line `line`.
fn top_feed_of(r: &common::Run, line: u32) -> f64 {
    let feeds = r.pts.iter().filter(|p| p.line == line).map(|p| p.feed);
    feeds.fold(0.0, f64::max)
}

#[test]
fn bit_1_of_3004_runs_feeds_at_their_f_whatever_the_override() {
    // The override knob at 50 %: F1000 runs at 500 mm/min, F2000 under
    // #3004 = 2 at 2000, and the F2000 after #3004 = 0 at 1000 again.
    // Each move is 50 mm: 2000 mm/min (33.3 mm/s) is reached in
    // 33.3² / (2·2000) = 0.28 mm on the reference machine's Z.
    let src = "O0001\nG98 G01 W-50 F1000\n#3004=2\nG01 W-50 F2000\n#3004=0\nG01 W-50\nM30\n";
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.feed_override_pct = 50.0,
        |_, _| {},
        60.0,
    );
    assert_eq!(r.state, RunState::Ended);
    let tops = [2, 4, 6].map(|l| top_feed_of(&r, l));
    for (top, want) in tops.iter().zip([500.0, 2000.0, 1000.0]) {
        assert!((top - want).abs() < 1e-6, "{tops:?}");
    }
}

/// Periods in which the axes stand between the first and the last period
/// that moves.
fn standing_inside(r: &common::Run) -> usize {
    let moving: Vec<usize> = (r.pts.iter().enumerate())
        .filter(|(_, p)| p.feed > 0.0)
        .map(|(i, _)| i)
        .collect();
    let (Some(&first), Some(&last)) = (moving.first(), moving.last()) else {
        return 0;
    };
    (first..last).filter(|&i| r.pts[i].feed == 0.0).count()
}

#[test]
fn bit_2_of_3004_lets_g61_blend_the_corner() {
    // A square corner in G61 stops (at least one standing period); with
    // #3004 = 4 the two feeds blend, as in G64, and never stand between.
    let corner = "G61 G98 G01 U-20 F2000\nW-20\nM30\n";
    let run = |src: &str| {
        let r = run_with(
            src,
            Machine::reference(),
            runtime::AutoAck,
            |_| {},
            |_, _| {},
            60.0,
        );
        assert_eq!(r.state, RunState::Ended);
        standing_inside(&r)
    };
    assert!(run(&format!("O0001\n{corner}")) >= 1);
    assert_eq!(run(&format!("O0001\n#3004=4\n{corner}")), 0);
}

/// Runs `src` pressing feed hold once 0.1 s in, then cycle start when the
/// motion holds: the end state, and the Z where it held.
fn held_at(src: &str) -> (RunState, f64) {
    let mut held_at = None;
    let mut pressed = false;
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |c, sp| {
            if !pressed && sp.time_s >= 0.1 {
                c.feed_hold();
                pressed = true;
            }
            if c.state() == RunState::Held && held_at.is_none() {
                held_at = Some(sp.z);
                c.cycle_start();
            }
        },
        60.0,
    );
    (r.state, held_at.expect("the hold took effect"))
}

#[test]
fn bit_0_of_3004_lets_the_block_finish_through_a_feed_hold() {
    // Feed hold is pressed 0.1 s into line 3, which runs under #3004 = 1:
    // it runs to its end (W-20 from Z0: Z-20) and the motion brakes as
    // line 5 starts, the first block without the bit: from 1000 mm/min
    // (16.67 mm/s) at Z's 2000 mm/s², v²/2a = 0.069 mm past Z-20. Cycle
    // start resumes it.
    let src = "O0001\n#3004=1\nG98 G01 W-20 F1000\n#3004=0\nG01 W-20\nM30\n";
    let (state, z) = held_at(src);
    assert_eq!(state, RunState::Ended);
    assert!(z <= -20.0 && z > -20.07, "held at Z{z}");
    // Without the bit the same press stops line 3 on its way: at 0.1 s
    // the tool is about 1.6 mm along (1000 mm/min = 16.7 mm/s).
    let (_, z) = held_at(&src.replace("#3004=1", "#3004=0"));
    assert!(z > -5.0 && z < -1.0, "held at Z{z}");
}

#[test]
fn bit_0_of_3003_runs_single_block_through_its_blocks() {
    // Single block on: each of the four moves stops at its end, except
    // the two under #3003 = 1.
    let src = "O0001\n#3003=1\nG00 W-1\nG00 W-1\n#3003=0\nG00 W-1\nG00 W-1\nM30\n";
    let mut stops = Vec::new();
    let r = run_with(
        src,
        Machine::reference(),
        runtime::AutoAck,
        |c| c.single_block = true,
        |c, sp| {
            if c.state() == RunState::Stopped(PauseKind::SingleBlock) {
                stops.push(sp.line);
            }
        },
        60.0,
    );
    assert_eq!(r.state, RunState::Ended);
    assert_eq!(stops, [6, 7]);
}

/// A host whose coolant (M08) never reports its completion (FIN).
struct CoolantNeverDone;

impl runtime::Plc for CoolantNeverDone {
    fn request(&mut self, _: runtime::plc::PlcFunction) {}
    fn done(&mut self, f: runtime::plc::PlcFunction) -> bool {
        f != runtime::plc::PlcFunction::M(8)
    }
}

/// The run state after `periods` periods of `src` on that host.
fn state_after(src: &str, periods: usize) -> RunState {
    let machine = Machine::reference();
    let m = common::module(src, &machine);
    let mut ctl = runtime::Controller::new(m, machine, CoolantNeverDone).expect("loads");
    ctl.cycle_start();
    for _ in 0..periods {
        ctl.run_ahead();
        ctl.tick();
        if ctl.state() == RunState::Ended {
            break;
        }
    }
    ctl.state()
}

#[test]
fn bit_1_of_3003_goes_on_without_the_fin() {
    // G00 W-1 takes well under a second (100 mm/s rapid on Z): with
    // #3003 = 2 the M08 is requested and the run ends within 10 s; without
    // it the run waits at the M08 for a FIN that never comes.
    let src = "M08\nG00 W-1\nM30\n";
    let ended = state_after(&format!("O0001\n#3003=2\n{src}"), 10_000);
    assert_eq!(ended, RunState::Ended);
    assert_ne!(
        state_after(&format!("O0001\n{src}"), 10_000),
        RunState::Ended
    );
}
