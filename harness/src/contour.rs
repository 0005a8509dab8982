//! Contours of micro-moves through the runtime: bytes → a ZX program of
//! lines and arcs from 0.5 µm to 10 mm → a run that `gbvm check` must
//! certify (every axis within its limits, every end point reached), with
//! jerk limiting off or on. Random contours like these found faults in
//! the planner's corners and in jerk limiting on arcs
//! (runtime/tests/contour_limits.rs runs a fixed set of them).

use core::f64::consts::{FRAC_PI_2, TAU};
use nc::Machine;
use runtime::{AutoAck, Config, Controller, RunState};

/// Moves a contour has at most (4 bytes each).
pub const MAX_MOVES: usize = 40;
/// Periods a run may take: 600 s, far more than 40 moves of 10 mm at the
/// slowest feed need.
pub const MAX_TICKS: u64 = 600_000;

/// The feeds the settings byte chooses from.
pub const FEEDS: [&str; 4] = ["G98 F100", "G98 F800", "G98 F3000", "G99 F0.2"];
/// Arc radii in halves of the chord.
pub const RADII: [f64; 5] = [1.0001, 1.01, 1.5, 3.0, 20.0];

/// A contour read from bytes, and whether to run it with jerk limiting.
///
/// The first byte holds the settings: bit 0 jerk limiting, bit 1 G61
/// (else G64), bits 2–3 the feed ([`FEEDS`]). Then 4 bytes a move: the
/// first gives G01 (0, 1), G02 (2) or G03 (3) by its value mod 4, and bit
/// 2 a move along an axis; the second the length 10^(−3.3 + 4.3·b/255)
/// mm; the third the direction (b/256 of a turn, or (b mod 4) quarter
/// turns along an axis); the fourth an arc's radius ([`RADII`], mod 5).
/// X is a diameter from 60 within 0…120, Z from 2 within −80…10, both to
/// 3 decimals; a move that rounds to no move is left out.
pub fn decode(data: &[u8]) -> (String, bool) {
    let flags = data.first().copied().unwrap_or(0);
    let mut s = format!(
        "G00 X60 Z2\nM03 S1000\n{}\n{}\n",
        if flags & 2 != 0 { "G61" } else { "G64" },
        FEEDS[usize::from(flags >> 2) % FEEDS.len()],
    );
    let (mut x, mut z) = (60.0f64, 2.0f64);
    let moves = data.get(1..).unwrap_or_default().chunks_exact(4);
    for m in moves.take(MAX_MOVES) {
        let len = libm::pow(10.0, -3.3 + 4.3 * f64::from(m[1]) / 255.0);
        let a = if m[0] & 4 != 0 {
            FRAC_PI_2 * f64::from(m[2] % 4)
        } else {
            TAU * f64::from(m[2]) / 256.0
        };
        let nx = mm((x + 2.0 * len * libm::cos(a)).clamp(0.0, 120.0));
        let nz = mm((z + len * libm::sin(a)).clamp(-80.0, 10.0));
        if (nx, nz) == (x, z) {
            continue;
        }
        match m[0] % 4 {
            g @ (2 | 3) => {
                let half = libm::hypot((nx - x) / 2.0, nz - z) / 2.0;
                let r = half * RADII[usize::from(m[3]) % RADII.len()];
                s += &format!("G0{g} X{nx:.3} Z{nz:.3} R{r:.4}\n");
            }
            _ => s += &format!("G01 X{nx:.3} Z{nz:.3}\n"),
        }
        (x, z) = (nx, nz);
    }
    (s + "G00 X80 Z5\nM30\n", flags & 1 != 0)
}

/// A coordinate as a program writes it: 3 decimals.
fn mm(v: f64) -> f64 {
    libm::round(v * 1000.0) / 1000.0
}

/// The target: a contour that compiles runs to its end (or an alarm)
/// within [`MAX_TICKS`] and is certified.
pub fn certified(data: &[u8]) {
    let (src, jerk) = decode(data);
    certified_on("contour.nc", &src, Machine::reference(), jerk, MAX_TICKS);
}

/// A program that compiles on `machine` runs, jerk limiting on or off,
/// to an alarm, or to its end within `ticks` periods and is certified
/// (this target's and the `plane` target's check).
pub(crate) fn certified_on(name: &str, src: &str, machine: Machine, jerk: bool, ticks: u64) {
    let opts = compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    };
    let Some(module) = compiler::compile(name, src.as_bytes(), &opts).module else {
        return;
    };
    let mut cfg = Config::from_machine(&machine);
    cfg.jerk_limited = jerk;
    let mut ctl = match Controller::with_config(module, machine, cfg, AutoAck) {
        Ok(c) => c,
        Err(e) => panic!("a compiled module does not load: {e}\n{src}"),
    };
    let (cert, _) = ctl.run_certified(ticks);
    match ctl.state() {
        RunState::Ended => {}
        RunState::Alarm(_) => return,
        s => panic!("the run did not end in {ticks} periods ({s:?})\n{src}"),
    }
    if let Some(v) = cert.violation() {
        panic!("jerk {jerk}: line {}: {v}\n{src}", v.line);
    }
}
