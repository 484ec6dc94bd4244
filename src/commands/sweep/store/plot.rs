//! Drawing a finished sweep's figure again from its directory.

use std::path::{Path, PathBuf};

use super::summary::{read_summary, SUMMARY_FILE, TABLE_FILE};
use super::verify;
use crate::error::{Error, Result};
use crate::figures::sweep as figure;
use crate::writers;

/// Draws the figures of the finished sweep in `dir` from its sweep.csv, in the formats and size
/// of `options`, and writes them into `dir` as one set. A shard's directory, or a sweep.csv
/// that is not the one sweep.json was written with, is refused.
pub fn plot_dir(dir: &Path, options: &crate::figures::page::FigureOptions) -> Result<Vec<PathBuf>> {
    options.sizes.check()?;
    let summary = read_summary(dir)?.ok_or_else(|| Error::SweepStore {
        path: dir.join(SUMMARY_FILE),
        message: "cannot read it: not found".to_string(),
    })?;
    if summary.shard.is_some() {
        return Err(Error::SweepStore {
            path: dir.join(SUMMARY_FILE),
            message: "is a shard's: merge the shards (flexrock sweep merge) and plot the merged directory".to_string(),
        });
    }
    let table_path = dir.join(TABLE_FILE);
    let bytes = std::fs::read(&table_path).map_err(|e| Error::SweepStore {
        path: table_path.clone(),
        message: format!("cannot read it: {e}"),
    })?;
    if verify::sha256_hex_of(&[bytes.as_slice()]) != summary.table_sha256 {
        return Err(Error::SweepStore {
            path: table_path,
            message: "is not the table sweep.json was written with (its SHA-256 differs)"
                .to_string(),
        });
    }
    let table = crate::sweep_table::SweepTable::read(&table_path)?;
    let files = figure::files(&summary.plan, &table, options)?;
    if files.is_empty() {
        return Err(Error::SweepStore {
            path: dir.join(SUMMARY_FILE),
            message: "is of a sweep that has no figure (a map needs two numeric axes, a spectrum a minimum search over one, an IDA records against a scale)".to_string(),
        });
    }
    let set: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    writers::write_atomically(dir, &set)
}
