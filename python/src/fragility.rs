//! `fragility`: the study of `flexrock fragility` (incremental dynamic analysis over a suite),
//! its sweep's rows kept in memory; `fit_capacities` and `fit_stripes`: the core's fits of a
//! lognormal fragility function to the user's own capacities or counts. The study's summary
//! is returned as the text of fragility.json; the Python side reads it.

use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use flexrock_core::analysis::fragility::study::{self, Study};
use flexrock_core::analysis::fragility::{
    fit_capacities as core_fit_capacities, fit_stripes as core_fit_stripes, Capacity, FitError,
    Measure, RecordResult, Stripe,
};
use flexrock_core::analysis::sweep::{Cell, Interval, Request, Sweep};

use crate::model::Model;
use crate::FlexrockError;

fn fit_error(what: &str, e: FitError) -> PyErr {
    FlexrockError::new_err(format!("{what}: {e}"))
}

/// The study over the suite `records` (a directory, a list file or a pattern); returns
/// fragility.json's text.
#[pyfunction]
#[pyo3(signature = (model, records, im, period, scale, scan, tol, bootstrap, seed))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fragility(
    py: Python<'_>,
    model: &Model,
    records: String,
    im: String,
    period: Option<f64>,
    scale: (f64, f64),
    scan: Option<usize>,
    tol: Option<f64>,
    bootstrap: usize,
    seed: u64,
) -> PyResult<String> {
    let state = model.state();
    if let Some(motion) = &state.ground_motion {
        return Err(FlexrockError::new_err(format!(
            "model: its ground motion ({}) was given as arrays; a fragility study varies the \
             model's record file: give a model with a record excitation (kind = \"record\")",
            motion.record.source
        )));
    }
    let measure = Measure::parse("im", &im).map_err(crate::err)?;
    let axis = study::record_axis(&records).map_err(crate::err)?;
    let scale = Interval {
        lo: scale.0,
        hi: scale.1,
    };
    let mut settings = Study {
        model_file: state.path.as_ref().map_or_else(
            || "(model given as text)".into(),
            |p| p.display().to_string(),
        ),
        measure,
        period,
        scale,
        bootstrap,
        seed,
    };
    settings.check().map_err(crate::err)?;
    let request = Request {
        settings: state.settings.clone(),
        axes: vec![axis],
        find_min: Some(("excitation.scale".to_string(), scale)),
        scan,
        tol,
        ..Request::default()
    };
    let here = std::env::current_dir()?;
    let sweep = match &state.path {
        Some(path) => {
            let sweep = Sweep::new(path, request, &here);
            crate::sweep::refuse_changed(&sweep, path, &state.text)?;
            sweep
        }
        None => Sweep::from_text(&state.text, &here, request, &here),
    }
    .map_err(|e| crate::err(e.renamed("find_min", "scale")))?;
    let measures = study::suite_measures(&sweep, measure, period).map_err(crate::err)?;
    settings.period = measures.period;
    // The points, computed on a thread of their own so that Ctrl-C stops them.
    let sweep = Arc::new(sweep);
    let points = sweep.points();
    let mut rows = Vec::with_capacity(points);
    crate::sweep::compute_points(py, &sweep, |part| {
        rows.extend(part);
        Ok(())
    })?;
    if rows.len() != points {
        return Err(FlexrockError::new_err(format!(
            "the study stopped after {} of {points} records",
            rows.len()
        )));
    }
    // Each record's result from its row's cells, by column name.
    let names = sweep.plan.result_columns();
    let layout = sweep.plan.layout();
    let col = |name: &str| {
        names.iter().position(|n| n == name).ok_or_else(|| {
            FlexrockError::new_err(format!("the sweep's rows have no column {name}"))
        })
    };
    let (status, reason, min, bands, n_bands) = (
        col("status")?,
        col("reason")?,
        col("min_overturning")?,
        col("overturning_bands")?,
        col("n_bands")?,
    );
    let text = |cell: &Cell| match cell {
        Cell::Text(t) => t.clone().unwrap_or_default(),
        _ => String::new(),
    };
    let paths = &sweep.plan.axes[0].values;
    let mut results = Vec::with_capacity(points);
    for (i, row) in rows.iter().enumerate() {
        let cells = row.cells(layout);
        if text(&cells[status]) != "ok" {
            return Err(FlexrockError::new_err(format!(
                "records = {}: {}: its minimum search is {}: {}",
                records,
                paths[i],
                text(&cells[status]),
                text(&cells[reason])
            )));
        }
        let scale = match cells[min] {
            Cell::Float(x) => x,
            _ => None,
        };
        let unscaled = measures.unscaled[i];
        results.push(RecordResult {
            path: paths[i].clone(),
            label: measures.labels[i].clone(),
            im_unscaled: unscaled,
            min_overturning_scale: scale,
            capacity: study::capacity(measure, unscaled, scale, settings.scale.hi),
            overturning_bands: text(&cells[bands]),
            n_bands: match cells[n_bands] {
                Cell::Int(n) => n.unwrap_or(0),
                _ => 0,
            },
        });
    }
    let summary = study::summarize(&settings, results).map_err(|e| fit_error("records", e))?;
    serde_json::to_string(&summary).map_err(|e| FlexrockError::new_err(e.to_string()))
}

