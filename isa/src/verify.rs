//! The verifier: after it accepts a module, every index an instruction or
//! table holds points at something that exists, so the VM may index without
//! checking and trust that no file can make it panic.

use alloc::vec::Vec;

use crate::block::{RecordError, RecordStarts, Records};
use crate::encoding::len_to_u32;
use crate::{addr, CmpOp, Instr, LoadError, MathFunc, Module, Operand, TableError, SWITCHES};

/// Registers are addressed by a `u8`.
const MAX_REGS: u16 = 256;

/// The local variables a macro-call argument can set: `#1..=#33` (the
/// compiler maps argument letters onto them).
const ARG_VARS: core::ops::RangeInclusive<u8> = 1..=33;

impl Module {
    /// Checks every cross-reference; the first problem found is returned.
    ///
    /// [`Module::from_bytes`] runs this, and the compiler may run it on what
    /// it built. What is checked: sizes fit the format; `num_regs <= 256`;
    /// every operand is in range for its kind; one source location per
    /// instruction, each naming a listed file; a non-empty program table with
    /// distinct numbers, code ranges inside the code and sorted sequence
    /// tables pointing into their own program; a block-skip guard jumps
    /// forward; every typed block record decodes (addresses valid,
    /// varints and decimals well formed, raw values finite, nothing past
    /// the section) and every `block`, `profile` and `move` operand is
    /// where one starts (a `move`'s, where a plain move's does).
    pub fn verify(&self) -> Result<(), LoadError> {
        self.verify_walked(RecordStarts::default())
    }

    /// [`Module::verify`] with `records` as the module's `blocks` (they
    /// replace what it held), the walk of their records done so far
    /// reused: only what was added since their last [`Records::walk`] is
    /// walked here. The same checks as `verify`, and the same first error.
    /// (The bytes come with the walk, not apart: a walk vouches only for
    /// the bytes it was done on.)
    pub fn verify_with(&mut self, records: Records) -> Result<(), LoadError> {
        let (bytes, walk) = records.into_parts();
        self.blocks = bytes;
        self.verify_walked(walk)
    }

    /// `verify`, with `walk` the walk so far of these very `blocks` (of a
    /// prefix of them, as `Records` keeps it; empty for a walk from
    /// scratch), carried on over the rest.
    fn verify_walked(&self, walk: RecordStarts) -> Result<(), LoadError> {
        self.verify_sizes()?;
        if self.num_regs > MAX_REGS {
            return Err(TableError::TooManyRegisters {
                num_regs: self.num_regs,
            }
            .into());
        }
        // Tables first: an operand error is only meaningful once the table
        // it indexes is known to be sound.
        self.verify_programs()?;
        self.verify_lines()?;
        let bad_block = |(at, e): (usize, RecordError)| TableError::BadBlock { at, what: e.what() };
        let records = walk.complete(&self.blocks).map_err(bad_block)?;
        let spans = self.program_spans();
        for (pc, instr) in self.code.iter().enumerate() {
            let pc = len_to_u32(pc);
            instr.try_visit_operands(|op| self.check_operand(pc, op))?;
            if let Instr::Block { rec } | Instr::Profile { rec } | Instr::Move { rec } = *instr {
                if !records.contains(rec) {
                    return Err(TableError::BlockOutOfRange { pc }.into());
                }
            }
            if let Instr::Move { rec } = *instr {
                if !records.is_move(rec) {
                    return Err(TableError::NotAMove { pc }.into());
                }
            }
            if let Instr::GotoSeqIn { inside, .. } = *instr {
                let loops = loops_at(&spans, pc);
                if inside == 0 || usize::try_from(inside).map_or(true, |l| l > loops) {
                    return Err(TableError::LoopOutOfRange { pc }.into());
                }
            }
            if let Instr::SkipBlock { target, .. } = *instr {
                // Forward only: between two charges of the block budget
                // the pc must only move forward (the VM's bound).
                if target <= pc {
                    return Err(LoadError::BackwardSkip { pc });
                }
            }
        }
        Ok(())
    }

    /// Every count must fit the format's `u32` fields (only reachable by an
    /// in-memory module: a file cannot express more).
    fn verify_sizes(&self) -> Result<(), LoadError> {
        let too_large = |what| Err(TableError::TooLarge { what }.into());
        let fits = |n: usize| u32::try_from(n).is_ok();
        if !fits(self.code.len()) {
            return too_large("code");
        }
        if !fits(self.consts.len()) {
            return too_large("constant pool");
        }
        if !fits(self.strings.len()) || !self.strings.iter().all(|s| fits(s.len())) {
            return too_large("string table");
        }
        if !fits(self.programs.len()) || !self.programs.iter().all(|p| fits(p.seqs.len())) {
            return too_large("program table");
        }
        if !fits(self.lines.len()) {
            return too_large("line table");
        }
        if !fits(self.files.len()) || !self.files.iter().all(|f| fits(f.name.len())) {
            return too_large("file table");
        }
        if !fits(self.machine.len()) {
            return too_large("machine text");
        }
        if !fits(self.blocks.len()) {
            return too_large("blocks section");
        }
        Ok(())
    }

