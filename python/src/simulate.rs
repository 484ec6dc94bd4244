//! `simulate` and its `Result` (numpy arrays of the history, the events, the episodes and the
//! summary), and `props`.

use std::sync::Arc;

use numpy::PyArray1;
use pyo3::exceptions::PyImportError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use flexrock_core::model::{Overrides, Setting};
use flexrock_core::tables::run_tables::HISTORY_COLUMNS;

use crate::model::Model;
use crate::{err, interrupt, FlexrockError};

/// The solution of `simulate`: history columns as numpy arrays, events, summary.
#[pyclass(module = "flexrock", name = "Result")]
pub(crate) struct SimResult {
    #[pyo3(get)]
    t: Py<PyAny>,
    #[pyo3(get)]
    q: Py<PyAny>,
    #[pyo3(get)]
    qdot: Py<PyAny>,
    #[pyo3(get)]
    s: Py<PyAny>,
    #[pyo3(get)]
    r: Py<PyAny>,
    /// Mode names (as history.csv): a numpy array of str.
    #[pyo3(get)]
    mode: Py<PyAny>,
    #[pyo3(get)]
    floor_acc: Py<PyAny>,
    #[pyo3(get, name = "F")]
    force: Py<PyAny>,
    #[pyo3(get)]
    energy_residual: Py<PyAny>,
    #[pyo3(get)]
    work_input: Py<PyAny>,
    #[pyo3(get)]
    work_damping: Py<PyAny>,
    #[pyo3(get)]
    events: Py<PyAny>,
    /// The rocking episodes: dicts with episodes.csv's columns (None where the CSV is empty).
    #[pyo3(get)]
    episodes: Py<PyAny>,
    #[pyo3(get)]
    summary: Py<PyAny>,
}

#[pymethods]
impl SimResult {
    /// The history as a pandas DataFrame, with history.csv's columns.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|_| {
            PyImportError::new_err(
                "Result.to_pandas() needs pandas: pip install pandas (or pip install './python[pandas]')",
            )
        })?;
        let columns = PyDict::new(py);
        for name in HISTORY_COLUMNS {
            columns.set_item(name, self.column(py, name))?;
        }
        pandas.call_method1("DataFrame", (columns,))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let n = self.t.bind(py).len()?;
        let events = self.events.bind(py).len()?;
        Ok(format!("Result({n} samples, {events} events)"))
    }
}

impl SimResult {
    fn column(&self, py: Python<'_>, name: &str) -> Py<PyAny> {
        let c = match name {
            "t" => &self.t,
            "q" => &self.q,
            "qdot" => &self.qdot,
            "s" => &self.s,
            "r" => &self.r,
            "mode" => &self.mode,
            "floor_acc" => &self.floor_acc,
            "F" => &self.force,
            "energy_residual" => &self.energy_residual,
            "work_input" => &self.work_input,
            _ => &self.work_damping,
        };
        c.clone_ref(py)
    }
}

pub(crate) fn json<'py, T: serde::Serialize>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| FlexrockError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The body as understood and its derived constants: the JSON of `flexrock props --json`.
#[pyfunction]
pub(crate) fn props<'py>(py: Python<'py>, model: &Model) -> PyResult<Bound<'py, PyAny>> {
    json(py, &flexrock_core::properties(&model.state().model))
}

/// An error about a value given as a Python argument, named by the argument: `rtol (sets
/// solver.rtol) = -1: ...`; other errors as they are.
pub(crate) fn err_naming(e: flexrock_core::Error, arguments: &[(&str, &str)]) -> PyErr {
    match e {
        flexrock_core::Error::InvalidParameter { key, value, rule } => {
            let key = match arguments.iter().find(|(k, _)| *k == key) {
                Some((_, argument)) => format!("{argument} (sets {key})"),
                None => key,
            };
            err(flexrock_core::Error::InvalidParameter { key, value, rule })
        }
        other => err(other),
    }
}

