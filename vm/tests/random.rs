//! Random valid modules: each verifies, and every run ends (done or an
//! alarm) within the bound that the block budget implies, without a
//! panic; stepping one instruction at a time gives the same run as one
//! call.
//!
//! The bound: every instruction that can move control backwards (a
//! backward jump, GOTO, a call, M99) or that executes a block is charged to
//! the budget, and between two charges the pc only grows. So a run of a
//! module of `n` instructions with a budget of `b` blocks ends within
//! `(b + 1) · (n + 1)` steps.

mod common;

use common::Canon;
use isa::{addr, Instr, Module, Program, SourceFileInfo, SourceLoc};
use proptest::prelude::*;
use vm::{Status, Vm};

const REGS: u8 = 4;
/// Constants the generated code loads and puts into words: finite and
/// modest, so blocks reach the kernel with ordinary values.
const CONSTS: [f64; 8] = [0.0, 1.0, -2.5, 3.0, 30.0, 100.0, 0.5, 2.0];
/// Variable numbers across every range of dialect.md §7.1 and past them.
const VARS: [u32; 14] = [
    0, 1, 2, 33, 34, 100, 101, 199, 500, 999, 3000, 3006, 4115, 5001,
];
/// Word addresses a generated block uses: G, X, Z, F, M.
const ADDRS: [u8; 5] = [6, 23, 25, 5, 12];
const BUDGET: u64 = 50;

/// The typed blocks every generated module carries (`G0 X1 Z2.`,
/// `G1 F0.5`, `M30`), and where each record starts.
fn typed_blocks() -> (Vec<u8>, Vec<u32>) {
    let w = |addr, value, flags| isa::BlockWord { addr, value, flags };
    let records: [&[isa::BlockWord]; 3] = [
        &[w(6, 0.0, 3), w(23, 1.0, 3), w(25, 2.0, 2)],
        &[w(6, 1.0, 3), w(23, -2.5, 2), w(5, 0.5, 2)],
        &[w(12, 30.0, 3)],
    ];
    let mut m = Module::default();
    let recs = records
        .iter()
        .map(|words| m.push_block(words).expect("fits a record"))
        .collect();
    (m.blocks, recs)
}

/// One instruction from raw numbers; operands are brought into range so
/// the module verifies (`len` instructions, `progs` programs).
fn instr(raw: (u8, u8, u8, u8, u32), len: u32, progs: u32) -> Instr {
    let (sel, a, b, c, w) = raw;
    let (ra, rb, rc) = (a % REGS, b % REGS, c % REGS);
    let k = w % CONSTS.len() as u32;
    let var = VARS[w as usize % VARS.len()];
    let target = w % len;
    let prog = w % progs;
    match sel % 38 {
        0 => Instr::LoadK { dst: ra, k },
        1 => Instr::LoadNull { dst: ra },
        2 => Instr::Mov { dst: ra, src: rb },
        3 => Instr::LoadVar { dst: ra, var },
        4 => Instr::LoadVarInd { dst: ra, idx: rb },
        5 => Instr::StoreVar { var, src: ra },
        6 => Instr::StoreVarInd { idx: ra, src: rb },
        7 => Instr::Neg { dst: ra, a: rb },
        8 => Instr::Add {
            dst: ra,
            a: rb,
            b: rc,
        },
        9 => Instr::Sub {
            dst: ra,
            a: rb,
            b: rc,
        },
        10 => Instr::Mul {
            dst: ra,
            a: rb,
            b: rc,
        },
        11 => Instr::Div {
            dst: ra,
            a: rb,
            b: rc,
        },
        12 => Instr::Mod {
            dst: ra,
            a: rb,
            b: rc,
        },
        13 => Instr::Func {
            dst: ra,
            a: rb,
            f: c % 15,
        },
        14 => Instr::Cmp {
            dst: ra,
            a: rb,
            b: rc,
            op: (w % 6) as u8,
        },
        15 | 16 => Instr::Jump { target },
        17 | 18 => Instr::JumpIfNot { cond: ra, target },
        19 => Instr::GotoSeq { seq: ra },
        20 => Instr::Word {
            addr: ADDRS[b as usize % ADDRS.len()],
            src: ra,
        },
        21 => Instr::WordK {
            addr: ADDRS[b as usize % ADDRS.len()],
            k,
            flags: 0,
        },
        22 => Instr::Exec { flags: 0 },
        23 => Instr::CallSub { prog, count: ra },
        24 => Instr::CallMacro { prog, count: ra },
        25 => Instr::CallSubDyn { num: ra, count: rb },
        26 => Instr::Arg {
            var: 1 + c % 33,
            src: ra,
        },
        27 => Instr::Ret,
        28 => Instr::RetSeq { seq: ra },
        29 => {
            let recs = typed_blocks().1;
            Instr::Block {
                rec: recs[w as usize % recs.len()],
            }
        }
        // (The first two records are plain moves.)
        30 => Instr::Move {
            rec: typed_blocks().1[w as usize % 2],
        },
        31 => Instr::ExecMove,
        32 => Instr::AddK { dst: ra, a: rb, k },
        33 => Instr::SubK { dst: ra, a: rb, k },
        34 => Instr::MulK { dst: ra, a: rb, k },
        35 => Instr::CmpK {
            dst: ra,
            a: rb,
            k,
            op: (w % 6) as u8,
        },
        36 => Instr::DivK { dst: ra, a: rb, k },
        _ => Instr::Halt,
    }
}

