//! Machine lock: the program runs as ever (its blocks, its positions on
//! the screen, its time, its alarms), but the axes stand. An operator
//! checks a new program this way, usually with dry run, before a part
//! is cut (docs/machine.md, "Machine lock").
//!
//! The switch is read when a run (a program, MDI blocks, a restart) or a
//! manual move starts from idle: the axes are held where they stand
//! then. Switching mid-run would have to stop the axes, or start them,
//! in one period, which no drive can follow; so the switch waits for the
//! next start. The reset (or the end of MDI) that ends a locked run
//! brings the programmed point back to where the axes stand, so that the
//! next run, a manual move or a measured cut starts from the slide and
//! not from where the program left its point.

use crate::math::V2;

/// The panel switch and, while a locked run runs, where the axes stand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MachineLock {
    /// The panel switch, as the operator last set it.
    pub switch: bool,
    /// The machine set point (slide units) and C the axes are held at.
    held: Option<(V2, f64)>,
}

impl MachineLock {
    /// The switch as the machine file sets it, nothing held.
    pub fn new(switch: bool) -> MachineLock {
        MachineLock { switch, held: None }
    }

    /// A run or a manual move starts with the axes at `axes` and `c`:
    /// they are held there if the switch is on.
    pub fn start(&mut self, axes: V2, c: f64) {
        if self.held.is_none() && self.switch {
            self.held = Some((axes, c));
        }
    }

    /// The set point and C the axes are given: the held ones while
    /// locked, else the run's.
    pub fn axes(&self, axes: V2, c: f64) -> (V2, f64) {
        self.held.unwrap_or((axes, c))
    }

    /// The run ends: where the axes were held, if they were.
    pub fn release(&mut self) -> Option<(V2, f64)> {
        self.held.take()
    }

    /// The axes are held for the run under way.
    pub fn holds(&self) -> bool {
        self.held.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_passes_the_run_through_and_holds_nothing() {
        let mut lock = MachineLock::new(false);
        lock.start(V2::new(10.0, -5.0), 30.0);
        assert!(!lock.holds());
        let to = (V2::new(12.5, -7.0), 45.0);
        assert_eq!(lock.axes(to.0, to.1), to);
        assert_eq!(lock.release(), None);
    }

    #[test]
    fn on_holds_the_start_until_released_once() {
        let mut lock = MachineLock::new(true);
        let at = (V2::new(10.0, -5.0), 30.0);
        lock.start(at.0, at.1);
        assert_eq!(lock.axes(V2::new(12.5, -7.0), 45.0), at);
        // A second start (a manual move appended) keeps the first hold,
        // and so does the switch turned off mid-run.
        lock.start(V2::new(1.0, 1.0), 0.0);
        lock.switch = false;
        assert_eq!(lock.axes(V2::ZERO, 0.0), at);
        assert_eq!(lock.release(), Some(at));
        assert_eq!(lock.release(), None);
        assert_eq!(lock.axes(V2::ZERO, 0.0), (V2::ZERO, 0.0));
    }
}
