//! The exit codes of `gbcc` and `gbvm`: one table for both, so that a
//! script can tell a bad program from a bad command line or a full disk
//! (README, "Exit codes").

use std::process::ExitCode;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exit {
    /// Everything asked for was done.
    Ok = 0,
    /// The input is wrong: compile errors, an unreadable input, a module
    /// or machine file that is refused.
    Input = 1,
    /// `gbvm run`: the program stopped on a run-time alarm.
    Alarm = 2,
    /// An output could not be written (a full disk, a closed pipe).
    Write = 3,
    /// The command line is wrong (unknown option, missing argument);
    /// sysexits' EX_USAGE.
    Usage = 64,
}

impl From<Exit> for ExitCode {
    fn from(e: Exit) -> ExitCode {
        ExitCode::from(e as u8)
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
