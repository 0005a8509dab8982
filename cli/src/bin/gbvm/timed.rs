//! `gbvm run` through the interpolation runtime, period by period, as the
//! reference host runs it: every PLC function completes at once and cycle
//! start is pressed at every stop. It writes the trace, the plot and the
//! statistics (and the canon, when they come with it).

use super::{
    fail, load, load_machine, main_lines, note, open_vars, output_failed, printable, Format,
    RunArgs, StatsFormat, E_TIME,
};
use cli::canon::Canon;
use nc::{Event, Sink};
use std::io::{BufWriter, StdoutLock, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// Where the statistics go: stdout when nothing else takes it.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum StatsTo {
    Stdout,
    Stderr,
}

/// What a run through the interpolation runtime writes.
pub(crate) struct Outputs {
    /// The canon on stdout.
    pub canon: bool,
    /// The per-period trace on stdout.
    pub trace: Option<Format>,
    /// The coordinates of the trace.
    pub frame: runtime::trace::Frame,
    pub plot: Option<PathBuf>,
    pub stock: Option<runtime::plot::Stock>,
    pub stats: Option<(StatsFormat, StatsTo)>,
    pub quiet: bool,
    /// `--max-time`, else the machine's run.max_time_s (per part).
    pub max_time: Option<f64>,
    /// `--parts`: the parts to make in a row.
    pub parts: Option<u32>,
}

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

/// The module's own facts the outputs name.
struct Program {
    /// Its source files, by index.
    files: Vec<String>,
    /// The main program's number (none for O0000).
    number: Option<u32>,
}

/// What the periods leave for the outputs.
struct Record<'a> {
    stats: runtime::stats::Stats,
    plot: Option<runtime::plot::Plot>,
    /// Where the first roughing cycle began: the stock's corner.
    cycle_start: Option<(f64, f64)>,
    /// The last period's set point.
    last: runtime::SetPoint,
    progress: cli::progress::Progress,
    /// The source's own facts (its roughing cycles' lines).
    info: &'a cli::program_info::ProgramInfo,
}

/// How the periods ended, when not with the program or an alarm.
enum Cut {
    /// Ctrl-C.
    Interrupted,
    /// The simulated time ran out at this set point (E6006).
    TimedOut(runtime::SetPoint),
}

/// The canon, the trace and the statistics share stdout.
type Stdout = Canon<BufWriter<StdoutLock<'static>>>;

/// Runs the module through the interpolation runtime.
pub(crate) fn run_timed(args: &RunArgs, out: &Outputs) -> ExitCode {
    catch_interrupt();
    let (mut ctl, program, main_lines) = match open(args) {
        Ok(opened) => opened,
        Err(e) => return fail(&e),
    };
    let vars_file = match open_vars(args.vars, ctl.vm_mut()) {
        Ok(v) => v,
        Err(e) => return fail(&e),
    };
    let info = source_info(out, &program.files);
    let mut canon = Canon::new(BufWriter::new(std::io::stdout().lock()));
    if out.trace == Some(Format::Csv) {
        let c_axis = ctl.engine().config().c.is_some();
        canon.write(&format!("{}\n", runtime::trace::csv_header(c_axis)));
    }
    if let Some(at) = args.from {
        if let Err(e) = restart(&mut ctl, at, &mut canon, out) {
            return refused(e, canon);
        }
    }
    let mut rec = Record {
        stats: runtime::stats::Stats::new(ctl.engine().config().period_s),
        plot: out.plot.as_ref().map(|_| runtime::plot::Plot::new()),
        cycle_start: None,
        last: runtime::SetPoint::default(),
        progress: cli::progress::Progress::bar(main_lines, "run", out.quiet),
        info: &info,
    };
    let max_time = out.max_time.unwrap_or(ctl.machine().run.max_time_s);
    let cut = periods(&mut ctl, &mut canon, &mut rec, out, &program, max_time);
    rec.progress.finish();
    if out.parts.is_some() {
        if ctl.state() == runtime::RunState::Ended {
            // The run-ahead keeps what the last part counted.
            ctl.run_ahead();
        }
        counters_note(ctl.counters());
    }
    rec.stats.blocks = ctl.blocks();
    let alarm = match &cut {
        Some(Cut::TimedOut(sp)) => Some(time_alarm(&program.files, sp, max_time)),
        _ => ctl.alarm(),
    };
    end_canon(&mut canon, alarm.as_ref(), out);
    let ran = Ran {
        ctl: &ctl,
        program: &program,
        interrupted: matches!(cut, Some(Cut::Interrupted)),
        alarm,
    };
    finish(ran, rec, canon, vars_file, args, out)
}

