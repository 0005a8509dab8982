//! The `.gbc` container layout.
//!
//! ```text
//! magic    "GBC\0"
//! version  u16                         (VERSION)
//! section  × 9, in the order of Section::ALL:
//!          tag u8, length u32, payload[length]
//! crc      u32                         CRC32 of every byte before it
//! ```
//!
//! All integers are little-endian. Payloads:
//!
//! | section    | payload                                                   |
//! |------------|-----------------------------------------------------------|
//! | `Code`     | the instructions back to back (their count is implied)    |
//! | `Consts`   | count u32, then each `f64` as its `u64` bits              |
//! | `Strings`  | count u32, then each: length u32, UTF-8 bytes             |
//! | `Programs` | count u32, then each: number, entry, end, seq count u32,  |
//! |            | then `(number u32, pc u32)` per sequence entry, then the  |
//! |            | loop count u32 and each loop's parent u32, then the count |
//! |            | u32 and the loop u32 of each sequence entry (or none)     |
//! | `Lines`    | instruction count u32, then the runs of the line table    |
//! |            | (see [`LineTable`]), delta-encoded                        |
//! | `Files`    | count u32, then each: length u32, UTF-8 name, hash u32    |
//! | `Machine`  | UTF-8 text, the whole payload                             |
//! | `Regs`     | num_regs u16                                              |
//! | `Blocks`   | the typed block records back to back (see [`block`])      |
//!
//! The order is fixed and nothing may be left over, so every accepted file
//! has exactly one encoding: `from_bytes(b)?.to_bytes() == b`. New sections
//! come with a new [`VERSION`]. `Blocks` is last so that a loader may keep
//! the file's buffer as the section ([`Module::from_vec`]).
//!
//! [`block`]: crate::block

use alloc::string::String;
use alloc::vec::Vec;
use core::ops::Range;

use crate::encoding::{len_to_u32, Le, Reader};
use crate::instr::MAX_ENCODED_LEN;
use crate::{Instr, LineTable, LoadError, Module, Program, SourceFileInfo, TableError};

/// The first four bytes of every `.gbc` file.
pub const MAGIC: [u8; 4] = *b"GBC\0";

/// The format version this build reads and writes.
/// Version 2 added `skipblock` (block delete decided at run time);
/// version 3 the typed blocks (`block`, the `Blocks` section) and the
/// line table as delta-encoded runs; version 4 `profile` (a G70–G73
/// profile block as a typed record, shared with the block where it stands);
/// version 5 `move` (a typed plain move); version 6 `execmove` (a plain
/// move with computed words); version 7 `addk`, `subk`, `mulk`, `divk`
/// and `cmpk` (arithmetic and comparisons with a constant operand);
/// version 8 a program's DO loops and the loop of each sequence number,
/// `gotoseqin` (a computed GOTO inside a loop: E6008 into another) and
/// `callsubpacked` (a computed M98 P split by the VM); version 9 `charge`
/// and `goto`, so that every macro statement counts against the block
/// budget, and `useralarm` (G65 H99 with a computed number); version 10
/// strings that hold a message's UTF-8 text as written (escaped only where
/// it is printed: an older VM would print each character's bytes).
pub const VERSION: u16 = 10;

/// Bytes before the first section: magic and version.
pub const HEADER_LEN: usize = 6;

/// Bytes of the CRC32 trailer.
pub const CRC_LEN: usize = 4;

/// Section tags, in the order they appear in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Section {
    /// Instructions.
    Code = 1,
    /// Constant pool.
    Consts = 2,
    /// String table.
    Strings = 3,
    /// Program table.
    Programs = 4,
    /// The source location of every instruction, as runs.
    Lines = 5,
    /// Source files.
    Files = 6,
    /// Machine settings text.
    Machine = 7,
    /// Register count.
    Regs = 8,
    /// Typed block records.
    Blocks = 9,
}

impl Section {
    /// Every section, in file order.
    pub const ALL: [Section; 9] = [
        Section::Code,
        Section::Consts,
        Section::Strings,
        Section::Programs,
        Section::Lines,
        Section::Files,
        Section::Machine,
        Section::Regs,
        Section::Blocks,
    ];
}

// Smallest encoded record of each counted table, used to bound counts
// against the bytes present before allocating.
const CONST_LEN: usize = 8;
const STRING_MIN: usize = 4;
const PROGRAM_MIN: usize = 24;
const SEQ_LEN: usize = 8;
const FILE_MIN: usize = 8;

