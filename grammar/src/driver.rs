//! The driver: cuts the source into lines and blocks, lexes each block, has
//! the blocks parsed, and applies the rules that span a whole line (`%`
//! lines, simulator directives, the O line).
//!
//! Blocks are parsed in batches (one LALRPOP parse for up to [`BATCH`]
//! blocks): a parse sets up and grows its stacks anew, which costs more
//! than the parsing itself for short blocks. In a batch each run of literal
//! words (`X10 Z-5 F.2`, most of any program) is handed over as one token
//! whose words the driver has built, so the parser shifts and reduces once
//! per run instead of once per word; a block that is nothing but one run
//! (after a sequence number or not) skips the parser altogether, since the
//! grammar can only make it a block of those words; such a block written
//! plainly (blanks only between words, no comment) is lexed straight from
//! the source, without compacting it first. When a batch fails,
//! its blocks are parsed again one by one from their plain tokens, so a
//! syntax error still costs only its own block and is reported exactly as
//! a single-block parse sees it (tests check that both ways give the same
//! result, on every fixture and on random text).

use crate::ast::{Addr, Ast, Block, Body, Comment, Line, ProgramStart, Seq, Word};
use crate::compact::{self, Compactor, OffsetMap, Terminator};
use crate::diag::Diagnostic;
use crate::errors;
use crate::lexer::{self, RunRef, Spanned, Tok};
use crate::parser::{self, actions, BatchParser, Parsed};
use crate::span::Span;
use std::ops::Range;

/// Blocks per batch: enough to spread the parse set-up, few enough that a
/// failed batch (parsed again block by block) costs little.
const BATCH: usize = 64;

/// Inputs from this size are parsed in two halves, one on a second
/// thread: below it, a thread costs more than it saves.
const SPLIT_BYTES: usize = 256 * 1024;

/// Parses a whole file. See [`crate::parse`].
pub fn parse(src: &[u8]) -> (Ast, Vec<Diagnostic>) {
    let limit = end_of_input(src);
    match split_point(src, limit).filter(|_| limit >= SPLIT_BYTES) {
        Some(mid) => run_halves(src, mid, limit),
        None => run(src, 0, limit, true),
    }
}

/// Parses a part of a file. See [`crate::parse_lines`].
pub fn parse_lines(src: &[u8], start: usize, len: usize) -> (Ast, Vec<Diagnostic>, usize) {
    let limit = end_of_input(src);
    let start = start.min(limit);
    let from = start.saturating_add(len).min(limit);
    let end = match memchr::memchr(b'\n', &src[from..limit]) {
        Some(lf) => from + lf + 1,
        None => limit,
    };
    let (ast, diags) = run(src, start, end, true);
    let next = if end >= limit { src.len() } else { end };
    (ast, diags, next)
}

/// Parses every block alone, without batches or word runs: the plain path
/// that the batched one must equal (tests compare them).
#[cfg(test)]
pub fn parse_unbatched(src: &[u8]) -> (Ast, Vec<Diagnostic>) {
    run(src, 0, end_of_input(src), false)
}

/// Parses in two halves whatever the size (tests compare with `parse`).
#[cfg(test)]
pub fn parse_in_halves(src: &[u8]) -> (Ast, Vec<Diagnostic>) {
    let limit = end_of_input(src);
    match split_point(src, limit) {
        Some(mid) => run_halves(src, mid, limit),
        None => run(src, 0, limit, true),
    }
}

/// Where the input ends: a Ctrl-Z as the very last byte is the DOS
/// end-of-file mark.
fn end_of_input(src: &[u8]) -> usize {
    match src.last() {
        Some(0x1A) => src.len() - 1,
        _ => src.len(),
    }
}

/// The start of a line near the middle: just after the first LF from
/// there. Every LF ends a line (comments and blocks stop at it), and
/// nothing carries over from one line to the next but the line count,
/// which only tells lines apart; so the two halves parse exactly as the
/// whole does, one after the other.
fn split_point(src: &[u8], limit: usize) -> Option<usize> {
    let half = limit / 2;
    let lf = memchr::memchr(b'\n', &src[half..limit])?;
    Some(half + lf + 1).filter(|&mid| mid < limit)
}

