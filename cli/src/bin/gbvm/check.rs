//! `gbvm check`: runs a module through the runtime as `gbvm run` does and
//! certifies every period (runtime::certify): axis velocity, acceleration
//! and jerk within the machine's limits, every canon end point reached,
//! thread leads, G96 and the spindle. One summary line on stdout; the
//! first violation on stderr, placed by its source line.

use super::{fail, load, note, printable, E_TIME};
use runtime::RunState;
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

/// Exit code of a run that breaks the certificate.
const VIOLATION: u8 = 1;

pub(super) fn check(
    file: &Path,
    machine: Option<&Path>,
    max_time: Option<f64>,
    from: Option<vm::restart::RestartAt>,
) -> ExitCode {
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let files: Vec<String> = module.files.iter().map(|f| f.name.clone()).collect();
    let machine = match cli::load_machine(machine) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let mut ctl = match runtime::Controller::new(module, machine, runtime::AutoAck) {
        Ok(c) => c,
        Err(runtime::LoadError::Machine(key)) => {
            return fail(&format!(
                "{} was compiled for another machine configuration ({key}); compile it again with this --machine",
                file.display()
            ))
        }
        Err(e) => return fail(&format!("{}: {e}", file.display())),
    };
    let period = ctl.engine().config().period_s;
    let max_time = max_time.unwrap_or(ctl.machine().run.max_time_s);
    let max_ticks = (max_time / period).ceil() as u64;
    let (cert, last) = match from.map(|at| ctl.run_certified_from(at, max_ticks)) {
        None => ctl.run_certified(max_ticks),
        Some(Ok(run)) => run,
        Some(Err(runtime::RestartRefused::Search(runtime::RestartError::Alarm(a)))) => {
            note(format_args!("{}", printable(&a.header())));
            return cli::exit::Exit::Alarm.into();
        }
        Some(Err(e)) => return fail(&format!("--from: {e}")),
    };
    let ended = ctl.state() == RunState::Ended;
    let name = |i: u16| printable(files.get(usize::from(i)).map_or("", String::as_str));
    let verdict = match (ended, cert.violation()) {
        (true, None) => "certified",
        _ => "not certified",
    };
    let mut out = std::io::stdout().lock();
    let printed = writeln!(out, "{verdict}: {}", cert.summary()).and_then(|()| out.flush());
    if let Err(e) = printed {
        return super::output_failed(&e);
    }
    if !ended {
        // An alarm, or the time bound: the run did not reach its end, so
        // nothing is certified (exit 2, as `gbvm run`).
        match ctl.alarm() {
            Some(a) => note(format_args!("{}", printable(&a.header()))),
            None => note(format_args!(
                "{}:{}:1: alarm[E{E_TIME:04}]: the run did not end within {max_time} s of simulated time (run.max_time_s, --max-time)",
                name(last.file),
                last.line
            )),
        }
        return cli::exit::Exit::Alarm.into();
    }
    match cert.violation() {
        Some(v) => {
            note(format_args!("{}:{}: violation: {v}", name(v.file), v.line));
            ExitCode::from(VIOLATION)
        }
        None => ExitCode::SUCCESS,
    }
}
