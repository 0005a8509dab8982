//! The canon's commonest lines as bytes, without `core::fmt`.
//!
//! A long program's canon is nearly all `RAPID`, `LINE` and `ARC` lines,
//! and writing them through the formatting machinery (a `Display` per
//! field, a call per piece) took a quarter of `gbvm run`'s time. These
//! lines are written here digit by digit into a buffer, with the same
//! text as [`Event`]'s `Display` (tests compare the two); every other
//! event, and a number past the integer path of [`decimal`], is left to
//! `Display`.

use super::decimal;
use super::event::{Dir, Event};

/// The longest line written here: `ARC DIR=CCW` and four fields of at
/// most 21 bytes each (sign, 15 digits, point, 4 decimals).
const CAPACITY: usize = 128;

/// One canon line being written.
pub struct LineBuf {
    bytes: [u8; CAPACITY],
    len: usize,
}

impl Default for LineBuf {
    fn default() -> Self {
        LineBuf {
            bytes: [0; CAPACITY],
            len: 0,
        }
    }
}

impl LineBuf {
    /// The line written, without a line end.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    fn push(&mut self, s: &[u8]) -> Option<()> {
        let end = self.len.checked_add(s.len()).filter(|&e| e <= CAPACITY)?;
        self.bytes[self.len..end].copy_from_slice(s);
        self.len = end;
        Some(())
    }

    /// `name` and the number as the canon prints it; `None` for a value
    /// the integer path does not take.
    ///
    /// Byte by byte into the line, where a copy of each piece (name,
    /// sign, digits) was a call to `memcpy` for a few bytes: a fifth of
    /// this function's time.
    fn field(&mut self, name: &[u8], v: f64) -> Option<()> {
        let n = decimal::ten_thousandths(v)?;
        let abs = n.unsigned_abs();
        let (whole, frac) = (abs / 10_000, abs % 10_000);
        let digits = decimal_digits(whole);
        let mut at = self.len;
        // The name, a sign, the digits, a point and four decimals.
        if at + name.len() + 1 + digits + 5 > CAPACITY {
            return None;
        }
        for &b in name {
            self.bytes[at] = b;
            at += 1;
        }
        if n < 0 {
            self.bytes[at] = b'-';
            at += 1;
        }
        put_digits(&mut self.bytes[at..at + digits], whole);
        at += digits;
        if frac != 0 {
            // Four decimals, the trailing zeros dropped.
            self.bytes[at] = b'.';
            put_digits(&mut self.bytes[at + 1..at + 5], frac);
            at += 5 - frac.trailing_zeros_decimal();
        }
        self.len = at;
        Some(())
    }
}

/// The number of decimal digits of `v` (1 for 0).
fn decimal_digits(mut v: u64) -> usize {
    let mut digits = 1;
    while v >= 10 {
        v /= 10;
        digits += 1;
    }
    digits
}

/// `v`'s last `out.len()` decimal digits, with leading zeros, into `out`.
fn put_digits(out: &mut [u8], mut v: u64) {
    for d in out.iter_mut().rev() {
        *d = b'0' + (v % 10) as u8;
        v /= 10;
    }
}

/// The number of trailing decimal zeros of a value below 10⁴ (not 0).
trait TrailingZeros {
    fn trailing_zeros_decimal(self) -> usize;
}

impl TrailingZeros for u64 {
    fn trailing_zeros_decimal(mut self) -> usize {
        let mut zeros = 0;
        while self.is_multiple_of(10) && zeros < 4 {
            self /= 10;
            zeros += 1;
        }
        zeros
    }
}

impl Event {
    /// Writes this event's canon line into `out` when it is a `RAPID`,
    /// `LINE` or `ARC` whose numbers take the integer path: the text
    /// `Display` gives. `false` (and `out` to be discarded) otherwise.
    pub fn write_fast(&self, out: &mut LineBuf) -> bool {
        self.fast(out).is_some()
    }

    fn fast(&self, out: &mut LineBuf) -> Option<()> {
        match *self {
            Event::Rapid { x, z, c } => out.motion(b"RAPID", x, z, c),
            Event::Line { x, z, c } => out.motion(b"LINE", x, z, c),
            Event::Arc { dir, x, z, cx, cz } => {
                out.push(match dir {
                    Dir::Cw => b"ARC DIR=CW",
                    Dir::Ccw => b"ARC DIR=CCW",
                })?;
                out.field(b" X=", x)?;
                out.field(b" Z=", z)?;
                out.field(b" CX=", cx)?;
                out.field(b" CZ=", cz)
            }
            _ => None,
        }
    }
}

impl LineBuf {
    fn motion(&mut self, word: &[u8], x: f64, z: f64, c: Option<f64>) -> Option<()> {
        self.push(word)?;
        self.field(b" X=", x)?;
        self.field(b" Z=", z)?;
        match c {
            Some(c) => self.field(b" C=", c),
            None => Some(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    fn fast(e: &Event) -> Option<alloc::string::String> {
        let mut out = LineBuf::default();
        e.write_fast(&mut out)
            .then(|| core::str::from_utf8(out.as_bytes()).unwrap().to_string())
    }

    /// Values that round every way: halves, ties to even, negatives that
    /// round to zero, trailing zeros, large and tiny magnitudes.
    const VALUES: &[f64] = &[
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        0.00005,
        0.00015,
        -0.00004,
        -0.00005,
        12.3456,
        12.34565,
        100.1,
        99.99995,
        -3.17159265,
        2.5e-7,
        123456789.0,
        9.0e14,
        -9.0e14,
        1.0e15,
        1.0e300,
    ];

    #[test]
    fn fast_lines_read_as_display_writes_them() {
        let mut fast_ones = 0;
        for &x in VALUES {
            for &z in VALUES {
                let c = if x > z { Some(x - z) } else { None };
                let events = [
                    Event::Rapid { x, z, c },
                    Event::Line { x, z, c: None },
                    Event::Arc {
                        dir: Dir::Ccw,
                        x,
                        z,
                        cx: z,
                        cz: x,
                    },
                    Event::Arc {
                        dir: Dir::Cw,
                        x: z,
                        z: x,
                        cx: 1.5,
                        cz: -0.25,
                    },
                ];
                for e in &events {
                    if let Some(text) = fast(e) {
                        assert_eq!(text, e.to_string(), "{e:?}");
                        fast_ones += 1;
                    }
                }
            }
        }
        // Only a value past about 9·10¹⁴ leaves the fast path.
        assert!(fast_ones > 1000, "{fast_ones}");
    }

    #[test]
    fn other_events_and_huge_values_are_left_to_display() {
        assert_eq!(
            fast(&Event::Line {
                x: 1.0e300,
                z: 0.0,
                c: None
            }),
            None
        );
        assert_eq!(
            fast(&Event::Rapid {
                x: f64::NAN,
                z: 0.0,
                c: None
            }),
            None
        );
        assert_eq!(
            fast(&Event::Line {
                x: 1.0,
                z: 2.0,
                c: Some(f64::INFINITY)
            }),
            None
        );
        assert_eq!(
            fast(&Event::Line {
                x: 12.5,
                z: -0.00004,
                c: Some(3.0)
            })
            .as_deref(),
            Some("LINE X=12.5 Z=0 C=3")
        );
    }
}
