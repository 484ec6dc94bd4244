//! The summary of a fragility analysis (fragility.json): how it was made, the fit of each damage
//! state with its bootstrap intervals, and each record's capacity.

use serde::Serialize;

use super::{Capacity, Measure};

/// The lower and upper percentiles of the bootstrap intervals.
pub const PERCENTILES: [f64; 2] = [5.0, 95.0];
/// The rule the capacity of a record with several overturning bands follows.
pub const CAPACITY_RULE: &str = "the first (smallest) overturning intensity: the upper end of \
                                 the bisected bracket of the first transition from standing to \
                                 overturned";

/// One record's result.
#[derive(Debug, Clone, Serialize)]
pub struct RecordResult {
    /// The record file, as the sweep names it.
    pub path: String,
    /// Its name: event, station and component where the file gives them, else the file's name.
    pub label: String,
    /// Its intensity measure at scale 1.
    pub im_unscaled: f64,
    /// The smallest overturning scale found, or none (censored).
    pub min_overturning_scale: Option<f64>,
    /// The capacity, observed or censored, in the measure's units.
    pub capacity: Capacity,
    /// The overturning bands of scanned scales, `lo-hi;...`.
    pub overturning_bands: String,
    /// Their number; more than one: overturning is not monotonic in the scale for this record.
    pub n_bands: usize,
}

/// An interval of the bootstrap.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Interval90 {
    /// The lower percentile's value.
    pub lo: f64,
    /// The upper percentile's value.
    pub hi: f64,
}

/// The fit of one damage state.
#[derive(Debug, Clone, Serialize)]
pub struct StateFit {
    /// The damage state.
    pub state: String,
    /// The median, in the measure's units.
    pub theta: f64,
    /// The dispersion (divisor n: the maximum likelihood form).
    pub beta: f64,
    /// The dispersion with the divisor n - 1, where no record is censored.
    pub beta_unbiased: Option<f64>,
    /// `moments` or `censored-mle`.
    pub method: String,
    /// The 15.87 % and 84.13 % fractiles of the capacity, theta exp(-beta) and theta exp(beta).
    pub fractile_16: f64,
    /// See `fractile_16`.
    pub fractile_84: f64,
    /// Bootstrap interval of theta.
    pub theta_interval: Option<Interval90>,
    /// Bootstrap interval of beta.
    pub beta_interval: Option<Interval90>,
    /// Records with an observed capacity.
    pub observed: usize,
    /// Records censored above the range.
    pub censored: usize,
}

/// fragility.json.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Version of flexrock.
    pub flexrock_version: String,
    /// Its commit.
    pub flexrock_commit: String,
    /// The model file as named.
    pub model_file: String,
    /// `ida`.
    pub analysis: String,
    /// The intensity measure.
    pub im: Measure,
    /// Its unit.
    pub im_unit: String,
    /// How it scales: the power of the record's factor.
    pub im_scale_power: i32,
    /// The period of Sa, s (for `sa` only).
    pub sa_period_s: Option<f64>,
    /// The range of excitation.scale searched.
    pub scale_range: [f64; 2],
    /// The rule of a record's capacity.
    pub capacity_rule: String,
    /// How a censored record enters the fit.
    pub censoring: String,
    /// The fits, one per damage state.
    pub fits: Vec<StateFit>,
    /// Bootstrap resamples asked for.
    pub bootstrap: usize,
    /// Resamples that gave no fit (left out of the intervals).
    pub bootstrap_failed: usize,
    /// The bootstrap's seed (SplitMix64).
    pub seed: u64,
    /// The percentiles of the intervals.
    pub percentiles: [f64; 2],
    /// The records, in the sweep's order.
    pub records: Vec<RecordResult>,
    /// What the reader must know.
    pub warnings: Vec<String>,
}
