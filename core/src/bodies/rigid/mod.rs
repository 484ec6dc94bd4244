//! The rigid block of the rigid limit (book/src/model.md §7; Housner 1963): the reference
//! that overturning spectra of the elastic body are plotted against, and what the elastic model
//! must tend to as E grows.
//!
//! Everything is in top-displacement units, q = theta H (theta the tilt), so that results compare
//! directly with the elastic model's q. With k^2 = 3 g/(2 H) (book/src/model.md §7, eq. A5;
//! p = k):
//!
//! - rocking right (q > 0): q'' = k^2 (q - B) - (3/2) a(t); rocking left (q < 0):
//!   q'' = k^2 (q + B) - (3/2) a(t);
//! - at rest (q = 0, q' = 0) the block stays until the floor acceleration reaches the uplift
//!   acceleration a_up: it starts rocking right when a(t) < -a_up, left when a(t) > a_up.
//!   Housner's block has a_up = g B/H ([`RigidBlock::housner`]); the elastic model's rigid limit
//!   uplifts at (lambda^3/(8 sigma)) g B/H = 1.1226 g B/H ([`RigidBlock::elastic_limit`], see
//!   [`ModeShapeIntegrals::rigid_limit_uplift_factor`]);
//! - when q crosses 0 the block hits the floor: q' -> e q' with Housner's restitution
//!   e = (2 H^2 - B^2)/(2 (H^2 + B^2)) (eq. A7), and it rocks on about the other toe;
//! - when |q| reaches B it has overturned (terminal).
//!
//! That is the small-angle (linearised, slender) form of Housner's equation, the default
//! ([`RigidForm::SmallAngle`]), and the form the elastic model tends to as E grows. The other
//! form ([`RigidForm::Full`]) is the full equation of a rectangular rigid block, the paper's
//! eq. A6 (Ichinose 1986, appendix), also Housner 1963 (Bull. Seismol. Soc. Am. 53(2)), Zhang and
//! Makris 2001 (J. Eng. Mech. 127(5)) and Dimitrakopoulos and DeJong 2012 (Proc. R. Soc. A 468).
//! With alpha = atan(B/H), R = sqrt(H^2 + B^2)/2 (the half-diagonal), p^2 = 3 g/(4 R) and
//! theta = q/H:
//!
//! ```text
//! theta'' = -p^2 [ sin(s alpha - theta) + (a(t)/g) cos(s alpha - theta) ],   s = sgn(theta)
//! ```
//!
//! with the same sign convention as the small-angle form: a(t) > 0 is the floor accelerating
//! towards +x, which tilts the block towards -x (q < 0). With sin x ~ x, cos x ~ 1, alpha ~ B/H
//! and R ~ H/2 it is the small-angle equation above; the two differ by O(alpha^2). The rules
//! are the same in both forms:
//!
//! - uplift when |a| reaches a_up (g tan alpha = g B/H for Housner's block), in the direction
//!   above;
//! - at an impact q' -> e q' with Housner's e = 1 - (3/2) sin^2 alpha, which follows from the
//!   conservation of angular momentum about the new toe for a rectangular block of any
//!   slenderness, so it is no small-angle approximation;
//! - overturned when theta reaches the equation's unstable equilibrium: |theta| = alpha, that
//!   is |q| = H atan(B/H), in the full form; |theta| = B/H, |q| = B, in the small-angle form
//!   ([`RigidBlock::overturning_displacement`]); or, by the other rule
//!   ([`RigidOverturning::CannotReturn`], that of Zhang and Makris 2001 and Makris and Roussos
//!   2000), only once the block cannot come back (below);
//! - chatter is cut short by the same rule (below), with each form's pull towards the floor.
//!
//! # When a block has overturned
//!
//! By default ([`RigidOverturning::ReachesLimit`]) a block has overturned the moment |theta|
//! reaches the limit above, and the run ends there. Past the limit the floor can still bring it
//! back: a pulse's second half pushes a block that passed alpha early in the pulse back towards
//! the floor. The rocking literature's minimum overturning accelerations count such a block as
//! standing: a block has overturned only if it never returns to the floor. By that rule
//! ([`RigidOverturning::CannotReturn`]) the run goes on past the limit (both equations hold there,
//! up to |theta| = pi/2, where the block lies on its side), and the block has overturned
//!
//! - when it lies on its side, |q| = H pi/2; or
//! - at the first moment the floor is at rest for good ([`FloorMotion::quiet_after`]) or the run
//!   ends, if its free motion from there never brings it back to the floor: in the small-angle
//!   form when s (q - s B) + s q'/k >= 0 (the free motion q - s B = c1 e^(k t) + c2 e^(-k t)
//!   then never returns, c1 >= 0); in the full form when it is past alpha and not moving back
//!   fast enough to cross it again, or before alpha and moving out fast enough to cross it: the
//!   energy (1/2) theta'^2 - 2 p^2 sin^2((alpha - s theta)/2), conserved by the free motion,
//!   decides whether it crosses theta = s alpha (above 0) or not (below), and the direction of
//!   motion which way. (A block still past the limit when a run ends with the floor moving is
//!   judged as if the floor stopped then.)
//!
//! Its overturning time is then that moment, and its q where it was judged.
//!
//! # Numerical method
//!
//! Within a mode the equation is linear with constant coefficients, x'' = k^2 x + f(t) with
//! x = q - s B (s = +1 right, -1 left) and f = -(3/2) a. Its solution over a time tau from
//! (q0, v0) is exact up to the forcing integral:
//!
//! ```text
//! q(tau) = q0 cosh(k tau) - 2 s B sinh^2(k tau/2) + (v0/k) sinh(k tau) + (1/k) int_0^tau sinh(k (tau - u)) f(u) du
//! v(tau) = (q0 - s B) k sinh(k tau) + v0 cosh(k tau)                 + int_0^tau cosh(k (tau - u)) f(u) du
//! ```
//!
//! The integrals are taken by 8-point Gauss-Legendre quadrature over [0, tau] (exact for a
//! forcing that is a polynomial of degree 13 or less, e.g. a record's linear pieces; for a sine
//! of period Tp its relative error is of order (2 pi tau/Tp)^16). Steps are at most
//! [`RigidSettings::max_step`] long and stop exactly at every breakpoint of the floor motion, so
//! that no quadrature straddles a kink. Every event is located by bisection on the exact
//! propagator from the step's start (each trial time is a fresh propagation, not an
//! interpolation), down to the resolution of the floating-point time. A step is split at a root
//! of q' (located the same way) when q' changes sign in it, so that q is monotone on each piece
//! and a guard can be crossed at most once on it, in the direction q moves: an impact only moving
//! towards the floor, an overturn only moving away. The turning points are also the peaks of |q|.
//! At rest, the floor acceleration is sampled at eight points per step and a crossing of +-a_up
//! is located by bisection; an excursion beyond a_up shorter than an eighth of a step can be
//! missed. Halving the step changes event times and peaks by about 1e-13 (see the tests).
//!
//! The full equation has no closed-form propagator: each stretch of rocking is integrated by
//! diffsol's Tsit45 method (an explicit Runge-Kutta pair of orders 5 and 4) to the tolerances of
//! [`RigidSettings`] (by default [`DEFAULT_FULL_RTOL`] and [`DEFAULT_FULL_ATOL_FRACTION`] H), in
//! the event loop every diffsol run of the project shares: the floor's breakpoints are stops,
//! impacts and the overturn are located on each step's dense output, and the method restarts
//! after each impact. Checked against an independent integration of the full equation to 1e-11
//! (see the tests).
//!
//! # Chatter
//!
//! A block that lands slowly while |a| < g B/H falls back from either side: its impacts form a
//! geometric sequence whose flights shrink by e each time and which ends in finite time (Zeno).
//! After an impact with |q'| = v while |a(t)| < g B/H, the remaining sequence, if the floor
//! acceleration stayed as it is, would last at most 2 v / (c (g B/H - |a|) (1 - e)), with
//! c = 3/2 in the small-angle form and c = (3/2) cos^2 alpha in the full form (its pull towards
//! the floor at theta = 0, H p^2 (sin alpha - (|a|/g) cos alpha)). When that
//! is at most [`ZENO_TIME`] the block is put at rest ([`RigidEventKind::Settle`]). Since
//! g B/H <= a_up, the resting block stays until the floor reaches a_up.

