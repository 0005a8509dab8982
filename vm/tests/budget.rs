//! The block budget (dialect.md §7.12, E6005) and resumable stepping.
//!
//! Every loop must end, whatever instruction closes it: a backward
//! transfer of control is charged like a block, so a module that loops
//! forever, compiled or crafted, stops with E6005 once the budget is used.

mod common;

use common::{alarm_of, run, vm, Asm, Canon};
use isa::{Instr, Module, Opcode};
use vm::Status;

/// E6005: the block budget is used up (dialect.md §8.4).
const BUDGET_ALARM: u32 = 6005;

/// The module of issue 20 item 1: a small module whose first instruction
/// is `loadk r0, k0`, written to bytes; byte 11 (the first opcode: 4 bytes
/// of magic, 2 of version, the code section's tag and 4-byte length) is
/// flipped from `loadk` (0x01) to `jumpifnot` (0x21), leaving the operand
/// bytes `r0` and `0` to read `jumpifnot r0, @0`, and the CRC is
/// recomputed.
fn crafted_loop() -> Vec<u8> {
    let mut a = Asm::new();
    a.load(0, 5.0); // #1 = 5
    a.op(Instr::StoreVar { var: 1, src: 0 });
    a.line(2);
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    let mut bytes = a.build().to_bytes();
    assert_eq!(
        bytes[11],
        Opcode::LoadK as u8,
        "the first opcode is at byte 11"
    );
    bytes[11] ^= 0x20;
    assert_eq!(bytes[11], Opcode::JumpIfNot as u8);
    let body = bytes.len() - 4;
    let crc = crc32fast::hash(&bytes[..body]);
    bytes[body..].copy_from_slice(&crc.to_le_bytes());
    bytes
}

#[test]
fn a_crafted_backward_conditional_jump_ends_with_the_budget_alarm() {
    let bytes = crafted_loop();
    let module = Module::from_bytes(&bytes).expect("the verifier accepts the crafted loop");
    assert_eq!(module.code[0], Instr::JumpIfNot { cond: 0, target: 0 });

    // With --max-blocks 1: the first pass of `jumpifnot r0, @0` (r0 is
    // vacant, so the jump is taken) is block 1; the second is block 2,
    // past the budget.
    let mut machine = vm(module.clone());
    machine.max_blocks = 1;
    let mut canon = Canon::default();
    let alarm = alarm_of(machine.step(10, &mut canon));
    assert_eq!(alarm.code, BUDGET_ALARM);
    assert_eq!((alarm.file.as_str(), alarm.line), (common::FILE, 1));
    assert_eq!(canon.0.len(), 1);
    assert!(canon.0[0].starts_with("ALARM CODE=6005 "), "{:?}", canon.0);

    // With a budget of 1000 blocks the loop runs exactly 1000 times: the
    // 1001st jump is the alarm (one instruction per pass).
    let mut machine = vm(module);
    machine.max_blocks = 1000;
    let mut canon = Canon::default();
    assert_eq!(machine.step(1000, &mut canon), Status::OutOfBudget);
    assert!(canon.0.is_empty());
    assert_eq!(alarm_of(machine.step(1, &mut canon)).code, BUDGET_ALARM);
}

/// A loop closed by a backward `jumpifnot` whose test stays false.
#[test]
fn a_loop_closed_by_a_conditional_jump_is_charged_per_turn() {
    let mut a = Asm::new();
    a.load(0, 0.0); // pc 0: r0 = 0, always false
    let top = a.here();
    a.line(3);
    a.op(Instr::JumpIfNot {
        cond: 0,
        target: top,
    }); // pc 1: loops on itself
    a.op(Instr::Halt);
    let mut machine = vm(a.build());
    machine.max_blocks = 7;
    let mut canon = Canon::default();
    // pc 0, then 7 charged turns: 8 instructions within the budget.
    assert_eq!(machine.step(8, &mut canon), Status::OutOfBudget);
    let alarm = alarm_of(machine.step(1, &mut canon));
    assert_eq!((alarm.code, alarm.line), (BUDGET_ALARM, 3));
}

#[test]
fn forward_jumps_are_not_blocks() {
    // r0 = 0: `jumpifnot` skips the G00 block; `jump` skips a second one;
    // only the M30 block is executed, so a budget of one block suffices.
    let mut a = Asm::new();
    a.load(0, 0.0);
    let skip = a.op(Instr::JumpIfNot { cond: 0, target: 0 });
    a.word('G', 0.0);
    a.word('X', 1.0);
    a.exec();
    let over = a.op(Instr::Jump { target: 0 });
    a.word('G', 0.0);
    a.word('X', 2.0);
    a.exec();
    let end = a.here();
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    a.set(
        skip,
        Instr::JumpIfNot {
            cond: 0,
            target: over,
        },
    );
    a.set(over, Instr::Jump { target: end });
    let mut machine = vm(a.build());
    machine.max_blocks = 1;
    let mut canon = Canon::default();
    assert_eq!(machine.run(&mut canon), Status::Done);
    assert_eq!(canon.0, ["STOP KIND=M30"]);
}

