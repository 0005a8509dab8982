//! Calls and returns: M98/M99, M9000–M9999, G65/G66/G67 and the G65 H
//! operations of macro A (dialect.md §7.8–§7.11).

use crate::lower::Gen;
use crate::words::{Call, WordValue};
use grammar::ast::{Expr, Value, Word};
use grammar::Span;
use isa::Instr;
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

pub fn lower_call(g: &mut Gen<'_>, call: Call<'_>, span: Span) {
    match call {
        Call::Sub { p, l, span } => sub_call(g, p, l, span),
        Call::SubM { number, span } => {
            let Some(prog) = known(g, number, span, "M") else {
                return;
            };
            let count = load(g, 1.0);
            g.emit(Instr::CallSub { prog, count });
        }
        Call::Ret { p: None } => {
            g.emit(Instr::Ret);
        }
        Call::Ret { p: Some(p) } => {
            if let Some(seq) = g.value_reg(&p) {
                g.emit(Instr::RetSeq { seq });
            }
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
        } => macro_a(g, h, p, q, r, s.to(span)),
        Call::ModalCancel => {
            g.emit(Instr::ModalCancel);
        }
    }
}

fn load(g: &mut Gen<'_>, v: f64) -> u8 {
    let r = g.expr.alloc();
    let k = g.konst(v);
    g.emit(Instr::LoadK { dst: r, k });
    r
}

/// The program index of a literal call target, E2012 when it is nowhere.
fn known(g: &mut Gen<'_>, number: u32, span: Span, how: &str) -> Option<u32> {
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

fn sub_call(g: &mut Gen<'_>, p: Option<WordValue<'_>>, l: Option<WordValue<'_>>, span: Span) {
    let Some(p) = p else {
        g.error("E2006", span, "M98 needs P, the program to call");
        return;
    };
    match (p.literal(), l.map(|l| l.literal())) {
        (Some(pv), None) | (Some(pv), Some(Some(_))) => {
            let (number, count) = m98_target(pv, l.and_then(|l| l.literal()));
            let Some(prog) = known(g, number, span, "M98") else {
                return;
            };
            let count = load(g, count as f64);
            g.emit(Instr::CallSub { prog, count });
        }
        _ => {
            // Computed: split P at run time the way m98_target does.
            let Some(num) = g.value_reg(&p) else { return };
            let count = match l {
                Some(l) => match g.value_reg(&l) {
                    Some(r) => r,
                    None => return,
                },
                None => {
                    let count = g.expr.alloc();
                    let k = g.konst(10_000.0);
                    let ten_k = g.expr.alloc();
                    g.emit(Instr::LoadK { dst: ten_k, k });
                    g.emit(Instr::Div {
                        dst: count,
                        a: num,
                        b: ten_k,
                    });
                    g.emit(Instr::Func {
                        dst: count,
                        a: count,
                        f: nc::value::Func::Fix as u8,
                    });
                    let tmp = g.expr.alloc();
                    g.emit(Instr::Mul {
                        dst: tmp,
                        a: count,
                        b: ten_k,
                    });
                    g.emit(Instr::Sub {
                        dst: num,
                        a: num,
                        b: tmp,
                    });
                    count
                }
            };
            g.emit(Instr::CallSubDyn { num, count });
        }
    }
}

fn macro_call(
    g: &mut Gen<'_>,
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
        Some(l) => g.value_reg(&l),
        None => Some(load(g, 1.0)),
    };
    let Some(count) = count else { return };
    let increment = g.machine.machine.decimal_point == nc::machine::DecimalPoint::Increment;
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
        if let Some(src) = g.value_reg(&value) {
            g.emit(Instr::Arg { var: a.var, src });
        }
    }
    match p.literal() {
        Some(pv) => {
            let number = round_half_away(pv).max(0.0) as u32;
            let Some(prog) = known(g, number, span, name) else {
                return;
            };
            g.emit(if modal {
                Instr::ModalCall { prog, count }
            } else {
                Instr::CallMacro { prog, count }
            });
        }
        None => {
            let Some(num) = g.value_reg(&p) else { return };
            g.emit(if modal {
                Instr::ModalCallDyn { num, count }
            } else {
                Instr::CallMacroDyn { num, count }
            });
        }
    }
}

