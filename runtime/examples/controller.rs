//! Runs a program tick by tick as a controller would: the host's PLC
//! takes its time to acknowledge M08, the operator turns the feed override
//! down for a while and presses feed hold once.
//!
//! `cargo run -p runtime --example controller [FILE.gbc]` (without a file
//! it compiles a small built-in program).

use runtime::plc::{Plc, PlcFunction};
use runtime::{Controller, RunState};

/// A PLC whose coolant valve needs 50 periods to report "on".
#[derive(Default)]
struct SlowCoolant {
    busy: u32,
}

impl Plc for SlowCoolant {
    fn request(&mut self, f: PlcFunction) {
        if f == PlcFunction::M(8) {
            self.busy = 50;
        }
    }

    fn done(&mut self, _: PlcFunction) -> bool {
        self.busy = self.busy.saturating_sub(1);
        self.busy == 0
    }
}

const PROGRAM: &str = "O0001
G50 X100 Z50
T0101 M03 S1000
G00 X40 Z2 M08
G99 G01 Z-20 F0.15
X50 Z-30
G02 X60 Z-35 R5
G01 Z-50
G00 X100 Z50 M09
M30
";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let machine = nc::Machine::reference();
    let bytes = match std::env::args().nth(1) {
        Some(path) => std::fs::read(path)?,
        None => {
            let out = compiler::compile(
                "built-in.nc",
                PROGRAM.as_bytes(),
                &compiler::Options::default(),
            );
            let rendered = out.render();
            let module = out.module.ok_or(rendered)?;
            module.to_bytes()
        }
    };
    let module = isa::Module::from_bytes(&bytes).map_err(|e| format!("{e}"))?;
    let mut ctl = Controller::new(module, machine, SlowCoolant::default())?;
    ctl.cycle_start();
    let mut held = false;
    loop {
        // Ordinary context: keep the planner fed.
        ctl.run_ahead();
        // Real-time context: one period.
        let sp = ctl.tick();
        let t = sp.time_s;
        if (1.0..1.5).contains(&t) {
            ctl.set_feed_override(50.0);
        } else {
            ctl.set_feed_override(100.0);
        }
        if !held && t >= 2.0 {
            ctl.feed_hold();
            held = true;
        }
        match ctl.state() {
            RunState::Held if t >= 2.5 => ctl.cycle_start(),
            RunState::Stopped(_) => ctl.cycle_start(),
            RunState::Ended => break,
            RunState::Alarm(_) => {
                if let Some(a) = ctl.alarm() {
                    eprintln!("{}", a.header());
                }
                break;
            }
            _ => {}
        }
        if ((t * 1000.0).round() as u64).is_multiple_of(100) {
            println!(
                "t={t:7.3}s  X={:9.4} Z={:9.4}  S={:7.1} rpm  F={:8.1} mm/min  line {:3}  {:?}",
                sp.x,
                sp.z,
                sp.spindle_rpm,
                sp.feed,
                sp.line,
                ctl.state()
            );
        }
    }
    println!(
        "ended at t={:.3}s after {} blocks",
        ctl.engine().time_s(),
        ctl.blocks()
    );
    Ok(())
}
