//! `gbvm`: runs, disassembles and verifies `.gbc` modules.

use clap::{Parser, Subcommand, ValueEnum};

use cli::canon::Canon;
use nc::{Event, Machine, Sink};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use vm::{Status, Vm};

#[path = "gbvm/check.rs"]
mod check;

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
}

impl From<FrameArg> for runtime::trace::Frame {
    fn from(f: FrameArg) -> Self {
        match f {
            FrameArg::Work => runtime::trace::Frame::Work,
            FrameArg::Machine => runtime::trace::Frame::Machine,
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Run a module and print what the machine is told to do.
    Run {
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
        /// Coordinates of the trace's x and z: work (the programmed point,
        /// as the canon) or machine (the axis set points from machine
        /// zero, work zero and tool offset applied). Default: work.
        #[arg(long, value_enum, value_name = "work|machine")]
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
        /// Passes a main-program M99 makes before the run ends.
        #[arg(long, value_name = "N", default_value_t = 1)]
        repeat: u32,
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
    },
    /// Run a module through the runtime and certify every period: axis
    /// velocity, acceleration (and jerk where limited) within the
    /// machine's limits, every canon end point reached, thread leads,
    /// G96 and the spindle. Prints one summary line; exit 0 when all
    /// hold, 1 with the first violation, 2 when the run does not end.
    Check {
        file: PathBuf,
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
        /// Simulated seconds the run may last (E6006 past it); default
        /// run.max_time_s.
        #[arg(long, value_name = "S")]
        max_time: Option<f64>,
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
    // The buffer becomes the module's typed blocks: the file is held once.
    isa::Module::from_vec(bytes).map_err(|e| format!("{name}: not a valid .gbc module: {e}"))
}

/// Text that comes from a module's tables (file names, messages), as the
/// canon prints strings (canon.md): `"` and every character outside
/// printable ASCII become `?`. A crafted module then cannot put escape
/// sequences or extra, fake diagnostic lines on the terminal, and an
/// alarm's message reads as in the canon's `MSG`.
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
        } => {
            if let Some(t) = max_time.filter(|t| !(t.is_finite() && *t > 0.0 && *t <= 1.0e6)) {
                note(format_args!(
                    "gbvm: error: --max-time {t}: give seconds above 0, at most 1000000"
                ));
                return cli::exit::Exit::Usage.into();
            }
            check::check(&file, machine.as_deref(), max_time)
        }
        Command::Verify { file } => match load(&file) {
            Ok(_) => print_out(&format!("{}: ok\n", file.display())),
            Err(e) => fail(&e),
        },
        Command::Run {
            file,
            emit,
            format,
            frame,
            plot,
            stock,
            stats,
            quiet,
            machine,
            block_skip,
            max_blocks,
            max_time,
            repeat,
            vars,
            jit,
        } => {
            // --stats alone takes stdout; an explicit --emit keeps it.
            let stats_out = match (stats, emit) {
                (None, _) => None,
                (Some(f), None) => Some((f, StatsTo::Stdout)),
                (Some(f), Some(_)) => Some((f, StatsTo::Stderr)),
            };
            let emit = match (emit, stats) {
                (Some(e), _) => Some(e),
                (None, Some(_)) => None,
                (None, None) => Some(Emit::Canon),
            };
            if emit != Some(Emit::Trace) && format == Format::Json {
                let _ = writeln!(
                    std::io::stderr(),
                    "gbvm: error: --format json applies to --emit trace"
                );
                return cli::exit::Exit::Usage.into();
            }
            if emit != Some(Emit::Trace) && frame.is_some() {
                note(format_args!("gbvm: error: --frame applies to --emit trace"));
                return cli::exit::Exit::Usage.into();
            }
            if let Some(t) = max_time.filter(|t| !(t.is_finite() && *t > 0.0 && *t <= 1.0e6)) {
                note(format_args!(
                    "gbvm: error: --max-time {t}: give seconds above 0, at most 1000000"
                ));
                return cli::exit::Exit::Usage.into();
            }
            let stock = match stock.as_deref().map(cli::program_info::parse_stock) {
                None => None,
                Some(Ok(s)) => Some(s),
                Some(Err(e)) => return fail(&e),
            };
            if emit == Some(Emit::Canon) && plot.is_none() && stats.is_none() {
                return run(
                    &file,
                    (machine.as_deref(), block_skip),
                    max_blocks,
                    repeat,
                    vars.as_deref(),
                    quiet,
                    jit,
                );
            }
            let out = Outputs {
                canon: emit == Some(Emit::Canon),
                trace: (emit == Some(Emit::Trace)).then_some(format),
                frame: frame.map_or(runtime::trace::Frame::Work, Into::into),
                plot,
                stock,
                stats: stats_out,
                quiet,
                max_time,
            };
            run_timed(
                &file,
                (machine.as_deref(), block_skip),
                max_blocks,
                repeat,
                vars.as_deref(),
                &out,
                jit,
            )
        }
    }
}

