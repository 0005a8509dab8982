//! The block budget counts every executed block, macro statements alike
//! (machine.md §4): a WHILE at each test, an IF whether or not its THEN or
//! GOTO runs, a GOTO whichever way it jumps, a DO and an END at each pass.
//! Each program's count is worked out by hand below; it runs to its end
//! with `--max-blocks` of exactly that count and stops with E6005 at one
//! less, with the JIT off and forced on alike.

use std::path::PathBuf;
use std::process::Command;

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-budget-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The exit code and last canon line of `src` run with a budget of `max`.
fn run(name: &str, src: &str, max: u64, jit: &str) -> (Option<i32>, String) {
    let d = dir();
    let nc = d.join(format!("{name}.nc"));
    let gbc = d.join(format!("{name}.gbc"));
    std::fs::write(&nc, src).unwrap();
    let c = Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .arg(&nc)
        .arg("-o")
        .arg(&gbc)
        .output()
        .unwrap();
    assert!(c.status.success(), "{}", String::from_utf8_lossy(&c.stderr));
    let r = Command::new(env!("CARGO_BIN_EXE_gbvm"))
        .arg("run")
        .arg(&gbc)
        .args(["--max-blocks", &max.to_string(), &format!("--jit={jit}")])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&r.stdout);
    (
        r.status.code(),
        out.lines().last().unwrap_or("").to_string(),
    )
}

/// (name, program, its executed blocks).
const CASES: &[(&str, &str, u64)] = &[
    // #1=0; WHILE tested 11 times; 10 × (#1=#1+1, END); M30:
    // 1 + 11 + 20 + 1.
    ("while", "#1=0\nWHILE[#1LT10]DO1\n#1=#1+1\nEND1\nM30\n", 33),
    // As above with an IF in the body, its THEN run on 5 of the 10
    // turns: the IF counts on all 10. 1 + 11 + 10 × 3 + 1.
    (
        "if_then",
        "#1=0\nWHILE[#1LT10]DO1\nIF[#1GE5]THEN#2=#1\n#1=#1+1\nEND1\nM30\n",
        43,
    ),
    // A loop closed by IF … GOTO backward (taken 9 times, not the 10th),
    // then a GOTO forward over a G00: #1=0, 10 × (N10, IF), GOTO, M30:
    // 1 + 20 + 1 + 1.
    (
        "gotos",
        "#1=0\nN10#1=#1+1\nIF[#1LT10]GOTO10\nGOTO20\nG00X1\nN20M30\n",
        23,
    ),
    // A bare DO left by IF … GOTO forward on the 10th turn: turns 1–9
    // run DO, #1=, IF, END (36); the 10th DO, #1=, IF (3); with #1=0
    // and M30: 41.
    (
        "do",
        "#1=0\nDO1\n#1=#1+1\nIF[#1GE10]GOTO50\nEND1\nN50M30\n",
        41,
    ),
    // G65 H82 (GOTO when #j ≠ #k) back to N10 9 times, not the 10th:
    // #1=0, 10 × (N10, G65), M30: 1 + 20 + 1.
    ("h82", "#1=0\nN10#1=#1+1\nG65H82P10Q#1R10\nM30\n", 22),
];

#[test]
fn every_executed_block_counts_once() {
    for &(name, src, blocks) in CASES {
        for jit in ["off", "always"] {
            let (code, last) = run(name, src, blocks, jit);
            assert_eq!(code, Some(0), "{name} --jit={jit} with {blocks}: {last}");
            assert_eq!(last, "STOP KIND=M30", "{name} --jit={jit}");
            let (code, last) = run(name, src, blocks - 1, jit);
            assert_eq!(code, Some(2), "{name} --jit={jit} with {}", blocks - 1);
            assert!(last.starts_with("ALARM CODE=6005"), "{name}: {last}");
        }
    }
}
