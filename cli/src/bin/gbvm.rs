//! `gbvm`: runs, disassembles and verifies `.gbc` modules.

// The arguments' doc comments are clap's help text, not rustdoc: `X<diameter>`
// there is what the user types.
#![allow(rustdoc::invalid_html_tags)]

use clap::{Parser, Subcommand, ValueEnum};

use nc::Machine;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use vm::{Status, Vm};

#[path = "gbvm/check.rs"]
mod check;
#[path = "gbvm/timed.rs"]
mod timed;

use timed::{Outputs, StatsTo};

/// The alarm of a timed run that used up its simulated time (E6006,
/// docs/machine.md): a run that cannot end (an endless dwell, a move of
/// 10^20 mm, a feed override of 0) stops instead of writing without end.
const E_TIME: u32 = 6006;

/// What `gbvm run` runs, and how, whatever it writes.
struct RunArgs<'a> {
    file: &'a Path,
    machine: (Option<&'a Path>, Option<Switch>),
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&'a Path>,
    jit: cli::jit::JitMode,
    from: Option<vm::restart::RestartAt>,
}

/// mimalloc (cli::allocator says why).
#[global_allocator]
static ALLOCATOR: cli::allocator::Mimalloc = cli::allocator::Mimalloc;

#[derive(Parser)]
#[command(name = "gbvm", version, about = "Run gbc bytecode")]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Emit {
    Canon,
    Trace,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum StatsFormat {
    Text,
    Json,
}

/// A panel switch given on the command line.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Switch {
    On,
    Off,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
    Csv,
    Json,
}

/// The coordinates of the trace (runtime::trace::Frame).
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum FrameArg {
    Work,
    Machine,
    Counts,
}

impl From<FrameArg> for runtime::trace::Frame {
    fn from(f: FrameArg) -> Self {
        match f {
            FrameArg::Work => runtime::trace::Frame::Work,
            FrameArg::Machine => runtime::trace::Frame::Machine,
            FrameArg::Counts => runtime::trace::Frame::Counts,
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Run a module and print what the machine is told to do.
    Run(RunCmd),
    /// Run a module through the runtime and certify every period: axis
    /// velocity, acceleration (and jerk where limited) within the
    /// machine's limits, every canon end point reached, thread leads,
    /// G96 and the spindle. Prints one summary line; exit 0 when all
    /// hold, 1 with the first violation, 2 when the run does not end, 3
    /// when the line could not be written.
    Check {
        file: PathBuf,
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
        /// Simulated seconds the run may last (E6006 past it); default
        /// run.max_time_s.
        #[arg(long, value_name = "S")]
        max_time: Option<f64>,
        /// Certify the run restarted at this block, as `gbvm run --from`
        /// (the approach included).
        #[arg(long, value_name = "LINE|N…[@PASS]")]
        from: Option<vm::restart::RestartAt>,
    },
    /// Print the annotated listing of a module.
    Disasm { file: PathBuf },
    /// Load and verify a module.
    Verify { file: PathBuf },
}

/// `gbvm run`'s arguments.
#[derive(clap::Args)]
struct RunCmd {
    file: PathBuf,
    /// canon: the motion listing (docs/formats.md); trace: one line
    /// per interpolation period
    /// (time_s,x,z,spindle_rpm,feed,line,motion,tool,file; a c column
    /// after z on a machine with a C axis). Default: canon, or nothing
    /// when --stats takes standard output.
    #[arg(long, value_enum)]
    emit: Option<Emit>,
    /// Format of the trace: CSV with a header, or JSON lines.
    #[arg(long, value_enum, default_value = "csv")]
    format: Format,
    /// Coordinates of the trace's x and z (and c): work (the programmed
    /// point, as the canon), machine (the axis set points from machine
    /// zero, work zero and tool offset applied) or counts (the machine
    /// set points as whole steps of the resolution, C in 0.001°, the axis
    /// compensation added: what a position-command or pulse interface
    /// sends). Default: work.
    #[arg(long, value_enum, value_name = "work|machine|counts")]
    frame: Option<FrameArg>,
    /// Draw the XZ toolpath into an SVG file, framed on the cutting
    /// moves (rapids dashed, feeds solid, threads in their own colour;
    /// start point, tool changes and stock marked).
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// The stock the plot draws: X<diameter> Z<length>, face at Z0
    /// (default: the program's [BILLET line, else the corner of its
    /// first roughing cycle).
    #[arg(long, value_name = "X… Z…")]
    stock: Option<String>,
    /// Print cycle time in total, per tool and per operation (h:mm:ss
    /// and seconds), distances and blocks: on stdout without --emit,
    /// else on stderr. --stats=json for one JSON object.
    #[arg(long, value_enum, num_args = 0..=1, require_equals = true, default_missing_value = "text", value_name = "FORMAT")]
    stats: Option<StatsFormat>,
    /// No progress bar.
    #[arg(long, short = 'q')]
    quiet: bool,
    #[arg(long, value_name = "FILE")]
    machine: Option<PathBuf>,
    /// The block-skip switches /1–/9 at the start: on skips the `/`
    /// blocks; default operator.block_skip of the machine file.
    #[arg(long, value_enum, value_name = "on|off")]
    block_skip: Option<Switch>,
    /// Block budget (E6005 past it); default run.max_blocks.
    #[arg(long, value_name = "N")]
    max_blocks: Option<u64>,
    /// Simulated seconds a timed run (--emit trace, --plot, --stats)
    /// may last before it stops with E6006; default run.max_time_s.
    #[arg(long, value_name = "S")]
    max_time: Option<f64>,
    /// Program restart: run from this block of the main file, a line
    /// (120) or a sequence number (N120); @PASS for the PASS-th time the
    /// run reaches it (N120@3). The blocks before it run without motion;
    /// then the last origin, tool, speed, spindle, coolant and feed are
    /// given again and the tool goes where the whole run's tool stands
    /// there (under G41/G42, on the compensated path), X first, then Z
    /// (Z first with the machine file's run.restart_approach =
    /// "z_then_x").
    #[arg(long, value_name = "LINE|N…[@PASS]")]
    from: Option<vm::restart::RestartAt>,
    /// Passes a main-program M99 makes before the run ends.
    #[arg(long, value_name = "N", default_value_t = 1)]
    repeat: u32,
    /// Make N parts in a row, as cycle start after each end makes them
    /// on a controller: each part from where the one before left the
    /// axes, the part counter (#3901) and the tool life of the machine
    /// file's groups carried on. Runs through the runtime; --max-time
    /// bounds each part.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    parts: Option<u32>,
    /// Keep #500–#999 in FILE (loaded at the start, rewritten
    /// crash-safely whenever the program changes them).
    #[arg(long, value_name = "FILE")]
    vars: Option<PathBuf>,
    /// Compile hot macro loops to machine code: auto (a loop that has
    /// gone round 500 times), always (at its first round), off. The
    /// output is the same either way.
    #[arg(
        long,
        value_enum,
        default_value = "auto",
        value_name = "auto|always|off"
    )]
    jit: cli::jit::JitMode,
}

