//! CSV and text records.
//!
//! Comma-separated (CSV) or whitespace-separated (text), one row per sample, either two columns
//! `t, acc` (the time column must start at 0 and be uniformly spaced to 1e-6 relative; dt is
//! derived from it) or one column `acc` (dt must be given by the caller). An optional first
//! row of non-numeric column names is kept in [`Record::title`]; where the acceleration's
//! column is named `acc_m_s2`, `acc_g` or `acc_cm_s2` (as `flexrock record csv` writes it),
//! that is the unit the file declares. `#` starts a comment that runs to the end of the line;
//! blank lines are skipped.

use super::accelerogram::Record;
use super::error::{Location, RecordError};
use super::meta::RecordMeta;
use super::sampling::{check_dt, check_samples, dt_agrees, RELATIVE_DT_TOLERANCE};
use super::text::{numbered_lines, parse_number, quote, strip_byte_order_mark, NumberError};

/// Acceleration column names that declare their unit, with that unit: the names `flexrock
/// record csv` writes.
pub const UNIT_COLUMNS: [(&str, &str); 3] =
    [("acc_m_s2", "m/s2"), ("acc_g", "g"), ("acc_cm_s2", "cm/s2")];

/// How the fields of a row are separated.
#[derive(Clone, Copy)]
enum Separator {
    Comma,
    Whitespace,
}

impl Separator {
    fn split(self, content: &str) -> Vec<&str> {
        match self {
            Separator::Comma => content.split(',').map(str::trim).collect(),
            Separator::Whitespace => content.split_whitespace().collect(),
        }
    }
}

/// One CSV data row: its line number and its numbers.
struct CsvRow {
    line_number: usize,
    fields: Vec<f64>,
}

/// Reads a CSV record from its text: two columns `t, acc` (uniform t from 0; dt derived and, if
/// `dt` is given, checked against it) or one column `acc` (then `dt` is required).
pub fn parse_csv(text: &str, source: &str, dt: Option<f64>) -> Result<Record, RecordError> {
    parse_columns(text, source, dt, Separator::Comma)
}

/// Reads a text record (columns separated by spaces or tabs) by the rules of [`parse_csv`].
pub fn parse_text(text: &str, source: &str, dt: Option<f64>) -> Result<Record, RecordError> {
    parse_columns(text, source, dt, Separator::Whitespace)
}

fn parse_columns(
    text: &str,
    source: &str,
    dt: Option<f64>,
    separator: Separator,
) -> Result<Record, RecordError> {
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
        let fields = separator.split(content);

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
    let mut meta = RecordMeta::of_format(match separator {
        Separator::Comma => "csv",
        Separator::Whitespace => "text",
    });
    if let Some(header) = title.first() {
        let column = separator.split(header).last().copied().unwrap_or("");
        if let Some((name, unit)) = UNIT_COLUMNS
            .iter()
            .find(|(name, _)| column.eq_ignore_ascii_case(name))
        {
            meta.units = Some(unit);
            meta.units_said = format!("its column {name}");
        }
    }
    Ok(Record {
        source: source.to_string(),
        title,
        dt: record_dt,
        values,
        meta,
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
