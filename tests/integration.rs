//! The command line's integration tests: one test binary, one build and link of the crate. Each
//! file of tests/ is a module named for its concern; `cargo test --release --test integration
//! sweep::` runs one (book/src/developer/tests.md). The tests of a binary run as threads of one
//! process: none changes the environment or the working directory, and each writes only into
//! its own `common::scratch_dir`.

mod common;

// The command line and its rules.
mod cli;
mod hostile_io;
mod layers;
mod tables;
mod timings_apart;

// The solvers and inputs through the crate.
mod newmark;
mod records;
mod self_weight;

// Commands.
mod criteria;
mod fem_cli;
mod figures;
mod fragility;
mod plot_cli;
mod report;
mod rigid_cli;
mod row_sweep;
mod rows;
mod sweep;
mod sweep_slurm;
mod sweep_store;

// The documents: the README and the book against the program.
mod book_links;
mod book_reference;
mod quoted_outputs;
