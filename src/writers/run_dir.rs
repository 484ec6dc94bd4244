//! A run's output directory read back: the history.csv, events.csv and summary.json that
//! `flexrock run` writes, parsed into typed rows by column name (CSV) and by key (JSON), never by
//! position. Used by `flexrock plot` and `flexrock events`; also holds the event log as a table
//! for people.
//!
//! Every failure names the file, the line and column (or the key) and what was expected, as an
//! input error ([`Error::RunFile`], exit code 2): nothing is written before all inputs are read.

use std::fmt::Write as _;
use std::io::Read;
use std::path::Path;

use serde::de::DeserializeOwned;

use crate::error::{Error, Result};
use crate::writers::{EPISODE_COLUMNS, EVENT_COLUMNS, HISTORY_COLUMNS};
use flexrock_core::integrate::solution::{Event, Sample};
use flexrock_core::physics::constants::Constants;
use flexrock_core::tables::run_tables::MAX_HISTORY_ROW_BYTES;

/// The sampled history of a run.
pub const HISTORY_FILE: &str = "history.csv";
/// The events of a run.
pub const EVENTS_FILE: &str = "events.csv";
/// The rocking episodes of a run.
pub const EPISODES_FILE: &str = "episodes.csv";
/// The summary of a run.
pub const SUMMARY_FILE: &str = "summary.json";

/// Largest history.csv read, bytes (1.5 GiB): [`MAX_HISTORY_ROWS`] rows of the widest
/// ([`MAX_HISTORY_ROW_BYTES`]) fit.
pub const MAX_HISTORY_BYTES: u64 = 3 << 29;
/// Most rows of history.csv read: the 1e6 grid rows `run` allows and room for 1.5e6 events
/// (about 350 MB in memory).
pub const MAX_HISTORY_ROWS: usize = 4_000_000;

const _: () = assert!(
    (MAX_HISTORY_ROWS as u64 + 1) * MAX_HISTORY_ROW_BYTES as u64 <= MAX_HISTORY_BYTES,
    "a history of MAX_HISTORY_ROWS rows must be readable"
);

/// Largest events.csv read, bytes (256 MiB).
pub const MAX_EVENTS_BYTES: u64 = 256 << 20;
/// Largest summary.json read, bytes (16 MiB; `run` writes a few kB).
pub const MAX_SUMMARY_BYTES: u64 = 16 << 20;

/// One row of history.csv, read back: the [`Sample`] the run wrote.
pub type HistoryRow = Sample;

/// What the figures need from summary.json, each read by its key.
#[derive(Debug, Clone)]
pub struct RunSummaryFile {
    /// The derived constants the run used: the automaton is rebuilt from them.
    pub constants: Constants,
    /// The energies the residual is measured against, J.
    pub energy_scale: f64,
    /// Largest |energy_residual|, J.
    pub max_energy_residual: f64,
    /// Number of uplifts.
    pub n_uplift: usize,
    /// Number of landings.
    pub n_landing: usize,
    /// When the body fell over, if it did, s.
    pub t_overturn: Option<f64>,
}

/// A run directory, read.
#[derive(Debug, Clone)]
pub struct RunData {
    /// The rows of history.csv.
    pub history: Vec<HistoryRow>,
    /// The rows of events.csv.
    pub events: Vec<Event>,
    /// What the figures need from summary.json.
    pub summary: RunSummaryFile,
}

impl RunData {
    /// Reads summary.json, events.csv and history.csv of `dir`.
    pub fn read(dir: &Path) -> Result<Self> {
        let summary = read_summary(dir)?;
        let events = read_events(dir)?;
        let path = dir.join(HISTORY_FILE);
        let history = parse_history(bounded(&path, MAX_HISTORY_BYTES)?, &path)?;
        Ok(RunData {
            history,
            events,
            summary,
        })
    }

    /// The same from the bytes of the three files (as `run` is about to write them into
    /// `dir`), through the same parsers: `run --plot` draws exactly what `plot` would.
    pub fn from_bytes(dir: &Path, history: &[u8], events: &[u8], summary: &[u8]) -> Result<Self> {
        let unbounded = |bytes: &[u8]| Bounded {
            reader: std::io::Cursor::new(bytes.to_vec()),
            limit: u64::MAX,
        };
        Ok(RunData {
            summary: parse_summary(summary, &dir.join(SUMMARY_FILE))?,
            events: parse_table(
                unbounded(events),
                &dir.join(EVENTS_FILE),
                &EVENT_COLUMNS,
                usize::MAX,
            )?,
            history: parse_history(unbounded(history), &dir.join(HISTORY_FILE))?,
        })
    }
}

