//! What is read back is checked before it is used: every stored row against the plan (its point
//! index, its coordinates, its number of fields, its status, the bytes flexrock writes), every
//! chunk against the seal it was written with, every sweep.csv against the digest in its
//! sweep.json. A chunk of another sweep, a chunk copied over another, swapped or edited lines,
//! CRLF line ends: each fails one of these checks, and is never taken for rows of this sweep.

use crate::writers;
use flexrock_core::analysis::sweep::Plan;

pub use flexrock_core::analysis::sweep::{sha256_hex, sha256_hex_of};

/// The first line of a chunk file: the seal of its rows.
const CHUNK_SEAL_PREFIX: &str = "# flexrock sweep chunk, sha256 ";

/// The seal of the rows of points `points` of the sweep `identity`: a chunk cannot be moved to
/// another place in the sweep, or into another sweep, and still verify.
fn seal(identity: &str, points: &std::ops::Range<usize>, rows: &[u8]) -> String {
    let place = format!("{identity}\n{}..{}\n", points.start, points.end);
    sha256_hex_of(&[place.as_bytes(), rows])
}

/// A chunk file's seal line; the rows as sweep.csv holds them follow it.
pub(super) fn chunk_seal_line(
    identity: &str,
    points: &std::ops::Range<usize>,
    rows: &[u8],
) -> String {
    format!("{CHUNK_SEAL_PREFIX}{}\n", seal(identity, points, rows))
}

/// The rows of a chunk file of points `points`, once its seal and its rows verify; else what
/// is wrong with it.
pub(super) fn chunk_rows<'a>(
    plan: &Plan,
    identity: &str,
    points: &std::ops::Range<usize>,
    bytes: &'a [u8],
) -> Result<&'a [u8], String> {
    let line_end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .ok_or("has no seal line (it was not written by this version of flexrock)")?;
    let rows = &bytes[line_end + 1..];
    let stored = std::str::from_utf8(&bytes[..line_end])
        .ok()
        .and_then(|line| line.strip_prefix(CHUNK_SEAL_PREFIX))
        .ok_or("has no seal line (it was not written by this version of flexrock)")?;
    if stored != seal(identity, points, rows) {
        return Err(format!(
            "does not match its seal for points {}..{} of this sweep (it was edited, or belongs \
             to another place or another sweep)",
            points.start, points.end
        ));
    }
    check_rows(plan, points, rows)?;
    Ok(rows)
}

/// Checks rows (CSV without header) as those of points `points` of `plan`: one row per point,
/// in order, each with the point's index and coordinates, the plan's number of columns, a
/// known status, and written byte for byte as flexrock writes them.
pub(super) fn check_rows(
    plan: &Plan,
    points: &std::ops::Range<usize>,
    rows: &[u8],
) -> Result<(), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(rows);
    let mut rewritten = writers::Table::without_header();
    let mut count = 0usize;
    let rules = RowRules::of(plan);
    for (line, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("row {}: not CSV: {e}", line + 1))?;
        count = line + 1;
        let point = points.start + line;
        if point >= points.end {
            continue;
        }
        rules.check(plan, point, line, &record.iter().collect::<Vec<_>>())?;
        rewritten.row(record.iter());
    }
    rules.check_count(count, points)?;
    if rewritten.into_bytes() != rows {
        return Err(
            "is not written as flexrock writes it (line ends, quoting or spacing changed)"
                .to_string(),
        );
    }
    Ok(())
}

/// Checks the fields of rows just computed, before they are written, by the rules of
/// [`check_rows`] but the bytes (which the writer makes).
pub(super) fn check_fields(
    plan: &Plan,
    points: &std::ops::Range<usize>,
    rows: &[csv::StringRecord],
) -> Result<(), String> {
    let rules = RowRules::of(plan);
    for (line, (point, fields)) in points.clone().zip(rows).enumerate() {
        let fields: Vec<&str> = fields.iter().collect();
        rules.check(plan, point, line, &fields)?;
    }
    rules.check_count(rows.len(), points)
}

/// What every row of a plan must be.
struct RowRules {
    columns: usize,
    status: Option<usize>,
}

impl RowRules {
    fn of(plan: &Plan) -> Self {
        let columns = plan.columns();
        RowRules {
            status: columns.iter().position(|c| c == "status"),
            columns: columns.len(),
        }
    }

    /// Row `line` (from 0), which belongs to point `point`.
    fn check(&self, plan: &Plan, point: usize, line: usize, fields: &[&str]) -> Result<(), String> {
        if fields.len() != self.columns {
            return Err(format!(
                "row {} has {} fields where the sweep has {} columns",
                line + 1,
                fields.len(),
                self.columns
            ));
        }
        if fields[0] != point.to_string() {
            return Err(format!(
                "row {} is point {:?} where point {point} belongs (rows lost, repeated or out of \
                 order)",
                line + 1,
                fields[0]
            ));
        }
        for ((axis, &i), &field) in plan
            .axes
            .iter()
            .zip(&plan.coordinates(point))
            .zip(&fields[1..])
        {
            if axis.values.get(i).map(String::as_str) != Some(field) {
                return Err(format!(
                    "row {} (point {point}) has {} = {field:?} where the plan has {:?}",
                    line + 1,
                    axis.key,
                    axis.values.get(i).map_or("", String::as_str)
                ));
            }
        }
        if let Some(s) = self.status {
            if !matches!(fields[s], "ok" | "invalid" | "failed") {
                return Err(format!(
                    "row {} (point {point}) has status {:?} (not ok, invalid or failed)",
                    line + 1,
                    fields[s]
                ));
            }
        }
        Ok(())
    }

    /// `count` rows were found for `points`.
    fn check_count(&self, count: usize, points: &std::ops::Range<usize>) -> Result<(), String> {
        if count != points.len() {
            return Err(format!(
                "holds {count} rows for the {} points {}..{}",
                points.len(),
                points.start,
                points.end
            ));
        }
        Ok(())
    }
}

/// Checks sweep.csv's bytes against the plan: the header is the plan's columns, the rows those
/// of `points`. Returns the rows without the header.
pub(super) fn table_rows<'a>(
    plan: &Plan,
    points: &std::ops::Range<usize>,
    table: &'a [u8],
) -> Result<&'a [u8], String> {
    let columns = plan.columns();
    let header =
        writers::Table::new(&columns.iter().map(String::as_str).collect::<Vec<_>>()).into_bytes();
    let rows = table
        .strip_prefix(header.as_slice())
        .ok_or("does not start with the header of this sweep's columns")?;
    check_rows(plan, points, rows)?;
    Ok(rows)
}
