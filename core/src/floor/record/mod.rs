//! Ground-motion records: reading accelerograms from PEER "AT2" files ([`parse_at2`]), COSMOS
//! V1/V2 files ([`parse_cosmos`]), ESM/ITACA ASCII files ([`parse_esm`]), CSV files
//! ([`parse_csv`]) and whitespace-separated text ([`parse_text`]); each format's layout is
//! described in its own module. Each reader keeps what the file says about itself
//! ([`RecordMeta`]: the units of its values where it declares them, the event, station,
//! component, magnitude and distance where it gives them), and refuses a file that holds a
//! velocity or a displacement rather than an acceleration, naming what it holds. No reader
//! corrects a baseline or filters: the samples are the file's.
//!
//! [`suite`] reads a suite of records (a directory, or a list file); the records' intensity
//! measures are [`crate::floor::intensity`]'s.
//!
//! # Files
//!
//! [`read_record`] reads only regular files (not a device such as /dev/zero, a FIFO or a
//! directory) of at most [`MAX_RECORD_BYTES`], checked before reading, through a reader that
//! stops at that limit.
//!
//! Every error names the file, the 1-based line number where there is one, and what was
//! expected and found. No input, however malformed, makes the readers panic.

mod accelerogram;
mod at2;
mod cosmos;
mod csv;
mod error;
mod esm;
mod format;
mod meta;
mod read;
mod samples;
mod sampling;
pub mod suite;
#[cfg(test)]
mod tests;
mod text;
mod units;

pub use accelerogram::Record;
pub use at2::parse_at2;
pub use cosmos::parse_cosmos;
pub use csv::{parse_csv, parse_text};
pub use error::{Location, RecordError};
pub use esm::parse_esm;
pub use format::RecordFormat;
pub use meta::{unit_of, Quantity, RecordMeta};
pub use read::{read_record, read_record_named, MAX_RECORD_BYTES};
pub use samples::{check_sample_dt, dt_from_times, record_from_samples, MAX_RECORD_SAMPLES};
pub use sampling::{MIN_DT, MIN_SAMPLES};
pub use units::{acceleration_unit, resolve_units, UNIT_NAMES};
