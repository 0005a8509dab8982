//! Program restart through the controller: the search runs while idle,
//! and cycle start then gives the restored state, the approach from where
//! the axes stand (X first, then Z) and the program from the block on.

mod common;

use common::{check_limits, module, Run};
use nc::Machine;
use runtime::{
    ActiveCodes, Config, Controller, JogRate, Manual, ManualAxis, RestartAt, RestartError,
    RestartRefused, Restarted, RunState, SetPoint, Target,
};

const TWO_TOOLS: &str = "\
G00 X200 Z100
T0101
G97 S1000 M03
G00 X52 Z2
G99 G01 Z-30 F0.2
G00 X60 Z2
T0202
S800 M04
G00 X40 Z2
N100 G01 Z-20 F0.1
X50
G00 X200 Z100
M30
";

const N100: RestartAt = RestartAt {
    target: Target::Seq(100),
    pass: 1,
};

fn controller() -> Controller {
    let machine = Machine::reference();
    let m = module(TWO_TOOLS, &machine);
    let mut ctl = Controller::new(m, machine, runtime::AutoAck).expect("loads");
    // (The queue filled from the start, as a host does before cycle
    // start: the restart replaces it.)
    ctl.run_ahead();
    ctl
}

/// By hand, the codes in force at N100, before it runs: G00 from the
/// block before, G97 from line 3, G99 and F0.2 from line 5, S800 and
/// T0202 from lines 7 and 8; the rest power-on (dialect.md §3).
fn at_n100() -> ActiveCodes {
    ActiveCodes {
        g: [
            0, 970, 990, 210, 400, 230, 800, 670, 540, 640, 180, 150, 131,
        ],
        f: 0.2,
        s: 800.0,
        t: 202,
    }
}

/// Cycle start, then every period to the end (at most 120 simulated s).
fn run_to_end(ctl: &mut Controller, pts: &mut Vec<SetPoint>) {
    ctl.cycle_start();
    loop {
        ctl.run_ahead();
        let sp = ctl.tick();
        pts.push(sp);
        match ctl.state() {
            RunState::Ended => return,
            RunState::Stopped(_) => ctl.cycle_start(),
            RunState::Alarm(a) => panic!("alarm {a}"),
            _ => {}
        }
        assert!(sp.time_s < 120.0, "not done: {:?}", ctl.state());
    }
}

fn checked(pts: Vec<SetPoint>) {
    let machine = Machine::reference();
    let run = Run {
        pts,
        canon: Vec::new(),
        state: RunState::Ended,
        alarm: None,
        cfg: Config::from_machine(&machine),
    };
    check_limits(&run, false);
}

#[test]
fn a_restart_runs_the_second_tool_s_cut_from_where_the_axes_stand() {
    let mut ctl = controller();
    let mut pts = Vec::new();
    // The operator has jogged Z to -10 from the power-on point X0 Z0
    // (work and machine coordinates are one on the reference machine).
    let step = Manual::Step {
        axis: ManualAxis::Z,
        distance: -10.0,
        rate: JogRate::Rapid,
    };
    assert_eq!(ctl.manual(step), Ok(()));
    while ctl.state() != RunState::Idle {
        ctl.run_ahead();
        pts.push(ctl.tick());
    }
    let manual = pts.len();
    // N100 starts where the block before left the tool: X40 Z2.
    let to_n100 = Restarted {
        m_codes: Vec::new(),
        destination: runtime::Xz { x: 40.0, z: 2.0 },
        codes: at_n100(),
    };
    assert_eq!(ctl.restart_from(N100), Ok(to_n100));
    run_to_end(&mut ctl, &mut pts);
    let run = &pts[manual..];
    // X first, at Z-10, from X0 to 40; then Z.
    let first_z = run.iter().position(|p| p.z != -10.0).expect("Z moves");
    assert!(first_z > 0 && run[..first_z].iter().all(|p| p.z == -10.0));
    assert!(
        (run[first_z - 1].x - 40.0).abs() < 1e-6,
        "{:?}",
        run[first_z - 1]
    );
    // The second tool cuts with the spindle reversed at 800 rpm; the
    // first tool's cut to Z-30 is not run again.
    assert!(run.iter().all(|p| p.tool == 2));
    assert!(run.iter().all(|p| p.z >= -20.0 - 1e-9));
    assert!(run.iter().any(|p| (p.spindle_rpm + 800.0).abs() < 1e-6));
    assert!(run.iter().all(|p| p.spindle_rpm <= 0.0));
    let cut = run.iter().filter(|p| (p.z + 20.0).abs() < 1e-9);
    assert!(cut.clone().any(|p| (p.x - 50.0).abs() < 1e-9));
    let end = pts.last().expect("periods");
    assert_eq!((end.x, end.z), (200.0, 100.0));
    checked(pts);
}

#[test]
fn a_restart_is_refused_while_a_program_runs() {
    let mut ctl = controller();
    ctl.cycle_start();
    for _ in 0..10 {
        ctl.run_ahead();
        ctl.tick();
    }
    assert_eq!(ctl.restart_from(N100), Err(RestartRefused::NotIdle));
    // Nothing changed: the program runs its first cut.
    let mut pts = Vec::new();
    run_to_end(&mut ctl, &mut pts);
    assert!(pts.iter().any(|p| p.z == -30.0));
}

