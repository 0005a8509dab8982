//! What the operator does between programs, while the machine stands
//! idle: restart the program at a block, select another program, edit
//! the offset page and the production counters. Each starts the program
//! afresh where the axes stand.

use super::Controller;
use crate::plc::Plc;
use crate::runahead::Standing;
use alloc::string::String;
use nc::counters::{Counters, Parts};
use nc::machine::Xz;
use nc::machine_check::BadKey;
use nc::offset_page::{OffsetLengths, WorkOffset};
use nc::{Machine, Sink};
use vm::restart::{RestartAt, RestartError, Restarted};

/// Why [`Controller::select_program`] kept the program it has.
#[derive(Debug, Clone, PartialEq)]
pub enum SelectRefused {
    /// A program runs, stands stopped, ended or in an alarm, or a manual
    /// move runs: reset first.
    NotIdle,
    /// Compiled for a machine whose compile-time keys differ (the first
    /// that does, with both values).
    Machine(String),
}

impl core::fmt::Display for SelectRefused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SelectRefused::NotIdle => {
                write!(f, "another program needs an idle machine: reset first")
            }
            SelectRefused::Machine(key) => write!(
                f,
                "compiled for another machine configuration (its compile-time keys differ: {key})"
            ),
        }
    }
}

impl core::error::Error for SelectRefused {}

/// Why [`Controller::restart_from`] did not restart.
#[derive(Debug, Clone, PartialEq)]
pub enum RestartRefused {
    /// A program runs, stands stopped, ended or in an alarm, or a manual
    /// move runs: reset first.
    NotIdle,
    /// The search did not reach a block the run can resume at.
    Search(RestartError),
}

