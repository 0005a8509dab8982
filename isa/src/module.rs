//! The in-memory form of a `.gbc` file: code plus the tables it indexes.

use alloc::string::String;
use alloc::vec::Vec;

use crate::block::{push_record, BlockWord};
use crate::{Instr, LineTable, LoadError};

/// A compiled module: what `gbcc` writes and the VM runs.
///
/// Build one freely; [`Module::verify`] (which [`Module::from_bytes`] always
/// runs) is what makes it safe to execute.
#[derive(Debug, Clone, Default)]
pub struct Module {
    /// The instructions of every program, back to back.
    pub code: Vec<Instr>,
    /// Constant pool (`Const` operands); any `f64`, NaNs included, kept
    /// bit-exact.
    pub consts: Vec<f64>,
    /// String table (`Str` operands): messages and comments.
    pub strings: Vec<String>,
    /// Program table (`Prog` operands); `programs[0]` is the main program.
    pub programs: Vec<Program>,
    /// Source location of each instruction (as many as `code`), as runs.
    pub lines: LineTable,
    /// Source files that `lines` refer to.
    pub files: Vec<SourceFileInfo>,
    /// The compile-relevant machine settings, canonical text: the VM refuses
    /// a module compiled for a different machine.
    pub machine: String,
    /// Registers used (`<= 256`); every `Reg` operand is `< num_regs`, so
    /// the VM can allocate the register file once.
    pub num_regs: u16,
    /// The records of the typed blocks (`block` operands are offsets into
    /// it), back to back; see [`block`](crate::block) for the layout.
    pub blocks: Vec<u8>,
}

/// One `O` program of the module.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct Program {
    /// The program number (`O0001` → 1).
    pub number: u32,
    /// First pc of its code.
    pub entry: u32,
    /// One past its last pc (`entry..end`).
    pub end: u32,
    /// `(sequence number, pc)`, sorted by number then pc: the run-time
    /// `GOTO`/`M99 P` targets. A number may repeat; the first block wins.
    pub seqs: Vec<(u32, u32)>,
    /// The program's DO loops, numbered from 1 in source order:
    /// `loops[i]` is the number of the loop that holds loop i + 1, 0 for
    /// none (so always less than i + 1). Empty in a program without loops.
    pub loops: Vec<u32>,
    /// The innermost loop that holds each entry of `seqs` (0: none), in
    /// the same order; empty when no numbered block lies in a loop.
    pub seq_loops: Vec<u32>,
}

/// Where an instruction came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SourceLoc {
    /// Index into `Module::files`.
    pub file: u16,
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub col: u32,
}

/// A source file the module was compiled from.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct SourceFileInfo {
    /// The name as given to the compiler.
    pub name: String,
    /// CRC32 of the file's bytes, so a debugger can tell a stale source.
    pub hash: u32,
}

impl Module {
    /// Serializes to the `.gbc` format (see [`format`](crate::format)).
    ///
    /// Does not verify: a module that fails [`Module::verify`] still writes
    /// (tests rely on that to forge bad files) but will not load.
    pub fn to_bytes(&self) -> Vec<u8> {
        crate::format::write(self)
    }

    /// Serializes as [`Module::to_bytes`] does, handing the bytes to
    /// `sink` a piece at a time, so that a large module goes to its file
    /// without a second copy in memory. Stops at the sink's first error.
    pub fn write_to<E>(&self, mut sink: impl FnMut(&[u8]) -> Result<(), E>) -> Result<(), E> {
        crate::format::write_with(self, &mut sink)
    }

    /// Parses a `.gbc` file and verifies it. Never panics and never
    /// allocates more than a small multiple of `bytes.len()`, whatever the
    /// bytes are.
    pub fn from_bytes(bytes: &[u8]) -> Result<Module, LoadError> {
        let (mut module, blocks) = crate::format::read(bytes)?;
        module.blocks = bytes.get(blocks).unwrap_or_default().to_vec();
        module.verify()?;
        Ok(module)
    }

