//! `Model`: a model file (or its text, or a dict of its tables) with keys set on it, validated
//! by the core's rules.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard};

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyList, PyMapping, PyString, PyTuple};

use flexrock_core::model::{
    check_key, effective_table, read_model_table, read_schema, value_in_effect, Overrides,
    RecordCache, Setting,
};

use crate::motion::{GroundMotion, Motion};
use crate::{err, FlexrockError};

/// What names a model given as a dict in messages.
const DICT: &str = "(dict)";

/// The keys of `[excitation]` that say where a record comes from: a model whose ground motion
/// was given as arrays has its record from them, and refuses these.
pub(crate) const RECORD_SOURCE_KEYS: [&str; 5] = [
    "excitation.kind",
    "excitation.path",
    "excitation.format",
    "excitation.units",
    "excitation.dt",
];

/// A model as it stands: where it comes from, the keys set on it, and the model they make.
#[derive(Clone)]
pub(crate) struct State {
    /// The model file, when read from one (record paths are relative to it).
    pub(crate) path: Option<PathBuf>,
    /// The model file's text as read when the model was made, or the text of a model given as
    /// text (or as a dict).
    pub(crate) text: String,
    pub(crate) settings: Vec<Setting>,
    /// A ground motion given as arrays, in place of the file's `[excitation]` table.
    pub(crate) ground_motion: Option<Arc<Motion>>,
    /// The model the settings make: shared with the computations under way, never changed.
    pub(crate) model: Arc<flexrock_core::model::Model>,
}

/// The model of a file (`path`, as read when the model was made: `text`) or of a text, with
/// `ground_motion` in place of its `[excitation]` when given, and `overrides`.
fn build(
    path: Option<&Path>,
    text: &str,
    ground_motion: Option<&Motion>,
    overrides: &Overrides,
) -> flexrock_core::Result<flexrock_core::model::Model> {
    let source = path.unwrap_or(Path::new(flexrock_core::model::MODEL_TEXT));
    if let Some(path) = path {
        file_unchanged(path, text)?;
    }
    let Some(motion) = ground_motion else {
        return match path {
            Some(path) => flexrock_core::model::Model::load(path, overrides),
            None => flexrock_core::model::Model::from_toml_str(text, overrides),
        };
    };
    let mut table = parse_table(text, source)?;
    with_motion(&mut table, motion);
    let file = read_schema(&table, &overrides.settings, source)?;
    let records = RecordCache::default();
    records.insert(
        &Path::new(".").join(&motion.record.source),
        motion.record.clone(),
    );
    flexrock_core::model::Model::from_file_cached(file, overrides, Path::new("."), &records)
}

/// Refuses a model file whose text is no longer `text`, what the model was made from: the
/// model reads its file again at every change (and when unpickled), and would otherwise
/// silently become another.
fn file_unchanged(path: &Path, text: &str) -> flexrock_core::Result<()> {
    let (now, _) = read_model_table(path)?;
    if now != text {
        return Err(flexrock_core::Error::invalid(
            "model file",
            path.display().to_string(),
            "has changed since the model was read from it: read it again with Model.from_file",
        ));
    }
    Ok(())
}

/// A model file's text as a table, `source` naming it in messages.
fn parse_table(text: &str, source: &Path) -> flexrock_core::Result<toml::Table> {
    toml::from_str(text).map_err(|e| flexrock_core::Error::ParseModel {
        path: source.to_path_buf(),
        message: e.to_string().trim_end().to_string(),
    })
}

impl State {
    /// The model of this state's file or text and ground motion, with `overrides`.
    pub(crate) fn build(
        &self,
        overrides: &Overrides,
    ) -> flexrock_core::Result<flexrock_core::model::Model> {
        build(
            self.path.as_deref(),
            &self.text,
            self.ground_motion.as_deref(),
            overrides,
        )
    }

    /// The model file's table as written (without the settings).
    pub(crate) fn base_table(&self) -> flexrock_core::Result<toml::Table> {
        parse_table(&self.text, &self.source())
    }

