//! The smallest value of a model-file key (an amplitude, a record's scale) that overturns the
//! rigid block alone on the model's floor: the sweep's minimum search (a scan of the interval,
//! then bisection of the first transition from standing to overturned) made on the block.

use serde::Serialize;

use crate::analysis::sweep::axis::{self, Interval, MAX_AXIS_VALUES};
use crate::analysis::sweep::find_min::{self, FindMin, HousnerOptions, Trial};
use crate::bodies::rigid::RigidBlock;
use crate::error::{Error, Result};
use crate::model::Model;

/// What the search found, as summary.json's `find_min` writes it.
#[derive(Debug, Clone, Serialize)]
pub struct RigidSearch {
    /// The key searched.
    pub key: String,
    /// The interval searched.
    pub lo: f64,
    /// Its upper end.
    pub hi: f64,
    /// Values scanned from `lo` to `hi`.
    pub scan: usize,
    /// Width of the final bracket, in the key's units.
    pub tol: f64,
    /// The smallest value found to overturn the block (the upper end of the final bracket);
    /// None when no scanned value did.
    pub min_overturning: Option<f64>,
    /// The largest value below it found not to; None when `lo` overturns already.
    pub safe_below: Option<f64>,
    /// The bands of scanned values that overturned, `lo-hi` separated by `;`.
    pub bands: String,
    /// Number of bands.
    pub n_bands: usize,
    /// When the block overturned at `min_overturning`, s.
    pub t_overturn_s: Option<f64>,
    /// Runs made.
    pub simulations: usize,
}

/// Searches `interval` of `key` for the smallest value that overturns Housner's block made as
/// `options` say, of the body of the model `model_at(value)` gives at each value; `scan` values
/// (default [`find_min::DEFAULT_SCAN`]), bisected to `tol` (default
/// [`find_min::DEFAULT_TOL_SHARE`] of the interval).
pub fn search_rigid(
    key: &str,
    interval: Interval,
    (scan, tol): (Option<usize>, Option<f64>),
    options: HousnerOptions,
    model_at: impl Fn(f64) -> Result<Model> + Sync,
) -> Result<RigidSearch> {
    axis::check_interval(key, &interval)?;
    let scan = scan.unwrap_or(find_min::DEFAULT_SCAN);
    if !(2..=MAX_AXIS_VALUES).contains(&scan) {
        return Err(Error::invalid(
            "scan",
            scan,
            &format!("must lie in 2..={MAX_AXIS_VALUES}"),
        ));
    }
    let tol = tol.unwrap_or(find_min::DEFAULT_TOL_SHARE * (interval.hi - interval.lo));
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(Error::invalid("tol", tol, "must be a positive number"));
    }
    let find = FindMin {
        key: key.to_string(),
        lo: interval.lo,
        hi: interval.hi,
        scan,
        tol,
        rigid_form: options.form,
        rigid_overturning: options.overturning,
        rigid_restitution: options.restitution,
    };
    let trial = |value: f64| -> Result<Trial> {
        let model = model_at(value)?;
        let b = &model.body;
        let block = options.apply(RigidBlock::housner(b.height, b.width, b.gravity)?)?;
        Trial::of_rigid(&model, &block)
    };
    // A value the model refuses is named as the search's, not as a setting of the user's.
    let outcome = find_min::search(&find, trial).map_err(|(value, e)| {
        Error::invalid(
            &format!("find_min {key}"),
            value,
            &format!("the model or its run fails there: {e}"),
        )
    })?;
    Ok(RigidSearch {
        key: find.key,
        lo: find.lo,
        hi: find.hi,
        scan,
        tol,
        min_overturning: outcome.min_overturning,
        safe_below: outcome.safe_below,
        bands: outcome.bands,
        n_bands: outcome.n_bands,
        t_overturn_s: outcome.t_overturn,
        simulations: outcome.simulations,
    })
}
