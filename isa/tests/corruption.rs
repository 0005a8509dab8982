//! A damaged or forged `.gbc` file is rejected with a typed error, never
//! loaded and never a panic.

mod common;

use common::{edit_lines, put_u32, reseal, sample_module, seal, section};
use isa::format::{Section, CRC_LEN, HEADER_LEN, MAGIC, VERSION};
use isa::{addr, Instr, LoadError, Module, Program, TableError};
use proptest::prelude::*;

fn sample_bytes() -> Vec<u8> {
    sample_module().to_bytes()
}

/// Accepting a file is fine only if it is well formed: it verifies and is
/// the one encoding of what it decodes to.
fn check_accepted(bytes: &[u8], module: &Module) {
    assert_eq!(module.verify(), Ok(()));
    assert_eq!(module.to_bytes(), bytes, "accepted a non-canonical file");
}

// ---------------------------------------------------------------------------
// Truncation and bit flips over the whole file

#[test]
fn every_truncation_is_rejected() {
    let bytes = sample_bytes();
    for len in 0..bytes.len() {
        let err = Module::from_bytes(&bytes[..len]).expect_err("truncated file loaded");
        assert!(
            matches!(err, LoadError::Truncated { .. } | LoadError::BadChecksum),
            "length {len}: {err:?}"
        );
    }
}

#[test]
fn every_truncation_with_a_fresh_checksum_is_rejected() {
    // Past the checksum, the parser itself must notice the missing data.
    let bytes = sample_bytes();
    let body = &bytes[..bytes.len() - CRC_LEN];
    for len in 0..body.len() {
        let file = seal(body[..len].to_vec());
        assert!(
            Module::from_bytes(&file).is_err(),
            "body cut at {len} loaded"
        );
    }
}

#[test]
fn every_bit_flip_is_rejected() {
    let bytes = sample_bytes();
    for bit in 0..bytes.len() * 8 {
        let mut bad = bytes.clone();
        bad[bit / 8] ^= 1 << (bit % 8);
        assert!(
            Module::from_bytes(&bad).is_err(),
            "flip of bit {bit} loaded"
        );
    }
}

#[test]
fn every_bit_flip_with_a_fresh_checksum_is_rejected_or_canonical() {
    // Some flips make another valid module (a different constant, another
    // in-range register); those must still verify and re-encode the same.
    let bytes = sample_bytes();
    let mut accepted = 0;
    for bit in 0..(bytes.len() - CRC_LEN) * 8 {
        let mut bad = bytes.clone();
        bad[bit / 8] ^= 1 << (bit % 8);
        let bad = reseal(bad);
        if let Ok(module) = Module::from_bytes(&bad) {
            check_accepted(&bad, &module);
            accepted += 1;
        }
    }
    assert!(accepted > 0, "expected some flips to give valid modules");
}

// ---------------------------------------------------------------------------
// Header and checksum

#[test]
fn bad_magic() {
    let mut bytes = sample_bytes();
    bytes[0] = b'X';
    assert_eq!(Module::from_bytes(&bytes), Err(LoadError::BadMagic));
    assert_eq!(Module::from_bytes(b"PK\x03\x04"), Err(LoadError::BadMagic));
    assert_eq!(
        Module::from_bytes(b"G"),
        Err(LoadError::Truncated { at: 1 })
    );
    assert_eq!(
        Module::from_bytes(b"GBC\0\x01"),
        Err(LoadError::Truncated { at: 4 })
    );
    assert_eq!(Module::from_bytes(b""), Err(LoadError::Truncated { at: 0 }));
}

#[test]
fn unsupported_version() {
    let mut bytes = sample_bytes();
    bytes[4..6].copy_from_slice(&(VERSION + 1).to_le_bytes());
    let expected = Err(LoadError::UnsupportedVersion { found: VERSION + 1 });
    assert_eq!(Module::from_bytes(&bytes), expected);
    assert_eq!(Module::from_bytes(&reseal(bytes)), expected);
}

#[test]
fn bad_checksum() {
    let mut bytes = sample_bytes();
    let last = bytes.len() - 1;
    bytes[last] ^= 0x80;
    assert_eq!(Module::from_bytes(&bytes), Err(LoadError::BadChecksum));
    // A header and a trailer but nothing else.
    let mut tiny = MAGIC.to_vec();
    tiny.extend_from_slice(&VERSION.to_le_bytes());
    tiny.extend_from_slice(&[0; CRC_LEN]);
    assert_eq!(Module::from_bytes(&tiny), Err(LoadError::BadChecksum));
    tiny.truncate(HEADER_LEN);
    assert_eq!(
        Module::from_bytes(&seal(tiny)),
        Err(LoadError::Truncated { at: HEADER_LEN })
    );
}

