//! PEER "AT2" records.
//!
//! # PEER AT2
//!
//! Four header lines, then the values:
//!
//! - lines 1-3: free text (database, event/station/component, units); kept in [`Record::title`].
//!   Line 3 says what the file holds and in which unit, as `ACCELERATION TIME SERIES IN UNITS
//!   OF G` (PEER NGA-West2), `ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: ...`
//!   (older PEER files), `... IN UNITS OF CM/SEC/SEC` or `The units are (g)`: the unit is the
//!   word after `UNITS OF` or `UNITS ARE` (any letter case, parentheses and a final `.`
//!   dropped), read by [`unit_of`]. A file whose line 3 says `VELOCITY` or `DISPLACEMENT`, or
//!   names a unit of velocity or displacement, is refused; a unit not known is refused; a line
//!   3 that names no unit leaves the unit to the user. Line 2 gives the event, date, station
//!   and component where it has their form, `<event>, <date>, <station>, <component>` (PEER
//!   NGA-West2: `Imperial Valley-02, 5/19/1940, El Centro Array #9, 180`), with the date
//!   (`M/D/YY` or `M/D/YYYY`) inside the event's field or after it, and a time (`14:06`) after
//!   the date skipped (older PEER files: `BORAH PEAK EQ, 10/28/83, 14:06, ANL-767 ..., 196`);
//! - line 4: the number of points and the sampling interval, as `NPTS=<count>, DT=<seconds>`
//!   with case-insensitive keys, an optional comma and an optional unit word (`SEC`, `S`,
//!   `SECS`, `SECOND`, `SECONDS`; a trailing comma as in PEER NGA files), e.g.
//!   `NPTS=  1559, DT= .02000 SEC`, `NPTS=   1451, dt=  .02000`, `NPTS=   7998, DT=   .0050 SEC,`;
//!   or the older layout `<count> <seconds> NPTS, DT`, e.g. `3930 0.00500 NPTS, DT`;
//! - lines 5 onwards: the values, any number per line, separated by whitespace (typically the
//!   Fortran layouts 8F10.5 or 5E15.7). A line whose whitespace-separated tokens are not all
//!   numbers is read again as fixed-width fields of 10 or 15 characters, so that fields that
//!   touch (`-100.12345-100.12345`) are still read. Where both widths read such a line, the
//!   file's layout decides: the width the other lines are laid out in (their length per value),
//!   else the one that gives NPTS values.
//!
//! The number of values must equal NPTS; NaN and infinite values are errors; dt must be at
//! least [`MIN_DT`].
//! CRLF line ends, a missing newline after the last value, blank lines and a UTF-8 byte-order
//! mark are accepted.
//!

use super::accelerogram::Record;
use super::error::{Location, RecordError};
use super::meta::{unit_of, Quantity, RecordMeta};
use super::sampling::{check_dt, check_samples};
use super::text::{
    numbered_lines, parse_number, quote, strip_byte_order_mark, strip_prefix_ignore_case,
    NumberError,
};

/// What the 4th line of an AT2 file must look like (used in messages).
const AT2_HEADER_FORM: &str = "\"NPTS=<count>, DT=<seconds>\" in the 4th header line";

/// Splits `text` after its leading characters that satisfy `keep`.
fn split_leading(text: &str, keep: impl Fn(char) -> bool) -> (&str, &str) {
    let end = text.find(|c: char| !keep(c)).unwrap_or(text.len());
    text.split_at(end)
}

