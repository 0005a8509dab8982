//! What the tests of the compiler's passes share: the suite programs, a
//! generator of random macro programs, and ways to run modules in the VM.
#![allow(dead_code)]

use isa::Instr;
use nc::event::Event;
use nc::Machine;
use std::path::Path;
use vm::{Status, Vm};

/// (code, line, message) of every diagnostic of `src`.
pub fn messages(src: &str, opts: &compiler::Options) -> Vec<(&'static str, usize, String)> {
    let c = compiler::compile("p.nc", src.as_bytes(), opts);
    c.diags
        .iter()
        .map(|(f, d)| {
            let line = c.files[*f].line_col(d.span.start).0;
            (d.code, line, d.message.clone())
        })
        .collect()
}

/// (code, line) of every diagnostic of `src`.
pub fn codes(src: &str, opts: &compiler::Options) -> Vec<(&'static str, usize)> {
    messages(src, opts)
        .into_iter()
        .map(|(code, line, _)| (code, line))
        .collect()
}

/// Every program of the conformance suite, the public corpus and the
/// examples, with its name and the machine it is for.
pub fn suite() -> Vec<(String, Vec<u8>, Machine)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        root.join("../../shared/conformance"),
        root.join("../../shared/corpus/public"),
        root.join("../examples"),
    ];
    let mut programs = Vec::new();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for path in entries.flatten().map(|e| e.path()) {
            // (The corpus names programs as their authors did, some
            // without an extension.)
            let ext = path.extension().and_then(|e| e.to_str());
            if !path.is_file()
                || path.file_name().is_some_and(|n| n == "run")
                || matches!(ext, Some("tsv" | "toml" | "canon" | "err" | "md" | "sh"))
            {
                continue;
            }
            let src = std::fs::read(&path).expect("readable");
            programs.push((path.display().to_string(), src, machine_of(&path)));
        }
    }
    programs
}

pub fn machine_of(path: &Path) -> Machine {
    let toml = path.with_extension("toml");
    match std::fs::read_to_string(&toml) {
        Ok(text) => {
            Machine::from_toml(&text).unwrap_or_else(|e| panic!("{}: {e:?}", toml.display()))
        }
        Err(_) => Machine::reference(),
    }
}

/// A small random generator (xorshift), so that the programs below are
/// the same on every run.
pub struct Rng(pub u64);

impl Rng {
    pub fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }

    pub fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// Blocks that set modal codes (and move, so that the kernel runs them).
const SETTERS: &[&str] = &[
    "G98",
    "G99",
    "G20",
    "G21",
    "G61",
    "G64",
    "G54",
    "G55",
    "G96 S100",
    "G97 S500",
    "G00 X40 Z2",
    "G01 X30 Z-1 F1",
    "U-1 W-1",
    "G83 X0 Z-5 Q1000 F1",
    "G80",
    "G28 U0",
    "G50 G55 X40 Z2",
    "G#100",
    "G18",
    "G40",
    "G42 G01 X20 Z-3 F1",
    "X26 Z-8",
    "G01 X26 Z-8 ,C1",
    "G01 W-3 ,R1",
    "G32 W-5 F1.5",
    "G02 X30 Z-12 R3",
    "G01 X20 A30 F1",
    // Moves with computed words (#500 may be vacant: its word drops out).
    "G01 X[20+#1] Z-#100 F[#1+1]",
    "G00 U#1 W[0-#100]",
    "X#500 Z-3",
    "G02 X[30+#1] Z-12 R[#100*3]",
    "G01 Z-4 F[#1-1]",
];

/// A random main program of settings, branches, loops, GOTOs and calls,
/// and the subprograms it calls: O1000 (by M98, with a count) and O1001
/// (by G66 after moves).
pub fn random_program(rng: &mut Rng) -> String {
    // (The tool starts where the last program left it: a first absolute
    // move tells where it is.)
    let mut src = String::from("O0001\n#100=[#500+1]*0+1\n#1=0\nG00 X50 Z2\n");
    let mut label = 10;
    for _ in 0..rng.below(12) + 3 {
        match rng.below(8) {
            0 => {
                let cond = rng.pick(&["#1EQ0", "#500EQ1", "#1LT2"]);
                src += &format!(
                    "IF[{cond}]GOTO{label}\n{}\nN{label} {}\n",
                    rng.pick(SETTERS),
                    rng.pick(SETTERS)
                );
                label += 10;
            }
            1 => {
                src += &format!(
                    "#2=0\nWHILE[#2LT2]DO1\n{}\n#2=#2+1\nEND1\n",
                    rng.pick(SETTERS)
                );
            }
            2 => src += &format!("M98 P1000 L{}\n", rng.pick(&["1", "2", "3", "[#1+1]"])),
            3 => {
                src += &format!(
                    "G66 P1001\n{}\nG67\n",
                    rng.pick(&["G01 X20 Z-2 F1", "X30", "G98", "G01 X[20+#1] Z-#100 F1"])
                )
            }
            4 => src += &format!("#1=#1+{}\n", rng.below(2)),
            _ => src += &format!("{}\n", rng.pick(SETTERS)),
        }
    }
    src += "M30\nO1000\n";
    for _ in 0..rng.below(3) {
        src += &format!("{}\n", rng.pick(SETTERS));
    }
    src += &format!(
        "IF[#1EQ1]GOTO5\n{}\nN5 M99\nO1001\n{}\nM99\n",
        rng.pick(SETTERS),
        rng.pick(SETTERS)
    );
    src
}

/// Whether `instr` hands an NC block to the kernel where it stands (a
/// G70–G73 profile block waits for its cycle instead).
pub fn runs_block(instr: &Instr) -> bool {
    match *instr {
        Instr::Block { .. } | Instr::Move { .. } | Instr::ExecMove => true,
        Instr::Exec { flags } => flags & vm::PROFILE == 0,
        _ => false,
    }
}

/// Runs two VMs one instruction at a time, at most `steps`: after each,
/// the status, the events printed and the kernel's whole state must be
/// the same. The number of instructions compared.
pub fn lockstep(name: &str, mut vms: [Vm; 2], steps: usize) -> usize {
    let mut sinks: [Vec<Event>; 2] = Default::default();
    for step in 0..steps {
        let [a, b] = &mut vms;
        let [sa, sb] = &mut sinks;
        let status = a.step(1, sa);
        let other = b.step(1, sb);
        assert_eq!(
            format!("{status:?}"),
            format!("{other:?}"),
            "{name}: status at step {step}"
        );
        assert_eq!(sa, sb, "{name}: events at step {step}");
        assert_eq!(
            format!("{:?}", a.nc.st),
            format!("{:?}", b.nc.st),
            "{name}: kernel state after step {step}"
        );
        sa.clear();
        sb.clear();
        if matches!(status, Status::Done | Status::Alarm(_)) {
            return step + 1;
        }
    }
    steps
}