    /// Like [`Module::from_bytes`], but keeps the file's buffer as the
    /// module's `blocks` (the section is last in the file): a large file
    /// is then in memory once, not twice.
    pub fn from_vec(mut bytes: Vec<u8>) -> Result<Module, LoadError> {
        let (mut module, blocks) = crate::format::read(&bytes)?;
        bytes.truncate(blocks.end);
        bytes.drain(..blocks.start);
        module.blocks = bytes;
        module.verify()?;
        Ok(module)
    }

    /// Appends a typed block of `words` to `blocks`; its offset for a
    /// `block` instruction, or `None` (nothing added) when the words do
    /// not fit a record (see [`block::encode_record`](crate::block::encode_record)).
    pub fn push_block(&mut self, words: &[BlockWord]) -> Option<u32> {
        push_record(words, &mut self.blocks)
    }

    /// The words of the typed block at `rec`, in order, each handed to
    /// `f`; `None` if no well-formed record starts there (never on a
    /// verified module's `block` operands).
    pub fn block_words(&self, rec: u32, f: impl FnMut(BlockWord)) -> Option<()> {
        let at = usize::try_from(rec).ok()?;
        crate::block::decode_record(&self.blocks, at, f)
            .ok()
            .map(|_| ())
    }

    /// The pc of the first block numbered `seq` in program `prog`, if any.
    ///
    /// Relies on the sequence table being sorted (which `verify` checks);
    /// on an unverified module it may miss but never panics.
    pub fn pc_of_seq(&self, prog: usize, seq: u32) -> Option<u32> {
        self.seq_target(prog, seq).map(|(pc, _)| pc)
    }

    /// The pc of the first block numbered `seq` in program `prog` and the
    /// innermost DO loop that holds it (0: none), if there is one.
    pub fn seq_target(&self, prog: usize, seq: u32) -> Option<(u32, u32)> {
        let p = self.programs.get(prog)?;
        let first = p.seqs.partition_point(|&(number, _)| number < seq);
        match p.seqs.get(first) {
            Some(&(number, pc)) if number == seq => {
                Some((pc, p.seq_loops.get(first).copied().unwrap_or(0)))
            }
            _ => None,
        }
    }

    /// Whether loop `outer` of program `prog` holds loop `inner` (a loop
    /// holds itself; loop 0, outside every loop, holds all). Bounded on an
    /// unverified module.
    pub fn loop_holds(&self, prog: usize, outer: u32, inner: u32) -> bool {
        (self.programs.get(prog)).is_some_and(|p| loop_holds(&p.loops, outer, inner))
    }
}

/// Whether loop `outer` holds loop `inner` in a table of loops numbered
/// from 1, `parents[i]` the loop that holds loop i + 1 (0: none) — a
/// program's `loops`, and the compiler's while it builds them. A loop
/// holds itself; 0, outside every loop, holds all. The walk is bounded, so
/// a crafted table cannot make it loop.
pub fn loop_holds(parents: &[u32], outer: u32, inner: u32) -> bool {
    let mut l = inner;
    for _ in 0..=parents.len() {
        if l == outer {
            return true;
        }
        match l.checked_sub(1).and_then(|i| parents.get(i as usize)) {
            Some(&parent) => l = parent,
            None => return outer == 0,
        }
    }
    false
}

/// Equality with constants compared bit for bit, so a module holding a NaN
/// equals itself and a round trip can be checked with `==` (which also
/// makes `Eq` sound).
impl PartialEq for Module {
    fn eq(&self, other: &Module) -> bool {
        // Destructured so a new field cannot be forgotten here.
        let Module {
            code,
            consts,
            strings,
            programs,
            lines,
            files,
            machine,
            num_regs,
            blocks,
        } = self;
        *code == other.code
            && consts.len() == other.consts.len()
            && consts
                .iter()
                .zip(&other.consts)
                .all(|(a, b)| a.to_bits() == b.to_bits())
            && *strings == other.strings
            && *programs == other.programs
            && *lines == other.lines
            && *files == other.files
            && *machine == other.machine
            && *num_regs == other.num_regs
            && *blocks == other.blocks
    }
}

impl Eq for Module {}