/// The count and dt of a `NPTS=<count>[,] DT=<dt> [unit]` line, if it has that form.
fn parse_keyed_header(line: &str) -> Option<(usize, f64)> {
    let rest = strip_prefix_ignore_case(line.trim(), "NPTS")?.trim_start();
    let rest = rest.strip_prefix('=')?.trim_start();
    let (count_text, rest) = split_leading(rest, |c| c.is_ascii_digit());
    let count = count_text.parse::<usize>().ok()?;
    let rest = rest.trim_start();
    let rest = rest.strip_prefix(',').unwrap_or(rest).trim_start();
    let rest = strip_prefix_ignore_case(rest, "DT")?.trim_start();
    let rest = rest.strip_prefix('=')?.trim_start();
    let (dt_text, unit) = split_leading(rest, |c| {
        c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'e' | 'E')
    });
    let dt = dt_text.parse::<f64>().ok()?;
    // PEER NGA files end the line with a comma: `NPTS=   7998, DT=   .0050 SEC,`.
    let unit = unit.trim();
    let unit = unit.strip_suffix(',').unwrap_or(unit).trim_end();
    let unit_is_seconds = ["", "S", "SEC", "SECS", "SECOND", "SECONDS"]
        .iter()
        .any(|allowed| unit.eq_ignore_ascii_case(allowed));
    unit_is_seconds.then_some((count, dt))
}

/// The count and dt of an old-style `<count> <dt> NPTS, DT` line, if it has that form.
fn parse_old_style_header(line: &str) -> Option<(usize, f64)> {
    let without_commas = line.replace(',', " ");
    let words: Vec<&str> = without_commas.split_whitespace().collect();
    match words.as_slice() {
        [count, dt, npts, dt_word]
            if npts.eq_ignore_ascii_case("NPTS") && dt_word.eq_ignore_ascii_case("DT") =>
        {
            Some((count.parse().ok()?, dt.parse().ok()?))
        }
        _ => None,
    }
}

/// The numbers of `line` read as consecutive fields of `width` characters, if every field is a
/// finite number and the line (without trailing blanks) is a whole number of fields.
fn parse_fixed_width(line: &str, width: usize) -> Option<Vec<f64>> {
    let chars: Vec<char> = line.trim_end().chars().collect();
    if width == 0 || !chars.len().is_multiple_of(width) {
        return None;
    }
    chars
        .chunks(width)
        .map(|field| {
            let field: String = field.iter().collect();
            parse_number(field.trim()).ok()
        })
        .collect()
}

/// Fortran field widths of AT2 layouts: 8F10.5 and 5E15.7.
const AT2_FIELD_WIDTHS: [usize; 2] = [10, 15];

/// One AT2 data line, read.
enum At2Line {
    /// Whitespace-separated numbers; the field width the line is laid out in, if its length is
    /// a whole number of fields of 10 or 15 characters (`   .1181069E-02  -.1366453E-02`: 15).
    Tokens {
        values: Vec<f64>,
        width: Option<usize>,
    },
    /// Fields that touch (`-100.12345-100.12345`), read as fixed-width fields of 10 and of 15
    /// characters (None where that width does not read).
    Touching {
        ten: Option<Vec<f64>>,
        fifteen: Option<Vec<f64>>,
    },
}

/// Reads one AT2 data line; an error names the first token that is not a finite number when the
/// line reads neither as whitespace-separated numbers nor as fixed-width fields.
fn parse_at2_values_line(line: &str, at: impl Fn() -> Location) -> Result<At2Line, RecordError> {
    let mut values = Vec::new();
    for token in line.split_whitespace() {
        match parse_number(token) {
            Ok(value) => values.push(value),
            Err(NumberError::NotFinite) => {
                return Err(RecordError::NotFinite {
                    at: at(),
                    token: quote(token),
                })
            }
            Err(NumberError::NotANumber) => {
                // Fortran fields may touch each other ("-100.12345-100.12345"): read the line
                // again as fixed-width fields before giving up.
                let ten = parse_fixed_width(line, AT2_FIELD_WIDTHS[0]);
                let fifteen = parse_fixed_width(line, AT2_FIELD_WIDTHS[1]);
                if ten.is_none() && fifteen.is_none() {
                    return Err(RecordError::NotANumber {
                        at: at(),
                        token: quote(token),
                    });
                }
                return Ok(At2Line::Touching { ten, fifteen });
            }
        }
    }
    let length = line.trim_end().chars().count();
    let width = AT2_FIELD_WIDTHS
        .into_iter()
        .find(|&w| !values.is_empty() && length == w * values.len());
    Ok(At2Line::Tokens { values, width })
}

