//! Tokens of one block, lexed with logos from the text [`crate::compact`]
//! hands over (comments taken out, blanks removed wherever they stood
//! inside a token; the others are skipped here), with their spans mapped
//! back to offsets in the original source. A block of literal words only,
//! most of any program, is lexed by [`word_at`] instead, one pass that
//! makes the same tokens (tests compare the two on random text).
//!
//! Keywords win by longest match, so `DO1` is a loop and `D01` a word,
//! `GOTO` is not `G` + `OTO`, and `ANDSIN` is `AND` `SIN`. A letter followed
//! by a letter is therefore never a keyword split by accident: in NC words a
//! letter always needs a value, so such a pair is an error either way.

use crate::ast::{Comment, Func, RelOp};
use crate::compact::OffsetMap;
use crate::diag::Diagnostic;
use crate::span::Span;
use logos::Logos;

/// A numeric literal without its sign and span (the grammar adds both).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumLit {
    pub value: f64,
    pub has_point: bool,
    pub decimals: u8,
}

/// A whole word with a literal value, `X-12.5`: one token rather than three,
/// because such words are most of any program and every token costs a
/// lexer step and a parser shift. A letter directly followed by a sign or a
/// digit is always the start of a word (outside a word, letters only occur
/// in keywords), so the lexer can take the word in one piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WordLit {
    /// The value with its sign applied.
    pub value: f64,
    /// The source offset where the value (its sign, if any) starts; set by
    /// [`lex_block`] (logos only knows the compacted text).
    pub value_start: u32,
    /// The upper-case address letter.
    pub letter: u8,
    pub has_point: bool,
    pub decimals: u8,
}

/// Where the words of a [`Tok::Run`] are: `words[start..start + len]` of
/// the batch being parsed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunRef {
    pub start: u32,
    pub len: u32,
}

/// Why logos could not make a token.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LexError {
    /// A character that starts no token.
    #[default]
    Char,
    /// Digits and points that are not a number (`1.2.3`, `.`).
    Number,
    /// Digits beyond the largest double (more than 308 before the point):
    /// they would read as infinity.
    Range,
}

