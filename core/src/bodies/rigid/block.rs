//! The rigid block itself: its geometry, the equation it obeys, its restitution and when it
//! counts as overturned.

use serde::{Deserialize, Serialize};

use super::Result;
use crate::base::invalid::InvalidParameter;
use crate::physics::body::positive;
use crate::physics::constants::ModeShapeIntegrals;

/// Which rocking equation a block obeys (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidForm {
    /// The small-angle (linearised, slender) form, q'' = k^2 (q - s B) - (3/2) a, k^2 =
    /// 3 g/(2 H): the default, and the form the elastic model tends to as E grows.
    #[default]
    SmallAngle,
    /// Housner's full equation of a rectangular block, theta'' = -p^2 [sin(s alpha - theta) +
    /// (a/g) cos(s alpha - theta)], p^2 = 3 g/(4 R), R = sqrt(H^2 + B^2)/2, alpha = atan(B/H).
    Full,
}

impl RigidForm {
    /// Every form, in the order they are listed to users.
    pub const ALL: [RigidForm; 2] = [RigidForm::SmallAngle, RigidForm::Full];

    /// The name in files and on the command line: `small-angle` or `full`.
    pub fn name(self) -> &'static str {
        match self {
            RigidForm::SmallAngle => "small-angle",
            RigidForm::Full => "full",
        }
    }

    /// True for the default, the small-angle form.
    pub fn is_small_angle(&self) -> bool {
        *self == RigidForm::SmallAngle
    }

    /// The form named `text`; `key` names the setting in the message of an unknown name.
    pub fn parse(key: &str, text: &str) -> std::result::Result<Self, InvalidParameter> {
        RigidForm::ALL
            .into_iter()
            .find(|f| f.name() == text)
            .ok_or_else(|| {
                InvalidParameter::new(
                    key,
                    text,
                    "must be \"small-angle\" (the linearised equation, the default) or \"full\" \
                     (Housner's full equation)",
                )
            })
    }
}

impl std::fmt::Display for RigidForm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// When a rocking block counts as overturned (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidOverturning {
    /// The moment |theta| reaches the equation's unstable equilibrium (alpha in the full form,
    /// B/H in the small-angle form): the default.
    #[default]
    ReachesLimit,
    /// Only once it cannot come back: its free motion, once the floor is at rest for good (or
    /// the run ends), never returns it to the floor, or it lies on its side. The rule of the
    /// rocking literature's minimum overturning accelerations (Zhang and Makris 2001; Makris and
    /// Roussos 2000).
    CannotReturn,
}

impl RigidOverturning {
    /// The name in files: `reaches-limit` or `cannot-return`.
    pub fn name(self) -> &'static str {
        match self {
            RigidOverturning::ReachesLimit => "reaches-limit",
            RigidOverturning::CannotReturn => "cannot-return",
        }
    }

    /// True for the default.
    pub fn is_reaches_limit(&self) -> bool {
        *self == RigidOverturning::ReachesLimit
    }

    /// Every rule, in the order they are listed to users.
    pub const ALL: [RigidOverturning; 2] = [
        RigidOverturning::ReachesLimit,
        RigidOverturning::CannotReturn,
    ];

    /// The rule named `text`; `key` names the setting in the message of an unknown name.
    pub fn parse(key: &str, text: &str) -> std::result::Result<Self, InvalidParameter> {
        RigidOverturning::ALL
            .into_iter()
            .find(|r| r.name() == text)
            .ok_or_else(|| {
                InvalidParameter::new(
                    key,
                    text,
                    "must be \"reaches-limit\" (overturned when the tilt reaches its limit, the \
                     default) or \"cannot-return\" (only once the block cannot come back)",
                )
            })
    }
}

impl std::fmt::Display for RigidOverturning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A slender rigid block of height H and width B standing on a rigid floor.
#[derive(Debug, Clone, Serialize)]
pub struct RigidBlock {
    height: f64,
    width: f64,
    gravity: f64,
    uplift_acceleration: f64,
    /// The equation it obeys; not written for the default, so that its JSON is unchanged.
    #[serde(skip_serializing_if = "RigidForm::is_small_angle")]
    form: RigidForm,
    /// A coefficient of restitution of its own, or None for Housner's; not written for the
    /// default.
    #[serde(skip_serializing_if = "Option::is_none")]
    restitution: Option<f64>,
    /// When it counts as overturned; not written for the default.
    #[serde(skip_serializing_if = "RigidOverturning::is_reaches_limit")]
    overturning: RigidOverturning,
}

