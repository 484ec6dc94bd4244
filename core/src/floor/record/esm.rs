//! ESM and ITACA ASCII records (the Engineering Strong Motion database and the Italian
//! accelerometric archive; the "DYNA" header).
//!
//! # Layout
//!
//! A header of `KEY: VALUE` lines (the value may be empty), the first `EVENT_NAME:`, then the
//! values, one or more per line. The header ends at the first line that is not `KEY: VALUE`.
//! Keys relied on, each required once:
//!
//! - `SAMPLING_INTERVAL_S`: dt, s;
//! - `NDATA`: the number of values, which must be the number found;
//! - `UNITS`: `cm/s^2`, `m/s^2`, `g` (or another spelling [`unit_of`] reads); a unit of velocity
//!   or displacement is refused;
//! - `DATA_TYPE`: `ACCELERATION` (ESM), `PROCESSED ACCELERATION` or `UNPROCESSED ACCELERATION`
//!   (ITACA); `VELOCITY`, `DISPLACEMENT` and response spectra are refused.
//!
//! Metadata, where given: `EVENT_NAME` (else `EVENT_ID`), `EVENT_DATE_YYYYMMDD`, the magnitude
//! (`EVENT_MAGNITUDE`, else `MAGNITUDE_W`, `MAGNITUDE_L`, `MAGNITUDE_S`, the first given),
//! `NETWORK` and `STATION_CODE` (`IT.AQG`), `STREAM` (else `COMPONENT`) and
//! `EPICENTRAL_DISTANCE_KM`. A value of `None` or an empty one is not given.

use std::collections::HashMap;

use super::accelerogram::Record;
use super::error::{Location, RecordError};
use super::meta::{unit_of, Quantity, RecordMeta};
use super::sampling::{check_dt, check_samples};
use super::text::{numbered_lines, parse_number, quote, strip_byte_order_mark, NumberError};

/// The keys an ESM file must give.
const REQUIRED: [&str; 4] = ["SAMPLING_INTERVAL_S", "NDATA", "UNITS", "DATA_TYPE"];

