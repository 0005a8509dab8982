//! Radius programming (machine.md `axes.x.diameter = false`, №001.2 = 0):
//! the program's X values are radii. A program written on the diameter
//! and the same program with every X value halved, run in radius
//! programming, make the same moves; the variables that read or write an
//! X value read and write radii (docs/language.md, "Radius programming").

mod common;

use common::suite;
use compiler::{compile, Options};
use nc::machine::DecimalPoint;
use nc::{Event, Machine};
use vm::{Status, Vm};

/// A machine like `m`, programmed on the radius.
fn on_radius(m: &Machine) -> Machine {
    let mut m = m.clone();
    m.axes.x.diameter = false;
    m
}

/// The canon of a run of `src` on `machine`, how it ended and the VM
/// after it; the diagnostics where it does not compile.
fn run(src: &str, machine: &Machine) -> Result<(Vec<String>, Status, Vm), String> {
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    let c = compile("p.nc", src.as_bytes(), &opts);
    let module = match c.module {
        Some(module) if !c.has_errors() => module,
        _ => return Err(c.render()),
    };
    let mut vm = Vm::new(module, machine.clone());
    let mut events: Vec<Event> = Vec::new();
    let status = vm.run(&mut events);
    Ok((events.iter().map(|e| e.to_string()).collect(), status, vm))
}

/// `src` with its X values halved: X and U words, and the I of G22 and
/// G05.1; not a
/// dwell's X/U (seconds) nor the radial U of a G71/G73 first block (one
/// without P). `None` for a line this cannot rewrite (a macro statement,
/// a call's arguments, G16's polar radius).
fn halved(src: &str) -> Option<String> {
    let mut out = String::new();
    // (Each line with its own end: a DOS end-of-file mark stays last.)
    for line in src.split_inclusive('\n') {
        out.push_str(&halve_line(line)?);
    }
    Some(out)
}

/// One block of `halved`.
fn halve_line(line: &str) -> Option<String> {
    let code = without_comments(line).to_ascii_uppercase();
    if code.contains('#') || ["G65", "G66", "G16"].iter().any(|g| code.contains(g)) {
        return None;
    }
    let has_g = |g: &str| words(&code).any(|(l, n)| l == 'G' && n == g);
    let dwell = has_g("04") || has_g("4");
    let first_block = ["71", "73"].iter().any(|g| has_g(g)) && !code.contains('P');
    // (I is an X value on G22 and G05.1, a radial distance elsewhere.)
    let x_i = has_g("22") || has_g("05.1") || has_g("5.1");
    let mut out = String::new();
    let mut chars = line.char_indices().peekable();
    let mut depth = 0;
    while let Some((i, c)) = chars.next() {
        out.push(c);
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            _ => {}
        }
        let letter = c.to_ascii_uppercase();
        let halve = match letter {
            'X' => !dwell,
            'U' => !dwell && !first_block,
            'I' => x_i,
            _ => false,
        };
        if depth > 0 || !halve {
            continue;
        }
        let number: String = line[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+'))
            .collect();
        let v: f64 = number.parse().ok()?;
        out.push_str(&format!("{}", v / 2.0));
        for _ in 0..number.chars().count() {
            chars.next();
        }
    }
    Some(out)
}

/// A block's text outside its comments.
fn without_comments(line: &str) -> String {
    let mut depth = 0;
    line.chars()
        .filter(|&c| {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                _ => return depth == 0,
            }
            false
        })
        .collect()
}

/// The (letter, digits) of a block's words (no comment in `code`).
fn words(code: &str) -> impl Iterator<Item = (char, String)> + '_ {
    code.char_indices()
        .filter(|(_, c)| c.is_ascii_alphabetic())
        .map(move |(i, c)| {
            let n = code[i + 1..]
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            (c, n)
        })
}

/// Programs with the X words the suite does not have: G53, G52, angle
/// programming, G36, G22's area, G05.1, G12.1, G7.1 and a drilling cycle
/// along X.
fn more() -> Vec<(String, Vec<u8>, Machine)> {
    let c_axis = Machine::from_toml("[axes.c]\nenabled = true\n").expect("a machine file");
    let programs = [
        "G00 X100 Z50\nG53 X-40 Z-20\nG00 X60 Z10\nG52 X10 Z-5\nG00 X40 Z0\nG52 X0 Z0\n\
         G01 X30 Q150000 F100\nG01 U-6 ,A160\nQ170000\nX10 Z-60 Q135000\nG00 X80 Z20\nM30\n",
        // (The move into G22's area stops the run: the same alarm.)
        "T0101\nG00 X50 Z5\nG36 X40\nG00 X80 Z20\nG22 X100 Z50 I-20 K-60\nG00 X90 Z10\nM30\n",
        "G00 X40 Z0\nG05.1 X60 Z-20 I56 K-8 F100\nG05 X40 Z-40 I-4 K-10\nM30\n",
        "G00 X60 Z5 C0\nG12.1\nG01 X20 C10 F100\nX-20 C10\nG13.1\nG00 X60 Z5\nG7.1 C30\n\
         G01 Z-10 C20 F100\nX50\nG7.1 C0\nG00 X80 Z10\nG87 X20 C0 Z-5 R2 F50\nG80\nM30\n",
    ];
    let reference = Machine::reference;
    let machines = [reference(), reference(), reference(), c_axis];
    (programs.iter().zip(machines).enumerate())
        .map(|(i, (src, m))| (format!("more {i}"), src.as_bytes().to_vec(), m))
        .collect()
}