impl RigidBlock {
    /// Housner's block: it uplifts when the floor acceleration reaches g B/H, where the moment of
    /// the inertia force about a toe equals that of the weight.
    pub fn housner(height: f64, width: f64, gravity: f64) -> Result<Self> {
        check_geometry(height, width, gravity)?;
        Self::with_uplift_acceleration(height, width, gravity, gravity * width / height)
    }

    /// The elastic model's rigid limit (E -> infinity): it uplifts at the limit of the elastic
    /// model's quasi-static uplift acceleration omega^2 s_n / beta1, that is at
    /// (lambda^3/(8 sigma)) g B/H = 1.1226 g B/H ([`ModeShapeIntegrals::rigid_limit_uplift_factor`]
    /// with the exact constants), and rocks like Housner's block.
    pub fn elastic_limit(height: f64, width: f64, gravity: f64) -> Result<Self> {
        check_geometry(height, width, gravity)?;
        let factor = ModeShapeIntegrals::exact().rigid_limit_uplift_factor();
        Self::with_uplift_acceleration(height, width, gravity, factor * gravity * width / height)
    }

    /// A block with its own uplift acceleration, which must be at least g B/H: a block lifted
    /// by a smaller floor acceleration would fall back at once.
    pub fn with_uplift_acceleration(
        height: f64,
        width: f64,
        gravity: f64,
        uplift_acceleration: f64,
    ) -> Result<Self> {
        check_geometry(height, width, gravity)?;
        let tipping = gravity * width / height;
        if !(uplift_acceleration.is_finite() && uplift_acceleration >= tipping) {
            return Err(InvalidParameter::new(
                "rigid.uplift_acceleration",
                uplift_acceleration,
                &format!(
                    "must be a finite number of at least g B/H = {tipping} m/s^2: below it a \
                     lifted block falls straight back"
                ),
            )
            .into());
        }
        Ok(RigidBlock {
            height,
            width,
            gravity,
            uplift_acceleration,
            form: RigidForm::SmallAngle,
            restitution: None,
            overturning: RigidOverturning::ReachesLimit,
        })
    }

    /// The same block obeying the equation `form` (the constructors give the small-angle form).
    pub fn with_form(mut self, form: RigidForm) -> Self {
        self.form = form;
        self
    }

    /// The equation the block obeys.
    pub fn form(&self) -> RigidForm {
        self.form
    }

    /// The same block with the coefficient of restitution `e` (the ratio of q' after an impact
    /// to q' before it) instead of Housner's, as papers that fix it (e.g. 0.9) use
    /// ([`check_restitution`]).
    pub fn with_restitution(mut self, e: f64) -> Result<Self> {
        check_restitution("rigid.restitution", e)?;
        self.restitution = Some(e);
        Ok(self)
    }

    /// The same block counted as overturned by `rule` (the constructors give
    /// [`RigidOverturning::ReachesLimit`]).
    pub fn with_overturning(mut self, rule: RigidOverturning) -> Self {
        self.overturning = rule;
        self
    }

    /// When the block counts as overturned.
    pub fn overturning(&self) -> RigidOverturning {
        self.overturning
    }

    /// alpha = atan(B/H), the slenderness angle, rad.
    pub fn slenderness(&self) -> f64 {
        (self.width / self.height).atan()
    }

    /// Height H, m.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Width B, m; |q| = B is the overturning limit of the small-angle form.
    pub fn width(&self) -> f64 {
        self.width
    }

    /// |q| at which the block has overturned, m: B in the small-angle form (theta = B/H), H
    /// atan(B/H) in the full form (theta = alpha).
    pub fn overturning_displacement(&self) -> f64 {
        match self.form {
            RigidForm::SmallAngle => self.width,
            RigidForm::Full => self.height * self.slenderness(),
        }
    }

    /// Gravity acceleration g, m/s^2.
    pub fn gravity(&self) -> f64 {
        self.gravity
    }