/// Reads events.csv of a run directory.
pub fn read_events(dir: &Path) -> Result<Vec<Event>> {
    let path = dir.join(EVENTS_FILE);
    parse_table(
        bounded(&path, MAX_EVENTS_BYTES)?,
        &path,
        &EVENT_COLUMNS,
        usize::MAX,
    )
}

/// A table of a run directory as `flexrock events` prints it: events.csv, or episodes.csv.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunTable {
    /// events.csv, columns [`EVENT_COLUMNS`].
    Events,
    /// episodes.csv, columns [`EPISODE_COLUMNS`].
    Episodes,
}

impl RunTable {
    /// The file's name.
    pub fn file(self) -> &'static str {
        match self {
            RunTable::Events => EVENTS_FILE,
            RunTable::Episodes => EPISODES_FILE,
        }
    }

    /// Its columns.
    pub fn columns(self) -> &'static [&'static str] {
        match self {
            RunTable::Events => &EVENT_COLUMNS,
            RunTable::Episodes => &EPISODE_COLUMNS,
        }
    }
}

/// A table of a run directory: its bytes, after checking that its header is the table's
/// columns and every row has as many fields.
pub fn read_table_csv(dir: &Path, table: RunTable) -> Result<Vec<u8>> {
    let path = dir.join(table.file());
    let bytes = read_whole(&path, MAX_EVENTS_BYTES)?;
    table_rows(&bytes, &path, table.columns())?;
    Ok(bytes)
}

/// The rows of a table as JSON objects by column name: numbers as numbers, empty fields as
/// null, words as strings.
pub fn table_json(bytes: &[u8], path: &Path, table: RunTable) -> Result<serde_json::Value> {
    let columns = table.columns();
    let rows = table_rows(bytes, path, columns)?;
    Ok(serde_json::Value::Array(
        rows.into_iter()
            .map(|row| {
                let object = columns
                    .iter()
                    .zip(row)
                    .map(|(column, field)| {
                        let value = if field.is_empty() {
                            serde_json::Value::Null
                        } else if let Ok(i) = field.parse::<u64>() {
                            serde_json::Value::from(i)
                        } else if let Some(x) = field
                            .parse::<f64>()
                            .ok()
                            .and_then(serde_json::Number::from_f64)
                        {
                            serde_json::Value::Number(x)
                        } else {
                            serde_json::Value::String(field)
                        };
                        (column.to_string(), value)
                    })
                    .collect();
                serde_json::Value::Object(object)
            })
            .collect(),
    ))
}

fn table_rows(bytes: &[u8], path: &Path, columns: &[&str]) -> Result<Vec<Vec<String>>> {
    let mut reader = csv::ReaderBuilder::new().from_reader(bytes);
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| fail(path, format!("not a CSV table: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    if header != columns {
        return Err(fail(
            path,
            format!(
                "has the columns {}; expected {}",
                header.join(","),
                columns.join(",")
            ),
        ));
    }
    reader
        .records()
        .enumerate()
        .map(|(i, record)| {
            record
                .map(|r| r.iter().map(str::to_string).collect())
                .map_err(|e| fail(path, format!("row {}: {e}", i + 1)))
        })
        .collect()
}

/// Reads the keys of summary.json that the figures need.
pub fn read_summary(dir: &Path) -> Result<RunSummaryFile> {
    let path = dir.join(SUMMARY_FILE);
    parse_summary(&read_whole(&path, MAX_SUMMARY_BYTES)?, &path)
}

/// The bytes of an input file of at most `limit` bytes (see [`bounded`]).
fn read_whole(path: &Path, limit: u64) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut source = bounded(path, limit)?;
    source
        .reader
        .read_to_end(&mut bytes)
        .map_err(|e| fail(path, format!("cannot read: {e}")))?;
    if bytes.len() as u64 > source.limit {
        return Err(too_large(path, source.limit));
    }
    Ok(bytes)
}

fn fail(path: &Path, message: String) -> Error {
    Error::RunFile {
        path: path.to_path_buf(),
        message,
    }
}

fn too_large(path: &Path, limit: u64) -> Error {
    fail(
        path,
        format!(
            "larger than {} MiB, the most flexrock reads of this file",
            limit >> 20
        ),
    )
}

/// A reader that may yield one byte more than `limit`, so that a larger file is noticed.
struct Bounded<R> {
    reader: R,
    limit: u64,
}