/// The core's fit of capacities: `capacity[i]` observed, or censored (above it) where
/// `censored[i]`. Returns `{"theta", "beta", "beta_unbiased", "method", "observed",
/// "censored"}`.
#[pyfunction]
pub(crate) fn fit_capacities<'py>(
    py: Python<'py>,
    capacity: Vec<f64>,
    censored: Vec<bool>,
) -> PyResult<Bound<'py, PyDict>> {
    if capacity.len() != censored.len() {
        return Err(FlexrockError::new_err(format!(
            "censored: has {} values for {} capacities: give one per capacity",
            censored.len(),
            capacity.len()
        )));
    }
    let capacities: Vec<Capacity> = capacity
        .iter()
        .zip(&censored)
        .map(|(&x, &c)| {
            if c {
                Capacity::Censored(x)
            } else {
                Capacity::Observed(x)
            }
        })
        .collect();
    let fit = core_fit_capacities(&capacities).map_err(|e| fit_error("capacity", e))?;
    let out = PyDict::new(py);
    out.set_item("theta", fit.fit.theta)?;
    out.set_item("beta", fit.fit.beta)?;
    out.set_item("beta_unbiased", fit.beta_unbiased)?;
    out.set_item("method", fit.method)?;
    out.set_item("observed", fit.observed)?;
    out.set_item("censored", fit.censored)?;
    Ok(out)
}

/// The core's fit of counts at intensity levels: `damaged[j]` of `records[j]` records reached
/// the damage state at `levels[j]`. Returns `{"theta", "beta", "method"}`.
#[pyfunction]
pub(crate) fn fit_stripes<'py>(
    py: Python<'py>,
    levels: Vec<f64>,
    records: Vec<usize>,
    damaged: Vec<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    if records.len() != levels.len() || damaged.len() != levels.len() {
        return Err(FlexrockError::new_err(format!(
            "levels, records, damaged: have {}, {} and {} values: give one of each per level",
            levels.len(),
            records.len(),
            damaged.len()
        )));
    }
    let mut stripes = Vec::with_capacity(levels.len());
    for (j, ((&level, &n), &z)) in levels.iter().zip(&records).zip(&damaged).enumerate() {
        if z > n {
            return Err(FlexrockError::new_err(format!(
                "damaged[{j}] = {z}: must be at most records[{j}] = {n}"
            )));
        }
        stripes.push(Stripe {
            level,
            records: n,
            damaged: z,
        });
    }
    let fit = core_fit_stripes(&stripes).map_err(|e| fit_error("levels", e))?;
    let out = PyDict::new(py);
    out.set_item("theta", fit.theta)?;
    out.set_item("beta", fit.beta)?;
    out.set_item("method", "stripes-mle")?;
    Ok(out)
}