#[test]
fn backward_jumps_and_computed_gotos_are_charged() {
    // `DO1 … END1` without a block inside: an unconditional jump to itself.
    let mut a = Asm::new();
    a.op(Instr::Jump { target: 0 });
    let mut machine = vm(a.build());
    machine.max_blocks = 5;
    let mut canon = Canon::default();
    assert_eq!(machine.step(5, &mut canon), Status::OutOfBudget);
    assert_eq!(alarm_of(machine.step(1, &mut canon)).code, BUDGET_ALARM);

    // `N10 GOTO #1` with #1 = 10: a computed GOTO is charged every time.
    let mut a = Asm::new();
    a.load(0, 10.0); // pc 0
    a.seq(10);
    a.op(Instr::GotoSeq { seq: 0 }); // pc 1: N10
    let mut machine = vm(a.build());
    machine.max_blocks = 5;
    let mut canon = Canon::default();
    // pc 0, then five charged GOTOs.
    assert_eq!(machine.step(6, &mut canon), Status::OutOfBudget);
    assert_eq!(alarm_of(machine.step(1, &mut canon)).code, BUDGET_ALARM);
}

/// Three motion blocks, an assignment and M30: five blocks.
fn five_blocks() -> Module {
    let mut a = Asm::new();
    for (line, x) in [(1, 1.0), (2, 2.0), (3, 3.0)] {
        a.line(line);
        a.word('G', 0.0);
        a.word('X', x);
        a.exec();
    }
    a.line(4);
    a.load(0, 7.0);
    a.op(Instr::StoreVar { var: 100, src: 0 });
    a.line(5);
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    a.build()
}

#[test]
fn the_budget_counts_executed_blocks_and_assignments() {
    let mut machine = vm(five_blocks());
    machine.max_blocks = 5;
    let mut canon = Canon::default();
    assert_eq!(machine.run(&mut canon), Status::Done);
    assert_eq!(
        canon.0,
        [
            "RAPID X=1 Z=0",
            "RAPID X=2 Z=0",
            "RAPID X=3 Z=0",
            "STOP KIND=M30"
        ]
    );

    // One block less: the M30 block (line 5) is the fifth charge, one
    // past a budget of 4.
    let mut machine = vm(five_blocks());
    machine.max_blocks = 4;
    let mut canon = Canon::default();
    let alarm = alarm_of(machine.run(&mut canon));
    assert_eq!((alarm.code, alarm.line), (BUDGET_ALARM, 5));
    assert_eq!(canon.0.len(), 4, "{:?}", canon.0);
    assert!(canon.0[3].starts_with("ALARM CODE=6005"));
}

#[test]
fn the_budget_counts_every_pass_of_a_repeated_program() {
    // `G00 X1` then M99 in the main program: two blocks a pass; three
    // passes are six blocks (dialect.md §7.11: E6005 counts every pass).
    let build = || {
        let mut a = Asm::new();
        a.word('G', 0.0);
        a.word('X', 1.0);
        a.exec();
        a.op(Instr::Ret);
        a.build()
    };
    let mut machine = vm(build());
    machine.repeat = 3;
    machine.max_blocks = 6;
    let mut canon = Canon::default();
    assert_eq!(machine.run(&mut canon), Status::Done);
    assert_eq!(
        canon.0,
        [
            "RAPID X=1 Z=0",
            "RAPID X=1 Z=0",
            "RAPID X=1 Z=0",
            "STOP KIND=M99"
        ]
    );
    let mut machine = vm(build());
    machine.repeat = 3;
    machine.max_blocks = 5;
    assert_eq!(
        alarm_of(machine.run(&mut Canon::default())).code,
        BUDGET_ALARM
    );
}

