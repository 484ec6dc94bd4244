//! `flexrock record info|csv`: the quick look a user takes at a record before trusting it.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::model::STANDARD_GRAVITY;
use crate::output::{number, readable, Table};
use crate::record::{read_record, Record, RecordFormat};

/// Reads a record for the `record` commands (format by extension unless given).
pub fn load(path: &Path, format: Option<&str>, dt: Option<f64>) -> Result<Record> {
    let format = match format {
        None => None,
        Some("peer-at2") => Some(RecordFormat::PeerAt2),
        Some("csv") => Some(RecordFormat::Csv),
        Some(other) => {
            return Err(Error::invalid(
                "--format",
                format!("\"{other}\""),
                "must be \"peer-at2\" or \"csv\"",
            ))
        }
    };
    read_record(path, format, dt).map_err(|source| Error::Record {
        key: "record".to_string(),
        source,
    })
}

/// Factor from the record's units to m/s^2.
pub fn unit_factor(units: &str) -> Result<f64> {
    match units {
        "g" => Ok(STANDARD_GRAVITY),
        "m/s2" => Ok(1.0),
        "cm/s2" => Ok(0.01),
        other => Err(Error::invalid(
            "--units",
            format!("\"{other}\""),
            "must be \"g\", \"m/s2\" or \"cm/s2\"",
        )),
    }
}

/// What the reader understood, for `flexrock record info`.
pub fn info_text(record: &Record, units: &str) -> Result<String> {
    let factor = unit_factor(units)?;
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
    let _ = writeln!(t, "units      {units} (1 {units} = {} m/s^2)", readable(factor));
    let _ = writeln!(
        t,
        "PGA        {:.6} g = {:.6} m/s^2 at t = {} s",
        peak_si / STANDARD_GRAVITY,
        peak_si,
        readable(t_peak)
    );
    Ok(t)
}

/// The record as a two-column CSV, `t,acc_m_s2`.
pub fn csv_bytes(record: &Record, units: &str) -> Result<Vec<u8>> {
    let factor = unit_factor(units)?;
    let mut table = Table::new(&["t", "acc_m_s2"]);
    for (k, v) in record.values.iter().enumerate() {
        table.row([number(k as f64 * record.dt), number(v * factor)]);
    }
    Ok(table.into_bytes())
}
