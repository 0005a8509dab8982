//! Plane geometry of arcs in the ZX plane (z horizontal, r up; G02 is
//! clockwise in this view, dialect.md §2.4).

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::point::Pt;

/// `a` modulo `m` in `[0, |m|)`, as `f64::rem_euclid` (which `core` lacks).
pub fn rem_euclid(a: f64, m: f64) -> f64 {
    let r = a % m;
    if r < 0.0 {
        r + m.abs()
    } else {
        r
    }
}

/// `floor`, by an integer cast where that is exact: `libm::floor` is a
/// software routine on baseline x86-64, and the kernel and the planner call
/// this for every block. From 2^52 on every double is an integer already;
/// NaN and the infinities fail the range test and pass through. An integer
/// (−0 included) is returned as it is, so the sign of a zero survives.
pub fn floor(v: f64) -> f64 {
    const EXACT: f64 = 4_503_599_627_370_496.0; // 2^52
    if !(v > -EXACT && v < EXACT) {
        return v;
    }
    let t = (v as i64) as f64;
    if t == v {
        v
    } else if t > v {
        t - 1.0
    } else {
        t
    }
}

/// `floor` of a value ≥ 0 (or NaN): one comparison less than [`floor`],
/// for the rounding of every G and M word and the planner's period counts.
#[inline]
pub fn floor_non_negative(v: f64) -> f64 {
    if v < 4_503_599_627_370_496.0 {
        (v as i64) as f64
    } else {
        v
    }
}

/// Half a chord may exceed |R| by this much and still be a half circle.
const RADIUS_SLACK_MM: f64 = 0.001;

/// The centre of an arc from `from` to `to` with signed radius `r`
/// (R > 0: the arc of at most 180°, R < 0: the larger one). `None` for a
/// 0° arc (end = start), which is no move.
pub fn centre_from_radius(from: Pt, to: Pt, r: f64, cw: bool) -> Result<Option<Pt>, NcError> {
    let (dz, dr) = (to.z - from.z, to.r - from.r);
    // (A plain square root: lengths in mm cannot overflow, and this runs
    // for every R arc, where `libm::hypot`'s scaling costs most.)
    let chord = libm::sqrt(dz * dz + dr * dr);
    if chord < 1e-9 {
        return Ok(None);
    }
    let half = chord / 2.0;
    if half > r.abs() + RADIUS_SLACK_MM {
        return fail(
            Alarm::ArcRadiusTooSmall,
            format!(
                "arc radius {:.4} is too small: the end point is {:.4} mm away (half the chord exceeds |R|)",
                r.abs(),
                chord
            ),
        );
    }
    let h = libm::sqrt((r * r - half * half).max(0.0));
    // Unit chord direction (z, r) and its right-hand normal (r, -z): a
    // clockwise minor arc has its centre on the right of the chord.
    let (uz, ur) = (dz / chord, dr / chord);
    let (nz, nr) = (ur, -uz);
    let side = if cw == (r > 0.0) { 1.0 } else { -1.0 };
    let mid = Pt::new((from.r + to.r) / 2.0, (from.z + to.z) / 2.0);
    Ok(Some(Pt::new(mid.r + side * h * nr, mid.z + side * h * nz)))
}

/// E4002: with I/K the end point must lie on the circle within the
/// tolerance.
pub fn check_on_circle(from: Pt, to: Pt, centre: Pt, tolerance: f64) -> Result<(), NcError> {
    let (r0, r1) = (from.dist(centre), to.dist(centre));
    if (r0 - r1).abs() > tolerance {
        return fail(
            Alarm::ArcEndOffCircle,
            format!(
                "the end point is off the arc: its distance from the centre is {r1:.4}, the start's {r0:.4}"
            ),
        );
    }
    Ok(())
}

