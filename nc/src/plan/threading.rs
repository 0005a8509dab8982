//! The multiple threading cycles G76 (cycles.md §11, §12) and G78 (§19)
//! as paths: the depths of the passes, flank or alternating infeed,
//! run-in, pull-out and starts. The executor (`exec::cycles`) keeps the
//! first blocks' words, reads the second block's and prints.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::plan::legs::{self, sign, thread, Leg, PullOut, EPS, MAX_LEGS};

/// No thread cycle cuts more passes than this.
const MAX_PASSES: usize = 100_000;

/// The thread of a second block: the start A, the end D = (X, Z) at full
/// depth, the taper i (radius, start minus end), the height k.
#[derive(Debug, Clone, Copy)]
pub struct Thread {
    pub a: Pt,
    pub end: Pt,
    pub taper: f64,
    pub height: f64,
    /// First depth Δd, and the lead.
    pub first: f64,
    pub lead: f64,
}

impl Thread {
    pub fn sz(&self) -> f64 {
        sign(self.end.z - self.a.z)
    }

    /// +1 for an outside thread (A above the root), −1 inside.
    pub fn so(&self) -> f64 {
        sign(self.a.r - self.end.r)
    }

    /// The radius of a pass at depth δ at z: the root line moved out by
    /// k − δ (§11).
    pub fn r_at(&self, depth: f64, z: f64) -> f64 {
        let span = self.a.z - self.end.z;
        let t = if span.abs() > EPS {
            (z - self.end.z) / span
        } else {
            0.0
        };
        self.end.r + self.taper * t + self.so() * (self.height - depth)
    }

    pub fn at(&self, depth: f64, z: f64) -> Pt {
        Pt::new(self.r_at(depth, z), z)
    }
}

/// The roughing depths (§11, §19.1): decreasing Δd·√n or equal steps of
/// Δd, each at least Δdmin deeper than the last; the pass that would reach
/// k − d is cut at k − d and ends the roughing.
pub fn rough_depths(
    t: &Thread,
    dmin: f64,
    allowance: f64,
    decreasing: bool,
) -> Result<Vec<f64>, NcError> {
    let last = t.height - allowance;
    let mut out = Vec::new();
    if last <= EPS {
        return Ok(out);
    }
    let mut previous = 0.0;
    for n in 1u32.. {
        if n as usize > MAX_PASSES {
            return fail(
                Alarm::BadThread,
                "the first depth Δd is too small: the thread would take too many passes",
            );
        }
        let mut depth = if decreasing {
            t.first * libm::sqrt(f64::from(n))
        } else {
            previous + t.first
        };
        if depth - previous < dmin {
            depth = previous + dmin;
        }
        if depth >= last - EPS {
            out.push(last);
            break;
        }
        out.push(depth);
        previous = depth;
    }
    Ok(out)
}

/// The finishing passes at full depth k: the first removes d, the others
/// nothing.
pub fn finish(depths: &mut Vec<f64>, height: f64, passes: i64) -> Result<(), NcError> {
    let n = usize::try_from(passes).unwrap_or(0);
    if n > MAX_PASSES {
        return fail(
            Alarm::BadThread,
            format!("{passes} finishing passes are too many"),
        );
    }
    depths.extend(core::iter::repeat_n(height, n));
    Ok(())
}

/// k and Δd of a second block must be positive (§11, §19).
pub fn check_depths(k: f64, dd: f64) -> Result<(), NcError> {
    if k <= 0.0 || dd <= 0.0 {
        return fail(
            Alarm::BadThread,
            format!("thread height k ({k:.4}) and first depth Δd ({dd:.4}) must be positive"),
        );
    }
    Ok(())
}

/// How the passes of a thread are cut: roughing to the finishing
/// allowance d by decreasing (Δd·√n) or equal depths at least Δdmin apart,
/// then m finishing passes, along a flank of angle a; the pull-out at the
/// end of each pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Passes {
    pub dmin: f64,
    pub allowance: f64,
    pub decreasing: bool,
    pub finishing: i64,
    /// The thread angle a, degrees.
    pub angle: f64,
    pub pull: Option<PullOut>,
}

impl Passes {
    /// All the depths, roughing then finishing.
    fn depths(&self, t: &Thread) -> Result<Vec<f64>, NcError> {
        let mut depths = rough_depths(t, self.dmin, self.allowance, self.decreasing)?;
        finish(&mut depths, t.height, self.finishing)?;
        Ok(depths)
    }

    /// tan(a/2): how far along Z a pass starts per unit of depth.
    fn tan(&self) -> f64 {
        libm::tan((self.angle / 2.0).to_radians())
    }
}