/// Parses `..mid` here and `mid..limit` on a second thread, and joins the
/// two in order.
/// (Without a second thread, the second half is parsed after the first.)
fn run_halves(src: &[u8], mid: usize, limit: usize) -> (Ast, Vec<Diagnostic>) {
    let ((mut ast, mut diags), (rest, more)) = std::thread::scope(|s| {
        let second = std::thread::Builder::new().spawn_scoped(s, || run(src, mid, limit, true));
        // (Room for the whole tree: the second half is appended to it.)
        let first = run_sized(src, 0, mid, lines_in(&src[..limit]), true);
        let second = match second {
            Ok(thread) => thread
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
            Err(_) => run(src, mid, limit, true),
        };
        (first, second)
    });
    ast.lines.extend(rest.lines);
    diags.extend(more);
    (ast, diags)
}

/// Parses the lines of `src[start..limit]` (`start` a line start).
fn run(src: &[u8], start: usize, limit: usize, batched: bool) -> (Ast, Vec<Diagnostic>) {
    run_sized(src, start, limit, lines_in(&src[start..limit]), batched)
}

/// About one syntax-tree line per LF: counting is cheap and saves growing
/// (copying) a large vector again and again.
fn lines_in(text: &[u8]) -> usize {
    memchr::memchr_iter(b'\n', text).count() + 1
}

/// [`run`] with room for `lines` lines of the tree.
fn run_sized(
    src: &[u8],
    start: usize,
    limit: usize,
    lines: usize,
    batched: bool,
) -> (Ast, Vec<Diagnostic>) {
    let mut driver = Driver {
        src,
        compactor: Compactor::default(),
        ast: Ast {
            lines: Vec::with_capacity(lines),
        },
        diags: Vec::new(),
        tokens: Vec::new(),
        batch: Vec::new(),
        runs: Vec::new(),
        entries: Vec::new(),
        blocks: 0,
        word_blocks: 0,
        words: Vec::new(),
        line_no: 0,
        line: LineState::default(),
        parser: BatchParser::new(),
        batched,
    };
    let mut pos = start;
    while pos < limit {
        pos = driver.line(pos, limit);
        driver.line_no += 1;
        if driver.blocks + driver.word_blocks >= BATCH {
            driver.flush();
        }
    }
    driver.flush();
    (driver.ast, driver.diags)
}

/// Something found in the file, kept in order until its batch is parsed.
enum Entry {
    /// A line of the tree that needs no parsing (`%`, only comments).
    Ready(Line),
    /// A warning or an error found before parsing (`%` text, directive).
    Note(Diagnostic),
    /// A block whose characters or tokens are faulty.
    Faulty {
        line: usize,
        after_semicolon: bool,
        diag: Diagnostic,
    },
    /// A block of literal words only (`runs[words]`), perhaps numbered:
    /// no parse needed.
    Words {
        line: usize,
        seq: Option<Seq>,
        words: Range<usize>,
        comments: Vec<Comment>,
        span: Span,
    },
    /// A block to parse: its tokens are `tokens[range]`.
    Block {
        line: usize,
        after_semicolon: bool,
        range: Range<usize>,
        comments: Vec<Comment>,
        span: Span,
    },
}

/// Where a lexed block stands: its line, whether a `;` ended the block
/// before it on that line, and its span.
#[derive(Clone, Copy)]
struct Place {
    line: usize,
    after_semicolon: bool,
    span: Span,
}

