//! Output files: CSV tables and JSON summaries, written atomically. Writers see only the
//! solver-agnostic [`Solution`](flexrock_core::integrate::solution::Solution) types, never a solver.

mod atomic;
pub mod run_dir;
mod run_files;
mod summary;
mod table;

pub(crate) use atomic::remove_stale_temporaries;
pub use atomic::{
    check_creatable, write_atomically, write_checkpoint, write_file_atomically,
    write_named_atomically, FileSet, TEMPORARY_PREFIX,
};
pub use run_files::{episodes_csv, events_csv, history_csv};
pub use summary::{json_bytes, milliseconds, Timings, WallTimes};
pub use table::{push_row, Table};

pub use flexrock_core::tables::run_tables::{
    episode_fields, EpisodeField, EPISODE_COLUMNS, EVENT_COLUMNS, HISTORY_COLUMNS,
};

pub use flexrock_core::base::format::{
    count, file_kind, list, number, push_number, readable, scientific, shortest, significant,
};
