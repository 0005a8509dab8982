//! Polar and cylindrical interpolation keep every joint within its
//! limits: random plane programs (lines, arcs, G00, the axis outside the
//! plane moving alone; a fixed seed) are certified period by period
//! (`runtime::certify`, as `gbvm check` does). Before the planner knew
//! the joints, C ran at up to 50 times its speed near the centre.

mod common;

use nc::Machine;
use runtime::certify::Certifier;
use runtime::{AutoAck, Config, Controller, RunState};

/// A small deterministic generator (64-bit LCG, Knuth's constants).
struct Lcg(u64);

impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        ((lo + (hi - lo) * self.unit()) * 1000.0).round() / 1000.0
    }

    fn pick<T: Copy>(&mut self, of: &[T]) -> T {
        of[((self.unit() * of.len() as f64) as usize).min(of.len() - 1)]
    }
}

/// A contour of G12.1: points in x −30…30, c −20…20 (radius values).
fn polar(rng: &mut Lcg) -> String {
    let mut s = String::from("G98 G00 X40 Z2 C0\nG12.1\n");
    let (mut x, mut c) = (20.0f64, 0.0f64);
    for _ in 0..3 + (rng.unit() * 6.0) as usize {
        let (nx, nc) = (rng.range(-30.0, 30.0), rng.range(-20.0, 20.0));
        let f = rng.pick(&[100, 300, 1000, 3000]);
        match rng.pick(&["G01", "G00", "G02", "G03", "Z"]) {
            "Z" => {
                s += &format!("G01 Z{} F{f}\n", rng.range(-5.0, 2.0));
                continue;
            }
            g @ ("G02" | "G03") => {
                let half = (nx - x).hypot(nc - c) / 2.0;
                if half < 0.05 {
                    continue;
                }
                let r = (half * rng.range(1.01, 3.0) * 1000.0).round() / 1000.0;
                s += &format!("{g} X{} C{nc} R{r} F{f}\n", 2.0 * nx);
            }
            g => s += &format!("{g} X{} C{nc} F{f}\n", 2.0 * nx),
        }
        (x, c) = (nx, nc);
    }
    s + "G13.1\nM30\n"
}

/// A groove of G7.1 on a cylinder of radius 5…40.
fn cylinder(rng: &mut Lcg) -> String {
    let r = rng.pick(&[5.0, 10.0, 20.0, 40.0]);
    let mut s = format!("G98 G00 X{} Z0 C0\nG7.1 C{r}.\n", 2.0 * r);
    for _ in 0..3 + (rng.unit() * 6.0) as usize {
        let (z, c) = (rng.range(-30.0, 0.0), rng.range(-200.0, 200.0));
        let f = rng.pick(&[100, 300, 1000, 3000]);
        match rng.pick(&["G01", "G00", "G02", "G03", "X"]) {
            "X" => s += &format!("G01 X{} F{f}\n", 2.0 * r - rng.range(0.0, 2.0)),
            g @ ("G02" | "G03") => {
                s += &format!("{g} Z{z} C{c} R{} F{f}\n", rng.range(20.0, 200.0))
            }
            g => s += &format!("{g} Z{z} C{c} F{f}\n"),
        }
    }
    s + "G7.1 C0\nM30\n"
}

/// `Some(verdict)` of a run of `src` to its end: `Ok` certified, `Err`
/// the violation; `None` where it does not compile or stops with an
/// alarm (an arc that cannot be drawn, a path through the centre).
fn certify(src: &str, jerk: bool) -> Option<Result<(), String>> {
    let mut machine = Machine::reference();
    machine.axes.c.enabled = true;
    let opts = compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    };
    let module = compiler::compile("plane.nc", src.as_bytes(), &opts).module?;
    let mut cfg = Config::from_machine(&machine);
    cfg.jerk_limited = jerk;
    let mut ctl = Controller::with_config(module, machine, cfg, AutoAck).expect("loads");
    let engine = ctl.engine();
    let start = engine.position();
    let mut cert = Certifier::new(engine.config(), start.x(), start.z, engine.c());
    ctl.cycle_start();
    // (600 s of simulated time at 1 ms periods.)
    for _ in 0..600_000 {
        ctl.run_ahead_tap(&mut cert);
        cert.period(&ctl.tick());
        match ctl.state() {
            RunState::Ended => break,
            RunState::Alarm(_) => return None,
            _ => {}
        }
    }
    assert_eq!(
        ctl.state(),
        RunState::Ended,
        "{src}: the run did not end in 600 s"
    );
    cert.finish(true);
    Some(match cert.violation() {
        None => Ok(()),
        Some(v) => Err(format!("line {}: {v}", v.line)),
    })
}

#[test]
fn random_plane_programs_are_certified() {
    let mut rng = Lcg(2026);
    let mut certified = 0;
    for k in 0..48 {
        let src = if k % 2 == 0 {
            polar(&mut rng)
        } else {
            cylinder(&mut rng)
        };
        for jerk in [false, true] {
            match certify(&src, jerk) {
                Some(Ok(())) => certified += 1,
                Some(Err(v)) => panic!("jerk {jerk}: {v}\n{src}"),
                None => {}
            }
        }
    }
    // Most of them run (a random arc may not fit its R).
    assert!(certified >= 80, "{certified} of 96 runs certified");
}
