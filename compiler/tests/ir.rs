//! The IR: what `build` makes of a small program (the expected text is
//! worked out by hand from the rules of `build` and the printer's format,
//! docs/manual.md `--emit=ir`), the validator's findings on IR put
//! together by hand, and every real program's IR valid.

use compiler::ir::{self, Arena, Handle, Loc, Terminator};
use compiler::{compile, compile_ir, Options};
use std::path::Path;

const PROGRAM: &str =
    "#1 = 2\nG98 G01 X#1 Z-[#1 + 1] F100\nIF [#2 GT 0] GOTO 10\nN10 M98 P9000\nM30\nO9000\nM99\n";

/// The printer's line: the text padded to column 44, then the location.
fn line(text: &str, loc: &str) -> String {
    format!("    {text:<40} ; t.nc:{loc}\n")
}

fn printed(opts: &Options) -> String {
    let (c, ir) = compile_ir("t.nc", PROGRAM.as_bytes(), opts);
    assert!(!c.has_errors(), "{}", c.render());
    let ir = ir.expect("the IR of a program that compiles");
    assert_eq!(ir::validate(&ir), Ok(()));
    ir::print::print(&ir, &c.files)
}

/// The expected IR, with the NC block of line 2 as `nc2`.
fn expected(nc2: &str) -> String {
    // Line 3's test branches to a block that only jumps to N10 (the GOTO,
    // a block of its own), or else to one that charges the IF block to
    // the budget and goes on at N10 (the block after the IF); N10's call
    // goes on into the M30 block, which M30 ends; the main program's own
    // end (halt) stands after it, unreached. O9000 is its M99 alone: a
    // program ending in M99 needs no end.
    [
        "function O0000\nbb0:\n".to_string(),
        line("#1 = 2", "1:1"),
        line(nc2, "2:1"),
        line("branch #2 GT 0 then bb1 else bb2", "3:1"),
        "bb1:\n".into(),
        line("goto bb3", "3:1"),
        "bb2:\n".into(),
        line("charge", "3:1"),
        line("follow bb3", "3:1"),
        "bb3:\n".into(),
        line("seq N10", "4:1"),
        line("call m98 O9000 count 1 then bb4", "4:1"),
        "bb4:\n".into(),
        line("nc M30", "5:1"),
        line("ended", "5:1"),
        "bb5:\n".into(),
        line("halt", "5:1"),
        "function O0000\n".replace("0000", "9000") + "bb0:\n",
        line("return", "7:1"),
    ]
    .concat()
}

#[test]
fn a_small_program_prints_as_worked_out_by_hand() {
    // -O1: #1 is known to be 2 on line 2, so X and Z are constants
    // (computed values, printed without a decimal point).
    assert_eq!(
        printed(&Options::default()),
        expected("nc G98 G1 X2 Z-3 F100")
    );
    // -O0: the words stay expressions.
    let o0 = Options {
        optimize: false,
        ..Options::default()
    };
    assert_eq!(printed(&o0), expected("nc G98 G1 X#1 Z[-[#1 + 1]] F100"));
}

#[test]
fn guards_loops_and_macro_a_jumps_are_blocks_and_terminators() {
    let src = "/1 G01 X1\nWHILE [#1 LT 3] DO1\n#1 = #1 + 1\nEND1\nG65 H81 P7 Q#1 R3\nN7 M30\n";
    let (c, ir) = compile_ir("t.nc", src.as_bytes(), &Options::default());
    assert!(!c.has_errors(), "{}", c.render());
    let ir = ir.expect("IR");
    let text = ir::print::print(&ir, &c.files);
    // The guard jumps past the guarded block to the loop head, which the
    // END jumps back to; the head charges the WHILE block, then the test
    // leaves the loop for the G65 block.
    for want in [
        line("skip /1 to bb2 else bb1", "1:1"),
        "bb1:\n".to_string() + &line("move G1 X1", "1:1"),
        "bb2:\n".to_string()
            + &line("charge", "2:1")
            + &line("branch #1 LT 3 then bb3 else bb4", "2:1"),
        "bb3:\n".to_string() + &line("#1 = #1 + 1", "3:1") + &line("jump bb2", "4:1"),
        // (`#1 + 0`: a vacant #1 counts as 0 in the H form, §7.5.)
        "bb4:\n".to_string() + &line("goto N7 if #1 + 0 EQ 3 else bb5", "5:1"),
        "bb5:\n".to_string() + &line("seq N7", "6:1"),
    ] {
        assert!(text.contains(&want), "{want}\nnot in\n{text}");
    }
}

fn loc() -> Loc {
    Loc::default()
}

/// A function of `n` empty blocks laid out in order, each halting.
fn function(n: usize) -> ir::Function {
    let mut f = ir::Function::default();
    for _ in 0..n {
        let b = f.blocks.append(ir::Block {
            ops: Vec::new(),
            term: Some(Terminator::Halt),
        });
        f.term_locs.push(loc());
        f.layout.push(b);
    }
    f
}

fn block(i: usize) -> Handle<ir::Block> {
    Handle::from_index(i).expect("a small index")
}

fn errors(f: ir::Function) -> Vec<String> {
    let m = ir::Module {
        functions: vec![f],
        strings: Vec::new(),
    };
    match ir::validate(&m) {
        Ok(()) => Vec::new(),
        Err(es) => es.into_iter().map(|e| e.message).collect(),
    }
}

fn set_term(f: &mut ir::Function, b: usize, t: Terminator) {
    if let Some(x) = f.blocks.get_mut(block(b)) {
        x.term = Some(t);
    }
}

