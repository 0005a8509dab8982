//! Test helpers: blocks written as text, run through the kernel on the
//! reference machine, their events as canon lines.

use alloc::string::String;
use alloc::string::ToString;
use alloc::vec::Vec;

use crate::base::event::Event;
use crate::base::machine::Machine;
use crate::base::words::{addr, Word, LITERAL, NO_POINT};
use crate::exec::Nc;

/// The literal words of a block such as `G92 X30. Z-30 F2`: a word
/// without a decimal point carries `NO_POINT`, as the compiler marks it.
pub fn words(block: &str) -> Vec<Word> {
    block
        .split_whitespace()
        .map(|w| {
            let (letter, number) = w.split_at(1);
            let value: f64 = number.parse().unwrap_or_else(|_| panic!("bad word {w}"));
            let flags = if number.contains('.') {
                LITERAL
            } else {
                LITERAL | NO_POINT
            };
            Word {
                addr: addr(letter.as_bytes()[0].to_ascii_uppercase()),
                value,
                flags,
            }
        })
        .collect()
}

/// A kernel on the reference machine that runs blocks one at a time.
pub struct Lathe {
    pub nc: Nc,
}

impl Lathe {
    pub fn new() -> Lathe {
        Lathe {
            nc: Nc::new(Machine::reference()),
        }
    }

    /// The reference machine with its C axis enabled.
    pub fn with_c() -> Lathe {
        let mut m = Machine::reference();
        m.axes.c.enabled = true;
        Lathe { nc: Nc::new(m) }
    }

    /// The canon lines of one block; panics on an alarm.
    pub fn run(&mut self, block: &str) -> Vec<String> {
        match self.try_run(block) {
            Ok(lines) => lines,
            Err(code) => panic!("{block}: alarm E{code}"),
        }
    }

    /// The canon lines of one block, or its alarm's code.
    pub fn try_run(&mut self, block: &str) -> Result<Vec<String>, u16> {
        let mut events: Vec<Event> = Vec::new();
        self.nc
            .exec(&words(block), &mut events)
            .map_err(|e| e.code)?;
        Ok(events.iter().map(|e| e.to_string()).collect())
    }
}

/// The canon lines of a whole program.
pub fn run(blocks: &[&str]) -> Vec<String> {
    let mut m = Lathe::new();
    blocks.iter().flat_map(|b| m.run(b)).collect()
}

/// The code of the alarm a program stops with (0 when it does not).
pub fn run_err(blocks: &[&str]) -> u16 {
    let mut m = Lathe::new();
    for b in blocks {
        if let Err(code) = m.try_run(b) {
            return code;
        }
    }
    0
}

/// The numbers of a canon line: `RAPID X=1 Z=2` → [1, 2].
pub fn nums(line: &str) -> Vec<f64> {
    line.split_whitespace()
        .filter_map(|f| f.split_once('=').and_then(|(_, v)| v.parse().ok()))
        .collect()
}

/// Asserts that a canon line has this keyword and these numbers (within
/// 1e-4, the canon's resolution).
pub fn assert_line(line: &str, keyword: &str, expected: &[f64]) {
    assert!(line.starts_with(keyword), "{line} is not a {keyword}");
    let got = nums(line);
    assert_eq!(got.len(), expected.len(), "{line} vs {expected:?}");
    for (g, e) in got.iter().zip(expected) {
        assert!((g - e).abs() < 1.5e-4, "{line} vs {expected:?}");
    }
}