/// Opens an input file: a regular file only (a FIFO would block, /dev/zero never end), of at
/// most `limit` bytes, checked before reading and enforced while reading.
fn bounded(path: &Path, limit: u64) -> Result<Bounded<std::io::Take<std::fs::File>>> {
    let what = match path.file_name().and_then(|n| n.to_str()) {
        Some(HISTORY_FILE) => "the history that `flexrock run` writes",
        Some(EVENTS_FILE) => "the event log that `flexrock run` writes",
        Some(EPISODES_FILE) => "the rocking episodes that `flexrock run` writes",
        _ => "the summary that `flexrock run` writes",
    };
    let metadata = std::fs::metadata(path)
        .map_err(|e| fail(path, format!("cannot read it ({e}); expected {what} here")))?;
    if !metadata.is_file() {
        return Err(fail(
            path,
            format!(
                "is {}; expected a regular file, {what}",
                crate::writers::file_kind(metadata.file_type())
            ),
        ));
    }
    if metadata.len() > limit {
        return Err(too_large(path, limit));
    }
    let file = std::fs::File::open(path).map_err(|e| fail(path, format!("cannot read: {e}")))?;
    Ok(Bounded {
        reader: file.take(limit.saturating_add(1)),
        limit,
    })
}

fn parse_history<R: Read>(source: Bounded<R>, path: &Path) -> Result<Vec<HistoryRow>> {
    let rows: Vec<HistoryRow> = parse_table(source, path, &HISTORY_COLUMNS, MAX_HISTORY_ROWS)?;
    if rows.is_empty() {
        return Err(fail(
            path,
            "has no rows; expected at least the state at the start of the run".to_string(),
        ));
    }
    Ok(rows)
}

/// Parses a CSV table whose header must hold `columns` (in any order; others are ignored) into
/// rows of `T`, each field taken by its column name.
fn parse_table<T: DeserializeOwned, R: Read>(
    source: Bounded<R>,
    path: &Path,
    columns: &[&str],
    max_rows: usize,
) -> Result<Vec<T>> {
    let limit = source.limit;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(source.reader);
    let expected = format!(
        "expected the columns {} that `flexrock run` writes",
        columns.join(",")
    );
    let headers = reader
        .headers()
        .map_err(|e| fail(path, csv_message(&e, &[], None)))?
        .clone();
    let names: Vec<String> = headers.iter().map(str::to_string).collect();
    for column in columns {
        if !names.iter().any(|n| n == column) {
            let found = if names.iter().all(|n| n.is_empty()) {
                "the file is empty".to_string()
            } else {
                format!("its header is `{}`", names.join(","))
            };
            let hint = if column.starts_with("work_") {
                " (a history.csv of an earlier flexrock lacks the work columns: run the model again)"
            } else {
                ""
            };
            return Err(fail(
                path,
                format!("no column `{column}`: {found}; {expected}{hint}"),
            ));
        }
    }
    let mut rows = Vec::new();
    let mut record = csv::StringRecord::new();
    loop {
        match reader.read_record(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            Err(e) => return Err(fail(path, csv_message(&e, &names, None))),
        }
        let row: T = record
            .deserialize(Some(&headers))
            .map_err(|e| fail(path, csv_message(&e, &names, Some(&record))))?;
        if rows.len() == max_rows {
            return Err(fail(
                path,
                format!("has more than {max_rows} rows, the most flexrock reads"),
            ));
        }
        rows.push(row);
    }
    if reader.position().byte() > limit {
        return Err(too_large(path, limit));
    }
    Ok(rows)
}

/// A CSV error as a message naming the line and, for a value, its column and the value.
fn csv_message(error: &csv::Error, names: &[String], record: Option<&csv::StringRecord>) -> String {
    let line = |pos: &Option<csv::Position>| {
        pos.as_ref()
            .or_else(|| record.and_then(|r| r.position()))
            .map_or_else(String::new, |p| format!("line {}: ", p.line()))
    };
    match error.kind() {
        csv::ErrorKind::Io(e) => format!("cannot read: {e}"),
        csv::ErrorKind::Utf8 { pos, .. } => format!("{}not UTF-8 text", line(pos)),
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => format!(
            "{}{len} fields where the header has {expected_len}",
            line(pos)
        ),
        csv::ErrorKind::Deserialize { pos, err } => {
            // csv does not tell the field of a word that names no variant of an enum (mode,
            // kind): it is the field that holds the word the message quotes.
            let field = err.field().map(|i| i as usize).or_else(|| {
                let text = err.kind().to_string();
                let word = text.strip_prefix("unknown variant `")?.split('`').next()?;
                record?.iter().position(|v| v == word)
            });
            let column = field
                .and_then(|i| names.get(i))
                .map_or_else(String::new, |name| format!("column `{name}`: "));
            let value = (err.field().is_some())
                .then_some(field)
                .flatten()
                .and_then(|i| record.and_then(|r| r.get(i)))
                .map_or_else(String::new, |v| format!("`{v}`: "));
            let what = match err.kind() {
                csv::DeserializeErrorKind::ParseFloat(_) => "expected a number".to_string(),
                csv::DeserializeErrorKind::ParseInt(_) => {
                    "expected a whole number (the event index)".to_string()
                }
                other => other.to_string(),
            };
            format!("{}{column}{value}{what}", line(pos))
        }
        other => format!("{other:?}"),
    }
}

