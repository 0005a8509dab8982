//! `gbcc`: the gbc compiler driver, with gcc's conventions.

use clap::Parser;
use cli::exit::Exit;
use cli::io::{Dest, STDIN_NAME};
use cli::report::{Format, Reporter};
use compiler::{Compiled, Options};
use std::ffi::OsString;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// mimalloc (cli::allocator says why).
#[global_allocator]
static ALLOCATOR: cli::allocator::Mimalloc = cli::allocator::Mimalloc;

/// Whether standard error was closed when gbcc started (`2>&-`). Rust's
/// start-up code opens /dev/null in its place before `main`, where every
/// write succeeds: a diagnostic would be lost without a trace, and the
/// exit code would not say so (diagnostics.md: 3). So it is looked at
/// before that, from the ELF start-up list, which runs first.
static STDERR_CLOSED: AtomicBool = AtomicBool::new(false);

#[cfg(target_os = "linux")]
mod start_up {
    use std::ffi::{c_char, c_int};
    use std::sync::atomic::Ordering;

    type StartUp = extern "C" fn(c_int, *const *const c_char, *const *const c_char);

    #[used]
    #[link_section = ".init_array"]
    static LOOK_AT_STDERR: StartUp = look_at_stderr;

    /// (Called by the C library with main's arguments, not needed here.)
    extern "C" fn look_at_stderr(_: c_int, _: *const *const c_char, _: *const *const c_char) {
        // SAFETY: F_GETFD only asks whether descriptor 2 is open; it
        // touches no memory.
        let closed = unsafe { libc::fcntl(2, libc::F_GETFD) } == -1;
        super::STDERR_CLOSED.store(closed, Ordering::Relaxed);
    }
}

#[derive(Parser)]
#[command(
    name = "gbcc",
    version,
    about = "Compile GSK980TDi lathe G-code into .gbc bytecode",
    after_help = "Also: -MD (write a make dependency file), -MF FILE (its name). \
                  Exit codes: 0 ok, 1 errors or a usage error, 3 an output or a diagnostic \
                  could not be written."
)]
struct Args {
    /// Program files (.nc); - reads standard input.
    #[arg(required_unless_present = "explain")]
    files: Vec<PathBuf>,
    /// Output file (default: the input's name with .gbc, or .s with -S;
    /// standard output with -E); - is standard output.
    #[arg(short = 'o')]
    output: Option<PathBuf>,
    /// Write the annotated bytecode listing instead of a .gbc.
    #[arg(short = 'S')]
    listing: bool,
    /// Print the program as plain G-code after macros, subprograms and
    /// cycles are resolved (a run on the reference host).
    #[arg(short = 'E')]
    expand: bool,
    /// --emit=ir: write the compiler's IR (every program's blocks, each
    /// operation with its file:line:col) instead of a module; default
    /// name FILE.ir.
    #[arg(long = "emit", value_name = "WHAT", value_parser = ["ir"])]
    emit: Option<String>,
    /// Library folder searched for called programs (repeatable).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Preset a variable for the run: -D '#100=5'.
    #[arg(short = 'D', value_name = "#N=VALUE")]
    define: Vec<String>,
    /// Optimisation level: -O0 (no folding), -O1 (constant folding, default).
    #[arg(short = 'O', value_name = "LEVEL", default_value = "1")]
    opt: String,
    /// Warnings: -Wall, -Wextra, -Werror, -Werror=W101, -Wno-error=W101,
    /// -WW113, -Wno-W113 (docs/diagnostics.md).
    #[arg(short = 'W', value_name = "WARN")]
    warn: Vec<String>,
    /// Suppress every warning.
    #[arg(short = 'w')]
    no_warnings: bool,
    /// -fsyntax-only, -fdiagnostics-format=text|json|sarif,
    /// -fdiagnostics-color=auto|always|never, -fmax-errors=N (default 20,
    /// 0: no limit).
    #[arg(short = 'f', value_name = "FLAG")]
    flags: Vec<String>,
    /// Machine file (TOML, docs/machine.md); the reference machine by default.
    #[arg(long = "machine", value_name = "FILE")]
    machine: Option<PathBuf>,
    /// #500–#999 as the run will start with them (the file of `gbvm run
    /// --vars`): the compile-time run that warns where the run stops
    /// (W124) starts with them, so a program that reads them is run too.
    #[arg(long = "vars", value_name = "FILE")]
    vars: Option<PathBuf>,
    /// Print the long explanation of a diagnostic code (E4009, W113).
    #[arg(long = "explain", value_name = "CODE")]
    explain: Option<String>,
    /// No progress spinner (it shows on a terminal after a second).
    #[arg(long, short = 'q')]
    quiet: bool,
}

