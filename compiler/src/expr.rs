//! Expressions into the IR, with constant folding (dialect.md §7.4).
//! Folding uses the very functions the VM evaluates with (`nc::value`), so
//! a folded program computes exactly what the unfolded one would.

use crate::build::Builder;
use crate::ir::{self, Handle};
use grammar::ast::{BinOp, Cond, Expr, Func, LogicOp, RelOp, UnOp};
use nc::value::{self, Bin, Rel};
use nc::NcError;

pub fn bin_of(op: BinOp) -> Bin {
    match op {
        BinOp::Add => Bin::Add,
        BinOp::Sub => Bin::Sub,
        BinOp::Mul => Bin::Mul,
        BinOp::Div => Bin::Div,
        BinOp::Mod => Bin::Mod,
        BinOp::And => Bin::And,
        BinOp::Or => Bin::Or,
        BinOp::Xor => Bin::Xor,
    }
}

pub fn func_of(f: Func) -> value::Func {
    use value::Func as V;
    match f {
        Func::Sin => V::Sin,
        Func::Cos => V::Cos,
        Func::Tan => V::Tan,
        Func::Asin => V::Asin,
        Func::Acos => V::Acos,
        Func::Atan => V::Atan,
        Func::Sqrt => V::Sqrt,
        Func::Abs => V::Abs,
        Func::Round => V::Round,
        Func::Fix => V::Fix,
        Func::Fup => V::Fup,
        Func::Ln => V::Ln,
        Func::Exp => V::Exp,
        Func::Bin => V::Bin,
        Func::Bcd => V::Bcd,
    }
}

pub fn rel_of(op: RelOp) -> Rel {
    match op {
        RelOp::Eq => Rel::Eq,
        RelOp::Ne => Rel::Ne,
        RelOp::Gt => Rel::Gt,
        RelOp::Lt => Rel::Lt,
        RelOp::Ge => Rel::Ge,
        RelOp::Le => Rel::Le,
    }
}

/// The value of an expression that reads no variable; `None` when it does.
pub fn fold(e: &Expr) -> Option<Result<f64, NcError>> {
    Some(match e {
        Expr::Num(n) => Ok(n.value),
        Expr::Var(_) => return None,
        Expr::Paren { inner, .. } => return fold(inner),
        Expr::Unary { op, operand, .. } => {
            let v = fold(operand)?;
            v.map(|v| if *op == UnOp::Neg { value::neg(v) } else { v })
        }
        Expr::Binary { op, lhs, rhs, .. } => {
            let (a, b) = (fold(lhs)?, fold(rhs)?);
            a.and_then(|a| b.and_then(|b| value::binary(bin_of(*op), a, b)))
        }
        Expr::Call { func, arg, .. } => fold(arg)?.and_then(|a| value::func(func_of(*func), a)),
        Expr::Atan2 { y, x, .. } => {
            let (a, b) = (fold(y)?, fold(x)?);
            a.and_then(|y| b.and_then(|x| value::atan2(y, x)))
        }
    })
}

/// An expression into the IR. With -O1 every subexpression that reads no
/// variable is a constant (pass `fold` adds what the variables bring),
/// with -O0 only the literal numbers. W116 for an operation that always
/// faults.
pub fn build(b: &mut Builder<'_>, e: &Expr) -> Handle<ir::Expr> {
    if b.optimize || matches!(e, Expr::Num(_)) {
        if let Some(Ok(v)) = fold(e) {
            return b.add_expr(ir::Expr::Const(v));
        }
    }
    let node = match e {
        Expr::Num(n) => ir::Expr::Const(n.value),
        Expr::Var(v) => {
            let index = v.index.expr();
            match fold(&index) {
                Some(Ok(n)) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => {
                    ir::Expr::Var(n as u32)
                }
                _ => ir::Expr::VarInd(build(b, &index)),
            }
        }
        Expr::Paren { inner, .. } => return build(b, inner),
        Expr::Unary { op, operand, .. } => {
            let a = build(b, operand);
            if *op != UnOp::Neg {
                return a;
            }
            ir::Expr::Neg(a)
        }
        Expr::Binary { op, lhs, rhs, span } => {
            warn_if_faulty(b, e, *span);
            let l = build(b, lhs);
            let r = build(b, rhs);
            ir::Expr::Binary {
                op: bin_of(*op),
                a: l,
                b: r,
            }
        }
        Expr::Call { func, arg, span } => {
            warn_if_faulty(b, e, *span);
            let a = build(b, arg);
            ir::Expr::Func {
                f: func_of(*func),
                a,
            }
        }
        Expr::Atan2 { y, x, span } => {
            warn_if_faulty(b, e, *span);
            let y = build(b, y);
            let x = build(b, x);
            ir::Expr::Atan2 { y, x }
        }
    };
    b.add_expr(node)
}

/// W116: the operation itself faults on constant operands, so the alarm
/// will fire whenever the block is reached.
fn warn_if_faulty(b: &mut Builder<'_>, e: &Expr, span: grammar::Span) {
    let operands_ok = match e {
        Expr::Binary { lhs, rhs, .. } => {
            matches!((fold(lhs), fold(rhs)), (Some(Ok(_)), Some(Ok(_))))
        }
        Expr::Call { arg, .. } => matches!(fold(arg), Some(Ok(_))),
        Expr::Atan2 { y, x, .. } => matches!((fold(y), fold(x)), (Some(Ok(_)), Some(Ok(_)))),
        _ => false,
    };
    if let (true, Some(Err(err))) = (operands_ok, fold(e)) {
        b.warn("W116", span, always_fails(&err));
    }
}

/// The message of W116 for the alarm `err`.
pub fn always_fails(err: &NcError) -> String {
    format!(
        "this always fails when reached: {} (alarm E{:04} at run time)",
        err.message, err.code
    )
}

/// A condition into the IR: comparisons, joined bitwise.
pub fn build_cond(b: &mut Builder<'_>, c: &Cond) -> Handle<ir::Expr> {
    let node = match c {
        Cond::Rel { op, lhs, rhs, .. } => {
            let l = build(b, lhs);
            let r = build(b, rhs);
            ir::Expr::Compare {
                op: rel_of(*op),
                a: l,
                b: r,
            }
        }
        Cond::Logic { op, lhs, rhs, .. } => {
            let l = build_cond(b, lhs);
            let r = build_cond(b, rhs);
            let op = match op {
                LogicOp::And => Bin::And,
                LogicOp::Or => Bin::Or,
                LogicOp::Xor => Bin::Xor,
            };
            ir::Expr::Binary { op, a: l, b: r }
        }
    };
    b.add_expr(node)
}