/// The circle through three points and whether start → mid → end runs
/// clockwise (G05).
pub fn circle_through(a: Pt, b: Pt, c: Pt) -> Result<(Pt, bool), NcError> {
    if a.dist(c) < 1e-9 {
        return fail(
            Alarm::ThreePointArc,
            "G05: the end point equals the start point",
        );
    }
    // Cross product of (b - a) × (c - a) in (z, r): negative is clockwise.
    let cross = (b.z - a.z) * (c.r - a.r) - (b.r - a.r) * (c.z - a.z);
    if cross.abs() < 1e-9 {
        return fail(
            Alarm::ThreePointArc,
            "G05: the three points lie on one line",
        );
    }
    let d = 2.0 * cross;
    let (sa, sb, sc) = (
        a.z * a.z + a.r * a.r,
        b.z * b.z + b.r * b.r,
        c.z * c.z + c.r * c.r,
    );
    let z = (sa * (b.r - c.r) + sb * (c.r - a.r) + sc * (a.r - b.r)) / d;
    let r = (sa * (c.z - b.z) + sb * (a.z - c.z) + sc * (b.z - a.z)) / d;
    Ok((Pt::new(r, z), cross < 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Pt, r: f64, z: f64) -> bool {
        (a.r - r).abs() < 1e-4 && (a.z - z).abs() < 1e-4
    }

    /// The cast-based floor gives `libm::floor`'s bits for integers and
    /// halves, both zeros, values near 2^52 and 2^63, the infinities, NaN
    /// and a spread of generated values of every magnitude.
    #[test]
    fn floor_matches_libm_bit_for_bit() {
        let mut values = alloc::vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            2.5,
            -2.5,
            1e-300,
            -1e-300,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.3e18,
            -9.3e18,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut x: u64 = 1;
        for _ in 0..20_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let mantissa = (x >> 11) as f64 / (1u64 << 53) as f64;
            let exp = ((x >> 3) % 140) as i32 - 70;
            let sign = if x & 1 == 0 { 1.0 } else { -1.0 };
            values.push(sign * mantissa * libm::pow(2.0, exp as f64));
        }
        for &v in &values {
            assert_eq!(floor(v).to_bits(), libm::floor(v).to_bits(), "{v:e}");
        }
        assert!(floor(f64::NAN).is_nan());
        for v in values.iter().filter(|v| **v >= 0.0) {
            assert_eq!(floor_non_negative(*v), libm::floor(*v), "{v:e}");
        }
        assert!(floor_non_negative(f64::NAN).is_nan());
    }

    #[test]
    fn radius_centres_match_the_hand_checks() {
        // arc_r_form: G03 X30 Z-5 R5 from X20 Z0 → centre r10 z-5.
        let c = centre_from_radius(Pt::new(10.0, 0.0), Pt::new(15.0, -5.0), 5.0, false).unwrap();
        assert!(close(c.unwrap(), 10.0, -5.0));
        // G02 X40 Z-20 R5 from X30 Z-15 → centre r20 z-15.
        let c = centre_from_radius(Pt::new(15.0, -15.0), Pt::new(20.0, -20.0), 5.0, true).unwrap();
        assert!(close(c.unwrap(), 20.0, -15.0));
        // G03 X30 Z-40 R10 from X40 Z-30 → r 10.0838 z -31.2919.
        let c =
            centre_from_radius(Pt::new(20.0, -30.0), Pt::new(15.0, -40.0), 10.0, false).unwrap();
        assert!(close(c.unwrap(), 10.0838, -31.2919));
    }

    #[test]
    fn negative_radius_takes_the_other_centre() {
        let a = centre_from_radius(Pt::new(0.0, 0.0), Pt::new(0.0, -10.0), 10.0, true)
            .unwrap()
            .unwrap();
        let b = centre_from_radius(Pt::new(0.0, 0.0), Pt::new(0.0, -10.0), -10.0, true)
            .unwrap()
            .unwrap();
        assert!((a.r + b.r).abs() < 1e-9 && (a.z - b.z).abs() < 1e-9);
    }

    #[test]
    fn too_small_a_radius_is_e4001() {
        let e = centre_from_radius(Pt::new(0.0, 0.0), Pt::new(0.0, -10.0), 4.0, true).unwrap_err();
        assert_eq!(e.code, 4001);
        // Within 0.001 mm it is a half circle.
        assert!(centre_from_radius(Pt::new(0.0, 0.0), Pt::new(0.0, -10.0), 4.9995, true).is_ok());
    }

    #[test]
    fn three_points_give_centre_and_direction() {
        // (z,r): (0,0) → (5,5) → (10,0): over the top, clockwise in ZX.
        let (c, cw) =
            circle_through(Pt::new(0.0, 0.0), Pt::new(5.0, 5.0), Pt::new(0.0, 10.0)).unwrap();
        assert!(close(c, 0.0, 5.0));
        assert!(cw);
        assert_eq!(
            circle_through(Pt::new(0.0, 0.0), Pt::new(0.0, 5.0), Pt::new(0.0, 10.0))
                .unwrap_err()
                .code,
            4004
        );
    }
}

/// One element of a contour: the geometry a block moves along. It is the
/// one element type of the kernel and the runtime: the planners' `Curve`
/// (`plan::curve`) is an element with its angles worked out once, the
/// runtime's `Curve` (`runtime::geom`) its interpolation form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Element {
    Line {
        from: Pt,
        to: Pt,
    },
    Arc {
        from: Pt,
        to: Pt,
        centre: Pt,
        cw: bool,
    },
}

impl Element {
    pub fn start(&self) -> Pt {
        match *self {
            Element::Line { from, .. } | Element::Arc { from, .. } => from,
        }
    }

    pub fn end(&self) -> Pt {
        match *self {
            Element::Line { to, .. } | Element::Arc { to, .. } => to,
        }
    }

    /// The same element moved by `d`, end points and centre alike.
    pub fn shifted(&self, d: Pt) -> Element {
        match *self {
            Element::Line { from, to } => Element::Line {
                from: from.add(d),
                to: to.add(d),
            },
            Element::Arc {
                from,
                to,
                centre,
                cw,
            } => Element::Arc {
                from: from.add(d),
                to: to.add(d),
                centre: centre.add(d),
                cw,
            },
        }
    }
}