/// `-MD` and `-MF FILE`, taken off the command line before clap sees it
/// (clap has no two-letter short options).
#[derive(Default)]
struct DepOptions {
    md: bool,
    mf: Option<PathBuf>,
}

fn take_dep_options(args: Vec<OsString>) -> Result<(Vec<OsString>, DepOptions), String> {
    let mut rest = Vec::new();
    let mut deps = DepOptions::default();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        if a == "--" {
            rest.push(a);
            rest.extend(it.by_ref());
            break;
        }
        if a == "-MD" {
            deps.md = true;
        } else if a == "-MF" {
            let file = it.next().ok_or("-MF needs a file name")?;
            deps.mf = Some(file.into());
        } else if let Some(file) = a.to_str().and_then(|s| s.strip_prefix("-MF")) {
            deps.mf = Some(file.into());
        } else {
            rest.push(a);
        }
    }
    Ok((rest, deps))
}

/// The `-f` switches.
struct Flags {
    syntax_only: bool,
    format: Format,
    color: bool,
    max_errors: usize,
}

fn parse_flags(flags: &[String]) -> Result<Flags, String> {
    let mut f = Flags {
        syntax_only: false,
        format: Format::Text,
        color: false,
        max_errors: cli::report::DEFAULT_MAX_ERRORS,
    };
    let mut color = ColorChoice::Auto;
    for flag in flags {
        match flag.as_str() {
            "syntax-only" => f.syntax_only = true,
            "diagnostics-format=text" => f.format = Format::Text,
            "diagnostics-format=json" => f.format = Format::Json,
            "diagnostics-format=sarif" | "diagnostics-format=sarif-stderr" => {
                f.format = Format::Sarif
            }
            "diagnostics-color" | "diagnostics-color=always" => color = ColorChoice::Always,
            "no-diagnostics-color" | "diagnostics-color=never" => color = ColorChoice::Never,
            "diagnostics-color=auto" => color = ColorChoice::Auto,
            other => {
                let n = other
                    .strip_prefix("max-errors=")
                    .ok_or_else(|| format!("unknown option -f{other}"))?;
                f.max_errors = n
                    .parse()
                    .map_err(|_| format!("-fmax-errors expects a count, got '{n}'"))?;
            }
        }
    }
    f.color = color.resolve();
    Ok(f)
}

#[derive(Clone, Copy)]
enum ColorChoice {
    Auto,
    Always,
    Never,
}

impl ColorChoice {
    /// auto: colour on a terminal, unless NO_COLOR is set (no-color.org).
    fn resolve(self) -> bool {
        match self {
            ColorChoice::Always => true,
            ColorChoice::Never => false,
            ColorChoice::Auto => {
                std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
                    && std::io::stderr().is_terminal()
            }
        }
    }
}

fn usage(msg: &str) -> Exit {
    // The terminal may be gone; the exit code still says it.
    let _ = writeln_stderr(&format!("gbcc: error: {msg}"));
    Exit::Usage
}

fn writeln_stderr(text: &str) -> std::io::Result<()> {
    use std::io::Write;
    writeln!(std::io::stderr().lock(), "{text}")
}

