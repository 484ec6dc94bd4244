//! Speed of whole simulations, output sampling included (the README reports these numbers).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock::model::{Model, Overrides};

fn load(rtol: f64, atol: f64) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/ichinose1986.toml");
    let overrides = Overrides {
        rtol: Some(rtol),
        atol: Some(atol),
        ..Overrides::default()
    };
    Model::load(&path, &overrides).expect("the reference model loads")
}

/// The paper's example over 6 s with BDF. The model file pairs rtol = 1e-10 with atol = 1e-12 m;
/// the cases below keep that ratio, and also show rtol = 1e-8 with the file's atol.
fn reference_case(c: &mut Criterion) {
    for (rtol, atol) in [(1e-6, 1e-8), (1e-8, 1e-10), (1e-8, 1e-12), (1e-10, 1e-12)] {
        let model = load(rtol, atol);
        c.bench_function(
            &format!("ichinose1986 6 s bdf rtol={rtol:e} atol={atol:e}"),
            |b| b.iter(|| flexrock::run::simulate(std::hint::black_box(&model)).expect("solves")),
        );
    }
}

criterion_group!(benches, reference_case);
criterion_main!(benches);
