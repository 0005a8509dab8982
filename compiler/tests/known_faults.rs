//! W119: an arc of a program with macros that cannot be drawn from the
//! point the compiler knows the tool stands at, whatever path reaches it.

use compiler::{compile, Options};

/// The codes and lines of the diagnostics of `src`, and whether it
/// compiled to a module.
fn diagnostics(src: &str) -> (Vec<(String, usize)>, bool) {
    let c = compile("t.nc", src.as_bytes(), &Options::default());
    let found = c
        .diags
        .iter()
        .map(|(f, d)| {
            let line = c.files[*f].line_col(d.span.start).0;
            (d.code.to_string(), line)
        })
        .collect();
    (found, c.module.is_some())
}

fn w119(src: &str) -> Vec<usize> {
    let (found, compiled) = diagnostics(src);
    assert!(compiled, "{src}: {found:?}");
    found
        .into_iter()
        .filter(|(code, _)| code == "W119")
        .map(|(_, line)| line)
        .collect()
}

#[test]
fn an_arc_that_cannot_close_is_warned_of_and_still_compiles() {
    // From X0 Z0 to X20 Z-30 the half chord is 15.8 mm: R2 cannot reach.
    let src = "#1=1\nG00 X0 Z0\nG02 X20 Z-30 R2\nM30\n";
    assert_eq!(w119(src), [3]);
    let c = compile("t.nc", src.as_bytes(), &Options::default());
    let d = &c.diags[0].1;
    assert!(d.message.contains("E4001"), "{}", d.message);
    // I/K puts the centre at X0 Z-10 (radius 10); the end point X20 Z-30
    // is 22.4 mm from it: off the circle.
    assert_eq!(w119("#1=1\nG00 X0 Z0\nG03 X20 Z-30 I0 K-10\nM30\n"), [3]);
    // A start point computed from values the compiler folds is known.
    assert_eq!(w119("#1=0\nG00 X#1 Z0\nG02 X20 Z-30 R2\nM30\n"), [3]);
}

#[test]
fn no_warning_where_the_arc_can_be_drawn_or_its_start_is_not_known() {
    // R20 reaches.
    assert!(w119("#1=1\nG00 X0 Z0\nG02 X20 Z-30 R20\nM30\n").is_empty());
    // The start point is computed (#500 is kept from run to run: not
    // known to the compiler).
    assert!(w119("G00 X#500 Z0\nG02 X20 Z-30 R2\nM30\n").is_empty());
    // Paths meet from two points.
    let join = "G00 X0 Z0\nIF[#500EQ1]GOTO10\nG00 Z-20\nN10 G02 X20 Z-30 R2\nM30\n";
    assert!(w119(join).is_empty());
    // Compensation bends the path: the kernel decides as it runs.
    assert!(w119("#1=1\nT0101\nG00 X0 Z0\nG42 G01 X2 F1\nG02 X20 Z-30 R2\nM30\n").is_empty());
}

#[test]
fn a_static_program_gets_the_error_itself() {
    let (found, compiled) = diagnostics("G00 X0 Z0\nG02 X20 Z-30 R2\nM30\n");
    assert!(!compiled);
    assert_eq!(found, [("E4001".to_string(), 2)]);
}
