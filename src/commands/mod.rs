//! The commands behind the binary, as library functions: each computes with the core and writes
//! its files (through [`crate::writers`] and [`crate::figures`]).
//!
//! - [`run`]: `flexrock props` and `flexrock run`;
//! - [`criteria`]: `flexrock criteria`, the overturning criteria of elastic bodies beside the
//!   rigid block's;
//! - [`compare`], [`converge`]: Newmark against the adaptive reference;
//! - [`fem`], [`pushover`]: the finite element check (`flexrock fem`, `flexrock fem --pushover`);
//! - [`record`]: `flexrock record info` and `flexrock record csv`;
//! - [`report`]: validation/REPORT.md from the files of `compare`, `converge` and `run`;
//! - [`rigid`]: `flexrock rigid`, Housner's block alone on the model's floor;
//! - [`sweep`]: `flexrock sweep`, the core's sweeps on disk (chunks, resuming, shards, merge).

pub mod compare;
pub mod converge;
pub mod criteria;
pub mod fem;
pub mod fragility;
pub mod pushover;
pub mod record;
pub mod report;
pub mod rigid;
pub mod row;
pub mod run;
pub mod sweep;
