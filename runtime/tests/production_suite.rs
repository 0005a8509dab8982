//! Every conformance program made twice in a row: on a machine whose M30
//! rewinds, cycle start alone after the first part must make the second
//! part period for period as a reset and cycle start do on one whose M30
//! does not, and both must leave the same counters. (A program ending
//! with M02, past its last block or in an alarm is not rewound.)

mod common;

use common::module;
use nc::Machine;
use runtime::{Controller, Counters, Motion, RunState};
use std::path::{Path, PathBuf};

/// What a period shows of the path, not its time (a rewind's reset
/// shifts it by a period): x, z, axis_x, axis_z, feed, line, motion, tool.
type Period = (f64, f64, f64, f64, f64, u32, Motion, u32);

const MAX_TICKS: usize = 3_000_000;

fn conformance() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/conformance");
    dir.is_dir().then_some(dir)
}

fn machine_of(path: &Path, rewinds: bool) -> Machine {
    let mut m = match std::fs::read_to_string(path.with_extension("toml")) {
        Ok(text) => Machine::from_toml(&text).expect("the case's machine file"),
        Err(_) => Machine::reference(),
    };
    m.run.m30_rewinds = rewinds;
    m
}

/// Ticks until the program has ended (`Some`) or an alarm (`None`),
/// recording the periods from the first motion on when `rec` is given.
fn to_end(ctl: &mut Controller, mut rec: Option<&mut Vec<Period>>) -> Option<()> {
    for _ in 0..MAX_TICKS {
        ctl.run_ahead();
        let sp = ctl.tick();
        if let Some(r) = rec.as_deref_mut() {
            if sp.motion != Motion::None || !r.is_empty() {
                let p = (
                    sp.x, sp.z, sp.axis_x, sp.axis_z, sp.feed, sp.line, sp.motion, sp.tool,
                );
                r.push(p);
            }
        }
        match ctl.state() {
            RunState::Ended => {
                ctl.run_ahead();
                return Some(());
            }
            RunState::Alarm(_) => return None,
            RunState::Stopped(_) => ctl.cycle_start(),
            _ => {}
        }
    }
    panic!("not done in {MAX_TICKS} periods");
}

/// The second part's periods and the counters after it, or `None` when
/// the first part does not end in a rewind (or in an alarm).
fn two_parts(path: &Path, rewinds: bool) -> Option<(Vec<Period>, Counters)> {
    let machine = machine_of(path, rewinds);
    let src = std::fs::read_to_string(path).expect("readable");
    let mut ctl = Controller::new(module(&src, &machine), machine, runtime::AutoAck).ok()?;
    ctl.cycle_start();
    to_end(&mut ctl, None)?;
    if rewinds {
        // Cycle start alone: a reset in the next period, then the part.
        ctl.cycle_start();
        ctl.run_ahead();
        ctl.tick();
        if ctl.state() == RunState::Ended {
            // M02, or the end of the blocks: no rewind.
            return None;
        }
    } else {
        ctl.reset();
        while ctl.state() != RunState::Idle {
            ctl.run_ahead();
            ctl.tick();
        }
        ctl.cycle_start();
    }
    let mut periods = Vec::new();
    to_end(&mut ctl, Some(&mut periods))?;
    Some((periods, ctl.counters().clone()))
}

#[test]
fn every_rewound_second_part_is_a_reset_and_cycle_start() {
    let Some(dir) = conformance() else {
        println!("skipping: the conformance suite is not beside the project");
        return;
    };
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("readable")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .filter(|p| !p.with_extension("err").exists())
        .collect();
    names.sort();
    let mut rewound = 0;
    for path in &names {
        let Some((parts, counters)) = two_parts(path, true) else {
            continue;
        };
        let (again, again_counters) =
            two_parts(path, false).unwrap_or_else(|| panic!("{}: no second part", path.display()));
        if let Some(k) = (0..parts.len().max(again.len())).find(|&k| parts.get(k) != again.get(k)) {
            panic!(
                "{}: period {k} of {} / {}: {:?} against {:?}",
                path.display(),
                parts.len(),
                again.len(),
                parts.get(k),
                again.get(k)
            );
        }
        assert_eq!(counters, again_counters, "{}", path.display());
        assert!(counters.parts.machined >= 2.0, "{}", path.display());
        rewound += 1;
    }
    println!("{rewound} of {} programs rewound", names.len());
    // Most cases end with M30 (counted when the suite was written: 60
    // and more of them).
    assert!(rewound >= 60, "{rewound} of {} rewound", names.len());
}
