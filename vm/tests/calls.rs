//! Calls on hand-built modules: M98 and G65 levels and repetitions, the
//! nesting limits of dialect.md §7.12, M99 P, computed targets and the
//! modal call. Expected values are worked out by hand from the spec.

mod common;

use common::{alarm_of, run, Asm};
use isa::{CmpOp, Instr};
use vm::{Status, Vm};

/// `#var = #var + 1`, using r6 and r7.
fn bump(a: &mut Asm, var: u32) {
    a.op(Instr::LoadVar { dst: 6, var });
    a.load(7, 1.0);
    a.op(Instr::Add { dst: 6, a: 6, b: 7 });
    a.op(Instr::StoreVar { var, src: 6 });
}

fn done(a: Asm) -> Vm {
    let (status, canon, vm) = run(a.build());
    assert_eq!(status, Status::Done, "{canon:?}");
    vm
}

fn var(vm: &Vm, n: u32) -> f64 {
    vm.variable(n).unwrap()
}

/// Runs `call` on line `line`, r0 holding `value` (vacant for `None`) and
/// r1 vacant, with one program after the main one, number `callee`, that
/// adds 1 to #100: #100 after the run, or the alarm's code (its line
/// checked).
fn call_once(value: Option<f64>, call: Instr, callee: u32, line: u32) -> Result<f64, u32> {
    let mut a = Asm::new();
    match value {
        Some(v) => a.load(0, v),
        None => a.op(Instr::LoadNull { dst: 0 }),
    };
    a.op(Instr::LoadNull { dst: 1 });
    a.line(line);
    a.op(call);
    a.op(Instr::Halt);
    a.program(callee);
    bump(&mut a, 100);
    a.op(Instr::Ret);
    let (status, _, vm) = run(a.build());
    match status {
        Status::Done => Ok(var(&vm, 100)),
        other => {
            let alarm = alarm_of(other);
            assert_eq!(alarm.line, line);
            Err(alarm.code)
        }
    }
}

#[test]
fn m98_repeats_on_the_callers_local_level() {
    // Main: #1 = 0, M98 P2 L3; O0002: #1 = #1 + 1, M99. The subprogram
    // shares the caller's locals (§7.1) and runs three times (§7.11).
    let mut a = Asm::new();
    a.load(0, 0.0);
    a.op(Instr::StoreVar { var: 1, src: 0 });
    a.load(1, 3.0);
    a.op(Instr::CallSub { prog: 1, count: 1 });
    a.op(Instr::Halt);
    a.program(2);
    bump(&mut a, 1);
    a.op(Instr::Ret);
    assert_eq!(var(&done(a), 1), 3.0);
}

#[test]
fn a_vacant_repeat_count_is_once_and_outside_1_to_9999_an_alarm() {
    let calls = |v: Option<f64>| call_once(v, Instr::CallSub { prog: 1, count: 0 }, 2, 4);
    // An L word left out (vacant, §7.5) is once; §7.6: a count below 1
    // or past 9999 is E5010 (L is 1…9999, §7.9).
    assert_eq!(calls(Some(0.0)), Err(5010));
    assert_eq!(calls(None), Ok(1.0));
    assert_eq!(calls(Some(2.4)), Ok(2.0), "rounded");
    assert_eq!(calls(Some(9999.0)), Ok(9999.0));
    assert_eq!(calls(Some(10000.0)), Err(5010));
    assert_eq!(calls(Some(-1.0)), Err(5010));
}

/// `callsubpacked`: a computed `M98 P<count:4><program:4>` (§7.11), split
/// when it runs: count 0 is once, a vacant P is E5009 (§7.5), a program
/// that does not exist E6003.
#[test]
fn a_computed_packed_m98_is_split_when_it_runs() {
    let calls = |v: Option<f64>| call_once(v, Instr::CallSubPacked { num: 0 }, 2, 3);
    assert_eq!(calls(Some(2.0)), Ok(1.0));
    assert_eq!(calls(Some(30_002.0)), Ok(3.0));
    assert_eq!(calls(Some(2.4)), Ok(1.0), "rounded");
    assert_eq!(calls(None), Err(5009));
    assert_eq!(calls(Some(40_003.0)), Err(6003));
}

