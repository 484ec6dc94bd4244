//! Ground-motion records: reading accelerograms from PEER "AT2" files and simple CSV files.
//!
//! # PEER AT2
//!
//! Four header lines, then the values:
//!
//! - lines 1-3: free text (database, event/station/component, units); kept in [`Record::title`];
//! - line 4: the number of points and the sampling interval, as `NPTS=<count>, DT=<seconds>`
//!   with case-insensitive keys, an optional comma and an optional unit word (`SEC`, `S`,
//!   `SECS`, `SECOND`, `SECONDS`; a trailing comma as in PEER NGA files), e.g.
//!   `NPTS=  1559, DT= .02000 SEC`, `NPTS=   1451, dt=  .02000`, `NPTS=   7998, DT=   .0050 SEC,`;
//!   or the older layout `<count> <seconds> NPTS, DT`, e.g. `3930 0.00500 NPTS, DT`;
//! - lines 5 onwards: the values, any number per line, separated by whitespace (typically the
//!   Fortran layouts 8F10.5 or 5E15.7). A line whose whitespace-separated tokens are not all
//!   numbers is read again as fixed-width fields of 10 or 15 characters, so that fields that
//!   touch (`-100.12345-100.12345`) are still read. Where both widths read such a line, the
//!   file's layout decides: the width the other lines are laid out in (their length per value),
//!   else the one that gives NPTS values.
//!
//! The number of values must equal NPTS; NaN and infinite values are errors; dt must be at
//! least [`MIN_DT`].
//! CRLF line ends, a missing newline after the last value, blank lines and a UTF-8 byte-order
//! mark are accepted.
//!
//! # CSV
//!
//! Comma-separated, one row per sample, either two columns `t, acc` (the time column must start
//! at 0 and be uniformly spaced to 1e-6 relative; dt is derived from it) or one column `acc`
//! (dt must be given by the caller). An optional first row of non-numeric column names is
//! kept in [`Record::title`]. `#` starts a comment that runs to the end of the line; blank
//! lines are skipped.
//!
//! # Files
//!
//! [`read_record`] reads only regular files (not a device such as /dev/zero, a FIFO or a
//! directory) of at most [`MAX_RECORD_BYTES`], checked before reading, through a reader that
//! stops at that limit.
//!
//! Every error names the file, the 1-based line number where there is one, and what was
//! expected and found. No input, however malformed, makes the readers panic.