#[test]
fn a_refused_restart_leaves_the_program_at_its_start() {
    let mut ctl = controller();
    let at = RestartAt {
        target: Target::Seq(999),
        pass: 1,
    };
    let refused = Err(RestartRefused::Search(RestartError::NoBlock(at.target)));
    assert_eq!(ctl.restart_from(at), refused);
    let twice = RestartAt { pass: 2, ..N100 };
    assert!(matches!(
        ctl.restart_from(twice),
        Err(RestartRefused::Search(RestartError::NotReached {
            reached: 1,
            ..
        }))
    ));
    let mut pts = Vec::new();
    run_to_end(&mut ctl, &mut pts);
    // The whole program: the first tool's cut reaches X52 Z-30.
    assert!(pts
        .iter()
        .any(|p| (p.x, p.z) == (52.0, -30.0) && p.tool == 1));
    assert!(pts
        .iter()
        .any(|p| (p.x, p.z) == (50.0, -20.0) && p.tool == 2));
    checked(pts);
}

/// A loop whose round starts by reading the position (which waits for the
/// motion, `Status::Sync`): the controller's restart at the second round
/// prints the canon the VM's own restart prints, the round of #1 = 1
/// (X38), not the first.
#[test]
fn a_restart_in_the_controller_prints_the_vm_s_canon() {
    let src = "\
G00 X50 Z2
#1=0
WHILE[#1LT3]DO1
#2=#5041
G01 X[40-#1*2] Z-10 F500
#1=#1+1
END1
M30
";
    let machine = Machine::reference();
    let at: RestartAt = "4@2".parse().expect("a restart point");
    let mut vm = vm::Vm::new(module(src, &machine), machine.clone());
    let mut expected = Vec::new();
    vm::restart::search(&mut vm, at, &mut expected).expect("restarts");
    vm.run(&mut expected);
    let lines: Vec<String> = expected.iter().map(ToString::to_string).collect();
    assert_eq!(
        lines[..4],
        [
            "FEED F=500 MODE=MIN",
            "RAPID X=40 Z=0",
            "RAPID X=40 Z=-10",
            "LINE X=38 Z=-10"
        ]
    );
    let mut ctl = Controller::new(module(src, &machine), machine, runtime::AutoAck).expect("loads");
    let mut canon: Vec<nc::Event> = Vec::new();
    // The second round starts where the first ended: X40 Z-10.
    // The first round left G01 and F500; the rest is power-on.
    let round = Restarted {
        m_codes: Vec::new(),
        destination: runtime::Xz { x: 40.0, z: -10.0 },
        codes: ActiveCodes {
            g: [
                10, 970, 980, 210, 400, 230, 800, 670, 540, 640, 180, 150, 131,
            ],
            f: 500.0,
            s: 0.0,
            t: 0,
        },
    };
    assert_eq!(ctl.restart_from_tap(at, &mut canon), Ok(round));
    ctl.cycle_start();
    for _ in 0..200_000 {
        ctl.run_ahead_tap(&mut canon);
        ctl.tick();
        if ctl.state() == RunState::Ended {
            break;
        }
    }
    assert_eq!(ctl.state(), RunState::Ended);
    assert_eq!(canon, expected);
}

/// A split controller, both halves driven from this thread: the
/// interpreter's restart waits for the real-time half's reset, then the
/// run prints the VM's canon of the restart. A refused one leaves the
/// program at its start.
#[test]
fn a_split_controller_restarts_at_its_reset() {
    let machine = Machine::reference();
    let m = module(TWO_TOOLS, &machine);
    let mut vm = vm::Vm::new(m.clone(), machine.clone());
    let mut expected = Vec::new();
    vm::restart::search(&mut vm, N100, &mut expected).expect("restarts");
    vm.run(&mut expected);
    for (at, restarted) in [(N100, true), (RestartAt { pass: 3, ..N100 }, false)] {
        let ctl = Controller::new(m.clone(), machine.clone(), runtime::AutoAck).expect("loads");
        let (mut interp, mut rt) = ctl.split();
        let mut canon: Vec<nc::Event> = Vec::new();
        interp.run_ahead();
        interp.restart_from(at);
        assert_eq!(interp.take_restart_result(), None);
        rt.reset();
        let result = loop {
            rt.tick();
            interp.run_ahead_tap(&mut canon);
            if let Some(r) = interp.take_restart_result() {
                break r;
            }
        };
        assert_eq!(result.is_ok(), restarted, "{result:?}");
        rt.cycle_start();
        let mut pts = Vec::new();
        while rt.state() != RunState::Ended {
            interp.run_ahead_tap(&mut canon);
            pts.push(rt.tick());
            assert!(pts.len() < 200_000, "{:?}", rt.state());
        }
        if restarted {
            assert_eq!(canon, expected);
        } else {
            assert!(pts.iter().any(|p| (p.x, p.z) == (52.0, -30.0)));
        }
    }
}

/// A profile under G42 (tool 1: R 0.8, tip 3), restarted at its taper
/// (line 5): the controller prints the VM's canon of the restart, the
/// approach ends on the compensated point X20 Z-20.4686
/// (compiler/tests/restart.rs works it out), and the periods after it
/// name the lines the whole run's periods name from the taper on.
#[test]
fn a_restart_inside_compensation_runs_as_the_whole_run_from_the_compensated_point() {
    let src = "T0101\nG00 X50 Z2\nG42 G01 X20 Z0 F100\nZ-20\nX40 Z-30\nZ-40\nG40 G00 X60\nM30\n";
    let machine = Machine::from_toml("[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n")
        .expect("a machine");
    let at: RestartAt = "5".parse().expect("a restart point");
    let mut vm = vm::Vm::new(module(src, &machine), machine.clone());
    let mut expected = Vec::new();
    vm::restart::search(&mut vm, at, &mut expected).expect("restarts");
    vm.run(&mut expected);
    let lines = |pts: &[SetPoint]| {
        let mut l: Vec<u32> = pts.iter().map(|p| p.line).collect();
        l.dedup();
        l
    };
    let mut whole =
        Controller::new(module(src, &machine), machine.clone(), runtime::AutoAck).expect("loads");
    let mut whole_pts = Vec::new();
    run_to_end(&mut whole, &mut whole_pts);
    let mut ctl = Controller::new(module(src, &machine), machine, runtime::AutoAck).expect("loads");
    let mut canon: Vec<nc::Event> = Vec::new();
    let r = ctl.restart_from_tap(at, &mut canon).expect("restarts");
    let to = r.destination;
    assert!(
        (to.x - 20.0).abs() < 1e-12 && (to.z + 20.468_629).abs() < 1e-6,
        "{to:?}"
    );
    ctl.cycle_start();
    let mut pts = Vec::new();
    while ctl.state() != RunState::Ended {
        ctl.run_ahead_tap(&mut canon);
        pts.push(ctl.tick());
        assert!(pts.len() < 200_000, "{:?}", ctl.state());
    }
    assert_eq!(canon, expected);
    let approach_end = pts.iter().position(|p| p.motion == runtime::Motion::Feed);
    let approach_end = approach_end.expect("moves after the approach") - 1;
    let p = pts[approach_end];
    assert!(
        (p.x - 20.0).abs() < 1e-9 && (p.z + 20.468_629).abs() < 1e-6,
        "{p:?}"
    );
    // The approach is the taper's line's; then the whole run's lines.
    let whole_lines = lines(&whole_pts);
    let from_taper = whole_lines
        .iter()
        .position(|&l| l == 5)
        .expect("line 5 runs");
    assert_eq!(lines(&pts), whole_lines[from_taper..]);
    assert_eq!((pts.last().map(|p| (p.x, p.z))), Some((60.0, -40.0)));
}

/// The operator's screen after a restart's search shows the codes the run
/// resumes with, as a control's does, until a block runs; a refused
/// restart and another program selected bring back the power-on codes.
#[test]
fn the_screen_shows_the_codes_a_restart_resumes_with() {
    let mut ctl = controller();
    let power_on = ctl.active_codes();
    assert_eq!(
        power_on.to_string(),
        "G00 G97 G98 G21 G40 G23 G80 G67 G54 G64 G18 G15 G13.1 F0 S0 T0000"
    );
    let restarted = ctl.restart_from(N100).expect("restarts");
    assert_eq!(restarted.codes, at_n100());
    assert_eq!(ctl.active_codes(), at_n100());
    assert_eq!(
        at_n100().to_string(),
        "G00 G97 G99 G21 G40 G23 G80 G67 G54 G64 G18 G15 G13.1 F0.2 S800 T0202"
    );
    let never = RestartAt {
        target: Target::Seq(999),
        pass: 1,
    };
    assert!(ctl.restart_from(never).is_err());
    assert_eq!(ctl.active_codes(), power_on);
    // Restarted, then another program selected: it starts at power-on.
    ctl.restart_from(N100).expect("restarts");
    let machine = Machine::reference();
    assert_eq!(ctl.select_program(module(TWO_TOOLS, &machine)), Ok(()));
    assert_eq!(ctl.active_codes(), power_on);
    // Again, and the run: the approach shows them, N100's cut its own
    // G01 F0.1.
    ctl.restart_from(N100).expect("restarts");
    ctl.cycle_start();
    let mut seen = Vec::new();
    for _ in 0..100_000 {
        ctl.run_ahead();
        let p = ctl.tick();
        let codes = ctl.active_codes();
        if seen.last() != Some(&(p.line, codes)) {
            seen.push((p.line, codes));
        }
        if p.line == 11 {
            break;
        }
    }
    let cut = ActiveCodes {
        g: [
            10, 970, 990, 210, 400, 230, 800, 670, 540, 640, 180, 150, 131,
        ],
        f: 0.1,
        ..at_n100()
    };
    assert_eq!(seen.first(), Some(&(10, at_n100())), "{seen:?}");
    assert!(seen.contains(&(10, cut)), "{seen:?}");
}
