//! The rules of a record's sampling: its interval and its number of samples.

use super::error::{Location, RecordError};

/// Tolerance, relative to dt, for a uniform time column and for agreeing dt values.
pub(super) const RELATIVE_DT_TOLERANCE: f64 = 1e-6;

/// Smallest sampling interval accepted, s (100 kHz). Strong-motion accelerographs sample at
/// 100 Hz to a few kHz (dt from 0.01 s down to a few 1e-4 s); a smaller dt is a mistake in the
/// file (or a unit other than seconds), and every sample is a stop time of the adaptive solver.
pub const MIN_DT: f64 = 1e-5;

/// Which rule of a sampling interval a dt breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum DtRule {
    NotFinite,
    NotPositive,
    BelowMinimum,
}

/// The rule the sampling interval `dt` breaks, if any: it must be finite, > 0 and at least
/// [`MIN_DT`], an inclusive limit (a mean step of a time column in steps of 1e-5 s, which rounds
/// to 9.999999999999999e-6, passes). The one rule of a dt read from a file, given with it or
/// given with samples in memory.
pub(super) fn dt_rule(dt: f64) -> Option<DtRule> {
    if !dt.is_finite() {
        Some(DtRule::NotFinite)
    } else if dt <= 0.0 {
        Some(DtRule::NotPositive)
    } else if !crate::base::limits::at_least(dt, MIN_DT) {
        Some(DtRule::BelowMinimum)
    } else {
        None
    }
}

/// Checks that a dt is finite, > 0 and at least [`MIN_DT`] ([`dt_rule`]).
pub(super) fn check_dt(dt: f64, at: Location) -> Result<f64, RecordError> {
    match dt_rule(dt) {
        Some(DtRule::NotFinite) => Err(RecordError::NonFiniteDt { at, found: dt }),
        Some(DtRule::NotPositive) => Err(RecordError::InvalidDt { at, found: dt }),
        Some(DtRule::BelowMinimum) => Err(RecordError::DtTooSmall {
            at,
            found: dt,
            limit: MIN_DT,
        }),
        None => Ok(dt),
    }
}

/// Whether two dt values agree to [`RELATIVE_DT_TOLERANCE`].
pub(super) fn dt_agrees(a: f64, b: f64) -> bool {
    (a - b).abs() <= RELATIVE_DT_TOLERANCE * a.abs().max(b.abs())
}

/// Fewest values a record may have: a(t) is linear between samples, so one sample defines no
/// motion (its duration would be 0).
pub const MIN_SAMPLES: usize = 2;

/// Refuses a record of fewer than [`MIN_SAMPLES`] values.
pub(super) fn check_samples(values: &[f64], file: &str) -> Result<(), RecordError> {
    if values.len() < MIN_SAMPLES {
        return Err(RecordError::TooFewSamples {
            file: file.to_string(),
            found: values.len(),
        });
    }
    Ok(())
}
