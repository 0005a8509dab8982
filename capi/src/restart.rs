//! Program restart (`runtime::Controller::restart_from`): a run that
//! begins at a block in the middle of the program, as after a broken
//! insert or an interrupted shift.

use std::borrow::Cow;

use crate::{fail, put, put_xz, with_ctl, Ctl, Failure, GbcController, GbcStatus, Outcome};
use runtime::{RestartAt, RestartError, RestartRefused, Restarted, Target};

/// The last program restart asked for on a controller.
pub(crate) enum LastRestart {
    None,
    /// On a split controller: asked, its search not yet run (it runs in
    /// the `gbc_run_ahead` after the real-time half's reset).
    Pending,
    Taken(Restarted),
    /// Refused: the status and text the refusal gave.
    Refused(GbcStatus, Cow<'static, str>),
}

impl LastRestart {
    fn taken(&self) -> Option<&Restarted> {
        match self {
            LastRestart::Taken(r) => Some(r),
            _ => None,
        }
    }
}

/// Program restart at the block on source line `line` (1-based) of the
/// main file, the `pass`-th time the run reaches it (1: the first; a
/// block in a loop or a subprogram is reached more than once). The
/// program runs from its start in search mode up to that block: nothing
/// moves and no PLC function is handed over, but #500–#999 are written
/// as in a full run (through `vars_store`, from this call: a counter
/// there counts again). At the next `gbc_cycle_start` the PLC gets the
/// restored tool, gear or speed, spindle direction and coolant, the axes
/// go from where they stand to the block's start point (a rapid of X
/// and C, then one of Z), and the program goes on from the block. Taken
/// only while the controller is idle: before the first cycle start, or
/// after `gbc_reset` once `gbc_state` gives `GBC_RUN_STATE_IDLE`.
///
/// The statuses, each with `gbc_last_error`'s text saying why:
/// - line 0 or pass 0: [`GbcStatus::InvalidArgument`];
/// - a program runs, stands stopped, ended or in an alarm, a manual move
///   runs, or a reset is still running: [`GbcStatus::NotIdle`];
/// - the main file has no block on the line, the line is a cycle's
///   profile, or the run ends before reaching the block `pass` times:
///   [`GbcStatus::RestartNotFound`];
/// - what is in force at the block cannot be resumed there (a thread
///   chain open before the block, polar or cylindrical interpolation):
///   [`GbcStatus::RestartHeld`];
/// - the program raised an alarm before the block:
///   [`GbcStatus::RestartAlarm`].
///
/// A refused restart leaves the program at its start, so cycle start
/// then runs it from the beginning.
///
/// On the interpreter half of a split controller the call only asks for
/// the restart (after the argument checks): give `gbc_reset` on the
/// real-time half, as the operator's reset goes with a restart; the
/// `gbc_run_ahead` after it runs the search, and `gbc_restart_result`
/// then tells how it went.
#[no_mangle]
pub extern "C" fn gbc_restart_from(controller: GbcController, line: u32, pass: u32) -> GbcStatus {
    restart(controller, Target::Line(line), pass)
}

/// Program restart at the block numbered `seq` (`N<seq>`) in the main
/// file — the first such block, as `GOTO` finds it — the `pass`-th time
/// the run reaches it. Otherwise as `gbc_restart_from` (pass 0 is
/// [`GbcStatus::InvalidArgument`]; no such N in the main file,
/// [`GbcStatus::RestartNotFound`]).
#[no_mangle]
pub extern "C" fn gbc_restart_from_seq(
    controller: GbcController,
    seq: u32,
    pass: u32,
) -> GbcStatus {
    restart(controller, Target::Seq(seq), pass)
}

/// Checks the arguments (after the handle, before the program, as
/// `gbc_spindle_feedback` does) and asks the controller to restart.
fn restart(controller: GbcController, target: Target, pass: u32) -> GbcStatus {
    with_ctl(controller, |c| {
        if pass == 0 {
            return Err(fail(
                GbcStatus::InvalidArgument,
                "the pass is 0: passes count from 1 (the first time the run reaches the block)",
            ));
        }
        if target == Target::Line(0) {
            return Err(fail(
                GbcStatus::InvalidArgument,
                "the line is 0: source lines count from 1",
            ));
        }
        let at = RestartAt { target, pass };
        if let Some(i) = c.interp.as_mut() {
            i.restart_from(at);
            c.restart = LastRestart::Pending;
            return Ok(());
        }
        let r = c.run()?.restart_from(at);
        c.restart = outcome(r.clone());
        refused(r.map(|_| ()))
    })
}

/// What the last restart came to, kept for `gbc_restart_result` and the
/// restart page's calls.
fn outcome(r: Result<Restarted, RestartRefused>) -> LastRestart {
    match r {
        Ok(r) => LastRestart::Taken(r),
        Err(e) => {
            let Failure { status, message } = refusal(e);
            LastRestart::Refused(status, message)
        }
    }
}

/// On a split controller, after a `gbc_run_ahead`: the outcome of the
/// restart asked for, once its search has run.
pub(crate) fn take_split_result(c: &mut Ctl) {
    let Some(i) = c.interp.as_mut() else { return };
    if let Some(r) = i.take_restart_result() {
        c.restart = outcome(r.map_err(RestartRefused::Search));
    }
}

/// How the last program restart asked for went: [`GbcStatus::Ok`] when
/// it was taken (`gbc_restart_m_codes` and `gbc_restart_destination`
/// give its page), the status `gbc_restart_from` gave when it was
/// refused (with its `gbc_last_error` text), and on a split controller
/// [`GbcStatus::RestartPending`] until its search has run. No restart
/// asked for: [`GbcStatus::RestartNotFound`].
#[no_mangle]
pub extern "C" fn gbc_restart_result(controller: GbcController) -> GbcStatus {
    with_ctl(controller, |c| match &c.restart {
        LastRestart::Taken(_) => Ok(()),
        LastRestart::Pending => Err(GbcStatus::RestartPending.into()),
        LastRestart::Refused(status, text) => Err(fail(*status, text.clone())),
        LastRestart::None => Err(fail(
            GbcStatus::RestartNotFound,
            "no program restart has been asked for",
        )),
    })
}

/// The M codes the blocks before the last restart taken gave, other than
/// the spindle's and coolant's (a clamp, a C-axis mode, a tailstock: the
/// machine's meaning), each once, in the order of their last use: a
/// restart does not give them again, so the host shows them and the
/// operator gives those the block needs by hand, as a control does after
/// its search. `*len` gets how many there are and `codes` the first
/// `cap` of them; `cap` 0 with a null `codes` asks for the count only.
/// None after a refused restart or before any.
///
/// # Safety
/// `codes` is null or writable for `cap` values; `len` is null or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_restart_m_codes(
    controller: GbcController,
    codes: *mut u32,
    cap: usize,
    len: *mut usize,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if len.is_null() || (codes.is_null() && cap > 0) {
            return Err(fail(
                GbcStatus::NullPointer,
                "len is null, or codes is null while cap is not 0",
            ));
        }
        let m = c.restart.taken().map_or(&[][..], |r| &r.m_codes[..]);
        let n = m.len().min(cap);
        if n > 0 {
            // SAFETY: non-null and writable for `cap` ≥ n values by the
            // caller's promise.
            unsafe { core::ptr::copy_nonoverlapping(m.as_ptr(), codes, n) };
        }
        // SAFETY: checked non-null; the caller's promise.
        unsafe { put(len, m.len()) }
    })
}