#[test]
fn g65_gets_a_fresh_local_level_with_its_arguments() {
    // Main: #1 = 9, #3 = 4; G65 P9001 L2 A5 B#0.
    // O9001: #100 = #100 + #1; #101 = [#2 EQ #0]; #102 = #3; #3 = 77.
    // §7.9: the macro's locals are a fresh set (#3 null, not the caller's
    // 4) plus its arguments (#1 = 5; a null argument leaves #2 null);
    // after M99 the caller's level is back (#1 = 9, #3 = 4). Run twice:
    // #100 = 5 + 5 (a vacant #100 counts as 0).
    let mut a = Asm::new();
    a.load(0, 9.0);
    a.op(Instr::StoreVar { var: 1, src: 0 });
    a.load(0, 4.0);
    a.op(Instr::StoreVar { var: 3, src: 0 });
    a.load(0, 5.0);
    a.op(Instr::LoadNull { dst: 1 });
    a.load(2, 2.0);
    a.op(Instr::Arg { var: 1, src: 0 });
    a.op(Instr::Arg { var: 2, src: 1 });
    a.op(Instr::CallMacro { prog: 1, count: 2 });
    a.op(Instr::Halt);
    a.program(9001);
    a.op(Instr::LoadVar { dst: 0, var: 100 });
    a.op(Instr::LoadVar { dst: 1, var: 1 });
    a.op(Instr::Add { dst: 0, a: 0, b: 1 });
    a.op(Instr::StoreVar { var: 100, src: 0 });
    a.op(Instr::LoadVar { dst: 2, var: 2 });
    a.op(Instr::LoadNull { dst: 3 });
    a.op(Instr::Cmp {
        dst: 4,
        a: 2,
        b: 3,
        op: CmpOp::Eq.code(),
    });
    a.op(Instr::StoreVar { var: 101, src: 4 });
    a.op(Instr::LoadVar { dst: 5, var: 3 });
    a.op(Instr::StoreVar { var: 102, src: 5 });
    a.load(5, 77.0);
    a.op(Instr::StoreVar { var: 3, src: 5 });
    a.op(Instr::Ret);
    let vm = done(a);
    assert_eq!(var(&vm, 100), 10.0);
    assert_eq!(var(&vm, 101), 1.0, "#2 of the macro is null");
    assert!(var(&vm, 102).is_nan(), "the macro's #3 starts null");
    assert_eq!((var(&vm, 1), var(&vm, 3)), (9.0, 4.0));
}

/// O0001 calls O0002, which counts its level in #100 and calls itself,
/// by `call` (the call on line 20), without end.
fn recursion(call: Instr) -> (vm::Alarm, f64) {
    let mut a = Asm::new();
    a.load(0, 1.0);
    a.op(call);
    a.op(Instr::Halt);
    a.program(2);
    bump(&mut a, 100);
    a.load(0, 1.0);
    a.line(20);
    a.op(call);
    a.op(Instr::Ret);
    let (status, _, vm) = run(a.build());
    (alarm_of(status), var(&vm, 100))
}

#[test]
fn macro_and_subprogram_nesting_stops_past_four_levels() {
    // §7.12: four macro levels, four subprogram levels; the fifth call is
    // E6004, made from the fourth level (#100 = 4), at its line.
    for call in [
        Instr::CallMacro { prog: 1, count: 0 },
        Instr::CallSub { prog: 1, count: 0 },
    ] {
        let (alarm, levels) = recursion(call);
        assert_eq!((alarm.code, alarm.line), (6004, 20), "{call}");
        assert_eq!(levels, 4.0, "{call}");
    }
}

/// G65 and M98 alternating: O0002 (reached by G65) and O0003 (by M98)
/// each count their level in #100 and call the other while #100 < #101.
fn alternating(limit: f64) -> (Status, f64) {
    let mut a = Asm::new();
    a.load(0, limit);
    a.op(Instr::StoreVar { var: 101, src: 0 });
    a.op(Instr::LoadNull { dst: 0 });
    a.op(Instr::CallMacro { prog: 1, count: 0 });
    a.op(Instr::Halt);
    for (number, next) in [
        (2, Instr::CallSub { prog: 2, count: 0 }),
        (3, Instr::CallMacro { prog: 1, count: 0 }),
    ] {
        a.program(number);
        bump(&mut a, 100);
        a.op(Instr::LoadVar { dst: 1, var: 100 });
        a.op(Instr::LoadVar { dst: 2, var: 101 });
        a.op(Instr::Cmp {
            dst: 3,
            a: 1,
            b: 2,
            op: CmpOp::Lt.code(),
        });
        let skip = a.op(Instr::JumpIfNot { cond: 3, target: 0 });
        a.op(Instr::LoadNull { dst: 0 });
        a.line(30 + number);
        a.op(next);
        let ret = a.op(Instr::Ret);
        a.set(
            skip,
            Instr::JumpIfNot {
                cond: 3,
                target: ret,
            },
        );
    }
    let (status, _, vm) = run(a.build());
    (status, var(&vm, 100))
}

#[test]
fn eight_calls_in_all_may_nest() {
    // §7.12: 4 macro + 4 subprogram levels = 8 in all (Decision): eight
    // nested calls run and return; the ninth, a G65 from O0003 on the
    // eighth level (line 33), is E6004.
    assert_eq!(alternating(8.0), (Status::Done, 8.0));
    let (status, levels) = alternating(9.0);
    let alarm = alarm_of(status);
    assert_eq!((alarm.code, alarm.line, levels), (6004, 33, 8.0));
}