// ---------------------------------------------------------------------------
// Forged at the byte level, with a correct checksum

#[test]
fn bad_opcode_byte() {
    let bytes = sample_bytes();
    let code = section(&bytes, Section::Code);
    let second = code.payload + sample_module().code[0].encoded_len();
    for byte in (0..=u8::MAX).filter(|&b| isa::Opcode::from_u8(b).is_none()) {
        let mut bad = bytes.clone();
        bad[code.payload] = byte;
        assert_eq!(
            Module::from_bytes(&reseal(bad)),
            Err(LoadError::BadOpcode { pc: 0, byte }),
        );
        let mut bad = bytes.clone();
        bad[second] = byte;
        assert_eq!(
            Module::from_bytes(&reseal(bad)),
            Err(LoadError::BadOpcode { pc: 1, byte }),
        );
    }
}

#[test]
fn huge_length_fields() {
    let bytes = sample_bytes();
    // (section, offset in its payload of a u32 length or count)
    let strings = section(&bytes, Section::Strings);
    let cases = [
        (
            "code section length",
            section(&bytes, Section::Code).len_field,
        ),
        ("consts count", section(&bytes, Section::Consts).payload),
        ("strings count", strings.payload),
        ("first string length", strings.payload + 4),
        ("programs count", section(&bytes, Section::Programs).payload),
        (
            "first seq count",
            section(&bytes, Section::Programs).payload + 4 + 12,
        ),
        ("files count", section(&bytes, Section::Files).payload),
        (
            "machine length",
            section(&bytes, Section::Machine).len_field,
        ),
    ];
    for (what, at) in cases {
        for huge in [u32::MAX, u32::MAX / 2, 0x0100_0000] {
            let mut bad = bytes.clone();
            put_u32(&mut bad, at, huge);
            assert_eq!(
                Module::from_bytes(&reseal(bad)),
                Err(LoadError::Truncated { at }),
                "{what} = {huge:#x}"
            );
        }
    }
}

#[test]
fn a_huge_line_count_is_refused_against_the_code() {
    // The line table's count is of instructions, not of its records: a
    // huge one is out of proportion to the code section (164 bytes).
    let bytes = sample_module().to_bytes();
    let at = section(&bytes, Section::Lines).payload;
    let code = section(&bytes, Section::Code).len;
    let mut bad = bytes.clone();
    put_u32(&mut bad, at, u32::MAX);
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(TableError::CodeSize {
            bytes: code,
            lines: u32::MAX as usize
        }
        .into())
    );
}

#[test]
fn code_ending_mid_instruction() {
    // Without the final `ret`, the code ends in `retseq r0`; cut its
    // operand byte off (and shorten the section to match).
    let mut module = sample_module();
    module.code.pop();
    edit_lines(&mut module, |l| {
        l.pop();
    });
    module.programs[1].end -= 1;
    let mut bytes = module.to_bytes();
    let code = section(&bytes, Section::Code);
    let last = code.payload + code.len - 1; // the `r0` of `retseq r0`
    bytes.remove(last);
    put_u32(&mut bytes, code.len_field, (code.len - 1) as u32);
    assert_eq!(
        Module::from_bytes(&reseal(bytes)),
        Err(LoadError::Truncated { at: last })
    );
}

#[test]
fn sections_out_of_order() {
    let mut module = sample_module();
    module.machine.clear();
    let mut bytes = module.to_bytes();
    // Swap the (empty) machine section with the regs section's tag.
    let machine = section(&bytes, Section::Machine);
    bytes[machine.tag] = Section::Regs as u8;
    assert_eq!(
        Module::from_bytes(&reseal(bytes)),
        Err(LoadError::UnexpectedSection {
            at: machine.tag,
            found: Section::Regs as u8,
            expected: Section::Machine as u8,
        })
    );
}

#[test]
fn trailing_bytes() {
    let bytes = sample_bytes();
    // One extra byte after the last section.
    let mut bad = bytes.clone();
    let at = bad.len() - CRC_LEN;
    bad.insert(at, 0);
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::TrailingBytes { at })
    );
    // A section longer than its contents.
    let mut bad = bytes.clone();
    let regs = section(&bad, Section::Regs);
    bad.insert(regs.payload + regs.len, 0);
    put_u32(&mut bad, regs.len_field, regs.len as u32 + 1);
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::TrailingBytes {
            at: regs.payload + regs.len
        })
    );
    // Constant pool with a count one short of its bytes.
    let mut bad = bytes;
    let consts = section(&bad, Section::Consts);
    put_u32(&mut bad, consts.payload, 3);
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::TrailingBytes {
            at: consts.payload + 4 + 3 * 8
        })
    );
}

