//! Speed of sweep points (the README reports these numbers): one point of a pulse map as a
//! sweep runs it (no history), how its time grows with the simulated duration and with the
//! number of events, a whole 20 x 20 map in process (points, chunks, files, figure), and the
//! 100 x 100 map of the exact method's speed goal by the exact method and tsit45.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrock::commands::sweep::store;
use flexrock_core::analysis::sweep::{Axis, Request, Sweep};
use flexrock_core::model::{Model, Overrides, Setting};

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

/// The map of `request` on the pulse model, written into `out` (emptied first).
fn sweep_map(out: &Path, request: Request) -> store::SweepReport {
    let _ = std::fs::remove_dir_all(out);
    let sweep = Sweep::new(&model_file(), request, Path::new(".")).unwrap();
    let target = store::Target {
        out: out.to_path_buf(),
        ..store::Target::default()
    };
    store::run(&sweep, &target, &store::Silent).unwrap()
}

/// The request of a map over `period` and `amplitude` (axis texts) with `settings`.
fn map_request(settings: Vec<Setting>, period: &str, amplitude: &str) -> Request {
    Request {
        settings,
        axes: vec![
            Axis::parse(&format!("excitation.period={period}"), Path::new(".")).unwrap(),
            Axis::parse(&format!("excitation.amplitude={amplitude}"), Path::new(".")).unwrap(),
        ],
        ..Request::default()
    }
}

/// A whole 20 x 20 map of the pulse model, written to a temporary directory each time.
fn map(c: &mut Criterion) {
    let out = std::env::temp_dir().join(format!("flexrock-bench-map-{}", std::process::id()));
    c.bench_function(
        "sweep map 20 x 20 pulse bdf (in process, files included)",
        |b| {
            b.iter(|| {
                sweep_map(
                    &out,
                    map_request(Vec::new(), "lin:0.2:3:20", "lin:0.5:15:20"),
                )
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
        let request = || {
            map_request(
                vec![Setting::text("solver.method", method)],
                "lin:0.3:2:100",
                "lin:1:6:100",
            )
        };
        group.bench_function(format!("{method} (in process, files included)"), |b| {
            b.iter(|| sweep_map(&out, request()))
        });
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&out);
}

criterion_group!(benches, one_point, duration, map, large_map);
criterion_main!(benches);
