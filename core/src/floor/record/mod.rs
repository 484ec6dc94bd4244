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

mod at2;
mod cosmos;
mod csv;
mod error;
mod esm;
mod meta;
mod samples;
pub mod suite;
#[cfg(test)]
mod tests;

use std::path::Path;

pub use at2::parse_at2;
pub use cosmos::parse_cosmos;
pub use csv::{parse_csv, parse_text};
pub use error::{Location, RecordError};
pub use esm::parse_esm;
pub use meta::{resolve_units, unit_of, Quantity, RecordMeta};
pub use samples::{check_sample_dt, dt_from_times, record_from_samples, MAX_RECORD_SAMPLES};

/// An accelerogram sampled at a uniform interval.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The file name as given, for messages.
    pub source: String,
    /// The header lines before the NPTS line (event/station lines); for CSV the row of column
    /// names, if the file has one.
    pub title: Vec<String>,
    /// Sampling interval, s.
    pub dt: f64,
    /// The values as in the file (units of the file, e.g. g).
    pub values: Vec<f64>,
    /// What the file says about itself: its units, event, station, component...
    pub meta: RecordMeta,
}

impl Record {
    /// Time of the last value, `(n - 1) * dt`, s (0 for fewer than two values).
    pub fn duration(&self) -> f64 {
        self.values.len().saturating_sub(1) as f64 * self.dt
    }

    /// The value of largest magnitude (with its sign) and its time, s. The first one wins a tie;
    /// `(0.0, 0.0)` for a record without values.
    pub fn peak(&self) -> (f64, f64) {
        let mut peak_index = 0;
        let mut peak_value = 0.0_f64;
        for (index, &value) in self.values.iter().enumerate() {
            if value.abs() > peak_value.abs() {
                peak_index = index;
                peak_value = value;
            }
        }
        (peak_value, peak_index as f64 * self.dt)
    }
}

/// Names of the units of acceleration a record may be in (the values of `excitation.units` and
/// `--units`), for messages.
pub const UNIT_NAMES: &str = "\"g\", \"m/s2\" or \"cm/s2\"";

/// The canonical name of the unit `units` named by the key or flag `key`, and its factor to
/// m/s^2 (g is standard gravity, whatever a body's `gravity`).
pub fn acceleration_unit(
    key: &str,
    units: &str,
) -> Result<(&'static str, f64), crate::base::invalid::InvalidParameter> {
    match units {
        "g" => Ok(("g", crate::base::units::STANDARD_GRAVITY)),
        "m/s2" => Ok(("m/s2", 1.0)),
        "cm/s2" => Ok(("cm/s2", 0.01)),
        other => Err(crate::base::invalid::InvalidParameter::new(
            key,
            format!("\"{other}\""),
            &format!("must be {UNIT_NAMES}"),
        )),
    }
}

/// The file layouts [`read_record`] understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RecordFormat {
    /// PEER Strong Motion Database "AT2" text file.
    PeerAt2,
    /// Comma-separated values: `t, acc` or `acc`.
    Csv,
    /// Whitespace-separated columns: `t acc` or `acc`.
    Text,
    /// COSMOS Strong Motion Data Format, V1 or V2 (one channel).
    Cosmos,
    /// ESM (Engineering Strong Motion database) or ITACA ASCII: `KEY: VALUE` lines, then values.
    Esm,
}

impl RecordFormat {
    /// Every format, in the order of [`RecordFormat::NAMES`].
    pub const ALL: [RecordFormat; 5] = [
        RecordFormat::PeerAt2,
        RecordFormat::Csv,
        RecordFormat::Text,
        RecordFormat::Cosmos,
        RecordFormat::Esm,
    ];

    /// The names of the formats as a model file or a flag gives them, for messages.
    pub const NAMES: &'static str = "\"peer-at2\", \"csv\", \"text\", \"cosmos\" or \"esm\"";