use std::fmt;
use std::path::Path;

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
) -> Result<(&'static str, f64), crate::invalid::InvalidParameter> {
    match units {
        "g" => Ok(("g", crate::units::STANDARD_GRAVITY)),
        "m/s2" => Ok(("m/s2", 1.0)),
        "cm/s2" => Ok(("cm/s2", 0.01)),
        other => Err(crate::invalid::InvalidParameter::new(
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
}

impl RecordFormat {
    /// The format named `name` (`peer-at2`, `csv`) by a model file key or flag `key`.
    pub fn from_name(key: &str, name: &str) -> Result<Self, crate::invalid::InvalidParameter> {
        match name {
            "peer-at2" => Ok(Self::PeerAt2),
            "csv" => Ok(Self::Csv),
            other => Err(crate::invalid::InvalidParameter::new(
                key,
                format!("\"{other}\""),
                "must be \"peer-at2\" or \"csv\"",
            )),
        }
    }

    /// The format implied by a file's extension (`.AT2`/`.at2`, `.csv`; any letter case).
    pub fn from_extension(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?;
        if extension.eq_ignore_ascii_case("at2") {
            Some(Self::PeerAt2)
        } else if extension.eq_ignore_ascii_case("csv") {
            Some(Self::Csv)
        } else {
            None
        }
    }
}

/// Where in which file something went wrong: displays as `file` or `file line N`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file, as given.
    pub file: String,
    /// 1-based line number, if the problem belongs to one line.
    pub line: Option<usize>,
}

impl Location {
    fn file(file: &str) -> Self {
        Self {
            file: file.to_string(),
            line: None,
        }
    }

    fn line(file: &str, line: usize) -> Self {
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

/// What the 4th line of an AT2 file must look like (used in messages).
const AT2_HEADER_FORM: &str = "\"NPTS=<count>, DT=<seconds>\" in the 4th header line";

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
    crate::format::shortest(x)
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

    /// The file is larger than [`MAX_RECORD_BYTES`].
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
        "{file}: cannot tell the record format from the extension \
         (expected .AT2 or .csv, found {extension:?}); give the format explicitly"
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

    /// The record has fewer than [`MIN_SAMPLES`] values.
    #[error(
        "{file}: the record has {}; a record needs at least 2 samples (one interval of dt) to \
         define the floor acceleration between them",
        crate::format::count(*.found, "sample", "samples")
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

    /// dt is below [`MIN_DT`].
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

/// Splits `text` after its leading characters that satisfy `keep`.
fn split_leading(text: &str, keep: impl Fn(char) -> bool) -> (&str, &str) {
    let end = text.find(|c: char| !keep(c)).unwrap_or(text.len());
    text.split_at(end)
}

/// The count and dt of a `NPTS=<count>[,] DT=<dt> [unit]` line, if it has that form.
fn parse_keyed_header(line: &str) -> Option<(usize, f64)> {
    let rest = strip_prefix_ignore_case(line.trim(), "NPTS")?.trim_start();
    let rest = rest.strip_prefix('=')?.trim_start();
    let (count_text, rest) = split_leading(rest, |c| c.is_ascii_digit());
    let count = count_text.parse::<usize>().ok()?;
    let rest = rest.trim_start();
    let rest = rest.strip_prefix(',').unwrap_or(rest).trim_start();
    let rest = strip_prefix_ignore_case(rest, "DT")?.trim_start();
    let rest = rest.strip_prefix('=')?.trim_start();
    let (dt_text, unit) = split_leading(rest, |c| {
        c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'e' | 'E')
    });
    let dt = dt_text.parse::<f64>().ok()?;
    // PEER NGA files end the line with a comma: `NPTS=   7998, DT=   .0050 SEC,`.
    let unit = unit.trim();
    let unit = unit.strip_suffix(',').unwrap_or(unit).trim_end();
    let unit_is_seconds = ["", "S", "SEC", "SECS", "SECOND", "SECONDS"]
        .iter()
        .any(|allowed| unit.eq_ignore_ascii_case(allowed));
    unit_is_seconds.then_some((count, dt))
}

/// The count and dt of an old-style `<count> <dt> NPTS, DT` line, if it has that form.
fn parse_old_style_header(line: &str) -> Option<(usize, f64)> {
    let without_commas = line.replace(',', " ");
    let words: Vec<&str> = without_commas.split_whitespace().collect();
    match words.as_slice() {
        [count, dt, npts, dt_word]
            if npts.eq_ignore_ascii_case("NPTS") && dt_word.eq_ignore_ascii_case("DT") =>
        {
            Some((count.parse().ok()?, dt.parse().ok()?))
        }
        _ => None,
    }
}

/// Checks that a dt is finite, > 0 and at least [`MIN_DT`].
fn check_dt(dt: f64, at: Location) -> Result<f64, RecordError> {
    if !dt.is_finite() {
        Err(RecordError::NonFiniteDt { at, found: dt })
    } else if dt <= 0.0 {
        Err(RecordError::InvalidDt { at, found: dt })
    } else if dt < MIN_DT {
        Err(RecordError::DtTooSmall {
            at,
            found: dt,
            limit: MIN_DT,
        })
    } else {
        Ok(dt)
    }
}

/// Whether two dt values agree to [`RELATIVE_DT_TOLERANCE`].
fn dt_agrees(a: f64, b: f64) -> bool {
    (a - b).abs() <= RELATIVE_DT_TOLERANCE * a.abs().max(b.abs())
}

/// The numbers of `line` read as consecutive fields of `width` characters, if every field is a
/// finite number and the line (without trailing blanks) is a whole number of fields.
fn parse_fixed_width(line: &str, width: usize) -> Option<Vec<f64>> {
    let chars: Vec<char> = line.trim_end().chars().collect();
    if width == 0 || !chars.len().is_multiple_of(width) {
        return None;
    }
    chars
        .chunks(width)
        .map(|field| {
            let field: String = field.iter().collect();
            parse_number(field.trim()).ok()
        })
        .collect()
}

/// Fortran field widths of AT2 layouts: 8F10.5 and 5E15.7.
const AT2_FIELD_WIDTHS: [usize; 2] = [10, 15];

/// One AT2 data line, read.
enum At2Line {
    /// Whitespace-separated numbers; the field width the line is laid out in, if its length is
    /// a whole number of fields of 10 or 15 characters (`   .1181069E-02  -.1366453E-02`: 15).
    Tokens {
        values: Vec<f64>,
        width: Option<usize>,
    },
    /// Fields that touch (`-100.12345-100.12345`), read as fixed-width fields of 10 and of 15
    /// characters (None where that width does not read).
    Touching {
        ten: Option<Vec<f64>>,
        fifteen: Option<Vec<f64>>,
    },
}

/// Reads one AT2 data line; an error names the first token that is not a finite number when the
/// line reads neither as whitespace-separated numbers nor as fixed-width fields.
fn parse_at2_values_line(line: &str, at: impl Fn() -> Location) -> Result<At2Line, RecordError> {
    let mut values = Vec::new();
    for token in line.split_whitespace() {
        match parse_number(token) {
            Ok(value) => values.push(value),
            Err(NumberError::NotFinite) => {
                return Err(RecordError::NotFinite {
                    at: at(),
                    token: quote(token),
                })
            }
            Err(NumberError::NotANumber) => {
                // Fortran fields may touch each other ("-100.12345-100.12345"): read the line
                // again as fixed-width fields before giving up.
                let ten = parse_fixed_width(line, AT2_FIELD_WIDTHS[0]);
                let fifteen = parse_fixed_width(line, AT2_FIELD_WIDTHS[1]);
                if ten.is_none() && fifteen.is_none() {
                    return Err(RecordError::NotANumber {
                        at: at(),
                        token: quote(token),
                    });
                }
                return Ok(At2Line::Touching { ten, fifteen });
            }
        }
    }
    let length = line.trim_end().chars().count();
    let width = AT2_FIELD_WIDTHS
        .into_iter()
        .find(|&w| !values.is_empty() && length == w * values.len());
    Ok(At2Line::Tokens { values, width })
}

/// The values of an AT2 file's data lines. A line of touching fields may read both as 10- and
/// as 15-character fields (`-0.0001234567890.0009876543210` is two F15 fields, or three
/// nonsense F10 ones); its width is the file's: the one that the other lines are laid out in
/// (by their length per value, or by reading at one width only), else the one that gives the
/// header's NPTS values, else 10.
fn at2_values(lines: Vec<At2Line>, declared_count: usize) -> Vec<f64> {
    let mut votes = [0usize; 2];
    for line in &lines {
        let width = match line {
            At2Line::Tokens { width, .. } => *width,
            At2Line::Touching { ten, fifteen } => match (ten, fifteen) {
                (Some(_), None) => Some(AT2_FIELD_WIDTHS[0]),
                (None, Some(_)) => Some(AT2_FIELD_WIDTHS[1]),
                _ => None,
            },
        };
        if let Some(w) = width {
            votes[usize::from(w == AT2_FIELD_WIDTHS[1])] += 1;
        }
    }
    let values_at = |fifteen_wide: bool| -> Vec<f64> {
        lines
            .iter()
            .flat_map(|line| match line {
                At2Line::Tokens { values, .. } => values.clone(),
                At2Line::Touching { ten, fifteen } => {
                    let (preferred, other) = if fifteen_wide {
                        (fifteen, ten)
                    } else {
                        (ten, fifteen)
                    };
                    preferred
                        .clone()
                        .or_else(|| other.clone())
                        .unwrap_or_default()
                }
            })
            .collect()
    };
    let fifteen_wide = match votes {
        [ten, fifteen] if fifteen > ten => true,
        [ten, fifteen] if ten > fifteen => false,
        _ => values_at(true).len() == declared_count && values_at(false).len() != declared_count,
    };
    values_at(fifteen_wide)
}

/// Reads a PEER AT2 record from its text. `source` names the file in messages.
pub fn parse_at2(text: &str, source: &str) -> Result<Record, RecordError> {
    let text = strip_byte_order_mark(text);
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            file: source.to_string(),
        });
    }

    let mut lines = numbered_lines(text);
    let title: Vec<String> = lines
        .by_ref()
        .take(3)
        .map(|(_, line)| line.trim_end().to_string())
        .collect();
    let Some((header_line_number, header_line)) = lines.next() else {
        return Err(RecordError::TooFewHeaderLines {
            file: source.to_string(),
            found: title.len(),
        });
    };
    let header_at = || Location::line(source, header_line_number);

    let (declared_count, dt) = parse_keyed_header(header_line)
        .or_else(|| parse_old_style_header(header_line))
        .ok_or_else(|| RecordError::BadHeader {
            at: header_at(),
            expected: AT2_HEADER_FORM,
            found: quote(header_line.trim_end()),
        })?;
    if declared_count == 0 {
        return Err(RecordError::InvalidCount {
            at: header_at(),
            found: declared_count,
        });
    }
    let dt = check_dt(dt, header_at())?;

    let data_lines = lines
        .map(|(line_number, line)| {
            parse_at2_values_line(line, || Location::line(source, line_number))
        })
        .collect::<Result<Vec<At2Line>, RecordError>>()?;
    let values = at2_values(data_lines, declared_count);

    let file = source.to_string();
    if values.is_empty() {
        return Err(RecordError::NoValues {
            file,
            declared: declared_count,
        });
    }
    if values.len() < declared_count {
        return Err(RecordError::TooFewValues {
            file,
            declared: declared_count,
            found: values.len(),
        });
    }
    if values.len() > declared_count {
        return Err(RecordError::TooManyValues {
            file,
            declared: declared_count,
            found: values.len(),
        });
    }

    check_samples(&values, &file)?;
    Ok(Record {
        source: file,
        title,
        dt,
        values,
    })
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

/// One CSV data row: its line number and its numbers.
struct CsvRow {
    line_number: usize,
    fields: Vec<f64>,
}

/// Reads a CSV record from its text: two columns `t, acc` (uniform t from 0; dt derived and, if
/// `dt` is given, checked against it) or one column `acc` (then `dt` is required).
pub fn parse_csv(text: &str, source: &str, dt: Option<f64>) -> Result<Record, RecordError> {
    let text = strip_byte_order_mark(text);
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            file: source.to_string(),
        });
    }

    let mut rows: Vec<CsvRow> = Vec::new();
    let mut title = Vec::new();
    let mut column_count: Option<usize> = None;
    for (line_number, line) in numbered_lines(text) {
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let at = || Location::line(source, line_number);
        let fields: Vec<&str> = content.split(',').map(str::trim).collect();

        match column_count {
            None => {
                if !matches!(fields.len(), 1 | 2) {
                    return Err(RecordError::BadColumnCount {
                        at: at(),
                        found: fields.len(),
                    });
                }
                column_count = Some(fields.len());
                let is_header_row = fields
                    .iter()
                    .all(|field| matches!(parse_number(field), Err(NumberError::NotANumber)));
                if is_header_row {
                    title.push(content.to_string());
                    continue;
                }
            }
            Some(expected) if fields.len() != expected => {
                return Err(RecordError::RaggedRow {
                    at: at(),
                    expected,
                    found: fields.len(),
                });
            }
            Some(_) => {}
        }

        let numbers = fields
            .iter()
            .map(|field| match parse_number(field) {
                Ok(value) => Ok(value),
                Err(NumberError::NotANumber) => Err(RecordError::NotANumber {
                    at: at(),
                    token: quote(field),
                }),
                Err(NumberError::NotFinite) => Err(RecordError::NotFinite {
                    at: at(),
                    token: quote(field),
                }),
            })
            .collect::<Result<Vec<f64>, RecordError>>()?;
        rows.push(CsvRow {
            line_number,
            fields: numbers,
        });
    }

    if rows.is_empty() {
        return Err(RecordError::NoRows {
            file: source.to_string(),
        });
    }

    let has_time_column = column_count == Some(2);
    let record_dt = if has_time_column {
        let derived = dt_from_time_column(&rows, source)?;
        if let Some(given) = dt {
            let given = check_dt(given, Location::file(source))?;
            if !dt_agrees(given, derived) {
                return Err(RecordError::DtConflict {
                    file: source.to_string(),
                    given,
                    found: derived,
                });
            }
        }
        derived
    } else {
        let given = dt.ok_or_else(|| RecordError::MissingDt {
            file: source.to_string(),
        })?;
        check_dt(given, Location::file(source))?
    };

    let values: Vec<f64> = rows
        .iter()
        .filter_map(|row| row.fields.last().copied())
        .collect();
    check_samples(&values, source)?;
    Ok(Record {
        source: source.to_string(),
        title,
        dt: record_dt,
        values,
    })
}

