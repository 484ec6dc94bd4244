//! The TOML model file: its schema (key names are a contract), defaults and validation.
//!
//! A model file is read into [`ModelFile`] exactly as written (unknown keys are errors), then
//! [`Model::from_file`] applies the defaults, checks every rule and derives the constants.
//! Each section's rules live in a file of their own: `excitation_section.rs`,
//! `solver_section.rs`, `fem_section.rs`; the body and the initial state are checked here.

mod excitation_section;
mod fem_section;
mod row_file;
mod setting;
mod solver_section;
mod table;

pub use setting::{check_key, model_dir, value_text, Setting};
pub use table::{default_value, effective_table, schema_keys, value_in_effect};

use excitation_section::floor_from_section;
pub(crate) use excitation_section::keys_of_kind;
pub use excitation_section::STANDARD_GRAVITY;
pub use excitation_section::{record_path, RecordCache};
pub use fem_section::{
    FemSetup, DEFAULT_FEM_DT, DEFAULT_FEM_MU_K, DEFAULT_FEM_MU_S, DEFAULT_FEM_NX, DEFAULT_FEM_NY,
    DEFAULT_FEM_THETA, DEFAULT_POISSON_RATIO, FEM_SNAPSHOT_TIMES,
};
pub use row_file::{is_row_table, RowModel, RowSection, RowSimulationSection};
use solver_section::{check_rtol, newmark_from_section, solver_from_section};
pub use solver_section::{
    DEFAULT_NEWMARK_BETA, DEFAULT_NEWMARK_DT, DEFAULT_NEWMARK_GAMMA, MAX_ATOL_OVER_WIDTH, MAX_RTOL,
    MIN_RTOL,
};

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::floor::FloorMotion;
use crate::integrate::adaptive::{AdaptiveMethod, AdaptiveSettings};
use crate::integrate::newmark::NewmarkSettings;
use crate::integrate::{History, InitialState, SolverSettings};
use crate::physics::body::{positive, Body, ConstantSet, SelfWeight};
use crate::physics::constants::Constants;

/// The model file as written.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// The `[body]` table.
    pub body: BodySection,
    /// The `[excitation]` table.
    pub excitation: ExcitationSection,
    /// Every key of it is optional for records, so the table may be left out.
    #[serde(default)]
    pub simulation: SimulationSection,
    #[serde(default)]
    /// The `[solver]` table (optional).
    pub solver: SolverSection,
    /// Settings of `flexrock fem` (optional; see [`Model::fem_with`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fem: Option<FemSection>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
/// The `[body]` table: the body's size, material and damping.
pub struct BodySection {
    /// H, m.
    pub height: f64,
    /// B, in-plane width, m.
    pub width: f64,
    /// D, out-of-plane depth, m (default 1).
    pub depth: Option<f64>,
    /// Density, kg/m^3 (or give `mass`).
    pub density: Option<f64>,
    /// M, total mass, kg (or give `density`).
    pub mass: Option<f64>,
    /// E, Young's modulus, Pa (or give `flexural_rigidity` or `period`).
    pub youngs_modulus: Option<f64>,
    /// EI, flexural rigidity, N m^2 (or give `youngs_modulus` or `period`).
    pub flexural_rigidity: Option<f64>,
    /// Pre-uplift period T, s, from which EI follows (or give `youngs_modulus` or `flexural_rigidity`).
    pub period: Option<f64>,
    /// h, damping ratio before uplift (default 0.05).
    pub damping_ratio: Option<f64>,
    /// g, m/s^2 (default 9.81).
    pub gravity: Option<f64>,
    /// "exact" (default) or "paper": which mode-shape constants to use.
    pub constants: Option<String>,
    /// "paper" (default) or "consistent": how the weight enters the bending.
    pub self_weight: Option<String>,
    /// Poisson's ratio, used only by the finite element analysis.
    pub poisson_ratio: Option<f64>,
}