/// A token. `N` and `O` are tokens of their own because the grammar treats
/// them apart from the other address letters (sequence and program numbers).
#[derive(Logos, Debug, Clone, Copy, PartialEq)]
#[logos(utf8 = false, error = LexError)]
// Blanks reach the lexer only where they separate tokens (compact.rs).
#[logos(skip r"[ \t]+")]
pub enum Tok {
    #[regex("[A-MP-Za-mp-z]", |lex| lex.slice()[0].to_ascii_uppercase())]
    Letter(u8),
    // Digits and points are taken in one simple run and checked by the
    // callback: a cheaper automaton, and `X1.2.3` is one malformed number.
    #[regex(r"[A-MP-Za-mp-z][+-]?[0-9.]+", |lex| word(lex.slice()))]
    Word(WordLit),
    #[token("N", ignore(case))]
    N,
    /// `N` and its digits in one token, as for words (a sequence number is
    /// in most blocks).
    #[regex(r"[Nn][0-9.]+", |lex| word(lex.slice()))]
    Seq(WordLit),
    #[token("O", ignore(case))]
    O,
    #[token(":")]
    Colon,
    #[regex(r"[0-9.]+", |lex| number(lex.slice()))]
    Num(NumLit),
    #[token(",")]
    Comma,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("#")]
    Hash,
    #[token("[")]
    LBrack,
    #[token("]")]
    RBrack,
    #[token("=")]
    Assign,
    #[token("IF", ignore(case))]
    If,
    #[token("THEN", ignore(case))]
    Then,
    #[token("GOTO", ignore(case))]
    Goto,
    #[token("WHILE", ignore(case))]
    While,
    #[token("DO", ignore(case))]
    Do,
    #[token("END", ignore(case))]
    End,
    #[token("EQ", |_| RelOp::Eq, ignore(case))]
    #[token("NE", |_| RelOp::Ne, ignore(case))]
    #[token("GT", |_| RelOp::Gt, ignore(case))]
    #[token("LT", |_| RelOp::Lt, ignore(case))]
    #[token("GE", |_| RelOp::Ge, ignore(case))]
    #[token("LE", |_| RelOp::Le, ignore(case))]
    Rel(RelOp),
    #[token("AND", ignore(case))]
    And,
    #[token("OR", ignore(case))]
    Or,
    #[token("XOR", ignore(case))]
    Xor,
    #[token("MOD", ignore(case))]
    Mod,
    /// `ATAN` apart from the other functions: it has a two-argument form.
    #[token("ATAN", ignore(case))]
    Atan,
    #[token("SIN", |_| Func::Sin, ignore(case))]
    #[token("COS", |_| Func::Cos, ignore(case))]
    #[token("TAN", |_| Func::Tan, ignore(case))]
    #[token("ASIN", |_| Func::Asin, ignore(case))]
    #[token("ACOS", |_| Func::Acos, ignore(case))]
    #[token("SQRT", |_| Func::Sqrt, ignore(case))]
    #[token("ABS", |_| Func::Abs, ignore(case))]
    #[token("ROUND", |_| Func::Round, ignore(case))]
    #[token("FIX", |_| Func::Fix, ignore(case))]
    #[token("FUP", |_| Func::Fup, ignore(case))]
    #[token("LN", |_| Func::Ln, ignore(case))]
    #[token("EXP", |_| Func::Exp, ignore(case))]
    #[token("BIN", |_| Func::Bin, ignore(case))]
    #[token("BCD", |_| Func::Bcd, ignore(case))]
    Func(Func),
    /// The end of a block in a batch of blocks parsed together (never
    /// produced by logos: the driver puts it between blocks).
    Eob,
    /// A run of literal words (`X10 Z-5 ,C1`), already built (never produced
    /// by logos: the driver groups word tokens for batch parsing).
    Run(RunRef),
}

impl Tok {
    /// How the token is written, for messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Letter(c) => format!("letter `{}`", *c as char),
            Tok::N => "`N`".into(),
            Tok::O => "`O`".into(),
            Tok::Colon => "`:`".into(),
            Tok::Num(_) => "number".into(),
            Tok::Word(w) => format!("word `{}…`", w.letter as char),
            Tok::Seq(_) => "sequence number".into(),
            Tok::Comma => "`,`".into(),
            Tok::Plus => "`+`".into(),
            Tok::Minus => "`-`".into(),
            Tok::Star => "`*`".into(),
            Tok::Slash => "`/`".into(),
            Tok::Hash => "`#`".into(),
            Tok::LBrack => "`[`".into(),
            Tok::RBrack => "`]`".into(),
            Tok::Assign => "`=`".into(),
            Tok::If => "`IF`".into(),
            Tok::Then => "`THEN`".into(),
            Tok::Goto => "`GOTO`".into(),
            Tok::While => "`WHILE`".into(),
            Tok::Do => "`DO`".into(),
            Tok::End => "`END`".into(),
            Tok::Rel(op) => format!("`{}`", rel_name(*op)),
            Tok::And => "`AND`".into(),
            Tok::Or => "`OR`".into(),
            Tok::Xor => "`XOR`".into(),
            Tok::Mod => "`MOD`".into(),
            Tok::Atan => "`ATAN`".into(),
            Tok::Func(f) => format!("`{}`", func_name(*f)),
            Tok::Eob => "end of block".into(),
            Tok::Run(_) => "words".into(),
        }
    }

    /// An address letter (including `N` and `O`): the start of a word.
    pub fn is_letter(&self) -> bool {
        matches!(self, Tok::Letter(_) | Tok::N | Tok::O)
    }

    /// A number, alone or as the value of a word token.
    pub fn has_number(&self) -> bool {
        matches!(self, Tok::Num(_) | Tok::Word(_))
    }

    /// A token that can only start a macro statement.
    pub fn starts_statement(&self) -> bool {
        matches!(
            self,
            Tok::Hash | Tok::If | Tok::Goto | Tok::While | Tok::Do | Tok::End
        )
    }
}

