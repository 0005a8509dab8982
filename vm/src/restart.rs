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
//!
//! Under nose-radius compensation the start point is the compensated
//! tool's, which depends on the target's own move: the element of the
//! block before waits for it. The search then reads on past the target
//! until that element is printed (`catch_up`), and what the run printed
//! after it follows the approach.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use core::str::FromStr;
use isa::Instr;
use nc::base::machine::{RestartApproach, Xz};
use nc::base::point::Pt;
use nc::Event;
use nc::{ActiveCodes, Placed, Sink, RUNNING};

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
    /// Where the last move printed ends (none after a reference return,
    /// an origin or a plane of polar or cylindrical interpolation, whose
    /// frame it is not in).
    end: Option<Pt>,
    /// The other M codes, each once, in the order of their last use.
    others: Vec<u32>,
}

/// A restart that has begun: where its approach goes, and what the
/// search saw that it does not give again.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Restarted {
    /// The M codes the blocks before the target gave, other than the
    /// spindle's and coolant's (a clamp, a C-axis mode, a tailstock: the
    /// machine's meaning), each once, in the order of their last use. A
    /// control shows them after its search, and the operator gives those
    /// the block needs by hand.
    pub m_codes: Vec<u32>,
    /// Where the approach ends, work coordinates (X on the diameter): the
    /// block's start point, under nose-radius compensation the
    /// compensated tool's. A control's restart page shows it before the
    /// cycle start that moves there.
    pub destination: Xz,
    /// The codes in force at the block, before it runs: each modal
    /// group's G code, F, S and the T word the blocks before left. A
    /// control's restart page shows them with the destination, and the
    /// operator's screen until the approach runs.
    pub codes: ActiveCodes,
}

/// The coolant codes a restart gives again (M07 mist, M08 flood, M09
/// off); the meaning of any other M code is the machine's.
const COOLANT: [u32; 3] = [7, 8, 9];

/// The tag the restart gives the elements that wait at the target for
/// the blocks after it (a compensated element, a corner word, an angle
/// pair's first block): no pc has it, so the search sees where their
/// printing ends even when the target is their own block on a later pass.
const WAITING: u32 = RUNNING - 1;

/// The sink of the search: keeps, and passes an alarm on.
struct Search<'a> {
    out: &'a mut dyn Sink,
    kept: Kept,
    /// Past the target, while the elements of earlier blocks wait.
    catch: Option<CatchUp>,
}

/// The search past the target (`catch_up`): what the waiting elements of
/// the blocks before print is kept as the search keeps; what follows is
/// the run after the restart, given after the approach.
#[derive(Default)]
struct CatchUp {
    /// The sink is told [`WAITING`]: the events are the earlier blocks'.
    earlier: bool,
    /// The earlier blocks' elements are printed.
    done: bool,
    /// The run from there on.
    after: Placed,
}

impl Sink for Search<'_> {
    fn emit(&mut self, event: Event) {
        match &mut self.catch {
            _ if matches!(event, Event::Alarm { .. }) => self.out.emit(event),
            Some(c) if !c.earlier => c.after.emit(event),
            _ => self.kept.keep(event),
        }
    }

    fn origin(&mut self, block: u32) {
        // (Before the target the search places nothing.)
        let Some(c) = &mut self.catch else {
            return;
        };
        if block == WAITING {
            c.earlier = true;
            return;
        }
        c.done |= c.earlier;
        c.earlier = false;
        c.after.origin(block);
    }
}

