//! `sweep`: a parametric study in memory, its columns by name.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::err;
use crate::model::{toml_value, Model};

/// A sweep value as the axis text `flexrock sweep --vary KEY=A,B` would hold.
fn axis_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    Ok(match toml_value(value)? {
        toml::Value::Float(x) => flexrock::output::shortest(x),
        toml::Value::String(s) => s,
        other => other.to_string(),
    })
}

/// A parametric study: every combination of the axes' values (the last axis varies fastest),
/// in parallel. Returns sweep.csv's columns by name: numbers as float64 arrays (NaN where the
/// CSV field is empty), `point` as int64, text columns (status, reason, overturned, ...) as
/// lists of str.
#[pyfunction]
#[pyo3(signature = (model, axes, find_min=None, scan=None, tol=None))]
pub(crate) fn sweep<'py>(
    py: Python<'py>,
    model: &Model,
    axes: &Bound<'py, PyDict>,
    find_min: Option<(String, f64, f64)>,
    scan: Option<usize>,
    tol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    use flexrock::sweep::{store, Axis, Interval, Request, Sweep};
    let mut request = Request {
        settings: model.settings.clone(),
        scan,
        tol,
        find_min: find_min.map(|(key, lo, hi)| (key, Interval { lo, hi })),
        ..Request::default()
    };
    for (key, values) in axes.iter() {
        let key: String = key.extract()?;
        let texts = values
            .try_iter()?
            .map(|v| axis_text(&v?))
            .collect::<PyResult<Vec<String>>>()?;
        request.axes.push(Axis::new(&key, texts));
    }
    // The library's sweep reads a model file: a model given as text goes to a temporary one.
    let scratch;
    let path = match (&model.path, &model.text) {
        (Some(path), _) => path.clone(),
        (None, text) => {
            scratch = tempfile::tempdir()?;
            let path = scratch.path().join("model.toml");
            let text = text.as_deref().unwrap_or_default();
            std::fs::write(
                &path,
                record_paths_from_here(text).unwrap_or_else(|| text.to_owned()),
            )?;
            path
        }
    };
    let sweep = Sweep::new(&path, request).map_err(err)?;
    let columns = sweep.plan.columns();
    let rows = py.detach(|| store::rows(&sweep, &store::Silent));
    let out = PyDict::new(py);
    for (c, name) in columns.iter().enumerate() {
        let fields: Vec<&str> = rows.iter().map(|r| r[c].as_str()).collect();
        if name == "point" {
            let points: Vec<i64> = fields.iter().map(|f| f.parse().unwrap_or(-1)).collect();
            out.set_item(name, PyArray1::from_vec(py, points))?;
            continue;
        }
        let numbers: Option<Vec<f64>> = fields
            .iter()
            .map(|f| {
                if f.is_empty() {
                    Some(f64::NAN)
                } else {
                    f.parse::<f64>().ok()
                }
            })
            .collect();
        // A column is numeric when every non-empty field is a number (and one is not empty).
        match numbers {
            Some(v) if fields.iter().any(|f| !f.is_empty()) || !is_text_column(name) => {
                out.set_item(name, PyArray1::from_vec(py, v))?
            }
            _ => out.set_item(name, fields)?,
        }
    }
    Ok(out)
}

/// A model text whose relative `excitation.path` is made absolute from the current directory,
/// as `simulate` reads it (the sweep reads the text from a temporary directory, so a relative
/// record path would be looked for there). `None` when there is nothing to change (or the text
/// does not parse: the sweep then reports that itself).
fn record_paths_from_here(text: &str) -> Option<String> {
    let mut table: toml::Table = text.parse().ok()?;
    let excitation = table.get_mut("excitation")?.as_table_mut()?;
    let path = std::path::Path::new(excitation.get("path")?.as_str()?);
    if path.is_absolute() {
        return None;
    }
    let absolute = std::env::current_dir().ok()?.join(path);
    excitation.insert(
        "path".to_owned(),
        toml::Value::String(absolute.to_str()?.to_owned()),
    );
    Some(table.to_string())
}

/// Columns of sweep.csv that hold text (so that an all-empty one stays a list of str).
fn is_text_column(name: &str) -> bool {
    matches!(name, "status" | "reason" | "overturned" | "final_mode")
        || name.starts_with("excitation.path")
}
