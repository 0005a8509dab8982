//! Where the axes stand, published by the real-time half for the
//! interpreter's measured cut (`Interpreter::measure_tool_offset`): X
//! and Z of the machine set point while the axes stand idle or at the
//! program's end, else nothing.
//!
//! Two `f64` do not fit one atomic, so they go under a sequence count
//! (a seqlock): the writer makes the count odd, writes, makes it even
//! again; a reader takes the values only if it saw the same even count
//! before and after. The writer never waits. The reader retries only
//! while a write is under way (a few stores), and gives up after
//! [`TRIES`] (reading "not standing": the slide moves if it writes so
//! often).

use core::sync::atomic::{fence, AtomicU32, Ordering};
use nc::machine::Xz;

/// Reads a reader tries before it takes the point for not standing.
const TRIES: usize = 64;

/// The bits of "not standing" in X (a NaN no set point is).
const NONE: u64 = u64::MAX;

pub(super) struct StandingCell {
    seq: AtomicU32,
    /// X's and Z's bits, low half first.
    words: [AtomicU32; 4],
}

impl StandingCell {
    pub fn new(at: Option<Xz>) -> StandingCell {
        StandingCell {
            seq: AtomicU32::new(0),
            words: halves(at).map(AtomicU32::new),
        }
    }

    /// The real-time half's write (its only writer).
    pub fn store(&self, at: Option<Xz>) {
        let s = self.seq.load(Ordering::Relaxed);
        self.seq.store(s.wrapping_add(1), Ordering::Relaxed);
        // The odd count is seen before any of the new values.
        fence(Ordering::Release);
        for (w, v) in self.words.iter().zip(halves(at)) {
            w.store(v, Ordering::Relaxed);
        }
        self.seq.store(s.wrapping_add(2), Ordering::Release);
    }

    /// The interpreter's read.
    pub fn load(&self) -> Option<Xz> {
        for _ in 0..TRIES {
            let before = self.seq.load(Ordering::Acquire);
            if before % 2 == 1 {
                core::hint::spin_loop();
                continue;
            }
            let [x0, x1, z0, z1] = self.words.each_ref().map(|w| w.load(Ordering::Relaxed));
            let (x, z) = (join(x0, x1), join(z0, z1));
            // The values are read before the count again.
            fence(Ordering::Acquire);
            if self.seq.load(Ordering::Relaxed) == before {
                return (x != NONE).then(|| Xz {
                    x: f64::from_bits(x),
                    z: f64::from_bits(z),
                });
            }
        }
        None
    }
}

/// X's and Z's bits (NONE for none) in 32-bit halves, low first.
fn halves(at: Option<Xz>) -> [u32; 4] {
    let (x, z) = at.map_or((NONE, NONE), |p| (p.x.to_bits(), p.z.to_bits()));
    [x as u32, (x >> 32) as u32, z as u32, (z >> 32) as u32]
}

fn join(low: u32, high: u32) -> u64 {
    u64::from(low) | u64::from(high) << 32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_read_as_written_and_none_as_none() {
        let cell = StandingCell::new(None);
        assert_eq!(cell.load(), None);
        let at = Xz { x: 52.1, z: -0.25 };
        cell.store(Some(at));
        assert_eq!(cell.load(), Some(at));
        cell.store(None);
        assert_eq!(cell.load(), None);
    }

    /// A writer on another thread storing pairs whose Z is always −X:
    /// no read ever mixes two of them.
    #[test]
    fn a_read_never_mixes_two_writes() {
        extern crate std;
        let cell = StandingCell::new(Some(Xz { x: 0.0, z: 0.0 }));
        let done = core::sync::atomic::AtomicBool::new(false);
        std::thread::scope(|s| {
            s.spawn(|| {
                for i in 0..200_000u32 {
                    let v = f64::from(i);
                    cell.store(Some(Xz { x: v, z: -v }));
                }
                done.store(true, Ordering::Release);
            });
            while !done.load(Ordering::Acquire) {
                if let Some(p) = cell.load() {
                    assert_eq!(p.z, -p.x);
                }
            }
        });
        assert_eq!(
            cell.load(),
            Some(Xz {
                x: 199_999.0,
                z: -199_999.0
            })
        );
    }
}
