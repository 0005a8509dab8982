//! W127 against the run: random programs of one loop (a WHILE, a DO left
//! by an IF … GOTO, a WHILE with a second way out behind a branch, or an
//! IF … GOTO back to an earlier block), whose body steps some variables
//! and not others. Where `gbcc` warns W127 and the
//! run's loop goes round, only an alarm may end the run: under a budget of
//! [`BUDGET`] blocks, E6005.

use crate::jit_diff::Choices;
use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

/// The run's block budget: far above what a loop that ends needs.
pub const BUDGET: u64 = 5_000;

const VARS: [&str; 3] = ["#1", "#2", "#3"];
const OPS: [&str; 6] = ["LT", "LE", "GT", "GE", "EQ", "NE"];

/// What one program did.
#[derive(Debug)]
pub struct Outcome {
    /// The source.
    pub src: String,
    /// W127 was given.
    pub warned: bool,
    /// The loop's test ran more than once: the loop went round.
    pub went_round: bool,
    /// How the run ended.
    pub end: Status,
}

impl Outcome {
    /// W127 holds: a warned loop that went round ends only with an alarm.
    pub fn holds(&self) -> bool {
        let alarm = matches!(self.end, Status::Alarm(_));
        !(self.warned && self.went_round) || alarm
    }
}

/// A program of one loop from `c`, compiled and run.
pub fn check(c: &mut Choices) -> Outcome {
    let (src, test_line) = program(c);
    let compiled = compile("w.nc", src.as_bytes(), &Options::default());
    let warned = compiled.diags.iter().any(|(_, d)| d.code == "W127");
    // (A program that does not compile does not run: nothing to hold.)
    let (runs, end) = match compiled.module {
        Some(module) => run(module, test_line),
        None => (0, Status::Done),
    };
    Outcome {
        src,
        warned,
        went_round: runs >= 2,
        end,
    }
}

/// The source and the line of the loop's test.
fn program(c: &mut Choices) -> (String, u32) {
    let mut lines: Vec<String> = VARS.iter().map(|v| format!("{v}={}", c.below(4))).collect();
    let test = condition(c);
    match c.below(4) {
        0 => {
            lines.push(format!("WHILE{test}DO1"));
            body(c, &mut lines);
            lines.push("END1".into());
            lines.push("M30".into());
            (lines.join("\n") + "\n", VARS.len() as u32 + 1)
        }
        1 => {
            lines.push("DO1".into());
            body(c, &mut lines);
            lines.push(format!("IF{test}GOTO9"));
            let line = lines.len() as u32;
            body(c, &mut lines);
            lines.push("END1".into());
            lines.push("N9 M30".into());
            (lines.join("\n") + "\n", line)
        }
        2 => {
            // A second way out, behind a branch of the body: met on the
            // rounds where the branch does not skip it.
            lines.push(format!("WHILE{test}DO1"));
            let line = lines.len() as u32;
            body(c, &mut lines);
            lines.push(format!("IF{}GOTO7", condition(c)));
            lines.push(format!("IF{}GOTO9", condition(c)));
            lines.push("N7 G00 W-0.1".into());
            body(c, &mut lines);
            lines.push("END1".into());
            lines.push("N9 M30".into());
            (lines.join("\n") + "\n", line)
        }
        _ => {
            lines.push("N5 G00 U0.1".into());
            body(c, &mut lines);
            lines.push(format!("IF{test}GOTO5"));
            let line = lines.len() as u32;
            lines.push("M30".into());
            (lines.join("\n") + "\n", line)
        }
    }
}

fn condition(c: &mut Choices) -> String {
    let a = VARS[c.below(VARS.len())];
    let op = OPS[c.below(OPS.len())];
    let b = match c.below(2) {
        0 => VARS[c.below(VARS.len())].to_string(),
        _ => c.below(6).to_string(),
    };
    format!("[{a}{op}{b}]")
}

/// Up to three statements: a step, a set, a move, an IF … THEN.
fn body(c: &mut Choices, lines: &mut Vec<String>) {
    for _ in 0..c.below(4) {
        let v = VARS[c.below(VARS.len())];
        lines.push(match c.below(4) {
            0 => format!("{v}={v}+1"),
            1 => format!("{v}={}", c.below(4)),
            2 => "G00 W-0.1".into(),
            _ => format!("IF{}THEN{v}={v}-1", condition(c)),
        });
    }
}

/// Runs the module an instruction at a time: how often line `test` was
/// entered (from another line, or by a jump back into it), and the end.
fn run(module: isa::Module, test: u32) -> (u32, Status) {
    let mut vm = Vm::new(module, Machine::reference());
    vm.max_blocks = BUDGET;
    let mut events: Vec<Event> = Vec::new();
    let (mut runs, mut last) = (0, None);
    loop {
        let pc = vm.pc();
        let line = vm.loc_at(pc).line;
        let entered = match last {
            Some((prev_pc, prev_line)) => prev_line != line || pc <= prev_pc,
            None => true,
        };
        if line == test && entered {
            runs += 1;
        }
        last = Some((pc, line));
        events.clear();
        match vm.step(1, &mut events) {
            Status::Event | Status::OutOfBudget | Status::Sync => continue,
            end => return (runs, end),
        }
    }
}
