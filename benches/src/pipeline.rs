//! The runtime benches' pipelines, shared with the profiling example:
//! a program's move commands, planning them, VM + planning, and an engine
//! ticked period by period.

use runtime::command::{Command, Move, MoveKind, Path, Tag};
use runtime::math::V2;
use runtime::planner::Planner;
use runtime::translate::Translator;
use runtime::{AutoAck, Config, Engine};
use std::sync::atomic::{AtomicBool, Ordering};

/// The commands a program turns into (VM and translation done once):
/// its moves.
pub fn commands(src: &str) -> Vec<Command> {
    let mut out = all_commands(src);
    out.retain(|c| matches!(c, Command::Move(_)));
    out
}

/// Its moves and PLC functions (the spindle a thread waits for).
pub fn spindle_commands(src: &str) -> Vec<Command> {
    let mut out = all_commands(src);
    out.retain(|c| matches!(c, Command::Move(_) | Command::Plc(_)));
    out
}

fn all_commands(src: &str) -> Vec<Command> {
    let machine = nc::Machine::reference();
    let mut vm = vm::Vm::new(crate::build(src), machine.clone());
    let mut events: Vec<nc::Event> = Vec::new();
    let _ = vm.run(&mut events);
    let mut t = Translator::new(V2::ZERO);
    let mut out = Vec::new();
    for e in &events {
        t.event(e, &vm.nc, &machine, &mut out);
    }
    out
}

/// Pushes every command, retiring from the head when the queue is full.
pub fn plan_all(p: &mut Planner, cmds: &[Command]) -> usize {
    p.clear();
    p.set_tail(V2::ZERO);
    let tag = Tag::default();
    for &c in cmds {
        if p.push(c, tag).is_err() {
            for _ in 0..256 {
                p.pop();
            }
            let _ = p.push(c, tag);
        }
    }
    p.replan();
    p.len()
}

/// VM + translation + planning of a compiled program.
pub fn vm_plan(module: isa::Module, p: &mut Planner) -> usize {
    struct Plan<'a> {
        t: Translator,
        p: &'a mut Planner,
        nc: nc::Nc,
        m: nc::Machine,
        buf: Vec<Command>,
    }
    impl nc::Sink for Plan<'_> {
        fn emit(&mut self, e: nc::Event) {
            self.buf.clear();
            self.t.event(&e, &self.nc, &self.m, &mut self.buf);
            for &c in &self.buf {
                if self.p.push(c, Tag::default()).is_err() {
                    for _ in 0..256 {
                        self.p.pop();
                    }
                    let _ = self.p.push(c, Tag::default());
                }
            }
        }
    }
    let machine = nc::Machine::reference();
    let mut vm = vm::Vm::new(module, machine.clone());
    p.clear();
    p.set_tail(V2::ZERO);
    let nc = vm.nc.clone();
    let mut sink = Plan {
        t: Translator::new(V2::ZERO),
        p,
        nc,
        m: machine,
        buf: Vec::new(),
    };
    let _ = vm.run(&mut sink);
    sink.p.replan();
    sink.p.len()
}

/// Parse + compile + VM + translation + planning of a whole program.
pub fn end_to_end(src: &str, p: &mut Planner) -> usize {
    vm_plan(crate::build(src), p)
}

/// As [`vm_plan`] through a split controller: the interpreter on a
/// thread of its own, the real-time half planning on this one (retiring
/// planned moves, as the interpolator would, whenever the look-ahead is
/// queued: the interpreter waits for that).
/// Returns the moves planned.
pub fn vm_plan_split(module: isa::Module) -> usize {
    let machine = nc::Machine::reference();
    let ctl = runtime::Controller::with_config(module, machine, Config::default(), AutoAck);
    let Ok(ctl) = ctl else { return 0 };
    let (mut interp, mut rt) = ctl.split();
    let ahead = rt.engine().config().lookahead_blocks;
    let done = AtomicBool::new(false);
    let mut planned = 0;
    std::thread::scope(|s| {
        s.spawn(|| {
            while !interp.finished() {
                interp.run_ahead();
                // (The look-ahead is queued: let a third thread, such as
                // the compiler's freeing of the trees, have the core.)
                std::thread::yield_now();
            }
            done.store(true, Ordering::Release);
        });
        loop {
            let finished = done.load(Ordering::Acquire);
            if rt.plan_pending() == 0 {
                if finished && rt.pending() == 0 {
                    break;
                }
                std::thread::yield_now();
            }
            let q = rt.engine_mut().planner_mut();
            if q.len() >= ahead {
                for _ in 0..256 {
                    q.pop();
                }
                planned += 256;
            }
        }
    });
    planned + rt.engine().planner().len()
}

/// Parse + compile + split VM ‖ planning of a whole program.
pub fn end_to_end_split(src: &str) -> usize {
    vm_plan_split(crate::build(src))
}

/// An engine running `cmds` over and over; `tick` it.
pub struct Ticker {
    pub e: Engine<AutoAck>,
    cmds: Vec<Command>,
    next: usize,
}

impl Ticker {
    pub fn new(cmds: Vec<Command>) -> Ticker {
        let mut e = Engine::new(Config::default(), AutoAck);
        e.cycle_start();
        let mut t = Ticker { e, cmds, next: 0 };
        t.refill();
        t
    }

    /// Keeps the queue fed (the non-real-time side), restarting the
    /// program when it has been used up.
    pub fn refill(&mut self) {
        while self.e.planner().len() + 1 < self.e.planner().capacity() {
            if self.next == self.cmds.len() {
                self.next = 0;
                // Back to the program start at rapid, from wherever it is.
                let to = match self.cmds[0] {
                    Command::Move(m) => m.path.to(),
                    _ => V2::ZERO,
                };
                let _ = self.e.push(
                    Command::Move(Move {
                        kind: MoveKind::Rapid,
                        path: Path::Line { to },
                        shift: V2::ZERO,
                        c: None,
                    }),
                    Tag::default(),
                );
                continue;
            }
            let c = self.cmds[self.next];
            self.next += 1;
            let _ = self.e.push(c, Tag::default());
        }
        self.e.replan();
    }

    pub fn low(&self) -> bool {
        self.e.planner().len() < 1100
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_split_pipeline_plans_what_the_one_thread_pipeline_plans() {
        for src in [crate::arcs(5000), crate::short_segments(5000)] {
            // What one planner, never full, queues of the program's moves
            // (not those of zero length) ...
            let cfg = Config {
                queue_capacity: 8192,
                ..Config::default()
            };
            let mut p = Planner::new(&cfg);
            let tag = Tag::default();
            let cmds = commands(&src);
            let queued = cmds
                .iter()
                .filter(|&&c| p.push(c, tag) == Ok(runtime::planner::Pushed::Queued))
                .count();
            assert!(queued > 4900);
            // ... and the program's end after them.
            assert_eq!(vm_plan_split(crate::build(&src)), queued + 1);
        }
    }
}
