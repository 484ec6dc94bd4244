//! Fragility functions: the probability that a body reaches a damage state (overturning,
//! rocking beyond a share of the overturning displacement, uplift) as a lognormal function of
//! an intensity measure, fitted to the results of a sweep over a suite of records.
//!
//! - [`measure`]: the intensity measures and how each scales with a record's factor;
//! - [`normal`]: the standard normal distribution function;
//! - [`lognormal`]: the fit of capacities (incremental dynamic analysis), with records that did
//!   not overturn in the searched range as censored capacities;
//! - [`stripes`]: the fit of counts at intensity levels (multiple-stripe analysis) by maximum
//!   likelihood of the binomial likelihood (Baker 2015);
//! - [`optimize`]: the Nelder-Mead search both maximum likelihood fits use;
//! - [`bootstrap`]: resampling over records, with its own seeded generator;
//! - [`study`]: the study over a suite the command line and the Python bindings share: the
//!   suite's axis, the records' measures and names, their capacities and the summary.
//!
//! A fit is P(DS | IM = x) = Phi(ln(x / theta) / beta): theta the median, beta the dispersion.

pub mod bootstrap;
pub mod lognormal;
pub mod measure;
pub mod normal;
pub mod optimize;
pub mod stripes;
pub mod study;
mod summary;

use serde::Serialize;

pub use lognormal::{fit_capacities, Capacity};
pub use measure::Measure;
pub use stripes::{fit_stripes, Stripe};
pub use summary::{Interval90, RecordResult, StateFit, Summary, CAPACITY_RULE, PERCENTILES};

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
