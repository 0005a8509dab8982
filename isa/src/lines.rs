//! The line table: the source location of every instruction, kept as
//! runs.
//!
//! A run is a stretch of instructions `pc..pc + len` in one file at one
//! column whose line either stays (`step` 0: the words of a block) or
//! grows by one per instruction (`step` 1: a straight program, one typed
//! block a line). Runs follow each other without gaps, so a run's first
//! pc is the sum of the lengths before it and is not stored.
//!
//! In the file (and in memory) each run is delta-encoded against the one
//! before it:
//!
//! ```text
//! varint  len << 2 | step << 1 | file_changed     (len >= 1; step 0 if len 1)
//! varint  file                                    (only if file_changed)
//! varint  zigzag(line - previous run's last line)
//! varint  col
//! ```
//!
//! The first run's "previous" is file 0, line 0. Memory is the encoded
//! bytes plus a checkpoint every [`CHECK_EVERY`] runs, so a look-up is a
//! binary search over the checkpoints and at most that many runs decoded.

use alloc::vec::Vec;

use crate::block::{get_varint, put_varint};
use crate::SourceLoc;

/// Runs between two checkpoints.
pub const CHECK_EVERY: u32 = 8;

/// One run of instructions with regular locations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Run {
    /// First pc.
    pc: u32,
    /// Instructions in the run (>= 1).
    len: u32,
    /// Location of the first instruction.
    loc: SourceLoc,
    /// Line growth per instruction: 0 or 1.
    step: u8,
}

impl Run {
    fn end(&self) -> u32 {
        self.pc.saturating_add(self.len)
    }

    fn last_line(&self) -> u32 {
        self.line_at(self.len.saturating_sub(1))
    }

    fn line_at(&self, offset: u32) -> u32 {
        self.loc
            .line
            .saturating_add(offset.saturating_mul(u32::from(self.step)))
    }

    /// Whether `loc` is what this run gives its next instruction; a run of
    /// one instruction can still choose its step.
    fn extend_with(&self, loc: SourceLoc) -> Option<u8> {
        let same_place = loc.file == self.loc.file && loc.col == self.loc.col;
        if !same_place || self.len == u32::MAX {
            return None;
        }
        let next_line = u64::from(self.loc.line) + u64::from(self.len);
        match self.len {
            1 if loc.line == self.loc.line => Some(0),
            1 if u64::from(loc.line) == next_line => Some(1),
            _ if self.step == 0 && loc.line == self.loc.line => Some(0),
            _ if self.step == 1 && u64::from(loc.line) == next_line => Some(1),
            _ => None,
        }
    }
}

/// The state a run is delta-encoded against: the run before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
struct Base {
    pc: u32,
    line: u32,
    file: u16,
}

/// Where decoding may start: the byte offset of a run and its base.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Checkpoint {
    offset: u32,
    base: Base,
}

/// Why a line table does not decode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineTableError {
    /// A run runs past the section or a varint is malformed.
    Malformed,
    /// A run with no instructions, a step of 1 on a single instruction, or
    /// a file "change" to the same file.
    NotCanonical,
    /// A line, column, file or pc past its field's range.
    OutOfRange,
    /// The runs do not cover exactly the declared instruction count.
    CountMismatch,
}

impl LineTableError {
    /// What is wrong, in words.
    pub const fn what(self) -> &'static str {
        match self {
            LineTableError::Malformed => "malformed run",
            LineTableError::NotCanonical => "run not in its one encoding",
            LineTableError::OutOfRange => "line, column, file or pc out of range",
            LineTableError::CountMismatch => "runs do not cover the instructions",
        }
    }
}

/// The source location of every instruction, as runs (see the module
/// docs). Build it with [`LineTable::push`] or collect it from locations.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct LineTable {
    /// The closed runs, encoded.
    bytes: Vec<u8>,
    /// One every `CHECK_EVERY` closed runs, the first at run 0.
    checkpoints: Vec<Checkpoint>,
    /// Closed runs.
    closed: u32,
    /// The base the next closed run is encoded against.
    base: Base,
    /// The last run, still growing.
    open: Option<Run>,
    /// The largest file index named.
    max_file: Option<u16>,
}

impl LineTable {
    /// An empty table.
    pub fn new() -> LineTable {
        LineTable::default()
    }

    /// Instructions covered.
    pub fn len(&self) -> usize {
        self.open.map_or(self.base.pc, |r| r.end()) as usize
    }