struct Driver<'src> {
    src: &'src [u8],
    compactor: Compactor,
    ast: Ast,
    diags: Vec<Diagnostic>,
    /// The tokens of the pending blocks, as lexed (a block that fails in
    /// its batch is parsed again from these).
    tokens: Vec<Spanned>,
    /// The same blocks for the batch parse: each followed by `Eob`, runs of
    /// literal words as one `Run` token...
    batch: Vec<Spanned>,
    /// ... whose words are these.
    runs: Vec<Word>,
    entries: Vec<Entry>,
    /// The number of `Entry::Block`s pending.
    blocks: usize,
    /// ... and of `Entry::Words`.
    word_blocks: usize,
    /// The words of the block being lexed in place (kept for their room).
    words: Vec<Word>,
    /// The physical line being scanned.
    line_no: usize,
    /// The line rules' state for the line of the last entry handed out.
    line: LineState,
    parser: BatchParser,
    /// Parse in batches (always, but in the tests that check batching).
    batched: bool,
}

/// What the blocks of one physical line have shown so far.
#[derive(Default)]
struct LineState {
    line_no: usize,
    /// A program start stood on this line.
    program: bool,
    /// A block with words or a statement (or a faulty one) stood on it.
    other: bool,
}

fn is_blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
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
    } else if src[end] == b'\r' && end + 1 < limit && src[end + 1] == b'\n' {
        end + 2
    } else {
        end + 1
    }
}

/// `range` without the blanks at either end.
fn trim(src: &[u8], mut range: Range<usize>) -> Range<usize> {
    while range.start < range.end && is_blank(src[range.start]) {
        range.start += 1;
    }
    while range.end > range.start && is_blank(src[range.end - 1]) {
        range.end -= 1;
    }
    range
}

/// Copies a block's tokens to `batch`, each run of literal words (`X10`,
/// `,C1`) replaced by one `Run` token whose words go to `runs`, built as
/// the grammar builds them.
fn group_words(toks: &[Spanned], batch: &mut Vec<Spanned>, runs: &mut Vec<Word>) {
    let mut run: Option<(usize, usize)> = None; // (source start, first word)
    let mut i = 0;
    while i < toks.len() {
        match literal_word(toks, i) {
            Some((w, used)) => {
                run.get_or_insert((toks[i].0, runs.len()));
                runs.push(w);
                i += used;
            }
            None => {
                end_run(&mut run, batch, runs);
                batch.push(toks[i]);
                i += 1;
            }
        }
    }
    end_run(&mut run, batch, runs);
}

/// The literal word whose tokens start at `toks[i]` (`X10`, or `,` and
/// `C1`), built as the grammar builds it, and how many tokens it took.
fn literal_word(toks: &[Spanned], i: usize) -> Option<(Word, usize)> {
    match (toks.get(i)?, toks.get(i + 1)) {
        (&(l, Tok::Word(w), r), _) => Some((
            actions::word(Addr::Letter(w.letter as char), w, Span::new(l, r)),
            1,
        )),
        (&(l, Tok::Comma, _), Some(&(_, Tok::Word(w), r))) => Some((
            actions::word(Addr::Comma(w.letter as char), w, Span::new(l, r)),
            2,
        )),
        _ => None,
    }
}

/// A block whose tokens are literal words only, after a sequence number
/// or not: what the grammar makes of it (`Block: Head Words`, the head
/// empty or `Seq`), its sequence number and words. `None` for any other
/// block, and for a faulty sequence number, which the parser reports.
fn plain_block(toks: &[Spanned]) -> Option<(Option<Seq>, Vec<Word>)> {
    let (seq, first) = match toks.first() {
        Some(&(l, Tok::Seq(w), r)) => (Some(actions::seq(w, Span::new(l, r)).ok()?), 1),
        _ => (None, 0),
    };
    if first == toks.len() {
        return None;
    }
    let mut words = Vec::with_capacity(toks.len() - first);
    let mut i = first;
    while i < toks.len() {
        let (w, used) = literal_word(toks, i)?;
        words.push(w);
        i += used;
    }
    Some((seq, words))
}

