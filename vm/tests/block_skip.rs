//! Block delete as a live switch: a `skipblock` guard reads the switch
//! when the VM reaches the block, so a change decides for the blocks read
//! after it and for none read before.

mod common;

use common::{vm, Asm, Canon};
use isa::{Instr, Module};
use vm::Status;

/// `G00 X1`, `/G00 X2`, `/3 G00 X3`, `G00 X4`, `M30`: the guarded blocks
/// on switches 1 and 3.
fn guarded() -> Module {
    let mut a = Asm::new();
    let mut guards = Vec::new();
    for (x, switch) in [(1.0, None), (2.0, Some(1)), (3.0, Some(3)), (4.0, None)] {
        let guard = switch.map(|s| {
            (
                s,
                a.op(Instr::SkipBlock {
                    switch: s,
                    target: 0,
                }),
            )
        });
        a.word('G', 0.0);
        a.word('X', x);
        a.exec();
        guards.extend(guard.map(|(s, pc)| (s, pc, a.here())));
    }
    a.word('M', 30.0);
    a.exec();
    a.op(Instr::Halt);
    for (switch, pc, target) in guards {
        a.set(pc, Instr::SkipBlock { switch, target });
    }
    a.build()
}

/// The X of each RAPID line of a canon.
fn rapids(canon: &[String]) -> Vec<String> {
    canon
        .iter()
        .filter(|l| l.starts_with("RAPID"))
        .map(|l| l.split(' ').nth(1).unwrap_or_default().to_string())
        .collect()
}

#[test]
fn the_machine_file_gives_the_starting_state() {
    // The reference machine has every switch on: both guarded blocks go.
    let mut on = vm(guarded());
    let mut canon = Canon::default();
    assert_eq!(on.run(&mut canon), Status::Done);
    assert_eq!(rapids(&canon.0), ["X=1", "X=4"]);

    let mut off = vm(guarded());
    for n in 1..=9 {
        off.set_block_skip(n, false);
    }
    let mut canon = Canon::default();
    assert_eq!(off.run(&mut canon), Status::Done);
    assert_eq!(rapids(&canon.0), ["X=1", "X=2", "X=3", "X=4"]);
}

#[test]
fn each_guard_reads_its_own_switch() {
    // Switch 1 off, switch 3 on: `/` runs, `/3` is skipped.
    let mut m = vm(guarded());
    m.set_block_skip(1, false);
    assert!(!m.block_skip(1) && m.block_skip(3));
    let mut canon = Canon::default();
    assert_eq!(m.run(&mut canon), Status::Done);
    assert_eq!(rapids(&canon.0), ["X=1", "X=2", "X=4"]);
}

#[test]
fn a_change_decides_for_the_blocks_read_after_it() {
    // Switch 1 on while the VM reads `G00 X1` (the first event), then off:
    // the `/G00 X2` read next runs; switch 3 stays on.
    let mut m = vm(guarded());
    let mut canon = Canon::default();
    assert_eq!(m.step(1000, &mut canon), Status::Event);
    m.set_block_skip(1, false);
    assert_eq!(m.run(&mut canon), Status::Done);
    assert_eq!(rapids(&canon.0), ["X=1", "X=2", "X=4"]);
}

#[test]
fn switch_numbers_outside_one_to_nine_name_no_switch() {
    let mut m = vm(guarded());
    m.set_block_skip(0, false);
    m.set_block_skip(10, false);
    assert!((1..=9).all(|n| m.block_skip(n)));
    assert!(!m.block_skip(0) && !m.block_skip(10));
}