    /// The format's name in a model file, a flag and a record's metadata.
    pub fn name(self) -> &'static str {
        match self {
            RecordFormat::PeerAt2 => "peer-at2",
            RecordFormat::Csv => "csv",
            RecordFormat::Text => "text",
            RecordFormat::Cosmos => "cosmos",
            RecordFormat::Esm => "esm",
        }
    }

    /// The format named `name` by a model file key or flag `key`.
    pub fn from_name(
        key: &str,
        name: &str,
    ) -> Result<Self, crate::base::invalid::InvalidParameter> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                crate::base::invalid::InvalidParameter::new(
                    key,
                    format!("\"{name}\""),
                    &format!("must be {}", Self::NAMES),
                )
            })
    }

    /// The format implied by a file's extension, any letter case: `.AT2` (PEER; also its
    /// velocity and displacement files `.VT2` and `.DT2`, which the reader refuses by what their
    /// header says they hold), `.csv`, `.txt` and `.dat` (text), `.V1`, `.V2`, `.V1c`, `.V2c`
    /// (COSMOS), `.ASC` (ESM).
    pub fn from_extension(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match extension.as_str() {
            "at2" | "vt2" | "dt2" => Self::PeerAt2,
            "csv" => Self::Csv,
            "txt" | "dat" => Self::Text,
            "v1" | "v2" | "v1c" | "v2c" => Self::Cosmos,
            "asc" => Self::Esm,
            _ => return None,
        })
    }

    /// The format a file's first line shows: COSMOS files name their layout there
    /// (`Corrected acceleration    (Format v01.20 with 13 text lines)`), ESM and ITACA files
    /// start with `EVENT_NAME:`.
    pub fn from_content(text: &str) -> Option<Self> {
        let first = strip_byte_order_mark(text).lines().next()?;
        if first.starts_with("EVENT_NAME:") {
            Some(Self::Esm)
        } else if first.to_ascii_lowercase().contains("(format v") {
            Some(Self::Cosmos)
        } else {
            None
        }
    }

    /// The format of the file `path` of text `text`: its extension's for `.AT2`, `.csv`, COSMOS
    /// and ESM extensions; else the one its first line shows; else text for `.txt` and `.dat`.
    pub fn detect(path: &Path, text: &str) -> Option<Self> {
        match Self::from_extension(path) {
            Some(Self::Text) | None => Self::from_content(text).or(Self::from_extension(path)),
            known => known,
        }
    }
}

/// Tolerance, relative to dt, for a uniform time column and for agreeing dt values.
const RELATIVE_DT_TOLERANCE: f64 = 1e-6;

/// Longest piece of file text quoted in a message, in characters.
const MAX_QUOTED_CHARS: usize = 80;

/// Smallest sampling interval accepted, s (100 kHz). Strong-motion accelerographs sample at
/// 100 Hz to a few kHz (dt from 0.01 s down to a few 1e-4 s); a smaller dt is a mistake in the
/// file (or a unit other than seconds), and every sample is a stop time of the adaptive solver.
pub const MIN_DT: f64 = 1e-5;

/// Largest record file read, bytes (64 MiB). The largest real AT2 files are a few MB (a long
/// record at 200 Hz has some 60 000 values, 10-16 characters each).
pub const MAX_RECORD_BYTES: u64 = 64 * 1024 * 1024;

/// A number in a message (shortest exact form: `1e-300`, not 300 zeros).
fn shown(x: f64) -> String {
    crate::base::format::shortest(x)
}

/// Why a token is not a usable value.
enum NumberError {
    NotANumber,
    NotFinite,
}

/// A finite number in Rust/Fortran free form (`-0.00128`, `.1181069E-02`, `1e5`).
fn parse_number(token: &str) -> Result<f64, NumberError> {
    match token.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        Ok(_) => Err(NumberError::NotFinite),
        Err(_) => Err(NumberError::NotANumber),
    }
}

/// `text` cut to at most [`MAX_QUOTED_CHARS`] characters, for quoting in a message.
fn quote(text: &str) -> String {
    let mut chars = text.chars();
    let mut quoted: String = chars.by_ref().take(MAX_QUOTED_CHARS).collect();
    if chars.next().is_some() {
        quoted.push_str("...");
    }
    quoted
}

/// The lines of `text` without line ends (`\n` or `\r\n`), numbered from 1.
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(index, line)| (index + 1, line))
}

fn strip_byte_order_mark(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// `text` without the prefix `prefix` (compared ignoring ASCII case), if it starts with it.
fn strip_prefix_ignore_case<'a>(text: &'a str, prefix: &str) -> Option<&'a str> {
    let head = text.get(..prefix.len())?;
    if head.eq_ignore_ascii_case(prefix) {
        text.get(prefix.len()..)
    } else {
        None
    }
}

/// Which rule of a sampling interval a dt breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DtRule {
    NotFinite,
    NotPositive,
    BelowMinimum,
}

/// The rule the sampling interval `dt` breaks, if any: it must be finite, > 0 and at least
/// [`MIN_DT`], an inclusive limit (a mean step of a time column in steps of 1e-5 s, which rounds
/// to 9.999999999999999e-6, passes). The one rule of a dt read from a file, given with it or
/// given with samples in memory.
fn dt_rule(dt: f64) -> Option<DtRule> {
    if !dt.is_finite() {
        Some(DtRule::NotFinite)
    } else if dt <= 0.0 {
        Some(DtRule::NotPositive)
    } else if !crate::base::limits::at_least(dt, MIN_DT) {
        Some(DtRule::BelowMinimum)
    } else {
        None
    }
}

