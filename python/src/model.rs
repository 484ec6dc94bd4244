//! `Model`: a model file (or its text) with keys set on it, validated by the core's rules.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use flexrock_core::model::{
    check_key, effective_table, read_model_table, read_schema, value_in_effect, Overrides,
    RecordCache, Setting,
};

use crate::motion::{GroundMotion, Motion};
use crate::{err, FlexrockError};

/// A model: a model file (or its text) and the keys set on it with `set`, validated.
#[pyclass(module = "flexrock")]
pub(crate) struct Model {
    /// The model file, when read from one (record paths are relative to it).
    pub(crate) path: Option<PathBuf>,
    /// The text of a model given as text.
    pub(crate) text: Option<String>,
    pub(crate) settings: Vec<Setting>,
    /// A ground motion given as arrays, in place of the file's `[excitation]` table.
    pub(crate) ground_motion: Option<Arc<Motion>>,
    pub(crate) model: flexrock_core::model::Model,
}

impl Model {
    pub(crate) fn build(
        &self,
        overrides: &Overrides,
    ) -> flexrock_core::Result<flexrock_core::model::Model> {
        if let Some(motion) = &self.ground_motion {
            let mut table = self.base_table()?;
            with_motion(&mut table, motion);
            let file = read_schema(&table, &overrides.settings, &self.source())?;
            let records = RecordCache::default();
            records.insert(
                &Path::new(".").join(&motion.record.source),
                motion.record.clone(),
            );
            return flexrock_core::model::Model::from_file_cached(
                file,
                overrides,
                Path::new("."),
                &records,
            );
        }
        match (&self.path, &self.text) {
            (Some(path), _) => flexrock_core::model::Model::load(path, overrides),
            (None, Some(text)) => flexrock_core::model::Model::from_toml_str(text, overrides),
            (None, None) => unreachable!("a model has a file or a text"),
        }
    }

    /// The model file's table as written (without the settings).
    fn base_table(&self) -> flexrock_core::Result<toml::Table> {
        match (&self.path, &self.text) {
            (Some(path), _) => Ok(read_model_table(path)?.1),
            (None, text) => toml::from_str(text.as_deref().unwrap_or_default()).map_err(|e| {
                flexrock_core::Error::ParseModel {
                    path: self.source(),
                    message: e.to_string().trim_end().to_string(),
                }
            }),
        }
    }

    /// The model file, or `(model text)`, for messages.
    fn source(&self) -> PathBuf {
        self.path
            .clone()
            .unwrap_or_else(|| PathBuf::from("(model text)"))
    }

    /// The table in effect: the file's, with the settings applied (and the ground motion's
    /// `[excitation]` in place of the file's), its record path relative to the current
    /// directory (as `from_toml` and `from_dict` read it).
    fn effective(&self) -> PyResult<toml::Table> {
        let mut base = self.base_table().map_err(err)?;
        if let Some(motion) = &self.ground_motion {
            with_motion(&mut base, motion);
        }
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

    /// Refuses to write a model whose ground motion was given as arrays: it has no file.
    fn has_a_file(&self, what: &str) -> PyResult<()> {
        match &self.ground_motion {
            Some(motion) => Err(FlexrockError::new_err(format!(
                "Model.{what}(): the model's ground motion ({}) was given as arrays and has no \
                 record file to name; write its samples to a CSV record file and set \
                 excitation.path to it",
                motion.record.source
            ))),
            None => Ok(()),
        }
    }

    pub(crate) fn overrides(&self) -> Overrides {
        Overrides {
            settings: self.settings.clone(),
            ..Overrides::default()
        }
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
            pyo3::types::PyList::new(py, items)?.into_any()
        }
        toml::Value::Datetime(d) => d.to_string().into_bound_py_any(py)?,
    })
}

/// A nested dict (tables as the model file's) as a TOML table; `at` names it in messages.
fn toml_table(d: &Bound<'_, PyDict>, at: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in d.iter() {
        let key: String = key.extract().map_err(|_| {
            FlexrockError::new_err(format!("d{at}: every key must be a str, not {key:?}"))
        })?;
        let here = format!("{at}[{key:?}]");
        let value = match value.cast::<PyDict>() {
            Ok(inner) => toml::Value::Table(toml_table(inner, &here)?),
            Err(_) => toml_value(&value)
                .map_err(|e| FlexrockError::new_err(format!("d{here}: {}", e.value(d.py()))))?,
        };
        table.insert(key, value);
    }
    Ok(table)
}