    /// Each program's code as `(entry, end, loop count)`, sorted.
    fn program_spans(&self) -> Vec<(u32, u32, usize)> {
        let mut spans: Vec<_> = (self.programs.iter())
            .map(|p| (p.entry, p.end, p.loops.len()))
            .collect();
        spans.sort_unstable();
        spans
    }

    #[inline]
    fn check_operand(&self, pc: u32, op: Operand) -> Result<(), LoadError> {
        let below = |index: u32, len: usize| usize::try_from(index).is_ok_and(|i| i < len);
        let ok = match op {
            Operand::Reg(r) => u16::from(r) < self.num_regs,
            Operand::Pc(target) => below(target, self.code.len()),
            Operand::Const(k) => below(k, self.consts.len()),
            Operand::Str(s) => below(s, self.strings.len()),
            Operand::Prog(p) => below(p, self.programs.len()),
            Operand::FuncCode(f) => MathFunc::from_code(f).is_some(),
            Operand::CmpCode(c) => CmpOp::from_code(c).is_some(),
            Operand::Addr(a) => a <= addr::MAX,
            Operand::ArgVar(v) => ARG_VARS.contains(&v),
            Operand::Switch(n) => SWITCHES.contains(&n),
            // Followed through the records in `verify`.
            Operand::Rec(_) => true,
            // Flags, alarm codes and variable numbers: any value; the VM
            // gives them meaning (an unknown #var is a run-time alarm).
            Operand::U8(_) | Operand::U16(_) | Operand::U32(_) | Operand::Var(_) => true,
        };
        if ok {
            Ok(())
        } else {
            Err(operand_error(pc, op))
        }
    }

    fn verify_lines(&self) -> Result<(), LoadError> {
        if self.lines.len() != self.code.len() {
            return Err(TableError::LinesMismatch {
                lines: self.lines.len(),
                code: self.code.len(),
            }
            .into());
        }
        let files_ok = self
            .lines
            .max_file()
            .is_none_or(|f| usize::from(f) < self.files.len());
        if files_ok {
            return Ok(());
        }
        // The first culprit, found only once there is one.
        let pc = self
            .lines
            .iter()
            .position(|loc| usize::from(loc.file) >= self.files.len())
            .unwrap_or(0);
        Err(TableError::FileOutOfRange { pc: len_to_u32(pc) }.into())
    }

    fn verify_programs(&self) -> Result<(), LoadError> {
        if self.programs.is_empty() {
            return Err(TableError::NoPrograms.into());
        }
        let code_len = self.code.len();
        for (index, p) in self.programs.iter().enumerate() {
            let index = len_to_u32(index);
            let end_ok = usize::try_from(p.end).is_ok_and(|end| end <= code_len);
            if p.entry > p.end || !end_ok {
                return Err(TableError::ProgramRange {
                    index,
                    entry: p.entry,
                    end: p.end,
                }
                .into());
            }
            // Strictly increasing (number, pc): sorted, and no entry twice.
            if !p.seqs.is_sorted_by(|a, b| a < b) {
                return Err(TableError::SeqsUnsorted { index }.into());
            }
            if let Some(&(seq, pc)) = p
                .seqs
                .iter()
                .find(|&&(_, pc)| !(p.entry..p.end).contains(&pc))
            {
                return Err(TableError::SeqOutOfRange { index, seq, pc }.into());
            }
            if !loops_ok(p) {
                return Err(TableError::BadLoops { index }.into());
            }
        }
        let mut numbers: Vec<u32> = self.programs.iter().map(|p| p.number).collect();
        numbers.sort_unstable();
        let duplicate = numbers.windows(2).find_map(|w| match *w {
            [a, b] if a == b => Some(a),
            _ => None,
        });
        match duplicate {
            Some(number) => Err(TableError::DuplicateProgram { number }.into()),
            None => Ok(()),
        }
    }
}

/// The loop count of the program whose code holds `pc` (0 for none):
/// of those that start at or before it, the last, the longest of any
/// that start together.
fn loops_at(spans: &[(u32, u32, usize)], pc: u32) -> usize {
    let i = spans.partition_point(|&(entry, _, _)| entry <= pc);
    match i.checked_sub(1).and_then(|i| spans.get(i)) {
        Some(&(_, end, loops)) if pc < end => loops,
        _ => 0,
    }
}