#[test]
fn computed_call_targets() {
    let dynamic = |v: Option<f64>| call_once(v, Instr::CallSubDyn { num: 0, count: 1 }, 1234, 5);
    // §7.11/§8.4: a computed number naming no program is E6003; null as
    // a call target E5009 (§7.5); the number is rounded.
    assert_eq!(dynamic(Some(1234.0)), Ok(1.0));
    assert_eq!(dynamic(Some(1233.5)), Ok(1.0));
    assert_eq!(dynamic(Some(4321.0)), Err(6003));
    assert_eq!(dynamic(None), Err(5009));

    // The same for G65 with a computed number.
    let mut a = Asm::new();
    a.load(0, 77.0);
    a.op(Instr::LoadNull { dst: 1 });
    a.line(6);
    a.op(Instr::CallMacroDyn { num: 0, count: 1 });
    a.op(Instr::Halt);
    let alarm = alarm_of(run(a.build()).0);
    assert_eq!((alarm.code, alarm.line), (6003, 6));
}

/// Main: M98 P2, then `G00 X1` (skipped by M99 P50), N50 M30.
/// O0002: M99 P<seq> on line 9.
fn return_to(seq: f64) -> (Status, Vec<String>) {
    let mut a = Asm::new();
    a.op(Instr::LoadNull { dst: 0 });
    a.op(Instr::CallSub { prog: 1, count: 0 });
    a.word('G', 0.0);
    a.word('X', 1.0);
    a.exec();
    a.seq(50);
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    a.program(2);
    a.load(0, seq);
    a.line(9);
    a.op(Instr::RetSeq { seq: 0 });
    let (status, canon, _) = run(a.build());
    (status, canon)
}

#[test]
fn m99_p_returns_to_a_block_of_the_caller() {
    // §7.11: after the last repetition, return to Nn of the caller.
    assert_eq!(
        return_to(50.0),
        (Status::Done, vec!["STOP KIND=M30".to_string()])
    );
    // No N60 in the caller: E6002 at the M99.
    let (status, _) = return_to(60.0);
    let alarm = alarm_of(status);
    assert_eq!((alarm.code, alarm.line), (6002, 9));
}

#[test]
fn a_computed_goto_to_a_missing_or_vacant_target() {
    let goto = |seq: Option<f64>| {
        let mut a = Asm::new();
        match seq {
            Some(n) => a.load(0, n),
            None => a.op(Instr::LoadNull { dst: 0 }),
        };
        a.line(3);
        a.op(Instr::GotoSeq { seq: 0 });
        a.word('G', 0.0);
        a.word('X', 1.0);
        a.exec();
        a.seq(20);
        a.word('M', 30.0);
        a.exec();
        a.op(Instr::Halt);
        let (status, canon, _) = run(a.build());
        match status {
            Status::Done => Ok(canon),
            other => {
                let alarm = alarm_of(other);
                assert_eq!(alarm.line, 3);
                Err(alarm.code)
            }
        }
    };
    // §7.7: GOTO 20 skips the G00 block; a missing computed target is
    // E6001 (§8.4), a null one E5009 (§7.5), 20.4 rounds to 20 (§7.6).
    assert_eq!(goto(Some(20.0)), Ok(vec!["STOP KIND=M30".to_string()]));
    assert_eq!(goto(Some(20.4)), Ok(vec!["STOP KIND=M30".to_string()]));
    assert_eq!(goto(Some(30.0)), Err(6001));
    assert_eq!(goto(None), Err(5009));
}

#[test]
fn a_modal_call_follows_each_move_until_g67() {
    // G66 P2; G00 X1 (calls); M05 (no move: no call); G00 X2 (calls);
    // G67; G00 X3 (no call). O0002 counts its calls in #100 (§7.9).
    let mut a = Asm::new();
    a.op(Instr::LoadNull { dst: 0 });
    a.op(Instr::ModalCall { prog: 1, count: 0 });
    for (letter, value) in [('X', 1.0), ('M', 5.0), ('X', 2.0)] {
        if letter == 'X' {
            a.word('G', 0.0);
        }
        a.word(letter, value);
        a.exec();
    }
    a.op(Instr::ModalCancel);
    a.word('G', 0.0);
    a.word('X', 3.0);
    a.exec();
    a.op(Instr::Halt);
    a.program(2);
    bump(&mut a, 100);
    a.op(Instr::Ret);
    assert_eq!(var(&done(a), 100), 2.0);
}

#[test]
fn a_computed_modal_call() {
    // G66 P#1 with #1 = 2, then two moves: O0002 runs after each (§7.9).
    let mut a = Asm::new();
    a.load(0, 2.0);
    a.op(Instr::LoadNull { dst: 1 });
    a.op(Instr::ModalCallDyn { num: 0, count: 1 });
    for x in [1.0, 2.0] {
        a.word('G', 0.0);
        a.word('X', x);
        a.exec();
    }
    a.op(Instr::Halt);
    a.program(2);
    bump(&mut a, 100);
    a.op(Instr::Ret);
    assert_eq!(var(&done(a), 100), 2.0);
}
