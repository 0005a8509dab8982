//! The fuzz targets' bodies: each takes arbitrary bytes and checks that
//! the part under test answers cleanly — a diagnostic, an error, a run
//! that ends within its budget — and never panics or hangs. `fuzz/` runs
//! them under libFuzzer (nightly); `tests/bounded.rs` runs them a few
//! seconds each on stable, from seeds and random mutations.

pub mod contour;
pub mod endless;
pub mod expr;
pub mod jit_diff;
pub mod plane;
pub mod thread;

use compiler::predict::CODES;
use compiler::{compile, Options};
use nc::Machine;
use vm::{Status, Vm};

/// Blocks a fuzzed program or module may run.
const MAX_BLOCKS: u64 = 2_000;
/// Instructions it may run: far above what `MAX_BLOCKS` blocks take
/// unless a loop escapes the block budget.
const MAX_STEPS: u64 = 2_000_000;

/// The front end: bytes → tree and diagnostics, each rendered as text,
/// as rustc-shaped JSON and as SARIF (`gbcc`'s three forms).
pub fn front_end(data: &[u8]) {
    use cli::report::{Format, Reporter};
    let (_ast, diags) = grammar::parse(data);
    let file = grammar::SourceFile::new("fuzz.nc", data);
    for d in &diags {
        let _ = file.render(d);
    }
    for format in [Format::Json, Format::Sarif] {
        let mut r = Reporter::new(Vec::new(), format, false, Default::default());
        r.max_errors = 0;
        for d in &diags {
            r.report(&file, d);
        }
        r.finish();
    }
}

/// The whole compiler: bytes → a module or diagnostics. A module it emits
/// always verifies and runs within its budget, to the same events and the
/// same end with the kernel's short path for plain moves as without it
/// (`nc::exec::plain`), with its loops compiled by the JIT, as the module
/// compiled without typed moves (pass
/// `resolve`) and as the module compiled without folding (-O0), and
/// where W124 tells the alarm its run stops with, it does; the dry run's
/// warnings of a static program are found again when a macro statement
/// makes it dynamic (`predict`); a plain
/// program compiled a few lines at a time
/// (`compiler::stream`) gives the same module and diagnostics as compiled
/// whole; compiled for radius programming, it compiles or is refused as
/// cleanly, and runs within its budget.
pub fn compiler(data: &[u8]) {
    on_the_radius(data);
    let c = compile("fuzz.nc", data, &Options::default());
    let text = c.render();
    let small_chunks = Options {
        chunk_bytes: 16,
        ..Options::default()
    };
    if let Some(s) = compiler::stream::compile("fuzz.nc", &data.into(), &small_chunks) {
        assert_eq!(s.render(), text, "the chunked compile reports otherwise");
        let bytes = |m: &Option<isa::Module>| m.as_ref().map(isa::Module::to_bytes);
        assert!(
            bytes(&s.module) == bytes(&c.module),
            "the chunked module differs"
        );
    }
    if let Some(module) = c.module {
        prediction_holds(&c.diags, &c.files, &module);
        dynamic_run_warns_too(data, (&c.diags, &c.files), &module);
        restart_holds(data, &module);
        let bytes = module.to_bytes();
        let back = isa::Module::from_bytes(&bytes);
        assert!(back.is_ok(), "a compiled module must verify: {back:?}");
        if let Ok(m) = back {
            let short = run_bounded(m.clone(), true, jit::Mode::Off);
            assert!(
                short == run_bounded(m.clone(), false, jit::Mode::Off),
                "the plain-move path runs otherwise"
            );
            assert!(
                short == run_bounded(m, true, jit::Mode::Always),
                "the module runs otherwise with its loops compiled"
            );
            let variants = [
                (
                    Options {
                        resolve: false,
                        ..Options::default()
                    },
                    "the module without typed moves runs otherwise",
                ),
                (
                    Options {
                        optimize: false,
                        ..Options::default()
                    },
                    "the module without folding (-O0) runs otherwise",
                ),
            ];
            for (opts, what) in variants {
                if let Some(other) = compile("fuzz.nc", data, &opts).module {
                    assert!(short == run_bounded(other, true, jit::Mode::Off), "{what}");
                }
            }
        }
    }
}

