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
    isa::Module::from_bytes(&bytes).map_err(|e| format!("{name}: not a valid .gbc module: {e}"))
}

fn fail(msg: &str) -> ExitCode {
    let _ = writeln!(std::io::stderr(), "gbvm: error: {msg}");
    cli::exit::Exit::Input.into()
}

/// Prints each event as one canon line.
struct Canon<W: Write> {
    out: W,
    broken: bool,
}

impl<W: Write> Sink for Canon<W> {
    fn emit(&mut self, e: Event) {
        if !self.broken && writeln!(self.out, "{e}").is_err() {
            self.broken = true;
        }
    }
}

/// Writes a listing to standard output; a full disk or a closed pipe is
/// exit code 3 (cli::exit), not a panic.
fn print_out(text: &str) -> ExitCode {
    match cli::io::Dest::Stdout.write(text.as_bytes()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "gbvm: error: {e}");
            cli::exit::Exit::Write.into()
        }
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
        Command::Verify { file } => match load(&file) {
            Ok(_) => print_out(&format!("{}: ok\n", file.display())),
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
            repeat,
            vars,
        } => {
            if emit == Emit::Canon && format == Format::Json {
                let _ = writeln!(
                    std::io::stderr(),
                    "gbvm: error: --format json applies to --emit trace"
                );
                return cli::exit::Exit::Usage.into();
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
            let out = Outputs {
                trace: (emit == Emit::Trace).then_some(format),
                plot,
                stats,
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
    if let Some(path) = store {
        match cli::vars::load(&path) {
            Ok(values) => *vm.persistent_mut() = values,
            Err(e) => return fail(&e),
        }
        vm.set_storage(Box::new(cli::vars::FileStorage(path)));
    }
    let stdout = std::io::stdout();
    let mut sink = Canon {
        out: BufWriter::new(stdout.lock()),
        broken: false,
    };
    let status = vm.run(&mut sink);
    let lost = sink.out.flush().is_err() || sink.broken;
    if let Status::Alarm(a) = &status {
        let _ = writeln!(std::io::stderr(), "{}", a.header());
    }
    // The canon is the run's result: losing it is a failure of its own.
    if lost {
        let _ = writeln!(
            std::io::stderr(),
            "gbvm: error: cannot write the canon to standard output"
        );
        return cli::exit::Exit::Write.into();
    }
    match status {
        Status::Alarm(_) => cli::exit::Exit::Alarm.into(),
        _ => ExitCode::SUCCESS,
    }
}

/// What a run through the interpolation runtime writes.
struct Outputs {
    /// The per-period trace on stdout (else the canon is printed there).
    trace: Option<Format>,
    plot: Option<PathBuf>,
    stats: bool,
}

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
    if let Some(path) = store {
        match cli::vars::load(&path) {
            Ok(values) => *ctl.vm_mut().persistent_mut() = values,
            Err(e) => return fail(&e),
        }
        ctl.vm_mut()
            .set_storage(Box::new(cli::vars::FileStorage(path)));
    }
    let stdout = std::io::stdout();
    let mut w = BufWriter::new(stdout.lock());
    let mut broken = false;
    if out.trace == Some(Format::Csv) {
        let c_axis = ctl.engine().config().c.is_some();
        broken |= writeln!(w, "{}", runtime::trace::csv_header(c_axis)).is_err();
    }
    let period = ctl.engine().config().period_s;
    let mut stats = runtime::stats::Stats::new(period);
    let mut plot = out.plot.as_ref().map(|_| runtime::plot::Plot::new());
    let mut line = String::new();
    {
        // The canon goes to stdout when no trace does.
        let mut canon = Canon {
            out: &mut w,
            broken: false,
        };
        struct Quiet;
        impl Sink for Quiet {
            fn emit(&mut self, _: Event) {}
        }
        let mut quiet = Quiet;
        ctl.cycle_start();
        loop {
            if out.trace.is_none() {
                ctl.run_ahead_tap(&mut canon);
            } else {
                ctl.run_ahead_tap(&mut quiet);
            }
            let sp = ctl.tick();
            if let Some(f) = out.trace {
                line.clear();
                let _ = match f {
                    Format::Csv => runtime::trace::write_csv(&mut line, &sp),
                    Format::Json => runtime::trace::write_json(&mut line, &sp),
                };
                if !broken && canon.out.write_all(line.as_bytes()).is_err() {
                    broken = true;
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
        }
        broken |= canon.broken;
    }
    stats.blocks = ctl.blocks();
    let alarm = ctl.alarm();
    // A VM alarm printed its ALARM line with the canon; the runtime's own
    // (E7001, E7002, E7003, E4010) end the canon here.
    if let (Some(a), None) = (&alarm, out.trace) {
        if matches!(a.code, 7001 | 7002 | 7003 | 4010) {
            let e = Event::Alarm {
                code: a.code,
                msg: a.message.clone(),
            };
            broken |= writeln!(w, "{e}").is_err();
        }
    }
    // A closed stdout (`| head`) ends the output, not the run.
    let _ = broken;
    let _ = w.flush();
    drop(w);
    if let (Some(path), Some(p)) = (&out.plot, plot.as_mut()) {
        let title = file.display().to_string();
        if let Err(e) = std::fs::write(path, p.svg(&title)) {
            return fail(&format!("{}: {e}", path.display()));
        }
    }
    if out.stats {
        eprint!("{stats}");
    }
    match alarm {
        Some(a) => {
            eprintln!("{}", a.header());
            ExitCode::from(2)
        }
        None => ExitCode::SUCCESS,
    }
}
