//! The VM's expression evaluation against the reference evaluator of
//! `harness::expr` (written from dialect.md §7.4–§7.6), on proptest's
//! random expressions with vacant operands. Compiled without folding so
//! the VM, not the folder, computes; a second run with folding must agree
//! bit for bit.

use harness::expr::{close, eval, run_folded, E};
use proptest::prelude::*;

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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn vm_matches_the_reference(e in expr()) {
        let want = eval(&e).map(|v| v.unwrap_or(f64::NAN));
        let got = run_folded(&e, false);
        match (want, got) {
            (Ok(w), Ok(g)) => prop_assert!(close(w, g), "{}: want {w}, got {g}", e.text()),
            (w, g) => prop_assert_eq!(w.map(|_| ()), g.map(|_| ()), "{}", e.text()),
        }
    }

    #[test]
    fn folding_computes_exactly_what_the_vm_computes(e in expr()) {
        let (a, b) = (run_folded(&e, false), run_folded(&e, true));
        match (a, b) {
            (Ok(x), Ok(y)) => prop_assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()), "{}: {x} vs {y}", e.text()),
            (x, y) => prop_assert_eq!(x.map(|_| ()), y.map(|_| ()), "{}", e.text()),
        }
    }
}
