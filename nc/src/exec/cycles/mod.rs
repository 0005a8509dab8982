//! Single canned cycles, threading, grooving and drilling (cycles.md §1–§4,
//! §9–§12, §16–§22): G90 G92 G94, G32 G32.1 G32.2 G32.3 G33 G34 G92.1,
//! G74 G75 G76 G78, G83 G84 G87 G88.
//!
//! Every cycle first computes its whole path as a list of legs
//! (`legs::Leg`) and checks it, and only then prints it: an alarm of a
//! cycle block comes before any of its legs, at compile time (the dry run)
//! and at run time alike.

use alloc::format;

mod arc_thread;
mod drill;
mod groove;
mod lead;
// The legs and the G90/G94 paths are the compensation's input (comp.md §9).
pub(crate) mod legs;
mod multi;
mod tapping;
mod thread;
mod thread_cycle;
pub(crate) mod turning;
mod words;

#[cfg(test)]
pub(crate) mod testing;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{self, Drill, Motion, OneShot, G};
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};

/// Modal state of these cycles: the thread lead, the G90/G92/G94 run, the
/// thread words, the first blocks of G74–G78 and the drilling data.
#[derive(Debug, Clone, Default)]
pub struct CycleState {
    /// The one modal thread lead in mm (dialect.md §4.3).
    pub(crate) lead: Option<f64>,
    /// The values of the G90/G92/G92.1/G94 run in progress (§4).
    pub(crate) run: Option<turning::Run>,
    /// G92 J, K (pull-out γx, γz in mm) until a G92 gives new ones (§3).
    pub(crate) g92_pull: Option<(f64, f64)>,
    /// G32/G34 chains and their run-out words (§16).
    pub(crate) chain: thread::Chain,
    /// The first blocks of G76 and G78 (§11, §19).
    pub(crate) g76: multi::G76First,
    pub(crate) g78: multi::G78First,
    /// The retracts e of the first G74 and G75 blocks (§9, §10).
    pub(crate) groove: groove::Retracts,
    /// Group-10 data and the M29 rules (§21, §22).
    pub(crate) drill: drill::DrillState,
}

/// What a block does in group 2 of canon.md's order, once its modal codes
/// have taken effect (the same choice as `Nc::motion`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Func {
    /// A group-00 function owns the block.
    OneShot(OneShot),
    /// A drilling/tapping cycle of group 10 is in force.
    Drill(Drill),
    /// The group-01 motion in force.
    Motion(Motion),
}

pub(crate) fn func(nc: &Nc, p: &Parsed) -> Func {
    // G09 only adds an exact stop: the block's motion runs as usual.
    match p.one_shot() {
        Some(code) if code != OneShot::ExactStop => Func::OneShot(code),
        _ => match nc.st.modal.drill() {
            Some(drill) => Func::Drill(drill),
            None => Func::Motion(nc.st.modal.motion),
        },
    }
}

/// Whether the block's F is a thread lead rather than the modal feed
/// (cycles.md §0 "thread lead and feed"): G32–G34, G92, G92.1, G76, G78 and
/// the tapping cycles G84/G88.
pub fn f_is_lead(nc: &Nc, p: &Parsed) -> bool {
    match func(nc, p) {
        Func::OneShot(code) => matches!(code, OneShot::MultiThread | OneShot::SpiralThread),
        Func::Drill(code) => code.taps(),
        Func::Motion(code) => code.is_thread(),
    }
}

/// The rules of this module that every block passes before its group-1
/// events: the end of a G32/G34 chain, the words a new run or a
/// non-thread code forgets, the M29 rules and the clamp code of a drilling
/// block. Returns the block's clamp M code, which is not a PLC M code.
pub fn before_block(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
) -> Result<Option<crate::base::mcode::M>, NcError> {
    let f = func(nc, p);
    check_negative_f(p, f)?;
    thread::next_block(nc, f, p, sink);
    forget(nc, p);
    drill::before_block(nc, f, p)
}

/// [`before_block`] for a block the plain path takes (`plain::takes`,
/// its group-1 code already in force): at most a G00–G03, an axis word,
/// no M word, no drilling cycle in force. The same rules in the same
/// order, those alone that can act on such a block: the general one asks
/// of it what only other blocks have (140 of the 1 730 instructions
/// `gbvm` spends on a plain G01; 95 fewer so). `compiler/tests/plain_path.rs`
/// and `plain.rs`'s tests compare the two.
pub(crate) fn before_plain_block(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    // (Not a thread nor a tapping code: F is never a left-hand lead.)
    check_negative_f(p, Func::Motion(nc.st.modal.motion))?;
    // A code that is not a thread ends a G32/G34 chain.
    thread::flush(nc, sink);
    if p.motion().is_some() {
        let st = &mut nc.st.cycles;
        st.g92_pull = None;
        st.chain.runout = None;
        st.run = None;
    }
    drill::before_plain_block(nc, p)
}

/// F < 0 is a left-hand lead, which only the rigid threads and tapping
/// cycles have (dialect.md §4.3, cycles.md §22); block.rs lets a negative
/// F through when the block's function depends on the modal state.
fn check_negative_f(p: &Parsed, f: Func) -> Result<(), NcError> {
    let left_hand = matches!(
        f,
        Func::Motion(Motion::RigidThread | Motion::RigidThreadCycle)
            | Func::Drill(Drill::FaceTap | Drill::SideTap)
    );
    match p.get(b'F') {
        Some(v) if v < 0.0 && !left_hand => fail(
            p.range_alarm(b'F'),
            "F must not be negative (only G32.1, G92.1, G84 and G88 take a left-hand lead F < 0)",
        ),
        _ => Ok(()),
    }
}

