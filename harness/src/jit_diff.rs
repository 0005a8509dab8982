//! The JIT against the interpreter: random macro programs, each run with
//! the loop tier off and with every loop compiled at its first round; the
//! events, the end, the alarm and every variable must be the same, bit
//! for bit. The programs come from a seed (the test suite, long runs) or
//! from a fuzzer's bytes (`fuzz/`, target `jit`): the same generator
//! reads its choices from either.

use compiler::{compile, Options};
use nc::{Event, Machine};
use vm::{Status, TierStats, Vm};

/// Where the generator's choices come from.
pub enum Choices<'a> {
    /// A xorshift stream from a seed.
    Seed(u64),
    /// A fuzzer's bytes, then zeros.
    Bytes(&'a [u8]),
}

impl Choices<'_> {
    /// A choice among `n` (`n` ≥ 1).
    pub fn below(&mut self, n: usize) -> usize {
        let raw = match self {
            Choices::Seed(s) => {
                *s ^= *s << 13;
                *s ^= *s >> 7;
                *s ^= *s << 17;
                *s >> 16
            }
            Choices::Bytes(b) => match b.split_first() {
                Some((&first, rest)) => {
                    *b = rest;
                    u64::from(first)
                }
                None => 0,
            },
        };
        (raw % n.max(1) as u64) as usize
    }

    fn pick<'s>(&mut self, items: &[&'s str]) -> &'s str {
        items[self.below(items.len())]
    }
}

const VARS: &[&str] = &["#1", "#2", "#3", "#4", "#5", "#100", "#101", "#500"];
const VALUES: &[&str] = &[
    "0",
    "1",
    "2",
    "-3",
    "0.5",
    "0.0000000001",
    // Near 1 as EQ takes it, and just beyond (the JIT's comparison with a
    // constant decides a value far from it alone).
    "1.0000000005",
    "1.000000003",
    "90",
    "1000",
    "#0",
    "#1",
    "#2",
    "#3",
    "#4",
    "#5",
    "#9",
    "#100",
    "#101",
    "#500",
    "#4001",
];
const FUNCS: &[&str] = &[
    "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP", "LN", "EXP",
    "BIN", "BCD",
];
const OPS: &[&str] = &["+", "-", "*", "/", "MOD", "AND", "OR", "XOR"];
const RELS: &[&str] = &["EQ", "NE", "GT", "LT", "GE", "LE"];

/// An expression over the variables: operators, every function, vacant
/// operands, nested brackets. Most operands of a function or a division
/// are kept in its domain (one in eight is not), so that most runs get
/// through their loops and some end on a domain alarm.
fn expr(c: &mut Choices, depth: u32) -> String {
    if depth == 0 {
        return c.pick(VALUES).to_string();
    }
    let raw = c.below(8) == 0;
    match c.below(6) {
        0 | 1 => c.pick(VALUES).to_string(),
        2 => {
            let f = c.pick(FUNCS);
            let a = expr(c, depth - 1);
            let a = match f {
                _ if raw => a,
                "ASIN" | "ACOS" => format!("SIN[{a}]"),
                "LN" => format!("ABS[{a}]+1"),
                "SQRT" | "BIN" | "BCD" => format!("ABS[{a}]"),
                "TAN" => format!("FIX[{a}]+0.5"),
                "EXP" => format!("SIN[{a}]*5"),
                _ => a,
            };
            format!("{f}[{a}]")
        }
        3 => {
            let (y, x) = (expr(c, depth - 1), expr(c, depth - 1));
            match raw {
                true => format!("ATAN[{y}]/[{x}]"),
                false => format!("ATAN[{y}]/[ABS[{x}]+1]"),
            }
        }
        4 => format!("-[{}]", expr(c, depth - 1)),
        _ => {
            let (a, op, b) = (expr(c, depth - 1), c.pick(OPS), expr(c, depth - 1));
            match op {
                "/" | "MOD" if !raw => format!("[{a}{op}[ABS[{b}]+0.5]]"),
                _ => format!("[{a}{op}{b}]"),
            }
        }
    }
}

fn condition(c: &mut Choices) -> String {
    format!("{}{}{}", expr(c, 1), c.pick(RELS), expr(c, 1))
}