/// The destination `#i` of a G65 H block.
fn destination(g: &mut Gen<'_>, p: Option<&Word>, span: Span) -> Option<u32> {
    let var = p.and_then(|w| match &w.value {
        Value::Expr(e) => match &**e {
            Expr::Var(v) => crate::expr::fold(&v.index).and_then(|r| r.ok()),
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
/// dialect.md §8). **Decision:** Q is a constant here, as the alarm
/// numbers of a real program are; a variable Q is E2060 and a constant
/// outside 0…99 is E1010, both at compile time.
fn user_alarm(g: &mut Gen<'_>, q: Option<WordValue<'_>>, span: Span) {
    let n = match q {
        None => 0.0,
        Some(q) => match q.literal() {
            Some(v) => round_half_away(v),
            None => {
                g.error("E2060", span, "G65 H99: Q must be a constant 0…99");
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
    let msg = g.string("G65 H99 user alarm");
    g.emit(Instr::Alarm {
        code: 500 + n as u16,
        msg,
    });
}

fn operand(g: &mut Gen<'_>, v: Option<WordValue<'_>>) -> Option<u8> {
    match v {
        Some(v) => g.value_reg(&v),
        None => Some(load(g, 0.0)),
    }
}

fn macro_a(
    g: &mut Gen<'_>,
    h: WordValue<'_>,
    p: Option<&Word>,
    q: Option<WordValue<'_>>,
    r: Option<WordValue<'_>>,
    span: Span,
) {
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
        return user_alarm(g, q, span);
    }
    let Some(dst) = destination(g, p, span) else {
        return;
    };
    let (Some(j), Some(k)) = (operand(g, q), operand(g, r)) else {
        return;
    };
    let out = g.expr.alloc();
    use nc::value::Func as F;
    let ops: Vec<Instr> = match h {
        1 => vec![
            Instr::LoadK {
                dst: out,
                k: g.konst(0.0),
            },
            Instr::Add {
                dst: out,
                a: j,
                b: out,
            },
        ],
        2 => vec![Instr::Add {
            dst: out,
            a: j,
            b: k,
        }],
        3 => vec![Instr::Sub {
            dst: out,
            a: j,
            b: k,
        }],
        4 => vec![Instr::Mul {
            dst: out,
            a: j,
            b: k,
        }],
        5 => vec![Instr::Div {
            dst: out,
            a: j,
            b: k,
        }],
        11 => vec![Instr::BitOr {
            dst: out,
            a: j,
            b: k,
        }],
        12 => vec![Instr::BitAnd {
            dst: out,
            a: j,
            b: k,
        }],
        13 => vec![Instr::BitXor {
            dst: out,
            a: j,
            b: k,
        }],
        21 => vec![Instr::Func {
            dst: out,
            a: j,
            f: F::Sqrt as u8,
        }],
        22 => vec![Instr::Func {
            dst: out,
            a: j,
            f: F::Abs as u8,
        }],
        23 => vec![
            Instr::Div {
                dst: out,
                a: j,
                b: k,
            },
            Instr::Func {
                dst: out,
                a: out,
                f: F::Fix as u8,
            },
            Instr::Mul {
                dst: out,
                a: out,
                b: k,
            },
            Instr::Sub {
                dst: out,
                a: j,
                b: out,
            },
        ],
        26 => vec![
            Instr::LoadVar { dst: out, var: dst },
            Instr::Mul {
                dst: out,
                a: out,
                b: j,
            },
            Instr::Div {
                dst: out,
                a: out,
                b: k,
            },
        ],
        27 | 28 => {
            let t = g.expr.alloc();
            vec![
                Instr::Mul {
                    dst: out,
                    a: j,
                    b: j,
                },
                Instr::Mul { dst: t, a: k, b: k },
                if h == 27 {
                    Instr::Add {
                        dst: out,
                        a: out,
                        b: t,
                    }
                } else {
                    Instr::Sub {
                        dst: out,
                        a: out,
                        b: t,
                    }
                },
                Instr::Func {
                    dst: out,
                    a: out,
                    f: F::Sqrt as u8,
                },
            ]
        }
        31..=33 => {
            let f = [F::Sin, F::Cos, F::Tan][(h - 31) as usize];
            vec![
                Instr::Func {
                    dst: out,
                    a: k,
                    f: f as u8,
                },
                Instr::Mul {
                    dst: out,
                    a: j,
                    b: out,
                },
            ]
        }
        34 => vec![Instr::Atan2 {
            dst: out,
            y: j,
            x: k,
        }],
        _ => {
            g.error(
                "E2060",
                span,
                format!("G65 H{h:02} is not an operation of this dialect"),
            );
            return;
        }
    };
    for i in ops {
        g.emit(i);
    }
    g.emit(Instr::StoreVar { var: dst, src: out });
}

fn macro_a_jump(
    g: &mut Gen<'_>,
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
    let Some(seq) = g.value_reg(&crate::words::value_of(p)) else {
        return;
    };
    let skip = if h == 80 {
        None
    } else {
        let (Some(j), Some(k)) = (operand(g, q), operand(g, r)) else {
            return;
        };
        let op = [0u8, 1, 2, 3, 4, 5][(h - 81) as usize];
        let c = g.expr.alloc();
        g.emit(Instr::Cmp {
            dst: c,
            a: j,
            b: k,
            op,
        });
        Some(g.emit(Instr::JumpIfNot { cond: c, target: 0 }))
    };
    g.emit(Instr::GotoSeq { seq });
    if let Some(at) = skip {
        let here = g.pc();
        if let Instr::JumpIfNot { target, .. } = &mut g.module.code[at] {
            *target = here;
        }
    }
}
