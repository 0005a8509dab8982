//! Layer 3, the modal state: the code in force in each modal group and how
//! a block's G codes change it.

use crate::base::gcode::{self, Code, G};
pub use crate::base::gcode::{
    Comp, Drill, FeedMode, ModalCall, Motion, PathMode, Plane, Polar, PolarCmd, SpeedMode, Stroke,
    Units, Work,
};
use crate::base::machine::Machine;

/// The code in force in each modal group (dialect.md §3), one typed field
/// per group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modal {
    /// Group 01.
    pub motion: Motion,
    /// Group 02.
    pub speed_mode: SpeedMode,
    /// Group 03.
    pub feed_mode: FeedMode,
    /// Group 06.
    pub units: Units,
    /// Group 07.
    pub comp: Comp,
    /// Group 09.
    pub stroke: Stroke,
    /// Group 10.
    pub drill: Drill,
    /// Group 12.
    pub modal_call: ModalCall,
    /// Group 14.
    pub work: Work,
    /// Group 15.
    pub path_mode: PathMode,
    /// Group 16.
    pub plane: Plane,
    /// Group 17.
    pub polar_cmd: PolarCmd,
    /// Group 21.
    pub polar: Polar,
}

impl Modal {
    /// The power-on codes of machine.md §1; G20 on an inch machine.
    pub fn power_on(m: &Machine) -> Modal {
        let units = if m.machine.power_on_units == crate::base::machine::Units::Inch {
            Units::Inch
        } else {
            Units::Metric
        };
        Modal {
            motion: Motion::Rapid,
            speed_mode: SpeedMode::Rpm,
            feed_mode: FeedMode::PerMinute,
            units,
            comp: Comp::Off,
            stroke: Stroke::Off,
            drill: Drill::Off,
            modal_call: ModalCall::Off,
            work: Work::G54,
            path_mode: PathMode::Continuous,
            plane: Plane::Zx,
            polar_cmd: PolarCmd::Off,
            polar: Polar::Off,
        }
    }

    /// The code in force in group `g` (#4001–#4022), 0 for a group the
    /// dialect does not have or the one-shot group.
    pub fn group(&self, g: u8) -> Code {
        match g {
            gcode::MOTION => self.motion.code(),
            gcode::SPEED_MODE => self.speed_mode.code(),
            gcode::FEED_MODE => self.feed_mode.code(),
            gcode::UNITS => self.units.code(),
            gcode::COMP => self.comp.code(),
            gcode::STROKE => self.stroke.code(),
            gcode::DRILL => self.drill.code(),
            gcode::MODAL_CALL => self.modal_call.code(),
            gcode::WORK => self.work.code(),
            gcode::EXACT => self.path_mode.code(),
            gcode::PLANE => self.plane.code(),
            gcode::POLAR_CMD => self.polar_cmd.code(),
            gcode::POLAR => self.polar.code(),
            _ => 0,
        }
    }

    /// Puts a modal code in force in its group; a one-shot code changes
    /// nothing.
    pub fn set(&mut self, g: G) {
        match g {
            G::OneShot(_) => {}
            G::Motion(c) => self.motion = c,
            G::SpeedMode(c) => self.speed_mode = c,
            G::FeedMode(c) => self.feed_mode = c,
            G::Units(c) => self.units = c,
            G::Comp(c) => self.comp = c,
            G::Stroke(c) => self.stroke = c,
            G::Drill(c) => self.drill = c,
            G::ModalCall(c) => self.modal_call = c,
            G::Work(c) => self.work = c,
            G::PathMode(c) => self.path_mode = c,
            G::Plane(c) => self.plane = c,
            G::PolarCmd(c) => self.polar_cmd = c,
            G::Polar(c) => self.polar = c,
        }
    }

    /// G20 in force.
    #[inline]
    pub fn inch(&self) -> bool {
        self.units == Units::Inch
    }

    /// G99 in force (feed per revolution).
    #[inline]
    pub fn per_rev(&self) -> bool {
        self.feed_mode == FeedMode::PerRev
    }

    /// G96 in force (constant surface speed).
    #[inline]
    pub fn css_mode(&self) -> bool {
        self.speed_mode == SpeedMode::SurfaceSpeed
    }

    /// Group 06: G20 or G21.
    #[inline]
    pub fn units(&self) -> Units {
        self.units
    }

    /// Group 03: G98 or G99.
    #[inline]
    pub fn feed_mode(&self) -> FeedMode {
        self.feed_mode
    }

    /// Group 02: G96 or G97.
    #[inline]
    pub fn speed_mode(&self) -> SpeedMode {
        self.speed_mode
    }

    /// Group 07: G40, G41 or G42.
    #[inline]
    pub fn comp(&self) -> Comp {
        self.comp
    }

    /// Group 15: G61 or G64.
    #[inline]
    pub fn path_mode(&self) -> PathMode {
        self.path_mode
    }

    /// Group 10: the drilling cycle in force, `None` under G80.
    #[inline]
    pub fn drill(&self) -> Option<Drill> {
        Some(self.drill).filter(|&c| c != Drill::Off)
    }

    /// Index 0..6 of the active work system (G54 = 0).
    #[inline]
    pub fn work_index(&self) -> usize {
        self.work.index()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_on_modes_are_those_of_machine_md() {
        // machine.md §1 (the reference machine): G00, G21, G97, G98 (per
        // minute), G40, G23, G80, G67, G54, G64, G18, G15, G13.1.
        let m = Modal::power_on(&Machine::reference());
        assert_eq!(m.motion, Motion::Rapid);
        assert_eq!(m.units(), Units::Metric);
        assert_eq!(m.speed_mode(), SpeedMode::Rpm);
        assert_eq!(m.feed_mode(), FeedMode::PerMinute);
        assert_eq!(m.comp(), Comp::Off);
        assert_eq!(m.path_mode(), PathMode::Continuous);
        assert_eq!(m.drill(), None);
        assert_eq!(m.work_index(), 0);
        // #4001… read the power-on code of every group as gcode's table.
        for g in 0..gcode::GROUPS as u8 {
            assert_eq!(m.group(g), gcode::power_on(g).unwrap_or(0), "group {g}");
        }
    }

    #[test]
    fn set_codes_read_back_typed() {
        let mut m = Modal::power_on(&Machine::reference());
        for code in [420, 610, 830, 990, 200, 560, 921] {
            m.set(G::from_code(code).unwrap());
        }
        assert_eq!(m.comp(), Comp::Right);
        assert_eq!(m.comp().side(), Some(-1.0));
        assert_eq!(m.path_mode(), PathMode::ExactStop);
        assert_eq!(m.drill(), Some(Drill::FaceDrill));
        assert!(m.per_rev() && m.inch());
        assert_eq!(m.work_index(), 2);
        assert_eq!(m.motion, Motion::RigidThreadCycle);
        assert_eq!(m.group(gcode::DRILL), 830);
        assert_eq!(m.group(gcode::WORK), 560);
        assert_eq!(m.group(gcode::MOTION), 921);
        // A one-shot code is no modal state.
        let before = m;
        m.set(G::OneShot(gcode::OneShot::Dwell));
        assert_eq!(m, before);
    }
}