/// How the run went, for [`finish`].
struct Ran<'a> {
    ctl: &'a runtime::Controller<runtime::AutoAck>,
    program: &'a Program,
    /// Ctrl-C stopped it.
    interrupted: bool,
    alarm: Option<runtime::AlarmInfo>,
}

/// Writes the statistics, #500–#999 and the plot; the exit code.
fn finish(
    ran: Ran,
    mut rec: Record,
    mut canon: Stdout,
    vars_file: Option<cli::vars::VarsFile>,
    args: &RunArgs,
    out: &Outputs,
) -> ExitCode {
    let Ran {
        ctl,
        program,
        interrupted,
        alarm,
    } = ran;
    let stopped_at = interrupted.then(|| cli::stats_json::Stopped {
        file: program
            .files
            .get(usize::from(rec.last.file))
            .cloned()
            .unwrap_or_default(),
        line: rec.last.line,
    });
    let stats = |format| {
        let tier = ctl.vm().tier_stats();
        stats_text(&rec.stats, format, &program.files, &stopped_at, tier)
    };
    if let Some((format, StatsTo::Stdout)) = out.stats {
        canon.write(&stats(format));
    }
    let output_error = canon.finish();
    if let Some(Err(e)) = vars_file.map(cli::vars::VarsFile::finish) {
        return fail(&e);
    }
    let plot = PlotOutput {
        plot: rec.plot.as_mut(),
        cycle_start: rec.cycle_start,
        info: rec.info,
    };
    // The plot is an output: one that could not be written is exit 3.
    if let Err(e) = write_plot(plot, out, args, program) {
        note(format_args!("gbvm: error: {e}"));
        return cli::exit::Exit::Write.into();
    }
    if let Some((format, StatsTo::Stderr)) = out.stats {
        let _ = write!(std::io::stderr().lock(), "{}", stats(format));
    }
    if let Some(at) = &stopped_at {
        return interrupted_exit(at, out, rec.last.time_s);
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

/// `--parts`: the counters the parts left, on stderr, as a control's
/// setting page shows them.
fn counters_note(c: &runtime::Counters) {
    let p = c.parts;
    note(format_args!(
        "gbvm: note: --parts: parts machined (#3901) {}, required (#3902) {}",
        p.machined, p.required
    ));
    for g in &c.life {
        let unit = match g.unit {
            runtime::LifeUnit::Count => "uses",
            runtime::LifeUnit::Minutes => "minutes",
        };
        let tools: Vec<String> = (0..g.tools.len())
            .map(|i| {
                let used = g.used.get(i).copied().unwrap_or(0.0);
                let state = match (used >= g.life, g.current == Some(i)) {
                    (true, _) => " (worn out)",
                    (false, true) => " (current)",
                    (false, false) => "",
                };
                let used = match g.unit {
                    runtime::LifeUnit::Count => format!("{used}"),
                    runtime::LifeUnit::Minutes => format!("{used:.3}"),
                };
                format!("T{:04} {used}{state}", g.tools[i])
            })
            .collect();
        note(format_args!(
            "gbvm: note: --parts: tool-life group {} ({unit}, life {}): {}",
            g.number,
            g.life,
            tools.join(", ")
        ));
    }
}

/// `--from`: the restart's search, its restored state and approach told
/// to the canon when it is printed.
fn restart(
    ctl: &mut runtime::Controller<runtime::AutoAck>,
    at: vm::restart::RestartAt,
    canon: &mut Stdout,
    out: &Outputs,
) -> Result<(), runtime::RestartRefused> {
    let r = match out.canon {
        true => ctl.restart_from_tap(at, canon),
        false => ctl.restart_from(at),
    }?;
    super::restarted(&r);
    Ok(())
}

/// A refused restart's exit code, after what the canon holds.
fn refused(e: runtime::RestartRefused, canon: Stdout) -> ExitCode {
    match (canon.finish(), e) {
        (Some(e), _) => output_failed(&e),
        (None, runtime::RestartRefused::Search(runtime::RestartError::Alarm(a))) => {
            note(format_args!("{}", printable(&a.header())));
            cli::exit::Exit::Alarm.into()
        }
        (None, e) => fail(&format!("--from: {e}")),
    }
}

/// The module loaded into a controller for the machine, with the run's
/// settings; the program's facts and the main file's length (the
/// progress bar's).
fn open(args: &RunArgs) -> Result<(runtime::Controller<runtime::AutoAck>, Program, u64), String> {
    let module = load(args.file)?;
    let program = Program {
        files: module.files.iter().map(|f| f.name.clone()).collect(),
        number: module
            .programs
            .first()
            .map(|p| p.number)
            .filter(|&n| n != 0),
    };
    let lines = main_lines(&module);
    let machine = load_machine(args.machine)?;
    let mut ctl = match runtime::Controller::new(module, machine, runtime::AutoAck) {
        Ok(c) => c,
        Err(runtime::LoadError::Machine(key)) => return Err(format!(
            "{} was compiled for another machine configuration ({key}); compile it again with this --machine",
            args.file.display()
        )),
        Err(e) => return Err(format!("{}: {e}", args.file.display())),
    };
    if let Some(n) = args.max_blocks {
        ctl.set_max_blocks(n);
    }
    ctl.set_repeat(args.repeat);
    args.jit.attach(ctl.vm_mut());
    Ok((ctl, program, lines))
}

/// The source, if it can still be read, for the plot's title and stock.
fn source_info(out: &Outputs, files: &[String]) -> cli::program_info::ProgramInfo {
    match (&out.plot, files.first()) {
        // (Read as every input is: a crafted module naming a device must
        // not hang the run.)
        (Some(_), Some(name)) => cli::io::read_file(std::path::Path::new(name))
            .map(|b| cli::program_info::ProgramInfo::read(&String::from_utf8_lossy(&b)))
            .unwrap_or_default(),
        _ => Default::default(),
    }
}

/// Runs period after period until the program ends, an alarm, Ctrl-C,
/// the time bound or a failed output; `None` for the first two.
fn periods(
    ctl: &mut runtime::Controller<runtime::AutoAck>,
    canon: &mut Stdout,
    rec: &mut Record,
    out: &Outputs,
    program: &Program,
    max_time: f64,
) -> Option<Cut> {
    // Whole periods: the bound is exact in ticks, not subject to a sum of
    // rounded times.
    let max_ticks = (max_time / ctl.engine().config().period_s).ceil() as u64;
    let mut ticks = 0u64;
    let mut part = 1;
    let mut quiet = nc::Discard;
    let mut warned = Vec::new();
    let mut line = String::new();
    let name = |i: u16| program.files.get(usize::from(i)).map_or("", String::as_str);
    ctl.cycle_start();
    loop {
        if out.canon {
            ctl.run_ahead_tap(canon);
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
                Format::Csv => runtime::trace::write_csv(&mut line, &sp, out.frame, name(sp.file)),
                Format::Json => {
                    runtime::trace::write_json(&mut line, &sp, out.frame, name(sp.file))
                }
            };
            canon.write(&line);
        }
        rec.add(&sp);
        if STOP.load(Ordering::Relaxed) {
            return Some(Cut::Interrupted);
        }
        match ctl.state() {
            runtime::RunState::Stopped(_) | runtime::RunState::Idle => ctl.cycle_start(),
            // The next part: a reset, then (idle) cycle start, as a
            // rewinding M30's cycle start makes it.
            runtime::RunState::Ended if part < out.parts.unwrap_or(1) => {
                part += 1;
                ticks = 0;
                ctl.reset();
            }
            runtime::RunState::Ended | runtime::RunState::Alarm(_) => return None,
            _ => {}
        }
        // The output is what a timed run is for: once it fails, stop.
        if canon.failed() {
            return None;
        }
        if ticks >= max_ticks {
            return Some(Cut::TimedOut(sp));
        }
    }
}

impl Record<'_> {
    /// One period's set point, into the statistics, the plot and the
    /// progress bar.
    fn add(&mut self, sp: &runtime::SetPoint) {
        self.stats.add(sp);
        if let Some(p) = self.plot.as_mut() {
            p.add(sp);
            let roughing = sp.file == 0 && self.info.roughing.contains(&sp.line);
            if self.cycle_start.is_none() && roughing {
                self.cycle_start = Some((self.last.x, self.last.z));
            }
        }
        self.progress.set(sp.line.into(), || {
            format!("line {} · {:.1} s of cycle time", sp.line, sp.time_s)
        });
        self.last = *sp;
    }
}

