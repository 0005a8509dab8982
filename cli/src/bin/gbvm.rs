//! `gbvm`: runs, disassembles and verifies `.gbc` modules.

use clap::{Parser, Subcommand, ValueEnum};
use nc::{Event, Sink};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use vm::{Status, Vm};

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
enum Format {
    Csv,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Run a module and print what the machine is told to do.
    Run {
        file: PathBuf,
        /// canon: the motion listing of canon.md; trace: one line per
        /// interpolation period (time_s,x,z,spindle_rpm,feed,line; a c
        /// column after z on a machine with a C axis).
        #[arg(long, value_enum, default_value = "canon")]
        emit: Emit,
        /// Format of the trace: CSV with a header, or JSON lines.
        #[arg(long, value_enum, default_value = "csv")]
        format: Format,
        /// Draw the XZ toolpath into an SVG file (rapids dashed, feeds
        /// solid, threads in their own colour).
        #[arg(long, value_name = "FILE.svg")]
        plot: Option<PathBuf>,
        /// Print cycle time per tool and in total, distance cut and at
        /// rapid, and blocks executed (on stderr).
        #[arg(long)]
        stats: bool,
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
        /// Block budget (E6005 past it); default run.max_blocks.
        #[arg(long, value_name = "N")]
        max_blocks: Option<u64>,
        /// Simulated seconds a timed run (--emit trace, --plot, --stats)
        /// may last before it stops with E6006; default run.max_time_s.
        #[arg(long, value_name = "S")]
        max_time: Option<f64>,
        /// Passes a main-program M99 makes before the run ends.
        #[arg(long, value_name = "N", default_value_t = 1)]
        repeat: u32,
        /// Keep #500–#999 in FILE (loaded at the start, rewritten
        /// crash-safely whenever the program changes them).
        #[arg(long, value_name = "FILE")]
        vars: Option<PathBuf>,
    },
    /// Print the annotated listing of a module.
    Disasm { file: PathBuf },
    /// Load and verify a module.
    Verify { file: PathBuf },
}

fn load(path: &Path) -> Result<isa::Module, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    isa::Module::from_bytes(&bytes)
        .map_err(|e| format!("{}: not a valid .gbc module: {e}", path.display()))
}

fn fail(msg: &str) -> ExitCode {
    note(format_args!("gbvm: error: {msg}"));
    ExitCode::from(1)
}

/// One line on stderr; a stderr that cannot be written to (`2>/dev/full`)
/// has nobody left to tell, so its error is dropped rather than panicking.
fn note(line: std::fmt::Arguments) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Exit code of a run whose output could not be written (README).
const EXIT_OUTPUT: u8 = 3;

/// The end of a command whose standard output failed: a closed pipe
/// (`| head`) is the reader's choice and goes unremarked; any other error
/// (a full device) is reported. Either way the output is incomplete, so the
/// command does not succeed.
fn output_failed(e: &std::io::Error) -> ExitCode {
    if e.kind() != std::io::ErrorKind::BrokenPipe {
        note(format_args!("gbvm: error: standard output: {e}"));
    }
    ExitCode::from(EXIT_OUTPUT)
}

/// Writes `text` to stdout and flushes it.
fn print_all(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()
}

/// Prints each event as one canon line. After the first write error it
/// writes no more and keeps the error for the exit status.
struct Canon<W: Write> {
    out: W,
    error: Option<std::io::Error>,
}

impl<W: Write> Sink for Canon<W> {
    fn emit(&mut self, e: Event) {
        if self.error.is_none() {
            if let Err(err) = writeln!(self.out, "{e}") {
                self.error = Some(err);
            }
        }
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match args.command {
        Command::Disasm { file } => match load(&file) {
            Ok(m) => match print_all(&m.disassemble()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => output_failed(&e),
            },
            Err(e) => fail(&e),
        },
        Command::Verify { file } => match load(&file) {
            Ok(_) => match print_all(&format!("{}: ok\n", file.display())) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => output_failed(&e),
            },
            Err(e) => fail(&e),
        },
        Command::Run {
            file,
            emit,
            format,
            plot,
            stats,
            machine,
            max_blocks,
            max_time,
            repeat,
            vars,
        } => {
            if emit == Emit::Canon && format == Format::Json {
                return fail("--format json applies to --emit trace");
            }
            if emit == Emit::Canon && plot.is_none() && !stats {
                return run(
                    &file,
                    machine.as_deref(),
                    max_blocks,
                    repeat,
                    vars.as_deref(),
                );
            }
            if let Some(t) = max_time.filter(|t| !(t.is_finite() && *t > 0.0 && *t <= 1.0e6)) {
                return fail(&format!(
                    "--max-time {t}: give seconds above 0, at most 1000000"
                ));
            }
            let out = Outputs {
                trace: (emit == Emit::Trace).then_some(format),
                plot,
                stats,
                max_time,
            };
            run_timed(
                &file,
                machine.as_deref(),
                max_blocks,
                repeat,
                vars.as_deref(),
                &out,
            )
        }
    }
}