/// The machine file (or the reference machine) with the panel's
/// block-skip switches as the command line sets them.
fn load_machine((path, block_skip): (Option<&Path>, Option<Switch>)) -> Result<Machine, String> {
    let mut machine = cli::load_machine(path)?;
    if let Some(s) = block_skip {
        machine.operator.block_skip = [s == Switch::On; 9];
    }
    Ok(machine)
}

fn run(
    file: &Path,
    machine: (Option<&Path>, Option<Switch>),
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&Path>,
    quiet: bool,
    jit: cli::jit::JitMode,
) -> ExitCode {
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let main_lines = main_lines(&module);
    let machine = match load_machine(machine) {
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
    // Only the canon is wanted: a step need not end at every block (it
    // still ends every 65 536 instructions for the progress bar).
    vm.stop_at_blocks = false;
    jit.attach(&mut vm);
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
    // Block by block (as `Vm::run`), to move the progress bar.
    let mut progress = cli::progress::Progress::bar(main_lines, "run", quiet);
    let (status, output_error) = cli::canon::on_writer_thread(|sink| loop {
        match vm.step(1 << 16, sink) {
            Status::Event | Status::OutOfBudget | Status::Sync => {
                progress.set_from(|| {
                    let line = vm.last_loc().line;
                    (line.into(), format!("line {line}"))
                });
            }
            other => break other,
        }
    });
    progress.finish();
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

#[derive(Clone, Copy, PartialEq, Eq)]
enum StatsTo {
    Stdout,
    Stderr,
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

/// What a run through the interpolation runtime writes.
struct Outputs {
    /// The canon on stdout.
    canon: bool,
    /// The per-period trace on stdout.
    trace: Option<Format>,
    /// The coordinates of the trace.
    frame: runtime::trace::Frame,
    plot: Option<PathBuf>,
    stock: Option<runtime::plot::Stock>,
    stats: Option<(StatsFormat, StatsTo)>,
    quiet: bool,
    /// `--max-time`, else the machine's run.max_time_s.
    max_time: Option<f64>,
}

/// The alarm of a timed run that used up its simulated time (E6006,
/// docs/machine.md): a run that cannot end (an endless dwell, a move of
/// 10^20 mm, a feed override of 0) stops instead of writing without end.
const E_TIME: u32 = 6006;

/// Exit code of a run interrupted by Ctrl-C (128 + SIGINT, as a shell
/// reports it).
const INTERRUPTED: u8 = 130;

/// Set by Ctrl-C; the run loop looks at it every period and stops.
static STOP: AtomicBool = AtomicBool::new(false);

/// Ctrl-C stops the run at the next period, so that the plot and the
/// statistics of the run so far are still written; a second Ctrl-C ends
/// the process at once.
fn catch_interrupt() {
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::Relaxed) {
            std::process::exit(INTERRUPTED.into());
        }
    });
}

