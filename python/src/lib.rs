//! Python bindings of flexrock: `Model`, `props`, `simulate` (a `Result` of numpy arrays) and
//! `sweep` (a dict of sweep.csv's columns). Every number comes from the library exactly as the
//! command line computes it; no file is written (but a temporary copy of a model given as text,
//! for a sweep).

use std::path::PathBuf;

use numpy::PyArray1;
use pyo3::create_exception;
use pyo3::exceptions::{PyImportError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use flexrock::model::{check_key, Overrides, Setting};
use flexrock::output::HISTORY_COLUMNS;

create_exception!(
    flexrock,
    FlexrockError,
    PyValueError,
    "An error of flexrock, with the message the command line prints."
);

fn err(e: flexrock::Error) -> PyErr {
    FlexrockError::new_err(e.to_string())
}

/// A model: a model file (or its text) and the keys set on it with `set`, validated.
#[pyclass(module = "flexrock")]
struct Model {
    /// The model file, when read from one (record paths are relative to it).
    path: Option<PathBuf>,
    /// The text of a model given as text.
    text: Option<String>,
    settings: Vec<Setting>,
    model: flexrock::model::Model,
}

impl Model {
    fn build(&self, overrides: &Overrides) -> flexrock::Result<flexrock::model::Model> {
        match (&self.path, &self.text) {
            (Some(path), _) => flexrock::model::Model::load(path, overrides),
            (None, Some(text)) => flexrock::model::Model::from_toml_str(text, overrides),
            (None, None) => unreachable!("a model has a file or a text"),
        }
    }

    fn overrides(&self) -> Overrides {
        Overrides {
            settings: self.settings.clone(),
            ..Overrides::default()
        }
    }
}

/// A Python value as a model-file value: bool, int, float or str.
fn toml_value(value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = value.extract::<bool>() {
        if value.is_instance_of::<pyo3::types::PyBool>() {
            return Ok(toml::Value::Boolean(b));
        }
    }
    if value.is_instance_of::<pyo3::types::PyInt>() {
        return Ok(toml::Value::Integer(value.extract::<i64>()?));
    }
    if let Ok(x) = value.extract::<f64>() {
        if !value.is_instance_of::<pyo3::types::PyString>() {
            return Ok(toml::Value::Float(x));
        }
    }
    if let Ok(s) = value.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    Err(FlexrockError::new_err(format!(
        "a model-file value must be a number, a string or a bool, not {}",
        value.get_type().name()?
    )))
}

#[pymethods]
impl Model {
    /// Reads and validates a model file (as `flexrock run FILE`).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Model> {
        let model = flexrock::model::Model::load(&path, &Overrides::default()).map_err(err)?;
        Ok(Model {
            path: Some(path),
            text: None,
            settings: Vec::new(),
            model,
        })
    }

    /// Parses and validates the text of a model file (record paths relative to the current
    /// directory).
    #[staticmethod]
    fn from_toml(text: String) -> PyResult<Model> {
        let model =
            flexrock::model::Model::from_toml_str(&text, &Overrides::default()).map_err(err)?;
        Ok(Model {
            path: None,
            text: Some(text),
            settings: Vec::new(),
            model,
        })
    }

    /// Sets a model-file key (as `--set KEY=VALUE`), checked by the rules of the file; on a bad
    /// key or value raises FlexrockError and leaves the model as it was.
    fn set(&mut self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        check_key(key).map_err(|rule| err(flexrock::Error::invalid("key", key, &rule)))?;
        // A record path typed here is relative to the current directory; the model file reads
        // it relative to its own directory (a model given as text reads from the current one).
        let here = std::env::current_dir()?;
        let model_dir = match &self.path {
            Some(path) => here.join(path.parent().unwrap_or(std::path::Path::new(""))),
            None => here.clone(),
        };
        let setting = Setting {
            key: key.to_string(),
            value: toml_value(value)?,
        }
        .rebased(&here, &model_dir);
        let mut settings = self.settings.clone();
        settings.retain(|s| s.key != key);
        settings.push(setting);
        let overrides = Overrides {
            settings: settings.clone(),
            ..Overrides::default()
        };
        let model = self.build(&overrides).map_err(err)?;
        self.settings = settings;
        self.model = model;
        Ok(())
    }

    /// The keys set with `set`, as `key=value`.
    #[getter]
    fn settings(&self) -> Vec<String> {
        self.settings
            .iter()
            .map(|s| format!("{}={}", s.key, s.value_text()))
            .collect()
    }

    /// The model file, or None for a model given as text.
    #[getter]
    fn path(&self) -> Option<PathBuf> {
        self.path.clone()
    }

    fn __repr__(&self) -> String {
        let source = match &self.path {
            Some(p) => format!("{:?}", p.display().to_string()),
            None => "(model text)".to_string(),
        };
        format!("Model({source}, settings={:?})", self.settings())
    }
}

