//! `GroundMotion`: a floor acceleration record given as numpy arrays (or read from a record
//! file by `read_record`), checked by the rules and limits of a record file; a model solved
//! under it (`Model.with_ground_motion`) takes it through the core's recorded motion, exactly as
//! it takes a record file with the same samples.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::PyArray1;
use pyo3::prelude::*;

use flexrock_core::excitation::RecordedMotion;
use flexrock_core::record::{
    acceleration_unit, dt_from_times, read_record as read_record_file, record_from_samples,
    resolve_units, Record, RecordFormat,
};

use crate::FlexrockError;

/// The samples of a ground motion, as given (in `units`), with the factor to m/s^2.
#[derive(Debug)]
pub(crate) struct Motion {
    /// Samples in `units`, `source` the name it goes by (the file, or `arrays`).
    pub(crate) record: Record,
    pub(crate) units: &'static str,
    factor: f64,
}

impl Motion {
    /// The motion these samples are, in m/s^2, with the record file's metadata.
    pub(crate) fn recorded(&self) -> RecordedMotion {
        RecordedMotion::new(
            self.record.source.clone(),
            self.record.dt,
            self.record.values.iter().map(|v| v * self.factor).collect(),
        )
        .with_meta(self.record.meta.clone())
    }

    /// The `[excitation]` table of a model under this motion (the record taken from memory).
    pub(crate) fn excitation_table(&self) -> toml::Value {
        let mut t = toml::Table::new();
        t.insert("kind".into(), toml::Value::String("record".into()));
        t.insert(
            "path".into(),
            toml::Value::String(self.record.source.clone()),
        );
        t.insert("units".into(), toml::Value::String(self.units.into()));
        toml::Value::Table(t)
    }
}

fn invalid(e: impl std::fmt::Display) -> PyErr {
    FlexrockError::new_err(e.to_string())
}

/// A 1-D float64 copy of `value` (any sequence of numbers), named `name` in errors.
fn floats(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let numpy = value.py().import("numpy")?;
    let array = numpy
        .call_method1("asarray", (value, "float64"))
        .map_err(|e| {
            FlexrockError::new_err(format!(
                "{name}: must be a 1-D sequence of numbers ({})",
                e.value(value.py())
            ))
        })?;
    let ndim: usize = array.getattr("ndim")?.extract()?;
    if ndim != 1 {
        return Err(FlexrockError::new_err(format!(
            "{name}: must be 1-D (one sample per time), has shape {}",
            array.getattr("shape")?.repr()?
        )));
    }
    array.call_method0("tolist")?.extract()
}

fn unit(units: &str) -> PyResult<(&'static str, f64)> {
    acceleration_unit("units", units).map_err(invalid)
}

/// A floor acceleration record sampled at a uniform interval.
#[pyclass(module = "flexrock", name = "GroundMotion", frozen)]
pub(crate) struct GroundMotion {
    pub(crate) motion: Arc<Motion>,
}

#[pymethods]
impl GroundMotion {
    #[new]
    #[pyo3(signature = (acceleration, dt=None, *, time=None, units, source=None))]
    fn new(
        acceleration: &Bound<'_, PyAny>,
        dt: Option<f64>,
        time: Option<&Bound<'_, PyAny>>,
        units: &str,
        source: Option<String>,
    ) -> PyResult<GroundMotion> {
        let (units, factor) = unit(units)?;
        let values = floats(acceleration, "acceleration")?;
        let dt =
            match (dt, time) {
                (Some(dt), None) => dt,
                (None, Some(time)) => {
                    let times = floats(time, "time")?;
                    if times.len() != values.len() {
                        return Err(FlexrockError::new_err(format!(
                            "time has {} values and acceleration {}: give one time per sample",
                            times.len(),
                            values.len()
                        )));
                    }
                    dt_from_times("time", &times).map_err(invalid)?
                }
                _ => return Err(FlexrockError::new_err(
                    "give the sampling interval either as dt (s) or as time (s, one per sample), \
                     not both and not neither",
                )),
            };
        let source = source.unwrap_or_else(|| "arrays".to_owned());
        let record =
            record_from_samples(&source, "dt", dt, "acceleration", values).map_err(invalid)?;
        Ok(GroundMotion {
            motion: Arc::new(Motion {
                record,
                units,
                factor,
            }),
        })
    }

    /// Sampling interval, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.motion.record.dt
    }

    /// The samples in m/s^2 (the given values times the units' factor), a float64 array.
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f = self.motion.factor;
        PyArray1::from_iter(py, self.motion.record.values.iter().map(|v| v * f))
    }

    /// The sample times k dt, s, a float64 array.
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let dt = self.motion.record.dt;
        PyArray1::from_iter(
            py,
            (0..self.motion.record.values.len()).map(|k| k as f64 * dt),
        )
    }

    /// The units the samples were given in: "g", "m/s2" or "cm/s2".
    #[getter]
    fn units(&self) -> &'static str {
        self.motion.units
    }

    /// Where the samples came from: the record file, or the `source` given (default "arrays").
    #[getter]
    fn source(&self) -> String {
        self.motion.record.source.clone()
    }

    /// Time of the last sample, (n - 1) dt, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.motion.record.duration()
    }

    /// What the record file says about itself: a dict of ``format`` and the ``units`` it
    /// declares, and its ``event``, ``date``, ``station``, ``component``, ``magnitude`` and
    /// ``distance_km`` (None where the file does not give one).
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = serde_json::to_string(&self.motion.record.meta)
            .map_err(|e| FlexrockError::new_err(e.to_string()))?;
        py.import("json")?.call_method1("loads", (text,))
    }

    /// A short name for a legend: event, station and component where the file gives them,
    /// else the source.
    #[getter]
    fn label(&self) -> String {
        self.motion.record.meta.label(&self.motion.record.source)
    }

    fn __len__(&self) -> usize {
        self.motion.record.values.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "GroundMotion({:?}, {} samples, dt={} s, units={:?})",
            self.motion.record.source,
            self.motion.record.values.len(),
            self.motion.record.dt,
            self.motion.units
        )
    }
}

/// Reads a record file (PEER AT2, COSMOS V1/V2, ESM/ITACA, CSV or text) into a GroundMotion;
/// `units` for a file that does not say its own.
#[pyfunction]
#[pyo3(signature = (path, format=None, dt=None, units=None))]
pub(crate) fn read_record(
    path: PathBuf,
    format: Option<&str>,
    dt: Option<f64>,
    units: Option<&str>,
) -> PyResult<GroundMotion> {
    let format = format
        .map(|name| RecordFormat::from_name("format", name))
        .transpose()
        .map_err(invalid)?;
    let record = read_record_file(&path, format, dt).map_err(invalid)?;
    if units.is_none() && record.meta.units.is_none() {
        return Err(FlexrockError::new_err(format!(
            "units = None: required for {} records whose file does not say the unit of its \
             values ({}): {}",
            match record.meta.format {
                "csv" => "CSV",
                "peer-at2" => "AT2",
                other => other,
            },
            record.source,
            flexrock_core::record::UNIT_NAMES
        )));
    }
    let (units, factor) = resolve_units(&record, "units", units).map_err(invalid)?;
    Ok(GroundMotion {
        motion: Arc::new(Motion {
            record,
            units,
            factor,
        }),
    })
}
