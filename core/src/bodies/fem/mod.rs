//! 2D plane-stress finite element model of an elastic prismatic body rocking on a rigid floor,
//! after the verification analysis of Ichinose (1986), Section 3.
//!
//! Units are SI throughout: metres, seconds, kilograms, newtons, pascals. x is horizontal
//! (positive to the right), y vertical (positive up); the body occupies `0 <= x <= width`,
//! `0 <= y <= height` undeformed, with its base on the floor at y = 0. The left toe is
//! (0, 0), the right toe (width, 0).
//!
//! # Discretisation
//!
//! * **Element**: 4-node incompatible-mode quadrilateral QM6 (Wilson-Taylor), plane stress,
//!   thickness = `depth`, 2 x 2 Gauss integration, the four bubble modes condensed statically.
//!   Chosen because a bilinear Q4 locks in shear when bent (a 2 x 5 mesh of the slender body
//!   would be several times too stiff), whereas QM6 represents pure bending of rectangles
//!   exactly at the cost of a 4-node stencil that keeps the matrices narrow-banded. Taylor's
//!   centre-Jacobian correction keeps the constant-strain patch test exact on distorted meshes.
//! * **Mass**: lumped, row-sum of the consistent mass (each node gets ∫ N_a ρ D dA; a quarter of
//!   each adjacent rectangle). Diagonal, so gravity loads, the inertial floor load and
//!   the impact of a landing node are all node-local.
//! * **Gravity**: applied statically first with every base node pinned; the body then starts
//!   from this state (u = u_g, at rest).
//! * **P-Delta** (`p_delta`, default true): the geometric (initial-stress) stiffness K_σ of the
//!   static gravity stresses (all element stresses, incompatible modes included, integrated with
//!   the bilinear shape-function gradients) is added to K. It acts on u - u_g only: the
//!   constant load vector is F_g + K_σ u_g, so the static state is unchanged. For a rigid
//!   rotation θ about a toe it supplies the second-order moment -M g (H/2) θ, so the weight's
//!   moment about the toe is M g (B - q)/2 for small rotations and the body can overturn
//!   (the restoring force vanishes at q = B as in the SDOF model, book/src/model.md §3).
//!   Without it the restoring moment of a linear model stays at M g B/2 after uplift.
//!   The formulation remains geometrically linear (small rotations).
//! * **Damping**: \[C\] = (h T_d/π)\[K\] with the *elastic* K only. K_σ is left out of C: the
//!   paper's damping is a property of the material, it stays positive semi-definite, and it is
//!   the same with and without P-Delta.
//!
//! # Floor, contact and friction
//!
//! Displacements and velocities are relative to the floor; the floor acceleration a(t) enters
//! as the horizontal inertial load -m a(t) on every node. Each base node is
//! [`ContactState::Free`] (no constraint), [`ContactState::Slip`] (uy = 0; the kinetic
//! friction force Rx = s μk Ry acts on its x dof, s = ±1 the friction direction chosen at slip
//! onset as the sign of Rx then, i.e. opposing the slip) or [`ContactState::Fixed`] (uy = 0 and
//! ux held where it was when the node stuck — 0 unless the node slipped earlier; the paper's
//! "stay at the position of the previous time step"). Constrained dofs have zero velocity
//! and acceleration. The reactions (Rx, Ry) of the constrained dofs are the equilibrium
//! residuals M a + C v + K_t u - F at the end of the step.
//!
//! State changes follow the paper: they are decided from the solution at the end of step n and
//! apply from step n + 1 (no re-solution of step n):
//!
//! | from | condition | to | applied to the state at t_n |
//! |---|---|---|---|
//! | Free | uy <= 0 | Fixed | uy = 0, node velocity and acceleration = 0 (plastic impact of the node), ux held |
//! | Fixed | Ry < 0 | Free | - |
//! | Fixed | Ry >= 0 and \|Rx\| > μs Ry | Slip | friction direction s = sign(Rx) |
//! | Slip | Ry < 0 | Free | - |
//! | Slip | Ry >= 0 and s ux' >= 0 | Fixed | node velocity and acceleration = 0, ux held |
//!
//! The last row is the paper's `Rx ux' >= 0` with Rx = s μk Ry written through its sign, so
//! that a frictionless (μk = 0) node still slides instead of re-sticking at once.
//! Setting the landing node's velocity to zero is a plastic impact of that node's lumped
//! mass only; the rest of the body is stopped through the elastic body over the next steps.
//! Within a step the only iteration is on the friction force of slipping nodes (fixed-point
//! on Ry, at most 10 re-solves with the same factors), so friction is implicit in Ry.
//! The effective stiffness is factorised once per distinct constraint pattern and cached.
//!
//! # Time integration
//!
//! [`TimeScheme::Newmark`] (β, γ) in displacement form; β = 1/6, γ = 1/2 is the paper's linear
//! acceleration method (stable for dt <= sqrt(12)/ω_max = 0.551 T_min, undamped or damped since
//! γ = 1/2), β = 1/4 the unconditionally stable average acceleration. [`TimeScheme::WilsonTheta`]
//! solves the linear acceleration step over θ dt with the load extrapolated linearly and
//! interpolates back (θ >= 1.37 is unconditionally stable; θ = 1.4 usual). Use
//! [`stability_limit`] / [`critical_time_step`] to warn or refuse before running;
//! [`FemResult::critical_time_step`] repeats the check for the settings used.
//!
//! # Output decomposition of the top displacement
//!
//! With θ_j = (uy(0, y_j) - uy(B, y_j))/B the rotation of the node row j (clockwise positive,
//! from the two edge nodes), the top displacement q = mean ux of the top nodes splits exactly:
//! * rocking r = θ_0 H (base rotation from the two base corners' uplift difference);
//! * slipping = mean ux of the base nodes;
//! * flexural s = ∫_0^H (θ(y) - θ_0) dy, trapezoidal over the node rows;
//! * shearing = q - r - slipping - s (the remainder: shear strain plus any non-plane-section
//!   warping of the rows).
//!
//! # Static pushover and the meaning of "uplift"
//!
//! [`pushover`] applies lateral loads λ m U(y) (U the first cantilever mode) from the gravity
//! state under top-displacement control; base nodes in contact are held in x and y, and leave
//! or re-enter contact by a no-tension/no-penetration active-set iteration.
//!
//! On the flexible base ([`BaseSupport::Flexible`], the paper's) a continuum on a rigid floor
//! has no sharp uplift: its base starts to open at the heel once the base moment passes roughly
//! the kern value (≈ M g B/6) and the contact zone then shrinks towards the toe.
//! [`PushoverPoint::heel_lifted`] marks the opening, [`PushoverPoint::uplift`] the state where
//! only one corner node is on the floor. For a stiff body (E = 500 MPa) the curve still follows
//! the SDOF model closely (its pre-uplift line and rocking line meet within 3 % of s_n, and the
//! rocking branch matches F(q) within 2 % for 0.1 B <= q <= 0.6 B). For the paper's soft body
//! (E = 5 MPa, toe strains of several %) the contact zone at the toe stays 1/4-1/3 of B wide:
//! the base shear peaks at about 1050 N near q ≈ 0.205 m (mesh-converged from 8 x 40 to
//! 32 x 80).
//!
//! On a rigid base plate ([`BaseSupport::RigidPlate`]) the base stays flat until the base moment
//! reaches N B/2 and then pivots about the toe, as the beam-column model of book/src/model.md §7a
//! (a rigid base section on toe springs) and the SDOF model assume: the reference body lifts off at
//! q = 0.194 m with 1549 N (beam-column: 0.1895 m, 1565 N). The plate is a set of penalty springs
//! on the base nodes (stretching and the second difference of uy) 1e4 times stiffer than the body's
//! base section; the results do not change from 1e3 to 1e5.
//!
//! # Stability of the paper's run
//!
//! With the lumped mass and the base free the 2 x 5 mesh has ω_max = 539.1 rad/s
//! (T_min = 0.01165 s; 534.6 rad/s with the base held), so the linear acceleration limit is
//! dt = 0.00643 s and the paper's dt = 0.0071 s lies beyond it.
//! The run does not blow up (every contact change resets the growing highest mode) but it
//! shows spurious contact chatter (5x the state changes of an average-acceleration run);
//! dt <= 0.0064 s, average acceleration or Wilson θ = 1.4 avoid it.

