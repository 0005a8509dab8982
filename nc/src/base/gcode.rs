//! The G-code table: every code of the dialect with its modal group
//! (dialect.md §3), and the codes of other dialects that get a hint (§4.13).

use alloc::format;
use alloc::string::String;

use crate::base::alarm::Alarm;

/// A G code times ten (`G6.2` → 62, `G01` → 10), so it fits an integer.
pub type Code = u16;

/// Modal groups, numbered as dialect.md §3.
pub const ONE_SHOT: u8 = 0;
pub const MOTION: u8 = 1;
pub const SPEED_MODE: u8 = 2;
pub const FEED_MODE: u8 = 3;
pub const UNITS: u8 = 6;
pub const COMP: u8 = 7;
pub const STROKE: u8 = 9;
pub const DRILL: u8 = 10;
pub const MODAL_CALL: u8 = 12;
pub const WORK: u8 = 14;
pub const EXACT: u8 = 15;
pub const PLANE: u8 = 16;
pub const POLAR_CMD: u8 = 17;
pub const POLAR: u8 = 21;
pub const GROUPS: usize = 22;

/// Declares the typed codes of one modal group: an enum whose variants
/// carry their code, `code()`, `from_code()` and the list `CODES` that the
/// group table below is built from, so a code is written once.
macro_rules! group_codes {
    ($(#[$doc:meta])* $name:ident { $($(#[$vdoc:meta])* $variant:ident = $code:literal,)* }) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $($(#[$vdoc])* $variant,)*
        }

        impl $name {
            /// Every code of the group, in the table's order.
            pub const CODES: &'static [Code] = &[$($code),*];

            /// The code times ten (`G6.2` → 62).
            pub const fn code(self) -> Code {
                match self {
                    $($name::$variant => $code,)*
                }
            }

            /// `G6.2`, `G01` for messages.
            pub fn name(self) -> String {
                name(self.code())
            }

            /// The typed code of a code of this group, `None` for another.
            pub const fn from_code(code: Code) -> Option<$name> {
                match code {
                    $($code => Some($name::$variant),)*
                    _ => None,
                }
            }
        }

        impl From<$name> for G {
            fn from(c: $name) -> G {
                G::$name(c)
            }
        }
    };
}

group_codes! {
    /// Group 00: the one-shot functions, which own the block they are in.
    OneShot {
        /// G04 dwell.
        Dwell = 40,
        /// G7.1 cylindrical interpolation.
        Cylindrical = 71,
        /// G09 exact stop of one block.
        ExactStop = 90,
        /// G10 data setting on.
        DataSetting = 100,
        /// G11 data setting off.
        DataSettingEnd = 110,
        /// G28 return to the reference point.
        Home = 280,
        /// G30 return to the 2nd–4th reference point.
        HomeN = 300,
        /// G31 skip.
        Skip = 310,
        /// G36 tool measurement in X.
        MeasureX = 360,
        /// G37 tool measurement in Z.
        MeasureZ = 370,
        /// G50 coordinate system setting (or spindle limit with S).
        SetCoordinates = 500,
        /// G52 local coordinate system.
        Local = 520,
        /// G53 machine coordinates.
        MachineCoords = 530,
        /// G65 macro call.
        MacroCall = 650,
        /// G70 finishing cycle.
        Finish = 700,
        /// G71 stock removal in turning.
        RoughTurn = 710,
        /// G72 stock removal in facing.
        RoughFace = 720,
        /// G73 pattern repeating.
        Pattern = 730,
        /// G74 face peck drilling / grooving.
        PeckFace = 740,
        /// G75 outer diameter grooving.
        PeckGroove = 750,
        /// G76 multiple threading cycle.
        MultiThread = 760,
        /// G78 multiple threading with spiral-in.
        SpiralThread = 780,
    }
}

