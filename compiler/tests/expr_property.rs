//! The VM's expression evaluation against a small reference evaluator
//! written here from dialect.md §7.4–§7.6 (random expressions, vacant
//! operands included). Compiled with -O0 so the VM, not the folder,
//! computes; a second run with folding must agree bit for bit.

use compiler::{compile, Options};
use nc::Machine;
use proptest::prelude::*;
use vm::Vm;

/// #1 = 2.5, #2 = -4, #3 vacant.
const SETUP: &str = "#1=2.5\n#2=-4\n";

#[derive(Debug, Clone)]
enum E {
    Num(f64),
    Var(u8),
    Neg(Box<E>),
    Bin(&'static str, Box<E>, Box<E>),
    Fun(&'static str, Box<E>),
}

impl E {
    fn text(&self) -> String {
        match self {
            E::Num(v) => format!("{v}"),
            E::Var(n) => format!("#{n}"),
            E::Neg(a) => format!("[-{}]", a.text()),
            E::Bin(op, a, b) => format!("[{}{}{}]", a.text(), op, b.text()),
            E::Fun(f, a) => format!("{f}[{}]", a.text()),
        }
    }
}

/// The reference: `Ok(None)` is vacant, `Err(code)` an alarm.
fn eval(e: &E) -> Result<Option<f64>, u16> {
    let z = |v: Option<f64>| v.unwrap_or(0.0);
    let round = |v: f64| {
        if v < 0.0 {
            -((-v) + 0.5).floor()
        } else {
            (v + 0.5).floor()
        }
    };
    let r = match e {
        E::Num(v) => *v,
        E::Var(1) => 2.5,
        E::Var(2) => -4.0,
        E::Var(_) => return Ok(None),
        E::Neg(a) => -z(eval(a)?),
        E::Bin(op, a, b) => {
            let (x, y) = (z(eval(a)?), z(eval(b)?));
            match *op {
                "+" => x + y,
                "-" => x - y,
                "*" => x * y,
                "/" if y == 0.0 => return Err(5001),
                "/" => x / y,
                "MOD" => {
                    let (i, j) = (round(x) as i64, round(y) as i64);
                    if j == 0 {
                        return Err(5001);
                    }
                    (i % j) as f64
                }
                "AND" => (round(x) as i64 & round(y) as i64) as f64,
                "OR" => (round(x) as i64 | round(y) as i64) as f64,
                _ => (round(x) as i64 ^ round(y) as i64) as f64,
            }
        }
        E::Fun(f, a) => {
            let x = z(eval(a)?);
            match *f {
                "ABS" => x.abs(),
                "SQRT" if x < 0.0 => return Err(5002),
                "SQRT" => x.sqrt(),
                "ROUND" => round(x),
                "FIX" => x.trunc(),
                "FUP" => x.signum() * x.abs().ceil(),
                "SIN" => x.to_radians().sin(),
                _ => x.to_radians().cos(),
            }
        }
    };
    if !r.is_finite() {
        return Err(5006);
    }
    Ok(Some(if r == 0.0 { 0.0 } else { r }))
}

fn expr() -> impl Strategy<Value = E> {
    let leaf = prop_oneof![
        (-20i32..20).prop_map(|v| E::Num(v as f64)),
        (-2000i32..2000).prop_map(|v| E::Num(v as f64 / 100.0)),
        (1u8..=3).prop_map(E::Var),
    ];
    leaf.prop_recursive(5, 40, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|a| E::Neg(Box::new(a))),
            (
                prop::sample::select(vec!["+", "-", "*", "/", "MOD", "AND", "OR", "XOR"]),
                inner.clone(),
                inner.clone()
            )
                .prop_map(|(op, a, b)| E::Bin(op, Box::new(a), Box::new(b))),
            (
                prop::sample::select(vec!["ABS", "SQRT", "ROUND", "FIX", "FUP", "SIN", "COS"]),
                inner
            )
                .prop_map(|(f, a)| E::Fun(f, Box::new(a))),
        ]
    })
}

/// Runs `#100 = e` and reads #100, or the alarm code.
fn run(e: &E, optimize: bool) -> Result<f64, u16> {
    let src = format!("{SETUP}#100={}\nM30\n", e.text());
    let c = compile(
        "p.nc",
        src.as_bytes(),
        &Options {
            optimize,
            ..Options::default()
        },
    );
    assert!(!c.has_errors(), "{src}: {}", c.render());
    let mut vm = Vm::new(c.module.expect("module"), Machine::reference());
    let mut events: Vec<nc::Event> = Vec::new();
    match vm.run(&mut events) {
        vm::Status::Alarm(a) => Err(a.code as u16),
        _ => Ok(vm.variable(100).expect("#100 is readable")),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a.is_nan() && b.is_nan()) || (a - b).abs() <= 1e-9 * 1f64.max(a.abs()).max(b.abs())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn vm_matches_the_reference(e in expr()) {
        let want = eval(&e).map(|v| v.unwrap_or(f64::NAN));
        let got = run(&e, false);
        match (want, got) {
            (Ok(w), Ok(g)) => prop_assert!(close(w, g), "{}: want {w}, got {g}", e.text()),
            (w, g) => prop_assert_eq!(w.map(|_| ()), g.map(|_| ()), "{}", e.text()),
        }
    }

    #[test]
    fn folding_computes_exactly_what_the_vm_computes(e in expr()) {
        let (a, b) = (run(&e, false), run(&e, true));
        match (a, b) {
            (Ok(x), Ok(y)) => prop_assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()), "{}: {x} vs {y}", e.text()),
            (x, y) => prop_assert_eq!(x.map(|_| ()), y.map(|_| ()), "{}", e.text()),
        }
    }
}