mod banded;
mod dynamics;
mod eigen;
mod element;
mod mesh;
mod model;
mod pushover;
#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use dynamics::simulate_fem;
pub use pushover::pushover;

use banded::BandedSym;
use model::Model;

/// The elastic body (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemBody {
    /// Height H, m.
    pub height: f64,
    /// In-plane width B, m.
    pub width: f64,
    /// Out-of-plane depth D (plane-stress thickness), m.
    pub depth: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Damping ratio h of \[C\] = (h T_d/π)\[K\], dimensionless.
    pub damping_ratio: f64,
    /// Period T_d at which the stiffness-proportional damping equals h, s.
    pub damping_period: f64,
    /// Gravity acceleration g, m/s².
    pub gravity: f64,
    /// How the base meets the floor.
    #[serde(default)]
    pub base: BaseSupport,
}

/// How the body's base meets the floor.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BaseSupport {
    /// Every base node touches the floor on its own (the paper's model): the continuum's base
    /// opens progressively from the heel.
    #[default]
    Flexible,
    /// The base nodes are tied to a weightless rigid plate (ux equal, uy linear in x), the base
    /// section of the beam-column model of book/src/model.md §7a: the plate stays flat until the
    /// base moment reaches N B/2, then pivots about a corner.
    RigidPlate,
}

