//! Plane vectors and the few functions the runtime needs, through `libm`
//! so that the `no_std` core computes the same bits on every host.

use core::ops::{Add, Mul, Neg, Sub};

/// A point or vector of the ZX plane in slide coordinates: `r` is the
/// radial coordinate (X / 2), `z` the Z coordinate, both mm. Angles are
/// measured from +Z towards +X (the ZX view with Z right and X up), so
/// G03 (CCW) turns the angle up.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct V2 {
    pub r: f64,
    pub z: f64,
}

impl V2 {
    pub const ZERO: V2 = V2 { r: 0.0, z: 0.0 };

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

    pub fn dot(self, o: V2) -> f64 {
        self.r * o.r + self.z * o.z
    }

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
        V2 {
            r: libm::sin(a),
            z: libm::cos(a),
        }
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

pub fn sqrt(v: f64) -> f64 {
    libm::sqrt(v)
}

pub const PI: f64 = core::f64::consts::PI;
pub const TAU: f64 = core::f64::consts::TAU;

pub use nc::geom::floor;

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
