//! W124: the alarm a run stops with, told at compile time. A static
//! program's dry run gives it; a program with macros is run in the VM,
//! unless it reads #500–#999 or a variable by a computed number. That run
//! gives the dry run's warnings of the blocks it executes too (W105–W118).
//! Every line and code here is worked out by hand and cross-checked
//! against a run on the VM.

use compiler::{compile, Options};

mod common;
use common::{codes, messages, suite};

/// The alarm (canon code, line) a run on the VM stops with, #500 preset
/// to `v500` (vacant when `None`, as a run without `--vars` has it).
fn vm_alarm(src: &str, opts: &Options, v500: Option<f64>) -> Option<(u32, u32)> {
    let module = compile("p.nc", src.as_bytes(), opts).module;
    let mut vm = vm::Vm::new(module.expect("compiles"), opts.machine.clone());
    if let Some(v) = v500 {
        vm.persistent_mut()[0] = v;
    }
    let mut events: Vec<nc::Event> = Vec::new();
    match vm.run(&mut events) {
        vm::Status::Alarm(a) => Some((a.code, a.line)),
        _ => None,
    }
}

/// The W124 diagnostics as (line, message).
fn w124(src: &str, opts: &Options) -> Vec<(usize, String)> {
    messages(src, opts)
        .into_iter()
        .filter(|(code, ..)| *code == "W124")
        .map(|(_, line, msg)| (line, msg))
        .collect()
}

/// The one diagnostic of `src` and its line.
fn only(src: &str, opts: &Options) -> (grammar::Diagnostic, usize) {
    let c = compile("p.nc", src.as_bytes(), opts);
    let [(f, d)] = &c.diags[..] else {
        panic!("one diagnostic: {}", c.render());
    };
    (d.clone(), c.files[*f].line_col(d.span.start).0)
}

/// One W124, on `line`, for the alarm E`code` (its message the kernel's),
/// and the VM's run stops there with it.
fn told_and_run(src: &str, opts: &Options, code: u32, line: usize) {
    let found = w124(src, opts);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, line);
    let head = format!("the run stops here with E{code}: ");
    assert!(found[0].1.starts_with(&head), "{found:?}");
    assert_eq!(vm_alarm(src, opts, None), Some((code, line as u32)));
}

#[test]
fn a_loop_that_divides_by_zero_is_told_at_its_block() {
    // #1 = 3, 2, 1 move to X20, X30, X60; in the fourth round #1 = 0 and
    // 60/#1 stops the run on line 4.
    let src = "G98 G00 X50 Z2\n#1=3\nWHILE[#1GE0]DO1\nG01 X[60/#1] Z-10 F100\n\
               #1=#1-1\nEND1\nM30\n";
    let opts = Options::default();
    assert_eq!(
        w124(src, &opts),
        [(
            4,
            "the run stops here with E5001: division by zero".to_string()
        )]
    );
    assert_eq!(vm_alarm(src, &opts, None), Some((5001, 4)));
    // Stopping at #1 = 1, the loop never divides by zero.
    let fixed = src.replace("GE0", "GE1");
    assert_eq!(codes(&fixed, &opts), []);
    assert_eq!(vm_alarm(&fixed, &opts, None), None);
}

#[test]
fn the_run_is_not_made_when_its_warning_is_off() {
    // (`gbcc -Wno-W124` and `-w` compile with `predict` off.)
    let src = "G98 G00 X50 Z2\n#1=3\nWHILE[#1GE0]DO1\nG01 X[60/#1] Z-10 F100\n\
               #1=#1-1\nEND1\nM30\n";
    let off = Options {
        predict: false,
        ..Options::default()
    };
    assert_eq!(codes(src, &off), []);
    assert_eq!(codes(src, &Options::default()), [("W124", 4)]);
}

#[test]
fn the_run_decides_where_a_modal_warning_stands() {
    // The first pass over line 3 cuts its thread in G97; line 6 turns G96
    // on and GOTO10 runs line 3 again, now in G96: W110 there, once.
    let src = "#1=0\nG97 S500 M3\nN10 G32 W-10 F1.5\n#1=#1+1\nIF[#1GE2]GOTO30\n\
               G96 S100\nGOTO10\nN30 M30\n";
    let opts = Options::default();
    let w110 = |src: &str| -> Vec<(&str, usize)> {
        let found = codes(src, &opts);
        found.into_iter().filter(|c| c.0 == "W110").collect()
    };
    assert_eq!(w110(src), [("W110", 3)]);
    // Leaving after the first pass, the thread is never cut in G96.
    assert_eq!(w110(&src.replace("GE2", "GE1")), []);
    // Nor is the run made when the program reads #500 (the loop's bound
    // may come from there), or when none of its warnings is reported.
    assert_eq!(w110(&src.replace("#1=0", "#1=#500")), []);
    let off = Options {
        predict: false,
        ..Options::default()
    };
    assert_eq!(codes(src, &off), []);
}