impl BaseSupport {
    /// The name used in model files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            BaseSupport::Flexible => "flexible",
            BaseSupport::RigidPlate => "rigid-plate",
        }
    }

    /// The base support spelled `name` in a model file.
    pub fn from_name(name: &str) -> Option<Self> {
        [BaseSupport::Flexible, BaseSupport::RigidPlate]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

impl FemBody {
    /// The paper's body: H = 4 m, B = 0.7 m, D = 1 m, 600 kg/m³, E = 5 MPa, ν = 0.25,
    /// h = 0.05 at T_d = 1.55 s, g = 9.81 m/s².
    pub fn reference() -> Self {
        Self {
            height: 4.0,
            width: 0.7,
            depth: 1.0,
            density: 600.0,
            youngs_modulus: 5.0e6,
            poisson_ratio: 0.25,
            damping_ratio: 0.05,
            damping_period: 1.55,
            gravity: 9.81,
            base: BaseSupport::Flexible,
        }
    }

    /// Total mass M, kg.
    pub fn mass(&self) -> f64 {
        crate::physics::body::prism_mass(self.density, self.height, self.width, self.depth)
    }

    /// Flexural rigidity EI = E D B³/12, N m².
    pub fn flexural_rigidity(&self) -> f64 {
        crate::physics::body::solid_section_flexural_rigidity(
            self.youngs_modulus,
            self.width,
            self.depth,
        )
    }
}

impl Default for FemBody {
    fn default() -> Self {
        Self::reference()
    }
}

/// Time-stepping scheme.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TimeScheme {
    /// Newmark family: 0 < β <= 1/2, 1/2 <= γ <= 1.
    Newmark {
        /// β.
        beta: f64,
        /// γ.
        gamma: f64,
    },
    /// Wilson θ (linear acceleration over θ dt), θ >= 1.
    WilsonTheta {
        /// θ.
        theta: f64,
    },
}

impl TimeScheme {
    /// Linear acceleration method (Newmark β = 1/6, γ = 1/2), the paper's scheme.
    pub fn linear_acceleration() -> Self {
        Self::Newmark {
            beta: 1.0 / 6.0,
            gamma: 0.5,
        }
    }
    /// Average acceleration (Newmark β = 1/4, γ = 1/2), unconditionally stable.
    pub fn average_acceleration() -> Self {
        Self::Newmark {
            beta: 0.25,
            gamma: 0.5,
        }
    }
    /// Wilson θ = 1.4.
    pub fn wilson() -> Self {
        Self::WilsonTheta { theta: 1.4 }
    }
}

/// Mesh, time stepping, friction and output settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemSettings {
    /// Elements across the width (>= 1).
    pub nx: usize,
    /// Elements up the height (>= 1).
    pub ny: usize,
    /// Time step, s.
    pub dt: f64,
    /// Duration of the run, s.
    pub duration: f64,
    /// The time-stepping scheme.
    pub scheme: TimeScheme,
    /// Static friction coefficient μs.
    pub mu_s: f64,
    /// Kinetic friction coefficient μk <= μs.
    pub mu_k: f64,
    /// Include the geometric stiffness of the gravity prestress.
    pub p_delta: bool,
    /// Times (s) at which nodal displacements are stored (the first step at or after each).
    pub snapshot_times: Vec<f64>,
    /// Initial rigid rotation (rad, clockwise positive) about the right toe if positive, about
    /// the left toe if negative, applied at rest on top of the gravity state; the other base
    /// nodes start Free. 0 = upright.
    pub initial_rotation: f64,
}

