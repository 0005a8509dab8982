//! Program restart: a run that begins at a block in the middle of the
//! program, as a control's "program restart" does after a broken insert or
//! an interrupted shift (docs/manual.md, "Program restart").
//!
//! The program runs from its start in search mode: every statement and
//! block executes, so variables, modal state, offsets and the call stack
//! are what they would be at the target, but nothing it prints reaches
//! the sink. At the target the restored state is printed (the last origin,
//! tool, gear or speed, spindle direction, coolant code and feed), then
//! the approach: a rapid of X (and C) to the target's start point, then
//! one of Z. The run goes on from there as usual.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use core::str::FromStr;
use isa::Instr;
use nc::base::machine::RestartApproach;
use nc::base::point::Pt;
use nc::Event;
use nc::{Sink, RUNNING};

use crate::{Alarm, Status, Vm};

/// The block a restart begins at, in the main file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The block on this line (1-based).
    Line(u32),
    /// The block with this sequence number (the first, as a GOTO finds it).
    Seq(u32),
}

/// Where a restart begins: a block, and which time the run reaches it
/// (a block in a loop or a subprogram is reached more than once).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RestartAt {
    /// The block.
    pub target: Target,
    /// The pass, from 1.
    pub pass: u32,
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Target::Line(l) => write!(f, "line {l}"),
            Target::Seq(n) => write!(f, "N{n}"),
        }
    }
}

/// `120`, `N120`, with `@3` for the third pass.
impl FromStr for RestartAt {
    type Err = String;

    fn from_str(s: &str) -> Result<RestartAt, String> {
        let bad = || {
            format!("`{s}`: give a line (120) or a sequence number (N120), with @PASS for a later pass (N120@3)")
        };
        let (block, pass) = match s.split_once('@') {
            Some((b, p)) => (b, p.parse::<u32>().ok().filter(|&p| p > 0).ok_or_else(bad)?),
            None => (s, 1),
        };
        let target = match block.strip_prefix(['N', 'n']) {
            Some(n) => Target::Seq(n.parse().map_err(|_| bad())?),
            None => Target::Line(block.parse().ok().filter(|&l| l > 0).ok_or_else(bad)?),
        };
        Ok(RestartAt { target, pass })
    }
}

/// Why a restart cannot begin where asked.
#[derive(Debug, Clone, PartialEq)]
pub enum RestartError {
    /// The main file has no block there.
    NoBlock(Target),
    /// The line is a cycle's profile, which only its cycle reads.
    Profile(u32),
    /// The run ended before reaching the block that many times.
    NotReached {
        /// The block.
        target: Target,
        /// The pass asked for.
        pass: u32,
        /// The times it was reached.
        reached: u32,
    },
    /// At the block the kernel is in a state a restart cannot resume.
    Held {
        /// The block's line.
        line: u32,
        /// What holds it.
        why: &'static str,
    },
    /// The search stopped on a run-time alarm (its `ALARM` is in the sink).
    Alarm(Alarm),
}

impl fmt::Display for RestartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RestartError::NoBlock(t) => write!(f, "the main file has no block at {t}"),
            RestartError::Profile(l) => write!(
                f,
                "line {l} is in a cycle's profile, which the cycle reads: restart at the cycle's block"
            ),
            RestartError::NotReached {
                target,
                pass,
                reached,
            } => match reached {
                0 => write!(f, "the run never reaches {target}"),
                n => write!(
                    f,
                    "the run reaches {target} {n} time(s), so there is no pass {pass}"
                ),
            },
            RestartError::Held { line, why } => write!(
                f,
                "cannot restart at line {line}: {why}; restart at an earlier block, where it is not in force"
            ),
            RestartError::Alarm(a) => write!(f, "the search stopped on an alarm: {}", a.header()),
        }
    }
}

/// The first instruction of the target line's code: where the run
/// enters the line.
fn first_entry(vm: &Vm, line: u32) -> Option<u32> {
    (0..vm.module().code.len() as u32).find(|&pc| {
        let loc = vm.loc_at(pc);
        loc.file == 0 && loc.line == line
    })
}

