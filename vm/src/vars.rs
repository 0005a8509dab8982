//! The variables the VM keeps itself: locals per call level and the
//! commons (dialect.md §7.1). System variables belong to the NC kernel.

use alloc::vec::Vec;

use nc::value::VACANT;

/// Local call levels 0…4 (main program + four macro levels).
pub const LOCAL_LEVELS: usize = 5;

/// Locals per call level, commons and persistent variables.
#[derive(Debug, Clone)]
pub struct Vars {
    locals: Vec<[f64; 33]>,
    /// #100–#199 (vacant as NaN).
    pub common: [f64; 100],
    /// #500–#999 (vacant as NaN).
    pub persistent: [f64; 500],
    /// Set when #500–#999 changed since the last save.
    pub persistent_dirty: bool,
}

/// Where a plain variable number lives.
pub enum Slot {
    /// #1–#33 of the current call level (index 0–32).
    Local(usize),
    /// #100–#199 (index 0–99).
    Common(usize),
    /// #500–#999 (index 0–499).
    Persistent(usize),
}

/// The slot of variable `n`, or `None` for a system or unknown number.
pub fn slot(n: u32) -> Option<Slot> {
    match n {
        1..=33 => Some(Slot::Local(n as usize - 1)),
        100..=199 => Some(Slot::Common(n as usize - 100)),
        500..=999 => Some(Slot::Persistent(n as usize - 500)),
        _ => None,
    }
}

impl Default for Vars {
    fn default() -> Self {
        let mut locals = Vec::with_capacity(LOCAL_LEVELS);
        locals.push([VACANT; 33]);
        Vars {
            locals,
            common: [VACANT; 100],
            persistent: [VACANT; 500],
            persistent_dirty: false,
        }
    }
}

impl Vars {
    /// The value in a slot (vacant as NaN).
    pub fn get(&self, s: &Slot) -> f64 {
        match *s {
            Slot::Local(i) => self.locals.last().map_or(VACANT, |l| l[i]),
            Slot::Common(i) => self.common[i],
            Slot::Persistent(i) => self.persistent[i],
        }
    }

    /// The current call level's #1–#33, #100–#199 and #500–#999 (read
    /// only), for a tier's compiled code.
    pub fn split(&mut self) -> (&mut [f64; 33], &mut [f64; 100], &[f64; 500]) {
        if self.locals.is_empty() {
            self.locals.push([VACANT; 33]);
        }
        let top = self.locals.len() - 1;
        (&mut self.locals[top], &mut self.common, &self.persistent)
    }

    /// Sets a slot; a changed persistent value marks them dirty.
    pub fn set(&mut self, s: &Slot, v: f64) {
        match *s {
            Slot::Local(i) => {
                if let Some(l) = self.locals.last_mut() {
                    l[i] = v;
                }
            }
            Slot::Common(i) => self.common[i] = v,
            Slot::Persistent(i) => {
                if self.persistent[i].to_bits() != v.to_bits() {
                    self.persistent[i] = v;
                    self.persistent_dirty = true;
                }
            }
        }
    }

    /// A new local level for a macro call, its arguments set.
    pub fn push_level(&mut self, args: &[(u8, f64)]) {
        let mut l = [VACANT; 33];
        for &(var, v) in args {
            if let Some(slot) = (var as usize).checked_sub(1).and_then(|i| l.get_mut(i)) {
                *slot = v;
            }
        }
        self.locals.push(l);
    }

    /// Back to the caller's local level (the main level stays).
    pub fn pop_level(&mut self) {
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }

    /// Refreshes the current level with the arguments (the next repetition
    /// of a macro called with L).
    pub fn refresh_level(&mut self, args: &[(u8, f64)]) {
        self.pop_level();
        self.push_level(args);
    }
}