/// A VM alarm printed its ALARM line with the canon (the kernel raises
/// E7001 and E7002 too, at the same move as the runtime, so that a plain
/// canon run ends the same way); the runtime's own (E7003, E4010, an
/// E7001/E7002 the kernel cannot see) and the time bound end the canon
/// here. The canon sink prints one ALARM line at most.
fn end_canon<W: Write>(canon: &mut Canon<W>, alarm: Option<&runtime::AlarmInfo>, out: &Outputs) {
    if let (Some(a), true) = (alarm, out.canon) {
        if matches!(a.code, 7001 | 7002 | 7003 | 4010 | E_TIME) {
            canon.emit(Event::Alarm {
                code: a.code,
                msg: a.message.clone(),
            });
        }
    }
}

/// Writes the SVG plot, when asked for, with the stock: `--stock`, else
/// the program's `[BILLET` line, else the corner of its first roughing
/// cycle.
fn write_plot(
    plot: PlotOutput,
    out: &Outputs,
    args: &RunArgs,
    program: &Program,
) -> Result<(), String> {
    let (Some(path), Some(p)) = (&out.plot, plot.plot) else {
        return Ok(());
    };
    let info = plot.info;
    let stock = out.stock.or(info.billet).or_else(|| {
        let (d, z) = plot.cycle_start?;
        Some(runtime::plot::Stock {
            diameter: d.abs(),
            right: z,
            left: p.cut_zmin().filter(|&l| l < z)?,
        })
    });
    if let Some(s) = stock {
        p.set_stock(s);
    }
    let title = info.title(&args.file.display().to_string(), program.number);
    std::fs::write(path, p.svg(&title)).map_err(|e| format!("{}: {e}", path.display()))
}

/// The plot a run drew, and what says where its stock is.
struct PlotOutput<'a> {
    plot: Option<&'a mut runtime::plot::Plot>,
    cycle_start: Option<(f64, f64)>,
    info: &'a cli::program_info::ProgramInfo,
}

/// Says where Ctrl-C stopped the run and what holds the run so far.
fn interrupted_exit(at: &cli::stats_json::Stopped, out: &Outputs, time_s: f64) -> ExitCode {
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
        time_s
    ));
    ExitCode::from(INTERRUPTED)
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