impl FemSettings {
    /// The paper's analysis: 2 x 5 mesh, dt = 0.0071 s, 6 s, linear acceleration,
    /// μs = 0.8, μk = 0.4, with P-Delta.
    pub fn paper() -> Self {
        Self {
            nx: 2,
            ny: 5,
            dt: 0.0071,
            duration: 6.0,
            scheme: TimeScheme::linear_acceleration(),
            mu_s: 0.8,
            mu_k: 0.4,
            p_delta: true,
            snapshot_times: Vec::new(),
            initial_rotation: 0.0,
        }
    }
}

impl Default for FemSettings {
    fn default() -> Self {
        Self::paper()
    }
}

/// Contact state of a base node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ContactState {
    /// Uplifted: no constraint.
    Free,
    /// On the floor, sliding: uy = 0, kinetic friction.
    Slip,
    /// On the floor, stuck: ux and uy held.
    Fixed,
}

/// One output step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemStep {
    /// Time, s.
    pub t: f64,
    /// Top displacement relative to the floor (mean ux of the top nodes), m.
    pub q: f64,
    /// Rocking part r = H (uy_left_corner - uy_right_corner)/B, m.
    pub rocking: f64,
    /// Slipping part: mean ux of the base nodes, m.
    pub slipping: f64,
    /// Flexural part s: integrated section rotation relative to the base, m.
    pub flexural: f64,
    /// Shearing part: q - rocking - slipping - flexural, m.
    pub shearing: f64,
    /// Top velocity relative to the floor (mean vx of the top nodes), m/s.
    pub top_velocity: f64,
    /// Angular momentum about the left toe, Σ m (Δy vx - Δx vy) with deformed positions and
    /// velocities relative to the floor, clockwise positive (same sign as q'), kg m²/s.
    pub momentum_left_toe: f64,
    /// Angular momentum about the right toe (same convention), kg m²/s.
    pub momentum_right_toe: f64,
    /// Lowest vertical displacement of a base node, m (negative = below the floor).
    pub lowest_base_uy: f64,
    /// State of each base node, left to right.
    pub base_states: Vec<ContactState>,
}

/// A base-node state change.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactEvent {
    /// Time of the step whose solution triggered the change (it applies from the next step), s.
    pub t: f64,
    /// Base node index, 0 = left corner .. nx = right corner.
    pub node: usize,
    /// The state before the change.
    pub from: ContactState,
    /// The state after the change.
    pub to: ContactState,
    /// Reactions at that step (0 for a Free node), N: horizontal Rx.
    pub rx: f64,
    /// Vertical reaction Ry at that step, N.
    pub ry: f64,
}

/// Nodal displacements at one time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// Requested time, s.
    pub requested: f64,
    /// Time of the stored step, s.
    pub t: f64,
    /// (ux, uy) of every node relative to the floor, m (node order of
    /// [`FemResult::node_coordinates`]).
    pub displacements: Vec<[f64; 2]>,
}

/// Result of [`simulate_fem`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemResult {
    /// One entry per time step, t = 0 first.
    pub steps: Vec<FemStep>,
    /// Every base-node state change, in order.
    pub events: Vec<ContactEvent>,
    /// The displacements at the requested snapshot times.
    pub snapshots: Vec<Snapshot>,
    /// Undeformed node coordinates (x, y), m; node (i, j) is `j (nx + 1) + i`.
    pub node_coordinates: Vec<[f64; 2]>,
    /// Static gravity reactions (Rx, Ry) of the base nodes, N.
    pub static_reactions: Vec<[f64; 2]>,
    /// Highest fixed-base circular frequency of the mesh, rad/s.
    pub highest_frequency: f64,
    /// Stability limit of the scheme on this mesh, s (None = unconditionally stable).
    pub critical_time_step: Option<f64>,
    /// Time at which |q| exceeded the width B (static overturning limit); the run stops there.
    pub overturned_at: Option<f64>,
}

/// A static pushover curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pushover {
    /// One point per requested top displacement, in order, up to where the curve ended.
    pub points: Vec<PushoverPoint>,
    /// The first requested q at which the body, standing on one corner, turned about it
    /// freely (no stiffness: without P-Delta the restoring moment stays at its uplift value), so
    /// the displacement-controlled sweep stopped there.
    pub free_rotation_at: Option<f64>,
}