#[test]
fn a_modal_warning_in_a_program_with_macros_names_its_word() {
    // W105 and W114 point at the word (line, column) as the dry run does.
    let src = "#1=20\nG20\nG00 X#1 Z150\nG97 S9000 M3\nM30\n";
    let c = compile("p.nc", src.as_bytes(), &Options::default());
    let at: Vec<(&str, (usize, usize))> = (c.diags.iter())
        .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start)))
        .collect();
    assert_eq!(at, [("W105", (3, 9)), ("W114", (4, 5))]);
}

/// `src` with a macro statement added at its end (before a closing `%`;
/// a DOS end-of-file mark, Ctrl-Z, left out): the same run, no longer
/// static.
fn made_dynamic(src: &str) -> String {
    let body = src.trim_end_matches(|c: char| c.is_whitespace() || c == '\x1a');
    match body.strip_suffix('%') {
        Some(head) => format!("{head}\n#1=1\n%\n"),
        None => format!("{body}\n#1=1\n"),
    }
}

#[test]
fn every_suite_program_made_dynamic_keeps_its_dry_run_warnings() {
    // The dry run of a static program and the compile-time run of the
    // same program with macros find the same warnings: two runs of the
    // kernel, one from the trees, one from the module in the VM. (Not
    // where they stop differently by design: a feed move at F = 0, W107,
    // which the dry run passes and the VM stops at; a dry run out of
    // steps, W120; a run past the block budget, W122.)
    let ran = [
        "W105", "W108", "W110", "W111", "W112", "W114", "W118", "W125", "W126",
    ];
    let of = |c: &compiler::Compiled| -> Vec<(&'static str, usize, usize)> {
        (c.diags.iter())
            .filter(|(_, d)| ran.contains(&d.code))
            .map(|(f, d)| (d.code, *f, c.files[*f].line_col(d.span.start).0))
            .collect()
    };
    let (mut compared, mut warned) = (0, 0);
    for (name, src, machine) in suite() {
        let opts = Options {
            machine,
            ..Options::default()
        };
        let Ok(text) = std::str::from_utf8(&src) else {
            continue;
        };
        let plain = compile(&name, &src, &opts);
        let stops = ["W107", "W120", "W122"];
        if plain.has_errors() || plain.diags.iter().any(|(_, d)| stops.contains(&d.code)) {
            continue;
        }
        let dynamic = compile(&name, made_dynamic(text).as_bytes(), &opts);
        assert!(!dynamic.has_errors(), "{name}: {}", dynamic.render());
        assert_eq!(of(&dynamic), of(&plain), "{name}");
        compared += 1;
        warned += usize::from(!of(&plain).is_empty());
    }
    // (The suite's programs: most compile; several get such warnings.)
    assert!(
        compared > 100 && warned >= 5,
        "{compared} compared, {warned} warned"
    );
}

#[test]
fn a_thread_warning_names_the_thread_block_when_the_program_has_macros() {
    // A thread block's moves wait for the next block and print while it
    // runs; W126 and W118 still name the thread block, in the VM's run as
    // in the dry run. At 3000 rpm (S30003, clamped) a lead of 2 asks Z for
    // 6000 mm/min, above its 5000 (W126); K3 is short of the run-out Z
    // needs to stop (W118). The G34 blocks are lines 5 and 9.
    let src = "O0084\nG97 S30003 M3\nG00 X40 Z5\nX29\nG34 Z-30 F2 R0.1 J1 K3\n\
               G00 X40\nZ5\nX29\nG34 Z-20 F4 R-0.2 J1 K3\nG00 X40\nZ5\nM30\n";
    let at = |src: &str| -> Vec<(&'static str, usize)> {
        let c = compile("p.nc", src.as_bytes(), &Options::default());
        (c.diags.iter())
            .filter(|(_, d)| ["W118", "W126"].contains(&d.code))
            .map(|(f, d)| (d.code, c.files[*f].line_col(d.span.start).0))
            .collect()
    };
    let expected = [("W126", 5), ("W118", 5), ("W126", 9), ("W118", 9)];
    assert_eq!(at(src), expected);
    assert_eq!(at(&made_dynamic(src)), expected);
}

