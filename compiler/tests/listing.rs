//! Golden `gbcc -S` listings: every instruction with its source place.

use compiler::{compile, Options};

fn listing(name: &str, src: &str, optimize: bool) -> String {
    let c = compile(
        name,
        src.as_bytes(),
        &Options {
            optimize,
            ..Options::default()
        },
    );
    assert!(!c.has_errors(), "{}", c.render());
    c.module.expect("module").disassemble()
}

const LOOP: &str = "O0042 (LOOP AND CALL)
N10 #1=0
N20 WHILE[#1LT3]DO1
N30 G01 X[#1*2+10] Z-5 F0.2
N40 #1=#1+1
N50 END1
N60 M98 P20043
N70 M30
O0043
G00 U2
M99
";

#[test]
fn loop_and_subprogram_call() {
    insta::assert_snapshot!(listing("loop.nc", LOOP, true));
}

#[test]
fn folded_and_unfolded_arithmetic() {
    let src = "#1=[2+3]*4\nG00 X[#1/2] Z[SQRT[16]]\nM30\n";
    insta::assert_snapshot!("folded", listing("fold.nc", src, true));
    insta::assert_snapshot!("unfolded", listing("fold.nc", src, false));
}