/// `-D '#N=VALUE'`: N a variable a program may preset (locals #1–#33,
/// common #100–#199 and #500–#999), VALUE a finite number.
fn parse_define(d: &str) -> Result<(u32, f64), String> {
    let malformed = || format!("-D expects #N=VALUE, got '{d}'");
    let (var, value) = d
        .trim()
        .trim_start_matches('#')
        .split_once('=')
        .ok_or_else(malformed)?;
    let var: u32 = var.trim().parse().map_err(|_| malformed())?;
    let value: f64 = value.trim().parse().map_err(|_| malformed())?;
    if !matches!(var, 1..=33 | 100..=199 | 500..=999) {
        return Err(format!(
            "-D '{d}': #{var} cannot be preset (only #1–#33, #100–#199, #500–#999)"
        ));
    }
    if !value.is_finite() {
        return Err(format!("-D '{d}': the value must be a finite number"));
    }
    Ok((var, value))
}

/// `--vars FILE`: its #500–#999, read once (the file stays `gbvm run`'s).
fn read_vars(path: &Path) -> Result<Box<[f64; 500]>, String> {
    let text = cli::io::read_text(path)?;
    cli::vars::parse(&text, path).map(Box::new)
}

fn main() -> ExitCode {
    match run() {
        Ok(e) | Err(e) => e.into(),
    }
}

/// The driver's settings, checked.
struct Job {
    args: Args,
    deps: DepOptions,
    flags: Flags,
    opts: Options,
}

fn setup() -> Result<(Job, Reporter<cli::io::ErrStream>), Exit> {
    let (argv, deps) = take_dep_options(std::env::args_os().collect()).map_err(|e| usage(&e))?;
    let args: Args = cli::exit::parse_args(argv)?;
    if let Some(code) = &args.explain {
        return Err(explain(code));
    }
    let flags = parse_flags(&args.flags).map_err(|e| usage(&e))?;
    let policy = warning_policy(&args)?;
    let predict = compiler::predict::CODES.iter().any(|c| policy.reports(c));
    let optimize = match args.opt.as_str() {
        "0" => false,
        "1" | "2" | "s" => true,
        other => return Err(usage(&format!("unknown optimisation level -O{other}"))),
    };
    let mut defines = Vec::new();
    for d in &args.define {
        let def = parse_define(d).map_err(|msg| usage(&msg))?;
        defines.push(def);
    }
    check_files(&args, &flags, &deps)?;
    let input_error = |e: String| {
        let _ = writeln_stderr(&format!("gbcc: error: {e}"));
        Exit::Input
    };
    let machine = cli::load_machine(args.machine.as_deref()).map_err(input_error)?;
    let vars = args
        .vars
        .as_deref()
        .map(read_vars)
        .transpose()
        .map_err(input_error)?;
    let mut reporter = Reporter::new(
        cli::io::ErrStream::new(STDERR_CLOSED.load(Ordering::Relaxed)),
        flags.format,
        flags.color,
        policy,
    );
    reporter.max_errors = flags.max_errors;
    let opts = Options {
        machine,
        include: args.include.clone(),
        optimize,
        defines,
        // (W124's run at compile time is skipped when nobody will see it.)
        predict,
        vars,
        ..Options::default()
    };
    Ok((
        Job {
            args,
            deps,
            flags,
            opts,
        },
        reporter,
    ))
}

/// The warnings reported, from -W and -w in order.
fn warning_policy(args: &Args) -> Result<cli::warnings::Policy, Exit> {
    let mut policy = cli::warnings::Policy::default();
    for w in &args.warn {
        policy.apply(w).map_err(|e| usage(&e))?;
    }
    if args.no_warnings {
        policy.silence();
    }
    Ok(policy)
}

/// Usage errors of the input files: one output for several, standard
/// input twice, an output that is an input.
fn check_files(args: &Args, flags: &Flags, deps: &DepOptions) -> Result<(), Exit> {
    let several = args.files.len() > 1;
    if several && !flags.syntax_only && (args.output.is_some() || deps.mf.is_some()) {
        return Err(usage("-o or -MF with several input files"));
    }
    if args.files.iter().filter(|f| f.as_os_str() == "-").count() > 1 {
        return Err(usage("standard input (-) given twice"));
    }
    if let Some(out) = &args.output {
        if let Some(src) = args.files.iter().find(|f| cli::io::same_file(f, out)) {
            return Err(usage(&format!(
                "the output {} is the input {}: refusing to overwrite the source",
                out.display(),
                src.display()
            )));
        }
    }
    Ok(())
}