/// The sampling interval of a uniform time column starting at 0 (the first field of each row).
fn dt_from_time_column(rows: &[CsvRow], source: &str) -> Result<f64, RecordError> {
    let times: Vec<(usize, f64)> = rows
        .iter()
        .filter_map(|row| Some((row.line_number, *row.fields.first()?)))
        .collect();
    let (Some(&(first_line, first_time)), Some(&(_, last_time))) = (times.first(), times.last())
    else {
        return Err(RecordError::NoRows {
            file: source.to_string(),
        });
    };
    if times.len() < 2 {
        return Err(RecordError::TooFewRowsForDt {
            file: source.to_string(),
        });
    }

    let mean_step = (last_time - first_time) / (times.len() - 1) as f64;
    let dt = check_dt(mean_step, Location::file(source))?;
    if first_time.abs() > RELATIVE_DT_TOLERANCE * dt {
        return Err(RecordError::TimeNotFromZero {
            at: Location::line(source, first_line),
            found: first_time,
        });
    }
    for pair in times.windows(2) {
        if let [(_, previous), (line_number, time)] = pair {
            let step = time - previous;
            if (step - dt).abs() > RELATIVE_DT_TOLERANCE * dt {
                return Err(RecordError::NonUniformTime {
                    at: Location::line(source, *line_number),
                    step,
                    mean: dt,
                });
            }
        }
    }
    Ok(dt)
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
            found: crate::format::file_kind(metadata.file_type()),
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

/// Reads a record file. Without `format`, the extension decides (`.AT2`/`.at2`: PEER AT2,
/// `.csv`: CSV). `dt` is required for one-column CSV; otherwise, if given, it must agree with
/// the file's dt to 1e-6 relative.
pub fn read_record(
    path: &Path,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    let source = path.display().to_string();
    let format = match format.or_else(|| RecordFormat::from_extension(path)) {
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
    let bytes = read_bounded(path, &source)?;
    let text = decode_utf8(bytes, &source)?;
    match format {
        RecordFormat::Csv => parse_csv(&text, &source, dt),
        RecordFormat::PeerAt2 => {
            let record = parse_at2(&text, &source)?;
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const EL_CENTRO: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/records/elCentro.AT2"
    );
    const ANLA196: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/records/ANLA196.AT2"
    );

    fn read_text(path: &str) -> String {
        std::fs::read_to_string(path).unwrap_or_else(|error| panic!("cannot read {path}: {error}"))
    }

    fn el_centro_text() -> String {
        read_text(EL_CENTRO)
    }

    fn parse_el_centro(text: &str) -> Result<Record, RecordError> {
        parse_at2(text, "elCentro.AT2")
    }

    /// The Display message of an error that must occur.
    fn error_message<T: fmt::Debug>(result: Result<T, RecordError>) -> String {
        match result {
            Ok(value) => panic!("expected an error, got {value:?}"),
            Err(error) => error.to_string(),
        }
    }

    fn assert_close(actual: f64, expected: f64) {
        assert!(
            (actual - expected).abs() <= 1e-12 * expected.abs().max(1.0),
            "expected {expected}, got {actual}"
        );
    }

    /// A small valid AT2 text mixing the 5E15.7 and 8F10.5 layouts (6 values).
    const SMALL_AT2: &str = "PEER STRONG MOTION DATABASE RECORD.\n\
        SOME EVENT, SOME STATION, 090\n\
        ACCELERATION TIME HISTORY IN UNITS OF G\n\
        NPTS=   6, DT= .01000 SEC\n\
        \x20  .1181069E-02  -.1366453E-02   .9006674E-03\n\
        \x20 -0.00128   0.00368   0.00864\n";

    // --- the validation records ---------------------------------------------------------------

    #[test]
    fn el_centro_count_dt_title_first_and_last_values() {
        let record = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
        assert_eq!(record.values.len(), 1559);
        assert_close(record.dt, 0.02);
        assert_eq!(record.title.len(), 3);
        assert_eq!(
            record.title[0],
            "Data for El Centro 1940 North South Component (Peknold Version)"
        );
        assert_eq!(record.title[2], "The units are (g)");
        // From the file text: line 5 starts "   0.00630", the file ends "   0.00000".
        assert_close(record.values[0], 0.00630);
        assert_close(record.values[1], 0.00364);
        assert_close(record.values[1558], 0.00000);
        assert_close(record.values[1557], -0.00006);
        assert_close(record.duration(), 1558.0 * 0.02);
    }

    #[test]
    fn el_centro_peak_value_and_time() {
        // Computed independently with awk over the values after line 4: the largest magnitude
        // is -0.31882, the 102nd value (index 101, line 17), so t = 101 * 0.02 s = 2.02 s.
        let record = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
        let (peak, time) = record.peak();
        assert_close(peak, -0.31882);
        assert_close(time, 2.02);
    }

    #[test]
    fn anla196_count_dt_title_first_and_last_values() {
        let record = parse_at2(&read_text(ANLA196), "ANLA196.AT2").expect("ANLA196.AT2 parses");
        assert_eq!(record.values.len(), 1451);
        assert_close(record.dt, 0.02);
        assert_eq!(
            record.title[1],
            "BORAH PEAK EQ, 10/28/83, 14:06, ANL-767 REACTOR PLANT (BASEMENT), 196"
        );
        // From the file text: line 5 starts "  -.1941782E-03", the last line is "  -.8501408E-05".
        assert_close(record.values[0], -0.1941782e-3);
        assert_close(record.values[1], -0.9395342e-3);
        assert_close(record.values[1450], -0.8501408e-5);
        assert_close(record.values[1449], -0.6450653e-5);
    }

    #[test]
    fn read_record_detects_at2_by_extension_and_names_the_path() {
        let record = read_record(Path::new(EL_CENTRO), None, None).expect("elCentro.AT2 reads");
        assert_eq!(record.source, EL_CENTRO);
        let parsed = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
        assert_eq!(record.values, parsed.values);
        assert_eq!(record.title, parsed.title);

        let with_dt = read_record(Path::new(ANLA196), Some(RecordFormat::PeerAt2), Some(0.02));
        assert_eq!(with_dt.expect("ANLA196.AT2 reads").values.len(), 1451);
        let message = error_message(read_record(Path::new(ANLA196), None, Some(0.01)));
        assert!(
            message.contains("dt given as 0.01 but the file says 0.02"),
            "{message}"
        );
    }

    #[test]
    fn crlf_and_trailing_blank_lines_parse_identically() {
        let text = el_centro_text();
        let original = parse_el_centro(&text).expect("elCentro.AT2 parses");
        let crlf = text.replace('\n', "\r\n");
        assert!(crlf.contains("\r\n"));
        assert_eq!(parse_el_centro(&crlf).expect("CRLF parses"), original);
        let padded = format!("{crlf}\r\n\r\n   \r\n\n");
        assert_eq!(parse_el_centro(&padded).expect("padded parses"), original);
        let with_bom = format!("\u{feff}{text}");
        assert_eq!(parse_el_centro(&with_bom).expect("BOM parses"), original);
    }

    // --- AT2 errors ---------------------------------------------------------------------------

    #[test]
    fn dropped_last_value_fails_with_the_count_message() {
        let text = el_centro_text();
        let truncated = text
            .trim_end()
            .strip_suffix("0.00000")
            .expect("elCentro.AT2 ends with 0.00000");
        let message = error_message(parse_el_centro(truncated));
        assert_eq!(
            message,
            "elCentro.AT2: header says NPTS=1559 but the file has 1558 values (truncated file?)"
        );
    }

    #[test]
    fn an_extra_value_fails_with_the_count_message() {
        let text = format!("{}   0.00001\n", el_centro_text());
        let message = error_message(parse_el_centro(&text));
        assert_eq!(
            message,
            "elCentro.AT2: header says NPTS=1559 but the file has 1560 values"
        );
    }

    #[test]
    fn zero_or_negative_header_dt_fails() {
        let text = el_centro_text();
        let zero = text.replacen("DT= .02000 SEC", "DT= 0 SEC", 1);
        assert_eq!(
            error_message(parse_el_centro(&zero)),
            "elCentro.AT2 line 4: dt must be > 0, found 0"
        );
        let negative = text.replacen("DT= .02000 SEC", "DT= -.02000 SEC", 1);
        assert_eq!(
            error_message(parse_el_centro(&negative)),
            "elCentro.AT2 line 4: dt must be > 0, found -0.02"
        );
        let huge = text.replacen("DT= .02000 SEC", "DT= 1e999 SEC", 1);
        assert_eq!(
            error_message(parse_el_centro(&huge)),
            "elCentro.AT2 line 4: dt must be a finite number, found inf"
        );
    }

    #[test]
    fn malformed_header_line_fails_quoting_it() {
        let text = el_centro_text().replacen("NPTS=  1559, DT= .02000 SEC", "NPTS 1559 DT .02", 1);
        assert_eq!(
            error_message(parse_el_centro(&text)),
            "elCentro.AT2 line 4: expected \"NPTS=<count>, DT=<seconds>\" in the 4th header \
             line, found \"NPTS 1559 DT .02\""
        );
        let no_count = el_centro_text().replacen("NPTS=  1559,", "NPTS=  0,", 1);
        assert_eq!(
            error_message(parse_el_centro(&no_count)),
            "elCentro.AT2 line 4: NPTS must be > 0, found 0"
        );
    }

    #[test]
    fn non_number_token_fails_naming_the_line() {
        // -0.31882 is on line 17 of elCentro.AT2.
        let text = el_centro_text().replacen("-0.31882", " 0.0O123", 1);
        assert_eq!(
            error_message(parse_el_centro(&text)),
            "elCentro.AT2 line 17: value \"0.0O123\" is not a number"
        );
    }

    #[test]
    fn nan_and_infinite_values_fail_naming_the_line() {
        for token in ["     NaN", "     nan", "     inf", "-Infinity", "  1e999 "] {
            let text = el_centro_text().replacen("-0.31882", token, 1);
            let message = error_message(parse_el_centro(&text));
            assert!(
                message.starts_with("elCentro.AT2 line 17: value \"")
                    && message.ends_with("\" is NaN or infinite"),
                "{message}"
            );
        }
    }

    #[test]
    fn empty_file_fails() {
        for text in ["", "   ", "\n\n", "\r\n  \r\n"] {
            assert_eq!(
                error_message(parse_el_centro(text)),
                "elCentro.AT2: empty file"
            );
        }
    }

    #[test]
    fn header_only_fails() {
        let text = el_centro_text();
        let header: String = text
            .lines()
            .take(4)
            .map(|line| format!("{line}\n"))
            .collect();
        assert_eq!(
            error_message(parse_el_centro(&header)),
            "elCentro.AT2: no values after the header (header says NPTS=1559)"
        );
    }

    #[test]
    fn fewer_than_four_header_lines_fails() {
        let text = "Data for El Centro\nThe units are (g)\n";
        assert_eq!(
            error_message(parse_el_centro(text)),
            "elCentro.AT2: fewer than 4 header lines (the file has 2 lines)"
        );
    }

    #[test]
    fn header_variants_are_accepted() {
        let header_lines = [
            "NPTS=  6, DT= .01000 SEC",
            "NPTS=   6, dt=  .01000",
            "NPTS=   6, dt=   .0100 SEC",
            "npts=6 dt=0.01 s",
            "NPTS=6,DT=1.0E-02 seconds",
            "  6  0.01  NPTS, DT",
            "6 .01000 npts,dt",
            "NPTS=   6, DT=   .0100 SEC,",
        ];
        for header_line in header_lines {
            let text = SMALL_AT2.replacen("NPTS=   6, DT= .01000 SEC", header_line, 1);
            let record = parse_at2(&text, "small.AT2")
                .unwrap_or_else(|error| panic!("{header_line:?} rejected: {error}"));
            assert_eq!(record.values.len(), 6);
            assert_close(record.dt, 0.01);
        }
    }

    #[test]
    fn header_variants_are_rejected() {
        let header_lines = [
            "NPTS=6, DT=0.01 MIN",
            "NPTS=6.0, DT=0.01",
            "NPTS=, DT=0.01",
            "NPTS=6",
            "DT=0.01, NPTS=6",
            "NPTS=6, DT=0.01 SEC extra",
            "6 0.01",
            "6 0.01 NPTS, DT, G",
            "   .1181069E-02  -.1366453E-02",
        ];
        for header_line in header_lines {
            let text = SMALL_AT2.replacen("NPTS=   6, DT= .01000 SEC", header_line, 1);
            let message = error_message(parse_at2(&text, "small.AT2"));
            assert!(
                message.starts_with("small.AT2 line 4: expected \"NPTS=<count>, DT=<seconds>\""),
                "{header_line:?}: {message}"
            );
        }
    }

    #[test]
    fn fixed_width_fields_that_touch_are_read() {
        let f10 = SMALL_AT2.replacen(
            "  -0.00128   0.00368   0.00864",
            "-100.12345-200.12345   0.00864",
            1,
        );
        let record = parse_at2(&f10, "f10.AT2").expect("touching F10.5 fields parse");
        assert_eq!(&record.values[3..], &[-100.12345, -200.12345, 0.00864]);

        let e15 = SMALL_AT2.replacen(
            "   .1181069E-02  -.1366453E-02   .9006674E-03",
            "-1.1181069E-002-2.1366453E-002   .9006674E-03",
            1,
        );
        let record = parse_at2(&e15, "e15.AT2").expect("touching E15.7 fields parse");
        assert_eq!(
            &record.values[..3],
            &[-1.1181069e-2, -2.1366453e-2, 0.9006674e-3]
        );

        // Touching fields that are not on a 10- or 15-character grid are an error.
        let misaligned = SMALL_AT2.replacen("  -0.00128   0.00368", " -0.00128-0.00368  ", 1);
        assert_eq!(
            error_message(parse_at2(&misaligned, "bad.AT2")),
            "bad.AT2 line 6: value \"-0.00128-0.00368\" is not a number"
        );
    }

    #[test]
    fn touching_fifteen_character_fields_on_a_line_of_a_multiple_of_ten_are_read_at_15() {
        // Two F15.12 fields that touch, 30 characters: read at 10 they would be three numbers
        // ("-0.0001234", "5678900.00", "0987654321"); the file is laid out in 15-character
        // fields (its other line has 45 characters for 3 values), and NPTS = 5 says so too.
        let text = "PEER\nEVENT\nUNITS OF G\nNPTS=   5, DT= .01000 SEC\n\
            \x20 0.000111111111 -0.000222222222 -0.000333333333\n\
            -0.0001234567890.000987654321\n";
        // (the second field is 15 characters: "0.000987654321" with a trailing "0")
        let text = text.replace("0.000987654321\n", "0.0009876543210\n");
        let record = parse_at2(&text, "f15.AT2").expect("touching F15 fields parse");
        assert_eq!(
            record.values,
            [
                0.000111111111,
                -0.000222222222,
                -0.000333333333,
                -0.000123456789,
                0.000987654321
            ]
        );
        // A file of touching lines only: NPTS decides between 2 values a line and 3.
        let only = "PEER\nEVENT\nUNITS OF G\nNPTS=   4, DT= .01000 SEC\n\
            -0.0001234567890.0009876543210\n\
            -0.0001234567890.0009876543210\n";
        let record = parse_at2(only, "only.AT2").expect("touching F15 fields parse");
        assert_eq!(
            record.values,
            [
                -0.000123456789,
                0.000987654321,
                -0.000123456789,
                0.000987654321
            ]
        );
    }

    #[test]
    fn a_record_of_one_sample_is_refused_naming_the_file() {
        let one = "PEER\nEVENT\nUNITS OF G\nNPTS=   1, DT= .01000 SEC\n   0.00128\n";
        assert_eq!(
            error_message(parse_at2(one, "one.AT2")),
            "one.AT2: the record has 1 sample; a record needs at least 2 samples (one interval \
             of dt) to define the floor acceleration between them"
        );
        assert!(error_message(parse_csv("0.1\n", "one.csv", Some(0.01)))
            .starts_with("one.csv: the record has 1 sample; a record needs at least 2 samples"));
    }

    // --- CSV ----------------------------------------------------------------------------------

    #[test]
    fn csv_with_time_column_derives_dt() {
        let text = "# a comment\nt, acc # names\n0.00, 0.1\n0.01, -0.3\n\n0.02, 0.2\n0.03,0.0\n";
        let record = parse_csv(text, "two.csv", None).expect("two-column CSV parses");
        assert_close(record.dt, 0.01);
        assert_eq!(record.values, vec![0.1, -0.3, 0.2, 0.0]);
        assert_eq!(record.title, vec!["t, acc".to_string()]);
        let (peak, time) = record.peak();
        assert_close(peak, -0.3);
        assert_close(time, 0.01);

        let crlf = text.replace('\n', "\r\n");
        assert_eq!(
            parse_csv(&crlf, "two.csv", Some(0.01)).expect("CRLF parses"),
            record
        );
        assert_eq!(
            error_message(parse_csv(text, "two.csv", Some(0.02))),
            "two.csv: dt given as 0.02 but the file says 0.01"
        );
    }

    #[test]
    fn csv_with_one_column_needs_dt() {
        let text = "acc\n0.1\n-0.3\n0.2\n";
        let record = parse_csv(text, "one.csv", Some(0.005)).expect("one-column CSV parses");
        assert_close(record.dt, 0.005);
        assert_eq!(record.values, vec![0.1, -0.3, 0.2]);
        let no_header = parse_csv("0.1\n-0.3\n0.2", "one.csv", Some(0.005)).expect("parses");
        assert_eq!(no_header.values, record.values);

        assert_eq!(
            error_message(parse_csv(text, "one.csv", None)),
            "one.csv: a one-column CSV file needs dt from the caller, none was given"
        );
        assert_eq!(
            error_message(parse_csv(text, "one.csv", Some(-0.02))),
            "one.csv: dt must be > 0, found -0.02"
        );
        assert_eq!(
            error_message(parse_csv(text, "one.csv", Some(f64::NAN))),
            "one.csv: dt must be a finite number, found NaN"
        );
    }

    #[test]
    fn csv_with_non_uniform_time_column_is_rejected() {
        let text = "t,acc\n0.0,0.1\n0.01,0.2\n0.021,0.3\n0.03,0.4\n";
        let message = error_message(parse_csv(text, "gap.csv", None));
        assert!(
            message.starts_with("gap.csv line 4: time step 0.011")
                && message.contains("(the time column must be uniformly spaced)"),
            "{message}"
        );
        let late_start = "0.01,0.1\n0.02,0.2\n0.03,0.3\n";
        assert_eq!(
            error_message(parse_csv(late_start, "late.csv", None)),
            "late.csv line 1: the time column must start at 0, found 0.01"
        );
        assert_eq!(
            error_message(parse_csv("0.0,0.1\n", "single.csv", None)),
            "single.csv: a time column needs at least 2 rows to give dt, found 1"
        );
        assert_eq!(
            error_message(parse_csv("0.0,0.1\n-0.01,0.2\n", "back.csv", None)),
            "back.csv: dt must be > 0, found -0.01"
        );
    }

    #[test]
    fn csv_errors_name_the_line() {
        assert_eq!(
            error_message(parse_csv("t,acc\n0,0.1\n0.01,x\n", "bad.csv", None)),
            "bad.csv line 3: value \"x\" is not a number"
        );
        assert_eq!(
            error_message(parse_csv("0,0.1\n0.01,NaN\n", "nan.csv", None)),
            "nan.csv line 2: value \"NaN\" is NaN or infinite"
        );
        assert_eq!(
            error_message(parse_csv("0,0.1\n0.01\n", "ragged.csv", None)),
            "ragged.csv line 2: expected 2 fields like the first row, found 1"
        );
        assert_eq!(
            error_message(parse_csv("t,acc,vel\n0,0.1,0\n", "three.csv", None)),
            "three.csv line 1: expected 1 column (acc) or 2 columns (t, acc), found 3"
        );
        assert_eq!(
            error_message(parse_csv("# only a comment\nt,acc\n", "names.csv", None)),
            "names.csv: no data rows"
        );
        assert_eq!(
            error_message(parse_csv("", "empty.csv", None)),
            "empty.csv: empty file"
        );
    }

    // --- files, bytes and the Record methods --------------------------------------------------

    #[test]
    fn invalid_utf8_is_an_error_naming_the_line() {
        let bytes = b"line one\nline two\nbad \xff byte\n".to_vec();
        assert_eq!(
            error_message(decode_utf8(bytes, "bytes.AT2")),
            "bytes.AT2 line 3: the file is not UTF-8 text (invalid byte at offset 22)"
        );
    }

    #[test]
    fn read_record_reports_missing_files_and_unknown_extensions() {
        let missing = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../validation/records/missing.AT2"
        );
        let message = error_message(read_record(Path::new(missing), None, None));
        assert!(
            message.starts_with(&format!("{missing}: cannot read the file: ")),
            "{message}"
        );
        let message = error_message(read_record(Path::new("record.txt"), None, None));
        assert!(
            message.starts_with("record.txt: cannot tell the record format from the extension"),
            "{message}"
        );
        assert_eq!(
            RecordFormat::from_extension(Path::new("a/b/X.at2")),
            Some(RecordFormat::PeerAt2)
        );
        assert_eq!(
            RecordFormat::from_extension(Path::new("X.CSV")),
            Some(RecordFormat::Csv)
        );
        assert_eq!(RecordFormat::from_extension(Path::new("X")), None);
    }

    #[test]
    fn peak_and_duration_of_small_records() {
        let mut record = Record {
            source: "r".to_string(),
            title: Vec::new(),
            dt: 0.5,
            values: vec![0.1, -0.4, 0.4, 0.2],
        };
        assert_eq!(record.peak(), (-0.4, 0.5));
        assert_eq!(record.duration(), 1.5);
        record.values.clear();
        assert_eq!(record.peak(), (0.0, 0.0));
        assert_eq!(record.duration(), 0.0);
    }

    // --- no panic, whatever the input ---------------------------------------------------------

    /// One edit of a text: insert, delete or replace a character at a position.
    #[derive(Debug, Clone)]
    enum Edit {
        Insert(usize, char),
        Delete(usize),
        Replace(usize, char),
    }

    fn edit_strategy() -> impl Strategy<Value = Edit> {
        // Characters that matter to the parsers, plus any character at all.
        let interesting = prop::sample::select(vec![
            ' ', '\n', '\r', ',', '=', '#', '-', '+', '.', 'E', 'e', '0', '9', 'N', 'D', 'S', 'n',
            '\u{feff}', 'é', '\u{0}',
        ]);
        let character = prop_oneof![interesting, any::<char>()];
        prop_oneof![
            (any::<usize>(), character.clone()).prop_map(|(at, c)| Edit::Insert(at, c)),
            any::<usize>().prop_map(Edit::Delete),
            (any::<usize>(), character).prop_map(|(at, c)| Edit::Replace(at, c)),
        ]
    }

    fn apply_edits(text: &str, edits: &[Edit]) -> String {
        let mut chars: Vec<char> = text.chars().collect();
        for edit in edits {
            match *edit {
                Edit::Insert(at, c) => chars.insert(at % (chars.len() + 1), c),
                Edit::Delete(at) if !chars.is_empty() => {
                    chars.remove(at % chars.len());
                }
                Edit::Replace(at, c) if !chars.is_empty() => {
                    let index = at % chars.len();
                    chars[index] = c;
                }
                _ => {}
            }
        }
        chars.into_iter().collect()
    }

    fn parse_everything(text: &str) {
        let _ = parse_at2(text, "fuzz.AT2");
        let _ = parse_csv(text, "fuzz.csv", None);
        let _ = parse_csv(text, "fuzz.csv", Some(0.01));
        let _ = parse_csv(text, "fuzz.csv", Some(-1.0));
        if let Ok(record) = parse_at2(text, "fuzz.AT2") {
            let _ = (record.peak(), record.duration());
        }
    }

    proptest! {
        #[test]
        fn arbitrary_strings_do_not_panic(text in any::<String>()) {
            parse_everything(&text);
        }

        #[test]
        fn arbitrary_bytes_do_not_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
            parse_everything(&String::from_utf8_lossy(&bytes));
            if let Ok(text) = decode_utf8(bytes, "fuzz.bin") {
                parse_everything(&text);
            }
        }

        #[test]
        fn mutated_at2_texts_do_not_panic(edits in prop::collection::vec(edit_strategy(), 1..12)) {
            let mutated = apply_edits(SMALL_AT2, &edits);
            parse_everything(&mutated);
            parse_everything(&mutated.replace('\n', "\r\n"));
        }

        #[test]
        fn mutated_csv_texts_do_not_panic(edits in prop::collection::vec(edit_strategy(), 1..12)) {
            let csv = "t,acc\n0.00,0.1\n0.01,-0.3 # peak\n0.02,0.2\n";
            parse_everything(&apply_edits(csv, &edits));
        }

        #[test]
        fn numeric_fields_round_trip(values in prop::collection::vec(-1e3f64..1e3, 2..40)) {
            let mut text = format!("a\nb\nc\nNPTS= {}, DT= .005 SEC\n", values.len());
            for (index, value) in values.iter().enumerate() {
                text.push_str(&format!("{value:15.7E}"));
                if index % 5 == 4 {
                    text.push('\n');
                }
            }
            let record = parse_at2(&text, "round.AT2").map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert_eq!(record.values.len(), values.len());
            for (read, written) in record.values.iter().zip(&values) {
                prop_assert!((read - written).abs() <= 1e-6 * written.abs().max(1e-30));
            }
        }
    }
}
