//! The model file of one body, read, checked and ready to run: [`Model`] applies the defaults,
//! checks every rule of each section (each section's rules live in a file of their own) and
//! derives the constants.

use std::path::{Path, PathBuf};

use super::body_section::{body_from_section, check_stands_up};
use super::excitation_section::{floor_from_section, vertical_from_section};
use super::fem_section::{self, FemSetup};
use super::overrides::{Overrides, DT_WITHOUT_NEWMARK};
use super::read::{parse_model_text, read_model_text, MODEL_TEXT};
use super::schema::{FemOverrides, ModelFile, SolverSection};
use super::setting;
use super::simulation_section::{initial_from_section, run_duration};
use super::solver_section::{self, check_rtol, newmark_from_section, solver_from_section};
use super::RecordCache;
use crate::error::{Error, Result};
use crate::floor::{FloorMotion, Shaking};
use crate::integrate::adaptive::{AdaptiveMethod, AdaptiveSettings};
use crate::integrate::newmark::NewmarkSettings;
use crate::integrate::{History, InitialState, SolverSettings};
use crate::physics::body::Body;
use crate::physics::constants::Constants;

/// A validated model, ready to run.
pub struct Model {
    /// The file it came from, if any.
    pub path: Option<PathBuf>,
    /// The file as read, with command-line overrides applied.
    pub file: ModelFile,
    /// The validated body.
    pub body: Body,
    /// The constants derived from the body.
    pub constants: Constants,
    /// The floor motion (horizontal).
    pub floor: Box<dyn FloorMotion>,
    /// The floor's vertical acceleration, upwards positive, if `[excitation.vertical]` gives one.
    pub vertical: Option<Box<dyn FloorMotion>>,
    /// The initial state.
    pub initial: InitialState,
    /// Simulated time, s.
    pub duration: f64,
    /// The solver and its settings.
    pub solver: SolverSettings,
}

impl Model {
    /// Reads, parses and validates a model file.
    pub fn load(path: &Path, overrides: &Overrides) -> Result<Model> {
        let text = read_model_text(path)?;
        let file = parse_model_text(&text, &overrides.settings, path)?;
        let linked = setting::linked_dir(path);
        let base_dir = linked
            .as_deref()
            .unwrap_or_else(|| path.parent().unwrap_or(Path::new(".")));
        let mut model = Model::from_file(file, overrides, base_dir).map_err(|e| match e {
            // A value set from outside the file is not the file's fault: the error names its
            // key alone, and the caller names it as it was given.
            Error::InvalidParameter { key, value, rule } if overrides.sets(&key) => {
                let hint = if key == "solver.dt" && rule.starts_with("not a parameter") {
                    DT_WITHOUT_NEWMARK
                } else {
                    ""
                };
                Error::InvalidParameter {
                    key,
                    value,
                    rule: format!("{rule}{hint}"),
                }
            }
            // A number derived from the body's keys, some of them set from outside the file:
            // the message names those settings too.
            Error::InvalidParameter { key, value, rule }
                if key.starts_with("derived ") && !overrides.body_settings().is_empty() =>
            {
                Error::InModel {
                    path: path.to_path_buf(),
                    source: Box::new(Error::InvalidParameter {
                        key,
                        value,
                        rule: format!("{rule}; with {}", overrides.body_settings()),
                    }),
                }
            }
            // A record named from outside the file is not the file's either.
            e @ Error::Record { .. } if overrides.sets("excitation.path") => e,
            other => Error::InModel {
                path: path.to_path_buf(),
                source: Box::new(other),
            },
        })?;
        model.path = Some(path.to_path_buf());
        Ok(model)
    }

    /// Parses and validates the text of a model file; record paths are relative to the
    /// current directory.
    pub fn from_toml_str(text: &str, overrides: &Overrides) -> Result<Model> {
        let file = parse_model_text(text, &overrides.settings, Path::new(MODEL_TEXT))?;
        Model::from_file(file, overrides, Path::new("."))
    }

    /// Validates a parsed model file; record paths are relative to `base_dir`.
    pub fn from_file(file: ModelFile, overrides: &Overrides, base_dir: &Path) -> Result<Model> {
        Model::from_file_cached(file, overrides, base_dir, &RecordCache::default())
    }

    /// [`Model::from_file`], taking records from `records` (and reading them into it).
    pub fn from_file_cached(
        file: ModelFile,
        overrides: &Overrides,
        base_dir: &Path,
        records: &RecordCache,
    ) -> Result<Model> {
        Model::from_file_keeping(file, overrides, base_dir, records, History::Sampled)
    }

    /// [`Model::from_file_cached`] for a run that keeps no history ([`crate::simulate_peaks`]: a
    /// sweep's point), to which the limit on history rows does not apply.
    pub(crate) fn for_peaks(
        file: ModelFile,
        base_dir: &Path,
        records: &RecordCache,
    ) -> Result<Model> {
        let none = Overrides::default();
        Model::from_file_keeping(file, &none, base_dir, records, History::PeaksOnly)
    }