#[test]
fn an_arc_too_small_for_its_chord_in_a_loop_is_told() {
    // Each round draws an arc from r10 Z0 to r20 Z-10 (U20 is 10 mm of
    // radius): its chord is √(10² + 10²) = 14.14 mm. R12 and R8 span it
    // (24 and 16 mm); R4 (8 mm) does not: E4001 on line 4, third round.
    let src = "G98 G00 X20 Z0\n#1=12\nWHILE[#1GT0]DO1\nG02 U20 W-10 R#1 F100\n\
               G00 U-20 W10\n#1=#1-4\nEND1\nM30\n";
    let opts = Options::default();
    told_and_run(src, &opts, 4001, 4);
}

#[test]
fn a_program_alarm_is_told_with_its_number_and_text() {
    // #1 = 60 > 50: `#3000 = 5` stops the run on line 2 with alarm 3005.
    let src = "#1=60\nIF[#1GT50]THEN#3000=5(DIAMETER TOO BIG)\nG00 X#1 Z2\nM30\n";
    let opts = Options::default();
    assert_eq!(
        w124(src, &opts),
        [(
            2,
            "the run stops here with alarm 3005: DIAMETER TOO BIG".to_string()
        )]
    );
    assert_eq!(vm_alarm(src, &opts, None), Some((3005, 2)));
}

#[test]
fn a_program_alarms_text_is_told_as_the_canon_prints_it() {
    // The module keeps the comment as written (UTF-8, an escape byte
    // included); the warning shows it as the canon does, a `?` for each
    // byte outside printable ASCII: é is two.
    let src = "#3000=5(TOO BIG \u{e9} \x1b[31m)\nM30\n";
    assert_eq!(
        w124(src, &Options::default()),
        [(
            1,
            "the run stops here with alarm 3005: TOO BIG ?? ?[31m".to_string()
        )]
    );
}

#[test]
fn a_program_that_reads_persistent_variables_is_not_run() {
    // Without --vars #500 is vacant and 60/#500 divides by zero on line
    // 2; with #500 = 2 kept from an earlier run it does not. The compiler
    // cannot know which, so it says nothing.
    let src = "G98 G00 X50 Z2\n#1=60/#500\nG01 X#1 Z-5 F100\nM30\n";
    let opts = Options::default();
    assert_eq!(codes(src, &opts), []);
    assert_eq!(vm_alarm(src, &opts, None), Some((5001, 2)));
    assert_eq!(vm_alarm(src, &opts, Some(2.0)), None);
}

#[test]
fn a_program_that_reads_persistent_variables_is_run_with_the_values_given() {
    // `gbcc --vars FILE`: the run starts with FILE's #500, as `gbvm run
    // --vars FILE` will: #500 = 0 divides by zero on line 2, #500 = 2 not.
    let src = "G98 G00 X50 Z2\n#1=60/#500\nG01 X#1 Z-5 F100\nM30\n";
    let with = |v500: f64| {
        let mut vars = Box::new([f64::NAN; 500]);
        vars[0] = v500;
        Options {
            vars: Some(vars),
            ..Options::default()
        }
    };
    let (d, line) = only(src, &with(0.0));
    assert_eq!((d.code, line), ("W124", 2));
    assert!(
        d.notes.iter().any(|n| n.contains("--vars")),
        "{:?}",
        d.notes
    );
    assert_eq!(
        vm_alarm(src, &Options::default(), Some(0.0)),
        Some((5001, 2))
    );
    assert_eq!(codes(src, &with(2.0)), []);
}

#[test]
fn a_persistent_variable_preset_with_d_is_known() {
    // `-D '#500=3'` is stored at the main program's start, over what
    // --vars set: #1 runs 3, 2, 1, 0 and line 3 divides by zero.
    let src = "#1=#500\nWHILE[#1GE0]DO1\nG01 X[60/#1] Z-10 F100\n#1=#1-1\nEND1\nM30\n";
    let preset = Options {
        defines: vec![(500, 3.0)],
        ..Options::default()
    };
    told_and_run(src, &preset, 5001, 3);
    // Without it, #500 is --vars's, unknown here.
    assert_eq!(codes(src, &Options::default()), []);
}

