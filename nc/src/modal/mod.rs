//! Layer 3, the modal state: the code in force in each modal group and how
//! a block's G codes change it.

use crate::base::gcode::{self, Code, GROUPS};
use crate::base::machine::Machine;

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
        if m.machine.power_on_units == crate::base::machine::Units::Inch {
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
        self.units() == Units::Inch
    }

    /// G99 in force (feed per revolution).
    pub fn per_rev(&self) -> bool {
        self.feed_mode() == FeedMode::PerRev
    }

    /// G96 in force (constant surface speed).
    pub fn css_mode(&self) -> bool {
        self.speed_mode() == SpeedMode::SurfaceSpeed
    }

    /// Group 06: G20 or G21.
    pub fn units(&self) -> Units {
        match self.group(gcode::UNITS) {
            200 => Units::Inch,
            _ => Units::Metric,
        }
    }

    /// Group 03: G98 or G99.
    pub fn feed_mode(&self) -> FeedMode {
        match self.group(gcode::FEED_MODE) {
            990 => FeedMode::PerRev,
            _ => FeedMode::PerMinute,
        }
    }

    /// Group 02: G96 or G97.
    pub fn speed_mode(&self) -> SpeedMode {
        match self.group(gcode::SPEED_MODE) {
            960 => SpeedMode::SurfaceSpeed,
            _ => SpeedMode::Rpm,
        }
    }

    /// Group 07: G40, G41 or G42.
    pub fn comp(&self) -> Comp {
        match self.group(gcode::COMP) {
            410 => Comp::Left,
            420 => Comp::Right,
            _ => Comp::Off,
        }
    }

    /// Group 15: G61 or G64.
    pub fn path_mode(&self) -> PathMode {
        match self.group(gcode::EXACT) {
            610 => PathMode::ExactStop,
            _ => PathMode::Continuous,
        }
    }

    /// Group 10: the drilling cycle in force, `None` under G80.
    pub fn drill(&self) -> Option<Code> {
        Some(self.group(gcode::DRILL)).filter(|&c| c != 800)
    }

    /// Index 0..6 of the active work system (G54 = 0).
    pub fn work_index(&self) -> usize {
        ((self.group(gcode::WORK).saturating_sub(540)) / 10).min(5) as usize
    }
}

/// Group 06: the unit of length words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// G20.
    Inch,
    /// G21.
    Metric,
}

/// Group 03: what F means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedMode {
    /// G98: mm (inch) per minute.
    PerMinute,
    /// G99: mm (inch) per revolution.
    PerRev,
}

/// Group 02: what S means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpeedMode {
    /// G96: surface speed, m/min.
    SurfaceSpeed,
    /// G97: spindle speed, rpm.
    Rpm,
}

/// Group 07: nose-radius compensation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comp {
    /// G40.
    Off,
    /// G41: the tool left of the path.
    Left,
    /// G42: the tool right of the path.
    Right,
}

impl Comp {
    /// +1 for G41, -1 for G42 (comp.md §2), `None` for G40.
    pub fn side(self) -> Option<f64> {
        match self {
            Comp::Left => Some(1.0),
            Comp::Right => Some(-1.0),
            Comp::Off => None,
        }
    }
}

/// Group 15: whether blocks end in an exact stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathMode {
    /// G61.
    ExactStop,
    /// G64.
    Continuous,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_on_modes_are_those_of_machine_md() {
        // machine.md §1 (the reference machine): G21, G97, G98 (per
        // minute), G40, G64, G80.
        let m = Modal::power_on(&Machine::reference());
        assert_eq!(m.units(), Units::Metric);
        assert_eq!(m.speed_mode(), SpeedMode::Rpm);
        assert_eq!(m.feed_mode(), FeedMode::PerMinute);
        assert_eq!(m.comp(), Comp::Off);
        assert_eq!(m.path_mode(), PathMode::Continuous);
        assert_eq!(m.drill(), None);
    }

    #[test]
    fn set_codes_read_back_typed() {
        let mut m = Modal::power_on(&Machine::reference());
        m.set(gcode::COMP, 420);
        m.set(gcode::EXACT, 610);
        m.set(gcode::DRILL, 830);
        m.set(gcode::FEED_MODE, 990);
        m.set(gcode::UNITS, 200);
        assert_eq!(m.comp(), Comp::Right);
        assert_eq!(m.comp().side(), Some(-1.0));
        assert_eq!(m.path_mode(), PathMode::ExactStop);
        assert_eq!(m.drill(), Some(830));
        assert!(m.per_rev() && m.inch());
        assert_eq!(m.group(gcode::DRILL), 830);
    }
}