/// A program's loop tables: each loop's parent comes before it (so the
/// loops nest, and a walk to the outermost ends), and each sequence entry
/// (all or none) names a loop that exists.
fn loops_ok(p: &crate::Program) -> bool {
    let parents = (p.loops.iter().enumerate()).all(|(i, &parent)| (parent as usize) <= i);
    let entries = p.seq_loops.is_empty() || p.seq_loops.len() == p.seqs.len();
    let known = (p.seq_loops.iter()).all(|&l| (l as usize) <= p.loops.len());
    parents && entries && known
}

/// The error of an operand that failed its check (kept out of the checking
/// loop, which runs for every operand of every instruction).
#[cold]
fn operand_error(pc: u32, op: Operand) -> LoadError {
    let what = match op {
        Operand::Reg(_) => return LoadError::RegisterOutOfRange { pc },
        Operand::Pc(_) => return LoadError::JumpOutOfRange { pc },
        Operand::Const(_) => return LoadError::ConstOutOfRange { pc },
        Operand::Str(_) => return LoadError::StringOutOfRange { pc },
        Operand::Prog(_) => return LoadError::ProgramOutOfRange { pc },
        Operand::Rec(_) => return TableError::BlockOutOfRange { pc }.into(),
        Operand::FuncCode(_) => "math function",
        Operand::CmpCode(_) => "comparison",
        Operand::Addr(_) => "word address",
        Operand::ArgVar(_) => "argument variable",
        Operand::Switch(_) => "block-skip switch",
        Operand::U8(_) | Operand::U16(_) | Operand::U32(_) | Operand::Var(_) => "plain",
    };
    LoadError::BadOperand { pc, what }
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;
    use crate::block::BlockWord;
    use crate::{Program, SourceFileInfo, SourceLoc};

    /// Word addresses: G, M, X and Z.
    const G: u8 = 6;
    const M: u8 = 12;
    const X: u8 = 23;
    const Z: u8 = 25;

    fn word(addr: u8, value: f64) -> BlockWord {
        BlockWord {
            addr,
            value,
            flags: 0,
        }
    }

    /// The words of record `i`: mostly plain moves, every third an M code
    /// (not a move), every fifth with a raw value (a longer record).
    fn record(i: usize) -> Vec<BlockWord> {
        let x = i as f64 * 0.5;
        match i % 5 {
            _ if i % 3 == 2 => vec![word(M, 3.0), word(X, x)],
            4 => vec![word(G, 1.0), word(X, 0.1 + 0.2), word(Z, -x)],
            _ => vec![word(G, 1.0), word(X, x), word(Z, -x)],
        }
    }

    /// A module of one program whose code names each record at `recs`
    /// (a `move` where `moves` says, a `block` elsewhere), then halts.
    fn naming(recs: &[(u32, bool)]) -> Module {
        let mut code: Vec<Instr> = (recs.iter())
            .map(|&(rec, plain)| match plain {
                true => Instr::Move { rec },
                false => Instr::Block { rec },
            })
            .collect();
        code.push(Instr::Halt);
        let end = len_to_u32(code.len());
        Module {
            lines: vec![SourceLoc::default(); code.len()].into(),
            code,
            programs: vec![Program {
                number: 1,
                entry: 0,
                end,
                ..Program::default()
            }],
            files: vec![SourceFileInfo::default()],
            num_regs: 1,
            ..Module::default()
        }
    }

    /// `count` records, walked after every `piece` of them (0: never):
    /// the records, and their offsets with whether each is a plain move.
    fn pushed(count: usize, piece: usize) -> (Records, Vec<(u32, bool)>) {
        let mut records = Records::default();
        let mut recs = Vec::new();
        for i in 0..count {
            let at = records.push(&record(i)).expect("the record fits");
            recs.push((at, i % 3 != 2));
            if piece != 0 && (i + 1) % piece == 0 {
                assert_eq!(records.walk(), Ok(()));
            }
        }
        (records, recs)
    }

    /// `verify_with` on `records` and `verify` on a module holding their
    /// bytes, from `module` as it is.
    fn both(module: &Module, records: Records) -> (Result<(), LoadError>, Result<(), LoadError>) {
        let mut whole = module.clone();
        whole.blocks = records.bytes().to_vec();
        let mut with = module.clone();
        (with.verify_with(records), whole.verify())
    }

    fn bad_block(at: usize, e: RecordError) -> Result<(), LoadError> {
        Err(TableError::BadBlock { at, what: e.what() }.into())
    }

    #[test]
    fn a_walk_in_pieces_is_the_walk_of_the_whole() {
        for piece in [1, 2, 7, 64, 200] {
            let (mut records, recs) = pushed(200, piece);
            // (The last piece: what is left.)
            assert_eq!(records.walk(), Ok(()));
            let whole = RecordStarts::of(records.bytes()).expect("the records decode");
            assert_eq!(records.walked(), &whole, "piece {piece}");
            assert_eq!(whole.walked(), records.bytes().len());
            assert_eq!(both(&naming(&recs), records), (Ok(()), Ok(())));
        }
    }

    #[test]
    fn operands_are_checked_against_a_walk_in_pieces() {
        let (_, recs) = pushed(50, 0);
        // A `block` between two records, past the last one, and a `move`
        // naming an M code.
        let (between, _) = recs[10];
        let mut past = recs.clone();
        past[20] = (u32::MAX, false);
        let mut not_a_move = recs.clone();
        not_a_move[2].1 = true;
        let mut inside = recs.clone();
        inside[7] = (between + 1, false);
        let cases = [
            (inside, TableError::BlockOutOfRange { pc: 7 }),
            (past, TableError::BlockOutOfRange { pc: 20 }),
            (not_a_move, TableError::NotAMove { pc: 2 }),
        ];
        for (named, want) in cases {
            let (records, _) = pushed(50, 3);
            let want = Err(want.into());
            assert_eq!(both(&naming(&named), records), (want.clone(), want));
        }
    }

    /// Bad records, each with its error, appended raw after good ones.
    fn bad_records() -> [(&'static [u8], RecordError); 5] {
        [
            (&[1, X, 45], RecordError::BadDecimal),
            (&[0], RecordError::Empty),
            (&[1, 29, 5], RecordError::BadAddress),
            (&[1, X, 0x96, 0x00], RecordError::BadVarint),
            (&[2, X, 5], RecordError::Truncated),
        ]
    }

    #[test]
    fn a_bad_record_in_a_later_piece_is_found_where_a_whole_walk_finds_it() {
        for (bad, e) in bad_records() {
            let (mut records, recs) = pushed(30, 10);
            let at = records.bytes().len();
            records.append_raw(bad);
            if e != RecordError::Truncated {
                // (A truncated record can only be the last.)
                records.push(&record(1)).expect("the record fits");
            }
            assert_eq!(records.walk(), Err((at, e)), "{bad:?}");
            // The walk stopped before it: found again.
            assert_eq!(records.walked().walked(), at);
            assert_eq!(records.walk(), Err((at, e)));
            let want = bad_block(at, e);
            assert_eq!(both(&naming(&recs), records), (want.clone(), want));
        }
    }

    #[test]
    fn a_walk_that_stopped_short_is_carried_on() {
        // Good records, then bad ones, not walked yet.
        let (records, recs) = pushed(40, 16);
        assert!(records.walked().walked() < records.bytes().len());
        assert_eq!(both(&naming(&recs), records), (Ok(()), Ok(())));
        for (bad, e) in bad_records() {
            let (mut records, recs) = pushed(40, 16);
            let at = records.bytes().len();
            records.append_raw(bad);
            let want = bad_block(at, e);
            assert_eq!(both(&naming(&recs), records), (want.clone(), want));
        }
        // A section never walked.
        let (records, recs) = pushed(40, 0);
        let bytes = records.into_bytes();
        let (with, whole) = both(&naming(&recs), Records::from(bytes));
        assert_eq!((with, whole), (Ok(()), Ok(())));
    }

    #[test]
    fn a_walk_past_the_section_is_done_again() {
        // The section ends inside its third record; a walk of more bytes
        // saw that record whole, and the operand naming it would pass.
        let (records, recs) = pushed(3, 0);
        let bytes = records.into_bytes();
        let cut = bytes.len() - 1;
        let longer = RecordStarts::of(&bytes).expect("the records decode");
        let mut module = naming(&recs);
        module.blocks = bytes[..cut].to_vec();
        let (third, _) = recs[2];
        let want = bad_block(third as usize, RecordError::Truncated);
        assert_eq!(module.verify(), want);
        assert_eq!(module.verify_walked(longer), want);
        // And one that is not bad, only shorter: records 0 and 1.
        let mut shorter = naming(&recs[..2]);
        shorter.blocks = bytes[..third as usize].to_vec();
        let longer = RecordStarts::of(&bytes).expect("the records decode");
        let walk = longer
            .complete(&shorter.blocks)
            .expect("the records decode");
        assert_eq!(walk.walked(), third as usize);
        assert!(!walk.contains(third), "no record starts at the end");
        assert_eq!(shorter.verify_walked(RecordStarts::default()), Ok(()));
    }
}
