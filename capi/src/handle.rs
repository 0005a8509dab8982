//! The handle registry: a handle is a number, never a pointer, so a null,
//! freed (dangling) or forged handle, or one of the wrong kind, is found
//! out by looking it up in a fixed table — without touching the memory
//! of an object that may be gone.
//!
//! A handle is `generation << 32 | kind << 16 | slot + 1`, bits 24–31
//! zero. Only that exact number is accepted: decoding checks every bit,
//! so no other value names the same object. A slot's
//! generation is odd while it holds an object and even while it is free;
//! freeing bumps it, so every handle to the old object stops matching.
//! The table is a static array of atomics: a look-up takes no lock and
//! allocates nothing, so it may run in the period loop.

use core::sync::atomic::{AtomicPtr, AtomicU32, AtomicU8, Ordering};

use crate::types::GbcStatus;

/// Objects alive at once, all kinds together (`GBC_HANDLE_CAPACITY`).
pub(crate) const CAPACITY: usize = crate::types::GBC_HANDLE_CAPACITY;

/// What a handle names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Kind {
    Machine = 1,
    Controller = 2,
    /// The real-time half of a split controller.
    Realtime = 3,
}

/// A type that lives behind a handle.
pub trait Object: Sized {
    /// The kind written into its handles.
    const KIND: Kind;
}

struct Slot {
    generation: AtomicU32,
    kind: AtomicU8,
    ptr: AtomicPtr<()>,
}

static TABLE: [Slot; CAPACITY] = [const {
    Slot {
        generation: AtomicU32::new(0),
        kind: AtomicU8::new(0),
        ptr: AtomicPtr::new(core::ptr::null_mut()),
    }
}; CAPACITY];

fn encode(generation: u32, kind: Kind, slot: usize) -> u64 {
    (u64::from(generation) << 32) | ((kind as u64) << 16) | (slot as u64 + 1)
}

/// The slot, generation and kind a handle claims (not yet checked
/// against the table). `None` unless `h` is exactly what [`encode`]
/// makes of them: a slot in the table, a known kind and the unused bits
/// zero — a changed bit anywhere must not name the same object.
fn decode(h: u64) -> Option<(usize, u32, Kind)> {
    let slot = usize::try_from(h & 0xffff).ok()?.checked_sub(1)?;
    if slot >= CAPACITY {
        return None;
    }
    let kind = match (h >> 16) & 0xff {
        1 => Kind::Machine,
        2 => Kind::Controller,
        3 => Kind::Realtime,
        _ => return None,
    };
    let generation = (h >> 32) as u32;
    (encode(generation, kind, slot) == h).then_some((slot, generation, kind))
}

/// Puts `obj` in a free slot; `Err(Limit)` when all are taken.
pub fn insert<T: Object>(obj: T) -> Result<u64, GbcStatus> {
    let ptr = Box::into_raw(Box::new(obj)).cast::<()>();
    for (i, s) in TABLE.iter().enumerate() {
        let g = s.generation.load(Ordering::Acquire);
        if g % 2 == 1 {
            continue;
        }
        let live = g.wrapping_add(1);
        if s.generation
            .compare_exchange(g, live, Ordering::AcqRel, Ordering::Acquire)
            .is_ok()
        {
            s.kind.store(T::KIND as u8, Ordering::Release);
            s.ptr.store(ptr, Ordering::Release);
            return Ok(encode(live, T::KIND, i));
        }
    }
    // SAFETY: `ptr` came from `Box::into_raw` above and was never shared.
    drop(unsafe { Box::from_raw(ptr.cast::<T>()) });
    Err(GbcStatus::Limit)
}

/// The live slot a handle names and the kind of its object.
fn find(h: u64) -> Result<(&'static Slot, Kind, *mut ()), GbcStatus> {
    let (i, generation, kind) = decode(h).ok_or(GbcStatus::InvalidHandle)?;
    let s = TABLE.get(i).ok_or(GbcStatus::InvalidHandle)?;
    if generation % 2 == 0 || s.generation.load(Ordering::Acquire) != generation {
        return Err(GbcStatus::InvalidHandle);
    }
    let ptr = s.ptr.load(Ordering::Acquire);
    if ptr.is_null() || s.kind.load(Ordering::Acquire) != kind as u8 {
        return Err(GbcStatus::InvalidHandle);
    }
    Ok((s, kind, ptr))
}

/// The kind of the live object a handle names.
pub fn kind_of(h: u64) -> Result<Kind, GbcStatus> {
    find(h).map(|(_, kind, _)| kind)
}

