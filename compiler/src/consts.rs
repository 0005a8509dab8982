//! The index that keeps the module's constant pool free of repeats.
//!
//! An exact table holds the first `EXACT` distinct values: all of a
//! small program's. Once it is full, a small direct-mapped table of recent
//! values takes over: the values a large program repeats (feeds, speeds,
//! codes) come back often enough to stay in it, and so do coordinates that
//! repeat close together. A CAM program of a million distinct coordinates
//! gains little from a full table, and the random probes into one that
//! large cost more than all the rest of the lowering. A value the recent
//! table has lost is stored again: the pool then holds it twice, which
//! changes nothing but the pool's size.

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
        let next = pool.len() as u32;
        if self.exact.len() < EXACT {
            let k = *self.exact.entry(bits).or_insert(next);
            if k == next {
                pool.push(v);
            }
            return k;
        }
        let slot = slot_of(bits);
        let (b, k) = self.recent[slot];
        if b == bits && k != u32::MAX {
            return k;
        }
        pool.push(v);
        self.recent[slot] = (bits, next);
        next
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

    /// Past the exact table: a value used in every block and a value
    /// repeated soon after its first use are found; every index stays
    /// right.
    #[test]
    fn large_pools_still_find_early_and_recent_values() {
        let mut ix = ConstIndex::default();
        let mut pool = Vec::new();
        for i in 0..EXACT {
            ix.index(&mut pool, i as f64);
        }
        assert_eq!(pool.len(), EXACT);
        // A feed first used before the table filled: stored once more, at
        // its first use after that.
        let feed = ix.index(&mut pool, 7.0);
        assert_eq!(feed as usize, EXACT);
        for i in 0..50_000 {
            let v = 1e6 + i as f64 * 0.001;
            let k = ix.index(&mut pool, v);
            check(&pool, v, k);
            // The same coordinate again in the next block: no new entry.
            let len = pool.len();
            assert_eq!(ix.index(&mut pool, v), k);
            assert_eq!(pool.len(), len);
            // The feed, in every block: found, unless a coordinate took
            // its slot a moment ago.
            let f = ix.index(&mut pool, 7.0);
            check(&pool, 7.0, f);
        }
        // Coordinates once each; the feed a few times at most.
        assert!(pool.len() < EXACT + 50_000 + 100, "{}", pool.len());
    }
}