/// Reads an ESM or ITACA ASCII record from its text. `source` names the file in messages.
pub fn parse_esm(text: &str, source: &str) -> Result<Record, RecordError> {
    let text = strip_byte_order_mark(text);
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            file: source.to_string(),
        });
    }
    let rule = |line: usize, rule: String| RecordError::HeaderRule {
        at: Location::line(source, line),
        rule,
    };
    let mut lines = numbered_lines(text).peekable();
    let mut header: HashMap<String, (usize, String)> = HashMap::new();
    let mut title = Vec::new();
    while let Some(&(number, line)) = lines.peek() {
        let Some((key, value)) = line.split_once(':') else {
            break;
        };
        let key = key.trim();
        let is_key = !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || "_/^-".contains(c));
        if !is_key {
            break;
        }
        if number == 1 && key != "EVENT_NAME" {
            break;
        }
        if let Some((first, _)) = header.get(key) {
            return Err(rule(
                number,
                format!("{key} is given twice (first at line {first})"),
            ));
        }
        header.insert(key.to_string(), (number, value.trim().to_string()));
        title.push(line.trim_end().to_string());
        lines.next();
    }
    if header.is_empty() {
        return Err(rule(
            1,
            "expected an ESM header, \"KEY: VALUE\" lines starting with EVENT_NAME:".to_string(),
        ));
    }
    let header_end = title.len();
    let required = |key: &str| -> Result<(usize, &str), RecordError> {
        match header.get(key) {
            Some((line, value)) if !value.is_empty() => Ok((*line, value.as_str())),
            Some((line, _)) => Err(rule(*line, format!("{key} has no value"))),
            None => Err(rule(
                header_end,
                format!(
                    "the header has no {key} line (an ESM or ITACA record gives {})",
                    REQUIRED.join(", ")
                ),
            )),
        }
    };

    let (line, data_type) = required("DATA_TYPE")?;
    let upper = data_type.to_ascii_uppercase();
    for quantity in [Quantity::Velocity, Quantity::Displacement] {
        if upper.contains(&quantity.name().to_ascii_uppercase()) {
            return Err(RecordError::NotAcceleration {
                at: Location::line(source, line),
                quantity,
                found: quote(data_type),
            });
        }
    }
    if !matches!(
        upper.as_str(),
        "ACCELERATION" | "PROCESSED ACCELERATION" | "UNPROCESSED ACCELERATION"
    ) {
        return Err(rule(
            line,
            format!(
                "DATA_TYPE is {:?}; flexrock reads ACCELERATION (or ITACA's PROCESSED or \
                 UNPROCESSED ACCELERATION) time series",
                quote(data_type)
            ),
        ));
    }
    let (units_line, units_text) = required("UNITS")?;
    let units = match unit_of(units_text) {
        Some((Quantity::Acceleration, name)) => name,
        Some((quantity, _)) => {
            return Err(RecordError::NotAcceleration {
                at: Location::line(source, units_line),
                quantity,
                found: format!("UNITS: {units_text}"),
            })
        }
        None => {
            return Err(RecordError::UnknownUnit {
                at: Location::line(source, units_line),
                found: units_text.to_string(),
            })
        }
    };
    let (line, dt_text) = required("SAMPLING_INTERVAL_S")?;
    let dt = match parse_number(dt_text) {
        Ok(dt) => check_dt(dt, Location::line(source, line))?,
        Err(_) => {
            return Err(rule(
                line,
                format!(
                    "SAMPLING_INTERVAL_S is {:?}, not a number of seconds",
                    quote(dt_text)
                ),
            ))
        }
    };
    let (ndata_line, ndata_text) = required("NDATA")?;
    let declared = ndata_text
        .parse::<usize>()
        .ok()
        .filter(|&n| n > 0)
        .ok_or_else(|| {
            rule(
                ndata_line,
                format!(
                    "NDATA is {:?}, not a count of values > 0",
                    quote(ndata_text)
                ),
            )
        })?;

    let mut values = Vec::with_capacity(declared.min(1 << 16));
    for (number, line) in lines {
        for token in line.split_whitespace() {
            match parse_number(token) {
                Ok(v) => values.push(v),
                Err(NumberError::NotFinite) => {
                    return Err(RecordError::NotFinite {
                        at: Location::line(source, number),
                        token: quote(token),
                    })
                }
                Err(NumberError::NotANumber) => {
                    return Err(RecordError::NotANumber {
                        at: Location::line(source, number),
                        token: quote(token),
                    })
                }
            }
        }
    }
    if values.len() != declared {
        return Err(rule(
            ndata_line,
            format!(
                "NDATA = {declared} but the file has {} values{}",
                values.len(),
                if values.len() < declared {
                    " (truncated file?)"
                } else {
                    ""
                }
            ),
        ));
    }
    check_samples(&values, source)?;

    let given = |key: &str| {
        header
            .get(key)
            .map(|(_, v)| v.as_str())
            .filter(|v| !v.is_empty() && !v.eq_ignore_ascii_case("none"))
    };
    let mut meta = RecordMeta::of_format("esm");
    meta.units = Some(units);
    meta.units_said = format!("line {units_line} \"UNITS: {units_text}\"");
    meta.event = given("EVENT_NAME")
        .or(given("EVENT_ID"))
        .map(str::to_string);
    meta.date = given("EVENT_DATE_YYYYMMDD").map(|d| {
        if d.len() == 8 && d.bytes().all(|b| b.is_ascii_digit()) {
            format!("{}-{}-{}", &d[..4], &d[4..6], &d[6..])
        } else {
            d.to_string()
        }
    });
    meta.magnitude = [
        "EVENT_MAGNITUDE",
        "MAGNITUDE_W",
        "MAGNITUDE_L",
        "MAGNITUDE_S",
    ]
    .into_iter()
    .find_map(|key| given(key).and_then(|v| parse_number(v).ok()));
    meta.station = given("STATION_CODE").map(|code| match given("NETWORK") {
        Some(network) => format!("{network}.{code}"),
        None => code.to_string(),
    });
    meta.component = given("STREAM").or(given("COMPONENT")).map(str::to_string);
    meta.distance_km = given("EPICENTRAL_DISTANCE_KM").and_then(|v| parse_number(v).ok());
    Ok(Record {
        source: source.to_string(),
        title,
        dt,
        values,
        meta,
    })
}
