//! The M-code table (dialect.md §6.1): the codes the kernel gives a
//! meaning to, typed, with their class and the canon group they act in.
//! Every other code 0…8999 is handed to the PLC. The numbers are written
//! here only; the rest of the kernel asks the typed code.

/// An M code as the kernel reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum M {
    /// M00: program stop.
    Stop,
    /// M01: optional stop.
    OptionalStop,
    /// M02: end of program.
    End,
    /// M03: spindle forward (CW).
    SpindleCw,
    /// M04: spindle reverse (CCW).
    SpindleCcw,
    /// M05: spindle stop.
    SpindleStop,
    /// M08: coolant on.
    CoolantOn,
    /// M09: coolant off.
    CoolantOff,
    /// M11: tailstock back.
    TailstockBack,
    /// M13: chuck unclamp.
    ChuckUnclamp,
    /// M29: rigid tapping mode (before G84/G88).
    RigidTapping,
    /// M30: end of program and rewind.
    EndRewind,
    /// M33: lubrication off.
    LubricationOff,
    /// M97: another dialect's local subprogram call (E2004).
    ForeignLocalCall,
    /// M98: subprogram call.
    SubCall,
    /// M99: return.
    Return,
    /// M9000…M9999: the call of the program of the same number.
    MacroCall(u16),
    /// Any other code: the PLC's.
    Plc(u16),
}

/// What an M code is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// M00, M01, M02, M30.
    ProgramStop,
    /// M03, M04, M05.
    Spindle,
    /// M08, M09.
    Coolant,
    /// M98, M99, M9000…M9999: the compiler and the VM handle them.
    Call,
    /// Every other code: printed for the PLC (`M CODE=`).
    Plc,
}

/// When in a block an M code acts (canon.md's groups).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Timing {
    /// Group 1, with the spindle start, before the motion.
    Before,
    /// Group 3, after the motion.
    After,
    /// Group 4, last: stops and ends.
    Last,
    /// After everything: calls and returns, outside the kernel.
    Calls,
}

/// The highest M code (dialect.md §1.9: four digits).
pub const MAX: u16 = 9999;

impl M {
    /// The typed code of M`code` (0…9999).
    pub const fn from_code(code: u16) -> M {
        match code {
            0 => M::Stop,
            1 => M::OptionalStop,
            2 => M::End,
            3 => M::SpindleCw,
            4 => M::SpindleCcw,
            5 => M::SpindleStop,
            8 => M::CoolantOn,
            9 => M::CoolantOff,
            11 => M::TailstockBack,
            13 => M::ChuckUnclamp,
            29 => M::RigidTapping,
            30 => M::EndRewind,
            33 => M::LubricationOff,
            97 => M::ForeignLocalCall,
            98 => M::SubCall,
            99 => M::Return,
            9000..=MAX => M::MacroCall(code),
            n => M::Plc(n),
        }
    }

    /// The number as written.
    pub const fn code(self) -> u16 {
        match self {
            M::Stop => 0,
            M::OptionalStop => 1,
            M::End => 2,
            M::SpindleCw => 3,
            M::SpindleCcw => 4,
            M::SpindleStop => 5,
            M::CoolantOn => 8,
            M::CoolantOff => 9,
            M::TailstockBack => 11,
            M::ChuckUnclamp => 13,
            M::RigidTapping => 29,
            M::EndRewind => 30,
            M::LubricationOff => 33,
            M::ForeignLocalCall => 97,
            M::SubCall => 98,
            M::Return => 99,
            M::MacroCall(n) | M::Plc(n) => n,
        }
    }

    pub fn class(self) -> Class {
        match self {
            M::Stop | M::OptionalStop | M::End | M::EndRewind => Class::ProgramStop,
            M::SpindleCw | M::SpindleCcw | M::SpindleStop => Class::Spindle,
            M::CoolantOn | M::CoolantOff => Class::Coolant,
            M::SubCall | M::Return | M::MacroCall(_) => Class::Call,
            M::TailstockBack
            | M::ChuckUnclamp
            | M::RigidTapping
            | M::LubricationOff
            | M::ForeignLocalCall
            | M::Plc(_) => Class::Plc,
        }
    }

    /// The canon group the code acts in (dialect.md §6.1: the "off" codes
    /// after the motion, stops last, every other before).
    pub fn timing(self) -> Timing {
        match self {
            M::SpindleStop
            | M::CoolantOff
            | M::TailstockBack
            | M::ChuckUnclamp
            | M::LubricationOff => Timing::After,
            _ => match self.class() {
                Class::ProgramStop => Timing::Last,
                Class::Call => Timing::Calls,
                _ => Timing::Before,
            },
        }
    }

    /// M02, M30: the program ends.
    pub fn ends_program(self) -> bool {
        matches!(self, M::End | M::EndRewind)
    }

    /// Whether the code can be a drilling cycle's clamp code (the cycle's
    /// M word, cycles.md §21): a code acting before the motion that is
    /// no spindle start and not M29.
    pub fn can_clamp(self) -> bool {
        self.timing() == Timing::Before
            && !matches!(self.class(), Class::Spindle)
            && self != M::RigidTapping
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every code 0…9999 reads back as its own number.
    #[test]
    fn codes_round_trip() {
        for code in 0..=MAX {
            assert_eq!(M::from_code(code).code(), code);
        }
    }

    /// dialect.md §6.1's table, copied by hand: the "when" column.
    #[test]
    fn timing_follows_the_dialect_table() {
        let after = [5, 9, 11, 13, 33];
        let last = [0, 1, 2, 30];
        let calls = [98, 99, 9000, 9500, 9999];
        for code in 0..=MAX {
            let want = if after.contains(&code) {
                Timing::After
            } else if last.contains(&code) {
                Timing::Last
            } else if calls.contains(&code) || code >= 9000 {
                Timing::Calls
            } else {
                Timing::Before
            };
            assert_eq!(M::from_code(code).timing(), want, "M{code}");
        }
    }

    /// The clamp codes of a drilling block: every code but M00–M05, M09,
    /// M11, M13, M29, M30, M33, M98, M99 and the macro calls (cycles.md
    /// §21, as the kernel read them before this table).
    #[test]
    fn clamp_codes() {
        for code in 0..=MAX {
            let not = matches!(code, 0..=5 | 9 | 11 | 13 | 29 | 30 | 33 | 98 | 99 | 9000..=9999);
            assert_eq!(M::from_code(code).can_clamp(), !not, "M{code}");
        }
        assert_eq!(M::from_code(8).class(), Class::Coolant);
        assert_eq!(M::from_code(3).class(), Class::Spindle);
        assert_eq!(M::from_code(9001), M::MacroCall(9001));
        assert_eq!(M::from_code(41), M::Plc(41));
        assert!(M::from_code(30).ends_program() && !M::from_code(0).ends_program());
    }
}