/// The block at `src[start..]` if it is literal words only, after a
/// sequence number or not, written plainly (blanks only between words, no
/// comment): its sequence number, its words (appended to `words`), its
/// span and where it ends; `None` for any other block, and for a faulty
/// sequence number, which the parser reports. The tree is the one the
/// other way (compactor, lexer, [`plain_block`]) gives: after a word's
/// digits a blank can only lead to the next word's letter (before a digit,
/// point or sign it would join the two, which the compactor does), and
/// `lexer::word_at` lexes as logos does. Each word is built as it is
/// lexed, with no token in between.
fn words_in_place(
    src: &[u8],
    start: usize,
    words: &mut Vec<Word>,
) -> Option<(Option<Seq>, Span, usize)> {
    let mut seq = None;
    let mut i = start;
    while i < src.len() {
        match src[i] {
            b' ' | b'\t' => i += 1,
            b'\n' | b'\r' | b';' => break,
            _ => {
                let (tok, end) = lexer::word_at(src, i, &OffsetMap::InPlace(0))?;
                let span = Span::new(i, end);
                match tok {
                    Tok::Word(w) => {
                        words.push(actions::word(Addr::Letter(w.letter as char), w, span));
                    }
                    // (A sequence number only heads a block.)
                    Tok::Seq(w) if seq.is_none() && words.is_empty() => {
                        seq = Some(actions::seq(w, span).ok()?);
                    }
                    _ => return None,
                }
                i = end;
            }
        }
    }
    // (A sequence number alone is the parser's, as in `plain_block`.)
    let (first, last) = (words.first()?.span, words.last()?.span);
    let head = seq.map_or(first, |s: Seq| s.span);
    Some((seq, head.to(last), i))
}

fn end_run(run: &mut Option<(usize, usize)>, batch: &mut Vec<Spanned>, runs: &[Word]) {
    if let Some((start, first)) = run.take() {
        let end = runs.last().map_or(start, |w| w.span.end as usize);
        let r = RunRef {
            start: first as u32,
            len: (runs.len() - first) as u32,
        };
        batch.push((start, Tok::Run(r), end));
    }
}

/// A block whose tokens (from `batch[first..]`) are one run of literal
/// words, after a sequence number or not: the grammar makes it a block of
/// those words and nothing else (`Block: Head Words`, the head empty or
/// `Seq`, `Words: "run"`), so the driver takes the run's words itself and
/// spares the parser the block; its tokens leave the batch. Returns the
/// sequence number and where the words are in the runs.
fn only_words(batch: &mut Vec<Spanned>, first: usize) -> Option<(Option<Seq>, Range<usize>)> {
    let (seq, r) = match batch[first..] {
        [(_, Tok::Run(r), _)] => (None, r),
        // A faulty number is left to the parser, which reports it.
        [(l, Tok::Seq(w), r), (_, Tok::Run(run), _)] => {
            (Some(actions::seq(w, Span::new(l, r)).ok()?), run)
        }
        _ => return None,
    };
    batch.truncate(first);
    let start = r.start as usize;
    Some((seq, start..start + r.len as usize))
}

