//! The in-memory form of a `.gbc` file: code plus the tables it indexes.

use alloc::string::String;
use alloc::vec::Vec;

use crate::{Instr, LoadError};

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
    /// Source location of each instruction (same length as `code`).
    pub lines: Vec<SourceLoc>,
    /// Source files that `lines` refer to.
    pub files: Vec<SourceFileInfo>,
    /// The compile-relevant machine settings, canonical text: the VM refuses
    /// a module compiled for a different machine.
    pub machine: String,
    /// Registers used (`<= 256`); every `Reg` operand is `< num_regs`, so
    /// the VM can allocate the register file once.
    pub num_regs: u16,
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

    /// Parses a `.gbc` file and verifies it. Never panics and never
    /// allocates more than a small multiple of `bytes.len()`, whatever the
    /// bytes are.
    pub fn from_bytes(bytes: &[u8]) -> Result<Module, LoadError> {
        let module = crate::format::read(bytes)?;
        module.verify()?;
        Ok(module)
    }

    /// The pc of the first block numbered `seq` in program `prog`, if any.
    ///
    /// Relies on the sequence table being sorted (which `verify` checks);
    /// on an unverified module it may miss but never panics.
    pub fn pc_of_seq(&self, prog: usize, seq: u32) -> Option<u32> {
        let seqs = &self.programs.get(prog)?.seqs;
        let first = seqs.partition_point(|&(number, _)| number < seq);
        match seqs.get(first) {
            Some(&(number, pc)) if number == seq => Some(pc),
            _ => None,
        }
    }
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
    }
}

impl Eq for Module {}
