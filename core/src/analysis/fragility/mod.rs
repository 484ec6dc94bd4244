//! Fragility functions: the probability that a body reaches a damage state (overturning,
//! rocking beyond a share of the overturning displacement, uplift) as a lognormal function of
//! an intensity measure, fitted to the results of a sweep over a suite of records.
//!
//! - `fit`: what a fit gives ([`Lognormal`]) and why one cannot be made ([`FitError`]);
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
mod fit;
pub mod lognormal;
pub mod measure;
pub mod normal;
pub mod optimize;
pub mod stripes;
pub mod study;
mod summary;

pub use fit::{FitError, Lognormal};
pub use lognormal::{fit_capacities, Capacity};
pub use measure::Measure;
pub use stripes::{fit_stripes, Stripe};
pub use summary::{Interval90, RecordResult, StateFit, Summary, CAPACITY_RULE, PERCENTILES};