/// Parses the container; does not verify cross-references. The module
/// comes without its `blocks`, whose payload's place in `bytes` is
/// returned for the caller to copy or keep.
pub(crate) fn read(bytes: &[u8]) -> Result<(Module, Range<usize>), LoadError> {
    let head = bytes.get(..bytes.len().min(MAGIC.len())).unwrap_or(&[]);
    if !MAGIC.starts_with(head) {
        return Err(LoadError::BadMagic);
    }
    if bytes.len() < MAGIC.len() {
        return Err(LoadError::Truncated { at: bytes.len() });
    }
    let mut r = Reader::new(bytes, MAGIC.len());
    let version = r.u16()?;
    if version != VERSION {
        return Err(LoadError::UnsupportedVersion { found: version });
    }
    let body_len = bytes
        .len()
        .checked_sub(CRC_LEN)
        .filter(|&n| n >= HEADER_LEN)
        .ok_or(LoadError::Truncated { at: bytes.len() })?;
    let (body, trailer) = bytes
        .split_at_checked(body_len)
        .ok_or(LoadError::Truncated { at: bytes.len() })?;
    let stored = Reader::new(trailer, 0).u32()?;
    if crc32fast::hash(body) != stored {
        return Err(LoadError::BadChecksum);
    }

    let mut r = Reader::new(body, HEADER_LEN);
    let sections = layout(&mut r)?;
    if !r.is_empty() {
        return Err(LoadError::TrailingBytes { at: r.pos() });
    }
    let code_len = declared_code(&sections)?;
    let code = payload(sections.code, |s| read_code(s, code_len))?;
    let consts = payload(sections.consts, |s| {
        table(s, CONST_LEN, |s| s.u64().map(f64::from_bits))
    })?;
    let strings = payload(sections.strings, |s| table(s, STRING_MIN, read_string))?;
    let programs = payload(sections.programs, |s| table(s, PROGRAM_MIN, read_program))?;
    let lines = payload(sections.lines, read_lines)?;
    let files = payload(sections.files, |s| {
        table(s, FILE_MIN, |s| {
            Ok(SourceFileInfo {
                name: read_string(s)?,
                hash: s.u32()?,
            })
        })
    })?;
    let machine = payload(sections.machine, |s| {
        let at = s.pos();
        utf8(s.rest(), at)
    })?;
    let num_regs = payload(sections.regs, Reader::u16)?;
    let mut blocks = sections.blocks;
    let start = blocks.pos();
    let end = start + blocks.rest().len();
    let module = Module {
        code,
        consts,
        strings,
        programs,
        lines,
        files,
        machine,
        num_regs,
        blocks: Vec::new(),
    };
    Ok((module, start..end))
}

/// Each section's payload, found from the section headers alone.
struct Sections<'a> {
    code: Reader<'a>,
    consts: Reader<'a>,
    strings: Reader<'a>,
    programs: Reader<'a>,
    lines: Reader<'a>,
    files: Reader<'a>,
    machine: Reader<'a>,
    regs: Reader<'a>,
    blocks: Reader<'a>,
}

/// Walks the eight section headers: each tag where the format puts it,
/// each declared length within the bytes present. Nothing is decoded or
/// allocated before every declared size is known to fit the file.
fn layout<'a>(r: &mut Reader<'a>) -> Result<Sections<'a>, LoadError> {
    let mut next = |want: Section| {
        let at = r.pos();
        let tag = r.u8()?;
        if tag != want as u8 {
            return Err(LoadError::UnexpectedSection {
                at,
                found: tag,
                expected: want as u8,
            });
        }
        r.split_sized()
    };
    // Struct expression fields are evaluated in the order written, which
    // is the file order.
    Ok(Sections {
        code: next(Section::Code)?,
        consts: next(Section::Consts)?,
        strings: next(Section::Strings)?,
        programs: next(Section::Programs)?,
        lines: next(Section::Lines)?,
        files: next(Section::Files)?,
        machine: next(Section::Machine)?,
        regs: next(Section::Regs)?,
        blocks: next(Section::Blocks)?,
    })
}