/// Solves a model. `method`, `rtol`, `atol`, `duration` (s) and `output_dt` (s) replace the
/// model file's `solver.method`, `solver.rtol`, `solver.atol`, `simulation.duration` and
/// `solver.output_dt` for this run; an error about one of them names the argument.
#[pyfunction]
#[pyo3(signature = (model, method=None, rtol=None, atol=None, duration=None, output_dt=None))]
pub(crate) fn simulate(
    py: Python<'_>,
    model: &Model,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
    duration: Option<f64>,
    output_dt: Option<f64>,
) -> PyResult<SimResult> {
    // The model as it stands now: a key set meanwhile (from another thread) changes the next run.
    let state = model.state();
    let given = method.is_some()
        || rtol.is_some()
        || atol.is_some()
        || duration.is_some()
        || output_dt.is_some();
    let m = if given {
        let mut overrides = Overrides {
            method,
            rtol,
            atol,
            duration,
            ..state.overrides()
        };
        if let Some(dt) = output_dt {
            overrides.settings.retain(|s| s.key != "solver.output_dt");
            overrides
                .settings
                .push(Setting::number("solver.output_dt", dt));
        }
        let arguments = [
            ("solver.method", "method"),
            ("solver.rtol", "rtol"),
            ("solver.atol", "atol"),
            ("simulation.duration", "duration"),
            ("solver.output_dt", "output_dt"),
        ];
        Arc::new(
            state
                .build(&overrides)
                .map_err(|e| err_naming(e, &arguments))?,
        )
    } else {
        state.model
    };
    // A record cut short by the duration is said (a UserWarning at the caller of
    // flexrock.simulate), as the command line says it.
    if let Some(text) = flexrock_core::simulate::record_truncation(&m) {
        let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
        let text = std::ffi::CString::new(text).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 2)?;
    }
    let solving = Arc::clone(&m);
    let solution = interrupt::run(py, move || flexrock_core::simulate(&solving))?.map_err(err)?;
    let summary = json(py, &flexrock_core::tables::summary::summary(&m, &solution))?.unbind();
    result_of(py, &solution, m.body.height, summary)
}

/// The `Result` of a solution: its history as numpy arrays, its events and episodes as dicts,
/// and `summary`.
fn result_of(
    py: Python<'_>,
    solution: &flexrock_core::integrate::solution::Solution,
    height: f64,
    summary: Py<PyAny>,
) -> PyResult<SimResult> {
    let samples = &solution.samples;
    let column = |f: fn(&flexrock_core::integrate::solution::Sample) -> f64| -> Py<PyAny> {
        PyArray1::from_vec(py, samples.iter().map(f).collect())
            .into_any()
            .unbind()
    };
    let modes: Vec<&str> = samples.iter().map(|s| s.mode.name()).collect();
    let numpy = py.import("numpy")?;
    let mode = numpy.call_method1("array", (modes,))?.unbind();
    let events = PyList::empty(py);
    for e in &solution.events {
        let d = PyDict::new(py);
        d.set_item("index", e.index)?;
        d.set_item("t", e.t)?;
        d.set_item("kind", e.kind.name())?;
        d.set_item("from", e.from.name())?;
        d.set_item("to", e.to.name())?;
        d.set_item("q", e.q)?;
        d.set_item("qdot_before", e.qdot_before)?;
        d.set_item("qdot_after", e.qdot_after)?;
        events.append(d)?;
    }
    let episodes = PyList::empty(py);
    for e in &solution.episodes {
        use flexrock_core::tables::run_tables::{episode_fields, EpisodeField, EPISODE_COLUMNS};
        let d = PyDict::new(py);
        for (column, field) in EPISODE_COLUMNS.iter().zip(episode_fields(e, height)) {
            match field {
                EpisodeField::Count(n) => d.set_item(column, n)?,
                EpisodeField::Word(w) => d.set_item(column, w)?,
                EpisodeField::Number(x) => d.set_item(column, x)?,
            }
        }
        episodes.append(d)?;
    }
    Ok(SimResult {
        t: column(|s| s.t),
        q: column(|s| s.q),
        qdot: column(|s| s.qdot),
        s: column(|s| s.s),
        r: column(|s| s.r),
        mode,
        floor_acc: column(|s| s.floor_acc),
        force: column(|s| s.restoring_force),
        energy_residual: column(|s| s.energy_residual),
        work_input: column(|s| s.work_input),
        work_damping: column(|s| s.work_damping),
        events: events.into_any().unbind(),
        episodes: episodes.into_any().unbind(),
        summary,
    })
}

/// The solution of `simulate_row`: each column's `Result`, the impacts, the contacts' history
/// and the summary.
#[pyclass(module = "flexrock", name = "RowResult")]
pub(crate) struct RowResult {
    /// Each column's `Result`, left to right; its `summary` is the column's entry of the row's.
    #[pyo3(get)]
    columns: Py<PyAny>,
    /// The impacts: dicts with impacts.csv's columns.
    #[pyo3(get)]
    impacts: Py<PyAny>,
    /// Every contact at every sampled instant: dicts with contacts.csv's columns (`force` and
    /// `friction_force` None under the impact law).
    #[pyo3(get)]
    contacts: Py<PyAny>,
    /// The dict of the row's summary.json.
    #[pyo3(get)]
    summary: Py<PyAny>,
}

#[pymethods]
impl RowResult {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "RowResult({} columns, {} impacts)",
            self.columns.bind(py).len()?,
            self.impacts.bind(py).len()?
        ))
    }
}

