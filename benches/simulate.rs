//! Speed of whole simulations (the README reports these numbers).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock::model::{Model, Overrides};

fn load(rtol: f64) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/ichinose1986.toml");
    let overrides = Overrides {
        rtol: Some(rtol),
        ..Overrides::default()
    };
    Model::load(&path, &overrides).expect("the reference model loads")
}

fn reference_case(c: &mut Criterion) {
    for rtol in [1e-6, 1e-8, 1e-10] {
        let model = load(rtol);
        c.bench_function(&format!("ichinose1986 6 s bdf rtol={rtol:e}"), |b| {
            b.iter(|| flexrock::run::simulate(std::hint::black_box(&model)).expect("solves"))
        });
    }
}

criterion_group!(benches, reference_case);
criterion_main!(benches);