impl BodySection {
    /// Whether `other` is the same section: every number of the same bits (0 and -0 differ,
    /// a NaN is itself), every text the same. The section is taken apart field by field, so
    /// that a field added to it without a comparison here does not compile.
    pub(crate) fn same_as(&self, other: &BodySection) -> bool {
        let BodySection {
            height,
            width,
            depth,
            density,
            mass,
            youngs_modulus,
            flexural_rigidity,
            period,
            damping_ratio,
            gravity,
            constants,
            self_weight,
            poisson_ratio,
        } = self;
        let bits = |x: &Option<f64>| x.map(f64::to_bits);
        height.to_bits() == other.height.to_bits()
            && width.to_bits() == other.width.to_bits()
            && [
                (depth, &other.depth),
                (density, &other.density),
                (mass, &other.mass),
                (youngs_modulus, &other.youngs_modulus),
                (flexural_rigidity, &other.flexural_rigidity),
                (period, &other.period),
                (damping_ratio, &other.damping_ratio),
                (gravity, &other.gravity),
                (poisson_ratio, &other.poisson_ratio),
            ]
            .iter()
            .all(|(a, b)| bits(a) == bits(b))
            && *constants == other.constants
            && *self_weight == other.self_weight
    }
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
/// The `[excitation]` table: the floor motion.
pub struct ExcitationSection {
    /// Which floor motion, e.g. "paper-sine", "sine-pulse", "ricker" or "record".
    pub kind: String,
    /// A, amplitude of the floor acceleration, m/s^2.
    pub amplitude: Option<f64>,
    /// Tp, period, s.
    pub period: Option<f64>,
    /// paper-sine: length of the cubic ramp, s.
    pub ramp: Option<f64>,
    /// sine-pulse: number of cycles.
    pub cycles: Option<f64>,
    /// sine-pulse: "antisymmetric" (sine) or "symmetric" (cosine).
    pub shape: Option<String>,
    /// ricker: time of the peak, s.
    pub center: Option<f64>,
    /// record: file, relative to the model file.
    pub path: Option<String>,
    /// record: "peer-at2" or "csv".
    pub format: Option<String>,
    /// record: "g", "m/s2" or "cm/s2".
    pub units: Option<String>,
    /// record: factor applied to the values.
    pub scale: Option<f64>,
    /// record: first and last record time used, s.
    pub start: Option<f64>,
    /// record: last record time used, s.
    pub end: Option<f64>,
    /// record, sine-pulse: free vibration after the record or pulse when simulation.duration is
    /// not given, s.
    pub tail: Option<f64>,
    /// record: sampling interval of a one-column CSV file, s.
    pub dt: Option<f64>,
}

#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
/// The `[simulation]` table: duration and initial state.
pub struct SimulationSection {
    /// Required, except for records and sine pulses with a `tail`, where it defaults to their
    /// length plus the tail.
    pub duration: Option<f64>,
    /// q at t = 0, m.
    pub q0: Option<f64>,
    /// q' at t = 0, m/s.
    pub qdot0: Option<f64>,
}

#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
/// The `[solver]` table: which solver and its settings.
pub struct SolverSection {
    /// The solver, e.g. "bdf" or "newmark".
    pub method: Option<String>,
    /// Relative tolerance of an adaptive solver.
    pub rtol: Option<f64>,
    /// Absolute tolerance of an adaptive solver, m.
    pub atol: Option<f64>,
    /// Spacing of the sampled history, s.
    pub output_dt: Option<f64>,
    /// Newmark time step, s.
    pub dt: Option<f64>,
    /// Newmark's beta.
    pub newmark_beta: Option<f64>,
    /// Newmark's gamma.
    pub newmark_gamma: Option<f64>,
    /// "compensate" or "substep": how Newmark handles a mode change inside a step.
    pub newmark_variant: Option<String>,
}

/// The `[fem]` section: the finite element analysis of `flexrock fem`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FemSection {
    /// Elements across the width.
    pub nx: Option<usize>,
    /// Elements up the height.
    pub ny: Option<usize>,
    /// Time step, s.
    pub dt: Option<f64>,
    /// The time-stepping scheme's name.
    pub scheme: Option<String>,
    /// Wilson θ.
    pub theta: Option<f64>,
    /// Static friction coefficient μs.
    pub mu_s: Option<f64>,
    /// Kinetic friction coefficient μk.
    pub mu_k: Option<f64>,
    /// Whether to include the geometric stiffness of the gravity prestress.
    pub p_delta: Option<bool>,
    /// The base support's name, "flexible" or "rigid-plate".
    pub base: Option<String>,
    /// Period T_d at which the stiffness-proportional damping equals h, s.
    pub damping_period: Option<f64>,
    /// Duration of the finite element run, s.
    pub duration: Option<f64>,
}

/// Command-line values of `flexrock fem` that take precedence over the `[fem]` section.
#[derive(Debug, Clone, Default)]
pub struct FemOverrides {
    /// Elements across the width (`fem.nx`).
    pub nx: Option<usize>,
    /// Elements up the height (`fem.ny`).
    pub ny: Option<usize>,
    /// The time-stepping scheme's name (`fem.scheme`).
    pub scheme: Option<String>,
    /// Time step, s (`fem.dt`).
    pub dt: Option<f64>,
}

