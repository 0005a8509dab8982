//! Calls and returns: M98/M99, M9000–M9999, G65/G66/G67 and the G65 H
//! operations of macro A (dialect.md §7.8–§7.11), built into the IR's call
//! and return terminators and macro-A operations.

use crate::build::Builder;
use crate::ir::{self, CallKind, Callee, Count, Op, Terminator};
use crate::words::{Call, WordValue};
use grammar::ast::{Expr, Value, Word};
use grammar::Span;
use nc::block::round_half_away;

/// The program number and repeat count a literal `M98 P [L]` names.
pub fn m98_target(p: f64, l: Option<f64>) -> (u32, u32) {
    let p = round_half_away(p).max(0.0) as u64;
    match l {
        Some(l) => (
            p.min(u32::MAX as u64) as u32,
            round_half_away(l).max(1.0) as u32,
        ),
        // P<cccc><pppp>: four digits of count, four of program.
        None => ((p % 10_000) as u32, ((p / 10_000) as u32).max(1)),
    }
}

/// Builds a block's call; `comment` is the block's first comment (the
/// message of an alarm a G65 H block raises).
pub fn build_call(g: &mut Builder<'_>, call: Call<'_>, span: Span, comment: Option<&str>) {
    match call {
        Call::Sub { p, l, span } => sub_call(g, p, l, span),
        Call::SubM { number, span } => {
            let Some(prog) = known(g, number, span, &format!("M{number}")) else {
                return;
            };
            let count = konst(g, 1.0);
            g.call(ir::Call {
                kind: CallKind::Sub,
                callee: Callee::Program(prog),
                count: Count::Expr(count),
                args: Vec::new(),
            });
        }
        Call::Ret { p: None } => g.terminate(Terminator::Return { seq: None }),
        Call::Ret { p: Some(p) } => {
            let seq = g.value(&p);
            g.terminate(Terminator::Return { seq: Some(seq) });
        }
        Call::Macro {
            modal,
            p,
            l,
            args,
            span,
        } => macro_call(g, modal, p, l, &args, span),
        Call::MacroA {
            h,
            p,
            q,
            r,
            span: s,
        } => macro_a(g, (h, p, q, r), s.to(span), comment),
        Call::ModalCancel => {
            g.push(Op::ModalCancel);
        }
    }
}

fn konst(g: &mut Builder<'_>, v: f64) -> ir::Handle<ir::Expr> {
    g.add_expr(ir::Expr::Const(v))
}

/// The program index of a literal call target, E2012 when it is nowhere.
fn known(g: &mut Builder<'_>, number: u32, span: Span, how: &str) -> Option<u32> {
    let found = g.program_index(number);
    if found.is_none() {
        g.error(
            "E2012",
            span,
            format!("{how} calls O{number:04}, which is neither in this file nor in a library folder (-I)"),
        );
    }
    found
}

fn sub_call(g: &mut Builder<'_>, p: Option<WordValue<'_>>, l: Option<WordValue<'_>>, span: Span) {
    let Some(p) = p else {
        g.error("E2006", span, "M98 needs P, the program to call");
        return;
    };
    let call = match (p.literal(), l) {
        // A written program and a computed count: with L, P is the program
        // itself (no count packed in it), known now.
        (Some(pv), Some(count)) if count.literal().is_none() => {
            let (number, _) = m98_target(pv, Some(1.0));
            let Some(prog) = known(g, number, span, "M98") else {
                return;
            };
            ir::Call {
                kind: CallKind::Sub,
                callee: Callee::Program(prog),
                count: Count::Expr(g.value(&count)),
                args: Vec::new(),
            }
        }
        (Some(pv), _) => {
            let (number, count) = m98_target(pv, l.and_then(|l| l.literal()));
            let Some(prog) = known(g, number, span, "M98") else {
                return;
            };
            ir::Call {
                kind: CallKind::Sub,
                callee: Callee::Program(prog),
                count: Count::Expr(konst(g, count as f64)),
                args: Vec::new(),
            }
        }
        _ => {
            // Computed: P is split at run time the way m98_target does.
            let num = g.value(&p);
            let count = match l {
                Some(l) => Count::Expr(g.value(&l)),
                None => Count::Packed,
            };
            ir::Call {
                kind: CallKind::Sub,
                callee: Callee::Dynamic(num),
                count,
                args: Vec::new(),
            }
        }
    };
    g.call(call);
}