#[test]
fn the_validator_accepts_sound_ir_and_names_each_fault() {
    assert_eq!(errors(function(2)), Vec::<String>::new());

    // A block without its terminator.
    let mut f = function(2);
    if let Some(x) = f.blocks.get_mut(block(1)) {
        x.term = None;
    }
    assert_eq!(
        errors(f),
        ["O0000 (function 0): block #1 has no terminator"]
    );

    // A fall-through edge to a block that does not come next.
    let mut f = function(3);
    set_term(&mut f, 0, Terminator::Follow(block(2)));
    assert_eq!(
        errors(f),
        ["O0000 (function 0): block #0 goes on into #2, which is not the next block"]
    );

    // A jump to a block that is not laid out, and that block itself.
    let mut f = function(2);
    f.layout.pop();
    set_term(&mut f, 0, Terminator::Jump(block(1)));
    assert_eq!(
        errors(f),
        [
            "O0000 (function 0): block #1 is not laid out",
            "O0000 (function 0): block #0 goes to #1, which is not laid out",
        ]
    );

    // A branch on an expression that is not in the arena, and a call of a
    // function the module does not have.
    let mut f = function(2);
    let cond: Handle<ir::Expr> = Handle::from_index(7).expect("index");
    set_term(
        &mut f,
        0,
        Terminator::Branch {
            cond,
            then: block(1),
            otherwise: block(1),
        },
    );
    let count = f.exprs.append(ir::Expr::Const(1.0));
    let call = ir::Call {
        kind: ir::CallKind::Sub,
        callee: ir::Callee::Program(3),
        count: ir::Count::Expr(count),
        args: Vec::new(),
    };
    let extra = f.blocks.append(ir::Block::default());
    f.term_locs.push(loc());
    f.layout.push(extra);
    set_term(&mut f, 1, Terminator::Call { call, next: extra });
    set_term(&mut f, 2, Terminator::Halt);
    assert_eq!(
        errors(f),
        [
            "O0000 (function 0): expression #7 is not one",
            "O0000 (function 0): a call names function 3, which is not one",
        ]
    );

    // An expression whose operand comes after it (a cycle could hide
    // there), and an operation in two blocks.
    let mut f = function(2);
    let mut exprs: Arena<ir::Expr> = Arena::default();
    let later: Handle<ir::Expr> = Handle::from_index(1).expect("index");
    exprs.append(ir::Expr::Neg(later));
    exprs.append(ir::Expr::Const(1.0));
    f.exprs = exprs;
    let op = f.ops.append(ir::Op::ModalCancel);
    f.op_locs.push(loc());
    for b in [0, 1] {
        if let Some(x) = f.blocks.get_mut(block(b)) {
            x.ops.push(op);
        }
    }
    assert_eq!(
        errors(f),
        [
            "O0000 (function 0): operation #0 stands in two blocks",
            "O0000 (function 0): expression #0 uses #1, which does not come before it",
        ]
    );

    // A typed move with a computed G code (it could be any code). Its
    // computed X is allowed (`execmove`).
    let mut f = function(1);
    let x = f.exprs.append(ir::Expr::Const(1.0));
    for w in [
        ir::Word::new(6, ir::WordValue::Expr(x)),
        ir::Word::new(23, ir::WordValue::Expr(x)),
        ir::Word::new(25, ir::WordValue::Const(-2.0, 0)),
    ] {
        f.words.push(w);
        f.word_spans.push(grammar::Span::default());
    }
    let op = f.ops.append(ir::Op::Nc(ir::NcBlock {
        words: (0, 3),
        kind: ir::NcKind::Move(None),
        msg: None,
    }));
    f.op_locs.push(loc());
    if let Some(x) = f.blocks.get_mut(block(0)) {
        x.ops.push(op);
    }
    assert_eq!(
        errors(f),
        ["O0000 (function 0): a typed move with a computed G code"]
    );
}

/// Every conformance, corpus and example program builds into valid IR
/// (compile validates it: an invalid IR would be E0000).
#[test]
fn every_real_program_builds_into_valid_ir() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        root.join("../../shared/conformance"),
        root.join("../../shared/corpus/public"),
        root.join("../examples"),
    ];
    let mut seen = 0;
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let path = e.path();
            let name = path.to_string_lossy().to_string();
            let program = path
                .extension()
                .is_none_or(|x| x == "nc" || x == "cnc" || x == "txt");
            if !program || name.ends_with("MANIFEST.tsv") || !path.is_file() {
                continue;
            }
            let Ok(bytes) = std::fs::read(&path) else {
                continue;
            };
            let c = compile(&name, &bytes, &Options::default());
            assert!(
                c.diags.iter().all(|(_, d)| d.code != "E0000"),
                "{name}: {}",
                c.render()
            );
            seen += 1;
        }
    }
    assert!(seen >= 100, "only {seen} programs found");
}

#[test]
fn a_packed_count_belongs_to_a_computed_m98_and_subprograms_take_no_arguments() {
    let mut f = function(2);
    let one = f.exprs.append(ir::Expr::Const(1.0));
    let call = ir::Call {
        kind: ir::CallKind::Sub,
        callee: ir::Callee::Program(0),
        count: ir::Count::Packed,
        args: vec![(1, one)],
    };
    set_term(
        &mut f,
        0,
        Terminator::Call {
            call,
            next: block(1),
        },
    );
    assert_eq!(
        errors(f),
        [
            "O0000 (function 0): only a computed M98 P packs its count into P",
            "O0000 (function 0): a subprogram call passes no arguments",
        ]
    );
}
