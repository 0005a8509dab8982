//! The run of a program with macros, made at compile time: W124 and the
//! modal warnings.
//!
//! A static program is dry-run through the kernel (`check`), and a
//! geometry fault in it is a compile error. A program with macros may
//! reach a block with other values, so its faults stay run-time alarms
//! (dialect.md §0). Yet a `gbvm run` depends on nothing but the module
//! and the machine file: the host's inputs, the clock, the offsets and
//! the block-skip switches all start as the machine file sets them. Only
//! #500–#999 come from outside (`--vars`, or the machine file's
//! `macro.persistent_file`, keeps them between runs). So a
//! program that reads none of those (or only those `-D` presets, or all
//! of them when `gbcc --vars` gives them) runs the same way every time it
//! is run as the machine file has it, and the compiler can run it: in the VM
//! itself, for a bounded number of instructions. Where that run stops
//! with an alarm, the compiler warns at the alarm's block (W124); the
//! program still compiles. On the way, the blocks the run executes get
//! the warnings a static program's dry run gives (`dry_warn`, W118),
//! each block read as the VM left the kernel after it.

use crate::dry_warn::{Counts, Warner};
use crate::link::Unit;
use crate::thread_room::RoomCheck;
use grammar::ast::{Block, Body, Line};
use grammar::{Diagnostic, SourceFile, Span};
use isa::{Instr, Module};
use nc::{Machine, Placed};

/// The warnings a prediction may give: W124 and those of the blocks it
/// runs. (The compile-time run is made only when one of them is
/// reported.)
pub const CODES: [&str; 11] = [
    "W104", "W105", "W108", "W110", "W111", "W112", "W114", "W118", "W124", "W125", "W126",
];

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

/// The warnings of the run of `module` (built from `units`, whose trees
/// it reads: the warnings of a block ask for its words as written, with
/// `opts`), if its run does not depend on #500–#999 it does not know:
/// those of the blocks it ran, then W124 where it stops with an alarm
/// within its budget. `diags` are the compilation's so far: an alarm a
/// warning there already names at that line (`NAMES_ALARM`) is not
/// told again.
pub fn run(
    module: &Module,
    units: &[Unit],
    files: &[SourceFile],
    opts: &crate::Options,
    diags: &[(usize, Diagnostic)],
) -> Vec<(usize, Diagnostic)> {
    let m = &opts.machine;
    let unknown = |i: &Instr| reads_from_outside(i, &opts.defines);
    if opts.vars.is_none() && module.code.iter().any(unknown) {
        return Vec::new();
    }
    let mut vm = vm::Vm::new(module.clone(), m.clone());
    if let Some(vars) = &opts.vars {
        *vm.persistent_mut() = **vars;
    }
    let budget = EXTRA_STEPS.saturating_add(module.code.len() as u64);
    // The blocks it may charge are bounded as its instructions are (one
    // instruction may run a cycle of many legs); E6005 is the run's own
    // only under the machine's budget.
    vm.max_blocks = budget.min(m.run.max_blocks);
    let mut watch = Watch::new(units, files, m);
    let status = watch.run(&mut vm, budget);
    let mut found = watch.warnings();
    if let vm::Status::Alarm(a) = status {
        let own = a.code != BUDGET || vm.max_blocks == m.run.max_blocks;
        let told = own.then(|| alarm(&a, files, diags, opts.vars.is_some()));
        let hint = |(unit, d): (usize, Diagnostic)| match argument_read(module) {
            Some(help) => (unit, d.with_help(help)),
            None => (unit, d),
        };
        found.extend(told.flatten().map(hint));
    }
    found
}