fn run() -> Result<Exit, Exit> {
    let (job, mut reporter) = setup()?;
    let mut failed = false;
    let mut write_failed = false;
    let mut usage_failed = false;
    for file in &job.args.files {
        match compile_one(&job, file, &mut reporter) {
            Ok(()) => {}
            Err(Exit::Write) => write_failed = true,
            Err(Exit::Usage) => usage_failed = true,
            Err(_) => failed = true,
        }
    }
    if !reporter.finish() {
        write_failed = true;
    }
    Ok(if write_failed {
        Exit::Write
    } else if usage_failed {
        Exit::Usage
    } else if failed {
        Exit::Input
    } else {
        Exit::Ok
    })
}

/// Compiles one input and writes what was asked for.
fn compile_one<W: std::io::Write>(
    job: &Job,
    file: &Path,
    reporter: &mut Reporter<W>,
) -> Result<(), Exit> {
    let (name, bytes) = read_program(file, reporter)?;
    let stale = remove_stale_module(job, file);
    let (compiled, ir) = compile(job, &name, &bytes);
    // (Gone before anything is written where it was.)
    if let Some(removal) = stale {
        let _ = removal.join();
    }
    report(&compiled, reporter)?;
    if job.flags.syntax_only {
        return Ok(());
    }
    if job.args.expand {
        return write_expanded(job, &compiled, &bytes, reporter);
    }
    write_output(job, file, &compiled, ir.as_ref(), reporter)
}

/// Removes, on a thread of its own, the module this compile is to replace:
/// the handle to wait for, if there is one.
///
/// A failed compile then leaves no module behind, as gcc removes the
/// output of a failed compile: the old program cannot be run by mistake
/// for the new one. And the kernel drops a large file's cached pages when
/// it goes (1.4 ms for the 4 MB module of the 200 000-block benchmark),
/// which is then done while the program is compiled, not when the new
/// module is written over it. Only a regular file that is a module goes
/// (a symbolic link, a listing or a source at the output's name stays:
/// the usual checks then apply when the output is written).
fn remove_stale_module(job: &Job, input: &Path) -> Option<std::thread::JoinHandle<()>> {
    let args = &job.args;
    if job.flags.syntax_only || args.expand || Output::of(args) != Output::Module {
        return None;
    }
    let Dest::File(path) = output_name(input, args.output.as_deref(), Output::Module) else {
        return None;
    };
    if !cli::io::is_module_file(&path) {
        return None;
    }
    // (Not removed: the new module is written over it as before.)
    let remove = |path: &Path| drop(std::fs::remove_file(path));
    let thread = std::thread::Builder::new().name("gbcc-remove".into());
    let on_thread = path.clone();
    match thread.spawn(move || remove(&on_thread)) {
        Ok(handle) => Some(handle),
        // (No thread to be had: removed here.)
        Err(_) => {
            remove(&path);
            None
        }
    }
}

/// The program's name and bytes; a `.gbc` module given as a program is an
/// input error.
fn read_program<W: std::io::Write>(
    file: &Path,
    reporter: &mut Reporter<W>,
) -> Result<(String, std::sync::Arc<[u8]>), Exit> {
    // (The compiler keeps the source shared with its diagnostics.)
    let (name, bytes) = cli::io::read_input_shared(file).map_err(|e| {
        reporter.driver_error(&e);
        Exit::Input
    })?;
    if cli::io::is_module(&bytes) {
        reporter.driver_error(&format!(
            "{name} is a compiled .gbc module, not a program: run it with `gbvm run {name}`"
        ));
        return Err(Exit::Input);
    }
    Ok((name, bytes))
}

