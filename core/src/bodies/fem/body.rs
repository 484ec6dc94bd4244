//! The elastic body of the finite element model and the support of its base.

use serde::{Deserialize, Serialize};

use super::error::{check_positive, invalid, FemError};

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

pub(super) fn validate_body(body: &FemBody) -> Result<(), FemError> {
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
