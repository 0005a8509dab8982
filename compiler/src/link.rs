//! Programs: splitting a file into its O programs and finding the called
//! ones in the file or in the library folders (dialect.md §1.2, §7.11).

use grammar::ast::{Ast, Block, Body, Line};
use grammar::{Diagnostic, Span};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One source file with its tree.
pub struct Unit {
    pub name: String,
    /// Shared with the unit's `SourceFile`.
    pub bytes: Arc<[u8]>,
    pub ast: Ast,
}

/// One O program: where its blocks are.
pub struct Program {
    pub number: u32,
    pub unit: usize,
    /// Indices into the unit's `ast.lines` of its blocks.
    pub blocks: Vec<usize>,
    pub span: Span,
}

/// Splits a file into programs: blocks before the first O line belong to
/// the main (first) program.
pub fn split(unit_index: usize, unit: &Unit, diags: &mut Vec<(usize, Diagnostic)>) -> Vec<Program> {
    let mut programs: Vec<Program> = Vec::new();
    // The numbers in `programs`: a search of the list per O line made a
    // file of many programs quadratic.
    let mut numbers = std::collections::HashSet::new();
    let mut before_first_o = Vec::new();
    for (i, line) in unit.ast.lines.iter().enumerate() {
        match line {
            Line::ProgramStart(p) => {
                if p.number > 9999 {
                    diags.push((
                        unit_index,
                        Diagnostic::warning(
                            "W117",
                            p.span,
                            "program number above 9999: the GSK980TDi stores O0000–O9999",
                        ),
                    ));
                }
                // Words before the first O line are a main program of
                // their own, O0000; comments or bare N blocks there just
                // lead into the first program.
                let leading = std::mem::take(&mut before_first_o);
                let blocks = if programs.is_empty() && has_words(unit, &leading) {
                    programs.push(Program {
                        number: 0,
                        unit: unit_index,
                        blocks: leading,
                        span: Span::default(),
                    });
                    numbers.insert(0);
                    Vec::new()
                } else {
                    leading
                };
                if numbers.contains(&p.number) {
                    diags.push((unit_index, defined_twice(p, &programs)));
                }
                numbers.insert(p.number);
                programs.push(Program {
                    number: p.number,
                    unit: unit_index,
                    blocks,
                    span: p.span,
                });
            }
            Line::Block(_) => match programs.last_mut() {
                Some(last) => last.blocks.push(i),
                None => before_first_o.push(i),
            },
            Line::Percent(_) => {}
        }
    }
    if programs.is_empty() {
        programs.push(Program {
            number: 0,
            unit: unit_index,
            blocks: before_first_o,
            span: Span::default(),
        });
    }
    programs
}

/// E1005 at the O line `p`, whose number `programs` already has.
fn defined_twice(p: &grammar::ast::ProgramStart, programs: &[Program]) -> Diagnostic {
    let msg = format!("program O{:04} is defined twice in this file", p.number);
    let d = Diagnostic::error("E1005", p.span, msg);
    // The main program that has no O line of its own is O0000.
    match programs.first() {
        Some(first) if p.number == 0 && first.span == Span::default() => d.with_help(
            "the blocks before the first O line are the main program, O0000: give this program another number",
        ),
        _ => d,
    }
}

fn has_words(unit: &Unit, lines: &[usize]) -> bool {
    lines
        .iter()
        .filter_map(|&l| block(unit, l))
        .any(|b| match &b.body {
            Body::Words(ws) => !ws.is_empty(),
            Body::Stmt(_) => true,
        })
}

/// The block of a program's i-th entry.
pub fn block(unit: &Unit, line: usize) -> Option<&Block> {
    match unit.ast.lines.get(line) {
        Some(Line::Block(b)) => Some(b),
        _ => None,
    }
}

/// Finds the file of program `number` in the library folders: `O` + the
/// number with or without leading zeros, with or without `.nc`, `.txt` or
/// `.ngc`, in any case.
pub fn find_library(dirs: &[PathBuf], number: u32) -> Option<PathBuf> {
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        let mut names: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        names.sort();
        if let Some(p) = names.into_iter().find(|p| names_program(p, number)) {
            return Some(p);
        }
    }
    None
}

fn names_program(path: &Path, number: u32) -> bool {
    if !path.is_file() {
        return false;
    }
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return false;
    };
    let lower = name.to_ascii_lowercase();
    let stem = [".nc", ".txt", ".ngc"]
        .iter()
        .find_map(|ext| lower.strip_suffix(ext))
        .unwrap_or(&lower);
    let Some(digits) = stem.strip_prefix('o') else {
        return false;
    };
    !digits.is_empty()
        && digits.len() <= 8
        && digits.bytes().all(|b| b.is_ascii_digit())
        && digits.parse::<u32>().ok() == Some(number)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn library_names_match_with_and_without_zeros_and_extensions() {
        let dir = std::env::temp_dir().join(format!("gbc-link-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for name in ["O1234", "o0012.NC", "O58214.nc", "O77.doc"] {
            std::fs::write(dir.join(name), b"M99\n").unwrap();
        }
        let dirs = vec![dir.clone()];
        assert!(find_library(&dirs, 1234).is_some());
        assert!(find_library(&dirs, 12).is_some());
        assert!(find_library(&dirs, 58214).is_some());
        assert!(find_library(&dirs, 77).is_none());
        assert!(find_library(&dirs, 5).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