#[test]
fn bad_utf8() {
    let bytes = sample_bytes();
    let strings = section(&bytes, Section::Strings);
    let first_text = strings.payload + 8; // count, length
    let mut bad = bytes.clone();
    bad[first_text] = 0xFF;
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::BadUtf8 { at: first_text })
    );

    let files = section(&bytes, Section::Files);
    let mut bad = bytes.clone();
    bad[files.payload + 8] = 0xC0;
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::BadUtf8 {
            at: files.payload + 8
        })
    );

    let machine = section(&bytes, Section::Machine);
    let mut bad = bytes;
    bad[machine.payload + 3] = 0x80;
    assert_eq!(
        Module::from_bytes(&reseal(bad)),
        Err(LoadError::BadUtf8 {
            at: machine.payload
        })
    );
}

// ---------------------------------------------------------------------------
// Forged as modules: structurally fine, semantically wrong. `to_bytes` does
// not verify, so it writes them with a correct checksum.

/// `verify` on the module and `from_bytes` on its file give `expected`.
fn rejects(module: Module, expected: LoadError) {
    assert_eq!(module.verify(), Err(expected.clone()), "verify");
    assert_eq!(
        Module::from_bytes(&module.to_bytes()),
        Err(expected),
        "from_bytes"
    );
}

fn with(edit: impl FnOnce(&mut Module)) -> Module {
    let mut m = sample_module();
    edit(&mut m);
    m
}

#[test]
fn register_out_of_range() {
    rejects(
        with(|m| m.code[2] = Instr::Mov { dst: 7, src: 0 }),
        LoadError::RegisterOutOfRange { pc: 2 },
    );
    rejects(
        with(|m| {
            m.code[18] = Instr::Cmp {
                dst: 6,
                a: 0,
                b: 255,
                op: 0,
            }
        }),
        LoadError::RegisterOutOfRange { pc: 18 },
    );
    rejects(
        with(|m| m.num_regs = 6),
        LoadError::RegisterOutOfRange { pc: 18 },
    );
}

#[test]
fn too_many_registers() {
    rejects(
        with(|m| m.num_regs = 257),
        TableError::TooManyRegisters { num_regs: 257 }.into(),
    );
    // 256 is the most a u8 can address, and allowed.
    assert_eq!(with(|m| m.num_regs = 256).verify(), Ok(()));
}

#[test]
fn jump_out_of_range() {
    let len = sample_module().code.len() as u32;
    rejects(
        with(|m| m.code[35] = Instr::Jump { target: len }),
        LoadError::JumpOutOfRange { pc: 35 },
    );
    rejects(
        with(|m| {
            m.code[19] = Instr::JumpIfNot {
                cond: 6,
                target: u32::MAX,
            }
        }),
        LoadError::JumpOutOfRange { pc: 19 },
    );
}

#[test]
fn const_out_of_range() {
    rejects(
        with(|m| m.code[0] = Instr::LoadK { dst: 0, k: 4 }),
        LoadError::ConstOutOfRange { pc: 0 },
    );
    rejects(
        with(|m| {
            m.code[20] = Instr::WordK {
                addr: 23,
                k: u32::MAX,
                flags: 0,
            }
        }),
        LoadError::ConstOutOfRange { pc: 20 },
    );
}

#[test]
fn string_out_of_range() {
    rejects(
        with(|m| m.code[22] = Instr::SetMsg { s: 2 }),
        LoadError::StringOutOfRange { pc: 22 },
    );
    rejects(
        with(|m| {
            m.strings.pop();
        }),
        LoadError::StringOutOfRange { pc: 34 },
    );
}

#[test]
fn program_out_of_range() {
    rejects(
        with(|m| m.code[25] = Instr::CallSub { prog: 2, count: 1 }),
        LoadError::ProgramOutOfRange { pc: 25 },
    );
}

