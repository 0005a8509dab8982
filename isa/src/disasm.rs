//! The human-readable listing of a module (`gbcc -S`, golden tests).
//!
//! ```text
//! O0001:
//!   0000  loadk r0, k0 (12.5)   ; part.nc:3:1
//! N20:
//!   0001  add r3, r1, r2        ; part.nc:4:5
//! ```
//!
//! Works on unverified modules too (a dump of a bad module is what one
//! wants when debugging the compiler): missing table entries print as `?`.

use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;
use core::fmt::{self, Write};

use crate::encoding::len_to_u32;
use crate::{Module, Operand};

/// Instruction text is padded to this width before the source location, so
/// the locations line up.
const TEXT_WIDTH: usize = 21;

impl Module {
    /// The listing: a summary, then per program an `O0001:` header and its
    /// instructions (`  pc  text  ; file:line:col`), sequence numbers marked
    /// `N20:`, constants, strings and programs shown by value.
    pub fn disassemble(&self) -> String {
        let mut out = String::new();
        // Writing to a String cannot fail.
        let _ = self.write_listing(&mut out);
        out
    }

    fn write_listing(&self, out: &mut String) -> fmt::Result {
        writeln!(
            out,
            "; {} instructions, {} constants, {} strings, {} programs, {} registers",
            self.code.len(),
            self.consts.len(),
            self.strings.len(),
            self.programs.len(),
            self.num_regs
        )?;
        writeln!(out, "; machine: {:?}", self.machine)?;
        for (i, file) in self.files.iter().enumerate() {
            writeln!(
                out,
                "; file {i}: {} (crc32 {:08x})",
                Name(&file.name),
                file.hash
            )?;
        }

        let len = self.code.len();
        let mut listed = vec![false; len];
        for p in &self.programs {
            writeln!(out, "\nO{:04}:", p.number)?;
            let start = usize::try_from(p.entry).unwrap_or(usize::MAX).min(len);
            let end = usize::try_from(p.end).unwrap_or(usize::MAX).min(len);
            // Labels in pc order, for merging with the instructions.
            let mut labels: Vec<(u32, u32)> = p.seqs.iter().map(|&(n, pc)| (pc, n)).collect();
            labels.sort_unstable();
            let mut labels = labels.into_iter().peekable();
            for pc in start..end.max(start) {
                let pc32 = len_to_u32(pc);
                while let Some((_, n)) = labels.next_if(|&(at, _)| at <= pc32) {
                    writeln!(out, "N{n}:")?;
                }
                self.write_instr(out, pc)?;
                if let Some(seen) = listed.get_mut(pc) {
                    *seen = true;
                }
            }
            // Labels past the code (only in an unverified module).
            for (_, n) in labels {
                writeln!(out, "N{n}:")?;
            }
        }

        if listed.contains(&false) {
            writeln!(out, "\n; outside any program:")?;
            for (pc, _) in listed.iter().enumerate().filter(|(_, seen)| !**seen) {
                self.write_instr(out, pc)?;
            }
        }
        Ok(())
    }

    fn write_instr(&self, out: &mut String, pc: usize) -> fmt::Result {
        let Some(instr) = self.code.get(pc) else {
            return Ok(());
        };
        let mut text = String::new();
        write!(text, "{instr}")?;
        instr.try_visit_operands(|op| self.annotate(&mut text, op))?;
        write!(out, "  {pc:04}  ")?;
        match self.lines.get(pc) {
            Some(loc) => {
                let file = Name(
                    self.files
                        .get(usize::from(loc.file))
                        .map_or("?", |f| f.name.as_str()),
                );
                writeln!(out, "{text:<TEXT_WIDTH$} ; {file}:{}:{}", loc.line, loc.col)
            }
            None => writeln!(out, "{text}"),
        }
    }

    /// Shows what a table index stands for.
    fn annotate(&self, text: &mut String, op: Operand) -> fmt::Result {
        let at = |index: u32| usize::try_from(index).unwrap_or(usize::MAX);
        match op {
            Operand::Const(k) => match self.consts.get(at(k)) {
                // A NaN's payload is part of the value the VM sees.
                Some(value) if value.is_nan() => write!(text, " (NaN 0x{:016x})", value.to_bits()),
                Some(value) => write!(text, " ({value:?})"),
                None => text.write_str(" (?)"),
            },
            Operand::Str(s) => match self.strings.get(at(s)) {
                Some(s) => write!(text, " ({s:?})"),
                None => text.write_str(" (?)"),
            },
            Operand::Prog(p) => match self.programs.get(at(p)) {
                Some(p) => write!(text, " (O{:04})", p.number),
                None => text.write_str(" (?)"),
            },
            Operand::Rec(b) => self.annotate_block(text, b),
            _ => Ok(()),
        }
    }
}

impl Module {
    /// A typed block's words as G-code (`(G1 X12.5 Z-33.25 F0.2)`),
    /// each value written as the decimal-point rule reads it: with a
    /// point unless it was written without one (`X50` vs `X50.`).
    fn annotate_block(&self, text: &mut String, rec: u32) -> fmt::Result {
        let mut words = String::new();
        let mut result = Ok(());
        let found = self.block_words(rec, |w| {
            let name = crate::addr::name(w.addr).unwrap_or("?");
            let sep = if words.is_empty() { "" } else { " " };
            let value = alloc::format!("{}", w.value);
            let point = if w.flags & NO_POINT == 0 && !value.contains('.') {
                "."
            } else {
                ""
            };
            result = result.and(write!(words, "{sep}{name}{value}{point}"));
        });
        result?;
        match found {
            Some(()) => write!(text, " ({words})"),
            None => text.write_str(" (?)"),
        }
    }
}

/// `wordk`/record flag bit 0: written without a decimal point.
const NO_POINT: u8 = 1;

/// A file name as listed: control characters escaped as Rust does
/// (`\n`, `\u{1b}`), so a crafted name cannot break the listing into
/// fake lines or send escape sequences to a terminal; other text as is.
struct Name<'a>(&'a str);

impl fmt::Display for Name<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_debug())?;
            } else {
                f.write_char(c)?;
            }
        }
        Ok(())
    }
}
