//! Typed blocks: the records of the `Blocks` section that a `block`
//! instruction hands to the kernel in one go.
//!
//! A record is one NC block whose words are all known at compile time:
//!
//! ```text
//! record  count u8 (1..=255), then `count` words in the order written
//! word    head u8: address (bits 0–4, 0..=28), flags (bits 5–6),
//!                  raw (bit 7)
//!         raw = 1: the value's f64 bits, u64 little-endian (finite)
//!         raw = 0: the value as a decimal, one LEB128 varint v:
//!                  v & 63 = exponent + 22 (exponent -22..=22),
//!                  v >> 6 & 1 = sign, v >> 7 = mantissa (< 2^53)
//! ```
//!
//! A decimal decodes as `mantissa × 10^exponent` computed with one exact
//! division or multiplication: mantissa and power of ten are both exact
//! doubles, so the result is the correctly rounded value of the decimal,
//! the same `f64` the lexer (and `str::parse`) gives for that literal.
//! The encoder keeps a decimal only when it decodes to the very bits it was
//! given, and falls back to the raw bits otherwise, so every finite value
//! survives bit for bit; a literal as written (`12.5`, `-33.25`, `0.2`)
//! takes one to three bytes.

use alloc::vec::Vec;

/// A word of a typed block, as the kernel receives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockWord {
    /// The word address (see [`addr`](crate::addr)).
    pub addr: u8,
    /// The value.
    pub value: f64,
    /// The flags `wordk` carries (bit 0: written without a decimal point,
    /// bit 1: written as a literal); only these two bits fit a record.
    pub flags: u8,
}

/// The flag bits a record can carry.
pub const FLAG_MASK: u8 = 0b11;

/// The most words one record holds.
pub const MAX_WORDS: usize = u8::MAX as usize;

const ADDR_BITS: u8 = 0b1_1111;
const FLAG_SHIFT: u32 = 5;
const RAW: u8 = 0x80;

/// Decimal exponents a compact value may have: 10^22 is the largest
/// power of ten that is an exact double.
const EXP_MAX: i32 = 22;
const EXP_BIAS: u64 = EXP_MAX as u64;
const EXP_CODES: u64 = 2 * EXP_BIAS + 1;
/// Mantissas below 2^53 are exact doubles.
const MANTISSA_LIMIT: u64 = 1 << 53;
/// 2⁻⁵⁰: how far from an integer a scaled value may be and still be a
/// decimal's mantissa (`decimal_of`).
const SKIP_BOUND: f64 = 1.0 / (1u64 << 50) as f64;
/// A u64 takes at most ten LEB128 bytes.
const VARINT_MAX: usize = 10;

const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Why a record does not decode (the verifier reports it with the
/// record's place).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordError {
    /// The record or a value runs past the end of the section.
    Truncated,
    /// A record without words.
    Empty,
    /// A word address past `,R`.
    BadAddress,
    /// A varint longer than needed or than a u64.
    BadVarint,
    /// A decimal exponent outside -22..=22 or a mantissa of 2^53 or more.
    BadDecimal,
    /// A raw value that is infinite or NaN.
    NotFinite,
}

impl RecordError {
    /// What is wrong, in words.
    pub const fn what(self) -> &'static str {
        match self {
            RecordError::Truncated => "record runs past the section",
            RecordError::Empty => "record without words",
            RecordError::BadAddress => "bad word address",
            RecordError::BadVarint => "malformed varint",
            RecordError::BadDecimal => "decimal out of range",
            RecordError::NotFinite => "value not finite",
        }
    }
}

