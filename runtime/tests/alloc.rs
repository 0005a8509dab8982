//! The per-period path allocates nothing: a counting global allocator
//! sees no allocation inside `tick()` over whole runs (lines, arcs, a
//! thread, G96, feed hold, dwell, PLC functions), while `run_ahead` — the
//! VM side — may allocate as it likes between the ticks. The same holds
//! for the real-time half of a split controller, ticked while its
//! interpreter allocates on a thread of its own (the count is per thread).

mod common;

use common::module;
use nc::Machine;
use runtime::{Controller, RunState};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCS.fetch_add(1, Ordering::Relaxed);
        }
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        if COUNTING.with(Cell::get) {
            ALLOCS.fetch_add(1, Ordering::Relaxed);
        }
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCS.fetch_add(1, Ordering::Relaxed);
        }
        unsafe { System.realloc(p, l, n) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const PROGRAM: &str = "O0001\nG50 X100 Z50\nT0101 M03 S800\nG00 X40 Z2 M08\nG99 G01 Z-20 F0.2\nX50 Z-30\nG02 X60 Z-35 R5\n\
               G98 G01 Z-40 F300\nG04 X0.2\nG96 S120\nG01 X20 F200\nG97 S600\nG00 X30 Z5\nG32 Z-20 F1.5\nG00 X100 Z50 M09\nM30\n";

#[test]
fn ticks_allocate_nothing() {
    let m = module(PROGRAM, &Machine::reference());
    let mut ctl = Controller::new(m, Machine::reference(), runtime::AutoAck).unwrap();
    ctl.cycle_start();
    let mut ticks = 0u64;
    loop {
        ctl.run_ahead();
        COUNTING.with(|c| c.set(true));
        let sp = ctl.tick();
        COUNTING.with(|c| c.set(false));
        ticks += 1;
        if ticks == 3000 {
            ctl.feed_hold();
        }
        if ticks == 3300 {
            ctl.cycle_start();
        }
        match ctl.state() {
            RunState::Ended | RunState::Alarm(_) => break,
            RunState::Stopped(_) => ctl.cycle_start(),
            _ => {}
        }
        assert!(sp.time_s < 600.0);
    }
    assert_eq!(ctl.state(), RunState::Ended);
    assert!(ticks > 10_000);
    assert_eq!(
        ALLOCS.load(Ordering::Relaxed),
        0,
        "allocations inside tick()"
    );
}

#[test]
fn split_ticks_allocate_nothing() {
    let m = module(PROGRAM, &Machine::reference());
    let ctl = Controller::new(m, Machine::reference(), runtime::AutoAck).unwrap();
    let (mut interp, mut rt) = ctl.split();
    rt.cycle_start();
    let stop = std::sync::atomic::AtomicBool::new(false);
    let mut ticks = 0u64;
    let mut allocs = 0;
    std::thread::scope(|s| {
        s.spawn(|| {
            while !stop.load(Ordering::Acquire) {
                interp.run_ahead();
                std::thread::yield_now();
            }
        });
        let before = ALLOCS.load(Ordering::Relaxed);
        loop {
            COUNTING.with(|c| c.set(true));
            let sp = rt.tick();
            COUNTING.with(|c| c.set(false));
            ticks += 1;
            match rt.state() {
                RunState::Ended | RunState::Alarm(_) => break,
                RunState::Stopped(_) => rt.cycle_start(),
                RunState::Starved => std::thread::yield_now(),
                _ => {}
            }
            assert!(sp.time_s < 600.0);
        }
        allocs = ALLOCS.load(Ordering::Relaxed) - before;
        stop.store(true, Ordering::Release);
    });
    assert_eq!(rt.state(), RunState::Ended);
    assert!(ticks > 10_000);
    assert_eq!(allocs, 0, "allocations inside the split tick()");
}