impl FemOverrides {
    /// Whether a value from outside the model file set the key `key`.
    pub fn sets(&self, key: &str) -> bool {
        match key {
            "fem.nx" => self.nx.is_some(),
            "fem.ny" => self.ny.is_some(),
            "fem.scheme" => self.scheme.is_some(),
            "fem.dt" => self.dt.is_some(),
            _ => false,
        }
    }
}

/// Largest model file read, bytes: a model file is a few hundred bytes.
pub const MAX_MODEL_FILE_BYTES: u64 = 1024 * 1024;

/// The text of a model file: only a regular file of at most [`MAX_MODEL_FILE_BYTES`] (so that
/// /dev/zero or a FIFO is refused rather than read until memory runs out).
pub fn read_model_text(path: &Path) -> Result<String> {
    use std::io::Read as _;
    let refuse = |source| Error::ReadModel {
        path: path.to_path_buf(),
        source,
    };
    let invalid = |message: String| {
        refuse(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            message,
        ))
    };
    let metadata = std::fs::metadata(path).map_err(refuse)?;
    if !metadata.is_file() {
        return Err(invalid(format!(
            "it is {}; a model file must be a regular file",
            crate::base::format::file_kind(metadata.file_type())
        )));
    }
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(refuse)?
        .take(MAX_MODEL_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(refuse)?;
    if text.len() as u64 > MAX_MODEL_FILE_BYTES {
        return Err(invalid(format!(
            "larger than the limit of {MAX_MODEL_FILE_BYTES} bytes for a model file"
        )));
    }
    Ok(text)
}

/// A model file's text and its TOML table, as written (the schema is checked by
/// [`read_schema`]); the file is read as [`Model::load`] reads it (a regular file of at most
/// [`MAX_MODEL_FILE_BYTES`]).
pub fn read_model_table(path: &Path) -> Result<(String, toml::Table)> {
    let text = read_model_text(path)?;
    let table = parse_table(&text, path)?;
    Ok((text, table))
}

/// What names a model given as text (not read from a file) in messages.
pub const MODEL_TEXT: &str = "(model text)";