pub fn rel_name(op: RelOp) -> &'static str {
    match op {
        RelOp::Eq => "EQ",
        RelOp::Ne => "NE",
        RelOp::Gt => "GT",
        RelOp::Lt => "LT",
        RelOp::Ge => "GE",
        RelOp::Le => "LE",
    }
}

pub fn func_name(f: Func) -> &'static str {
    match f {
        Func::Sin => "SIN",
        Func::Cos => "COS",
        Func::Tan => "TAN",
        Func::Asin => "ASIN",
        Func::Acos => "ACOS",
        Func::Atan => "ATAN",
        Func::Sqrt => "SQRT",
        Func::Abs => "ABS",
        Func::Round => "ROUND",
        Func::Fix => "FIX",
        Func::Fup => "FUP",
        Func::Ln => "LN",
        Func::Exp => "EXP",
        Func::Bin => "BIN",
        Func::Bcd => "BCD",
    }
}

/// Exact powers of ten as doubles (10^22 is the largest exact one).
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Reads `digits[.digits]` or `.digits` from a run of digits and points.
///
/// Short literals, nearly all of them, take the exact fast path: an integer
/// mantissa below 2^53 divided by an exact power of ten is correctly
/// rounded, so it equals what the standard parser returns; longer ones go
/// through the standard parser.
pub fn number(s: &[u8]) -> Result<NumLit, LexError> {
    let mut mantissa: u64 = 0;
    let mut point = None;
    for (i, &b) in s.iter().enumerate() {
        if b == b'.' {
            if point.is_some() {
                return Err(LexError::Number);
            }
            point = Some(i);
        } else {
            mantissa = mantissa
                .wrapping_mul(10)
                .wrapping_add(u64::from(b.wrapping_sub(b'0')));
        }
    }
    let digits = s.len() - usize::from(point.is_some());
    if digits == 0 {
        return Err(LexError::Number);
    }
    let decimals = point.map_or(0, |p| s.len() - p - 1);
    let value = if digits <= 15 {
        mantissa as f64 / POW10[decimals]
    } else {
        std::str::from_utf8(s)
            .ok()
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(f64::INFINITY)
    };
    if !value.is_finite() {
        return Err(LexError::Range);
    }
    Ok(NumLit {
        value,
        has_point: point.is_some(),
        decimals: decimals.min(u8::MAX as usize) as u8,
    })
}

/// Reads a word token: letter, optional sign, number.
fn word(s: &[u8]) -> Result<WordLit, LexError> {
    let letter = s[0].to_ascii_uppercase();
    let (negative, digits) = match s.get(1) {
        Some(b'-') => (true, &s[2..]),
        Some(b'+') => (false, &s[2..]),
        _ => (false, &s[1..]),
    };
    let n = number(digits)?;
    Ok(WordLit {
        value: if negative { -n.value } else { n.value },
        value_start: 1,
        letter,
        has_point: n.has_point,
        decimals: n.decimals,
    })
}

/// A lexed token with its source span.
pub type Spanned = (usize, Tok, usize);

/// Brackets may nest 32 deep (dialect.md §7.4).
pub const MAX_DEPTH: usize = 32;

/// Operators (and `#`, functions) allowed in one block. Not in the spec:
/// it bounds the depth of expression trees so that nothing that walks them
/// recursively (drop, the compiler) can overflow the stack on hostile input;
/// real blocks stay far below it.
pub const MAX_OPERATORS: usize = 256;

