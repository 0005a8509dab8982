//! The gbc compiler: parses a program file, links the programs it calls
//! (from the file or from library folders), checks it, builds it into the
//! IR (`ir`, pass `build`) and emits a verified `.gbc` module from that
//! (pass `emit`).

// Errors here are diagnostics, built once per faulty block on the cold
// path: their size does not matter, boxing them would only add noise.
#![allow(clippy::result_large_err)]

pub mod build;
pub mod calls;
pub mod check;
pub mod codes;
pub mod consts;
pub mod data_setting;
pub mod dry_warn;
pub mod emit;
pub mod endless;
pub mod expr;
pub mod fold;
pub mod hash;
pub mod ir;
pub mod known_faults;
pub mod link;
pub mod lint;
pub mod modal;
pub mod predict;
pub mod profile;
pub mod recursion;
pub mod resolve;
pub mod stream;
pub mod thread_room;
pub mod words;

use grammar::{Diagnostic, SourceFile};
use link::{Program, Unit};
use nc::Machine;
use std::path::PathBuf;
use std::sync::Arc;

/// What the driver passes in.
#[derive(Debug, Clone)]
pub struct Options {
    pub machine: Machine,
    /// Library folders searched for called programs (`-I`).
    pub include: Vec<PathBuf>,
    /// Constant folding (`-O1`, the default).
    pub optimize: bool,
    /// `-D '#100=5'`: variables preset at the start of the run.
    pub defines: Vec<(u32, f64)>,
    /// A longer program of plain blocks is compiled a chunk of about
    /// this many bytes at a time (`stream`).
    pub chunk_bytes: usize,
    /// Pass `resolve`: plain moves become typed moves (off only to
    /// compare the two forms in tests).
    pub resolve: bool,
    /// Run a program with macros in the VM for W124 and the modal
    /// warnings (`predict`); off when none of those would be reported
    /// (`-w`, `-Wno-` each of [`predict::CODES`]).
    pub predict: bool,
    /// #500–#999 as a run will start with them (`gbcc --vars FILE`, in
    /// `gbvm run --vars`'s form; NaN is vacant): the compile-time run
    /// starts with them too, so a program that reads them is run.
    pub vars: Option<Box<[f64; 500]>>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            machine: Machine::reference(),
            include: Vec::new(),
            optimize: true,
            defines: Vec::new(),
            chunk_bytes: CHUNK_BYTES,
            resolve: true,
            predict: true,
            vars: None,
        }
    }
}

/// The chunk of a long plain program (`stream`): its tree and IR (about
/// 20 bytes a source byte) are, with the next chunks on their way, all of
/// the program that `gbcc` holds besides the source and the module. At
/// 32 KiB or 1 MiB the 1M-block benchmark compiled no faster; at 1 MiB
/// it held 20 MB more.
pub const CHUNK_BYTES: usize = 1 << 16;

/// The result of a compilation: the module when there was no error, and
/// every diagnostic with the file it belongs to.
pub struct Compiled {
    pub module: Option<isa::Module>,
    pub files: Vec<SourceFile>,
    pub diags: Vec<(usize, Diagnostic)>,
}

impl Compiled {
    pub fn has_errors(&self) -> bool {
        self.diags.iter().any(|(_, d)| d.is_error())
    }

    /// Every diagnostic rendered, in order.
    pub fn render(&self) -> String {
        self.diags
            .iter()
            .map(|(f, d)| self.files[*f].render(d))
            .collect::<Vec<_>>()
            .join("\n")
    }
}

/// Compiles the program file `name` with contents `bytes`.
pub fn compile(name: &str, bytes: &[u8], opts: &Options) -> Compiled {
    compile_keeping(name, bytes.into(), opts, false).0
}

/// Compiles as [`compile`] does, from a source the caller shares (the
/// compiler holds it without a copy).
pub fn compile_shared(name: &str, bytes: Arc<[u8]>, opts: &Options) -> Compiled {
    compile_keeping(name, bytes, opts, false).0
}

/// Compiles as [`compile`] does, and gives the IR the module was emitted
/// from too (`gbcc --emit=ir`; `None` after an error before the build).
pub fn compile_ir(name: &str, bytes: &[u8], opts: &Options) -> (Compiled, Option<ir::Module>) {
    compile_keeping(name, bytes.into(), opts, true)
}

