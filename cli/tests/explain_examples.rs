//! The wrong and right examples of docs/diagnostics.md are real: each
//! wrong example gives its code (when compiled, or when run on the VM) and
//! the right one does not. The few that need another machine than the
//! reference, or the timed runtime, are listed with the reason.

use cli::explain::{entries, Entry};

/// Codes whose examples this test cannot confirm on the reference machine
/// with the VM alone.
const UNCHECKED: &[(&str, &str)] = &[
    (
        "E2061",
        "the argument letters are refused earlier by the parser (E1004, E1006, E2002)",
    ),
    ("E2099", "needs a machine with a C axis"),
    ("E4030", "needs a machine with a Y axis"),
    ("E4033", "needs a machine with a C axis"),
    ("E4036", "needs a nose radius in the tool table"),
    (
        "E6008",
        "the example is the reference's description; the VM does not raise it yet",
    ),
    (
        "E6006",
        "raised by a timed run of gbvm (cli/tests/hardening.rs), not the VM",
    ),
    (
        "W122",
        "needs a program longer than the reference machine's budget of 2 000 000 blocks (compiler/tests/dry_run_budget.rs checks it under a smaller one)",
    ),
    ("E7002", "raised by the interpolation runtime, not the VM"),
    ("E7003", "raised by the interpolation runtime, not the VM"),
    ("E7005", "needs a machine with tool-life groups"),
    ("E7006", "needs a host whose probe does not answer"),
    ("E7007", "needs a recorded thread position"),
    (
        "E7008",
        "a computed parameter number needs a G10 L52 form of the machine",
    ),
];

/// The source of the code block after the `tag` paragraph of an entry.
fn example(e: &Entry, tag: &str) -> Option<String> {
    let body = format!("\n{}", e.body);
    let rest = body.split(&format!("\n{tag}")).nth(1)?;
    let (_, block) = rest.split_once("```\n")?;
    Some(block.split("```").next()?.to_string())
}

/// The codes a program gives: its compile diagnostics, then the alarm of
/// a run on the VM when it compiled (`E5002`, or `505` for a user alarm).
fn codes_of(src: &str) -> Vec<String> {
    let opts = compiler::Options::default();
    let c = compiler::compile("x.nc", src.as_bytes(), &opts);
    let mut codes: Vec<String> = c.diags.iter().map(|(_, d)| d.code.to_string()).collect();
    if let Some(module) = c.module {
        let mut vm = vm::Vm::new(module, opts.machine.clone());
        // E6005's runaway loop needs no two million blocks to show.
        vm.max_blocks = 10_000;
        let mut events: Vec<nc::Event> = Vec::new();
        if let vm::Status::Alarm(a) = vm.run(&mut events) {
            let code = a.code;
            codes.push(match code {
                500..=999 | 3000..=3999 => code.to_string(),
                _ => format!("E{code:04}"),
            });
        }
    }
    codes
}

/// Whether `found` is `code`, or lies in its range (`3000–3999`).
fn matches(code: &str, found: &str) -> bool {
    match code.split_once('–') {
        Some((lo, hi)) => found.parse::<u32>().is_ok_and(|n| {
            lo.parse::<u32>().is_ok_and(|lo| n >= lo) && hi.parse::<u32>().is_ok_and(|hi| n <= hi)
        }),
        None => code == found,
    }
}

#[test]
fn wrong_examples_give_their_code_and_right_ones_do_not() {
    let mut checked = 0;
    for e in entries() {
        let skip = UNCHECKED.iter().any(|(c, _)| *c == e.code);
        if skip || e.body.contains("gbc does not report it yet") {
            continue;
        }
        let wrong = example(e, "Wrong").unwrap_or_else(|| panic!("{}: no wrong example", e.code));
        let right = example(e, "Right").unwrap_or_else(|| panic!("{}: no right example", e.code));
        let w = codes_of(&wrong);
        assert!(
            w.iter().any(|c| matches(e.code, c)),
            "{}: wrong example gives {w:?}",
            e.code
        );
        let r = codes_of(&right);
        assert!(
            !r.iter().any(|c| matches(e.code, c)),
            "{}: right example gives {r:?}",
            e.code
        );
        checked += 1;
    }
    // 107 entries, 14 of them unchecked above.
    assert_eq!(checked, 107 - UNCHECKED.len());
}
