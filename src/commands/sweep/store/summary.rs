//! What a finished sweep leaves: sweep.json (its summary) and sweep.csv, read back and checked.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::shard::{PointRange, Shard};
use super::verify;
use super::Counts;
use crate::error::{Error, Result};
use crate::figures::sweep as figure;
use flexrock_core::analysis::sweep::Plan;

/// sweep.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepSummary {
    /// Version of flexrock that wrote it.
    pub flexrock_version: String,
    /// The commit that flexrock was built from, or "unknown" (and empty in a sweep.json written
    /// before it was recorded).
    #[serde(default)]
    pub flexrock_commit: String,
    /// Whether the program's sources differed from that commit; null when unknown.
    #[serde(default)]
    pub flexrock_dirty: Option<bool>,
    /// What was computed.
    pub plan: Plan,
    /// Set for a shard's directory; absent for a whole sweep (also a merged one).
    pub shard: Option<Shard>,
    /// The points of this directory's rows.
    pub points: PointRange,
    /// Counts of its rows.
    pub counts: Counts,
    /// sweep.csv's columns, in order.
    pub columns: Vec<String>,
    /// The files written with it.
    pub files: Vec<String>,
    /// SHA-256 of sweep.csv's bytes, so that a sweep.csv edited, replaced or swapped with
    /// another shard's is recognised.
    pub table_sha256: String,
}

/// What `flexrock sweep` reports.
#[derive(Debug)]
pub struct SweepReport {
    /// The directory written.
    pub dir: PathBuf,
    /// Its sweep.json.
    pub summary: SweepSummary,
    /// Points computed by this process (0 when the directory already held the whole result).
    pub computed: usize,
    /// Points found on disk from an earlier, interrupted run.
    pub resumed: usize,
    /// The files of the result.
    pub files: Vec<PathBuf>,
    /// True when this process wrote them (false when it found them done).
    pub written: bool,
    /// What the user must know: chunks that did not verify and were computed again, a
    /// directory that could not be locked or cleaned.
    pub warnings: Vec<String>,
}

pub(super) const SUMMARY_FILE: &str = "sweep.json";
pub(super) const TABLE_FILE: &str = "sweep.csv";
/// Every file of a finished sweep, the only names a sweep ever removes from its directory: the
/// table, each figure in each format, and sweep.json.
pub(super) fn result_files() -> Vec<String> {
    let mut names = vec![TABLE_FILE.to_string()];
    names.extend(figure::figure_files());
    names.push(SUMMARY_FILE.to_string());
    names
}

pub(super) fn read_summary(dir: &Path) -> Result<Option<SweepSummary>> {
    let path = dir.join(SUMMARY_FILE);
    let bytes = match std::fs::read(&path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(Error::SweepStore {
                path,
                message: format!("cannot read: {e}"),
            })
        }
    };
    let summary: SweepSummary = serde_json::from_slice(&bytes).map_err(|e| Error::SweepStore {
        path: path.clone(),
        message: format!("not a flexrock sweep.json: {e}"),
    })?;
    Ok(Some(SweepSummary {
        plan: summary.plan.clone().restored(),
        ..summary
    }))
}

/// sweep.csv's rows without the header, once the file matches the digest in its sweep.json and
/// its rows verify against the plan; else what is wrong with it.
pub(super) fn read_table(
    path: &Path,
    summary: &SweepSummary,
) -> std::result::Result<Vec<u8>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot be read: {e}"))?;
    if verify::sha256_hex(&bytes) != summary.table_sha256 {
        return Err(format!(
            "does not match the digest of sweep.csv in its sweep.json ({})",
            summary.table_sha256
        ));
    }
    let points = summary.points.first..summary.points.end;
    verify::table_rows(&summary.plan, &points, &bytes).map(<[u8]>::to_vec)
}
