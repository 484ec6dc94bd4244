//! The fit of counts at intensity levels (multiple-stripe analysis): at level x_j, z_j of n_j
//! records reached the damage state. theta and beta maximise the binomial likelihood
//! sum_j z_j ln Phi(u_j) + (n_j - z_j) ln Phi(-u_j), u_j = ln(x_j / theta) / beta (Baker 2015).

use serde::Serialize;

use super::lognormal::minimus;
use super::{normal, optimize, FitError, Lognormal};

/// The counts at one level.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stripe {
    /// The intensity level.
    pub level: f64,
    /// Records run at it (those whose run succeeded).
    pub records: usize,
    /// Of them, those that reached the damage state.
    pub damaged: usize,
}

/// Fits `stripes` (see the module). Refused when the counts fix no finite maximum: no record
/// damaged, every record damaged, or the damaged stripes all above the undamaged ones with
/// nothing between (zero dispersion).
pub fn fit_stripes(stripes: &[Stripe]) -> Result<Lognormal, FitError> {
    for s in stripes {
        if !(s.level.is_finite() && s.level > 0.0) {
            return Err(FitError::NotPositive {
                what: "level".into(),
                value: s.level,
            });
        }
    }
    let stripes: Vec<Stripe> = stripes.iter().copied().filter(|s| s.records > 0).collect();
    let total: usize = stripes.iter().map(|s| s.records).sum();
    let damaged: usize = stripes.iter().map(|s| s.damaged).sum();
    if damaged == 0 {
        return Err(FitError::Degenerate(
            "no record reached the damage state at any level: the median lies above the \
             highest level (raise the levels)"
                .into(),
        ));
    }
    if damaged == total {
        return Err(FitError::Degenerate(
            "every record reached the damage state at every level: the median lies below the \
             lowest level (lower the levels)"
                .into(),
        ));
    }
    let all_or_none = stripes
        .iter()
        .all(|s| s.damaged == 0 || s.damaged == s.records);
    let highest_undamaged = stripes
        .iter()
        .filter(|s| s.damaged == 0)
        .map(|s| s.level)
        .fold(f64::NEG_INFINITY, f64::max);
    let lowest_damaged = stripes
        .iter()
        .filter(|s| s.damaged == s.records)
        .map(|s| s.level)
        .fold(f64::INFINITY, f64::min);
    if all_or_none && highest_undamaged < lowest_damaged {
        return Err(FitError::Degenerate(format!(
            "no record reached the damage state at {} and every record did at {}: the \
             counts fix no dispersion (zero dispersion); add levels between",
            highest_undamaged, lowest_damaged
        )));
    }
    let minus_log_likelihood = |p: [f64; 2]| {
        let (mu, beta) = (p[0], p[1].exp());
        let mut sum = 0.0;
        for s in &stripes {
            let u = (s.level.ln() - mu) / beta;
            if s.damaged > 0 {
                sum -= s.damaged as f64 * normal::ln_cdf(u);
            }
            if s.records > s.damaged {
                sum -= (s.records - s.damaged) as f64 * normal::ln_cdf(-u);
            }
        }
        sum
    };
    // Start at the mean ln level of the damaged runs, beta 0.5.
    let start = stripes
        .iter()
        .map(|s| s.damaged as f64 * s.level.ln())
        .sum::<f64>()
        / damaged as f64;
    let best = optimize::minimize(
        minimus(minus_log_likelihood),
        [start, 0.5f64.ln()],
        [0.2, 0.2],
    );
    Ok(Lognormal {
        theta: best[0].exp(),
        beta: best[1].exp(),
    })
}