fn macro_call(
    g: &mut Builder<'_>,
    modal: bool,
    p: Option<WordValue<'_>>,
    l: Option<WordValue<'_>>,
    args: &[crate::words::Arg<'_>],
    span: Span,
) {
    let name = if modal { "G66" } else { "G65" };
    let Some(p) = p else {
        g.error(
            "E2002",
            span,
            format!("{name} must be followed by P (the program) or H"),
        );
        return;
    };
    let count = match l {
        Some(l) => g.value(&l),
        None => konst(g, 1.0),
    };
    let increment = g.machine.machine.decimal_point == nc::machine::DecimalPoint::Increment;
    let mut values = Vec::with_capacity(args.len());
    for a in args {
        let value = match a.value {
            // In increment mode a length without a point is in 0.001 mm.
            WordValue::Literal(v, flags)
                if increment && a.length && flags & nc::words::NO_POINT != 0 =>
            {
                WordValue::Literal(v * 0.001, flags)
            }
            v => v,
        };
        values.push((a.var, g.value(&value)));
    }
    let callee = match p.literal() {
        Some(pv) => {
            let number = round_half_away(pv).max(0.0) as u32;
            let Some(prog) = known(g, number, span, name) else {
                return;
            };
            Callee::Program(prog)
        }
        None => Callee::Dynamic(g.value(&p)),
    };
    g.call(ir::Call {
        kind: if modal {
            CallKind::Modal
        } else {
            CallKind::Macro
        },
        callee,
        count: Count::Expr(count),
        args: values,
    });
}

/// The destination `#i` of a G65 H block.
fn destination(g: &mut Builder<'_>, p: Option<&Word>, span: Span) -> Option<u32> {
    let var = p.and_then(|w| match &w.value {
        Value::Expr(e) => match &**e {
            Expr::Var(v) => crate::expr::fold(&v.index.expr()).and_then(|r| r.ok()),
            _ => None,
        },
        _ => None,
    });
    match var {
        Some(n) if n >= 1.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => Some(n as u32),
        _ => {
            g.error(
                "E2060",
                p.map_or(span, |w| w.span),
                "G65 H: P must name the destination variable as #i",
            );
            None
        }
    }
}

/// `G65 H99 Q n`: alarm 500 + n, n = 0…99 (the 500–599 band of
/// dialect.md §8). Q is a variable or a constant (§7.8): a constant
/// outside 0…99 is E1010 at compile time, a computed one E5010 when the
/// block runs.
fn user_alarm(g: &mut Builder<'_>, q: Option<WordValue<'_>>, span: Span, comment: Option<&str>) {
    let n = match q {
        None => 0.0,
        Some(q) => match q.literal() {
            Some(v) => round_half_away(v),
            None => {
                let q = operand(g, Some(q));
                let msg = g.string(user_alarm_message(comment));
                g.push(Op::UserAlarm { q, msg });
                return;
            }
        },
    };
    if !(0.0..=99.0).contains(&n) {
        g.error(
            "E1010",
            span,
            format!("G65 H99: Q{n} is outside 0…99 (alarms 500…599)"),
        );
        return;
    }
    let msg = g.string(user_alarm_message(comment));
    g.push(Op::Alarm {
        code: 500 + n as u16,
        msg,
    });
}

/// The message of a `G65 H99` alarm: the block's comment, as a `#3000`
/// alarm's (canon.md leaves it to the implementation); else ours.
pub fn user_alarm_message(comment: Option<&str>) -> &str {
    comment.unwrap_or("G65 H99 user alarm")
}

/// The alarm a `G65 H99 Q n` block raises, 500 + n, when its words are
/// literal and valid (else the block is a compile error).
pub fn user_alarm_code(call: &Call<'_>) -> Option<u32> {
    let Call::MacroA { h, q, .. } = call else {
        return None;
    };
    if h.literal().map(round_half_away) != Some(99.0) {
        return None;
    }
    let n = match q {
        None => 0.0,
        Some(q) => round_half_away(q.literal()?),
    };
    (0.0..=99.0).contains(&n).then_some(500 + n as u32)
}

/// Q or R of a G65 H block: 0 when absent.
fn operand(g: &mut Builder<'_>, v: Option<WordValue<'_>>) -> ir::Handle<ir::Expr> {
    match v {
        Some(v) => g.value(&v),
        None => konst(g, 0.0),
    }
}

/// `e + 0`: the value of `e`, 0 where it is vacant.
fn plus_zero(g: &mut Builder<'_>, e: ir::Handle<ir::Expr>) -> ir::Handle<ir::Expr> {
    let zero = konst(g, 0.0);
    g.add_expr(ir::Expr::Binary {
        op: nc::value::Bin::Add,
        a: e,
        b: zero,
    })
}

/// The words H, P, Q and R of a G65 H block.
type MacroAWords<'a> = (
    WordValue<'a>,
    Option<&'a Word>,
    Option<WordValue<'a>>,
    Option<WordValue<'a>>,
);

