//! `Model`: a model file (or its text) with keys set on it, validated by the core's rules.

use std::path::PathBuf;

use pyo3::prelude::*;

use flexrock::model::{check_key, Overrides, Setting};

use crate::{err, FlexrockError};

/// A model: a model file (or its text) and the keys set on it with `set`, validated.
#[pyclass(module = "flexrock")]
pub(crate) struct Model {
    /// The model file, when read from one (record paths are relative to it).
    pub(crate) path: Option<PathBuf>,
    /// The text of a model given as text.
    pub(crate) text: Option<String>,
    pub(crate) settings: Vec<Setting>,
    pub(crate) model: flexrock::model::Model,
}

impl Model {
    pub(crate) fn build(&self, overrides: &Overrides) -> flexrock::Result<flexrock::model::Model> {
        match (&self.path, &self.text) {
            (Some(path), _) => flexrock::model::Model::load(path, overrides),
            (None, Some(text)) => flexrock::model::Model::from_toml_str(text, overrides),
            (None, None) => unreachable!("a model has a file or a text"),
        }
    }

    pub(crate) fn overrides(&self) -> Overrides {
        Overrides {
            settings: self.settings.clone(),
            ..Overrides::default()
        }
    }
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