/// A loop that sums 1…10 into #100 and shows the running sum after each
/// turn: `WHILE [#101 LE 10] DO1 / #100 = #100 + #101 / G00 X#100 Z#101 /
/// #101 = #101 + 1 / END1 / M30`.
fn summing_loop() -> Module {
    let mut a = Asm::new();
    a.load(0, 0.0);
    a.op(Instr::StoreVar { var: 100, src: 0 });
    a.load(0, 1.0);
    a.op(Instr::StoreVar { var: 101, src: 0 });
    let top = a.here();
    a.op(Instr::LoadVar { dst: 0, var: 101 });
    a.load(1, 10.0);
    a.op(Instr::Cmp {
        dst: 2,
        a: 0,
        b: 1,
        op: isa::CmpOp::Le.code(),
    });
    let exit = a.op(Instr::JumpIfNot { cond: 2, target: 0 });
    a.op(Instr::LoadVar { dst: 3, var: 100 });
    a.op(Instr::Add { dst: 3, a: 3, b: 0 });
    a.op(Instr::StoreVar { var: 100, src: 3 });
    a.show(3, 0);
    a.load(1, 1.0);
    a.op(Instr::Add { dst: 0, a: 0, b: 1 });
    a.op(Instr::StoreVar { var: 101, src: 0 });
    a.op(Instr::Jump { target: top });
    let end = a.here();
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    a.set(
        exit,
        Instr::JumpIfNot {
            cond: 2,
            target: end,
        },
    );
    a.build()
}

#[test]
fn stepping_in_slices_gives_the_same_run_as_one_call() {
    let (status, whole, done) = run(summing_loop());
    assert_eq!(status, Status::Done);
    // The running sums 1, 3, 6, … 55 (n(n+1)/2), each with its n.
    let expected: Vec<String> = (1..=10)
        .map(|n| format!("RAPID X={} Z={n}", n * (n + 1) / 2))
        .chain(["STOP KIND=M30".to_string()])
        .collect();
    assert_eq!(whole, expected);
    assert_eq!(done.variable(100).unwrap(), 55.0);

    for slice in [1, 2, 3, 7, 1000] {
        let mut machine = vm(summing_loop());
        let mut canon = Canon::default();
        let mut out_of_budget = 0;
        let status = loop {
            match machine.step(slice, &mut canon) {
                Status::OutOfBudget => out_of_budget += 1,
                Status::Event => {}
                other => break other,
            }
        };
        assert_eq!(status, Status::Done, "slice {slice}");
        assert_eq!(canon.0, whole, "slice {slice}");
        assert_eq!(machine.variable(100).unwrap(), 55.0);
        assert_eq!(machine.variable(101).unwrap(), 11.0);
        if slice < 10 {
            assert!(out_of_budget > 0, "slice {slice} never ran out");
        }
    }
}

#[test]
fn a_zero_budget_does_nothing_and_a_block_returns_an_event() {
    let mut machine = vm(five_blocks());
    let mut canon = Canon::default();
    assert_eq!(machine.step(0, &mut canon), Status::OutOfBudget);
    assert!(canon.0.is_empty());
    // The first block's three instructions and its event, then control
    // comes back even though budget remains.
    assert_eq!(machine.step(100, &mut canon), Status::Event);
    assert_eq!(canon.0, ["RAPID X=1 Z=0"]);
    // After the end, stepping again only repeats Done.
    assert_eq!(machine.run(&mut canon), Status::Done);
    assert_eq!(machine.step(100, &mut canon), Status::Done);
    assert_eq!(canon.0.len(), 4);
}

#[test]
fn a_current_position_read_waits_for_the_motion_then_resumes() {
    // `G00 X5 Z-2` then `#100 = #5021`: with `sync_positions` set, the
    // read first returns Sync (the host lets the move finish), and the
    // next call runs it. The value is the programmed end point (§7.2:
    // current equals the end point of the last executed move), X in
    // diameter as written.
    let build = || {
        let mut a = Asm::new();
        a.word('G', 0.0);
        a.word('X', 5.0);
        a.word('Z', -2.0);
        a.exec();
        a.op(Instr::LoadVar { dst: 0, var: 5021 });
        a.op(Instr::StoreVar { var: 100, src: 0 });
        a.op(Instr::LoadVar { dst: 0, var: 5022 });
        a.op(Instr::StoreVar { var: 101, src: 0 });
        a.op(Instr::Halt);
        a.build()
    };
    let mut machine = vm(build());
    machine.sync_positions = true;
    let mut canon = Canon::default();
    assert_eq!(machine.step(100, &mut canon), Status::Event);
    assert_eq!(machine.step(100, &mut canon), Status::Sync);
    assert!(machine.variable(100).unwrap().is_nan(), "not read yet");
    // One wait covers every read up to the next block.
    assert_eq!(machine.step(100, &mut canon), Status::Done);
    assert_eq!(machine.variable(100).unwrap(), 5.0);
    assert_eq!(machine.variable(101).unwrap(), -2.0);
    assert_eq!(canon.0, ["RAPID X=5 Z=-2"]);

    // Without it, the same run never stops to wait.
    let (status, _, done) = run(build());
    assert_eq!(status, Status::Done);
    assert_eq!(done.variable(100).unwrap(), 5.0);
}
