//! Expressions into registers, with constant folding (dialect.md §7.4).
//! Folding uses the very functions the VM evaluates with (`nc::value`), so
//! a folded program computes exactly what the unfolded one would.

use crate::hash::IntMap;
use crate::lower::Gen;
use grammar::ast::{BinOp, Cond, Expr, Func, LogicOp, RelOp, UnOp};
use isa::Instr;
use nc::value::{self, Bin, Rel};
use nc::NcError;

/// Register allocation for the statement being compiled: a stack, reset at
/// every block (no value lives across blocks in a register).
#[derive(Default)]
pub struct ExprGen {
    next: u16,
    max: u16,
    overflow: bool,
    /// Variables whose value is known at this point of straight-line code
    /// (constant propagation, -O1); NaN is a known vacant value.
    known: IntMap<u32, f64>,
}

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
    fold_with(e, &IntMap::default())
}

/// The value of an expression whose variables are all in `known`.
pub fn fold_with(e: &Expr, known: &IntMap<u32, f64>) -> Option<Result<f64, NcError>> {
    let f = |e: &Expr| fold_with(e, known);
    Some(match e {
        Expr::Num(n) => Ok(n.value),
        Expr::Var(v) => match f(&v.index)? {
            Ok(n) if n.fract() == 0.0 && n >= 0.0 => return known.get(&(n as u32)).map(|v| Ok(*v)),
            _ => return None,
        },
        Expr::Paren { inner, .. } => return f(inner),
        Expr::Unary { op, operand, .. } => {
            let v = f(operand)?;
            v.map(|v| if *op == UnOp::Neg { value::neg(v) } else { v })
        }
        Expr::Binary { op, lhs, rhs, .. } => {
            let (a, b) = (f(lhs)?, f(rhs)?);
            a.and_then(|a| b.and_then(|b| value::binary(bin_of(*op), a, b)))
        }
        Expr::Call { func, arg, .. } => f(arg)?.and_then(|a| value::func(func_of(*func), a)),
        Expr::Atan2 { y, x, .. } => {
            let (a, b) = (f(y)?, f(x)?);
            a.and_then(|y| b.and_then(|x| value::atan2(y, x)))
        }
    })
}

/// Plain variables a program can hold constants in (system variables
/// change behind the compiler's back).
fn propagatable(n: u32) -> bool {
    matches!(n, 1..=33 | 100..=199 | 500..=999)
}

impl ExprGen {
    pub fn reset(&mut self) {
        self.next = 0;
    }

    /// A join point (a jump target, a loop head, a call): nothing is known.
    pub fn forget_all(&mut self) {
        self.known.clear();
    }

    pub fn forget(&mut self, var: u32) {
        // Mostly nothing is known: spare the hashing then.
        if !self.known.is_empty() {
            self.known.remove(&var);
        }
    }

    pub fn snapshot(&self) -> IntMap<u32, f64> {
        self.known.clone()
    }

    /// After a conditional statement: keep only what it left unchanged.
    pub fn restore_minus_changes(&mut self, before: IntMap<u32, f64>) {
        let now = std::mem::take(&mut self.known);
        self.known = before
            .into_iter()
            .filter(|(k, v)| now.get(k).is_some_and(|w| w.to_bits() == v.to_bits()))
            .collect();
    }

    /// After `#var = e`: remember its value when it is a constant.
    pub fn assigned(&mut self, var: u32, value: &Expr, optimize: bool) {
        match fold_with(value, &self.known) {
            Some(Ok(v)) if optimize && propagatable(var) => {
                self.known.insert(var, v);
            }
            _ => self.forget(var),
        }
    }

    /// The value of `e` from constants and known variables (-O1).
    pub fn known_value(&self, e: &Expr) -> Option<f64> {
        match fold_with(e, &self.known) {
            Some(Ok(v)) => Some(v),
            _ => None,
        }
    }

    pub fn touch(&mut self, n: u16) {
        self.max = self.max.max(n);
    }

    pub fn max_regs(&self) -> u16 {
        self.max
    }

    pub fn alloc(&mut self) -> u8 {
        if self.next >= 255 {
            self.overflow = true;
            return 254;
        }
        let r = self.next as u8;
        self.next += 1;
        self.max = self.max.max(self.next);
        r
    }

    fn free_to(&mut self, r: u8) {
        self.next = r as u16 + 1;
    }

    /// A constant expression's value (folding always applies here: jump
    /// targets and variable numbers are resolved at compile time if they
    /// can be).
    pub fn constant(&self, e: &Expr) -> Option<Result<f64, NcError>> {
        fold(e)
    }

    pub fn compile(&mut self, g: &mut Gen<'_>, e: &Expr) -> Option<u8> {
        let r = self.node(g, e);
        if self.overflow {
            g.error(
                "E1014",
                e.span(),
                "expression too deep for the register file",
            );
            self.overflow = false;
            return None;
        }
        Some(r)
    }