    /// The model file's table with the ground motion's `[excitation]` in place of its own.
    pub(crate) fn table_with_motion(&self) -> flexrock_core::Result<toml::Table> {
        let mut table = self.base_table()?;
        if let Some(motion) = &self.ground_motion {
            with_motion(&mut table, motion);
        }
        Ok(table)
    }

    /// The model file, or `(model text)`, for messages.
    pub(crate) fn source(&self) -> PathBuf {
        self.path
            .clone()
            .unwrap_or_else(|| PathBuf::from(flexrock_core::model::MODEL_TEXT))
    }

    /// The table in effect: the file's, with the settings applied (and the ground motion's
    /// `[excitation]` in place of the file's), its record path relative to the current
    /// directory (as `from_toml` and `from_dict` read it).
    fn effective(&self) -> PyResult<toml::Table> {
        let base = self.table_with_motion().map_err(err)?;
        let mut table = effective_table(&base, &self.settings, &self.source()).map_err(err)?;
        if let (Some(path), None) = (&self.path, &self.ground_motion) {
            let here = std::env::current_dir()?;
            let model_dir = flexrock_core::model::model_dir(&here, Some(path));
            if let Some(excitation) = table.get_mut("excitation").and_then(|e| e.as_table_mut()) {
                if let Some(record) = excitation.get("path").cloned() {
                    let rebased = Setting {
                        key: "excitation.path".to_owned(),
                        value: record,
                    }
                    .rebased(&model_dir, &here);
                    excitation.insert("path".to_owned(), rebased.value);
                }
            }
        }
        Ok(table)
    }

    /// The table of the model file `to_dict` and `to_toml` give: [`State::effective`], and for
    /// a model whose ground motion was given as arrays, an `[excitation]` that reads it from
    /// `record_path` (a CSV record file that must hold exactly its samples).
    fn model_file(&self, what: &str, record_path: Option<PathBuf>) -> PyResult<toml::Table> {
        let Some(motion) = &self.ground_motion else {
            if let Some(path) = record_path {
                return Err(FlexrockError::new_err(format!(
                    "record_path = {}: names the record file of a ground motion given as \
                     arrays; this model reads its own record, and Model.{what}() names it",
                    path.display()
                )));
            }
            return self.effective();
        };
        let Some(record_path) = record_path else {
            return Err(FlexrockError::new_err(format!(
                "Model.{what}(): the model's ground motion ({}) was given as arrays, and a model \
                 file reads its record from a file: write it with \
                 model.ground_motion.to_csv(PATH), then call model.{what}(record_path=PATH) \
                 (or pickle the model)",
                motion.record.source
            )));
        };
        motion.check_record_file(&record_path)?;
        let mut base = self.base_table().map_err(err)?;
        let excitation = motion.record_file_table(&record_path.to_string_lossy());
        base.insert("excitation".to_owned(), toml::Value::Table(excitation));
        effective_table(&base, &self.settings, &self.source()).map_err(err)
    }

    pub(crate) fn overrides(&self) -> Overrides {
        Overrides {
            settings: self.settings.clone(),
            ..Overrides::default()
        }
    }

    /// This state with `changes` set (each replacing an earlier setting of its key), checked
    /// together: the model they make, or the first error, naming its key.
    fn with(&self, changes: Vec<Setting>) -> PyResult<State> {
        let mut settings = self.settings.clone();
        for setting in changes {
            settings.retain(|s| s.key != setting.key);
            settings.push(setting);
        }
        let next = State {
            settings,
            ..self.clone()
        };
        let model = next.build(&next.overrides()).map_err(err)?;
        Ok(State {
            model: Arc::new(model),
            ..next
        })
    }
}

/// A model: a model file (or its text, or a dict of its tables) and the keys set on it,
/// validated.
#[pyclass(module = "flexrock", frozen)]
pub(crate) struct Model {
    state: Mutex<State>,
}

