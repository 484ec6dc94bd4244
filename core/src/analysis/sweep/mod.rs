//! Parametric studies: one model, axes over any of its numeric keys (and over record files),
//! one [`PointResult`] per point.
//!
//! - [`axis`]: the axes and their values (`KEY=LO:HI:STEP`, `log:LO:HI:N`, lists, file patterns);
//! - [`find_min`]: the smallest overturning value of a key at every point (scan, then bisect);
//! - [`point_result`]: what a point gives, typed, and the column names of sweep.csv;
//! - [`rows`]: sweeps of a row of columns (a model file with a `[row]` table): the keys of a
//!   row, and each column's outcome in the row against its outcome alone.
//!
//! Every point is the base model with the point's keys set ([`crate::model::Setting`]), read
//! and checked by the same rules as a model file: a point that breaks one is a row with its
//! reason, not the end of the sweep. Points run in parallel (with the `parallel` feature, on by
//! default); each is computed alone, so that the rows are the same whatever the number of
//! threads. Writing the rows to disk (chunks, resuming, shards) is the command line's business.
//!
//! Values a request holds are named by the sweep file's keys in messages (`vary KEY`,
//! `find_min KEY`, `scan`, `tol`, `chunk_size`); the command line names them by its flags.
//!
//! The files, besides those above: [`Request`] (what a user asks, from flags or a sweep file),
//! [`Sweep`] (a request checked against the model and made a [`Plan`]), the points' runner,
//! and the digests of the plan and of the records a sweep reads ([`sha256_hex`]).

pub mod axis;
pub mod cell;
mod digest;
pub mod find_min;
mod in_order;
mod plan;
pub mod point_result;
mod points;
mod request;
pub mod rows;
mod setup;

pub use axis::{Axis, Interval};
pub use cell::Cell;
pub use digest::{sha256_hex, sha256_hex_of};
pub use find_min::{FindMin, HousnerOptions};
pub use plan::{Plan, RecordInput, SIMULATIONS_PER_CHUNK};
pub use point_result::{Layout, Outcome, PointResult, RecordCells, Status};
pub use request::{Request, SweepFile};
pub use setup::Sweep;