/// Compiles as the job asks: the syntax alone, with the IR kept for
/// `--emit=ir`, or to a module.
fn compile(
    job: &Job,
    name: &str,
    bytes: &std::sync::Arc<[u8]>,
) -> (compiler::Compiled, Option<compiler::ir::Module>) {
    if job.flags.syntax_only {
        return (syntax(name, bytes), None);
    }
    let _spinner = cli::progress::Spinner::start(format!("compiling {name}"), job.args.quiet);
    if job.args.emit.as_deref() == Some("ir") {
        compiler::compile_ir(name, bytes, &job.opts)
    } else {
        (
            compiler::compile_shared(name, bytes.clone(), &job.opts),
            None,
        )
    }
}

/// Prints the diagnostics in source order, file by file, as a reader goes
/// through the program (the passes find them in their own order: a run's
/// warnings come after those of the words); an error fails the compile.
fn report<W: std::io::Write>(
    compiled: &compiler::Compiled,
    reporter: &mut Reporter<W>,
) -> Result<(), Exit> {
    let mut diags: Vec<&(usize, grammar::Diagnostic)> = compiled.diags.iter().collect();
    diags.sort_by_key(|(f, d)| (*f, d.span.start));
    let mut errors = false;
    for (f, d) in diags {
        errors |= reporter.report(&compiled.files[*f], d);
    }
    if errors || compiled.has_errors() {
        return Err(Exit::Input);
    }
    Ok(())
}

/// `-E`: the program as plain G-code (an alarm of its run fails it).
fn write_expanded<W: std::io::Write>(
    job: &Job,
    compiled: &compiler::Compiled,
    bytes: &[u8],
    reporter: &mut Reporter<W>,
) -> Result<(), Exit> {
    let dest = Dest::new(job.args.output.as_deref().unwrap_or(Path::new("-")));
    let (text, alarm) = expand(compiled, bytes, &job.opts);
    dest.write(text.as_bytes()).map_err(|e| {
        reporter.driver_error(&e);
        Exit::Write
    })?;
    if let Some(a) = alarm {
        reporter.alarm(&a);
        return Err(Exit::Input);
    }
    Ok(())
}

/// Writes the module, its listing (`-S`) or its IR (`--emit=ir`), and the
/// dependency file.
fn write_output<W: std::io::Write>(
    job: &Job,
    file: &Path,
    compiled: &compiler::Compiled,
    ir: Option<&compiler::ir::Module>,
    reporter: &mut Reporter<W>,
) -> Result<(), Exit> {
    let args = &job.args;
    let kind = Output::of(args);
    let dest = output_name(file, args.output.as_deref(), kind);
    let deps = dep_file(job, file, &dest);
    if let Err(e) = check_overwrites(job, compiled, &dest, deps.as_ref()) {
        reporter.driver_error(&e);
        return Err(Exit::Usage);
    }
    let Some(module) = &compiled.module else {
        reporter.driver_error("no module was produced");
        return Err(Exit::Input);
    };
    let written = match (kind, ir) {
        (Output::Ir, Some(ir)) => {
            let facts = compiler::modal::analyze(ir, &job.opts.machine);
            let notes = |f, op| facts.note(ir, f, op);
            let text = compiler::ir::print::print_with(ir, &compiled.files, &notes);
            dest.write(text.as_bytes())
        }
        (Output::Ir, None) => {
            reporter.driver_error("no IR was built");
            return Err(Exit::Input);
        }
        (Output::Listing, _) => dest.write(module.disassemble().as_bytes()),
        // Straight to the file: a large module is not copied whole first.
        (Output::Module, _) => dest.write_with(|sink| module.write_to(sink)),
    };
    let written = match &deps {
        Some(d) => written.and_then(|()| write_deps(job, d, compiled)),
        None => written,
    };
    written.map_err(|e| {
        reporter.driver_error(&e);
        Exit::Write
    })
}

/// What a compile writes.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Output {
    Module,
    /// `-S`.
    Listing,
    /// `--emit=ir`.
    Ir,
}

