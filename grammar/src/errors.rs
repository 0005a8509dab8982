//! The one place where a parse failure becomes a diagnostic.
//!
//! LALRPOP reports the token it could not use and the terminals it
//! expected; the dialect wants codes that name the real fault (a word
//! without value is E1007, a letter pair E1008, words mixed with a
//! statement E1013, an expression fault E1014 …). [`convert`] looks at the
//! offending token, its neighbours and the expected set to pick the code,
//! labels the exact span, adds "expected one of …" and a help line where a
//! likely fix exists. Only failing blocks come here, so it may take its
//! time (it even re-parses a prefix of the block to see whether a complete
//! block stands before the fault).

use crate::diag::Diagnostic;
use crate::lexer::{func_name, Spanned, Tok};
use crate::parser::{self, BatchParser, PError};
use crate::span::Span;
use lalrpop_util::ParseError;

/// Turns any parse error of the block `toks` into a diagnostic.
pub fn convert(err: PError, toks: &[Spanned], src: &[u8], parser: &BatchParser) -> Diagnostic {
    match err {
        ParseError::User { error } => *error,
        ParseError::InvalidToken { location } => Diagnostic::error(
            "E1001",
            Span::new(location, location + 1),
            "character not allowed here",
        ),
        ParseError::ExtraToken { token: (l, t, r) } => Diagnostic::error(
            "E1008",
            Span::new(l, r),
            format!("unexpected {}", t.describe()),
        ),
        ParseError::UnrecognizedToken {
            token: (_, Tok::Eob, _),
            expected,
        } => Fault::new(toks, toks.len(), &expected, src, parser).diagnose(),
        ParseError::UnrecognizedToken {
            token: (l, _, _),
            expected,
        } => {
            let at = toks.partition_point(|t| t.0 < l);
            Fault::new(toks, at, &expected, src, parser).diagnose()
        }
        ParseError::UnrecognizedEof { expected, .. } => {
            Fault::new(toks, toks.len(), &expected, src, parser).diagnose()
        }
    }
}

/// A parse failure at token `at` (`toks.len()` for the end of the block).
struct Fault<'a> {
    toks: &'a [Spanned],
    at: usize,
    expected: Vec<&'a str>,
    src: &'a [u8],
    parser: &'a BatchParser,
}

#[derive(PartialEq, Eq, Clone, Copy)]
enum Kind {
    /// `O1234` / `:1234`.
    Program,
    /// NC words (or nothing yet).
    Words,
    /// A macro statement.
    Stmt,
}