#[test]
fn halving_a_program_s_x_values_gives_the_same_moves_on_the_radius() {
    let (mut compared, mut moved, mut extra) = (0, 0, 0);
    for (name, src, machine) in suite().into_iter().chain(more()) {
        let Ok(text) = std::str::from_utf8(&src) else {
            continue;
        };
        // (Without a decimal point, an increment-mode X5 is 5 µm: its
        // half has no literal of its own.)
        if machine.machine.decimal_point == DecimalPoint::Increment {
            continue;
        }
        let (Some(half), Ok((canon, status, _))) = (halved(text), run(text, &machine)) else {
            continue;
        };
        let (radius, radius_status, _) = run(&half, &on_radius(&machine))
            .unwrap_or_else(|e| panic!("{name} halved does not compile:\n{e}"));
        assert_eq!(radius, canon, "{name}");
        assert_eq!(
            format!("{radius_status:?}"),
            format!("{status:?}"),
            "{name}"
        );
        compared += 1;
        moved += usize::from(canon.iter().any(|l| l.contains(" X=")));
        extra += usize::from(name.starts_with("more "));
    }
    // (Most suite programs are static and compile.)
    assert!(
        compared > 80 && moved > 80 && extra == 4,
        "{compared} compared, {moved} moved X, {extra} of `more`"
    );
}

#[test]
fn the_halving_leaves_dwells_and_radial_words_alone() {
    // The test's own rewriting, checked by hand.
    let src =
        "G04 X1.5\nG71 U2 R1\nG71 P1 Q2 U0.5 W0.1\nG22 X100 Z50 I-20 K-10\nG01 X21 U-3 (X8)\n";
    let want =
        "G04 X1.5\nG71 U2 R1\nG71 P1 Q2 U0.25 W0.1\nG22 X50 Z50 I-10 K-10\nG01 X10.5 U-1.5 (X8)\n";
    assert_eq!(halved(src).as_deref(), Some(want));
    assert_eq!(halved("#1=2\nG00 X#1\n"), None);
}

#[test]
fn x_variables_read_and_write_radii() {
    // The machine file keeps tool offsets on the diameter (machine.md):
    // geometry X -6 is a radius of -3. G54's X 10 (a radius) is a work
    // zero 20 mm of diameter from the machine's.
    let mut m = on_radius(&Machine::reference());
    let file = "[axes.x]\ndiameter = false\n[[tools.offset]]\nnumber = 1\nx = -6.0\n";
    m.tools = Machine::from_toml(file).expect("a machine file").tools;
    let src = "T0101\nG00 X20 Z5\n#1=#5001\n#2=#2701\n#2001=0.5\n#3=#2001\n#8=#5081\n\
               #5221=10\n#4=#5001\n#5=#5021\nG31 U-4 F100\n#6=#5061\n#7=#995\n#9=#5041\nM30\n";
    let (canon, status, vm) = run(src, &m).expect("compiles");
    assert!(matches!(status, Status::Done), "{status:?}");
    let var = |n| vm.variable(n).expect("a variable");
    // X20 is 20 of radius; the offset reads -3, the wear written 0.5 reads
    // 0.5 back (1 mm of diameter in the table); the active offset is
    // their sum, -5 of diameter.
    assert_eq!((var(1), var(2), var(3), var(8)), (20.0, -3.0, 0.5, -2.5));
    // The tool stays where it is on the machine: 20 of radius there, 10
    // from the new zero.
    assert_eq!((var(4), var(5)), (10.0, 20.0));
    // G31 U-4 without a skip signal ends at 6 of radius: the skip
    // position, #995 and the current position read it.
    assert_eq!((var(6), var(7), var(9)), (6.0, 6.0, 6.0));
    // The canon prints diameters: the move to X40 (T0101's offset acts
    // on the machine side), the work zero at X20 of diameter.
    assert!(canon.iter().any(|l| l == "RAPID X=40 Z=5"), "{canon:?}");
    assert!(canon.iter().any(|l| l == "ORIGIN X=20 Z=0"), "{canon:?}");
}

#[test]
fn g10_l52_switches_between_diameter_and_radius() {
    // №001.2 = 0 (bit 2 off): the X words that follow are radii; set
    // again, diameters.
    let src = "G00 X20 Z5\nG10 L52\nN1 W00000000\nG11\nG00 X20\n\
               G10 L52\nN1 W00000100\nG11\nG00 X20\nM30\n";
    let (canon, _, _) = run(src, &Machine::reference()).expect("compiles");
    let xs: Vec<&str> = canon
        .iter()
        .filter(|l| l.starts_with("RAPID"))
        .map(String::as_str)
        .collect();
    assert_eq!(xs, ["RAPID X=20 Z=5", "RAPID X=40 Z=5", "RAPID X=20 Z=5"]);
}