/// Parses summary.json: a JSON object, from which each key the figures need is deserialised on
/// its own, so that an error names the key.
fn parse_summary(bytes: &[u8], path: &Path) -> Result<RunSummaryFile> {
    let value: serde_json::Value = serde_json::from_slice(bytes).map_err(|e| {
        fail(
            path,
            format!("not valid JSON ({e}); expected the summary that `flexrock run` writes"),
        )
    })?;
    let serde_json::Value::Object(map) = value else {
        return Err(fail(
            path,
            "not a JSON object; expected the summary that `flexrock run` writes".to_string(),
        ));
    };
    if map.contains_key("row") && map.contains_key("columns") {
        return Err(fail(
            path,
            "the summary of a row of columns (history-K.csv for column K): `flexrock run \
             --plot` draws a row's figures as it runs it; `flexrock plot` draws a single \
             body's run"
                .to_string(),
        ));
    }
    fn key<T: DeserializeOwned>(
        map: &serde_json::Map<String, serde_json::Value>,
        path: &Path,
        key: &str,
        expected: &str,
    ) -> Result<T> {
        let value = map
            .get(key)
            .ok_or_else(|| fail(path, format!("no key `{key}`; expected {expected}")))?;
        T::deserialize(value)
            .map_err(|e| fail(path, format!("key `{key}`: {e}; expected {expected}")))
    }
    let summary = RunSummaryFile {
        constants: key(&map, path, "constants", "the derived constants of the body")?,
        energy_scale: key(&map, path, "energy_scale", "the energy scale in J")?,
        max_energy_residual: key(
            &map,
            path,
            "max_energy_residual",
            "the largest energy residual in J",
        )?,
        n_uplift: key(&map, path, "n_uplift", "the number of uplifts")?,
        n_landing: key(&map, path, "n_landing", "the number of landings")?,
        t_overturn: key(
            &map,
            path,
            "t_overturn",
            "the time of overturning in s, or null",
        )?,
    };
    let c = &summary.constants;
    let positive = [
        ("constants.width", c.width),
        ("constants.uplift_displacement", c.uplift_displacement),
        ("constants.generalised_mass", c.generalised_mass),
        ("constants.generalised_stiffness", c.generalised_stiffness),
    ];
    for (name, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            return Err(fail(
                path,
                format!(
                    "key `{name}` = {}: expected a positive number",
                    crate::writers::shortest(value)
                ),
            ));
        }
    }
    if c.uplift_displacement >= c.width {
        return Err(fail(
            path,
            format!(
                "key `constants.uplift_displacement` = {} is not below `constants.width` = {}: \
                 no body of the model has that",
                crate::writers::shortest(c.uplift_displacement),
                crate::writers::shortest(c.width)
            ),
        ));
    }
    for (name, value) in [
        ("energy_scale", summary.energy_scale),
        ("max_energy_residual", summary.max_energy_residual),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(fail(
                path,
                format!(
                    "key `{name}` = {}: expected a number of joules, zero or more",
                    crate::writers::shortest(value)
                ),
            ));
        }
    }
    Ok(summary)
}

/// The event log as an aligned table with a header (`flexrock events`); for an empty log, one
/// line saying so.
pub fn events_table(events: &[Event], source: &Path) -> String {
    if events.is_empty() {
        return format!(
            "no events in {}: no uplift, landing or overturning\n",
            source.display()
        );
    }
    let header = [
        "index",
        "t (s)",
        "kind",
        "from",
        "to",
        "q (m)",
        "qdot_before (m/s)",
        "qdot_after (m/s)",
    ];
    let rows: Vec<[String; 8]> = events
        .iter()
        .map(|e| {
            [
                e.index.to_string(),
                format!("{:.9}", e.t),
                e.kind.name().to_string(),
                e.from.name().to_string(),
                e.to.name().to_string(),
                format!("{:.9}", e.q),
                format!("{:.9}", e.qdot_before),
                format!("{:.9}", e.qdot_after),
            ]
        })
        .collect();
    let mut widths = header.map(str::len);
    for row in &rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.len());
        }
    }
    // Numbers right-aligned, words left-aligned.
    let numeric = [true, true, false, false, false, true, true, true];
    let line = |cells: &[&str]| {
        let mut text = String::new();
        for (i, cell) in cells.iter().enumerate() {
            let w = widths[i];
            if i > 0 {
                text.push_str("  ");
            }
            if numeric[i] {
                let _ = write!(text, "{cell:>w$}");
            } else {
                let _ = write!(text, "{cell:<w$}");
            }
        }
        text.trim_end().to_string() + "\n"
    };
    let mut t = line(&header);
    for row in &rows {
        t.push_str(&line(&row.each_ref().map(String::as_str)));
    }
    t
}
