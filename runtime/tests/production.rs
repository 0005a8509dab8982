//! Production runs: the part counter and tool life carry from part to
//! part, a run that does not finish counts nothing, and on a machine
//! whose M30 rewinds, cycle start after it runs the next part. The
//! expected counts are counted by hand from the programs.

mod common;

use common::{module, reset_to_idle};
use nc::Machine;
use runtime::{Controller, Motion, Parts, RestartAt, RunState, SetPoint, Target};

/// Group 1: two tools, each good for two uses.
const LIFE: &str =
    "[[tool_life.group]]\nnumber = 1\nlife = 2\nunit = \"count\"\ntools = [101, 202]\n";

/// A part: the counter read at its start, a tool of group 1, one cut.
const PART: &str = "#100=#3901\nT0199\nG00 X40 Z2\nG01 Z-20 F300\nG00 X60 Z2\nM30\n";

fn machine(rewinds: bool) -> Machine {
    let text = format!("[run]\nm30_rewinds = {rewinds}\n{LIFE}");
    Machine::from_toml(&text).expect("a machine file")
}

fn controller(src: &str, rewinds: bool) -> Controller {
    let m = machine(rewinds);
    Controller::new(module(src, &m), m, runtime::AutoAck).expect("loads")
}

/// Cycle start, then every period until the program has ended (after
/// running, not the end it stood at); the run-ahead then sees the end.
fn part(ctl: &mut Controller) -> SetPoint {
    ctl.cycle_start();
    let mut left_end = false;
    for _ in 0..400_000 {
        ctl.run_ahead();
        let sp = ctl.tick();
        match ctl.state() {
            RunState::Ended if left_end => {
                ctl.run_ahead();
                return sp;
            }
            RunState::Ended => {}
            RunState::Alarm(a) => panic!("alarm {a}"),
            _ => left_end = true,
        }
    }
    panic!("not done: {:?}", ctl.state());
}

fn used(ctl: &Controller) -> Vec<f64> {
    ctl.counters().life[0].used.clone()
}

fn parts(machined: f64, required: f64) -> Parts {
    Parts { machined, required }
}

#[test]
fn cycle_start_after_m30_runs_the_next_part_and_counts_it() {
    let mut ctl = controller(PART, true);
    assert_eq!(ctl.counters().parts, parts(0.0, 0.0));
    let sp = part(&mut ctl);
    assert_eq!((sp.x, sp.z, sp.tool), (60.0, 2.0, 1));
    assert_eq!(ctl.counters().parts.machined, 1.0);
    assert_eq!(used(&ctl), [1.0, 0.0]);
    // No reset: the second part starts where the first ended.
    part(&mut ctl);
    assert_eq!(ctl.vm().variable(100), Ok(1.0));
    assert_eq!(ctl.counters().parts.machined, 2.0);
    assert_eq!(used(&ctl), [2.0, 0.0]);
    // Tool 1 has had its two uses: the third part takes tool 2.
    let sp = part(&mut ctl);
    assert_eq!(sp.tool, 2);
    assert_eq!(ctl.vm().variable(100), Ok(2.0));
    assert_eq!(ctl.counters().parts.machined, 3.0);
    assert_eq!(used(&ctl), [2.0, 1.0]);
    assert_eq!(ctl.counters().life[0].current, Some(1));
}

#[test]
fn without_the_key_the_ended_program_waits_for_a_reset() {
    let mut ctl = controller(PART, false);
    part(&mut ctl);
    ctl.cycle_start();
    for _ in 0..100 {
        ctl.run_ahead();
        ctl.tick();
        assert_eq!(ctl.state(), RunState::Ended);
    }
    assert_eq!(ctl.counters().parts.machined, 1.0);
    reset_to_idle(&mut ctl);
    part(&mut ctl);
    assert_eq!(ctl.vm().variable(100), Ok(1.0));
    assert_eq!(ctl.counters().parts.machined, 2.0);
    assert_eq!(used(&ctl), [2.0, 0.0]);
}

