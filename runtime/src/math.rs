//! Plane vectors and the few functions the runtime needs, through `libm`
//! so that the `no_std` core computes the same bits on every host.

/// A point or vector of the ZX plane in slide coordinates: the kernel's
/// point type ([`nc::point::Pt`]), so positions cross between the kernel
/// and the runtime unconverted.
pub type V2 = nc::point::Pt;

/// `v > 0`, false for NaN (guards against bad input read as "not positive").
#[inline]
pub fn is_pos(v: f64) -> bool {
    v > 0.0
}

/// Square root (`libm`, the same on every host).
pub fn sqrt(v: f64) -> f64 {
    libm::sqrt(v)
}

/// π.
pub const PI: f64 = core::f64::consts::PI;
/// 2π.
pub const TAU: f64 = core::f64::consts::TAU;

pub use nc::geom::floor;

/// `(sin a, cos a)` with one argument reduction: the interpolator turns
/// every arc set point by an angle. The same bits as `libm::sin` and
/// `libm::cos` (a test checks).
#[inline]
pub fn sin_cos(a: f64) -> (f64, f64) {
    libm::sincos(a)
}

/// `a` modulo `m` in [0, m) (`f64::rem_euclid` is not in `core`).
pub fn rem_euclid(a: f64, m: f64) -> f64 {
    let r = a - m * floor(a / m);
    if r >= m || r < 0.0 {
        0.0
    } else {
        r
    }
}

/// `a` brought into (−π, π].
pub fn wrap_pi(a: f64) -> f64 {
    let mut a = libm::remainder(a, TAU);
    if a <= -PI {
        a += TAU;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sin_cos` gives `libm::sin`'s and `libm::cos`'s bits: tiny angles
    /// (both sides of every small-angle shortcut), the interpolator's range
    /// and beyond, multiples of π/4, ±0, the infinities and NaN.
    #[test]
    fn sin_cos_matches_sin_and_cos_bit_for_bit() {
        let mut values = alloc::vec![0.0, -0.0, PI, -PI, TAU, 1e300, -1e300, f64::MIN_POSITIVE];
        for k in -64..=64 {
            values.push(k as f64 * PI / 4.0);
        }
        for e in -60..12 {
            for m in [1.0, 1.1, 1.3, 1.45, 1.5, 1.9999] {
                values.push(m * libm::pow(2.0, e as f64));
                values.push(-m * libm::pow(2.0, e as f64));
            }
        }
        let mut x: u64 = 5;
        for _ in 0..200_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            values.push(((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 200.0);
        }
        for &a in &values {
            let (s, c) = sin_cos(a);
            assert_eq!(s.to_bits(), libm::sin(a).to_bits(), "sin {a:e}");
            assert_eq!(c.to_bits(), libm::cos(a).to_bits(), "cos {a:e}");
        }
        for a in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let (s, c) = sin_cos(a);
            assert!(s.is_nan() && c.is_nan());
        }
    }
}
