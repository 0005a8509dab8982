//! The VM's side of a second tier (`vm::Tier`), with a tier scripted
//! here: when it is asked (a backward jump, and the instruction after the
//! one its code left at), what it is lent, and that what it hands back
//! counts: the pc, the variables, the block budget and the step's fuel.

mod common;

use common::{Asm, Canon};
use isa::{Instr, Module};
use std::sync::{Arc, Mutex};
use vm::{Entry, LoopState, Ran, Status, Tier, TierStats};

/// Records every entry; at the loop head it "runs" the loop body itself
/// (#1 += 1 and r0 = #1, a block charged, 3 instructions of fuel) and
/// leaves at the comparison, which the interpreter runs on.
struct Script {
    head: u32,
    leave_at: u32,
    seen: Arc<Mutex<Vec<(u32, Entry)>>>,
}

impl Tier for Script {
    fn stats(&self) -> TierStats {
        TierStats::default()
    }

    fn bind(&mut self, _: &Module) {}

    fn enter(&mut self, _: &Module, pc: u32, entry: Entry, s: LoopState<'_>) -> Option<u32> {
        self.seen.lock().unwrap().push((pc, entry));
        if pc != self.head || *s.fuel < 3 || *s.blocks >= s.max_blocks {
            return None;
        }
        s.locals[0] += 1.0;
        s.regs[0] = s.locals[0];
        *s.blocks += 1;
        *s.fuel -= 3;
        Some(self.leave_at)
    }
}

/// `#1 = 0; loop: #1 = #1 + 1 (3 instructions); if #1 < 5 goto loop`.
fn counting_loop() -> (Module, u32, u32) {
    let mut a = Asm::new();
    a.load(0, 0.0);
    a.op(Instr::StoreVar { var: 1, src: 0 });
    let head = a.here();
    a.op(Instr::LoadVar { dst: 0, var: 1 });
    let one = a.k(1.0);
    a.op(Instr::AddK {
        dst: 0,
        a: 0,
        k: one,
    });
    a.op(Instr::StoreVar { var: 1, src: 0 });
    let five = a.k(5.0);
    a.op(Instr::CmpK {
        dst: 1,
        a: 0,
        k: five,
        op: 3,
    });
    let test = a.here();
    a.op(Instr::JumpIfNot { cond: 1, target: 0 });
    let back = a.op(Instr::Jump { target: head });
    let end = a.here();
    a.set(
        test,
        Instr::JumpIfNot {
            cond: 1,
            target: end,
        },
    );
    a.op(Instr::Halt);
    (a.build(), head, back)
}

#[test]
fn a_tier_is_asked_at_backward_jumps_and_its_pc_and_state_count() {
    let (module, head, back) = counting_loop();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let mut vm = common::vm(module);
    // The tier's code leaves at the comparison (its "body" done).
    let compare = head + 3;
    vm.set_tier(Box::new(Script {
        head,
        leave_at: compare,
        seen: seen.clone(),
    }));
    let status = vm.run(&mut Canon::default());
    assert_eq!(status, Status::Done);
    // Round 1 interpreted (#1 = 1); rounds 2–5 by the tier at each back
    // edge: #1 ends at 5 as interpreting all would give.
    assert_eq!(vm.variable(1).unwrap(), 5.0);
    let seen = seen.lock().unwrap().clone();
    let back_edges = seen
        .iter()
        .filter(|(pc, e)| *pc == head && *e == Entry::BackEdge { from: back })
        .count();
    assert_eq!(back_edges, 4);
    // After each leave the VM offers the next instruction (the tier has
    // nothing there and says so).
    assert!(seen.contains(&(compare + 1, Entry::Resume)));
}

#[test]
fn the_fuel_a_tier_uses_ends_the_step() {
    let (module, head, _) = counting_loop();
    let mut vm = common::vm(module);
    vm.set_tier(Box::new(Script {
        head,
        leave_at: head + 3,
        seen: Arc::new(Mutex::new(Vec::new())),
    }));
    // 6 instructions take the run to the first back edge (the jump
    // included); with 10, the tier's 3 and the rest leave the step out of
    // budget before the loop ends, and the next steps finish it.
    let mut canon = Canon::default();
    assert_eq!(vm.step(10, &mut canon), Status::OutOfBudget);
    assert!(vm.variable(1).unwrap() < 5.0);
    assert_eq!(vm.run(&mut canon), Status::Done);
    assert_eq!(vm.variable(1).unwrap(), 5.0);
}

#[test]
fn a_charge_the_tier_makes_counts_against_the_block_budget() {
    // Interpreted, the run charges 10 blocks (the first store of #1, 5
    // stores in the loop, 4 back edges); the tier charges one block a
    // round in place of the store, so with it the count is the same.
    let ends = |budget: u64, tier: bool| {
        let (module, head, _) = counting_loop();
        let mut vm = common::vm(module);
        vm.max_blocks = budget;
        if tier {
            vm.set_tier(Box::new(Script {
                head,
                leave_at: head + 3,
                seen: Arc::new(Mutex::new(Vec::new())),
            }));
        }
        match vm.run(&mut Canon::default()) {
            Status::Alarm(a) => Some(a.code),
            _ => None,
        }
    };
    for tier in [false, true] {
        assert_eq!(ends(10, tier), None);
        assert_eq!(ends(9, tier), Some(6005));
    }
}