    fn from_file_keeping(
        mut file: ModelFile,
        overrides: &Overrides,
        base_dir: &Path,
        records: &RecordCache,
        history: History,
    ) -> Result<Model> {
        if let Some(m) = &overrides.method {
            // Switching between the families of methods (Newmark, the adaptive methods, the exact
            // one) on the command line sets aside the file's keys of the other family: they were
            // written for the file's method.
            let gives_tolerance = file.solver.rtol.is_some() || file.solver.atol.is_some();
            let file_method = file
                .solver
                .method
                .as_deref()
                .unwrap_or(solver_section::default_method(gives_tolerance));
            if solver_section::method_family(m) != solver_section::method_family(file_method) {
                // Keys set from outside the file (`--set solver.dt=...`) were given for this
                // method, and stay to meet its rules.
                fn given<T>(overrides: &Overrides, key: &str, value: Option<T>) -> Option<T> {
                    value.filter(|_| overrides.settings.iter().any(|s| s.key == key))
                }
                let old = std::mem::take(&mut file.solver);
                file.solver = SolverSection {
                    method: None,
                    output_dt: old.output_dt,
                    rtol: given(overrides, "solver.rtol", old.rtol),
                    atol: given(overrides, "solver.atol", old.atol),
                    dt: given(overrides, "solver.dt", old.dt),
                    newmark_beta: given(overrides, "solver.newmark_beta", old.newmark_beta),
                    newmark_gamma: given(overrides, "solver.newmark_gamma", old.newmark_gamma),
                    newmark_variant: given(
                        overrides,
                        "solver.newmark_variant",
                        old.newmark_variant,
                    ),
                };
            }
            file.solver.method = Some(m.clone());
        }
        if let Some(r) = overrides.rtol {
            file.solver.rtol = Some(r);
        }
        if let Some(a) = overrides.atol {
            file.solver.atol = Some(a);
        }
        if let Some(d) = overrides.duration {
            file.simulation.duration = Some(d);
        }
        if let Some(dt) = overrides.dt {
            file.solver.dt = Some(dt);
        }
        if let Some(v) = &overrides.newmark_variant {
            file.solver.newmark_variant = Some(v.clone());
        }

        let body = records.body(&file.body, body_from_section)?;
        let constants = records.constants(&body)?;
        check_stands_up(&file.body, &body, &constants)?;
        let (floor, natural_duration) = floor_from_section(&file.excitation, base_dir, records)?;
        let (vertical, natural_duration) =
            match vertical_from_section(&file.excitation, base_dir, records)? {
                None => (None, natural_duration),
                // A record pair runs for the longer of its two records.
                Some((v, length)) => (
                    Some(v),
                    natural_duration.map(|h| h.max(length.unwrap_or(h))),
                ),
            };
        let duration = run_duration(file.simulation.duration, natural_duration, &file.excitation)?;
        Shaking::new(floor.as_ref(), vertical.as_deref()).check_contact(body.gravity, duration)?;
        let initial = initial_from_section(&file.simulation, &body)?;
        let solver =
            solver_from_section(&file.solver, duration, constants.omega, body.width, history)?;
        Ok(Model {
            path: None,
            file,
            body,
            constants,
            floor,
            vertical,
            initial,
            duration,
            solver,
        })
    }

    /// The floor's horizontal and vertical motions together.
    pub fn shaking(&self) -> Shaking<'_> {
        Shaking::new(self.floor.as_ref(), self.vertical.as_deref())
    }

    /// The finite element setup of the `[fem]` section (or its defaults) with command-line
    /// overrides applied, checked like the file (messages name the flags). Only `flexrock fem`
    /// asks for it: a `[fem]` section the finite element analysis would refuse does not stop
    /// `run` or `sweep`.
    pub fn fem_with(&self, overrides: &FemOverrides) -> Result<FemSetup> {
        fem_section::fem_with_overrides(
            &self.file,
            &self.body,
            &self.constants,
            self.duration,
            overrides,
        )
        .map_err(|e| match (e, &self.path) {
            // A value of the file names the file; a value set from outside names its key alone.
            (e @ Error::InvalidParameter { .. }, Some(path))
                if !matches!(&e, Error::InvalidParameter { key, .. }
                    if key.split(", ").any(|k| overrides.sets(k))) =>
            {
                Error::InModel {
                    path: path.clone(),
                    source: Box::new(e),
                }
            }
            (e, _) => e,
        })
    }
}

impl Model {
    /// The reference of a comparison or a convergence study: the exact solution on the model's
    /// output grid, or, when `rtol` is given, the tight adaptive run of
    /// [`Model::reference_settings`].
    pub fn reference(&self, rtol: Option<f64>) -> Result<SolverSettings> {
        Ok(match rtol {
            None => SolverSettings::Exact(crate::integrate::exact::ExactSettings {
                output_dt: self.solver.output_dt(),
            }),
            Some(rtol) => SolverSettings::Adaptive(self.reference_settings(rtol)?),
        })
    }

    /// Settings of a tight adaptive reference: the file's adaptive method (BDF when the file
    /// names Newmark) at `rtol`, with atol = rtol / 100 (q is of order 0.1 m), on the model's
    /// output grid.
    pub fn reference_settings(&self, rtol: f64) -> Result<AdaptiveSettings> {
        check_rtol("rtol", rtol)?;
        let method = match self.solver {
            SolverSettings::Adaptive(a) => a.method,
            SolverSettings::Newmark(_) | SolverSettings::Exact(_) => AdaptiveMethod::Bdf,
        };
        Ok(AdaptiveSettings {
            method,
            rtol,
            atol: rtol * 1e-2,
            output_dt: self.solver.output_dt(),
        })
    }

    /// Newmark settings for this model: the file's Newmark keys when it names Newmark, the
    /// paper's otherwise, with `dt` and `variant` taking precedence. Checked like the file.
    pub fn newmark_settings(
        &self,
        dt: Option<f64>,
        variant: Option<&str>,
    ) -> Result<NewmarkSettings> {
        let mut section = match &self.file.solver.method {
            Some(m) if m == "newmark" => self.file.solver.clone(),
            _ => SolverSection {
                output_dt: self.file.solver.output_dt,
                ..SolverSection::default()
            },
        };
        if dt.is_some() {
            section.dt = dt;
        }
        if let Some(v) = variant {
            section.newmark_variant = Some(v.to_string());
        }
        newmark_from_section(
            &section,
            self.duration,
            self.constants.omega,
            self.solver.output_dt(),
        )
    }
}
