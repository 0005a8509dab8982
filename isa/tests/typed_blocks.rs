//! Typed blocks and the run-length line table: values survive the record
//! encoding bit for bit, tampered records and line tables are refused at
//! load (never a panic), and the table answers as the old per-instruction
//! one did on a real module.

mod common;

use common::{reseal, section, typed_module};
use isa::block::{decimal_of, decode_record, encode_record, BlockWord};
use isa::format::Section;
use isa::{Instr, LineTable, LoadError, Module, Program, SourceFileInfo, SourceLoc, TableError};
use proptest::prelude::*;

/// Encodes one word and decodes it again.
fn round_trip(value: f64) -> (f64, usize) {
    let word = BlockWord {
        addr: 23,
        value,
        flags: 2,
    };
    let mut bytes = Vec::new();
    assert!(encode_record(&[word], &mut bytes), "{value:?} encodes");
    let mut back = Vec::new();
    let end = decode_record(&bytes, 0, |w| back.push(w)).expect("decodes");
    assert_eq!(end, bytes.len());
    assert_eq!(back.len(), 1);
    assert_eq!((back[0].addr, back[0].flags), (23, 2));
    (back[0].value, bytes.len())
}

/// A decimal literal as written: up to 15 digits with the point anywhere
/// (or none), and a sign.
fn literal() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(0u8..10, 1..=15),
        any::<prop::sample::Index>(),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(digits, point, has_point, negative)| {
            let mut s: String = digits.iter().map(|d| char::from(b'0' + d)).collect();
            if has_point {
                s.insert(point.index(digits.len() + 1), '.');
            }
            if negative {
                s.insert(0, '-');
            }
            s
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn every_finite_f64_survives(bits in any::<u64>()) {
        let value = f64::from_bits(bits);
        prop_assume!(value.is_finite());
        let (back, _) = round_trip(value);
        prop_assert_eq!(back.to_bits(), bits);
    }

    #[test]
    fn every_literal_of_up_to_15_digits_survives_compactly(text in literal()) {
        // The reference value is the standard library's correctly rounded
        // parse, which the lexer equals on literals this short (its own
        // tests check that).
        let value: f64 = text.parse().expect("a literal parses");
        prop_assert!(decimal_of(value).is_some(), "{} has a decimal form", text);
        let (back, len) = round_trip(value);
        prop_assert_eq!(back.to_bits(), value.to_bits(), "{}", text);
        // Count, head, then a varint of at most 8 bytes: a longer one
        // (a mantissa of 2^49 or more) is stored as the raw 8 bytes.
        prop_assert!(len <= 10, "{} took {} bytes", text, len);
    }
}

#[test]
fn literals_as_in_the_benchmark_are_small() {
    // Worked by hand from the layout (isa/src/block.rs): G1 is 1 × 10^0,
    // varint 1 << 7 | 22 = 150 (2 bytes); 12.5 is 125 × 10^-1, 16021
    // (2 bytes); -33.25 is 3325 × 10^-2 with the sign, 425 684 (3 bytes);
    // 0.2 is 2 × 10^-1, 277 (2 bytes). With the count and four heads:
    // 1 + 3 + 3 + 4 + 3 = 14 bytes for `G1 X12.5 Z-33.25 F0.2`.
    let w = |addr: u8, value: f64| BlockWord {
        addr,
        value,
        flags: 2,
    };
    let words = [w(6, 1.0), w(23, 12.5), w(25, -33.25), w(5, 0.2)];
    let mut bytes = Vec::new();
    assert!(encode_record(&words, &mut bytes));
    assert_eq!(bytes.len(), 14);
    // A value with no short decimal is stored raw: 0.1 + 0.2 needs 17
    // digits, more than a mantissa below 2^53 holds.
    assert_eq!(round_trip(0.1 + 0.2), (0.1 + 0.2, 1 + 1 + 8));
    assert_eq!(round_trip(-0.0).0.to_bits(), (-0.0f64).to_bits());
}

#[test]
fn records_that_do_not_fit_are_refused_whole() {
    let ok = BlockWord {
        addr: 0,
        value: 1.0,
        flags: 0,
    };
    let mut bytes = vec![7];
    let refused = [
        vec![],
        vec![ok; 256],
        vec![BlockWord { addr: 29, ..ok }],
        vec![BlockWord { flags: 4, ..ok }],
        vec![
            ok,
            BlockWord {
                value: f64::NAN,
                ..ok
            },
        ],
        vec![BlockWord {
            value: f64::INFINITY,
            ..ok
        }],
    ];
    for words in refused {
        assert!(!encode_record(&words, &mut bytes), "{words:?}");
        assert_eq!(bytes, [7], "nothing appended");
    }
}