#[test]
fn m02_does_not_rewind() {
    let mut ctl = controller("G00 X40 Z2\nM02\n", true);
    part(&mut ctl);
    ctl.cycle_start();
    for _ in 0..100 {
        ctl.run_ahead();
        ctl.tick();
        assert_eq!(ctl.state(), RunState::Ended);
    }
    assert_eq!(ctl.counters().parts.machined, 0.0);
}

/// Ticks until the X axis has left X0 (the program is under way and the
/// VM has read it to its M30 long before).
fn into_the_run(ctl: &mut Controller) {
    ctl.cycle_start();
    for _ in 0..400_000 {
        ctl.run_ahead();
        let sp = ctl.tick();
        if sp.x > 10.0 {
            return;
        }
    }
    panic!("never moved");
}

#[test]
fn a_run_abandoned_by_a_reset_counts_nothing() {
    let mut ctl = controller(PART, true);
    into_the_run(&mut ctl);
    // The VM has counted T0199 and M30 already; the part is not made.
    assert_eq!(ctl.vm().variable(3901), Ok(1.0));
    reset_to_idle(&mut ctl);
    ctl.run_ahead();
    assert_eq!(ctl.counters().parts.machined, 0.0);
    assert_eq!(used(&ctl), [0.0, 0.0]);
}

#[test]
fn a_restarted_part_counts_once() {
    let mut ctl = controller(PART, true);
    into_the_run(&mut ctl);
    reset_to_idle(&mut ctl);
    // The insert broke in the cut: restart at it (line 4). The search
    // passes T0199 once more; the abandoned run counted nothing.
    let at = RestartAt {
        target: Target::Line(4),
        pass: 1,
    };
    assert!(ctl.restart_from(at).is_ok());
    part(&mut ctl);
    assert_eq!(ctl.counters().parts.machined, 1.0);
    assert_eq!(used(&ctl), [1.0, 0.0]);
}

#[test]
fn the_operator_sets_the_counters_and_the_required_count_is_reached() {
    let mut ctl = controller(PART, true);
    assert_eq!(ctl.set_parts(parts(10.0, 12.0)), Ok(()));
    part(&mut ctl);
    assert_eq!(ctl.vm().variable(100), Ok(10.0));
    assert_eq!(ctl.counters().parts, parts(11.0, 12.0));
    assert!(!ctl.counters().parts.reached());
    part(&mut ctl);
    assert!(ctl.counters().parts.reached());
    // Bad values change nothing.
    for bad in [parts(1.5, 0.0), parts(-1.0, 0.0), parts(0.0, f64::NAN)] {
        assert!(ctl.set_parts(bad).is_err());
    }
    assert_eq!(ctl.counters().parts, parts(12.0, 12.0));
    // New inserts in group 1; there is no group 9.
    assert_eq!(used(&ctl), [2.0, 0.0]);
    assert_eq!(ctl.renew_tool_life(1), Ok(()));
    assert!(ctl.renew_tool_life(9).is_err());
    let sp = part(&mut ctl);
    assert_eq!(sp.tool, 1);
    assert_eq!(used(&ctl), [1.0, 0.0]);
}

#[test]
fn an_edit_while_running_keeps_the_runs_count() {
    let mut ctl = controller(PART, true);
    into_the_run(&mut ctl);
    assert_eq!(ctl.set_parts(parts(0.0, 5.0)), Ok(()));
    // Edits while running are for the counters, not the running VM.
    assert_eq!(ctl.vm().variable(3902), Ok(0.0));
    part(&mut ctl);
    // The run's M30 counts on the operator's 0.
    assert_eq!(ctl.counters().parts, parts(1.0, 5.0));
}

#[test]
fn a_table_written_by_the_program_lasts_for_its_run() {
    // G10 L3 replaces the table for this run (machine.md): its uses are
    // not the machine file's groups'. The part still counts.
    let src = "G10 L3\nP1 L5 Q1\nT0303\nG11\nT0199\nG00 X40 Z2\nM30\n";
    let mut ctl = controller(src, true);
    let sp = part(&mut ctl);
    assert_eq!(sp.tool, 3);
    assert_eq!(ctl.counters().parts.machined, 1.0);
    assert_eq!(used(&ctl), [0.0, 0.0]);
}

