//! A cheap hasher for the compiler's maps keyed by integers (constant
//! bits, variable numbers). The standard SipHash guards against chosen
//! collisions, but costs more than the rest of a lookup; a multiply that
//! folds its high half into the low one spreads integer keys well.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A map with [`IntHasher`].
pub type IntMap<K, V> = HashMap<K, V, BuildHasherDefault<IntHasher>>;

/// Hashes integer keys by multiplying (other input is folded in bytewise).
#[derive(Default, Clone, Copy)]
pub struct IntHasher(u64);

/// An odd constant with well-mixed bits (the golden ratio's fraction).
const K: u64 = 0x9e37_79b9_7f4a_7c15;

impl IntHasher {
    fn add(&mut self, x: u64) {
        let m = u128::from((self.0 ^ x).wrapping_add(K)) * u128::from(K);
        self.0 = (m as u64) ^ ((m >> 64) as u64);
    }
}

impl Hasher for IntHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.add(u64::from(b));
        }
    }

    fn write_u32(&mut self, x: u32) {
        self.add(u64::from(x));
    }

    fn write_u64(&mut self, x: u64) {
        self.add(x);
    }
}

#[cfg(test)]
mod tests {
    use super::IntMap;

    #[test]
    fn keys_stay_apart() {
        let mut m: IntMap<u64, u32> = IntMap::default();
        for i in 0..10_000u32 {
            m.insert(f64::from(i).to_bits(), i);
        }
        assert_eq!(m.len(), 10_000);
        assert!((0..10_000u32).all(|i| m.get(&f64::from(i).to_bits()) == Some(&i)));
    }
}