group_codes! {
    /// Group 01: the motion in force.
    Motion {
        /// G00 rapid.
        Rapid = 0,
        /// G01 line at feed.
        Line = 10,
        /// G02 arc clockwise.
        ArcCw = 20,
        /// G03 arc counterclockwise.
        ArcCcw = 30,
        /// G05 arc through a mid point given relative to the start.
        ThreePoint = 50,
        /// G05.1 arc through an absolute mid point.
        ThreePointAbs = 51,
        /// G6.2 ellipse clockwise.
        EllipseCw = 62,
        /// G6.3 ellipse counterclockwise.
        EllipseCcw = 63,
        /// G7.2 parabola clockwise.
        ParabolaCw = 72,
        /// G7.3 parabola counterclockwise.
        ParabolaCcw = 73,
        /// G32 thread.
        Thread = 320,
        /// G32.1 rigid thread.
        RigidThread = 321,
        /// G32.2 arc thread clockwise.
        ArcThreadCw = 322,
        /// G32.3 arc thread counterclockwise.
        ArcThreadCcw = 323,
        /// G33 tapping.
        Tapping = 330,
        /// G34 variable-lead thread.
        VariableThread = 340,
        /// G90 turning cycle.
        TurningCycle = 900,
        /// G92 thread cycle.
        ThreadCycle = 920,
        /// G92.1 rigid thread cycle.
        RigidThreadCycle = 921,
        /// G94 facing cycle.
        FacingCycle = 940,
    }
}

impl Motion {
    /// The threads: any other group-01 code ends a thread run and clears
    /// its J/K words (dialect.md §4.3).
    pub fn is_thread(self) -> bool {
        matches!(
            self,
            Motion::Thread
                | Motion::RigidThread
                | Motion::ArcThreadCw
                | Motion::ArcThreadCcw
                | Motion::Tapping
                | Motion::VariableThread
                | Motion::ThreadCycle
                | Motion::RigidThreadCycle
        )
    }

    /// G00, G01: straight moves.
    pub fn is_straight(self) -> bool {
        matches!(self, Motion::Rapid | Motion::Line)
    }

    /// G02, G03: arcs by centre or radius.
    pub fn is_arc(self) -> bool {
        matches!(self, Motion::ArcCw | Motion::ArcCcw)
    }

    /// G00–G05.1: the moves that take part in contours and corners.
    pub fn is_contour(self) -> bool {
        self.is_straight()
            || self.is_arc()
            || matches!(self, Motion::ThreePoint | Motion::ThreePointAbs)
    }

    /// G6.2, G6.3, G7.2, G7.3: conics.
    pub fn is_conic(self) -> bool {
        matches!(
            self,
            Motion::EllipseCw | Motion::EllipseCcw | Motion::ParabolaCw | Motion::ParabolaCcw
        )
    }

    /// G6.2, G6.3: ellipses.
    pub fn is_ellipse(self) -> bool {
        matches!(self, Motion::EllipseCw | Motion::EllipseCcw)
    }

    /// G6.2, G7.2: conics that run clockwise.
    pub fn is_cw_conic(self) -> bool {
        matches!(self, Motion::EllipseCw | Motion::ParabolaCw)
    }
}

group_codes! {
    /// Group 02: what S means.
    SpeedMode {
        /// G96: surface speed, m/min.
        SurfaceSpeed = 960,
        /// G97: spindle speed, rpm.
        Rpm = 970,
    }
}

group_codes! {
    /// Group 03: what F means.
    FeedMode {
        /// G98: mm (inch) per minute.
        PerMinute = 980,
        /// G99: mm (inch) per revolution.
        PerRev = 990,
    }
}

group_codes! {
    /// Group 06: the unit of length words.
    Units {
        /// G20.
        Inch = 200,
        /// G21.
        Metric = 210,
    }
}

