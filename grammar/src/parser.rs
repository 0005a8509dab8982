//! The driver: cuts the source into lines and blocks, lexes and parses one
//! block at a time (so a syntax error costs only its own block), and applies
//! the rules that span a whole line (`%` lines, simulator directives, the O
//! line).

use crate::ast::{Ast, Block, BlockDelete, Body, Line, ProgramStart, Seq, Stmt, Word};
use crate::compact::{Compactor, Scanned, Terminator};
use crate::diag::Diagnostic;
use crate::errors;
use crate::lexer::{self, Spanned, Tok};
use crate::span::Span;
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

/// Parses a whole file. See [`crate::parse`].
pub fn parse(src: &[u8]) -> (Ast, Vec<Diagnostic>) {
    // About one syntax-tree line per LF: counting is cheap and saves growing
    // (copying) a large vector again and again.
    let newlines = src.iter().filter(|&&b| b == b'\n').count();
    let mut driver = Driver {
        compactor: Compactor::default(),
        sink: Sink {
            src,
            ast: Ast {
                lines: Vec::with_capacity(newlines + 1),
            },
            diags: Vec::new(),
            tokens: Vec::new(),
            parser: BlockParser::new(),
        },
    };
    // A Ctrl-Z as the very last byte is the DOS end-of-file mark.
    let limit = match src.last() {
        Some(0x1A) => src.len() - 1,
        _ => src.len(),
    };
    let mut pos = 0;
    while pos < limit {
        pos = driver.line(pos, limit);
    }
    (driver.sink.ast, driver.sink.diags)
}

struct Driver<'src> {
    compactor: Compactor,
    sink: Sink<'src>,
}

/// Everything but the compactor, so a scanned block (which borrows the
/// compactor's buffers) can be handed over while it is alive.
struct Sink<'src> {
    src: &'src [u8],
    ast: Ast,
    diags: Vec<Diagnostic>,
    /// The current block's tokens (reused).
    tokens: Vec<Spanned>,
    parser: BlockParser,
}

/// What the blocks of one physical line have seen so far.
#[derive(Default)]
struct LineState {
    /// The number of blocks scanned on this line before the current one.
    blocks: usize,
    /// A program start stood on this line.
    program: bool,
    /// A block with words or a statement (or a faulty one) stood on it.
    other: bool,
}

fn is_blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

impl Driver<'_> {
    /// Handles the line starting at `pos`; returns where the next one starts.
    fn line(&mut self, pos: usize, limit: usize) -> usize {
        let src = self.sink.src;
        let mut first = pos;
        while first < limit && is_blank(src[first]) {
            first += 1;
        }
        match src.get(first).filter(|_| first < limit) {
            Some(b'%') => {
                let end = line_end(src, first, limit);
                self.sink.percent_line(first, end);
                return next_line(src, end, limit);
            }
            Some(b'[') if is_directive(&src[first + 1..limit]) => {
                let end = line_end(src, first, limit);
                let mut last = end;
                while last > first && is_blank(src[last - 1]) {
                    last -= 1;
                }
                self.sink.diags.push(
                    Diagnostic::warning(
                        "W102",
                        Span::new(first, last),
                        "simulator directive ignored",
                    )
                    .with_label("this line is skipped")
                    .with_note("a line starting with `[` and a letter is a simulator setting, not part of the program"),
                );
                return next_line(src, end, limit);
            }
            _ => {}
        }
        let mut state = LineState::default();
        let mut start = pos;
        loop {
            let scanned = self.compactor.scan(src, start, limit);
            let end = scanned.end;
            let terminator = scanned.terminator;
            self.sink.block(scanned, &mut state);
            state.blocks += 1;
            match terminator {
                Terminator::Semicolon => start = end + 1,
                Terminator::LineEnd => return next_line(src, end, limit),
                Terminator::Eof => return limit,
            }
        }
    }
}

/// `[` followed (after blanks) by a letter: `[BILLET X55 Z128`.
fn is_directive(rest: &[u8]) -> bool {
    rest.iter()
        .find(|&&b| !is_blank(b))
        .is_some_and(|b| b.is_ascii_alphabetic())
}

/// The offset of the end of the line that contains `from`.
fn line_end(src: &[u8], from: usize, limit: usize) -> usize {
    src[from..limit]
        .iter()
        .position(|&b| b == b'\n' || b == b'\r')
        .map_or(limit, |i| from + i)
}

/// The start of the line after the terminator at `end` (CR LF counts once).
fn next_line(src: &[u8], end: usize, limit: usize) -> usize {
    if end >= limit {
        limit
    } else if src[end] == b'\r' && src.get(end + 1) == Some(&b'\n') && end + 1 < limit {
        end + 2
    } else {
        end + 1
    }
}