/// Appends the record of `words`; `false` (and nothing appended) when they
/// do not fit one: no word, more than [`MAX_WORDS`], a bad address, flags
/// outside [`FLAG_MASK`] or a value that is not finite.
pub fn encode_record(words: &[BlockWord], out: &mut Vec<u8>) -> bool {
    let Ok(count) = u8::try_from(words.len()) else {
        return false;
    };
    if count == 0 {
        return false;
    }
    // The words are put together on the stack and appended a chunk at a
    // time (one chunk for nearly every block): a push per byte, with its
    // capacity check, was most of the encoder's cost. Each word is checked
    // as it is encoded; one that does not fit takes the record back.
    let start = out.len();
    out.reserve(1 + words.len() * WORD_MAX);
    out.push(count);
    let mut buf = [0u8; CHUNK_WORDS * WORD_MAX];
    for chunk in words.chunks(CHUNK_WORDS) {
        let mut len = 0;
        for w in chunk {
            let Some(n) = put_word(w, &mut buf[len..len + WORD_MAX]) else {
                out.truncate(start);
                return false;
            };
            len += n;
        }
        out.extend_from_slice(&buf[..len]);
    }
    true
}

/// The most bytes one word takes: its head, then a varint of a code below
/// 2^56 (`shorter_than_raw`) or the eight raw bytes.
const WORD_MAX: usize = 9;
/// Words put together on the stack before they are appended.
const CHUNK_WORDS: usize = 8;

/// Writes the word `w` at the start of `out`, [`WORD_MAX`] bytes long;
/// how many bytes it took, or `None` for a word that does not fit a
/// record (a bad address, flags outside [`FLAG_MASK`], a value that is not
/// finite).
fn put_word(w: &BlockWord, out: &mut [u8]) -> Option<usize> {
    if w.addr > crate::addr::MAX || w.flags & !FLAG_MASK != 0 {
        return None;
    }
    let head = w.addr | w.flags << FLAG_SHIFT;
    match decimal_of(w.value).filter(|&c| shorter_than_raw(c)) {
        Some(code) => {
            out[0] = head;
            Some(1 + write_varint(code, &mut out[1..]))
        }
        // (`decimal_of` found the value finite before anything else.)
        None if w.value.is_finite() => {
            out[0] = head | RAW;
            out[1..WORD_MAX].copy_from_slice(&w.value.to_bits().to_le_bytes());
            Some(WORD_MAX)
        }
        None => None,
    }
}

/// Decodes the record starting at `bytes[at]`, calling `f` with each word
/// in order; returns the position just past it.
pub fn decode_record(
    bytes: &[u8],
    at: usize,
    mut f: impl FnMut(BlockWord),
) -> Result<usize, RecordError> {
    walk_record(bytes, at, |addr, flags, stored| {
        f(BlockWord {
            addr,
            value: stored.value(),
            flags,
        })
    })
}

/// A word's value as stored: checked, a decimal not yet worked out (the
/// verifier needs few values, and the division is most of a word's cost).
#[derive(Clone, Copy)]
enum Stored {
    Raw(f64),
    Decimal(u64),
}

impl Stored {
    fn value(self) -> f64 {
        match self {
            Stored::Raw(v) => v,
            // (A code `walk_record` passed on has a value.)
            Stored::Decimal(code) => decimal_value(code).unwrap_or(f64::NAN),
        }
    }
}

/// Checks the record at `bytes[at]` word by word, calling `f` with each
/// word's address, flags and stored value; the position past it.
fn walk_record(
    bytes: &[u8],
    at: usize,
    mut f: impl FnMut(u8, u8, Stored),
) -> Result<usize, RecordError> {
    let mut pos = at;
    let count = *bytes.get(pos).ok_or(RecordError::Truncated)?;
    pos += 1;
    if count == 0 {
        return Err(RecordError::Empty);
    }
    for _ in 0..count {
        let head = *bytes.get(pos).ok_or(RecordError::Truncated)?;
        pos += 1;
        let addr = head & ADDR_BITS;
        if addr > crate::addr::MAX {
            return Err(RecordError::BadAddress);
        }
        let (value, next) = if head & RAW != 0 {
            let (v, next) = raw_value(bytes, pos)?;
            (Stored::Raw(v), next)
        } else {
            let (code, next) = get_varint(bytes, pos)?;
            if !is_decimal(code) {
                return Err(RecordError::BadDecimal);
            }
            (Stored::Decimal(code), next)
        };
        pos = next;
        f(addr, (head >> FLAG_SHIFT) & FLAG_MASK, value);
    }
    Ok(pos)
}