/// Lexes one compacted block, appending its tokens to `out`, and checks
/// what needs the token stream but not the grammar: stray characters,
/// comments inside words, bracket depth. On failure `out` is left as it was.
pub fn lex_block(
    text: &[u8],
    map: OffsetMap<'_>,
    comments: &[Comment],
    out: &mut Vec<Spanned>,
) -> Result<(), Box<Diagnostic>> {
    let first = out.len();
    let result = lex_into(text, map, comments, first, out);
    if result.is_err() {
        out.truncate(first);
    }
    result
}

fn lex_into(
    text: &[u8],
    map: OffsetMap<'_>,
    comments: &[Comment],
    first: usize,
    out: &mut Vec<Spanned>,
) -> Result<(), Box<Diagnostic>> {
    if !lex_words(text, &map, out) {
        lex_tokens(text, &map, first, out)?;
    }
    for comment in comments {
        check_comment_place(comment, &out[first..])?;
    }
    Ok(())
}

/// The usual block, literal words and perhaps a sequence number between
/// blanks (`N10 G01 X-1.5 Z2 F.2`), lexed by [`word_at`], each word's
/// value read in the same pass as its extent. The tokens are those logos
/// makes: a letter followed by a sign or a
/// digit or a point can only start a word (keywords are letters only), and
/// the word runs to the end of its digits and points. `false`, with `out`
/// as it was, at anything else (an `O`, a comma, an operator, a faulty
/// number or word): logos lexes such a block and reports its faults.
fn lex_words(text: &[u8], map: &OffsetMap<'_>, out: &mut Vec<Spanned>) -> bool {
    let first = out.len();
    let mut i = 0;
    while i < text.len() {
        if is_skipped(text[i]) {
            i += 1;
            continue;
        }
        match word_at(text, i, map) {
            Some((tok, end)) => {
                out.push((map.start(i), tok, map.end(end)));
                i = end;
            }
            None => {
                out.truncate(first);
                return false;
            }
        }
    }
    true
}