impl Driver<'_> {
    /// Scans the line starting at `pos`; returns where the next one starts.
    fn line(&mut self, pos: usize, limit: usize) -> usize {
        let src = self.src;
        let first = trim(src, pos..limit).start;
        if first < limit && src[first] == b'%' {
            let end = line_end(src, first, limit);
            self.percent_line(first, end);
            return next_line(src, end, limit);
        }
        if first < limit && src[first] == b'[' && is_directive(&src[first + 1..limit]) {
            let end = line_end(src, first, limit);
            let text = trim(src, first..end);
            self.entries.push(Entry::Note(
                Diagnostic::warning("W102", Span::new(text.start, text.end), "simulator directive ignored")
                    .with_label("this line is skipped")
                    .with_note(
                        "a line starting with `[` and a letter is a simulator setting, not part of the program",
                    ),
            ));
            return next_line(src, end, limit);
        }
        let mut start = pos;
        let mut after_semicolon = false;
        loop {
            let (end, terminator) = self.block(start, limit, after_semicolon);
            match terminator {
                Terminator::Semicolon => {
                    start = end + 1;
                    after_semicolon = true;
                }
                Terminator::LineEnd => return next_line(src, end, limit),
                Terminator::Eof => return limit,
            }
        }
    }

    fn percent_line(&mut self, at: usize, end: usize) {
        self.ready(Line::Percent(Span::new(at, at + 1)));
        let rest = trim(self.src, at + 1..end);
        if !rest.is_empty() {
            self.entries.push(Entry::Note(
                Diagnostic::error(
                    "E1003",
                    Span::new(rest.start, rest.end),
                    "text after `%` on a `%` line",
                )
                .with_label("a `%` line holds nothing else")
                .with_help("put the text on a line of its own"),
            ));
        }
    }

    /// Scans and lexes the block at `start`; returns where it ends.
    fn block(&mut self, start: usize, limit: usize, after_semicolon: bool) -> (usize, Terminator) {
        // (Not in the tests' plain mode: the reference.)
        if self.batched && self.entries.is_empty() {
            if let Some(end) = self.words_in_place(start, limit) {
                return end;
            }
        }
        let scanned = self.compactor.scan(self.src, start, limit);
        let end = (scanned.end, scanned.terminator);
        let line = self.line_no;
        if let Some(diag) = scanned.error {
            self.entries.push(Entry::Faulty {
                line,
                after_semicolon,
                diag,
            });
            return end;
        }
        let Some(span) = scanned.span else {
            return end; // an empty block
        };
        if scanned.text.is_empty() {
            // Only comments: nothing to parse.
            let line = Line::Block(Block {
                delete: None,
                seq: None,
                body: Body::Words(Vec::new()),
                comments: scanned.comments,
                span,
            });
            self.ready(line);
            return end;
        }
        let first = self.tokens.len();
        let lexed = lexer::lex_block(
            scanned.text,
            scanned.map,
            &scanned.comments,
            &mut self.tokens,
        );
        // Taken out before `lexed`: `scanned` borrows the compactor.
        let comments = scanned.comments;
        let place = Place {
            line,
            after_semicolon,
            span,
        };
        match lexed {
            Ok(()) => self.lexed(first, place, comments),
            Err(diag) => self.entries.push(Entry::Faulty {
                line,
                after_semicolon,
                diag: *diag,
            }),
        }
        end
    }

    /// Files the block whose tokens start at `first`: straight into the
    /// tree, as a block of words for the batch, or as a block the grammar
    /// parses.
    fn lexed(&mut self, first: usize, place: Place, comments: Vec<Comment>) {
        let Place {
            line,
            after_semicolon,
            span,
        } = place;
        let range = first..self.tokens.len();
        // Nothing waits to be parsed before it (entries keep file order):
        // a block of literal words goes straight into the tree. (Not in the
        // tests' plain mode: the reference.)
        if self.batched && self.entries.is_empty() {
            if let Some((seq, words)) = plain_block(&self.tokens[range.clone()]) {
                self.tokens.truncate(first);
                let parsed = Parsed::Words {
                    delete: None,
                    seq,
                    words,
                };
                self.finish(parsed, line, comments, span);
                return;
            }
        }
        let batched = self.batch.len();
        group_words(&self.tokens[range.clone()], &mut self.batch, &mut self.runs);
        // (Not in the tests' plain mode: the reference to equal.)
        let words = match self.batched {
            true => only_words(&mut self.batch, batched),
            false => None,
        };
        if let Some((seq, words)) = words {
            self.word_blocks += 1;
            self.entries.push(Entry::Words {
                line,
                seq,
                words,
                comments,
                span,
            });
            return;
        }
        self.batch
            .push((span.end as usize, Tok::Eob, span.end as usize));
        self.blocks += 1;
        self.entries.push(Entry::Block {
            line,
            after_semicolon,
            range,
            comments,
            span,
        });
    }

    /// The usual block, literal words in place (`N10 G01 Z2`: blanks
    /// only between words, no comment), lexed and put into the tree in one
    /// pass over its bytes, where compacting it first and lexing the result
    /// took two; where it ends, or `None` (nothing done) for any other
    /// block ([`words_in_place`]). The words go to a buffer kept from block
    /// to block, then to a vector of their exact length: a block of the
    /// tree keeps no spare room.
    fn words_in_place(&mut self, start: usize, limit: usize) -> Option<(usize, Terminator)> {
        self.words.clear();
        let (seq, span, end) = words_in_place(&self.src[..limit], start, &mut self.words)?;
        let mut words = Vec::with_capacity(self.words.len());
        words.append(&mut self.words);
        // (Straight to the tree: a block of words is no program number.)
        let block = Block {
            delete: None,
            seq,
            body: Body::Words(words),
            comments: Vec::new(),
            span,
        };
        self.push_block(block, self.line_no);
        Some((end, compact::terminator_at(self.src, end, limit)))
    }

    /// A line of the tree that needs no parsing: straight in when nothing
    /// waits before it.
    fn ready(&mut self, line: Line) {
        if self.entries.is_empty() {
            self.ast.lines.push(line);
        } else {
            self.entries.push(Entry::Ready(line));
        }
    }

    /// Parses the pending blocks and hands every pending entry out in order.
    fn flush(&mut self) {
        let mut batch = None;
        if self.blocks > 0 && self.batched {
            let tokens = self.batch.iter().map(|&t| Ok::<_, Box<Diagnostic>>(t));
            if let Ok(parsed) = self.parser.parse(&self.runs, tokens) {
                if parsed.len() == self.blocks {
                    batch = Some(parsed.into_iter());
                }
            }
        }
        let mut entries = std::mem::take(&mut self.entries);
        for entry in entries.drain(..) {
            match entry {
                Entry::Ready(line) => self.ast.lines.push(line),
                Entry::Note(d) => self.diags.push(d),
                Entry::Faulty {
                    line,
                    after_semicolon,
                    diag,
                } => {
                    self.line_state(line).other = true;
                    self.report(diag, after_semicolon);
                }
                Entry::Words {
                    line,
                    seq,
                    words,
                    comments,
                    span,
                } => {
                    let words = self.runs.get(words).unwrap_or_default().to_vec();
                    let parsed = Parsed::Words {
                        delete: None,
                        seq,
                        words,
                    };
                    self.finish(parsed, line, comments, span);
                }
                Entry::Block {
                    line,
                    after_semicolon,
                    range,
                    comments,
                    span,
                } => {
                    let parsed = match batch.as_mut().and_then(|b| b.next()) {
                        Some(p) => Ok(p),
                        None => self.parse_one(&range),
                    };
                    match parsed {
                        Ok(p) => self.finish(p, line, comments, span),
                        Err(d) => {
                            self.line_state(line).other = true;
                            self.report(*d, after_semicolon);
                        }
                    }
                }
            }
        }
        // Keep the buffers' capacity for the next batch.
        self.entries = entries;
        self.tokens.clear();
        self.batch.clear();
        self.runs.clear();
        self.blocks = 0;
        self.word_blocks = 0;
    }

    /// Parses one block alone (a failed batch), converting its fault.
    fn parse_one(&self, range: &Range<usize>) -> Result<Parsed, Box<Diagnostic>> {
        let toks = &self.tokens[range.clone()];
        parser::parse_block(&self.parser, toks)
            .map_err(|e| Box::new(errors::convert(e, toks, self.src, &self.parser)))
    }

    fn line_state(&mut self, line: usize) -> &mut LineState {
        if self.line.line_no != line {
            self.line = LineState {
                line_no: line,
                ..LineState::default()
            };
        }
        &mut self.line
    }

    /// Adds a parsed block to the tree, after the O-line rules: a program
    /// number stands on its own line, with only comments beside it.
    fn finish(&mut self, parsed: Parsed, line: usize, comments: Vec<Comment>, span: Span) {
        let (delete, seq, body) = match parsed {
            Parsed::Program { number } => {
                let state = self.line_state(line);
                if state.other {
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
                state.program = true;
                self.ast.lines.push(Line::ProgramStart(ProgramStart {
                    number,
                    comments,
                    span,
                }));
                return;
            }
            Parsed::Words { delete, seq, words } => (delete, seq, Body::Words(words)),
            Parsed::Stmt { delete, seq, stmt } => (delete, seq, Body::Stmt(stmt)),
        };
        let block = Block {
            delete,
            seq,
            body,
            comments,
            span,
        };
        self.push_block(block, line);
    }

    /// Adds a block of `line` to the tree, unless a program number stands
    /// before it on that line.
    fn push_block(&mut self, block: Block, line: usize) {
        let state = self.line_state(line);
        state.other = true;
        if state.program {
            self.diags.push(
                Diagnostic::error(
                    "E1004",
                    block.span,
                    "the O line holds only the program number and comments",
                )
                .with_label("a block after the program number")
                .with_help("start a new line for this block"),
            );
            return;
        }
        self.ast.lines.push(Line::Block(block));
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
        if d.code == "E1010" && d.help.is_none() && spelled.iter().any(|&b| is_blank(b)) {
            let joined = crate::diag::quote(
                spelled
                    .iter()
                    .filter(|&&b| !is_blank(b))
                    .map(|&b| (b as char).to_ascii_uppercase()),
            );
            d.help = Some(format!(
                "blanks are ignored, even inside numbers: this reads `{joined}`; is an address letter missing?"
            ));
        }
        self.diags.push(d);
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// Every fixture, corpus and conformance file parses the same in
    /// batches (with word runs) as block by block.
    #[test]
    fn batches_equal_single_blocks() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let dirs = [
            root.join("tests/data/ok"),
            root.join("tests/data/err"),
            root.join("../../shared/corpus/public"),
            root.join("../../shared/conformance"),
        ];
        let mut files = 0;
        for dir in dirs {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for entry in entries.flatten() {
                let bytes = std::fs::read(entry.path()).unwrap();
                let batched = super::parse(&bytes);
                let single = super::parse_unbatched(&bytes);
                assert!(batched == single, "{}", entry.path().display());
                let halves = super::parse_in_halves(&bytes);
                assert!(halves == single, "halves: {}", entry.path().display());
                for len in [0, 7, 100] {
                    let parts = in_parts(&bytes, len);
                    assert!(
                        parts == single,
                        "parts of {len}: {}",
                        entry.path().display()
                    );
                }
                files += 1;
            }
        }
        assert!(files > 40, "only {files} files");
    }

    /// A file parsed with `parse_lines`, `len` bytes at a time, joined.
    fn in_parts(src: &[u8], len: usize) -> (super::Ast, Vec<super::Diagnostic>) {
        let (mut ast, mut diags) = (super::Ast { lines: Vec::new() }, Vec::new());
        let mut start = 0;
        while start < src.len() {
            let (part, found, next) = super::parse_lines(src, start, len);
            assert!(next > start, "no progress at {start}");
            ast.lines.extend(part.lines);
            diags.extend(found);
            start = next;
        }
        (ast, diags)
    }

    const WORDISH: &[u8] = b"GXZNFgxzn0123456789..+-   \t\n\n\r;()O,#/";

    const ALPHABET: &[u8] = b"GXZNOF#[]=+-*/.,;()% \n\r0123456789EQIFTHENGOTODOWHILESIN\x1a";

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// Random G-code-like text, faults included, parses the same both ways.
        #[test]
        fn batches_equal_single_blocks_on_random_text(
            src in proptest::collection::vec(proptest::sample::select(ALPHABET), 0..300),
            len in 0usize..40,
        ) {
            let single = super::parse_unbatched(&src);
            proptest::prop_assert!(super::parse(&src) == single);
            proptest::prop_assert!(super::parse_in_halves(&src) == single);
            proptest::prop_assert!(in_parts(&src, len) == single);
        }

        /// Text mostly of literal words, upper and lower case, blanks and
        /// tabs between and inside them, comments, `;` and line ends: the
        /// blocks the driver lexes in place parse as the plain path
        /// parses them, and so do the ones it leaves to the compactor.
        #[test]
        fn words_in_place_parse_as_the_plain_path(
            src in proptest::collection::vec(proptest::sample::select(WORDISH), 0..300),
        ) {
            proptest::prop_assert!(super::parse(&src) == super::parse_unbatched(&src));
        }
    }
}
