//! What one loop's compiled code covers: the instructions from the loop's
//! head to its back edge, which of them run natively, where the code may
//! be entered and which registers and variables it keeps in machine
//! registers.
//!
//! Every instruction the code does not handle is an *exit*: the code
//! stores its state and returns that instruction's pc, unexecuted, to the
//! interpreter, which runs it and may come back in at the next pc (an
//! entry). An NC block the code runs by a call into the kernel's executor;
//! it may leave after it, so the pc after a block is an entry too. An
//! instruction that would fault, or a charge the block budget cannot take,
//! exits the same way, so that the interpreter raises the alarm with its
//! own message and line.

use std::collections::{BTreeMap, BTreeSet};

use isa::{Instr, Module};

/// Loops longer than this stay interpreted (the code grows with them).
const MAX_LEN: u32 = 4096;

/// Where a variable number lives, as far as compiled code is concerned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// #1–#33 of the current level (index 0–32).
    Local(usize),
    /// #100–#199 (index 0–99).
    Common(usize),
    /// #500–#999 (index 0–499): read in place, written by the interpreter
    /// (which hands the change to the storage).
    Persistent(usize),
    /// #0, always vacant.
    Null,
    /// Anything else (system variables): the interpreter's.
    Other,
}

impl Place {
    pub fn of(n: u32) -> Place {
        match n {
            0 => Place::Null,
            1..=33 => Place::Local(n as usize - 1),
            100..=199 => Place::Common(n as usize - 100),
            500..=999 => Place::Persistent(n as usize - 500),
            _ => Place::Other,
        }
    }

    /// Kept in a machine register while the code runs (locals, commons).
    fn is_cached(self) -> bool {
        matches!(self, Place::Local(_) | Place::Common(_))
    }
}

/// Whether compiled code runs `instr` itself (else it is an exit).
pub fn is_native(instr: &Instr) -> bool {
    use Instr::*;
    match *instr {
        LoadK { .. } | LoadNull { .. } | Mov { .. } | Neg { .. } => true,
        Add { .. } | Sub { .. } | Mul { .. } | Div { .. } | Mod { .. } => true,
        BitAnd { .. } | BitOr { .. } | BitXor { .. } | Func { .. } | Atan2 { .. } => true,
        AddK { .. } | SubK { .. } | MulK { .. } | DivK { .. } => true,
        Cmp { .. } | CmpK { .. } | Jump { .. } | JumpIfNot { .. } => true,
        Goto { .. } | Charge => true,
        Word { .. } | WordK { .. } => true,
        LoadVar { var, .. } => Place::of(var) != Place::Other,
        StoreVar { var, .. } => Place::of(var).is_cached(),
        _ => false,
    }
}

/// Whether `instr` is an NC block, which the code runs by a direct call
/// into the kernel's executor (`vm::Kernel`), and may leave after (`vm::Ran`).
pub fn is_block(instr: &Instr) -> bool {
    match *instr {
        Instr::Exec { flags } => flags & vm::PROFILE == 0,
        Instr::ExecMove | Instr::Move { .. } | Instr::Block { .. } => true,
        _ => false,
    }
}

/// Whether `instr` writes nothing but its destination register (the first
/// register operand): a run of such instructions can be run again from
/// its start, if it reads no register it did not write itself.
pub fn is_pure(instr: &Instr) -> bool {
    use Instr::*;
    match *instr {
        Jump { .. } | JumpIfNot { .. } | Word { .. } | WordK { .. } | StoreVar { .. } => false,
        Goto { .. } | Charge => false,
        _ => is_native(instr),
    }
}

/// A loop: the instructions `head..=tail`, `tail` being its back edge.
#[derive(Debug, Clone)]
pub struct Region {
    pub head: u32,
    pub tail: u32,
    /// The pcs that start a basic block of the code.
    pub leaders: BTreeSet<u32>,
    /// The pcs at which the code may be entered: the head, and the pc after
    /// each exit instruction.
    pub entries: BTreeSet<u32>,
    /// The registers the code uses.
    pub regs: BTreeSet<u8>,
    /// The locals and commons it uses (variable numbers).
    pub vars: BTreeSet<u32>,
    /// For each instruction of a *restartable* run of pure ones (no leader
    /// inside, every register it reads written earlier in the run), the
    /// run's first pc: a fault in the run may be found at its end and
    /// leave there, to run again from the start in the interpreter (the
    /// registers it wrote are dead there, and nothing else changed).
    pub restart: BTreeMap<u32, u32>,
}