/// Statements of a loop body (`level`: the DO number free for a nested
/// loop; `label`: the next N number).
fn statements(c: &mut Choices, src: &mut String, level: u32, label: &mut u32) {
    for _ in 0..c.below(5) + 1 {
        let var = c.pick(VARS);
        match c.below(10) {
            0..=3 => *src += &format!("{var}={}\n", expr(c, 2)),
            4 => *src += &format!("IF[{}]THEN{var}={}\n", condition(c), expr(c, 1)),
            5 => {
                *src += &format!(
                    "IF[{}]GOTO{label}\n{var}={}\nN{label}\n",
                    condition(c),
                    expr(c, 1)
                );
                *label += 10;
            }
            6 => *src += &format!("G01 X[{}] Z[{}] F100\n", expr(c, 1), expr(c, 1)),
            7 if level <= 3 => {
                // A nested counted loop, its own counter.
                let n = 10 + level;
                *src += &format!("#{n}=0\nWHILE[#{n}LT{}]DO{level}\n", c.below(4) + 1);
                statements(c, src, level + 1, label);
                *src += &format!("#{n}=#{n}+1\nEND{level}\n");
            }
            8 => {
                // (A call and a system variable twice: weighted.)
                *src += c.pick(&[
                    "M98 P1000\n",
                    "#5=#5021\n",
                    "G04 X0.01\n",
                    "#3=#[1+#20 MOD 3]\n",
                    "#[2+#20 MOD 2]=#20\n",
                    "M98 P1000\n",
                    "#5=#5021\n",
                    "#3000=#0\n",
                ])
            }
            _ => *src += &format!("#500={}\n", expr(c, 1)),
        }
    }
}

/// A random macro program: a few loops (WHILE, and a GOTO loop) around
/// random statements, the main counter bounded so that most runs end.
pub fn program(c: &mut Choices) -> String {
    let mut src = String::from("O0001\nG00 X50 Z2\n");
    let mut label = 100;
    for _ in 0..c.below(3) + 1 {
        src += &format!("#{}={}\n", 1 + c.below(5), expr(c, 1));
        match c.below(3) {
            0 => {
                src += &format!("#20=0\nN{label} #20=#20+1\n");
                let back = label;
                label += 10;
                statements(c, &mut src, 1, &mut label);
                src += &format!("IF[#20LT{}]GOTO{back}\n", c.below(30) + 1);
            }
            _ => {
                src += &format!("#20=0\nWHILE[#20LT{}]DO1\n", c.below(40) + 1);
                statements(c, &mut src, 2, &mut label);
                src += "#20=#20+1\nEND1\n";
            }
        }
    }
    src += "G01 X[#1] Z[#2] F100\nM30\n";
    src += "O1000\n#4=#4+1\nG01 W-0.5 F100\nM99\n";
    src
}

/// Every variable a program can write: locals, commons, persistents.
fn variables(vm: &Vm) -> Vec<u64> {
    (1..=33)
        .chain(100..=199)
        .chain(500..=999)
        .map(|n| vm.variable(n).map_or(u64::MAX, f64::to_bits))
        .collect()
}

/// How a run went: its events, its end, and every variable's bits.
#[derive(Debug, PartialEq)]
pub struct Outcome {
    pub events: Vec<Event>,
    pub end: String,
    pub vars: Vec<u64>,
}

/// How a run goes: `max_blocks` blocks at most, `step` instructions per
/// call of `Vm::step`, which ends at every block or not
/// (`Vm::stop_at_blocks`).
#[derive(Debug, Clone, Copy)]
pub struct Runs {
    pub max_blocks: u64,
    pub step: u64,
    pub stop_at_blocks: bool,
}

/// Runs `module` with the JIT in `mode`, its loops compiled again with
/// the optimiser after `optimize_after` instructions (`jit::Jit`).
pub fn run(
    module: isa::Module,
    mode: jit::Mode,
    optimize_after: u64,
    how: Runs,
) -> (Outcome, TierStats) {
    let mut vm = Vm::new(module, Machine::reference());
    vm.max_blocks = how.max_blocks;
    vm.stop_at_blocks = how.stop_at_blocks;
    if let Some(tier) = jit::Jit::new(mode) {
        vm.set_tier(Box::new(tier.optimize_after(optimize_after)));
    }
    let mut events = Vec::new();
    let end = loop {
        match vm.step(how.step, &mut events) {
            Status::Event | Status::OutOfBudget | Status::Sync => continue,
            other => break other,
        }
    };
    let outcome = Outcome {
        events,
        end: format!("{end:?}"),
        vars: variables(&vm),
    };
    (outcome, vm.tier_stats().unwrap_or_default())
}

