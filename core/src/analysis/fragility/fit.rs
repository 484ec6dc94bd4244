//! What a fit gives, a lognormal fragility function ([`Lognormal`]), and why a fit cannot be
//! made ([`FitError`]).

use serde::Serialize;

use super::normal;

/// A lognormal fragility function.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Lognormal {
    /// The median theta, in the intensity measure's units.
    pub theta: f64,
    /// The dispersion beta, the standard deviation of ln IM.
    pub beta: f64,
}

impl Lognormal {
    /// P(DS | IM = x).
    pub fn probability(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        normal::cdf((x / self.theta).ln() / self.beta)
    }
}

/// Why a fit cannot be made: each names the rule the data break.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Too few records to fit two parameters.
    #[error("{records} records: a fit needs at least 2")]
    TooFewRecords {
        /// The number given.
        records: usize,
    },
    /// A capacity or level that is not a positive finite number.
    #[error("{what} = {value}: must be a positive finite number")]
    NotPositive {
        /// What the value is.
        what: String,
        /// The value.
        value: f64,
    },
    /// The data fix no finite dispersion.
    #[error("{0}")]
    Degenerate(String),
}
