//! Angle programming (drawing-dimension input) with `Q` or `,A`
//! (dialect.md §5.2, §5.3): the line's angle counter-clockwise from +Z in
//! the ZX view, slope Δr/ΔZ = tan Q.

use alloc::format;

use super::elem::{cross, heading};
use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;
use crate::base::words::COMMA_A;
use crate::block::Parsed;

/// Angles within this many degrees of the forbidden ones are E4008.
const LIMIT_DEG: f64 = 1.0;

/// The block's angle in degrees, normalised to 0…360: `Q` in 0.001°,
/// `,A` in degrees at face value (block.rs already rejects both at once).
pub fn angle_of(p: &Parsed) -> Option<f64> {
    let deg = p
        .get(b'Q')
        .map(|q| q * 0.001)
        .or_else(|| p.word_at(COMMA_A).map(|w| w.value))?;
    Some(crate::base::geom::rem_euclid(deg, 360.0))
}

/// How far `deg` is from the nearest multiple of 180° (a line's angle
/// and its reverse are the same line).
fn off_axis(deg: f64) -> f64 {
    let m = crate::base::geom::rem_euclid(deg, 180.0);
    m.min(180.0 - m)
}

/// `X(U) Q`: the point with radius `r` on the line through `from` at
/// `deg`. Near-horizontal lines never reach another X: E4008.
pub fn end_at_r(from: Pt, deg: f64, r: f64) -> Result<Pt, NcError> {
    if off_axis(deg) <= LIMIT_DEG {
        return fail(
            Alarm::BadAngle,
            format!("angle {deg:.3}° is within 1° of the Z axis: it cannot end at a given X"),
        );
    }
    let t = heading(deg);
    Ok(Pt::new(r, from.z + (r - from.r) * t.z / t.r))
}

/// `Z(W) Q`: the point with this Z on the line through `from` at `deg`.
pub fn end_at_z(from: Pt, deg: f64, z: f64) -> Result<Pt, NcError> {
    if (off_axis(deg) - 90.0).abs() <= LIMIT_DEG {
        return fail(
            Alarm::BadAngle,
            format!("angle {deg:.3}° is within 1° of the X axis: it cannot end at a given Z"),
        );
    }
    let t = heading(deg);
    Ok(Pt::new(from.r + (z - from.z) * t.r / t.z, z))
}

/// The two-block form: where the line through `from` at `q1` meets the
/// line through `to` at `q2`. Lines within 1° of each other: E4008.
pub fn intersection(from: Pt, q1: f64, to: Pt, q2: f64) -> Result<Pt, NcError> {
    let diff = crate::base::geom::rem_euclid(q1 - q2, 180.0);
    if diff.min(180.0 - diff) < LIMIT_DEG {
        return fail(
            Alarm::BadAngle,
            format!(
                "the two lines of angle programming ({q1:.3}° and {q2:.3}°) differ by less than 1°"
            ),
        );
    }
    let (t1, t2) = (heading(q1), heading(q2));
    // from + λ·t1 = to + μ·t2.
    let lambda = cross(to.sub(from), t2) / cross(t1, t2);
    Ok(Pt::new(from.r + lambda * t1.r, from.z + lambda * t1.z))
}