fn macro_a(g: &mut Builder<'_>, words: MacroAWords<'_>, span: Span, comment: Option<&str>) {
    let (h, p, q, r) = words;
    let Some(h) = h.literal().map(round_half_away) else {
        g.error(
            "E2060",
            span,
            "G65 H: the operation number must be written as a literal",
        );
        return;
    };
    let h = h as u32;
    if (80..=86).contains(&h) {
        return macro_a_jump(g, h, p, q, r, span);
    }
    if h == 99 {
        return user_alarm(g, q, span, comment);
    }
    let Some(dst) = destination(g, p, span) else {
        return;
    };
    let (j, k) = (operand(g, q), operand(g, r));
    let Some(op) = ir::MacroAOp::of(h) else {
        g.error(
            "E2060",
            span,
            format!("G65 H{h:02} is not an operation of this dialect"),
        );
        return;
    };
    let value = op.value(dst, j, k, &mut |e| g.add_expr(e));
    // (As `#3000 = n (TEXT)`: the block's comment is the message.)
    let msg = matches!(dst, 3000 | 3006).then(|| g.string(comment.unwrap_or("")));
    g.push(Op::MacroA {
        op,
        dst,
        j,
        k,
        value,
        msg,
    });
}

/// G65 H80 (GOTO P) and H81–H86 (GOTO P when Q op R).
fn macro_a_jump(
    g: &mut Builder<'_>,
    h: u32,
    p: Option<&Word>,
    q: Option<WordValue<'_>>,
    r: Option<WordValue<'_>>,
    span: Span,
) {
    let Some(p) = p else {
        g.error(
            "E2006",
            span,
            format!("G65 H{h}: P, the sequence number to jump to, is missing"),
        );
        return;
    };
    let value = crate::words::value_of(p);
    if let Some(n) = value.literal() {
        // A written target: into a loop from outside is E2015 (§7.7),
        // checked when the program's numbers are all known.
        let n = round_half_away(n).clamp(0.0, u32::MAX as f64) as u32;
        g.literal_jumps.push(crate::build::LiteralJump {
            h,
            seq: n,
            span: p.span,
            inside: g.in_loop,
        });
    }
    let seq = g.value(&value);
    // H81…H86: EQ, NE, GT, LT, GE, LE, the order of the ISA's codes.
    match nc::value::Rel::from_code((h - 80).saturating_sub(1) as u8).filter(|_| h != 80) {
        None => {
            let inside = g.in_loop;
            g.terminate(Terminator::Goto { seq, inside })
        }
        Some(op) => {
            // A vacant operand counts as 0 (dialect.md §7.5), where EQ and
            // NE would tell it from 0: `j + 0`, as H01 stores.
            let (j, k) = (operand(g, q), operand(g, r));
            let (j, k) = (plus_zero(g, j), plus_zero(g, k));
            g.goto_if(seq, op, j, k);
        }
    }
}