/// A program restart (`vm::restart`) at a line the input picks: the run
/// after the restored state and the approach prints what the whole run
/// prints from its first arrival at that block on. (Skipped for a
/// program whose whole run is long: it is stepped one instruction at a
/// time.)
fn restart_holds(data: &[u8], module: &isa::Module) {
    use vm::restart::{search, RestartAt, Target};
    let last = module.lines.iter().filter(|l| l.file == 0).map(|l| l.line);
    let Some(lines) = last.max().filter(|_| module.code.len() <= 4_000) else {
        return;
    };
    let pick = data
        .iter()
        .fold(0u32, |h, &b| h.wrapping_mul(31).wrapping_add(b.into()));
    let at = RestartAt {
        target: Target::Line(1 + pick % lines),
        pass: 1,
    };
    let Some((events, first)) = stepped_run(module) else {
        return;
    };
    let mut vm = Vm::new(module.clone(), Machine::reference());
    vm.max_blocks = MAX_BLOCKS;
    let mut prefix: Vec<nc::Event> = Vec::new();
    if search(&mut vm, at, &mut prefix).is_err() {
        return;
    }
    let mark = first.get(&vm.pc()).copied();
    assert!(
        mark.is_some(),
        "the restart begins where the whole run never comes"
    );
    let mut rest: Vec<nc::Event> = Vec::new();
    vm.run(&mut rest);
    let text = |e: &[nc::Event]| format!("{e:?}");
    assert!(
        text(&rest) == text(&events[mark.unwrap_or(0)..]),
        "a restart at {:?} prints otherwise than the whole run",
        at.target
    );
}

/// The whole run one instruction at a time: its events, and the number
/// printed before the first arrival at each pc; `None` when it is long.
fn stepped_run(
    module: &isa::Module,
) -> Option<(Vec<nc::Event>, std::collections::HashMap<u32, usize>)> {
    let mut vm = Vm::new(module.clone(), Machine::reference());
    vm.max_blocks = MAX_BLOCKS;
    let mut events: Vec<nc::Event> = Vec::new();
    let mut first = std::collections::HashMap::new();
    for _ in 0..200_000 {
        first.entry(vm.pc()).or_insert(events.len());
        if let Status::Done | Status::Alarm(_) = vm.step(1, &mut events) {
            // Where the run stopped counts too: a restart whose target's
            // waiting elements are printed only by the end (M30 under
            // nose-radius compensation) resumes there, all printed.
            first.entry(vm.pc()).or_insert(events.len());
            return Some((events, first));
        }
        if events.len() > 20_000 {
            return None;
        }
    }
    None
}

/// The program compiled and run for radius programming (machine.md
/// `axes.x.diameter = false`), where the kernel reads X words otherwise.
fn on_the_radius(data: &[u8]) {
    let mut machine = Machine::reference();
    machine.axes.x.diameter = false;
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    if let Some(module) = compile("fuzz.nc", data, &opts).module {
        run_bounded_on(module, machine, true, jit::Mode::Off);
    }
}

/// W124 tells the alarm a run stops with: a run with #500–#999 set (as
/// `--vars` would) and its loops compiled by the JIT stops there too, with
/// that alarm.
fn prediction_holds(
    diags: &[(usize, grammar::Diagnostic)],
    files: &[grammar::SourceFile],
    module: &isa::Module,
) {
    let Some((file, d)) = diags.iter().find(|(_, d)| d.code == "W124") else {
        return;
    };
    let mut vm = Vm::new(module.clone(), Machine::reference());
    vm.persistent_mut().fill(7.0);
    if let Some(t) = jit::Jit::new(jit::Mode::Always) {
        vm.set_tier(Box::new(t));
    }
    let Status::Alarm(a) = vm.run(&mut nc::Discard) else {
        panic!(
            "W124 told an alarm the run does not stop with: {}",
            d.message
        );
    };
    let told = compiler::predict::warning(a.code, &a.message, d.span);
    assert_eq!(told.message, d.message, "W124 told another alarm");
    let line = files[*file].line_col(d.span.start).0;
    assert_eq!(a.line as usize, line, "W124 told another line");
}

