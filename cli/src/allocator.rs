//! The tools' allocator: mimalloc, called the way its small-block fast path
//! expects.
//!
//! A large program's compile makes and frees one small allocation per
//! block (its words), which mimalloc does faster than the system allocator.
//! Its aligned entry point, which the `mimalloc` crate calls for every
//! allocation, serves a size that is not a power of two (a block of four
//! 48-byte words) by over-allocating on a slow path whenever the size's page
//! has no free block at hand. Every mimalloc block is aligned to a pointer's
//! size, so allocations that need no more go through plain `mi_malloc`.
//!
//! Large buffers (a program's source, the module's tables, the output)
//! go to the system allocator instead: it maps them from the system and
//! gives them back when freed, where mimalloc keeps the freed memory of
//! a grown table committed for a while, and `gbcc` held a third more than
//! it needed at its peak (the 1M-block benchmark, README). Which one a
//! block came from follows from its size, which `dealloc` and `realloc`
//! are given too.
//!
//! mimalloc is built without transparent huge pages (its `no_thp`
//! feature). With them it asks the kernel to back its arena with 2 MiB
//! pages, and the first small allocation then has a whole 2 MiB page
//! cleared: a fifth of a short `gbcc` run's time, and 1–2 ms and 8 MB of
//! resident memory of each benchmark run of the README, for no gain
//! measured on the long ones. The system allocator's blocks of 2 MiB and
//! more do get huge pages (`huge`): they are read or written whole.
//!
//! The libraries leave the choice of allocator to whoever links them.

use core::alloc::{GlobalAlloc, Layout};
use core::ffi::c_void;
use libmimalloc_sys as mi;
use std::alloc::System;

/// Blocks from this size are the system allocator's. (At 1 MiB, the
/// chunks' trees and IR of `gbcc`, which are smaller, kept 8 MB more on
/// the 1M-block benchmark.)
const LARGE: usize = 1 << 16;

fn is_large(size: usize) -> bool {
    size >= LARGE
}

/// What every block `mi_malloc` returns is aligned to.
const PLAIN_ALIGN: usize = core::mem::size_of::<usize>();

pub struct Mimalloc;

// SAFETY: every call hands mimalloc a size and, where the alignment is
// above what `mi_malloc` guarantees, that alignment; memory is freed by
// `mi_free`, which takes blocks from either entry point.
unsafe impl GlobalAlloc for Mimalloc {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if is_large(layout.size()) {
            return huge(System.alloc(layout), layout.size());
        }
        if layout.align() <= PLAIN_ALIGN {
            mi::mi_malloc(layout.size()).cast()
        } else {
            mi::mi_malloc_aligned(layout.size(), layout.align()).cast()
        }
    }

    #[inline]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if is_large(layout.size()) {
            return huge(System.alloc_zeroed(layout), layout.size());
        }
        if layout.align() <= PLAIN_ALIGN {
            mi::mi_zalloc(layout.size()).cast()
        } else {
            mi::mi_zalloc_aligned(layout.size(), layout.align()).cast()
        }
    }

    #[inline]
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if is_large(layout.size()) {
            System.dealloc(ptr, layout);
        } else {
            mi::mi_free(ptr.cast::<c_void>());
        }
    }

    #[inline]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        match (is_large(layout.size()), is_large(new_size)) {
            (true, true) => return huge(System.realloc(ptr, layout, new_size), new_size),
            (false, false) => {}
            // Across the line: into a block of the other allocator.
            _ => return self.move_to(ptr, layout, new_size),
        }
        if layout.align() <= PLAIN_ALIGN {
            mi::mi_realloc(ptr.cast::<c_void>(), new_size).cast()
        } else {
            mi::mi_realloc_aligned(ptr.cast::<c_void>(), new_size, layout.align()).cast()
        }
    }
}

/// The size of a transparent huge page (x86-64, AArch64 with 4 KiB pages).
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back the whole huge pages inside a large block with
/// huge pages (where transparent huge pages are enabled for `madvise`, as
/// Debian has them): a 4.5 MB source is then read into one or two of them
/// and the 4 KiB pages at its ends rather than 1 100 small pages, and the
/// process gives them back as fast when it exits. Reading the 200 000-block
/// benchmark's source took 2.0 ms, 0.6 ms so (a test in C, same machine).
/// Only blocks of a huge page or more: the pages are filled as they are
/// touched, so a block's part that is never written costs at most the
/// one page it ends in. The advice is a hint: refused, nothing changes.
unsafe fn huge(block: *mut u8, size: usize) -> *mut u8 {
    #[cfg(target_os = "linux")]
    if size >= HUGE_PAGE && !block.is_null() {
        let start = (block as usize).next_multiple_of(HUGE_PAGE);
        let end = (block as usize + size) & !(HUGE_PAGE - 1);
        if end > start {
            libc::madvise(start as *mut c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
    block
}

impl Mimalloc {
    /// `realloc` from one allocator's block to the other's: a new block,
    /// the bytes both hold, the old block freed.
    unsafe fn move_to(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let Ok(new_layout) = Layout::from_size_align(new_size, layout.align()) else {
            return core::ptr::null_mut();
        };
        let new = self.alloc(new_layout);
        if !new.is_null() {
            core::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
            self.dealloc(ptr, layout);
        }
        new
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Allocates, writes, grows and frees blocks of every alignment the
    /// shim routes either way, checking each address's alignment.
    #[test]
    fn blocks_are_aligned_and_keep_their_bytes() {
        let a = Mimalloc;
        for align in [1, 2, 4, 8, 16, 32, 64, 4096] {
            // (The last sizes grow across `LARGE`, or start past it.)
            for size in [
                1,
                7,
                8,
                24,
                48,
                192,
                200,
                1000,
                5000,
                70_000,
                400_000,
                2 << 20,
            ] {
                let Ok(layout) = Layout::from_size_align(size, align) else {
                    continue;
                };
                unsafe {
                    let p = a.alloc(layout);
                    assert!(!p.is_null());
                    assert_eq!(p as usize % align, 0, "size {size} align {align}");
                    for i in 0..size {
                        *p.add(i) = (i % 251) as u8;
                    }
                    let q = a.realloc(p, layout, size * 3);
                    assert!(!q.is_null());
                    assert_eq!(q as usize % align, 0, "grown {size} align {align}");
                    for i in 0..size {
                        assert_eq!(*q.add(i), (i % 251) as u8);
                    }
                    a.dealloc(q, Layout::from_size_align_unchecked(size * 3, align));
                    let z = a.alloc_zeroed(layout);
                    assert_eq!(z as usize % align, 0);
                    assert!((0..size).all(|i| *z.add(i) == 0));
                    a.dealloc(z, layout);
                }
            }
        }
    }
}