group_codes! {
    /// Group 07: nose-radius compensation.
    Comp {
        /// G40.
        Off = 400,
        /// G41: the tool left of the path.
        Left = 410,
        /// G42: the tool right of the path.
        Right = 420,
    }
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

group_codes! {
    /// Group 09: stored stroke check 2.
    Stroke {
        /// G22: the area is forbidden.
        On = 220,
        /// G23: no check.
        Off = 230,
    }
}

group_codes! {
    /// Group 10: the drilling and rigid tapping cycles.
    Drill {
        /// G80: none.
        Off = 800,
        /// G83 face drilling (along Z).
        FaceDrill = 830,
        /// G84 face tapping (along Z).
        FaceTap = 840,
        /// G87 side drilling (along X).
        SideDrill = 870,
        /// G88 side tapping (along X).
        SideTap = 880,
    }
}

impl Drill {
    /// G84, G88: tapping, whose F is a lead.
    pub fn taps(self) -> bool {
        matches!(self, Drill::FaceTap | Drill::SideTap)
    }

    /// G83, G84: holes along Z.
    pub fn along_z(self) -> bool {
        matches!(self, Drill::FaceDrill | Drill::FaceTap)
    }
}

group_codes! {
    /// Group 12: the modal macro call.
    ModalCall {
        /// G66.
        On = 660,
        /// G67.
        Off = 670,
    }
}

group_codes! {
    /// Group 14: the workpiece coordinate system.
    Work {
        /// G54, the first.
        G54 = 540,
        /// G55.
        G55 = 550,
        /// G56.
        G56 = 560,
        /// G57.
        G57 = 570,
        /// G58.
        G58 = 580,
        /// G59, the sixth.
        G59 = 590,
    }
}

impl Work {
    /// Index 0..6 of the system (G54 = 0), into the work offset table.
    pub fn index(self) -> usize {
        match self {
            Work::G54 => 0,
            Work::G55 => 1,
            Work::G56 => 2,
            Work::G57 => 3,
            Work::G58 => 4,
            Work::G59 => 5,
        }
    }
}

group_codes! {
    /// Group 15: whether blocks end in an exact stop.
    PathMode {
        /// G61.
        ExactStop = 610,
        /// G64.
        Continuous = 640,
    }
}

group_codes! {
    /// Group 16: the plane.
    Plane {
        /// G17.
        Xy = 170,
        /// G18, the lathe's plane.
        Zx = 180,
        /// G19.
        Yz = 190,
    }
}

group_codes! {
    /// Group 17: polar coordinate command.
    PolarCmd {
        /// G15: off.
        Off = 150,
        /// G16: on.
        On = 160,
    }
}

group_codes! {
    /// Group 21: polar interpolation.
    Polar {
        /// G12.1: on.
        On = 121,
        /// G13.1: off.
        Off = 131,
    }
}

/// A code of the dialect, typed by its modal group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum G {
    OneShot(OneShot),
    Motion(Motion),
    SpeedMode(SpeedMode),
    FeedMode(FeedMode),
    Units(Units),
    Comp(Comp),
    Stroke(Stroke),
    Drill(Drill),
    ModalCall(ModalCall),
    Work(Work),
    PathMode(PathMode),
    Plane(Plane),
    PolarCmd(PolarCmd),
    Polar(Polar),
}

impl G {
    /// The typed code, `None` for a code not of the dialect.
    pub fn from_code(code: Code) -> Option<G> {
        // A direct table, as `group`: this runs for every G word of every
        // block the kernel parses.
        TYPED.get(code as usize).copied().flatten()
    }