/// A Python value as a model-file value: bool, int, float or str.
pub(crate) fn toml_value(value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
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
    /// Reads and validates a model file; its record paths are relative to its directory.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Model> {
        let model = flexrock_core::model::Model::load(&path, &Overrides::default()).map_err(err)?;
        Ok(Model {
            path: Some(path),
            text: None,
            settings: Vec::new(),
            ground_motion: None,
            model,
        })
    }

    /// Parses and validates the text of a model file (record paths relative to the current
    /// directory).
    #[staticmethod]
    fn from_toml(text: String) -> PyResult<Model> {
        let model = flexrock_core::model::Model::from_toml_str(&text, &Overrides::default())
            .map_err(err)?;
        Ok(Model {
            path: None,
            text: Some(text),
            settings: Vec::new(),
            ground_motion: None,
            model,
        })
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
    ///     A key the model file does not know or a value that breaks its rules (named).
    ///
    /// Examples
    /// --------
    /// >>> m = flexrock.Model.from_dict({"body": {...}, "excitation": {"kind": "free"}})
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Model> {
        let table = toml_table(d, "")?;
        let text = toml::to_string(&table).map_err(|e| FlexrockError::new_err(e.to_string()))?;
        Model::from_toml(text)
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
        match value_in_effect(&self.effective()?, key).map_err(err)? {
            Some(value) => py_value(py, &value),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// The model file's tables with the settings applied, as a nested dict.
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
    ///     For a model whose ground motion was given as arrays (it has no record file).
    ///
    /// Examples
    /// --------
    /// >>> flexrock.Model.from_dict(model.to_dict())
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.has_a_file("to_dict")?;
        py_value(py, &toml::Value::Table(self.effective()?))
    }

    /// The model file with the settings applied, as TOML text.
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
    ///     For a model whose ground motion was given as arrays (it has no record file).
    ///
    /// Examples
    /// --------
    /// >>> pathlib.Path("mine.toml").write_text(model.to_toml())
    fn to_toml(&self) -> PyResult<String> {
        self.has_a_file("to_toml")?;
        toml::to_string(&self.effective()?).map_err(|e| FlexrockError::new_err(e.to_string()))
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
        let settings: Vec<Setting> = self
            .settings
            .iter()
            .filter(|s| !s.key.starts_with("excitation."))
            .cloned()
            .collect();
        let mut out = Model {
            path: self.path.clone(),
            text: self.text.clone(),
            settings,
            ground_motion: Some(Arc::clone(&ground_motion.motion)),
            model: self.build(&Overrides::default()).map_err(err)?,
        };
        out.model = out.build(&out.overrides()).map_err(err)?;
        Ok(out)
    }

    /// The ground motion given as arrays, or None for the file's `[excitation]`.
    #[getter]
    fn ground_motion(&self) -> Option<GroundMotion> {
        self.ground_motion.as_ref().map(|m| GroundMotion {
            motion: Arc::clone(m),
        })
    }

    /// Sets a model-file key, checked by the rules of the file; on a bad key or value raises
    /// FlexrockError naming the key and leaves the model as it was. A record path is relative to
    /// the current directory.
    fn set(&mut self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        check_key(key).map_err(|rule| err(flexrock_core::Error::invalid("key", key, &rule)))?;
        // A record path typed here is relative to the current directory; the model file reads
        // it relative to its own directory (a model given as text reads from the current one).
        let here = std::env::current_dir()?;
        let setting = Setting {
            key: key.to_string(),
            value: toml_value(value)?,
        }
        .typed_in(&here, self.path.as_deref());
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
        let motion = match &self.ground_motion {
            Some(m) => format!(", ground_motion={:?}", m.record.source),
            None => String::new(),
        };
        format!("Model({source}, settings={:?}{motion})", self.settings())
    }
}