impl Kept {
    /// Keeps `event` if it sets a state or ends a move.
    fn keep(&mut self, event: Event) {
        let slot = match &event {
            Event::Origin { .. } => {
                // (The last end is in the old frame.)
                self.end = None;
                &mut self.origin
            }
            Event::Tool { .. } => &mut self.tool,
            Event::Gear { .. } => &mut self.gear,
            Event::Speed { .. } => &mut self.speed,
            Event::Spindle(_) => &mut self.spindle,
            Event::M(code) if COOLANT.contains(code) => &mut self.coolant,
            Event::M(code) => {
                self.others.retain(|c| c != code);
                self.others.push(*code);
                return;
            }
            Event::Feed { .. } => &mut self.feed,
            // (A plane's moves are not in X and Z: where the tool stands
            // after one is the kernel's point.)
            Event::PolarOn | Event::Cylinder(Some(_)) => {
                self.plane = true;
                self.end = None;
                return;
            }
            Event::PolarOff { .. } | Event::Cylinder(None) => {
                self.plane = false;
                self.end = None;
                return;
            }
            Event::Home { .. } => {
                self.end = None;
                return;
            }
            _ => {
                self.end = event.end().map(|(x, z)| Pt::xz(x, z)).or(self.end);
                return;
            }
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
        catch: None,
    };
    let found = reach(vm, entry, at, &mut search).and_then(|()| resume(vm, line, &mut search));
    if let Some(t) = tier {
        vm.set_tier(t);
    }
    let resume = found?;
    let Search {
        out,
        mut kept,
        catch,
    } = search;
    let restarted = Restarted {
        m_codes: core::mem::take(&mut kept.others),
        destination: Xz {
            x: resume.to.x(),
            z: resume.to.z,
        },
        codes: resume.codes,
    };
    out.origin(entry);
    restore(kept, out);
    approach(vm, standing, resume, out);
    out.origin(RUNNING);
    if let Some(c) = catch {
        replay(c.after, out);
    }
    Ok(restarted)
}

/// Where the run resumes, with the work zero and C the blocks before the
/// target left.
struct Resume {
    /// The approach's end: where the tool stands when the target's
    /// output begins (work coordinates).
    to: Pt,
    origin: Pt,
    c: f64,
    /// The codes in force at the target, before it is read.
    codes: ActiveCodes,
}

/// At the target: refused if the run cannot resume there; otherwise
/// where it does: where the whole run's tool stands when the target's
/// output begins, the end of the last move printed before it. Under
/// nose-radius compensation that is the compensated tool's point, not
/// the programmed one; when an element of the blocks before waits for
/// the target's move (or a corner word or an angle does), the search
/// reads on until it is printed. When no move was printed since the
/// start, a reference return or a new origin, the programmed point.
fn resume(vm: &mut Vm, line: u32, search: &mut Search) -> Result<Resume, RestartError> {
    if let Some(why) = held(vm, &search.kept) {
        return Err(RestartError::Held { line, why });
    }
    let (programmed, origin, c) = (vm.nc.position(), vm.nc.origin(), vm.nc.c());
    let codes = vm.nc.active_codes();
    if let Some(block) = vm.nc.waiting_block() {
        catch_up(vm, search, block)?;
    }
    let to = search.kept.end.unwrap_or(programmed);
    Ok(Resume {
        to,
        origin,
        c,
        codes,
    })
}

/// Steps the VM past the target until the elements waiting there
/// (`block`'s last) are printed, or the run ends. An alarm about one of
/// them names `block`, as the whole run's would.
fn catch_up(vm: &mut Vm, search: &mut Search, block: u32) -> Result<(), RestartError> {
    vm.nc.retag_waiting(WAITING);
    search.catch = Some(CatchUp::default());
    loop {
        match vm.step(1, search) {
            Status::Alarm(a) => return Err(RestartError::Alarm(named(vm, a, block))),
            Status::Done => return Ok(()),
            _ if search.catch.as_ref().is_some_and(|c| c.done) => return Ok(()),
            _ => {}
        }
    }
}

/// An alarm about an element tagged [`WAITING`] (which names no line)
/// names `block` instead.
fn named(vm: &Vm, mut a: Alarm, block: u32) -> Alarm {
    if a.line == 0 {
        let loc = vm.loc_at(block);
        a.line = loc.line;
        a.col = loc.col;
        a.file = vm
            .module()
            .files
            .get(loc.file as usize)
            .map_or_else(String::new, |f| f.name.clone());
    }
    a
}

/// Gives what the run printed past the target, each event under its
/// block's tag, then the running block's.
fn replay(after: Placed, out: &mut dyn Sink) {
    let mut origins = after.origins.into_iter().peekable();
    for (i, e) in after.events.into_iter().enumerate() {
        while let Some((_, tag)) = origins.next_if(|&(at, _)| at <= i) {
            out.origin(tag);
        }
        out.emit(e);
    }
    out.origin(RUNNING);
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

/// What at the target keeps the run from resuming there: a thread chain
/// open, or a plane mode.
fn held(vm: &Vm, kept: &Kept) -> Option<&'static str> {
    if vm.nc.thread_waiting() || vm.nc.thread_chain_open() {
        // (A thread block continues the chain of the one before it
        // without a new spindle sync: started on its own it would cut
        // out of phase.)
        Some("a thread chain is open (the block before is a G32/G34 move)")
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
        end: _,
    } = kept;
    for e in [origin, tool, gear, speed, spindle, coolant, feed]
        .into_iter()
        .flatten()
    {
        sink.emit(e);
    }
}

/// From `standing` (machine coordinates, and C) to where the run
/// resumes: X and C first, then Z, or Z first, as the machine's
/// `run.restart_approach` says; each leg left out when it does not move.
fn approach(vm: &Vm, (standing, standing_c): (Pt, f64), resume: Resume, sink: &mut dyn Sink) {
    let Resume { to, origin, c, .. } = resume;
    let from = standing.sub(origin);
    let turns = vm.nc.machine.axes.c.enabled && (c - standing_c).abs() > 1e-9;
    let c = turns.then_some(c);
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