/// Reads and verifies a module; `-` is standard input. A source program
/// given by mistake is told to be compiled first.
fn load(path: &Path) -> Result<isa::Module, String> {
    let (name, bytes) = cli::io::read_input(path)?;
    if !cli::io::is_module(&bytes) && !bytes.is_empty() && bytes.is_ascii() {
        return Err(format!(
            "{name} is G-code source, not a .gbc module: compile it first \
             (gbcc {name} -o x.gbc && gbvm run x.gbc)"
        ));
    }
    // The buffer becomes the module's typed blocks: the file is held once.
    isa::Module::from_vec(bytes).map_err(|e| format!("{name}: not a valid .gbc module: {e}"))
}

/// Text that comes from a module's tables (file names, messages), as the
/// canon prints strings (canon.md): `"` and every character outside
/// printable ASCII become `?`. A crafted module then cannot put escape
/// sequences or extra, fake diagnostic lines on the terminal, and an
/// alarm's message reads as in the canon's `MSG` (a program's text, one
/// `?` per byte, comes so from `NcError::header` already).
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            ' '..='~' if c != '"' => c,
            _ => '?',
        })
        .collect()
}

fn fail(msg: &str) -> ExitCode {
    note(format_args!("gbvm: error: {msg}"));
    cli::exit::Exit::Input.into()
}

/// One line on stderr; a stderr that cannot be written to (`2>/dev/full`)
/// has nobody left to tell, so its error is dropped rather than panicking.
fn note(line: std::fmt::Arguments) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// The end of a command whose standard output failed: a closed pipe
/// (`| head`) is the reader's choice and goes unremarked; any other error
/// (a full device) is reported. Either way the output is incomplete, so the
/// command does not succeed (exit 3, cli::exit).
fn output_failed(e: &std::io::Error) -> ExitCode {
    if e.kind() != std::io::ErrorKind::BrokenPipe {
        note(format_args!("gbvm: error: standard output: {e}"));
    }
    cli::exit::Exit::Write.into()
}

