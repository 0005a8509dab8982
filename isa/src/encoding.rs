//! Little-endian primitives shared by the instruction codec and the
//! container.
//!
//! All reads go through [`Reader`], which checks every length against the
//! bytes that are actually there *before* anything is sliced or allocated:
//! that is what keeps a hostile length field from panicking the loader or
//! making it reserve gigabytes.

use alloc::vec::Vec;

use crate::LoadError;

/// A cursor over a byte slice whose positions are absolute offsets into the
/// file, so every error points at the byte where the problem is.
#[derive(Debug, Clone)]
pub(crate) struct Reader<'a> {
    /// The readable bytes; a section reader is cut off at its section's end
    /// but keeps the file's start, so `pos` stays a file offset.
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(bytes: &'a [u8], pos: usize) -> Self {
        Reader { bytes, pos }
    }

    pub(crate) fn pos(&self) -> usize {
        self.pos
    }

    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.remaining() == 0
    }

    /// The next `n` bytes, or `Truncated` at the current position.
    pub(crate) fn take(&mut self, n: usize) -> Result<&'a [u8], LoadError> {
        let at = self.pos;
        let slice = at
            .checked_add(n)
            .and_then(|end| self.bytes.get(at..end))
            .ok_or(LoadError::Truncated { at })?;
        self.pos = at + n;
        Ok(slice)
    }

    /// Everything up to the end of this reader.
    pub(crate) fn rest(&mut self) -> &'a [u8] {
        let rest = self.bytes.get(self.pos..).unwrap_or(&[]);
        self.pos = self.pos.max(self.bytes.len());
        rest
    }

    /// A `u32` length followed by that many bytes. A length running past
    /// the end is reported at the length field, the byte that lies.
    pub(crate) fn sized(&mut self) -> Result<&'a [u8], LoadError> {
        let at = self.pos;
        let len = self.len_u32()?;
        self.take(len).map_err(|_| LoadError::Truncated { at })
    }

    /// Like [`Reader::sized`], as a reader of its own positioned at the
    /// payload's start and ending at its end (positions stay file offsets).
    pub(crate) fn split_sized(&mut self) -> Result<Reader<'a>, LoadError> {
        let start = self.pos.saturating_add(4);
        self.sized()?;
        let bytes = self.bytes.get(..self.pos).unwrap_or(&[]);
        Ok(Reader { bytes, pos: start })
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], LoadError> {
        let at = self.pos;
        self.take(N)?
            .try_into()
            .map_err(|_| LoadError::Truncated { at })
    }

    pub(crate) fn u8(&mut self) -> Result<u8, LoadError> {
        self.array::<1>().map(|[b]| b)
    }

    pub(crate) fn u16(&mut self) -> Result<u16, LoadError> {
        self.array().map(u16::from_le_bytes)
    }

    pub(crate) fn u32(&mut self) -> Result<u32, LoadError> {
        self.array().map(u32::from_le_bytes)
    }

    pub(crate) fn u64(&mut self) -> Result<u64, LoadError> {
        self.array().map(u64::from_le_bytes)
    }

    /// A `u32` length as `usize`.
    pub(crate) fn len_u32(&mut self) -> Result<usize, LoadError> {
        let at = self.pos;
        let len = self.u32()?;
        usize::try_from(len).map_err(|_| LoadError::Truncated { at })
    }

    /// A `u32` record count, accepted only if `count` records of at least
    /// `min_record` bytes each can fit in what is left: the caller may then
    /// `Vec::with_capacity(count)` without trusting the file.
    pub(crate) fn count(&mut self, min_record: usize) -> Result<usize, LoadError> {
        let at = self.pos;
        let count = self.len_u32()?;
        match count.checked_mul(min_record) {
            Some(need) if need <= self.remaining() => Ok(count),
            _ => Err(LoadError::Truncated { at }),
        }
    }
}

/// A fixed-width little-endian value: the operand types and the container's
/// integer fields.
pub(crate) trait Le: Copy {
    fn put(self, out: &mut Vec<u8>);
    fn get(r: &mut Reader<'_>) -> Result<Self, LoadError>;
}

impl Le for u8 {
    fn put(self, out: &mut Vec<u8>) {
        out.push(self);
    }
    fn get(r: &mut Reader<'_>) -> Result<Self, LoadError> {
        r.u8()
    }
}

impl Le for u16 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn get(r: &mut Reader<'_>) -> Result<Self, LoadError> {
        r.u16()
    }
}

impl Le for u32 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn get(r: &mut Reader<'_>) -> Result<Self, LoadError> {
        r.u32()
    }
}

impl Le for u64 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn get(r: &mut Reader<'_>) -> Result<Self, LoadError> {
        r.u64()
    }
}

/// A length as the format's `u32`. Lengths that do not fit are saturated:
/// the resulting file is then rejected by the loader rather than silently
/// wrapped (and `Module::verify` reports such a module as `TooLarge`).
pub(crate) fn len_to_u32(len: usize) -> u32 {
    u32::try_from(len).unwrap_or(u32::MAX)
}