impl Model {
    fn new(state: State) -> Model {
        Model {
            state: Mutex::new(state),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // A panic cannot leave the state half-changed: it is replaced whole.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The model as it stands now: what a computation works on, whatever is set meanwhile.
    pub(crate) fn state(&self) -> State {
        self.lock().clone()
    }

    /// Sets `changes` (keys and their values), checked together; on an error the model stays
    /// as it was.
    fn set_all(&self, changes: Vec<(String, toml::Value)>) -> PyResult<()> {
        let here = std::env::current_dir()?;
        let mut state = self.lock();
        let mut settings = Vec::with_capacity(changes.len());
        for (key, value) in changes {
            check_key(&key)
                .map_err(|rule| err(flexrock_core::Error::invalid("key", &key, &rule)))?;
            if let (Some(motion), true) =
                (&state.ground_motion, RECORD_SOURCE_KEYS.contains(&&*key))
            {
                return Err(FlexrockError::new_err(format!(
                    "{key} = {}: the model's ground motion ({}) was given as arrays, and says \
                     where its record comes from; excitation.scale, start, end and tail may be \
                     set on it. For another record, use with_ground_motion, or a model without \
                     arrays",
                    flexrock_core::model::value_text(&value),
                    motion.record.source
                )));
            }
            // A record path typed here is relative to the current directory; the model file
            // reads it relative to its own directory (a model given as text reads from the
            // current one).
            settings.push(Setting { key, value }.typed_in(&here, state.path.as_deref()));
        }
        *state = state.with(settings)?;
        Ok(())
    }
}

/// The model file's table under a ground motion given as arrays: its `[excitation]` replaced,
/// and its `simulation.duration` dropped, which was the file's excitation's: the motion runs
/// for its own length (and its tail) unless a duration is set on the model.
fn with_motion(table: &mut toml::Table, motion: &Motion) {
    table.insert("excitation".to_owned(), motion.excitation_table());
    if let Some(simulation) = table.get_mut("simulation").and_then(|s| s.as_table_mut()) {
        simulation.remove("duration");
    }
}

/// A model-file value as a Python value.
pub(crate) fn py_value<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    use pyo3::IntoPyObjectExt;
    Ok(match value {
        toml::Value::Boolean(b) => b.into_bound_py_any(py)?,
        toml::Value::Integer(i) => i.into_bound_py_any(py)?,
        toml::Value::Float(x) => x.into_bound_py_any(py)?,
        toml::Value::String(s) => s.into_bound_py_any(py)?,
        toml::Value::Table(t) => {
            let d = PyDict::new(py);
            for (k, v) in t {
                d.set_item(k, py_value(py, v)?)?;
            }
            d.into_any()
        }
        toml::Value::Array(a) => {
            let items = a
                .iter()
                .map(|v| py_value(py, v))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any()
        }
        toml::Value::Datetime(d) => d.to_string().into_bound_py_any(py)?,
    })
}

/// The place `["section"]["name"]` in a dict of the key `section.name`.
fn dict_path(key: &str) -> String {
    key.split('.').map(|part| format!("[{part:?}]")).collect()
}

/// A nested dict of the model file's tables as a TOML table: every key a str, every section a
/// dict, every value a bool, a number or a str (named `d["section"]["name"]` in errors).
fn toml_table(d: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (section, values) in d.iter() {
        let section = key_text(&section, "d")?;
        let at = format!("d{}", dict_path(&section));
        let values = values.cast::<PyDict>().map_err(|_| {
            PyTypeError::new_err(format!(
                "{at} = {}: must be a dict of the keys of the model file's [{section}] table, \
                 e.g. {{\"height\": 4.0}}",
                short_repr(values.as_any())
            ))
        })?;
        let nested = section == "excitation";
        table.insert(
            section,
            toml::Value::Table(dict_values(values, &at, nested)?),
        );
    }
    Ok(table)
}

/// The values of one table's dict (`at` names it); with `nested`, its `vertical` key may be a
/// dict of its own: the floor's vertical motion, `[excitation.vertical]`.
fn dict_values(values: &Bound<'_, PyDict>, at: &str, nested: bool) -> PyResult<toml::Table> {
    let mut inner = toml::Table::new();
    for (key, value) in values.iter() {
        let key = key_text(&key, at)?;
        let name = format!("{at}{}", dict_path(&key));
        let item = match value.cast::<PyDict>() {
            Ok(vertical) if nested && key == "vertical" => {
                toml::Value::Table(dict_values(vertical, &name, false)?)
            }
            _ => toml_value(&value, &name)?,
        };
        inner.insert(key, item);
    }
    Ok(inner)
}

/// A key of a dict, which must be a str (`at` names the dict).
fn key_text(key: &Bound<'_, PyAny>, at: &str) -> PyResult<String> {
    key.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "{at}: every key must be a str, not {}",
            short_repr(key)
        ))
    })
}

