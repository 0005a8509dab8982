//! Shared fixtures: a small module that uses every opcode, and helpers to
//! forge files byte by byte.

#![allow(dead_code)] // each test binary uses a different subset

use isa::format::{Section, CRC_LEN, HEADER_LEN};
use isa::{addr, BlockWord, Instr, Module, Program, SourceFileInfo, SourceLoc};

/// A main program `O0001` and a macro `O9010`, together using every opcode
/// at least once (checked by `sample_uses_every_opcode`).
pub fn sample_module() -> Module {
    use Instr::*;
    // Comments: pc, and what a test relies on.
    #[rustfmt::skip]
    let main = vec![
        LoadK { dst: 0, k: 0 },                         // 0  N10
        LoadNull { dst: 1 },                            // 1
        Mov { dst: 2, src: 0 },                         // 2
        LoadVar { dst: 3, var: 100 },                   // 3
        LoadVarInd { dst: 4, idx: 3 },                  // 4
        StoreVar { var: 500, src: 2 },                  // 5
        StoreVarInd { idx: 3, src: 2 },                 // 6
        Neg { dst: 5, a: 0 },                           // 7
        Add { dst: 5, a: 0, b: 2 },                     // 8
        Sub { dst: 5, a: 5, b: 2 },                     // 9
        Mul { dst: 5, a: 5, b: 2 },                     // 10
        Div { dst: 5, a: 5, b: 2 },                     // 11
        Mod { dst: 5, a: 5, b: 2 },                     // 12
        BitAnd { dst: 5, a: 5, b: 2 },                  // 13
        BitOr { dst: 5, a: 5, b: 2 },                   // 14
        BitXor { dst: 5, a: 5, b: 2 },                  // 15
        Func { dst: 5, a: 0, f: 14 },                   // 16 BCD, the last code
        Atan2 { dst: 5, y: 0, x: 2 },                   // 17
        Cmp { dst: 6, a: 0, b: 2, op: 5 },              // 18 LE, the last code; r6 = top reg
        JumpIfNot { cond: 6, target: 22 },              // 19
        WordK { addr: 23, k: 1, flags: 1 },             // 20 X100 (no decimal point)
        Word { addr: addr::COMMA_R, src: 5 },           // 21 ,R[#5]
        SetMsg { s: 0 },                                // 22 N20
        Exec { flags: 0 },                              // 23
        GotoSeq { seq: 3 },                             // 24
        CallSub { prog: 1, count: 1 },                  // 25
        CallSubDyn { num: 3, count: 1 },                // 26
        Arg { var: 1, src: 0 },                         // 27 first argument
        Arg { var: 33, src: 2 },                        // 28 last argument
        CallMacro { prog: 1, count: 1 },                // 29
        CallMacroDyn { num: 3, count: 1 },              // 30 N20 again
        ModalCall { prog: 1, count: 1 },                // 31
        ModalCallDyn { num: 3, count: 1 },              // 32
        ModalCancel,                                    // 33
        Alarm { code: 5001, msg: 1 },                   // 34 the last string
        Jump { target: 37 },                            // 35
        SkipBlock { switch: 9, target: 37 },            // 36 the last switch
        Halt,                                           // 37
    ];
    let sub = vec![
        LoadK { dst: 0, k: 3 }, // 38 N1
        RetSeq { seq: 0 },      // 39
        Ret,                    // 40
    ];
    let main_len = main.len() as u32;
    let mut lines: Vec<SourceLoc> = (0..main_len)
        .map(|pc| SourceLoc {
            file: 0,
            line: pc + 1,
            col: 1 + pc % 3,
        })
        .collect();
    lines.extend((0..sub.len() as u32).map(|i| SourceLoc {
        file: 1,
        line: i + 2,
        col: 1,
    }));
    let code: Vec<Instr> = main.into_iter().chain(sub).collect();
    let code_len = code.len() as u32;
    Module {
        code,
        consts: vec![12.5, 100.0, -0.0, f64::from_bits(0x7ff8_0000_dead_beef)],
        strings: vec!["CHECK PART".to_string(), "TOO BIG".to_string()],
        programs: vec![
            Program {
                number: 1,
                entry: 0,
                end: main_len,
                seqs: vec![(10, 0), (20, 22), (20, 30)],
                ..Program::default()
            },
            Program {
                number: 9010,
                entry: main_len,
                end: code_len,
                seqs: vec![(1, main_len)],
                ..Program::default()
            },
        ],
        lines: lines.into(),
        files: vec![
            SourceFileInfo {
                name: "part.nc".to_string(),
                hash: 0x1234_abcd,
            },
            SourceFileInfo {
                name: "O9010.nc".to_string(),
                hash: 0xdead_beef,
            },
        ],
        machine: "control=gsk980tdi\nunits=mm\n".to_string(),
        num_regs: 7,
        blocks: Vec::new(),
    }
}