#[test]
fn bad_operands() {
    let cases = [
        (
            16,
            Instr::Func {
                dst: 5,
                a: 0,
                f: 15,
            },
            "math function",
        ),
        (
            18,
            Instr::Cmp {
                dst: 6,
                a: 0,
                b: 2,
                op: 6,
            },
            "comparison",
        ),
        (
            21,
            Instr::Word {
                addr: addr::MAX + 1,
                src: 5,
            },
            "word address",
        ),
        (
            20,
            Instr::WordK {
                addr: 255,
                k: 1,
                flags: 1,
            },
            "word address",
        ),
        (27, Instr::Arg { var: 0, src: 0 }, "argument variable"),
        (28, Instr::Arg { var: 34, src: 2 }, "argument variable"),
        // `/` is switch 1 and `/9` the last: 0 and 10 name no switch.
        (
            36,
            Instr::SkipBlock {
                switch: 0,
                target: 37,
            },
            "block-skip switch",
        ),
        (
            36,
            Instr::SkipBlock {
                switch: 10,
                target: 37,
            },
            "block-skip switch",
        ),
    ];
    for (pc, instr, what) in cases {
        rejects(
            with(|m| m.code[pc as usize] = instr),
            LoadError::BadOperand { pc, what },
        );
    }
}

#[test]
fn malformed_block_skip_guards() {
    // The sample's guard is at pc 36 and skips to the `halt` at 37.
    let len = sample_module().code.len() as u32;
    rejects(
        with(|m| {
            m.code[36] = Instr::SkipBlock {
                switch: 1,
                target: len,
            }
        }),
        LoadError::JumpOutOfRange { pc: 36 },
    );
    // A guard may only skip forward: onto itself or back would let a loop
    // run without charging the block budget (`rejects` also loads the
    // file, so this is the loader's answer too).
    for target in [36, 0] {
        rejects(
            with(|m| m.code[36] = Instr::SkipBlock { switch: 1, target }),
            LoadError::BackwardSkip { pc: 36 },
        );
    }
}

#[test]
fn bad_seq_tables() {
    let main_end = sample_module().programs[0].end;
    rejects(
        with(|m| m.programs[0].seqs = vec![(10, 0), (20, main_end)]),
        TableError::SeqOutOfRange {
            index: 0,
            seq: 20,
            pc: main_end,
        }
        .into(),
    );
    // The macro's label may not point into the main program.
    rejects(
        with(|m| m.programs[1].seqs = vec![(1, 5)]),
        TableError::SeqOutOfRange {
            index: 1,
            seq: 1,
            pc: 5,
        }
        .into(),
    );
    rejects(
        with(|m| m.programs[0].seqs = vec![(20, 22), (10, 0)]),
        TableError::SeqsUnsorted { index: 0 }.into(),
    );
    rejects(
        with(|m| m.programs[0].seqs = vec![(20, 30), (20, 22)]),
        TableError::SeqsUnsorted { index: 0 }.into(),
    );
}

#[test]
fn bad_program_tables() {
    rejects(with(|m| m.programs.clear()), TableError::NoPrograms.into());
    rejects(
        with(|m| m.programs[1].number = 1),
        TableError::DuplicateProgram { number: 1 }.into(),
    );
    let len = sample_module().code.len() as u32;
    rejects(
        with(|m| m.programs[1].end = len + 1),
        TableError::ProgramRange {
            index: 1,
            entry: len - 3,
            end: len + 1,
        }
        .into(),
    );
    rejects(
        with(|m| {
            m.programs[1].entry = len;
            m.programs[1].end = len - 1;
            m.programs[1].seqs.clear();
        }),
        TableError::ProgramRange {
            index: 1,
            entry: len,
            end: len - 1,
        }
        .into(),
    );
    // An empty program at the very end is allowed by the format.
    let m = with(|m| {
        m.programs.push(Program {
            number: 2,
            entry: len,
            end: len,
            ..Program::default()
        });
    });
    assert_eq!(m.verify(), Ok(()));
}

#[test]
fn bad_line_tables() {
    rejects(
        with(|m| {
            edit_lines(m, |l| {
                l.pop();
            })
        }),
        TableError::LinesMismatch {
            lines: 40,
            code: 41,
        }
        .into(),
    );
    rejects(
        with(|m| edit_lines(m, |l| l[7].file = 2)),
        TableError::FileOutOfRange { pc: 7 }.into(),
    );
    rejects(
        with(|m| m.files.truncate(1)),
        TableError::FileOutOfRange { pc: 38 }.into(),
    );
}

#[test]
fn errors_read_well() {
    assert_eq!(
        LoadError::BadMagic.to_string(),
        "not a .gbc file (bad magic number)"
    );
    assert_eq!(
        LoadError::UnsupportedVersion { found: 9 }.to_string(),
        format!("unsupported .gbc format version 9 (this build reads version {VERSION})")
    );
    assert_eq!(
        LoadError::BadOpcode { pc: 3, byte: 0xfe }.to_string(),
        "unknown opcode byte 0xfe at pc 3"
    );
    let table: LoadError = TableError::DuplicateProgram { number: 12 }.into();
    assert_eq!(table.to_string(), "program O0012 defined twice");
}

