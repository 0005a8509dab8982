//! The words of one block as the kernel receives them: every value already
//! computed (a vacant one left out), in the order they were written.

use alloc::string::String;
use alloc::string::ToString;
use alloc::vec::Vec;

/// Word addresses: `A`..`Z` are 0..=25, the Fanuc comma words follow.
pub const COMMA_A: u8 = 26;
pub const COMMA_C: u8 = 27;
pub const COMMA_R: u8 = 28;
pub const ADDR_COUNT: usize = 29;

/// Flag: a literal written without a decimal point (the decimal-point rule
/// and increment mode look at it).
pub const NO_POINT: u8 = 1;
/// Flag: the value was written as a literal (not computed).
pub const LITERAL: u8 = 2;

pub const fn addr(letter: u8) -> u8 {
    letter - b'A'
}

/// The name of an address for messages.
pub fn addr_name(a: u8) -> String {
    match a {
        COMMA_A => ",A".into(),
        COMMA_C => ",C".into(),
        COMMA_R => ",R".into(),
        a if a < 26 => ((b'A' + a) as char).to_string(),
        _ => "?".into(),
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    pub addr: u8,
    pub value: f64,
    pub flags: u8,
}

impl Word {
    pub fn literal_with_point(&self) -> bool {
        self.flags & LITERAL != 0 && self.flags & NO_POINT == 0
    }
}

/// A reusable buffer of one block's words (cleared, not reallocated, per
/// block).
#[derive(Debug, Clone, Default)]
pub struct Words {
    pub list: Vec<Word>,
}

impl Words {
    pub fn clear(&mut self) {
        self.list.clear();
    }

    pub fn push(&mut self, addr: u8, value: f64, flags: u8) {
        self.list.push(Word { addr, value, flags });
    }
}
