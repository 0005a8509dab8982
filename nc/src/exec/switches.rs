//! `#3003` and `#3004`: the program's switches over the operator's
//! controls (dialect.md §7, system variables: "runtime only"). The kernel
//! keeps what the program wrote, reads it back, and the runtime asks it as
//! each block's commands leave: a G61 corner under `#3004` bit 2 blends, a
//! feed under bit 1 runs at its F whatever the override knob says.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};

/// One of the switches a bit of `#3003` or `#3004` sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Switch {
    /// `#3003` bit 0: no single-block stop at the end of a block.
    NoSingleBlock,
    /// `#3003` bit 1: an M, S or T function does not wait for its FIN.
    NoFinWait,
    /// `#3004` bit 0: feed hold is ignored.
    NoFeedHold,
    /// `#3004` bit 1: the feed override is ignored (feeds run at 100 %).
    NoFeedOverride,
    /// `#3004` bit 2: no exact stop (G09, G61) at the end of a block.
    NoExactStop,
}

impl Switch {
    /// The variable and the bit that set it.
    const fn bit(self) -> (u32, u8) {
        match self {
            Switch::NoSingleBlock => (3003, 1),
            Switch::NoFinWait => (3003, 2),
            Switch::NoFeedHold => (3004, 1),
            Switch::NoFeedOverride => (3004, 2),
            Switch::NoExactStop => (3004, 4),
        }
    }
}

/// The values of `#3003` and `#3004` (0 at power-on and after a reset).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Switches {
    s3003: u8,
    s3004: u8,
}

impl Switches {
    pub fn is_on(self, s: Switch) -> bool {
        let (n, bit) = s.bit();
        let v = if n == 3003 { self.s3003 } else { self.s3004 };
        v & bit != 0
    }

    /// `#n` as written (n: 3003 or 3004).
    pub fn read(self, n: u32) -> f64 {
        f64::from(if n == 3003 { self.s3003 } else { self.s3004 })
    }

    /// Writes `#n` (3003 or 3004): an integer made of its defined bits
    /// (0…3, 0…7), else E5010. Null writes 0, as for any system variable.
    pub fn write(&mut self, n: u32, x: f64) -> Result<(), NcError> {
        let max = if n == 3003 { 3.0 } else { 7.0 };
        if libm::trunc(x) != x || !(0.0..=max).contains(&x) {
            return fail(
                Alarm::ValueOutOfRange,
                format!("#{n} = {x}: its bits make an integer 0…{max}"),
            );
        }
        let v = x as u8;
        if n == 3003 {
            self.s3003 = v;
        } else {
            self.s3004 = v;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_bit_sets_its_own_switch() {
        let mut s = Switches::default();
        s.write(3004, 6.0).unwrap();
        assert!(s.is_on(Switch::NoFeedOverride) && s.is_on(Switch::NoExactStop));
        assert!(!s.is_on(Switch::NoFeedHold) && !s.is_on(Switch::NoSingleBlock));
        s.write(3003, 1.0).unwrap();
        assert!(s.is_on(Switch::NoSingleBlock) && !s.is_on(Switch::NoFinWait));
        assert_eq!((s.read(3003), s.read(3004)), (1.0, 6.0));
    }

    #[test]
    fn a_value_outside_the_bits_is_e5010() {
        let mut s = Switches::default();
        for (n, x) in [(3004, 8.0), (3004, -1.0), (3003, 4.0), (3004, 1.5)] {
            let e = s.write(n, x).unwrap_err();
            assert_eq!(e.code, Alarm::ValueOutOfRange as u16, "#{n}={x}");
        }
        assert_eq!(s, Switches::default());
    }
}