/// The number of instructions the line table declares (one location per
/// instruction), checked against the code section's length before the
/// code is decoded: every instruction takes 1 to `MAX_ENCODED_LEN` bytes,
/// so a code section out of proportion to its line table is refused
/// before it costs memory (8 bytes per instruction decoded).
fn declared_code(sections: &Sections<'_>) -> Result<usize, LoadError> {
    let lines = sections.lines.clone().len_u32()?;
    let bytes = sections.code.remaining();
    let fits = lines <= bytes && bytes <= lines.saturating_mul(MAX_ENCODED_LEN);
    if fits {
        Ok(lines)
    } else {
        Err(TableError::CodeSize { bytes, lines }.into())
    }
}

/// Decodes a section's payload with `decode`, which must consume it
/// exactly.
fn payload<'a, T>(
    mut s: Reader<'a>,
    decode: impl FnOnce(&mut Reader<'a>) -> Result<T, LoadError>,
) -> Result<T, LoadError> {
    let value = decode(&mut s)?;
    if !s.is_empty() {
        return Err(LoadError::TrailingBytes { at: s.pos() });
    }
    Ok(value)
}

/// A counted table; the count is checked against the bytes present before
/// anything is reserved.
fn table<'a, T>(
    s: &mut Reader<'a>,
    min_record: usize,
    mut record: impl FnMut(&mut Reader<'a>) -> Result<T, LoadError>,
) -> Result<Vec<T>, LoadError> {
    let count = s.count(min_record)?;
    let mut items = Vec::with_capacity(count);
    for _ in 0..count {
        items.push(record(s)?);
    }
    Ok(items)
}

/// The instructions; `expected` (checked against the section's length)
/// sizes the vector, so a well-formed file decodes without regrowing.
fn read_code(s: &mut Reader<'_>, expected: usize) -> Result<Vec<Instr>, LoadError> {
    // Every instruction takes at least one byte, so should the count be
    // off this still grows to at most `size_of::<Instr>()` times the
    // section length.
    let mut code = Vec::with_capacity(expected);
    while !s.is_empty() {
        let pc = len_to_u32(code.len());
        code.push(Instr::read(s, pc)?);
    }
    Ok(code)
}

/// The line table: its instruction count, then runs to the end of the
/// payload (held as they are encoded, so in no more memory than the
/// section's bytes and a checkpoint per 8 runs).
fn read_lines(s: &mut Reader<'_>) -> Result<LineTable, LoadError> {
    let at = s.pos();
    let count = s.u32()?;
    LineTable::read(s.rest(), count).map_err(|e| TableError::BadLines { at, what: e.what() }.into())
}

fn read_string(s: &mut Reader<'_>) -> Result<String, LoadError> {
    let at = s.pos().saturating_add(4);
    utf8(s.sized()?, at)
}

fn utf8(bytes: &[u8], at: usize) -> Result<String, LoadError> {
    core::str::from_utf8(bytes)
        .map(String::from)
        .map_err(|_| LoadError::BadUtf8 { at })
}

fn read_program(s: &mut Reader<'_>) -> Result<Program, LoadError> {
    let number = s.u32()?;
    let entry = s.u32()?;
    let end = s.u32()?;
    let seqs = table(s, SEQ_LEN, |s| Ok((s.u32()?, s.u32()?)))?;
    let loops = table(s, 4, |s| s.u32())?;
    let seq_loops = table(s, 4, |s| s.u32())?;
    Ok(Program {
        number,
        entry,
        end,
        seqs,
        loops,
        seq_loops,
    })
}

/// Serializes `m` as laid out above.
pub(crate) fn write(m: &Module) -> Vec<u8> {
    // Room for all of it: growing the buffer would copy a large module
    // (and hold it twice for a moment).
    let mut out = Vec::with_capacity(size_bound(m));
    let written = write_with(m, &mut |bytes: &[u8]| {
        out.extend_from_slice(bytes);
        Ok::<(), core::convert::Infallible>(())
    });
    match written {
        Ok(()) => out,
        Err(never) => match never {},
    }
}

