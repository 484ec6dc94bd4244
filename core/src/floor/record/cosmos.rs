//! COSMOS V1 and V2 records (the COSMOS Strong Motion Data Format, version 1.20).
//!
//! # Layout
//!
//! One channel: a text header, an integer header, a real header, comments, then data blocks.
//!
//! - line 1 names what the file holds and how many text lines its header has:
//!   `Corrected acceleration    (Format v01.20 with 13 text lines)` (V2) or `Uncorrected
//!   acceleration ...` (V1). Raw counts (V0), velocities, displacements and spectra are refused.
//!   Line 2 names the event (`Record of <event> of <date>`), line 5 the station (`Code:<code>`);
//!   the text line `Values used when parameter or data value is unknown/unspecified: -999,
//!   -999.00` gives the values that stand for an unknown integer and real.
//! - `<n> Integer-header values follow on <m> lines, Format= (10I8)`, then those m lines: the
//!   n integers. Those read: 2 (the data's physical quantity: 1 acceleration), 3 (its unit's
//!   code: 2 g, 4 cm/s/s, 10 gal), 40, 42 and 43 (year, month, day of the event) and 54 (the
//!   channel's orientation: an azimuth 1-360, or 400-402 vertical, 500-501 radial and
//!   transverse, 600-601 longitudinal and tangential, 700-701 horizontal of unknown azimuth).
//! - `<n> Real-header values follow on <m> lines, Format= (5F15.6)`, then the n reals. Those
//!   read: 13-16 (magnitudes: Mw, ML, Ms, other; the first known is kept), 17 (the epicentral
//!   distance, km), 62 (the sampling interval, ms) and 63 (the record's length, s).
//! - `<n> Comment line(s) follow, each starting with a "|":`, then the n comment lines.
//! - the data block: `<NPTS> acceleration pts, approx <x> secs, units=cm/sec2(04),
//!   Format=(8F10.5)`, then the NPTS values, any number per line (as whitespace-separated
//!   numbers, or as the Format's fixed-width fields where they touch). Blocks of velocity and
//!   displacement may follow (V2), and a line `End-of-data for Chan 1 ...`; they are not read.
//!
//! Every field relied on is checked: the counts of values and lines, the data's quantity in line
//! 1, integer 2 and the data line, its unit in integer 3 and the data line, the sampling
//! interval (known, positive), the length NPTS x dt against real 63 (to a sample) and against
//! the data line's approximate seconds (to 1 s and 1 %), and exactly NPTS values. A second
//! channel in the same file is refused.

use super::accelerogram::Record;
use super::error::{Location, RecordError};
use super::meta::{unit_of, Quantity, RecordMeta};
use super::sampling::{check_dt, check_samples};
use super::text::{numbered_lines, parse_number, quote, strip_byte_order_mark, NumberError};

/// A numbered line of the file.
type Line<'a> = (usize, &'a str);

/// The physical units codes of COSMOS Table 2 that are units of acceleration flexrock reads,
/// of velocity or of displacement, with their canonical names.
fn unit_code(code: i64) -> Option<(Quantity, &'static str)> {
    Some(match code {
        2 => (Quantity::Acceleration, "g"),
        4 | 10 => (Quantity::Acceleration, "cm/s2"),
        5 => (Quantity::Velocity, "cm/s"),
        6 => (Quantity::Displacement, "cm"),
        _ => return None,
    })
}

/// The reader's state: the file's lines and where it is.
struct Reader<'a> {
    source: &'a str,
    lines: Vec<Line<'a>>,
    next: usize,
}

impl<'a> Reader<'a> {
    fn at(&self, line: usize) -> Location {
        Location::line(self.source, line)
    }

    fn rule(&self, line: usize, rule: String) -> RecordError {
        RecordError::HeaderRule {
            at: self.at(line),
            rule,
        }
    }