impl Sink<'_> {
    fn percent_line(&mut self, at: usize, end: usize) {
        self.ast.lines.push(Line::Percent(Span::new(at, at + 1)));
        let rest = &self.src[at + 1..end];
        if let Some(i) = rest.iter().position(|&b| !is_blank(b)) {
            let mut last = rest.len();
            while last > i && is_blank(rest[last - 1]) {
                last -= 1;
            }
            self.diags.push(
                Diagnostic::error(
                    "E1003",
                    Span::new(at + 1 + i, at + 1 + last),
                    "text after `%` on a `%` line",
                )
                .with_label("a `%` line holds nothing else")
                .with_help("put the text on a line of its own"),
            );
        }
    }

    fn block(&mut self, scanned: Scanned<'_>, line: &mut LineState) {
        let after_semicolon = line.blocks > 0;
        if let Some(d) = scanned.error {
            line.other = true;
            self.diags.push(d);
            return;
        }
        let Some(span) = scanned.span else {
            return; // an empty block
        };
        if scanned.text.is_empty() {
            // Only comments: no tokens to parse.
            self.ast.lines.push(Line::Block(Block {
                delete: None,
                seq: None,
                body: Body::Words(Vec::new()),
                comments: scanned.comments,
                span,
            }));
            return;
        }
        if let Err(d) = lexer::lex_block(
            scanned.text,
            scanned.map,
            &scanned.comments,
            &mut self.tokens,
        ) {
            line.other = true;
            self.report(*d, after_semicolon);
            return;
        }
        let tokens = self.tokens.iter().map(|&t| Ok::<_, Box<Diagnostic>>(t));
        match self.parser.parse(tokens) {
            Ok(Parsed::Program { number, .. }) => {
                if line.other {
                    self.diags.push(
                        Diagnostic::error(
                            "E1004",
                            span,
                            "a program number must start its own line",
                        )
                        .with_label("other blocks stand before it on this line")
                        .with_help("put the O line on a line of its own"),
                    );
                    return;
                }
                line.program = true;
                self.ast.lines.push(Line::ProgramStart(ProgramStart {
                    number,
                    comments: scanned.comments,
                    span,
                }));
            }
            Ok(parsed) => {
                line.other = true;
                if line.program {
                    self.diags.push(
                        Diagnostic::error(
                            "E1004",
                            span,
                            "the O line holds only the program number and comments",
                        )
                        .with_label("a block after the program number")
                        .with_help("start a new line for this block"),
                    );
                    return;
                }
                let (delete, seq, body) = match parsed {
                    Parsed::Words { delete, seq, words } => (delete, seq, Body::Words(words)),
                    Parsed::Stmt { delete, seq, stmt } => (delete, seq, Body::Stmt(*stmt)),
                    Parsed::Program { .. } => return,
                };
                self.ast.lines.push(Line::Block(Block {
                    delete,
                    seq,
                    body,
                    comments: scanned.comments,
                    span,
                }));
            }
            Err(e) => {
                line.other = true;
                let d = errors::convert(e, &self.tokens, self.src, &self.parser);
                self.report(d, after_semicolon);
            }
        }
    }

    fn report(&mut self, mut d: Diagnostic, after_semicolon: bool) {
        // `T0505 ;bedame de 3mm`: `;` ends a block, it does not start a comment.
        if after_semicolon && d.code == "E1008" && d.help.is_none() {
            d.help = Some(
                "`;` ends a block, so this text is a block of its own: put comments in ( )".into(),
            );
        }
        // `G00 3.7347` is `G003.7347`: say so when blanks made the number.
        let spelled = self.src.get(d.span.range()).unwrap_or_default();
        if d.help.is_none() && spelled.iter().any(|&b| is_blank(b)) && d.code != "E1013" {
            let joined: String = spelled
                .iter()
                .filter(|&&b| !is_blank(b))
                .map(|&b| (b as char).to_ascii_uppercase())
                .collect();
            if joined.bytes().all(|b| b.is_ascii_graphic()) {
                d.help = Some(format!(
                    "blanks are ignored, even inside numbers: this reads `{joined}`; is an address letter missing?"
                ));
            }
        }
        self.diags.push(d);
    }
}

/// The semantic actions that can fail, and the small builders the grammar
/// uses; each failure names its own code.
pub(crate) mod actions {
    use super::{PError, Parsed};
    use crate::ast::*;
    use crate::diag::Diagnostic;
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

    pub fn word(letter: u8, value: Value, span: Span) -> R<Word> {
        if let (b'G', Value::Number(n)) = (letter, &value) {
            if n.decimals > 1 {
                return fail(
                    Diagnostic::error(
                        "E1010",
                        span,
                        format!("G value with {} decimals", n.decimals),
                    )
                    .with_label("G codes have at most one decimal (`G6.2`)"),
                );
            }
        }
        Ok(Word {
            addr: Addr::Letter(letter as char),
            value,
            span,
        })
    }

    pub fn comma_word(letter: u8, letter_span: Span, n: Number, span: Span) -> R<Word> {
        if !matches!(letter, b'A' | b'C' | b'R') {
            return fail(
                Diagnostic::error(
                    "E1008",
                    letter_span,
                    format!("unknown comma word `,{}`", letter as char),
                )
                .with_label("only `,A`, `,C` and `,R` exist"),
            );
        }
        Ok(Word {
            addr: Addr::Comma(letter as char),
            value: Value::Number(n),
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