/// Checks that a dt is finite, > 0 and at least [`MIN_DT`] ([`dt_rule`]).
fn check_dt(dt: f64, at: Location) -> Result<f64, RecordError> {
    match dt_rule(dt) {
        Some(DtRule::NotFinite) => Err(RecordError::NonFiniteDt { at, found: dt }),
        Some(DtRule::NotPositive) => Err(RecordError::InvalidDt { at, found: dt }),
        Some(DtRule::BelowMinimum) => Err(RecordError::DtTooSmall {
            at,
            found: dt,
            limit: MIN_DT,
        }),
        None => Ok(dt),
    }
}

/// Whether two dt values agree to [`RELATIVE_DT_TOLERANCE`].
fn dt_agrees(a: f64, b: f64) -> bool {
    (a - b).abs() <= RELATIVE_DT_TOLERANCE * a.abs().max(b.abs())
}

/// Fewest values a record may have: a(t) is linear between samples, so one sample defines no
/// motion (its duration would be 0).
pub const MIN_SAMPLES: usize = 2;

/// Refuses a record of fewer than [`MIN_SAMPLES`] values.
fn check_samples(values: &[f64], file: &str) -> Result<(), RecordError> {
    if values.len() < MIN_SAMPLES {
        return Err(RecordError::TooFewSamples {
            file: file.to_string(),
            found: values.len(),
        });
    }
    Ok(())
}

/// The text of a file's bytes; invalid UTF-8 is an error naming the line and byte offset.
fn decode_utf8(bytes: Vec<u8>, source: &str) -> Result<String, RecordError> {
    String::from_utf8(bytes).map_err(|error| {
        let byte_offset = error.utf8_error().valid_up_to();
        let valid_part = error.as_bytes().get(..byte_offset).unwrap_or(&[]);
        let line = 1 + valid_part.iter().filter(|&&byte| byte == b'\n').count();
        RecordError::NotUtf8 {
            at: Location::line(source, line),
            byte_offset,
        }
    })
}

/// The bytes of a record file: only a regular file (checked before opening it, so that a FIFO
/// does not block and /dev/zero is not read), of at most [`MAX_RECORD_BYTES`] (checked before
/// reading, and enforced while reading in case the file grows).
fn read_bounded(path: &Path, source: &str) -> Result<Vec<u8>, RecordError> {
    use std::io::Read as _;
    let read_error = |error| RecordError::Read {
        file: source.to_string(),
        error,
    };
    let too_large = |size| RecordError::TooLarge {
        file: source.to_string(),
        size,
        limit: MAX_RECORD_BYTES,
    };
    let metadata = std::fs::metadata(path).map_err(read_error)?;
    if !metadata.is_file() {
        return Err(RecordError::NotRegularFile {
            file: source.to_string(),
            found: crate::base::format::file_kind(metadata.file_type()),
        });
    }
    if metadata.len() > MAX_RECORD_BYTES {
        return Err(too_large(metadata.len()));
    }
    let file = std::fs::File::open(path).map_err(read_error)?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(MAX_RECORD_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_RECORD_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Reads a record file. Without `format`, [`RecordFormat::detect`] tells it from the extension
/// and the first line. `dt` is required for one-column CSV and text; otherwise, if given, it
/// must agree with the file's dt to 1e-6 relative.
pub fn read_record(
    path: &Path,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    read_record_named(path, &path.display().to_string(), format, dt)
}

/// [`read_record`], with the file named `name` in every error (a full path, say, where `path`
/// is relative to another directory); the record's source is `path` as given.
pub fn read_record_named(
    path: &Path,
    name: &str,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    let mut record = read_named(path, name, format, dt)?;
    record.source = path.display().to_string();
    Ok(record)
}

fn read_named(
    path: &Path,
    name: &str,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    let source = name.to_string();
    let bytes = read_bounded(path, &source)?;
    let text = decode_utf8(bytes, &source)?;
    let format = match format.or_else(|| RecordFormat::detect(path, &text)) {
        Some(format) => format,
        None => {
            return Err(RecordError::UnknownFormat {
                extension: path
                    .extension()
                    .map(|extension| extension.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                file: source,
            })
        }
    };
    let record = match format {
        RecordFormat::Csv => return parse_csv(&text, &source, dt),
        RecordFormat::Text => return parse_text(&text, &source, dt),
        RecordFormat::PeerAt2 => parse_at2(&text, &source)?,
        RecordFormat::Cosmos => parse_cosmos(&text, &source)?,
        RecordFormat::Esm => parse_esm(&text, &source)?,
    };
    if let Some(given) = dt {
        let given = check_dt(given, Location::file(&source))?;
        if !dt_agrees(given, record.dt) {
            return Err(RecordError::DtConflict {
                file: source,
                given,
                found: record.dt,
            });
        }
    }
    Ok(record)
}