/// Writes a listing to standard output and flushes it.
fn print_out(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => output_failed(&e),
    }
}

fn main() -> ExitCode {
    let args: Args = match cli::exit::parse_args(std::env::args_os().collect()) {
        Ok(a) => a,
        Err(e) => return e.into(),
    };
    match args.command {
        Command::Disasm { file } => match load(&file) {
            Ok(m) => print_out(&m.disassemble()),
            Err(e) => fail(&e),
        },
        Command::Check {
            file,
            machine,
            max_time,
            from,
        } => match check_max_time(max_time) {
            Ok(()) => check::check(&file, machine.as_deref(), max_time, from),
            Err(code) => code,
        },
        Command::Verify { file } => match load(&file) {
            Ok(_) => print_out(&format!("{}: ok\n", file.display())),
            Err(e) => fail(&e),
        },
        Command::Run(cmd) => run_command(&cmd),
    }
}

/// `gbvm run`: checks the arguments' combinations, then runs to the
/// canon alone, or through the runtime for the other outputs.
fn run_command(cmd: &RunCmd) -> ExitCode {
    // --stats alone takes stdout; an explicit --emit keeps it.
    let stats_out = match (cmd.stats, cmd.emit) {
        (None, _) => None,
        (Some(f), None) => Some((f, StatsTo::Stdout)),
        (Some(f), Some(_)) => Some((f, StatsTo::Stderr)),
    };
    let emit = match (cmd.emit, cmd.stats) {
        (Some(e), _) => Some(e),
        (None, Some(_)) => None,
        (None, None) => Some(Emit::Canon),
    };
    if let Err(code) = check_run_options(cmd, emit) {
        return code;
    }
    let stock = match cmd.stock.as_deref().map(cli::program_info::parse_stock) {
        None => None,
        Some(Ok(s)) => Some(s),
        Some(Err(e)) => return fail(&e),
    };
    let run_args = RunArgs {
        file: &cmd.file,
        machine: (cmd.machine.as_deref(), cmd.block_skip),
        max_blocks: cmd.max_blocks,
        repeat: cmd.repeat,
        vars: cmd.vars.as_deref(),
        jit: cmd.jit,
        from: cmd.from,
    };
    let timed = cmd.plot.is_some() || cmd.stats.is_some() || cmd.parts.is_some();
    if emit == Some(Emit::Canon) && !timed {
        return run(&run_args, cmd.quiet);
    }
    let out = Outputs {
        canon: emit == Some(Emit::Canon),
        trace: (emit == Some(Emit::Trace)).then_some(cmd.format),
        frame: cmd.frame.map_or(runtime::trace::Frame::Work, Into::into),
        plot: cmd.plot.clone(),
        stock,
        stats: stats_out,
        quiet: cmd.quiet,
        max_time: cmd.max_time,
        parts: cmd.parts,
    };
    timed::run_timed(&run_args, &out)
}

/// Usage errors of `gbvm run`: options that apply only to the trace, and
/// a --max-time out of range.
fn check_run_options(cmd: &RunCmd, emit: Option<Emit>) -> Result<(), ExitCode> {
    if emit != Some(Emit::Trace) && cmd.format == Format::Json {
        let _ = writeln!(
            std::io::stderr(),
            "gbvm: error: --format json applies to --emit trace"
        );
        return Err(cli::exit::Exit::Usage.into());
    }
    if emit != Some(Emit::Trace) && cmd.frame.is_some() {
        note(format_args!("gbvm: error: --frame applies to --emit trace"));
        return Err(cli::exit::Exit::Usage.into());
    }
    check_max_time(cmd.max_time)
}

/// `--max-time` must be a number of seconds in (0, 10^6].
fn check_max_time(max_time: Option<f64>) -> Result<(), ExitCode> {
    if let Some(t) = max_time.filter(|t| !(t.is_finite() && *t > 0.0 && *t <= 1.0e6)) {
        // (`{t:?}`: 1e300 as such; Display writes out its 301 digits.)
        note(format_args!(
            "gbvm: error: --max-time {t:?}: give seconds above 0, at most 1000000"
        ));
        return Err(cli::exit::Exit::Usage.into());
    }
    Ok(())
}

/// The machine file (or the reference machine) with the panel's
/// block-skip switches as the command line sets them.
fn load_machine((path, block_skip): (Option<&Path>, Option<Switch>)) -> Result<Machine, String> {
    let mut machine = cli::load_machine(path)?;
    if let Some(s) = block_skip {
        *machine.operator.block_skip = [s == Switch::On; 9];
    }
    Ok(machine)
}