#[test]
fn a_split_controller_counts_and_rewinds_too() {
    let (mut interp, mut rt) = controller(PART, true).split();
    let mut ends = 0;
    rt.cycle_start();
    for _ in 0..400_000 {
        interp.run_ahead();
        rt.tick();
        if rt.state() == RunState::Ended {
            ends += 1;
            if ends == 3 {
                break;
            }
            rt.cycle_start();
            // Out of Ended: the rewind's reset, then the part.
            while rt.state() == RunState::Ended {
                interp.run_ahead();
                rt.tick();
            }
        }
    }
    assert_eq!(ends, 3);
    interp.run_ahead();
    assert_eq!(interp.counters().parts.machined, 3.0);
    assert_eq!(interp.counters().life[0].used, [2.0, 1.0]);
}

#[test]
fn counters_kept_over_a_power_off_are_restored() {
    let mut ctl = controller(PART, true);
    let mut kept = ctl.counters().clone();
    kept.parts = parts(7.0, 0.0);
    kept.life[0].used = vec![2.0, 0.0];
    // Counters that do not fit this machine change nothing.
    let mut other = kept.clone();
    other.life[0].tools[1] = 303;
    assert!(ctl.restore_counters(other).is_err());
    let mut negative = kept.clone();
    negative.life[0].used[1] = -1.0;
    assert!(ctl.restore_counters(negative).is_err());
    assert_eq!(ctl.counters().parts.machined, 0.0);
    assert_eq!(ctl.restore_counters(kept), Ok(()));
    // Tool 1 is worn out: the part takes tool 2 and counts the eighth.
    let sp = part(&mut ctl);
    assert_eq!(sp.tool, 2);
    assert_eq!(ctl.vm().variable(100), Ok(7.0));
    assert_eq!(ctl.counters().parts.machined, 8.0);
    assert_eq!(used(&ctl), [2.0, 1.0]);
}

/// What a period shows of the path: x, z, axis_x, axis_z, feed, line,
/// motion, tool (not the time, which a rewind's reset shifts by a period).
type Period = (f64, f64, f64, f64, f64, u32, Motion, u32);

/// The periods of the second part, from its first motion on, on a
/// machine whose M30 rewinds (cycle start alone) and on one whose does
/// not (reset, then cycle start).
fn second_part(rewinds: bool) -> Vec<Period> {
    let mut ctl = controller(common::SHAFT, rewinds);
    part(&mut ctl);
    if !rewinds {
        reset_to_idle(&mut ctl);
    }
    ctl.cycle_start();
    let mut periods = Vec::new();
    for _ in 0..400_000 {
        ctl.run_ahead();
        let sp = ctl.tick();
        if sp.motion != Motion::None || !periods.is_empty() {
            periods.push((
                sp.x, sp.z, sp.axis_x, sp.axis_z, sp.feed, sp.line, sp.motion, sp.tool,
            ));
        }
        if ctl.state() == RunState::Ended && !periods.is_empty() {
            return periods;
        }
    }
    panic!("not done: {:?}", ctl.state());
}

#[test]
fn a_rewind_runs_the_part_as_reset_and_cycle_start_do() {
    let rewound = second_part(true);
    assert!(rewound.len() > 1000, "{}", rewound.len());
    assert_eq!(rewound, second_part(false));
}

#[test]
fn a_minutes_group_adds_up_its_cutting_time_over_parts() {
    // One cut of 22 mm (Z2 to Z-20) at 300 mm/min a part: 22/300 min.
    let text = "[run]\nm30_rewinds = true\n[[tool_life.group]]\nnumber = 1\nlife = 10\nunit = \"minutes\"\ntools = [101]\n";
    let m = Machine::from_toml(text).expect("a machine file");
    let mut ctl = Controller::new(module(PART, &m), m, runtime::AutoAck).expect("loads");
    part(&mut ctl);
    part(&mut ctl);
    let minutes = used(&ctl)[0];
    assert!((minutes - 2.0 * 22.0 / 300.0).abs() < 1e-9, "{minutes}");
}