/// The warnings of the blocks a run executes, which a static program gets
/// from its dry run, the program made dynamic by a macro statement at its
/// end gets from the compile-time run in the VM, at the same lines. (Not
/// W107, which the VM's run tells as its alarm; and only for a program
/// without calls or W120/W122, whose dry run and VM run count their
/// budgets otherwise: calls cost instructions the dry run does not count.)
fn dynamic_run_warns_too(
    data: &[u8],
    found: (&[(usize, grammar::Diagnostic)], &[grammar::SourceFile]),
    module: &isa::Module,
) {
    // (The prediction's warnings but its alarm, W124.)
    let of_blocks = |d: &grammar::Diagnostic| d.code != "W124" && CODES.contains(&d.code);
    let stops = |d: &grammar::Diagnostic| matches!(d.code, "W107" | "W120" | "W122");
    let calls = module.code.iter().any(|i| {
        use isa::Instr::*;
        matches!(
            i,
            CallSub { .. }
                | CallSubDyn { .. }
                | CallMacro { .. }
                | CallMacroDyn { .. }
                | ModalCall { .. }
                | ModalCallDyn { .. }
        )
    });
    let (diags, files) = found;
    if calls || diags.iter().any(|(_, d)| stops(d)) {
        return;
    }
    let dynamic = compile(
        "fuzz.nc",
        &[data, b"\n#1=1\n"].concat(),
        &Options::default(),
    );
    if dynamic.has_errors() {
        return;
    }
    let ran = |diags: &[(usize, grammar::Diagnostic)], files: &[grammar::SourceFile]| {
        (diags.iter())
            .filter(|(_, d)| of_blocks(d))
            .map(|(f, d)| (d.code, files[*f].line_col(d.span.start).0))
            .collect::<std::collections::BTreeSet<_>>()
    };
    let found = ran(diags, files);
    let predicted = ran(&dynamic.diags, &dynamic.files);
    assert!(
        found.is_subset(&predicted),
        "the program made dynamic lacks warnings: {found:?} against {predicted:?}"
    );
}

/// The `.gbc` loader and verifier: bytes → an error or a module that runs
/// within its budget, the same with its loops compiled by the JIT. The CRC trailer is made right first, so that the
/// fuzzer reaches the verifier instead of stopping at the checksum (the
/// bytes are also tried as they are).
pub fn module(data: &[u8]) {
    let _ = isa::Module::from_bytes(data);
    let Some(body_len) = data.len().checked_sub(4) else {
        return;
    };
    let mut fixed = data[..body_len].to_vec();
    fixed.extend_from_slice(&crc32fast::hash(&fixed).to_le_bytes());
    if let Ok(m) = isa::Module::from_bytes(&fixed) {
        let _ = m.disassemble();
        let interpreted = run_bounded(m.clone(), true, jit::Mode::Off);
        assert!(
            interpreted == run_bounded(m, true, jit::Mode::Always),
            "the module runs otherwise with its loops compiled"
        );
    }
}

/// The machine-file reader: text → a machine or a located error; a
/// machine it accepts builds a runtime configuration.
pub fn machine(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(m) = Machine::from_toml(text) {
        let _ = m.compile_keys();
        compensated_moves(m);
    }
}