/// The target's line and the pc that enters it. A cycle's profile
/// block is read by its cycle (before the cycle block runs) and
/// otherwise jumped over, so a restart there is refused.
fn entry(vm: &Vm, target: Target) -> Result<(u32, u32), RestartError> {
    let line = match target {
        Target::Line(l) => l,
        Target::Seq(n) => {
            let pc = vm
                .module()
                .pc_of_seq(0, n)
                .ok_or(RestartError::NoBlock(target))?;
            let loc = vm.loc_at(pc);
            if loc.file != 0 {
                return Err(RestartError::NoBlock(target));
            }
            loc.line
        }
    };
    let profile = vm.module().code.iter().enumerate().any(|(pc, i)| {
        let loc = vm.loc_at(pc as u32);
        matches!(i, Instr::Profile { .. }) && loc.file == 0 && loc.line == line
    });
    if profile {
        return Err(RestartError::Profile(line));
    }
    let pc = first_entry(vm, line).ok_or(RestartError::NoBlock(target))?;
    Ok((line, pc))
}

/// What the search keeps of the events it swallows: the last of each
/// kind that sets a state the run after the restart relies on.
#[derive(Default)]
struct Kept {
    origin: Option<Event>,
    tool: Option<Event>,
    gear: Option<Event>,
    speed: Option<Event>,
    spindle: Option<Event>,
    coolant: Option<Event>,
    feed: Option<Event>,
    /// Polar or cylindrical interpolation in force.
    plane: bool,
    /// The other M codes, each once, in the order of their last use.
    others: Vec<u32>,
}

/// A restart that has begun: what the search saw that it does not give
/// again.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Restarted {
    /// The M codes the blocks before the target gave, other than the
    /// spindle's and coolant's (a clamp, a C-axis mode, a tailstock: the
    /// machine's meaning), each once, in the order of their last use. A
    /// control shows them after its search, and the operator gives those
    /// the block needs by hand.
    pub m_codes: Vec<u32>,
}

/// The coolant codes a restart gives again (M07 mist, M08 flood, M09
/// off); the meaning of any other M code is the machine's.
const COOLANT: [u32; 3] = [7, 8, 9];

/// The sink of the search: keeps, and passes an alarm on.
struct Search<'a> {
    out: &'a mut dyn Sink,
    kept: Kept,
}

impl Sink for Search<'_> {
    fn emit(&mut self, event: Event) {
        let k = &mut self.kept;
        let slot = match &event {
            Event::Origin { .. } => &mut k.origin,
            Event::Tool { .. } => &mut k.tool,
            Event::Gear { .. } => &mut k.gear,
            Event::Speed { .. } => &mut k.speed,
            Event::Spindle(_) => &mut k.spindle,
            Event::M(code) if COOLANT.contains(code) => &mut k.coolant,
            Event::M(code) => {
                k.others.retain(|c| c != code);
                k.others.push(*code);
                return;
            }
            Event::Feed { .. } => &mut k.feed,
            Event::PolarOn | Event::Cylinder(Some(_)) => {
                k.plane = true;
                return;
            }
            Event::PolarOff { .. } | Event::Cylinder(None) => {
                k.plane = false;
                return;
            }
            Event::Alarm { .. } => {
                self.out.emit(event);
                return;
            }
            _ => return,
        };
        *slot = Some(event);
    }
}

/// Runs `vm` (fresh, before its first instruction) in search mode up to
/// `at`, then prints the restored state and the approach into `sink`:
/// the run goes on from the target with [`Vm::step`]. The machine stands
/// where the kernel's programmed point is at the start. A tier is set
/// aside for the search, whose pc is checked at every instruction.
pub fn search(vm: &mut Vm, at: RestartAt, sink: &mut dyn Sink) -> Result<Restarted, RestartError> {
    let (line, entry) = entry(vm, at.target)?;
    let standing = (vm.nc.position().add(vm.nc.origin()), vm.nc.c());
    let tier = vm.take_tier();
    let mut search = Search {
        out: sink,
        kept: Kept::default(),
    };
    let found = reach(vm, entry, at, &mut search);
    if let Some(t) = tier {
        vm.set_tier(t);
    }
    found?;
    let why = held(vm, &search.kept).map(|why| RestartError::Held { line, why });
    if let Some(e) = why {
        return Err(e);
    }
    let Search { out, mut kept } = search;
    let m_codes = core::mem::take(&mut kept.others);
    out.origin(entry);
    restore(kept, out);
    approach(vm, standing, out);
    out.origin(RUNNING);
    Ok(Restarted { m_codes })
}

