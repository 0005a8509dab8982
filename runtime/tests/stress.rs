//! Generated programs (a fixed pseudo-random sequence) with lines, arcs,
//! rapids, feed changes, overrides turned and feed holds pressed at odd
//! moments: every end point reached, every axis within its limits.

mod common;

pub use common::*;
use nc::Machine;
use runtime::RunState;

struct Seq(u64);

impl Seq {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }
    fn unit(&mut self) -> f64 {
        (self.next() % 1_000_000) as f64 / 1_000_000.0
    }
}

pub fn program(seed: u64, blocks: usize) -> String {
    let mut g = Seq(seed);
    let mut s = String::from("O0100\nG97 S1200 M03\nG00 X40 Z0\nG98 F500\n");
    let (mut x, mut z) = (40.0f64, 0.0f64);
    for _ in 0..blocks {
        let nx = (x + (g.unit() - 0.5) * 8.0).clamp(2.0, 80.0);
        let nz = z - g.unit() * 3.0 - 0.01;
        match g.next() % 10 {
            0 => s.push_str(&format!("G00 X{nx:.3} Z{nz:.3}\n")),
            1 | 2 => {
                let chord = ((nx - x) / 2.0).hypot(nz - z);
                let r = chord / 2.0 + g.unit() * 5.0 + 0.01;
                let code = if g.next().is_multiple_of(2) {
                    "G02"
                } else {
                    "G03"
                };
                s.push_str(&format!(
                    "G98 {code} X{nx:.3} Z{nz:.3} R{r:.3} F{}\n",
                    200 + g.next() % 2000
                ));
            }
            3 => s.push_str(&format!(
                "G99 G01 X{nx:.3} Z{nz:.3} F0.{}\n",
                1 + g.next() % 3
            )),
            4 => s.push_str(&format!(
                "G98 G01 X{nx:.3} Z{nz:.3} F{}\n",
                100 + g.next() % 4000
            )),
            // G98 after G99 keeps the number of F: give it again.
            _ => s.push_str(&format!("G98 G01 X{nx:.3} Z{nz:.3} F800\n")),
        }
        x = nx;
        z = nz;
    }
    s.push_str("G00 X100 Z10\nM30\n");
    s
}

/// One generated program, run with the operator playing with the panel.
pub fn run_seed(seed: u64, log: &mut dyn FnMut(f64, &str)) -> Run {
    let src = program(seed, 150);
    let mut g = Seq(seed * 77);
    let mut next_event = 0.2;
    let mut hold_until = None;
    run_with(
        &src,
        Machine::reference(),
        runtime::AutoAck,
        |_| {},
        |ctl, sp| {
            if let Some(t) = hold_until {
                if sp.time_s >= t {
                    hold_until = None;
                    ctl.cycle_start();
                    log(sp.time_s, "cycle start");
                }
            }
            if sp.time_s >= next_event {
                next_event += 0.05 + g.unit() * 0.4;
                match g.next() % 4 {
                    0 => {
                        let o = (g.next() % 16) as f64 * 10.0;
                        ctl.set_feed_override(o);
                        log(sp.time_s, &format!("feed override {o}"));
                    }
                    1 => {
                        let r = [
                            runtime::RapidOverride::F0,
                            runtime::RapidOverride::P25,
                            runtime::RapidOverride::P50,
                            runtime::RapidOverride::P100,
                        ][(g.next() % 4) as usize];
                        ctl.set_rapid_override(r);
                        log(sp.time_s, &format!("rapid override {r:?}"));
                    }
                    2 if hold_until.is_none() => {
                        ctl.feed_hold();
                        hold_until = Some(sp.time_s + 0.1);
                        log(sp.time_s, "feed hold");
                    }
                    _ => {
                        ctl.set_feed_override(100.0);
                        log(sp.time_s, "feed override 100");
                    }
                }
            }
        },
        3600.0,
    )
}

#[test]
fn generated_programs_stay_within_the_limits() {
    for seed in 1..=6u64 {
        let r = run_seed(seed, &mut |_, _| {});
        assert_eq!(r.state, RunState::Ended, "seed {seed}");
        check_end_points(&r);
        let (v, a) = worst_ratios(&r, false);
        eprintln!("seed {seed}: {} periods, worst velocity {v:.6}, worst acceleration {a:.6} of the limits", r.pts.len());
        check_limits(&r, false);
    }
}

/// The same at the shortest and the longest period the machine allows.
#[test]
fn other_periods_stay_within_the_limits() {
    for (period, seed) in [(0.125, 7u64), (2.0, 8), (8.0, 9)] {
        let m = Machine::from_toml(&format!("[machine]\ninterpolation_period_ms = {period}\n"))
            .unwrap();
        let src = program(seed, 60);
        let r = run_with(&src, m, runtime::AutoAck, |_| {}, |_, _| {}, 3600.0);
        assert_eq!(r.state, RunState::Ended, "period {period}");
        check_end_points(&r);
        let (v, a) = worst_ratios(&r, false);
        eprintln!(
            "period {period} ms: {} periods, worst velocity {v:.6}, worst acceleration {a:.6}",
            r.pts.len()
        );
        check_limits(&r, false);
    }
}
