//! The syntax tree of a GSK980TDi program file.
//!
//! Every node carries a [`Span`] of byte offsets into the original source
//! bytes. The tree is purely syntactic: the meaning of words (modal groups,
//! the decimal-point rule, cycles) is the compiler's business.

use crate::span::Span;

/// A whole file: its lines in order (programs are delimited by
/// [`Line::ProgramStart`]; the compiler splits them).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ast {
    pub lines: Vec<Line>,
}

/// One item of the file in source order.
#[derive(Debug, Clone, PartialEq)]
pub enum Line {
    /// A `%` tape mark line.
    Percent(Span),
    /// `O1234` or `:1234`, the start of a program.
    ProgramStart(ProgramStart),
    /// An ordinary block (NC words or one macro statement).
    Block(Block),
}

impl Line {
    pub fn span(&self) -> Span {
        match self {
            Line::Percent(s) => *s,
            Line::ProgramStart(p) => p.span,
            Line::Block(b) => b.span,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct ProgramStart {
    pub number: u32,
    /// The comments written on the O line (a program title, usually).
    pub comments: Vec<Comment>,
    pub span: Span,
}

/// A block: an optional block-delete mark, an optional sequence number and
/// either NC words or a macro statement. Comments are collected separately
/// because `#3000`/`#3006` use them as their message.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// `/` (switch 1) or `/n`.
    pub delete: Option<BlockDelete>,
    pub seq: Option<Seq>,
    pub body: Body,
    pub comments: Vec<Comment>,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockDelete {
    /// The switch number, 1 when written as a bare `/`.
    pub switch: u8,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seq {
    pub number: u32,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Comment {
    /// The text between `(` and `)` as written when it is UTF-8; else
    /// (Latin-1, GBK) every byte outside printable ASCII, and `"`,
    /// replaced by `?`, as the canon prints it (`compact::comment_text`).
    pub text: String,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Body {
    /// NC words (possibly none: a block of only a sequence number or only
    /// comments).
    Words(Vec<Word>),
    /// Boxed: statements are rare and large, and every line of the tree
    /// is as large as its largest kind.
    Stmt(Box<Stmt>),
}

/// An address letter (or a Fanuc comma word) and its value.
#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    pub addr: Addr,
    pub value: Value,
    pub span: Span,
}

/// The address of a word.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Addr {
    /// A letter `A`..`Z`, upper case.
    Letter(char),
    /// `,A` `,C` `,R`.
    Comma(char),
}

impl std::fmt::Display for Addr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Addr::Letter(c) => write!(f, "{c}"),
            Addr::Comma(c) => write!(f, ",{c}"),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A literal as written.
    Number(Number),
    /// `#n`, `#[e]` or `[e]` (optionally signed): computed at run time or
    /// folded by the compiler. Boxed: computed words are few, and every
    /// word of the tree is as large as its largest kind.
    Expr(Box<Expr>),
}

/// A numeric literal, kept with the facts the decimal-point rule needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number {
    pub value: f64,
    /// Written with a `.` (`X30.`, `.5`).
    pub has_point: bool,
    /// Digits after the point (`G6.2` → 1; used to reject `G1.25`).
    pub decimals: u8,
    pub span: Span,
}

impl Number {
    /// The literal of digits `n` (no point) written at `span`.
    pub fn digits(n: u32, span: Span) -> Number {
        Number {
            value: f64::from(n),
            has_point: false,
            decimals: 0,
            span,
        }
    }
}

/// A macro statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// `#i = expr`.
    Assign {
        target: VarRef,
        value: Expr,
        span: Span,
    },
    /// `GOTO n`.
    Goto { target: Expr, span: Span },
    /// `IF [cond] GOTO n`.
    IfGoto {
        cond: Cond,
        target: Expr,
        span: Span,
    },
    /// `IF [cond] THEN #i = expr`.
    IfThen {
        cond: Cond,
        then: Box<Stmt>,
        span: Span,
    },
    /// `WHILE [cond] DO m`.
    While {
        cond: Cond,
        label: Label,
        span: Span,
    },
    /// `DO m` (an endless loop).
    Do { label: Label, span: Span },
    /// `END m`.
    End { label: Label, span: Span },
}

impl Stmt {
    pub fn span(&self) -> Span {
        match self {
            Stmt::Assign { span, .. }
            | Stmt::Goto { span, .. }
            | Stmt::IfGoto { span, .. }
            | Stmt::IfThen { span, .. }
            | Stmt::While { span, .. }
            | Stmt::Do { span, .. }
            | Stmt::End { span, .. } => *span,
        }
    }
}

/// A DO/END label as written (the compiler checks 1..3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Label {
    pub value: u32,
    pub span: Span,
}

/// `#n` or `#[expr]`: the number of a variable.
#[derive(Debug, Clone, PartialEq)]
pub struct VarRef {
    pub index: VarIndex,
    pub span: Span,
}

/// The number of a variable: digits, held in place with their span (most
/// variables of a macro program are written so; a box each made the tree
/// a third larger), or computed (`##12`, `#[expr]`, and digits past a
/// `u32`, which name no variable).
#[derive(Debug, Clone, PartialEq)]
pub enum VarIndex {
    Number(u32, Span),
    Expr(Box<Expr>),
}

impl VarIndex {
    /// The index as an expression (digits as [`Expr::Num`]).
    pub fn expr(&self) -> std::borrow::Cow<'_, Expr> {
        match self {
            VarIndex::Number(n, span) => {
                std::borrow::Cow::Owned(Expr::Num(Number::digits(*n, *span)))
            }
            VarIndex::Expr(e) => std::borrow::Cow::Borrowed(e),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    Num(Number),
    Var(VarRef),
    /// `[e]`: kept so the null rules (a bracketed bare variable copies null)
    /// and spans stay faithful.
    Paren {
        inner: Box<Expr>,
        span: Span,
    },
    Unary {
        op: UnOp,
        operand: Box<Expr>,
        span: Span,
    },
    Binary {
        op: BinOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
        span: Span,
    },
    Call {
        func: Func,
        arg: Box<Expr>,
        span: Span,
    },
    /// `ATAN[a]/[b]`.
    Atan2 {
        y: Box<Expr>,
        x: Box<Expr>,
        span: Span,
    },
}

impl Expr {
    pub fn span(&self) -> Span {
        match self {
            Expr::Num(n) => n.span,
            Expr::Var(v) => v.span,
            Expr::Paren { span, .. }
            | Expr::Unary { span, .. }
            | Expr::Binary { span, .. }
            | Expr::Call { span, .. }
            | Expr::Atan2 { span, .. } => *span,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Plus,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Or,
    Xor,
    Mul,
    Div,
    And,
    Mod,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Abs,
    Round,
    Fix,
    Fup,
    Ln,
    Exp,
    Bin,
    Bcd,
}

/// A condition of IF/WHILE.
#[derive(Debug, Clone, PartialEq)]
pub enum Cond {
    /// `[a EQ b]`.
    Rel {
        op: RelOp,
        lhs: Expr,
        rhs: Expr,
        span: Span,
    },
    /// `[c1 AND c2 …]` folded left.
    Logic {
        op: LogicOp,
        lhs: Box<Cond>,
        rhs: Box<Cond>,
        span: Span,
    },
}

impl Cond {
    pub fn span(&self) -> Span {
        match self {
            Cond::Rel { span, .. } | Cond::Logic { span, .. } => *span,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RelOp {
    Eq,
    Ne,
    Gt,
    Lt,
    Ge,
    Le,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LogicOp {
    And,
    Or,
    Xor,
}
