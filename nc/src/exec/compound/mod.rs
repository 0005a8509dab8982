//! The compound cycles G70, G71, G72, G73 over an ns…nf profile
//! (cycles.md §5–§8, §15).
//!
//! The compiler (or the VM) hands the profile blocks over with
//! `Nc::push_profile` before the cycle block runs; errors about one of them
//! carry its tag. G71/G72 compute in a frame where the infeed runs along r
//! and the cut along z: G72 is G71 on the profile mirrored at r = z.

use alloc::format;
use alloc::vec::Vec;

#[cfg(test)]
mod conic_tests;
mod finish;
mod out;
#[cfg(test)]
mod tests;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::OneShot;
use crate::base::point::Pt;
use crate::block::{round_half_away, Parsed};
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::curve::swap;
use crate::plan::profile::{self, Kind};
use crate::plan::roughing::{pattern, pockets, rough, too_many, Job, Path};

/// First-block values of G71 (U Δd, R e) or G72 (W Δd, R e).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stock {
    pub depth: f64,
    pub retract: f64,
}

/// First-block values of G73: relief Δi (radius), Δk, pass count d.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Relief {
    pub di: f64,
    pub dk: f64,
    pub passes: f64,
}

/// Modal first-block values of G71/G72/G73 (cycles.md §0): each stays until
/// the next first block of the same code changes it.
#[derive(Debug, Clone, PartialEq)]
pub struct CompoundState {
    pub g71: Stock,
    pub g72: Stock,
    pub g73: Relief,
}

impl Default for CompoundState {
    /// Before any first block: Δd = e = 0 (the cycle then alarms), and
    /// Δi = Δk = 0 with d = 1 for G73.
    fn default() -> Self {
        CompoundState {
            g71: Stock::default(),
            g72: Stock::default(),
            g73: Relief {
                di: 0.0,
                dk: 0.0,
                passes: 1.0,
            },
        }
    }
}

/// A G70–G73 block; `nc.profile` holds the ns…nf blocks for a cycle block.
pub fn run(
    nc: &mut Nc,
    code: OneShot,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let blocks = core::mem::take(&mut nc.profile);
    let (has_p, has_q) = (p.has(b'P'), p.has(b'Q'));
    if has_p != has_q {
        return fail(Alarm::BadProfile, "the cycle needs both P (ns) and Q (nf)");
    }
    if !has_p {
        return if code == OneShot::Finish {
            fail(Alarm::MissingWord, "G70 needs P (ns) and Q (nf)")
        } else {
            first_block(nc, code, p)
        };
    }
    out.moved = true;
    match code {
        OneShot::Finish => finish::run(nc, &blocks, sink),
        OneShot::RoughTurn | OneShot::RoughFace => {
            stock_removal(nc, code == OneShot::RoughFace, p, &blocks, sink)
        }
        _ => pattern_repeat(nc, p, &blocks, sink),
    }
}

/// `G71 U R`, `G72 W R`, `G73 U W R`: words left out keep their value.
fn first_block(nc: &mut Nc, code: OneShot, p: &Parsed) -> Result<(), NcError> {
    let r = nc.len_of(p, b'R');
    let turning = code == OneShot::RoughTurn;
    match code {
        OneShot::RoughTurn | OneShot::RoughFace => {
            let depth = nc.len_of(p, if turning { b'U' } else { b'W' });
            let st = if turning {
                &mut nc.st.compound.g71
            } else {
                &mut nc.st.compound.g72
            };
            st.depth = depth.unwrap_or(st.depth);
            st.retract = r.unwrap_or(st.retract);
        }
        _ => {
            let (di, dk) = (nc.len_of(p, b'U'), nc.len_of(p, b'W'));
            let d = count(p, b'R')?;
            let st = &mut nc.st.compound.g73;
            st.di = di.unwrap_or(st.di);
            st.dk = dk.unwrap_or(st.dk);
            st.passes = d.unwrap_or(st.passes);
        }
    }
    Ok(())
}

