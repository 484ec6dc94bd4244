//! Speed of the finite element analysis over the paper's 6 s (the README reports these).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock_core::bodies::fem::{pushover, simulate_fem, BaseSupport, FemBody, TimeScheme};
use flexrock_core::model::{Model, Overrides};

fn fem_runs(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/ichinose1986.toml");
    let model = Model::load(&path, &Overrides::default()).expect("the reference model loads");
    let floor = |t: f64| model.floor.acceleration(t);
    let mut group = c.benchmark_group("fem 6 s");
    group.sample_size(10);
    for (nx, ny, scheme, name) in [
        (
            2,
            5,
            TimeScheme::linear_acceleration(),
            "linear-acceleration",
        ),
        (
            2,
            5,
            TimeScheme::average_acceleration(),
            "average-acceleration",
        ),
        (
            8,
            40,
            TimeScheme::average_acceleration(),
            "average-acceleration",
        ),
    ] {
        let setup = model
            .fem_with(&Default::default())
            .expect("the [fem] section is valid");
        let mut settings = setup.settings.clone();
        settings.nx = nx;
        settings.ny = ny;
        settings.scheme = scheme;
        group.bench_function(format!("{nx}x{ny} {name} dt=0.0071"), |b| {
            b.iter(|| {
                simulate_fem(&setup.body, std::hint::black_box(&settings), &floor).expect("runs")
            })
        });
    }
    group.finish();
}

/// The sweep of `flexrock fem --pushover` on 8 x 40: 400 steps of q up to B, per base.
fn pushovers(c: &mut Criterion) {
    let mut group = c.benchmark_group("pushover 8x40 400 steps");
    group.sample_size(10);
    for base in [BaseSupport::Flexible, BaseSupport::RigidPlate] {
        let body = FemBody {
            base,
            ..FemBody::reference()
        };
        let qs: Vec<f64> = (1..=400).map(|k| body.width * k as f64 / 400.0).collect();
        group.bench_function(format!("{base:?}"), |b| {
            b.iter(|| pushover(&body, 8, 40, true, std::hint::black_box(&qs)).expect("runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, fem_runs, pushovers);
criterion_main!(benches);