/// The compact form of `v`, if it has one: the varint of a decimal that
/// decodes to exactly `v`, with the fewest digits (`12.5` is 125 × 10^-1,
/// `3000` is 3 × 10^3).
pub fn decimal_of(v: f64) -> Option<u64> {
    if !v.is_finite() {
        return None;
    }
    if let Some(code) = four_places(v) {
        return Some(code);
    }
    let sign = u64::from(v.is_sign_negative());
    let a = v.abs();
    for (decimals, &scale) in POW10.iter().enumerate() {
        let scaled = a * scale;
        if scaled >= MANTISSA_LIMIT as f64 {
            break;
        }
        // A mantissa m that decodes to `v` is within m·2⁻⁵² of the
        // product (two roundings of 2⁻⁵³): a product farther than
        // scaled·2⁻⁵⁰ from every integer has none, and costs no decoding.
        // (Past 2⁵¹ the bound is 2 or more, so no product is skipped.)
        let near = scaled as u64;
        // (Exact: the product less its integer part.)
        let frac = scaled - near as f64;
        if frac.min(1.0 - frac) > scaled * SKIP_BOUND {
            continue;
        }
        // The product is within an ulp or so of the mantissa sought;
        // the neighbours cover truncation on either side.
        for m in [near, near + 1, near.saturating_sub(1)] {
            let exp = -(decimals as i32);
            let code = pack(m, sign, exp);
            if m < MANTISSA_LIMIT && decimal_value(code).map(f64::to_bits) == Some(v.to_bits()) {
                return Some(if decimals == 0 {
                    strip_zeros(m, sign)
                } else {
                    code
                });
            }
        }
    }
    None
}

/// Below this magnitude two decimals of at most four places are 10⁻⁴ or
/// more apart and an ulp is at most 2⁻²²: no two of them decode to the
/// same double.
const FOUR_PLACES_BELOW: f64 = 1e9;

/// [`decimal_of`] for a value of at most four decimal places below
/// [`FOUR_PLACES_BELOW`] (nearly every literal of a program), its mantissa
/// read off `|v|·10⁴` without a search; `None` for any other value.
///
/// The same answer as the search, which goes up from no places and takes
/// the first mantissa that decodes to `v`: the code found decodes to `v`,
/// and no other decimal of at most four places does, since two of them
/// are 10⁻⁴ or more apart and each would be within half an ulp of `v`. So
/// the search finds nothing with fewer places, and at these places this
/// mantissa (with no places, its trailing zeros moved into the exponent,
/// as the search does).
fn four_places(v: f64) -> Option<u64> {
    // (`v` is finite: `decimal_of` checked.)
    let a = v.abs();
    if a >= FOUR_PLACES_BELOW {
        return None;
    }
    // (Nearest or next: a wrong guess fails the check below. Below 10¹³,
    // through i64, which converts either way in one instruction.)
    let scaled = (a * 1e4 + 0.5) as i64;
    // The code decodes to the double nearest scaled × 10⁻⁴ whatever the places
    // its trailing zeros leave (both operands of the decoding's one
    // operation are exact): one division checks it, before it is packed.
    if (scaled as f64 / 1e4).to_bits() != a.to_bits() {
        return None;
    }
    let m = scaled as u64;
    let sign = u64::from(v.is_sign_negative());
    // The places are read off the last four digits: one division of the
    // mantissa, then tests of a small number.
    let places = match (m % 10_000) as u32 {
        0 => return Some(strip_zeros(m / 10_000, sign)),
        r if r % 1_000 == 0 => 1,
        r if r % 100 == 0 => 2,
        r if r % 10 == 0 => 3,
        _ => 4,
    };
    let mantissa = match places {
        1 => m / 1_000,
        2 => m / 100,
        3 => m / 10,
        _ => m,
    };
    Some(pack(mantissa, sign, -places))
}