/// The comparison for one program: compiled as `gbcc` does and without
/// folding (more of its arithmetic is left to run), each run with the JIT
/// off and always, with a small step and a block budget that may end the
/// run inside a loop. The compiled runs take the quick code alone, the
/// optimised code alone, and the optimised code from a few rounds in (the
/// quick code replaced while the loop runs, where it runs few blocks). Returns the compiled runs' JIT statistics.
pub fn compare(src: &str, max_blocks: u64, step: u64) -> TierStats {
    let mut all = TierStats::default();
    for optimize in [true, false] {
        let opts = Options {
            optimize,
            ..Options::default()
        };
        let Some(module) = compile("jit.nc", src.as_bytes(), &opts).module else {
            continue;
        };
        let how = |stop_at_blocks| Runs {
            max_blocks,
            step,
            stop_at_blocks,
        };
        verify_loops(&module, src);
        let (off, _) = run(module.clone(), jit::Mode::Off, 0, how(true));
        // Compiled code leaves after each block where steps end at
        // blocks, and runs its blocks through where they do not.
        for (stop_at_blocks, optimize_after) in
            [(true, u64::MAX), (false, u64::MAX), (true, 0), (false, 40)]
        {
            let mode = jit::Mode::Always;
            let (on, stats) = run(module.clone(), mode, optimize_after, how(stop_at_blocks));
            if off != on {
                panic!(
                    "the JIT runs otherwise (-O{}, {max_blocks} blocks, step {step}, \
                     stop at blocks: {stop_at_blocks}, optimised after {optimize_after}):\n{src}\n{}",
                    u8::from(optimize),
                    difference(&off, &on)
                );
            }
            all.compiled += stats.compiled;
            all.optimized += stats.optimized;
            all.entries += stats.entries;
            all.blocks += stats.blocks;
            all.failed += stats.failed;
        }
    }
    all
}

/// Every loop of `module` the JIT takes compiles, and Cranelift's
/// verifier accepts the function built (a run leaves the verifier off,
/// and a function it would reject could run wrongly). At the quick level
/// only: both levels build the same function, and the optimiser's passes
/// are Cranelift's.
fn verify_loops(module: &isa::Module, src: &str) {
    let Ok(mut compiler) = jit::Compiler::verifying(jit::Level::Quick) else {
        return;
    };
    for (head, tail) in jit::loops(module) {
        if !jit::takes(module, head, tail) {
            continue;
        }
        if let Err(e) = compiler.compile(module, head, tail) {
            panic!("the loop {head}..={tail} does not compile: {e}\n{src}");
        }
    }
}

/// What differs between two outcomes, briefly.
fn difference(off: &Outcome, on: &Outcome) -> String {
    let numbers = (1..=33).chain(100..=199).chain(500..=999);
    let vars: Vec<String> = numbers
        .zip(off.vars.iter().zip(&on.vars))
        .filter(|(_, (a, b))| a != b)
        .map(|(n, (a, b))| format!("#{n}: {} / {}", f64::from_bits(*a), f64::from_bits(*b)))
        .collect();
    let first = off.events.iter().zip(&on.events).position(|(a, b)| a != b);
    format!(
        "off / on: end {} / {}; {} / {} events, first differing {first:?}: {:?} / {:?}; variables {vars:?}",
        off.end,
        on.end,
        off.events.len(),
        on.events.len(),
        first.and_then(|i| off.events.get(i)),
        first.and_then(|i| on.events.get(i)),
    )
}

/// The fuzz body: a program from the bytes, compared as [`compare`] does.
pub fn differential(data: &[u8]) {
    let (head, rest) = data.split_at(data.len().min(2));
    let max_blocks = 50 + 20 * head.first().map_or(100, |&b| u64::from(b));
    let step = 1 + head.get(1).map_or(1000, |&b| u64::from(b) * 7);
    let src = program(&mut Choices::Bytes(rest));
    compare(&src, max_blocks, step);
}
