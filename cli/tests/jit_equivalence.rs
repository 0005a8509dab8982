//! The loop JIT changes no output: every conformance program (with its
//! machine file), every public corpus program and every example that
//! compiles prints, with `gbvm run --jit=always` (every loop compiled at
//! its first round), the same canon, byte for byte, and ends with the same
//! exit status as with `--jit=off`. A few macro programs written here make
//! sure compiled code really runs in the comparison (`--stats` says how
//! many loops were compiled).

mod cases;

use cases::{conformance_cases, corpus_cases, example_cases, Case};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(bin: &str, args: &[&str]) -> Output {
    Command::new(bin).args(args).output().unwrap()
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gbc-jit-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn machine_args(machine: &Option<PathBuf>) -> Vec<String> {
    match machine {
        Some(m) => vec!["--machine".into(), m.display().to_string()],
        None => Vec::new(),
    }
}

/// The canon and exit code of a run with `--jit=MODE` (and any `extra`
/// arguments).
fn canon(gbc: &Path, case: &Case, mode: &str, extra: &[&str]) -> (String, Option<i32>) {
    let mut args: Vec<String> = vec!["run".into(), gbc.display().to_string()];
    args.push(format!("--jit={mode}"));
    args.extend(machine_args(&case.machine));
    args.extend(extra.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = run(env!("CARGO_BIN_EXE_gbvm"), &args);
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        out.status.code(),
    )
}

/// Whether the case compiled, and whether both runs agree (else why not).
fn check(case: &Case, dir: &Path) -> Option<Result<(), String>> {
    let gbc = dir.join(format!("{}.gbc", case.name.replace('/', "_")));
    let mut args = vec![case.src.display().to_string(), "-q".into(), "-o".into()];
    args.push(gbc.display().to_string());
    args.extend(machine_args(&case.machine));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    if !run(env!("CARGO_BIN_EXE_gbcc"), &args).status.success() {
        return None;
    }
    let off = canon(&gbc, case, "off", &[]);
    let on = canon(&gbc, case, "always", &[]);
    Some(match off == on {
        true => Ok(()),
        false => Err(format!(
            "{}: off {:?} / always {:?}",
            case.name, off.1, on.1
        )),
    })
}

#[test]
fn every_program_prints_the_same_canon_with_its_loops_compiled() {
    let dir = scratch("all");
    let mut cases = conformance_cases();
    cases.extend(corpus_cases(&dir));
    cases.extend(example_cases());
    let (mut same, mut wrong) = (0, Vec::new());
    for case in &cases {
        match check(case, &dir) {
            None => {}
            Some(Ok(())) => same += 1,
            Some(Err(why)) => wrong.push(why),
        }
    }
    eprintln!("{same} programs the same");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // The examples at least; with ../shared beside the repository, the
    // 112 programs of expand_equivalence.rs and the example.
    let expected = if cases.len() > example_cases().len() {
        113
    } else {
        1
    };
    assert!(same >= expected, "only {same} programs compared");
    let _ = std::fs::remove_dir_all(dir);
}

/// Macro loops that compile (a contour by points, nested loops, a GOTO
/// loop with an alarm inside, a loop that uses up the block budget): the
/// same canon and exit, and `--stats` shows the JIT compiled them.
#[test]
fn macro_loops_run_compiled_and_print_the_same() {
    let dir = scratch("loops");
    let programs = [
        // An ellipse by points: a move with computed words every round.
        "#1=40\n#2=20\n#3=0\nG00 X80 Z0\nWHILE[#3LE360]DO1\nG01 X[2*#1*COS[#3]] Z[#2*SIN[#3]-20] F0.1\n#3=#3+5\nEND1\nM30\n",
        // Nested loops and an IF in the inner one.
        "#1=0\nG00 X50 Z2\nWHILE[#1LT5]DO1\n#2=0\nWHILE[#2LT4]DO2\nIF[[#1+#2]MOD2EQ0]THEN#3=#3+#2\n#2=#2+1\nEND2\nG01 X[40-#1] Z[-#3] F0.2\n#1=#1+1\nEND1\nM30\n",
        // A GOTO loop that ends on a domain alarm (E5002) in its 6th round.
        "#1=5\nG00 X50 Z2\nN10 #2=SQRT[#1]\nG01 X[40+#2] Z-1 F0.2\n#1=#1-1\nIF[#1GT-3]GOTO10\nM30\n",
    ];
    for (i, src) in programs.iter().enumerate() {
        let path = dir.join(format!("p{i}.nc"));
        std::fs::write(&path, src).unwrap();
        let case = Case {
            name: format!("loop{i}"),
            src: path,
            machine: None,
        };
        assert_eq!(check(&case, &dir), Some(Ok(())), "{src}");
        let gbc = dir.join(format!("loop{i}.gbc"));
        let (stats, _) = canon(&gbc, &case, "always", &["--stats"]);
        assert!(stats.contains("jit: "), "no loop compiled:\n{src}\n{stats}");
        if i == 0 {
            // 73 rounds (#3 = 0, 5 … 360): the first interpreted up to the
            // backward jump that compiles the loop; the code then runs the
            // other 72 moves by its direct call into the kernel, entered
            // at that jump and after each of its moves but the last.
            assert!(
                stats.contains("code entered 73 times, 72 blocks run from it"),
                "{stats}"
            );
            // 72 rounds of about 30 instructions: far from the million
            // after which a loop is compiled again, optimised.
            assert!(!stats.contains("optimised"), "{stats}");
        }
    }
    // The block budget used up inside compiled code: the same E6005 at the
    // same line, after the same moves.
    let case = Case {
        name: "loop0".into(),
        src: dir.join("p0.nc"),
        machine: None,
    };
    let gbc = dir.join("loop0.gbc");
    let off = canon(&gbc, &case, "off", &["--max-blocks", "40"]);
    let on = canon(&gbc, &case, "always", &["--max-blocks", "40"]);
    assert!(off.0.contains("ALARM CODE=6005"), "{}", off.0);
    assert_eq!(off, on);
    let _ = std::fs::remove_dir_all(dir);
}

/// A loop that runs long is compiled twice under `--jit=auto`: quickly at
/// its 500th round, and again with the optimiser once that code has run a
/// million instructions (37 a round: past the 27 500th round of 40 000);
/// the canon and every variable printed are those of the interpreter. Not
/// so a loop that runs a block every few instructions.
#[test]
fn a_long_loop_is_compiled_again_optimised_and_prints_the_same() {
    let dir = scratch("long");
    let src = "#1=0\n#2=0\n#3=0\nWHILE[#1LT40000]DO1\n#4=#1*0.001\n\
               #2=#2+SIN[#4]*0.5-#4*0.01\nIF[#2LT-100]THEN#2=#2+100\n\
               #3=#3+SQRT[ABS[#2]]/[#1+1]-FIX[#4]\n#1=#1+1\nEND1\n\
               G00 X[#2] Z[-#3]\nM30\n";
    let path = dir.join("long.nc");
    std::fs::write(&path, src).unwrap();
    let case = Case {
        name: "long".into(),
        src: path,
        machine: None,
    };
    assert_eq!(check(&case, &dir), Some(Ok(())), "{src}");
    let gbc = dir.join("long.gbc");
    let off = canon(&gbc, &case, "off", &[]);
    let auto = canon(&gbc, &case, "auto", &[]);
    assert_eq!(off, auto);
    let (stats, _) = canon(&gbc, &case, "auto", &["--stats"]);
    assert!(
        stats.contains("jit: 1 loops compiled (1 again, optimised)"),
        "{stats}"
    );
    // A long loop that runs a move every round (13 instructions) spends
    // its time in the kernel: it keeps its quick code.
    let src = "#1=0\nG00 X50 Z2\nWHILE[#1LT120000]DO1\n#2=#1*0.001\n\
               #1=#1+1\nG01 X[50-#2] Z[-#2] F100\nEND1\nM30\n";
    std::fs::write(dir.join("moves.nc"), src).unwrap();
    let case = Case {
        name: "moves".into(),
        src: dir.join("moves.nc"),
        machine: None,
    };
    assert_eq!(check(&case, &dir), Some(Ok(())), "{src}");
    let (stats, _) = canon(&dir.join("moves.gbc"), &case, "auto", &["--stats"]);
    assert!(stats.contains("jit: 1 loops compiled in"), "{stats}");
    let _ = std::fs::remove_dir_all(dir);
}
