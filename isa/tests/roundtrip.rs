//! Round trips: module → bytes → module, instruction → bytes → instruction,
//! and the listing, for every opcode the table defines.

mod common;

use std::collections::BTreeSet;

use common::{constant_operands_module, loops_module, sample_module, typed_module};
use isa::{Instr, LoadError, Module, Opcode, Operand, OperandKind, OperandMut};
use proptest::prelude::*;

#[test]
fn sample_uses_every_opcode() {
    // The typed blocks, the constant operands and the loops have samples
    // of their own.
    let (sample, typed, k) = (sample_module(), typed_module(), constant_operands_module());
    let loops = loops_module();
    let used: BTreeSet<Opcode> = sample
        .code
        .iter()
        .chain(&typed.code)
        .chain(&k.code)
        .chain(&loops.code)
        .map(Instr::opcode)
        .collect();
    let all: BTreeSet<Opcode> = Opcode::ALL.iter().copied().collect();
    let missing: Vec<_> = all.difference(&used).collect();
    assert!(missing.is_empty(), "the samples lack {missing:?}");
}

#[test]
fn sample_verifies() {
    assert_eq!(sample_module().verify(), Ok(()));
    let k = constant_operands_module();
    assert_eq!(k.verify(), Ok(()));
    assert_eq!(Module::from_bytes(&k.to_bytes()), Ok(k));
    let loops = loops_module();
    assert_eq!(loops.verify(), Ok(()));
    assert_eq!(Module::from_bytes(&loops.to_bytes()), Ok(loops));
}

/// Which loop holds which, and where a sequence number stands, as the VM
/// asks them at a computed GOTO (E6008).
#[test]
fn loop_tables_answer_the_vm() {
    let m = loops_module();
    assert_eq!(m.seq_target(0, 10), Some((2, 2)));
    assert_eq!(m.seq_target(0, 30), Some((4, 0)));
    assert_eq!(m.seq_target(0, 40), None);
    // Loop 1 holds loop 2 and itself; loop 2 does not hold loop 1; no
    // loop (0) holds everything, and no loop but 0 holds the outside.
    assert!(m.loop_holds(0, 1, 2));
    assert!(m.loop_holds(0, 2, 2));
    assert!(!m.loop_holds(0, 2, 1));
    assert!(m.loop_holds(0, 0, 2));
    assert!(!m.loop_holds(0, 1, 0));
    // Out of range: no answer but "no", and no panic.
    assert!(!m.loop_holds(0, 1, 7));
    assert!(!m.loop_holds(3, 0, 0));
}

/// The verifier's rules for the loop tables and `gotoseqin`.
#[test]
fn bad_loop_tables_are_rejected() {
    use isa::TableError;
    let bad_loops = |edit: fn(&mut Module)| {
        let mut m = loops_module();
        edit(&mut m);
        m.verify()
    };
    let table = Err(TableError::BadLoops { index: 0 }.into());
    // A parent not before its child (a cycle), a loop beyond the table,
    // entries that do not match the sequence table.
    assert_eq!(bad_loops(|m| m.programs[0].loops = vec![2, 1]), table);
    assert_eq!(bad_loops(|m| m.programs[0].seq_loops[0] = 3), table);
    assert_eq!(
        bad_loops(|m| m.programs[0].seq_loops.pop().map_or((), drop)),
        table
    );
    // A GOTO in loop 0 or 3 of a program of two loops.
    let goto_in = |inside| {
        let mut m = loops_module();
        m.code[1] = Instr::GotoSeqIn { seq: 0, inside };
        m.verify()
    };
    assert_eq!(goto_in(0), Err(TableError::LoopOutOfRange { pc: 1 }.into()));
    assert_eq!(goto_in(3), Err(TableError::LoopOutOfRange { pc: 1 }.into()));
    assert_eq!(goto_in(2), Ok(()));
    // No loop table at all is a program without loops.
    assert_eq!(bad_loops(|m| m.programs[0].seq_loops.clear()), Ok(()));
}

#[test]
fn module_round_trips() {
    let module = sample_module();
    let bytes = module.to_bytes();
    let back = Module::from_bytes(&bytes).expect("sample loads");
    assert_eq!(back, module);
    // Constants survive bit for bit, NaN payload and the sign of zero too.
    let bits = |m: &Module| m.consts.iter().map(|k| k.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&back), bits(&module));
    // One encoding per module.
    assert_eq!(back.to_bytes(), bytes);
    assert_eq!(back.disassemble(), module.disassemble());
}

#[test]
fn module_equality_is_bitwise_on_constants() {
    let a = sample_module();
    let mut b = sample_module();
    assert_eq!(a, b); // holds a NaN, still equal to itself
    b.consts[2] = 0.0; // was -0.0, which `==` on f64 would call equal
    assert_ne!(a, b);
}

