//! The index that keeps the module's constant pool free of repeats.
//!
//! An exact table holds the first [`EXACT`] distinct values: all of a small
//! program's, and the ones a large program repeats (feeds, speeds, codes,
//! round coordinates) are nearly always among its first. Past that, a
//! small direct-mapped table of recent values catches the rest that repeat
//! close together. A CAM program of a million distinct coordinates gains
//! little from a full table, and the random probes into one that large
//! cost more than all the rest of the lowering. A value missed by both is
//! stored again: the pool may then hold it twice, which changes nothing
//! but the pool's size.

use crate::hash::IntMap;

/// Distinct values remembered exactly.
const EXACT: usize = 4096;

/// Slots of the table of recent values (a power of two; 64 KiB).
const RECENT: usize = 4096;

/// A recent-table slot that holds nothing (no pool has this many entries).
const EMPTY: (u64, u32) = (0, u32::MAX);

pub struct ConstIndex {
    exact: IntMap<u64, u32>,
    recent: Vec<(u64, u32)>,
}

impl Default for ConstIndex {
    fn default() -> ConstIndex {
        ConstIndex {
            exact: IntMap::default(),
            recent: vec![EMPTY; RECENT],
        }
    }
}

impl ConstIndex {
    /// The index of `v` in `pool`, appending it when it is not found.
    /// Values are told apart by their bits (so −0 is not 0).
    pub fn index(&mut self, pool: &mut Vec<f64>, v: f64) -> u32 {
        let bits = v.to_bits();
        if let Some(&k) = self.exact.get(&bits) {
            return k;
        }
        let slot = slot_of(bits);
        let (b, k) = self.recent[slot];
        if b == bits && k != u32::MAX {
            return k;
        }
        let k = pool.len() as u32;
        pool.push(v);
        if self.exact.len() < EXACT {
            self.exact.insert(bits, k);
        } else {
            self.recent[slot] = (bits, k);
        }
        k
    }
}

/// A slot from the high bits of a multiplicative hash (the low bits of a
/// double's pattern are often all zero).
fn slot_of(bits: u64) -> usize {
    (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - RECENT.trailing_zeros())) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index names a pool entry with the value's own bits.
    fn check(pool: &[f64], v: f64, k: u32) {
        assert_eq!(pool[k as usize].to_bits(), v.to_bits(), "{v}");
    }

    /// A small program's values are stored once each, in first-use order.
    #[test]
    fn small_pools_hold_each_value_once() {
        let mut ix = ConstIndex::default();
        let mut pool = Vec::new();
        let values = [1.0, 0.2, -0.0, 0.0, 1.0, 0.2, 30.5, -0.0, 1.0];
        let ks: Vec<u32> = values.iter().map(|&v| ix.index(&mut pool, v)).collect();
        assert_eq!(ks, [0, 1, 2, 3, 0, 1, 4, 2, 0]);
        assert_eq!(pool.len(), 5);
        for (&v, &k) in values.iter().zip(&ks) {
            check(&pool, v, k);
        }
    }

    /// Past the exact table: the values it holds and a value repeated
    /// soon after its first use are still found; every index stays right.
    #[test]
    fn large_pools_still_find_early_and_recent_values() {
        let mut ix = ConstIndex::default();
        let mut pool = Vec::new();
        for i in 0..EXACT {
            ix.index(&mut pool, i as f64);
        }
        assert_eq!(pool.len(), EXACT);
        for i in 0..50_000 {
            let v = 1e6 + i as f64 * 0.001;
            let k = ix.index(&mut pool, v);
            check(&pool, v, k);
            // The same coordinate again in the next block: no new entry.
            let len = pool.len();
            assert_eq!(ix.index(&mut pool, v), k);
            assert_eq!(pool.len(), len);
            // A feed from the start of the program: found exactly.
            assert_eq!(ix.index(&mut pool, 7.0), 7);
        }
        assert_eq!(pool.len(), EXACT + 50_000);
    }
}