/// Moves that turn each axis back (C too, on a machine with one), run on
/// `m` for at most a few simulated seconds: the drives' command (the
/// counts) never lies further from the set point than the machine's
/// backlash and largest pitch correction, and half a count.
fn compensated_moves(m: Machine) {
    let src = match m.axes.c.enabled {
        false => "G00 X40 Z-5\nG01 Z-2 F3000\nG00 X20\nG01 X30 Z-4\nM30\n",
        true => "G00 X40 Z-5 C-20\nG01 Z-2 C5 F3000\nG00 X20 C-3\nG01 X30 Z-4\nM30\n",
    };
    let options = Options {
        machine: m.clone(),
        ..Options::default()
    };
    let Some(module) = compile("fuzz.nc", src.as_bytes(), &options).module else {
        return;
    };
    let res = m.machine.resolution_mm;
    // The largest correction of a table of [position, correction] pairs.
    let largest = |t: &[Vec<f64>]| {
        let adds = t.iter().flatten().skip(1).step_by(2);
        adds.fold(0.0, |w: f64, c| w.max(c.abs()))
    };
    let bound =
        |a: &nc::machine::LinearAxis| a.backlash_mm + largest(&a.pitch_comp_mm) + res / 2.0 + 1e-9;
    let (bx, bz) = (bound(&m.axes.x), bound(&m.axes.z));
    let c = &m.axes.c;
    let bc = c.backlash_deg + largest(&c.pitch_comp_deg) + runtime::counts::C_STEP_DEG / 2.0 + 1e-9;
    let Ok(mut ctl) = runtime::Controller::new(module, m, runtime::AutoAck) else {
        return;
    };
    ctl.cycle_start();
    for _ in 0..5_000 {
        ctl.run_ahead();
        let p = ctl.tick();
        let (dx, dz) = (
            p.counts.x as f64 * res - p.axis_x,
            p.counts.z as f64 * res - p.axis_z,
        );
        assert!(dx.abs() <= bx && dz.abs() <= bz, "{dx} {dz} at {p:?}");
        let dc = p.counts.c as f64 * runtime::counts::C_STEP_DEG - p.c.unwrap_or(0.0);
        assert!(dc.abs() <= bc, "{dc} at {p:?}");
        if ctl.state() != runtime::RunState::Running {
            return;
        }
    }
}

/// How a bounded run went: a hash of every event, how it ended and the
/// kernel's state at the end, as text.
#[derive(PartialEq)]
struct Run {
    events: u64,
    end: String,
    state: String,
}

/// Runs a verified module on the reference machine with a small block
/// budget, plain moves on the kernel's short path or not, its loops
/// compiled by the JIT or not (`tier`); it must end
/// (done, alarm or budget) within `MAX_STEPS`.
fn run_bounded(module: isa::Module, plain: bool, tier: jit::Mode) -> Run {
    run_bounded_on(module, Machine::reference(), plain, tier)
}

/// [`run_bounded`] on `machine`.
fn run_bounded_on(module: isa::Module, machine: Machine, plain: bool, tier: jit::Mode) -> Run {
    use std::hash::{Hash, Hasher};
    let mut vm = Vm::new(module, machine);
    vm.max_blocks = MAX_BLOCKS;
    vm.nc.set_plain_path(plain);
    if let Some(t) = jit::Jit::new(tier) {
        vm.set_tier(Box::new(t));
    }
    let mut events: Vec<nc::Event> = Vec::new();
    let mut hash = std::collections::hash_map::DefaultHasher::new();
    // Instructions spent (whole slices of 10 000) and early returns (an
    // event or a sync ends a slice early; each needs a block at least).
    let (mut steps, mut stops) = (0u64, 0u64);
    while steps < MAX_STEPS && stops < MAX_STEPS {
        let status = vm.step(10_000, &mut events);
        // Hashed, not kept: memory stays flat. (Event by event: where a
        // slice of instructions ends depends on the code, not the run.)
        for e in &events {
            format!("{e:?}").hash(&mut hash);
        }
        events.clear();
        match status {
            Status::OutOfBudget => steps += 10_000,
            Status::Event | Status::Sync => stops += 1,
            end => {
                return Run {
                    events: hash.finish(),
                    end: format!("{end:?}"),
                    state: format!("{:?}", vm.nc.st),
                }
            }
        }
    }
    panic!("a verified module ran {MAX_STEPS} instructions within {MAX_BLOCKS} blocks");
}
