//! flexrock: reference solutions of the Ichinose (1986) model of a slender elastic body rocking
//! on a rigid floor; the command-line layer (files, figures, reports, sweeps) on top of
//! [`flexrock_core`], the physics and numerics.
//!
//! From [`flexrock_core`], re-exported here under the same names:
//! - [`body`]: the physical body; [`constants`]: everything derived from it
//!   (book/src/model.md §2-§5);
//! - [`automaton`]: the hybrid automaton (modes, right-hand sides, guards, resets);
//! - [`excitation`]: floor motions behind the [`excitation::FloorMotion`] trait; [`record`]:
//!   recorded ground motions;
//! - [`solver`]: solvers that drive the automaton; [`solution`]: what they return;
//! - [`model`]: the TOML model file; [`rigid`]: the slender rigid block of the rigid limit;
//!   [`findings`]: the paper's qualitative findings in numbers; [`error`], [`format`](mod@format).
//!
//! Here, the command-line layer:
//! - [`fem`]: the plane-stress finite element check of the paper's Section 3 (the numerics of
//!   [`flexrock_core::fem`], and the commands [`fem::run`], [`fem::pushover_run`] that write
//!   the files of [`flexrock_core::fem_check`] and [`flexrock_core::pushover_check`]);
//! - [`output`]: CSV/JSON writers; [`run`]: the `props` and `run` commands;
//! - [`run_dir`]: a run's output directory read back (typed), and its event table;
//!   [`run_plot`]: the figures of a run;
//! - [`compare`], [`converge`]: Newmark against the adaptive reference (the files and tables of
//!   [`flexrock_core::compare`] and [`flexrock_core::converge`]); [`plot`]: SVG figures
//!   from series; [`report`]: the validation report assembled from their files;
//!   [`record_tools`]: the record commands;
//! - [`sweep`]: parametric studies (axes, minimum overturning searches, chunks, shards, maps).
//!
//! See [`flexrock_core`] for a worked example.

#![warn(missing_docs)]

pub use flexrock_core;
pub use flexrock_core::{
    automaton, body, constants, error, excitation, findings, format, model, record, rigid,
    solution, solver,
};

pub mod compare;
pub mod converge;
pub mod fem;
pub mod flags;
pub mod output;
pub mod plot;
pub mod record_tools;
pub mod report;
pub mod run;
pub mod run_dir;
pub mod run_plot;
pub mod sweep;

pub use error::{Error, Result};
