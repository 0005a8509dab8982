//! The front end of gbc: bytes in, syntax tree and diagnostics out.
//!
//! [`parse`] is the only entry point; how it works can change behind it.
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
