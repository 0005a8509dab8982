//! The generated parser, what it returns, and its semantic actions.

use crate::ast::{BlockDelete, Seq, Stmt, Word};
use crate::diag::Diagnostic;
use crate::lexer::{Spanned, Tok};
use lalrpop_util::ParseError;

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications, dead_code)]
    grammar
);

/// What the generated parser returns for one block; the driver adds the
/// comments and the block span and builds the AST's
/// [`Line`](crate::ast::Line).
pub enum Parsed {
    Program {
        number: u32,
    },
    Words {
        delete: Option<BlockDelete>,
        seq: Option<Seq>,
        words: Vec<Word>,
    },
    Stmt {
        delete: Option<BlockDelete>,
        seq: Option<Seq>,
        stmt: Box<Stmt>,
    },
}

/// What the generated parser returns on failure.
pub type PError = ParseError<usize, Tok, Box<Diagnostic>>;

/// The parser of blocks, each followed by [`Tok::Eob`] (the generated
/// tables are static: making one is free).
pub type BatchParser = grammar::BatchParser;

/// Parses one block (its tokens without the final `Eob`).
pub fn parse_block(parser: &BatchParser, toks: &[Spanned]) -> Result<Parsed, PError> {
    let end = toks.last().map_or(0, |t| t.2);
    let tokens = toks
        .iter()
        .copied()
        .chain(std::iter::once((end, Tok::Eob, end)))
        .map(Ok);
    let mut parsed = parser.parse(&[], tokens)?;
    match (parsed.pop(), parsed.is_empty()) {
        (Some(p), true) => Ok(p),
        // One block in, one result out: anything else is a bug of ours,
        // reported rather than panicking.
        _ => Err(ParseError::User {
            error: Box::new(Diagnostic::error(
                "E1014",
                crate::span::Span::new(toks.first().map_or(0, |t| t.0), end),
                "internal error: block parsed into other than one result",
            )),
        }),
    }
}

/// The semantic actions that can fail, and the small builders the grammar
/// uses; each failure names its own code.
pub(crate) mod actions {
    use super::{PError, Parsed};
    use crate::ast::*;
    use crate::diag::Diagnostic;
    use crate::lexer::{RunRef, WordLit};
    use crate::span::Span;
    use lalrpop_util::ParseError;

    type R<T> = Result<T, PError>;

    fn fail<T>(d: Diagnostic) -> R<T> {
        Err(ParseError::User { error: Box::new(d) })
    }

    /// Largest program number: 8 digits (dialect.md §1.2).
    const MAX_PROGRAM: f64 = 99_999_999.0;
    /// Largest sequence number (dialect.md §1.6).
    const MAX_SEQ: f64 = 99_999.0;

    pub fn program_start(n: Number) -> R<Parsed> {
        if n.has_point {
            return fail(
                Diagnostic::error("E1009", n.span, "program number with a decimal point")
                    .with_label("an integer is needed here"),
            );
        }
        if n.value > MAX_PROGRAM {
            return fail(
                Diagnostic::error("E1004", n.span, "program number above 99999999")
                    .with_label("more than 8 digits"),
            );
        }
        Ok(Parsed::Program {
            number: n.value as u32,
        })
    }

    pub fn block_delete(n: Number, span: Span) -> R<BlockDelete> {
        if n.has_point || !(1.0..=9.0).contains(&n.value) {
            return fail(
                Diagnostic::error("E1015", span, "block-delete switch must be 1 to 9")
                    .with_label("`/` or `/1` … `/9`"),
            );
        }
        Ok(BlockDelete {
            switch: n.value as u8,
            span,
        })
    }

    pub fn seq(w: WordLit, span: Span) -> R<Seq> {
        let digits = Span::new(w.value_start as usize, span.end as usize);
        if w.has_point {
            return fail(
                Diagnostic::error("E1006", digits, "sequence number with a decimal point")
                    .with_label("N takes an integer"),
            );
        }
        if w.value > MAX_SEQ {
            return fail(
                Diagnostic::error("E1006", digits, "sequence number above 99999")
                    .with_label("N takes 0 to 99999"),
            );
        }
        Ok(Seq {
            number: w.value as u32,
            span,
        })
    }

    /// The words of a run token (none for a bad reference, which the
    /// driver never makes).
    pub fn run(runs: &[Word], r: RunRef) -> &[Word] {
        let start = r.start as usize;
        runs.get(start..start + r.len as usize).unwrap_or_default()
    }

    /// A word with a literal value (the value's span starts after the
    /// letter, at its sign or first digit).
    pub fn word(addr: Addr, w: WordLit, span: Span) -> Word {
        Word {
            addr,
            value: Value::Number(Number {
                value: w.value,
                has_point: w.has_point,
                decimals: w.decimals,
                span: Span::new(w.value_start as usize, span.end as usize),
            }),
            span,
        }
    }