/// Steps the VM up to the `at.pass`-th arrival at `entry`.
fn reach(vm: &mut Vm, entry: u32, at: RestartAt, sink: &mut Search) -> Result<(), RestartError> {
    let mut reached = 0;
    // (After `Sync` the VM stands before the same instruction, which has
    // not run: not a second arrival.)
    let mut arrived = true;
    loop {
        if arrived && vm.pc() == entry {
            reached += 1;
            if reached == at.pass {
                return Ok(());
            }
        }
        let status = vm.step(1, sink);
        arrived = status != Status::Sync;
        match status {
            Status::Event | Status::OutOfBudget | Status::Sync => {}
            Status::Done => {
                let (target, pass) = (at.target, at.pass);
                return Err(RestartError::NotReached {
                    target,
                    pass,
                    reached,
                });
            }
            Status::Alarm(a) => return Err(RestartError::Alarm(a)),
        }
    }
}

/// What at the target keeps the run from resuming there: moves the
/// kernel holds back, or a plane mode.
fn held(vm: &Vm, kept: &Kept) -> Option<&'static str> {
    if vm.nc.thread_waiting() || vm.nc.thread_chain_open() {
        // (A thread block continues the chain of the one before it
        // without a new spindle sync: started on its own it would cut
        // out of phase.)
        Some("a thread chain is open (the block before is a G32/G34 move)")
    } else if vm.nc.contour_held() {
        Some("tool-nose compensation is in force, or a move waits for this block (a corner word, an angle)")
    } else if kept.plane {
        Some("polar or cylindrical interpolation is in force")
    } else {
        None
    }
}

/// The state the search kept, in the order a program sets it.
fn restore(kept: Kept, sink: &mut dyn Sink) {
    let Kept {
        origin,
        tool,
        gear,
        speed,
        spindle,
        coolant,
        feed,
        plane: _,
        others: _,
    } = kept;
    for e in [origin, tool, gear, speed, spindle, coolant, feed]
        .into_iter()
        .flatten()
    {
        sink.emit(e);
    }
}

/// From `standing` (machine coordinates, and C) to the kernel's
/// programmed point: X and C first, then Z, or Z first, as the machine's
/// `run.restart_approach` says; each leg left out when it does not move.
fn approach(vm: &Vm, (standing, standing_c): (Pt, f64), sink: &mut dyn Sink) {
    let to = vm.nc.position();
    let from = standing.sub(vm.nc.origin());
    let turns = vm.nc.machine.axes.c.enabled && (vm.nc.c() - standing_c).abs() > 1e-9;
    let c = turns.then(|| vm.nc.c());
    let x_moves = (to.r - from.r).abs() > 1e-9 || c.is_some();
    let z_moves = (to.z - from.z).abs() > 1e-9;
    // The corner between the two legs.
    let corner = match vm.nc.machine.run.restart_approach {
        RestartApproach::XThenZ => Pt::new(to.r, from.z),
        RestartApproach::ZThenX => Pt::new(from.r, to.z),
    };
    let first_is_x = vm.nc.machine.run.restart_approach == RestartApproach::XThenZ;
    let (first, second) = match first_is_x {
        true => (x_moves.then_some(c), z_moves.then_some(None)),
        false => (z_moves.then_some(None), x_moves.then_some(c)),
    };
    if let Some(c) = first {
        sink.emit(Event::Rapid {
            x: corner.x(),
            z: corner.z,
            c,
        });
    }
    if let Some(c) = second {
        sink.emit(Event::Rapid {
            x: to.x(),
            z: to.z,
            c,
        });
    }
}