/// Runs the module to its canon, without the runtime (the canon is
/// written on a thread of its own).
fn run(args: &RunArgs, quiet: bool) -> ExitCode {
    let file = args.file;
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let main_lines = main_lines(&module);
    let machine = match load_machine(args.machine) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    if let Some(key) = nc::Machine::compile_keys_differ(&module.machine, &machine.compile_keys()) {
        return fail(&format!(
            "{} was compiled for another machine configuration ({key}); compile it again with this --machine",
            file.display()
        ));
    }
    let mut vm = Vm::new(module, machine);
    if let Some(n) = args.max_blocks {
        vm.max_blocks = n;
    }
    vm.repeat = args.repeat.max(1);
    // Only the canon is wanted: a step need not end at every block (it
    // still ends every 65 536 instructions for the progress bar).
    vm.stop_at_blocks = false;
    args.jit.attach(&mut vm);
    let vars_file = match open_vars(args.vars, &mut vm) {
        Ok(v) => v,
        Err(e) => return fail(&e),
    };
    // Block by block (as `Vm::run`), to move the progress bar.
    let mut progress = cli::progress::Progress::bar(main_lines, "run", quiet);
    let (status, output_error) = cli::canon::on_writer_thread(|sink| {
        if let Some(at) = args.from {
            restarted(&vm::restart::search(&mut vm, at, sink)?);
        }
        Ok(loop {
            match vm.step(1 << 16, sink) {
                Status::Event | Status::OutOfBudget | Status::Sync => {
                    progress.set_from(|| {
                        let line = vm.last_loc().line;
                        (line.into(), format!("line {line}"))
                    });
                }
                other => break other,
            }
        })
    });
    progress.finish();
    let status = match status {
        Ok(s) => s,
        Err(vm::restart::RestartError::Alarm(a)) => Status::Alarm(a),
        Err(e) => return fail(&format!("--from: {e}")),
    };
    if let Status::Alarm(a) = &status {
        note(format_args!("{}", printable(&a.header())));
    }
    if let Some(Err(e)) = vars_file.map(cli::vars::VarsFile::finish) {
        return fail(&e);
    }
    // The canon is the run's result: losing it is a failure of its own.
    match (output_error, status) {
        (Some(e), _) => output_failed(&e),
        (None, Status::Alarm(_)) => cli::exit::Exit::Alarm.into(),
        (None, _) => ExitCode::SUCCESS,
    }
}

/// What a restart (`--from`) does, told on stderr as a control's restart
/// page shows it: where the approach goes, the codes in force it resumes
/// with, and the M codes of the machine's own the blocks before gave,
/// which it does not give again.
fn restarted(r: &vm::restart::Restarted) {
    let to = r.destination;
    note(format_args!(
        "gbvm: note: --from: the approach goes to X{} Z{} (work coordinates)",
        nc::event::Num(to.x),
        nc::event::Num(to.z)
    ));
    note(format_args!(
        "gbvm: note: --from: the run resumes with {}",
        r.codes
    ));
    if r.m_codes.is_empty() {
        return;
    }
    let codes: Vec<String> = r.m_codes.iter().map(|m| format!("M{m:02}")).collect();
    note(format_args!(
        "gbvm: note: --from: the blocks before it gave {}, which a restart does not give again: give those the block needs by hand",
        codes.join(", ")
    ));
}

/// The main file's last line: the length of the progress bar.
fn main_lines(module: &isa::Module) -> u64 {
    module
        .lines
        .iter()
        .filter(|l| l.file == 0)
        .map(|l| u64::from(l.line))
        .max()
        .unwrap_or(1)
}

/// The file of #500–#999 the run starts from and leaves them in:
/// `--vars`, else the machine's persistent file; none when neither names
/// one. Its values are loaded into `vm`.
fn open_vars(vars: Option<&Path>, vm: &mut Vm) -> Result<Option<cli::vars::VarsFile>, String> {
    let store = vars.map(Path::to_path_buf).or_else(|| {
        let f = &vm.nc.machine.r#macro.persistent_file;
        (!f.is_empty()).then(|| PathBuf::from(f))
    });
    let Some((file, values)) = store.map(|p| cli::vars::VarsFile::open(&p)).transpose()? else {
        return Ok(None);
    };
    *vm.persistent_mut() = values;
    vm.set_storage(file.storage());
    Ok(Some(file))
}