/// What logos skips between tokens.
fn is_skipped(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// The word or sequence number at `text[i]` and where it ends, as logos
/// lexes it (its value read in the same pass, as [`number`] reads it);
/// `None` for anything else, a value of more than 15 digits (logos's, by
/// the standard parser) or a word that does not check.
// (Always inlined: it runs for every word of a plain block, and a call
// returned its token through memory; 5 % of the front end's instructions.)
#[inline(always)]
pub(crate) fn word_at(text: &[u8], i: usize, map: &OffsetMap<'_>) -> Option<(Tok, usize)> {
    let letter = text[i].to_ascii_uppercase();
    let seq = letter == b'N';
    if !letter.is_ascii_uppercase() || letter == b'O' {
        return None;
    }
    let mut end = i + 1;
    let mut negative = false;
    // (A sequence number takes no sign: `N-1` is `N` and `-`.)
    if !seq && matches!(text.get(end), Some(b'+' | b'-')) {
        negative = text[end] == b'-';
        end += 1;
    }
    let start = end;
    let mut mantissa = 0u64;
    let mut point = None;
    while let Some(&b) = text.get(end) {
        match b {
            b'0'..=b'9' => mantissa = mantissa * 10 + u64::from(b - b'0'),
            b'.' if point.is_none() => point = Some(end),
            // (`1.2.3`: logos reports it.)
            b'.' => return None,
            _ => break,
        }
        end += 1;
        if end - start > 16 {
            return None;
        }
    }
    let digits = end - start - usize::from(point.is_some());
    let decimals = point.map_or(0, |p| end - p - 1);
    if digits == 0 || digits > 15 || (letter == b'G' && decimals > 1) {
        return None;
    }
    let magnitude = mantissa as f64 / POW10[decimals];
    let w = WordLit {
        value: if negative { -magnitude } else { magnitude },
        value_start: map.start(i + 1) as u32,
        letter,
        has_point: point.is_some(),
        decimals: decimals as u8,
    };
    Some((if seq { Tok::Seq(w) } else { Tok::Word(w) }, end))
}

/// Lexes with logos: every token the language has.
fn lex_tokens(
    text: &[u8],
    map: &OffsetMap<'_>,
    first: usize,
    out: &mut Vec<Spanned>,
) -> Result<(), Box<Diagnostic>> {
    let mut lex = Tok::lexer(text);
    let mut bounds = Bounds::default();
    while let Some(next) = lex.next() {
        let range = lex.span();
        let start = map.start(range.start);
        let end = map.end(range.end);
        let tok = match next {
            Ok(Tok::Word(mut w)) => {
                w.value_start = map.start(range.start + 1) as u32;
                let after_comma = matches!(out[first..].last(), Some((_, Tok::Comma, _)));
                check_word(w, after_comma, start, end)?;
                Tok::Word(w)
            }
            Ok(Tok::Seq(mut w)) => {
                w.value_start = map.start(range.start + 1) as u32;
                Tok::Seq(w)
            }
            Ok(tok) => tok,
            Err(LexError::Number) => return Err(malformed_number(text, range, map, end)),
            Err(LexError::Range) => return Err(too_large(text, range, map, end)),
            Err(LexError::Char) => return Err(Box::new(bad_char(text[range.start], start, end))),
        };
        let prev = out[first..].last().map(|(_, t, _)| t);
        bounds.count(&tok, prev, Span::new(start, end))?;
        out.push((start, tok, end));
    }
    Ok(())
}

/// The start of a number's value in a token `range` of `text`: after its
/// address letter, if it has one.
fn value_start(text: &[u8], range: &core::ops::Range<usize>, map: &OffsetMap<'_>) -> usize {
    match text[range.clone()].first() {
        Some(c) if c.is_ascii_alphabetic() => map.start(range.start + 1),
        _ => map.start(range.start),
    }
}

/// E1007: a number with two decimal points, or a point without digits.
#[cold]
fn malformed_number(
    text: &[u8],
    range: core::ops::Range<usize>,
    map: &OffsetMap<'_>,
    end: usize,
) -> Box<Diagnostic> {
    let slice = &text[range.clone()];
    let value = match slice.first() {
        Some(c) if c.is_ascii_alphabetic() => &slice[1..],
        _ => slice,
    };
    let span = Span::new(value_start(text, &range, map), end);
    let spelled = crate::diag::quote(value.iter().map(|&b| b as char));
    let d = if value.iter().any(u8::is_ascii_digit) {
        Diagnostic::error("E1007", span, format!("malformed number `{spelled}`"))
            .with_label("a number has at most one decimal point")
    } else {
        Diagnostic::error("E1007", span, "malformed number: `.` without digits")
            .with_label("a point needs a digit before or after it")
            .with_help("write `0.` or `.0`")
    };
    Box::new(d)
}

/// E1010: a number beyond the largest double.
#[cold]
fn too_large(
    text: &[u8],
    range: core::ops::Range<usize>,
    map: &OffsetMap<'_>,
    end: usize,
) -> Box<Diagnostic> {
    let span = Span::new(value_start(text, &range, map), end);
    Box::new(
        Diagnostic::error("E1010", span, "number too large: it is not a finite value")
            .with_label("more digits than a double can hold (about 1.8e308)"),
    )
}

/// The bounds on a block's expressions (E1014): how deep its brackets
/// nest and how many operators it has, so that no later pass recurses or
/// works without end.
#[derive(Default)]
struct Bounds {
    depth: usize,
    operators: usize,
}

impl Bounds {
    /// Counts `tok`, which follows `prev` in its block.
    #[inline]
    fn count(&mut self, tok: &Tok, prev: Option<&Tok>, span: Span) -> Result<(), Box<Diagnostic>> {
        match tok {
            Tok::LBrack => {
                self.depth += 1;
                if self.depth > MAX_DEPTH {
                    return Err(too_deep(span));
                }
            }
            Tok::RBrack => self.depth = self.depth.saturating_sub(1),
            // A sign or `#` right after an address is part of a word value
            // and cannot nest.
            Tok::Plus | Tok::Minus | Tok::Hash
                if !prev.is_some_and(|t| t.is_letter() || *t == Tok::Comma) =>
            {
                self.operators += 1;
            }
            Tok::Star
            | Tok::Slash
            | Tok::And
            | Tok::Or
            | Tok::Xor
            | Tok::Mod
            | Tok::Func(_)
            | Tok::Atan => self.operators += 1,
            _ => {}
        }
        if self.operators > MAX_OPERATORS {
            return Err(too_long(span));
        }
        Ok(())
    }
}

#[cold]
fn too_deep(span: Span) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::error(
            "E1014",
            span,
            format!("brackets nested more than {MAX_DEPTH} deep"),
        )
        .with_label("too deep"),
    )
}

