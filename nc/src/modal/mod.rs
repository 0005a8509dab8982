//! Layer 3, the modal state: the code in force in each modal group and how
//! a block's G codes change it.

use crate::base::gcode::{self, Code, GROUPS};
use crate::base::machine::{Machine, Units};

/// The code in force in each modal group (dialect.md §3), indexed by the
/// group numbers of [`gcode`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modal {
    codes: [Code; GROUPS],
}

impl Modal {
    /// The power-on codes of machine.md §1; G20 on an inch machine.
    pub fn power_on(m: &Machine) -> Modal {
        let mut codes = [0; GROUPS];
        for (g, slot) in codes.iter_mut().enumerate() {
            *slot = gcode::power_on(g as u8).unwrap_or(0);
        }
        if m.machine.power_on_units == Units::Inch {
            codes[gcode::UNITS as usize] = 200;
        }
        Modal { codes }
    }

    /// The code in force in group `g`.
    pub fn group(&self, g: u8) -> Code {
        self.codes[g as usize]
    }

    /// Puts `code` in force in group `g`.
    pub fn set(&mut self, g: u8, code: Code) {
        self.codes[g as usize] = code;
    }

    /// G20 in force.
    pub fn inch(&self) -> bool {
        self.group(gcode::UNITS) == 200
    }

    /// G99 in force (feed per revolution).
    pub fn per_rev(&self) -> bool {
        self.group(gcode::FEED_MODE) == 990
    }

    /// G96 in force (constant surface speed).
    pub fn css_mode(&self) -> bool {
        self.group(gcode::SPEED_MODE) == 960
    }

    /// Index 0..6 of the active work system (G54 = 0).
    pub fn work_index(&self) -> usize {
        ((self.group(gcode::WORK).saturating_sub(540)) / 10).min(5) as usize
    }
}
