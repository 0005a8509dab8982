//! A controller on two threads, as a real-time host runs it: the
//! interpreter keeps the queue filled from an ordinary thread while the
//! period loop — here paced at 1 ms by the wall clock — ticks the
//! real-time half. They share no lock.
//!
//! `cargo run -p runtime --example threads [FILE.gbc]` (without a file it
//! compiles a small built-in program).

use runtime::{Controller, RunState};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

const PROGRAM: &str = "O0001
G50 X100 Z50
T0101 M03 S1000
G00 X40 Z2 M08
G99 G01 Z-20 F0.3
X50 Z-30
G02 X60 Z-35 R5
G01 Z-50
G00 X100 Z50 M09
M30
";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let machine = nc::Machine::reference();
    let module = match std::env::args().nth(1) {
        Some(path) => isa::Module::from_bytes(&std::fs::read(path)?).map_err(|e| format!("{e}"))?,
        None => {
            let out = compiler::compile("built-in.nc", PROGRAM.as_bytes(), &Default::default());
            let rendered = out.render();
            out.module.ok_or(rendered)?
        }
    };
    let (mut interp, mut rt) = Controller::new(module, machine, runtime::AutoAck)?.split();
    let stop = AtomicBool::new(false);
    rt.cycle_start();
    let start = Instant::now();
    std::thread::scope(|s| {
        // The ordinary context: run the VM ahead whenever there is room.
        s.spawn(|| {
            while !stop.load(Ordering::Acquire) {
                interp.run_ahead();
                std::thread::sleep(Duration::from_millis(5));
            }
        });
        // The real-time context: one tick per period, on time.
        let period = Duration::from_secs_f64(rt.engine().config().period_s);
        let mut next = Instant::now();
        loop {
            let sp = rt.tick();
            if ((sp.time_s * 1000.0).round() as u64).is_multiple_of(500) {
                println!(
                    "t={:7.3}s  X={:9.4} Z={:9.4}  line {:3}  {:?}",
                    sp.time_s,
                    sp.x,
                    sp.z,
                    sp.line,
                    rt.state()
                );
            }
            match rt.state() {
                RunState::Stopped(_) => rt.cycle_start(),
                RunState::Ended | RunState::Alarm(_) => break,
                _ => {}
            }
            next += period;
            std::thread::sleep(next.saturating_duration_since(Instant::now()));
        }
        stop.store(true, Ordering::Release);
    });
    println!(
        "{:?} at t={:.3}s after {:.3}s of wall time",
        rt.state(),
        rt.engine().time_s(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