/// Runs the module through the interpolation runtime, period by period,
/// as the reference host: every PLC function completes at once and cycle
/// start is pressed at every stop.
fn run_timed(
    file: &Path,
    machine: (Option<&Path>, Option<Switch>),
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&Path>,
    out: &Outputs,
    jit: cli::jit::JitMode,
) -> ExitCode {
    catch_interrupt();
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let files: Vec<String> = module.files.iter().map(|f| f.name.clone()).collect();
    let number = module
        .programs
        .first()
        .map(|p| p.number)
        .filter(|&n| n != 0);
    let main_lines = main_lines(&module);
    let machine = match load_machine(machine) {
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
    jit.attach(ctl.vm_mut());
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
    // The source, if it can still be read, for the plot's title and stock.
    let info = match (&out.plot, files.first()) {
        (Some(_), Some(name)) => std::fs::read(name)
            .map(|b| cli::program_info::ProgramInfo::read(&String::from_utf8_lossy(&b)))
            .unwrap_or_default(),
        _ => Default::default(),
    };
    let stdout = std::io::stdout();
    // The canon, the trace and the statistics share stdout.
    let mut canon = Canon::new(BufWriter::new(stdout.lock()));
    if out.trace == Some(Format::Csv) {
        let c_axis = ctl.engine().config().c.is_some();
        canon.write(&format!("{}\n", runtime::trace::csv_header(c_axis)));
    }
    let period = ctl.engine().config().period_s;
    let mut stats = runtime::stats::Stats::new(period);
    let mut plot = out.plot.as_ref().map(|_| runtime::plot::Plot::new());
    let mut progress = cli::progress::Progress::bar(main_lines, "run", out.quiet);
    // Where the first roughing cycle began: the stock's corner.
    let mut cycle_start: Option<(f64, f64)> = None;
    let mut last = runtime::SetPoint::default();
    let mut line = String::new();
    let mut interrupted = false;
    let max_time = out.max_time.unwrap_or(ctl.machine().run.max_time_s);
    // Whole periods: the bound is exact in ticks, not subject to a sum of
    // rounded times.
    let max_ticks = (max_time / period).ceil() as u64;
    let mut ticks = 0u64;
    let mut timed_out = None;
    {
        let mut quiet = nc::Discard;
        let mut warned = Vec::new();
        let name = |i: u16| files.get(usize::from(i)).map_or("", String::as_str);
        ctl.cycle_start();
        loop {
            if out.canon {
                ctl.run_ahead_tap(&mut canon);
            } else {
                ctl.run_ahead_tap(&mut quiet);
            }
            let sp = ctl.tick();
            ticks += 1;
            while let Some(w) = ctl.engine_mut().take_room_warning() {
                room_warning(&mut warned, &w, name(w.tag.file));
            }
            if let Some(f) = out.trace {
                line.clear();
                let _ = match f {
                    Format::Csv => {
                        runtime::trace::write_csv(&mut line, &sp, out.frame, name(sp.file))
                    }
                    Format::Json => {
                        runtime::trace::write_json(&mut line, &sp, out.frame, name(sp.file))
                    }
                };
                canon.write(&line);
            }
            stats.add(&sp);
            if let Some(p) = plot.as_mut() {
                p.add(&sp);
                if cycle_start.is_none() && sp.file == 0 && info.roughing.contains(&sp.line) {
                    cycle_start = Some((last.x, last.z));
                }
            }
            progress.set(sp.line.into(), || {
                format!("line {} · {:.1} s of cycle time", sp.line, sp.time_s)
            });
            last = sp;
            if STOP.load(Ordering::Relaxed) {
                interrupted = true;
                break;
            }
            match ctl.state() {
                runtime::RunState::Stopped(_) | runtime::RunState::Idle => ctl.cycle_start(),
                runtime::RunState::Ended | runtime::RunState::Alarm(_) => break,
                _ => {}
            }
            // The output is what a timed run is for: once it fails, stop.
            if canon.failed() {
                break;
            }
            if ticks >= max_ticks {
                timed_out = Some(sp);
                break;
            }
        }
    }
    progress.finish();
    stats.blocks = ctl.blocks();
    let alarm = match timed_out {
        Some(sp) => Some(time_alarm(&files, &sp, max_time)),
        None => ctl.alarm(),
    };
    // A VM alarm printed its ALARM line with the canon (the kernel raises
    // E7001 and E7002 too, at the same move as the runtime, so that a plain
    // canon run ends the same way); the runtime's own (E7003, E4010, an
    // E7001/E7002 the kernel cannot see) and the time bound end the canon
    // here. The canon sink prints one ALARM line at most.
    if let (Some(a), true) = (&alarm, out.canon) {
        if matches!(a.code, 7001 | 7002 | 7003 | 4010 | E_TIME) {
            canon.emit(Event::Alarm {
                code: a.code,
                msg: a.message.clone(),
            });
        }
    }
    let stopped_at = interrupted.then(|| cli::stats_json::Stopped {
        file: files
            .get(usize::from(last.file))
            .cloned()
            .unwrap_or_default(),
        line: last.line,
    });
    if let Some((format, StatsTo::Stdout)) = out.stats {
        canon.write(&stats_text(
            &stats,
            format,
            &files,
            &stopped_at,
            ctl.vm().tier_stats(),
        ));
    }
    let output_error = canon.finish();
    if let Some(Err(e)) = vars_file.map(cli::vars::VarsFile::finish) {
        return fail(&e);
    }
    if let (Some(path), Some(p)) = (&out.plot, plot.as_mut()) {
        let stock = out.stock.or(info.billet).or_else(|| {
            let (d, z) = cycle_start?;
            Some(runtime::plot::Stock {
                diameter: d.abs(),
                right: z,
                left: p.cut_zmin().filter(|&l| l < z)?,
            })
        });
        if let Some(s) = stock {
            p.set_stock(s);
        }
        let title = info.title(&file.display().to_string(), number);
        if let Err(e) = std::fs::write(path, p.svg(&title)) {
            return fail(&format!("{}: {e}", path.display()));
        }
    }
    if let Some((format, StatsTo::Stderr)) = out.stats {
        let _ = write!(
            std::io::stderr().lock(),
            "{}",
            stats_text(&stats, format, &files, &stopped_at, ctl.vm().tier_stats())
        );
    }
    if let Some(at) = &stopped_at {
        let wrote = match (&out.plot, out.stats.is_some()) {
            (Some(p), true) => format!(
                "; the plot ({}) and the statistics hold the run so far",
                p.display()
            ),
            (Some(p), false) => format!("; the plot ({}) holds the run so far", p.display()),
            (None, true) => "; the statistics hold the run so far".to_string(),
            (None, false) => String::new(),
        };
        note(format_args!(
            "gbvm: interrupted at {}:{} after {:.3} s of cycle time{wrote}",
            printable(&at.file),
            at.line,
            last.time_s
        ));
        return ExitCode::from(INTERRUPTED);
    }
    if let Some(a) = &alarm {
        note(format_args!("{}", printable(&a.header())));
    }
    match (output_error, alarm) {
        (Some(e), _) => output_failed(&e),
        (None, Some(_)) => cli::exit::Exit::Alarm.into(),
        (None, None) => ExitCode::SUCCESS,
    }
}

/// W118 found at run time, once per block and kind (a cycle's passes
/// repeat it), on stderr as gbcc prints warnings.
fn room_warning(warned: &mut Vec<(u16, u32, bool)>, w: &runtime::RoomWarning, file: &str) {
    let key = (w.tag.file, w.tag.line, w.exit);
    if warned.contains(&key) {
        return;
    }
    warned.push(key);
    note(format_args!(
        "{}:{}:{}: warning[W118]: {}",
        printable(file),
        w.tag.line,
        w.tag.col,
        w.message()
    ));
}

/// E6006 at the block running when the time ran out.
fn time_alarm(files: &[String], sp: &runtime::SetPoint, max_time: f64) -> runtime::AlarmInfo {
    runtime::AlarmInfo {
        code: E_TIME,
        message: format!(
            "the run did not end within {max_time} s of simulated time (run.max_time_s, --max-time)"
        ),
        file: files.get(usize::from(sp.file)).cloned().unwrap_or_default(),
        line: sp.line,
        col: 1,
    }
}

/// The statistics as text or JSON.
fn stats_text(
    stats: &runtime::stats::Stats,
    format: StatsFormat,
    files: &[String],
    stopped_at: &Option<cli::stats_json::Stopped>,
    tier: Option<vm::TierStats>,
) -> String {
    let jit = tier.and_then(cli::stats_json::Jit::of);
    match format {
        StatsFormat::Text => {
            let mut t = stats.to_string();
            if let Some(at) = stopped_at {
                t.push_str(&format!("interrupted at: {}:{}\n", at.file, at.line));
            }
            if let Some(j) = &jit {
                t.push_str(&j.line());
            }
            t
        }
        StatsFormat::Json => {
            let stopped = stopped_at.as_ref().map(|a| cli::stats_json::Stopped {
                file: a.file.clone(),
                line: a.line,
            });
            let mut j = cli::stats_json::Report::new(stats, files, stopped, jit).to_json();
            j.push('\n');
            j
        }
    }
}