fn run(
    file: &Path,
    machine: Option<&Path>,
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&Path>,
) -> ExitCode {
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let machine = match cli::load_machine(machine) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    if module.machine != machine.compile_keys() {
        return fail(&format!(
            "{} was compiled for another machine configuration (its compile-time keys differ); compile it again with this --machine",
            file.display()
        ));
    }
    let mut vm = Vm::new(module, machine);
    if let Some(n) = max_blocks {
        vm.max_blocks = n;
    }
    vm.repeat = repeat.max(1);
    let store = vars.map(Path::to_path_buf).or_else(|| {
        let f = &vm.nc.machine.r#macro.persistent_file;
        (!f.is_empty()).then(|| PathBuf::from(f))
    });
    let vars_file = match store.map(|p| cli::vars::VarsFile::open(&p)).transpose() {
        Ok(v) => v.map(|(file, values)| {
            *vm.persistent_mut() = values;
            vm.set_storage(file.storage());
            file
        }),
        Err(e) => return fail(&e),
    };
    let stdout = std::io::stdout();
    let mut sink = Canon {
        out: BufWriter::new(stdout.lock()),
        error: None,
    };
    let status = vm.run(&mut sink);
    if let (None, Err(e)) = (&sink.error, sink.out.flush()) {
        sink.error = Some(e);
    }
    if let Status::Alarm(a) = &status {
        note(format_args!("{}", a.header()));
    }
    if let Some(Err(e)) = vars_file.map(cli::vars::VarsFile::finish) {
        return fail(&e);
    }
    match (sink.error, status) {
        (Some(e), _) => output_failed(&e),
        (None, Status::Alarm(_)) => ExitCode::from(2),
        (None, _) => ExitCode::SUCCESS,
    }
}

/// What a run through the interpolation runtime writes.
struct Outputs {
    /// The per-period trace on stdout (else the canon is printed there).
    trace: Option<Format>,
    plot: Option<PathBuf>,
    stats: bool,
    /// `--max-time`, else the machine's run.max_time_s.
    max_time: Option<f64>,
}

/// The alarm of a timed run that used up its simulated time (E6006,
/// README): a run that cannot end (an endless dwell, a move of 10^20 mm,
/// a feed override of 0) stops instead of writing without end.
const E_TIME: u32 = 6006;

