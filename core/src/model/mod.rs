//! The TOML model file: its schema (key names are a contract), defaults and validation.
//!
//! A model file is read into [`ModelFile`] exactly as written (unknown keys are errors), then
//! [`Model::from_file`] applies the defaults, checks every rule and derives the constants. Each
//! section's rules live in a file of their own (`body_section.rs`, `excitation_section.rs`,
//! `simulation_section.rs`, `solver_section.rs`, `fem_section.rs`); a row of columns has its own
//! file (`row_file.rs`).

mod body_file;
mod body_section;
mod excitation_section;
mod fem_section;
mod overrides;
mod read;
mod row_file;
mod schema;
mod setting;
mod simulation_section;
mod solver_section;
mod table;

pub use body_file::Model;
pub(crate) use excitation_section::keys_of_kind;
pub use excitation_section::{record_path, RecordCache, STANDARD_GRAVITY};
pub use fem_section::{
    FemSetup, DEFAULT_FEM_DT, DEFAULT_FEM_MU_K, DEFAULT_FEM_MU_S, DEFAULT_FEM_NX, DEFAULT_FEM_NY,
    DEFAULT_FEM_THETA, DEFAULT_POISSON_RATIO, FEM_SNAPSHOT_TIMES,
};
pub use overrides::{Overrides, DT_WITHOUT_NEWMARK};
pub(crate) use read::parse_table;
pub use read::{
    is_row_table, read_model_table, read_model_text, read_schema, PreparedSchema,
    MAX_MODEL_FILE_BYTES, MODEL_TEXT,
};
pub use row_file::{RowModel, RowSection, RowSimulationSection};
pub use schema::{
    BodySection, ExcitationSection, FemOverrides, FemSection, ModelFile, SimulationSection,
    SolverSection, DEFAULT_ATOL, DEFAULT_DAMPING_RATIO, DEFAULT_DEPTH, DEFAULT_GRAVITY,
    DEFAULT_OUTPUT_DT, DEFAULT_RTOL, MAX_DURATION, MAX_INITIAL_VELOCITY,
};
pub use setting::{check_key, model_dir, value_text, Setting};
pub use solver_section::{
    DEFAULT_NEWMARK_BETA, DEFAULT_NEWMARK_DT, DEFAULT_NEWMARK_GAMMA, MAX_ATOL_OVER_WIDTH, MAX_RTOL,
    MIN_RTOL,
};
pub use table::{default_value, effective_table, schema_keys, value_in_effect};
