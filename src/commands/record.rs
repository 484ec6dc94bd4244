//! `flexrock record info|csv|intensity|spectrum`: the look a user takes at a record before
//! trusting it, and its intensity measures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::writers::{number, readable, Table};
use flexrock_core::analysis::sweep::{Cell, RecordCells};
use flexrock_core::bodies::oscillator::{self, SpectralOrdinate};
use flexrock_core::floor::intensity::{self, GroundMeasures};
use flexrock_core::floor::record::{read_record, resolve_units, Record, RecordFormat};
use flexrock_core::floor::RecordedMotion;
use flexrock_core::model::STANDARD_GRAVITY;

/// The acceleration column of the CSV files `flexrock record csv` writes.
pub const CSV_ACCELERATION_COLUMN: &str = "acc_m_s2";

/// A record read for the `record` commands, with the unit of its values.
pub struct LoadedRecord {
    /// The record as read, values in the file's units.
    pub record: Record,
    /// "g", "m/s2" or "cm/s2".
    pub units: &'static str,
    /// Factor from `units` to m/s^2.
    pub factor: f64,
}

impl LoadedRecord {
    /// The motion the record is: its values in m/s^2, linear between samples.
    pub fn motion(&self) -> RecordedMotion {
        RecordedMotion::new(
            self.record.source.clone(),
            self.record.dt,
            self.record.values.iter().map(|v| v * self.factor).collect(),
        )
        .with_meta(self.record.meta.clone())
    }
}

/// Reads a record for the `record` commands (format from the extension and the first line
/// unless given). The unit is the one the file declares (an AT2 or COSMOS header, an ESM
/// `UNITS` line, a CSV column named `acc_m_s2`, `acc_g` or `acc_cm_s2`); `units` gives it for
/// a file that declares none, and is refused where it contradicts the file.
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
    let (units, factor) = resolve_units(&record, "--units", units)?;
    Ok(LoadedRecord {
        record,
        units,
        factor,
    })
}

/// The unit's canonical name and its factor to m/s^2.
pub fn unit_factor(units: &str) -> Result<(&'static str, f64)> {
    Ok(flexrock_core::floor::record::acceleration_unit(
        "--units", units,
    )?)
}

/// Periods (s) and the damping ratio of the spectral ordinates a command computes, checked.
pub fn check_periods(periods: &[f64], damping: f64) -> Result<()> {
    for &period in periods {
        oscillator::check_oscillator("--period", period, "--damping", damping)?;
    }
    Ok(())
}

/// The spectral ordinates of `motion` at `periods`.
fn ordinates(
    motion: &RecordedMotion,
    periods: &[f64],
    damping: f64,
) -> Result<Vec<SpectralOrdinate>> {
    check_periods(periods, damping)?;
    oscillator::spectrum(motion, periods, damping)
        .map_err(|e| Error::from(flexrock_core::Error::from(e)))
}