/// A hint for a main program that reads a local variable #1–#33 before
/// any of its instructions sets it (in the order they are written): run
/// as a main program, its arguments are vacant, which is likely what it
/// stops on. (A macro body compiled on its own looks like that.)
fn argument_read(module: &Module) -> Option<String> {
    let main = module.programs.first()?;
    let code = module.code.get(main.entry as usize..main.end as usize)?;
    // Bit n: #n set by an instruction before.
    let mut set = 0u64;
    let var = code.iter().find_map(|i| match *i {
        Instr::StoreVar { var, .. } if var < 64 => {
            set |= 1 << var;
            None
        }
        // (Which one it sets is known only when it runs.)
        Instr::StoreVarInd { .. } => Some(None),
        Instr::LoadVar { var, .. } if (1..=33).contains(&var) && set & (1 << var) == 0 => {
            Some(Some(var))
        }
        _ => None,
    })??;
    Some(format!(
        "O{:04} reads #{var} before it sets it: run as the main program, its arguments are vacant. \
         If it is a macro called with G65 or G66, compile the program that calls it (with -I) to check the call",
        main.number
    ))
}

/// W124 for the alarm `a` the run stopped with (`with_vars`: starting with
/// the #500–#999 of `gbcc --vars`), unless a warning of `diags` names it
/// at its line.
fn alarm(
    a: &vm::Alarm,
    files: &[SourceFile],
    diags: &[(usize, Diagnostic)],
    with_vars: bool,
) -> Option<(usize, Diagnostic)> {
    let unit = files.iter().position(|f| f.name == a.file)?;
    let span = block_span(files.get(unit)?, a.line, a.col)?;
    let line = |d: &Diagnostic| files[unit].line_col(d.span.start).0;
    let told = diags
        .iter()
        .any(|(u, d)| *u == unit && NAMES_ALARM.contains(&d.code) && line(d) == a.line as usize);
    if told {
        return None;
    }
    let note = match with_vars {
        false => KNOWN,
        true => KNOWN_WITH_VARS,
    };
    Some((unit, stops_with(a.code, &a.message, span).with_note(note)))
}

/// W124's note: why the run is known.
const KNOWN: &str = "every value this program uses is known when it is compiled, so \
                     `gbvm run` stops here every time (with the machine file's settings)";

/// W124's note for a run that started with the #500–#999 of `--vars`.
const KNOWN_WITH_VARS: &str = "every value this program uses is known when it is compiled, \
                               so `gbvm run` stops here every time it starts with the \
                               #500–#999 of --vars (and the machine file's settings)";

/// What watches the blocks of the run: the dry run's warnings, fed with
/// each block's words as written and the kernel's state around it.
struct Watch<'a> {
    units: &'a [Unit],
    files: &'a [SourceFile],
    warner: Warner,
    room: RoomCheck,
    /// The events of the block being run (its place is known once it
    /// ran), with the tags of those an earlier block left waiting.
    events: Placed,
    /// The index in its tree of the block found last: the next is most
    /// often a few lines on.
    near: usize,
}

impl<'a> Watch<'a> {
    fn new(units: &'a [Unit], files: &'a [SourceFile], m: &Machine) -> Self {
        Watch {
            units,
            files,
            warner: Warner::default(),
            room: RoomCheck::new(m),
            events: Placed::default(),
            near: 0,
        }
    }

    /// Runs `vm` for at most `budget` instructions, a block at a time:
    /// the status it ends with (never `Event`).
    fn run(&mut self, vm: &mut vm::Vm, budget: u64) -> vm::Status {
        vm.stop_at_blocks = true;
        let mut left = budget;
        loop {
            let before = self.warner.before(&vm.nc);
            let charged = vm.blocks_charged();
            self.events.clear();
            match vm.step(left, &mut self.events) {
                vm::Status::Event => self.block(vm, before),
                // An M02/M30 block ends the run; running past the last
                // block or the main program's M99 runs none.
                vm::Status::Done if vm.blocks_charged() != charged => {
                    self.block(vm, before);
                    return vm::Status::Done;
                }
                other => return other,
            }
            left = vm.fuel_left();
        }
    }

