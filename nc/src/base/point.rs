//! Points of the ZX plane, the one point and vector type of the kernel and
//! of the runtime (which calls it `runtime::math::V2`).

/// A point or vector in the ZX plane: `r` is the radial coordinate
/// (X / 2), `z` the Z coordinate, both mm. Angles are measured from +Z
/// towards +X (the ZX view with Z right and X up), so G03 (CCW) turns the
/// angle up.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pt {
    /// Radial coordinate (X as a radius).
    pub r: f64,
    /// Z.
    pub z: f64,
}

impl Pt {
    /// The origin.
    pub const ZERO: Pt = Pt { r: 0.0, z: 0.0 };

    /// A point from radius and Z.
    pub const fn new(r: f64, z: f64) -> Pt {
        Pt { r, z }
    }

    /// From a diameter X and a Z, as the canon writes points (the
    /// runtime's spelling of [`Pt::xz`], the same value).
    pub fn from_xz(x: f64, z: f64) -> Pt {
        Pt { r: x * 0.5, z }
    }

    /// Dot product.
    pub fn dot(self, o: Pt) -> f64 {
        self.r * o.r + self.z * o.z
    }

    /// Euclidean length.
    pub fn norm(self) -> f64 {
        // No overflow to fear at machine scales; sqrt is exact IEEE. (The
        // kernel's `dist` uses `hypot`; each keeps its bits.)
        libm::sqrt(self.r * self.r + self.z * self.z)
    }

    /// The unit vector, or zero for a zero vector.
    pub fn unit(self) -> Pt {
        let n = self.norm();
        if n > 0.0 {
            self * (1.0 / n)
        } else {
            Pt::ZERO
        }
    }

    /// The vector at angle `a` from +Z.
    pub fn polar(a: f64) -> Pt {
        let (r, z) = libm::sincos(a);
        Pt { r, z }
    }

    /// The angle of this vector from +Z.
    pub fn angle(self) -> f64 {
        libm::atan2(self.r, self.z)
    }

    /// Rotated by +90° (from +Z towards +X).
    pub fn perp(self) -> Pt {
        Pt {
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

    /// From a diameter X and a Z.
    pub fn xz(x: f64, z: f64) -> Pt {
        Pt { r: x / 2.0, z }
    }

    pub fn x(self) -> f64 {
        self.r * 2.0
    }

    pub fn dist(self, o: Pt) -> f64 {
        libm::hypot(self.r - o.r, self.z - o.z)
    }

    #[allow(clippy::should_implement_trait)] // also `+` below; the method reads well in chains
    pub fn add(self, o: Pt) -> Pt {
        Pt::new(self.r + o.r, self.z + o.z)
    }

    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, o: Pt) -> Pt {
        Pt::new(self.r - o.r, self.z - o.z)
    }
}

impl core::ops::Add for Pt {
    type Output = Pt;
    fn add(self, o: Pt) -> Pt {
        Pt::new(self.r + o.r, self.z + o.z)
    }
}

impl core::ops::Sub for Pt {
    type Output = Pt;
    fn sub(self, o: Pt) -> Pt {
        Pt::new(self.r - o.r, self.z - o.z)
    }
}

impl core::ops::Mul<f64> for Pt {
    type Output = Pt;
    fn mul(self, k: f64) -> Pt {
        Pt {
            r: self.r * k,
            z: self.z * k,
        }
    }
}

impl core::ops::Neg for Pt {
    type Output = Pt;
    fn neg(self) -> Pt {
        Pt {
            r: -self.r,
            z: -self.z,
        }
    }
}