    /// Whether no instruction is covered.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The largest file index any location names.
    pub fn max_file(&self) -> Option<u16> {
        self.max_file
    }

    /// Bytes held (the encoded runs and the checkpoints): what the table
    /// costs in memory, for the tests that bound it.
    pub fn heap_bytes(&self) -> usize {
        self.bytes.capacity() + self.checkpoints.capacity() * core::mem::size_of::<Checkpoint>()
    }

    /// Adds the location of the next instruction.
    pub fn push(&mut self, loc: SourceLoc) {
        let pc = u32::try_from(self.len()).unwrap_or(u32::MAX);
        if let Some(run) = &mut self.open {
            if let Some(step) = run.extend_with(loc) {
                run.step = step;
                run.len += 1;
                return;
            }
        }
        self.start_run(Run {
            pc,
            len: 1,
            loc,
            step: 0,
        });
    }

    fn start_run(&mut self, run: Run) {
        if let Some(prev) = self.open.take() {
            self.close(prev);
        }
        self.max_file = self.max_file.max(Some(run.loc.file));
        self.open = Some(run);
    }

    /// Encodes `run` after the closed ones.
    fn close(&mut self, run: Run) {
        if self.closed.is_multiple_of(CHECK_EVERY) {
            self.checkpoints.push(Checkpoint {
                offset: u32::try_from(self.bytes.len()).unwrap_or(u32::MAX),
                base: self.base,
            });
        }
        encode_run(&run, self.base, &mut self.bytes);
        self.closed += 1;
        self.base = Base {
            pc: run.end(),
            line: run.last_line(),
            file: run.loc.file,
        };
    }

    /// The location of instruction `pc`, or `None` past the table.
    pub fn get(&self, pc: usize) -> Option<SourceLoc> {
        let pc = u32::try_from(pc).ok()?;
        if let Some(run) = self.open.filter(|r| r.pc <= pc) {
            return (pc < run.end()).then(|| loc_in(&run, pc));
        }
        let i = self
            .checkpoints
            .partition_point(|c| c.base.pc <= pc)
            .checked_sub(1)?;
        let check = self.checkpoints.get(i)?;
        let mut at = check.offset as usize;
        let mut base = check.base;
        while at < self.bytes.len() {
            let (run, next) = decode_run(&self.bytes, at, base).ok()?;
            if pc < run.end() {
                return Some(loc_in(&run, pc));
            }
            base = base_after(&run);
            at = next;
        }
        None
    }

    /// Every instruction's location, in pc order.
    pub fn iter(&self) -> impl Iterator<Item = SourceLoc> + '_ {
        self.runs()
            .flat_map(|run| (run.pc..run.end()).map(move |pc| loc_in(&run, pc)))
    }

    fn runs(&self) -> impl Iterator<Item = Run> + '_ {
        let mut at = 0;
        let mut base = Base::default();
        let closed = core::iter::from_fn(move || {
            let (run, next) = decode_run(&self.bytes, at, base).ok()?;
            at = next;
            base = base_after(&run);
            Some(run)
        });
        closed.take(self.closed as usize).chain(self.open)
    }

    /// The `Lines` payload: the instruction count (u32), then the runs.
    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        let count = u32::try_from(self.len()).unwrap_or(u32::MAX);
        out.extend_from_slice(&count.to_le_bytes());
        out.extend_from_slice(&self.bytes);
        if let Some(run) = self.open {
            encode_run(&run, self.base, out);
        }
    }

    /// Parses the runs of a `Lines` payload (after its count), which must
    /// cover exactly `count` instructions.
    pub(crate) fn read(bytes: &[u8], count: u32) -> Result<LineTable, LineTableError> {
        let mut table = LineTable::new();
        // The runs are encoded again as read, into as many bytes.
        table.bytes.reserve_exact(bytes.len());
        let mut at = 0;
        while at < bytes.len() {
            let (run, next) = decode_run(bytes, at, table.base_for_next())?;
            if run.end() > count {
                return Err(LineTableError::CountMismatch);
            }
            table.start_run(run);
            at = next;
        }
        if table.len() != count as usize {
            return Err(LineTableError::CountMismatch);
        }
        table.checkpoints.shrink_to_fit();
        Ok(table)
    }

    /// The base of a run after the open one.
    fn base_for_next(&self) -> Base {
        self.open.map_or(self.base, |r| base_after(&r))
    }
}

impl FromIterator<SourceLoc> for LineTable {
    fn from_iter<I: IntoIterator<Item = SourceLoc>>(iter: I) -> LineTable {
        let mut table = LineTable::new();
        for loc in iter {
            table.push(loc);
        }
        table
    }
}