#![warn(missing_docs)]

use serde::{Deserialize, Serialize};

use crate::base::invalid::InvalidParameter;
use crate::integrate::SolverError;
use crate::physics::constants::ModeShapeIntegrals;

type Result<T> = std::result::Result<T, SolverError>;
use crate::base::limits::MAX_DURATION;
use crate::floor::{floor_limit_rule, within_floor_limit, FloorMotion};
use crate::integrate::budget::RunBudget;
use crate::integrate::InitialState;

mod full;
use full::FullEquation;

/// Longest default step, s. The propagator is exact between steps up to the forcing quadrature,
/// so the step length serves mainly to bound the time in which q' could turn twice unseen.
pub const DEFAULT_MAX_STEP: f64 = 1e-3;

/// The default step is also at most this fraction of the block's time scale 1/k.
pub const DEFAULT_STEP_FRACTION: f64 = 0.05;

/// A chattering block is put at rest when the impacts still to come would end within this
/// time, s (see the module documentation).
pub const ZENO_TIME: f64 = 1e-6;

/// Relative tolerance of the full equation's adaptive integration.
pub const DEFAULT_FULL_RTOL: f64 = 1e-12;

/// Absolute tolerance of the full equation's adaptive integration, as a fraction of H.
pub const DEFAULT_FULL_ATOL_FRACTION: f64 = 1e-13;

