//! Each instruction family of the VM on hand-built modules: arithmetic,
//! functions and comparisons with their vacant rules, variables, words,
//! jumps and alarms with their source lines.
//!
//! Every expected value is worked out by hand from
//! `../shared/spec/dialect.md` (the section is named at each table), not
//! taken from a run.

mod common;

use common::{alarm_of, run, Asm};
use isa::{CmpOp, Instr, MathFunc};
use vm::Status;

/// The source line the instruction under test is given, so each alarm can
/// be checked to name it.
const LINE: u32 = 7;

/// Loads `v` into `r`; `None` is the vacant value.
fn put(a: &mut Asm, r: u8, v: Option<f64>) {
    match v {
        Some(v) => a.load(r, v),
        None => a.op(Instr::LoadNull { dst: r }),
    };
}

/// Runs `body` (which leaves its result in the register it returns), then
/// `#100 = result`. `Ok` with the value of #100, or `Err` with the alarm
/// code, after checking the alarm names line [`LINE`] of the test file.
fn eval(body: impl FnOnce(&mut Asm) -> u8) -> Result<f64, u32> {
    let mut a = Asm::new();
    let r = body(&mut a);
    a.line(LINE + 1);
    a.op(Instr::StoreVar { var: 100, src: r });
    a.op(Instr::Halt);
    let (status, canon, vm) = run(a.build());
    match status {
        Status::Done => Ok(vm.variable(100).unwrap()),
        Status::Alarm(alarm) => {
            assert_eq!((alarm.file.as_str(), alarm.line), (common::FILE, LINE));
            let last = canon.last().cloned().unwrap_or_default();
            assert!(
                last.starts_with(&format!("ALARM CODE={} ", alarm.code)),
                "{canon:?}"
            );
            Err(alarm.code)
        }
        other => panic!("unexpected {other:?}"),
    }
}

/// Makes an instruction `dst = a <op> b` from `(dst, a, b)`.
type BinOp = fn(u8, u8, u8) -> Instr;

