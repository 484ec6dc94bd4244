//! The model file's schema: its sections exactly as written (key names are a contract; unknown
//! keys are errors) and the defaults the core uses for keys a file leaves out.

use serde::{Deserialize, Serialize};

pub use crate::base::limits::MAX_DURATION;

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
    /// Settings of `flexrock fem` (optional; see [`Model::fem_with`](super::Model::fem_with)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fem: Option<FemSection>,
}

impl ModelFile {
    /// The field of `key` (`section.name`) where it is an optional number of the body,
    /// excitation, simulation or solver section; None for any other key. A number set here is
    /// what reading the section again with the key set to it gives.
    pub(crate) fn number_mut(&mut self, key: &str) -> Option<&mut Option<f64>> {
        let (section, name) = key.split_once('.')?;
        let (b, e, s, v) = (
            &mut self.body,
            &mut self.excitation,
            &mut self.simulation,
            &mut self.solver,
        );
        Some(match (section, name) {
            ("body", "depth") => &mut b.depth,
            ("body", "density") => &mut b.density,
            ("body", "mass") => &mut b.mass,
            ("body", "youngs_modulus") => &mut b.youngs_modulus,
            ("body", "flexural_rigidity") => &mut b.flexural_rigidity,
            ("body", "period") => &mut b.period,
            ("body", "damping_ratio") => &mut b.damping_ratio,
            ("body", "gravity") => &mut b.gravity,
            ("body", "poisson_ratio") => &mut b.poisson_ratio,
            ("excitation", "amplitude") => &mut e.amplitude,
            ("excitation", "period") => &mut e.period,
            ("excitation", "ramp") => &mut e.ramp,
            ("excitation", "cycles") => &mut e.cycles,
            ("excitation", "center") => &mut e.center,
            ("excitation", "scale") => &mut e.scale,
            ("excitation", "start") => &mut e.start,
            ("excitation", "end") => &mut e.end,
            ("excitation", "tail") => &mut e.tail,
            ("excitation", "dt") => &mut e.dt,
            ("simulation", "duration") => &mut s.duration,
            ("simulation", "q0") => &mut s.q0,
            ("simulation", "qdot0") => &mut s.qdot0,
            ("solver", "rtol") => &mut v.rtol,
            ("solver", "atol") => &mut v.atol,
            ("solver", "output_dt") => &mut v.output_dt,
            ("solver", "dt") => &mut v.dt,
            ("solver", "newmark_beta") => &mut v.newmark_beta,
            ("solver", "newmark_gamma") => &mut v.newmark_gamma,
            _ => return None,
        })
    }
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
    /// e, the factor on q' at every landing on top of the reset q' -> q'/zetaL, in (0, 1]
    /// (default 1, the paper's landing). Left out of a written file when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub landing_restitution: Option<f64>,
    /// Whether the strain-rate damping term acts while rocking (default true, as the paper).
    /// Left out of a written file when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping_while_rocking: Option<bool>,
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
            landing_restitution,
            damping_while_rocking,
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
                (landing_restitution, &other.landing_restitution),
            ]
            .iter()
            .all(|(a, b)| bits(a) == bits(b))
            && *constants == other.constants
            && *self_weight == other.self_weight
            && *damping_while_rocking == other.damping_while_rocking
    }
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
/// The `[excitation]` table: the floor motion.
pub struct ExcitationSection {
    /// Which floor motion, e.g. "paper-sine", "sine-pulse", "ricker" or "record"; in
    /// `[excitation.vertical]` also "ratio", the kind when only `ratio` is given.
    #[serde(default, skip_serializing_if = "String::is_empty")]
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
    /// ratio (`[excitation.vertical]` only): a_v(t) = ratio x the horizontal a(t). Not
    /// written when None, so that the files that echo the section are unchanged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// The floor's vertical acceleration (upwards positive), a table of the same keys.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertical: Option<Box<ExcitationSection>>,
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