/// A pushover point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PushoverPoint {
    /// Prescribed top displacement q (mean ux of the top nodes), m.
    pub q: f64,
    /// Base shear = sum of the applied lateral loads, N.
    pub base_shear: f64,
    /// Load factor λ of the pattern m U(y) λ, m/s².
    pub load_factor: f64,
    /// True when the body rocks on one toe: every base node but one corner is off the floor
    /// (the discrete counterpart of the SDOF model's uplift).
    pub uplift: bool,
    /// True when at least one corner is off the floor (the base has started to open).
    pub heel_lifted: bool,
    /// Number of base nodes on the floor (no gap).
    pub contact_nodes: usize,
    /// Flexural part s, m.
    pub flexural: f64,
    /// Rocking part r, m.
    pub rocking: f64,
    /// Shearing part (remainder), m.
    pub shearing: f64,
    /// True when no contact set was exactly admissible and the least violating contiguous
    /// contact zone was taken (violation <= 1 % of |q| or of the weight; see [`pushover`]).
    pub approximate_contact: bool,
}

/// Errors, naming the parameter, its value and the rule broken.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FemError {
    /// A parameter breaks a rule.
    #[error("invalid parameter `{name}` = {value}: {rule}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value, as quoted in the message.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// An element's Jacobian determinant is not positive (the element is inverted or flat).
    #[error("degenerate element: {detail}")]
    DegenerateElement {
        /// Where the Jacobian fails, and its determinant.
        detail: String,
    },
    /// A linear system has no unique solution.
    #[error("singular system: {context}")]
    SingularMatrix {
        /// Which system.
        context: String,
    },
    /// The displacements became non-finite or larger than 1e6 m.
    #[error(
        "solution diverged at t = {t} s (non-finite or |u| > 1e6 m); dt may exceed the stability limit"
    )]
    Diverged {
        /// Time of the step that diverged, s.
        t: f64,
    },
    /// The base contact states did not settle.
    #[error("contact iteration did not converge at {context}")]
    ContactNotConverged {
        /// Where, e.g. the pushover displacement.
        context: String,
    },
}

fn invalid(name: &'static str, value: impl crate::base::format::Quoted, rule: &str) -> FemError {
    FemError::InvalidParameter {
        name,
        value: value.quoted(),
        rule: rule.to_string(),
    }
}

fn check_positive(name: &'static str, v: f64) -> Result<(), FemError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(name, v, "must be finite and > 0"))
    }
}

// Size limits of an analysis. They live here and only here: `model::fem_section` applies them
// to the model file and the command line (naming the keys and flags), `validate_mesh` and
// `validate_settings` to direct calls of the library.

/// Most elements along either side of the mesh.
pub const MAX_ELEMENTS_PER_SIDE: usize = 1000;

/// Most entries of one banded matrix of the mesh: 4e6 entries of 8 bytes are 32 MB. The dofs
/// (node rows numbered across the width) give 2 (nx+1)(ny+1) rows of 2 nx + 6 entries (the
/// half-bandwidth 2 nx + 5 and the diagonal). A dynamic run holds about six such matrices (K,
/// K_sigma, the tangent, C, the effective matrix and one being factorised) and a cache of
/// factors capped at [`FACTOR_CACHE_BYTES`], so at most about 0.5 GB. The 8 x 40 mesh has
/// 16 236 entries, 32 x 80 has 374 220, 64 x 160 has 2.8e6.
pub const MAX_BAND_ENTRIES: f64 = 4.0e6;

/// Memory the cache of factorised effective matrices (one per base contact pattern) may use.
pub const FACTOR_CACHE_BYTES: f64 = 256.0 * 1024.0 * 1024.0;

/// Most time steps of a dynamic run (each a row of fem_history.csv and a point of every
/// figure: 1e6 steps are some 250 MB of history text).
pub const MAX_STEPS: f64 = 1.0e6;

/// Most work of a dynamic run, in steps x band entries: each step solves with a banded factor
/// (a few flops per entry). The 8 x 40 mesh runs its 845 steps (1.4e7) in 0.14 s on the
/// 2-core machine of the README's timings, so the limit is about 100 s there.
pub const MAX_STEP_WORK: f64 = 1.0e10;

