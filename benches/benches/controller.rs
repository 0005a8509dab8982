//! Criterion group `controller`: what an operator waits for at the panel.
//! MDI: the typed line compiled for the machine and taken by an idle
//! controller (the latency from Enter to cycle start being possible).
//! A program given as text: compiled and loaded into a new controller,
//! as `gbc_controller_load_source` does.

use criterion::{criterion_group, criterion_main, Criterion};
use nc::Machine;
use runtime::Controller;

fn compiled(src: &str, machine: &Machine) -> isa::Module {
    let opts = compiler::Options {
        machine: machine.clone(),
        ..compiler::Options::default()
    };
    match compiler::compile("MDI", src.as_bytes(), &opts).module {
        Some(m) => m,
        None => panic!("{src:?} does not compile"),
    }
}

fn controller(c: &mut Criterion) {
    let machine = Machine::reference();
    let shaft = include_str!("../../examples/shaft.nc");
    let mut ctl = Controller::new(compiled(shaft, &machine), machine.clone(), runtime::AutoAck)
        .expect("loads");
    let mut g = c.benchmark_group("controller");
    g.bench_function("mdi_line_compile_and_take", |b| {
        b.iter(|| {
            let blocks = compiled("M03 S500\n", &machine);
            ctl.mdi(blocks).expect("idle")
        })
    });
    g.bench_function("shaft_text_compile_and_load", |b| {
        b.iter(|| {
            let m = compiled(shaft, &machine);
            Controller::new(m, machine.clone(), runtime::AutoAck).expect("loads")
        })
    });
    g.finish();
}

criterion_group!(benches, controller);
criterion_main!(benches);