/// The values of an AT2 file's data lines. A line of touching fields may read both as 10- and
/// as 15-character fields (`-0.0001234567890.0009876543210` is two F15 fields, or three
/// nonsense F10 ones); its width is the file's: the one that the other lines are laid out in
/// (by their length per value, or by reading at one width only), else the one that gives the
/// header's NPTS values, else 10.
fn at2_values(lines: Vec<At2Line>, declared_count: usize) -> Vec<f64> {
    let mut votes = [0usize; 2];
    for line in &lines {
        let width = match line {
            At2Line::Tokens { width, .. } => *width,
            At2Line::Touching { ten, fifteen } => match (ten, fifteen) {
                (Some(_), None) => Some(AT2_FIELD_WIDTHS[0]),
                (None, Some(_)) => Some(AT2_FIELD_WIDTHS[1]),
                _ => None,
            },
        };
        if let Some(w) = width {
            votes[usize::from(w == AT2_FIELD_WIDTHS[1])] += 1;
        }
    }
    let values_at = |fifteen_wide: bool| -> Vec<f64> {
        lines
            .iter()
            .flat_map(|line| match line {
                At2Line::Tokens { values, .. } => values.clone(),
                At2Line::Touching { ten, fifteen } => {
                    let (preferred, other) = if fifteen_wide {
                        (fifteen, ten)
                    } else {
                        (ten, fifteen)
                    };
                    preferred
                        .clone()
                        .or_else(|| other.clone())
                        .unwrap_or_default()
                }
            })
            .collect()
    };
    let fifteen_wide = match votes {
        [ten, fifteen] if fifteen > ten => true,
        [ten, fifteen] if ten > fifteen => false,
        _ => values_at(true).len() == declared_count && values_at(false).len() != declared_count,
    };
    values_at(fifteen_wide)
}

/// Reads a PEER AT2 record from its text. `source` names the file in messages.
pub fn parse_at2(text: &str, source: &str) -> Result<Record, RecordError> {
    let text = strip_byte_order_mark(text);
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            file: source.to_string(),
        });
    }

    let mut lines = numbered_lines(text);
    let title: Vec<String> = lines
        .by_ref()
        .take(3)
        .map(|(_, line)| line.trim_end().to_string())
        .collect();
    let Some((header_line_number, header_line)) = lines.next() else {
        return Err(RecordError::TooFewHeaderLines {
            file: source.to_string(),
            found: title.len(),
        });
    };
    let header_at = || Location::line(source, header_line_number);

    let (declared_count, dt) = parse_keyed_header(header_line)
        .or_else(|| parse_old_style_header(header_line))
        .ok_or_else(|| RecordError::BadHeader {
            at: header_at(),
            expected: AT2_HEADER_FORM,
            found: quote(header_line.trim_end()),
        })?;
    if declared_count == 0 {
        return Err(RecordError::InvalidCount {
            at: header_at(),
            found: declared_count,
        });
    }
    let dt = check_dt(dt, header_at())?;

    let data_lines = lines
        .map(|(line_number, line)| {
            parse_at2_values_line(line, || Location::line(source, line_number))
        })
        .collect::<Result<Vec<At2Line>, RecordError>>()?;
    let values = at2_values(data_lines, declared_count);

    let file = source.to_string();
    if values.is_empty() {
        return Err(RecordError::NoValues {
            file,
            declared: declared_count,
        });
    }
    if values.len() < declared_count {
        return Err(RecordError::TooFewValues {
            file,
            declared: declared_count,
            found: values.len(),
        });
    }
    if values.len() > declared_count {
        return Err(RecordError::TooManyValues {
            file,
            declared: declared_count,
            found: values.len(),
        });
    }

    check_samples(&values, &file)?;
    let mut meta = RecordMeta::of_format("peer-at2");
    if let Some(line) = title.get(2) {
        if let Some((units, said)) = at2_units(line, || Location::line(source, 3))? {
            meta.units = Some(units);
            meta.units_said = format!("line 3 {said:?}");
        }
    }
    if let Some(line) = title.get(1) {
        event_fields(line, &mut meta);
    }
    Ok(Record {
        source: file,
        title,
        dt,
        values,
        meta,
    })
}