// ---------------------------------------------------------------------------
// Random input

/// A valid header followed by anything, sealed, to get past the first
/// checks into the section parser.
fn sealed_body(rest: &[u8]) -> Vec<u8> {
    let mut body = MAGIC.to_vec();
    body.extend_from_slice(&VERSION.to_le_bytes());
    body.extend_from_slice(rest);
    seal(body)
}

#[derive(Debug, Clone)]
enum Mutation {
    Set(usize, u8),
    Insert(usize, u8),
    Remove(usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Set(i, b)),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        1 => any::<usize>().prop_map(Mutation::Remove),
        1 => any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len().max(1);
    match *m {
        Mutation::Set(i, b) => {
            if let Some(slot) = bytes.get_mut(i % len) {
                *slot = b;
            }
        }
        Mutation::Insert(i, b) => bytes.insert(i % (bytes.len() + 1), b),
        Mutation::Remove(i) => {
            if !bytes.is_empty() {
                bytes.remove(i % len);
            }
        }
        Mutation::Truncate(i) => bytes.truncate(i % len),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..1024)) {
        prop_assert!(Module::from_bytes(&bytes).is_err());
        if let Ok(m) = Module::from_bytes(&sealed_body(&bytes)) {
            check_accepted(&sealed_body(&bytes), &m);
        }
    }

    #[test]
    fn mutated_files_never_panic(
        mutations in proptest::collection::vec(mutation(), 1..8),
        fresh_checksum in any::<bool>(),
    ) {
        let mut bytes = sample_bytes();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        if fresh_checksum && bytes.len() >= CRC_LEN {
            bytes = reseal(bytes);
        }
        if let Ok(module) = Module::from_bytes(&bytes) {
            check_accepted(&bytes, &module);
            // Whatever loaded can be listed.
            let _ = module.disassemble();
        }
    }

    #[test]
    fn mutated_modules_never_panic_the_tools(
        edits in proptest::collection::vec((any::<usize>(), any::<u32>()), 1..6),
    ) {
        // Nonsense in-memory modules: verify, disassemble and pc_of_seq
        // must cope without a panic.
        let mut m = sample_module();
        for &(which, value) in &edits {
            match which % 6 {
                0 => m.num_regs = value as u16,
                1 => m.programs[which % 2].entry = value,
                2 => m.programs[which % 2].end = value,
                3 => m.programs[which % 2].seqs.push((value, value / 2)),
                4 => edit_lines(&mut m, |l| l[which % 41].file = value as u16),
                _ => m.code[which % 41] = Instr::Jump { target: value },
            }
        }
        let _ = m.verify();
        let _ = m.disassemble();
        for prog in 0..3 {
            let _ = m.pc_of_seq(prog, 10);
        }
        if m.verify().is_ok() {
            prop_assert_eq!(Module::from_bytes(&m.to_bytes()), Ok(m));
        }
    }
}

#[test]
fn a_code_section_out_of_proportion_to_its_line_table() {
    // The sample's 41 instructions take more than 41 bytes; a code section
    // of 41 × 8 + 1 bytes (8: the longest instruction, `cmpk`) cannot
    // hold 41 instructions, nor can one of 40 bytes.
    let module = sample_module();
    assert_eq!(module.code.len(), 41);
    for len in [40, 41 * 8 + 1] {
        let bytes = module.to_bytes();
        let code = section(&bytes, Section::Code);
        let mut forged = bytes[..code.payload].to_vec();
        put_u32(&mut forged, code.len_field, len as u32);
        forged.resize(code.payload + len, isa::Opcode::Ret as u8);
        forged.extend_from_slice(&bytes[code.payload + code.len..]);
        assert_eq!(
            Module::from_bytes(&reseal(forged)),
            Err(TableError::CodeSize {
                bytes: len,
                lines: 41
            }
            .into()),
            "{len} bytes"
        );
    }
    // At the bounds, 41 and 41 × 8 bytes of `ret`s, the sizes pass and the
    // verifier finds the real count (41 one-byte `ret`s are a well-formed
    // code section; 328 of them are not one per source location).
    let bytes = module.to_bytes();
    let code = section(&bytes, Section::Code);
    let mut forged = bytes[..code.payload].to_vec();
    put_u32(&mut forged, code.len_field, 41 * 8);
    forged.resize(code.payload + 41 * 8, isa::Opcode::Ret as u8);
    forged.extend_from_slice(&bytes[code.payload + code.len..]);
    assert_eq!(
        Module::from_bytes(&reseal(forged)),
        Err(TableError::LinesMismatch {
            lines: 41,
            code: 41 * 8
        }
        .into())
    );
}
