//! `GroundMotion`: a floor acceleration record given as numpy arrays (or read from a record
//! file by `read_record`), checked by the rules and limits of a record file; a model solved
//! under it (`Model.with_ground_motion`) takes it through the core's recorded motion, exactly as
//! it takes a record file with the same samples.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};

use flexrock_core::floor::record::{
    acceleration_unit, dt_from_times, read_record as read_record_file, record_from_samples,
    resolve_units, Record, RecordFormat, MAX_RECORD_BYTES, MAX_RECORD_SAMPLES,
};
use flexrock_core::floor::RecordedMotion;

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

    /// The `[excitation]` table of a model file that reads this motion from the CSV record file
    /// `path`, as `to_csv` writes it: one column, so that dt is the motion's to the bit.
    pub(crate) fn record_file_table(&self, path: &str) -> toml::Table {
        let mut t = toml::Table::new();
        t.insert("kind".into(), toml::Value::String("record".into()));
        t.insert("path".into(), toml::Value::String(path.into()));
        t.insert("format".into(), toml::Value::String("csv".into()));
        t.insert("units".into(), toml::Value::String(self.units.into()));
        t.insert("dt".into(), toml::Value::Float(self.record.dt));
        t
    }

    /// Refuses `path` unless it is a CSV record file of exactly these samples at this dt.
    pub(crate) fn check_record_file(&self, path: &Path) -> PyResult<()> {
        let record = read_record_file(path, Some(RecordFormat::Csv), Some(self.record.dt))
            .map_err(invalid)?;
        let same = record.dt.to_bits() == self.record.dt.to_bits()
            && record.values.len() == self.record.values.len()
            && record
                .values
                .iter()
                .zip(&self.record.values)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same {
            return Err(FlexrockError::new_err(format!(
                "record_path = {}: does not hold the model's ground motion ({}, {} samples at dt \
                 = {} s): write it with model.ground_motion.to_csv(record_path) first",
                path.display(),
                self.record.source,
                self.record.values.len(),
                flexrock_core::base::format::shortest(self.record.dt)
            )));
        }
        Ok(())
    }
}

fn invalid(e: impl std::fmt::Display) -> PyErr {
    FlexrockError::new_err(e.to_string())
}

/// The samples of `value` (any 1-D sequence of numbers) as float64, named `name` in errors.
/// Their number is checked against [`MAX_RECORD_SAMPLES`] before any is copied (a numpy
/// array by its shape, a sequence by its length), so that a huge or broadcast array is refused
/// without being made.
fn floats(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let py = value.py();
    let shape = value.getattr("shape").ok();
    let count = match shape.as_ref().map(|s| (s, s.extract::<Vec<usize>>())) {
        Some((shape, Ok(lengths))) if lengths.len() != 1 => {
            return Err(FlexrockError::new_err(format!(
                "{name}: must be 1-D (one sample per time), has shape {}",
                shape.repr()?
            )))
        }
        Some((_, Ok(lengths))) => Some(lengths[0]),
        _ => value.len().ok(),
    };
    if let Some(n) = count {
        check_count(name, n)?;
    }
    let numpy = py.import("numpy")?;
    let array = numpy
        .call_method1("asarray", (value, "float64"))
        .map_err(|e| {
            FlexrockError::new_err(format!(
                "{name}: must be a 1-D sequence of numbers ({})",
                e.value(py)
            ))
        })?;
    let ndim: usize = array.getattr("ndim")?.extract()?;
    if ndim != 1 {
        return Err(FlexrockError::new_err(format!(
            "{name}: must be 1-D (one sample per time), has shape {}",
            array.getattr("shape")?.repr()?
        )));
    }
    let array: PyReadonlyArray1<'_, f64> = array.extract()?;
    check_count(name, array.len()?)?;
    Ok(array.as_array().iter().copied().collect())
}

/// Refuses more samples than a record may have, before they are copied.
fn check_count(name: &str, n: usize) -> PyResult<()> {
    if n > MAX_RECORD_SAMPLES {
        return Err(FlexrockError::new_err(format!(
            "{name} = {n} samples: more than the limit for a record, {MAX_RECORD_SAMPLES} samples \
             (as many as the largest record file holds)"
        )));
    }
    Ok(())
}

