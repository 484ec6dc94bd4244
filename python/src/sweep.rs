//! `sweep`: a parametric study computed in memory by the core, returned as typed columns.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use flexrock_core::sweep::{Axis, Cell, Interval, Request, Sweep};

use crate::model::{toml_value, Model};
use crate::FlexrockError;

/// A sweep value as the axis text `KEY=A,B` would hold.
fn axis_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    Ok(match toml_value(value)? {
        toml::Value::Float(x) => flexrock_core::format::shortest(x),
        toml::Value::String(s) => s,
        other => other.to_string(),
    })
}

/// An error about the request, named by the Python argument that gave the value: `axes["KEY"]`,
/// `find_min`, `scan`, `tol`, `rigid_form`, `rigid_overturning`, `rigid_restitution`.
fn request_error(e: flexrock_core::Error) -> PyErr {
    use flexrock_core::Error;
    let renamed = match e {
        Error::InvalidParameter { key, value, rule } => {
            let key = match key.split_once(' ') {
                Some(("vary", k)) => format!("axes[{k:?}]"),
                Some(("find_min", _)) => "find_min".to_string(),
                None if key == "vary" => "axes".to_string(),
                _ => key,
            };
            Error::InvalidParameter { key, value, rule }
        }
        other => other,
    };
    FlexrockError::new_err(renamed.to_string())
}

fn cell<'py>(py: Python<'py>, cell: &Cell) -> PyResult<Bound<'py, PyAny>> {
    Ok(match cell {
        Cell::Bool(Some(b)) => b.into_pyobject(py)?.to_owned().into_any(),
        Cell::Int(Some(n)) => n.into_pyobject(py)?.into_any(),
        Cell::Float(Some(x)) => x.into_pyobject(py)?.into_any(),
        Cell::Text(Some(t)) => t.into_pyobject(py)?.into_any(),
        _ => py.None().into_bound(py),
    })
}

/// A parametric study: every combination of the axes' values (the last axis varies fastest),
/// computed in parallel in memory. Returns the typed columns of sweep.csv:
/// `{"columns": [...], "kinds": ["int"|"float"|"bool"|"str", ...], "values": [[...], ...],
/// "axes": [(key, [values]), ...]}`, None where sweep.csv's field is empty.
#[pyfunction]
#[pyo3(signature = (
    model, axes, find_min=None, scan=None, tol=None, rigid_form=None, rigid_overturning=None,
    rigid_restitution=None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn sweep<'py>(
    py: Python<'py>,
    model: &Model,
    axes: &Bound<'py, PyDict>,
    find_min: Option<(String, f64, f64)>,
    scan: Option<usize>,
    tol: Option<f64>,
    rigid_form: Option<String>,
    rigid_overturning: Option<String>,
    rigid_restitution: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let rigid_form = match rigid_form {
        Some(text) => Some(
            flexrock_core::rigid::RigidForm::parse("rigid_form", &text)
                .map_err(|e| request_error(e.into()))?,
        ),
        None => None,
    };
    let rigid_overturning = match rigid_overturning {
        Some(text) => Some(
            flexrock_core::rigid::RigidOverturning::parse("rigid_overturning", &text)
                .map_err(|e| request_error(e.into()))?,
        ),
        None => None,
    };
    let mut request = Request {
        settings: model.settings.clone(),
        scan,
        tol,
        rigid_form,
        rigid_overturning,
        rigid_restitution,
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
    // Paths the user typed (record files of an axis, a model given as text) are relative to the
    // current directory; a model file's own record paths are relative to the file.
    let here = std::env::current_dir()?;
    let sweep = match (&model.path, &model.text) {
        (Some(path), _) => Sweep::new(path, request, &here),
        (None, text) => {
            Sweep::from_text(text.as_deref().unwrap_or_default(), &here, request, &here)
        }
    }
    .map_err(request_error)?;
    let plan = &sweep.plan;
    let find = plan.layout();
    let rows = py.detach(|| sweep.rows(0..sweep.points(), &|| {}));
    let mut columns: Vec<String> = vec!["point".into()];
    let mut kinds: Vec<&str> = vec!["int"];
    for axis in &plan.axes {
        columns.push(axis.key.clone());
        kinds.push(if axis.is_numeric() { "float" } else { "str" });
    }
    let first = columns.len();
    columns.extend(plan.result_columns());
    // The kinds of the result columns, from a row without values.
    let empty = plan.empty_cells();
    kinds.extend(empty.iter().map(|c| c.kind().name()));
    let values: Vec<Bound<'py, PyList>> = (0..columns.len()).map(|_| PyList::empty(py)).collect();
    for (index, row) in rows.iter().enumerate() {
        values[0].append(index)?;
        for ((a, axis), &i) in plan.axes.iter().enumerate().zip(&plan.coordinates(index)) {
            match axis.number(i) {
                Some(x) => values[1 + a].append(x)?,
                None => values[1 + a].append(&axis.values[i])?,
            }
        }
        for (c, cell_value) in row.cells(find).iter().enumerate() {
            values[first + c].append(self::cell(py, cell_value)?)?;
        }
    }
    let axes_out = PyList::empty(py);
    for axis in &plan.axes {
        let list = PyList::empty(py);
        for i in 0..axis.len() {
            match axis.number(i) {
                Some(x) => list.append(x)?,
                None => list.append(&axis.values[i])?,
            }
        }
        axes_out.append((axis.key.clone(), list))?;
    }
    let out = PyDict::new(py);
    out.set_item("columns", columns)?;
    out.set_item("kinds", kinds)?;
    out.set_item("values", values)?;
    out.set_item("axes", axes_out)?;
    Ok(out)
}
