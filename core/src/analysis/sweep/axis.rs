//! Axes of a sweep: a model-file key and the values it takes, from `KEY=SPEC`.
//!
//! SPEC is one of
//! - `LO:HI:STEP`: LO, LO + STEP, ... up to HI (HI included when it is a whole number of steps
//!   from LO, to 1e-9 of a step);
//! - `lin:LO:HI:N` / `log:LO:HI:N`: N values from LO to HI, both included, evenly spaced or
//!   evenly spaced in log (LO, HI > 0);
//! - a comma list, `0.5,1,2` or `bdf,tsit45`; one value is a list of one;
//! - for `excitation.path`, a file pattern (`records/*.AT2`), expanded and sorted; several
//!   patterns may be listed with commas.
//!
//! Every value is computed from its index (LO + i STEP), never by accumulation, so that a sweep
//! has the same values on every machine.
//!
//! Numbers must be finite and at most [`MAX_MAGNITUDE`] in size, so that every value, cell edge
//! and figure coordinate made from them is finite. The number of values a range gives is
//! checked against the room the other axes leave under [`MAX_POINTS`] before any value is made.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::model::{check_key, value_text, Setting};

/// Most points a sweep may have (a week of a 2-core machine at 6 ms a point).
pub const MAX_POINTS: usize = 100_000_000;
/// Most values one axis (or a minimum search's scan) may take: their text is held in memory.
pub const MAX_AXIS_VALUES: usize = 1_000_000;
/// Largest magnitude of a number in an axis or a search interval: far beyond any quantity of
/// the model, and small enough that the cells of a map drawn around such values stay finite.
pub const MAX_MAGNITUDE: f64 = 1e300;

/// One axis: a model-file key and its values, in order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// The model-file key, e.g. `excitation.amplitude`.
    pub key: String,
    /// The values, as the CSV shows them (numbers in their shortest exact form).
    pub values: Vec<String>,
    /// The values as TOML, for setting them. Not serialised: rebuilt from `values`.
    #[serde(skip)]
    settings: Vec<toml::Value>,
}

impl Axis {
    /// Parses `KEY=SPEC`; file patterns of `excitation.path` are relative to `base_dir`.
    pub fn parse(text: &str, base_dir: &Path) -> Result<Axis> {
        Axis::parse_beside(text, base_dir, 1)
    }

    /// Parses `KEY=SPEC` as an axis beside others that have `others` points between them: the
    /// axis may have at most [`MAX_POINTS`] / `others` values, checked before they are made.
    pub fn parse_beside(text: &str, base_dir: &Path, others: usize) -> Result<Axis> {
        let (key, spec) = split(text, "vary")?;
        let room = Room {
            values: MAX_AXIS_VALUES.min(MAX_POINTS / others.max(1)),
            others,
        };
        let values = expand(key, spec, base_dir, room)
            .map_err(|rule| Error::invalid(&format!("vary {key}"), spec, &rule))?;
        Ok(Axis::new(key, values))
    }

    /// An axis over the given values (each read as TOML, else as text).
    pub fn new(key: &str, values: Vec<String>) -> Axis {
        let settings = values.iter().map(|v| toml_value(v)).collect();
        Axis {
            key: key.to_string(),
            values,
            settings,
        }
    }

    /// The setting of the `index`-th value.
    pub fn setting(&self, index: usize) -> Setting {
        Setting {
            key: self.key.clone(),
            value: self.settings[index].clone(),
        }
    }

    /// The `index`-th value as a number, if it is one.
    pub fn number(&self, index: usize) -> Option<f64> {
        match &self.settings[index] {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        }
    }