/// Entries of one banded matrix of an nx x ny mesh (see [`MAX_BAND_ENTRIES`]).
pub fn band_entries(nx: usize, ny: usize) -> f64 {
    2.0 * (nx as f64 + 1.0) * (ny as f64 + 1.0) * (2.0 * nx as f64 + 6.0)
}

/// The size limit an analysis breaks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SizeLimit {
    /// nx outside 1..=[`MAX_ELEMENTS_PER_SIDE`].
    Nx(usize),
    /// ny outside 1..=[`MAX_ELEMENTS_PER_SIDE`].
    Ny(usize),
    /// The mesh's banded matrices are larger than [`MAX_BAND_ENTRIES`].
    Band {
        /// Elements across the width.
        nx: usize,
        /// Elements up the height.
        ny: usize,
    },
    /// More time steps than [`MAX_STEPS`].
    Steps {
        /// The number of time steps asked for.
        steps: f64,
    },
    /// More steps x band entries than [`MAX_STEP_WORK`].
    Work {
        /// The number of time steps asked for.
        steps: f64,
        /// Entries of one banded matrix of the mesh.
        entries: f64,
    },
}

impl SizeLimit {
    /// The rule broken, for messages.
    pub fn rule(&self) -> String {
        use crate::base::format::readable;
        match *self {
            SizeLimit::Nx(_) | SizeLimit::Ny(_) => {
                format!("the number of elements must lie in 1..={MAX_ELEMENTS_PER_SIDE}")
            }
            SizeLimit::Band { nx, ny } => format!(
                "the {nx} x {ny} mesh's banded matrices would have {:.3e} entries \
                 (2 (nx+1)(ny+1) (2 nx + 6)), {} MB each; at most {:e} entries ({} MB) are \
                 accepted, e.g. 64 x 160; choose fewer elements, mostly across the width",
                band_entries(nx, ny),
                readable((band_entries(nx, ny) * 8e-6).round()),
                MAX_BAND_ENTRIES,
                readable(MAX_BAND_ENTRIES * 8e-6)
            ),
            SizeLimit::Steps { steps } => format!(
                "gives {} time steps; at most {:e} are accepted; choose a larger step or a \
                 shorter duration",
                step_count(steps),
                MAX_STEPS
            ),
            SizeLimit::Work { steps, entries } => format!(
                "gives {} time steps on a mesh with {:.0} band entries, {:.2e} in all; at most \
                 {:e} (about 100 s of computing) are accepted; choose a larger step, a shorter \
                 duration or a coarser mesh",
                step_count(steps),
                entries,
                steps * entries,
                MAX_STEP_WORK
            ),
        }
    }
}

/// A number of time steps as a message gives it: whole below 1e15, else in scientific notation
/// (not the 300 digits of a step of 1e-300 s).
fn step_count(steps: f64) -> String {
    if steps < 1e15 {
        format!("{:.0}", steps.floor())
    } else {
        format!("{:.3e}", steps)
    }
}

/// Checks the size of a mesh against the limits above.
pub fn check_mesh_size(nx: usize, ny: usize) -> Result<(), SizeLimit> {
    if !(1..=MAX_ELEMENTS_PER_SIDE).contains(&nx) {
        return Err(SizeLimit::Nx(nx));
    }
    if !(1..=MAX_ELEMENTS_PER_SIDE).contains(&ny) {
        return Err(SizeLimit::Ny(ny));
    }
    if band_entries(nx, ny) > MAX_BAND_ENTRIES {
        return Err(SizeLimit::Band { nx, ny });
    }
    Ok(())
}

/// Checks the size of a dynamic run (mesh, steps, work); `dt` and `duration` must be positive.
pub fn check_run_size(nx: usize, ny: usize, dt: f64, duration: f64) -> Result<(), SizeLimit> {
    check_mesh_size(nx, ny)?;
    let steps = duration / dt;
    if !crate::base::limits::at_most(steps, MAX_STEPS) {
        return Err(SizeLimit::Steps { steps });
    }
    let entries = band_entries(nx, ny);
    if !crate::base::limits::at_most(steps * entries, MAX_STEP_WORK) {
        return Err(SizeLimit::Work { steps, entries });
    }
    Ok(())
}

/// The library's form of a size error: named by the parameter.
fn size_error(limit: SizeLimit) -> FemError {
    let rule = limit.rule();
    match limit {
        SizeLimit::Nx(n) => invalid("nx", n, &rule),
        SizeLimit::Ny(n) => invalid("ny", n, &rule),
        SizeLimit::Band { nx, ny } => invalid("nx, ny", format!("{nx}, {ny}"), &rule),
        SizeLimit::Steps { steps } | SizeLimit::Work { steps, .. } => {
            invalid("duration / dt", steps, &rule)
        }
    }
}

