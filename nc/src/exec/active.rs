//! The codes in force, as a control's screen shows them for the block it
//! runs (Fanuc's program-check page, the modal state a LinuxCNC GUI
//! shows): the G code of each modal group, and F, S and the T word as the
//! program last gave them (#4001–#4021, #4109, #4119, #4120).

use core::fmt;

use crate::base::event::Num;
use crate::base::gcode::{self, Code};
use crate::base::machine::Machine;
use crate::exec::Nc;
use crate::modal::Modal;

/// The modal groups of [`ActiveCodes::g`], in its order (dialect.md §3):
/// motion, speed mode, feed mode, units, compensation, stroke check,
/// drilling cycle, modal call, work system, exact stop, plane, polar
/// command, polar mode.
pub const GROUPS: [u8; 13] = [
    gcode::MOTION,
    gcode::SPEED_MODE,
    gcode::FEED_MODE,
    gcode::UNITS,
    gcode::COMP,
    gcode::STROKE,
    gcode::DRILL,
    gcode::MODAL_CALL,
    gcode::WORK,
    gcode::EXACT,
    gcode::PLANE,
    gcode::POLAR_CMD,
    gcode::POLAR,
];

/// The codes in force after a block.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ActiveCodes {
    /// The G code in force in each group of [`GROUPS`], in tenths as
    /// #4001–#4021 read them times ten: G01 is 10, G96 is 960, G12.1 is
    /// 121.
    pub g: [Code; 13],
    /// F as last programmed (mm/min under G98, mm/rev under G99, inch
    /// units under G20); 0 before any.
    pub f: f64,
    /// S as last programmed (rev/min under G97, m/min under G96); 0
    /// before any.
    pub s: f64,
    /// The T word as last programmed: tool and offset (T0101 is 101); 0
    /// before any.
    pub t: u32,
}

impl ActiveCodes {
    /// No block has run (the [`Default`]).
    pub const NONE: ActiveCodes = ActiveCodes {
        g: [0; 13],
        f: 0.0,
        s: 0.0,
        t: 0,
    };

    /// The codes a run starts with on `machine` (machine.md §1).
    pub fn power_on(machine: &Machine) -> ActiveCodes {
        ActiveCodes {
            g: groups(&Modal::power_on(machine)),
            ..ActiveCodes::default()
        }
    }
}

/// As a control's screen lists them: `G00 G97 G99 … F0.2 S800 T0202`
/// (each group's G code in [`GROUPS`]' order, then F, S and the T word).
impl fmt::Display for ActiveCodes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for code in self.g {
            write!(f, "{} ", gcode::name(code))?;
        }
        write!(f, "F{} S{} T{:04}", Num(self.f), Num(self.s), self.t)
    }
}

fn groups(modal: &Modal) -> [Code; 13] {
    GROUPS.map(|g| modal.group(g))
}

impl Nc {
    /// The codes in force after the last block.
    pub fn active_codes(&self) -> ActiveCodes {
        let last = |letter: u8| {
            let v = self.st.last[usize::from(letter - b'A')];
            if v.is_nan() {
                0.0
            } else {
                v
            }
        };
        ActiveCodes {
            g: groups(&self.st.modal),
            f: last(b'F'),
            s: last(b'S'),
            // (A T word is a whole number of at most 4 digits.)
            t: last(b'T') as u32,
        }
    }
}