    /// True when every value is a number.
    pub fn is_numeric(&self) -> bool {
        (0..self.values.len()).all(|i| self.number(i).is_some())
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True for an axis without values (never made by [`Axis::parse`]).
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Rebuilds the TOML values after deserialisation.
    pub(crate) fn restored(self) -> Axis {
        Axis::new(&self.key, self.values)
    }
}

/// The interval of `find_min = "KEY=LO:HI"` (`--find-min`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

/// Parses `KEY=LO:HI` of `find_min` (`--find-min`).
pub fn parse_interval(text: &str) -> Result<(String, Interval)> {
    let (key, spec) = split(text, "find_min")?;
    let flag = format!("find_min {key}");
    let parts: Vec<&str> = spec.split(':').collect();
    let [lo, hi] = parts.as_slice() else {
        return Err(Error::invalid(&flag, spec, "must be LO:HI, e.g. 0.5:15"));
    };
    let lo = number(lo).map_err(|rule| Error::invalid(&flag, spec, &rule))?;
    let hi = number(hi).map_err(|rule| Error::invalid(&flag, spec, &rule))?;
    let interval = Interval { lo, hi };
    check_interval(key, &interval)?;
    Ok((key.to_string(), interval))
}

/// The rules every axis meets, however it was made: a known key, at least one value and at
/// most [`MAX_AXIS_VALUES`], numbers finite and at most [`MAX_MAGNITUDE`] in size, no value
/// twice.
pub fn check_axis(axis: &Axis) -> Result<()> {
    let shown = || {
        let mut text: Vec<&str> = axis.values.iter().take(5).map(String::as_str).collect();
        if axis.values.len() > 5 {
            text.push("...");
        }
        text.join(",")
    };
    let refuse = |rule: &str| Error::invalid(&format!("vary {}", axis.key), shown(), rule);
    check_key(&axis.key).map_err(|rule| refuse(&rule))?;
    if axis.values.is_empty() {
        return Err(refuse("an axis needs at least one value"));
    }
    if axis.values.len() > MAX_AXIS_VALUES {
        return Err(refuse(&format!(
            "has more than the {MAX_AXIS_VALUES} values an axis may have"
        )));
    }
    for value in &axis.values {
        if let Ok(x) = value.trim().parse::<f64>() {
            finite(x, value).map_err(|rule| refuse(&rule))?;
        }
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(duplicate) = axis.values.iter().find(|v| !seen.insert(v.as_str())) {
        return Err(refuse(&format!("the value {duplicate} appears twice")));
    }
    Ok(())
}

/// The rules of a minimum search's interval: finite ends, at most [`MAX_MAGNITUDE`] in size,
/// LO below HI.
pub fn check_interval(key: &str, interval: &Interval) -> Result<()> {
    let spec = format!(
        "{}:{}",
        crate::base::format::shortest(interval.lo),
        crate::base::format::shortest(interval.hi)
    );
    let flag = format!("find_min {key}");
    for x in [interval.lo, interval.hi] {
        finite(x, &crate::base::format::shortest(x))
            .map_err(|rule| Error::invalid(&flag, &spec, &rule))?;
    }
    if interval.lo >= interval.hi {
        return Err(Error::invalid(&flag, &spec, "LO must be below HI"));
    }
    Ok(())
}

fn split<'a>(text: &'a str, flag: &str) -> Result<(&'a str, &'a str)> {
    let Some((key, spec)) = text.split_once('=') else {
        return Err(Error::invalid(
            flag,
            text,
            "must be KEY=VALUES, e.g. excitation.amplitude=0.5:10:0.5",
        ));
    };
    let key = key.trim();
    check_key(key).map_err(|rule| Error::invalid(flag, text, &rule))?;
    Ok((key, spec.trim()))
}

/// A value as TOML: a number, a boolean, or else text.
fn toml_value(text: &str) -> toml::Value {
    match toml::from_str::<toml::Table>(&format!("value = {text}"))
        .ok()
        .and_then(|mut t| t.remove("value"))
    {
        Some(v @ (toml::Value::Float(_) | toml::Value::Integer(_) | toml::Value::Boolean(_))) => {
            match v {
                // Every number is a float, so that `1` and `1.0` are the same point.
                toml::Value::Integer(i) => toml::Value::Float(i as f64),
                other => other,
            }
        }
        Some(toml::Value::String(s)) => toml::Value::String(s),
        _ => toml::Value::String(text.to_string()),
    }
}

fn number(text: &str) -> std::result::Result<f64, String> {
    let x: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("\"{}\" is not a number", text.trim()))?;
    finite(x, text.trim())
}

/// `x` (written `text`) if it is finite and at most [`MAX_MAGNITUDE`] in size.
fn finite(x: f64, text: &str) -> std::result::Result<f64, String> {
    if !x.is_finite() {
        return Err(format!("{text} is not a finite number"));
    }
    if x.abs() > MAX_MAGNITUDE {
        return Err(format!(
            "{text} is beyond the largest magnitude an axis takes, {MAX_MAGNITUDE:e}"
        ));
    }
    Ok(x)
}