    /// Floor acceleration at which the block at rest starts rocking, m/s^2.
    pub fn uplift_acceleration(&self) -> f64 {
        self.uplift_acceleration
    }

    /// g B/H, m/s^2: the floor acceleration at which the moments about a toe balance (Housner's
    /// uplift acceleration). Below it a block near q = 0 falls back to the floor from either side.
    pub fn tipping_acceleration(&self) -> f64 {
        self.gravity * self.width / self.height
    }

    /// The frequency parameter, rad/s: k = sqrt(3 g/(2 H)) in the small-angle form (the slender
    /// block's), p = sqrt(3 g/(4 R)), R = sqrt(H^2 + B^2)/2, in the full form.
    pub fn frequency(&self) -> f64 {
        match self.form {
            RigidForm::SmallAngle => (1.5 * self.gravity / self.height).sqrt(),
            RigidForm::Full => (0.75 * self.gravity / self.half_diagonal()).sqrt(),
        }
    }

    /// R = sqrt(H^2 + B^2)/2, m: the distance from a toe to the centre of mass.
    pub fn half_diagonal(&self) -> f64 {
        0.5 * self.height.hypot(self.width)
    }

    /// The coefficient of restitution, the ratio of q' after an impact to q' before it:
    /// Housner's e = (2 H^2 - B^2)/(2 (H^2 + B^2)) = 1 - 1.5 sin^2 alpha, or the block's own
    /// ([`RigidBlock::with_restitution`]).
    pub fn restitution(&self) -> f64 {
        let (h2, b2) = (self.height * self.height, self.width * self.width);
        self.restitution
            .unwrap_or((2.0 * h2 - b2) / (2.0 * (h2 + b2)))
    }

    /// The smallest speed q' at which a free block leaving q = 0 overturns, m/s: k B in the
    /// small-angle form; in the full form, from the energy p^2 (1 - cos alpha) the block must
    /// gain to reach theta = alpha, 2 p H sin(alpha/2).
    pub fn overturning_velocity(&self) -> f64 {
        match self.form {
            RigidForm::SmallAngle => self.frequency() * self.width,
            RigidForm::Full => {
                2.0 * self.frequency() * self.height * (0.5 * self.slenderness()).sin()
            }
        }
    }

    /// The pull towards the floor at q = 0 per unit of (g B/H - |a|): the q'' of a block at
    /// q = 0 under a floor acceleration |a| below g B/H is -c (g B/H - |a|), c = 3/2 in the
    /// small-angle form, (3/2) cos^2 alpha in the full form.
    pub(super) fn pull_factor(&self) -> f64 {
        match self.form {
            RigidForm::SmallAngle => 1.5,
            RigidForm::Full => 1.5 * self.slenderness().cos().powi(2),
        }
    }
}

/// A coefficient of restitution of a block's own (`key` names the setting) must lie strictly
/// between 0 and 1: with 1 the impacts of a block falling back and forth never lose speed, so
/// its chatter never ends; with 0 a block landing while the floor holds it at the tipping
/// acceleration lifts off again at no speed, an endless cascade. (Housner's e = 1 - 1.5
/// sin^2 alpha lies between them for every slender block.)
pub fn check_restitution(key: &str, e: f64) -> std::result::Result<(), InvalidParameter> {
    if e.is_finite() && e > 0.0 && e < 1.0 {
        return Ok(());
    }
    Err(InvalidParameter::new(
        key,
        e,
        "must lie strictly between 0 and 1: the ratio of the rocking speed after an impact to \
         the speed before it (at 1 a block's chatter never ends, at 0 it lifts off again at no \
         speed)",
    ))
}

fn check_geometry(height: f64, width: f64, gravity: f64) -> Result<()> {
    for (key, value) in [
        ("rigid.height", height),
        ("rigid.width", width),
        ("rigid.gravity", gravity),
    ] {
        positive(key, value)?;
    }
    if width >= height {
        return Err(InvalidParameter::new(
            "rigid.width",
            width,
            &format!(
                "the width must be less than the height ({height} m): the equations are those of \
                 a slender block"
            ),
        )
        .into());
    }
    Ok(())
}
