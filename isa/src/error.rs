//! Why a `.gbc` file (or an in-memory module) was rejected.
//!
//! Positions are byte offsets into the file (`at`) or instruction indexes
//! (`pc`), so a tool can point at the culprit; the loader stops at the
//! first problem.

use crate::format::VERSION;

/// A `.gbc` file or module that the VM must not run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file does not start with `GBC\0`.
    #[error("not a .gbc file (bad magic number)")]
    BadMagic,
    /// Written by a newer (or older) gbc; the layout may differ.
    #[error("unsupported .gbc format version {found} (this build reads version {VERSION})")]
    UnsupportedVersion {
        /// The version in the file.
        found: u16,
    },
    /// The data ends, or a length or count field claims more bytes than
    /// its section holds.
    #[error("truncated .gbc file: data missing at byte {at}")]
    Truncated {
        /// File offset of the field that could not be read in full.
        at: usize,
    },
    /// The CRC32 trailer does not match: the file was damaged.
    #[error("checksum mismatch: the .gbc file is corrupt")]
    BadChecksum,
    /// Sections come in one fixed order; this one is not the one expected.
    #[error("unexpected section tag {found} at byte {at} (expected {expected})")]
    UnexpectedSection {
        /// File offset of the tag.
        at: usize,
        /// The tag found.
        found: u8,
        /// The tag required at this point.
        expected: u8,
    },
    /// A section (or the file) has bytes left over after its contents.
    #[error("unexpected trailing bytes at byte {at}")]
    TrailingBytes {
        /// File offset of the first left-over byte.
        at: usize,
    },
    /// A string, file name or the machine text is not UTF-8.
    #[error("invalid UTF-8 text at byte {at}")]
    BadUtf8 {
        /// File offset of the text.
        at: usize,
    },
    /// An opcode byte that no instruction has.
    #[error("unknown opcode byte 0x{byte:02x} at pc {pc}")]
    BadOpcode {
        /// Instruction index (from [`Instr::decode`](crate::Instr::decode)
        /// alone: the byte position, as it knows no instruction index).
        pc: u32,
        /// The byte.
        byte: u8,
    },
    /// A register operand `>= num_regs`.
    #[error("register out of range at pc {pc}")]
    RegisterOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// A jump target `>= code.len()`.
    #[error("jump target out of range at pc {pc}")]
    JumpOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// A constant index past the constant pool.
    #[error("constant index out of range at pc {pc}")]
    ConstOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// A string index past the string table.
    #[error("string index out of range at pc {pc}")]
    StringOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// A program index past the program table.
    #[error("program index out of range at pc {pc}")]
    ProgramOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// An operand outside its kind's domain (function code, comparison,
    /// word address, argument number).
    #[error("bad {what} operand at pc {pc}")]
    BadOperand {
        /// Instruction index.
        pc: u32,
        /// Which kind of operand.
        what: &'static str,
    },
    /// A block-skip guard (`skipblock`) whose target is not past it.
    #[error("block-skip guard at pc {pc} does not jump forward")]
    BackwardSkip {
        /// Instruction index.
        pc: u32,
    },
    /// The tables around the code are inconsistent.
    #[error(transparent)]
    BadTable(#[from] TableError),
}

/// What is wrong with a module's tables (see [`LoadError::BadTable`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TableError {
    /// `num_regs > 256`: registers are addressed by a `u8`.
    #[error("num_regs {num_regs} exceeds 256")]
    TooManyRegisters {
        /// The value found.
        num_regs: u16,
    },
    /// A table, string or code block too long for the format's `u32`
    /// lengths and indexes.
    #[error("{what} too large for the .gbc format")]
    TooLarge {
        /// Which table.
        what: &'static str,
    },
    /// `lines` must have one entry per instruction.
    #[error("{lines} source locations for {code} instructions")]
    LinesMismatch {
        /// `lines.len()`.
        lines: usize,
        /// `code.len()`.
        code: usize,
    },
    /// The code section's length cannot hold one instruction per entry
    /// of the line table (an instruction takes 1 to 8 bytes, the longest
    /// encoding in the opcode table); found from
    /// the declared sizes, before the code is decoded.
    #[error(
        "a code section of {bytes} bytes cannot hold the {lines} instructions its line table lists"
    )]
    CodeSize {
        /// Length of the code section.
        bytes: usize,
        /// Entries of the line table.
        lines: usize,
    },
    /// The line table's runs do not decode, or do not cover the code.
    #[error("bad line table at byte {at}: {what}")]
    BadLines {
        /// File offset of the table.
        at: usize,
        /// What is wrong.
        what: &'static str,
    },
    /// A typed block record that does not decode.
    #[error("bad typed block record at byte {at} of the blocks section: {what}")]
    BadBlock {
        /// Offset of the record in the section.
        at: usize,
        /// What is wrong.
        what: &'static str,
    },
    /// A `block` operand that is not where a record starts.
    #[error("block at pc {pc} names no record")]
    BlockOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// A `move` whose record is not a plain move.
    #[error("move at pc {pc} names a record that is not a plain move")]
    NotAMove {
        /// Instruction index.
        pc: u32,
    },
    /// A source location names a file past the file table.
    #[error("source location of pc {pc} names a missing file")]
    FileOutOfRange {
        /// Instruction index.
        pc: u32,
    },
    /// There must be at least the main program.
    #[error("program table is empty")]
    NoPrograms,
    /// Two programs with the same number (`O` number).
    #[error("program O{number:04} defined twice")]
    DuplicateProgram {
        /// The program number.
        number: u32,
    },
    /// A program's `entry..end` is not inside the code (or `entry > end`).
    #[error("program {index} has code range {entry}..{end} outside the code")]
    ProgramRange {
        /// Index into the program table.
        index: u32,
        /// Its entry pc.
        entry: u32,
        /// Its end pc.
        end: u32,
    },
    /// A program's sequence table is not sorted by number, then pc.
    #[error("sequence table of program {index} is not sorted")]
    SeqsUnsorted {
        /// Index into the program table.
        index: u32,
    },
    /// A sequence number points outside its program's code.
    #[error("N{seq} of program {index} points at pc {pc}, outside the program")]
    SeqOutOfRange {
        /// Index into the program table.
        index: u32,
        /// The sequence number.
        seq: u32,
        /// The pc it names.
        pc: u32,
    },
    /// A program's loop table names a loop that does not hold the one it
    /// should (a parent not before its child, or a loop out of range), or
    /// its sequence entries' loops do not match its sequence table.
    #[error("the loop table of program {index} is inconsistent")]
    BadLoops {
        /// Index into the program table.
        index: u32,
    },
    /// A `gotoseqin` names a loop its program does not have.
    #[error("instruction {pc} names a loop its program does not have")]
    LoopOutOfRange {
        /// The instruction's pc.
        pc: u32,
    },
}