impl<'a> Fault<'a> {
    fn new(
        toks: &'a [Spanned],
        at: usize,
        expected: &'a [String],
        src: &'a [u8],
        parser: &'a BatchParser,
    ) -> Fault<'a> {
        let mut names: Vec<&str> = expected.iter().map(|e| e.trim_matches('"')).collect();
        names.sort_unstable();
        names.dedup();
        Fault {
            toks,
            at,
            expected: names,
            src,
            parser,
        }
    }

    fn tok(&self, i: usize) -> Option<Tok> {
        self.toks.get(i).map(|t| t.1)
    }

    fn span(&self, i: usize) -> Span {
        match self.toks.get(i) {
            Some(t) => Span::new(t.0, t.2),
            // The end of the block: just after its last token.
            None => match self.toks.last() {
                Some(t) => Span::new(t.2, t.2),
                None => Span::default(),
            },
        }
    }

    /// The source text of `span` as a message quotes it: without blanks,
    /// in upper case, clipped when long.
    fn text(&self, span: Span) -> String {
        let bytes = self.src.get(span.range()).unwrap_or_default();
        crate::diag::quote(
            bytes
                .iter()
                .filter(|b| !b.is_ascii_whitespace())
                .map(|&b| (b as char).to_ascii_uppercase()),
        )
    }

    fn expects(&self, name: &str) -> bool {
        self.expected.contains(&name)
    }

    /// Index of the first token of the body (after `/`, `/n` and `N n`).
    fn body_start(&self) -> usize {
        let mut i = 0;
        if self.tok(i) == Some(Tok::Slash) {
            i += 1;
            if matches!(self.tok(i), Some(Tok::Num(_))) {
                i += 1;
            }
        }
        if matches!(self.tok(i), Some(Tok::Seq(_))) {
            i += 1;
        }
        i
    }

    /// Token `at` stands where a sequence number may: first, or after `/n`.
    fn may_start_seq(&self, at: usize) -> bool {
        match at {
            0 => true,
            1 => self.tok(0) == Some(Tok::Slash),
            2 => self.tok(0) == Some(Tok::Slash) && matches!(self.tok(1), Some(Tok::Num(_))),
            _ => false,
        }
    }

    fn kind(&self) -> Kind {
        match self.tok(0) {
            Some(Tok::O | Tok::Colon) => Kind::Program,
            _ => match self.tok(self.body_start()) {
                Some(t) if t.starts_statement() => Kind::Stmt,
                _ => Kind::Words,
            },
        }
    }

    /// Bracket depth just before token `i`.
    fn depth(&self, i: usize) -> usize {
        self.toks[..i.min(self.toks.len())]
            .iter()
            .fold(0usize, |d, t| match t.1 {
                Tok::LBrack => d + 1,
                Tok::RBrack => d.saturating_sub(1),
                _ => d,
            })
    }

    /// Do the tokens before the fault form a complete block on their own?
    fn prefix_parses(&self) -> bool {
        self.at > 0 && parser::parse_block(self.parser, &self.toks[..self.at]).is_ok()
    }

    /// Tokens `start..end` are letters standing directly next to each other
    /// (the last may be a word token: `GX10` is `G` and `X10`).
    fn letter_run(&self, i: usize) -> (usize, usize) {
        let adjacent = |a: usize, b: usize| self.toks[a].2 == self.toks[b].0;
        let is_letter = |k: usize| self.toks.get(k).is_some_and(|t| t.1.is_letter());
        let is_word =
            |k: usize| matches!(self.toks.get(k), Some((_, Tok::Word(_) | Tok::Seq(_), _)));
        let mut start = i;
        while start > 0 && is_letter(start - 1) && adjacent(start - 1, start) {
            start -= 1;
        }
        let mut end = i + 1;
        if !is_word(i) {
            while (is_letter(end) || is_word(end)) && adjacent(end - 1, end) {
                end += 1;
                if is_word(end - 1) {
                    break;
                }
            }
        }
        (start, end)
    }

    /// The letters of a run (of a word token, only its letter).
    fn run_span(&self, start: usize, end: usize) -> Span {
        let last = match self.toks[end - 1] {
            (l, Tok::Word(_) | Tok::Seq(_), _) => Span::new(l, l + 1),
            _ => self.span(end - 1),
        };
        self.span(start).to(last)
    }

    fn expected_note(&self) -> Option<String> {
        // ("run" is the batch parser's grouping of words: "a word" says it.)
        let mut human: Vec<String> = self
            .expected
            .iter()
            .filter(|e| **e != "run")
            .map(|e| human_name(e))
            .collect();
        // After a bare address (`X`, `X-`) a number is welcome too: the
        // lexer would have made `X10` one word token, so the parser never
        // lists it.
        let bare_address = match self.at.checked_sub(1).and_then(|i| self.tok(i)) {
            Some(t) if t.is_letter() => true,
            Some(Tok::Plus | Tok::Minus) => {
                self.at >= 2 && self.tok(self.at - 2).is_some_and(|t| t.is_letter())
            }
            _ => false,
        };
        if bare_address && !self.expects("number") {
            human.push("a number".into());
        }
        (!human.is_empty()).then(|| format!("expected one of: {}", human.join(", ")))
    }

    fn diagnose(&self) -> Diagnostic {
        let d = self.classify();
        // A bare `N` fails as a token of its own: what was missing is its
        // digits, not any of the tokens that could start a block.
        let note = if self.tok(self.at) == Some(Tok::N) && self.may_start_seq(self.at) {
            Some("expected one of: digits after `N`".to_string())
        } else {
            self.expected_note()
        };
        match note {
            Some(note) => d.with_note(note),
            None => d,
        }
    }

    fn classify(&self) -> Diagnostic {
        let at = self.at;
        let tok = self.tok(at);
        let prev = at.checked_sub(1).and_then(|i| self.tok(i));
        let here = self.span(at);
        let kind = self.kind();
        let described = tok.map_or("end of block".to_string(), |t| t.describe());

        if kind == Kind::Program {
            return self.program_fault();
        }

        // `/#1 G00…` or `/[1] G00…`: a switch number that is not a literal
        // (dialect.md §7.6). (`/#1=5` is an optional assignment.)
        let words_follow = tok.is_some_and(|t| t.is_letter() || matches!(t, Tok::Word(_)));
        let variable_switch = self.tok(1) == Some(Tok::Hash) && words_follow;
        if self.tok(0) == Some(Tok::Slash)
            && (variable_switch || (at == 1 && tok == Some(Tok::LBrack)))
        {
            let last = if variable_switch { at - 1 } else { at };
            let span = self.span(0).to(self.span(last));
            return Diagnostic::error(
                "E1015",
                span,
                "the block-delete switch cannot be a variable or an expression",
            )
            .with_label("`/` takes no number or a literal 1 … 9")
            .with_help(
                "write `/` or `/n` with n a digit; to skip blocks by a variable, use `IF[…]GOTOn`",
            );
        }

        if let Some(t) = tok {
            if t.is_letter() || matches!(t, Tok::Word(_) | Tok::Seq(_)) {
                if let Some(d) = self.letter_fault(at) {
                    return d;
                }
            }
        }

        if prev == Some(Tok::Comma) {
            return Diagnostic::error(
                "E1008",
                self.span(at - 1),
                "`,` not followed by `A`, `C` or `R`",
            )
            .with_label("a comma word is `,A`, `,C` or `,R` and a number");
        }

        if prev == Some(Tok::Slash) && self.expected == ["["] {
            return Diagnostic::error("E1014", here, "`ATAN[a]/` must be followed by `[b]`")
                .with_label("not in brackets")
                .with_help("write `ATAN[a]/[b]`, or `[ATAN[a]]/b` to divide");
        }

        match tok {
            Some(Tok::Slash) if kind == Kind::Words && self.depth(at) == 0 => {
                return Diagnostic::error("E1015", here, "`/` not at the start of the block")
                    .with_label("block delete must come first")
                    .with_help("move `/` to the start of the block");
            }
            // `N` without digits: a sequence number is `N` and digits, one
            // token, so the parser fails at the `N` itself.
            Some(Tok::N) if self.may_start_seq(at) => {
                let next = self.toks.get(at + 1);
                return match next {
                    None => Diagnostic::error("E1007", here, "`N` has no value")
                        .with_label("a sequence number needs digits"),
                    Some(&(l, t, _))
                        if l == self.toks[at].2
                            && (t.is_letter() || matches!(t, Tok::Word(_) | Tok::Seq(_))) =>
                    {
                        match self.letter_fault(at + 1) {
                            Some(d) => d,
                            None => Diagnostic::error("E1007", here, "`N` has no value"),
                        }
                    }
                    Some(_) => Diagnostic::error(
                        "E1006",
                        self.span(at + 1),
                        "a sequence number must be a literal integer",
                    )
                    .with_label("N cannot take a variable or an expression"),
                };
            }
            Some(Tok::N | Tok::Seq(_)) => {
                return Diagnostic::error("E1006", here, "`N` must be the first word of the block")
                    .with_label("sequence number after other words")
                    .with_help("move the sequence number to the start of the block");
            }
            Some(Tok::O | Tok::Colon) => {
                return Diagnostic::error(
                    "E1004",
                    here,
                    "a program number must stand on its own line",
                )
                .with_label("program number inside a block");
            }
            Some(Tok::Rel(_)) => return self.relop_fault(at),
            _ => {}
        }

        match prev {
            Some(Tok::Func(_) | Tok::Atan) if tok != Some(Tok::LBrack) => {
                let name = self.text(self.span(at - 1));
                return Diagnostic::error(
                    "E1014",
                    self.span(at - 1),
                    format!("`{name}` without its argument in brackets"),
                )
                .with_label("a function takes `[expr]`")
                .with_help(format!("write `{name}[…]`"));
            }
            Some(Tok::Goto) => {
                return Diagnostic::error("E1014", here, "GOTO without a target")
                    .with_label(format!("{described} after GOTO"))
                    .with_help("write `GOTOn`, `GOTO#i` or `GOTO[expr]`");
            }
            _ => {}
        }
        if self.expects("=") && !self.expects("]") {
            return Diagnostic::error("E1014", here, "a variable must be followed by `=`")
                .with_label(format!("{described} after the variable"))
                .with_help("a statement that starts with `#` is an assignment: `#i=expr`");
        }

        if prev == Some(Tok::Then) {
            return Diagnostic::error("E1013", here, "only an assignment may follow THEN")
                .with_label(format!("{described} after THEN"))
                .with_help("write `IF[…]THEN#i=…`, or `IF[…]GOTOn` to jump");
        }

        let body = self.tok(self.body_start());
        let after_then = (self.body_start()..at).any(|i| self.tok(i) == Some(Tok::Then));
        if body == Some(Tok::If) && after_then && tok == Some(Tok::Hash) && self.depth(at) == 0 {
            return Diagnostic::error("E1013", here, "only one assignment may follow THEN")
                .with_label("a second statement after THEN's assignment")
                .with_help(
                    "put it in a block of its own, or skip a group of blocks with `IF[…]GOTOn`",
                );
        }
        if body == Some(Tok::If) && (self.expects("GOTO") || self.expects("THEN")) {
            let help = match tok {
                Some(Tok::Hash) => "write THEN before the assignment: `IF[…]THEN#i=…`",
                Some(Tok::Num(_)) => "write GOTO before the sequence number: `IF[…]GOTOn`",
                Some(Tok::And | Tok::Or | Tok::Xor) => {
                    "combine conditions inside one pair of brackets: `IF[[c1]AND[c2]]`"
                }
                _ => "add `GOTO n` or `THEN #i=…` after the condition",
            };
            return Diagnostic::error("E1014", here, "IF without GOTO or THEN")
                .with_label(format!("{described} after the condition"))
                .with_help(help);
        }
        if body == Some(Tok::While) && self.expects("DO") {
            return Diagnostic::error("E1014", here, "WHILE without DO")
                .with_label(format!("{described} after the condition"))
                .with_help("write `WHILE[…]DOm`");
        }

        // NC words and a macro statement in one block (E1013).
        let mixed = match (kind, tok) {
            (Kind::Words, Some(t)) => t.starts_statement() && self.depth(at) == 0,
            (Kind::Stmt, Some(t)) => {
                (t.is_letter() || matches!(t, Tok::Word(_) | Tok::Seq(_) | Tok::Comma))
                    && self.prefix_parses()
            }
            _ => false,
        };
        if mixed {
            let span = here.to(self.span(self.toks.len() - 1));
            return Diagnostic::error("E1013", span, "NC words and a macro statement in one block")
                .with_label(if kind == Kind::Words {
                    "a macro statement after NC words"
                } else {
                    "NC words after a macro statement"
                })
                .with_help("put the macro statement in a block of its own");
        }

        if tok == Some(Tok::RBrack) {
            let message = if self.depth(at) == 0 {
                "`]` without `[`"
            } else if prev == Some(Tok::LBrack) {
                "empty brackets"
            } else {
                "unexpected `]`"
            };
            return Diagnostic::error("E1014", here, message).with_label("here");
        }
        if tok.is_none() && self.expects("]") {
            let open = self.unclosed_bracket().unwrap_or(here);
            return Diagnostic::error("E1014", open, "`[` not closed")
                .with_label("this `[` has no `]`");
        }

        if kind == Kind::Words && self.depth(at) == 0 {
            return self.word_fault(at).unwrap_or_else(|| {
                Diagnostic::error("E1008", here, format!("unexpected {described}"))
                    .with_label("not a word")
            });
        }
        Diagnostic::error(
            "E1014",
            here,
            format!("expression syntax: unexpected {described}"),
        )
        .with_label("here")
    }

    /// The O line: `O` + digits, nothing else but comments (E1004).
    fn program_fault(&self) -> Diagnostic {
        let at = self.at;
        if at <= 1 {
            return match self.tok(1) {
                None => Diagnostic::error("E1004", self.span(0), "program number missing")
                    .with_label("digits must follow"),
                Some(_) => Diagnostic::error(
                    "E1004",
                    self.span(1),
                    "a program number must be a literal number",
                )
                .with_label("not digits"),
            };
        }
        let span = self.span(at).to(self.span(self.toks.len() - 1));
        Diagnostic::error(
            "E1004",
            span,
            "the O line holds only the program number and comments",
        )
        .with_label("other words on the O line")
        .with_help("start a new line for these words")
    }

    /// A letter where it cannot stand: a letter pair, an unknown function,
    /// a word whose value is missing.
    fn letter_fault(&self, at: usize) -> Option<Diagnostic> {
        let (start, end) = self.letter_run(at);
        let run = self.run_span(start, end);
        let name = self.text(run);
        if end - start >= 2 && self.tok(end) == Some(Tok::LBrack) {
            let known: Vec<&str> = FUNCS.iter().map(|f| func_name(*f)).collect();
            return Some(
                Diagnostic::error("E1014", run, format!("unknown function `{name}`"))
                    .with_label("not a function of this dialect")
                    .with_note(format!(
                        "the functions are {} and ATAN[a]/[b]",
                        known.join(" ")
                    )),
            );
        }
        if start == at {
            return None;
        }
        let prev = at - 1;
        if !self.toks[prev].1.is_letter() {
            return None;
        }
        if self.toks[prev].2 != self.toks[at].0 {
            // A blank stood between the letters: `G X10` is `G` without value.
            let letter = self.text(self.span(prev));
            return Some(
                Diagnostic::error("E1007", self.span(prev), format!("`{letter}` has no value"))
                    .with_label("a word needs a number, `#n` or `[expr]`"),
            );
        }
        // DT and DC exist only as PLC parameter addresses of G10 L52
        // (seed 000): valid codes that are not supported yet (dialect.md §8.2).
        if name.eq_ignore_ascii_case("DT") || name.eq_ignore_ascii_case("DC") {
            return Some(Diagnostic::error(
                "E2099",
                run,
                format!("PLC parameters ({name}) in G10 L52 are not implemented yet"),
            ));
        }
        let mut d = Diagnostic::error(
            "E1008",
            run,
            format!("`{name}` is not an address or a keyword"),
        )
        .with_label("a letter must be followed by its value");
        // `TO303`, `GO X1`: the letter O typed for the digit 0.
        if end - start == 2 && self.tok(at) == Some(Tok::O) {
            let digits = match self.toks.get(at + 1) {
                Some(&(l, Tok::Num(_), r)) if l == self.toks[at].2 => self.text(Span::new(l, r)),
                _ => String::new(),
            };
            let letter = self.text(self.span(prev));
            d = d.with_help(format!(
                "did you mean `{letter}0{digits}`? (the letter O is not the digit 0)"
            ));
        }
        Some(d)
    }

    fn relop_fault(&self, at: usize) -> Diagnostic {
        let in_condition = self.toks[..at]
            .iter()
            .any(|t| matches!(t.1, Tok::If | Tok::While))
            && self.depth(at) > 0;
        let name = self.text(self.span(at));
        if in_condition {
            Diagnostic::error(
                "E1014",
                self.span(at),
                "one relational operator per condition",
            )
            .with_label(format!("a second `{name}`"))
            .with_help("combine conditions: `[[a EQ b] AND [c EQ d]]`")
        } else {
            Diagnostic::error(
                "E1014",
                self.span(at),
                format!("relational operator `{name}` outside an IF or WHILE condition"),
            )
            .with_label("only allowed in `IF[…]` and `WHILE[…]`")
        }
    }

    /// Faults in the value of a word: `X`, `X-`, `X--1`, `28U0`, `S1=500`.
    fn word_fault(&self, at: usize) -> Option<Diagnostic> {
        let tok = self.tok(at);
        let prev = at.checked_sub(1).and_then(|i| self.tok(i));
        // The address whose value is being read, if any.
        let address = match prev {
            Some(t) if t.is_letter() => Some(at - 1),
            Some(Tok::Plus | Tok::Minus)
                if at >= 2 && self.tok(at - 2).is_some_and(|t| t.is_letter()) =>
            {
                Some(at - 2)
            }
            _ => None,
        };
        if let Some(a) = address {
            return Some(self.value_fault(a, at));
        }
        // `X#814+.1`: an expression as a word value needs brackets.
        if let Some(
            t @ (Tok::Plus
            | Tok::Minus
            | Tok::Star
            | Tok::Slash
            | Tok::And
            | Tok::Or
            | Tok::Xor
            | Tok::Mod),
        ) = tok
        {
            if let Some(d) = self.unbracketed_value(at, t) {
                return Some(d);
            }
        }
        self.without_address(at)
    }

    /// The value of the word at address token `a` is faulty at token `at`:
    /// a second sign, or no value.
    fn value_fault(&self, a: usize, at: usize) -> Diagnostic {
        let here = self.span(at);
        let comma = a > 0 && self.tok(a - 1) == Some(Tok::Comma);
        let start = if comma { a - 1 } else { a };
        let name = self.text(self.span(start).to(self.span(a)));
        let span = self.span(start).to(self.span(at - 1));
        match self.tok(at) {
            Some(Tok::Plus | Tok::Minus) => Diagnostic::error(
                "E1007",
                span.to(here),
                "malformed number: more than one sign",
            )
            .with_label("one sign at most"),
            _ if comma => {
                Diagnostic::error("E1007", span, format!("`{name}` needs a literal number"))
                    .with_label("a comma word takes a number")
            }
            _ => Diagnostic::error("E1007", span, format!("`{name}` has no value"))
                .with_label("a word needs a number, `#n` or `[expr]`"),
        }
    }

    /// E1014 where operator `t` at token `at` continues a word's value
    /// without brackets (`X#814+.1`).
    fn unbracketed_value(&self, at: usize, t: Tok) -> Option<Diagnostic> {
        let mut k = at;
        while k > 0 && matches!(self.tok(k - 1), Some(Tok::Num(_) | Tok::Hash)) {
            k -= 1;
        }
        let signed = k > 0 && matches!(self.tok(k - 1), Some(Tok::Plus | Tok::Minus));
        let letter = if signed {
            k.checked_sub(2)
        } else {
            k.checked_sub(1)
        };
        let l = letter.filter(|&l| k < at && self.tok(l).is_some_and(|t| t.is_letter()))?;
        let end = self.unbracketed_end(at);
        let value = self.text(self.span(l + 1).to(self.span(end)));
        let name = self.text(self.span(l));
        Some(
            Diagnostic::error(
                "E1014",
                self.span(at),
                format!("{} in a word value without brackets", t.describe()),
            )
            .with_label("a word takes `#n` or `[expr]`")
            .with_help(format!("write `{name}[{value}]`")),
        )
    }

    /// E1008: a number, `=`, sign, `#` or `[` where a word's address
    /// should be.
    fn without_address(&self, at: usize) -> Option<Diagnostic> {
        let here = self.span(at);
        match self.tok(at) {
            Some(Tok::Num(_)) => Some(
                Diagnostic::error(
                    "E1008",
                    here,
                    format!("number `{}` without an address letter", self.text(here)),
                )
                .with_label("which address?"),
            ),
            Some(Tok::Assign) => Some(
                Diagnostic::error("E1008", here, "`=` after a word")
                    .with_label("only a variable `#n` can be assigned")
                    .with_note("`S1=500` and the like belong to other controls"),
            ),
            Some(t @ (Tok::Plus | Tok::Minus | Tok::Hash | Tok::LBrack)) => Some(
                Diagnostic::error(
                    "E1008",
                    here,
                    format!("{} without an address letter", t.describe()),
                )
                .with_label("a value needs its address"),
            ),
            _ => None,
        }
    }

    /// The last token of an expression written without brackets from
    /// token `at` on: up to the next address letter or the end.
    fn unbracketed_end(&self, at: usize) -> usize {
        let mut end = at;
        while end + 1 < self.toks.len()
            && !matches!(
                self.toks[end + 1].1,
                Tok::Letter(_) | Tok::N | Tok::O | Tok::Word(_) | Tok::Seq(_) | Tok::Comma
            )
        {
            end += 1;
        }
        end
    }

    /// The innermost `[` still open at the end of the block.
    fn unclosed_bracket(&self) -> Option<Span> {
        let mut open = Vec::new();
        for (i, t) in self.toks.iter().enumerate() {
            match t.1 {
                Tok::LBrack => open.push(i),
                Tok::RBrack => {
                    open.pop();
                }
                _ => {}
            }
        }
        open.last().map(|&i| self.span(i))
    }
}

const FUNCS: [crate::ast::Func; 15] = {
    use crate::ast::Func::*;
    [
        Sin, Cos, Tan, Asin, Acos, Atan, Sqrt, Abs, Round, Fix, Fup, Ln, Exp, Bin, Bcd,
    ]
};

/// A reader's name for a terminal of the grammar.
fn human_name(terminal: &str) -> String {
    match terminal {
        "letter" => "an address letter".into(),
        "number" => "a number".into(),
        "relop" => "a relational operator".into(),
        "func" => "a function".into(),
        "eob" => "end of block".into(),
        "word" => "a word (`X10`)".into(),
        "seq" => "a sequence number (`N10`)".into(),
        other => format!("`{other}`"),
    }
}
