//! A small cache of source locations by pc.
//!
//! The line table is compact runs (`isa::LineTable`): a look-up is a
//! binary search and a few runs decoded. The trace and `gbvm run`'s
//! progress ask for the location of every block executed, and a loop runs
//! the same few blocks again and again: their answers are kept here.

use core::cell::Cell;

use isa::{LineTable, SourceLoc};

/// Entries, by `pc % SLOTS`.
const SLOTS: usize = 16;

/// No pc: a module has fewer than `u32::MAX` instructions.
const EMPTY: (u32, SourceLoc) = (
    u32::MAX,
    SourceLoc {
        file: 0,
        line: 0,
        col: 0,
    },
);

/// Direct-mapped: each pc has one slot. Interior mutability, so that a
/// look-up through `&Vm` can fill it.
#[derive(Debug)]
pub(crate) struct LocCache {
    slots: [Cell<(u32, SourceLoc)>; SLOTS],
}

impl Default for LocCache {
    fn default() -> Self {
        LocCache {
            slots: core::array::from_fn(|_| Cell::new(EMPTY)),
        }
    }
}

impl LocCache {
    /// The location of `pc` in `lines` (the default past its end).
    pub(crate) fn get(&self, lines: &LineTable, pc: u32) -> SourceLoc {
        let slot = &self.slots[pc as usize % SLOTS];
        match slot.get() {
            (at, loc) if at == pc => loc,
            _ => {
                let loc = lines.get(pc as usize).unwrap_or_default();
                slot.set((pc, loc));
                loc
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_as_the_table_and_keeps_answering() {
        // Lines 10, 10, 11, 12, … at columns 1 and 5: entries collide
        // (pc 3 and 19 share a slot) and are replaced.
        let locs: alloc::vec::Vec<SourceLoc> = (0..40)
            .map(|pc| SourceLoc {
                file: 0,
                line: 10 + pc / 2,
                col: 1 + 4 * (pc % 2),
            })
            .collect();
        let table: LineTable = locs.iter().copied().collect();
        let cache = LocCache::default();
        for pc in [3, 19, 3, 3, 0, 39, 19, 40] {
            let want = locs.get(pc as usize).copied().unwrap_or_default();
            assert_eq!(cache.get(&table, pc), want, "pc {pc}");
        }
    }
}