/// Changes the per-instruction locations of `m` through a plain vector
/// (the table itself is runs and is only appended to).
pub fn edit_lines(m: &mut Module, edit: impl FnOnce(&mut Vec<SourceLoc>)) {
    let mut locs: Vec<SourceLoc> = m.lines.iter().collect();
    edit(&mut locs);
    m.lines = locs.into();
}

/// A main program of typed blocks: `G98 G0 X50. Z2.` then `G1 X12.5
/// Z-33.25 F0.2` (literals as the lexer reads them), then a word stored
/// raw (0.1 + 0.2 has no short decimal) and a computed -0 (flags 0); then
/// the second record again as a profile block. The second is run as a
/// `move`, the others as `block`s.
pub fn typed_module() -> Module {
    let w = |letter: char, value: f64, flags: u8| BlockWord {
        addr: addr::from_letter(letter).unwrap(),
        value,
        flags,
    };
    const LIT: u8 = 2; // a literal with a decimal point
    const LIT_NO_POINT: u8 = 3;
    let records: [&[BlockWord]; 3] = [
        &[
            w('G', 98.0, LIT_NO_POINT),
            w('G', 0.0, LIT_NO_POINT),
            w('X', 50.0, LIT),
            w('Z', 2.0, LIT),
        ],
        &[
            w('G', 1.0, LIT_NO_POINT),
            w('X', 12.5, LIT),
            w('Z', -33.25, LIT),
            w('F', 0.2, LIT),
        ],
        &[w('U', 0.1 + 0.2, LIT), w('W', -0.0, 0)],
    ];
    let mut m = Module {
        programs: vec![Program {
            number: 1,
            entry: 0,
            end: 6,
            seqs: vec![(10, 1)],
            ..Program::default()
        }],
        files: vec![SourceFileInfo {
            name: "typed.nc".to_string(),
            hash: 0,
        }],
        num_regs: 1,
        ..Module::default()
    };
    for (i, words) in records.iter().enumerate() {
        let rec = m.push_block(words).expect("the words fit a record");
        // (The second is a plain move.)
        m.code.push(match i {
            1 => Instr::Move { rec },
            _ => Instr::Block { rec },
        });
        m.lines.push(SourceLoc {
            file: 0,
            line: i as u32 + 1,
            col: 1,
        });
    }
    m.code.push(Instr::Profile { rec: 12 });
    // (A move of the words built before it: here, none.)
    m.code.push(Instr::ExecMove);
    m.code.push(Instr::Halt);
    for _ in 0..3 {
        m.lines.push(SourceLoc {
            file: 0,
            line: 3,
            col: 1,
        });
    }
    m
}