#[cold]
fn too_long(span: Span) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::error(
            "E1014",
            span,
            format!("expression too long: more than {MAX_OPERATORS} operators in one block"),
        )
        .with_help("split the computation over several assignments"),
    )
}

/// What a word token alone shows: a G value with more than one decimal
/// (`G1.25`, E1010) and a comma word other than `,A` `,C` `,R` (E1008).
fn check_word(
    w: WordLit,
    after_comma: bool,
    start: usize,
    end: usize,
) -> Result<(), Box<Diagnostic>> {
    if after_comma && !matches!(w.letter, b'A' | b'C' | b'R') {
        return Err(Box::new(
            Diagnostic::error(
                "E1008",
                Span::new(start, start + 1),
                format!("unknown comma word `,{}`", w.letter as char),
            )
            .with_label("only `,A`, `,C` and `,R` exist"),
        ));
    }
    if w.letter == b'G' && !after_comma && w.decimals > 1 {
        return Err(Box::new(
            Diagnostic::error(
                "E1010",
                Span::new(start, end),
                format!("G value with {} decimals", w.decimals),
            )
            .with_label("G codes have at most one decimal (`G6.2`)"),
        ));
    }
    Ok(())
}

fn bad_char(byte: u8, start: usize, end: usize) -> Diagnostic {
    let span = Span::new(start, end);
    match byte {
        b'%' => Diagnostic::error("E1001", span, "`%` is only allowed alone on its own line")
            .with_label("not allowed here"),
        _ => Diagnostic::error(
            "E1001",
            span,
            format!("character `{}` not allowed outside a comment", byte as char),
        )
        .with_label("not part of the language"),
    }
}