/// An operation, its operands, the expected result and what it shows.
type BinCase = (BinOp, Option<f64>, Option<f64>, f64, &'static str);

/// `op(r0, r1)` with the operands loaded first; the operation on [`LINE`].
fn binary(op: BinOp, x: Option<f64>, y: Option<f64>) -> Result<f64, u32> {
    eval(|a| {
        put(a, 0, x);
        put(a, 1, y);
        a.line(LINE);
        a.op(op(2, 0, 1));
        2
    })
}

fn func(f: MathFunc, x: Option<f64>) -> Result<f64, u32> {
    eval(|a| {
        put(a, 0, x);
        a.line(LINE);
        a.op(Instr::Func {
            dst: 1,
            a: 0,
            f: f.code(),
        });
        1
    })
}

fn cmp(op: CmpOp, x: Option<f64>, y: Option<f64>) -> f64 {
    eval(|a| {
        put(a, 0, x);
        put(a, 1, y);
        a.op(Instr::Cmp {
            dst: 2,
            a: 0,
            b: 1,
            op: op.code(),
        });
        2
    })
    .expect("comparisons never alarm")
}

const N: Option<f64> = None;

fn v(x: f64) -> Option<f64> {
    Some(x)
}

#[test]
fn arithmetic_follows_section_7_4_and_vacant_counts_as_zero() {
    let add = |d, a, b| Instr::Add { dst: d, a, b };
    let sub = |d, a, b| Instr::Sub { dst: d, a, b };
    let mul = |d, a, b| Instr::Mul { dst: d, a, b };
    let div = |d, a, b| Instr::Div { dst: d, a, b };
    let rem = |d, a, b| Instr::Mod { dst: d, a, b };
    let and = |d, a, b| Instr::BitAnd { dst: d, a, b };
    let or = |d, a, b| Instr::BitOr { dst: d, a, b };
    let xor = |d, a, b| Instr::BitXor { dst: d, a, b };
    #[rustfmt::skip]
    let cases: [BinCase; 16] = [
        (add, v(7.0), v(5.0), 12.0, "7+5"),
        (sub, v(7.0), v(5.0), 2.0, "7-5"),
        (mul, v(7.0), v(5.0), 35.0, "7*5"),
        (div, v(7.0), v(5.0), 1.4, "7/5"),
        // MOD: remainder of the rounded operands, sign of a (§7.4).
        (rem, v(-7.0), v(3.0), -1.0, "-7 MOD 3"),
        (rem, v(7.0), v(3.0), 1.0, "7 MOD 3"),
        (rem, v(7.6), v(3.0), 2.0, "8 MOD 3 (7.6 rounds to 8)"),
        // AND/OR/XOR bitwise on rounded operands: 1100 ? 1010.
        (and, v(12.0), v(10.0), 8.0, "12 AND 10"),
        (or, v(12.0), v(10.0), 14.0, "12 OR 10"),
        (xor, v(12.0), v(10.0), 6.0, "12 XOR 10"),
        (and, v(2.5), v(1.0), 1.0, "3 AND 1 (2.5 rounds half away to 3)"),
        // §7.5: null counts as 0 in arithmetic.
        (add, N, v(7.0), 7.0, "#0+7"),
        (mul, N, v(5.0), 0.0, "#0*5"),
        (add, N, N, 0.0, "#0+#0"),
        (sub, N, v(2.0), -2.0, "#0-2"),
        (div, N, v(4.0), 0.0, "#0/4"),
    ];
    for (op, x, y, want, what) in cases {
        assert_eq!(binary(op, x, y), Ok(want), "{what}");
    }
    // -0 is 0 (§7.6): the stored value has the bits of +0.
    let minus_zero = binary(mul, v(-1.0), v(0.0)).unwrap();
    assert_eq!(minus_zero.to_bits(), 0.0f64.to_bits());
}

#[test]
fn arithmetic_errors_alarm_at_their_line() {
    let div = |d, a, b| Instr::Div { dst: d, a, b };
    let rem = |d, a, b| Instr::Mod { dst: d, a, b };
    let mul = |d, a, b| Instr::Mul { dst: d, a, b };
    // §8.4: E5001 division by zero (a vacant divisor counts as 0, §7.5;
    // MOD's divisor is rounded first, 0.4 → 0); E5006 result not finite.
    assert_eq!(binary(div, v(1.0), v(0.0)), Err(5001));
    assert_eq!(binary(div, v(1.0), N), Err(5001));
    assert_eq!(binary(rem, v(5.0), v(0.4)), Err(5001));
    assert_eq!(binary(mul, v(1e300), v(1e300)), Err(5006));
}

#[test]
fn unary_minus_mov_and_loads() {
    // §7.5: `-#1` with #1 null is 0; a copy keeps null.
    let neg = |x| {
        eval(|a| {
            put(a, 0, x);
            a.op(Instr::Neg { dst: 1, a: 0 });
            1
        })
    };
    assert_eq!(neg(v(5.0)), Ok(-5.0));
    assert_eq!(neg(N).map(f64::to_bits), Ok(0.0f64.to_bits()));
    let copied = eval(|a| {
        a.op(Instr::LoadNull { dst: 0 });
        a.op(Instr::Mov { dst: 1, src: 0 });
        1
    });
    assert!(copied.unwrap().is_nan(), "a copy of null is null");
    assert_eq!(
        eval(|a| {
            a.load(0, 2.25);
            a.op(Instr::Mov { dst: 3, src: 0 });
            3
        }),
        Ok(2.25)
    );
}

fn close(got: Result<f64, u32>, want: f64, what: &str) {
    let got = got.unwrap_or_else(|code| panic!("{what}: alarm {code}"));
    assert!((got - want).abs() <= 1e-12, "{what}: {got} != {want}");
}

#[test]
fn functions_follow_the_table_of_section_7_4() {
    use MathFunc::*;
    // Exact values of the table and of elementary trigonometry.
    #[rustfmt::skip]
    let cases = [
        (Sin, v(30.0), 0.5), (Cos, v(60.0), 0.5), (Tan, v(45.0), 1.0),
        (Asin, v(1.0), 90.0), (Acos, v(0.0), 90.0), (Acos, v(-1.0), 180.0),
        (Atan, v(1.0), 45.0), (Sqrt, v(16.0), 4.0), (Abs, v(-3.0), 3.0),
        (Round, v(-2.5), -3.0), (Round, v(2.5), 3.0), (Fix, v(-2.7), -2.0),
        (Fup, v(-2.2), -3.0), (Fup, v(2.2), 3.0), (Ln, v(1.0), 0.0),
        (Exp, v(0.0), 1.0),
        // BCD 0x25 (37) is 25; 25 is BCD 0x25; 1234 is 0x1234 = 4660.
        (Bin, v(37.0), 25.0), (Bcd, v(25.0), 37.0), (Bcd, v(1234.0), 4660.0),
        // §7.5: null counts as 0 in functions.
        (Sin, N, 0.0), (Cos, N, 1.0), (Abs, N, 0.0),
    ];
    for (f, x, want) in cases {
        close(func(f, x), want, &format!("{}[{x:?}]", f.name()));
    }
}

#[test]
fn function_domain_errors_are_the_alarms_of_section_8_4() {
    use MathFunc::*;
    #[rustfmt::skip]
    let cases = [
        (Tan, 90.0, 5005), (Tan, -90.0, 5005), (Tan, 270.0, 5005),
        (Sqrt, -1.0, 5002), (Asin, 1.5, 5003), (Acos, -1.01, 5003),
        (Ln, 0.0, 5004), (Ln, -1.0, 5004), (Exp, 1000.0, 5006),
        (Bin, -1.0, 5011), (Bcd, -1.0, 5011),
    ];
    for (f, x, code) in cases {
        assert_eq!(func(f, v(x)), Err(code), "{}[{x}]", f.name());
    }
}

#[test]
fn two_argument_arc_tangent() {
    let atan2 = |y, x| {
        eval(|a| {
            put(a, 0, y);
            put(a, 1, x);
            a.line(LINE);
            a.op(Instr::Atan2 { dst: 2, y: 0, x: 1 });
            2
        })
    };
    // §7.4: the direction of (b, a), 0…360; ATAN[-1]/[-1] = 225.
    close(atan2(v(-1.0), v(-1.0)), 225.0, "ATAN[-1]/[-1]");
    close(atan2(v(1.0), v(0.0)), 90.0, "ATAN[1]/[0]");
    close(atan2(v(0.0), v(-1.0)), 180.0, "ATAN[0]/[-1]");
    close(atan2(v(-1.0), v(0.0)), 270.0, "ATAN[-1]/[0]");
    assert_eq!(atan2(v(0.0), v(0.0)), Err(5005));
    assert_eq!(atan2(N, N), Err(5005), "null counts as 0");
}

#[test]
fn comparisons_with_tolerance_and_vacant() {
    use CmpOp::*;
    #[rustfmt::skip]
    let cases = [
        (Eq, v(1.0), v(1.0), 1.0), (Ne, v(1.0), v(2.0), 1.0),
        (Gt, v(2.0), v(1.0), 1.0), (Gt, v(1.0), v(1.0), 0.0),
        (Ge, v(1.0), v(1.0), 1.0), (Lt, v(1.0), v(2.0), 1.0),
        (Le, v(2.0), v(1.0), 0.0),
        // §7.6: equal within 1e-9 · max(1, |a|, |b|).
        (Eq, v(1.0), v(1.0 + 1e-10), 1.0), (Eq, v(1.0), v(1.0 + 1e-8), 0.0),
        (Eq, v(1e12), v(1e12 + 1.0), 1.0), (Gt, v(1e12 + 1.0), v(1e12), 0.0),
        (Le, v(1e12 + 1.0), v(1e12), 1.0),
        // §7.5: EQ/NE tell null from 0; the others count it as 0.
        (Eq, N, N, 1.0), (Eq, N, v(0.0), 0.0), (Ne, N, v(0.0), 1.0),
        (Ne, N, N, 0.0), (Ge, N, v(0.0), 1.0), (Gt, N, v(0.0), 0.0),
        (Lt, N, v(1.0), 1.0), (Le, v(0.0), N, 1.0),
    ];
    for (op, x, y, want) in cases {
        assert_eq!(cmp(op, x, y), want, "{x:?} {} {y:?}", op.name());
    }
}

#[test]
fn a_conditional_jump_is_taken_on_false_and_on_vacant() {
    // `jumpifnot` skips `#100 = 1` unless the condition holds; anything
    // but 0 and null is true (IF/WHILE tests).
    let taken = |cond: Option<f64>| {
        let mut a = Asm::new();
        a.load(1, 0.0);
        a.op(Instr::StoreVar { var: 100, src: 1 });
        put(&mut a, 0, cond);
        let jump = a.op(Instr::JumpIfNot { cond: 0, target: 0 });
        a.load(1, 1.0);
        a.op(Instr::StoreVar { var: 100, src: 1 });
        let end = a.op(Instr::Halt);
        a.set(
            jump,
            Instr::JumpIfNot {
                cond: 0,
                target: end,
            },
        );
        let (status, _, vm) = run(a.build());
        assert_eq!(status, Status::Done);
        vm.variable(100).unwrap() == 0.0
    };
    assert!(taken(v(0.0)));
    assert!(taken(N));
    assert!(!taken(v(1.0)));
    assert!(!taken(v(0.5)));
    assert!(!taken(v(-3.0)));
}

/// `#var = value`, then `#100 = #var`; the store on [`LINE`].
fn store_load(var: u32, value: f64) -> Result<f64, u32> {
    eval(|a| {
        a.load(0, value);
        a.line(LINE);
        a.op(Instr::StoreVar { var, src: 0 });
        a.line(LINE + 1);
        a.op(Instr::LoadVar { dst: 1, var });
        1
    })
}

#[test]
fn variable_ranges_of_section_7_1() {
    // Locals #1–#33, commons #100–#199, persistent #500–#999.
    for var in [1, 33, 100, 150, 199, 500, 999] {
        assert_eq!(store_load(var, 4.5), Ok(4.5), "#{var}");
    }
    // Between the ranges, numbers name no variable: E5008.
    for var in [34, 99, 200, 499] {
        assert_eq!(store_load(var, 4.5), Err(5008), "#{var}");
    }
    // #0 is read-only: E5007.
    assert_eq!(store_load(0, 1.0), Err(5007));
    // #0 reads as null; commons start null in a plain run.
    let read = |var| {
        eval(|a| {
            a.op(Instr::LoadVar { dst: 0, var });
            0
        })
    };
    assert!(read(0).unwrap().is_nan());
    assert!(read(100).unwrap().is_nan());
    assert!(read(999).unwrap().is_nan());
    assert!(read(1).unwrap().is_nan());
}

#[test]
fn reading_an_unknown_variable_names_its_line() {
    let got = eval(|a| {
        a.line(LINE);
        a.op(Instr::LoadVar { dst: 0, var: 300 });
        0
    });
    assert_eq!(got, Err(5008));
}

#[test]
fn persistent_variables_reach_the_host() {
    let mut a = Asm::new();
    a.load(0, 12.5);
    a.op(Instr::StoreVar { var: 500, src: 0 });
    a.op(Instr::StoreVar { var: 999, src: 0 });
    a.op(Instr::Halt);
    let (status, _, vm) = run(a.build());
    assert_eq!(status, Status::Done);
    let p = vm.persistent();
    assert_eq!((p[0], p[499]), (12.5, 12.5));
    assert!(p[1..499].iter().all(|x| x.is_nan()));
}

/// `#[idx] = 3` then `#100 = #[idx]`, the indirect forms.
fn indirect(idx: Option<f64>) -> Result<f64, u32> {
    eval(|a| {
        put(a, 0, idx);
        a.load(1, 3.0);
        a.line(LINE);
        a.op(Instr::StoreVarInd { idx: 0, src: 1 });
        a.op(Instr::LoadVarInd { dst: 2, idx: 0 });
        2
    })
}

#[test]
fn computed_variable_numbers() {
    // §7.1: the number is rounded half away from zero; null is E5009, a
    // negative number E5008.
    assert_eq!(indirect(v(100.0)), Ok(3.0));
    assert_eq!(indirect(v(100.5)), Ok(3.0));
    let rounded = eval(|a| {
        a.load(0, 100.5);
        a.load(1, 3.0);
        a.op(Instr::StoreVarInd { idx: 0, src: 1 });
        a.op(Instr::LoadVar { dst: 2, var: 101 });
        2
    });
    assert_eq!(rounded, Ok(3.0), "#[100.5] is #101");
    assert_eq!(indirect(N), Err(5009));
    assert_eq!(indirect(v(-1.0)), Err(5008));
    assert_eq!(indirect(v(250.0)), Err(5008));
    assert_eq!(indirect(v(0.0)), Err(5007));
    let read_null_index = eval(|a| {
        a.op(Instr::LoadNull { dst: 0 });
        a.line(LINE);
        a.op(Instr::LoadVarInd { dst: 1, idx: 0 });
        1
    });
    assert_eq!(read_null_index, Err(5009));
}

#[test]
fn a_vacant_word_is_left_out_of_its_block() {
    // §7.5: `G00 X#1 Z2` with #1 null is `G00 Z2`; from the start state
    // X0 Z0 (canon.md) the tool goes to X0 Z2.
    let mut a = Asm::new();
    a.op(Instr::LoadNull { dst: 0 });
    a.load(1, 2.0);
    a.show(0, 1);
    a.op(Instr::Halt);
    assert_eq!(common::canon_of(a.build()), ["RAPID X=0 Z=2"]);
}

#[test]
fn user_alarms_and_messages_of_section_7_3() {
    // `#3000 = n (TEXT)`: alarm 3000 + n (n rounded; null is 0) with the
    // block's comment; past 999: E5010.
    let user = |n: Option<f64>| {
        let mut a = Asm::new();
        a.word('G', 0.0);
        a.word('X', 1.0);
        a.exec();
        put(&mut a, 0, n);
        let text = a.s("TOOL WORN");
        a.line(LINE);
        a.op(Instr::SetMsg { s: text });
        a.op(Instr::StoreVar { var: 3000, src: 0 });
        a.op(Instr::Halt);
        let (status, canon, _) = run(a.build());
        (alarm_of(status), canon)
    };
    let (alarm, canon) = user(v(5.0));
    assert_eq!((alarm.code, alarm.line), (3005, LINE));
    assert_eq!(alarm.header(), "test.nc:7:1: alarm[3005]: TOOL WORN");
    // What came before the alarm is printed first.
    assert_eq!(
        canon,
        ["RAPID X=1 Z=0", "ALARM CODE=3005 MSG=\"TOOL WORN\""]
    );
    assert_eq!(user(v(2.5)).0.code, 3003);
    assert_eq!(user(N).0.code, 3000);
    assert_eq!(user(v(1000.0)).0.code, 5010);
    assert_eq!(user(v(-1.0)).0.code, 5010);

    // `#3006 = n (TEXT)`: a message, and the run goes on.
    let mut a = Asm::new();
    let text = a.s("CHECK");
    a.op(Instr::SetMsg { s: text });
    a.load(0, 1.0);
    a.op(Instr::StoreVar { var: 3006, src: 0 });
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    assert_eq!(
        common::canon_of(a.build()),
        ["MESSAGE TEXT=\"CHECK\"", "STOP KIND=M30"]
    );
}

/// A program's alarm keeps its text as written (UTF-8) for the host; its
/// canon MSG and its header print a `?` for each byte outside printable
/// ASCII (é is two), the implementation's wording as before.
#[test]
fn a_program_alarm_keeps_its_utf8_text() {
    let mut a = Asm::new();
    a.load(0, 5.0);
    let text = a.s("TOOL \"WORN\" \u{e9}");
    a.line(LINE);
    a.op(Instr::SetMsg { s: text });
    a.op(Instr::StoreVar { var: 3000, src: 0 });
    a.op(Instr::Halt);
    let (status, canon, _) = run(a.build());
    let alarm = alarm_of(status);
    assert_eq!(alarm.message, "TOOL \"WORN\" \u{e9}");
    assert_eq!(alarm.header(), "test.nc:7:1: alarm[3005]: TOOL ?WORN? ??");
    assert_eq!(canon, ["ALARM CODE=3005 MSG=\"TOOL ?WORN? ??\""]);
}

/// The (number, text) of each message stop, in order.
#[derive(Default)]
struct Messages(Vec<(u32, String)>);

impl vm::Sink for Messages {
    fn emit(&mut self, e: vm::Event) {
        if let vm::Event::Message { number, text } = e {
            self.0.push((number, text));
        }
    }
}

/// `#3006 = n`: the event carries n made whole, as `#3000` makes its
/// alarm number — rounded half away from zero, vacant 0 — and held in a
/// u32 (below 0: 0; beyond: u32::MAX); the canon line stays the text alone.
#[test]
fn a_message_carries_the_value_written_to_3006() {
    let values = [
        v(7.0),
        v(1.0),
        v(0.0),
        N,
        v(2.5),
        v(-2.5),
        v(-7.0),
        v(4294967294.6),
        v(1e12),
    ];
    let mut a = Asm::new();
    let text = a.s("SEE");
    for x in values {
        a.op(Instr::SetMsg { s: text });
        put(&mut a, 0, x);
        a.op(Instr::StoreVar { var: 3006, src: 0 });
    }
    a.op(Instr::Halt);
    let m = a.build();
    let mut vm = common::vm(m.clone());
    let mut got = Messages::default();
    assert_eq!(vm.run(&mut got), Status::Done);
    let numbers: Vec<u32> = got.0.iter().map(|(n, _)| *n).collect();
    // 2.5 → 3, -2.5 → -3 → 0, 4294967294.6 → 4294967295.
    assert_eq!(numbers, [7, 1, 0, 0, 3, 0, 0, u32::MAX, u32::MAX]);
    assert!(got.0.iter().all(|(_, t)| t == "SEE"));
    assert_eq!(common::canon_of(m), vec!["MESSAGE TEXT=\"SEE\""; 9]);
}

#[test]
fn a_compiled_alarm_names_its_line_and_message() {
    let mut a = Asm::new();
    a.word('G', 0.0);
    a.word('Z', -1.0);
    a.exec();
    let msg = a.s("division by zero");
    a.line(LINE);
    a.op(Instr::Alarm { code: 5001, msg });
    a.op(Instr::Halt);
    let (status, canon, _) = run(a.build());
    let alarm = alarm_of(status);
    assert_eq!(
        alarm.header(),
        "test.nc:7:1: alarm[E5001]: division by zero"
    );
    assert_eq!(
        canon,
        ["RAPID X=0 Z=-1", "ALARM CODE=5001 MSG=\"division by zero\""]
    );
}

#[test]
fn the_running_program_number() {
    // #4115: the number of the running program (O0001 here).
    assert_eq!(
        eval(|a| {
            a.op(Instr::LoadVar { dst: 0, var: 4115 });
            0
        }),
        Ok(1.0)
    );
}

/// `addk`, `subk`, `mulk`, `divk` and `cmpk` give what the register forms
/// give with the constant loaded first (the same `nc::value` rules: vacant
/// as 0, an overflow or a division by zero the same alarm), bit for bit,
/// over operands that reach each rule: vacant, ±0, huge, ordinary.
#[test]
fn constant_operands_compute_as_registers_do() {
    let values = [
        None,
        Some(0.0),
        Some(-0.0),
        Some(1.5),
        Some(-2.0),
        Some(1e308),
    ];
    let constants = [0.0, -0.0, 2.5, -1e308, 1e308];
    let bits = |r: Result<f64, u32>| r.map(f64::to_bits);
    for x in values {
        for k in constants {
            let with_k = |form: &dyn Fn(u8, u8, u32) -> Instr| {
                bits(eval(|a| {
                    put(a, 0, x);
                    let k = a.k(k);
                    a.line(LINE);
                    a.op(form(0, 0, k));
                    0
                }))
            };
            let with_reg = |form: &dyn Fn(u8, u8, u8) -> Instr| {
                bits(eval(|a| {
                    put(a, 0, x);
                    a.load(1, k);
                    a.line(LINE);
                    a.op(form(0, 0, 1));
                    0
                }))
            };
            let case = format!("{x:?} with {k}");
            assert_eq!(
                with_k(&|dst, a, k| Instr::AddK { dst, a, k }),
                with_reg(&|dst, a, b| Instr::Add { dst, a, b }),
                "add {case}"
            );
            assert_eq!(
                with_k(&|dst, a, k| Instr::SubK { dst, a, k }),
                with_reg(&|dst, a, b| Instr::Sub { dst, a, b }),
                "sub {case}"
            );
            assert_eq!(
                with_k(&|dst, a, k| Instr::MulK { dst, a, k }),
                with_reg(&|dst, a, b| Instr::Mul { dst, a, b }),
                "mul {case}"
            );
            assert_eq!(
                with_k(&|dst, a, k| Instr::DivK { dst, a, k }),
                with_reg(&|dst, a, b| Instr::Div { dst, a, b }),
                "div {case}"
            );
            for op in 0..6u8 {
                assert_eq!(
                    with_k(&|dst, a, k| Instr::CmpK { dst, a, k, op }),
                    with_reg(&|dst, a, b| Instr::Cmp { dst, a, b, op }),
                    "cmp {op} {case}"
                );
            }
        }
    }
}
