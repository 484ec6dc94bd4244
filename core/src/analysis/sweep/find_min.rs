//! The smallest value of a key (an amplitude, a record's scale) that overturns the body.
//!
//! Overturning is not monotonic in the amplitude (book/src/model.md §7c; Zhang and Makris 2001):
//! above the smallest overturning amplitude of a short pulse lies a band that leaves the body
//! standing. A bisection alone could land on any transition, so the search first scans the interval
//! on an even grid of `scan` values, which shows every band at least one grid step wide, then
//! bisects the first transition from standing to overturned to the tolerance `tol`. Bands narrower
//! than a grid step can be missed; the scan step is (HI - LO)/(scan - 1).

use serde::{Deserialize, Serialize};

use super::cell::Cell;
use crate::base::format::shortest;
use crate::bodies::rigid::{RigidBlock, RigidForm, RigidOverturning};

/// Default number of scanned values.
pub const DEFAULT_SCAN: usize = 100;
/// Default tolerance of the bisection, as a share of HI - LO.
pub const DEFAULT_TOL_SHARE: f64 = 1e-4;
/// Most bisection steps (a tolerance far below rounding ends there).
const MAX_BISECTIONS: usize = 200;

/// What to search.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FindMin {
    /// The model-file key, e.g. `excitation.amplitude`.
    pub key: String,
    /// Lower end of the interval searched.
    pub lo: f64,
    /// Upper end of the interval searched.
    pub hi: f64,
    /// Values scanned from `lo` to `hi`, both included.
    pub scan: usize,
    /// Width of the final bracket, in the key's units.
    pub tol: f64,
    /// The equation of Housner's block searched beside the body; not written for the default
    /// (small-angle), so that the stored plan of a default sweep is unchanged.
    #[serde(default, skip_serializing_if = "RigidForm::is_small_angle")]
    pub rigid_form: RigidForm,
    /// When Housner's block counts as overturned; not written for the default.
    #[serde(default, skip_serializing_if = "RigidOverturning::is_reaches_limit")]
    pub rigid_overturning: RigidOverturning,
    /// Housner's block's own coefficient of restitution, or None for Housner's; not written
    /// for the default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rigid_restitution: Option<f64>,
}

/// How Housner's block of a minimum search is made: its equation, its rule of overturning and
/// its coefficient of restitution. Each one other than the default adds a column to sweep.csv
/// (see [`super::point_result::RigidMinima`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HousnerOptions {
    /// The equation.
    pub form: RigidForm,
    /// When it counts as overturned.
    pub overturning: RigidOverturning,
    /// A coefficient of restitution of its own, or None for Housner's.
    pub restitution: Option<f64>,
}

impl HousnerOptions {
    /// `block` (a Housner block of the point's geometry) made as these options say.
    pub fn apply(&self, block: RigidBlock) -> Result<RigidBlock, crate::integrate::SolverError> {
        let block = block
            .with_form(self.form)
            .with_overturning(self.overturning);
        match self.restitution {
            Some(e) => block.with_restitution(e),
            None => Ok(block),
        }
    }
}

impl FindMin {
    /// How Housner's block of the search is made.
    pub fn housner(&self) -> HousnerOptions {
        HousnerOptions {
            form: self.rigid_form,
            overturning: self.rigid_overturning,
            restitution: self.rigid_restitution,
        }
    }

    /// The `i`-th scanned value (the ends exactly as given).
    pub fn scanned(&self, i: usize) -> f64 {
        if i == 0 {
            self.lo
        } else if i + 1 == self.scan {
            self.hi
        } else {
            self.lo + (self.hi - self.lo) * i as f64 / (self.scan - 1) as f64
        }
    }
}

/// One run of the search: overturned or not, when, and its cost.
#[derive(Debug, Clone, Copy)]
pub struct Trial {
    /// The body overturned.
    pub overturned: bool,
    /// When, s.
    pub t_overturn: Option<f64>,
    /// Accepted steps of the run.
    pub steps: usize,
    /// Right-hand-side evaluations of the run.
    pub rhs_evaluations: usize,
}

impl Trial {
    /// The run of the rigid block `block` alone on the floor of `model` (its own steps are
    /// counted; a search beside the body reports only the block's minimum).
    pub fn of_rigid(
        model: &crate::model::Model,
        block: &RigidBlock,
    ) -> Result<Trial, crate::error::Error> {
        let out = crate::simulate::simulate_rigid(model, block)?;
        Ok(Trial {
            overturned: out.overturned,
            t_overturn: out.t_overturn,
            steps: out.steps,
            rhs_evaluations: 0,
        })
    }
}