fn compile_keeping(
    name: &str,
    bytes: Arc<[u8]>,
    opts: &Options,
    keep_ir: bool,
) -> (Compiled, Option<ir::Module>) {
    if !keep_ir {
        if let Some(compiled) = stream::compile(name, &bytes, opts) {
            return (compiled, None);
        }
    }
    let mut diags = Vec::new();
    let mut units = vec![parse_unit(name, bytes, 0, &mut diags)];
    let mut programs = link::split(0, &units[0], &mut diags);
    link_libraries(&mut units, &mut programs, opts, &mut diags);
    diags.extend(recursion::check(&units, &programs));
    if has_errors(&diags) {
        let compiled = Compiled {
            module: None,
            files: source_files(&units),
            diags,
        };
        return (compiled, None);
    }
    let (files, module, ir) = lower_and_check(&mut units, &programs, opts, keep_ir, &mut diags);
    free_in_background(units, programs);
    let failed = has_errors(&diags);
    let compiled = Compiled {
        module: module.filter(|_| !failed),
        files,
        diags,
    };
    (compiled, ir)
}

/// Builds the programs into IR and emits them, dry-runs a static one and
/// verifies the module; the source files made on the way, and the IR.
///
/// The dry run needs only the trees: on a large program it runs on a
/// second thread beside the lowering. Its finding counts only if the
/// lowering found no error, as when it runs after it. A program that is
/// not dry-run gives its trees up once they are built into IR: the IR,
/// the module and the trees are then never held all at once.
fn lower_and_check(
    units: &mut [Unit],
    programs: &[Program],
    opts: &Options,
    keep_ir: bool,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> (Vec<SourceFile>, Option<isa::Module>, Option<ir::Module>) {
    // A static program without G-code macros is dry-run.
    let table = &opts.machine.r#macro.g_code_macros;
    let dry = !uses_g_code_macros(units, programs, table) && check::is_static(units, programs);
    match dry {
        true => lower_static(units, programs, opts, keep_ir, diags),
        false => lower_dynamic(units, programs, opts, keep_ir, diags),
    }
}

/// `lower_and_check` for a static program: dry-run beside the lowering
/// when it is large.
fn lower_static(
    units: &[Unit],
    programs: &[Program],
    opts: &Options,
    keep_ir: bool,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> (Vec<SourceFile>, Option<isa::Module>, Option<ir::Module>) {
    let dry_run = || check::dry_run(units, programs, &opts.machine);
    let parallel = block_count(programs) >= PARALLEL_BLOCKS;
    std::thread::scope(|s| {
        // (Without a second thread, the dry run comes after the lowering.)
        let early = match parallel {
            true => std::thread::Builder::new().spawn_scoped(s, dry_run).ok(),
            false => None,
        };
        let files = source_files(units);
        let ir = build_ir(units, programs, opts, diags);
        let (module, ir) = lower_ir(ir, units, &files, opts, diags);
        // (Not kept, the IR goes before the dry run is waited for.)
        let ir = ir.filter(|_| keep_ir);
        let failed = has_errors(diags);
        let found = match early {
            Some(run) => match run.join() {
                Ok(found) => found,
                // (A run the sequential order would not have made.)
                Err(_) if failed => Vec::new(),
                Err(panic) => std::panic::resume_unwind(panic),
            },
            None if !failed => dry_run(),
            None => Vec::new(),
        };
        (files, verified(module, found, diags), ir)
    })
}

/// `lower_and_check` for a program with macros: no dry run, but the
/// arcs pass `modal` proves faulty and the prediction's run.
fn lower_dynamic(
    units: &mut [Unit],
    programs: &[Program],
    opts: &Options,
    keep_ir: bool,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> (Vec<SourceFile>, Option<isa::Module>, Option<ir::Module>) {
    let files = source_files(units);
    let ir = build_ir(units, programs, opts, diags);
    // Loops that never end (a static program's dry run finds its own,
    // W120). Before fold, which makes a test that is always true a jump.
    if let Ok(ir) = &ir {
        diags.extend(endless::module(ir));
    }
    // (The prediction reads the trees: they go after it.)
    if !opts.predict {
        free_trees_in_background(units, programs);
    }
    let (module, ir) = lower_ir(ir, units, &files, opts, diags);
    // Not dry-run, a program may still hold a geometry alarm the
    // pass `modal` proves (W119).
    let arcs = ir.as_ref().is_some_and(known_faults::wanted);
    if let (Some(ir), false, true) = (&ir, has_errors(diags), arcs) {
        let facts = modal::analyze(ir, &opts.machine);
        diags.extend(known_faults::arcs(ir, &facts, &opts.machine));
    }
    // (Not kept, the IR goes before the prediction.)
    let ir = ir.filter(|_| keep_ir);
    let module = verified(module, Vec::new(), diags);
    // Nor is its run's alarm an error; but where the run is known,
    // the compiler makes it, says where it stops (W124) and gives the
    // warnings of the blocks it ran, as a dry run would.
    if let (Some(m), false, true) = (&module, has_errors(diags), opts.predict) {
        let found = predict::run(m, units, &files, opts, diags);
        diags.extend(found);
    }
    if opts.predict {
        free_trees_in_background(units, programs);
    }
    (files, module, ir)
}

/// Verifies the module when the lowering found no error, adds the dry
/// run's findings `found` (which count only then), and reports a module
/// that does not verify (E0000).
fn verified(
    module: Option<isa::Module>,
    found: Vec<(usize, Diagnostic)>,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> Option<isa::Module> {
    let failed = has_errors(diags);
    let verified = module.as_ref().filter(|_| !failed).map(|m| m.verify());
    if !failed {
        diags.extend(found);
    }
    if let (Some(Err(e)), false) = (verified, has_errors(diags)) {
        diags.push((
            0,
            Diagnostic::error(
                "E0000",
                grammar::Span::default(),
                format!("internal error: the generated module does not verify: {e}"),
            ),
        ));
    }
    module
}

/// Hands the trees of a large program, built into IR, to a thread that
/// frees them (see [`free_in_background`]); the units keep their names
/// and sources.
fn free_trees_in_background(units: &mut [Unit], programs: &[Program]) {
    if block_count(programs) < PARALLEL_BLOCKS {
        return;
    }
    let trees: Vec<grammar::ast::Ast> = units
        .iter_mut()
        .map(|u| std::mem::take(&mut u.ast))
        .collect();
    let _ = std::thread::Builder::new()
        .name("gbc-free".into())
        .spawn(move || drop(trees));
}

/// Frees the trees of a large program on a thread of its own: their
/// hundreds of thousands of small allocations take a tenth of the whole
/// compile to free, and nothing needs to wait for that. Small trees, and
/// the trees of a spawn that fails, are freed here.
fn free_in_background(units: Vec<Unit>, programs: Vec<Program>) {
    if block_count(&programs) < PARALLEL_BLOCKS {
        return;
    }
    let _ = std::thread::Builder::new()
        .name("gbc-free".into())
        .spawn(move || drop((units, programs)));
}

fn source_files(units: &[Unit]) -> Vec<SourceFile> {
    units
        .iter()
        .map(|u| SourceFile::new(u.name.clone(), u.bytes.clone()))
        .collect()
}

/// Blocks from which a program is dry-run on a thread of its own,
/// beside the lowering (below, a thread costs more than it saves).
const PARALLEL_BLOCKS: usize = 10_000;

fn has_errors(diags: &[(usize, Diagnostic)]) -> bool {
    diags.iter().any(|(_, d)| d.is_error())
}

fn block_count(programs: &[Program]) -> usize {
    programs.iter().map(|p| p.blocks.len()).sum()
}

/// Builds every program into IR (pass `build`): `None` after a build
/// error (the IR may then be incomplete; `--emit=ir` still prints it).
fn build_ir(
    units: &[Unit],
    programs: &[Program],
    opts: &Options,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> Result<ir::Module, ir::Module> {
    let (ir, mut found) =
        build::build(units, programs, &opts.machine, opts.optimize, &opts.defines);
    diags.append(&mut found);
    match has_errors(diags) {
        true => Err(ir),
        false => Ok(ir),
    }
}

/// Runs the passes after `build` on the IR, validates it and emits a
/// module that names its source files. No module after a build error or
/// an invalid IR (E0000).
fn lower_ir(
    ir: Result<ir::Module, ir::Module>,
    units: &[Unit],
    files: &[SourceFile],
    opts: &Options,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> (Option<isa::Module>, Option<ir::Module>) {
    let mut ir = match ir {
        Ok(ir) => ir,
        Err(ir) => return (None, Some(ir)),
    };
    if opts.optimize {
        diags.extend(fold::module(&mut ir, &opts.machine));
    }
    if opts.resolve {
        resolve::module(&mut ir);
    }
    if let Err(errors) = ir::validate(&ir) {
        for e in errors {
            let msg = format!("internal error: the IR is invalid: {}", e.message);
            diags.push((
                e.loc.file as usize,
                Diagnostic::error("E0000", e.loc.span, msg),
            ));
        }
        return (None, Some(ir));
    }
    let (mut module, mut found) = emit::emit(&ir, files, &opts.machine);
    diags.append(&mut found);
    module.files = units
        .iter()
        .map(|u| isa::SourceFileInfo {
            name: u.name.clone(),
            hash: crc32fast::hash(&u.bytes),
        })
        .collect();
    (Some(module), Some(ir))
}

fn parse_unit(
    name: &str,
    bytes: Arc<[u8]>,
    index: usize,
    diags: &mut Vec<(usize, Diagnostic)>,
) -> Unit {
    let (mut ast, ds) = grammar::parse(&bytes);
    // N inside G10 L52 is a parameter number (data_setting module).
    data_setting::prepare(&mut ast);
    diags.extend(ds.into_iter().map(|d| (index, d)));
    Unit {
        name: name.to_string(),
        bytes,
        ast,
    }
}

/// Does any block call a G-code macro (those programs are never static)?
fn uses_g_code_macros(units: &[Unit], programs: &[Program], table: &[u32; 10]) -> bool {
    // (No G code calls a macro unless the table names one.)
    table.iter().any(|&n| n != 0)
        && programs.iter().any(|p| {
            p.blocks
                .iter()
                .filter_map(|&l| link::block(&units[p.unit], l))
                .any(|b| match &b.body {
                    grammar::ast::Body::Words(ws) => {
                        words::g_code_macro(ws, table, p.number).is_some()
                    }
                    grammar::ast::Body::Stmt(_) => false,
                })
        })
}

/// Literal call targets of a program.
fn targets(unit: &Unit, prog: &Program, table: &[u32; 10]) -> Vec<u32> {
    let mut out = Vec::new();
    for &line in &prog.blocks {
        let Some(block) = link::block(unit, line) else {
            continue;
        };
        let grammar::ast::Body::Words(ws) = &block.body else {
            continue;
        };
        let split = match words::g_code_macro(ws, table, prog.number) {
            Some(call) => call,
            // Most blocks call nothing: no need to sort their words.
            None if !words::may_call(ws) => continue,
            None => words::classify(ws),
        };
        let Ok(split) = split else {
            continue;
        };
        match split.call {
            Some(words::Call::Sub { p: Some(p), l, .. }) => {
                if let Some(p) = p.literal() {
                    // With an L, written or computed, P is the program.
                    let l = l.map(|l| l.literal().unwrap_or(1.0));
                    out.push(calls::m98_target(p, l).0);
                }
            }
            Some(words::Call::SubM { number, .. }) => out.push(number),
            Some(words::Call::Macro { p: Some(p), .. }) => {
                if let Some(p) = p.literal() {
                    out.push(nc::block::round_half_away(p).max(0.0) as u32);
                }
            }
            _ => {}
        }
    }
    out
}

/// Adds the library files of every called program found in no unit yet.
fn link_libraries(
    units: &mut Vec<Unit>,
    programs: &mut Vec<Program>,
    opts: &Options,
    diags: &mut Vec<(usize, Diagnostic)>,
) {
    let mut dirs = opts.include.clone();
    dirs.extend(opts.machine.r#macro.library_dirs.iter().map(PathBuf::from));
    if dirs.is_empty() {
        // No folder to find a program in: the calls need not be looked at.
        return;
    }
    let mut i = 0;
    while i < programs.len() {
        let wanted = targets(
            &units[programs[i].unit],
            &programs[i],
            &opts.machine.r#macro.g_code_macros,
        );
        for number in wanted {
            if programs.iter().any(|p| p.number == number) {
                continue;
            }
            let Some(path) = link::find_library(&dirs, number) else {
                continue;
            };
            let Ok(bytes) = std::fs::read(&path) else {
                continue;
            };
            let index = units.len();
            let unit = parse_unit(&path.display().to_string(), bytes.into(), index, diags);
            let mut found = link::split(index, &unit, diags);
            units.push(unit);
            found.retain(|p| !programs.iter().any(|q| q.number == p.number));
            programs.extend(found);
        }
        i += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::{compile, Options, PARALLEL_BLOCKS};

    /// A static program of more than `PARALLEL_BLOCKS` blocks, `first`
    /// after the set-up block, an arc of too small a radius at the end.
    fn large(first: &str) -> String {
        let mut src = format!("G98 G00 X40 Z2 F100\n{first}\n");
        for _ in 0..PARALLEL_BLOCKS {
            src.push_str("G01 X40 Z1\n");
        }
        src.push_str("G02 X30 Z-20 R1\nM30\n");
        src
    }

    fn codes(src: &str) -> Vec<(&'static str, usize)> {
        let c = compile("t.nc", src.as_bytes(), &Options::default());
        c.diags
            .iter()
            .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
            .collect()
    }

    #[test]
    fn the_dry_run_beside_the_lowering_reports_as_after_it() {
        let end = PARALLEL_BLOCKS + 3;
        assert_eq!(codes(&large("G01 X40 Z1")), [("E4001", end)]);
        // A lowering error: the dry run's finding does not count.
        assert_eq!(codes(&large("G01 X40 X41")), [("E1011", 2)]);
    }
}