/// `repr(value)`, shortened to 80 characters.
pub(crate) fn short_repr(value: &Bound<'_, PyAny>) -> String {
    let text = value
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "(no repr)".into());
    if text.chars().count() <= 80 {
        return text;
    }
    let head: String = text.chars().take(77).collect();
    format!("{head}...")
}

/// A Python value as a model-file value, `name` naming it in errors: a bool (Python's or
/// numpy's), a str, an int (exact within 64 bits; beyond, the nearest float, if one holds it), a
/// float (or anything numpy or Python turns into one). Anything else is a TypeError.
pub(crate) fn toml_value(value: &Bound<'_, PyAny>, name: &str) -> PyResult<toml::Value> {
    if let Ok(b) = value.extract::<bool>() {
        return Ok(toml::Value::Boolean(b));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() || value.hasattr("__index__")? {
        if let Ok(i) = value.extract::<i64>() {
            return Ok(toml::Value::Integer(i));
        }
        // Beyond 64 bits: the nearest float, if there is one.
        return match value.extract::<f64>() {
            Ok(x) if x.is_finite() => Ok(toml::Value::Float(x)),
            _ => {
                let digits = value.str().map_or(0, |s| s.to_string().len());
                Err(FlexrockError::new_err(format!(
                    "{name} = an int of {digits} digits: beyond the largest number a model-file \
                     value holds, {:e}",
                    f64::MAX
                )))
            }
        };
    }
    value.extract::<f64>().map(toml::Value::Float).map_err(|_| {
        PyTypeError::new_err(format!(
            "{name} = {}: a model-file value must be a number, a str or a bool, not {}",
            short_repr(value),
            value
                .get_type()
                .name()
                .map_or_else(|_| "this type".into(), |n| n.to_string())
        ))
    })
}

/// The settings of a `set` or an `update`: `(key, value)` pairs, keys str.
fn changes(
    pairs: Vec<(Bound<'_, PyAny>, Bound<'_, PyAny>)>,
) -> PyResult<Vec<(String, toml::Value)>> {
    pairs
        .into_iter()
        .map(|(key, value)| {
            let key: String = key.extract().map_err(|_| {
                PyTypeError::new_err(format!("a key must be a str, not {}", short_repr(&key)))
            })?;
            let value = toml_value(&value, &key)?;
            Ok((key, value))
        })
        .collect()
}

/// A setting as pickled: `(key, value)`.
fn setting_state<'py>(py: Python<'py>, s: &Setting) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyTuple::new(
        py,
        [
            s.key.clone().into_pyobject(py)?.into_any(),
            py_value(py, &s.value)?,
        ],
    )?
    .into_any())
}