/// A computed axis value rounded to 15 significant digits, so that the rounding of its
/// arithmetic (0.1 + 2 x 0.1 = 0.30000000000000004) does not show in sweep.csv. The change is
/// below 1e-15 of the value.
fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.14e}").parse().unwrap_or(x)
}

/// How many values an axis may have: at most [`MAX_AXIS_VALUES`], and no more than leave the
/// sweep within [`MAX_POINTS`] beside the other axes' `others` points.
#[derive(Clone, Copy)]
struct Room {
    values: usize,
    others: usize,
}

impl Room {
    /// `n` values, if there is room for them.
    fn fits(self, n: usize) -> std::result::Result<usize, String> {
        if n > MAX_AXIS_VALUES {
            return Err(format!(
                "gives {n} values; an axis may have at most {MAX_AXIS_VALUES}"
            ));
        }
        if n > self.values {
            return Err(format!(
                "gives {n} values beside the other axes' {} points; a sweep may have at most {MAX_POINTS} points",
                self.others
            ));
        }
        Ok(n)
    }
}

fn count(text: &str, room: Room) -> std::result::Result<usize, String> {
    let n: usize = text
        .trim()
        .parse()
        .map_err(|_| format!("the count \"{}\" is not a whole number", text.trim()))?;
    if n == 0 {
        return Err("the count must be at least 1".to_string());
    }
    room.fits(n)
}

fn shortest(values: impl Iterator<Item = f64>) -> Vec<String> {
    values.map(crate::base::format::shortest).collect()
}

/// The values of a SPEC, as text.
fn expand(
    key: &str,
    spec: &str,
    base_dir: &Path,
    room: Room,
) -> std::result::Result<Vec<String>, String> {
    if spec.is_empty() {
        return Err("no values given".to_string());
    }
    let parts: Vec<&str> = spec.split(':').collect();
    let values = match parts.as_slice() {
        [kind @ ("lin" | "log"), lo, hi, n] => {
            let (lo, hi, n) = (number(lo)?, number(hi)?, count(n, room)?);
            if *kind == "log" && !(lo > 0.0 && hi > 0.0) {
                return Err("a log axis needs LO > 0 and HI > 0".to_string());
            }
            let at = |i: usize| -> f64 {
                if n == 1 {
                    return lo;
                }
                let f = i as f64 / (n - 1) as f64;
                // The ends exactly as given.
                match i {
                    0 => lo,
                    _ if i == n - 1 => hi,
                    _ if *kind == "log" => tidy((lo.ln() + f * (hi.ln() - lo.ln())).exp()),
                    // Weighted ends: 0.2 and 1.2 in 11 steps give 0.3, not 0.30000000000000004.
                    _ => tidy((lo * (n - 1 - i) as f64 + hi * i as f64) / (n - 1) as f64),
                }
            };
            shortest((0..n).map(at))
        }
        [lo, hi, step] if lo.trim().parse::<f64>().is_ok() => {
            let (lo, hi, step) = (number(lo)?, number(hi)?, number(step)?);
            if step <= 0.0 {
                return Err("STEP must be positive".to_string());
            }
            if hi < lo {
                return Err("HI must not be below LO".to_string());
            }
            let steps = ((hi - lo) / step + 1e-9).floor();
            if steps + 1.0 > MAX_AXIS_VALUES as f64 {
                return Err(format!(
                    "gives more than the {MAX_AXIS_VALUES} values an axis may have"
                ));
            }
            room.fits(steps as usize + 1)?;
            shortest((0..=steps as usize).map(|i| {
                let x = tidy(lo + i as f64 * step);
                // HI itself, not HI plus rounding, when it is a whole number of steps away.
                if (x - hi).abs() <= 1e-9 * step {
                    hi
                } else {
                    x
                }
            }))
        }
        _ if key == "excitation.path" => {
            let files = paths(spec, base_dir)?;
            room.fits(files.len())?;
            files
        }
        [lo, hi] if lo.trim().parse::<f64>().is_ok() && hi.trim().parse::<f64>().is_ok() => {
            return Err(format!(
                "LO:HI needs a STEP: write LO:HI:STEP (e.g. {lo}:{hi}:0.1) or lin:LO:HI:N"
            ))
        }
        _ if parts.len() > 1 => {
            return Err("must be LO:HI:STEP, lin:LO:HI:N, log:LO:HI:N or a comma list".to_string())
        }
        _ => {
            let items: Vec<String> = spec.split(',').map(|v| v.trim().to_string()).collect();
            if items.iter().any(|v| v.is_empty()) {
                return Err("an empty value in the list".to_string());
            }
            room.fits(items.len())?;
            // Numbers are written in their shortest form, so that `1.50` and `1.5` agree.
            items
                .into_iter()
                .map(|v| match (toml_value(&v), v.parse::<f64>()) {
                    (toml::Value::Float(x), _) => Ok(crate::base::format::shortest(finite(x, &v)?)),
                    // Beyond TOML's range (1e309) but a number still.
                    (_, Ok(x)) => finite(x, &v).map(crate::base::format::shortest),
                    (other, Err(_)) => Ok(value_text(&other)),
                })
                .collect::<std::result::Result<_, String>>()?
        }
    };
    let mut seen = std::collections::HashSet::new();
    if let Some(duplicate) = values.iter().find(|v| !seen.insert(v.as_str())) {
        return Err(format!("the value {duplicate} appears twice"));
    }
    Ok(values)
}

