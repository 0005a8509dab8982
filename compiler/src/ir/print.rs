//! `gbcc --emit=ir`: the IR as text, one function per program, its blocks
//! in layout order, each operation and terminator with the place in the
//! source it comes from (`file:line:col`).
//!
//! ```text
//! function O0001
//! bb0:
//!     #1 = 2                                   ; t.nc:1:1
//!     nc G01 X10. Z[#1 + 1]                    ; t.nc:2:1
//!     halt                                     ; t.nc:2:1
//! ```

use super::{
    Block, Call, CallKind, Callee, Count, Expr, Function, Handle, Loc, Module, NcKind, Op, StrId,
    Terminator, VarTarget, WordValue,
};
use grammar::SourceFile;
use nc::value::{Bin, Rel};
use nc::words::{COMMA_A, COMMA_C, COMMA_R, LITERAL, NO_POINT};
use std::fmt::Write;

/// The column at which locations start.
const LOC_COLUMN: usize = 44;

/// The module as text; `files` name the units of the locations.
pub fn print(m: &Module, files: &[SourceFile]) -> String {
    print_with(m, files, &|_, _| None)
}

/// What an analysis says of an operation (of the function with this
/// index), printed on a comment line under it.
pub type Notes<'a> = dyn Fn(usize, Handle<Op>) -> Option<String> + 'a;

/// The module as text, each operation followed by its note, if any.
pub fn print_with(m: &Module, files: &[SourceFile], notes: &Notes) -> String {
    let mut out = String::new();
    for (index, f) in m.functions.iter().enumerate() {
        // Blocks are named by their place in the layout.
        let mut place = vec![usize::MAX; f.blocks.len()];
        for (i, b) in f.layout.iter().enumerate() {
            if let Some(p) = place.get_mut(b.index()) {
                *p = i;
            }
        }
        let p = Printer {
            m,
            f,
            files,
            place,
            index,
            notes,
        };
        p.function(&mut out);
    }
    out
}

struct Printer<'a> {
    m: &'a Module,
    f: &'a Function,
    files: &'a [SourceFile],
    /// Each block's place in the layout, by handle.
    place: Vec<usize>,
    /// The function's index in the module, for `notes`.
    index: usize,
    notes: &'a Notes<'a>,
}

