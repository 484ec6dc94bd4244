//! What a user asks of a sweep ([`Request`]), from the command line's flags or a sweep file
//! ([`SweepFile`]).

use std::path::Path;

use serde::Deserialize;

use crate::bodies::rigid::{RigidForm, RigidOverturning};
use crate::error::{Error, Result};
use crate::floor::record::Record;
use crate::model::Setting;

use super::axis::{self, Axis, Interval};

/// What a user asks for.
#[derive(Debug, Clone, Default)]
pub struct Request {
    /// `--set` keys, applied to every point before its axis values.
    pub settings: Vec<Setting>,
    /// `--vary` axes.
    pub axes: Vec<Axis>,
    /// `--find-min KEY=LO:HI`.
    pub find_min: Option<(String, Interval)>,
    /// Scanned values of the minimum search [default: [`find_min::DEFAULT_SCAN`](super::find_min::DEFAULT_SCAN)].
    pub scan: Option<usize>,
    /// Bisection tolerance [default: [`find_min::DEFAULT_TOL_SHARE`](super::find_min::DEFAULT_TOL_SHARE) of HI - LO].
    pub tol: Option<f64>,
    /// Points per chunk [default: about [`SIMULATIONS_PER_CHUNK`](super::SIMULATIONS_PER_CHUNK) simulations].
    pub chunk_size: Option<usize>,
    /// The equation of Housner's block in the minimum search [default: small-angle].
    pub rigid_form: Option<RigidForm>,
    /// When Housner's block of the minimum search counts as overturned [default: when its
    /// tilt reaches its limit].
    pub rigid_overturning: Option<RigidOverturning>,
    /// Housner's block's own coefficient of restitution [default: Housner's].
    pub rigid_restitution: Option<f64>,
    /// Records held in memory (the Python bindings' ground motions), each under the path the
    /// model's `excitation.path` names it by: a point reads it from here, not from a file.
    pub records: Vec<(String, Record)>,
}

/// A sweep file: the axes, settings and search of a sweep, written as on the command line.
///
/// ```toml
/// vary = ["excitation.amplitude=0.5:15:0.5", "excitation.period=log:0.2:3:40"]
/// set = ["solver.method=tsit45", "solver.rtol=1e-8"]
/// find_min = "excitation.amplitude=0.5:15"   # optional
/// scan = 100                                  # optional
/// tol = 1e-3                                  # optional
/// rigid_form = "full"                         # optional, with find_min
/// rigid_overturning = "cannot-return"         # optional, with find_min
/// rigid_restitution = 0.9                     # optional, with find_min
/// ```
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// As `--vary`.
    #[serde(default)]
    pub vary: Vec<String>,
    /// As `--set`.
    #[serde(default)]
    pub set: Vec<String>,
    /// As `--find-min`.
    pub find_min: Option<String>,
    /// As `--scan`.
    pub scan: Option<usize>,
    /// As `--tol`.
    pub tol: Option<f64>,
    /// As `--chunk-size`.
    pub chunk_size: Option<usize>,
    /// As `--rigid-form`.
    pub rigid_form: Option<String>,
    /// As `--rigid-overturning`.
    pub rigid_overturning: Option<String>,
    /// As `--rigid-restitution`.
    pub rigid_restitution: Option<f64>,
}

impl Request {
    /// Adds the axis `KEY=SPEC` (file patterns relative to `base_dir`), checking that the sweep
    /// stays within [`axis::MAX_POINTS`] before the axis's values are made.
    pub fn vary(&mut self, text: &str, base_dir: &Path) -> Result<()> {
        let others = (self.axes.iter()).fold(1usize, |n, a| n.saturating_mul(a.len()));
        self.axes.push(Axis::parse_beside(text, base_dir, others)?);
        Ok(())
    }

    /// Adds a sweep file to the request; file patterns and record paths in it are relative to
    /// the file (its `set` record paths are written again relative to the model file `model`,
    /// which reads them). Relative `path` and `model` are relative to the directory `here`.
    pub fn add_file(&mut self, path: &Path, model: &Path, here: &Path) -> Result<()> {
        // Read as a model file is (a regular file of limited size), so that /dev/zero is refused.
        let text = crate::model::read_model_text(path).map_err(|e| match e {
            Error::ReadModel { path, source } => Error::SweepFile {
                path,
                message: format!("cannot read the sweep file: {source}"),
            },
            other => other,
        })?;
        let file: SweepFile = toml::from_str(&text).map_err(|e| Error::ParseModel {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        let in_file = |e: Error| Error::InModel {
            path: path.to_path_buf(),
            source: Box::new(e),
        };
        let model_dir = crate::model::model_dir(here, Some(model));
        for text in &file.set {
            let setting = Setting::parse(text).map_err(in_file)?;
            self.settings
                .push(setting.rebased(&here.join(base), &model_dir));
        }
        for text in &file.vary {
            self.vary(text, base).map_err(in_file)?;
        }
        if let Some(text) = &file.find_min {
            self.find_min = Some(axis::parse_interval(text).map_err(in_file)?);
        }
        self.scan = self.scan.or(file.scan);
        self.tol = self.tol.or(file.tol);
        self.chunk_size = self.chunk_size.or(file.chunk_size);
        if let Some(text) = &file.rigid_form {
            let form = RigidForm::parse("rigid_form", text).map_err(|e| in_file(e.into()))?;
            self.rigid_form = self.rigid_form.or(Some(form));
        }
        if let Some(text) = &file.rigid_overturning {
            let rule = RigidOverturning::parse("rigid_overturning", text)
                .map_err(|e| in_file(e.into()))?;
            self.rigid_overturning = self.rigid_overturning.or(Some(rule));
        }
        self.rigid_restitution = self.rigid_restitution.or(file.rigid_restitution);
        Ok(())
    }
}
