//! The operator's offset page: the tool offsets' lengths and the work
//! offsets a host edits between runs, as a control's offset screens do
//! (the operator measures a part and corrects a wear, or touches off a
//! new work zero). An edit changes the machine, so it holds for every
//! run after it, unlike a program's own writes (G10, #2001…, #5221…),
//! which last for their run (machine.md).
//!
//! A nose radius and tip direction are not here: they are compile keys
//! (the compiler resolves compensation with them), so they change with
//! the machine file and a new compile.

use alloc::format;

use crate::base::machine::{Machine, ToolOffset, Xz};
use crate::base::machine_check::{check, BadKey};

/// The lengths of one tool offset, mm, X on the diameter: geometry and
/// wear (#2701/#2801 and #2001/#2101 for offset 1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OffsetLengths {
    pub x: f64,
    pub z: f64,
    pub wear_x: f64,
    pub wear_z: f64,
}

/// A work offset: the external shift (EXOFS, #5201) or G54–G59 (#5221…).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorkOffset {
    External,
    G54,
    G55,
    G56,
    G57,
    G58,
    G59,
}

impl Machine {
    /// The lengths of tool offset `number` (1 ..= `tools.offsets`); `None`
    /// for a number outside the table.
    pub fn offset_lengths(&self, number: u32) -> Option<OffsetLengths> {
        if number == 0 || number > self.tools.offsets {
            return None;
        }
        let o = self.tools.offset.iter().find(|o| o.number == number);
        Some(o.map_or_else(OffsetLengths::default, |o| OffsetLengths {
            x: o.x,
            z: o.z,
            wear_x: o.wear_x,
            wear_z: o.wear_z,
        }))
    }

    /// Offset `number`'s lengths, or the refusal of a number outside
    /// the table (naming its size).
    pub fn offset_row(&self, number: u32) -> Result<OffsetLengths, BadKey> {
        self.offset_lengths(number).ok_or_else(|| BadKey {
            key: "tools.offsets".into(),
            msg: format!(
                "offset {number} is outside the table: offsets are 1 … {}",
                self.tools.offsets
            ),
        })
    }

    /// Sets the lengths of tool offset `number`; its nose radius and tip
    /// stay. Refused, changing nothing, for a number outside the table or
    /// a value outside the machine file's ranges (±10⁶ mm, finite).
    pub fn set_offset_lengths(&mut self, number: u32, l: OffsetLengths) -> Result<(), BadKey> {
        self.offset_row(number)?;
        let mut edited = self.clone();
        let offsets = &mut edited.tools.offset;
        let i = match offsets.iter().position(|o| o.number == number) {
            Some(i) => i,
            None => {
                offsets.push(ToolOffset {
                    number,
                    ..ToolOffset::default()
                });
                offsets.len() - 1
            }
        };
        let o = &mut offsets[i];
        (o.x, o.z, o.wear_x, o.wear_z) = (l.x, l.z, l.wear_x, l.wear_z);
        check(&edited)?;
        *self = edited;
        Ok(())
    }

    /// A work offset, mm (X on the diameter).
    pub fn work_offset_of(&self, w: WorkOffset) -> Xz {
        let c = &self.coords;
        [c.exofs, c.g54, c.g55, c.g56, c.g57, c.g58, c.g59][w as usize]
    }

    /// Sets a work offset. Refused, changing nothing, for a value outside
    /// the machine file's ranges.
    pub fn set_work_offset(&mut self, w: WorkOffset, at: Xz) -> Result<(), BadKey> {
        let mut edited = self.clone();
        let c = &mut edited.coords;
        let slot = match w {
            WorkOffset::External => &mut c.exofs,
            WorkOffset::G54 => &mut c.g54,
            WorkOffset::G55 => &mut c.g55,
            WorkOffset::G56 => &mut c.g56,
            WorkOffset::G57 => &mut c.g57,
            WorkOffset::G58 => &mut c.g58,
            WorkOffset::G59 => &mut c.g59,
        };
        *slot = at;
        check(&edited)?;
        *self = edited;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edit_sets_the_lengths_and_keeps_the_nose() {
        let mut m =
            Machine::from_toml("[[tools.offset]]\nnumber = 2\nradius = 0.4\ntip = 3\nx = -6.0\n")
                .expect("a machine file");
        let keys = m.compile_keys();
        let l = OffsetLengths {
            x: -5.5,
            z: 12.0,
            wear_x: -0.02,
            wear_z: 0.01,
        };
        assert_eq!(m.set_offset_lengths(2, l), Ok(()));
        assert_eq!(m.offset_lengths(2), Some(l));
        assert_eq!((m.tools.offset[0].radius, m.tools.offset[0].tip), (0.4, 3));
        // An offset not in the file gets an entry of its own.
        assert_eq!(m.offset_lengths(5), Some(OffsetLengths::default()));
        assert_eq!(m.set_offset_lengths(5, l), Ok(()));
        assert_eq!(m.offset_lengths(5), Some(l));
        // Lengths are no compile key: the module still runs.
        assert_eq!(m.compile_keys(), keys);
    }

    #[test]
    fn a_bad_edit_changes_nothing() {
        let mut m = Machine::reference();
        let before = m.clone();
        let nan = OffsetLengths {
            wear_x: f64::NAN,
            ..OffsetLengths::default()
        };
        assert!(m.set_offset_lengths(1, nan).is_err());
        let far = OffsetLengths {
            z: 2.0e6,
            ..OffsetLengths::default()
        };
        assert!(m.set_offset_lengths(1, far).is_err());
        // Offsets count 1 ..= tools.offsets (32).
        let e = m.set_offset_lengths(0, OffsetLengths::default());
        assert_eq!(
            e.map_err(|e| e.msg),
            Err("offset 0 is outside the table: offsets are 1 … 32".into())
        );
        assert!(m.set_offset_lengths(33, OffsetLengths::default()).is_err());
        assert_eq!(m.offset_lengths(33), None);
        let inf = Xz {
            x: 0.0,
            z: f64::INFINITY,
        };
        assert!(m.set_work_offset(WorkOffset::G55, inf).is_err());
        assert_eq!(m, before);
    }

    #[test]
    fn work_offsets_are_the_coords_section() {
        let mut m = Machine::reference();
        let at = Xz { x: 0.0, z: -250.0 };
        assert_eq!(m.set_work_offset(WorkOffset::G56, at), Ok(()));
        assert_eq!(m.coords.g56, at);
        assert_eq!(m.work_offset_of(WorkOffset::G56), at);
        assert_eq!(m.work_offset(3), at);
        assert_eq!(m.work_offset_of(WorkOffset::External), Xz::default());
    }
}