/// A group-01 code that is not a thread clears the J/K words of G32/G34
/// and G92; any group-01 code or a one-shot code other than G04 ends the
/// G90/G92/G94 run (cycles.md §3, §4, §16).
fn forget(nc: &mut Nc, p: &Parsed) {
    let st = &mut nc.st.cycles;
    if p.gs().any(|g| matches!(g, G::Motion(m) if !m.is_thread())) {
        st.g92_pull = None;
        st.chain.runout = None;
    }
    let ends_run = p.gs().any(|g| match g {
        G::Motion(_) => true,
        G::OneShot(o) => !matches!(o, OneShot::Dwell | OneShot::ExactStop),
        _ => false,
    });
    if ends_run {
        st.run = None;
    }
}

/// Prints a G32/G34 block that still waits to know whether it ends its
/// chain: at the end of a run or before an alarm nothing follows, so it is
/// the chain's last block and gets its run-out (§16.4).
pub fn flush(nc: &mut Nc, sink: &mut dyn Sink) {
    thread::flush(nc, sink);
}

impl Nc {
    /// A call or a return (M98, M99, G65, G66's call) between two thread
    /// blocks: an NC block that is not a G32/G34 move, so it ends the
    /// chain (cycles.md §16.2). The block that waits for its run-out gets
    /// it when the next block runs.
    pub fn break_thread_chain(&mut self) {
        self.st.cycles.chain.open = false;
    }
}

/// A block whose group-01 code is one of this module's.
pub fn motion(
    nc: &mut Nc,
    code: Motion,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    match code {
        Motion::TurningCycle | Motion::FacingCycle => turning::run(nc, code, p, sink, out),
        Motion::ThreadCycle | Motion::RigidThreadCycle => thread_cycle::run(nc, code, p, sink, out),
        Motion::Thread | Motion::RigidThread | Motion::VariableThread => {
            thread::run(nc, code, p, sink, out)
        }
        Motion::ArcThreadCw | Motion::ArcThreadCcw => arc_thread::run(nc, code, p, sink, out),
        Motion::Tapping => tapping::g33(nc, p, sink, out),
        _ => fail(
            Alarm::NotSupportedYet,
            format!("{} is not implemented yet", gcode::name(code.code())),
        ),
    }
}

/// G74, G75, G76, G78 blocks (group 00).
pub fn one_shot(
    nc: &mut Nc,
    code: OneShot,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    match code {
        OneShot::PeckFace | OneShot::PeckGroove => groove::run(nc, code, p, sink, out),
        OneShot::MultiThread => multi::g76(nc, p, sink, out),
        OneShot::SpiralThread => multi::g78(nc, p, sink, out),
        _ => fail(
            Alarm::NotSupportedYet,
            format!("{} is not implemented yet", gcode::name(code.code())),
        ),
    }
}

/// A block while a drilling/tapping cycle (group 10) is in force, or the
/// block that selects it.
pub fn drill(
    nc: &mut Nc,
    code: Drill,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    drill::run(nc, code, p, sink, out)
}

#[cfg(test)]
mod tests {
    use super::testing::{run, run_err, Lathe};
    use alloc::string::String;
    use alloc::string::ToString;
    use alloc::vec::Vec;

    #[test]
    fn a_thread_lead_is_not_the_modal_feed() {
        // F0.2 feeds; the G92 F1.5 and G76 F2 are leads; the G01 after
        // them still feeds at 0.2 (no new FEED line).
        let l = run(&[
            "G99 M03 S500",
            "G01 X30 Z2 F0.2",
            "G92 X28 Z-10 F1.5",
            "G01 X32",
            "G76 X27 Z-10 P1000 Q500 F2",
            "G01 X34",
        ]);
        assert_eq!(l.iter().filter(|e| e.starts_with("FEED")).count(), 1);
        assert_eq!(l.last().map(String::as_str), Some("LINE X=34 Z=2"));
    }

    #[test]
    fn a_waiting_thread_block_is_printed_by_flush() {
        let mut m = Lathe::new();
        m.run("G00 X30 Z5");
        assert!(m.run("G32 Z-20 F2 J1 K3").is_empty());
        let mut events = Vec::new();
        super::flush(&mut m.nc, &mut events);
        let l: Vec<String> = events.iter().map(|e| e.to_string()).collect();
        assert_eq!(l, ["THREAD X=30 Z=-17 LEAD=2", "THREAD X=32 Z=-20 LEAD=2"]);
    }

    #[test]
    fn block_rules_for_f_and_h() {
        // A negative F on a block naming a non-left-hand function is
        // E1010 before any state is known; in a modal G84 block it is a
        // left-hand lead.
        assert_eq!(run_err(&["G01 X10 F-1"]), 1010);
        assert_eq!(run_err(&["G01 X10 F1", "X20 F-1"]), 1010);
        assert_eq!(run_err(&["G32 Z-10 F-1"]), 1010);
        assert_eq!(
            run_err(&["G00 X0 Z5", "M29 S100", "G84 Z-10 F1", "Z-12 F-1"]),
            0
        );
        // H (incremental hole angle) needs a C axis.
        assert_eq!(run_err(&["G83 Z-10 H30 F1"]), 2005);
        assert_eq!(run_err(&["G83 Z-10 F1", "Z-12 H30"]), 2005);
        // Drilling counts and G78 D take no decimal point.
        assert_eq!(run_err(&["G83 Z-10 F1 K2."]), 1009);
        assert_eq!(run_err(&["G83 Z-10 F1", "Z-12 K2."]), 1009);
        assert_eq!(run_err(&["G78 D2."]), 1009);
    }
}
