//! Pass `resolve` types plain moves (`move` and `execmove`, read by the
//! kernel's short parse) and changes nothing else: every suite program and
//! a few hundred random macro programs compile with and without it to the
//! same code but for `block` ↔ `move` and `exec` ↔ `execmove`, and run in
//! the VM both ways one instruction at a time; after each, the status, the
//! events printed and the kernel's whole state must be the same.

use compiler::{compile, Options};
use isa::{Instr, Module};
use nc::Machine;
use vm::Vm;

mod common;
use common::{random_program, Rng};

/// Instructions run per program at most (the suites' loops are short).
const STEPS: usize = 100_000;

/// What one program gave: moves typed (those with a computed word
/// apart), instructions compared.
#[derive(Default)]
struct Compared {
    moves: Moves,
    steps: usize,
}

/// Typed moves: of constants (`move`), with a computed word (`execmove`).
#[derive(Default, Clone, Copy)]
struct Moves {
    constant: usize,
    computed: usize,
}

impl std::ops::AddAssign for Moves {
    fn add_assign(&mut self, o: Moves) {
        self.constant += o.constant;
        self.computed += o.computed;
    }
}

/// The module of `src` with and without `resolve`, if it compiles.
fn both_modules(src: &[u8], machine: &Machine) -> Option<[Module; 2]> {
    let with = |resolve| Options {
        machine: machine.clone(),
        resolve,
        ..Options::default()
    };
    let typed = compile("t.nc", src, &with(true)).module?;
    let words = compile("t.nc", src, &with(false)).module?;
    Some([typed, words])
}

/// The code is the same but for `move` where the other has `block`, on
/// the same record, and `execmove` where it has `exec`; the moves.
fn moves_only_differ(name: &str, typed: &Module, words: &Module) -> Moves {
    assert_eq!(typed.code.len(), words.code.len(), "{name}: code length");
    assert_eq!(typed.blocks, words.blocks, "{name}: records");
    let mut moves = Moves::default();
    for (pc, (a, b)) in typed.code.iter().zip(&words.code).enumerate() {
        match (a, b) {
            (Instr::Move { rec }, Instr::Block { rec: other }) if rec == other => {
                moves.constant += 1
            }
            (Instr::ExecMove, Instr::Exec { flags: 0 }) => moves.computed += 1,
            _ => assert_eq!(a, b, "{name}: pc {pc}"),
        }
    }
    moves
}

fn same_both_ways(name: &str, src: &[u8], machine: &Machine) -> Option<Compared> {
    let [typed, words] = both_modules(src, machine)?;
    let moves = moves_only_differ(name, &typed, &words);
    let vms = [typed, words].map(|m| Vm::new(m, machine.clone()));
    let steps = common::lockstep(name, vms, STEPS);
    Some(Compared { moves, steps })
}

#[test]
fn every_suite_program_runs_the_same_with_typed_moves() {
    let (mut programs, mut total) = (0, Compared::default());
    for (name, src, machine) in common::suite() {
        if let Some(c) = same_both_ways(&name, &src, &machine) {
            programs += 1;
            total.moves += c.moves;
            total.steps += c.steps;
        }
    }
    let Moves { constant, computed } = total.moves;
    eprintln!(
        "{programs} programs, {constant} typed moves of constants, {computed} with a computed \
         word, {} instructions compared",
        total.steps
    );
    assert!(programs >= 100, "only {programs} programs compiled");
    // The suites are mostly plain moves: most of their blocks are typed.
    assert!(constant >= 1000, "only {constant} typed moves");
    // Their macro programs compute a few points of contours.
    assert!(
        computed >= 5,
        "only {computed} typed moves with a computed word"
    );
}

#[test]
fn random_programs_run_the_same_with_typed_moves() {
    let mut rng = Rng(0x7e5d_0e5d_2026_1203);
    let machine = Machine::reference();
    let (mut programs, mut moves) = (0, Moves::default());
    for i in 0..300 {
        let src = random_program(&mut rng);
        let name = format!("random{i}.nc\n{src}");
        if let Some(c) = same_both_ways(&name, src.as_bytes(), &machine) {
            programs += 1;
            moves += c.moves;
        }
    }
    let Moves { constant, computed } = moves;
    eprintln!("{programs} programs, {constant} typed moves, {computed} with a computed word");
    assert!(programs >= 280, "only {programs} of 300 compiled");
    assert!(constant >= 100, "only {constant} typed moves");
    assert!(
        computed >= 100,
        "only {computed} typed moves with a computed word"
    );
}

/// A long plain program takes the chunked path (`stream`): its moves are
/// typed there too, and run as the whole-file path's.
#[test]
fn a_long_plain_program_is_typed_chunk_by_chunk() {
    let mut src = String::from("G98 G00 X50 Z2\n");
    for i in 0..20_000 {
        src.push_str(&format!("G01 X{}.5 Z-{}.25 F100\n", i % 50, i % 70));
    }
    src.push_str("M30\n");
    assert!(src.len() > Options::default().chunk_bytes);
    let machine = Machine::reference();
    let [typed, words] = both_modules(src.as_bytes(), &machine).expect("compiles");
    let moves = moves_only_differ("long", &typed, &words);
    assert_eq!((moves.constant, moves.computed), (20_000, 0));
    let c = same_both_ways("long", src.as_bytes(), &machine).expect("compiles");
    assert!(c.steps > 20_000);
}
