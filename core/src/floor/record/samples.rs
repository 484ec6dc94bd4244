//! A record given as samples in memory rather than as a file (the Python bindings'
//! `GroundMotion`): checked by the rules and limits of a record file, each error naming the
//! argument that holds the bad value (`acceleration[17]`, `dt`, `time[3]`) rather than a file
//! and line.

use super::accelerogram::Record;
use super::meta::RecordMeta;
use super::read::MAX_RECORD_BYTES;
use super::sampling::{dt_rule, DtRule, MIN_DT, MIN_SAMPLES, RELATIVE_DT_TOLERANCE};
use crate::base::invalid::InvalidParameter;

/// Most samples a record in memory may have: as many as the largest record file can hold
/// ([`MAX_RECORD_BYTES`], at two bytes, a digit and a line end, a sample).
pub const MAX_RECORD_SAMPLES: usize = (MAX_RECORD_BYTES / 2) as usize;

/// Checks a sampling interval named `name` (s) by a record file's rules: finite, > 0 and at
/// least [`MIN_DT`].
pub fn check_sample_dt(name: &str, dt: f64) -> Result<f64, InvalidParameter> {
    let rule = match dt_rule(dt) {
        Some(DtRule::NotFinite) => "must be a finite number of seconds".to_string(),
        Some(DtRule::NotPositive) => "must be > 0 s".to_string(),
        Some(DtRule::BelowMinimum) => format!(
            "is below the smallest sampling interval accepted, {} s (100 kHz; accelerographs \
             sample at 100 Hz to a few kHz)",
            crate::base::format::shortest(MIN_DT)
        ),
        None => return Ok(dt),
    };
    Err(InvalidParameter::new(name, dt, &rule))
}

/// A record of the samples `values` (named `values_name`) at the interval `dt` (named
/// `dt_name`), from `source` (for messages and tables). As in a record file: dt by
/// [`check_sample_dt`], every value finite, at least [`MIN_SAMPLES`] and at most
/// [`MAX_RECORD_SAMPLES`] of them.
pub fn record_from_samples(
    source: &str,
    dt_name: &str,
    dt: f64,
    values_name: &str,
    values: Vec<f64>,
) -> Result<Record, InvalidParameter> {
    let dt = check_sample_dt(dt_name, dt)?;
    let count = || crate::base::format::count(values.len(), "sample", "samples");
    if values.len() < MIN_SAMPLES {
        return Err(InvalidParameter::new(
            values_name,
            count(),
            "a record needs at least 2 samples (one interval of dt) to define the floor \
             acceleration between them",
        ));
    }
    if values.len() > MAX_RECORD_SAMPLES {
        return Err(InvalidParameter::new(
            values_name,
            count(),
            &format!(
                "more than the limit for a record, {MAX_RECORD_SAMPLES} samples (as many as the largest \
                 record file holds)"
            ),
        ));
    }
    if let Some((k, &v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(InvalidParameter::new(
            &format!("{values_name}[{k}]"),
            v,
            "every sample must be a finite number",
        ));
    }
    Ok(Record {
        source: source.to_string(),
        title: Vec::new(),
        dt,
        values,
        meta: RecordMeta::of_format("arrays"),
    })
}

/// The sampling interval of sample times `times` (named `name`) by the rule of a record file's
/// time column: they start at 0 and are uniformly spaced to 1e-6 relative; dt is the mean step.
pub fn dt_from_times(name: &str, times: &[f64]) -> Result<f64, InvalidParameter> {
    let (Some(&first), Some(&last)) = (times.first(), times.last()) else {
        return Err(InvalidParameter::new(
            name,
            "0 samples",
            "needs at least 2 times to give dt",
        ));
    };
    if times.len() < 2 {
        return Err(InvalidParameter::new(
            name,
            "1 sample",
            "needs at least 2 times to give dt",
        ));
    }
    if let Some((k, &t)) = times.iter().enumerate().find(|(_, t)| !t.is_finite()) {
        return Err(InvalidParameter::new(
            &format!("{name}[{k}]"),
            t,
            "every time must be a finite number",
        ));
    }
    let dt = (last - first) / (times.len() - 1) as f64;
    let dt = check_sample_dt(&format!("the mean step of {name}"), dt)?;
    if first.abs() > RELATIVE_DT_TOLERANCE * dt {
        return Err(InvalidParameter::new(
            &format!("{name}[0]"),
            first,
            "a record starts at t = 0 s",
        ));
    }
    for (k, pair) in times.windows(2).enumerate() {
        let step = pair[1] - pair[0];
        if (step - dt).abs() > RELATIVE_DT_TOLERANCE * dt {
            return Err(InvalidParameter::new(
                &format!("{name}[{}]", k + 1),
                pair[1],
                &format!(
                    "the times must be uniformly spaced (to 1e-6 relative): the step from \
                     {name}[{k}] is {} s, the mean step {} s",
                    crate::base::format::shortest(step),
                    crate::base::format::shortest(dt)
                ),
            ));
        }
    }
    Ok(dt)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_follow_the_rules_of_a_record_file() {
        let r = record_from_samples("a", "dt", 0.01, "acc", vec![0.0, 0.1, -0.2]).unwrap();
        assert_eq!((r.dt, r.values.len(), r.duration()), (0.01, 3, 0.02));
        let message = |dt: f64, values: Vec<f64>| {
            record_from_samples("a", "dt", dt, "acc", values)
                .unwrap_err()
                .to_string()
        };
        assert!(message(-1.0, vec![0.0; 3]).starts_with("dt = -1: must be > 0"));
        assert!(message(f64::NAN, vec![0.0; 3]).starts_with("dt = NaN: must be a finite"));
        assert!(message(1e-6, vec![0.0; 3]).contains("1e-5 s"));
        let mut values = vec![0.0; 20];
        values[17] = f64::NAN;
        let m = message(0.01, values);
        assert!(
            m.starts_with("acc[17] = NaN: every sample must be a finite number"),
            "{m}"
        );
        let mut values = vec![0.0; 20];
        values[17] = f64::INFINITY;
        let m = message(0.01, values);
        assert!(m.starts_with("acc[17] = inf"), "{m}");
        assert!(message(0.01, vec![0.0]).starts_with("acc = 1 sample: a record needs at least 2"));
    }

    #[test]
    fn times_give_dt_as_a_time_column_does() {
        let times: Vec<f64> = (0..5).map(|k| k as f64 * 0.02).collect();
        assert_eq!(dt_from_times("time", &times).unwrap(), 0.02);
        let late = [0.5, 0.52, 0.54];
        let m = dt_from_times("time", &late).unwrap_err().to_string();
        assert!(
            m.starts_with("time[0] = 0.5: a record starts at t = 0"),
            "{m}"
        );
        let uneven = [0.0, 0.01, 0.02, 0.035, 0.04];
        let m = dt_from_times("time", &uneven).unwrap_err().to_string();
        assert!(
            m.starts_with("time[3] = 0.035: the times must be uniformly spaced"),
            "{m}"
        );
        assert!(dt_from_times("time", &[0.0]).is_err());
        assert!(dt_from_times("time", &[0.0, f64::NAN]).is_err());
    }
}
