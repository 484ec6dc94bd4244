//! The core's integration tests: one test binary, one build and link of the crate. Each file of
//! core/tests/ is a module named for its concern; `cargo test --release --test core_integration
//! rigid::` runs one (book/src/developer/tests.md). The tests run as threads of one process:
//! none changes the environment or the working directory, and each writes only into its own
//! `common::scratch_dir`.

mod common;

mod constants;
mod criteria;
mod dynamics;
mod exact;
mod finite_inputs;
mod fragility;
mod hardening;
mod independent;
mod layers;
mod model_chapter;
mod model_robustness;
mod published_rigid;
mod random_models;
mod recorded_motion;
mod rigid;
mod rigid_forms;
mod rigid_vertical;
mod rocking_choices;
mod row;
mod row_compliant;
mod row_friction;
mod row_random;
mod row_sweep;
