//! The generated parser, what it returns, and its semantic actions.

use crate::ast::{BlockDelete, Seq, Stmt, Word};
use crate::diag::Diagnostic;
use crate::lexer::Tok;
use lalrpop_util::ParseError;

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications, dead_code)]
    grammar
);

/// What the generated parser returns for one block; the driver adds the
/// comments and the block span and builds the AST's [`Line`].
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

/// The parser of one block (the generated tables are static: this is free).
pub type BlockParser = grammar::LineParser;

/// The parser of a batch of blocks separated by [`Tok::Eob`].
pub type BatchParser = grammar::BatchParser;

/// The semantic actions that can fail, and the small builders the grammar
/// uses; each failure names its own code.
pub(crate) mod actions {
    use super::{PError, Parsed};
    use crate::ast::*;
    use crate::diag::Diagnostic;
    use crate::lexer::WordLit;
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
                Diagnostic::error("E1004", n.span, "program number with a decimal point")
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

    pub fn seq(n: Number, span: Span) -> R<Seq> {
        if n.has_point {
            return fail(
                Diagnostic::error("E1006", n.span, "sequence number with a decimal point")
                    .with_label("N takes an integer"),
            );
        }
        if n.value > MAX_SEQ {
            return fail(
                Diagnostic::error("E1006", n.span, "sequence number above 99999")
                    .with_label("N takes 0 to 99999"),
            );
        }
        Ok(Seq {
            number: n.value as u32,
            span,
        })
    }

    /// The number of a word token.
    fn literal(w: WordLit, end: usize) -> Number {
        Number {
            value: w.value,
            has_point: w.has_point,
            decimals: w.decimals,
            span: Span::new(w.value_start as usize, end),
        }
    }

    pub fn word(w: WordLit, span: Span) -> R<Word> {
        let n = literal(w, span.end as usize);
        if w.letter == b'G' && n.decimals > 1 {
            return fail(
                Diagnostic::error(
                    "E1010",
                    span,
                    format!("G value with {} decimals", n.decimals),
                )
                .with_label("G codes have at most one decimal (`G6.2`)"),
            );
        }
        Ok(Word {
            addr: Addr::Letter(w.letter as char),
            value: Value::Number(n),
            span,
        })
    }

    pub fn computed_word(letter: u8, value: Value, span: Span) -> R<Word> {
        Ok(Word {
            addr: Addr::Letter(letter as char),
            value,
            span,
        })
    }

    pub fn comma_word(w: WordLit, letter: usize, span: Span) -> R<Word> {
        if !matches!(w.letter, b'A' | b'C' | b'R') {
            return fail(
                Diagnostic::error(
                    "E1008",
                    Span::new(letter, letter + 1),
                    format!("unknown comma word `,{}`", w.letter as char),
                )
                .with_label("only `,A`, `,C` and `,R` exist"),
            );
        }
        Ok(Word {
            addr: Addr::Comma(w.letter as char),
            value: Value::Number(literal(w, span.end as usize)),
            span,
        })
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

#[doc(hidden)]
pub fn lex_only(src: &[u8]) -> usize {
    let mut c = Compactor::default();
    let mut toks = Vec::new();
    let mut n = 0;
    let mut pos = 0;
    while pos < src.len() {
        let s = c.scan(src, pos, src.len());
        let _ = lexer::lex_block(s.text, s.map, &s.comments, &mut toks);
        n += toks.len();
        pos = s.end + 1;
    }
    n
}
