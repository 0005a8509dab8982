//! G71/G72 type II, profiles with pockets (cycles.md §15), in the G71
//! frame: depth along r (infeed), position along z (cut). G72 arrives
//! mirrored (§15.7).

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use super::turn::{turns_back, Frame};
use super::{tail_start, too_many, Job, Path, Seg};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::plan::curve::{sign, Axis, EPS, SLACK};

/// At most this many pockets (seed, cycles.md §15.1).
const MAX_POCKETS: usize = 10;

/// A piece deeper than a level by more than this is deep (§15.2).
const DEEP: f64 = 1e-9;

/// The trimmed contour K′r and its measures (§15.1).
struct Contour<'a> {
    segs: &'a [Seg],
    a1: Pt,
    sx: f64,
    sz: f64,
}

/// The part [s0, s1] of element `seg`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    seg: usize,
    s0: f64,
    s1: f64,
}

impl Contour<'_> {
    fn depth(&self, p: Pt) -> f64 {
        self.sx * (p.r - self.a1.r)
    }

    fn position(&self, p: Pt) -> f64 {
        self.sz * p.z
    }

    /// The r of depth d.
    fn level_r(&self, d: f64) -> f64 {
        self.a1.r + self.sx * d
    }

    fn at(&self, p: Piece, s: f64) -> Pt {
        self.segs[p.seg].curve.at(s)
    }

    fn deep(&self, p: Piece, level: f64) -> bool {
        self.depth(self.at(p, (p.s0 + p.s1) / 2.0)) > level + DEEP
    }

    /// The smallest depth over [s0, s1] of element `seg`.
    fn min_depth(&self, seg: usize, s0: f64, s1: f64) -> f64 {
        let (lo, hi) = self.segs[seg].curve.range(Axis::R, s0, s1);
        (self.sx * (lo - self.a1.r)).min(self.sx * (hi - self.a1.r))
    }

    /// The pieces cut where they cross depth `level`.
    fn cut(&self, pieces: &[Piece], level: f64) -> Vec<Piece> {
        let r = self.level_r(level);
        let mut out = Vec::with_capacity(pieces.len() + 2);
        for &p in pieces {
            let mut s0 = p.s0;
            for s in self.segs[p.seg].curve.roots(Axis::R, r) {
                if s > s0 + 1e-12 && s < p.s1 - 1e-12 {
                    out.push(Piece { s1: s, s0, ..p });
                    s0 = s;
                }
            }
            out.push(Piece { s0, ..p });
        }
        out
    }

    /// The intervals at a level: maximal runs of pieces deeper than it.
    fn intervals(&self, level: f64) -> Vec<Vec<Piece>> {
        let whole: Vec<Piece> = (0..self.segs.len())
            .map(|seg| Piece {
                seg,
                s0: 0.0,
                s1: 1.0,
            })
            .collect();
        let mut out: Vec<Vec<Piece>> = Vec::new();
        let mut open = false;
        for p in self.cut(&whole, level) {
            if !self.deep(p, level) {
                open = false;
            } else if open {
                if let Some(run) = out.last_mut() {
                    run.push(p);
                }
            } else {
                out.push(vec![p]);
                open = true;
            }
        }
        out
    }

    /// h of §15.4: the infimum of the depth over the points whose position
    /// lies strictly between `u1` and `u2` (+∞ when there is none).
    fn lowest_between(&self, u1: f64, u2: f64) -> f64 {
        let (lo, hi) = (u1.min(u2), u1.max(u2));
        let mut h = f64::INFINITY;
        for (i, seg) in self.segs.iter().enumerate() {
            let c = &seg.curve;
            let mut cuts = vec![0.0, 1.0];
            cuts.extend(c.roots(Axis::Z, self.sz * lo));
            cuts.extend(c.roots(Axis::Z, self.sz * hi));
            cuts.sort_by(f64::total_cmp);
            for w in cuts.windows(2) {
                let u = self.position(c.at((w[0] + w[1]) / 2.0));
                if u > lo + DEEP && u < hi - DEEP {
                    h = h.min(self.min_depth(i, w[0], w[1]));
                }
            }
        }
        h
    }
}