fn unit(units: &str) -> PyResult<(&'static str, f64)> {
    acceleration_unit("units", units).map_err(invalid)
}

/// The header of a CSV record's acceleration column in `units`, as `flexrock record csv`
/// names it.
fn column_name(units: &str) -> &'static str {
    match units {
        "g" => "acc_g",
        "cm/s2" => "acc_cm_s2",
        _ => "acc_m_s2",
    }
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

    /// Writes the samples, as given (in `units`), to the CSV record file `path`: one value a
    /// line, each in its shortest form that reads back exactly, under a column named by the
    /// units. ``read_record(path, dt=gm.dt, units=gm.units)`` reads the same motion back, and
    /// ``Model.to_toml(record_path=path)`` names it in a model file.
    fn to_csv(&self, path: PathBuf) -> PyResult<()> {
        let record = &self.motion.record;
        let mut text = String::with_capacity(record.values.len() * 12 + 128);
        text.push_str(&format!(
            "# {}: {} samples at dt = {} s, in {}\n{}\n",
            record.source,
            record.values.len(),
            flexrock_core::base::format::shortest(record.dt),
            self.motion.units,
            column_name(self.motion.units)
        ));
        for &v in &record.values {
            flexrock_core::base::format::push_shortest(&mut text, v);
            text.push('\n');
            if text.len() as u64 > MAX_RECORD_BYTES {
                return Err(FlexrockError::new_err(format!(
                    "GroundMotion.to_csv: {} samples make a CSV record file of more than the \
                     {MAX_RECORD_BYTES} bytes a record file may have; pickle the model or the \
                     ground motion instead",
                    record.values.len()
                )));
            }
        }
        write_whole(&path, text.as_bytes())
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

    /// Pickled as its source, title lines, dt, units and samples (their bits).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let record = &self.motion.record;
        let mut bytes = Vec::with_capacity(record.values.len() * 8);
        for v in &record.values {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let state = (
            record.source.clone(),
            record.title.clone(),
            record.dt,
            self.motion.units,
            PyBytes::new(py, &bytes),
        )
            .into_pyobject(py)?;
        let restore = py
            .import("flexrock._native")?
            .getattr("_ground_motion_from_state")?;
        Ok(PyTuple::new(py, [restore, PyTuple::new(py, [state])?.into_any()])?.into_any())
    }
}

/// The ground motion pickled by `GroundMotion.__reduce__`.
#[pyfunction]
pub(crate) fn _ground_motion_from_state(
    state: (String, Vec<String>, f64, String, Vec<u8>),
) -> PyResult<GroundMotion> {
    let (source, title, dt, units, bytes) = state;
    if bytes.len() % 8 != 0 {
        return Err(FlexrockError::new_err(
            "a pickled GroundMotion whose samples are not whole float64 values",
        ));
    }
    let values = bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap_or_default()))
        .collect();
    let mut record =
        record_from_samples(&source, "dt", dt, "acceleration", values).map_err(invalid)?;
    record.title = title;
    let (units, factor) = unit(&units)?;
    Ok(GroundMotion {
        motion: Arc::new(Motion {
            record,
            units,
            factor,
        }),
    })
}

/// Writes `bytes` to `path` whole or not at all (a file beside it, then renamed over it); only
/// a regular file (or nothing) is replaced.
fn write_whole(path: &Path, bytes: &[u8]) -> PyResult<()> {
    let refuse = |rule: &str| FlexrockError::new_err(format!("{}: {rule}", path.display()));
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() {
            return Err(refuse(
                "is not a regular file; flexrock replaces only those",
            ));
        }
    }
    let name = path
        .file_name()
        .ok_or_else(|| refuse("names no file"))?
        .to_string_lossy();
    let partial = path.with_file_name(format!(".{name}.partial"));
    let written = std::fs::File::create(&partial)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| std::fs::rename(&partial, path));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&partial);
        return Err(pyo3::exceptions::PyOSError::new_err(format!(
            "{}: {e}",
            path.display()
        )));
    }
    Ok(())
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
            flexrock_core::floor::record::UNIT_NAMES
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
