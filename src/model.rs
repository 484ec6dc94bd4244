//! The TOML model file: its schema (key names are a contract), defaults and validation.
//!
//! A model file is read into [`ModelFile`] exactly as written (unknown keys are errors), then
//! [`Model::from_file`] applies the defaults, checks every rule and derives the constants.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::body::{positive, Body, ConstantSet};
use crate::constants::Constants;
use crate::error::{Error, Result};
use crate::excitation::{
    FloorMotion, Free, Harmonic, PaperSine, PulseShape, RecordedMotion, Ricker, SinePulse,
};
use crate::fem::{FemBody, FemSettings, TimeScheme};
use crate::record::{read_record, RecordFormat};
use crate::solver::adaptive::{AdaptiveMethod, AdaptiveSettings};
use crate::solver::newmark::{critical_omega_dt, NewmarkSettings, NewmarkVariant};
use crate::solver::{InitialState, SolverSettings};

/// The model file as written.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    pub body: BodySection,
    pub excitation: ExcitationSection,
    pub simulation: SimulationSection,
    #[serde(default)]
    pub solver: SolverSection,
    /// Settings of `flexrock fem` (optional; see [`fem_from_section`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fem: Option<FemSection>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodySection {
    pub height: f64,
    pub width: f64,
    pub depth: Option<f64>,
    pub density: Option<f64>,
    pub mass: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub flexural_rigidity: Option<f64>,
    pub period: Option<f64>,
    pub damping_ratio: Option<f64>,
    pub gravity: Option<f64>,
    pub constants: Option<String>,
    /// Poisson's ratio, used only by the finite element analysis.
    pub poisson_ratio: Option<f64>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExcitationSection {
    pub kind: String,
    pub amplitude: Option<f64>,
    pub period: Option<f64>,
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
    pub end: Option<f64>,
    /// record: free vibration after the record when the duration is not given, s.
    pub tail: Option<f64>,
    /// record: sampling interval of a one-column CSV file, s.
    pub dt: Option<f64>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationSection {
    /// Required, except for records, where it defaults to the record length plus `tail`.
    pub duration: Option<f64>,
    pub q0: Option<f64>,
    pub qdot0: Option<f64>,
}

#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    pub method: Option<String>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    pub output_dt: Option<f64>,
    pub dt: Option<f64>,
    pub newmark_beta: Option<f64>,
    pub newmark_gamma: Option<f64>,
    pub newmark_variant: Option<String>,
}

/// The `[fem]` section: the finite element analysis of `flexrock fem`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FemSection {
    pub nx: Option<usize>,
    pub ny: Option<usize>,
    pub dt: Option<f64>,
    pub scheme: Option<String>,
    pub theta: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_k: Option<f64>,
    pub p_delta: Option<bool>,
    pub damping_period: Option<f64>,
    pub duration: Option<f64>,
}

/// Command-line values of `flexrock fem` that take precedence over the `[fem]` section.
#[derive(Debug, Clone, Default)]
pub struct FemOverrides {
    pub nx: Option<usize>,
    pub ny: Option<usize>,
    pub scheme: Option<String>,
    pub dt: Option<f64>,
}

/// Command-line values that take precedence over the file.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    pub method: Option<String>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    pub duration: Option<f64>,
    /// Newmark time step (solver.dt).
    pub dt: Option<f64>,
    /// Newmark variant (solver.newmark_variant).
    pub newmark_variant: Option<String>,
}

pub const DEFAULT_DEPTH: f64 = 1.0;
pub const DEFAULT_DAMPING_RATIO: f64 = 0.05;
pub const DEFAULT_GRAVITY: f64 = 9.81;
pub const DEFAULT_RTOL: f64 = 1e-10;
pub const DEFAULT_ATOL: f64 = 1e-12;
pub const DEFAULT_OUTPUT_DT: f64 = 0.005;
/// The paper's time step (section 2.5).
pub const DEFAULT_NEWMARK_DT: f64 = 0.02;
/// Linear acceleration, the paper's choice.
pub const DEFAULT_NEWMARK_BETA: f64 = 1.0 / 6.0;
pub const DEFAULT_NEWMARK_GAMMA: f64 = 0.5;
/// More Newmark steps than this is a mistake in dt, not a wish.
const MAX_NEWMARK_STEPS: f64 = 1e8;
pub const DEFAULT_POISSON_RATIO: f64 = 0.25;
/// More history rows than this is a mistake in output_dt, not a wish.
const MAX_SAMPLES: f64 = 1e7;