    pub fn label(n: Number) -> R<Label> {
        if n.has_point || n.value > f64::from(u32::MAX) {
            return fail(
                Diagnostic::error("E1014", n.span, "loop label must be a whole number")
                    .with_label("write `DO1`, `END1` …"),
            );
        }
        Ok(Label {
            value: n.value as u32,
            span: n.span,
        })
    }

    /// The literal number of a variable: digits only (`#1.5` is no variable).
    pub fn index(n: Number) -> R<VarIndex> {
        if n.has_point {
            return fail(
                Diagnostic::error("E1014", n.span, "variable number with a decimal point")
                    .with_label("`#` takes digits, `#n`, or `[expr]`"),
            );
        }
        // (Digits past a `u32` name no variable: the run says so.)
        Ok(match n.value <= f64::from(u32::MAX) {
            true => VarIndex::Number(n.value as u32, n.span),
            false => VarIndex::Expr(Box::new(Expr::Num(n))),
        })
    }

    pub fn unary(op: UnOp, operand: Expr, span: Span) -> Expr {
        Expr::Unary {
            op,
            operand: Box::new(operand),
            span,
        }
    }

    pub fn binary(op: BinOp, lhs: Expr, rhs: Expr, span: Span) -> Expr {
        Expr::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
            span,
        }
    }

    /// `[[c1]AND[c2]]`: the outer brackets belong to the combined condition.
    pub fn widen(mut c: Box<Cond>, outer: Span) -> Box<Cond> {
        match &mut *c {
            Cond::Rel { span, .. } | Cond::Logic { span, .. } => *span = outer,
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use crate::ast::*;

    /// The one statement of a one-block program.
    fn stmt(src: &str) -> Stmt {
        let (ast, diags) = crate::parse(src.as_bytes());
        assert!(diags.is_empty(), "{src}: {diags:?}");
        match ast.lines.as_slice() {
            [Line::Block(Block {
                body: Body::Stmt(s),
                ..
            })] => (**s).clone(),
            other => panic!("{src}: {other:?}"),
        }
    }

    fn words(src: &str) -> Vec<Word> {
        let (ast, diags) = crate::parse(src.as_bytes());
        assert!(diags.is_empty(), "{src}: {diags:?}");
        match ast.lines.as_slice() {
            [Line::Block(Block {
                body: Body::Words(w),
                ..
            })] => w.clone(),
            other => panic!("{src}: {other:?}"),
        }
    }

    /// An expression as an S-expression, to state its shape compactly.
    fn sexp(e: &Expr) -> String {
        match e {
            Expr::Num(n) => format!("{}", n.value),
            Expr::Var(v) => format!("#{}", sexp(&v.index.expr())),
            Expr::Paren { inner, .. } => format!("[{}]", sexp(inner)),
            Expr::Unary { op, operand, .. } => format!("({op:?} {})", sexp(operand)),
            Expr::Binary { op, lhs, rhs, .. } => format!("({op:?} {} {})", sexp(lhs), sexp(rhs)),
            Expr::Call { func, arg, .. } => format!("({func:?} {})", sexp(arg)),
            Expr::Atan2 { y, x, .. } => format!("(Atan2 {} {})", sexp(y), sexp(x)),
        }
    }

    fn value(src: &str) -> String {
        match stmt(&format!("#1={src}")) {
            Stmt::Assign { value, .. } => sexp(&value),
            other => panic!("{other:?}"),
        }
    }

    fn cond(c: &Cond) -> String {
        match c {
            Cond::Rel { op, lhs, rhs, .. } => format!("({op:?} {} {})", sexp(lhs), sexp(rhs)),
            Cond::Logic { op, lhs, rhs, .. } => format!("({op:?} {} {})", cond(lhs), cond(rhs)),
        }
    }

    #[test]
    fn left_associative() {
        assert_eq!(value("20/4/5"), "(Div (Div 20 4) 5)");
        assert_eq!(value("10-4-3"), "(Sub (Sub 10 4) 3)");
        assert_eq!(value("2*3MOD4AND5"), "(And (Mod (Mul 2 3) 4) 5)");
        assert_eq!(value("1OR2XOR3+4"), "(Add (Xor (Or 1 2) 3) 4)");
    }

    #[test]
    fn precedence() {
        assert_eq!(value("1+2*3"), "(Add 1 (Mul 2 3))");
        assert_eq!(value("1-2/3"), "(Sub 1 (Div 2 3))");
        assert_eq!(value("1OR2AND3"), "(Or 1 (And 2 3))");
        assert_eq!(value("[1+2]*3"), "(Mul [(Add 1 2)] 3)");
        assert_eq!(value("SIN[30]+1"), "(Add (Sin 30) 1)");
    }

    #[test]
    fn unary_binds_tightest_and_nests_right() {
        assert_eq!(value("2*-3"), "(Mul 2 (Neg 3))");
        assert_eq!(value("-2*3"), "(Mul (Neg 2) 3)");
        assert_eq!(value("--1"), "(Neg (Neg 1))");
        assert_eq!(value("-+#2"), "(Neg (Plus #2))");
        assert_eq!(value("1--1"), "(Sub 1 (Neg 1))");
    }

    #[test]
    fn atan_forms() {
        assert_eq!(value("ATAN[1]/[2]"), "(Atan2 1 2)");
        assert_eq!(value("ATAN[1]/[2]/[3]"), "(Div (Atan2 1 2) [3])");
        assert_eq!(value("2*ATAN[1]/[2]"), "(Mul 2 (Atan2 1 2))");
        assert_eq!(value("-ATAN[1]/[-1]"), "(Neg (Atan2 1 (Neg 1)))");
        assert_eq!(value("ATAN[1]*2"), "(Mul (Atan 1) 2)");
        assert_eq!(value("ATAN[1]"), "(Atan 1)");
        assert_eq!(value("[ATAN[1]]/2"), "(Div [(Atan 1)] 2)");
    }

    #[test]
    fn variables() {
        assert_eq!(value("#2"), "#2");
        assert_eq!(value("##2"), "##2");
        assert_eq!(value("#[#2+1]"), "#[(Add #2 1)]");
        match stmt("#[#1]=5") {
            Stmt::Assign { target, .. } => assert_eq!(sexp(&target.index.expr()), "[#1]"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn conditions() {
        match stmt("IF[[#1EQ0]AND[#2GT1]OR[#3LT2]]GOTO5") {
            Stmt::IfGoto {
                cond: c, target, ..
            } => {
                assert_eq!(cond(&c), "(Or (And (Eq #1 0) (Gt #2 1)) (Lt #3 2))");
                assert_eq!(sexp(&target), "5");
            }
            other => panic!("{other:?}"),
        }
        match stmt("WHILE[#1LE[#2+1]]DO2") {
            Stmt::While { cond: c, label, .. } => {
                assert_eq!(cond(&c), "(Le #1 [(Add #2 1)])");
                assert_eq!(label.value, 2);
            }
            other => panic!("{other:?}"),
        }
        match stmt("N10IF[#859LT300]THEN#1100=1") {
            Stmt::IfThen { cond: c, then, .. } => {
                assert_eq!(cond(&c), "(Lt #859 300)");
                assert!(matches!(*then, Stmt::Assign { .. }));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn keywords_versus_words() {
        assert!(matches!(
            stmt("DO1"),
            Stmt::Do {
                label: Label { value: 1, .. },
                ..
            }
        ));
        assert!(matches!(
            stmt("END3"),
            Stmt::End {
                label: Label { value: 3, .. },
                ..
            }
        ));
        assert!(matches!(stmt("GOTO10"), Stmt::Goto { .. }));
        let w = words("D01 E5 G1X1E5");
        let addrs: Vec<String> = w.iter().map(|w| w.addr.to_string()).collect();
        assert_eq!(addrs, ["D", "E", "G", "X", "E"]);
    }

    #[test]
    fn number_forms() {
        let w = words("X30 X30. X30.0 X-30. Z.05 Z-.05 X+13.64 X0030 G6.2 ,A-30.5");
        let n: Vec<(f64, bool, u8)> = w
            .iter()
            .map(|w| match &w.value {
                Value::Number(n) => (n.value, n.has_point, n.decimals),
                other => panic!("{other:?}"),
            })
            .collect();
        assert_eq!(
            n,
            [
                (30.0, false, 0),
                (30.0, true, 0),
                (30.0, true, 1),
                (-30.0, true, 0),
                (0.05, true, 2),
                (-0.05, true, 2),
                (13.64, true, 2),
                (30.0, false, 0),
                (6.2, true, 1),
                (-30.5, true, 1),
            ]
        );
        assert_eq!(w[9].addr, Addr::Comma('A'));
    }

    #[test]
    fn blanks_inside_words_and_spans() {
        let w = words("X 3 0 . 5 F 0.25");
        match &w[0].value {
            Value::Number(n) => {
                assert_eq!(n.value, 30.5);
                assert_eq!(n.span, crate::Span::new(2, 9), "the span covers `3 0 . 5`");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(w[0].span, crate::Span::new(0, 9));
        assert_eq!(w[1].span, crate::Span::new(10, 16));
    }
}
