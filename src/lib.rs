//! flexrock: reference solutions of the Ichinose (1986) model of a slender elastic body rocking
//! on a rigid floor; the command-line layer (files, figures, reports, sweeps on disk) on top of
//! [`flexrock_core`], the physics, numerics and analysis.
//!
//! - [`commands`]: what each command computes (with the core) and writes;
//! - [`writers`]: CSV and JSON files written atomically, and a run's directory read back;
//! - [`figures`]: SVG, PDF and PNG figures of runs and sweeps;
//! - [`flags`]: the command line's names for model-file keys in messages;
//! - [`sweep_table`]: sweep.csv read back, and the counts of its rows;
//! - [`geometry`]: the body's height, width and gravity as the criteria take them.
//!
//! The core is used by its own name (`flexrock_core::model`, `flexrock_core::analysis::sweep`, ...); see
//! [`flexrock_core`] for a worked example from a model file to a sweep.

#![warn(missing_docs)]

pub use flexrock_core;

pub mod commands;
pub mod error;
pub mod figures;
pub mod flags;
pub mod geometry;
pub mod sweep_table;
pub mod writers;

pub use error::{Error, Result};