/// Runs the module through the interpolation runtime, period by period,
/// as the reference host: every PLC function completes at once and cycle
/// start is pressed at every stop.
fn run_timed(
    file: &Path,
    machine: Option<&Path>,
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&Path>,
    out: &Outputs,
) -> ExitCode {
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let machine = match cli::load_machine(machine) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let mut ctl = match runtime::Controller::new(module, machine, runtime::AutoAck) {
        Ok(c) => c,
        Err(runtime::LoadError::Machine) => {
            return fail(&format!(
                "{} was compiled for another machine configuration (its compile-time keys differ); compile it again with this --machine",
                file.display()
            ))
        }
        Err(e) => return fail(&format!("{}: {e}", file.display())),
    };
    if let Some(n) = max_blocks {
        ctl.set_max_blocks(n);
    }
    ctl.set_repeat(repeat);
    let store = vars.map(Path::to_path_buf).or_else(|| {
        let f = &ctl.machine().r#macro.persistent_file;
        (!f.is_empty()).then(|| PathBuf::from(f))
    });
    let vars_file = match store.map(|p| cli::vars::VarsFile::open(&p)).transpose() {
        Ok(v) => v.map(|(file, values)| {
            *ctl.vm_mut().persistent_mut() = values;
            ctl.vm_mut().set_storage(file.storage());
            file
        }),
        Err(e) => return fail(&e),
    };
    let stdout = std::io::stdout();
    // The canon goes to stdout when no trace does.
    let mut canon = Canon {
        out: BufWriter::new(stdout.lock()),
        error: None,
    };
    if out.trace == Some(Format::Csv) {
        let c_axis = ctl.engine().config().c.is_some();
        if let Err(e) = writeln!(canon.out, "{}", runtime::trace::csv_header(c_axis)) {
            canon.error = Some(e);
        }
    }
    let period = ctl.engine().config().period_s;
    let mut stats = runtime::stats::Stats::new(period);
    let mut plot = out.plot.as_ref().map(|_| runtime::plot::Plot::new());
    let mut line = String::new();
    struct Quiet;
    impl Sink for Quiet {
        fn emit(&mut self, _: Event) {}
    }
    let mut quiet = Quiet;
    let max_time = out.max_time.unwrap_or(ctl.machine().run.max_time_s);
    // Whole periods: the bound is exact in ticks, not subject to a sum of
    // rounded times.
    let max_ticks = (max_time / period).ceil() as u64;
    let mut ticks = 0u64;
    let mut timed_out = None;
    ctl.cycle_start();
    loop {
        if out.trace.is_none() {
            ctl.run_ahead_tap(&mut canon);
        } else {
            ctl.run_ahead_tap(&mut quiet);
        }
        let sp = ctl.tick();
        ticks += 1;
        if let Some(f) = out.trace {
            line.clear();
            let _ = match f {
                Format::Csv => runtime::trace::write_csv(&mut line, &sp),
                Format::Json => runtime::trace::write_json(&mut line, &sp),
            };
            if canon.error.is_none() {
                if let Err(e) = canon.out.write_all(line.as_bytes()) {
                    canon.error = Some(e);
                }
            }
        }
        stats.add(&sp);
        if let Some(p) = plot.as_mut() {
            p.add(&sp);
        }
        match ctl.state() {
            runtime::RunState::Stopped(_) | runtime::RunState::Idle => ctl.cycle_start(),
            runtime::RunState::Ended | runtime::RunState::Alarm(_) => break,
            _ => {}
        }
        // The output is what a timed run is for: once it fails, stop.
        if canon.error.is_some() {
            break;
        }
        if ticks >= max_ticks {
            timed_out = Some(sp.line);
            break;
        }
    }
    stats.blocks = ctl.blocks();
    let alarm = match timed_out {
        Some(line) => Some(time_alarm(&mut ctl, line, max_time)),
        None => ctl.alarm(),
    };
    // A VM alarm printed its ALARM line with the canon; the runtime's own
    // (E7001, E7002, E7003, E4010) end the canon here.
    if let (Some(a), None) = (&alarm, out.trace) {
        if matches!(a.code, 7001 | 7002 | 7003 | 4010 | E_TIME) {
            canon.emit(Event::Alarm {
                code: a.code,
                msg: a.message.clone(),
            });
        }
    }
    if let (None, Err(e)) = (&canon.error, canon.out.flush()) {
        canon.error = Some(e);
    }
    let output_error = canon.error.take();
    drop(canon);
    if let Some(Err(e)) = vars_file.map(cli::vars::VarsFile::finish) {
        return fail(&e);
    }
    if let (Some(path), Some(p)) = (&out.plot, plot.as_mut()) {
        let title = file.display().to_string();
        if let Err(e) = std::fs::write(path, p.svg(&title)) {
            return fail(&format!("{}: {e}", path.display()));
        }
    }
    if out.stats {
        let _ = write!(std::io::stderr().lock(), "{stats}");
    }
    if let Some(a) = &alarm {
        note(format_args!("{}", a.header()));
    }
    match (output_error, alarm) {
        (Some(e), _) => output_failed(&e),
        (None, Some(_)) => ExitCode::from(2),
        (None, None) => ExitCode::SUCCESS,
    }
}

/// E6006 at the block running when the time ran out (its line in the
/// main file: the set point carries the line only).
fn time_alarm(ctl: &mut runtime::Controller, line: u32, max_time: f64) -> runtime::AlarmInfo {
    let file = ctl
        .vm_mut()
        .module()
        .files
        .first()
        .map_or_else(String::new, |f| f.name.clone());
    runtime::AlarmInfo {
        code: E_TIME,
        message: format!(
            "the run did not end within {max_time} s of simulated time (run.max_time_s, --max-time)"
        ),
        file,
        line,
        col: 1,
    }
}
