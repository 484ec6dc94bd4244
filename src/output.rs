//! Output files: CSV tables and JSON summaries, written atomically. Writers see only the
//! solver-agnostic [`Solution`](crate::solution::Solution) types, never a solver.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::solution::{Event, Sample};

/// Column names of history.csv (a contract).
pub const HISTORY_COLUMNS: [&str; 9] = [
    "t",
    "q",
    "qdot",
    "s",
    "r",
    "mode",
    "floor_acc",
    "F",
    "energy_residual",
];

/// Column names of events.csv (a contract).
pub const EVENT_COLUMNS: [&str; 8] = [
    "index",
    "t",
    "kind",
    "from",
    "to",
    "q",
    "qdot_before",
    "qdot_after",
];

/// A CSV table built in memory, so that nothing reaches the disk before it is complete.
pub struct Table {
    writer: csv::Writer<Vec<u8>>,
}

impl Table {
    pub fn new(columns: &[&str]) -> Self {
        let mut writer = csv::Writer::from_writer(Vec::new());
        // Writing to memory cannot fail.
        let _ = writer.write_record(columns);
        Table { writer }
    }

    /// Appends a row of already formatted fields.
    pub fn row<I, S>(&mut self, fields: I)
    where
        I: IntoIterator<Item = S>,
        S: AsRef<[u8]>,
    {
        let _ = self.writer.write_record(fields);
    }

    pub fn into_bytes(self) -> Vec<u8> {
        self.writer.into_inner().unwrap_or_default()
    }
}

/// Formats a number so that it reads back exactly (shortest round-trip form).
pub fn number(x: f64) -> String {
    format!("{x}")
}

pub fn history_csv(samples: &[Sample]) -> Vec<u8> {
    let mut table = Table::new(&HISTORY_COLUMNS);
    for s in samples {
        table.row([
            number(s.t),
            number(s.q),
            number(s.qdot),
            number(s.s),
            number(s.r),
            s.mode.name().to_string(),
            number(s.floor_acc),
            number(s.restoring_force),
            number(s.energy_residual),
        ]);
    }
    table.into_bytes()
}

pub fn events_csv(events: &[Event]) -> Vec<u8> {
    let mut table = Table::new(&EVENT_COLUMNS);
    for e in events {
        table.row([
            e.index.to_string(),
            number(e.t),
            e.kind.name().to_string(),
            e.from.name().to_string(),
            e.to.name().to_string(),
            number(e.q),
            number(e.qdot_before),
            number(e.qdot_after),
        ]);
    }
    table.into_bytes()
}

pub fn json_bytes<T: serde::Serialize>(value: &T) -> Vec<u8> {
    let mut bytes = serde_json::to_vec_pretty(value).unwrap_or_default();
    bytes.push(b'\n');
    bytes
}

/// Writes a set of files into `dir` so that each appears whole or not at all: every file is first
/// written and synced under a temporary name, and only when all are written are they renamed.
pub fn write_atomically(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    let write_err = |path: &Path, source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(|e| write_err(dir, e))?;
    let mut staged = Vec::new();
    let result = (|| {
        for (name, bytes) in files {
            let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
            staged.push(tmp.clone());
            let mut f = std::fs::File::create(&tmp).map_err(|e| write_err(&tmp, e))?;
            f.write_all(bytes).map_err(|e| write_err(&tmp, e))?;
            f.sync_all().map_err(|e| write_err(&tmp, e))?;
        }
        let mut finals = Vec::new();
        for ((name, _), tmp) in files.iter().zip(&staged) {
            let target = dir.join(name);
            std::fs::rename(tmp, &target).map_err(|e| write_err(&target, e))?;
            finals.push(target);
        }
        Ok(finals)
    })();
    if result.is_err() {
        for tmp in &staged {
            let _ = std::fs::remove_file(tmp);
        }
    }
    result
}

/// Writes one file atomically (see [`write_atomically`]).
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| Error::Write {
            path: path.to_path_buf(),
            source: std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
        })?;
    write_atomically(dir, &[(name.as_str(), bytes.to_vec())]).map(|_| ())
}