#[test]
fn listing_is_stable() {
    insta::assert_snapshot!("sample_listing", sample_module().disassemble());
}

#[test]
fn instruction_text() {
    let cases = [
        (Instr::Add { dst: 3, a: 1, b: 2 }, "add r3, r1, r2"),
        (Instr::LoadK { dst: 0, k: 3 }, "loadk r0, k3"),
        (Instr::LoadVar { dst: 1, var: 100 }, "loadvar r1, #100"),
        (Instr::Func { dst: 1, a: 2, f: 6 }, "func r1, r2, SQRT"),
        (Instr::MulK { dst: 1, a: 2, k: 3 }, "mulk r1, r2, k3"),
        (
            Instr::CmpK {
                dst: 1,
                a: 2,
                k: 3,
                op: 3,
            },
            "cmpk r1, r2, k3, LT",
        ),
        (
            Instr::Cmp {
                dst: 1,
                a: 2,
                b: 3,
                op: 2,
            },
            "cmp r1, r2, r3, GT",
        ),
        (
            Instr::JumpIfNot {
                cond: 4,
                target: 12,
            },
            "jumpifnot r4, @0012",
        ),
        (
            Instr::WordK {
                addr: 23,
                k: 0,
                flags: 1,
            },
            "wordk X, k0, 1",
        ),
        (Instr::Word { addr: 26, src: 0 }, "word ,A, r0"),
        (Instr::Arg { var: 24, src: 0 }, "arg #24, r0"),
        (Instr::CallMacro { prog: 2, count: 1 }, "callmacro p2, r1"),
        (Instr::Alarm { code: 5001, msg: 0 }, "alarm 5001, s0"),
        (Instr::UserAlarm { q: 1, msg: 0 }, "useralarm r1, s0"),
        (Instr::Halt, "halt"),
        (Instr::Halt {}, "halt"),
        (
            Instr::Func {
                dst: 0,
                a: 0,
                f: 200,
            },
            "func r0, r0, func?200",
        ),
    ];
    for (instr, text) in cases {
        assert_eq!(instr.to_string(), text);
    }
}

/// The bytes of an instruction with opcode `op` whose operands are filled
/// from `fill`, built from the table alone.
fn forge(op: Opcode, fill: &mut impl FnMut() -> u8) -> Vec<u8> {
    let mut bytes = vec![op as u8];
    for kind in op.operand_kinds() {
        bytes.extend((0..kind.width()).map(|_| fill()));
    }
    bytes
}

#[test]
fn every_opcode_round_trips() {
    for &op in Opcode::ALL {
        let mut next = 0u8;
        let bytes = forge(op, &mut || {
            next = next.wrapping_add(0x35);
            next
        });
        assert_eq!(bytes.len(), op.encoded_len(), "{op:?}");
        let (instr, end) = Instr::decode(&bytes, 0).expect("decodes");
        assert_eq!(end, bytes.len(), "{op:?} length");
        assert_eq!(instr.opcode(), op);
        assert_eq!(instr.encoded_len(), bytes.len());
        let mut again = Vec::new();
        instr.encode(&mut again);
        assert_eq!(again, bytes, "{op:?} re-encodes");

        // The visitor sees the operands in table order with their kinds.
        let mut kinds = Vec::new();
        instr.visit_operands(|o| kinds.push(o.kind()));
        assert_eq!(kinds, op.operand_kinds(), "{op:?} kinds");
        assert_eq!(op.operand_names().len(), kinds.len());

        // The text is the mnemonic and one item per operand.
        let text = instr.to_string();
        let mut words = text.splitn(2, ' ');
        assert_eq!(words.next(), Some(op.mnemonic()));
        let shown = words.next().map_or(0, |rest| rest.split(", ").count());
        assert_eq!(shown, kinds.len(), "{text}");

        // Every shorter prefix is truncated, never misread.
        for cut in 0..bytes.len() {
            assert!(
                matches!(
                    Instr::decode(&bytes[..cut], 0),
                    Err(LoadError::Truncated { .. })
                ),
                "{op:?} cut at {cut}"
            );
        }
    }
}

