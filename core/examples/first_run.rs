//! The paper's example solved from Rust: read a model file, print the derived constants, solve,
//! and print the events and the peaks.
//!
//! Run it from the root of a clone:
//!
//! ```sh
//! cargo run --release -p flexrock-core --example first_run
//! ```

use std::path::Path;

use flexrock_core::{Model, Overrides};

fn main() -> Result<(), flexrock_core::Error> {
    // The model file of the paper's example; keys changed as `--set` would change them
    // go into the overrides (here none).
    let path = Path::new("models/ichinose1986.toml");
    let model = Model::load(path, &Overrides::default())?;

    // What the body's dimensions, mass and stiffness give (the model chapter, section 2).
    let c = &model.constants;
    println!("pre-uplift period T = {:.4} s", c.period);
    println!("uplift displacement s_n = {:.6} m", c.uplift_displacement);

    // The adaptive solver the file names (BDF at rtol 1e-10), with every uplift and landing
    // located by root finding.
    let solution = flexrock_core::simulate(&model)?;
    for e in &solution.events {
        println!(
            "{:>2}  t = {:.6} s  {:<8} {} -> {}  q' {:+.6} -> {:+.6} m/s",
            e.index,
            e.t,
            e.kind.name(),
            e.from.name(),
            e.to.name(),
            e.qdot_before,
            e.qdot_after
        );
    }
    println!(
        "max q = {:.6} m at t = {:.4} s; min q = {:.6} m at t = {:.4} s; overturned: {}",
        solution.max_q.value,
        solution.max_q.t,
        solution.min_q.value,
        solution.min_q.t,
        solution.overturned
    );
    // The sampled history, every solver.output_dt and at both sides of every event.
    let last = solution.samples.last().expect("a run has samples");
    println!(
        "{} samples; at t = {} s: q = {:.6} m, mode {}",
        solution.samples.len(),
        last.t,
        last.q,
        last.mode.name()
    );
    Ok(())
}
