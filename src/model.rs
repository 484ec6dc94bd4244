//! The TOML model file: its schema (key names are a contract), defaults and validation.
//!
//! A model file is read into [`ModelFile`] exactly as written (unknown keys are errors), then
//! [`Model::from_file`] applies the defaults, checks every rule and derives the constants.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::body::{positive, Body, ConstantSet};
use crate::constants::Constants;
use crate::error::{Error, Result};
use crate::excitation::{FloorMotion, Free, Harmonic, PaperSine};
use crate::fem::{FemBody, FemSettings, TimeScheme};
use crate::solver::adaptive::{AdaptiveMethod, AdaptiveSettings};
use crate::solver::InitialState;

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
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationSection {
    pub duration: f64,
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
}

pub const DEFAULT_DEPTH: f64 = 1.0;
pub const DEFAULT_DAMPING_RATIO: f64 = 0.05;
pub const DEFAULT_GRAVITY: f64 = 9.81;
pub const DEFAULT_RTOL: f64 = 1e-10;
pub const DEFAULT_ATOL: f64 = 1e-12;
pub const DEFAULT_OUTPUT_DT: f64 = 0.005;
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
    pub solver: AdaptiveSettings,
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
        let mut model = Model::from_file(file, overrides).map_err(|e| Error::InModel {
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
        Model::from_file(file, overrides)
    }

    /// Validates a parsed model file.
    pub fn from_file(mut file: ModelFile, overrides: &Overrides) -> Result<Model> {
        if let Some(m) = &overrides.method {
            file.solver.method = Some(m.clone());
        }
        if let Some(r) = overrides.rtol {
            file.solver.rtol = Some(r);
        }
        if let Some(a) = overrides.atol {
            file.solver.atol = Some(a);
        }
        if let Some(d) = overrides.duration {
            file.simulation.duration = d;
        }

        let body = body_from_section(&file.body)?;
        let constants = Constants::new(&body)?;
        let duration = file.simulation.duration;
        positive("simulation.duration", duration)?;
        let floor = floor_from_section(&file.excitation)?;
        let initial = initial_from_section(&file.simulation, &body)?;
        let solver = solver_from_section(&file.solver, duration)?;
        let fem = fem_from_section(&file, &body, &constants)?;
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
        fem_from_section(&file, &self.body, &self.constants)
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

fn floor_from_section(s: &ExcitationSection) -> Result<Box<dyn FloorMotion>> {
    let kind = s.kind.as_str();
    let keys = [
        ("amplitude", s.amplitude),
        ("period", s.period),
        ("ramp", s.ramp),
    ];
    let allowed: &[&str] = match kind {
        "paper-sine" => &["amplitude", "period", "ramp"],
        "harmonic" => &["amplitude", "period"],
        "free" => &[],
        other => {
            return Err(Error::invalid(
                "excitation.kind",
                format!("\"{other}\""),
                "must be \"paper-sine\", \"harmonic\" or \"free\"",
            ))
        }
    };
    for (key, value) in keys {
        match (value, allowed.contains(&key)) {
            (Some(v), false) => {
                return Err(Error::invalid(
                    &format!("excitation.{key}"),
                    v,
                    &format!("not a parameter of kind = \"{kind}\""),
                ))
            }
            (None, true) => {
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
    Ok(match kind {
        "paper-sine" => {
            let (period, ramp) = (s.period.unwrap_or(0.0), s.ramp.unwrap_or(0.0));
            positive("excitation.period", period)?;
            positive("excitation.ramp", ramp)?;
            Box::new(PaperSine::new(amplitude, period, ramp))
        }
        "harmonic" => {
            let period = s.period.unwrap_or(0.0);
            positive("excitation.period", period)?;
            Box::new(Harmonic { amplitude, period })
        }
        _ => Box::new(Free),
    })
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

fn solver_from_section(s: &SolverSection, duration: f64) -> Result<AdaptiveSettings> {
    let name = s.method.as_deref().unwrap_or("bdf");
    let method = AdaptiveMethod::from_name(name).ok_or_else(|| {
        Error::invalid(
            "solver.method",
            format!("\"{name}\""),
            "must be \"bdf\", \"esdirk34\" or \"tr-bdf2\"",
        )
    })?;
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
    let output_dt = s.output_dt.unwrap_or(DEFAULT_OUTPUT_DT);
    positive("solver.output_dt", output_dt)?;
    if duration / output_dt > MAX_SAMPLES {
        return Err(Error::invalid(
            "solver.output_dt",
            output_dt,
            &format!("gives more than {MAX_SAMPLES:e} history rows over {duration} s; choose a larger spacing"),
        ));
    }
    Ok(AdaptiveSettings {
        method,
        rtol,
        atol,
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
pub fn fem_from_section(file: &ModelFile, body: &Body, constants: &Constants) -> Result<FemSetup> {
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
    let duration = s.duration.unwrap_or(file.simulation.duration);
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