    /// The next line; an error naming `what` was expected where the file ends.
    fn line(&mut self, what: &str) -> Result<Line<'a>, RecordError> {
        let line = self
            .lines
            .get(self.next)
            .copied()
            .ok_or_else(|| RecordError::HeaderRule {
                at: Location::file(self.source),
                rule: format!("the file ends where {what} was expected"),
            })?;
        self.next += 1;
        Ok(line)
    }

    /// A block's count line, `<n> <words> ... on <m> lines, Format= (<k><X><w>...)`: n, m (if
    /// it says) and the field width w (if it says).
    fn count_line(
        &mut self,
        what: &str,
        words: &str,
    ) -> Result<(usize, Line<'a>, Option<usize>, Option<usize>), RecordError> {
        let (number, line) = self.line(what)?;
        let lower = line.to_ascii_lowercase();
        let count = lower
            .split_whitespace()
            .next()
            .and_then(|w| w.parse::<usize>().ok())
            .filter(|_| lower.contains(words));
        let Some(count) = count else {
            return Err(self.rule(
                number,
                format!(
                    "expected {what}, \"<count> {words} ...\", found {:?}",
                    quote(line.trim())
                ),
            ));
        };
        // `... follow on 10 lines`: the number before the word `lines`.
        let tokens: Vec<&str> = lower.split_whitespace().collect();
        let lines = tokens
            .windows(2)
            .find(|pair| pair[1].starts_with("line") && pair[1] != "line(s)")
            .and_then(|pair| pair[0].parse::<usize>().ok());
        Ok((count, (number, line), lines, format_width(&lower)))
    }

    /// `count` numbers from the next lines (exactly `lines` of them where the count line says),
    /// whitespace-separated or in fixed-width fields of `width`; the last line read must not
    /// hold more.
    fn numbers(
        &mut self,
        count: usize,
        lines: Option<usize>,
        width: Option<usize>,
        what: &str,
    ) -> Result<Vec<f64>, RecordError> {
        // The count is the file's word: memory is taken as the values come.
        let mut values = Vec::with_capacity(count.min(1 << 16));
        let mut read = 0;
        while values.len() < count {
            let Some(&(number, line)) = self.lines.get(self.next) else {
                return Err(RecordError::TooFewValues {
                    file: self.source.to_string(),
                    declared: count,
                    found: values.len(),
                });
            };
            if lines.is_some_and(|l| read == l) {
                return Err(self.rule(
                    number,
                    format!(
                        "the {what} has {} values on the {read} lines its count line gives, not \
                         {count}",
                        values.len()
                    ),
                ));
            }
            // A line of words (the next block's count line, `End-of-data`) ends the block:
            // too few values.
            let is_text = line
                .split_whitespace()
                .any(|w| w.len() >= 3 && w.chars().all(|c| c.is_ascii_alphabetic()));
            if is_text {
                return Err(self.rule(
                    number,
                    format!(
                        "the {what} ends here with {} values, fewer than the {count} its count \
                         line gives",
                        values.len()
                    ),
                ));
            }
            self.next += 1;
            read += 1;
            let found = numbers_of_line(line, width, || self.at(number))?;
            if values.len() + found.len() > count {
                return Err(self.rule(
                    number,
                    format!("the {what} has more than the {count} values its count line gives"),
                ));
            }
            values.extend(found);
        }
        if let Some(l) = lines.filter(|&l| l != read) {
            let number = self.lines.get(self.next - 1).map_or(0, |l| l.0);
            return Err(self.rule(
                number,
                format!("the {what} takes {read} lines, not the {l} its count line gives"),
            ));
        }
        Ok(values)
    }
}

/// The field width of a Fortran format `(10I8)`, `(5F15.6)`, `(1E15.6)` in `text`, if any.
fn format_width(text: &str) -> Option<usize> {
    let start = text.find("format")?;
    let rest = &text[start..];
    let open = rest.find('(')?;
    let inside = &rest[open + 1..];
    let letter = inside.find(|c: char| c.is_ascii_alphabetic())?;
    let digits: String = inside[letter + 1..]
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits.parse().ok().filter(|&w| w > 0)
}