/// An integer mantissa with its trailing zeros moved into the exponent
/// (`m × 10^e` stays an integer below 2^53, so exact either way).
fn strip_zeros(mut m: u64, sign: u64) -> u64 {
    let mut exp = 0;
    while m != 0 && m.is_multiple_of(10) && exp < EXP_MAX {
        m /= 10;
        exp += 1;
    }
    pack(m, sign, exp)
}

/// Whether the compact form of a value is worth it: a varint of more
/// than 8 bytes is longer than the raw bits.
fn shorter_than_raw(code: u64) -> bool {
    code < 1 << 56
}

fn pack(mantissa: u64, sign: u64, exp: i32) -> u64 {
    // exp is within ±22 here, so the bias keeps it non-negative.
    let exp_code = (i64::from(exp) + EXP_BIAS as i64) as u64;
    mantissa << 7 | sign << 6 | exp_code
}

/// The value of a decimal's varint, or `None` if it is out of range.
fn decimal_value(code: u64) -> Option<f64> {
    let exp_code = code & 63;
    let mantissa = code >> 7;
    if exp_code >= EXP_CODES || mantissa >= MANTISSA_LIMIT {
        return None;
    }
    let m = mantissa as f64;
    let exp = exp_code as usize;
    let bias = EXP_BIAS as usize;
    // Both operands exact: one correctly rounded operation.
    let magnitude = if exp >= bias {
        m * *POW10.get(exp - bias)?
    } else {
        m / *POW10.get(bias - exp)?
    };
    Some(if code >> 6 & 1 == 1 {
        -magnitude
    } else {
        magnitude
    })
}

/// Whether a varint is a decimal's code: an exponent within ±22 and a
/// mantissa below 2^53 (what `decimal_value` takes).
fn is_decimal(code: u64) -> bool {
    code & 63 < EXP_CODES && code >> 7 < MANTISSA_LIMIT
}

/// Reads a raw value at `bytes[at]`.
fn raw_value(bytes: &[u8], at: usize) -> Result<(f64, usize), RecordError> {
    let end = at.checked_add(8).ok_or(RecordError::Truncated)?;
    let raw: [u8; 8] = bytes
        .get(at..end)
        .and_then(|s| s.try_into().ok())
        .ok_or(RecordError::Truncated)?;
    let value = f64::from_bits(u64::from_le_bytes(raw));
    if !value.is_finite() {
        return Err(RecordError::NotFinite);
    }
    Ok((value, end))
}

/// Appends `v` as LEB128 ([`write_varint`]).
pub(crate) fn put_varint(v: u64, out: &mut Vec<u8>) {
    let mut buf = [0u8; VARINT_MAX];
    let len = write_varint(v, &mut buf);
    out.extend_from_slice(&buf[..len]);
}

/// Writes `v` as LEB128 at the start of `out`, which must have room for it
/// ([`VARINT_MAX`] bytes hold any u64): seven bits a byte, low bits first,
/// the high bit set on every byte but the last. How many bytes it took.
fn write_varint(mut v: u64, out: &mut [u8]) -> usize {
    let mut len = 0;
    while v >= 0x80 {
        out[len] = (v as u8 & 0x7f) | 0x80;
        v >>= 7;
        len += 1;
    }
    out[len] = v as u8;
    len + 1
}

/// Reads a LEB128 varint; refuses one longer than a u64 or with a
/// needless zero last byte (so every value has one encoding).
// (Always inlined: the walk of a section reads a varint for nearly every
// word, and a call returns its `Result` through memory.)
#[inline(always)]
pub(crate) fn get_varint(bytes: &[u8], at: usize) -> Result<(u64, usize), RecordError> {
    // Most values take one to three bytes (a literal as written): read
    // without the loop. (A last byte of 0 after the first is overlong, and
    // a short slice may be truncated: the loop says which.)
    let low = |b: u8| u64::from(b & 0x7f);
    match *bytes.get(at..).unwrap_or_default() {
        [b0, ..] if b0 < 0x80 => Ok((u64::from(b0), at + 1)),
        [b0, b1, ..] if (1..0x80).contains(&b1) => Ok((low(b0) | u64::from(b1) << 7, at + 2)),
        [b0, b1, b2, ..] if b1 >= 0x80 && (1..0x80).contains(&b2) => {
            Ok((low(b0) | low(b1) << 7 | u64::from(b2) << 14, at + 3))
        }
        _ => varint_loop(bytes, at),
    }
}

