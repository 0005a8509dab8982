//! `gbcc --emit=ir`: the IR listing, in its default file or on standard
//! output; nothing after an error; only `ir` is a value of `--emit`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-emit-ir-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gbcc(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gbcc"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

/// X written with a point keeps it, #1 is unknown (no assignment), M30
/// ends the program (the main program's halt follows, unreached): the
/// listing worked out by hand. The position is unknown where a program
/// starts, and the first block is not a plain move (two G codes) whose
/// end the pass would follow.
const PART: &str = "G98 G01 X10. Z#1 F100\nM30\n";
const LISTING: &str = "function O0000\nbb0:\n    nc G98 G1 X10. Z#1 F100                  ; part.nc:1:1\n        ; modal unknown: position X, position Z\n    nc M30                                   ; part.nc:2:1\n        ; modal unknown: position X, position Z\n    ended                                    ; part.nc:2:1\nbb1:\n    halt                                     ; part.nc:2:1\n";

#[test]
fn the_listing_goes_to_name_dot_ir_or_to_standard_output() {
    let d = dir("ok");
    std::fs::write(d.join("part.nc"), PART).unwrap();
    let out = gbcc(&["part.nc", "--emit=ir", "-q"], &d);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(std::fs::read_to_string(d.join("part.ir")).unwrap(), LISTING);
    assert!(!d.join("part.gbc").exists());
    let out = gbcc(&["part.nc", "--emit", "ir", "-o", "-", "-q"], &d);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&out.stdout), LISTING);
}

#[test]
fn an_error_writes_no_listing_and_other_values_are_usage_errors() {
    let d = dir("err");
    std::fs::write(d.join("bad.nc"), "G01 X1 X2\nM30\n").unwrap();
    let out = gbcc(&["bad.nc", "--emit=ir", "-q"], &d);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("E1011"));
    assert!(!d.join("bad.ir").exists());
    let out = gbcc(&["bad.nc", "--emit=asm"], &d);
    assert_eq!(out.status.code(), Some(1));
}

/// The `modal` pass's notes: a block after a join of G98 and G99 says
/// the feed mode is unknown there (worked out by hand: #1 = 1 is known,
/// but the IF stays a branch at -O0; the first move tells where the tool
/// is, and neither path moves it).
#[test]
fn the_listing_notes_the_modal_groups_not_known() {
    let d = dir("modal");
    std::fs::write(
        d.join("join.nc"),
        "G00 X0 Z0\n#1=1\nIF[#1EQ1]GOTO10\nG99\nN10 G01 X1 F1\nM30\n",
    )
    .unwrap();
    let out = gbcc(&["join.nc", "--emit=ir", "-O0", "-o", "-", "-q"], &d);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.contains("move G1 X1 F1"))
        .expect("the N10 block");
    assert_eq!(lines[at + 1].trim(), "; modal unknown: feed mode");
    // Before G99 everything is known: no note.
    let g99 = lines
        .iter()
        .position(|l| l.contains("nc G99"))
        .expect("G99");
    assert!(!lines[g99 + 1].contains("modal"), "{text}");
}