    /// `from_code` by the group's tables, to build [`TYPED`].
    const fn by_group(code: Code) -> Option<G> {
        if code as usize >= GROUP_OF.len() {
            return None;
        }
        let Some(group) = GROUP_OF[code as usize] else {
            return None;
        };
        Some(match group {
            ONE_SHOT => match OneShot::from_code(code) {
                Some(c) => G::OneShot(c),
                None => return None,
            },
            MOTION => match Motion::from_code(code) {
                Some(c) => G::Motion(c),
                None => return None,
            },
            SPEED_MODE => match SpeedMode::from_code(code) {
                Some(c) => G::SpeedMode(c),
                None => return None,
            },
            FEED_MODE => match FeedMode::from_code(code) {
                Some(c) => G::FeedMode(c),
                None => return None,
            },
            UNITS => match Units::from_code(code) {
                Some(c) => G::Units(c),
                None => return None,
            },
            COMP => match Comp::from_code(code) {
                Some(c) => G::Comp(c),
                None => return None,
            },
            STROKE => match Stroke::from_code(code) {
                Some(c) => G::Stroke(c),
                None => return None,
            },
            DRILL => match Drill::from_code(code) {
                Some(c) => G::Drill(c),
                None => return None,
            },
            MODAL_CALL => match ModalCall::from_code(code) {
                Some(c) => G::ModalCall(c),
                None => return None,
            },
            WORK => match Work::from_code(code) {
                Some(c) => G::Work(c),
                None => return None,
            },
            EXACT => match PathMode::from_code(code) {
                Some(c) => G::PathMode(c),
                None => return None,
            },
            PLANE => match Plane::from_code(code) {
                Some(c) => G::Plane(c),
                None => return None,
            },
            POLAR_CMD => match PolarCmd::from_code(code) {
                Some(c) => G::PolarCmd(c),
                None => return None,
            },
            POLAR => match Polar::from_code(code) {
                Some(c) => G::Polar(c),
                None => return None,
            },
            _ => return None,
        })
    }

    /// The code times ten.
    pub fn code(self) -> Code {
        match self {
            G::OneShot(c) => c.code(),
            G::Motion(c) => c.code(),
            G::SpeedMode(c) => c.code(),
            G::FeedMode(c) => c.code(),
            G::Units(c) => c.code(),
            G::Comp(c) => c.code(),
            G::Stroke(c) => c.code(),
            G::Drill(c) => c.code(),
            G::ModalCall(c) => c.code(),
            G::Work(c) => c.code(),
            G::PathMode(c) => c.code(),
            G::Plane(c) => c.code(),
            G::PolarCmd(c) => c.code(),
            G::Polar(c) => c.code(),
        }
    }
}

/// The typed code of every code below 1000, built once at compile time.
const TYPED: [Option<G>; 1000] = {
    let mut t = [None; 1000];
    let mut code = 0;
    while code < t.len() {
        t[code] = G::by_group(code as Code);
        code += 1;
    }
    t
};

const TABLE: &[(u8, &[Code])] = &[
    (ONE_SHOT, OneShot::CODES),
    (MOTION, Motion::CODES),
    (SPEED_MODE, SpeedMode::CODES),
    (FEED_MODE, FeedMode::CODES),
    (UNITS, Units::CODES),
    (COMP, Comp::CODES),
    (STROKE, Stroke::CODES),
    (DRILL, Drill::CODES),
    (MODAL_CALL, ModalCall::CODES),
    (WORK, Work::CODES),
    (EXACT, PathMode::CODES),
    (PLANE, Plane::CODES),
    (POLAR_CMD, PolarCmd::CODES),
    (POLAR, Polar::CODES),
];

/// The modal group of a code of the dialect, `None` for an unknown one.
pub fn group(code: Code) -> Option<u8> {
    // A direct table by code: this runs for every G word of every block.
    GROUP_OF.get(code as usize).copied().flatten()
}

/// Codes go up to G99.9 (999); the table is built once at compile time.
const GROUP_OF: [Option<u8>; 1000] = {
    let mut t = [None; 1000];
    let mut i = 0;
    while i < TABLE.len() {
        let (g, codes) = TABLE[i];
        let mut j = 0;
        while j < codes.len() {
            t[codes[j] as usize] = Some(g);
            j += 1;
        }
        i += 1;
    }
    t
};

/// The power-on code of each group (machine.md §1), `None` for one-shot.
pub fn power_on(group: u8) -> Option<Code> {
    Some(match group {
        MOTION => Motion::Rapid.code(),
        SPEED_MODE => SpeedMode::Rpm.code(),
        FEED_MODE => FeedMode::PerMinute.code(),
        UNITS => Units::Metric.code(),
        COMP => Comp::Off.code(),
        STROKE => Stroke::Off.code(),
        DRILL => Drill::Off.code(),
        MODAL_CALL => ModalCall::Off.code(),
        WORK => Work::G54.code(),
        EXACT => PathMode::Continuous.code(),
        PLANE => Plane::Zx.code(),
        POLAR_CMD => PolarCmd::Off.code(),
        POLAR => Polar::Off.code(),
        _ => return None,
    })
}

