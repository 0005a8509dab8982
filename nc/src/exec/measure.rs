//! G36/G37 automatic tool offset measurement (dialect.md §4.5).
//!
//! `G36 X` (`G37 Z`) names the measuring position, absolute. The tool
//! rapids to γ (№142/№143) before it on its way there, then feeds at the
//! measuring feed №141 until the measure signal (XAE/ZAE) arrives; the
//! difference between the programmed and the reached position is added to
//! the active offset. The kernel runs what a host answers through
//! `host.measure_at_target`: the signal exactly at the position (the
//! reference: the offset stays as it is), or never, which is E7006 once
//! the tool is ε (№144/№145) past the position. Compensation must be off
//! (checked with the other functions that need it off, in `comp`); a tool
//! and a non-zero offset number must be active (E4032). X is a diameter,
//! γ and ε are radial amounts for X.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::Event;
use crate::base::point::Pt;
use crate::base::words::addr;
use crate::block::Parsed;
use crate::exec::{Nc, Sink};

/// Runs a G36 (`x_axis`) or G37 block.
pub fn run(nc: &mut Nc, x_axis: bool, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    let (name, word, inc) = if x_axis {
        ("G36", b'X', b'U')
    } else {
        ("G37", b'Z', b'W')
    };
    if p.has(inc) {
        let msg = format!(
            "{name} takes the absolute measuring position {}, not {}",
            word as char, inc as char
        );
        return Err(NcError::new(Alarm::IncompatibleWords, msg).on_addr(addr(inc)));
    }
    let Some(at) = nc.len_of(p, word) else {
        return fail(
            Alarm::MissingWord,
            format!("{name} needs the measuring position {}", word as char),
        );
    };
    if nc.st.tool == 0 || nc.st.offset == 0 {
        return fail(
            Alarm::MeasureInComp,
            format!("{name} needs an active tool and a non-zero offset number (T word)"),
        );
    }
    let m = &nc.machine.measure;
    // Along the measured axis, in the kernel's radial coordinate for X.
    let (target, gamma, eps) = if x_axis {
        (nc.machine.radial(at), m.gamma_x_mm, m.epsilon_x_mm)
    } else {
        (at, m.gamma_z_mm, m.epsilon_z_mm)
    };
    let feed = m.feed_mm_min;
    let from = axis_of(nc.st.pos, x_axis);
    let dir = if target >= from { 1.0 } else { -1.0 };
    // The slow-down point γ before the position; a start closer than γ
    // feeds from where it stands.
    let slow = target - dir * gamma;
    if (slow - from) * dir > 0.0 {
        let to = with_axis(nc.st.pos, x_axis, slow);
        nc.rapid(to, sink);
    }
    let signal = nc.machine.host.measure_at_target;
    let end = if signal { target } else { target + dir * eps };
    feed_at(nc, feed, sink);
    let to = with_axis(nc.st.pos, x_axis, end);
    nc.st.pos = to;
    sink.emit(Event::Line {
        x: to.x(),
        z: to.z,
        c: None,
    });
    if !signal {
        return fail(
            Alarm::NoMeasuringSignal,
            format!("{name}: no measuring signal within ε past the position"),
        );
    }
    Ok(())
}

fn axis_of(p: Pt, x_axis: bool) -> f64 {
    if x_axis {
        p.r
    } else {
        p.z
    }
}

fn with_axis(mut p: Pt, x_axis: bool, v: f64) -> Pt {
    if x_axis {
        p.r = v;
    } else {
        p.z = v;
    }
    p
}

/// `FEED` for the measuring feed (mm/min) when it is not the last printed.
fn feed_at(nc: &mut Nc, f: f64, sink: &mut dyn Sink) {
    if nc.st.feed_due((f, false)) {
        sink.emit(Event::Feed { f, per_rev: false });
    }
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::Lathe;
    use alloc::string::{String, ToString};
    use alloc::vec::Vec;

    fn run(m: &mut Lathe, blocks: &[&str]) -> Result<Vec<String>, u16> {
        let mut canon = Vec::new();
        for b in blocks {
            canon.extend(m.try_run(b)?);
        }
        Ok(canon)
    }

    #[test]
    fn g36_rapids_to_gamma_then_feeds_to_the_position() {
        // From X100: γ = 2 mm radial = 4 mm on the diameter, so the rapid
        // ends at X60 + 4 = X64 coming down; then the measuring feed 50
        // mm/min to X60. The program's F0.2 per rev is printed again for
        // the next G01 because FEED changed in between.
        let mut m = Lathe::new();
        let canon = run(
            &mut m,
            &["T0101", "G99 G00 X100 Z5", "G36 X60.", "G01 Z0 F0.2"],
        );
        assert_eq!(
            canon.unwrap(),
            [
                "TOOL T=1 D=1",
                "RAPID X=100 Z=5",
                "RAPID X=64 Z=5",
                "FEED F=50 MODE=MIN",
                "LINE X=60 Z=5",
                "FEED F=0.2 MODE=REV",
                "LINE X=60 Z=0",
            ]
        );
    }

    #[test]
    fn g37_measures_along_z_from_either_side() {
        // From Z-10 up to Z-3: the slow-down point is Z-5 (γ = 2).
        let mut m = Lathe::new();
        let canon = run(&mut m, &["T0202", "G00 X20 Z-10", "G37 Z-3."]).unwrap();
        assert_eq!(
            canon[2..],
            ["RAPID X=20 Z=-5", "FEED F=50 MODE=MIN", "LINE X=20 Z=-3"]
        );
        // Closer than γ: no rapid, the feed starts where the tool stands.
        let canon = run(&mut m, &["G37 Z-4."]).unwrap();
        assert_eq!(canon, ["LINE X=20 Z=-4"]);
    }

    #[test]
    fn without_an_offset_number_it_is_e4032() {
        // Power-on: tool 1, offset 0.
        let mut m = Lathe::new();
        assert_eq!(run(&mut m, &["G36 X60."]), Err(4032));
        let mut m = Lathe::new();
        assert_eq!(run(&mut m, &["T0101", "G36 U-2."]), Err(2007));
        assert_eq!(run(&mut m, &["G37 X10."]), Err(2006));
    }

    #[test]
    fn no_signal_is_e7006_epsilon_past_the_position() {
        // ε = 0.5 mm radial: the feed goes on to X60 − 1 = X59.
        let mut machine = crate::base::machine::Machine::reference();
        machine.host.measure_at_target = false;
        let mut m = Lathe {
            nc: crate::exec::Nc::new(machine),
        };
        let mut canon = Vec::new();
        let mut code = 0;
        for b in ["T0101", "G00 X100 Z5", "G36 X60."] {
            let mut events = Vec::new();
            let r =
                m.nc.exec(&crate::exec::cycles::testing::words(b), &mut events);
            canon.extend(events.iter().map(|e| e.to_string()));
            if let Err(e) = r {
                code = e.code;
            }
        }
        assert_eq!(code, 7006);
        assert_eq!(canon.last().map(String::as_str), Some("LINE X=59 Z=5"));
    }
}