/// `get_varint` byte by byte.
fn varint_loop(bytes: &[u8], at: usize) -> Result<(u64, usize), RecordError> {
    let mut v: u64 = 0;
    for i in 0..VARINT_MAX {
        let byte = *bytes.get(at + i).ok_or(RecordError::Truncated)?;
        let bits = u64::from(byte & 0x7f);
        let shift = 7 * i as u32;
        if shift == 63 && bits > 1 {
            return Err(RecordError::BadVarint);
        }
        v |= bits << shift;
        if byte & 0x80 == 0 {
            if i > 0 && byte == 0 {
                return Err(RecordError::BadVarint);
            }
            return Ok((v, at + i + 1));
        }
    }
    Err(RecordError::BadVarint)
}

/// Whether a record's words make a plain move, as a `move` instruction
/// needs: X/Z/U/W, F, N, R, I and K each at most once, and at most one G
/// whose value is 0, 1, 2 or 3. Fed the words in turn.
struct MoveShape {
    seen: u32,
    plain: bool,
}

impl MoveShape {
    const G: u32 = letter(b'G');
    const ALLOWED: u32 = letter(b'X')
        | letter(b'Z')
        | letter(b'U')
        | letter(b'W')
        | letter(b'F')
        | letter(b'N')
        | letter(b'R')
        | letter(b'I')
        | letter(b'K')
        | Self::G;

    fn new() -> MoveShape {
        MoveShape {
            seen: 0,
            plain: true,
        }
    }

    #[inline]
    fn word(&mut self, addr: u8, value: Stored) {
        // (Addresses are below 29 in a record that decodes.)
        let bit = 1u32 << addr;
        let fits = match bit {
            Self::G => matches!(value.value(), 0.0 | 1.0 | 2.0 | 3.0),
            _ => Self::ALLOWED & bit != 0,
        };
        self.plain &= fits && self.seen & bit == 0;
        self.seen |= bit;
    }
}

/// The address bit of a letter.
const fn letter(c: u8) -> u32 {
    1 << (c - b'A')
}

/// Where the records of a `Blocks` section start, one bit per byte, each
/// record checked as it is found, and which of them are plain moves (a
/// bit at the same place). `block`, `profile` and `move` operands may name
/// records in any order (a profile block and the same block where it
/// stands share one record), so the verifier looks them up here; a
/// quarter of the section's size, against a table of `u32` starts that
/// would be half of it for the short records of a straight-line program.
///
/// The walk may be done a piece at a time as the section grows
/// ([`Records`]): a record is checked from its own bytes alone, so the
/// walk of a prefix, carried on over the rest, is the walk of the whole.
#[derive(Debug, Default)]
#[cfg_attr(test, derive(PartialEq))]
pub(crate) struct RecordStarts {
    starts: Vec<u64>,
    moves: Vec<u64>,
    /// The end of the last record checked: where the walk goes on.
    walked: usize,
}

impl RecordStarts {
    /// Room for the walk of `bytes` bytes (reserved, not written).
    fn with_capacity(bytes: usize) -> RecordStarts {
        let words = bytes.div_ceil(64);
        RecordStarts {
            starts: Vec::with_capacity(words),
            moves: Vec::with_capacity(words),
            walked: 0,
        }
    }

    /// Decodes every record of `bytes`; the first bad one is an error
    /// with its place.
    #[cfg(test)]
    pub(crate) fn of(bytes: &[u8]) -> Result<RecordStarts, (usize, RecordError)> {
        let mut walk = RecordStarts::default();
        walk.extend(bytes)?;
        Ok(walk)
    }