/// A comment may stand between words, not inside one (`X1(c)0`,
/// `X(c)10`: E1007). Tokens are lexed from the text without the comment,
/// so a comment inside a number or keyword lies inside one token's span.
fn check_comment_place(comment: &Comment, toks: &[Spanned]) -> Result<(), Box<Diagnostic>> {
    let at = comment.span.start as usize;
    let k = toks.partition_point(|t| t.0 < at);
    let inside = match (k.checked_sub(1).map(|i| &toks[i]), toks.get(k)) {
        (Some(prev), _) if prev.2 > at => true,
        (Some(prev), Some(next)) => {
            // (A `,` before a comment is left to the parser: `(a), (b)` is a
            // stray comma, not a split word.)
            let after_address = prev.1.is_letter() || prev.1 == Tok::Hash;
            let after_sign = matches!(prev.1, Tok::Plus | Tok::Minus)
                && k >= 2
                && (toks[k - 2].1.is_letter() || toks[k - 2].1 == Tok::Comma);
            let split_number = prev.1.has_number() && matches!(next.1, Tok::Num(_));
            after_address || after_sign || split_number
        }
        _ => false,
    };
    if inside {
        return Err(Box::new(
            Diagnostic::error("E1007", comment.span, "comment inside a word")
                .with_label("this comment splits a word")
                .with_help("put the comment between words"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok> {
        Tok::lexer(s.as_bytes()).map(|t| t.unwrap()).collect()
    }

    fn word(s: &[u8]) -> WordLit {
        super::word(s).unwrap()
    }

    fn number(s: &[u8]) -> NumLit {
        super::number(s).unwrap()
    }

    fn num(s: &str) -> NumLit {
        match toks(s).as_slice() {
            [Tok::Num(n)] => *n,
            other => panic!("{s}: {other:?}"),
        }
    }

    #[test]
    fn number_forms() {
        assert_eq!(
            num("30"),
            NumLit {
                value: 30.0,
                has_point: false,
                decimals: 0
            }
        );
        assert_eq!(
            num("30."),
            NumLit {
                value: 30.0,
                has_point: true,
                decimals: 0
            }
        );
        assert_eq!(
            num("30.0"),
            NumLit {
                value: 30.0,
                has_point: true,
                decimals: 1
            }
        );
        assert_eq!(
            num(".05"),
            NumLit {
                value: 0.05,
                has_point: true,
                decimals: 2
            }
        );
        assert_eq!(num("0030").value, 30.0);
        assert_eq!(num("6.2").decimals, 1);
        assert_eq!(num("13.64").value, 13.64);
        assert_eq!(num("0.1").value, 0.1);
    }

    #[test]
    fn fast_path_matches_std() {
        for s in [
            "0.1",
            "123.456",
            "99999.999",
            "1.7976931348",
            "0.000000000000001",
            "3.14159265358979",
        ] {
            assert_eq!(number(s.as_bytes()).value, s.parse::<f64>().unwrap(), "{s}");
        }
        let long = "12345678901234567890.123456789";
        assert_eq!(number(long.as_bytes()).value, long.parse::<f64>().unwrap());
    }

    #[test]
    fn no_exponent() {
        assert_eq!(
            toks("X1E5"),
            vec![Tok::Word(word(b"X1")), Tok::Word(word(b"E5"))]
        );
    }

    #[test]
    fn keywords_versus_words() {
        assert_eq!(toks("DO1")[0], Tok::Do);
        assert_eq!(toks("D01")[0], Tok::Word(word(b"D01")));
        assert_eq!(
            toks("x-.5")[0],
            Tok::Word(WordLit {
                value: -0.5,
                value_start: 1,
                letter: b'X',
                has_point: true,
                decimals: 1
            })
        );
        assert_eq!(toks("X#1")[0], Tok::Letter(b'X'));
        assert_eq!(toks("X-#1")[..2], [Tok::Letter(b'X'), Tok::Minus]);
        assert_eq!(toks("GOTO10")[0], Tok::Goto);
        assert_eq!(toks("goto10")[0], Tok::Goto);
        assert_eq!(toks("END1")[0], Tok::End);
        assert_eq!(toks("E1")[0], Tok::Word(word(b"E1")));
        assert_eq!(toks("EQ1")[0], Tok::Rel(RelOp::Eq));
        assert_eq!(toks("ANDSIN"), vec![Tok::And, Tok::Func(Func::Sin)]);
        assert_eq!(toks("ATAN"), vec![Tok::Atan]);
        assert_eq!(toks("ASIN"), vec![Tok::Func(Func::Asin)]);
        assert_eq!(toks("n10"), vec![Tok::Seq(word(b"N10"))]);
        assert_eq!(toks("N#1")[0], Tok::N);
        assert_eq!(toks("NE1")[0], Tok::Rel(RelOp::Ne));
        assert_eq!(toks("O1")[0], Tok::O);
        assert_eq!(
            toks("N10IF[#859LT300]THEN#1100=1")
                .iter()
                .filter(|t| matches!(t, Tok::If | Tok::Rel(RelOp::Lt) | Tok::Then))
                .count(),
            3
        );
    }

    #[test]
    fn malformed_numbers() {
        assert_eq!(super::number(b"1.2.3"), Err(LexError::Number));
        assert_eq!(super::number(b"."), Err(LexError::Number));
        assert_eq!(super::word(b"X1.2.3"), Err(LexError::Number));
        assert_eq!(super::word(b"X."), Err(LexError::Number));
        assert!(Tok::lexer(b"X.".as_slice()).any(|t| t.is_err()));
    }

    #[test]
    fn numbers_past_the_largest_double_are_out_of_range() {
        // f64::MAX is about 1.797e308: 309 nines exceed it, 308 do not.
        let nines = |n: usize| "9".repeat(n);
        assert_eq!(super::number(nines(309).as_bytes()), Err(LexError::Range));
        assert_eq!(
            super::word(format!("X-{}", nines(400)).as_bytes()),
            Err(LexError::Range)
        );
        assert!(super::number(nines(308).as_bytes()).is_ok());
        // 20 digits is large but finite: it stays a number.
        assert_eq!(
            super::number(b"99999999999999999999").map(|n| n.value),
            Ok(1e20)
        );
    }

    /// Lexes `text` with logos alone.
    fn by_logos(text: &[u8], map: &OffsetMap<'_>) -> Option<Vec<Spanned>> {
        let mut out = Vec::new();
        lex_tokens(text, map, 0, &mut out).ok().map(|()| out)
    }

    /// Lexes `text` with the word lexer alone.
    fn by_words(text: &[u8]) -> Option<Vec<Spanned>> {
        let mut out = Vec::new();
        lex_words(text, &OffsetMap::InPlace(0), &mut out).then_some(out)
    }

    #[test]
    fn the_word_lexer_takes_plain_blocks_only() {
        let blocks = [
            "N10 G01 X-1.5 Z2 F.2",
            "g1x1.5z-2",
            "X+1.",
            "N5",
            "G6.2 M3 S500",
            "X12345678901234.5",
        ];
        for block in blocks {
            let fast = by_words(block.as_bytes());
            assert!(fast.is_some(), "{block}");
            assert_eq!(fast, by_logos(block.as_bytes(), &OffsetMap::InPlace(0)));
        }
        // An O line, a computed word, a comma word, a keyword, a faulty
        // number, a G with two decimals, a signed N: logos's.
        // (And 16 digits, which logos reads with the standard parser.)
        let blocks = [
            "O1234",
            "X#1",
            "G01 X1,C2",
            "GOTO10",
            "X1.2.3",
            "G1.25",
            "N-1",
            "X-",
            "X1234567890123456",
        ];
        for block in blocks {
            assert_eq!(by_words(block.as_bytes()), None, "{block}");
        }
    }

    /// Bytes that make words and sequence numbers, and some that end the
    /// word lexer's part (`O`, keywords' letters, operators, a comma).
    const WORDISH: &[u8] = b"GXZNOFgxno0123456789..+-  \t,#[*EQDT";

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2048))]

        /// Where the word lexer takes a block, logos makes the same tokens
        /// of it, with the same spans, whether the text is the source's
        /// own bytes or a copy with its offset table.
        #[test]
        fn the_word_lexer_agrees_with_logos(
            text in proptest::collection::vec(proptest::sample::select(WORDISH), 0..40),
            base in 0usize..5,
            gaps in proptest::collection::vec(1u32..4, 40),
        ) {
            let offsets: Vec<u32> = gaps.iter().scan(0, |at, g| { *at += g; Some(*at) }).collect();
            for map in [OffsetMap::InPlace(base), OffsetMap::Copied(&offsets)] {
                let mut fast = Vec::new();
                if lex_words(&text, &map, &mut fast) {
                    proptest::prop_assert_eq!(by_logos(&text, &map), Some(fast));
                } else {
                    proptest::prop_assert!(fast.is_empty());
                }
            }
        }
    }

    #[test]
    fn blanks_are_skipped() {
        assert_eq!(
            toks("G01 X10\tZ-5"),
            vec![
                Tok::Word(word(b"G01")),
                Tok::Word(word(b"X10")),
                Tok::Word(word(b"Z-5"))
            ]
        );
    }
}
