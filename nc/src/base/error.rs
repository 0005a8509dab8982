//! The alarm the kernel raises: a dialect error code and a message.

use alloc::format;
use alloc::string::String;

use core::fmt;

pub use crate::base::alarm::Alarm;

/// An error of dialect.md §8 found while checking or executing a block.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NcError {
    /// The number of the code: E4001 → 4001.
    pub code: u16,
    pub message: String,
    /// The tag of the profile block (`Nc::push_profile`) that the error is
    /// about, when it is about one rather than the block executing (the
    /// VM also tags a block that a tier's compiled code ran: its pc).
    pub at: Option<u32>,
    /// The way out, when the alarm knows one (the compiler prints it as
    /// the diagnostic's help).
    pub help: Option<String>,
    /// A profile block the error points to while it stands on the cycle
    /// block (its tag, as `at`): the block where a G71/G72 profile turns
    /// back, E4009 being the cycle block's (dialect.md §8.3).
    pub culprit: Option<u32>,
    /// The word of the block the error is about, as its index in the
    /// block's word list (the compiler underlines that word); the block
    /// layer sets it from `addr`.
    pub word: Option<u16>,
    /// The address (`base::words::addr`) of the word the error is about,
    /// where the rule that found it knows no index.
    pub addr: Option<u8>,
    /// With `addr`, the other address of a pair of words that cannot
    /// stand together (X and U): the one written later is named, as the
    /// repeat is for E1011 (the block was fine up to it).
    pub pair: Option<u8>,
    /// Without `pair`, which word of `addr` (0: the first): the G code
    /// refused among several, the M word one too many.
    pub nth: u8,
}

impl NcError {
    /// An alarm of dialect.md §8; `message` says what the block did.
    #[cold]
    pub fn new(alarm: Alarm, message: impl Into<String>) -> NcError {
        NcError::numbered(alarm.code(), message)
    }

    /// An alarm the program raises itself: `#3000 = n` (3000 + n) and
    /// `G65 H99` (500 + Q), dialect.md §8.4.
    #[cold]
    pub fn numbered(code: u16, message: impl Into<String>) -> NcError {
        NcError {
            code,
            message: message.into(),
            at: None,
            help: None,
            culprit: None,
            word: None,
            addr: None,
            pair: None,
            nth: 0,
        }
    }

    /// Whether the number is one a program raised itself: `#3000 = n`
    /// (3000–3999) or `G65 H99` (500–999), whose message is the program's.
    pub fn is_program_alarm(code: u32) -> bool {
        (500..1000).contains(&code) || (3000..4000).contains(&code)
    }

    /// `FILE:LINE:COL: alarm[E5001]: message` as `gbvm` prints an alarm
    /// (`alarm[3005]` for one the program raised, canon.md); an alarm
    /// without a text, `#3000=7`, ends at the colon. The program's text
    /// of its own alarm reads as the canon's `MSG` (a terminal line gets
    /// no byte of the program outside printable ASCII); the message
    /// itself keeps it as written.
    pub fn header(code: u32, message: &str, file: &str, line: u32, col: u32) -> String {
        let (head, message) = match NcError::is_program_alarm(code) {
            true => (
                format!("{file}:{line}:{col}: alarm[{code}]:"),
                super::event::canon_text(message),
            ),
            false => (
                format!("{file}:{line}:{col}: alarm[E{code:04}]:"),
                message.into(),
            ),
        };
        match message.is_empty() {
            true => head,
            false => format!("{head} {message}"),
        }
    }

    /// The alarm of §8, `None` for one the program raised itself.
    pub fn alarm(&self) -> Option<Alarm> {
        Alarm::from_code(self.code)
    }

    /// The same error, about the word at `index` of the block.
    pub fn on_word(mut self, index: usize) -> NcError {
        self.word = u16::try_from(index).ok();
        self
    }

    /// The same error, about the block's word of address `a`.
    pub fn on_addr(mut self, a: u8) -> NcError {
        self.addr = Some(a);
        self
    }