    /// The warnings of the block `vm` ran last, which started in `before`.
    fn block(&mut self, vm: &vm::Vm, before: crate::dry_warn::Before) {
        let loc = vm.last_loc();
        let unit = loc.file as usize;
        let Some(block) = self.block_at(loc) else {
            return;
        };
        let Body::Words(ws) = &block.body else {
            return;
        };
        let mut counts = Counts::default();
        (self.room.unit, self.room.span) = (unit, block.span);
        let mut from = 0;
        for k in 0..self.events.origins.len() {
            let (at, tag) = self.events.origins[k];
            let run = self.events.events.get(from..at).unwrap_or_default();
            watch(&mut self.room, &mut counts, run);
            from = at;
            // The thread-room check names the block an event belongs to,
            // as the dry run's `Watchers::origin` does: a thread block's
            // moves wait for the next block and print while it runs.
            let own = Some(tag).filter(|&t| t != nc::RUNNING);
            let own = own.and_then(|pc| self.place_of(vm.loc_at(pc)));
            (self.room.unit, self.room.span) = own.unwrap_or((unit, block.span));
        }
        let rest = self.events.events.get(from..).unwrap_or_default();
        watch(&mut self.room, &mut counts, rest);
        self.events.clear();
        let lits = crate::check::watched_words(ws);
        let at = (ws.as_slice(), block.span);
        (self.warner).after(unit, &vm.nc, at, &lits, &counts, before);
    }

    /// The unit and span of the block at `loc`, an earlier one: the next
    /// block is still looked for near the last one run.
    fn place_of(&mut self, loc: isa::SourceLoc) -> Option<(usize, Span)> {
        let near = self.near;
        let span = self.block_at(loc).map(|b| b.span);
        self.near = near;
        Some((loc.file as usize, span?))
    }

    /// The block of the syntax tree that starts at `loc`.
    fn block_at(&mut self, loc: isa::SourceLoc) -> Option<&'a Block> {
        let i = loc.file as usize;
        let (unit, file) = (self.units.get(i)?, self.files.get(i)?);
        let line = file.line_range(usize::try_from(loc.line).ok()?.checked_sub(1)?)?;
        let start = (line.start + usize::try_from(loc.col).ok()?.checked_sub(1)?) as u32;
        let lines = &unit.ast.lines;
        let starts_at = |at: usize| lines.get(at).map(|l| l.span().start);
        // The lines after the last block found first, then a search.
        let ahead =
            (self.near..self.near.saturating_add(4)).find(|&at| starts_at(at) == Some(start));
        let at = ahead.unwrap_or_else(|| lines.partition_point(|l| l.span().start < start));
        self.near = at;
        match lines.get(at)? {
            Line::Block(b) if b.span.start == start => Some(b),
            _ => None,
        }
    }

    /// The warnings found, in the dry run's order.
    fn warnings(mut self) -> Vec<(usize, Diagnostic)> {
        self.room.finish();
        let mut found = self.warner.diags;
        found.append(&mut self.room.warnings);
        found
    }
}

/// Feeds `events`, printed under one block, to the thread-room check and
/// the block's counts.
fn watch(room: &mut RoomCheck, counts: &mut Counts, events: &[nc::Event]) {
    for e in events {
        room.event(e);
        counts.count(e);
    }
}

/// W124 at `span`, for the alarm `code` (the canon's: 3000 + n for
/// `#3000 = n`) with `message`: a static program's dry run gives it too.
pub fn warning(code: u32, message: &str, span: Span) -> Diagnostic {
    stops_with(code, message, span).with_note(KNOWN)
}

/// W124's text, without its note.
fn stops_with(code: u32, message: &str, span: Span) -> Diagnostic {
    let (code, message) = match nc::error::NcError::is_program_alarm(code) {
        // The program's text as the canon prints it: no byte of a comment
        // outside printable ASCII reaches the terminal.
        true => (format!("alarm {code}"), nc::event::canon_text(message)),
        false => (format!("E{code:04}"), message.to_string()),
    };
    // (A long message is clipped, as source text in any message is.)
    let message = grammar::diag::quote(message.chars());
    let msg = format!("the run stops here with {code}: {message}");
    Diagnostic::warning("W124", span, msg)
}

/// Whether `instr` reads a variable that `--vars` may have set before
/// the run: one of #500–#999 that no `-D` of `defines` presets (a preset
/// is stored at the main program's start, over what `--vars` set), or
/// any variable by a computed number.
fn reads_from_outside(instr: &Instr, defines: &[(u32, f64)]) -> bool {
    match *instr {
        Instr::LoadVar { var, .. } => {
            (500..=999).contains(&var) && !defines.iter().any(|&(d, _)| d == var)
        }
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
