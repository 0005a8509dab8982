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

const TABLE: &[(u8, &[Code])] = &[
    (
        ONE_SHOT,
        &[
            40, 71, 90, 100, 110, 280, 300, 310, 360, 370, 500, 520, 530, 650, 700, 710, 720, 730,
            740, 750, 760, 780,
        ],
    ),
    (
        MOTION,
        &[
            0, 10, 20, 30, 50, 51, 62, 63, 72, 73, 320, 321, 322, 323, 330, 340, 900, 920, 921, 940,
        ],
    ),
    (SPEED_MODE, &[960, 970]),
    (FEED_MODE, &[980, 990]),
    (UNITS, &[200, 210]),
    (COMP, &[400, 410, 420]),
    (STROKE, &[220, 230]),
    (DRILL, &[800, 830, 840, 870, 880]),
    (MODAL_CALL, &[660, 670]),
    (WORK, &[540, 550, 560, 570, 580, 590]),
    (EXACT, &[610, 640]),
    (PLANE, &[170, 180, 190]),
    (POLAR_CMD, &[150, 160]),
    (POLAR, &[121, 131]),
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
        MOTION => 0,
        SPEED_MODE => 970,
        FEED_MODE => 980,
        UNITS => 210,
        COMP => 400,
        STROKE => 230,
        DRILL => 800,
        MODAL_CALL => 670,
        WORK => 540,
        EXACT => 640,
        PLANE => 180,
        POLAR_CMD => 150,
        POLAR => 131,
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

    #[test]
    fn names_print_like_a_programmer_writes_them() {
        assert_eq!(name(10), "G01");
        assert_eq!(name(62), "G6.2");
        assert_eq!(name(321), "G32.1");
        assert_eq!(name(710), "G71");
    }
}
