//! Plane vectors and the few functions the runtime needs, through `libm`
//! so that the `no_std` core computes the same bits on every host.

use core::ops::{Add, Mul, Neg, Sub};

/// A point or vector of the ZX plane in slide coordinates: `r` is the
/// radial coordinate (X / 2), `z` the Z coordinate, both mm. Angles are
/// measured from +Z towards +X (the ZX view with Z right and X up), so
/// G03 (CCW) turns the angle up.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct V2 {
    /// Radial coordinate (X as a radius).
    pub r: f64,
    /// Z.
    pub z: f64,
}

impl V2 {
    /// The origin.
    pub const ZERO: V2 = V2 { r: 0.0, z: 0.0 };

    /// A vector from radius and Z.
    pub const fn new(r: f64, z: f64) -> V2 {
        V2 { r, z }
    }

    /// From a diameter X and a Z, as the canon writes points.
    pub fn from_xz(x: f64, z: f64) -> V2 {
        V2 { r: x * 0.5, z }
    }

    /// The diameter X of this point.
    pub fn x(self) -> f64 {
        self.r * 2.0
    }

    /// Dot product.
    pub fn dot(self, o: V2) -> f64 {
        self.r * o.r + self.z * o.z
    }

    /// Euclidean length.
    pub fn norm(self) -> f64 {
        // No overflow to fear at machine scales; sqrt is exact IEEE.
        libm::sqrt(self.r * self.r + self.z * self.z)
    }

    /// The unit vector, or zero for a zero vector.
    pub fn unit(self) -> V2 {
        let n = self.norm();
        if n > 0.0 {
            self * (1.0 / n)
        } else {
            V2::ZERO
        }
    }

    /// The vector at angle `a` from +Z.
    pub fn polar(a: f64) -> V2 {
        let (r, z) = sin_cos(a);
        V2 { r, z }
    }

    /// The angle of this vector from +Z.
    pub fn angle(self) -> f64 {
        libm::atan2(self.r, self.z)
    }

    /// Rotated by +90° (from +Z towards +X).
    pub fn perp(self) -> V2 {
        V2 {
            r: self.z,
            z: -self.r,
        }
    }

    /// The largest axis component, in absolute value.
    pub fn max_abs(self) -> f64 {
        self.r.abs().max(self.z.abs())
    }

    /// Both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.z.is_finite()
    }
}

impl Add for V2 {
    type Output = V2;
    fn add(self, o: V2) -> V2 {
        V2 {
            r: self.r + o.r,
            z: self.z + o.z,
        }
    }
}

impl Sub for V2 {
    type Output = V2;
    fn sub(self, o: V2) -> V2 {
        V2 {
            r: self.r - o.r,
            z: self.z - o.z,
        }
    }
}

impl Mul<f64> for V2 {
    type Output = V2;
    fn mul(self, k: f64) -> V2 {
        V2 {
            r: self.r * k,
            z: self.z * k,
        }
    }
}

impl Neg for V2 {
    type Output = V2;
    fn neg(self) -> V2 {
        V2 {
            r: -self.r,
            z: -self.z,
        }
    }
}

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