/// Runs the cycle from A to its return to A.
pub fn run(out: &mut Path, job: &Job) -> Result<(), NcError> {
    let Some(ns) = job.segs.first().filter(|s| s.ns) else {
        return fail(Alarm::BadRoughing, "the ns block makes no infeed move");
    };
    let a1 = job.a1;
    let sx = sign(ns.curve.end().r - a1.r);
    if sx == 0.0 {
        return fail(Alarm::BadRoughing, "the ns block makes no infeed move");
    }
    let keep = 1 + tail_start(&job.segs[1..], a1.r, sx);
    let trimmed = &job.segs[..keep];
    let cr = trimmed[keep - 1].curve.end();
    let sz = sign(cr.z - a1.z);
    if sz == 0.0 {
        return fail(
            Alarm::BadRoughing,
            "the profile makes no move along the cut",
        );
    }
    let k = Contour {
        segs: trimmed,
        a1,
        sx,
        sz,
    };
    let deepest = check(&k, &Frame::of(job, out.mirrored))?;
    too_many(deepest / job.dd)?;
    out.rapid(a1);
    let mut level = 1.0;
    while level * job.dd < deepest - EPS {
        pass(out, &k, (level - 1.0) * job.dd, level * job.dd, job.e);
        level += 1.0;
    }
    travel(out, &k, a1, job.e);
    allowance(out, &job.segs);
    if job.j1 {
        out.rapid(a1);
        allowance(out, &job.segs);
    }
    out.rapid(job.a);
    Ok(())
}

/// §15.1 checks before anything moves; the largest depth D.
fn check(k: &Contour, frame: &Frame) -> Result<f64, NcError> {
    let mut pockets = 0;
    let mut falling = false;
    let mut deepest: f64 = 0.0;
    for seg in k.segs {
        let c = &seg.curve;
        if !c.monotone(Axis::Z, k.sz, 0.0, 1.0) {
            return Err(turns_back(frame, seg, Axis::Z, k.sz, 0.0, 1.0));
        }
        let mut stops = vec![0.0];
        stops.extend(c.extremes(Axis::R));
        stops.push(1.0);
        for w in stops.windows(2) {
            let (d0, d1) = (k.depth(c.at(w[0])), k.depth(c.at(w[1])));
            deepest = deepest.max(d0).max(d1);
            // Only turns beyond the rounding of a tangent point count.
            if d1 - d0 < -SLACK {
                falling = true;
            } else if d1 - d0 > SLACK && falling {
                falling = false;
                pockets += 1;
            }
        }
    }
    if pockets > MAX_POCKETS {
        return fail(
            Alarm::BadRoughing,
            format!("the profile has {pockets} pockets; type II allows {MAX_POCKETS}"),
        );
    }
    Ok(deepest)
}

/// Pass between depths `top` and `bottom` (§15.3, §15.5 step 2).
fn pass(out: &mut Path, k: &Contour, top: f64, bottom: f64, e: f64) {
    for interval in k.intervals(top) {
        let pieces = k.cut(&interval, bottom);
        if !pieces.iter().any(|&p| k.deep(p, bottom)) {
            continue;
        }
        travel(out, k, k.at(pieces[0], pieces[0].s0), e);
        chain(out, k, &pieces, bottom);
        let end = out.pos();
        out.line(Pt::new(k.level_r(k.depth(end) - e), end.z - k.sz * e));
    }
}

/// Band pieces followed, runs of deep pieces cut straight along the level.
fn chain(out: &mut Path, k: &Contour, pieces: &[Piece], bottom: f64) {
    let mut i = 0;
    while let Some(&p) = pieces.get(i) {
        if k.deep(p, bottom) {
            let mut j = i;
            while pieces.get(j).is_some_and(|&q| k.deep(q, bottom)) {
                j += 1;
            }
            let last = pieces[j - 1];
            out.line(Pt::new(k.level_r(bottom), k.at(last, last.s1).z));
            i = j;
        } else {
            let seg = &k.segs[p.seg];
            out.piece(&seg.curve, p.s0, p.s1, seg.ns && seg.rapid);
            i += 1;
        }
    }
}

/// §15.4: up to the safe depth τ, along the cut, down to S.
fn travel(out: &mut Path, k: &Contour, s: Pt, e: f64) {
    let t = out.pos();
    let h = k.lowest_between(k.position(t), k.position(s));
    let r = k.level_r(k.depth(t).min(h - e));
    out.rapid(Pt::new(r, t.z));
    out.rapid(Pt::new(r, s.z));
    out.rapid(s);
}

/// §15.5 step 3: K′ from A′ to C′, its tail included.
fn allowance(out: &mut Path, segs: &[Seg]) {
    for s in segs {
        out.follow(&s.curve, s.ns && s.rapid);
    }
}