    /// The same error, about the block's word `n` (from 0) of address `a`.
    pub fn on_nth(mut self, a: u8, n: usize) -> NcError {
        self.addr = Some(a);
        self.nth = u8::try_from(n).unwrap_or(u8::MAX);
        self
    }

    /// The same error, about the later written of the block's words of
    /// addresses `a` and `b` (whichever of them it holds).
    pub fn on_pair(mut self, a: u8, b: u8) -> NcError {
        self.addr = Some(a);
        self.pair = Some(b);
        self
    }

    /// The index of the word the error names among a block's words, given
    /// their addresses in written order: `word`, else word `nth` of
    /// `addr` (of `addr` and `pair`, the later of their first words);
    /// `None` when it names none or the block holds no such word.
    pub fn word_among(&self, addrs: impl IntoIterator<Item = u8>) -> Option<usize> {
        if let Some(i) = self.word {
            return Some(usize::from(i));
        }
        let a = self.addr?;
        let (mut first, mut second) = (None, None);
        let mut skip = self.nth;
        for (i, x) in addrs.into_iter().enumerate() {
            if x == a && first.is_none() {
                match skip {
                    0 => first = Some(i),
                    _ => skip -= 1,
                }
            }
            if Some(x) == self.pair && second.is_none() {
                second = Some(i);
            }
        }
        // (`None` orders before any `Some`: the later of those found.)
        first.max(second)
    }

    /// The same error, about profile block `tag`.
    pub fn at(mut self, tag: u32) -> NcError {
        self.at = Some(tag);
        self
    }

    /// [`at`](NcError::at) unless the error names a block already.
    pub fn or_at(mut self, tag: u32) -> NcError {
        self.at.get_or_insert(tag);
        self
    }

    /// The same error, pointing to profile block `tag` (see `culprit`).
    pub fn pointing_to(mut self, tag: u32) -> NcError {
        self.culprit = Some(tag);
        self
    }

    /// The same error with a fix to suggest.
    pub fn with_help(mut self, help: impl Into<String>) -> NcError {
        self.help = Some(help.into());
        self
    }

    /// `E4001` as diagnostics print it.
    pub fn code_name(&self) -> String {
        format!("E{:04}", self.code)
    }
}

impl fmt::Display for NcError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "E{:04}: {}", self.code, self.message)
    }
}

impl core::error::Error for NcError {}

/// Shorthand for `Err(NcError::new(..))`.
pub fn fail<T>(alarm: Alarm, message: impl Into<String>) -> Result<T, NcError> {
    Err(NcError::new(alarm, message))
}

#[cfg(test)]
mod tests {
    use super::{Alarm, NcError};

    /// The word an error names among a block's addresses: its index, else
    /// its address's first word, of a pair the later one.
    #[test]
    fn the_named_word_of_a_pair_is_the_later() {
        let e = || NcError::new(Alarm::IncompatibleWords, "");
        let block = [6u8, 23, 20, 25];
        assert_eq!(e().on_pair(23, 20).word_among(block), Some(2));
        assert_eq!(e().on_pair(20, 23).word_among(block), Some(2));
        assert_eq!(e().on_pair(23, 9).word_among(block), Some(1));
        assert_eq!(e().on_pair(9, 25).word_among(block), Some(3));
        assert_eq!(e().on_addr(9).word_among(block), None);
        assert_eq!(e().on_word(0).on_addr(25).word_among(block), Some(0));
        assert_eq!(e().word_among(block), None);
        // Word n of an address: the M9 of M8 M9, the third G.
        let ms = [6u8, 12, 23, 12, 12, 6, 6];
        assert_eq!(e().on_nth(12, 1).word_among(ms), Some(3));
        assert_eq!(e().on_nth(6, 2).word_among(ms), Some(6));
        assert_eq!(e().on_nth(12, 3).word_among(ms), None);
        assert_eq!(e().on_nth(12, 0).word_among(ms), Some(1));
    }
}
