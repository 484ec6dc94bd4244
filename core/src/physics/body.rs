//! The physical body: a prismatic slender elastic body standing on a rigid floor.

use serde::{Deserialize, Serialize};

use crate::base::double_double::DoubleDouble as Dd;

use crate::base::invalid::InvalidParameter;

type Result<T> = std::result::Result<T, InvalidParameter>;

/// Which set of mode-shape constants to use (book/src/model.md §2, constants).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConstantSet {
    /// Constants computed exactly from the cantilever mode shape.
    Exact,
    /// The rounded values printed in Ichinose (1986), for reproducing the paper digit by digit.
    Paper,
}

impl ConstantSet {
    /// The model-file spelling ("exact" or "paper").
    pub fn name(self) -> &'static str {
        match self {
            ConstantSet::Exact => "exact",
            ConstantSet::Paper => "paper",
        }
    }
}

/// How the model treats the body's own weight in bending (`[body] self_weight`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SelfWeight {
    /// As the paper: the weight's moment about the toe, but no weight in the bending
    /// (book/src/model.md §2-§5, §7a).
    Paper,
    /// The self-weight-consistent variant (validation/SELF-WEIGHT.md): the flexural shape is the
    /// first mode of a cantilever carrying its own weight, the weight's P-Delta enters the
    /// stiffness, and the rocking branch follows equilibrium about the pivot toe.
    Consistent,
}

impl SelfWeight {
    /// The model-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            SelfWeight::Paper => "paper",
            SelfWeight::Consistent => "consistent",
        }
    }

    /// The variant spelled `name` in a model file.
    pub fn from_name(name: &str) -> Option<Self> {
        [SelfWeight::Paper, SelfWeight::Consistent]
            .into_iter()
            .find(|v| v.name() == name)
    }
}

/// A validated body. All quantities in SI units.
#[derive(Debug, Clone, Serialize)]
pub struct Body {
    /// H, m.
    pub height: f64,
    /// B, in-plane width, m.
    pub width: f64,
    /// D, out-of-plane depth, m.
    pub depth: f64,
    /// M, total mass, kg.
    pub mass: f64,
    /// EI, flexural rigidity of the section, N m^2.
    pub flexural_rigidity: f64,
    /// h, damping ratio before uplift.
    pub damping_ratio: f64,
    /// g, m/s^2.
    pub gravity: f64,
    /// Which mode-shape constants to use (`[body] constants`).
    pub constant_set: ConstantSet,
    /// Which variant of the model: the paper's, or self-weight-consistent.
    pub self_weight: SelfWeight,
    /// e, the factor on q' at every landing on top of the reset q' -> q'/zetaL, in (0, 1]:
    /// 1 is the paper's model (written out only when it is not 1).
    #[serde(skip_serializing_if = "is_one")]
    pub landing_restitution: f64,
    /// Whether the strain-rate damping term acts while rocking, as in the paper (written out only
    /// when it does not).
    #[serde(skip_serializing_if = "is_true")]
    pub damping_while_rocking: bool,
}

/// The paper's landing: no loss beyond the angular-momentum reset.
pub const DEFAULT_LANDING_RESTITUTION: f64 = 1.0;

fn is_one(x: &f64) -> bool {
    *x == DEFAULT_LANDING_RESTITUTION
}

fn is_true(x: &bool) -> bool {
    *x
}

/// Mass of a prism of `density` (kg/m^3) and size H x B x D (m), kg: the double nearest the
/// product of the numbers as written.
pub fn prism_mass(density: f64, height: f64, width: f64, depth: f64) -> f64 {
    let written = Dd::decimal;
    (written(density) * written(height) * written(width) * written(depth)).value()
}

/// EI = E D B^3 / 12 of a solid rectangular section of width B (in the plane of motion) and
/// depth D, N m^2: the double nearest it for the numbers as written.
pub fn solid_section_flexural_rigidity(youngs_modulus: f64, width: f64, depth: f64) -> f64 {
    let written = Dd::decimal;
    (written(youngs_modulus) * written(depth) * written(width).cube() / 12.0).value()
}

impl Body {
    /// Checks the rules that do not need the derived constants; `Constants::new` checks the rest
    /// (stability under self-weight, slenderness).
    pub fn validated(self) -> Result<Self> {
        let Body {
            height,
            width,
            depth,
            mass,
            flexural_rigidity,
            damping_ratio,
            gravity,
            landing_restitution,
            ..
        } = self;
        positive("body.height", height)?;
        positive("body.width", width)?;
        positive("body.depth", depth)?;
        positive("body.mass", mass)?;
        positive("body.flexural_rigidity", flexural_rigidity)?;
        positive("body.gravity", gravity)?;
        if !(0.0..1.0).contains(&damping_ratio) {
            return Err(InvalidParameter::new(
                "body.damping_ratio",
                damping_ratio,
                "the damping ratio must lie in [0, 1)",
            ));
        }
        if !(landing_restitution > 0.0 && landing_restitution <= 1.0) {
            return Err(InvalidParameter::new(
                "body.landing_restitution",
                landing_restitution,
                "the coefficient of restitution at landing must lie in (0, 1]: 1 is the paper's \
                 landing, smaller values take more of q' at each landing, and 0 would leave the \
                 body at rest on the uplift threshold",
            ));
        }
        if width >= height {
            return Err(InvalidParameter::new(
                "body.width",
                width,
                &format!(
                    "the width must be less than the height ({} m): the model is for slender bodies",
                    crate::base::format::shortest(height)
                ),
            ));
        }
        Ok(self)
    }

    /// gamma_g = M g H^2/EI: the weight's share in the bending (book/src/model.md §7a); a uniform
    /// cantilever buckles under its own weight at 7.837.
    pub fn gravity_parameter(&self) -> f64 {
        self.mass * self.gravity * self.height * self.height / self.flexural_rigidity
    }

    /// alpha = atan(B/H), the slenderness angle of the rocking literature (Housner 1963): a rigid
    /// block starts to rock at a floor acceleration of g tan(alpha).
    pub fn slenderness_angle(&self) -> f64 {
        (self.width / self.height).atan()
    }

    /// p = sqrt(3 g / (4 R)), R = sqrt(H^2 + B^2)/2: the frequency parameter of a rigid block
    /// (Housner 1963), rad/s; pulse frequencies are plotted over it.
    pub fn block_frequency_parameter(&self) -> f64 {
        let half_diagonal = 0.5 * self.height.hypot(self.width);
        (3.0 * self.gravity / (4.0 * half_diagonal)).sqrt()
    }
}

/// Rejects zero, negative, NaN and infinite values, and subnormal ones (below 2.2e-308, where
/// a number keeps fewer digits and its products vanish: a column 5e-324 m deep made a row's
/// contact matrix singular).
pub(crate) fn positive(key: &str, value: f64) -> Result<()> {
    if value.is_normal() && value > 0.0 {
        Ok(())
    } else if value.is_finite() && value > 0.0 {
        Err(InvalidParameter::new(
            key,
            value,
            &format!(
                "must be a finite number greater than 0 and at least {:e}: smaller numbers are \
                 subnormal, with fewer digits",
                f64::MIN_POSITIVE
            ),
        ))
    } else {
        Err(InvalidParameter::new(
            key,
            value,
            "must be a finite number greater than 0",
        ))
    }
}