#[test]
fn a_macro_body_run_as_the_main_program_gets_a_hint() {
    // O9001 reads its argument A (#1) first: run as the main program #1 is
    // vacant, 60/#1 divides by zero on line 2, and the help says why.
    let src = "O9001\n#2=60/#1\nG01 X#2 Z-5 F100\nM99\n";
    let (d, line) = only(src, &Options::default());
    assert_eq!((d.code, line), ("W124", 2));
    let help = d.help.as_deref().unwrap_or_default();
    assert!(
        help.starts_with("O9001 reads #1 before it sets it"),
        "{help}"
    );
    // Setting #1 first (2, 1, then 0 on the third round), the alarm is
    // told with no such hint.
    let main = "O9001\n#1=2\nWHILE[#1GE0]DO1\n#2=60/#1\nG01 X#2 Z-5 F100\n#1=#1-1\nEND1\nM99\n";
    let (d, line) = only(main, &Options::default());
    assert_eq!((d.code, line), ("W124", 4));
    assert!(d.help.is_none(), "{:?}", d.help);
}

#[test]
fn a_program_that_reads_a_variable_by_a_computed_number_is_not_run() {
    // #[#1] is #500 here: the same doubt.
    let src = "G98 G00 X50 Z2\n#1=500\n#2=60/#[#1]\nG01 X#2 Z-5 F100\nM30\n";
    let opts = Options::default();
    assert_eq!(codes(src, &opts), []);
    assert_eq!(vm_alarm(src, &opts, None), Some((5001, 3)));
}

/// A loop of `rounds` rounds of a move, then a division by zero on
/// line 7.
fn long_loop(rounds: u32) -> String {
    format!(
        "G98 G00 X50 Z2\n#1=0\nWHILE[#1LT{rounds}]DO1\nG01 W-0.001 F100\n#1=#1+1\nEND1\n\
         #2=1/[#1-#1]\nM30\n"
    )
}

#[test]
fn a_run_is_made_for_a_bounded_number_of_instructions() {
    // 1 000 rounds run well inside 200 000 instructions: told on line 7.
    let opts = Options::default();
    let short = long_loop(1000);
    assert_eq!(codes(&short, &opts), [("W124", 7)]);
    assert_eq!(vm_alarm(&short, &opts, None), Some((5001, 7)));
    // 100 000 rounds take more than 200 000 instructions (each round
    // runs its move, its assignment and its test): the run stops short
    // of line 7, and nothing is told, though the VM gets there.
    let long = long_loop(100_000);
    assert_eq!(codes(&long, &opts), []);
    assert_eq!(vm_alarm(&long, &opts, None), Some((5001, 7)));
}

#[test]
fn the_run_is_the_one_the_machine_file_makes() {
    // Host input 0 (#1000) is what the machine file says: off on the
    // reference machine, where line 1 raises alarm 3001; on, no alarm.
    let src = "IF[#1000EQ0]THEN#3000=1(DOOR OPEN)\nG00 X50 Z2\nM30\n";
    let reference = Options::default();
    assert_eq!(codes(src, &reference), [("W124", 1)]);
    assert_eq!(vm_alarm(src, &reference, None), Some((3001, 1)));
    let mut door_shut = Options::default();
    door_shut.machine.host.inputs = 1;
    assert_eq!(codes(src, &door_shut), []);
    assert_eq!(vm_alarm(src, &door_shut, None), None);
    // Block skip: the reference machine has every switch on, so the `/`
    // block is skipped; with the switches off it runs and alarms.
    let src = "#1=1\n/#3000=2(SKIP OFF)\nG00 X50 Z2\nM30\n";
    assert_eq!(codes(src, &reference), []);
    assert_eq!(vm_alarm(src, &reference, None), None);
    let mut switches_off = Options::default();
    *switches_off.machine.operator.block_skip = [false; 9];
    assert_eq!(codes(src, &switches_off), [("W124", 2)]);
    assert_eq!(vm_alarm(src, &switches_off, None), Some((3002, 2)));
}