#[pymethods]
impl Model {
    /// Reads and validates a model file; its record paths are relative to its directory.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Model> {
        let (text, _) = read_model_table(&path).map_err(err)?;
        let model = flexrock_core::model::Model::load(&path, &Overrides::default()).map_err(err)?;
        Ok(Model::new(State {
            path: Some(path),
            text,
            settings: Vec::new(),
            ground_motion: None,
            model: Arc::new(model),
        }))
    }

    /// Parses and validates the text of a model file (record paths relative to the current
    /// directory).
    #[staticmethod]
    fn from_toml(text: String) -> PyResult<Model> {
        let limit = flexrock_core::model::MAX_MODEL_FILE_BYTES;
        if text.len() as u64 > limit {
            return Err(FlexrockError::new_err(format!(
                "Model.from_toml: the text has {} bytes, beyond the {limit} bytes a model file \
                 may have",
                text.len()
            )));
        }
        let model = flexrock_core::model::Model::from_toml_str(&text, &Overrides::default())
            .map_err(err)?;
        Ok(Model::new(State {
            path: None,
            text,
            settings: Vec::new(),
            ground_motion: None,
            model: Arc::new(model),
        }))
    }

    /// Reads and validates a model given as a nested dict of the model file's tables.
    ///
    /// Parameters
    /// ----------
    /// d : dict
    ///     ``{"body": {...}, "excitation": {...}, "simulation": {...}, "solver": {...}}``, values
    ///     bool, int, float or str; record paths relative to the current directory.
    ///
    /// Returns
    /// -------
    /// Model
    ///
    /// Raises
    /// ------
    /// FlexrockError
    ///     A key the model file does not know or a value that breaks its rules, named by its
    ///     place in the dict (``d["body"]["height"] = -1: ...``).
    /// TypeError
    ///     A section that is not a dict, a key that is not a str, a value that is not a bool, a
    ///     number or a str (named as above).
    ///
    /// Examples
    /// --------
    /// >>> m = flexrock.Model.from_dict({"body": {...}, "excitation": {"kind": "free"}})
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Model> {
        let table = toml_table(d)?;
        let model = read_schema(&table, &[], Path::new(DICT))
            .and_then(|file| {
                flexrock_core::model::Model::from_file(file, &Overrides::default(), Path::new("."))
            })
            .map_err(|e| FlexrockError::new_err(in_dict(e, &table)))?;
        let text = toml::to_string(&table).map_err(|e| FlexrockError::new_err(e.to_string()))?;
        Ok(Model::new(State {
            path: None,
            text,
            settings: Vec::new(),
            ground_motion: None,
            model: Arc::new(model),
        }))
    }

    /// The value of a model-file key in effect.
    ///
    /// Parameters
    /// ----------
    /// key : str
    ///     ``section.name``, e.g. ``"excitation.amplitude"``.
    ///
    /// Returns
    /// -------
    /// bool, int, float, str or None
    ///     The value set with `set`, else the file's, else the default the solver uses for a key
    ///     the file leaves out, else None. A record path is relative to the current directory.
    ///
    /// Raises
    /// ------
    /// FlexrockError
    ///     A key the model file does not know, named, with the closest known key.
    ///
    /// Examples
    /// --------
    /// >>> model.get("body.gravity")
    /// 9.81
    fn get<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match value_in_effect(&self.state().effective()?, key).map_err(err)? {
            Some(value) => py_value(py, &value),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// The model file's tables with the settings applied, as a nested dict.
    ///
    /// Parameters
    /// ----------
    /// record_path : str or path-like, optional
    ///     For a model whose ground motion was given as arrays: the CSV record file that holds
    ///     its samples, as ``model.ground_motion.to_csv(record_path)`` writes it (checked: it
    ///     must hold exactly those samples). Relative to the current directory.
    ///
    /// Returns
    /// -------
    /// dict
    ///     ``Model.from_dict`` of it solves to the same numbers; record paths are relative to
    ///     the current directory.
    ///
    /// Raises
    /// ------
    /// FlexrockError
    ///     For a model whose ground motion was given as arrays, without ``record_path`` or with
    ///     one that does not hold its samples.
    ///
    /// Examples
    /// --------
    /// >>> flexrock.Model.from_dict(model.to_dict())
    #[pyo3(signature = (record_path=None))]
    fn to_dict<'py>(
        &self,
        py: Python<'py>,
        record_path: Option<PathBuf>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let table = self.state().model_file("to_dict", record_path)?;
        py_value(py, &toml::Value::Table(table))
    }

    /// The model file with the settings applied, as TOML text.
    ///
    /// Parameters
    /// ----------
    /// record_path : str or path-like, optional
    ///     For a model whose ground motion was given as arrays: the CSV record file that holds
    ///     its samples, as ``model.ground_motion.to_csv(record_path)`` writes it (checked).
    ///
    /// Returns
    /// -------
    /// str
    ///     ``Model.from_toml`` of it solves to the same numbers; record paths are relative to
    ///     the current directory.
    ///
    /// Raises
    /// ------
    /// FlexrockError
    ///     For a model whose ground motion was given as arrays, without ``record_path`` or with
    ///     one that does not hold its samples.
    ///
    /// Examples
    /// --------
    /// >>> pathlib.Path("mine.toml").write_text(model.to_toml())
    #[pyo3(signature = (record_path=None))]
    fn to_toml(&self, record_path: Option<PathBuf>) -> PyResult<String> {
        let table = self.state().model_file("to_toml", record_path)?;
        toml::to_string(&table).map_err(|e| FlexrockError::new_err(e.to_string()))
    }

    /// A new model whose ``[excitation]`` is a ground motion given as arrays.
    ///
    /// Parameters
    /// ----------
    /// ground_motion : GroundMotion
    ///     The record; the model's other tables and settings stay, its ``excitation.*``
    ///     settings are dropped. ``excitation.scale``, ``start``, ``end`` and ``tail`` may then
    ///     be set as for a record file.
    ///
    /// Returns
    /// -------
    /// Model
    ///
    /// Raises
    /// ------
    /// FlexrockError
    ///     A motion the model refuses (e.g. a peak beyond 20 g).
    ///
    /// Examples
    /// --------
    /// >>> shaken = model.with_ground_motion(flexrock.read_record("validation/records/elCentro.AT2"))
    fn with_ground_motion(&self, ground_motion: &GroundMotion) -> PyResult<Model> {
        let state = self.state();
        let settings: Vec<Setting> = state
            .settings
            .iter()
            .filter(|s| !s.key.starts_with("excitation."))
            .cloned()
            .collect();
        let next = State {
            settings,
            ground_motion: Some(Arc::clone(&ground_motion.motion)),
            ..state
        };
        let model = next.build(&next.overrides()).map_err(err)?;
        Ok(Model::new(State {
            model: Arc::new(model),
            ..next
        }))
    }

    /// The ground motion given as arrays, or None for the file's `[excitation]`.
    #[getter]
    fn ground_motion(&self) -> Option<GroundMotion> {
        self.state()
            .ground_motion
            .map(|motion| GroundMotion { motion })
    }

    /// Sets a model-file key, checked by the rules of the file; on a bad key or value raises
    /// FlexrockError naming the key and leaves the model as it was. A record path is relative to
    /// the current directory.
    fn set(&self, key: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_all(changes(vec![(key.clone(), value.clone())])?)
    }

    /// Sets several model-file keys at once, checked together (so that keys that only make
    /// sense together, such as a record file and its units, can be changed); on an error the
    /// model stays as it was.
    fn update(&self, settings: &Bound<'_, PyAny>) -> PyResult<()> {
        let mapping = settings.cast::<PyMapping>().map_err(|_| {
            PyTypeError::new_err(format!(
                "Model.update: takes a dict of keys and values, e.g. \
                 {{\"excitation.amplitude\": 3.0}}, not {}",
                short_repr(settings)
            ))
        })?;
        let pairs = mapping
            .items()?
            .iter()
            .map(|item| item.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>())
            .collect::<PyResult<Vec<_>>>()?;
        self.set_all(changes(pairs)?)
    }

    /// The keys set with `set`, as `key=value`.
    #[getter]
    fn settings(&self) -> Vec<String> {
        self.state()
            .settings
            .iter()
            .map(|s| format!("{}={}", s.key, s.value_text()))
            .collect()
    }

    /// The model file, or None for a model given as text.
    #[getter]
    fn path(&self) -> Option<PathBuf> {
        self.state().path
    }

    fn __repr__(&self) -> String {
        let state = self.state();
        let source = match &state.path {
            Some(p) => format!("{:?}", p.display().to_string()),
            None => "(model text)".to_string(),
        };
        let motion = match &state.ground_motion {
            Some(m) => format!(", ground_motion={:?}", m.record.source),
            None => String::new(),
        };
        format!("Model({source}, settings={:?}{motion})", self.settings())
    }

    /// A model of its own with the same file, text, settings and ground motion.
    fn __copy__(&self) -> Model {
        Model::new(self.state())
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Model {
        Model::new(self.state())
    }

    /// Pickled as its file's name and text (or its text), its settings and its ground motion;
    /// unpickled, it reads its file again and refuses one that has changed.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let state = self.state();
        let d = PyDict::new(py);
        d.set_item("path", &state.path)?;
        d.set_item("text", &state.text)?;
        let settings = state
            .settings
            .iter()
            .map(|s| setting_state(py, s))
            .collect::<PyResult<Vec<_>>>()?;
        d.set_item("settings", settings)?;
        d.set_item(
            "ground_motion",
            state.ground_motion.map(|motion| GroundMotion { motion }),
        )?;
        let restore = py
            .import("flexrock._native")?
            .getattr("_model_from_state")?;
        Ok(PyTuple::new(py, [restore, PyTuple::new(py, [d])?.into_any()])?.into_any())
    }
}