    fn load_const(&mut self, g: &mut Gen<'_>, v: f64) -> u8 {
        let r = self.alloc();
        let k = g.konst(v);
        g.emit(Instr::LoadK { dst: r, k });
        r
    }

    fn node(&mut self, g: &mut Gen<'_>, e: &Expr) -> u8 {
        if g.optimize || matches!(e, Expr::Num(_)) {
            let folded = if g.optimize {
                fold_with(e, &self.known)
            } else {
                fold(e)
            };
            if let Some(Ok(v)) = folded {
                return self.load_const(g, v);
            }
        }
        match e {
            Expr::Num(n) => self.load_const(g, n.value),
            Expr::Var(v) => match fold(&v.index) {
                Some(Ok(n)) if n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64 => {
                    let r = self.alloc();
                    g.emit(Instr::LoadVar {
                        dst: r,
                        var: n as u32,
                    });
                    r
                }
                _ => {
                    let idx = self.node(g, &v.index);
                    g.emit(Instr::LoadVarInd { dst: idx, idx });
                    idx
                }
            },
            Expr::Paren { inner, .. } => self.node(g, inner),
            Expr::Unary { op, operand, .. } => {
                let a = self.node(g, operand);
                if *op == UnOp::Neg {
                    g.emit(Instr::Neg { dst: a, a });
                }
                a
            }
            Expr::Binary { op, lhs, rhs, span } => {
                self.warn_if_faulty(g, e, *span);
                let a = self.node(g, lhs);
                let b = self.node(g, rhs);
                let (dst, a, b) = (a, a, b);
                g.emit(match op {
                    BinOp::Add => Instr::Add { dst, a, b },
                    BinOp::Sub => Instr::Sub { dst, a, b },
                    BinOp::Mul => Instr::Mul { dst, a, b },
                    BinOp::Div => Instr::Div { dst, a, b },
                    BinOp::Mod => Instr::Mod { dst, a, b },
                    BinOp::And => Instr::BitAnd { dst, a, b },
                    BinOp::Or => Instr::BitOr { dst, a, b },
                    BinOp::Xor => Instr::BitXor { dst, a, b },
                });
                self.free_to(dst);
                dst
            }
            Expr::Call { func, arg, span } => {
                self.warn_if_faulty(g, e, *span);
                let a = self.node(g, arg);
                g.emit(Instr::Func {
                    dst: a,
                    a,
                    f: func_of(*func) as u8,
                });
                a
            }
            Expr::Atan2 { y, x, span } => {
                self.warn_if_faulty(g, e, *span);
                let a = self.node(g, y);
                let b = self.node(g, x);
                g.emit(Instr::Atan2 { dst: a, y: a, x: b });
                self.free_to(a);
                a
            }
        }
    }

    /// W116: the operation itself faults on constant operands, so the alarm
    /// will fire whenever the block is reached.
    fn warn_if_faulty(&self, g: &mut Gen<'_>, e: &Expr, span: grammar::Span) {
        let operands_ok = match e {
            Expr::Binary { lhs, rhs, .. } => {
                matches!((fold(lhs), fold(rhs)), (Some(Ok(_)), Some(Ok(_))))
            }
            Expr::Call { arg, .. } => matches!(fold(arg), Some(Ok(_))),
            Expr::Atan2 { y, x, .. } => matches!((fold(y), fold(x)), (Some(Ok(_)), Some(Ok(_)))),
            _ => false,
        };
        if let (true, Some(Err(err))) = (operands_ok, fold(e)) {
            g.warn(
                "W116",
                span,
                format!(
                    "this always fails when reached: {} (alarm E{:04} at run time)",
                    err.message, err.code
                ),
            );
        }
    }

    pub fn cond(&mut self, g: &mut Gen<'_>, c: &Cond) -> Option<u8> {
        let r = self.cond_node(g, c);
        if self.overflow {
            g.error(
                "E1014",
                c.span(),
                "condition too deep for the register file",
            );
            self.overflow = false;
            return None;
        }
        Some(r)
    }

    fn cond_node(&mut self, g: &mut Gen<'_>, c: &Cond) -> u8 {
        match c {
            Cond::Rel { op, lhs, rhs, .. } => {
                let a = self.node(g, lhs);
                let b = self.node(g, rhs);
                g.emit(Instr::Cmp {
                    dst: a,
                    a,
                    b,
                    op: rel_of(*op) as u8,
                });
                self.free_to(a);
                a
            }
            Cond::Logic { op, lhs, rhs, .. } => {
                let a = self.cond_node(g, lhs);
                let b = self.cond_node(g, rhs);
                let (dst, a, b) = (a, a, b);
                g.emit(match op {
                    LogicOp::And => Instr::BitAnd { dst, a, b },
                    LogicOp::Or => Instr::BitOr { dst, a, b },
                    LogicOp::Xor => Instr::BitXor { dst, a, b },
                });
                self.free_to(dst);
                dst
            }
        }
    }
}