impl From<Vec<SourceLoc>> for LineTable {
    fn from(locs: Vec<SourceLoc>) -> LineTable {
        locs.into_iter().collect()
    }
}

fn loc_in(run: &Run, pc: u32) -> SourceLoc {
    SourceLoc {
        line: run.line_at(pc - run.pc),
        ..run.loc
    }
}

fn base_after(run: &Run) -> Base {
    Base {
        pc: run.end(),
        line: run.last_line(),
        file: run.loc.file,
    }
}

fn encode_run(run: &Run, base: Base, out: &mut Vec<u8>) {
    let file_changed = run.loc.file != base.file;
    let head = u64::from(run.len) << 2 | u64::from(run.step) << 1 | u64::from(file_changed);
    put_varint(head, out);
    if file_changed {
        put_varint(u64::from(run.loc.file), out);
    }
    let delta = i64::from(run.loc.line) - i64::from(base.line);
    put_varint(((delta << 1) ^ (delta >> 63)) as u64, out);
    put_varint(u64::from(run.loc.col), out);
}

fn decode_run(bytes: &[u8], at: usize, base: Base) -> Result<(Run, usize), LineTableError> {
    let varint = |at| get_varint(bytes, at).map_err(|_| LineTableError::Malformed);
    let (head, mut at) = varint(at)?;
    let len = u32::try_from(head >> 2).map_err(|_| LineTableError::OutOfRange)?;
    let step = (head >> 1 & 1) as u8;
    if len == 0 || (len == 1 && step == 1) {
        return Err(LineTableError::NotCanonical);
    }
    let mut file = base.file;
    if head & 1 == 1 {
        let (f, next) = varint(at)?;
        file = u16::try_from(f).map_err(|_| LineTableError::OutOfRange)?;
        if file == base.file {
            return Err(LineTableError::NotCanonical);
        }
        at = next;
    }
    let (zigzag, at) = varint(at)?;
    let delta = (zigzag >> 1) as i64 ^ -((zigzag & 1) as i64);
    let line = i64::from(base.line)
        .checked_add(delta)
        .and_then(|l| u32::try_from(l).ok())
        .ok_or(LineTableError::OutOfRange)?;
    let (col, at) = varint(at)?;
    let col = u32::try_from(col).map_err(|_| LineTableError::OutOfRange)?;
    let run = Run {
        pc: base.pc,
        len,
        loc: SourceLoc { file, line, col },
        step,
    };
    let last = u64::from(line) + u64::from(step) * u64::from(len - 1);
    if u32::try_from(last).is_err() || base.pc.checked_add(len).is_none() {
        return Err(LineTableError::OutOfRange);
    }
    Ok((run, at))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(file: u16, line: u32, col: u32) -> SourceLoc {
        SourceLoc { file, line, col }
    }

    #[test]
    fn a_straight_program_is_one_run() {
        // One typed block a line, lines 2..=1001, column 1.
        let table: LineTable = (2..1002).map(|line| at(0, line, 1)).collect();
        assert_eq!(table.len(), 1000);
        assert_eq!(table.runs().count(), 1);
        assert_eq!(table.get(0), Some(at(0, 2, 1)));
        assert_eq!(table.get(999), Some(at(0, 1001, 1)));
        assert_eq!(table.get(1000), None);
        let mut out = Vec::new();
        table.write(&mut out);
        // Count 1000, then one run: head 1000 << 2 | 2 = 4002 (2 bytes),
        // zigzag(2) = 4, col 1.
        assert_eq!(out, [0xe8, 0x03, 0, 0, 0xa2, 0x1f, 4, 1]);
    }

    #[test]
    fn look_ups_cross_checkpoints() {
        // Alternating columns break every run: 300 runs of 2 (same line).
        let locs: Vec<SourceLoc> = (0..600)
            .map(|pc| at((pc / 100) as u16 % 2, 10 + pc / 2, 1 + (pc / 2) % 2))
            .collect();
        let table: LineTable = locs.iter().copied().collect();
        for (pc, loc) in locs.iter().enumerate() {
            assert_eq!(table.get(pc), Some(*loc), "pc {pc}");
        }
        assert!(table.iter().eq(locs.iter().copied()));
        let mut out = Vec::new();
        table.write(&mut out);
        let back = LineTable::read(&out[4..], 600).expect("reads back");
        assert_eq!(back, table);
    }
}