/// `G6.2`, `G01` for messages.
pub fn name(code: Code) -> String {
    if code.is_multiple_of(10) {
        format!("G{:02}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Codes of other systems that would silently change meaning: the error
/// code and the hint of dialect.md §4.13, `None` for an ordinary unknown.
pub fn foreign(code: Code) -> Option<(Alarm, &'static str)> {
    match code {
        910 => Some((
            Alarm::ForeignDialect,
            "lathe \"A\" system: use U/W for incremental moves (G91 is the incremental mode of systems B/C and mills)",
        )),
        430 | 490 | 680 | 690 | 810 | 820 | 850 | 860 | 890 | 1130 | 1880 | 6000 => Some((
            Alarm::UnknownGCode,
            "not a GSK980TDi/Fanuc-lathe-A code (a mill or another control's code)",
        )),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_follow_the_dialect_table() {
        assert_eq!(group(10), Some(MOTION));
        assert_eq!(group(62), Some(MOTION));
        assert_eq!(group(710), Some(ONE_SHOT));
        assert_eq!(group(990), Some(FEED_MODE));
        assert_eq!(group(590), Some(WORK));
        assert_eq!(group(910), None);
        assert_eq!(group(15), None);
    }

    /// Every code of the dialect's table (dialect.md §3, copied here by
    /// hand) reads back as a typed code of its group with the same number,
    /// and no other number does.
    #[test]
    fn typed_codes_round_trip_through_the_table() {
        let spec: &[(u8, &[&str])] = &[
            (
                ONE_SHOT,
                &[
                    "G04", "G7.1", "G09", "G10", "G11", "G28", "G30", "G31", "G36", "G37", "G50",
                    "G52", "G53", "G65", "G70", "G71", "G72", "G73", "G74", "G75", "G76", "G78",
                ],
            ),
            (
                MOTION,
                &[
                    "G00", "G01", "G02", "G03", "G05", "G5.1", "G6.2", "G6.3", "G7.2", "G7.3",
                    "G32", "G32.1", "G32.2", "G32.3", "G33", "G34", "G90", "G92", "G92.1", "G94",
                ],
            ),
            (SPEED_MODE, &["G96", "G97"]),
            (FEED_MODE, &["G98", "G99"]),
            (UNITS, &["G20", "G21"]),
            (COMP, &["G40", "G41", "G42"]),
            (STROKE, &["G22", "G23"]),
            (DRILL, &["G80", "G83", "G84", "G87", "G88"]),
            (MODAL_CALL, &["G66", "G67"]),
            (WORK, &["G54", "G55", "G56", "G57", "G58", "G59"]),
            (EXACT, &["G61", "G64"]),
            (PLANE, &["G17", "G18", "G19"]),
            (POLAR_CMD, &["G15", "G16"]),
            (POLAR, &["G12.1", "G13.1"]),
        ];
        let mut count = 0;
        for &(g, names) in spec {
            for n in names {
                let code = (n[1..].parse::<f64>().unwrap() * 10.0).round() as Code;
                let typed = G::from_code(code).unwrap_or_else(|| panic!("{n}"));
                assert_eq!(typed.code(), code, "{n}");
                assert_eq!(group(code), Some(g), "{n}");
                count += 1;
            }
        }
        let typed = (0..1000).filter(|&c| G::from_code(c).is_some()).count();
        assert_eq!(typed, count);
        assert_eq!(Work::G57.index(), 3);
        assert_eq!(G::from_code(921), Some(G::Motion(Motion::RigidThreadCycle)));
        assert!(Motion::RigidThreadCycle.is_thread() && !Motion::TurningCycle.is_thread());
    }

    #[test]
    fn names_print_like_a_programmer_writes_them() {
        assert_eq!(name(10), "G01");
        assert_eq!(name(62), "G6.2");
        assert_eq!(name(321), "G32.1");
        assert_eq!(name(710), "G71");
    }
}
