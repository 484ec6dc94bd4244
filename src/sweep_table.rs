//! sweep.csv read back ([`SweepTable`]), from the file or from the rows a sweep just computed
//! (their pieces), and the counts of its rows ([`Counts`]): what the sweep's store writes and its
//! figures draw from.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use flexrock_core::analysis::sweep::Layout;

/// Counts of the rows, by status, and of the points that overturned (for a minimum search:
/// that overturned somewhere in the interval).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Rows with status ok.
    pub ok: usize,
    /// Rows with status invalid.
    pub invalid: usize,
    /// Rows with status failed.
    pub failed: usize,
    /// Points that overturned.
    pub overturned: usize,
    /// Runs whose energy residual exceeds [`crate::commands::run::ENERGY_RESIDUAL_WARNING_SHARE`] of their
    /// energy scale: no more accurate than that (a sweep with a minimum search has none).
    pub inaccurate: usize,
}

/// Rows of sweep.csv (CSV text without header, whole rows), verified against the plan, with
/// their fields where they were just computed (else they are read back from the text).
pub(crate) struct Piece {
    pub(crate) rows: Vec<u8>,
    pub(crate) records: Option<Vec<csv::StringRecord>>,
}

impl Piece {
    /// Rows read from a file.
    pub(crate) fn read_back(rows: Vec<u8>) -> Self {
        Piece {
            rows,
            records: None,
        }
    }
}

/// sweep.csv read back: its columns and rows of text.
pub struct SweepTable {
    /// Column names, from the header.
    pub columns: Vec<String>,
    /// The fields of each row, as text (one allocation per row: a map has many).
    pub rows: Vec<csv::StringRecord>,
    path: std::path::PathBuf,
}

impl SweepTable {
    /// The table of the rows `pieces` under `columns`: what a CSV reader finds in sweep.csv,
    /// the header and the pieces' text joined. A piece's fields are taken as they are where it
    /// has them (the text was written from them), else read from its text, the pieces in
    /// parallel; `path` names the table in messages.
    pub(crate) fn of_pieces(
        columns: &[String],
        pieces: &mut [Piece],
        path: &Path,
    ) -> Result<SweepTable> {
        use rayon::prelude::*;
        let read = |piece: &mut Piece| -> Result<Vec<csv::StringRecord>> {
            if let Some(records) = piece.records.take() {
                return Ok(records);
            }
            csv::ReaderBuilder::new()
                .has_headers(false)
                .from_reader(piece.rows.as_slice())
                .records()
                .map(|record| {
                    let malformed = |message: String| Error::ReadResult {
                        path: path.to_path_buf(),
                        message: format!("a malformed row: {message}"),
                    };
                    let record = record.map_err(|e| malformed(e.to_string()))?;
                    if record.len() != columns.len() {
                        return Err(malformed(format!(
                            "{} fields under {} columns",
                            record.len(),
                            columns.len()
                        )));
                    }
                    Ok(record)
                })
                .collect()
        };
        let parts: Vec<Vec<csv::StringRecord>> =
            pieces.par_iter_mut().map(read).collect::<Result<_>>()?;
        Ok(SweepTable {
            columns: columns.to_vec(),
            rows: parts.into_iter().flatten().collect(),
            path: path.to_path_buf(),
        })
    }

    /// The index of a column.
    pub fn column(&self, name: &str) -> Result<usize> {
        self.columns
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| Error::ReadResult {
                path: self.path.clone(),
                message: format!("has no column {name}"),
            })
    }

    /// A numeric field; None when empty or not a number.
    pub fn number(&self, row: usize, column: usize) -> Option<f64> {
        self.rows[row][column].parse().ok()
    }

    /// Counts of the rows by status, and of the points that overturned: for a minimum search,
    /// that overturned somewhere in the interval; for a row, where a column overturned.
    pub fn counts(&self, layout: Layout) -> Result<Counts> {
        let status = self.column("status")?;
        // Counted where the column is not empty (and, for runs, "true").
        let (overturned, any_value) = match layout {
            Layout::Runs => (self.column("overturned")?, false),
            Layout::Minimum(_) => (self.column("min_overturning")?, true),
            Layout::Row(_) => (self.column("overturned_column")?, true),
        };
        let find_min = any_value;
        let share = match layout {
            Layout::Runs => Some(self.column("energy_residual_share")?),
            _ => None,
        };
        let mut counts = Counts::default();
        for (r, row) in self.rows.iter().enumerate() {
            if share
                .and_then(|c| self.number(r, c))
                .is_some_and(|s| s > crate::commands::run::ENERGY_RESIDUAL_WARNING_SHARE)
            {
                counts.inaccurate += 1;
            }
            match &row[status] {
                "ok" => counts.ok += 1,
                "invalid" => counts.invalid += 1,
                _ => counts.failed += 1,
            }
            let over = &row[overturned];
            if (find_min && !over.is_empty()) || (!find_min && over == "true") {
                counts.overturned += 1;
            }
        }
        Ok(counts)
    }
}

impl SweepTable {
    /// The point number of row `r` (its first field).
    pub fn point(&self, r: usize, row: &csv::StringRecord) -> Result<usize> {
        row[0].parse().map_err(|_| Error::ReadResult {
            path: self.path.clone(),
            message: format!("row {} has no point number", r + 1),
        })
    }

    /// sweep.csv at `path`, read whole.
    pub fn read(path: &Path) -> Result<SweepTable> {
        let unreadable = |message: String| Error::ReadResult {
            path: path.to_path_buf(),
            message,
        };
        let mut reader =
            csv::Reader::from_path(path).map_err(|e| unreadable(format!("cannot read it: {e}")))?;
        let columns: Vec<String> = reader
            .headers()
            .map_err(|e| unreadable(format!("cannot read its header: {e}")))?
            .iter()
            .map(str::to_string)
            .collect();
        let rows = reader
            .records()
            .map(|r| r.map_err(|e| unreadable(format!("a malformed row: {e}"))))
            .collect::<Result<Vec<_>>>()?;
        Ok(SweepTable {
            columns,
            rows,
            path: path.to_path_buf(),
        })
    }
}