/// A main program of arithmetic and a comparison with constant operands
/// (`addk`, `subk`, `mulk`, `divk`, `cmpk`, format version 7), on `#100`;
/// `charge` and `goto` (version 9).
pub fn constant_operands_module() -> Module {
    use Instr::*;
    let code = vec![
        LoadVar { dst: 0, var: 100 },
        AddK { dst: 0, a: 0, k: 0 },
        SubK { dst: 0, a: 0, k: 1 },
        MulK { dst: 0, a: 0, k: 1 },
        DivK { dst: 0, a: 0, k: 1 },
        CmpK {
            dst: 1,
            a: 0,
            k: 0,
            op: 3,
        },
        StoreVar { var: 101, src: 1 },
        Charge,
        Goto { target: 10 },
        UserAlarm { q: 1, msg: 0 },
        Halt,
    ];
    let mut m = one_program("k.nc", code, Program::default(), vec![1.5, 2.0], 2);
    m.strings = vec!["OVERHEAT".to_string()];
    m
}

/// Recomputes the CRC trailer, so a forged change reaches the parser and the
/// verifier instead of being caught by the checksum.
pub fn reseal(mut bytes: Vec<u8>) -> Vec<u8> {
    let body = bytes.len() - CRC_LEN;
    let crc = crc32fast::hash(&bytes[..body]);
    bytes[body..].copy_from_slice(&crc.to_le_bytes());
    bytes
}

/// Appends a CRC trailer to a body.
pub fn seal(mut body: Vec<u8>) -> Vec<u8> {
    let crc = crc32fast::hash(&body);
    body.extend_from_slice(&crc.to_le_bytes());
    body
}

/// Where a section sits in a well-formed file.
#[derive(Debug, Clone, Copy)]
pub struct SectionAt {
    /// Offset of the tag byte.
    pub tag: usize,
    /// Offset of the u32 length.
    pub len_field: usize,
    /// Offset of the payload.
    pub payload: usize,
    /// Payload length.
    pub len: usize,
}

/// Locates `which` by walking the section headers.
pub fn section(bytes: &[u8], which: Section) -> SectionAt {
    let mut at = HEADER_LEN;
    loop {
        let tag = bytes[at];
        let len = u32::from_le_bytes(bytes[at + 1..at + 5].try_into().unwrap()) as usize;
        let here = SectionAt {
            tag: at,
            len_field: at + 1,
            payload: at + 5,
            len,
        };
        if tag == which as u8 {
            return here;
        }
        at = here.payload + len;
    }
}

/// Overwrites a little-endian u32 at `at`.
pub fn put_u32(bytes: &mut [u8], at: usize, value: u32) {
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
}

/// A main program with two DO loops, the second inside the first (format
/// version 8): N10 stands in loop 2, N20 in loop 1, N30 in none; a
/// computed GOTO (`gotoseqin`) stands in loop 1, and a computed packed
/// M98 (`callsubpacked`) in it.
pub fn loops_module() -> Module {
    use Instr::*;
    let code = vec![
        LoadVar { dst: 0, var: 100 },    // 0
        GotoSeqIn { seq: 0, inside: 1 }, // 1 (in loop 1)
        LoadK { dst: 0, k: 0 },          // 2 N10 (loop 2)
        CallSubPacked { num: 0 },        // 3 N20 (loop 1)
        GotoSeq { seq: 0 },              // 4 N30 (no loop)
        Halt,                            // 5
    ];
    let program = Program {
        seqs: vec![(10, 2), (20, 3), (30, 4)],
        loops: vec![0, 1],
        seq_loops: vec![2, 1, 0],
        ..Program::default()
    };
    one_program("loops.nc", code, program, vec![1.0], 1)
}

/// A module whose one program, O0001, is all of `code` (the rest of it
/// from `program`), each instruction a line of its own in `file`.
fn one_program(
    file: &str,
    code: Vec<Instr>,
    program: Program,
    consts: Vec<f64>,
    num_regs: u16,
) -> Module {
    let lines = (1..=code.len() as u32)
        .map(|line| SourceLoc {
            file: 0,
            line,
            col: 1,
        })
        .collect();
    Module {
        programs: vec![Program {
            number: 1,
            entry: 0,
            end: code.len() as u32,
            ..program
        }],
        files: vec![SourceFileInfo {
            name: file.to_string(),
            hash: 0,
        }],
        consts,
        num_regs,
        code,
        lines,
        ..Module::default()
    }
}