/// The solution of `simulate`: history columns as numpy arrays, events, summary.
#[pyclass(module = "flexrock", name = "Result")]
struct SimResult {
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

fn json<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| FlexrockError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The body as understood and its derived constants: the JSON of `flexrock props --json`.
#[pyfunction]
fn props<'py>(py: Python<'py>, model: &Model) -> PyResult<Bound<'py, PyAny>> {
    json(py, &flexrock::run::properties(&model.model))
}

/// An error about a value given as a Python argument, named by the argument: `rtol (sets
/// solver.rtol) = -1: ...`; other errors as they are.
fn err_naming(e: flexrock::Error, arguments: &[(&str, &str)]) -> PyErr {
    match e {
        flexrock::Error::InvalidParameter { key, value, rule } => {
            let key = match arguments.iter().find(|(k, _)| *k == key) {
                Some((_, argument)) => format!("{argument} (sets {key})"),
                None => key,
            };
            err(flexrock::Error::InvalidParameter { key, value, rule })
        }
        other => err(other),
    }
}

/// Solves a model. `method`, `rtol`, `atol`, `duration` (s) and `output_dt` (s) replace the
/// model file's `solver.method`, `solver.rtol`, `solver.atol`, `simulation.duration` and
/// `solver.output_dt` for this run; an error about one of them names the argument.
#[pyfunction]
#[pyo3(signature = (model, method=None, rtol=None, atol=None, duration=None, output_dt=None))]
fn simulate(
    py: Python<'_>,
    model: &Model,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
    duration: Option<f64>,
    output_dt: Option<f64>,
) -> PyResult<SimResult> {
    let given = method.is_some()
        || rtol.is_some()
        || atol.is_some()
        || duration.is_some()
        || output_dt.is_some();
    let rebuilt = if given {
        let mut overrides = Overrides {
            method,
            rtol,
            atol,
            duration,
            ..model.overrides()
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
        Some(
            model
                .build(&overrides)
                .map_err(|e| err_naming(e, &arguments))?,
        )
    } else {
        None
    };
    let m = rebuilt.as_ref().unwrap_or(&model.model);
    let solution = py.detach(|| flexrock::run::simulate(m)).map_err(err)?;
    let samples = &solution.samples;
    let column = |f: fn(&flexrock::solution::Sample) -> f64| -> Py<PyAny> {
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
        use flexrock::output::{episode_fields, EpisodeField, EPISODE_COLUMNS};
        let d = PyDict::new(py);
        for (column, field) in EPISODE_COLUMNS.iter().zip(episode_fields(e, m.body.height)) {
            match field {
                EpisodeField::Count(n) => d.set_item(column, n)?,
                EpisodeField::Word(w) => d.set_item(column, w)?,
                EpisodeField::Number(x) => d.set_item(column, x)?,
            }
        }
        episodes.append(d)?;
    }
    let summary = json(py, &flexrock::run::summary(m, &solution))?.unbind();
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
fn sweep<'py>(
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

#[pymodule]
#[pyo3(name = "flexrock")]
fn flexrock_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("FlexrockError", m.py().get_type::<FlexrockError>())?;
    m.add("__version__", flexrock::run::VERSION)?;
    m.add_class::<Model>()?;
    m.add_class::<SimResult>()?;
    m.add_function(wrap_pyfunction!(props, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    Ok(())
}