/// Runs the search; `run` simulates the point at a value of the key. The first error (a value
/// at which the model is invalid or the run fails) ends the search and is returned with its
/// value.
pub fn search<E: Send>(
    find: &FindMin,
    run: impl Fn(f64) -> Result<Trial, E> + Sync,
) -> Result<MinimumOutcome, (f64, E)> {
    let values: Vec<f64> = (0..find.scan).map(|i| find.scanned(i)).collect();
    // Collected in order, so that the error reported is the lowest value's, whatever the
    // threads did.
    let results: Vec<Result<Trial, (f64, E)>> = super::in_order::in_order(0..values.len(), |i| {
        run(values[i]).map_err(|e| (values[i], e))
    });
    let trials = results.into_iter().collect::<Result<Vec<Trial>, _>>()?;
    let mut outcome = MinimumOutcome {
        simulations: trials.len(),
        ..MinimumOutcome::default()
    };
    for trial in &trials {
        outcome.steps += trial.steps;
        outcome.rhs_evaluations += trial.rhs_evaluations;
    }
    let bands = bands(&values, &trials);
    outcome.n_bands = bands.len();
    outcome.bands = bands
        .iter()
        .map(|&(lo, hi)| {
            if lo == hi {
                shortest(lo)
            } else {
                format!("{}-{}", shortest(lo), shortest(hi))
            }
        })
        .collect::<Vec<_>>()
        .join(";");

    let Some(first) = trials.iter().position(|t| t.overturned) else {
        outcome.safe_below = Some(find.hi);
        return Ok(outcome);
    };
    outcome.t_overturn = trials[first].t_overturn;
    if first == 0 {
        outcome.min_overturning = Some(find.lo);
        return Ok(outcome);
    }
    // Bisect [standing, overturning].
    let (mut safe, mut over) = (values[first - 1], values[first]);
    for _ in 0..MAX_BISECTIONS {
        if over - safe <= find.tol {
            break;
        }
        let mid = 0.5 * (safe + over);
        if mid <= safe || mid >= over {
            break;
        }
        let trial = run(mid).map_err(|e| (mid, e))?;
        outcome.simulations += 1;
        outcome.steps += trial.steps;
        outcome.rhs_evaluations += trial.rhs_evaluations;
        if trial.overturned {
            over = mid;
            outcome.t_overturn = trial.t_overturn;
        } else {
            safe = mid;
        }
    }
    outcome.min_overturning = Some(over);
    outcome.safe_below = Some(safe);
    Ok(outcome)
}

/// Runs of consecutive overturning scanned values, as (first, last) value.
fn bands(values: &[f64], trials: &[Trial]) -> Vec<(f64, f64)> {
    let mut bands = Vec::new();
    let mut start = None;
    for (i, trial) in trials.iter().enumerate() {
        match (trial.overturned, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                bands.push((values[s], values[i - 1]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        bands.push((values[s], values[values.len() - 1]));
    }
    bands
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trial(overturned: bool) -> Trial {
        Trial {
            overturned,
            t_overturn: overturned.then_some(1.0),
            steps: 1,
            rhs_evaluations: 1,
        }
    }

    fn find(scan: usize, tol: f64) -> FindMin {
        FindMin {
            key: "excitation.amplitude".into(),
            lo: 0.0,
            hi: 10.0,
            scan,
            tol,
            rigid_form: RigidForm::SmallAngle,
            rigid_overturning: RigidOverturning::ReachesLimit,
            rigid_restitution: None,
        }
    }

    #[test]
    fn the_first_transition_is_bisected_and_bands_above_it_are_reported() {
        // Overturns on [2.345, 4.5) and on [7.2, 10]: a safe band between.
        let overturns = |a: f64| (2.345..4.5).contains(&a) || a >= 7.2;
        let out = search(&find(11, 1e-6), |a| Ok::<_, ()>(trial(overturns(a)))).unwrap();
        let min = out.min_overturning.unwrap();
        assert!(min >= 2.345 && min - 2.345 <= 1e-6, "{min}");
        assert!(out.safe_below.unwrap() < 2.345);
        assert_eq!(out.bands, "3-4;8-10");
        assert_eq!(out.n_bands, 2);
        assert_eq!(out.simulations, out.steps);
    }

    #[test]
    fn the_ends_of_the_interval() {
        let none = search(&find(5, 1e-3), |_| Ok::<_, ()>(trial(false))).unwrap();
        assert_eq!((none.min_overturning, none.safe_below), (None, Some(10.0)));
        assert_eq!(none.bands, "");
        let all = search(&find(5, 1e-3), |_| Ok::<_, ()>(trial(true))).unwrap();
        assert_eq!((all.min_overturning, all.safe_below), (Some(0.0), None));
        assert_eq!(all.bands, "0-10");
        let err = search(&find(5, 1e-3), |a| {
            if a > 4.0 {
                Err("bad")
            } else {
                Ok(trial(false))
            }
        });
        assert_eq!(err.unwrap_err(), (5.0, "bad"));
    }
}

/// What the search for the smallest overturning value of a point found.
#[derive(Debug, Clone, Default)]
pub struct MinimumOutcome {
    /// The smallest value found to overturn: the upper end of the final bracket. None when no
    /// scanned value overturned.
    pub min_overturning: Option<f64>,
    /// The largest value below it found not to overturn (the lower end of the bracket). None
    /// when the lowest value of the interval already overturned.
    pub safe_below: Option<f64>,
    /// The bands of scanned values that overturned, as `lo-hi` (`lo` alone for one value),
    /// separated by `;`.
    pub bands: String,
    /// Number of bands.
    pub n_bands: usize,
    /// Time of overturning at `min_overturning`.
    pub t_overturn: Option<f64>,
    /// Simulations run for the search, and their steps and right-hand-side evaluations.
    pub simulations: usize,
    /// Accepted steps of all the search's runs.
    pub steps: usize,
    /// Right-hand-side evaluations of all the search's runs.
    pub rhs_evaluations: usize,
}

impl MinimumOutcome {
    /// The cells, by column name.
    pub fn named(&self) -> [(&'static str, Cell); 8] {
        [
            ("min_overturning", Cell::Float(self.min_overturning)),
            ("safe_below", Cell::Float(self.safe_below)),
            ("overturning_bands", Cell::text(&self.bands)),
            ("n_bands", Cell::Int(Some(self.n_bands))),
            ("t_overturn", Cell::Float(self.t_overturn)),
            ("simulations", Cell::Int(Some(self.simulations))),
            ("steps", Cell::Int(Some(self.steps))),
            ("rhs_evaluations", Cell::Int(Some(self.rhs_evaluations))),
        ]
    }
}
