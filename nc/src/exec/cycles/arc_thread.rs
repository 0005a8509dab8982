//! G32.2 / G32.3: a thread along an arc at constant lead (dialect.md
//! §4.3): one `ARCTHREAD` event per block.

use super::lead;
use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event};
use crate::base::gcode::Motion;
use crate::base::geom;
use crate::base::point::Pt;
use crate::block::{round_half_away, Parsed};
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::thread::check_long_axis;

/// A G32.2 (322, clockwise) or G32.3 (323) block.
pub(crate) fn run(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let cw = code == Motion::ArcThreadCw;
    // I is the centre here, so the lead is F only.
    let written = lead::written(nc, p, false);
    lead::remember(nc, written);
    let centre_words = p.has(b'R') || p.has(b'I') || p.has(b'K');
    if !p.has_axis() && !centre_words {
        return Ok(());
    }
    let lead = lead::resolve(nc, written)?;
    let from = nc.st.pos;
    let to = nc.target(p);
    let Some(centre) = centre(nc, p, cw, from, to)? else {
        // A 0° arc with R: no move (as G02/G03).
        return Ok(());
    };
    check_long_axis(from, to, centre, cw)?;
    let q = p.get(b'Q').map_or(0.0, |q| round_half_away(q) / 1000.0);
    nc.st.pos = to;
    sink.emit(Event::ArcThread {
        dir: if cw { Dir::Cw } else { Dir::Ccw },
        x: to.x(),
        z: to.z,
        cx: centre.x(),
        cz: centre.z,
        lead,
        q: (q != 0.0).then_some(q),
    });
    out.moved = true;
    Ok(())
}

/// The centre by the G02/G03 rules: R wins over I/K; neither is E2006.
fn centre(nc: &Nc, p: &Parsed, cw: bool, from: Pt, to: Pt) -> Result<Option<Pt>, NcError> {
    if let Some(r) = nc.len_of(p, b'R') {
        return geom::centre_from_radius(from, to, r, cw);
    }
    if p.has(b'I') || p.has(b'K') {
        let i = nc.len_of(p, b'I').unwrap_or(0.0);
        let k = nc.len_of(p, b'K').unwrap_or(0.0);
        let c = Pt::new(from.r + i, from.z + k);
        geom::check_on_circle(from, to, c, nc.machine.machine.arc_tolerance_mm)?;
        return Ok(Some(c));
    }
    fail(
        Alarm::MissingWord,
        "G32.2/G32.3 need R or I/K to define the arc's centre",
    )
}

#[cfg(test)]
mod tests {
    use crate::base::event::{Dir, Event};
    use crate::base::point::Pt;
    use crate::exec::cycles::testing::{assert_line, run_err, Lathe};
    use crate::plan::thread::check_long_axis;
    use alloc::string::ToString;

    #[test]
    fn arcthread_prints_its_fields_in_order() {
        let e = Event::ArcThread {
            dir: Dir::Cw,
            x: 20.0,
            z: -10.0,
            cx: 37.32051,
            cz: -5.0,
            lead: 2.0,
            q: Some(90.0),
        };
        assert_eq!(
            e.to_string(),
            "ARCTHREAD DIR=CW X=20 Z=-10 CX=37.3205 CZ=-5 LEAD=2 Q=90"
        );
        assert!(e.is_motion() && !e.is_feed());
    }

    #[test]
    fn the_long_axis_changes_only_at_45_degrees() {
        // About (r20, z0), radius 10, θ from +Z towards +r. From θ = -30°
        // to +30° counter-clockwise the tangent stays within 30° of X.
        let c = Pt::new(20.0, 0.0);
        let at = |deg: f64| {
            let t = deg.to_radians();
            Pt::new(20.0 + 10.0 * t.sin(), 10.0 * t.cos())
        };
        assert!(check_long_axis(at(-30.0), at(30.0), c, false).is_ok());
        // From 30° to 60° it crosses 45°; clockwise from 30° to -30° it is
        // X-long again; from 60° to 120° Z-long; 100° to 170° crosses 135°.
        assert!(check_long_axis(at(30.0), at(60.0), c, false).is_err());
        assert!(check_long_axis(at(30.0), at(-30.0), c, true).is_ok());
        assert!(check_long_axis(at(60.0), at(120.0), c, false).is_ok());
        assert!(check_long_axis(at(100.0), at(170.0), c, false).is_err());
        // Clockwise from 30° to -30° the long way round crosses them all.
        assert!(check_long_axis(at(-30.0), at(30.0), c, true).is_err());
    }

    #[test]
    fn an_x_long_arc_thread_with_i_k() {
        // From X30 Z8.66025 (θ = -30° about r20 z0) to X50 Z8.66025
        // (θ = 30°), counter-clockwise: I5 K-8.66025, centre X40 Z0.
        let mut m = Lathe::new();
        m.run("M03 S200");
        m.run("G00 X30 Z8.66025");
        let l = m.run("G32.3 X50 Z8.66025 I5 K-8.66025 F1.5 Q180000");
        assert_line(
            &l[0],
            "ARCTHREAD DIR=CCW",
            &[50.0, 8.66025, 40.0, 0.0, 1.5, 180.0],
        );
        // From θ = 30° (X50 Z8.66025) to 60° (X57.3205 Z5) crosses 45°.
        assert_eq!(m.try_run("G32.3 X57.32051 Z5 I-5 K-8.66025"), Err(4010));
    }

    #[test]
    fn arc_thread_errors_and_the_modal_lead() {
        assert_eq!(run_err(&["G00 X20 Z0", "G32.2 X20 Z-10 F2"]), 2006);
        assert_eq!(run_err(&["G00 X20 Z0", "G32.2 X20 Z-10 R10"]), 2006);
        assert_eq!(run_err(&["G00 X20 Z0", "G32.2 X20 Z-30 R10 F1"]), 4001);
        // A full circle has no single long axis.
        assert_eq!(run_err(&["G00 X20 Z0", "G32.2 X20 Z0 K-5 F1"]), 4010);
        // The lead of a G32 is modal for G32.2.
        let mut m = Lathe::new();
        m.run("G00 X20 Z0");
        m.run("G32 W-1 F1.75");
        assert!(m.run("G32.2 X20 Z-6 R5")[0].ends_with("LEAD=1.75"));
        // With R, end = start is no move.
        assert!(m.run("G32.2 X20 Z-6 R5").is_empty());
    }
}