/// The model pickled by `Model.__reduce__`.
#[pyfunction]
pub(crate) fn _model_from_state(state: &Bound<'_, PyDict>) -> PyResult<Model> {
    let item = |name: &str| -> PyResult<Bound<'_, PyAny>> {
        state
            .get_item(name)?
            .ok_or_else(|| FlexrockError::new_err(format!("a pickled Model without {name:?}")))
    };
    let settings = item("settings")?
        .try_iter()?
        .map(|pair| {
            let (key, value): (String, Bound<'_, PyAny>) = pair?.extract()?;
            let value = toml_value(&value, &key)?;
            Ok(Setting { key, value })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let ground_motion: Option<PyRef<'_, GroundMotion>> = item("ground_motion")?.extract()?;
    let path: Option<PathBuf> = item("path")?.extract()?;
    let text: String = item("text")?.extract()?;
    let ground_motion = ground_motion.map(|g| Arc::clone(&g.motion));
    let overrides = Overrides {
        settings: settings.clone(),
        ..Overrides::default()
    };
    let model = build(path.as_deref(), &text, ground_motion.as_deref(), &overrides).map_err(err)?;
    Ok(Model::new(State {
        path,
        text,
        settings,
        ground_motion,
        model: Arc::new(model),
    }))
}

/// An error of a model given as a dict, its key named by its place in the dict
/// (`d["body"]["height"] = -1: ...`) when the key is one of the dict's.
fn in_dict(e: flexrock_core::Error, table: &toml::Table) -> String {
    let leaf = |key: &str| -> Option<&toml::Value> {
        let (section, name) = key.split_once('.')?;
        table.get(section)?.as_table()?.get(name)
    };
    match e {
        flexrock_core::Error::InvalidParameter { key, value, rule } if leaf(&key).is_some() => {
            format!("d{} = {value}: {rule}", dict_path(&key))
        }
        flexrock_core::Error::ParseModel { message, .. } => {
            // The schema names the key last, in backticks: "... in `body.height`".
            let key = message
                .rsplit_once(" in `")
                .and_then(|(_, rest)| rest.split_once('`'))
                .map(|(key, _)| key.to_owned());
            match key {
                Some(key) if leaf(&key).is_some() => {
                    let value = leaf(&key).map(flexrock_core::model::value_text);
                    let rule = message.replacen(&format!(" in `{key}`"), "", 1);
                    format!(
                        "d{} = {}: {rule}",
                        dict_path(&key),
                        value.unwrap_or_default()
                    )
                }
                Some(section) if table.contains_key(&section) => {
                    let rule = message.replacen(&format!(" in `{section}`"), "", 1);
                    format!("d{}: {rule}", dict_path(&section))
                }
                _ => format!("d: {message}"),
            }
        }
        other => other.to_string(),
    }
}