/// Points per step at which a resting block checks the floor acceleration against a_up.
const REST_SAMPLES: usize = 8;

/// Nodes (positive half) and weights of the 8-point Gauss-Legendre rule on [-1, 1].
const GAUSS_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GAUSS_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

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
    fn pull_factor(&self) -> f64 {
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
        if !(value.is_finite() && value > 0.0) {
            return Err(InvalidParameter::new(
                key,
                value,
                "must be a finite number greater than 0",
            )
            .into());
        }
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

/// Settings of a rigid-block run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RigidSettings {
    /// Longest step of the small-angle form and of a block at rest, s. Steps also stop at every
    /// breakpoint of the floor motion.
    pub max_step: f64,
    /// Relative tolerance of the full form's adaptive integration.
    pub rtol: f64,
    /// Absolute tolerance of the full form's adaptive integration, m.
    pub atol: f64,
}

impl RigidSettings {
    /// The default for a block: a longest step of min([`DEFAULT_MAX_STEP`],
    /// [`DEFAULT_STEP_FRACTION`] / k), and the full form's tolerances [`DEFAULT_FULL_RTOL`] and
    /// [`DEFAULT_FULL_ATOL_FRACTION`] H.
    pub fn for_block(block: &RigidBlock) -> Self {
        RigidSettings {
            max_step: DEFAULT_MAX_STEP.min(DEFAULT_STEP_FRACTION / block.frequency()),
            rtol: DEFAULT_FULL_RTOL,
            atol: DEFAULT_FULL_ATOL_FRACTION * block.height,
        }
    }
}

/// What the block is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidPhase {
    /// Standing on both toes, q = 0, q' = 0.
    Rest,
    /// Rocking about the right (+x) toe, q > 0.
    RockRight,
    /// Rocking about the left (-x) toe, q < 0.
    RockLeft,
    /// |q| reached B. Terminal.
    Overturned,
}

impl RigidPhase {
    /// +1 rocking right, -1 rocking left, 0 otherwise.
    fn side(self) -> f64 {
        match self {
            RigidPhase::RockRight => 1.0,
            RigidPhase::RockLeft => -1.0,
            RigidPhase::Rest | RigidPhase::Overturned => 0.0,
        }
    }

    fn rocking(side: f64) -> Self {
        if side > 0.0 {
            RigidPhase::RockRight
        } else {
            RigidPhase::RockLeft
        }
    }
}

/// What happened at an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidEventKind {
    /// The block at rest started rocking.
    Uplift,
    /// q crossed 0: q' -> e q', rocking on about the other toe.
    Impact,
    /// The chatter after an impact was cut short: the block is at rest (see the module
    /// documentation).
    Settle,
    /// The block overturned: |q| reached the overturning displacement, or, by
    /// [`RigidOverturning::CannotReturn`], it can no longer come back.
    Overturn,
}

