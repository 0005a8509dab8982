//! G71/G72 type I (cycles.md §5, §6), computed in the G71 frame: the
//! infeed runs along r, the cut along z. G72 arrives mirrored.

use super::turn::{turns_back, Frame};
use super::{tail_start, too_many, Job, Path, Seg};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::plan::curve::{sign, Axis, Curve, EPS};

/// Runs the cycle from A (the tool position) to its return to A.
pub fn run(out: &mut Path, job: &Job) -> Result<(), NcError> {
    let Some((ns, rest)) = job.segs.split_first().filter(|(s, _)| s.ns) else {
        return fail(Alarm::BadRoughing, "the ns block makes no infeed move");
    };
    let a1 = job.a1;
    let b1 = ns.curve.end();
    let sx = sign(b1.r - a1.r);
    if sx == 0.0 {
        return fail(Alarm::BadRoughing, "the ns block makes no infeed move");
    }
    let body = &rest[..tail_start(rest, a1.r, sx)];
    let cr = body.last().map_or(b1, |s| s.curve.end());
    let sz = sign(cr.z - b1.z);
    if sz == 0.0 {
        return fail(
            Alarm::BadRoughing,
            "the profile makes no move along Z (G71) / X (G72) to cut",
        );
    }
    let frame = Frame::of(job, out.mirrored);
    if job.k1 {
        check_monotone(&frame, body, sx, sz)?;
    }
    too_many((b1.r - a1.r).abs() / job.dd)?;
    let c1 = rest.last().map_or(b1, |s| s.curve.end());
    out.rapid(a1);
    let mut k = 1.0;
    loop {
        let level = a1.r + sx * k * job.dd;
        // Only levels strictly before B′ (cycles.md §0).
        if sx * (b1.r - level) <= EPS {
            break;
        }
        out.infeed(ns.rapid, Pt::new(level, a1.z));
        let zk = level_end(&frame, rest, level, sx, sz)?.unwrap_or(c1.z);
        let back = level - sx * job.e;
        out.line(Pt::new(level, zk));
        out.line(Pt::new(back, zk - sz * job.e));
        out.rapid(Pt::new(back, a1.z));
        k += 1.0;
    }
    out.infeed(ns.rapid, Pt::new(b1.r, a1.z));
    for s in rest {
        out.follow(&s.curve, false);
    }
    out.rapid(job.a);
    Ok(())
}

/// K1: the profile without its tail never goes back into the material
/// (deeper along r) nor back against the cut (along z).
fn check_monotone(frame: &Frame, body: &[Seg], sx: f64, sz: f64) -> Result<(), NcError> {
    for s in body {
        if !s.curve.monotone(Axis::Z, sz, 0.0, 1.0) {
            return Err(turns_back(frame, s, Axis::Z, sz, 0.0, 1.0));
        }
        if !s.curve.monotone(Axis::R, -sx, 0.0, 1.0) {
            return Err(turns_back(frame, s, Axis::R, -sx, 0.0, 1.0));
        }
    }
    Ok(())
}

/// The first parameter of `c` where it is no longer deeper than the level.
fn first_hit(c: &Curve, level: f64, sx: f64) -> Option<f64> {
    let out = |s: f64| sx * (c.at(s).r - level) <= EPS;
    if out(0.0) {
        return Some(0.0);
    }
    let mut hits = c.roots(Axis::R, level);
    if out(1.0) {
        hits.push(1.0);
    }
    hits.into_iter().reduce(f64::min)
}

/// Step 2.2: walking P′ from B′, the Z where the level cut ends, `None`
/// when P′ never comes back to the level. The stretch walked before that
/// point must run with the cut and never go deeper (E4009, dialect.md §4.8).
fn level_end(
    frame: &Frame,
    rest: &[Seg],
    level: f64,
    sx: f64,
    sz: f64,
) -> Result<Option<f64>, NcError> {
    for s in rest {
        let hit = first_hit(&s.curve, level, sx);
        let upto = hit.unwrap_or(1.0);
        let c = &s.curve;
        if !c.monotone(Axis::Z, sz, 0.0, upto) {
            return Err(turns_back(frame, s, Axis::Z, sz, 0.0, upto));
        }
        if !c.monotone(Axis::R, -sx, 0.0, upto) {
            return Err(turns_back(frame, s, Axis::R, -sx, 0.0, upto));
        }
        if let Some(s) = hit {
            return Ok(Some(c.at(s).z));
        }
    }
    Ok(None)
}