impl Region {
    /// The loop from `head` to the backward jump at `tail`, if it is one the
    /// tier compiles: in the code, not too long, and with something to run
    /// natively at its head.
    pub fn find(module: &Module, head: u32, tail: u32) -> Option<Region> {
        if head > tail || tail - head >= MAX_LEN {
            return None;
        }
        let code = module.code.get(head as usize..=tail as usize)?;
        if !code.first().is_some_and(is_native) {
            return None;
        }
        let mut region = Region {
            head,
            tail,
            leaders: BTreeSet::from([head]),
            entries: BTreeSet::from([head]),
            regs: BTreeSet::new(),
            vars: BTreeSet::new(),
            restart: BTreeMap::new(),
        };
        for (pc, instr) in (head..).zip(code) {
            region.note(pc, instr);
        }
        region.find_restarts(code);
        Some(region)
    }

    /// Whether `pc` lies in the loop.
    pub fn contains(&self, pc: u32) -> bool {
        (self.head..=self.tail).contains(&pc)
    }

    /// Whether the comparison at `pc` into `r` is read by nothing but the
    /// `jumpifnot` right after it (which only it reaches, not a leader):
    /// `r` is written again before it is read both where that falls
    /// through and at its target in the loop. (A target outside the loop
    /// is an exit at the `jumpifnot`, which the interpreter runs.)
    pub fn branches_on(&self, code: &[Instr], pc: u32, r: u8) -> bool {
        let branch = pc + 1;
        let Some(&Instr::JumpIfNot { cond, target }) = code.get(branch as usize) else {
            return false;
        };
        cond == r
            && !self.leaders.contains(&branch)
            && dead_at(code, branch + 1, r)
            && (!self.contains(target) || dead_at(code, target, r))
    }

    /// Instructions in the loop (what one round costs of the step's fuel).
    pub fn len(&self) -> u64 {
        u64::from(self.tail - self.head) + 1
    }

    /// Fills `restart` (the runs are cut at leaders and impure
    /// instructions).
    fn find_restarts(&mut self, code: &[Instr]) {
        let mut run = Run::default();
        for (pc, instr) in (self.head..).zip(code) {
            if self.leaders.contains(&pc) || !is_pure(instr) {
                run.close(&mut self.restart);
            }
            if is_pure(instr) {
                run.add(pc, instr);
            }
        }
        run.close(&mut self.restart);
    }

    fn note(&mut self, pc: u32, instr: &Instr) {
        let next = pc + 1;
        match *instr {
            Instr::Jump { target } | Instr::Goto { target } | Instr::JumpIfNot { target, .. } => {
                if self.contains(target) {
                    self.leaders.insert(target);
                }
                self.leaders.insert(next);
            }
            _ if !is_native(instr) => {
                self.leaders.insert(next);
                if next <= self.tail {
                    self.entries.insert(next);
                }
            }
            _ => {}
        }
        if !is_native(instr) {
            return;
        }
        instr.visit_operands(|op| match op {
            isa::Operand::Reg(r) => {
                self.regs.insert(r);
            }
            isa::Operand::Var(n) if Place::of(n).is_cached() => {
                self.vars.insert(n);
            }
            _ => {}
        });
    }
}

/// The register operands of a pure instruction (`is_pure`): the first is
/// its destination, the rest are read.
fn registers(instr: &Instr) -> Vec<u8> {
    let mut regs = Vec::new();
    instr.visit_operands(|op| {
        if let isa::Operand::Reg(r) = op {
            regs.push(r);
        }
    });
    regs
}

/// Whether register `r` is dead at `pc`: on the straight line from there,
/// a pure instruction writes it before anything reads it. Anything else
/// (a jump, a store, a block) ends the look as a read would. An exit on
/// that line changes nothing: the interpreter runs the same instructions
/// from there.
pub fn dead_at(code: &[Instr], pc: u32, r: u8) -> bool {
    for instr in code.iter().skip(pc as usize) {
        // (A charge touches no register; code that leaves there for the
        // budget's alarm reads none again.)
        if *instr == Instr::Charge {
            continue;
        }
        if !is_pure(instr) {
            return false;
        }
        let regs = registers(instr);
        let Some((&dst, reads)) = regs.split_first() else {
            continue;
        };
        if reads.contains(&r) {
            return false;
        }
        if dst == r {
            return true;
        }
    }
    false
}

/// A run of pure instructions being collected.
#[derive(Default)]
struct Run {
    members: Vec<u32>,
    written: BTreeSet<u8>,
    restartable: bool,
}

impl Run {
    fn add(&mut self, pc: u32, instr: &Instr) {
        if self.members.is_empty() {
            self.restartable = true;
            self.written.clear();
        }
        self.members.push(pc);
        let regs = registers(instr);
        if let Some((&dst, reads)) = regs.split_first() {
            if reads.iter().any(|r| !self.written.contains(r)) {
                self.restartable = false;
            }
            self.written.insert(dst);
        }
    }