/// The object behind a handle of kind `T`.
///
/// # Safety
/// The caller must not hold another reference to the same object (the C
/// contract: one call on a handle at a time, and no free during a call).
pub unsafe fn get<'a, T: Object>(h: u64) -> Result<&'a mut T, GbcStatus> {
    let (_, kind, ptr) = find(h)?;
    if kind != T::KIND {
        return Err(GbcStatus::WrongKind);
    }
    // SAFETY: the slot is live with kind `T`, so `ptr` is the `Box<T>`
    // that `insert` stored; exclusivity is the caller's promise.
    Ok(unsafe { &mut *ptr.cast::<T>() })
}

/// Frees the object behind a handle of kind `T`; the handle and every
/// copy of it stop working.
pub fn remove<T: Object>(h: u64) -> Result<(), GbcStatus> {
    let (s, kind, ptr) = find(h)?;
    if kind != T::KIND {
        return Err(GbcStatus::WrongKind);
    }
    let generation = (h >> 32) as u32;
    // Only one of two racing frees wins the slot.
    s.generation
        .compare_exchange(
            generation,
            generation.wrapping_add(1),
            Ordering::AcqRel,
            Ordering::Acquire,
        )
        .map_err(|_| GbcStatus::InvalidHandle)?;
    s.ptr.store(core::ptr::null_mut(), Ordering::Release);
    // SAFETY: this call won the slot, so no one else frees `ptr`, which
    // `insert` made from a `Box<T>` (the kind says `T`).
    drop(unsafe { Box::from_raw(ptr.cast::<T>()) });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    struct A(#[allow(dead_code)] u32);
    impl Object for A {
        const KIND: Kind = Kind::Machine;
    }
    struct B;
    impl Object for B {
        const KIND: Kind = Kind::Controller;
    }

    #[test]
    fn freed_and_foreign_handles_are_refused() {
        let h = insert(A(7)).unwrap();
        assert!(unsafe { get::<A>(h) }.is_ok());
        assert_eq!(unsafe { get::<B>(h) }.err(), Some(GbcStatus::WrongKind));
        remove::<A>(h).unwrap();
        assert_eq!(unsafe { get::<A>(h) }.err(), Some(GbcStatus::InvalidHandle));
        assert_eq!(remove::<A>(h), Err(GbcStatus::InvalidHandle));
        // A new object in the same slot does not revive the old handle.
        let h2 = insert(A(8)).unwrap();
        assert_ne!(h, h2);
        assert_eq!(unsafe { get::<A>(h) }.err(), Some(GbcStatus::InvalidHandle));
        remove::<A>(h2).unwrap();
        for bad in [0, 1, u64::MAX, 0xffff_ffff_0001_0001] {
            assert_eq!(
                unsafe { get::<A>(bad) }.err(),
                Some(GbcStatus::InvalidHandle)
            );
        }
    }

    #[test]
    fn a_handle_with_any_bit_changed_is_refused() {
        let h = insert(A(9)).unwrap();
        let ours: *mut A = unsafe { get::<A>(h) }.unwrap();
        for bit in 0..64 {
            let forged = h ^ (1 << bit);
            // A changed slot may name another test's live object, which is
            // right; it must never name this one.
            if let Ok(other) = unsafe { get::<A>(forged) } {
                assert_ne!(other as *mut A, ours, "bit {bit}: {forged:#x}");
            }
        }
        for high in [0x01, 0x5a, 0xff] {
            assert_eq!(
                unsafe { get::<A>(h | (high << 24)) }.err(),
                Some(GbcStatus::InvalidHandle)
            );
        }
        assert!(unsafe { get::<A>(h) }.is_ok());
        remove::<A>(h).unwrap();
    }

    #[test]
    fn decode_takes_only_what_encode_makes() {
        for (g, kind, slot) in [
            (1, Kind::Machine, 0),
            (u32::MAX, Kind::Controller, CAPACITY - 1),
        ] {
            assert_eq!(decode(encode(g, kind, slot)), Some((slot, g, kind)));
        }
        for bad in [
            encode(1, Kind::Machine, 0) | (1 << 24),
            (1 << 32) | (4 << 16) | 1,
            (1 << 32) | (1 << 16) | (CAPACITY as u64 + 1),
            (1 << 32) | (1 << 16),
        ] {
            assert_eq!(decode(bad), None, "{bad:#x}");
        }
    }
}