impl core::fmt::Display for RestartRefused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RestartRefused::NotIdle => write!(f, "a restart needs an idle machine: reset first"),
            RestartRefused::Search(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for RestartRefused {}

/// `module` was compiled for `machine`'s compile-time keys, or the first
/// that differs.
pub(crate) fn compiled_for(machine: &Machine, module: &isa::Module) -> Result<(), SelectRefused> {
    match Machine::compile_keys_differ(&module.machine, &machine.compile_keys()) {
        Some(key) => Err(SelectRefused::Machine(key)),
        None => Ok(()),
    }
}

impl<P: Plc> Controller<P> {
    /// Program restart (docs/embedding.md): while idle, the program
    /// runs from its start in search mode up to `at` (nothing moves),
    /// then, at cycle start, the restored state (origin, tool, speed,
    /// spindle, coolant, feed) and an approach from where the axes stand,
    /// X first, then Z (or as `run.restart_approach` says), and the
    /// program from `at` on. An edit of the
    /// offset page or another program selected after it starts the
    /// program afresh: make those first. A refused restart leaves the
    /// program at its start.
    pub fn restart_from(&mut self, at: RestartAt) -> Result<Restarted, RestartRefused> {
        self.restart_from_tap(at, &mut nc::Discard)
    }

    /// As [`Controller::restart_from`], handing the restored state and the
    /// approach to `tap` too, as [`Controller::run_ahead_tap`] does.
    pub fn restart_from_tap(
        &mut self,
        at: RestartAt,
        tap: &mut dyn Sink,
    ) -> Result<Restarted, RestartRefused> {
        if !self.engine.clear_idle() {
            return Err(RestartRefused::NotIdle);
        }
        let stand = self.standing();
        let found = self.ra.restart_from(at, stand, &mut self.engine, tap);
        // (The screen shows the codes the run resumes with, as a control
        // does after its search; a refused restart leaves the program at
        // its start.)
        let shown = match &found {
            Ok(r) => r.codes,
            Err(_) => nc::ActiveCodes::power_on(&self.ra.machine),
        };
        self.engine.show_codes(shown);
        found.map_err(RestartRefused::Search)
    }

    /// Selects another program (a verified module for this machine) while
    /// idle, as an operator picks one from the control's directory: the
    /// axes, the spindle, the offset page, #500–#999 and the panel's
    /// switches stay; the new program starts where the axes stand, with
    /// the power-on modes, at the next cycle start.
    pub fn select_program(&mut self, module: isa::Module) -> Result<(), SelectRefused> {
        let stand = self.place_for(&module)?;
        self.ra.start(module, stand, &mut self.engine);
        self.engine
            .show_codes(nc::ActiveCodes::power_on(&self.ra.machine));
        Ok(())
    }

    /// MDI (docs/embedding.md, "MDI"): while idle, blocks the operator
    /// typed, compiled for this machine, take the program's place where
    /// the axes stand; cycle start runs them. When they end, the machine
    /// is idle at once, the spindle and coolant as they left them, and
    /// the program is back at its start; a reset, a program restart or
    /// another program selected brings it back too.
    pub fn mdi(&mut self, blocks: isa::Module) -> Result<(), SelectRefused> {
        let stand = self.place_for(&blocks)?;
        self.ra.start_mdi(blocks, stand, &mut self.engine);
        Ok(())
    }

    /// Whether `module` may take the program's place now (compiled for
    /// this machine, the machine idle): where the axes stand, if so.
    fn place_for(&mut self, module: &isa::Module) -> Result<Standing, SelectRefused> {
        compiled_for(&self.ra.machine, module)?;
        if !self.engine.clear_idle() {
            return Err(SelectRefused::NotIdle);
        }
        Ok(self.standing())
    }

    /// MDI blocks are loaded or run (the program comes back when they end).
    pub fn in_mdi(&self) -> bool {
        self.ra.after_mdi.is_some()
    }

    /// Where the axes stand, for a run that starts afresh there. A reset
    /// (or manual move) that has just finished would otherwise start the
    /// program afresh at the next run-ahead: its report is taken here.
    fn standing(&mut self) -> Standing {
        // A run whose end the run-ahead has not seen counts first.
        if self.engine.take_ended() {
            self.ra.run_ended();
        }
        let _ = self.engine.take_reset_done();
        Standing {
            at: self.engine.position(),
            c: self.engine.c(),
        }
    }

    /// The offset page: the lengths of tool offset `number` (geometry and
    /// wear, X on the diameter) as the runs start with them; `None`
    /// outside the table.
    pub fn tool_offset(&self, number: u32) -> Option<OffsetLengths> {
        self.ra.machine.offset_lengths(number)
    }

    /// Sets the lengths of tool offset `number` for every run from now
    /// on (docs/embedding.md, "The offset page"): at once while idle (the
    /// program, not yet started, starts afresh with them), else from the
    /// next reset. A value out of the machine file's ranges is refused.
    pub fn set_tool_offset(&mut self, number: u32, l: OffsetLengths) -> Result<(), BadKey> {
        self.ra.machine.set_offset_lengths(number, l)?;
        self.apply_page();
        Ok(())
    }

    /// A work offset (EXOFS, G54–G59) as the runs start with it.
    pub fn work_offset(&self, w: WorkOffset) -> Xz {
        self.ra.machine.work_offset_of(w)
    }

    /// Sets a work offset for every run from now on, as
    /// [`Controller::set_tool_offset`] does.
    pub fn set_work_offset(&mut self, w: WorkOffset, at: Xz) -> Result<(), BadKey> {
        self.ra.machine.set_work_offset(w, at)?;
        self.apply_page();
        Ok(())
    }

    /// The production counters (docs/embedding.md): the parts machined
    /// and required (#3901, #3902) and the tool life of the machine
    /// file's groups, as the finished runs and the operator's edits left
    /// them. A run counts on them as it goes; what it counted is kept
    /// when the motion reaches its end, seen at the next
    /// [`Controller::run_ahead`]. A run a reset or an alarm abandons
    /// counts nothing.
    pub fn counters(&self) -> &Counters {
        &self.ra.counters
    }

    /// Sets the part counters (whole numbers, 0 … 99 999 999), as the
    /// operator does on the setting page. The running program keeps
    /// counting from what it started with, and its M30 then adds one to
    /// this value; while idle the program starts afresh with it.
    pub fn set_parts(&mut self, parts: Parts) -> Result<(), BadKey> {
        self.ra.set_parts(parts)?;
        self.apply_page();
        Ok(())
    }

    /// Tool-life group `number` as new (the operator changed its
    /// inserts): its tools unused and none selected, for the runs that
    /// start from now on (while idle, at once). Refused for a group the
    /// machine file does not have.
    pub fn renew_tool_life(&mut self, number: u32) -> Result<(), BadKey> {
        self.ra.renew_tool_life(number)?;
        self.apply_page();
        Ok(())
    }

    /// Restores counters the host kept over a power-off (all of
    /// [`Controller::counters`]), as [`Controller::set_parts`] sets the
    /// parts. Refused, changing nothing, unless they fit this machine:
    /// whole parts 0 … 99 999 999, the machine file's tool-life groups,
    /// uses finite and not negative.
    pub fn restore_counters(&mut self, c: Counters) -> Result<(), BadKey> {
        self.ra.restore_counters(c)?;
        self.apply_page();
        Ok(())
    }

    /// While idle, the program starts afresh on the edited machine.
    pub(super) fn apply_page(&mut self) {
        if self.engine.clear_idle() {
            let stand = self.standing();
            self.ra.restart(stand, &mut self.engine);
        }
    }
}