/// What the reader understood, and the record's intensity measures, for `flexrock record
/// info`; Sa(T) at each of `periods` (s), damping ratio `damping`.
pub fn info_text(loaded: &LoadedRecord, periods: &[f64], damping: f64) -> Result<String> {
    let LoadedRecord {
        record,
        units,
        factor,
    } = loaded;
    let motion = loaded.motion();
    let m = intensity::ground_measures(&motion);
    let (peak, _) = record.peak();
    let mut t = String::new();
    let _ = writeln!(t, "file       {}", record.source);
    let _ = writeln!(t, "format     {}", record.meta.format);
    for (i, line) in record.title.iter().enumerate() {
        let _ = writeln!(
            t,
            "{:<10} {}",
            if i == 0 { "header" } else { "" },
            line.trim_end()
        );
    }
    let meta = &record.meta;
    for (name, value) in [
        ("event", &meta.event),
        ("date", &meta.date),
        ("station", &meta.station),
        ("component", &meta.component),
    ] {
        if let Some(value) = value {
            let _ = writeln!(t, "{name:<10} {value}");
        }
    }
    if let Some(magnitude) = meta.magnitude {
        let _ = writeln!(t, "magnitude  {}", readable(magnitude));
    }
    if let Some(distance) = meta.distance_km {
        let _ = writeln!(t, "distance   {} km", readable(distance));
    }
    let _ = writeln!(t, "points     {}", record.values.len());
    let _ = writeln!(t, "dt         {} s", readable(record.dt));
    let _ = writeln!(
        t,
        "duration   {} s (first sample at t = 0)",
        readable(record.duration())
    );
    let said = match meta.units {
        Some(_) => format!(", as the file says ({})", meta.units_said),
        None => ", as given (the file does not say)".to_string(),
    };
    let _ = writeln!(
        t,
        "units      {units} (1 {units} = {} m/s^2){said}",
        readable(*factor)
    );
    let peak_si = peak * factor;
    let _ = writeln!(
        t,
        "PGA        {:.6} g = {:.6} m/s^2 at t = {} s",
        peak_si / STANDARD_GRAVITY,
        peak_si,
        readable(m.t_pga)
    );
    let _ = writeln!(
        t,
        "PGV        {:.6} m/s at t = {} s",
        m.pgv,
        readable(m.t_pgv)
    );
    let _ = writeln!(
        t,
        "PGD        {:.6} m at t = {} s (from rest, no baseline correction)",
        m.pgd,
        readable(m.t_pgd)
    );
    let _ = writeln!(t, "Arias      {:.6} m/s", m.arias);
    let _ = writeln!(t, "CAV        {:.6} m/s", m.cav);
    for s in ordinates(&motion, periods, damping)? {
        let _ = writeln!(
            t,
            "Sa         {:.6} g = {:.6} m/s^2 at T = {} s, {} % damping",
            s.sa / STANDARD_GRAVITY,
            s.sa,
            readable(s.period),
            readable(100.0 * s.damping)
        );
    }
    Ok(t)
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

/// The columns of `flexrock record spectrum`.
pub const SPECTRUM_COLUMNS: [&str; 7] = [
    "period_s",
    "damping",
    "sa_g",
    "sa_m_s2",
    "sd_m",
    "t_peak_s",
    "sa_at_samples_g",
];

/// The response spectrum of a record at `periods` (s), as CSV ([`SPECTRUM_COLUMNS`]).
pub fn spectrum_csv(loaded: &LoadedRecord, periods: &[f64], damping: f64) -> Result<Vec<u8>> {
    let mut table = Table::new(&SPECTRUM_COLUMNS);
    for s in ordinates(&loaded.motion(), periods, damping)? {
        table.row([
            number(s.period),
            number(s.damping),
            number(s.sa / STANDARD_GRAVITY),
            number(s.sa),
            number(s.sd),
            number(s.t_peak),
            number(s.sa_at_samples / STANDARD_GRAVITY),
        ]);
    }
    Ok(table.into_bytes())
}

/// The record files `inputs` name: each file itself, and the records of each directory or
/// list file (`*.list`) as a suite ([`flexrock_core::floor::record::suite`]), with the suite's scale.
pub fn expand_inputs(inputs: &[PathBuf]) -> Result<Vec<(PathBuf, f64)>> {
    let mut files = Vec::new();
    for input in inputs {
        let is_list = input
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("list"));
        if input.is_dir() || is_list {
            let suite =
                flexrock_core::floor::record::suite::read_suite(input).map_err(|source| {
                    flexrock_core::Error::Record {
                        key: "suite".to_string(),
                        source,
                    }
                })?;
            files.extend(suite.entries.into_iter().map(|e| (e.path, e.scale)));
        } else {
            files.push((input.clone(), 1.0));
        }
    }
    Ok(files)
}

/// The columns of `flexrock record intensity`: the file and its scale, the record columns of
/// a sweep over records (metadata, PGA and Sa in g, PGV, PGD, Arias intensity and CAV in SI
/// units), the times of the peaks, the format, units, sampling and Sa's oscillator.
pub fn intensity_columns() -> Vec<String> {
    let mut columns = vec!["file".to_string(), "scale".to_string()];
    columns.extend(flexrock_core::analysis::sweep::PointResult::record_columns());
    columns.extend(
        [
            "t_pga_s",
            "t_pgv_s",
            "t_pgd_s",
            "sa_period_s",
            "sa_damping",
            "format",
            "units",
            "points",
            "dt_s",
            "duration_s",
        ]
        .map(String::from),
    );
    columns
}

/// One record's row of `flexrock record intensity` (in the order of [`intensity_columns`]):
/// the measures of the record times `scale`, Sa at `period` (s) if given.
pub fn intensity_row(
    loaded: &LoadedRecord,
    scale: f64,
    period: Option<f64>,
    damping: f64,
) -> Result<Vec<String>> {
    let scaled = LoadedRecord {
        record: loaded.record.clone(),
        units: loaded.units,
        factor: loaded.factor * scale,
    };
    let motion = scaled.motion();
    let ground: GroundMeasures = intensity::ground_measures(&motion);
    let sa = match period {
        Some(period) => Some(ordinates(&motion, &[period], damping)?[0]),
        None => None,
    };
    let cells = RecordCells {
        meta: Some(loaded.record.meta.clone()),
        ground: Some(ground),
        sa: sa.map(|s| s.sa),
    };
    let mut row = vec![loaded.record.source.clone(), number(scale)];
    row.extend(cells.named().iter().map(|(_, c)| c.field()));
    let float = |x: Option<f64>| Cell::Float(x).field();
    row.extend([
        number(ground.t_pga),
        number(ground.t_pgv),
        number(ground.t_pgd),
        float(period),
        float(period.map(|_| damping)),
        loaded.record.meta.format.to_string(),
        loaded.units.to_string(),
        loaded.record.values.len().to_string(),
        number(loaded.record.dt),
        number(loaded.record.duration()),
    ]);
    Ok(row)
}

/// The table of `flexrock record intensity` over `records` (each with its scale).
pub fn intensity_csv(
    records: &[(LoadedRecord, f64)],
    period: Option<f64>,
    damping: f64,
) -> Result<Vec<u8>> {
    let columns = intensity_columns();
    let mut table = Table::new(&columns.iter().map(String::as_str).collect::<Vec<_>>());
    for (loaded, scale) in records {
        table.row(intensity_row(loaded, *scale, period, damping)?);
    }
    Ok(table.into_bytes())
}
