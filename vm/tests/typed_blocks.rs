//! Typed blocks (`block b`): the kernel gets the same words as from the
//! word form (`wordk…` + `exec`), so the canon and the alarms are the
//! same, and an alarm names the typed block's line.

mod common;

use common::{alarm_of, canon_of, run, Asm};

/// Literal flags as the compiler sets them: 2 a literal with a decimal
/// point, 3 one without.
const POINT: u8 = 2;
const NO_POINT: u8 = 3;

/// The same two blocks and M30 in word form or typed.
fn program(typed: bool, blocks: &[&[(char, f64, u8)]]) -> isa::Module {
    let mut a = Asm::new();
    for (i, words) in blocks.iter().enumerate() {
        a.line(i as u32 + 1);
        if typed {
            a.block(words);
        } else {
            for &(letter, value, flags) in words.iter() {
                let k = a.k(value);
                let addr = isa::addr::from_letter(letter).expect("a letter");
                a.op(isa::Instr::WordK { addr, k, flags });
            }
            a.exec();
        }
    }
    a.op(isa::Instr::Halt);
    a.build()
}

#[test]
fn a_typed_block_runs_as_its_words() {
    let blocks: [&[(char, f64, u8)]; 3] = [
        &[
            ('G', 0.0, NO_POINT),
            ('X', 10.0, NO_POINT),
            ('Z', 2.0, NO_POINT),
        ],
        &[
            ('G', 1.0, NO_POINT),
            ('Z', -5.0, NO_POINT),
            ('F', 100.0, NO_POINT),
        ],
        &[('M', 30.0, NO_POINT)],
    ];
    // The canon of `G00 X10 Z2 / G01 Z-5 F100 / M30` on the reference
    // machine (feed per minute at power-on), as canon.md writes it.
    let want = [
        "RAPID X=10 Z=2",
        "FEED F=100 MODE=MIN",
        "LINE X=10 Z=-5",
        "STOP KIND=M30",
    ];
    assert_eq!(canon_of(program(true, &blocks)), want);
    assert_eq!(canon_of(program(false, &blocks)), want);
}

#[test]
fn word_order_is_kept() {
    // M03 then M05 in one block and the reverse: the kernel reads M codes
    // in the order written, so the two differ, typed as in word form.
    for ms in [[3.0, 5.0], [5.0, 3.0]] {
        let blocks: [&[(char, f64, u8)]; 2] = [
            &[('S', 500.0, NO_POINT)],
            &[('M', ms[0], NO_POINT), ('M', ms[1], NO_POINT)],
        ];
        let typed = run(program(true, &blocks));
        let words = run(program(false, &blocks));
        assert_eq!((&typed.0, &typed.1), (&words.0, &words.1), "M{ms:?}");
    }
}

#[test]
fn an_alarm_of_a_typed_block_names_its_line() {
    // An unknown G code: the kernel's alarm, raised by the block on
    // line 2 in either form.
    let blocks: [&[(char, f64, u8)]; 2] = [
        &[('G', 0.0, NO_POINT), ('X', 10.0, POINT), ('Z', 2.0, POINT)],
        &[
            ('G', 1.0, NO_POINT),
            ('X', 10.0, POINT),
            ('G', 999.0, NO_POINT),
        ],
    ];
    let typed = alarm_of(run(program(true, &blocks)).0);
    let words = alarm_of(run(program(false, &blocks)).0);
    assert_eq!((typed.line, typed.col), (2, 1), "{}", typed.header());
    assert_eq!(typed, words);
}