#[test]
fn typed_module_round_trips_and_lists_its_blocks() {
    let module = typed_module();
    assert_eq!(module.verify(), Ok(()));
    let bytes = module.to_bytes();
    let back = Module::from_bytes(&bytes).expect("loads");
    assert_eq!(back, module);
    assert_eq!(back.to_bytes(), bytes);
    assert_eq!(Module::from_vec(bytes.clone()), Ok(module.clone()));
    let listing = module.disassemble();
    // Offsets by hand: record 0 (G98 G0 X50. Z2.) is 1 + 3 + 2 + 3 + 3 =
    // 12 bytes, record 1 the 14 above.
    for line in [
        "  0000  block b0 (G98 G0 X50. Z2.) ; typed.nc:1:1",
        "N10:\n  0001  move b12 (G1 X12.5 Z-33.25 F0.2) ; typed.nc:2:1",
        "  0002  block b26 (U0.30000000000000004 W-0.) ; typed.nc:3:1",
    ] {
        assert!(listing.contains(line), "{line:?} in\n{listing}");
    }
    let mut words = Vec::new();
    assert_eq!(module.block_words(12, |w| words.push(w)), Some(()));
    assert_eq!(words.len(), 4);
    assert_eq!(words[2].value, -33.25);
    assert_eq!(module.block_words(13, |_| {}), None, "not a record start");
}

#[test]
fn from_vec_keeps_the_file_buffer_as_the_blocks() {
    // The file is held once: the module's records are the file's own
    // buffer, cut down to the last section, not a copy of it.
    let module = typed_module();
    let bytes = module.to_bytes();
    let buffer = bytes.as_ptr();
    let loaded = Module::from_vec(bytes).expect("loads");
    assert_eq!(loaded.blocks.as_ptr(), buffer);
    assert_eq!(loaded, module);
    // A refused file is refused the same way by both loaders.
    let mut bad = module.to_bytes();
    bad[4] = 2; // version 2
    assert_eq!(
        Module::from_vec(bad.clone()),
        Err(LoadError::UnsupportedVersion { found: 2 })
    );
    assert_eq!(Module::from_bytes(&bad), Module::from_vec(bad));
}

/// The typed module with its blocks section replaced.
fn with_blocks(blocks: Vec<u8>) -> Module {
    Module {
        blocks,
        ..typed_module()
    }
}

fn bad_block(at: usize, what: &'static str) -> Result<(), LoadError> {
    Err(TableError::BadBlock { at, what }.into())
}

#[test]
fn tampered_records_are_refused() {
    let m = typed_module();
    let second = 12; // the start of record 1
    let mut cases: Vec<(Vec<u8>, Result<(), LoadError>)> = Vec::new();
    let mut edit = |f: &dyn Fn(&mut Vec<u8>), want| {
        let mut b = m.blocks.clone();
        f(&mut b);
        cases.push((b, want));
    };
    // Record 1's count 0.
    edit(
        &|b| b[second] = 0,
        bad_block(second, "record without words"),
    );
    // Its G word's address 29 (past ,R), flags kept.
    edit(
        &|b| b[second + 1] = (b[second + 1] & !0x1f) | 29,
        bad_block(second, "bad word address"),
    );
    // More words than the section holds.
    edit(
        &|b| b[26] = 9,
        bad_block(26, "record runs past the section"),
    );
    // The section cut inside the last record.
    edit(
        &|b| {
            b.pop();
        },
        bad_block(26, "record runs past the section"),
    );
    // The raw 0.30000000000000004 made a NaN and an infinity.
    for raw in [f64::NAN, f64::NEG_INFINITY] {
        edit(
            &move |b| b[28..36].copy_from_slice(&raw.to_bits().to_le_bytes()),
            bad_block(26, "value not finite"),
        );
    }
    for (blocks, want) in cases {
        assert_eq!(with_blocks(blocks).verify(), want);
    }

    // Values forged whole: an overlong varint, an exponent code of 45
    // (10^23 is not exact), a mantissa of 2^53.
    let forged: [(&[u8], &str); 3] = [
        (&[1, 23, 0x96, 0x00], "malformed varint"),
        (&[1, 23, 45], "decimal out of range"),
        (
            &[
                1, 23, 0x96, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01,
            ],
            "malformed varint",
        ),
    ];
    for (blocks, what) in forged {
        assert_eq!(with_blocks(blocks.to_vec()).verify(), bad_block(0, what));
    }
    let mut huge = vec![1, 23];
    let code: u64 = 1 << 60 | 22; // mantissa 2^53, exponent 0
    let mut v = code;
    while v >= 0x80 {
        huge.push(v as u8 | 0x80);
        v >>= 7;
    }
    huge.push(v as u8);
    assert_eq!(
        with_blocks(huge).verify(),
        bad_block(0, "decimal out of range")
    );
}