pub(crate) fn parse_table(text: &str, source: &Path) -> Result<toml::Table> {
    toml::from_str(text).map_err(|e| Error::ParseModel {
        path: source.to_path_buf(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// The text of a model file read into the schema, with `settings` applied. Without settings
/// the text is read directly, so that a message points at the line of the file.
fn parse_model_text(text: &str, settings: &[Setting], source: &Path) -> Result<ModelFile> {
    if settings.is_empty() {
        return toml::from_str(text).map_err(|e| {
            if toml::from_str::<toml::Table>(text).is_ok_and(|table| is_row_table(&table)) {
                return row_model_refused(source);
            }
            Error::ParseModel {
                path: source.to_path_buf(),
                message: crate::base::suggest::schema_hint(e.to_string().trim_end()),
            }
        });
    }
    let table = parse_table(text, source)?;
    if is_row_table(&table) {
        return Err(row_model_refused(source));
    }
    read_schema(&table, settings, source)
}

/// The error for a row model given where one body is read.
fn row_model_refused(source: &Path) -> Error {
    Error::ParseModel {
        path: source.to_path_buf(),
        message: "a model of a row of columns (it has a [row] table), where one body is read: \
                  this command takes a model file with a [body] table; `flexrock run` and \
                  `flexrock sweep` take a row"
            .to_string(),
    }
}

/// Values from outside the model file (command-line flags, Python arguments) that take
/// precedence over the file's.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    /// The solver (solver.method).
    pub method: Option<String>,
    /// Relative tolerance (solver.rtol).
    pub rtol: Option<f64>,
    /// Absolute tolerance (solver.atol), m.
    pub atol: Option<f64>,
    /// Duration (simulation.duration), s.
    pub duration: Option<f64>,
    /// Newmark time step (solver.dt).
    pub dt: Option<f64>,
    /// Newmark variant (solver.newmark_variant).
    pub newmark_variant: Option<String>,
    /// Any model-file key set to a value (`--set KEY=VALUE`), applied to the file's table
    /// before the fields above.
    pub settings: Vec<Setting>,
}

/// What a message about `solver.dt` set from outside the file adds when the method is not
/// Newmark's (the command line names the flags instead).
pub const DT_WITHOUT_NEWMARK: &str = " (solver.dt is read only with solver.method = \"newmark\")";

impl Overrides {
    /// The `--set` settings of the body's keys, as given ("--set body.youngs_modulus=100000",
    /// comma-separated); empty without any.
    pub fn body_settings(&self) -> String {
        self.settings
            .iter()
            .filter(|s| s.key.starts_with("body."))
            .map(|s| match s.value {
                // Shortest digits, with an exponent where large or small (1e-300, not 300
                // digits of zeros).
                toml::Value::Float(x) => format!("--set {}={x:?}", s.key),
                ref other => format!("--set {}={other}", s.key),
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Whether a value from outside the model file set the key `key` (an error about it is then
    /// not the file's: the caller names it as it was given, e.g. by the flag that set it).
    pub fn sets(&self, key: &str) -> bool {
        let field = match key {
            "solver.method" => self.method.is_some(),
            "solver.rtol" => self.rtol.is_some(),
            "solver.atol" => self.atol.is_some(),
            "solver.dt" => self.dt.is_some(),
            "solver.newmark_variant" => self.newmark_variant.is_some(),
            "simulation.duration" => self.duration.is_some(),
            _ => false,
        };
        field || self.settings.iter().any(|s| s.key == key)
    }
}

/// A model file's table read into the schema once with some settings (a sweep's `--set` keys),
/// from which the files of further settings (a sweep point's axes) are read again section by
/// section: [`PreparedSchema::read`] gives what [`read_schema`] gives, without cloning and
/// reading the sections no further setting names.
#[derive(Debug, Clone)]
pub struct PreparedSchema {
    /// The table as the file has it, and the settings every read starts with.
    table: toml::Table,
    common: Vec<Setting>,
    /// The table with the common settings, and its schema (None where it does not read: then
    /// every read is [`read_schema`]'s, with its message).
    prepared: Option<(toml::Table, ModelFile)>,
}

impl PreparedSchema {
    /// `table` with `common` applied, read once.
    pub fn new(table: toml::Table, common: &[Setting], source: &Path) -> Self {
        let prepared = read_schema(&table, common, source).ok().and_then(|file| {
            let mut with_common = table.clone();
            for setting in common {
                setting.apply(&mut with_common).ok()?;
            }
            Some((with_common, file))
        });
        PreparedSchema {
            table,
            common: common.to_vec(),
            prepared,
        }
    }

    /// The table as the file has it (without the common settings).
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// [`read_schema`] of the table with the common settings, then `further`.
    pub fn read(&self, further: &[Setting], source: &Path) -> Result<ModelFile> {
        let whole = || {
            let settings: Vec<Setting> = self.common.iter().chain(further).cloned().collect();
            read_schema(&self.table, &settings, source)
        };
        let Some((table, base)) = &self.prepared else {
            return whole();
        };
        let mut file = base.clone();
        let mut done: Vec<&str> = Vec::new();
        for setting in further {
            let Some((section, _)) = setting.key.split_once('.') else {
                return whole();
            };
            if done.contains(&section) {
                continue;
            }
            done.push(section);
            // The section as the table has it, with every further setting of it, in order.
            let mut one = toml::Table::new();
            if let Some(value) = table.get(section) {
                one.insert(section.to_string(), value.clone());
            }
            for s in further {
                if s.key.split_once('.').is_some_and(|(of, _)| of == section)
                    && s.apply(&mut one).is_err()
                {
                    return whole();
                }
            }
            let read = one
                .remove(section)
                .is_some_and(|value| file.set_section(section, value));
            if !read {
                // Not a section, or a value that breaks it: the whole read says which.
                return whole();
            }
        }
        Ok(file)
    }
}

impl ModelFile {
    /// Reads `value` as the section `name`; false (and the file unchanged) if it is not one of
    /// the file's sections or does not follow its schema.
    fn set_section(&mut self, name: &str, value: toml::Value) -> bool {
        fn read<T: serde::de::DeserializeOwned>(value: toml::Value) -> Option<T> {
            value.try_into().ok()
        }
        let set = match name {
            "body" => read(value).map(|section| self.body = section),
            "excitation" => read(value).map(|section| self.excitation = section),
            "simulation" => read(value).map(|section| self.simulation = section),
            "solver" => read(value).map(|section| self.solver = section),
            "fem" => read(value).map(|section| self.fem = Some(section)),
            _ => None,
        };
        set.is_some()
    }
}

/// Reads a model file's table into the schema, with `settings` applied first. A table that does
/// not follow the schema is the file's fault (`source` names it); a setting that breaks it is
/// the setting's, and the error names its key.
pub fn read_schema(table: &toml::Table, settings: &[Setting], source: &Path) -> Result<ModelFile> {
    let read = |table: toml::Table| -> std::result::Result<ModelFile, String> {
        table.try_into::<ModelFile>().map_err(|e| {
            crate::base::suggest::schema_hint(&e.to_string().trim_end().replace('\n', " "))
        })
    };
    if settings.is_empty() {
        return read(table.clone()).map_err(|message| Error::ParseModel {
            path: source.to_path_buf(),
            message,
        });
    }
    let mut with_settings = table.clone();
    for setting in settings {
        setting.apply(&mut with_settings)?;
    }
    match read(with_settings) {
        Ok(file) => Ok(file),
        Err(message) => {
            // Blame the first setting that breaks the schema on its own, else the file.
            for setting in settings {
                let mut alone = table.clone();
                setting.apply(&mut alone)?;
                if let Err(message) = read(alone) {
                    if read(table.clone()).is_ok() {
                        return Err(Error::invalid(
                            &setting.key,
                            setting.value_text(),
                            &format!("does not fit the model file's schema: {message}"),
                        ));
                    }
                }
            }
            Err(Error::ParseModel {
                path: source.to_path_buf(),
                message,
            })
        }
    }
}

/// Default D, out-of-plane depth, m.
pub const DEFAULT_DEPTH: f64 = 1.0;
/// Default h, damping ratio before uplift.
pub const DEFAULT_DAMPING_RATIO: f64 = 0.05;
/// Default g, m/s^2.
pub const DEFAULT_GRAVITY: f64 = 9.81;
/// Default relative tolerance of an adaptive solver.
pub const DEFAULT_RTOL: f64 = 1e-10;
/// Default absolute tolerance of an adaptive solver, m.
pub const DEFAULT_ATOL: f64 = 1e-12;
/// Default spacing of the sampled history, s.
pub const DEFAULT_OUTPUT_DT: f64 = 0.005;
/// Largest initial top velocity, m/s.
pub const MAX_INITIAL_VELOCITY: f64 = 100.0;
pub use crate::base::limits::MAX_DURATION;

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
    /// The floor motion.
    pub floor: Box<dyn FloorMotion>,
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
        let duration = run_duration(file.simulation.duration, natural_duration, &file.excitation)?;
        let initial = initial_from_section(&file.simulation, &body)?;
        let solver =
            solver_from_section(&file.solver, duration, constants.omega, body.width, history)?;
        Ok(Model {
            path: None,
            file,
            body,
            constants,
            floor,
            initial,
            duration,
            solver,
        })
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

/// The simulated time, s: `given` (`simulation.duration`), else the excitation's natural length
/// `natural` (a record's or a pulse's, with its tail); positive and at most [`MAX_DURATION`].
/// A natural length beyond it is blamed on the tail that made it.
fn run_duration(
    given: Option<f64>,
    natural: Option<f64>,
    excitation: &ExcitationSection,
) -> Result<f64> {
    let rule = format!(
        "must be at most {MAX_DURATION:e} s: no earthquake or shaking-table test lasts nearly \
         that long"
    );
    match (given, natural) {
        (Some(d), _) => {
            positive("simulation.duration", d)?;
            if d > MAX_DURATION {
                return Err(Error::invalid("simulation.duration", d, &rule));
            }
            Ok(d)
        }
        (None, Some(d)) => {
            if !(d > 0.0 && d <= MAX_DURATION) {
                // Blamed on the tail, unless the motion alone is too long.
                let tail = excitation.tail.unwrap_or(0.0);
                let (key, value) = match excitation.kind.as_str() {
                    _ if d - tail <= MAX_DURATION => {
                        ("excitation.tail", crate::base::format::shortest(tail))
                    }
                    "sine-pulse" => (
                        "excitation.cycles",
                        format!(
                            "{} (with excitation.period = {})",
                            crate::base::format::shortest(excitation.cycles.unwrap_or(1.0)),
                            crate::base::format::shortest(excitation.period.unwrap_or(0.0))
                        ),
                    ),
                    _ => {
                        return Err(Error::invalid(
                            "excitation.path",
                            excitation.path.clone().unwrap_or_default(),
                            &format!(
                                "the record lasts {} s: with no simulation.duration the run lasts \
                             the record and the tail, which {rule} (give simulation.duration \
                             or excitation.end)",
                                crate::base::format::shortest(d - tail)
                            ),
                        ))
                    }
                };
                return Err(Error::invalid(
                    key,
                    value,
                    &format!(
                        "with no simulation.duration the run lasts the {} ({} s) and the tail, \
                         {} s in all, which {rule}",
                        excitation.kind,
                        crate::base::format::shortest(d - tail),
                        crate::base::format::shortest(d)
                    ),
                ));
            }
            Ok(d)
        }
        (None, None) => Err(Error::invalid(
            "simulation.duration",
            "(missing)",
            &format!(
                "required for kind = \"{}\" (records, and sine pulses with excitation.tail, have \
                 a natural length)",
                excitation.kind
            ),
        )),
    }
}

/// Exactly one of a set of alternative keys must be given.
fn exactly_one(section: &str, alternatives: &[(&str, Option<f64>)]) -> Result<(usize, f64)> {
    let given: Vec<(usize, &str, f64)> = alternatives
        .iter()
        .enumerate()
        .filter_map(|(i, (k, v))| v.map(|v| (i, *k, v)))
        .collect();
    // Built only for a message: a sweep reads a body for every point.
    let names = || {
        alternatives
            .iter()
            .map(|(k, _)| format!("{section}.{k}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match given.as_slice() {
        [(i, _, v)] => Ok((*i, *v)),
        [] => Err(Error::invalid(
            &format!("{section}.{}", alternatives[0].0),
            "(missing)",
            &format!("give exactly one of {}", names()),
        )),
        [(_, k1, v1), (_, k2, v2), ..] => Err(Error::invalid(
            &format!("{section}.{k1}"),
            format!("{v1} (and {section}.{k2} = {v2})"),
            &format!("give exactly one of {}, not several", names()),
        )),
    }
}

fn body_from_section(s: &BodySection) -> Result<Body> {
    let constant_set = match s.constants.as_deref().unwrap_or("exact") {
        "exact" => ConstantSet::Exact,
        "paper" => ConstantSet::Paper,
        other => {
            return Err(Error::invalid(
                "body.constants",
                format!("\"{other}\""),
                "must be \"exact\" or \"paper\"",
            ))
        }
    };
    let self_weight = match s.self_weight.as_deref() {
        None => SelfWeight::Paper,
        Some(name) => SelfWeight::from_name(name).ok_or_else(|| {
            Error::invalid(
                "body.self_weight",
                format!("\"{name}\""),
                "must be \"paper\" (the paper's model) or \"consistent\" (the weight in the bending)",
            )
        })?,
    };
    if self_weight == SelfWeight::Consistent && constant_set == ConstantSet::Paper {
        return Err(Error::invalid(
            "body.constants",
            "\"paper\" (with body.self_weight = \"consistent\")",
            "the paper's rounded constants belong to the paper's mode shape; the consistent \
             variant computes its own, so use constants = \"exact\"",
        ));
    }
    positive("body.height", s.height)?;
    positive("body.width", s.width)?;
    let depth = s.depth.unwrap_or(DEFAULT_DEPTH);
    positive("body.depth", depth)?;

    let mass = match exactly_one("body", &[("density", s.density), ("mass", s.mass)])? {
        (0, density) => {
            positive("body.density", density)?;
            derived_product(
                "mass M = density H B D",
                "kg",
                crate::physics::body::prism_mass(density, s.height, s.width, depth),
                &[
                    ("body.density", density),
                    ("body.height", s.height),
                    ("body.width", s.width),
                    ("body.depth", depth),
                ],
            )?
        }
        (_, mass) => {
            positive("body.mass", mass)?;
            mass
        }
    };
    let damping_ratio = s.damping_ratio.unwrap_or(DEFAULT_DAMPING_RATIO);
    if !damping_ratio.is_finite() {
        return Err(Error::invalid(
            "body.damping_ratio",
            damping_ratio,
            "the damping ratio must lie in [0, 1)",
        ));
    }
    let mut body = Body {
        height: s.height,
        width: s.width,
        depth,
        mass,
        flexural_rigidity: f64::NAN,
        damping_ratio,
        gravity: s.gravity.unwrap_or(DEFAULT_GRAVITY),
        constant_set,
        self_weight,
    };
    body.flexural_rigidity = match exactly_one(
        "body",
        &[
            ("youngs_modulus", s.youngs_modulus),
            ("flexural_rigidity", s.flexural_rigidity),
            ("period", s.period),
        ],
    )? {
        (0, e) => {
            positive("body.youngs_modulus", e)?;
            derived_product(
                "flexural rigidity EI = E D B^3/12",
                "N m^2",
                crate::physics::body::solid_section_flexural_rigidity(e, s.width, depth),
                &[
                    ("body.youngs_modulus", e),
                    ("body.width", s.width),
                    ("body.depth", depth),
                ],
            )?
        }
        (1, ei) => {
            positive("body.flexural_rigidity", ei)?;
            ei
        }
        (_, period) => {
            positive("body.period", period)?;
            positive("body.gravity", body.gravity)?;
            // EI grows as M H^3 / T^2: it leaves the range of numbers for a period far from
            // any body's (2.2e-308 s made it inf).
            let (mass_key, mass_value) = match s.density {
                Some(density) => ("body.density", density),
                None => ("body.mass", body.mass),
            };
            derived_product(
                "flexural rigidity EI found from the period",
                "N m^2",
                Constants::flexural_rigidity_for_period(period, &body)?,
                &[
                    ("body.period", period),
                    (mass_key, mass_value),
                    ("body.height", s.height),
                ],
            )?
        }
    };
    Ok(body.validated()?)
}

/// `value`, a product of the keys `factors` (each finite and positive), when it is finite and
/// positive; otherwise the product overflowed or underflowed, and the factor farthest from 1 (the
/// key the user most likely mistyped) is blamed with its own value.
fn derived_product(what: &str, unit: &str, value: f64, factors: &[(&str, f64)]) -> Result<f64> {
    if value.is_normal() && value > 0.0 {
        return Ok(value);
    }
    let (key, factor) = factors
        .iter()
        .copied()
        .max_by(|a, b| a.1.ln().abs().total_cmp(&b.1.ln().abs()))
        .unwrap_or(("body", value));
    Err(Error::invalid(
        key,
        factor,
        &format!(
            "with it the {what} is {} {unit}, beyond the range of numbers, whose smallest normal \
             positive value is 2.2e-308 (give sizes in m, densities in kg/m^3, moduli in Pa)",
            crate::base::format::shortest(value)
        ),
    ))
}

/// Refuses a body whose uplift displacement s_n is not below its width B: it would lift off under
/// its own weight, and eq. 16 has no meaning. (In the paper's model self-weight buckling comes
/// first; with the weight in the bending s_n can reach B well short of buckling.) The message
/// names the stiffness key the file set, with its value, and the keys that move s_n.
fn check_stands_up(s: &BodySection, body: &Body, constants: &Constants) -> Result<()> {
    let s_n = constants.uplift_displacement;
    if s_n < body.width {
        return Ok(());
    }
    let (key, value) = [
        ("body.youngs_modulus", s.youngs_modulus),
        ("body.flexural_rigidity", s.flexural_rigidity),
        ("body.period", s.period),
    ]
    .into_iter()
    .find_map(|(key, value)| value.map(|v| (key, v)))
    .unwrap_or(("body.flexural_rigidity", body.flexural_rigidity));
    let mass_key = if s.mass.is_some() {
        "body.mass"
    } else {
        "body.density"
    };
    let remedy = if key == "body.period" {
        "shorten body.period"
    } else {
        "raise it"
    };
    Err(Error::invalid(
        key,
        value,
        &format!(
            "the body is unstable under its own weight: its derived uplift displacement s_n = {} m \
             (body.self_weight = \"{}\") must be less than the width B = {} m (body.width); \
             {remedy}, or lower {mass_key} or body.height",
            crate::base::format::significant(s_n, 6),
            body.self_weight.name(),
            crate::base::format::shortest(body.width),
        ),
    ))
}

fn initial_from_section(s: &SimulationSection, body: &Body) -> Result<InitialState> {
    let q = s.q0.unwrap_or(0.0);
    let qdot = s.qdot0.unwrap_or(0.0);
    if !(q.is_finite() && q.abs() < body.width) {
        return Err(Error::invalid(
            "simulation.q0",
            q,
            &format!(
                "the initial top displacement must satisfy |q0| < B = {} m (at |q0| >= B the body has already overturned)",
                body.width
            ),
        ));
    }
    if qdot.is_nan() || qdot.abs() > MAX_INITIAL_VELOCITY {
        return Err(Error::invalid(
            "simulation.qdot0",
            qdot,
            &format!(
                "must lie within +-{MAX_INITIAL_VELOCITY} m/s: far beyond any velocity a floor gives a body \
                 (earthquake ground velocities stay within a few m/s)"
            ),
        ));
    }
    Ok(InitialState { q, qdot })
}

#[cfg(test)]
mod prepared_schema_tests {
    use super::*;

    fn table(path: &str) -> toml::Table {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path);
        read_model_table(&path)
            .expect("a model of the repository")
            .1
    }

    /// What a read gives, as text: the file, or the error's message.
    fn outcome(read: Result<ModelFile>) -> String {
        match read {
            Ok(file) => format!("{file:?}"),
            Err(e) => format!("error: {e}"),
        }
    }

    /// Reading again only the sections the further settings name gives the file (or the error)
    /// that reading the whole table with every setting gives: for settings that read, break a
    /// section's schema, name no section, add a section, switch the solver's family, or set a
    /// key twice.
    #[test]
    fn a_prepared_read_is_the_whole_read() {
        let number = Setting::number;
        let text = Setting::text;
        let commons = [
            vec![],
            vec![text("solver.method", "exact")],
            vec![number("solver.rtol", 1e-9), number("body.height", 3.5)],
        ];
        let furthers = [
            vec![],
            vec![
                number("excitation.period", 0.7),
                number("excitation.amplitude", 2.0),
            ],
            vec![
                number("excitation.amplitude", 2.0),
                number("body.width", 0.5),
            ],
            vec![text("excitation.amplitude", "large")],
            vec![number("excitation.no_such_key", 1.0)],
            vec![number("nosection", 1.0)],
            vec![number("row.spacing", 1.0)],
            vec![number("fem.elements", 12.0)],
            vec![number("simulation.duration", 3.0)],
            vec![text("solver.method", "newmark"), number("solver.dt", 0.01)],
            vec![number("solver.dt", 0.01), text("solver.method", "newmark")],
            vec![
                number("solver.rtol", 1e-8),
                text("solver.method", "newmark"),
            ],
            vec![text("solver.method", "bdf")],
            vec![number("body.height", -1.0)],
            vec![
                number("excitation.period", 0.7),
                number("excitation.period", 0.9),
            ],
            vec![
                text("body.height", "tall"),
                number("excitation.period", 0.9),
            ],
        ];
        let source = Path::new("model.toml");
        let mut compared = 0;
        for model in ["models/pulse-map.toml", "models/ichinose1986.toml"] {
            let table = table(model);
            for common in &commons {
                let prepared = PreparedSchema::new(table.clone(), common, source);
                for further in &furthers {
                    let all: Vec<Setting> = common.iter().chain(further).cloned().collect();
                    let whole = outcome(read_schema(&table, &all, source));
                    let part = outcome(prepared.read(further, source));
                    assert_eq!(part, whole, "{model} with {all:?}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 2 * commons.len() * furthers.len());
    }

    /// A table that does not read with the common settings reads every time as a whole, with
    /// the whole read's message.
    #[test]
    fn a_table_that_does_not_read_gives_the_whole_reads_message() {
        let mut table = table("models/pulse-map.toml");
        table.insert("extra".into(), toml::Value::Integer(1));
        let source = Path::new("model.toml");
        let prepared = PreparedSchema::new(table.clone(), &[], source);
        assert!(prepared.prepared.is_none());
        let further = [Setting::number("excitation.period", 0.7)];
        let whole = outcome(read_schema(&table, &further, source));
        assert!(whole.starts_with("error"), "{whole}");
        assert_eq!(outcome(prepared.read(&further, source)), whole);
    }
}

#[cfg(test)]
mod body_cache_tests {
    use super::*;
    use std::cell::Cell;

    fn section() -> BodySection {
        let table = read_model_table(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("../models/pulse-map.toml"),
        )
        .expect("a model of the repository")
        .1;
        read_schema(&table, &[], Path::new("model.toml"))
            .expect("it reads")
            .body
    }

    /// The cache gives the body the section reads to, reads a section again unless every
    /// number has the same bits and every text is the same, and never keeps a refusal.
    #[test]
    fn a_body_is_read_again_unless_its_section_is_the_same() {
        let cache = RecordCache::default();
        let reads = Cell::new(0);
        let read = |s: &BodySection| {
            reads.set(reads.get() + 1);
            body_from_section(s)
        };
        let base = section();
        let first = cache.body(&base, read).expect("a body");
        assert_eq!(
            format!("{first:?}"),
            format!("{:?}", body_from_section(&base).unwrap())
        );
        cache.body(&base.clone(), read).expect("a body");
        assert_eq!(reads.get(), 1, "the same section is read once");
        let mut taller = base.clone();
        taller.height = f64::from_bits(base.height.to_bits() + 1);
        let body = cache.body(&taller, read).expect("a body");
        assert_eq!(body.height, taller.height);
        assert_eq!(reads.get(), 2);
        let mut signed = taller.clone();
        signed.poisson_ratio = Some(-0.0);
        let mut unsigned = taller.clone();
        unsigned.poisson_ratio = Some(0.0);
        cache.body(&signed, read).expect("a body");
        cache.body(&unsigned, read).expect("a body");
        let mut paper = unsigned.clone();
        paper.constants = Some("paper".into());
        cache.body(&paper, read).expect("a body");
        assert_eq!(
            reads.get(),
            5,
            "-0 and 0, and another text, are other sections"
        );
        let mut refused = paper.clone();
        refused.width = -1.0;
        assert!(cache.body(&refused, read).is_err());
        assert!(cache.body(&refused, read).is_err());
        assert_eq!(reads.get(), 7, "a refusal is not kept");
    }
}
