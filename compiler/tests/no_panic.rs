//! Bad input never panics: random mutations of the conformance programs go
//! through the whole pipeline (parse, link, check, lower, verify, run).

use compiler::{compile, Options};
use nc::Machine;
use proptest::prelude::*;
use std::path::Path;
use vm::Vm;

fn samples() -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/conformance");
    let mut out: Vec<Vec<u8>> = std::fs::read_dir(&dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "nc"))
                .filter_map(|p| std::fs::read(p).ok())
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    if out.is_empty() {
        out.push(b"G00 X10 Z2\n#1=#1+1\nIF[#1LT3]GOTO1\nG71U1R0.5\nM30\n".to_vec());
    }
    out
}

fn pipeline(src: &[u8]) {
    let c = compile("fuzz.nc", src, &Options::default());
    let _ = c.render();
    if let Some(module) = c.module {
        let bytes = module.to_bytes();
        let module = isa::Module::from_bytes(&bytes).expect("a compiled module verifies");
        let mut vm = Vm::new(module, Machine::reference());
        vm.max_blocks = 5_000;
        let mut events: Vec<nc::Event> = Vec::new();
        let _ = vm.run(&mut events);
    }
}

#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, u8),
    Delete(usize),
    Replace(usize, u8),
}

fn apply(mut src: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    for e in edits {
        let len = src.len().max(1);
        match *e {
            Edit::Insert(i, b) => src.insert(i % (len + 1).min(src.len() + 1), b),
            Edit::Delete(i) if !src.is_empty() => {
                src.remove(i % src.len());
            }
            Edit::Replace(i, b) if !src.is_empty() => {
                let n = src.len();
                src[i % n] = b;
            }
            _ => {}
        }
    }
    src
}

fn byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        prop::sample::select(b"GXZUWIKRPQLFSTM#[]=.-+0123456789;\n()/ONDEIFGOTOWHILEEND,".to_vec()),
        any::<u8>(),
    ]
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), byte()).prop_map(|(i, b)| Edit::Insert(i, b)),
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), byte()).prop_map(|(i, b)| Edit::Replace(i, b)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn mutated_programs_never_panic(pick in any::<usize>(), edits in prop::collection::vec(edit(), 1..8)) {
        let all = samples();
        let src = apply(all[pick % all.len()].clone(), &edits);
        pipeline(&src);
    }
}