impl Output {
    fn of(args: &Args) -> Output {
        match (args.emit.as_deref(), args.listing) {
            (Some("ir"), _) => Output::Ir,
            (_, true) => Output::Listing,
            _ => Output::Module,
        }
    }
}

/// The output of `input`: `-o`, else its name with `.gbc` (`.s` with -S,
/// `.ir` with --emit=ir) in the current folder (`a.gbc` for standard
/// input, as gcc's `a.out`).
fn output_name(input: &Path, output: Option<&Path>, kind: Output) -> Dest {
    if let Some(o) = output {
        return Dest::new(o);
    }
    let name = match input.file_name() {
        Some(n) if input.as_os_str() != "-" => PathBuf::from(n),
        _ => PathBuf::from("a"),
    };
    let ext = match kind {
        Output::Module => "gbc",
        Output::Listing => "s",
        Output::Ir => "ir",
    };
    Dest::File(name.with_extension(ext))
}

/// `-MD`/`-MF`: the make rule's target (the output, or the name it would
/// have had when it goes to standard output) and the file the rule goes
/// in: `-MF FILE`, or beside the output as `NAME.d`.
struct DepFile {
    target: PathBuf,
    path: PathBuf,
}

fn dep_file(job: &Job, input: &Path, dest: &Dest) -> Option<DepFile> {
    if !job.deps.md && job.deps.mf.is_none() {
        return None;
    }
    let target = match dest {
        Dest::File(p) => p.clone(),
        Dest::Stdout => match output_name(input, None, Output::of(&job.args)) {
            Dest::File(p) => p,
            Dest::Stdout => PathBuf::from("a.gbc"),
        },
    };
    let path = job
        .deps
        .mf
        .clone()
        .unwrap_or_else(|| target.with_extension("d"));
    Some(DepFile { target, path })
}

/// Refuses, before anything is written, an output or dependency file
/// that would replace a file the compile read, and a dependency file that
/// would replace the output: `-o` and `-MF` name any file, and a default
/// name can meet one too (a source named `part.gbc` or `part.d`).
fn check_overwrites(
    job: &Job,
    c: &Compiled,
    dest: &Dest,
    deps: Option<&DepFile>,
) -> Result<(), String> {
    let read = files_read(job, c);
    if let Dest::File(out) = dest {
        refuse_replacing("output", out, &read)?;
    }
    // (`-MF -` writes the rule to standard output.)
    let Some(Dest::File(path)) = deps.map(|d| Dest::new(&d.path)) else {
        return Ok(());
    };
    refuse_replacing("dependency file", &path, &read)?;
    match dest {
        Dest::File(out) if cli::io::replaces(&path, out) => Err(format!(
            "the dependency file {} is the output {}: refusing to overwrite it",
            path.display(),
            out.display()
        )),
        _ => Ok(()),
    }
}

/// The files a compile read, each with what messages call it: the
/// inputs of the command line (all of them: a later one is read after
/// this output is written), the library programs linked, the machine
/// and `--vars` files.
fn files_read<'a>(job: &'a Job, c: &'a Compiled) -> Vec<(&'static str, &'a Path)> {
    let args = &job.args;
    let inputs = args.files.iter().filter(|f| f.as_os_str() != "-");
    let mut read: Vec<(&str, &Path)> = inputs.map(|f| ("the input", f.as_path())).collect();
    // The first file is the program itself, named as its input.
    let linked = c.files.iter().skip(1).map(|f| Path::new(&f.name));
    read.extend(linked.map(|f| ("the library program", f)));
    read.extend(args.machine.as_deref().map(|m| ("the machine file", m)));
    read.extend(args.vars.as_deref().map(|v| ("the --vars file", v)));
    read
}

fn refuse_replacing(what: &str, out: &Path, read: &[(&str, &Path)]) -> Result<(), String> {
    match read.iter().find(|(_, f)| cli::io::replaces(out, f)) {
        Some((kind, f)) => Err(format!(
            "the {what} {} is {kind} {}: refusing to overwrite it",
            out.display(),
            f.display()
        )),
        None => Ok(()),
    }
}