/// A validated model, ready to run.
pub struct Model {
    /// The file it came from, if any.
    pub path: Option<PathBuf>,
    /// The file as read, with command-line overrides applied.
    pub file: ModelFile,
    pub body: Body,
    pub constants: Constants,
    pub floor: Box<dyn FloorMotion>,
    pub initial: InitialState,
    pub duration: f64,
    pub solver: SolverSettings,
    /// The finite element analysis as the `[fem]` section (or its defaults) describes it.
    pub fem: FemSetup,
}

impl Model {
    /// Reads, parses and validates a model file.
    pub fn load(path: &Path, overrides: &Overrides) -> Result<Model> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::ReadModel {
            path: path.to_path_buf(),
            source,
        })?;
        let file: ModelFile = toml::from_str(&text).map_err(|e| Error::ParseModel {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let base_dir = path.parent().unwrap_or(Path::new("."));
        let mut model =
            Model::from_file(file, overrides, base_dir).map_err(|e| Error::InModel {
                path: path.to_path_buf(),
                source: Box::new(e),
            })?;
        model.path = Some(path.to_path_buf());
        Ok(model)
    }

    /// Parses and validates the text of a model file (`source` names it in messages).
    pub fn from_toml_str(text: &str, overrides: &Overrides) -> Result<Model> {
        let file: ModelFile = toml::from_str(text).map_err(|e| Error::ParseModel {
            path: PathBuf::from("(model text)"),
            message: e.to_string().trim_end().to_string(),
        })?;
        Model::from_file(file, overrides, Path::new("."))
    }

    /// Validates a parsed model file; record paths are relative to `base_dir`.
    pub fn from_file(mut file: ModelFile, overrides: &Overrides, base_dir: &Path) -> Result<Model> {
        if let Some(m) = &overrides.method {
            // Switching between Newmark and the adaptive methods on the command line sets aside
            // the file's keys of the other family: they were written for the file's method.
            let newmark = |name: Option<&str>| name == Some("newmark");
            if newmark(Some(m)) != newmark(file.solver.method.as_deref()) {
                let keep_output_dt = file.solver.output_dt;
                file.solver = SolverSection {
                    output_dt: keep_output_dt,
                    ..SolverSection::default()
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

        let body = body_from_section(&file.body)?;
        let constants = Constants::new(&body)?;
        let (floor, natural_duration) = floor_from_section(&file.excitation, base_dir)?;
        let duration = match (file.simulation.duration, natural_duration) {
            (Some(d), _) | (None, Some(d)) => d,
            (None, None) => {
                return Err(Error::invalid(
                    "simulation.duration",
                    "(missing)",
                    &format!(
                        "required for kind = \"{}\" (only records have a natural length)",
                        file.excitation.kind
                    ),
                ))
            }
        };
        positive("simulation.duration", duration)?;
        let initial = initial_from_section(&file.simulation, &body)?;
        let solver = solver_from_section(&file.solver, duration, constants.omega)?;
        let fem = fem_from_section(&file, &body, &constants, duration)?;
        Ok(Model {
            path: None,
            file,
            body,
            constants,
            floor,
            initial,
            duration,
            solver,
            fem,
        })
    }

    /// The finite element setup with command-line overrides applied (checked like the file).
    pub fn fem_with(&self, overrides: &FemOverrides) -> Result<FemSetup> {
        let mut file = self.file.clone();
        let section = file.fem.get_or_insert_with(FemSection::default);
        section.nx = overrides.nx.or(section.nx);
        section.ny = overrides.ny.or(section.ny);
        section.dt = overrides.dt.or(section.dt);
        if let Some(scheme) = &overrides.scheme {
            section.scheme = Some(scheme.clone());
        }
        fem_from_section(&file, &self.body, &self.constants, self.duration)
    }
}

impl Model {
    /// Settings of a tight adaptive reference: the file's adaptive method (BDF when the file
    /// names Newmark) at `rtol`, with atol = rtol / 100 (q is of order 0.1 m), on the model's
    /// output grid.
    pub fn reference_settings(&self, rtol: f64) -> Result<AdaptiveSettings> {
        if !(rtol > 0.0 && rtol < 1.0) {
            return Err(Error::invalid(
                "rtol",
                rtol,
                "the relative tolerance must lie in (0, 1)",
            ));
        }
        let method = match self.solver {
            SolverSettings::Adaptive(a) => a.method,
            SolverSettings::Newmark(_) => AdaptiveMethod::Bdf,
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

/// Exactly one of a set of alternative keys must be given.
fn exactly_one(section: &str, alternatives: &[(&str, Option<f64>)]) -> Result<(usize, f64)> {
    let given: Vec<(usize, &str, f64)> = alternatives
        .iter()
        .enumerate()
        .filter_map(|(i, (k, v))| v.map(|v| (i, *k, v)))
        .collect();
    let names = alternatives
        .iter()
        .map(|(k, _)| format!("{section}.{k}"))
        .collect::<Vec<_>>()
        .join(", ");
    match given.as_slice() {
        [(i, _, v)] => Ok((*i, *v)),
        [] => Err(Error::invalid(
            &format!("{section}.{}", alternatives[0].0),
            "(missing)",
            &format!("give exactly one of {names}"),
        )),
        [(_, k1, v1), (_, k2, v2), ..] => Err(Error::invalid(
            &format!("{section}.{k1}"),
            format!("{v1} (and {section}.{k2} = {v2})"),
            &format!("give exactly one of {names}, not several"),
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
    positive("body.height", s.height)?;
    positive("body.width", s.width)?;
    let depth = s.depth.unwrap_or(DEFAULT_DEPTH);
    positive("body.depth", depth)?;

    let mass = match exactly_one("body", &[("density", s.density), ("mass", s.mass)])? {
        (0, density) => {
            positive("body.density", density)?;
            density * s.height * s.width * depth
        }
        (_, mass) => {
            positive("body.mass", mass)?;
            mass
        }
    };
    let flexural_rigidity = match exactly_one(
        "body",
        &[
            ("youngs_modulus", s.youngs_modulus),
            ("flexural_rigidity", s.flexural_rigidity),
            ("period", s.period),
        ],
    )? {
        (0, e) => {
            positive("body.youngs_modulus", e)?;
            e * depth * s.width.powi(3) / 12.0
        }
        (1, ei) => {
            positive("body.flexural_rigidity", ei)?;
            ei
        }
        (_, period) => {
            positive("body.period", period)?;
            Constants::flexural_rigidity_for_period(period, mass, s.height, constant_set)
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
    Body::new(
        s.height,
        s.width,
        depth,
        mass,
        flexural_rigidity,
        damping_ratio,
        s.gravity.unwrap_or(DEFAULT_GRAVITY),
        constant_set,
    )
}

/// Which keys each excitation kind takes (all others are errors).
const EXCITATION_KEYS: &[(&str, &[&str])] = &[
    ("paper-sine", &["amplitude", "period", "ramp"]),
    ("harmonic", &["amplitude", "period"]),
    ("sine-pulse", &["amplitude", "period", "cycles", "shape"]),
    ("ricker", &["amplitude", "period", "center"]),
    (
        "record",
        &[
            "path", "format", "units", "scale", "start", "end", "tail", "dt",
        ],
    ),
    ("free", &[]),
];

/// Keys that must be given for a kind (the others have defaults).
const REQUIRED_EXCITATION_KEYS: &[&str] = &["amplitude", "period", "ramp", "center", "path"];

/// The floor motion of the `[excitation]` section, and its natural length if it has one.
fn floor_from_section(
    s: &ExcitationSection,
    base_dir: &Path,
) -> Result<(Box<dyn FloorMotion>, Option<f64>)> {
    let kind = s.kind.as_str();
    let allowed = EXCITATION_KEYS
        .iter()
        .find(|(k, _)| *k == kind)
        .map(|(_, keys)| *keys)
        .ok_or_else(|| {
            let kinds: Vec<String> = EXCITATION_KEYS
                .iter()
                .map(|(k, _)| format!("\"{k}\""))
                .collect();
            Error::invalid(
                "excitation.kind",
                format!("\"{kind}\""),
                &format!("must be one of {}", kinds.join(", ")),
            )
        })?;
    let given: [(&str, Option<String>); 14] = [
        ("amplitude", s.amplitude.map(|v| v.to_string())),
        ("period", s.period.map(|v| v.to_string())),
        ("ramp", s.ramp.map(|v| v.to_string())),
        ("cycles", s.cycles.map(|v| v.to_string())),
        ("shape", s.shape.clone()),
        ("center", s.center.map(|v| v.to_string())),
        ("path", s.path.clone()),
        ("format", s.format.clone()),
        ("units", s.units.clone()),
        ("scale", s.scale.map(|v| v.to_string())),
        ("start", s.start.map(|v| v.to_string())),
        ("end", s.end.map(|v| v.to_string())),
        ("tail", s.tail.map(|v| v.to_string())),
        ("dt", s.dt.map(|v| v.to_string())),
    ];
    for (key, value) in &given {
        let wanted = allowed.contains(key);
        match value {
            Some(v) if !wanted => {
                return Err(Error::invalid(
                    &format!("excitation.{key}"),
                    v,
                    &format!("not a parameter of kind = \"{kind}\""),
                ))
            }
            None if wanted && REQUIRED_EXCITATION_KEYS.contains(key) => {
                return Err(Error::invalid(
                    &format!("excitation.{key}"),
                    "(missing)",
                    &format!("required for kind = \"{kind}\""),
                ))
            }
            _ => {}
        }
    }
    let amplitude = s.amplitude.unwrap_or(0.0);
    if !amplitude.is_finite() {
        return Err(Error::invalid(
            "excitation.amplitude",
            amplitude,
            "must be a finite number",
        ));
    }
    let period = s.period.unwrap_or(1.0);
    if allowed.contains(&"period") {
        positive("excitation.period", period)?;
    }
    let floor: Box<dyn FloorMotion> = match kind {
        "paper-sine" => {
            let ramp = s.ramp.unwrap_or(0.0);
            positive("excitation.ramp", ramp)?;
            Box::new(PaperSine::new(amplitude, period, ramp))
        }
        "harmonic" => Box::new(Harmonic { amplitude, period }),
        "sine-pulse" => {
            let cycles = s.cycles.unwrap_or(1.0);
            positive("excitation.cycles", cycles)?;
            let shape = match s.shape.as_deref().unwrap_or("antisymmetric") {
                "antisymmetric" => PulseShape::Antisymmetric,
                "symmetric" => PulseShape::Symmetric,
                other => {
                    return Err(Error::invalid(
                        "excitation.shape",
                        format!("\"{other}\""),
                        "must be \"antisymmetric\" (sine) or \"symmetric\" (cosine)",
                    ))
                }
            };
            Box::new(SinePulse::new(amplitude, period, cycles, shape))
        }
        "ricker" => {
            let center = s.center.unwrap_or(0.0);
            if !center.is_finite() {
                return Err(Error::invalid(
                    "excitation.center",
                    center,
                    "must be a finite number",
                ));
            }
            Box::new(Ricker {
                amplitude,
                period,
                center,
            })
        }
        "record" => {
            let (record, tail) = recorded_motion(s, base_dir)?;
            let length = record.end() + tail;
            return Ok((Box::new(record), Some(length)));
        }
        _ => Box::new(Free),
    };
    Ok((floor, None))
}

/// Standard gravity, for records in units of g (independent of the body's `gravity`).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Reads and trims the record of a `kind = "record"` section; returns it with the tail length.
fn recorded_motion(s: &ExcitationSection, base_dir: &Path) -> Result<(RecordedMotion, f64)> {
    let relative = s.path.clone().unwrap_or_default();
    let path = base_dir.join(&relative);
    let format = match s.format.as_deref() {
        None => None,
        Some("peer-at2") => Some(RecordFormat::PeerAt2),
        Some("csv") => Some(RecordFormat::Csv),
        Some(other) => {
            return Err(Error::invalid(
                "excitation.format",
                format!("\"{other}\""),
                "must be \"peer-at2\" or \"csv\"",
            ))
        }
    };
    if let Some(dt) = s.dt {
        positive("excitation.dt", dt)?;
    }
    let record = read_record(&path, format, s.dt).map_err(|e| Error::Record {
        key: "excitation.path".to_string(),
        source: e,
    })?;
    let is_at2 = matches!(format, Some(RecordFormat::PeerAt2))
        || (format.is_none() && record_format_of(&path) == Some(RecordFormat::PeerAt2));
    let units = match (s.units.as_deref(), is_at2) {
        (Some(u), _) => u,
        (None, true) => "g",
        (None, false) => {
            return Err(Error::invalid(
                "excitation.units",
                "(missing)",
                "required for CSV records: \"g\", \"m/s2\" or \"cm/s2\"",
            ))
        }
    };
    let unit_factor = match units {
        "g" => STANDARD_GRAVITY,
        "m/s2" => 1.0,
        "cm/s2" => 0.01,
        other => {
            return Err(Error::invalid(
                "excitation.units",
                format!("\"{other}\""),
                "must be \"g\", \"m/s2\" or \"cm/s2\"",
            ))
        }
    };
    let scale = s.scale.unwrap_or(1.0);
    if !scale.is_finite() {
        return Err(Error::invalid(
            "excitation.scale",
            scale,
            "must be a finite number",
        ));
    }
    let record_length = record.duration();
    let start = s.start.unwrap_or(0.0);
    let end = s.end.unwrap_or(record_length);
    if !(start.is_finite() && start >= 0.0 && start < record_length) {
        return Err(Error::invalid(
            "excitation.start",
            start,
            &format!("must lie in [0, {record_length}) s, the record's length"),
        ));
    }
    if !(end.is_finite() && end > start && end <= record_length * (1.0 + 1e-12)) {
        return Err(Error::invalid(
            "excitation.end",
            end,
            &format!("must lie in ({start}, {record_length}] s"),
        ));
    }
    let tail = s.tail.unwrap_or(0.0);
    if !(tail.is_finite() && tail >= 0.0) {
        return Err(Error::invalid("excitation.tail", tail, "must be 0 or more"));
    }
    // Trimming keeps whole samples: the first at or after `start`, the last at or before `end`.
    let first = (start / record.dt - 1e-9).ceil().max(0.0) as usize;
    let last = ((end / record.dt + 1e-9).floor() as usize).min(record.values.len() - 1);
    if last <= first {
        return Err(Error::invalid(
            "excitation.end",
            end,
            "leaves fewer than two samples of the record",
        ));
    }
    let values = record.values[first..=last]
        .iter()
        .map(|v| v * unit_factor * scale)
        .collect();
    Ok((
        RecordedMotion::new(
            format!(
                "{} (samples {}..={} of {})",
                relative,
                first,
                last,
                record.values.len()
            ),
            record.dt,
            values,
        ),
        tail,
    ))
}

fn record_format_of(path: &Path) -> Option<RecordFormat> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "at2" => Some(RecordFormat::PeerAt2),
        "csv" => Some(RecordFormat::Csv),
        _ => None,
    }
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
    if !qdot.is_finite() {
        return Err(Error::invalid(
            "simulation.qdot0",
            qdot,
            "must be a finite number",
        ));
    }
    Ok(InitialState { q, qdot })
}

fn solver_from_section(s: &SolverSection, duration: f64, omega: f64) -> Result<SolverSettings> {
    let name = s.method.as_deref().unwrap_or("bdf");
    let is_newmark = name == "newmark";
    let adaptive = AdaptiveMethod::from_name(name);
    if adaptive.is_none() && !is_newmark {
        return Err(Error::invalid(
            "solver.method",
            format!("\"{name}\""),
            "must be \"bdf\", \"esdirk34\", \"tr-bdf2\", \"tsit45\" or \"newmark\"",
        ));
    }
    // Keys of the other family of methods are mistakes, not silently ignored settings.
    let foreign: [(&str, Option<String>); 6] = [
        ("rtol", s.rtol.map(|v| v.to_string())),
        ("atol", s.atol.map(|v| v.to_string())),
        ("dt", s.dt.map(|v| v.to_string())),
        ("newmark_beta", s.newmark_beta.map(|v| v.to_string())),
        ("newmark_gamma", s.newmark_gamma.map(|v| v.to_string())),
        ("newmark_variant", s.newmark_variant.clone()),
    ];
    for (i, (key, value)) in foreign.iter().enumerate() {
        let belongs_to_newmark = i >= 2;
        if let Some(v) = value {
            if belongs_to_newmark != is_newmark {
                return Err(Error::invalid(
                    &format!("solver.{key}"),
                    v,
                    &format!("not a parameter of method = \"{name}\""),
                ));
            }
        }
    }
    let output_dt = s.output_dt.unwrap_or(DEFAULT_OUTPUT_DT);
    positive("solver.output_dt", output_dt)?;
    if duration / output_dt > MAX_SAMPLES {
        return Err(Error::invalid(
            "solver.output_dt",
            output_dt,
            &format!("gives more than {MAX_SAMPLES:e} history rows over {duration} s; choose a larger spacing"),
        ));
    }
    match adaptive {
        Some(method) => {
            let rtol = s.rtol.unwrap_or(DEFAULT_RTOL);
            if !(rtol > 0.0 && rtol < 1.0) {
                return Err(Error::invalid(
                    "solver.rtol",
                    rtol,
                    "the relative tolerance must lie in (0, 1)",
                ));
            }
            let atol = s.atol.unwrap_or(DEFAULT_ATOL);
            positive("solver.atol", atol)?;
            Ok(SolverSettings::Adaptive(AdaptiveSettings {
                method,
                rtol,
                atol,
                output_dt,
            }))
        }
        None => newmark_from_section(s, duration, omega, output_dt).map(SolverSettings::Newmark),
    }
}

fn newmark_from_section(
    s: &SolverSection,
    duration: f64,
    omega: f64,
    output_dt: f64,
) -> Result<NewmarkSettings> {
    let dt = s.dt.unwrap_or(DEFAULT_NEWMARK_DT);
    positive("solver.dt", dt)?;
    if duration / dt > MAX_NEWMARK_STEPS {
        return Err(Error::invalid(
            "solver.dt",
            dt,
            &format!("gives more than {MAX_NEWMARK_STEPS:e} steps over {duration} s; choose a larger step"),
        ));
    }
    let gamma = s.newmark_gamma.unwrap_or(DEFAULT_NEWMARK_GAMMA);
    if !(0.5..=1.0).contains(&gamma) {
        return Err(Error::invalid(
            "solver.newmark_gamma",
            gamma,
            "must lie in [1/2, 1] (below 1/2 Newmark's method amplifies every oscillation)",
        ));
    }
    let beta = s.newmark_beta.unwrap_or(DEFAULT_NEWMARK_BETA);
    if !(0.0..=0.5).contains(&beta) {
        return Err(Error::invalid(
            "solver.newmark_beta",
            beta,
            "must lie in [0, 1/2]",
        ));
    }
    let variant_name = s.newmark_variant.as_deref().unwrap_or("compensate");
    let variant = NewmarkVariant::from_name(variant_name).ok_or_else(|| {
        Error::invalid(
            "solver.newmark_variant",
            format!("\"{variant_name}\""),
            "must be \"compensate\" or \"substep\"",
        )
    })?;
    // Only the pre-uplift omega can make the method unstable: see critical_omega_dt.
    if let Some(limit) = critical_omega_dt(beta, gamma) {
        let dt_limit = limit / omega;
        if dt >= dt_limit {
            let period = 2.0 * std::f64::consts::PI / omega;
            return Err(Error::invalid(
                "solver.dt",
                dt,
                &format!(
                    "Newmark with beta = {beta:.6}, gamma = {gamma} is stable only for dt < {dt_limit:.6} s \
                     = {:.4} T (pre-uplift period T = {period:.6} s): omega dt must stay below 1/sqrt(gamma/2 - beta) = {limit:.6}; \
                     choose a smaller dt, or beta >= gamma/2 (e.g. 1/4) for unconditional stability",
                    dt_limit / period
                ),
            ));
        }
    }
    Ok(NewmarkSettings {
        dt,
        beta,
        gamma,
        variant,
        output_dt,
    })
}

/// A validated finite element analysis: the plane-stress body and the run settings.
#[derive(Debug, Clone, Serialize)]
pub struct FemSetup {
    pub body: FemBody,
    pub settings: FemSettings,
    /// The scheme's name as written in the model file.
    pub scheme_name: &'static str,
}

pub const DEFAULT_FEM_NX: usize = 2;
pub const DEFAULT_FEM_NY: usize = 5;
pub const DEFAULT_FEM_DT: f64 = 0.0071;
pub const DEFAULT_FEM_THETA: f64 = 1.4;
pub const DEFAULT_FEM_MU_S: f64 = 0.8;
pub const DEFAULT_FEM_MU_K: f64 = 0.4;
/// Deformed shapes are stored at these times (the paper's Fig. 9), s.
pub const FEM_SNAPSHOT_TIMES: [f64; 6] = [0.9, 1.0, 1.1, 1.2, 1.3, 1.4];

/// Builds the finite element analysis from `[body]` and `[fem]`. The plane-stress body takes
/// E = 12 EI/(D B^3) and the density M/(H B D) from the validated body, so every way of giving
/// the stiffness and the mass works; the damping period defaults to the pre-uplift period T.
pub fn fem_from_section(
    file: &ModelFile,
    body: &Body,
    constants: &Constants,
    simulation_duration: f64,
) -> Result<FemSetup> {
    let default = FemSection::default();
    let s = file.fem.as_ref().unwrap_or(&default);
    let poisson_ratio = file.body.poisson_ratio.unwrap_or(DEFAULT_POISSON_RATIO);
    if !(poisson_ratio.is_finite() && (0.0..0.5).contains(&poisson_ratio)) {
        return Err(Error::invalid(
            "body.poisson_ratio",
            poisson_ratio,
            "Poisson's ratio must lie in [0, 0.5)",
        ));
    }
    let nx = s.nx.unwrap_or(DEFAULT_FEM_NX);
    let ny = s.ny.unwrap_or(DEFAULT_FEM_NY);
    for (key, n) in [("fem.nx", nx), ("fem.ny", ny)] {
        if !(1..=1000).contains(&n) {
            return Err(Error::invalid(
                key,
                n,
                "the number of elements must lie in 1..=1000",
            ));
        }
    }
    if nx * ny > 200_000 {
        return Err(Error::invalid(
            "fem.nx",
            format!("{nx} (with fem.ny = {ny})"),
            "the mesh must have at most 200000 elements",
        ));
    }
    let dt = s.dt.unwrap_or(DEFAULT_FEM_DT);
    positive("fem.dt", dt)?;
    let duration = s.duration.unwrap_or(simulation_duration);
    positive("fem.duration", duration)?;
    if duration / dt > 1e7 {
        return Err(Error::invalid(
            "fem.dt",
            dt,
            &format!("gives more than 1e7 steps over {duration} s; choose a larger step"),
        ));
    }
    let name = s.scheme.as_deref().unwrap_or("linear-acceleration");
    let (scheme, scheme_name) = match name {
        "linear-acceleration" => (TimeScheme::linear_acceleration(), "linear-acceleration"),
        "average-acceleration" => (TimeScheme::average_acceleration(), "average-acceleration"),
        "wilson-theta" => {
            let theta = s.theta.unwrap_or(DEFAULT_FEM_THETA);
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(Error::invalid("fem.theta", theta, "must lie in [1, 3]"));
            }
            (TimeScheme::WilsonTheta { theta }, "wilson-theta")
        }
        other => {
            return Err(Error::invalid(
                "fem.scheme",
                format!("\"{other}\""),
                "must be \"linear-acceleration\", \"average-acceleration\" or \"wilson-theta\"",
            ))
        }
    };
    if let (Some(theta), false) = (s.theta, scheme_name == "wilson-theta") {
        return Err(Error::invalid(
            "fem.theta",
            theta,
            &format!("not a parameter of scheme = \"{scheme_name}\" (only of \"wilson-theta\")"),
        ));
    }
    let mu_s = s.mu_s.unwrap_or(DEFAULT_FEM_MU_S);
    let mu_k = s.mu_k.unwrap_or(DEFAULT_FEM_MU_K);
    for (key, mu) in [("fem.mu_s", mu_s), ("fem.mu_k", mu_k)] {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::invalid(
                key,
                mu,
                "a friction coefficient must be finite and >= 0",
            ));
        }
    }
    if mu_k > mu_s {
        return Err(Error::invalid(
            "fem.mu_k",
            mu_k,
            &format!("kinetic friction cannot exceed static friction (fem.mu_s = {mu_s})"),
        ));
    }
    let damping_period = s.damping_period.unwrap_or(constants.period);
    positive("fem.damping_period", damping_period)?;
    let fem_body = FemBody {
        height: body.height,
        width: body.width,
        depth: body.depth,
        density: body.mass / (body.height * body.width * body.depth),
        youngs_modulus: 12.0 * body.flexural_rigidity / (body.depth * body.width.powi(3)),
        poisson_ratio,
        damping_ratio: body.damping_ratio,
        damping_period,
        gravity: body.gravity,
    };
    let settings = FemSettings {
        nx,
        ny,
        dt,
        duration,
        scheme,
        mu_s,
        mu_k,
        p_delta: s.p_delta.unwrap_or(true),
        snapshot_times: FEM_SNAPSHOT_TIMES.to_vec(),
        initial_rotation: 0.0,
    };
    Ok(FemSetup {
        body: fem_body,
        settings,
        scheme_name,
    })
}