/// One event.
#[derive(Debug, Clone, Serialize)]
pub struct RigidEvent {
    /// Time, s.
    pub t: f64,
    /// What happened.
    pub kind: RigidEventKind,
    /// q at the event, m (0, or where the block was when it overturned).
    pub q: f64,
    /// q' just before, m/s.
    pub qdot_before: f64,
    /// q' just after, m/s.
    pub qdot_after: f64,
    /// The phase after the event.
    pub to: RigidPhase,
}

/// The state of the block at a time.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RigidState {
    /// Time, s.
    pub t: f64,
    /// Top displacement q = theta H, m.
    pub q: f64,
    /// q', m/s.
    pub qdot: f64,
    /// Phase.
    pub phase: RigidPhase,
}

/// The result of a rigid-block run.
#[derive(Debug, Clone, Serialize)]
pub struct RigidOutcome {
    /// The block overturned within the duration.
    pub overturned: bool,
    /// When it overturned, s.
    pub t_overturn: Option<f64>,
    /// Uplifts from rest.
    pub n_uplift: usize,
    /// Impacts (crossings of q = 0 while rocking).
    pub n_impact: usize,
    /// Chatters cut short by putting the block at rest.
    pub n_settle: usize,
    /// Time of the first uplift from rest, s.
    pub first_uplift: Option<f64>,
    /// Largest |q| over the run, m (the overturning displacement if it overturned when it
    /// reached it; by [`RigidOverturning::CannotReturn`] it may pass it and come back).
    pub max_abs_q: f64,
    /// When |q| was largest, s.
    pub t_max_abs_q: f64,
    /// The state at the end: at the duration, or at the overturn.
    pub final_state: RigidState,
    /// Every event, in order.
    pub events: Vec<RigidEvent>,
    /// Steps taken.
    pub steps: usize,
}

/// Simulates the block from rest over [0, duration] with the default settings.
pub fn simulate_block(
    block: &RigidBlock,
    floor: &dyn FloorMotion,
    duration: f64,
) -> Result<RigidOutcome> {
    simulate_from(
        block,
        floor,
        InitialState { q: 0.0, qdot: 0.0 },
        duration,
        &RigidSettings::for_block(block),
    )
}

/// Simulates the block from `initial` (|q0| < B) over [0, duration]. q0 > 0 starts rocking right,
/// q0 < 0 left; q0 = 0 starts rocking the way q'0 points, or at rest when q'0 = 0.
pub fn simulate_from(
    block: &RigidBlock,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &RigidSettings,
) -> Result<RigidOutcome> {
    if !(duration.is_finite() && duration > 0.0 && duration <= MAX_DURATION) {
        return Err(InvalidParameter::new(
            "rigid.duration",
            duration,
            &format!("must be a finite number greater than 0 and at most {MAX_DURATION:e} s"),
        )
        .into());
    }
    if !(settings.max_step.is_finite() && settings.max_step > 0.0) {
        return Err(InvalidParameter::new(
            "rigid.max_step",
            settings.max_step,
            "must be a finite number greater than 0",
        )
        .into());
    }
    for (key, value) in [("rigid.rtol", settings.rtol), ("rigid.atol", settings.atol)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(InvalidParameter::new(
                key,
                value,
                "must be a finite number greater than 0",
            )
            .into());
        }
    }
    let limit = block.overturning_displacement();
    if !(initial.q.is_finite() && initial.q.abs() < limit) {
        let rule = match block.form {
            RigidForm::SmallAngle => format!("must lie strictly between -B and B ({limit} m)"),
            RigidForm::Full => format!(
                "must lie strictly between -H atan(B/H) and H atan(B/H) ({limit} m), where the \
                 full equation's block overturns"
            ),
        };
        return Err(InvalidParameter::new("rigid.q0", initial.q, &rule).into());
    }
    if !initial.qdot.is_finite() {
        return Err(
            InvalidParameter::new("rigid.qdot0", initial.qdot, "must be a finite number").into(),
        );
    }
    let peak = floor.peak_acceleration();
    if !within_floor_limit(peak) {
        return Err(InvalidParameter::new(
            "rigid floor motion",
            floor.kind(),
            &floor_limit_rule(peak),
        )
        .into());
    }
    Run::new(block, floor, initial, duration, settings).run()
}