/// `r0 = 0; head: r0 += 1; r2 = r0·g − g; G[r2] X[r0] Z-1 (exec, line 3);
/// if r0 < 3 goto head (line 5)`: G0 in round 1, G[g] after it.
fn moving_loop(g: f64) -> (Module, u32, u32) {
    let mut a = Asm::new();
    a.load(0, 0.0);
    let head = a.here();
    let (one, gk) = (a.k(1.0), a.k(g));
    a.line(2);
    a.op(Instr::AddK {
        dst: 0,
        a: 0,
        k: one,
    });
    a.op(Instr::MulK {
        dst: 2,
        a: 0,
        k: gk,
    });
    a.op(Instr::SubK {
        dst: 2,
        a: 2,
        k: gk,
    });
    a.line(3);
    a.word_reg('G', 2);
    a.word_reg('X', 0);
    a.word('Z', -1.0);
    let exec = a.exec();
    a.line(5);
    let three = a.k(3.0);
    a.op(Instr::CmpK {
        dst: 1,
        a: 0,
        k: three,
        op: 3,
    });
    let test = a.here();
    a.op(Instr::JumpIfNot { cond: 1, target: 0 });
    a.op(Instr::Jump { target: head });
    let end = a.here();
    a.set(
        test,
        Instr::JumpIfNot {
            cond: 1,
            target: end,
        },
    );
    a.op(Instr::Halt);
    (a.build(), head, exec)
}

/// At the loop head it runs the round up to its block as the interpreter
/// would, then the block itself through the kernel it is lent, and
/// leaves after it. It records what the kernel said to each call.
struct RunsBlocks {
    head: u32,
    exec: u32,
    g: f64,
    calls: Arc<Mutex<Vec<Ran>>>,
}

impl Tier for RunsBlocks {
    fn stats(&self) -> TierStats {
        TierStats::default()
    }

    fn bind(&mut self, _: &Module) {}

    fn enter(&mut self, _: &Module, pc: u32, _: Entry, s: LoopState<'_>) -> Option<u32> {
        if pc != self.head || *s.fuel < 8 {
            return None;
        }
        let mut calls = self.calls.lock().unwrap();
        // Not a block: the kernel runs nothing.
        calls.push(s.kernel.run_block(self.head, s.words, s.blocks));
        s.regs[0] += 1.0;
        s.regs[2] = s.regs[0] * self.g - self.g;
        for (letter, v) in [('G', s.regs[2]), ('X', s.regs[0]), ('Z', -1.0)] {
            s.words.push(isa::addr::from_letter(letter).unwrap(), v, 0);
        }
        *s.fuel -= 7;
        let ran = s.kernel.run_block(self.exec, s.words, s.blocks);
        calls.push(ran);
        if ran == Ran::Leave {
            // The VM finishes that block first: a second is refused.
            calls.push(s.kernel.run_block(self.exec, s.words, s.blocks));
        }
        Some(self.exec + 1)
    }
}

/// Runs `moving_loop(g)`, with the scripted tier or without, its steps
/// ending at blocks or not; the canon, the status and how many steps
/// ended on a block.
fn run_moving(
    g: f64,
    tier: Option<Arc<Mutex<Vec<Ran>>>>,
    stop_at_blocks: bool,
) -> (Vec<String>, Status, usize) {
    let (module, head, exec) = moving_loop(g);
    let mut vm = common::vm(module);
    vm.stop_at_blocks = stop_at_blocks;
    if let Some(calls) = tier {
        vm.set_tier(Box::new(RunsBlocks {
            head,
            exec,
            g,
            calls,
        }));
    }
    let mut canon = Canon::default();
    let mut events = 0;
    let status = loop {
        match vm.step(1 << 16, &mut canon) {
            Status::Event => events += 1,
            Status::OutOfBudget | Status::Sync => {}
            other => break other,
        }
    };
    (canon.0, status, events)
}

#[test]
fn a_block_the_tier_runs_through_the_kernel_ends_the_step_as_the_interpreter_would() {
    let calls = Arc::new(Mutex::new(Vec::new()));
    let interpreted = run_moving(0.0, None, true);
    let tiered = run_moving(0.0, Some(calls.clone()), true);
    assert_eq!(interpreted.1, Status::Done);
    assert_eq!(interpreted.2, 3);
    let rapids = interpreted
        .0
        .iter()
        .filter(|l| l.starts_with("RAPID"))
        .count();
    assert_eq!(rapids, 3, "{:?}", interpreted.0);
    assert_eq!(tiered, interpreted);
    // Rounds 2 and 3 by the tier: the head refused, the block run (to be
    // finished by the VM), a second block refused, each time.
    use Ran::*;
    let calls = calls.lock().unwrap().clone();
    assert_eq!(calls, [Not, Leave, Not, Not, Leave, Not]);
}

#[test]
fn where_steps_run_past_blocks_the_tier_goes_on_after_its_blocks() {
    let calls = Arc::new(Mutex::new(Vec::new()));
    let interpreted = run_moving(0.0, None, true);
    let tiered = run_moving(0.0, Some(calls.clone()), false);
    // The same canon and end; no step ended on a block.
    assert_eq!((&tiered.0, &tiered.1), (&interpreted.0, &interpreted.1));
    assert_eq!(tiered.2, 0);
    use Ran::*;
    let calls = calls.lock().unwrap().clone();
    assert_eq!(calls, [Not, GoOn, Not, GoOn]);
}

#[test]
fn an_alarm_of_a_block_the_tier_ran_names_that_block() {
    // G7.7 (no such G code) in round 2, which the tier runs.
    for stop_at_blocks in [true, false] {
        let calls = Arc::new(Mutex::new(Vec::new()));
        let interpreted = run_moving(7.7, None, stop_at_blocks);
        let tiered = run_moving(7.7, Some(calls.clone()), stop_at_blocks);
        assert_eq!(tiered, interpreted);
        let alarm = common::alarm_of(tiered.1);
        assert_eq!(alarm.line, 3, "{alarm:?}");
        // A block that faults is the VM's to finish, steps ending at
        // blocks or not.
        assert_eq!(calls.lock().unwrap()[1], Ran::Leave);
    }
}