/// Record files: comma-separated paths or patterns, each pattern expanded and sorted.
fn paths(spec: &str, base_dir: &Path) -> std::result::Result<Vec<String>, String> {
    let mut files = Vec::new();
    for item in spec.split(',').map(str::trim) {
        if !item.contains(['*', '?', '[']) {
            files.push(item.to_string());
            continue;
        }
        let pattern = base_dir.join(item);
        let pattern = pattern
            .to_str()
            .ok_or_else(|| format!("the pattern {item} is not valid UTF-8"))?;
        let mut matched: Vec<String> = glob::glob(pattern)
            .map_err(|e| format!("the pattern {item} is malformed: {e}"))?
            .filter_map(|entry| entry.ok())
            .filter(|path| path.is_file())
            .map(|path| {
                path.strip_prefix(base_dir)
                    .unwrap_or(&path)
                    .to_string_lossy()
                    .into_owned()
            })
            .collect();
        if matched.is_empty() {
            return Err(format!("the pattern {item} matches no file"));
        }
        matched.sort();
        files.extend(matched);
    }
    // Values are relative to the current directory: a sweep file's are prefixed with its
    // directory.
    if !(base_dir.as_os_str().is_empty() || base_dir == Path::new(".")) {
        for file in &mut files {
            *file = base_dir.join(&*file).to_string_lossy().into_owned();
        }
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(spec: &str) -> Vec<String> {
        Axis::parse(&format!("excitation.amplitude={spec}"), Path::new("."))
            .unwrap()
            .values
    }

    #[test]
    fn ranges_include_both_ends_and_do_not_accumulate_rounding() {
        assert_eq!(
            values("0.5:1:0.1"),
            ["0.5", "0.6", "0.7", "0.8", "0.9", "1"]
        );
        // 0.1 * 3 is 0.30000000000000004: values are rounded to 15 significant digits.
        assert_eq!(values("0:0.3:0.1"), ["0", "0.1", "0.2", "0.3"]);
        assert_eq!(values("lin:0.2:1.2:11")[1], "0.3");
        assert_eq!(values("0.1:0.7:0.1")[2], "0.3");
        assert_eq!(values("1:2:0.4"), ["1", "1.4", "1.8"]);
        assert_eq!(values("lin:0:1:5"), ["0", "0.25", "0.5", "0.75", "1"]);
        let log = values("log:0.2:3:40");
        assert_eq!(log.len(), 40);
        assert_eq!((log[0].as_str(), log[39].as_str()), ("0.2", "3"));
        let ratio: f64 = log[1].parse::<f64>().unwrap() / 0.2;
        assert!((ratio - (15f64).powf(1.0 / 39.0)).abs() < 1e-12);
        assert_eq!(values("1.50, 2,3e0"), ["1.5", "2", "3"]);
    }

    #[test]
    fn an_axis_made_in_code_meets_the_rules_of_a_parsed_one() {
        let check = |values: &[&str]| {
            check_axis(&Axis::new(
                "excitation.amplitude",
                values.iter().map(|v| v.to_string()).collect(),
            ))
        };
        assert!(check(&["1", "2"]).is_ok());
        for bad in [&[][..], &["NaN"], &["1", "inf"], &["1e301"], &["1", "1"]] {
            let e = check(bad).expect_err("refused").to_string();
            assert!(
                e.starts_with("vary excitation.amplitude = "),
                "{bad:?}: {e}"
            );
        }
        assert!(check_axis(&Axis::new("amplitude", vec!["1".into()])).is_err());
    }

    #[test]
    fn an_interval_made_in_code_meets_the_rules_of_a_parsed_one() {
        let check = |lo, hi| check_interval("excitation.amplitude", &Interval { lo, hi });
        assert!(check(0.5, 15.0).is_ok());
        for (lo, hi) in [
            (2.0, 1.0),
            (1.0, 1.0),
            (f64::NAN, 1.0),
            (0.0, f64::INFINITY),
        ] {
            let e = check(lo, hi).expect_err("refused").to_string();
            assert!(e.starts_with("find_min excitation.amplitude = "), "{e}");
        }
    }

    #[test]
    fn bad_specs_are_refused_with_the_flag_and_key() {
        for bad in [
            "1:0:0.1",
            "0:1:0",
            "0:1:-1",
            "log:0:1:3",
            "lin:0:1:0",
            "lin:0:1:x",
            "a:b:c",
            "1,,2",
            "1,1",
            "",
            "0:1e12:1e-9",
            "nan:1:0.1",
        ] {
            let e = Axis::parse(&format!("excitation.amplitude={bad}"), Path::new("."))
                .expect_err(bad)
                .to_string();
            assert!(e.starts_with("vary excitation.amplitude"), "{bad}: {e}");
        }
        assert!(Axis::parse("amplitude=1", Path::new(".")).is_err());
        assert!(Axis::parse("excitation.amplitude", Path::new(".")).is_err());
    }

    #[test]
    fn infinite_and_overflowing_numbers_are_refused_at_parse() {
        for bad in [
            "inf,1",
            "1,-inf",
            "nan,1",
            "1e309,1",
            "-1e308,1e308",
            "1.5e308",
            "lin:1e308:1.7e308:3",
            "0:1e301:1e300",
            "log:1e-1:1e301:3",
        ] {
            let e = Axis::parse(&format!("excitation.amplitude={bad}"), Path::new("."))
                .expect_err(bad)
                .to_string();
            assert!(
                e.contains("not a finite number") || e.contains("largest magnitude"),
                "{bad}: {e}"
            );
        }
        // The largest magnitude itself is a value.
        assert_eq!(values("1e300,-1e300"), ["1e300", "-1e300"]);
        for bad in [
            "x=0:inf",
            "excitation.amplitude=-inf:1",
            "excitation.amplitude=0:1e301",
        ] {
            assert!(parse_interval(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_range_without_a_step_says_so() {
        let e = Axis::parse("excitation.period=0.2:3", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("needs a STEP"), "{e}");
    }

    #[test]
    fn the_point_cap_is_checked_before_an_axis_is_made() {
        // Beside an axis of 1000 values, one of 200000 would make 2e8 points.
        for spec in ["lin:0:1:200000", "0:1:0.000005", "log:1:2:1000000"] {
            let e = Axis::parse_beside(
                &format!("excitation.amplitude={spec}"),
                Path::new("."),
                1000,
            )
            .unwrap_err()
            .to_string();
            assert!(e.contains(&MAX_POINTS.to_string()), "{spec}: {e}");
        }
        let list = "1,2,3";
        let e = Axis::parse_beside(
            &format!("excitation.amplitude={list}"),
            Path::new("."),
            MAX_POINTS / 2,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("a sweep may have at most"), "{e}");
        assert_eq!(
            Axis::parse_beside("excitation.amplitude=lin:0:1:100000", Path::new("."), 1000)
                .unwrap()
                .len(),
            100_000
        );
    }

    #[test]
    fn text_values_and_intervals() {
        let axis = Axis::parse("solver.method=bdf,tsit45", Path::new(".")).unwrap();
        assert_eq!(axis.values, ["bdf", "tsit45"]);
        assert!(!axis.is_numeric());
        let (key, interval) = parse_interval("excitation.amplitude=0.5:15").unwrap();
        assert_eq!(key, "excitation.amplitude");
        assert_eq!(interval, Interval { lo: 0.5, hi: 15.0 });
        for bad in [
            "excitation.amplitude=2:1",
            "excitation.amplitude=1",
            "x=1:2",
        ] {
            assert!(parse_interval(bad).is_err(), "{bad}");
        }
    }
}