/// A run in progress.
struct Run<'a> {
    floor: &'a dyn FloorMotion,
    propagator: Propagator<'a>,
    /// The full equation's numbers, or None for the small-angle form.
    full: Option<FullEquation>,
    /// |q| at which the block has overturned ([`RigidOverturning::ReachesLimit`]).
    limit: f64,
    /// |q| at which a block rocking on past the limit lies on its side, H pi/2
    /// ([`RigidOverturning::CannotReturn`]).
    on_side: f64,
    overturning: RigidOverturning,
    restitution: f64,
    tipping: f64,
    /// See [`RigidBlock::pull_factor`].
    pull_factor: f64,
    uplift: f64,
    duration: f64,
    max_step: f64,
    breakpoint: usize,
    state: RigidState,
    budget: RunBudget,
    outcome: RigidOutcome,
}

impl<'a> Run<'a> {
    fn new(
        block: &RigidBlock,
        floor: &'a dyn FloorMotion,
        initial: InitialState,
        duration: f64,
        settings: &RigidSettings,
    ) -> Self {
        let side = if initial.q != 0.0 {
            initial.q.signum()
        } else if initial.qdot != 0.0 {
            initial.qdot.signum()
        } else {
            0.0
        };
        let phase = if side == 0.0 {
            RigidPhase::Rest
        } else {
            RigidPhase::rocking(side)
        };
        let state = RigidState {
            t: 0.0,
            q: initial.q,
            qdot: initial.qdot,
            phase,
        };
        Run {
            floor,
            propagator: Propagator {
                floor,
                quiet_after: floor.quiet_after(),
                k: block.frequency(),
                width: block.width,
            },
            full: match block.form {
                RigidForm::SmallAngle => None,
                RigidForm::Full => Some(FullEquation {
                    height: block.height,
                    alpha: block.slenderness(),
                    gravity: block.gravity,
                    scale: block.height * block.frequency().powi(2),
                    rtol: settings.rtol,
                    atol: settings.atol,
                }),
            },
            limit: block.overturning_displacement(),
            on_side: block.height * std::f64::consts::FRAC_PI_2,
            overturning: block.overturning,
            restitution: block.restitution(),
            tipping: block.tipping_acceleration(),
            pull_factor: block.pull_factor(),
            uplift: block.uplift_acceleration,
            duration,
            max_step: settings.max_step,
            breakpoint: 0,
            state,
            budget: RunBudget::new(),
            outcome: RigidOutcome {
                overturned: false,
                t_overturn: None,
                n_uplift: 0,
                n_impact: 0,
                n_settle: 0,
                first_uplift: None,
                max_abs_q: initial.q.abs(),
                t_max_abs_q: 0.0,
                final_state: state,
                events: Vec::new(),
                steps: 0,
            },
        }
    }

    fn run(mut self) -> Result<RigidOutcome> {
        let quiet_after = self.floor.quiet_after();
        while self.state.t < self.duration && self.state.phase != RigidPhase::Overturned {
            let quiet = quiet_after.is_some_and(|quiet| self.state.t >= quiet);
            // At rest on a floor at rest for good: nothing more can happen.
            if self.state.phase == RigidPhase::Rest && quiet {
                self.state.t = self.duration;
                break;
            }
            // Rocking on a floor at rest for good: its free motion decides.
            if quiet && self.judge_free_motion()? {
                break;
            }
            // The full form rocks in adaptive stretches of its own.
            if let (Some(full), true) = (self.full, self.state.phase != RigidPhase::Rest) {
                self.budget
                    .step(self.state.t, self.outcome.steps)
                    .map_err(|m| self.failure(m))?;
                let until = self.stretch_end();
                full::rock(&mut self, &full, until)?;
                continue;
            }
            let t_end = self.next_stop();
            self.outcome.steps += 1;
            self.budget
                .step(self.state.t, self.outcome.steps)
                .map_err(|m| self.failure(m))?;
            match self.state.phase {
                RigidPhase::Rest => self.rest_step(t_end)?,
                _ => self.rocking_step(t_end)?,
            }
        }
        if self.state.phase != RigidPhase::Overturned {
            self.judge_free_motion()?;
        }
        self.outcome.final_state = self.state;
        Ok(self.outcome)
    }