/// Serializes `m` as [`write`] does, handing the bytes to `sink` a piece
/// at a time: the file is never whole in memory (a large module goes
/// straight to its file). Stops at the sink's first error.
pub(crate) fn write_with<E>(
    m: &Module,
    sink: &mut dyn FnMut(&[u8]) -> Result<(), E>,
) -> Result<(), E> {
    let mut out = Out {
        sink,
        crc: crc32fast::Hasher::new(),
    };
    out.put(&MAGIC)?;
    out.put(&VERSION.to_le_bytes())?;
    code_section(&mut out, &m.code)?;
    let mut scratch = Vec::new();
    out.section(
        Section::Consts,
        small(&mut scratch, |o| {
            len_to_u32(m.consts.len()).put(o);
            for k in &m.consts {
                k.to_bits().put(o);
            }
        }),
    )?;
    out.section(
        Section::Strings,
        small(&mut scratch, |o| {
            len_to_u32(m.strings.len()).put(o);
            for s in &m.strings {
                string_out(o, s);
            }
        }),
    )?;
    out.section(
        Section::Programs,
        small(&mut scratch, |o| programs_out(o, &m.programs)),
    )?;
    out.section(Section::Lines, small(&mut scratch, |o| m.lines.write(o)))?;
    out.section(
        Section::Files,
        small(&mut scratch, |o| {
            len_to_u32(m.files.len()).put(o);
            for f in &m.files {
                string_out(o, &f.name);
                f.hash.put(o);
            }
        }),
    )?;
    out.section(Section::Machine, m.machine.as_bytes())?;
    out.section(Section::Regs, &m.num_regs.to_le_bytes())?;
    out.section(Section::Blocks, &m.blocks)?;
    let crc = out.crc.finalize();
    (out.sink)(&crc.to_le_bytes())
}

/// The sink, and the CRC of every byte handed to it.
struct Out<'s, E> {
    sink: &'s mut dyn FnMut(&[u8]) -> Result<(), E>,
    crc: crc32fast::Hasher,
}

impl<E> Out<'_, E> {
    fn put(&mut self, bytes: &[u8]) -> Result<(), E> {
        self.crc.update(bytes);
        (self.sink)(bytes)
    }

    fn head(&mut self, tag: Section, len: usize) -> Result<(), E> {
        self.put(&[tag as u8])?;
        self.put(&len_to_u32(len).to_le_bytes())
    }

    fn section(&mut self, tag: Section, payload: &[u8]) -> Result<(), E> {
        self.head(tag, payload.len())?;
        self.put(payload)
    }
}

/// A small section's payload, built in `scratch`.
fn small(scratch: &mut Vec<u8>, payload: impl FnOnce(&mut Vec<u8>)) -> &[u8] {
    scratch.clear();
    payload(scratch);
    scratch
}

/// The code: its length from the opcodes' widths, then the instructions
/// encoded a few thousand at a time.
fn code_section<E>(out: &mut Out<'_, E>, code: &[Instr]) -> Result<(), E> {
    const PIECE: usize = 4096;
    let len = code.iter().map(|i| i.opcode().encoded_len()).sum();
    out.head(Section::Code, len)?;
    let mut piece = Vec::with_capacity(PIECE * MAX_ENCODED_LEN);
    for instrs in code.chunks(PIECE) {
        piece.clear();
        for instr in instrs {
            instr.encode(&mut piece);
        }
        out.put(&piece)?;
    }
    Ok(())
}

fn programs_out(o: &mut Vec<u8>, programs: &[Program]) {
    len_to_u32(programs.len()).put(o);
    for p in programs {
        p.number.put(o);
        p.entry.put(o);
        p.end.put(o);
        len_to_u32(p.seqs.len()).put(o);
        for &(seq, pc) in &p.seqs {
            seq.put(o);
            pc.put(o);
        }
        for table in [&p.loops, &p.seq_loops] {
            len_to_u32(table.len()).put(o);
            for &l in table {
                l.put(o);
            }
        }
    }
}

/// At least the bytes [`write`] writes for `m`.
fn size_bound(m: &Module) -> usize {
    const SLACK: usize = 256;
    let code: usize = m.code.iter().map(|i| i.opcode().encoded_len()).sum();
    let strings: usize = m.strings.iter().map(|s| 4 + s.len()).sum();
    let programs: usize = (m.programs.iter())
        .map(|p| 24 + 8 * p.seqs.len() + 4 * (p.loops.len() + p.seq_loops.len()))
        .sum();
    let files: usize = m.files.iter().map(|f| 8 + f.name.len()).sum();
    let lines = m.lines.heap_bytes();
    let tables = 8 * m.consts.len() + strings + programs + files + lines;
    SLACK + code + tables + m.machine.len() + m.blocks.len()
}

fn string_out(out: &mut Vec<u8>, s: &str) {
    len_to_u32(s.len()).put(out);
    out.extend_from_slice(s.as_bytes());
}