/// An integer-only word (dialect.md §1.9): E1009 with a decimal point,
/// rounded half away from zero when computed.
fn count(p: &Parsed, letter: u8) -> Result<Option<f64>, NcError> {
    let Some(w) = p.word(letter) else {
        return Ok(None);
    };
    if w.literal_with_point() {
        let msg = format!(
            "{} takes an integer here; a decimal point is not allowed",
            letter as char
        );
        return Err(NcError::new(Alarm::DecimalPointNotAllowed, msg).on_addr(w.addr));
    }
    Ok(Some(round_half_away(w.value)))
}

/// The finishing allowance of a cycle block: U is an X value (a
/// diameter, unless in radius programming).
fn allowance(nc: &Nc, p: &Parsed) -> Pt {
    Pt::new(
        nc.radial_of(p, b'U').unwrap_or(0.0),
        nc.len_of(p, b'W').unwrap_or(0.0),
    )
}

/// G71 (`facing` false) and G72, types I and II.
fn stock_removal(
    nc: &mut Nc,
    facing: bool,
    p: &Parsed,
    blocks: &[(Vec<crate::base::words::Word>, u32)],
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let kind = profile::ns_kind(&nc.reader(), blocks, facing)?;
    let first = if facing {
        nc.st.compound.g72
    } else {
        nc.st.compound.g71
    };
    // The one-block Fanuc form gives Δd as D, with the machine's retract
    // (dialect.md §4.12).
    let (dd, e) = match nc.len_of(p, b'D') {
        Some(d) => (d, nc.machine.cycles.g71_retract_mm),
        None => (first.depth, first.retract),
    };
    if dd < 0.0 {
        let msg = format!(
            "the depth of cut Δd is negative ({}): give a positive one (G71 U… R… / G72 W… R…)",
            crate::base::event::Num(dd)
        );
        return fail(Alarm::BadRoughing, msg);
    }
    if dd == 0.0 || dd.is_nan() {
        return fail(
            Alarm::BadRoughing,
            "the depth of cut Δd is 0: give it in the first block (G71 U… R… / G72 W… R…)",
        );
    }
    let k1 = count(p, b'K')? == Some(1.0);
    let j1 = count(p, b'J')? == Some(1.0);
    let segs = profile::build(&nc.reader(), blocks)?;
    let a = nc.st.pos;
    let shift = allowance(nc, p);
    let frame = |q: Pt| if facing { swap(q) } else { q };
    let segs = segs
        .into_iter()
        .map(|s| {
            s.map(|c| {
                let c = c.shifted(shift);
                if facing {
                    c.swapped()
                } else {
                    c
                }
            })
        })
        .collect();
    let job = Job {
        a: frame(a),
        a1: frame(a.add(shift)),
        segs,
        dd,
        e,
        k1,
        j1,
    };
    // The legs made before an alarm are printed, as a control would
    // have moved them, then the alarm.
    let mut path = Path::new(nc.st.pos, facing);
    let done = match kind {
        Kind::Plain => rough::run(&mut path, &job),
        Kind::Pockets => pockets::run(&mut path, &job),
    };
    out::print(nc, sink, path.steps())?;
    done
}

/// G73.
fn pattern_repeat(
    nc: &mut Nc,
    p: &Parsed,
    blocks: &[(Vec<crate::base::words::Word>, u32)],
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let relief = nc.st.compound.g73;
    if relief.passes < 1.0 || relief.passes.is_nan() {
        return fail(
            Alarm::BadRoughing,
            format!("G73 needs at least one pass (R{})", relief.passes),
        );
    }
    too_many(relief.passes)?;
    let segs = profile::build(&nc.reader(), blocks)?;
    let pat = pattern::Pattern {
        di: relief.di,
        dk: relief.dk,
        passes: relief.passes as u32,
        allowance: allowance(nc, p),
    };
    let mut path = Path::new(nc.st.pos, false);
    pattern::run(&mut path, &segs, &pat);
    out::print(nc, sink, path.steps())?;
    Ok(())
}