    fn failure(&self, message: String) -> SolverError {
        SolverError::Failed {
            method: "rigid".to_string(),
            t: self.state.t,
            message,
        }
    }

    /// Where a stretch of the full form's rocking ends: the moment the floor comes to rest for
    /// good (where, by the rule that a block has overturned once it cannot come back, its free
    /// motion is judged; both rules end the stretch there, so that they take the same steps), or
    /// the end of the run.
    fn stretch_end(&self) -> f64 {
        match self.floor.quiet_after() {
            Some(quiet) if quiet > self.state.t => quiet.min(self.duration),
            _ => self.duration,
        }
    }

    /// The end of the next step: a step later, the next breakpoint, or the end of the run.
    fn next_stop(&mut self) -> f64 {
        let t = self.state.t;
        let breakpoints = self.floor.breakpoints();
        while self.breakpoint < breakpoints.len() && breakpoints[self.breakpoint] <= t {
            self.breakpoint += 1;
        }
        let mut end = (t + self.max_step).min(self.duration);
        if let Some(&b) = breakpoints.get(self.breakpoint) {
            end = end.min(b);
        }
        end
    }

    /// The side (+1 right, -1 left) a resting block starts rocking to under the floor
    /// acceleration `a`, or None if it stays. A floor at the uplift acceleration itself does not
    /// lift it: for Housner's block the moments about the toe then balance, and the block has no
    /// pull away from the floor.
    fn uplift_side(&self, a: f64) -> Option<f64> {
        if a < -self.uplift {
            Some(1.0)
        } else if a > self.uplift {
            Some(-1.0)
        } else {
            None
        }
    }

    fn rest_step(&mut self, t_end: f64) -> Result<()> {
        let t0 = self.state.t;
        let lifts = |t: f64| self.uplift_side(self.floor.acceleration(t)).is_some();
        let mut found = None;
        if lifts(t0) {
            found = Some(t0);
        } else {
            let mut previous = t0;
            for j in 1..=REST_SAMPLES {
                let t = if j == REST_SAMPLES {
                    t_end
                } else {
                    t0 + (t_end - t0) * j as f64 / REST_SAMPLES as f64
                };
                if lifts(t) {
                    found = Some(first_true(previous, t, &lifts));
                    break;
                }
                previous = t;
            }
        }
        match found {
            None => self.state.t = t_end,
            Some(t) => {
                let side = self.uplift_side(self.floor.acceleration(t)).unwrap_or(1.0);
                self.state = RigidState {
                    t,
                    q: 0.0,
                    qdot: 0.0,
                    phase: RigidPhase::rocking(side),
                };
                self.outcome.n_uplift += 1;
                self.outcome.first_uplift.get_or_insert(t);
                self.book(RigidEventKind::Uplift, 0.0, 0.0)?;
            }
        }
        Ok(())
    }