    /// Walks on from where the walk stopped to the end of `bytes`, which
    /// must begin with the bytes walked so far. The first bad record is an
    /// error with its place, and the walk stops before it (a later walk
    /// finds it again).
    pub(crate) fn extend(&mut self, bytes: &[u8]) -> Result<(), (usize, RecordError)> {
        let words = bytes.len().div_ceil(64);
        if self.starts.len() < words {
            self.starts.resize(words, 0);
            self.moves.resize(words, 0);
        }
        // (In a local, not in `self`, through the loop: the bit stores
        // need not be read back for it.)
        let mut next = self.walked;
        let walked = loop {
            if next >= bytes.len() {
                break Ok(());
            }
            let start = next;
            let mut shape = MoveShape::new();
            match walk_record(bytes, start, |addr, _, value| shape.word(addr, value)) {
                Ok(end) => next = end,
                Err(e) => break Err((start, e)),
            }
            // (`start` < `bytes.len()`: within the words sized above.)
            self.starts[start / 64] |= 1 << (start % 64);
            if shape.plain {
                self.moves[start / 64] |= 1 << (start % 64);
            }
        };
        self.walked = next;
        walked
    }

    /// The walk of all of `bytes`, this one carried on: `bytes` must begin
    /// with the bytes it walked. A walk that went past their end was of
    /// other bytes, and is done again from the start.
    pub(crate) fn complete(mut self, bytes: &[u8]) -> Result<RecordStarts, (usize, RecordError)> {
        if self.walked > bytes.len() {
            self = RecordStarts::default();
        }
        self.extend(bytes)?;
        Ok(self)
    }

    /// Whether a record starts at byte `at`.
    pub(crate) fn contains(&self, at: u32) -> bool {
        bit(&self.starts, at)
    }

    /// Whether the record at byte `at` is a plain move.
    pub(crate) fn is_move(&self, at: u32) -> bool {
        bit(&self.moves, at)
    }
}

/// A `Blocks` section as it is built, and the walk of its records done as
/// it grows: [`Module::verify_with`](crate::Module::verify_with) takes both,
/// and walks only what was added since the last [`Records::walk`]. The
/// bytes can only be appended to, so what the walk checked stays as it
/// was when it was checked (the walk is sound for these bytes alone,
/// which is why it is not handed over apart from them).
#[derive(Debug, Default)]
pub struct Records {
    bytes: Vec<u8>,
    walk: RecordStarts,
}

impl Records {
    /// Room for `bytes` bytes of records, reserved, not written.
    pub fn with_capacity(bytes: usize) -> Records {
        Records {
            bytes: Vec::with_capacity(bytes),
            walk: RecordStarts::with_capacity(bytes),
        }
    }

    /// Appends the record of `words`, as [`Module::push_block`](crate::Module::push_block) does.
    pub fn push(&mut self, words: &[BlockWord]) -> Option<u32> {
        push_record(words, &mut self.bytes)
    }

    /// Checks the records appended since the last walk. The first bad one
    /// is an error with its place, as the verifier would report it; the
    /// walk stops before it, and `verify_with` finds it again.
    pub fn walk(&mut self) -> Result<(), (usize, RecordError)> {
        self.walk.extend(&self.bytes)
    }

    /// The section's bytes.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// The section's bytes, the walk dropped.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    pub(crate) fn into_parts(self) -> (Vec<u8>, RecordStarts) {
        (self.bytes, self.walk)
    }
}

/// What the verifier's tests look into.
#[cfg(test)]
impl Records {
    /// Appends bytes as they are (a bad record, for the walk to find).
    pub(crate) fn append_raw(&mut self, bytes: &[u8]) {
        self.bytes.extend_from_slice(bytes);
    }

    pub(crate) fn walked(&self) -> &RecordStarts {
        &self.walk
    }
}

#[cfg(test)]
impl RecordStarts {
    pub(crate) fn walked(&self) -> usize {
        self.walked
    }
}

/// A section of records not walked yet.
impl From<Vec<u8>> for Records {
    fn from(bytes: Vec<u8>) -> Records {
        Records {
            bytes,
            walk: RecordStarts::default(),
        }
    }
}