/// Writes the make rule naming the source, the library programs and the
/// machine file.
fn write_deps(job: &Job, deps: &DepFile, c: &Compiled) -> Result<(), String> {
    let mut names: Vec<String> = c.files.iter().map(|f| f.name.clone()).collect();
    names.retain(|d| d != STDIN_NAME);
    if let Some(m) = &job.args.machine {
        names.push(m.display().to_string());
    }
    let rule = cli::depfile::rule(&deps.target.display().to_string(), &names);
    Dest::new(&deps.path).write(rule.as_bytes())
}

/// `--explain CODE`.
fn explain(code: &str) -> Exit {
    match cli::explain::find(code) {
        Some(e) => match Dest::Stdout.write(cli::explain::render(&e).as_bytes()) {
            Ok(()) => Exit::Ok,
            Err(_) => Exit::Write,
        },
        None => usage(&format!(
            "no diagnostic code '{code}' (codes are listed in docs/diagnostics.md)"
        )),
    }
}

/// -E: runs the module on the reference host (#500–#999 from `--vars`)
/// and returns what it did as G-code, and the alarm that ended it early.
fn expand(c: &Compiled, src: &[u8], opts: &Options) -> (String, Option<String>) {
    let machine = &opts.machine;
    let Some(module) = c.module.clone() else {
        return (String::new(), Some("no module was produced".into()));
    };
    let (mut ast, _) = grammar::parse(src);
    // The N of a G10 L52 block is a parameter number, not a label.
    compiler::data_setting::prepare(&mut ast);
    let file = &c.files[0];
    let mut seqs = std::collections::HashMap::new();
    for line in &ast.lines {
        if let grammar::ast::Line::Block(b) = line {
            if let Some(s) = b.seq {
                seqs.insert(file.line_col(b.span.start).0 as u32, s.number);
            }
        }
    }
    let mut vm = vm::Vm::new(module, machine.clone());
    if let Some(vars) = &opts.vars {
        *vm.persistent_mut() = **vars;
    }
    let zero = vm.nc.origin();
    let point = machine.machine.decimal_point == nc::machine::DecimalPoint::Increment;
    let mut out = cli::expand::Expand::new(seqs, (zero.x(), zero.z), point);
    let mut events = nc::Placed::default();
    loop {
        let start = (vm.nc.position().x(), vm.nc.position().z);
        let status = vm.step(1 << 16, &mut events);
        // A block of words computed at run time (`exec`, `execmove`): its
        // values are this run's, not the program's.
        let dynamic = |pc: u32| {
            matches!(
                vm.module().code.get(pc as usize),
                Some(isa::Instr::Exec { .. } | isa::Instr::ExecMove)
            )
        };
        let mut ran = false;
        for (run, pc) in events.runs() {
            let (line, pc) = match pc {
                Some(pc) => (vm.loc_at(pc).line, pc),
                None => (vm.last_loc().line, vm.last_block_pc()),
            };
            out.block_events(run, line, dynamic(pc), start);
            ran = true;
        }
        if !ran {
            // (A step that printed nothing is told too: the listing takes
            // the tool's start from the first step.)
            out.block_events(&[], vm.last_loc().line, dynamic(vm.last_block_pc()), start);
        }
        events.clear();
        match status {
            vm::Status::Event | vm::Status::OutOfBudget | vm::Status::Sync => continue,
            vm::Status::Done => return (out.out, None),
            vm::Status::Alarm(a) => return (out.out, Some(a.header())),
        }
    }
}

/// -fsyntax-only: the parser's findings alone.
fn syntax(name: &str, bytes: &[u8]) -> Compiled {
    let (_, diags) = grammar::parse(bytes);
    Compiled {
        module: None,
        files: vec![grammar::SourceFile::new(name, bytes)],
        diags: diags.into_iter().map(|d| (0, d)).collect(),
    }
}