    fn rocking_step(&mut self, t_end: f64) -> Result<()> {
        let RigidState {
            t: t0,
            q: q0,
            qdot: v0,
            phase,
        } = self.state;
        let side = phase.side();
        let propagator = self.propagator;
        let at = |t: f64| propagator.propagate(t0, q0, v0, side, t - t0);
        let (q1, v1) = at(t_end);
        if !(q1.is_finite() && v1.is_finite()) {
            return Err(self.failure(format!(
                "the state is no longer finite at t = {t_end} s (q = {q1}, q' = {v1}): the floor \
                 acceleration is not a finite number"
            )));
        }

        // Pieces on which q is monotone: (start time, q there, direction of motion). The first
        // moves the way q' points, or away from the floor when the block has just lifted off
        // (q' = 0, its acceleration pointing away from the floor); a second starts where q'
        // changes sign.
        let direction = if v0 != 0.0 { v0.signum() } else { side };
        let mut pieces = vec![(t0, q0, direction)];
        if v1 * direction < 0.0 {
            let t_turn = first_true(t0, t_end, |t| at(t).1 * direction <= 0.0);
            pieces.push((t_turn, at(t_turn).0, -direction));
        }
        for (i, &(ta, qa, d)) in pieces.iter().enumerate() {
            let (tb, qb) = pieces.get(i + 1).map_or((t_end, q1), |p| (p.0, p.1));
            self.peak(ta, qa);
            if d * side < 0.0 {
                // Moving towards the floor: an impact when q reaches 0.
                if side * qb <= 0.0 {
                    let te = if side * qa <= 0.0 {
                        ta
                    } else {
                        first_true(ta, tb, |t| side * at(t).0 <= 0.0)
                    };
                    return self.impact(te, at(te).1);
                }
            } else if side * qb >= self.away_limit() {
                // Moving away from it: overturned when |q| reaches the overturning displacement
                // (or, by the rule that it cannot return, when it lies on its side).
                let limit = self.away_limit();
                let te = first_true(ta, tb, |t| side * at(t).0 >= limit);
                return self.overturn(te, side * limit, at(te).1);
            }
        }
        self.peak(t_end, q1);
        self.state = RigidState {
            t: t_end,
            q: q1,
            qdot: v1,
            phase,
        };
        Ok(())
    }

    fn peak(&mut self, t: f64, q: f64) {
        if q.abs() > self.outcome.max_abs_q {
            self.outcome.max_abs_q = q.abs();
            self.outcome.t_max_abs_q = t;
        }
    }

    fn impact(&mut self, t: f64, qdot_before: f64) -> Result<()> {
        let side = -self.state.phase.side();
        let qdot = self.restitution * qdot_before;
        self.state = RigidState {
            t,
            q: 0.0,
            qdot,
            phase: RigidPhase::rocking(side),
        };
        self.outcome.n_impact += 1;
        self.book(RigidEventKind::Impact, qdot_before, qdot)?;

        // Chatter (see the module documentation): the impacts still to come would end within
        // 2 |q'| / (c (g B/H - |a|)(1 - e)).
        let a = self.floor.acceleration(t).abs();
        let pull = self.pull_factor * (self.tipping - a);
        if pull > 0.0 && 2.0 * qdot.abs() <= ZENO_TIME * pull * (1.0 - self.restitution) {
            self.state = RigidState {
                t,
                q: 0.0,
                qdot: 0.0,
                phase: RigidPhase::Rest,
            };
            self.outcome.n_settle += 1;
            self.book(RigidEventKind::Settle, qdot, 0.0)?;
        }
        Ok(())
    }

    /// |q| at which a block moving away from the floor has overturned.
    fn away_limit(&self) -> f64 {
        match self.overturning {
            RigidOverturning::ReachesLimit => self.limit,
            RigidOverturning::CannotReturn => self.on_side,
        }
    }

    /// By [`RigidOverturning::CannotReturn`], a rocking block whose free motion never brings it
    /// back to the floor has overturned now (see the module documentation); true if it has.
    fn judge_free_motion(&mut self) -> Result<bool> {
        let RigidState { t, q, qdot, phase } = self.state;
        if self.overturning != RigidOverturning::CannotReturn
            || !matches!(phase, RigidPhase::RockRight | RigidPhase::RockLeft)
        {
            return Ok(false);
        }
        let side = phase.side();
        let gone = match self.full {
            // q - s B = c1 e^(k t) + c2 e^(-k t), 2 s c1 = s (q - s B) + s q'/k.
            None => {
                let k = self.propagator.k;
                side * q - self.propagator.width + side * qdot / k >= 0.0
            }
            Some(FullEquation { height, alpha, .. }) => {
                let p = self.propagator.k;
                // u = s theta, w = s theta'; the energy above that of the barrier u = alpha.
                let (u, w) = (side * q / height, side * qdot / height);
                let half = 0.5 * (alpha - u);
                let excess = 0.5 * w * w - 2.0 * p * p * half.sin() * half.sin();
                if u >= alpha {
                    w >= 0.0 || excess <= 0.0
                } else {
                    w > 0.0 && excess >= 0.0
                }
            }
        };
        if gone {
            self.overturn(t, q, qdot)?;
        }
        Ok(gone)
    }