/// The G76 path (§11): every pass starts on the leading flank.
pub fn g76_path(t: &Thread, passes: &Passes) -> Result<Vec<Leg>, NcError> {
    let depths = passes.depths(t)?;
    let tan = passes.tan();
    let mut path = Vec::new();
    for (i, depth) in depths.into_iter().enumerate() {
        let z = t.a.z + t.sz() * depth * tan;
        check_start("G76", t, i + 1, depth, z)?;
        g76_pass(t, depth, z, passes.pull, &mut path)?;
    }
    Ok(path)
}

/// G78's infeed (§19.2): r (0 radial, 1 left flank, 2 right flank, 3
/// alternating), the number of starts L and the run-in E.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Infeed {
    pub cut_in: i64,
    pub starts: i64,
    pub run_in: f64,
}

/// The G78 path (§19): each depth once per start.
pub fn g78_path(t: &Thread, passes: &Passes, infeed: &Infeed) -> Result<Vec<Leg>, NcError> {
    let depths = passes.depths(t)?;
    let tan = passes.tan();
    let mut path = Vec::new();
    for (i, &depth) in depths.iter().enumerate() {
        let z = t.a.z + cut_in_shift(infeed.cut_in, i + 1, depth * tan);
        check_start("G78", t, i + 1, depth, z)?;
        for j in 0..infeed.starts {
            if path.len() > MAX_LEGS {
                return fail(
                    Alarm::BadThread,
                    format!("G78 L{}: too many starts", infeed.starts),
                );
            }
            let q = j as f64 * 360.0 / infeed.starts as f64;
            g78_pass(t, depth, z, q, infeed.run_in, passes.pull, &mut path)?;
        }
    }
    Ok(path)
}

/// Pass `n` at `depth` must start short of the thread's end: a flank
/// infeed shifts the start along Z by δ·tan(a/2), and on a thread shorter
/// than that shift the pass would run backwards along the helix (E4010:
/// a thread that cannot be cut, dialect.md §8.3).
fn check_start(cycle: &str, t: &Thread, n: usize, depth: f64, z: f64) -> Result<(), NcError> {
    if (t.end.z - z) * t.sz() > EPS {
        return Ok(());
    }
    if t.sz() == 0.0 {
        let msg = format!(
            "{cycle}: the thread has no length along Z (it starts and ends at Z{:.4})",
            t.a.z
        );
        return fail(Alarm::BadThread, msg);
    }
    fail(
        Alarm::BadThread,
        format!(
            "{cycle}: the flank infeed starts pass {n} (depth {depth:.4}) at Z{z:.4}, at or past the thread's end Z{:.4}; lengthen the thread or lower the angle",
            t.end.z
        ),
    )
}

/// One G76 pass at `depth`, starting at `z` (§11 "One pass").
fn g76_pass(
    t: &Thread,
    depth: f64,
    z: f64,
    pull: Option<PullOut>,
    out: &mut Vec<Leg>,
) -> Result<(), NcError> {
    let start = t.at(depth, z);
    out.push(Leg::Rapid(start));
    legs::pass(start, t.at(depth, t.end.z), t.lead, 0.0, pull, t.so(), out)?;
    out.push(Leg::Rapid(Pt::new(t.a.r, t.end.z)));
    out.push(Leg::Rapid(t.a));
    Ok(())
}

/// The start shift of pass n (1-based) at depth δ, `flank` = δ·tan(a/2):
/// r = 1 along the left (−Z side) flank, 2 the right, 3 alternating
/// (§19.2).
fn cut_in_shift(cut_in: i64, n: usize, flank: f64) -> f64 {
    match cut_in {
        1 => flank,
        2 => -flank,
        3 if n % 2 == 1 => flank,
        3 => -flank,
        _ => 0.0,
    }
}