/// Where the approach of the last restart taken goes, mm, work
/// coordinates (X on the diameter), to `*x` and `*z` (both required): the
/// block's start point, under nose-radius compensation the compensated
/// tool's, as a control's restart page shows it before the cycle start
/// that moves there. NaN and NaN after a refused restart or before any.
///
/// # Safety
/// `x` and `z` are null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_restart_destination(
    controller: GbcController,
    x: *mut f64,
    z: *mut f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let to = c.restart.taken().map(|r| r.destination);
        let to = to.unwrap_or(runtime::Xz {
            x: f64::NAN,
            z: f64::NAN,
        });
        // SAFETY: the caller's promise.
        unsafe { put_xz(x, z, to) }
    })
}

/// The status of a refused restart; a failed search keeps its own text
/// (it names the block, the pass or the alarm).
fn refused(r: Result<(), RestartRefused>) -> Outcome {
    r.map_err(refusal)
}

/// The failure of a refused restart.
fn refusal(e: RestartRefused) -> Failure {
    match e {
        RestartRefused::NotIdle => fail(
            GbcStatus::NotIdle,
            "a program runs, stands stopped, ended or in an alarm, or a manual move or a \
             reset runs: gbc_reset first and tick until the state is idle",
        ),
        RestartRefused::Search(e) => {
            let status = match e {
                RestartError::NoBlock(_)
                | RestartError::Profile(_)
                | RestartError::NotReached { .. } => GbcStatus::RestartNotFound,
                RestartError::Held { .. } => GbcStatus::RestartHeld,
                RestartError::Alarm(_) => GbcStatus::RestartAlarm,
            };
            fail(status, e.to_string())
        }
    }
}
