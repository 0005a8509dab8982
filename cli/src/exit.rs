//! The exit codes of `gbcc` and `gbvm`: one table for both, so that a
//! script can tell a bad program or command line from an alarm or a full
//! disk (README, "Exit codes").

use std::process::ExitCode;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exit {
    /// Everything asked for was done.
    Ok,
    /// The input is wrong: compile errors, an unreadable input, a module
    /// or machine file that is refused.
    Input,
    /// `gbvm run`: the program stopped on a run-time alarm.
    Alarm,
    /// An output could not be written (a full disk, a closed pipe).
    Write,
    /// The command line is wrong (unknown option, missing argument).
    Usage,
}

impl Exit {
    /// The process's code. A usage error is 1, as canon.md gives `gbvm
    /// run` for "usage, load or verification error" (and as gcc exits),
    /// not clap's 2, which is the alarm's.
    pub const fn code(self) -> u8 {
        match self {
            Exit::Ok => 0,
            Exit::Input | Exit::Usage => 1,
            Exit::Alarm => 2,
            Exit::Write => 3,
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(e: Exit) -> ExitCode {
        ExitCode::from(e.code())
    }
}

/// Parses the command line with clap; help and version print and end
/// with [`Exit::Ok`], a bad command line with [`Exit::Usage`] (clap's own
/// code is 2, which `gbvm` gives run-time alarms).
pub fn parse_args<P: clap::Parser>(args: Vec<std::ffi::OsString>) -> Result<P, Exit> {
    P::try_parse_from(args).map_err(|e| {
        let usage = e.use_stderr();
        // Nothing more can be said when the terminal is gone.
        let _ = e.print();
        if usage {
            Exit::Usage
        } else {
            Exit::Ok
        }
    })
}