/// One G78 pass at `depth` from `z` for one start (§19.3): with a run-in E
/// the tool starts E further out and enters at 45° over E along Z.
fn g78_pass(
    t: &Thread,
    depth: f64,
    z: f64,
    q: f64,
    run_in: f64,
    pull: Option<PullOut>,
    out: &mut Vec<Leg>,
) -> Result<(), NcError> {
    let end = t.at(depth, t.end.z);
    let length = (t.end.z - z).abs();
    let entry = run_in.max(0.0) + pull.map_or(0.0, |p| p.z);
    if run_in > 0.0 && entry >= length - EPS {
        return fail(
            Alarm::BadThread,
            format!("G78: the run-in and the pull-out ({entry:.4} mm) are not shorter than the pass ({length:.4} mm)"),
        );
    }
    let mut q = q;
    let mut from = t.at(depth, z);
    if run_in > 0.0 {
        out.push(Leg::Rapid(Pt::new(from.r + t.so() * run_in, z)));
        let z1 = z + t.sz() * run_in;
        from = t.at(depth, z1);
        out.push(thread(from, t.lead, q));
        q = 0.0;
    } else {
        out.push(Leg::Rapid(from));
    }
    legs::pass(from, end, t.lead, q, pull, t.so(), out)?;
    out.push(Leg::Rapid(Pt::new(t.a.r, t.end.z)));
    out.push(Leg::Rapid(t.a));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An outside thread from A (r 16, z 5) to the root r 14 at z -20:
    /// height 1, first depth 0.5, lead 2.
    fn outside() -> Thread {
        Thread {
            a: Pt::new(16.0, 5.0),
            end: Pt::new(14.0, -20.0),
            taper: 0.0,
            height: 1.0,
            first: 0.5,
            lead: 2.0,
        }
    }

    fn passes(angle: f64) -> Passes {
        Passes {
            dmin: 0.0,
            allowance: 0.0,
            decreasing: true,
            finishing: 1,
            angle,
            pull: None,
        }
    }

    #[test]
    fn g76_depths_grow_as_the_square_root_then_finish() {
        // Depths 0.5·√n: 0.5, 0.707, 0.866, then 1.0 reaches k and ends
        // the roughing; one finishing pass at k. Each pass: rapid to the
        // start at r = 14 + (k − δ), thread to z -20, out, back to A.
        let path = g76_path(&outside(), &passes(0.0)).unwrap();
        assert_eq!(path.len(), 5 * 4);
        assert_eq!(path[0], Leg::Rapid(Pt::new(14.5, 5.0)));
        assert_eq!(path[1], thread(Pt::new(14.5, -20.0), 2.0, 0.0));
        assert_eq!(path[2], Leg::Rapid(Pt::new(16.0, -20.0)));
        assert_eq!(path[3], Leg::Rapid(Pt::new(16.0, 5.0)));
        let Leg::Rapid(second) = path[4] else {
            panic!("{:?}", path[4])
        };
        assert!((second.r - (15.0 - 0.5 * libm::sqrt(2.0))).abs() < 1e-12);
        assert_eq!(path[16], Leg::Rapid(Pt::new(14.0, 5.0)));
        assert_eq!(path[12], path[16]);
    }

    #[test]
    fn a_60_degree_thread_starts_each_pass_on_the_flank() {
        // a = 60°: the pass at depth 0.5 starts 0.5·tan 30° further along
        // the cut (towards -Z) than A.
        let path = g76_path(&outside(), &passes(60.0)).unwrap();
        let Leg::Rapid(start) = path[0] else {
            panic!("{:?}", path[0])
        };
        let tan30 = 1.0 / libm::sqrt(3.0);
        assert!((start.z - (5.0 - 0.5 * tan30)).abs() < 1e-12);
        assert!((start.r - 14.5).abs() < 1e-12);
    }

    #[test]
    fn a_thread_shorter_than_the_flank_shift_is_e4010() {
        // A 1 mm thread (Z5 to Z4), k = 2, Δd = 1.5, a = 60°: pass 1 at
        // δ 1.5 starts at 5 − 1.5·tan 30° = 4.1340, short of Z4; pass 2 at
        // δ = k = 2 (1.5·√2 > 2) would start at 5 − 2·tan 30° = 3.8453,
        // past the end, and cut back towards +Z.
        let t = Thread {
            a: Pt::new(15.0, 5.0),
            end: Pt::new(13.0, 4.0),
            height: 2.0,
            first: 1.5,
            lead: 1.0,
            ..outside()
        };
        let err = g76_path(&t, &passes(60.0)).unwrap_err();
        assert_eq!(err.code, Alarm::BadThread as u16);
        assert!(
            err.message.contains("pass 2 (depth 2.0000) at Z3.8453"),
            "{}",
            err.message
        );
        // Radial infeed (a = 0) cuts the same thread.
        assert!(g76_path(&t, &passes(0.0)).is_ok());
        // A thread with no length is refused at any angle.
        let flat = Thread {
            end: Pt::new(13.0, 5.0),
            ..t
        };
        let err = g76_path(&flat, &passes(0.0)).unwrap_err();
        assert!(err.message.contains("no length along Z"), "{}", err.message);
    }

    #[test]
    fn g78_alternates_flanks_and_spreads_the_starts() {
        // Cut-in 3 alternates: pass 1 shifted by +δ·tan, pass 2 by −δ·tan;
        // two starts per depth at 0° and 180°.
        let infeed = Infeed {
            cut_in: 3,
            starts: 2,
            run_in: 0.0,
        };
        let path = g78_path(&outside(), &passes(60.0), &infeed).unwrap();
        assert_eq!(path.len(), 5 * 2 * 4);
        let tan30 = 1.0 / libm::sqrt(3.0);
        let Leg::Rapid(p1) = path[0] else { panic!() };
        let Leg::Rapid(p2) = path[8] else { panic!() };
        assert!((p1.z - (5.0 + 0.5 * tan30)).abs() < 1e-12);
        assert!((p2.z - (5.0 - 0.5 * libm::sqrt(2.0) * tan30)).abs() < 1e-12);
        let Leg::Thread { q, .. } = path[5] else {
            panic!()
        };
        assert_eq!(q, Some(180.0));
    }
}