/// A module of the given instructions, split into up to three programs
/// (O0001, O0002, O9001) at `cuts`, with sequence numbers 1–3 at `seqs`.
fn module(raw: Vec<(u8, u8, u8, u8, u32)>, cuts: (u32, u32), seqs: Vec<(u32, u32)>) -> Module {
    let len = raw.len() as u32;
    let mut bounds = vec![0, cuts.0 % len, cuts.1 % len, len];
    bounds.sort_unstable();
    bounds.dedup();
    let mut programs: Vec<Program> = bounds
        .windows(2)
        .zip([1, 2, 9001])
        .map(|(w, number)| Program {
            number,
            entry: w[0],
            end: w[1],
            ..Program::default()
        })
        .collect();
    for (n, pc) in seqs {
        let pc = pc % len;
        if let Some(p) = programs.iter_mut().find(|p| (p.entry..p.end).contains(&pc)) {
            p.seqs.push((1 + n % 3, pc));
        }
    }
    for p in &mut programs {
        p.seqs.sort_unstable();
        p.seqs.dedup();
    }
    let progs = programs.len() as u32;
    let mut code: Vec<Instr> = raw.into_iter().map(|r| instr(r, len, progs)).collect();
    // `block` operands may not go back in pc order (the verifier's rule).
    let mut last = 0;
    for i in &mut code {
        if let Instr::Block { rec } = i {
            *rec = (*rec).max(last);
            last = *rec;
        }
    }
    Module {
        code,
        consts: CONSTS.to_vec(),
        strings: vec!["MSG".to_string()],
        programs,
        lines: (0..len)
            .map(|pc| SourceLoc {
                file: 0,
                line: pc + 1,
                col: 1,
            })
            .collect(),
        files: vec![SourceFileInfo {
            name: "random.nc".to_string(),
            hash: 0,
        }],
        machine: String::new(),
        num_regs: u16::from(REGS),
        blocks: typed_blocks().0,
    }
}

fn fresh(m: &Module) -> Vm {
    let mut vm = common::vm(m.clone());
    vm.max_blocks = BUDGET;
    vm
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_modules_verify_and_every_run_ends(
        raw in prop::collection::vec(any::<(u8, u8, u8, u8, u32)>(), 1..40),
        cuts in any::<(u32, u32)>(),
        seqs in prop::collection::vec(any::<(u32, u32)>(), 0..6),
    ) {
        let m = module(raw, cuts, seqs);
        let loaded = Module::from_bytes(&m.to_bytes());
        prop_assert_eq!(loaded.as_ref(), Ok(&m));

        let bound = (BUDGET + 1) * (m.code.len() as u64 + 1);
        let mut vm = fresh(&m);
        let mut stepped = Canon::default();
        let mut steps = 0u64;
        let end = loop {
            match vm.step(1, &mut stepped) {
                Status::OutOfBudget | Status::Event | Status::Sync => {}
                other => break other,
            }
            steps += 1;
            prop_assert!(steps <= bound, "no end after {} steps", steps);
        };
        prop_assert!(matches!(end, Status::Done | Status::Alarm(_)));

        let mut whole = Canon::default();
        let once = fresh(&m).run(&mut whole);
        prop_assert_eq!(once, end);
        prop_assert_eq!(whole.0, stepped.0);
    }
}

#[test]
fn the_generator_reaches_every_family() {
    // Selector values 0…36 cover every arm of `instr` but `halt` (35
    // opcodes: jump and jumpifnot have two selectors each); a word
    // address outside the table would not verify.
    let kinds: std::collections::HashSet<_> = (0..37u8)
        .map(|sel| instr((sel, 1, 2, 3, 4), 10, 2).opcode())
        .collect();
    assert_eq!(kinds.len(), 35, "35 distinct opcodes");
    assert!(ADDRS.iter().all(|&a| a <= addr::MAX));
}