/// Appends the record of `words` to a section; its offset, or `None`
/// (nothing appended) when the words do not fit a record or the offset
/// does not fit an operand.
pub(crate) fn push_record(words: &[BlockWord], bytes: &mut Vec<u8>) -> Option<u32> {
    let at = u32::try_from(bytes.len()).ok()?;
    encode_record(words, bytes).then_some(at)
}

fn bit(bits: &[u64], at: u32) -> bool {
    let Ok(at) = usize::try_from(at) else {
        return false;
    };
    bits.get(at / 64)
        .is_some_and(|word| word & (1 << (at % 64)) != 0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    #[test]
    fn literals_take_few_bytes() {
        // 12.5 = 125 × 10^-1: (125 << 7 | 21) = 16021, two varint bytes.
        assert_eq!(decimal_of(12.5), Some(125 << 7 | 21));
        // -33.25 = -3325 × 10^-2: sign bit set, exponent code 20.
        assert_eq!(decimal_of(-33.25), Some(3325 << 7 | 1 << 6 | 20));
        // -0.0 keeps its sign: mantissa 0, sign 1, exponent 0 (code 22).
        assert_eq!(decimal_of(-0.0), Some(1 << 6 | 22));
        // 3000 = 3 × 10^3: exponent code 25.
        assert_eq!(decimal_of(3000.0), Some(3 << 7 | 25));
        // 0.1 + 0.2 needs 17 digits: no decimal form below 2^53.
        assert_eq!(decimal_of(0.1 + 0.2), None);
        let mut out = Vec::new();
        put_varint(16021, &mut out);
        assert_eq!(out, [0x95, 0x7d]);
    }

    /// `decimal_of` without its shortcuts (the four places read off, the
    /// skip of exponents): every exponent, every candidate decoded. The
    /// shortcuts must never change the answer.
    fn decimal_by_search(v: f64) -> Option<u64> {
        let sign = u64::from(v.is_sign_negative());
        let a = v.abs();
        for (decimals, &scale) in POW10.iter().enumerate() {
            let scaled = a * scale;
            if scaled >= MANTISSA_LIMIT as f64 {
                break;
            }
            let near = scaled as u64;
            for m in [near, near + 1, near.saturating_sub(1)] {
                let code = pack(m, sign, -(decimals as i32));
                if m < MANTISSA_LIMIT && decimal_value(code).map(f64::to_bits) == Some(v.to_bits())
                {
                    return Some(if decimals == 0 {
                        strip_zeros(m, sign)
                    } else {
                        code
                    });
                }
            }
        }
        None
    }

    /// A xorshift generator from `seed`: the random cases' source.
    fn xorshift(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    #[test]
    fn shortcuts_change_no_answer() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        for i in 0..200_000 {
            let r = next();
            let v = match i % 4 {
                // Up to four places (and a few more) around the bound
                // below which they are read off without a search.
                3 => {
                    let m = (r >> 11) % 10u64.pow((r % 15 + 1) as u32);
                    let v = m as f64 / POW10[(r >> 5) as usize % 7];
                    if r & 1 == 0 {
                        v
                    } else {
                        -v
                    }
                }
                // Decimals as written: up to 17 digits, up to 22 places.
                0 => {
                    let m = (r >> 11) % 10u64.pow((r % 17 + 1) as u32);
                    let e = (r >> 5) % 23;
                    let v = m as f64 / POW10[e as usize];
                    if r & 1 == 0 {
                        v
                    } else {
                        -v
                    }
                }
                // Any finite double.
                1 => f64::from_bits(r),
                // Near the 2^51 and 2^53 edges of the mantissa.
                _ => ((1u64 << 51) + (r % (3 << 51))) as f64 / POW10[(r % 4) as usize],
            };
            if v.is_finite() {
                assert_eq!(decimal_of(v), decimal_by_search(v), "{v:e}");
            }
        }
    }

    /// `encode_record` as the format reads, a byte at a time: the
    /// reference for the encoder's chunks and its checks as it goes.
    fn record_by_bytes(words: &[BlockWord]) -> Option<Vec<u8>> {
        let fits = |w: &BlockWord| {
            w.addr <= crate::addr::MAX && w.flags & !FLAG_MASK == 0 && w.value.is_finite()
        };
        let count = u8::try_from(words.len()).ok().filter(|&n| n > 0)?;
        if !words.iter().all(fits) {
            return None;
        }
        let mut out = vec![count];
        for w in words {
            let head = w.addr | w.flags << FLAG_SHIFT;
            match decimal_by_search(w.value).filter(|&c| shorter_than_raw(c)) {
                Some(code) => {
                    out.push(head);
                    put_varint(code, &mut out);
                }
                None => {
                    out.push(head | RAW);
                    out.extend_from_slice(&w.value.to_bits().to_le_bytes());
                }
            }
        }
        Some(out)
    }

    #[test]
    fn records_are_the_bytes_the_format_gives() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        for _ in 0..20_000 {
            let r = next();
            // Up to 20 words (past one chunk), now and then none.
            let n = (r % 21) as usize;
            let words: Vec<BlockWord> = (0..n)
                .map(|_| {
                    let r = next();
                    let value = match r % 5 {
                        0 => f64::from_bits(next()),
                        1 => (r >> 20) as f64 / 1e3,
                        2 => -((r >> 40) as f64) / POW10[(r >> 8) as usize % 23],
                        3 => (r >> 12) as f64,
                        _ => ((r >> 16) % 100_000) as f64 / 100.0,
                    };
                    // Now and then an address or flags that do not fit.
                    let addr = if r >> 60 == 0 {
                        29
                    } else {
                        (r >> 3) as u8 % 29
                    };
                    let flags = if r >> 59 == 1 { 4 } else { (r >> 1) as u8 & 3 };
                    BlockWord { addr, value, flags }
                })
                .collect();
            let mut out = vec![0xaa];
            let fits = encode_record(&words, &mut out);
            match record_by_bytes(&words) {
                Some(want) => {
                    assert!(fits, "{words:?}");
                    assert_eq!(out[1..], want[..], "{words:?}");
                }
                None => {
                    assert!(!fits, "{words:?}");
                    assert_eq!(out, [0xaa], "{words:?}");
                }
            }
        }
    }

    #[test]
    fn overlong_varints_are_refused() {
        assert_eq!(get_varint(&[0x80, 0x00], 0), Err(RecordError::BadVarint));
        assert_eq!(get_varint(&[0xff; 11], 0), Err(RecordError::BadVarint));
        assert_eq!(get_varint(&[0x80], 0), Err(RecordError::Truncated));
        let max = [0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01];
        assert_eq!(get_varint(&max, 0), Ok((u64::MAX, 10)));
    }

    /// LEB128 as its definition reads, byte after byte: the reference
    /// for the short forms `get_varint` reads without its loop.
    fn leb128(bytes: &[u8]) -> Result<(u64, usize), RecordError> {
        let mut v = 0u64;
        for (i, &b) in bytes.iter().enumerate().take(VARINT_MAX) {
            v |= u64::from(b & 0x7f).checked_shl(7 * i as u32).unwrap_or(0);
            if b & 0x80 == 0 {
                let overlong = i > 0 && b == 0;
                let too_big = i == VARINT_MAX - 1 && b > 1;
                return match overlong || too_big {
                    true => Err(RecordError::BadVarint),
                    false => Ok((v, i + 1)),
                };
            }
        }
        match bytes.len() < VARINT_MAX {
            true => Err(RecordError::Truncated),
            false => Err(RecordError::BadVarint),
        }
    }

    #[test]
    fn every_one_and_two_byte_start_reads_as_the_definition_says() {
        for b0 in 0..=255u8 {
            for b1 in 0..=255u8 {
                for tail in [&[][..], &[0x05], &[0x85, 0x01]] {
                    let bytes = [&[0x11, b0, b1][..], tail].concat();
                    let want = leb128(&bytes[1..]).map(|(v, n)| (v, n + 1));
                    assert_eq!(get_varint(&bytes, 1), want, "{bytes:02x?}");
                }
            }
        }
    }
}
