//! A small assembler for hand-built modules, and a sink that records the
//! canon, so the VM can be tested without the compiler.
//!
//! Events are kept as their canon text (canon.md): that text is the
//! contract, and it keeps these tests independent of how the kernel lays
//! out its event type.

#![allow(dead_code)] // each test binary uses a different subset

use isa::{addr, Instr, Module, Program, SourceFileInfo, SourceLoc};
use vm::{Event, Sink, Status, Vm};

/// The source file name every hand-built module claims.
pub const FILE: &str = "test.nc";

/// Builds a module instruction by instruction. Programs are written one
/// after the other; the first is the main program `O0001`.
pub struct Asm {
    m: Module,
    /// Source line given to the next instructions.
    line: u32,
    /// Number, entry and sequence table of the program being written.
    number: u32,
    entry: u32,
    seqs: Vec<(u32, u32)>,
}

impl Default for Asm {
    fn default() -> Self {
        Asm::new()
    }
}

impl Asm {
    pub fn new() -> Asm {
        Asm {
            m: Module {
                files: vec![SourceFileInfo {
                    name: FILE.to_string(),
                    hash: 0,
                }],
                ..Module::default()
            },
            line: 1,
            number: 1,
            entry: 0,
            seqs: Vec::new(),
        }
    }

    /// The source line of the instructions emitted from now on.
    pub fn line(&mut self, line: u32) -> &mut Self {
        self.line = line;
        self
    }

    /// The pc the next instruction gets.
    pub fn here(&self) -> u32 {
        self.m.code.len() as u32
    }

    /// Appends an instruction; returns its pc.
    pub fn op(&mut self, i: Instr) -> u32 {
        let pc = self.here();
        self.m.code.push(i);
        self.m.lines.push(SourceLoc {
            file: 0,
            line: self.line,
            col: 1,
        });
        pc
    }

    /// Replaces the instruction at `pc` (to point a jump forward once its
    /// target is known).
    pub fn set(&mut self, pc: u32, i: Instr) {
        self.m.code[pc as usize] = i;
    }

    /// A new constant-pool entry.
    pub fn k(&mut self, v: f64) -> u32 {
        self.m.consts.push(v);
        self.m.consts.len() as u32 - 1
    }

    /// A new string-table entry.
    pub fn s(&mut self, text: &str) -> u32 {
        self.m.strings.push(text.to_string());
        self.m.strings.len() as u32 - 1
    }

    /// `dst = v`.
    pub fn load(&mut self, dst: u8, v: f64) -> u32 {
        let k = self.k(v);
        self.op(Instr::LoadK { dst, k })
    }

    /// Marks the next instruction as block `N<n>` of the current program.
    pub fn seq(&mut self, n: u32) {
        let pc = self.here();
        self.seqs.push((n, pc));
    }

    /// A literal word (written with a decimal point: no scaling).
    pub fn word(&mut self, letter: char, v: f64) {
        let k = self.k(v);
        let addr = addr::from_letter(letter).expect("a letter");
        self.op(Instr::WordK { addr, k, flags: 0 });
    }

    /// A word whose value is register `src`.
    pub fn word_reg(&mut self, letter: char, src: u8) {
        let addr = addr::from_letter(letter).expect("a letter");
        self.op(Instr::Word { addr, src });
    }

    /// A typed block of literal words `(letter, value, flags)`, in order.
    pub fn block(&mut self, words: &[(char, f64, u8)]) -> u32 {
        let words: Vec<isa::BlockWord> = words
            .iter()
            .map(|&(letter, value, flags)| isa::BlockWord {
                addr: addr::from_letter(letter).expect("a letter"),
                value,
                flags,
            })
            .collect();
        let rec = self.m.push_block(&words).expect("the words fit a record");
        self.op(Instr::Block { rec })
    }

    /// The block built so far is executed.
    pub fn exec(&mut self) -> u32 {
        self.op(Instr::Exec { flags: 0 })
    }

    /// `G00 X<rx> Z<rz>`: a block whose canon line shows two registers
    /// (`RAPID X=… Z=…`); a vacant register leaves its word out (§7.5).
    pub fn show(&mut self, rx: u8, rz: u8) -> u32 {
        self.word('G', 0.0);
        self.word_reg('X', rx);
        self.word_reg('Z', rz);
        self.exec()
    }

    /// Ends the current program and starts `O<number>` at the next pc;
    /// returns the new program's index in the program table.
    pub fn program(&mut self, number: u32) -> u32 {
        self.close();
        self.number = number;
        self.entry = self.here();
        self.m.programs.len() as u32
    }

    fn close(&mut self) {
        let mut seqs = std::mem::take(&mut self.seqs);
        seqs.sort_unstable();
        self.m.programs.push(Program {
            number: self.number,
            entry: self.entry,
            end: self.here(),
            seqs,
            ..Program::default()
        });
    }

    /// The finished module, written and loaded again through the `.gbc`
    /// format: what the tests run is what a file would hold. Registers
    /// are counted from the highest one used.
    pub fn build(mut self) -> Module {
        self.close();
        let mut top = 0u16;
        for i in &self.m.code {
            i.visit_operands(|op| {
                if let isa::Operand::Reg(r) = op {
                    top = top.max(u16::from(r) + 1);
                }
            });
        }
        self.m.num_regs = top;
        let bytes = self.m.to_bytes();
        Module::from_bytes(&bytes).expect("the hand-built module verifies")
    }
}

/// Records each event as its canon line.
#[derive(Default)]
pub struct Canon(pub Vec<String>);

impl Sink for Canon {
    fn emit(&mut self, e: Event) {
        self.0.push(e.to_string());
    }
}

/// A VM for `m` on the reference machine (machine.md).
pub fn vm(m: Module) -> Vm {
    Vm::new(m, nc::Machine::reference())
}

/// Runs `m` to its end on the reference machine.
pub fn run(m: Module) -> (Status, Vec<String>, Vm) {
    let mut vm = vm(m);
    let mut canon = Canon::default();
    let status = vm.run(&mut canon);
    (status, canon.0, vm)
}

/// The alarm a run ended with (panics, failing the test, if it ended
/// otherwise).
pub fn alarm_of(status: Status) -> vm::Alarm {
    match status {
        Status::Alarm(a) => a,
        other => panic!("expected an alarm, got {other:?}"),
    }
}

/// The canon of `m` when it must end normally.
pub fn canon_of(m: Module) -> Vec<String> {
    let (status, canon, _) = run(m);
    assert_eq!(status, Status::Done, "canon so far: {canon:?}");
    canon
}