impl Printer<'_> {
    fn function(&self, out: &mut String) {
        let _ = writeln!(out, "function O{:04}", self.f.number);
        for &b in &self.f.layout {
            let Some(block) = self.f.blocks.get(b) else {
                continue;
            };
            let _ = writeln!(out, "{}:", self.name(b));
            for &op in &block.ops {
                let text = self.f.ops.get(op).map_or(String::new(), |o| self.op(o));
                let loc = self.f.op_locs.get(op.index()).copied();
                self.line(out, &text, loc);
                if let Some(note) = (self.notes)(self.index, op) {
                    let _ = writeln!(out, "        ; {note}");
                }
            }
            let text = block
                .term
                .as_ref()
                .map_or("(no terminator)".into(), |t| self.term(t));
            let loc = self.f.term_locs.get(b.index()).copied();
            self.line(out, &text, loc);
        }
    }

    fn line(&self, out: &mut String, text: &str, loc: Option<Loc>) {
        let loc = loc.and_then(|l| {
            let file = self.files.get(l.file as usize)?;
            let (line, col) = file.line_col(l.span.start);
            Some(format!("{}:{line}:{col}", file.name))
        });
        match loc {
            Some(loc) => {
                let _ = writeln!(out, "    {text:<w$} ; {loc}", w = LOC_COLUMN - 4);
            }
            None => {
                let _ = writeln!(out, "    {text}");
            }
        }
    }

    fn op(&self, op: &Op) -> String {
        match op {
            Op::Seq(n, _) => format!("seq N{n}"),
            Op::Nc(nc) => {
                let mut s = String::from(match nc.kind {
                    NcKind::Run => "nc",
                    NcKind::Move(_) => "move",
                    NcKind::Profile => "profile",
                });
                for w in self.f.words_of(nc) {
                    s.push(' ');
                    s.push_str(&address(w.addr));
                    match w.value() {
                        WordValue::Const(v, flags) => s.push_str(&literal(v, flags)),
                        WordValue::Expr(e) => s.push_str(&self.bracketed(e)),
                    }
                }
                self.with_msg(s, nc.msg)
            }
            Op::Assign { target, value, msg } => {
                let s = match target {
                    VarTarget::Direct(v) => format!("#{v} = {}", self.expr(*value)),
                    VarTarget::Indirect(i) => {
                        format!("#[{}] = {}", self.expr(*i), self.expr(*value))
                    }
                };
                self.with_msg(s, *msg)
            }
            Op::MacroA {
                op,
                dst,
                value,
                msg,
                ..
            } => {
                let s = format!("g65 H{:02} #{dst} = {}", op.h(), self.expr(*value));
                self.with_msg(s, *msg)
            }
            Op::Alarm { code, msg } => format!("alarm {code} {:?}", self.string(msg.0)),
            Op::UserAlarm { q, msg } => {
                format!("alarm 500+[{}] {:?}", self.expr(*q), self.string(msg.0))
            }
            Op::ModalCancel => "g67".into(),
            Op::Charge => "charge".into(),
        }
    }

    fn term(&self, t: &Terminator) -> String {
        match t {
            Terminator::Follow(b) => format!("follow {}", self.name(*b)),
            Terminator::Jump(b) => format!("jump {}", self.name(*b)),
            Terminator::GotoKnown(b) => format!("goto {}", self.name(*b)),
            Terminator::Branch {
                cond,
                then,
                otherwise,
            } => format!(
                "branch {} then {} else {}",
                self.expr(*cond),
                self.name(*then),
                self.name(*otherwise)
            ),
            Terminator::Skip { switch, skip, next } => {
                format!(
                    "skip /{switch} to {} else {}",
                    self.name(*skip),
                    self.name(*next)
                )
            }
            Terminator::Goto { seq, .. } => format!("goto N{}", self.bracketed(*seq)),
            Terminator::GotoIf {
                seq,
                op,
                j,
                k,
                next,
                ..
            } => format!(
                "goto N{} if {} {} {} else {}",
                self.bracketed(*seq),
                self.expr(*j),
                rel_name(*op),
                self.expr(*k),
                self.name(*next)
            ),
            Terminator::Call { call, next } => {
                format!("{} then {}", self.call(call), self.name(*next))
            }
            Terminator::Return { seq: None } => "return".into(),
            Terminator::Return { seq: Some(s) } => format!("return to N{}", self.bracketed(*s)),
            Terminator::Halt => "halt".into(),
            Terminator::Ended => "ended".into(),
        }
    }

    fn call(&self, call: &Call) -> String {
        let kind = match call.kind {
            CallKind::Sub => "call m98",
            CallKind::Macro => "call g65",
            CallKind::Modal => "call g66",
        };
        let callee = match call.callee {
            Callee::Program(p) => match self.m.functions.get(p as usize) {
                Some(f) => format!("O{:04}", f.number),
                None => format!("function {p}"),
            },
            Callee::Dynamic(e) => format!("O{}", self.bracketed(e)),
        };
        let count = match call.count {
            Count::Expr(e) => self.expr(e),
            Count::Packed => "(from P)".into(),
        };
        let mut s = format!("{kind} {callee} count {count}");
        for &(var, v) in &call.args {
            let _ = write!(s, " #{var}={}", self.expr(v));
        }
        s
    }

    fn name(&self, b: Handle<Block>) -> String {
        match self.place.get(b.index()) {
            Some(&p) if p != usize::MAX => format!("bb{p}"),
            _ => format!("(unplaced {b:?})"),
        }
    }

    /// `s` and the block's message (a #3000/#3006 comment), if it has one.
    fn with_msg(&self, mut s: String, msg: Option<StrId>) -> String {
        if let Some(m) = msg {
            let _ = write!(s, " msg {:?}", self.string(m.0));
        }
        s
    }

    fn string(&self, i: u32) -> &str {
        self.m.strings.get(i as usize).map_or("", |s| s.as_str())
    }

    /// An expression; one with an operator in brackets.
    fn bracketed(&self, e: Handle<Expr>) -> String {
        match self.f.exprs.get(e) {
            Some(Expr::Const(v)) => number(*v),
            Some(Expr::Var(_) | Expr::VarInd(_) | Expr::Func { .. } | Expr::Atan2 { .. }) => {
                self.expr(e)
            }
            _ => format!("[{}]", self.expr(e)),
        }
    }

    fn expr(&self, e: Handle<Expr>) -> String {
        let Some(x) = self.f.exprs.get(e) else {
            return format!("(bad {e:?})");
        };
        match *x {
            Expr::Const(v) => number(v),
            Expr::Var(n) => format!("#{n}"),
            Expr::VarInd(i) => format!("#[{}]", self.expr(i)),
            Expr::Neg(a) => format!("-{}", self.bracketed(a)),
            Expr::Binary { op, a, b } => format!(
                "{} {} {}",
                self.bracketed(a),
                bin_name(op),
                self.bracketed(b)
            ),
            Expr::Func { f, a } => {
                format!("{}[{}]", format!("{f:?}").to_uppercase(), self.expr(a))
            }
            Expr::Atan2 { y, x } => format!("ATAN[{}]/[{}]", self.expr(y), self.expr(x)),
            Expr::Compare { op, a, b } => format!(
                "{} {} {}",
                self.bracketed(a),
                rel_name(op),
                self.bracketed(b)
            ),
        }
    }
}

fn address(addr: u8) -> String {
    match addr {
        COMMA_A => ",A".into(),
        COMMA_C => ",C".into(),
        COMMA_R => ",R".into(),
        a => char::from(b'A' + a.min(25)).to_string(),
    }
}

/// A number as Rust prints it (the shortest that reads back the same).
fn number(v: f64) -> String {
    format!("{v}")
}

/// A word's constant, with the decimal point it was written with (`X10.`)
/// when it was written as a literal.
fn literal(v: f64, flags: u8) -> String {
    let s = number(v);
    let pointed = flags & LITERAL != 0 && flags & NO_POINT == 0;
    match pointed && !s.contains('.') && v.is_finite() {
        true => s + ".",
        false => s,
    }
}

fn bin_name(op: Bin) -> &'static str {
    match op {
        Bin::Add => "+",
        Bin::Sub => "-",
        Bin::Mul => "*",
        Bin::Div => "/",
        Bin::Mod => "MOD",
        Bin::And => "AND",
        Bin::Or => "OR",
        Bin::Xor => "XOR",
    }
}

fn rel_name(op: Rel) -> &'static str {
    match op {
        Rel::Eq => "EQ",
        Rel::Ne => "NE",
        Rel::Gt => "GT",
        Rel::Lt => "LT",
        Rel::Ge => "GE",
        Rel::Le => "LE",
    }
}
