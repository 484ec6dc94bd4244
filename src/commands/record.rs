//! `flexrock record info|csv`: the quick look a user takes at a record before trusting it.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::writers::{number, readable, Table};
use flexrock_core::model::STANDARD_GRAVITY;
use flexrock_core::record::{read_record, Record, RecordFormat};

/// The acceleration column of the CSV files `flexrock record csv` writes.
pub const CSV_ACCELERATION_COLUMN: &str = "acc_m_s2";

/// Acceleration column names that say their unit, as `flexrock record csv` writes them, with
/// that unit.
const UNIT_COLUMNS: [(&str, &str); 3] = [
    (CSV_ACCELERATION_COLUMN, "m/s2"),
    ("acc_g", "g"),
    ("acc_cm_s2", "cm/s2"),
];

/// A record read for the `record` commands, with the unit of its values.
pub struct LoadedRecord {
    /// The record as read, values in the file's units.
    pub record: Record,
    /// "g", "m/s2" or "cm/s2".
    pub units: &'static str,
    /// Factor from `units` to m/s^2.
    pub factor: f64,
}

/// Reads a record for the `record` commands (format by extension unless given). The unit is
/// `units` when given; otherwise g for PEER AT2 files, and for CSV files the unit their header
/// names (`acc_m_s2`, as `record csv` writes it); a CSV file without one needs `units`.
pub fn load(
    path: &Path,
    format: Option<&str>,
    dt: Option<f64>,
    units: Option<&str>,
) -> Result<LoadedRecord> {
    let format = format
        .map(|name| RecordFormat::from_name("--format", name))
        .transpose()?;
    if let Some(u) = units {
        unit_factor(u)?;
    }
    let record = read_record(path, format, dt).map_err(|source| flexrock_core::Error::Record {
        key: "record".to_string(),
        source,
    })?;
    let is_csv = format.or_else(|| RecordFormat::from_extension(path)) == Some(RecordFormat::Csv);
    let from_header = if is_csv { header_units(&record) } else { None };
    let units = match (units, from_header, is_csv) {
        (Some(given), Some((column, said)), _) if given != said => {
            return Err(Error::invalid(
                "--units",
                format!("\"{given}\""),
                &format!(
                    "contradicts the column {column} of {}, which is in {said}",
                    record.source
                ),
            ))
        }
        (Some(given), _, _) => given,
        (None, Some((_, said)), _) => said,
        (None, None, false) => "g",
        (None, None, true) => {
            return Err(Error::invalid(
                "--units",
                "(missing)",
                &format!(
                    "required for a CSV record whose header does not name its unit ({} has no \
                     column {CSV_ACCELERATION_COLUMN}): \"g\", \"m/s2\" or \"cm/s2\"",
                    record.source
                ),
            ))
        }
    };
    let (units, factor) = unit_factor(units)?;
    Ok(LoadedRecord {
        record,
        units,
        factor,
    })
}

/// The unit a CSV record's header names, with the column that names it.
fn header_units(record: &Record) -> Option<(&'static str, &'static str)> {
    let header = record.title.first()?;
    let column = header.split(',').next_back()?.trim();
    UNIT_COLUMNS
        .iter()
        .find(|(name, _)| column.eq_ignore_ascii_case(name))
        .copied()
}

/// The unit's canonical name and its factor to m/s^2.
pub fn unit_factor(units: &str) -> Result<(&'static str, f64)> {
    Ok(flexrock_core::record::acceleration_unit("--units", units)?)
}

/// What the reader understood, for `flexrock record info`.
pub fn info_text(loaded: &LoadedRecord) -> String {
    let LoadedRecord {
        record,
        units,
        factor,
    } = loaded;
    let (peak, t_peak) = record.peak();
    let peak_si = peak * factor;
    let mut t = String::new();
    let _ = writeln!(t, "file       {}", record.source);
    for (i, line) in record.title.iter().enumerate() {
        let _ = writeln!(
            t,
            "{:<10} {}",
            if i == 0 { "header" } else { "" },
            line.trim_end()
        );
    }
    let _ = writeln!(t, "points     {}", record.values.len());
    let _ = writeln!(t, "dt         {} s", readable(record.dt));
    let _ = writeln!(
        t,
        "duration   {} s (first sample at t = 0)",
        readable(record.duration())
    );
    let _ = writeln!(
        t,
        "units      {units} (1 {units} = {} m/s^2)",
        readable(*factor)
    );
    let _ = writeln!(
        t,
        "PGA        {:.6} g = {:.6} m/s^2 at t = {} s",
        peak_si / STANDARD_GRAVITY,
        peak_si,
        readable(t_peak)
    );
    t
}

/// The record as a two-column CSV, `t,acc_m_s2`.
pub fn csv_bytes(loaded: &LoadedRecord) -> Vec<u8> {
    let mut table = Table::new(&["t", CSV_ACCELERATION_COLUMN]);
    for (k, v) in loaded.record.values.iter().enumerate() {
        table.row([
            number(k as f64 * loaded.record.dt),
            number(v * loaded.factor),
        ]);
    }
    table.into_bytes()
}