    fn close(&mut self, restart: &mut BTreeMap<u32, u32>) {
        if let Some(&start) = self.members.first().filter(|_| self.restartable) {
            restart.extend(self.members.iter().map(|&pc| (pc, start)));
        }
        self.members.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn module(code: Vec<Instr>) -> Module {
        Module {
            code,
            consts: vec![0.0, 1.0, 10.0],
            num_regs: 2,
            ..Module::default()
        }
    }

    #[test]
    fn a_loop_with_a_block_is_entered_after_the_block() {
        // 0: loadvar r0,#1; 1: addk; 2: storevar; 3: wordk; 4: execmove;
        // 5: cmpk; 6: jumpifnot 8; 7: jump 0
        let m = module(vec![
            Instr::LoadVar { dst: 0, var: 1 },
            Instr::AddK { dst: 0, a: 0, k: 1 },
            Instr::StoreVar { var: 1, src: 0 },
            Instr::WordK {
                addr: 6,
                k: 1,
                flags: 0,
            },
            Instr::ExecMove,
            Instr::CmpK {
                dst: 1,
                a: 0,
                k: 2,
                op: 3,
            },
            Instr::JumpIfNot { cond: 1, target: 8 },
            Instr::Jump { target: 0 },
        ]);
        let r = Region::find(&m, 0, 7).expect("a region");
        assert_eq!(r.entries, BTreeSet::from([0, 5]));
        assert_eq!(r.leaders, BTreeSet::from([0, 5, 7, 8]));
        assert_eq!(r.regs, BTreeSet::from([0, 1]));
        assert_eq!(r.vars, BTreeSet::from([1]));
        assert_eq!(r.len(), 8);
        // 0–1 read only what 0 wrote; 5 reads r0, written before the
        // block (at 1), so its run cannot start over.
        assert_eq!(r.restart, BTreeMap::from([(0, 0), (1, 0)]));
    }

    /// A WHILE's head: the comparison's register is read by its
    /// `jumpifnot` alone where both ways write it again before reading
    /// it; not where one way reads it, or stores, or the branch is a
    /// leader.
    #[test]
    fn a_comparison_read_only_by_its_branch() {
        let head = |after: Instr| {
            module(vec![
                Instr::LoadVar { dst: 0, var: 1 },
                Instr::CmpK {
                    dst: 0,
                    a: 0,
                    k: 2,
                    op: 3,
                },
                Instr::JumpIfNot { cond: 0, target: 6 },
                after,
                Instr::StoreVar { var: 1, src: 0 },
                Instr::Jump { target: 0 },
                Instr::LoadK { dst: 0, k: 1 },
            ])
        };
        // 3 writes r0 (a load), and the target 6, outside, writes it.
        let m = head(Instr::LoadVar { dst: 0, var: 1 });
        let r = Region::find(&m, 0, 5).expect("a region");
        assert!(r.branches_on(&m.code, 1, 0));
        assert!(!r.branches_on(&m.code, 1, 1), "another register");
        assert!(!r.branches_on(&m.code, 0, 0), "not a comparison's pc");
        // 3 reads r0 (r1 = r0 + 1).
        let m = head(Instr::AddK { dst: 1, a: 0, k: 1 });
        let r = Region::find(&m, 0, 5).expect("a region");
        assert!(!r.branches_on(&m.code, 1, 0));
        // 3 is a store: the look ends there.
        let m = head(Instr::StoreVar { var: 2, src: 1 });
        let r = Region::find(&m, 0, 5).expect("a region");
        assert!(!r.branches_on(&m.code, 1, 0));
        // A jump to the branch makes it a leader.
        let mut m = head(Instr::LoadVar { dst: 0, var: 1 });
        m.code[5] = Instr::Jump { target: 2 };
        let r = Region::find(&m, 2, 5).expect("a region");
        assert!(r.leaders.contains(&2));
        assert!(!r.branches_on(&m.code, 1, 0));
    }

    #[test]
    fn system_variables_and_calls_are_exits() {
        assert!(!is_native(&Instr::LoadVar { dst: 0, var: 5021 }));
        assert!(!is_native(&Instr::StoreVar { var: 500, src: 0 }));
        assert!(!is_native(&Instr::StoreVar { var: 0, src: 0 }));
        assert!(is_native(&Instr::LoadVar { dst: 0, var: 500 }));
        assert!(is_native(&Instr::LoadVar { dst: 0, var: 0 }));
        assert!(!is_native(&Instr::Ret));
        assert!(!is_native(&Instr::GotoSeq { seq: 0 }));
    }

    #[test]
    fn a_loop_outside_the_code_or_headed_by_an_exit_is_not_compiled() {
        let m = module(vec![Instr::ExecMove, Instr::Jump { target: 0 }]);
        assert!(Region::find(&m, 0, 1).is_none());
        assert!(Region::find(&m, 0, 5).is_none());
        assert!(Region::find(&m, 1, 0).is_none());
    }
}
