//! The tables and summaries a run or an analysis writes: their column names, typed rows and
//! summary.json, shared by the command line and the Python bindings.

pub mod fields;
pub mod rigid_results;
pub mod row_results;
pub mod run_tables;
pub mod summary;
