//! The run of a program with macros, made at compile time: W124.
//!
//! A static program is dry-run through the kernel (`check`), and a
//! geometry fault in it is a compile error. A program with macros may
//! reach a block with other values, so its faults stay run-time alarms
//! (dialect.md §0). Yet a `gbvm run` depends on nothing but the module
//! and the machine file: the host's inputs, the clock, the offsets and
//! the block-skip switches all start as the machine file sets them. Only
//! #500–#999 come from outside (`--vars`, or the machine file's
//! `macro.persistent_file`, keeps them between runs). So a
//! program that reads none of those runs the same way every time it is
//! run as the machine file has it, and the compiler can run it: in the VM
//! itself, for a bounded number of instructions. Where that run stops
//! with an alarm, the compiler warns at the alarm's block; the program
//! still compiles.

use grammar::{Diagnostic, SourceFile, Span};
use isa::{Instr, Module};
use nc::{Discard, Machine};

/// Instructions a prediction may run beyond one for each instruction of
/// the module (a straight program is run whole, as the dry run does):
/// loops' rounds and calls' passes. About 2 ms of a loop that moves the
/// tool every 30 instructions.
const EXTRA_STEPS: u64 = 200_000;

/// E6005, the block budget used up.
const BUDGET: u32 = nc::error::Alarm::BlockBudget.code() as u32;

/// The warnings that name the alarm a run stops with at their block: a
/// recursion (W115), an operation that always faults (W116), an arc that
/// cannot be drawn (W119), calls nested too deep (W121), a missing
/// `M99 P` target (W123).
const NAMES_ALARM: [&str; 5] = ["W115", "W116", "W119", "W121", "W123"];

/// The warning for the alarm the run of `module` stops with, if it stops
/// with one within its budget and its run cannot depend on #500–#999.
/// `diags` are the compilation's so far: an alarm a warning there already
/// names at that line ([`NAMES_ALARM`]) is not told again.
pub fn alarm(
    module: &Module,
    files: &[SourceFile],
    m: &Machine,
    diags: &[(usize, Diagnostic)],
) -> Option<(usize, Diagnostic)> {
    if module.code.iter().any(reads_from_outside) {
        return None;
    }
    let mut vm = vm::Vm::new(module.clone(), m.clone());
    let budget = EXTRA_STEPS.saturating_add(module.code.len() as u64);
    // The blocks it may charge are bounded as its instructions are (one
    // instruction may run a cycle of many legs); E6005 is the run's own
    // only under the machine's budget.
    vm.max_blocks = budget.min(m.run.max_blocks);
    // (One step: it need not end at each block.)
    vm.stop_at_blocks = false;
    let alarm = match vm.step(budget, &mut Discard) {
        vm::Status::Alarm(a) if a.code != BUDGET || vm.max_blocks == m.run.max_blocks => a,
        _ => return None,
    };
    let unit = files.iter().position(|f| f.name == alarm.file)?;
    let span = block_span(files.get(unit)?, alarm.line, alarm.col)?;
    let line = |d: &Diagnostic| files[unit].line_col(d.span.start).0;
    let told = diags.iter().any(|(u, d)| {
        *u == unit && NAMES_ALARM.contains(&d.code) && line(d) == alarm.line as usize
    });
    if told {
        return None;
    }
    Some((unit, warning(alarm.code, &alarm.message, span)))
}

/// W124 at `span`, for the alarm `code` (the canon's: 3000 + n for
/// `#3000 = n`) with `message`: a static program's dry run gives it too.
pub fn warning(code: u32, message: &str, span: Span) -> Diagnostic {
    let code = match nc::error::NcError::is_program_alarm(code) {
        true => format!("alarm {code}"),
        false => format!("E{code:04}"),
    };
    Diagnostic::warning(
        "W124",
        span,
        format!("the run stops here with {code}: {message}"),
    )
    .with_note(
        "every value this program uses is known when it is compiled, so `gbvm run` \
         stops here every time (with the machine file's settings)",
    )
}

/// Whether `instr` reads a variable that `--vars` may have set before
/// the run: #500–#999, or any variable by a computed number.
fn reads_from_outside(instr: &Instr) -> bool {
    match *instr {
        Instr::LoadVar { var, .. } => (500..=999).contains(&var),
        Instr::LoadVarInd { .. } => true,
        _ => false,
    }
}

/// From the block's place (1-based line and byte column) to the end of
/// its line.
fn block_span(file: &SourceFile, line: u32, col: u32) -> Option<Span> {
    let range = file.line_range(usize::try_from(line).ok()?.checked_sub(1)?)?;
    let start = range.start + usize::try_from(col).ok()?.checked_sub(1)?;
    let text = file.bytes().get(start..range.end)?;
    let len = text
        .iter()
        .position(|&b| b == b'\n' || b == b'\r')
        .unwrap_or(text.len());
    Some(Span::new(start, start + len))
}