    /// The block has overturned at `q`.
    fn overturn(&mut self, t: f64, q: f64, qdot: f64) -> Result<()> {
        self.state = RigidState {
            t,
            q,
            qdot,
            phase: RigidPhase::Overturned,
        };
        self.peak(t, q);
        self.outcome.overturned = true;
        self.outcome.t_overturn = Some(t);
        self.book(RigidEventKind::Overturn, qdot, qdot)
    }

    /// Logs an event at the current state and counts it against the budget.
    fn book(&mut self, kind: RigidEventKind, qdot_before: f64, qdot_after: f64) -> Result<()> {
        let s = self.state;
        self.outcome.events.push(RigidEvent {
            t: s.t,
            kind,
            q: s.q,
            qdot_before,
            qdot_after,
            to: s.phase,
        });
        self.budget.event(s.t).map_err(|m| self.failure(m))
    }
}

/// The exact propagator of a rocking block (see the module documentation).
#[derive(Clone, Copy)]
struct Propagator<'a> {
    floor: &'a dyn FloorMotion,
    /// When the floor comes to rest for good ([`FloorMotion::quiet_after`]).
    quiet_after: Option<f64>,
    k: f64,
    width: f64,
}

impl Propagator<'_> {
    /// (q, q') a time `tau` after t0, from (q0, v0) at t0 rocking on `side`.
    fn propagate(&self, t0: f64, q0: f64, v0: f64, side: f64, tau: f64) -> (f64, f64) {
        self.propagate_small_angle(t0, q0, v0, side, tau)
    }

    /// The exact solution of q'' = k^2 (q - side B) - (3/2) a(t), with the forcing integrals by
    /// 8-point Gauss-Legendre quadrature.
    fn propagate_small_angle(&self, t0: f64, q0: f64, v0: f64, side: f64, tau: f64) -> (f64, f64) {
        let k = self.k;
        let (sinh, cosh) = ((k * tau).sinh(), (k * tau).cosh());
        let half_sinh = (0.5 * k * tau).sinh();
        let (mut int_sinh, mut int_cosh) = (0.0, 0.0);
        // Once the floor is at rest for good the forcing integrals vanish.
        let forced = self.quiet_after.is_none_or(|quiet| t0 < quiet);
        if forced {
            let half = 0.5 * tau;
            for (x, w) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
                for u in [half * (1.0 - x), half * (1.0 + x)] {
                    let f = -1.5 * self.floor.acceleration(t0 + u);
                    // sinh and cosh of the lag from one exponential.
                    let grow = (k * (tau - u)).exp();
                    let decay = 1.0 / grow;
                    int_sinh += w * 0.5 * (grow - decay) * f;
                    int_cosh += w * 0.5 * (grow + decay) * f;
                }
            }
            int_sinh *= half;
            int_cosh *= half;
        }
        let q = q0 * cosh - 2.0 * side * self.width * half_sinh * half_sinh
            + v0 / k * sinh
            + int_sinh / k;
        let v = (q0 - side * self.width) * k * sinh + v0 * cosh + int_cosh;
        (q, v)
    }
}

/// The earliest time in (lo, hi] at which `holds` is true, to the resolution of the floating-point
/// time, given that it holds at `hi` (and is taken not to at `lo`), by bisection.
fn first_true(lo: f64, hi: f64, mut holds: impl FnMut(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gauss_rule_is_exact_to_degree_15() {
        // int_{-1}^{1} x^n dx = 2/(n + 1) for even n, 0 for odd n.
        for n in 0..=15 {
            let mut sum = 0.0;
            for (x, w) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
                sum += w * (x.powi(n) + (-x).powi(n));
            }
            let exact = if n % 2 == 0 {
                2.0 / (n as f64 + 1.0)
            } else {
                0.0
            };
            assert!((sum - exact).abs() < 2e-15, "x^{n}: {sum} against {exact}");
        }
    }

    #[test]
    fn bisection_finds_the_first_time_to_the_last_bit() {
        let t = first_true(1.0, 2.0, |t| t >= std::f64::consts::SQRT_2);
        assert!((t - std::f64::consts::SQRT_2).abs() <= 2.0 * f64::EPSILON);
    }
}
