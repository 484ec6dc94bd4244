//! Speed of whole simulations, output sampling included (the README reports these numbers).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock_core::model::{Model, Overrides};
use flexrock_core::physics::body::{Body, SelfWeight};
use flexrock_core::physics::constants::Constants;

fn load(file: &str, overrides: Overrides) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    Model::load(&path, &overrides).expect("the model loads")
}

fn tolerances(rtol: f64, atol: f64) -> Overrides {
    Overrides {
        rtol: Some(rtol),
        atol: Some(atol),
        ..Overrides::default()
    }
}

/// The paper's example over 6 s with BDF. The model file pairs rtol = 1e-10 with atol = 1e-12 m;
/// the cases below keep that ratio, and also show rtol = 1e-8 with the file's atol.
fn reference_case(c: &mut Criterion) {
    for (rtol, atol) in [(1e-6, 1e-8), (1e-8, 1e-10), (1e-8, 1e-12), (1e-10, 1e-12)] {
        let model = load("models/ichinose1986.toml", tolerances(rtol, atol));
        c.bench_function(
            &format!("ichinose1986 6 s bdf rtol={rtol:e} atol={atol:e}"),
            |b| {
                b.iter(|| {
                    flexrock::commands::run::simulate(std::hint::black_box(&model)).expect("solves")
                })
            },
        );
    }
}

/// The reference body through the whole 31.16 s El Centro record (every one of its 1559 samples
/// a stop time), rtol = 1e-8, atol = 1e-10, with each method.
fn el_centro(c: &mut Criterion) {
    for method in ["bdf", "esdirk34", "tr-bdf2", "tsit45"] {
        let model = load(
            "models/elcentro1940.toml",
            Overrides {
                method: Some(method.to_string()),
                duration: Some(31.16),
                ..tolerances(1e-8, 1e-10)
            },
        );
        c.bench_function(&format!("elcentro1940 31.16 s {method} rtol=1e-8"), |b| {
            b.iter(|| {
                flexrock::commands::run::simulate(std::hint::black_box(&model)).expect("solves")
            })
        });
    }
}

/// The exact method on the paper's example and through the whole El Centro record, and tsit45
/// at rtol = 1e-10 and 1e-12 beside it (the accuracy the exact method's results are compared
/// at): each run with its history (and, for the exact method, its energy books and its two
/// estimate runs), and with peaks only, as a sweep's point or a minimum search's step runs.
fn exact(c: &mut Criterion) {
    for (file, duration) in [
        ("models/ichinose1986.toml", 6.0),
        ("models/elcentro1940.toml", 31.16),
    ] {
        let name = Path::new(file)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let model = load(
            file,
            Overrides {
                method: Some("exact".to_string()),
                duration: Some(duration),
                ..Overrides::default()
            },
        );
        c.bench_function(&format!("{name} {duration} s exact peaks-only"), |b| {
            b.iter(|| {
                flexrock_core::simulate::simulate_peaks(std::hint::black_box(&model))
                    .expect("solves")
            })
        });
        c.bench_function(&format!("{name} {duration} s exact"), |b| {
            b.iter(|| {
                flexrock::commands::run::simulate(std::hint::black_box(&model)).expect("solves")
            })
        });
        for (rtol, atol) in [(1e-10, 1e-12), (1e-12, 1e-14)] {
            let model = load(
                file,
                Overrides {
                    method: Some("tsit45".to_string()),
                    duration: Some(duration),
                    ..tolerances(rtol, atol)
                },
            );
            c.bench_function(&format!("{name} {duration} s tsit45 rtol={rtol:e}"), |b| {
                b.iter(|| {
                    flexrock::commands::run::simulate(std::hint::black_box(&model)).expect("solves")
                })
            });
            c.bench_function(
                &format!("{name} {duration} s tsit45 rtol={rtol:e} peaks-only"),
                |b| {
                    b.iter(|| {
                        flexrock_core::simulate::simulate_peaks(std::hint::black_box(&model))
                            .expect("solves")
                    })
                },
            );
        }
    }
}

/// The reference case at rtol = 1e-8 with the other methods.
fn reference_case_methods(c: &mut Criterion) {
    for method in ["esdirk34", "tr-bdf2", "tsit45"] {
        let model = load(
            "models/ichinose1986.toml",
            Overrides {
                method: Some(method.to_string()),
                ..tolerances(1e-8, 1e-10)
            },
        );
        c.bench_function(
            &format!("ichinose1986 6 s {method} rtol=1e-8 atol=1e-10"),
            |b| {
                b.iter(|| {
                    flexrock::commands::run::simulate(std::hint::black_box(&model)).expect("solves")
                })
            },
        );
    }
}

/// Deriving the constants of the paper's body in each variant: a sweep does it at every point,
/// and the consistent variant solves for its shape (a 12-mode Ritz eigenproblem) each time.
fn constants(c: &mut Criterion) {
    let model = load("models/ichinose1986.toml", Overrides::default());
    for variant in [SelfWeight::Paper, SelfWeight::Consistent] {
        let body = Body {
            self_weight: variant,
            ..model.body.clone()
        };
        c.bench_function(&format!("constants {}", variant.name()), |b| {
            b.iter(|| Constants::new(std::hint::black_box(&body)).expect("valid"))
        });
    }
}

criterion_group!(
    benches,
    reference_case,
    exact,
    reference_case_methods,
    el_centro,
    constants
);
criterion_main!(benches);
