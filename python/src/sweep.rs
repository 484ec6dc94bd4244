//! `sweep`: a parametric study computed by the core, its table kept in memory as typed numpy
//! columns. The table's size is checked against [`MAX_SWEEP_TABLE_BYTES`] before any point is
//! computed, its columns are made at their full size then (a MemoryError, never an abort, when
//! they cannot be), and the points run on a thread of their own, so that Ctrl-C stops them.

use std::sync::Arc;

use pyo3::exceptions::{PyMemoryError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyString};

use flexrock_core::analysis::sweep::axis::MAX_AXIS_VALUES;
use flexrock_core::analysis::sweep::cell::Kind;
use flexrock_core::analysis::sweep::{
    Axis, Cell, Interval, Layout, Plan, PointResult, Request, Sweep,
};

use crate::interrupt;
use crate::model::{short_repr, toml_value, Model};
use crate::table::{table_dict, Column};
use crate::FlexrockError;

/// Most memory the table of a sweep in Python may take (its columns at 8 bytes a number or a
/// text, 9 a count, 2 a truth value, and the texts made); the command line's sweep, which writes
/// its table to disk in chunks, has no such limit.
pub(crate) const MAX_SWEEP_TABLE_BYTES: usize = 256 * 1024 * 1024;

/// `b` bytes as a person reads them: `512 MiB`, `21.9 GiB`.
fn size_text(b: u64) -> String {
    const MIB: f64 = 1024.0 * 1024.0;
    let mib = b as f64 / MIB;
    if mib < 1024.0 {
        format!(
            "{} MiB",
            flexrock_core::base::format::shortest((mib * 10.0).round() / 10.0)
        )
    } else {
        let gib = mib / 1024.0;
        format!(
            "{} GiB",
            flexrock_core::base::format::shortest((gib * 10.0).round() / 10.0)
        )
    }
}

/// A sweep value as the axis text `KEY=A,B` would hold.
fn axis_text(value: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    Ok(match toml_value(value, name)? {
        toml::Value::Float(x) => flexrock_core::base::format::shortest(x),
        toml::Value::String(s) => s,
        other => other.to_string(),
    })
}

