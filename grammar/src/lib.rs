//! The front end of gbc: bytes in, syntax tree and diagnostics out.
//!
//! [`parse`] is the entry point, and [`parse_lines`] parses a part of a
//! file in the same way (a long program, a chunk at a time); how they work
//! can change behind them.
//! Today: `compact` cuts lines into blocks and removes blanks and comments,
//! `lexer` (logos) makes tokens with source spans, `grammar.lalrpop` (with
//! `parser`) parses blocks in batches, `errors` turns a parse failure into
//! a diagnostic, and `driver` ties them together and applies the line rules.

pub mod ast;
pub mod diag;
pub mod span;

mod compact;
mod driver;
mod errors;
mod lexer;
mod parser;

pub use ast::Ast;
pub use diag::{Diagnostic, Severity, SourceFile};
pub use span::Span;

/// Parses a whole program file.
///
/// `src` is taken as bytes (comments may hold Latin-1, GBK or UTF-8 text).
/// Every span in the tree and the diagnostics is a byte range of `src`.
/// A faulty block is reported and left out of the tree; the blocks after it
/// are still parsed, so one run reports every syntax error of the file.
/// Never panics.
pub fn parse(src: &[u8]) -> (Ast, Vec<Diagnostic>) {
    driver::parse(src)
}

/// Parses the lines of `src` from byte `start` (a line start) up to about
/// `len` bytes further: to the end of the line there, or to the end of the
/// input. Spans are byte ranges of the whole `src`. Returns the tree and
/// diagnostics of those lines, and where the next part starts (`src.len()`
/// after the last one).
///
/// Nothing carries over from one line to the next, so parsing a file part
/// by part gives, joined in order, exactly what [`parse`] gives.
pub fn parse_lines(src: &[u8], start: usize, len: usize) -> (Ast, Vec<Diagnostic>, usize) {
    driver::parse_lines(src, start, len)
}