/// Solves a row model file (a `[row]` table and one `[[column]]` per column) by the exact
/// method; `duration` (s) replaces `simulation.duration`.
#[pyfunction]
#[pyo3(signature = (path, duration=None))]
pub(crate) fn simulate_row(
    py: Python<'_>,
    path: std::path::PathBuf,
    duration: Option<f64>,
) -> PyResult<RowResult> {
    use flexrock_core::tables::row_results::{impact_rows, row_summary};
    let model = flexrock_core::model::RowModel::load(&path, duration)
        .map_err(|e| err_naming(e, &[("simulation.duration", "duration")]))?;
    let model = Arc::new(model);
    let solving = Arc::clone(&model);
    let solution = interrupt::run(py, move || flexrock_core::simulate::simulate_row(&solving))?
        .map_err(err)?;
    let summary = json(py, &row_summary(&model, &solution))?;
    let columns = PyList::empty(py);
    for (i, column) in solution.columns.iter().enumerate() {
        let own = summary.get_item("columns")?.get_item(i)?.unbind();
        columns.append(result_of(py, column, model.bodies[i].height, own)?)?;
    }
    // impacts.csv's rows, keyed by its column names (the row type serializes under them).
    let impacts = json(py, &impact_rows(&model, &solution))?;
    let contacts = crate::table::records(py, &solution.contact_history)?;
    Ok(RowResult {
        columns: columns.into_any().unbind(),
        impacts: impacts.unbind(),
        contacts: contacts.unbind(),
        summary: summary.unbind(),
    })
}

/// Housner's rigid block of the model's body (its height, width and gravity) alone on the
/// model's floor, horizontal and vertical: the command line's rigid summary.json as a dict,
/// with its events under "events".
#[pyfunction]
#[pyo3(signature = (model, form=None, overturning=None, restitution=None, find_min=None, scan=None, tol=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn rigid_block<'py>(
    py: Python<'py>,
    model: &Model,
    form: Option<String>,
    overturning: Option<String>,
    restitution: Option<f64>,
    find_min: Option<(String, f64, f64)>,
    scan: Option<usize>,
    tol: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    use flexrock_core::bodies::rigid::{
        check_restitution, RigidBlock, RigidForm, RigidOverturning,
    };
    let invalid = |e: flexrock_core::InvalidParameter| err(e.into());
    let options = flexrock_core::analysis::sweep::HousnerOptions {
        form: form
            .as_deref()
            .map(|f| RigidForm::parse("form", f))
            .transpose()
            .map_err(invalid)?
            .unwrap_or_default(),
        overturning: overturning
            .as_deref()
            .map(|o| RigidOverturning::parse("overturning", o))
            .transpose()
            .map_err(invalid)?
            .unwrap_or_default(),
        restitution: match restitution {
            Some(e) => {
                check_restitution("restitution", e).map_err(invalid)?;
                Some(e)
            }
            None => None,
        },
    };
    let state = model.state();
    let m = &state.model;
    let b = &m.body;
    let block = RigidBlock::housner(b.height, b.width, b.gravity)
        .and_then(|block| options.apply(block))
        .map_err(|e| err(e.into()))?;
    let outcome = py
        .detach(|| flexrock_core::simulate_rigid(m, &block))
        .map_err(err)?;
    if find_min.is_none() && (scan.is_some() || tol.is_some()) {
        return Err(FlexrockError::new_err(
            "scan and tol set the search of find_min, which was not asked for",
        ));
    }
    let search = match find_min {
        None => None,
        Some((key, lo, hi)) => {
            let model_at = |value: f64| {
                let mut overrides = state.overrides();
                overrides.settings.push(Setting::number(&key, value));
                state.build(&overrides)
            };
            let interval = flexrock_core::analysis::sweep::Interval { lo, hi };
            Some(
                py.detach(|| {
                    flexrock_core::analysis::rigid_search::search_rigid(
                        &key,
                        interval,
                        (scan, tol),
                        options,
                        model_at,
                    )
                })
                .map_err(err)?,
            )
        }
    };
    let summary = flexrock_core::tables::rigid_results::RigidSummary::of(m, &block, &outcome);
    let mut value =
        serde_json::to_value(&summary).map_err(|e| FlexrockError::new_err(e.to_string()))?;
    value["find_min"] =
        serde_json::to_value(&search).map_err(|e| FlexrockError::new_err(e.to_string()))?;
    let columns = flexrock_core::tables::rigid_results::RIGID_EVENT_COLUMNS;
    let events: Vec<serde_json::Value> = outcome
        .events
        .iter()
        .map(|e| {
            serde_json::json!({
                columns[0]: e.t,
                columns[1]: e.kind.name(),
                columns[2]: e.q,
                columns[3]: e.qdot_before,
                columns[4]: e.qdot_after,
                columns[5]: e.to.name(),
            })
        })
        .collect();
    value["events"] = serde_json::Value::Array(events);
    json(py, &value)
}
