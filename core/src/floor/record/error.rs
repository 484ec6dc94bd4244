//! What can go wrong reading a record: [`RecordError`], each message naming the file and line.

use std::fmt;

/// Where in which file something went wrong: displays as `file` or `file line N`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file, as given.
    pub file: String,
    /// 1-based line number, if the problem belongs to one line.
    pub line: Option<usize>,
}

impl Location {
    pub(super) fn file(file: &str) -> Self {
        Self {
            file: file.to_string(),
            line: None,
        }
    }

    pub(super) fn line(file: &str, line: usize) -> Self {
        Self {
            file: file.to_string(),
            line: Some(line),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{} line {}", self.file, line),
            None => write!(f, "{}", self.file),
        }
    }
}

/// Everything that can go wrong reading a record. Each message names the file (and line).
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The file could not be read.
    #[error("{file}: cannot read the file: {error}")]
    Read {
        /// The record file.
        file: String,
        /// Why.
        #[source]
        error: std::io::Error,
    },

    /// The path is not a regular file.
    #[error(
        "{file}: is {found}; a record must be a regular file (not a device, FIFO, socket or \
         directory)"
    )]
    NotRegularFile {
        /// The record file.
        file: String,
        /// What the path is, e.g. "a directory".
        found: &'static str,
    },

    /// The file is larger than [`MAX_RECORD_BYTES`](super::MAX_RECORD_BYTES).
    #[error(
        "{file}: the file has {size} bytes, more than the limit for a record, {limit} bytes \
         ({} MiB); real AT2 files have a few MB",
        .limit / (1024 * 1024)
    )]
    TooLarge {
        /// The record file.
        file: String,
        /// The file size, bytes.
        size: u64,
        /// The largest size accepted, bytes.
        limit: u64,
    },

    /// The file is not UTF-8 text.
    #[error("{at}: the file is not UTF-8 text (invalid byte at offset {byte_offset})")]
    NotUtf8 {
        /// Where in the file.
        at: Location,
        /// Offset of the first invalid byte.
        byte_offset: usize,
    },

    /// The format was not given and the extension does not tell it.
    #[error(
        "{file}: cannot tell the record format from the extension (expected .AT2, .csv, .txt, \
         .dat, .V1, .V2, .V1c, .V2c or .ASC, found {extension:?}) nor from the first line; give \
         the format explicitly"
    )]
    UnknownFormat {
        /// The record file.
        file: String,
        /// The extension found.
        extension: String,
    },

    /// The file is empty.
    #[error("{file}: empty file")]
    Empty {
        /// The record file.
        file: String,
    },

    /// An AT2 file has fewer than its 4 header lines.
    #[error("{file}: fewer than 4 header lines (the file has {found} lines)")]
    TooFewHeaderLines {
        /// The record file.
        file: String,
        /// The number of lines the file has.
        found: usize,
    },

    /// A header line is not of the expected form.
    #[error("{at}: expected {expected}, found {found:?}")]
    BadHeader {
        /// Where in the file.
        at: Location,
        /// What the line should hold.
        expected: &'static str,
        /// The line as found.
        found: String,
    },

    /// The record has fewer than [`MIN_SAMPLES`](super::MIN_SAMPLES) values.
    #[error(
        "{file}: the record has {}; a record needs at least 2 samples (one interval of dt) to \
         define the floor acceleration between them",
        crate::base::format::count(*.found, "sample", "samples")
    )]
    TooFewSamples {
        /// The record file.
        file: String,
        /// The number of values found.
        found: usize,
    },

    /// The NPTS of an AT2 header is 0.
    #[error("{at}: NPTS must be > 0, found {found}")]
    InvalidCount {
        /// Where in the file.
        at: Location,
        /// The NPTS found.
        found: usize,
    },

    /// dt (from a header, a time column or the caller) is not positive.
    #[error("{at}: dt must be > 0, found {}", shown(*.found))]
    InvalidDt {
        /// Where in the file.
        at: Location,
        /// The dt found, s.
        found: f64,
    },

    /// dt is NaN or infinite.
    #[error("{at}: dt must be a finite number, found {}", shown(*.found))]
    NonFiniteDt {
        /// Where in the file.
        at: Location,
        /// The dt found.
        found: f64,
    },

    /// dt is below [`MIN_DT`](super::MIN_DT).
    #[error(
        "{at}: dt = {} s is below the smallest sampling interval accepted, {} s (100 kHz; \
         accelerographs sample at 100 Hz to a few kHz)",
        shown(*.found), shown(*.limit)
    )]
    DtTooSmall {
        /// Where in the file.
        at: Location,
        /// The dt found, s.
        found: f64,
        /// The smallest dt accepted, s.
        limit: f64,
    },

    /// A value does not parse as a number.
    #[error("{at}: value {token:?} is not a number")]
    NotANumber {
        /// Where in the file.
        at: Location,
        /// The text of the value.
        token: String,
    },

    /// A value is NaN or infinite.
    #[error("{at}: value {token:?} is NaN or infinite")]
    NotFinite {
        /// Where in the file.
        at: Location,
        /// The text of the value.
        token: String,
    },

    /// An AT2 file has no values after its header.
    #[error("{file}: no values after the header (header says NPTS={declared})")]
    NoValues {
        /// The record file.
        file: String,
        /// The NPTS of the header.
        declared: usize,
    },

    /// An AT2 file has fewer values than its NPTS.
    #[error(
        "{file}: header says NPTS={declared} but the file has {found} values (truncated file?)"
    )]
    TooFewValues {
        /// The record file.
        file: String,
        /// The NPTS of the header.
        declared: usize,
        /// The number of values found.
        found: usize,
    },

    /// An AT2 file has more values than its NPTS.
    #[error("{file}: header says NPTS={declared} but the file has {found} values")]
    TooManyValues {
        /// The record file.
        file: String,
        /// The NPTS of the header.
        declared: usize,
        /// The number of values found.
        found: usize,
    },

    /// A CSV file has no data rows.
    #[error("{file}: no data rows")]
    NoRows {
        /// The record file.
        file: String,
    },

    /// The first row of a CSV file has neither 1 nor 2 columns.
    #[error("{at}: expected 1 column (acc) or 2 columns (t, acc), found {found}")]
    BadColumnCount {
        /// Where in the file.
        at: Location,
        /// The number of columns found.
        found: usize,
    },

    /// A CSV row has a different number of fields than the first row.
    #[error("{at}: expected {expected} fields like the first row, found {found}")]
    RaggedRow {
        /// Where in the file.
        at: Location,
        /// The number of fields of the first row.
        expected: usize,
        /// The number of fields of this row.
        found: usize,
    },

    /// A one-column CSV file was read without a dt.
    #[error("{file}: a one-column CSV file needs dt from the caller, none was given")]
    MissingDt {
        /// The record file.
        file: String,
    },

    /// A two-column CSV file has one row, too few to give dt.
    #[error("{file}: a time column needs at least 2 rows to give dt, found 1")]
    TooFewRowsForDt {
        /// The record file.
        file: String,
    },

    /// The time column of a CSV file does not start at 0.
    #[error("{at}: the time column must start at 0, found {}", shown(*.found))]
    TimeNotFromZero {
        /// Where in the file.
        at: Location,
        /// The first time, s.
        found: f64,
    },

    /// The time column of a CSV file is not uniformly spaced.
    #[error(
        "{at}: time step {} differs from the mean step {} by more than 1e-6 relative \
         (the time column must be uniformly spaced)",
        shown(*.step), shown(*.mean)
    )]
    NonUniformTime {
        /// Where in the file.
        at: Location,
        /// The step found there, s.
        step: f64,
        /// The mean step of the column, s.
        mean: f64,
    },

    /// The dt given and the dt of the file disagree.
    #[error("{file}: dt given as {} but the file says {}", shown(*.given), shown(*.found))]
    DtConflict {
        /// The record file.
        file: String,
        /// The dt given by the caller, s.
        given: f64,
        /// The dt of the file, s.
        found: f64,
    },

    /// The file holds a velocity or a displacement, not an acceleration.
    #[error(
        "{at}: the file holds a {} time series ({found:?}), not an acceleration; flexrock reads \
         ground accelerations only and does not differentiate: give the acceleration record of \
         the same motion",
        .quantity.name()
    )]
    NotAcceleration {
        /// Where the file says what it holds.
        at: Location,
        /// What it holds.
        quantity: super::Quantity,
        /// The words that say so.
        found: String,
    },

    /// A header names a unit flexrock does not know.
    #[error(
        "{at}: unknown unit {found:?} (the units of acceleration read: g, cm/s2 (also written \
         cm/sec/sec, cm/s^2, gal), m/s2)"
    )]
    UnknownUnit {
        /// Where in the file.
        at: Location,
        /// The unit as written.
        found: String,
    },

    /// A header breaks a rule of its format.
    #[error("{at}: {rule}")]
    HeaderRule {
        /// Where in the file.
        at: Location,
        /// The rule, with what was found.
        rule: String,
    },
}

/// A number in a message (shortest exact form: `1e-300`, not 300 zeros).
fn shown(x: f64) -> String {
    crate::base::format::shortest(x)
}