#[test]
fn opcode_table_is_consistent() {
    let mut bytes = BTreeSet::new();
    let mut mnemonics = BTreeSet::new();
    for &op in Opcode::ALL {
        assert!(bytes.insert(op as u8), "duplicate byte {op:?}");
        assert!(mnemonics.insert(op.mnemonic()), "duplicate mnemonic {op:?}");
        assert_eq!(
            op.mnemonic(),
            op.name().to_lowercase(),
            "mnemonic of {op:?}"
        );
        assert_eq!(Opcode::from_u8(op as u8), Some(op));
    }
    for byte in 0..=u8::MAX {
        if Opcode::from_u8(byte).is_none() {
            assert_eq!(
                Instr::decode(&[byte, 0, 0, 0, 0, 0, 0, 0, 0], 0),
                Err(LoadError::BadOpcode { pc: 0, byte })
            );
        }
    }
    assert_eq!(Opcode::from_u8(0), None, "zero bytes must not decode");
}

#[test]
fn decode_reports_next_position() {
    let mut bytes = vec![0xEE; 3];
    let first = Instr::Mov { dst: 1, src: 2 };
    let second = Instr::Jump { target: 70_000 };
    first.encode(&mut bytes);
    second.encode(&mut bytes);
    let (a, next) = Instr::decode(&bytes, 3).unwrap();
    let (b, end) = Instr::decode(&bytes, next).unwrap();
    assert_eq!((a, b, end), (first, second, bytes.len()));
    assert_eq!(
        Instr::decode(&bytes, end),
        Err(LoadError::Truncated { at: end })
    );
    assert_eq!(
        Instr::decode(&bytes, usize::MAX),
        Err(LoadError::Truncated { at: usize::MAX })
    );
    assert_eq!(
        Instr::decode(&bytes, 0),
        Err(LoadError::BadOpcode { pc: 0, byte: 0xEE })
    );
}

#[test]
fn visit_operands_mut_patches() {
    let mut instr = Instr::JumpIfNot { cond: 2, target: 0 };
    instr.visit_operands_mut(|op| match op {
        OperandMut::Pc(target) => *target = 41,
        OperandMut::Reg(r) => *r += 1,
        _ => {}
    });
    assert_eq!(
        instr,
        Instr::JumpIfNot {
            cond: 3,
            target: 41
        }
    );
    let mut seen = Vec::new();
    instr.visit_operands(|op| seen.push(op));
    assert_eq!(seen, [Operand::Reg(3), Operand::Pc(41)]);
}

#[test]
fn every_kind_has_its_width() {
    use OperandKind::*;
    for (kind, width) in [
        (Reg, 1),
        (U8, 1),
        (U16, 2),
        (U32, 4),
        (Pc, 4),
        (Const, 4),
        (Str, 4),
        (Prog, 4),
        (Var, 4),
        (ArgVar, 1),
        (Addr, 1),
        (FuncCode, 1),
        (CmpCode, 1),
        (Switch, 1),
    ] {
        assert_eq!(kind.width(), width, "{kind:?}");
    }
}

#[test]
fn pc_of_seq_finds_the_first_block() {
    let m = sample_module();
    assert_eq!(m.pc_of_seq(0, 10), Some(0));
    assert_eq!(m.pc_of_seq(0, 20), Some(22)); // N20 twice: the first wins
    assert_eq!(m.pc_of_seq(0, 15), None);
    assert_eq!(m.pc_of_seq(0, 1), None); // N1 is the macro's, not main's
    assert_eq!(m.pc_of_seq(1, 1), Some(38));
    assert_eq!(m.pc_of_seq(2, 1), None);
}

#[test]
fn helper_enums_agree_with_the_verifier_limits() {
    assert_eq!(isa::MathFunc::ALL.len(), 15);
    assert_eq!(isa::MathFunc::from_code(14), Some(isa::MathFunc::Bcd));
    assert_eq!(isa::CmpOp::ALL.len(), 6);
    assert_eq!(isa::CmpOp::from_code(5).map(isa::CmpOp::name), Some("LE"));
    assert_eq!(isa::addr::from_letter('x'), Some(23));
    assert_eq!(isa::addr::from_letter(','), None);
    assert_eq!(isa::addr::name(isa::addr::MAX), Some(",R"));
    assert_eq!(isa::addr::name(isa::addr::MAX + 1), None);
}

proptest! {
    /// Any operand values, any opcode: decode ∘ encode is the identity on
    /// bytes and on instructions.
    #[test]
    fn random_instructions_round_trip(
        index in 0..Opcode::ALL.len(),
        operand_bytes in proptest::collection::vec(any::<u8>(), 16),
    ) {
        let op = Opcode::ALL[index];
        let mut it = operand_bytes.into_iter();
        let bytes = forge(op, &mut || it.next().unwrap_or(0));
        let (instr, end) = Instr::decode(&bytes, 0).unwrap();
        prop_assert_eq!(end, bytes.len());
        let mut again = Vec::new();
        instr.encode(&mut again);
        prop_assert_eq!(&again, &bytes);
        prop_assert_eq!(Instr::decode(&again, 0).unwrap().0, instr);
    }
}
