//! Points of the ZX plane, the one unit of length of the kernel.

/// A point in the ZX plane: `r` is the radial coordinate (X / 2), in mm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pt {
    pub r: f64,
    pub z: f64,
}

impl Pt {
    pub const fn new(r: f64, z: f64) -> Pt {
        Pt { r, z }
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