/// The unit of acceleration an AT2 file's 3rd line declares, with the line as written; None
/// where it names none. A velocity or displacement file is refused, and so is a unit not known.
fn at2_units(
    line: &str,
    at: impl Fn() -> Location,
) -> Result<Option<(&'static str, String)>, RecordError> {
    let upper = line.to_ascii_uppercase();
    let said = quote(line.trim());
    for quantity in [Quantity::Velocity, Quantity::Displacement] {
        if upper.contains(&quantity.name().to_ascii_uppercase()) {
            return Err(RecordError::NotAcceleration {
                at: at(),
                quantity,
                found: said,
            });
        }
    }
    let Some(word) = ["UNITS OF", "UNITS ARE"].iter().find_map(|lead| {
        let rest = &line[upper.find(lead)? + lead.len()..];
        let rest = rest.trim_start().trim_start_matches('(').trim_start();
        let end = rest
            .find(|c: char| c.is_whitespace() || matches!(c, ',' | ')' | ';'))
            .unwrap_or(rest.len());
        Some(rest[..end].trim_end_matches('.').to_string())
    }) else {
        return Ok(None);
    };
    match unit_of(&word) {
        Some((Quantity::Acceleration, name)) => Ok(Some((name, said))),
        Some((quantity, _)) => Err(RecordError::NotAcceleration {
            at: at(),
            quantity,
            found: said,
        }),
        None => Err(RecordError::UnknownUnit {
            at: at(),
            found: word,
        }),
    }
}

/// A date as PEER files write it, `M/D/YY` or `M/D/YYYY` (US order): `YYYY-MM-DD` for a full
/// year, else as written. None for anything else.
fn peer_date(word: &str) -> Option<String> {
    let parts: Vec<&str> = word.split('/').collect();
    let [month, day, year] = parts.as_slice() else {
        return None;
    };
    let digits = |p: &str, widths: &[usize]| {
        widths.contains(&p.len()) && p.bytes().all(|b| b.is_ascii_digit())
    };
    if !(digits(month, &[1, 2]) && digits(day, &[1, 2]) && digits(year, &[2, 4])) {
        return None;
    }
    let (m, d): (u32, u32) = (month.parse().ok()?, day.parse().ok()?);
    if !((1..=12).contains(&m) && (1..=31).contains(&d)) {
        return None;
    }
    Some(if year.len() == 4 {
        format!("{year}-{m:02}-{d:02}")
    } else {
        word.to_string()
    })
}

/// The event, date, station and component of an AT2 file's 2nd line, where it has the form
/// `<event> [<date>], [<date>,] [<time>,] <station>, <component>`; nothing where no date is
/// found (the line is then free text, as in the El Centro "Peknold" file).
fn event_fields(line: &str, meta: &mut RecordMeta) {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    let date_at = fields.iter().enumerate().find_map(|(i, field)| {
        let words: Vec<&str> = field.split_whitespace().collect();
        words
            .iter()
            .position(|w| peer_date(w).is_some())
            .map(|w| (i, w, words))
    });
    let Some((field, word, words)) = date_at else {
        return;
    };
    meta.date = peer_date(words[word]);
    let event = if word > 0 {
        words[..word].join(" ")
    } else if field > 0 {
        fields[..field].join(", ")
    } else {
        String::new()
    };
    meta.event = (!event.is_empty()).then_some(event);
    // After the date: a time (`14:06`, `0230`) in its own field is skipped.
    let is_time = |f: &str| !f.is_empty() && f.chars().all(|c| c.is_ascii_digit() || c == ':');
    let rest: Vec<&str> = fields[field + 1..]
        .iter()
        .copied()
        .skip_while(|f| is_time(f))
        .collect();
    // The component: the last field, without a parenthesis after it (`180 (USGS STATION 117)`).
    if let [station @ .., component] = rest.as_slice() {
        let component = component.split(" (").next().unwrap_or("").trim();
        meta.component = (!component.is_empty()).then(|| component.to_string());
        let station = station.join(", ");
        meta.station = (!station.is_empty()).then_some(station);
    }
}