/// The values of the axis `key`: a sequence (a list, a tuple, a numpy array) of bools, numbers
/// or strs, at most [`MAX_AXIS_VALUES`] of them. A str is refused, not taken as its letters.
fn axis_values(key: &str, values: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let at = format!("axes[{key:?}]");
    if values.is_instance_of::<PyString>()
        || values.is_instance_of::<pyo3::types::PyBytes>()
        || values.is_instance_of::<PyDict>()
    {
        return Err(PyTypeError::new_err(format!(
            "{at} = {}: must be a sequence of values (a list, a tuple or a numpy array), not a \
             {}; for one value, give a list of one: [{}]",
            short_repr(values),
            values.get_type().name()?,
            short_repr(values)
        )));
    }
    let items = values.try_iter().map_err(|_| {
        PyTypeError::new_err(format!(
            "{at} = {}: must be a sequence of values (a list, a tuple or a numpy array), e.g. \
             [{}]",
            short_repr(values),
            short_repr(values)
        ))
    })?;
    let mut texts = Vec::new();
    for (i, item) in items.enumerate() {
        if i == MAX_AXIS_VALUES {
            return Err(FlexrockError::new_err(format!(
                "{at}: has more than the {MAX_AXIS_VALUES} values an axis may have"
            )));
        }
        texts.push(axis_text(&item?, &format!("{at}[{i}]"))?);
    }
    Ok(texts)
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

/// The table of a sweep: the point, the axes' values and the result columns of every point.
struct Table {
    names: Vec<String>,
    columns: Vec<Column>,
    /// Each axis's values as Python objects (floats, or strs), one per value.
    axis_values: Vec<Vec<Py<PyAny>>>,
    layout: Layout,
    /// Points in the table so far.
    len: usize,
    /// The table's bytes so far: its columns' room, and the strs made.
    bytes: usize,
    points: usize,
}

impl Table {
    /// The table of `plan`'s points, its columns made at their full size, after its size is
    /// checked against [`MAX_SWEEP_TABLE_BYTES`].
    fn new(py: Python<'_>, plan: &Plan) -> PyResult<Table> {
        let points = plan.points();
        let layout = plan.layout();
        let mut names: Vec<String> = vec!["point".into()];
        let mut kinds = vec![Kind::Int];
        for axis in &plan.axes {
            names.push(axis.key.clone());
            kinds.push(if axis.is_numeric() {
                Kind::Float
            } else {
                Kind::Text
            });
        }
        names.extend(plan.result_columns());
        // The kinds of the result columns, from a row without values.
        let empty = plan.empty_cells();
        kinds.extend(empty.iter().map(Cell::kind));
        let per_point: usize = kinds.iter().map(|&k| Column::bytes_per_cell(k)).sum();
        let bytes = points.checked_mul(per_point);
        let shape = plan
            .axes
            .iter()
            .map(|a| a.len().to_string())
            .collect::<Vec<_>>()
            .join(" x ");
        let size = |bytes: Option<usize>| match bytes {
            Some(b) => format!("{} ({b} bytes)", size_text(b as u64)),
            None => "more bytes than memory has".into(),
        };
        if bytes.is_none_or(|b| b > MAX_SWEEP_TABLE_BYTES) {
            return Err(FlexrockError::new_err(format!(
                "axes = {shape}: {points} points of {} columns, whose table would take {} in \
                 memory, beyond the {} a sweep in Python may hold (about {} points of these \
                 columns); sweep fewer points at a time, or run the command line's sweep \
                 (flexrock sweep), which writes its table to disk in chunks",
                names.len(),
                size(bytes),
                size_text(MAX_SWEEP_TABLE_BYTES as u64),
                MAX_SWEEP_TABLE_BYTES / per_point
            )));
        }
        let columns = kinds
            .iter()
            .map(|&k| Column::with_room(k, points))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| {
                PyMemoryError::new_err(format!(
                    "axes = {shape}: the table of {points} points takes {}, more than this \
                     process can have",
                    size(bytes)
                ))
            })?;
        let axis_values = plan
            .axes
            .iter()
            .map(|axis| {
                (0..axis.len())
                    .map(|i| match axis.number(i) {
                        Some(x) => PyFloat::new(py, x).into_any().unbind(),
                        None => PyString::new(py, &axis.values[i]).into_any().unbind(),
                    })
                    .collect()
            })
            .collect();
        Ok(Table {
            names,
            columns,
            axis_values,
            layout,
            len: 0,
            bytes: bytes.unwrap_or(0),
            points,
        })
    }

    /// Appends the rows of the next points.
    fn append(&mut self, py: Python<'_>, plan: &Plan, rows: Vec<PointResult>) -> PyResult<()> {
        let first = 1 + plan.axes.len();
        for row in rows {
            let index = self.len;
            self.columns[0].push_cell(py, &Cell::Int(Some(index)));
            for (a, &i) in plan.coordinates(index).iter().enumerate() {
                match &mut self.columns[1 + a] {
                    Column::Text(v, _) => v.push(self.axis_values[a][i].clone_ref(py)),
                    column => {
                        column.push_cell(py, &Cell::Float(plan.axes[a].number(i)));
                    }
                }
            }
            for (c, cell) in row.cells(self.layout).iter().enumerate() {
                self.bytes += self.columns[first + c].push_cell(py, cell);
            }
            self.len += 1;
        }
        if self.bytes > MAX_SWEEP_TABLE_BYTES {
            return Err(PyMemoryError::new_err(format!(
                "after {} of {} points, the sweep's table takes {} with its texts (the reasons \
                 of points that failed), beyond the {} a sweep in Python may hold; sweep fewer \
                 points at a time, or run the command line's sweep (flexrock sweep)",
                self.len,
                self.points,
                size_text(self.bytes as u64),
                size_text(MAX_SWEEP_TABLE_BYTES as u64)
            )));
        }
        Ok(())
    }

    /// `{"columns", "kinds", "values", "missing", "axes"}`: the table as `SweepResult` takes it;
    /// a number that is missing is NaN, without a mask.
    fn into_dict<'py>(mut self, py: Python<'py>, plan: &Plan) -> PyResult<Bound<'py, PyDict>> {
        for column in &mut self.columns {
            if let Column::Float(_, missing) = column {
                *missing = Vec::new();
            }
        }
        let axes = PyList::empty(py);
        for (axis, objects) in plan.axes.iter().zip(self.axis_values) {
            axes.append((axis.key.clone(), objects))?;
        }
        let out = table_dict(py, self.names, self.columns)?;
        out.set_item("axes", axes)?;
        Ok(out)
    }
}