pub(crate) fn validate_body(body: &FemBody) -> Result<(), FemError> {
    check_positive("height", body.height)?;
    check_positive("width", body.width)?;
    check_positive("depth", body.depth)?;
    check_positive("density", body.density)?;
    check_positive("youngs_modulus", body.youngs_modulus)?;
    check_positive("damping_period", body.damping_period)?;
    if !(body.poisson_ratio.is_finite() && (0.0..0.5).contains(&body.poisson_ratio)) {
        return Err(invalid(
            "poisson_ratio",
            body.poisson_ratio,
            "must lie in [0, 0.5)",
        ));
    }
    if !(body.damping_ratio.is_finite() && body.damping_ratio >= 0.0) {
        return Err(invalid(
            "damping_ratio",
            body.damping_ratio,
            "must be finite and >= 0",
        ));
    }
    if !(body.gravity.is_finite() && body.gravity >= 0.0) {
        return Err(invalid("gravity", body.gravity, "must be finite and >= 0"));
    }
    Ok(())
}

pub(crate) fn validate_mesh(nx: usize, ny: usize) -> Result<(), FemError> {
    check_mesh_size(nx, ny).map_err(size_error)
}

pub(crate) fn validate_settings(settings: &FemSettings) -> Result<(), FemError> {
    validate_mesh(settings.nx, settings.ny)?;
    check_positive("dt", settings.dt)?;
    if !(settings.duration.is_finite() && settings.duration >= 0.0) {
        return Err(invalid(
            "duration",
            settings.duration,
            "must be finite and >= 0",
        ));
    }
    check_run_size(settings.nx, settings.ny, settings.dt, settings.duration).map_err(size_error)?;
    if !(settings.mu_s.is_finite() && settings.mu_s >= 0.0) {
        return Err(invalid("mu_s", settings.mu_s, "must be finite and >= 0"));
    }
    if !(settings.mu_k.is_finite() && settings.mu_k >= 0.0) {
        return Err(invalid("mu_k", settings.mu_k, "must be finite and >= 0"));
    }
    if settings.mu_k > settings.mu_s {
        return Err(invalid(
            "mu_k",
            settings.mu_k,
            "must be <= mu_s (kinetic friction cannot exceed static)",
        ));
    }
    match settings.scheme {
        TimeScheme::Newmark { beta, gamma } => {
            if !(beta.is_finite() && beta > 0.0 && beta <= 0.5) {
                return Err(invalid("beta", beta, "must lie in (0, 1/2]"));
            }
            if !(gamma.is_finite() && (0.5..=1.0).contains(&gamma)) {
                return Err(invalid("gamma", gamma, "must lie in [1/2, 1]"));
            }
        }
        TimeScheme::WilsonTheta { theta } => {
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(invalid("theta", theta, "must lie in [1, 3]"));
            }
        }
    }
    if let Some(t) = settings.snapshot_times.iter().find(|t| !t.is_finite()) {
        return Err(invalid("snapshot_times", t, "must be finite"));
    }
    if !(settings.initial_rotation.is_finite() && settings.initial_rotation.abs() < 0.5) {
        return Err(invalid(
            "initial_rotation",
            settings.initial_rotation,
            "must be finite with |rotation| < 0.5 rad (small-rotation kinematics)",
        ));
    }
    Ok(())
}

/// Flags of the dofs held in the fixed-base eigenproblems: both dofs of every base node.
fn fixed_base_dofs(model: &Model) -> Vec<bool> {
    let base = model.base_dof_count();
    (0..model.mesh.dof_count()).map(|d| d < base).collect()
}