#[test]
fn block_operands_may_name_records_in_any_order() {
    // Records 1 then 0, and one named twice by a `profile`: a profile
    // block and the block where it stands share a record (version 4).
    let mut m = typed_module();
    m.code.swap(0, 1);
    assert_eq!(m.verify(), Ok(()));
    m.code[2] = Instr::Profile { rec: 12 };
    assert_eq!(m.verify(), Ok(()));
    let back = Module::from_bytes(&m.to_bytes()).expect("the module loads");
    assert_eq!(back, m);
    let listing = m.disassemble();
    let line = "  0002  profile b12 (G1 X12.5 Z-33.25 F0.2) ; typed.nc:3:1";
    assert!(listing.contains(line), "{line:?} in\n{listing}");
}

#[test]
fn block_operands_must_name_a_record() {
    let len = typed_module().blocks.len() as u32;
    for rec in [1, 11, 13, len, u32::MAX] {
        for instr in [
            Instr::Block { rec },
            Instr::Profile { rec },
            Instr::Move { rec },
        ] {
            let mut m = typed_module();
            m.code[1] = instr;
            assert_eq!(
                m.verify(),
                Err(TableError::BlockOutOfRange { pc: 1 }.into()),
                "{instr:?}"
            );
        }
    }
}

/// A `move` must name a plain move: X/Z/U/W, F, N, R, I and K each once
/// and at most one G written as 0–3. Records by hand, each a `move`.
#[test]
fn move_operands_must_name_a_plain_move() {
    let w = |letter: char, value: f64| BlockWord {
        addr: isa::addr::from_letter(letter).unwrap(),
        value,
        flags: 2,
    };
    let cases: [(&[BlockWord], bool); 10] = [
        (&[w('G', 1.0), w('X', 1.0), w('Z', -2.0), w('F', 0.2)], true),
        (&[w('N', 5.0), w('U', 1.0), w('W', -2.0)], true),
        (&[w('G', 3.0), w('X', 1.0), w('I', 1.0), w('K', 0.0)], true),
        (&[w('G', 2.0), w('Z', 1.0), w('R', 4.0)], true),
        (&[w('G', 4.0), w('X', 1.0)], false),
        (&[w('G', 1.5), w('X', 1.0)], false),
        (&[w('G', 0.0), w('G', 1.0), w('X', 1.0)], false),
        (&[w('X', 1.0), w('X', 2.0)], false),
        (&[w('X', 1.0), w('M', 3.0)], false),
        (&[w('X', 1.0), w('S', 300.0)], false),
    ];
    for (words, plain) in cases {
        let mut m = typed_module();
        let rec = m.push_block(words).expect("a record");
        m.code[1] = Instr::Move { rec };
        let want = match plain {
            true => Ok(()),
            false => Err(TableError::NotAMove { pc: 1 }.into()),
        };
        assert_eq!(m.verify(), want, "{words:?}");
    }
}

/// `bytes` with the payload of `which` replaced (lengths and CRC fixed).
fn with_payload(bytes: &[u8], which: Section, payload: &[u8]) -> Vec<u8> {
    let s = section(bytes, which);
    let mut out = bytes[..s.len_field].to_vec();
    out.extend_from_slice(&(payload.len() as u32).to_le_bytes());
    out.extend_from_slice(payload);
    out.extend_from_slice(&bytes[s.payload + s.len..]);
    reseal(out)
}