/// A parametric study: every combination of the axes' values (the last axis varies fastest),
/// computed in parallel. Returns the typed columns of sweep.csv as numpy arrays:
/// `{"columns": [...], "kinds": ["int"|"float"|"bool"|"str", ...], "values": [array, ...],
/// "missing": [bool array or None, ...], "axes": [(key, [values]), ...]}`.
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
    let state = model.state();
    let rigid_form = match rigid_form {
        Some(text) => Some(
            flexrock_core::bodies::rigid::RigidForm::parse("rigid_form", &text)
                .map_err(|e| request_error(e.into()))?,
        ),
        None => None,
    };
    let rigid_overturning = match rigid_overturning {
        Some(text) => Some(
            flexrock_core::bodies::rigid::RigidOverturning::parse("rigid_overturning", &text)
                .map_err(|e| request_error(e.into()))?,
        ),
        None => None,
    };
    let mut request = Request {
        settings: state.settings.clone(),
        scan,
        tol,
        rigid_form,
        rigid_overturning,
        rigid_restitution,
        find_min: find_min.map(|(key, lo, hi)| (key, Interval { lo, hi })),
        ..Request::default()
    };
    for (key, values) in axes.iter() {
        let key: String = key.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "axes: every key must be a str (a model-file key), not {}",
                short_repr(&key)
            ))
        })?;
        request
            .axes
            .push(Axis::new(&key, axis_values(&key, &values)?));
    }
    // Paths the user typed (record files of an axis, a model given as text) are relative to the
    // current directory; a model file's own record paths are relative to the file.
    let here = std::env::current_dir()?;
    let sweep = match (&state.ground_motion, &state.path) {
        (Some(motion), _) => {
            // The model's record is its ground motion, held in memory under its source's name.
            let keys = request
                .axes
                .iter()
                .map(|a| a.key.as_str())
                .chain(request.find_min.iter().map(|(k, _)| k.as_str()));
            for key in keys {
                if crate::model::RECORD_SOURCE_KEYS.contains(&key) {
                    return Err(FlexrockError::new_err(format!(
                        "axes[{key:?}]: the model's ground motion ({}) was given as arrays, and \
                         says where its record comes from; sweep a model with a record file \
                         to vary it",
                        motion.record.source
                    )));
                }
            }
            let table = state.table_with_motion().map_err(crate::err)?;
            let text =
                toml::to_string(&table).map_err(|e| FlexrockError::new_err(e.to_string()))?;
            request.records = vec![(motion.record.source.clone(), motion.record.clone())];
            Sweep::from_text(&text, &here, request, &here)
        }
        (None, Some(path)) => {
            let sweep = Sweep::new(path, request, &here);
            refuse_changed(&sweep, path, &state.text)?;
            sweep
        }
        (None, None) => Sweep::from_text(&state.text, &here, request, &here),
    }
    .map_err(request_error)?;
    let mut table = Table::new(py, &sweep.plan)?;
    let sweep = Arc::new(sweep);
    let points = sweep.points();
    compute_points(py, &sweep, |rows| table.append(py, &sweep.plan, rows))?;
    if table.len != points {
        return Err(FlexrockError::new_err(format!(
            "the sweep stopped after {} of {points} points",
            table.len
        )));
    }
    table.into_dict(py, &sweep.plan)
}

/// Refuses a sweep read from the model file `path` when the file has changed since the
/// model's `text` was read from it.
pub(crate) fn refuse_changed(
    sweep: &flexrock_core::Result<Sweep>,
    path: &std::path::Path,
    text: &str,
) -> PyResult<()> {
    match sweep {
        Ok(s) if s.plan.model_text != text => Err(FlexrockError::new_err(format!(
            "model file = {}: has changed since the model was read from it: read it again with \
             Model.from_file",
            path.display()
        ))),
        _ => Ok(()),
    }
}

/// Computes the points of `sweep` on a thread of their own, so that Ctrl-C stops them, in
/// chunks of at least four points per core, and hands each chunk's results to `take` in order.
/// Stopped early, fewer points reach `take`: the caller counts them.
pub(crate) fn compute_points(
    py: Python<'_>,
    sweep: &Arc<Sweep>,
    take: impl FnMut(Vec<PointResult>) -> PyResult<()>,
) -> PyResult<()> {
    let points = sweep.points();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = sweep.plan.chunk_size.max(4 * cores);
    let computing = Arc::clone(sweep);
    interrupt::run_in_parts(
        py,
        move |cancel, parts| {
            let mut start = 0;
            while start < points {
                let end = (start + chunk).min(points);
                let Some(rows) = computing.rows_until(start..end, &|| cancel.is_set()) else {
                    return;
                };
                if !parts.send(rows) {
                    return;
                }
                start = end;
            }
        },
        take,
    )
}