/// The numbers of one line: whitespace-separated, else fixed-width fields of `width`.
fn numbers_of_line(
    line: &str,
    width: Option<usize>,
    at: impl Fn() -> Location,
) -> Result<Vec<f64>, RecordError> {
    let mut values = Vec::new();
    for token in line.split_whitespace() {
        match parse_number(token) {
            Ok(v) => values.push(v),
            Err(NumberError::NotFinite) => {
                return Err(RecordError::NotFinite {
                    at: at(),
                    token: quote(token),
                })
            }
            Err(NumberError::NotANumber) => {
                let fixed = width.and_then(|w| fixed_fields(line, w));
                return fixed.ok_or_else(|| RecordError::NotANumber {
                    at: at(),
                    token: quote(token),
                });
            }
        }
    }
    Ok(values)
}

/// The numbers of `line` as consecutive fields of `width` characters (the last may be short).
fn fixed_fields(line: &str, width: usize) -> Option<Vec<f64>> {
    let chars: Vec<char> = line.trim_end().chars().collect();
    chars
        .chunks(width)
        .map(|field| {
            let field: String = field.iter().collect();
            parse_number(field.trim()).ok()
        })
        .collect()
}

/// The values that stand for an unknown integer and real in the text line that says so
/// (`Values used when parameter or data value is unknown/unspecified:   -999, -999.00`; not
/// another line that says `unknown`, such as `Site geology: unknown`).
fn unknown_values(text_lines: &[Line<'_>]) -> (Option<f64>, Option<f64>) {
    let Some((_, line)) = text_lines.iter().find(|(_, l)| {
        let l = l.to_ascii_lowercase();
        l.contains("values used") || l.contains("unknown/unspecified")
    }) else {
        return (None, None);
    };
    let Some((_, rest)) = line.split_once(':') else {
        return (None, None);
    };
    let mut numbers = rest
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter_map(|w| parse_number(w).ok());
    (numbers.next(), numbers.next())
}

/// Reads a COSMOS V1 or V2 record (one channel) from its text. `source` names the file in
/// messages.
pub fn parse_cosmos(text: &str, source: &str) -> Result<Record, RecordError> {
    let text = strip_byte_order_mark(text);
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            file: source.to_string(),
        });
    }
    let mut r = Reader {
        source,
        lines: numbered_lines(text).collect(),
        next: 0,
    };
    let (_, first) = r.line("the first line")?;
    let lower = first.to_ascii_lowercase();
    let text_lines = lower
        .split("with")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|w| w.parse::<usize>().ok())
        .filter(|_| lower.contains("(format v") && lower.contains("text lines"));
    let Some(text_lines) = text_lines else {
        return Err(r.rule(
            1,
            format!(
                "expected a COSMOS first line, \"<data>  (Format v01.20 with 13 text lines)\", \
                 found {:?}",
                quote(first.trim())
            ),
        ));
    };
    let holds = lower
        .split("(format")
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    for quantity in [Quantity::Velocity, Quantity::Displacement] {
        if holds.contains(quantity.name()) {
            return Err(RecordError::NotAcceleration {
                at: r.at(1),
                quantity,
                found: quote(first.trim()),
            });
        }
    }
    if !holds.contains("acceleration") || holds.contains("count") {
        return Err(r.rule(
            1,
            format!(
                "the file holds {holds:?}; flexrock reads corrected (V2) or uncorrected (V1) \
                 acceleration in physical units"
            ),
        ));
    }
    let mut header = vec![(1, first)];
    for _ in 1..text_lines {
        header.push(r.line("the text header")?);
    }
    let (int_unknown, real_unknown) = unknown_values(&header);

    let (count, _, lines, width) = r.count_line("the integer header's count line", "integer")?;
    let integers = r.numbers(count, lines, width, "integer header")?;
    let (count, _, lines, width) = r.count_line("the real header's count line", "real")?;
    let reals = r.numbers(count, lines, width, "real header")?;
    let (count, _, _, _) = r.count_line("the comments' count line", "comment")?;
    for _ in 0..count {
        let (number, line) = r.line("a comment line")?;
        if !line.starts_with('|') {
            return Err(r.rule(
                number,
                format!(
                    "expected a comment line starting with \"|\" ({count} follow the count line), \
                     found {:?}",
                    quote(line.trim())
                ),
            ));
        }
    }
    let integer = |i: usize| {
        integers
            .get(i - 1)
            .copied()
            .filter(|&v| Some(v) != int_unknown)
    };
    let real = |i: usize| {
        reals
            .get(i - 1)
            .copied()
            .filter(|&v| Some(v) != real_unknown)
    };

    // The data block's line: `<NPTS> acceleration pts, approx <x> secs, units=cm/sec2(04), ...`.
    let (npts, (data_line, data_text), _, width) =
        r.count_line("the acceleration data's count line", "pts")?;
    let data_lower = data_text.to_ascii_lowercase();
    let kind = data_lower.split_whitespace().nth(1).unwrap_or("");
    for quantity in [Quantity::Velocity, Quantity::Displacement] {
        if kind.starts_with(&quantity.name()[..3]) {
            return Err(RecordError::NotAcceleration {
                at: r.at(data_line),
                quantity,
                found: quote(data_text.trim()),
            });
        }
    }
    if !kind.starts_with("acc") {
        return Err(r.rule(
            data_line,
            format!(
                "expected the acceleration data's count line, \"<NPTS> acceleration pts, ...\", \
                 found {:?}",
                quote(data_text.trim())
            ),
        ));
    }
    // The unit: its word and its code in the data line, and integer 3.
    let units_text = data_text
        .split_once("units=")
        .or_else(|| data_text.split_once("UNITS="))
        .map(|(_, rest)| rest)
        .unwrap_or("");
    let word: String = units_text
        .chars()
        .take_while(|&c| c != '(' && c != ',')
        .collect();
    let code = units_text
        .split_once('(')
        .and_then(|(_, rest)| rest.split(')').next())
        .and_then(|c| c.trim().parse::<i64>().ok());
    let from_word = match unit_of(word.trim()) {
        Some(unit) => unit,
        None => {
            return Err(RecordError::UnknownUnit {
                at: r.at(data_line),
                found: word.trim().to_string(),
            })
        }
    };
    let mut units_said = format!("line {data_line} {:?}", quote(data_text.trim()));
    for (what, code) in [
        ("the data line's unit code", code),
        (
            "integer header value 3 (the unit's code)",
            integer(3).map(|v| v as i64),
        ),
    ] {
        if let Some(code) = code {
            if unit_code(code) != Some(from_word) {
                return Err(r.rule(
                    data_line,
                    format!(
                        "{what}, {code}, is not the unit {:?} the data line names",
                        word.trim()
                    ),
                ));
            }
        }
    }
    let (quantity, units) = from_word;
    if quantity != Quantity::Acceleration {
        return Err(RecordError::NotAcceleration {
            at: r.at(data_line),
            quantity,
            found: quote(data_text.trim()),
        });
    }
    match integer(2).map(|v| v as i64) {
        None | Some(1) => {}
        Some(other) => {
            let quantity = match other {
                2 => Some(Quantity::Velocity),
                3 => Some(Quantity::Displacement),
                _ => None,
            };
            return Err(match quantity {
                Some(quantity) => RecordError::NotAcceleration {
                    at: r.at(data_line),
                    quantity,
                    found: format!("integer header value 2 = {other}"),
                },
                None => r.rule(
                    data_line,
                    format!(
                        "integer header value 2 (the data's quantity) is {other}, not 1 \
                         (acceleration)"
                    ),
                ),
            });
        }
    }
    if integer(3).is_some() {
        units_said.push_str(" and integer header value 3");
    }

    // The sampling interval, real 62 in ms, and the lengths that check it.
    let Some(dt_ms) = real(62) else {
        return Err(r.rule(
            data_line,
            "the real header gives no sampling interval (real value 62, ms)".to_string(),
        ));
    };
    let dt = check_dt(dt_ms / 1000.0, r.at(data_line))?;
    let length = npts as f64 * dt;
    if let Some(said) = real(63) {
        if (said - length).abs() > dt * (1.0 + 1e-6) {
            return Err(r.rule(
                data_line,
                format!(
                    "the record's length in the real header (value 63) is {said} s, but NPTS = \
                     {npts} samples at dt = {dt} s (real value 62, {dt_ms} ms) last {length} s"
                ),
            ));
        }
    }
    let approx = data_lower
        .split("approx")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|w| w.trim_end_matches(',').parse::<f64>().ok());
    if let Some(approx) = approx {
        if (approx - length).abs() > 1.0 + 0.01 * length {
            return Err(r.rule(
                data_line,
                format!(
                    "the data line says approximately {approx} s, but NPTS = {npts} samples at \
                     dt = {dt} s (real value 62) last {length} s"
                ),
            ));
        }
    }
    let values = r.numbers(npts, None, width, "acceleration data")?;
    // What follows the values: not more values, and no second channel.
    if let Some(&(number, line)) = r.lines[r.next..].iter().find(|(_, l)| !l.trim().is_empty()) {
        if line.split_whitespace().all(|w| parse_number(w).is_ok()) {
            return Err(r.rule(
                number,
                format!(
                    "more values than the NPTS = {npts} the data line (line {data_line}) gives"
                ),
            ));
        }
    }
    if let Some(&(number, _)) = r.lines[r.next..]
        .iter()
        .find(|(_, l)| l.to_ascii_lowercase().contains("(format v"))
    {
        return Err(r.rule(
            number,
            "a second channel's header: the file holds more than one channel, and flexrock \
             reads one; split the file"
                .to_string(),
        ));
    }
    check_samples(&values, source)?;

    let mut meta = RecordMeta::of_format("cosmos");
    meta.units = Some(units);
    meta.units_said = units_said;
    if let Some(&(_, line)) = header.get(1) {
        let event = line.trim();
        let event = event
            .get(..10)
            .filter(|p| p.eq_ignore_ascii_case("record of "))
            .map_or(event, |_| &event[10..]);
        let event = event.split(" of ").next().unwrap_or("").trim();
        meta.event = (!event.is_empty()).then(|| event.to_string());
    }
    if let (Some(y), Some(m), Some(d)) = (integer(40), integer(42), integer(43)) {
        let (y, m, d) = (y as i64, m as i64, d as i64);
        if (1..=12).contains(&m) && (1..=31).contains(&d) && (1000..10000).contains(&y) {
            meta.date = Some(format!("{y:04}-{m:02}-{d:02}"));
        }
    }
    if let Some(&(_, line)) = header.get(4) {
        meta.station = line
            .split_once("Code:")
            .and_then(|(_, rest)| rest.split_whitespace().next())
            .map(str::to_string);
    }
    meta.component = integer(54).and_then(|o| {
        let o = o as i64;
        Some(match o {
            1..=360 => format!("{o:03}"),
            400 => "UP".into(),
            401 => "DOWN".into(),
            402 => "VERT".into(),
            500 => "RADIAL".into(),
            501 => "TRANSVERSE".into(),
            600 => "LONGITUDINAL".into(),
            601 => "TANGENTIAL".into(),
            700 => "H1".into(),
            701 => "H2".into(),
            _ => return None,
        })
    });
    meta.magnitude = (13..=16).find_map(real);
    meta.distance_km = real(17);
    Ok(Record {
        source: source.to_string(),
        title: header
            .iter()
            .map(|(_, l)| l.trim_end().to_string())
            .collect(),
        dt,
        values,
        meta,
    })
}
