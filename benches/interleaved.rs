//! The exact method's time as a share of tsit45's, measured in alternation.
//!
//! A virtual machine's speed drifts by a third within minutes, and criterion measures one
//! benchmark for seconds before the next, so the ratio of two of its results carries that
//! drift. Here each round times a block of exact runs, a block of tsit45 runs at rtol = 1e-10
//! and one at rtol = 1e-12 (about 50 ms each), then the exact runs again, and takes the ratio
//! of the medians within the round; the rounds' ratios are then summarised by their median and
//! range. The runs are those of `benches/simulate.rs`: the paper's example over 6 s and El
//! Centro 1940 over 31.16 s, with their history (what `flexrock run` computes, for the exact
//! method with its energy books and two estimate runs) and with peaks only (a sweep's point).
//!
//! ```sh
//! cargo bench --bench interleaved            # 9 rounds
//! cargo bench --bench interleaved -- 21      # 21 rounds
//! ```

use std::path::Path;
use std::time::Instant;

use flexrock_core::model::{Model, Overrides};

/// Wall time of the runs in one block, s.
const BLOCK: f64 = 0.05;

fn load(file: &str, method: &str, tolerances: Option<(f64, f64)>, duration: f64) -> Model {
    let overrides = Overrides {
        method: Some(method.to_string()),
        duration: Some(duration),
        rtol: tolerances.map(|(rtol, _)| rtol),
        atol: tolerances.map(|(_, atol)| atol),
        ..Overrides::default()
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    Model::load(&path, &overrides).expect("the model loads")
}

/// One run: with its history as `flexrock run` computes it, or with peaks only.
fn run(model: &Model, history: bool) {
    if history {
        std::hint::black_box(
            flexrock::commands::run::simulate(std::hint::black_box(model)).expect("solves"),
        );
    } else {
        std::hint::black_box(
            flexrock_core::simulate::simulate_peaks(std::hint::black_box(model)).expect("solves"),
        );
    }
}

/// The median time of `n` runs, s.
fn block(model: &Model, history: bool, n: usize) -> f64 {
    let mut times: Vec<f64> = (0..n)
        .map(|_| {
            let start = Instant::now();
            run(model, history);
            start.elapsed().as_secs_f64()
        })
        .collect();
    median(&mut times)
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The runs of `model` that fill a block (at least 5).
fn runs_per_block(model: &Model, history: bool) -> usize {
    let start = Instant::now();
    for _ in 0..3 {
        run(model, history);
    }
    let each = start.elapsed().as_secs_f64() / 3.0;
    ((BLOCK / each) as usize).max(5)
}

/// Median and range of `values`.
fn summary(values: &mut [f64]) -> String {
    let middle = median(values);
    format!(
        "{middle:.3} ({:.3} to {:.3})",
        values[0],
        values[values.len() - 1]
    )
}

fn main() {
    // `cargo bench` passes "--bench"; a number is the count of rounds.
    let rounds = std::env::args()
        .skip(1)
        .find_map(|arg| arg.parse::<usize>().ok())
        .unwrap_or(9)
        .max(1);
    println!(
        "{rounds} rounds; exact: the median time, ms; then its ratio to tsit45's time, the median \
         over the rounds and the range"
    );
    println!("| run | exact, ms | / tsit45 at rtol = 1e-10 | / tsit45 at rtol = 1e-12 |");
    println!("|---|---|---|---|");
    for (file, duration) in [
        ("models/ichinose1986.toml", 6.0),
        ("models/elcentro1940.toml", 31.16),
    ] {
        let exact = load(file, "exact", None, duration);
        let loose = load(file, "tsit45", Some((1e-10, 1e-12)), duration);
        let tight = load(file, "tsit45", Some((1e-12, 1e-14)), duration);
        for history in [true, false] {
            let counts = [&exact, &loose, &tight].map(|m| runs_per_block(m, history));
            let (mut times, mut to_loose, mut to_tight) = (vec![], vec![], vec![]);
            for _ in 0..rounds {
                let before = block(&exact, history, counts[0]);
                let loose_time = block(&loose, history, counts[1]);
                let tight_time = block(&tight, history, counts[2]);
                let after = block(&exact, history, counts[0]);
                let exact_time = 0.5 * (before + after);
                times.push(exact_time * 1e3);
                to_loose.push(exact_time / loose_time);
                to_tight.push(exact_time / tight_time);
            }
            println!(
                "| {file} {duration} s, {} | {} | {} | {} |",
                if history {
                    "with its history"
                } else {
                    "peaks only"
                },
                summary(&mut times),
                summary(&mut to_loose),
                summary(&mut to_tight)
            );
        }
    }
}
