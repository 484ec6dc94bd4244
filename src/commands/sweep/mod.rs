#![warn(missing_docs)]
//! `flexrock sweep`: the core's parametric studies ([`flexrock_core::analysis::sweep`]) on disk.
//!
//! - [`store`]: chunks on disk, resuming, shards and their merge;
//! - `threads`: the threads the points are computed on (`--threads`, [`start_threads`]);
//! - `report`: the lines `flexrock sweep` prints ([`report_text`]), and its [`warnings`];
//! - the map and the spectrum, drawn from sweep.csv alone, are in [`crate::figures::sweep`].
//!
//! Rows are written in point order, so that the output is the same whatever the number of
//! threads.

mod report;
pub mod store;
mod threads;

pub use report::{report_text, warnings};
pub use threads::{start_threads, MAX_THREADS};
