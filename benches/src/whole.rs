//! The whole-pipeline programs of issue #14 (the `pipeline` criterion
//! group and `peer/compare.sh` measure the same ones): source text in,
//! canon text out, as `gbcc` then `gbvm run --emit canon` do it.

use nc::{Event, Sink};
use std::fmt::Write as _;
use std::io::Write;

/// `n` G01 blocks at F100 mm/min (G98) after a rapid to X50 Z2: block `i`
/// (from 1) goes to X = i mod 50 + 0.5, Z = -(i mod 70 + 0.25), so the
/// numbers have one or two decimals and every block moves.
pub fn g1_blocks(n: usize) -> String {
    let mut s = String::with_capacity(n * 24 + 32);
    s.push_str("G98 G00 X50 Z2\n");
    for i in 1..=n {
        let _ = writeln!(s, "G01 X{}.5 Z-{}.25 F100", i % 50, i % 70);
    }
    s.push_str("M30\n");
    s
}

/// A WHILE loop of `n` iterations, each 4 assignments and a G01 whose
/// X and Z come from variables (the macro benchmark).
pub fn macro_loop(n: usize) -> String {
    format!(
        "G98 G00 X50 Z2\n#1=0\nWHILE[#1LT{n}]DO1\n#2=#1*0.001\n#3=50-#2\n#4=-#2*2\n#1=#1+1\nG01 X#3 Z#4 F100\nEND1\nM30\n"
    )
}

/// An ellipse of 3601 points by a macro: X = 2a·cos t, Z = b·sin t.
pub const ELLIPSE: &str = "#1=40\n#2=20\n#3=0\nG00 X80 Z0\nWHILE[#3LE360]DO1\nG01 X[2*#1*COS[#3]] Z[#2*SIN[#3]-20] F0.1\n#3=#3+0.1\nEND1\nM30\n";

/// Issue #17's numeric loop: `n` rounds of arithmetic, comparisons and
/// functions (one SIN, SQRT, ABS, FIX; a MOD-free IF), one move at the end.
pub fn numeric_loop(n: usize) -> String {
    format!(
        "G98 G00 X50 Z2\n#1=0\n#2=0\n#3=0\nWHILE[#1LT{n}]DO1\n#4=#1*0.001\n#2=#2+SIN[#4]*0.5-#4*0.01\nIF[#2LT-100]THEN#2=#2+100\n#3=#3+SQRT[ABS[#2]]/[#1+1]-FIX[#4]\n#1=#1+1\nEND1\nG01 X[#2] Z[-#3] F100\nM30\n"
    )
}

/// Prints each event as one canon line into a buffered writer, as
/// `gbvm run --emit canon` does; counts the lines. Write errors are
/// kept, not raised: a bench writes to a sink that cannot fail.
pub struct CanonText<W: Write> {
    out: std::io::BufWriter<W>,
    /// Lines written.
    pub lines: u64,
    /// The first write error.
    pub error: Option<std::io::Error>,
}

impl<W: Write> CanonText<W> {
    pub fn new(out: W) -> Self {
        CanonText {
            out: std::io::BufWriter::new(out),
            lines: 0,
            error: None,
        }
    }

    /// Flushes and gives back the writer (and the first error, if any).
    pub fn finish(self) -> (Option<W>, Option<std::io::Error>) {
        match self.out.into_inner() {
            Ok(w) => (Some(w), self.error),
            Err(e) => (None, self.error.or(Some(e.into_error()))),
        }
    }
}

impl<W: Write> Sink for CanonText<W> {
    fn emit(&mut self, e: Event) {
        self.lines += 1;
        if self.error.is_none() {
            if let Err(err) = writeln!(self.out, "{e}") {
                self.error = Some(err);
            }
        }
    }
}

/// The canon's line count of [`compile_and_run`] into a writer that
/// discards it; a failure stops the bench with its message.
pub fn canon_lines(src: &str, jit: jit::Mode) -> u64 {
    match compile_and_run(src, std::io::sink(), jit) {
        Ok((n, _)) => n,
        Err(e) => panic!("the bench program failed: {e}"),
    }
}

/// The whole pipeline on one source text: compile, write the module's
/// bytes, load and verify them, run on the reference machine (its loops
/// compiled as `jit` says) printing the canon into `out`. Gives the
/// canon's line count, or what failed.
pub fn compile_and_run<W: Write>(
    src: &str,
    out: W,
    jit: jit::Mode,
) -> Result<(u64, Option<W>), String> {
    let compiled = compiler::compile("bench.nc", src.as_bytes(), &compiler::Options::default());
    if compiled.has_errors() {
        return Err(compiled.render());
    }
    let bytes = compiled.module.ok_or("no module")?.to_bytes();
    let module = isa::Module::from_vec(bytes).map_err(|e| e.to_string())?;
    let mut vm = vm::Vm::new(module, nc::Machine::reference());
    // No budget: the numeric loop runs more blocks than the machine's
    // default allows (`gbvm run --max-blocks` for the same).
    vm.max_blocks = u64::MAX;
    if let Some(tier) = jit::Jit::new(jit) {
        vm.set_tier(Box::new(tier));
    }
    let mut sink = CanonText::new(out);
    let status = vm.run(&mut sink);
    let lines = sink.lines;
    match sink.finish() {
        (_, Some(e)) => Err(e.to_string()),
        (w, None) if matches!(status, vm::Status::Done) => Ok((lines, w)),
        _ => Err(format!("the run ended with {status:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The canon of a program, as text.
    fn canon(src: &str) -> String {
        match compile_and_run(src, Vec::new(), jit::Mode::Off) {
            Ok((_, Some(text))) => String::from_utf8(text).unwrap_or_default(),
            other => panic!("the program runs: {other:?}"),
        }
    }

    #[test]
    fn g1_blocks_print_one_line_per_block() {
        let text = canon(&g1_blocks(120));
        let lines: Vec<&str> = text.lines().collect();
        // RAPID, FEED, 120 LINEs, STOP: counted from the program.
        assert_eq!(lines.len(), 123);
        assert_eq!(lines[0], "RAPID X=50 Z=2");
        assert_eq!(lines[1], "FEED F=100 MODE=MIN");
        // Block 1: X 1 + 0.5, Z -(1 + 0.25); block 50: X 0 + 0.5,
        // Z -(50 + 0.25); block 71: X 21.5, Z -(1 + 0.25).
        assert_eq!(lines[2], "LINE X=1.5 Z=-1.25");
        assert_eq!(lines[51], "LINE X=0.5 Z=-50.25");
        assert_eq!(lines[72], "LINE X=21.5 Z=-1.25");
        assert_eq!(lines[122], "STOP KIND=M30");
        assert_eq!(text.matches("LINE ").count(), 120);
    }

    #[test]
    fn macro_loop_prints_one_line_per_iteration() {
        let text = canon(&macro_loop(1000));
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 1003);
        // Iteration k (from 0) moves to X = 50 - k/1000, Z = -2k/1000:
        // k = 0, then k = 999 (X 50 - 0.999, Z -1.998).
        assert_eq!(lines[2], "LINE X=50 Z=0");
        assert_eq!(lines[1001], "LINE X=49.001 Z=-1.998");
        assert_eq!(text.matches("LINE ").count(), 1000);
    }
}
