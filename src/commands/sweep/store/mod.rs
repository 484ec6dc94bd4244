//! A sweep on disk: chunks written as they finish, resumed after a kill, split into shards for a
//! scheduler and merged back.
//!
//! Layout of an output directory (a shard K of N writes into `DIR/shard-K-of-N/` instead):
//! - while running: `chunks/plan.json` (what is being computed) and `chunks/<c>.csv`, the rows
//!   of chunk c (points c x chunk_size onwards) under a seal line, each file written whole
//!   (temporary file, then rename), in the order the chunks finish; chunks are not synced to
//!   the disk: one torn by a crash of the machine fails its seal and is computed again;
//! - when done: `sweep.csv`, the figure, and last `sweep.json` (the plan, the counts and the
//!   digest of sweep.csv), written as one set; then what flexrock wrote in `chunks/` is removed.
//!
//! The rules that keep a sweep from losing, mixing or hanging:
//! - one process at a time: the directory is locked for the whole run (`dir.rs`), and a second
//!   process is refused;
//! - flexrock's own files only: `chunks/` is made by flexrock and is refused when it is a link,
//!   a file, or holds anything flexrock did not write; only the names flexrock writes are ever
//!   removed;
//! - a sweep is its plan: the model text, `--set` keys, axes, search, chunk size, version and
//!   the SHA-256 of every record file read ([`Plan::identity`](flexrock_core::analysis::sweep::Plan::identity)); a directory of another sweep
//!   is refused (or replaced with `--force`);
//! - nothing read back is trusted (`verify.rs`): every chunk is checked against its seal (the
//!   plan's identity, its points and its rows) and every row against the plan (point index,
//!   coordinates, columns, status, bytes); a chunk that fails is computed again, a sweep.csv
//!   that fails is refused, naming the file.
//!
//! Running the same command again skips the chunks on disk; a kill at any moment loses at most
//! the chunks being computed.

mod dir;
mod merge;
mod plot;
mod progress;
mod run;
mod shard;
mod summary;
mod verify;

pub use merge::merge;
pub use plot::plot_dir;
pub use progress::{Progress, Silent};
pub use run::{rows, run, Target};
pub use shard::{point_range, PointRange, Shard};
pub use summary::{SweepReport, SweepSummary};
pub use verify::sha256_hex;

pub use crate::sweep_table::Counts;
use crate::sweep_table::Piece;