#[test]
fn tampered_line_tables_are_refused() {
    let bytes = typed_module().to_bytes();
    let lines = section(&bytes, Section::Lines);
    let at = lines.payload;
    // By hand (isa/src/lines.rs): 6 instructions; a run of 3 (lines 1, 2,
    // 3, step 1: head 3 << 2 | 2 = 14, zigzag(+1) = 2, col 1), then the
    // profile, the execmove and the halt on line 3 (head 3 << 2 = 12, line
    // delta 0, col 1).
    assert_eq!(
        &bytes[at..at + lines.len],
        &[6, 0, 0, 0, 14, 2, 1, 12, 0, 1]
    );
    let bad = |what| Err(TableError::BadLines { at, what }.into());
    let cases: [(&[u8], Result<Module, LoadError>); 8] = [
        // A run of no instructions.
        (
            &[6, 0, 0, 0, 2, 2, 1, 12, 0, 1],
            bad("run not in its one encoding"),
        ),
        // One instruction with a step.
        (
            &[6, 0, 0, 0, 14, 2, 1, 6, 0, 1],
            bad("run not in its one encoding"),
        ),
        // A file "change" to the same file 0.
        (
            &[6, 0, 0, 0, 15, 0, 2, 1, 12, 0, 1],
            bad("run not in its one encoding"),
        ),
        // Runs covering 3 of 6 instructions, and 7 of 6.
        (
            &[6, 0, 0, 0, 14, 2, 1],
            bad("runs do not cover the instructions"),
        ),
        (
            &[6, 0, 0, 0, 14, 2, 1, 16, 0, 1],
            bad("runs do not cover the instructions"),
        ),
        // A line before line 0 (delta -4 from line 3: zigzag 7).
        (
            &[6, 0, 0, 0, 14, 2, 1, 12, 7, 1],
            bad("line, column, file or pc out of range"),
        ),
        // A run cut short, and an overlong varint.
        (&[6, 0, 0, 0, 14, 2, 1, 12, 0], bad("malformed run")),
        (
            &[6, 0, 0, 0, 14, 2, 1, 12, 0x80, 0, 1],
            bad("malformed run"),
        ),
    ];
    for (payload, want) in cases {
        let forged = with_payload(&bytes, Section::Lines, payload);
        assert_eq!(Module::from_bytes(&forged), want, "{payload:?}");
    }
    // A run in file 1 (head 12 | 1, file 1): there is one file only.
    let forged = with_payload(&bytes, Section::Lines, &[6, 0, 0, 0, 14, 2, 1, 13, 1, 0, 1]);
    assert_eq!(
        Module::from_bytes(&forged),
        Err(TableError::FileOutOfRange { pc: 3 }.into())
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn any_edit_of_the_new_sections_is_refused_or_loads(
        edits in prop::collection::vec((any::<bool>(), any::<prop::sample::Index>(), any::<u8>()), 1..4),
    ) {
        let bytes = typed_module().to_bytes();
        let mut forged = bytes.clone();
        for (in_lines, index, value) in edits {
            let which = if in_lines { Section::Lines } else { Section::Blocks };
            let s = section(&bytes, which);
            forged[s.payload + index.index(s.len)] = value;
        }
        // Whatever loads, verifies, lists and writes itself back.
        if let Ok(m) = Module::from_bytes(&reseal(forged)) {
            prop_assert_eq!(m.verify(), Ok(()));
            let _ = m.disassemble();
            let again = Module::from_bytes(&m.to_bytes());
            prop_assert_eq!(again, Ok(m));
        }
    }
}

/// The per-instruction locations of a version 2 file, read the way
/// version 2 laid them out: a count, then file u16, line u32, col u32.
fn v2_locations(bytes: &[u8]) -> (Vec<SourceLoc>, usize) {
    let u16_at = |at: usize| u16::from_le_bytes([bytes[at], bytes[at + 1]]);
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let lines = section(bytes, Section::Lines);
    let count = u32_at(lines.payload) as usize;
    let locs = (0..count)
        .map(|i| {
            let at = lines.payload + 4 + 10 * i;
            SourceLoc {
                file: u16_at(at),
                line: u32_at(at + 2),
                col: u32_at(at + 6),
            }
        })
        .collect();
    let files = section(bytes, Section::Files);
    (locs, u32_at(files.payload) as usize)
}

#[test]
fn the_line_table_answers_as_the_per_instruction_one_did() {
    // A real module: the public corpus program doosan-lynx300 O2311 as
    // gbcc of version 2 compiled it (word form, a location per `wordk`).
    let old = include_bytes!("fixtures/o2311.v2.gbc");
    assert_eq!(
        Module::from_bytes(old),
        Err(LoadError::UnsupportedVersion { found: 2 })
    );
    let (locs, files) = v2_locations(old);
    assert!(locs.len() > 500, "{} instructions", locs.len());
    // The same locations through the new table and a file round trip.
    let n = locs.len();
    let module = Module {
        code: vec![Instr::Halt; n],
        lines: locs.iter().copied().collect::<LineTable>(),
        programs: vec![Program {
            number: 1,
            entry: 0,
            end: n as u32,
            ..Program::default()
        }],
        files: (0..files)
            .map(|i| SourceFileInfo {
                name: format!("f{i}"),
                hash: 0,
            })
            .collect(),
        num_regs: 1,
        ..Module::default()
    };
    let loaded = Module::from_bytes(&module.to_bytes()).expect("loads");
    for (pc, loc) in locs.iter().enumerate() {
        assert_eq!(loaded.lines.get(pc), Some(*loc), "pc {pc}");
    }
    assert_eq!(loaded.lines.get(n), None);
    assert!(loaded.lines.iter().eq(locs.iter().copied()));
    // And cheaper than 12 bytes an instruction.
    let table = section(&loaded.to_bytes(), Section::Lines).len;
    let held = loaded.lines.heap_bytes();
    eprintln!("{n} instructions: line table {table} bytes in the file, {held} in memory");
    assert!(table * 3 < n * 12 && held * 2 < n * 12, "{table} / {held}");
}