#[test]
fn a_static_program_s_run_time_fault_is_told_by_its_dry_run() {
    // G22 forbids X-100…100, Z-100…100 (machine coordinates, the
    // reference machine's zero): the rapid to X20 Z2 on line 3 ends in it.
    // Compiled whole, and a few bytes at a time (`compiler::stream`).
    let src = "O0001\nG22 X100 Z100 I-100 K-100\nG00 X20 Z2\nG00 X300\nM30\n";
    for chunk_bytes in [usize::MAX, 16] {
        let opts = Options {
            chunk_bytes,
            ..Options::default()
        };
        let chunked = compiler::stream::compile("p.nc", &src.as_bytes().into(), &opts);
        assert_eq!(chunked.is_some(), chunk_bytes == 16);
        told_and_run(src, &opts, 7002, 3);
    }
}

#[test]
fn an_alarm_another_warning_names_is_not_told_twice() {
    // Folding proves 1/0 faults whenever line 2 runs (W116); the run
    // stops there, which W116 already says.
    let src = "G98 G00 X50 Z2\n#1=1/0\nM30\n";
    let opts = Options::default();
    assert_eq!(codes(src, &opts), [("W116", 2)]);
    assert_eq!(vm_alarm(src, &opts, None), Some((5001, 2)));
}

#[test]
fn a_cycle_longer_than_the_prediction_is_not_an_alarm() {
    // Passes of 0.001 mm from r100 to r0: 100 000 passes of 4 moves,
    // 400 000 legs, past the 200 000 or so blocks the prediction may
    // charge. The machine's budget (2 000 000) holds them: no warning,
    // though a run under the prediction's budget would stop with E6005.
    let src = "G98 G00 X200 Z2\n#1=0.001\nG71 U#1 R0.5\nG71 P10 Q20 U0 W0 F100\n\
               N10 G00 X0\nG01 Z-20\nN20 X200\nM30\n";
    let opts = Options::default();
    assert_eq!(codes(src, &opts), []);
    assert_eq!(vm_alarm(src, &opts, None), None);
    let mut small = Options::default();
    small.machine.run.max_blocks = 200_100;
    assert_eq!(vm_alarm(src, &small, None), Some((6005, 4)));
}

#[test]
fn an_alarm_in_a_library_program_is_told_in_its_file() {
    // O9010 (found with -I) divides 60 by its A; the main program calls
    // it with A = 2, 1, 0: the third call stops the run on O9010's line 2.
    let dir = std::env::temp_dir().join(format!("gbc-predict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let library = "O9010\n#2=60/#1\nG01 X#2 Z-5 F100\nM99\n";
    std::fs::write(dir.join("O9010.nc"), library).expect("the library program");
    let opts = Options {
        include: vec![dir.clone()],
        ..Options::default()
    };
    let src = "G98 G00 X50 Z2\n#5=2\nWHILE[#5GE0]DO1\nG65 P9010 A#5\n#5=#5-1\nEND1\nM30\n";
    let c = compile("p.nc", src.as_bytes(), &opts);
    let told: Vec<(&str, usize, &str)> = c
        .diags
        .iter()
        .map(|(f, d)| {
            let file = &c.files[*f];
            (file.name.as_str(), file.line_col(d.span.start).0, d.code)
        })
        .collect();
    let library_name = dir.join("O9010.nc").display().to_string();
    assert_eq!(told, [(library_name.as_str(), 2, "W124")]);
    let mut vm = vm::Vm::new(c.module.expect("compiles"), opts.machine.clone());
    let mut events: Vec<nc::Event> = Vec::new();
    let vm::Status::Alarm(a) = vm.run(&mut events) else {
        panic!("the run ends without an alarm");
    };
    assert_eq!(
        (a.code, a.file.as_str(), a.line),
        (5001, library_name.as_str(), 2)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_static_program_tells_the_user_alarm_its_run_stops_at() {
    // `G65 H99` ends the dry run of a static program: the alarm it raises
    // is told there (line 3), as the compile-time run of a program with
    // macros tells it, with the message the run prints.
    let src = "G00 X20 Z2\nG01 Z-5 F100\nG65 H99 Q7 (SPINDLE NOT READY)\nG00 X30\nM30\n";
    for (src, line) in [(src.to_string(), 3), (format!("#1=1\n{src}"), 4)] {
        let c = compile("p.nc", src.as_bytes(), &Options::default());
        let found: Vec<_> = (c.diags.iter())
            .map(|(f, d)| {
                (
                    d.code,
                    c.files[*f].line_col(d.span.start).0,
                    d.message.clone(),
                )
            })
            .collect();
        let msg = "the run stops here with alarm 507: SPINDLE NOT READY".to_string();
        assert_eq!(found, [("W124", line, msg)], "{src}");
    }
}
