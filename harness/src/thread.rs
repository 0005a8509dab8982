//! Thread cycles through the runtime: bytes → a G92, G76 or G32 thread
//! at a lead and spindle speed that may ask an axis for more than its
//! maximum cutting feed → a run that either stops with E4010 before the
//! thread, exactly where `gbcc` warned W126, or that `gbvm check`
//! certifies (every axis within its limits, every end point reached, the
//! lead kept away from the incomplete leads and the catch-up of a long
//! axis a corner turns). Random cycles like these found pull-outs braked
//! out of step with the spindle and run-outs that closed their lag ever
//! slower (runtime/tests/thread_motion.rs runs a fixed set of them).

use nc::Machine;
use runtime::certify::Kind;
use runtime::{AutoAck, Controller, RunState};

/// Spindle speeds (rev/min) the first byte chooses from (mod 5).
pub const SPEEDS: [u32; 5] = [200, 500, 1000, 1500, 2500];
/// Leads (mm) the first byte chooses from (bits 3–7, mod 8).
pub const LEADS: [f64; 8] = [0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0];
/// G76 pull-outs in tenths of the lead (mod 5).
pub const PULL_OUTS: [u32; 5] = [0, 5, 10, 20, 30];
/// Legs a G32 chain has after its Z thread at most (2 bytes each).
pub const MAX_LEGS: usize = 5;
/// Periods a run may take: 600 s, far more than a cycle needs.
pub const MAX_TICKS: u64 = 600_000;

/// A thread cycle read from bytes.
///
/// Byte 0: the spindle speed ([`SPEEDS`]) and the lead ([`LEADS`], from
/// bits 3–7). Byte 1: the cycle (mod 4): a G92 pass pair with a J/K
/// pull-out, a G76, a G32 chain, a taper G92 with a 45° pull-out. Bytes 2
/// and 3: the thread's diameter 10 + 50·b/255 and length 8 + 32·b/255
/// mm. Then, for G92: J = 0.2 + 3.8·b/255 (byte 4) and K the same of byte
/// 5, or K = J when byte 5 is even; for G76: the pull-out ([`PULL_OUTS`],
/// byte 4) and one or two finishing passes (byte 5, mod 2); for the G32
/// chain: from where the tool stands (diameter + 5), legs of 2 bytes
/// from byte 4 on, each b/32 mm out on the
/// diameter (0–7.97) and b/64 mm along −Z (0–3.98), a leg that rounds to
/// no move left out; for the taper: its R = 0.5 + 2.5·b/255 (byte 4).
/// Values are written to 3 decimals.
pub fn decode(data: &[u8]) -> String {
    let b = |i: usize| data.get(i).copied().unwrap_or(0);
    let unit = |i: usize| f64::from(b(i)) / 255.0;
    let rpm = SPEEDS[usize::from(b(0)) % SPEEDS.len()];
    let lead = LEADS[usize::from(b(0) >> 3) % LEADS.len()];
    let (d, l) = (10.0 + 50.0 * unit(2), 8.0 + 32.0 * unit(3));
    let mut s = format!("G97 S{rpm} M03\nG99\nG00 X{:.3} Z5\n", d + 5.0);
    match b(1) % 4 {
        0 => {
            let j = 0.2 + 3.8 * unit(4);
            let k = if b(5) % 2 == 0 {
                j
            } else {
                0.2 + 3.8 * unit(5)
            };
            s += &format!(
                "G92 X{:.3} Z-{l:.3} F{lead} J{j:.3} K{k:.3}\nX{:.3}\n",
                d - 0.3,
                d - 0.6
            );
        }
        1 => {
            let h = lead * 0.6;
            s += &format!(
                "G76 P0{}{:02}60 Q50 R0.02\nG76 X{:.3} Z-{l:.3} P{:.0} Q{:.0} F{lead}\n",
                1 + b(5) % 2,
                PULL_OUTS[usize::from(b(4)) % PULL_OUTS.len()],
                d - 2.0 * h,
                h * 1000.0,
                (h * 300.0).max(60.0)
            );
        }
        2 => s += &chain(data.get(4..).unwrap_or_default(), d + 5.0, l, lead),
        _ => {
            s += &format!(
                "G92 X{:.3} Z-{l:.3} R-{:.3} F{lead} J1 K1\n",
                d - 0.3,
                0.5 + 2.5 * unit(4)
            );
        }
    }
    s + "G00 X80 Z20\nM30\n"
}

/// A G32 Z thread of length `l` at diameter `d` (where the tool stands),
/// then up to [`MAX_LEGS`] legs out and along −Z (2 bytes each), then
/// out and back to Z5.
fn chain(legs: &[u8], d: f64, l: f64, lead: f64) -> String {
    let mut s = format!("G32 Z-{l:.3} F{lead}\n");
    let mut x = d;
    for leg in legs.chunks_exact(2).take(MAX_LEGS) {
        let (dx, dz) = (f64::from(leg[0]) / 32.0, f64::from(leg[1]) / 64.0);
        if format!("{dx:.3}{dz:.3}") == "0.0000.000" {
            continue;
        }
        x += dx;
        s += &format!("G32 X{x:.3} W-{dz:.3}\n");
    }
    s + &format!("G00 X{:.3}\nZ5\n", x + 7.0)
}

/// The target: a cycle that compiles either stops with E4010, which
/// `gbcc` warned (W126), or runs to its end within [`MAX_TICKS`] without
/// W126 and is certified. Where `gbcc` warned that a block of the chain
/// is too short to reach or to stop from thread speed (W118), the axes
/// cannot follow the programmed chain there (they run past its end), and
/// only the axes' and the spindle's limits are held to.
pub fn certified_or_warned(data: &[u8]) {
    let src = decode(data);
    let machine = Machine::reference();
    let compiled = compiler::compile("thread.nc", src.as_bytes(), &compiler::Options::default());
    let warned = |code: &str| compiled.diags.iter().any(|(_, d)| d.code == code);
    let (warned, no_room) = (warned("W126"), warned("W118"));
    let Some(module) = compiled.module else {
        return;
    };
    let mut ctl = match Controller::new(module, machine, AutoAck) {
        Ok(c) => c,
        Err(e) => panic!("a compiled module does not load: {e}\n{src}"),
    };
    let (cert, _) = ctl.run_certified(MAX_TICKS);
    match ctl.state() {
        RunState::Alarm(code) => {
            assert!(code == 4010 && warned, "alarm {code}, W126 {warned}\n{src}");
        }
        RunState::Ended => {
            assert!(!warned, "W126 but the run went on\n{src}");
            let held = |k: &Kind| !no_room || !matches!(k, Kind::EndPoint | Kind::Lead);
            for kind in Kind::ALL.iter().filter(|k| held(k)) {
                if let Some(v) = cert.worst(*kind).filter(|v| v.violates()) {
                    panic!("line {}: {v}\n{src}", v.line);
                }
            }
        }
        s => panic!("the run did not end in 600 s ({s:?})\n{src}"),
    }
}