/// The `count` lowest fixed-base (base nodes pinned) natural periods, s, longest first,
/// with or without the geometric stiffness of the gravity prestress.
pub fn fixed_base_periods(
    body: &FemBody,
    nx: usize,
    ny: usize,
    p_delta: bool,
    count: usize,
) -> Result<Vec<f64>, FemError> {
    validate_body(body)?;
    validate_mesh(nx, ny)?;
    let model = Model::build(body, nx, ny)?;
    let fixed = fixed_base_dofs(&model);
    let free = fixed.iter().filter(|f| !**f).count();
    if count == 0 || count > free {
        return Err(invalid(
            "count",
            count,
            "must lie in 1..=number of free dofs",
        ));
    }
    let k: BandedSym = model.tangent(p_delta);
    let values = eigen::lowest_eigenvalues(&k, &model.mass, &fixed, count)?;
    values
        .iter()
        .map(|&w2| {
            if w2 > 0.0 {
                Ok(2.0 * std::f64::consts::PI / w2.sqrt())
            } else {
                Err(FemError::SingularMatrix {
                    context: format!(
                        "non-positive eigenvalue {w2:e}: the body buckles under its own weight"
                    ),
                })
            }
        })
        .collect()
}

/// Highest circular frequency ω_max of the mesh with the base free (elastic K, lumped M), rad/s.
pub fn highest_frequency(body: &FemBody, nx: usize, ny: usize) -> Result<f64, FemError> {
    validate_body(body)?;
    validate_mesh(nx, ny)?;
    let model = Model::build(body, nx, ny)?;
    highest_frequency_of(&model)
}

/// Highest natural frequency with the base free, rad/s. Holding dofs can only lower the top of
/// the spectrum (eigenvalue interlacing), so this bounds every contact state of a run; a rigid
/// base plate raises it by orders of magnitude once its nodes leave the floor.
fn highest_frequency_of(model: &Model) -> Result<f64, FemError> {
    let free = vec![false; model.mesh.dof_count()];
    Ok(eigen::highest_eigenvalue(&model.stiffness, &model.mass, &free)?.sqrt())
}

/// Stability limit of the linear acceleration method on this mesh, dt_crit = sqrt(12)/ω_max
/// (= 0.551 T_min), s. Uses the elastic K with the base free; K_σ lowers ω_max slightly, so the
/// limit is on the safe side. Stiffness-proportional damping does not change it (γ = 1/2).
pub fn stability_limit(body: &FemBody, nx: usize, ny: usize) -> Result<f64, FemError> {
    Ok(
        crate::integrate::newmark::linear_acceleration_omega_dt()
            / highest_frequency(body, nx, ny)?,
    )
}

/// Undamped stability limit of a scheme for a highest frequency `omega_max` (rad/s), s;
/// None when the scheme is unconditionally stable (Newmark 2β >= γ >= 1/2, Wilson θ >= 1.37).
/// For Newmark, dt_crit = 1/(ω_max sqrt(γ/2 - β)). For Wilson θ < 1.37 the linear acceleration
/// limit sqrt(12)/ω_max is returned as a conservative value.
pub fn critical_time_step(scheme: TimeScheme, omega_max: f64) -> Option<f64> {
    match scheme {
        TimeScheme::Newmark { beta, gamma } => {
            crate::integrate::newmark::critical_omega_dt(beta, gamma).map(|limit| limit / omega_max)
        }
        TimeScheme::WilsonTheta { theta } => {
            if theta >= 1.37 {
                None
            } else {
                Some(crate::integrate::newmark::linear_acceleration_omega_dt() / omega_max)
            }
        }
    }
}

pub(crate) use crate::physics::constants::cantilever_mode;

/// Top-displacement decomposition shared by the dynamic and static analyses:
/// (q, rocking, slipping, flexural, shearing).
pub(crate) fn decompose(mesh: &mesh::Mesh, u: &[f64]) -> [f64; 5] {
    let (nx, ny) = (mesh.nx, mesh.ny);
    let row_rotation = |j: usize| {
        let left = mesh.node(0, j);
        let right = mesh.node(nx, j);
        (u[2 * left + 1] - u[2 * right + 1]) / mesh.width
    };
    let q = mesh.top_nodes().iter().map(|&n| u[2 * n]).sum::<f64>() / (nx + 1) as f64;
    let slipping = mesh.base_nodes().iter().map(|&n| u[2 * n]).sum::<f64>() / (nx + 1) as f64;
    let theta0 = row_rotation(0);
    let rocking = theta0 * mesh.height;
    let dy = mesh.height / ny as f64;
    let mut flexural = 0.0;
    let mut previous = 0.0;
    for j in 1..=ny {
        let current = row_rotation(j) - theta0;
        flexural += 0.5 * (previous + current) * dy;
        previous = current;
    }
    let shearing = q - rocking - slipping - flexural;
    [q, rocking, slipping, flexural, shearing]
}
