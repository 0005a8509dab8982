//! Block delete is the operator's switch, read as each block is: the
//! compiler keeps `/n` blocks behind a guard, one module serves both
//! switch states, and the compile-time checks hold for both.

use compiler::{compile, Compiled, Options};
use nc::{Event, Machine};
use vm::{Status, Vm};

fn compiled(src: &str) -> Compiled {
    compile("test.nc", src.as_bytes(), &Options::default())
}

/// The module of a program that must compile, written and loaded again.
fn module(src: &str) -> isa::Module {
    let c = compiled(src);
    assert!(!c.has_errors(), "{}", c.render());
    let bytes = c.module.expect("a module").to_bytes();
    isa::Module::from_bytes(&bytes).expect("the module loads")
}

/// Runs `m` on the reference machine with switches `off` turned off.
fn canon(m: isa::Module, off: &[u8]) -> Vec<String> {
    let mut vm = Vm::new(m, Machine::reference());
    for &n in off {
        vm.set_block_skip(n, false);
    }
    let mut events: Vec<Event> = Vec::new();
    assert_eq!(vm.run(&mut events), Status::Done);
    events.iter().map(|e| e.to_string()).collect()
}

const ALL: [u8; 9] = [1, 2, 3, 4, 5, 6, 7, 8, 9];

const SKIPPED: &str = "O0001\n#1=10\nG00 X40 Z2\n/G00 X20\n/#1=99\n/2 G01 Z-5 F100\nG00 X#1\nM30\n";

#[test]
fn one_module_runs_both_ways() {
    let m = module(SKIPPED);
    // Hand check, every switch on (the reference machine): the three `/`
    // blocks are skipped, #1 stays 10.
    assert_eq!(
        canon(m.clone(), &[]),
        ["RAPID X=40 Z=2", "RAPID X=10 Z=2", "STOP KIND=M30"]
    );
    // Every switch off: X20, then #1 = 99, the feed move to Z-5 at F100
    // (mm/min, G98 at power-on), and X#1 is X99 (the compiler must not
    // carry #1 = 10 past a block that may or may not run).
    assert_eq!(
        canon(m.clone(), &ALL),
        [
            "RAPID X=40 Z=2",
            "RAPID X=20 Z=2",
            "FEED F=100 MODE=MIN",
            "LINE X=20 Z=-5",
            "RAPID X=99 Z=-5",
            "STOP KIND=M30"
        ]
    );
    // Only switch 2 off: `/2` runs, the two `/` blocks do not.
    assert_eq!(
        canon(m, &[2]),
        [
            "RAPID X=40 Z=2",
            "FEED F=100 MODE=MIN",
            "LINE X=40 Z=-5",
            "RAPID X=10 Z=-5",
            "STOP KIND=M30"
        ]
    );
}

#[test]
fn a_skipped_last_block_runs_off_the_end() {
    // `/M30` last: with the switch on the program runs off its end (the
    // compiler puts a halt there), with it off M30 ends it.
    let m = module("O0001\nG00 X10 Z0\n/M30\n");
    assert_eq!(canon(m.clone(), &[]), ["RAPID X=10 Z=0"]);
    assert_eq!(canon(m, &ALL), ["RAPID X=10 Z=0", "STOP KIND=M30"]);
}

#[test]
fn a_goto_to_a_skipped_block_lands_on_its_guard() {
    // GOTO 5 reaches `/N5 #2=7`: skipped with the switch on, run with it
    // off; either way the program goes on with the next block.
    let src = "O0001\n#2=1\nGOTO 5\n#2=3\n/N5 #2=7\nG00 X#2 Z0\nM30\n";
    let m = module(src);
    assert_eq!(canon(m.clone(), &[]), ["RAPID X=1 Z=0", "STOP KIND=M30"]);
    assert_eq!(canon(m, &ALL), ["RAPID X=7 Z=0", "STOP KIND=M30"]);
}

const PROFILE: &str = "G98 G00 X40 Z2\nG71 U3 R1\nG71 P1 Q2 F0.2\nN1 G00 X28\n";

#[test]
fn a_profile_block_follows_the_switch_when_the_cycle_is_read() {
    // The same G71 with the taper as a `/` block and as a plain one: with
    // the switch off the cycle must cut what the plain program cuts; with
    // it on, what the program without the taper cuts.
    let guarded = format!("{PROFILE}/G01 X34 Z-3\nN2 G01 Z-10\nM30\n");
    let plain = format!("{PROFILE}G01 X34 Z-3\nN2 G01 Z-10\nM30\n");
    let without = format!("{PROFILE}N2 G01 Z-10\nM30\n");
    let m = module(&guarded);
    let off = canon(m.clone(), &ALL);
    assert_eq!(off, canon(module(&plain), &ALL));
    let on = canon(m, &[]);
    assert_eq!(on, canon(module(&without), &[]));
    assert_ne!(on, off);
}

/// The rendered errors of a program that must not compile.
fn errors(src: &str) -> String {
    let c = compiled(src);
    assert!(c.has_errors(), "expected an error:\n{src}");
    c.render()
}

#[test]
fn the_dry_run_reports_an_error_in_a_skipped_block() {
    // From X20 Z0 to X20 Z-10 the chord is 10 mm: R4 cannot make it (E4001),
    // though the reference machine starts with the block skipped.
    let out = errors("O0001\nG00 X20 Z0\n/G02 X20 Z-10 R4\nM30\n");
    assert!(out.contains("test.nc:3:1: error[E4001]"), "{out}");
    assert!(out.contains("block-skip switches off"), "{out}");
}

#[test]
fn the_dry_run_follows_a_skipped_block_that_moves() {
    // Without the `/` block the arc starts at X20 (chord 10 ≤ 2 × 6); with
    // it, at X60: chord √(20² + 10²) = 22.36 > 12, E4001 at line 4.
    let out = errors("O0001\nG00 X20 Z0\n/G00 X60\nG02 X20 Z-10 R6\nM30\n");
    assert!(out.contains("test.nc:4:1: error[E4001]"), "{out}");
    // The same arc with a `/` block that leaves it possible compiles.
    let c = compiled("O0001\nG00 X20 Z0\n/G00 X24\nG02 X20 Z-10 R6\nM30\n");
    assert!(!c.has_errors(), "{}", c.render());
}

#[test]
fn a_profile_is_checked_for_both_switch_states() {
    // `/G02` as the ns block of G71 (E2021) is a fault when the switch is
    // off, though the block is skipped at start-up.
    let out = errors(
        "G98 G00 X40 Z2\nG71 U3 R1\nG71 P1 Q2 F0.2\n/N1 G02 X28 Z0 R2\nG00 X28\nN2 G01 Z-10\nM30\n",
    );
    assert!(out.contains("error[E2021]"), "{out}");
    // Every profile block `/`: nothing is left with the switch on (E2020).
    let out = errors("G98 G00 X40 Z2\nG71 U3 R1\nG71 P1 Q2 F0.2\n/N1 G00 X28\n/N2 G01 Z-10\nM30\n");
    assert!(out.contains("error[E2020]"), "{out}");
}
