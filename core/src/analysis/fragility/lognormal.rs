//! The fit of capacities: the intensity at which each record first takes the body to the
//! damage state (incremental dynamic analysis).
//!
//! Without censored records the fit is by the moments of ln c: ln theta the mean of ln c_i and
//! beta the standard deviation with the divisor n, which is the maximum likelihood estimate of
//! a lognormal. The divisor n - 1 (the unbiased variance) gives a beta larger by
//! sqrt(n / (n - 1)); it is reported beside, as `beta_unbiased`.
//!
//! A record that did not reach the damage state within the searched range has a capacity above
//! the range's top, u: a censored capacity. With any such record the fit maximises the
//! likelihood with censoring, sum over the observed ln(phi(z_i) / beta) plus sum over the
//! censored ln(1 - Phi(z_u)), z = (ln x - ln theta) / beta. Without censored records that
//! maximum is the moments' fit above.

use serde::Serialize;

use super::{normal, optimize, FitError, Lognormal};

/// The capacity of one record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", content = "value", rename_all = "lowercase")]
pub enum Capacity {
    /// The smallest intensity that reached the damage state.
    Observed(f64),
    /// No intensity up to this one reached it: the capacity lies above.
    Censored(f64),
}

impl Capacity {
    /// The intensity the capacity is given by.
    pub fn value(self) -> f64 {
        match self {
            Capacity::Observed(x) | Capacity::Censored(x) => x,
        }
    }
}

/// A fit of capacities.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CapacityFit {
    /// theta and beta.
    pub fit: Lognormal,
    /// beta with the divisor n - 1; None with censored records (the likelihood has no such
    /// form).
    pub beta_unbiased: Option<f64>,
    /// `moments` or `censored-mle`.
    pub method: &'static str,
    /// Records with an observed capacity.
    pub observed: usize,
    /// Records with a censored one.
    pub censored: usize,
}

/// Fits `capacities` (see the module).
pub fn fit_capacities(capacities: &[Capacity]) -> Result<CapacityFit, FitError> {
    if capacities.len() < 2 {
        return Err(FitError::TooFewRecords {
            records: capacities.len(),
        });
    }
    for c in capacities {
        let x = c.value();
        if !(x.is_finite() && x > 0.0) {
            return Err(FitError::NotPositive {
                what: "capacity".into(),
                value: x,
            });
        }
    }
    let observed: Vec<f64> = capacities
        .iter()
        .filter_map(|c| match c {
            Capacity::Observed(x) => Some(x.ln()),
            Capacity::Censored(_) => None,
        })
        .collect();
    let censored: Vec<f64> = capacities
        .iter()
        .filter_map(|c| match c {
            Capacity::Censored(x) => Some(x.ln()),
            Capacity::Observed(_) => None,
        })
        .collect();
    let n = observed.len();
    if n < 2 {
        return Err(FitError::Degenerate(format!(
            "{n} of {} records reached the damage state within the searched range: a fit \
             needs at least 2 (widen the range)",
            capacities.len()
        )));
    }
    let mean = observed.iter().sum::<f64>() / n as f64;
    let squares: f64 = observed.iter().map(|y| (y - mean).powi(2)).sum();
    if squares == 0.0 || observed.iter().all(|&y| y == observed[0]) {
        return Err(FitError::Degenerate(format!(
            "every observed capacity is {}: zero dispersion, no lognormal fits",
            observed[0].exp()
        )));
    }
    let beta = (squares / n as f64).sqrt();
    if censored.is_empty() {
        return Ok(CapacityFit {
            fit: Lognormal {
                theta: mean.exp(),
                beta,
            },
            beta_unbiased: Some((squares / (n - 1) as f64).sqrt()),
            method: "moments",
            observed: n,
            censored: 0,
        });
    }
    let minus_log_likelihood = |p: [f64; 2]| {
        let (mu, beta) = (p[0], p[1].exp());
        let mut sum = 0.0;
        for &y in &observed {
            let z = (y - mu) / beta;
            sum += p[1] + 0.5 * z * z;
        }
        for &u in &censored {
            sum -= normal::ln_cdf(-(u - mu) / beta);
        }
        sum
    };
    let best = optimize::minimize(minimus(minus_log_likelihood), [mean, beta.ln()], [0.1, 0.1]);
    Ok(CapacityFit {
        fit: Lognormal {
            theta: best[0].exp(),
            beta: best[1].exp(),
        },
        beta_unbiased: None,
        method: "censored-mle",
        observed: n,
        censored: censored.len(),
    })
}

/// `f` with NaN (a parameter far out of range) taken as the worst value.
pub(super) fn minimus(f: impl Fn([f64; 2]) -> f64) -> impl Fn([f64; 2]) -> f64 {
    move |p| {
        let v = f(p);
        if v.is_nan() {
            f64::INFINITY
        } else {
            v
        }
    }
}
