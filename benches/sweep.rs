//! Speed of sweep points (the README reports these numbers): one point of a pulse map as a
//! sweep runs it (no history), how its time grows with the simulated duration and with the
//! number of events, and a whole 20 x 20 map in process (points, chunks, files, figure).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock::commands::sweep::store;
use flexrock_core::model::{Model, Overrides, Setting};
use flexrock_core::sweep::{Axis, Request, Sweep};

fn model_file() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("models/pulse-map.toml")
}

fn pulse(settings: &[(&str, f64)]) -> Model {
    let overrides = Overrides {
        settings: settings
            .iter()
            .map(|&(k, v)| Setting::number(k, v))
            .collect(),
        ..Overrides::default()
    };
    Model::load(&model_file(), &overrides).expect("the model loads")
}

/// One point: a 0.8 s one-sine pulse and 5 s of free rocking, bdf at rtol 1e-8, with no
/// uplift (1 m/s^2), with rocking (3 m/s^2: 2 uplifts) and overturning (4 m/s^2).
fn one_point(c: &mut Criterion) {
    for amplitude in [1.0, 3.0, 4.0] {
        let model = pulse(&[("excitation.amplitude", amplitude)]);
        let events = flexrock::commands::run::simulate_peaks(&model)
            .unwrap()
            .events
            .len();
        c.bench_function(
            &format!("sweep point pulse 0.8 s A={amplitude} tail 5 s bdf ({events} events)"),
            |b| {
                b.iter(|| {
                    flexrock::commands::run::simulate_peaks(std::hint::black_box(&model)).unwrap()
                })
            },
        );
    }
}

/// The same rocking point with 20 and 80 s of free rocking after the pulse (5 s above).
fn duration(c: &mut Criterion) {
    for tail in [20.0, 80.0] {
        let model = pulse(&[("excitation.amplitude", 3.0), ("excitation.tail", tail)]);
        let events = flexrock::commands::run::simulate_peaks(&model)
            .unwrap()
            .events
            .len();
        c.bench_function(
            &format!("sweep point pulse 0.8 s A=3 tail {tail} s bdf ({events} events)"),
            |b| {
                b.iter(|| {
                    flexrock::commands::run::simulate_peaks(std::hint::black_box(&model)).unwrap()
                })
            },
        );
    }
}

/// A whole 20 x 20 map of the pulse model, written to a temporary directory each time.
fn map(c: &mut Criterion) {
    let out = std::env::temp_dir().join(format!("flexrock-bench-map-{}", std::process::id()));
    let request = || Request {
        axes: vec![
            Axis::parse("excitation.period=lin:0.2:3:20", Path::new(".")).unwrap(),
            Axis::parse("excitation.amplitude=lin:0.5:15:20", Path::new(".")).unwrap(),
        ],
        ..Request::default()
    };
    c.bench_function(
        "sweep map 20 x 20 pulse bdf (in process, files included)",
        |b| {
            b.iter(|| {
                let _ = std::fs::remove_dir_all(&out);
                let sweep = Sweep::new(&model_file(), request(), Path::new(".")).unwrap();
                let target = store::Target {
                    out: out.clone(),
                    ..store::Target::default()
                };
                store::run(&sweep, &target, &store::Silent).unwrap()
            })
        },
    );
    let _ = std::fs::remove_dir_all(&out);
}

/// The 100 x 100 map of the book's exact-method chapter, by the exact method and by tsit45 at
/// the model's tolerance, in process with its files (the whole process adds its start and
/// end, a few ms).
fn large_map(c: &mut Criterion) {
    let out = std::env::temp_dir().join(format!("flexrock-bench-map100-{}", std::process::id()));
    let mut group = c.benchmark_group("sweep map 100 x 100 pulse");
    group.sample_size(10);
    for method in ["exact", "tsit45"] {
        let request = || Request {
            settings: vec![flexrock_core::model::Setting::text("solver.method", method)],
            axes: vec![
                Axis::parse("excitation.period=lin:0.2:3:100", Path::new(".")).unwrap(),
                Axis::parse("excitation.amplitude=lin:0.5:15:100", Path::new(".")).unwrap(),
            ],
            ..Request::default()
        };
        group.bench_function(format!("{method} (in process, files included)"), |b| {
            b.iter(|| {
                let _ = std::fs::remove_dir_all(&out);
                let sweep = Sweep::new(&model_file(), request(), Path::new(".")).unwrap();
                let target = store::Target {
                    out: out.clone(),
                    ..store::Target::default()
                };
                store::run(&sweep, &target, &store::Silent).unwrap()
            })
        });
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&out);
}

criterion_group!(benches, one_point, duration, map, large_map);
criterion_main!(benches);
