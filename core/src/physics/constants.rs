//! Derived constants of the SDOF model (book/src/model.md §2-§5 and §7a-§7b).

use serde::{Deserialize, Serialize};

use crate::base::double_double::DoubleDouble as Dd;
use crate::base::invalid::InvalidParameter;
use crate::physics::body::{Body, ConstantSet, SelfWeight, DEFAULT_LANDING_RESTITUTION};

type Result<T> = std::result::Result<T, InvalidParameter>;
use crate::physics::flexural_shape::SelfWeightedShape;

/// First root of cos L cosh L = -1 (first cantilever mode), to twice the precision: the root to
/// 60 digits, 1.8751040687119611664453082410782141625701, split into the double nearest it and the
/// double nearest the rest.
const MODE_ROOT_TWICE: Dd = Dd {
    hi: 1.875_104_068_711_961_1,
    lo: 5.255_420_140_731_619e-17,
};

/// First root of cos L cosh L = -1 (first cantilever mode): the double nearest it.
pub const MODE_ROOT: f64 = MODE_ROOT_TWICE.hi;

/// sigma = (cosh L + cos L)/(sinh L + sin L) = 0.73409551375891275582878278897692494488 to
/// twice the precision, as [`MODE_ROOT_TWICE`].
const MODE_SIGMA_TWICE: Dd = Dd {
    hi: 0.734_095_513_758_912_8,
    lo: -4.295_637_836_888_931_4e-17,
};

/// sigma = (cosh L + cos L)/(sinh L + sin L) of the first cantilever mode (book/src/model.md §2):
/// the double nearest it.
pub fn mode_sigma() -> f64 {
    MODE_SIGMA_TWICE.hi
}

/// The first cantilever mode U(xi), scaled to U(1) = 1 (book/src/model.md §2).
pub fn cantilever_mode(xi: f64) -> f64 {
    let (l, sigma) = (MODE_ROOT, mode_sigma());
    let z = l * xi;
    (z.cosh() - z.cos() - sigma * (z.sinh() - z.sin())) / 2.0
}

/// dU/dxi of the first cantilever mode [`cantilever_mode`].
pub fn cantilever_mode_slope(xi: f64) -> f64 {
    let (l, sigma) = (MODE_ROOT, mode_sigma());
    let z = l * xi;
    l * (z.sinh() + z.sin() - sigma * (z.cosh() - z.cos())) / 2.0
}

/// The slope d/dxi of the flexural shape of `body`'s variant at height xi H (see
/// [`flexural_shape_at`]): the turn of the sections there is this times s / H.
pub fn flexural_shape_slope_at(body: &Body, xi: f64) -> Option<f64> {
    match body.self_weight {
        SelfWeight::Paper => Some(cantilever_mode_slope(xi)),
        SelfWeight::Consistent => {
            SelfWeightedShape::new(body.gravity_parameter()).map(|shape| shape.slope(xi))
        }
    }
}

/// The flexural shape of `body`'s variant at height xi H, scaled to 1 at the top: the paper's
/// U(xi), or psi(xi) of the consistent variant (`None` when the body buckles under its own
/// weight).
pub fn flexural_shape_at(body: &Body, xi: f64) -> Option<f64> {
    match body.self_weight {
        SelfWeight::Paper => Some(cantilever_mode(xi)),
        SelfWeight::Consistent => {
            SelfWeightedShape::new(body.gravity_parameter()).map(|shape| shape.value(xi))
        }
    }
}

/// Value of M g H^2 / EI at which a uniform cantilever buckles under its own weight.
pub const SELF_WEIGHT_BUCKLING_PARAMETER: f64 = 7.837;

/// Share of [`SELF_WEIGHT_BUCKLING_PARAMETER`] above which a run warns that the self-weight the
/// model leaves out of bending matters: at the paper's own 0.235 a beam-column with it lifts off
/// 24 % later than s_n (book/src/model.md §7a); at 0.1 the errors are of order 10 %.
pub const SELF_WEIGHT_WARNING_SHARE: f64 = 0.1;

/// Shortest pre-uplift period a model may have, s.
pub const MIN_PERIOD: f64 = 1e-4;

/// The numbers of the flexural shape the model is built from, per unit height: the paper's
/// cantilever mode U (exact, or as printed in the paper), or the self-weighted mode psi of the
/// consistent variant (the crate's `flexural_shape` module).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct ModeShapeIntegrals {
    /// int_0^1 U dxi.
    pub int_u: f64,
    /// int_0^1 U^2 dxi.
    pub int_u2: f64,
    /// int_0^1 U xi dxi (1/L^2 for the paper's U): the base moment of the inertial loads m U.
    pub int_u_xi: f64,
    /// beta1 = int U / int U^2.
    pub beta1: f64,
    /// Ke = stiffness_coefficient * EI / H^3 (L^3 sigma = 4.8398 for U).
    pub stiffness_coefficient: f64,
    /// Base bending moment per flexural displacement s, in EI/H^2 (U''(0) = L^2 for U; Omega
    /// int psi xi for psi, from the inertial loads that hold s).
    pub base_moment_coefficient: f64,
    /// Whether the weight enters the bending (the consistent variant): then the flexural
    /// equation after uplift carries the weight's moment M g (int U) theta about the deflected
    /// axis (validation/SELF-WEIGHT.md).
    pub weight_in_bending: bool,
}

impl ModeShapeIntegrals {
    /// The exact numbers of the paper's U (book/src/model.md §2, constants).
    pub fn exact() -> Self {
        ShapeNumbers::exact().rounded()
    }

    /// The rounded values printed in the paper: L = 1.8751, int U = 0.3915 (Me = 0.3915 M),
    /// int U^2 = 0.2503, beta1 = 1.564, Ke = 4.840 EI/H^3.
    pub fn paper() -> Self {
        ShapeNumbers::paper().rounded()
    }

    /// The numbers of the self-weighted mode psi of the consistent variant. With
    /// omega^2 = Omega EI/(m H^4): Ke = K_psi int psi/int psi^2 = Omega (int psi) EI/H^3 (the
    /// base shear of the loads m psi per s), and the base moment of those loads per s is
    /// K_psi H (int psi xi)/int psi^2 = Omega (int psi xi) EI/H^2.
    pub fn self_weighted(psi: &SelfWeightedShape) -> Self {
        ShapeNumbers::self_weighted(psi).rounded()
    }

    /// The rigid-limit uplift factor: the quasi-static uplift acceleration omega^2 s_n / beta1 of
    /// the elastic model as EI -> infinity, in units of Housner's g B / H (the acceleration at which
    /// a rigid block tips). With omega^2 = Ke/Me = c_K EI/(int U M H^3) and, as EI -> infinity,
    /// s_n -> B M g H^2/(2 EI c_M) (eq. 8, c_M the base moment coefficient), omega^2 s_n / beta1
    /// -> [c_K/(2 int U c_M beta1)] g B/H. With the exact constants (c_K = L^3 sigma,
    /// int U = sigma/L, c_M = L^2, beta1 = 4 sigma/L) the bracket is L^3/(8 sigma) = 1.122622;
    /// with the paper's rounded ones 1.124082. The consistent variant's psi tends to U as
    /// EI -> infinity, so its factor is the same.
    ///
    /// It exceeds 1 because the one-mode model takes the base bending moment from the curvature of
    /// the first mode, EI (L/H)^2 s. Under the quasi-static uniform inertia load M a that a stiff
    /// body carries before uplift, the first mode alone gives a base moment of 4 sigma M a H / L^3
    /// = (8 sigma/L^3) M a H/2 = 0.891 of the exact M a H/2, so the floor must push 1.1226 times
    /// harder before the moment reaches the weight's M g B/2. A rigid block (and the exact statics
    /// of a stiff continuum) tips at g B/H. Once rocking, the elastic model's rigid limit is
    /// Housner's equation (book/src/model.md §7, rigid limit): only the uplift from rest differs.
    pub fn rigid_limit_uplift_factor(&self) -> f64 {
        self.stiffness_coefficient / (2.0 * self.int_u * self.base_moment_coefficient * self.beta1)
    }

    /// The shape of `body`'s variant: the paper's U (exact or rounded), or psi solved for the
    /// body's M g H^2/EI (`None` when the body buckles under its own weight).
    pub fn for_body(body: &Body) -> Option<Self> {
        ShapeNumbers::for_body(body).map(|numbers| numbers.rounded())
    }
}

/// The numbers of [`ModeShapeIntegrals`] to twice the precision: their one home, from which the
/// doubles are rounded once.
#[derive(Debug, Clone, Copy)]
struct ShapeNumbers {
    int_u: Dd,
    int_u2: Dd,
    int_u_xi: Dd,
    beta1: Dd,
    stiffness_coefficient: Dd,
    base_moment_coefficient: Dd,
    weight_in_bending: bool,
}

impl ShapeNumbers {
    /// The paper's U: int U = sigma/L, int U^2 = 1/4, int U xi = 1/L^2, Ke = L^3 sigma EI/H^3,
    /// U''(0) = L^2.
    fn exact() -> Self {
        let (l, sigma) = (MODE_ROOT_TWICE, MODE_SIGMA_TWICE);
        let int_u = sigma / l;
        let int_u2 = Dd::exact(0.25);
        ShapeNumbers {
            int_u,
            int_u2,
            int_u_xi: 1.0 / (l * l),
            beta1: int_u / int_u2,
            stiffness_coefficient: l.cube() * sigma,
            base_moment_coefficient: l * l,
            weight_in_bending: false,
        }
    }

    /// The paper's printed values, as the decimals they are printed as (worked out once: a
    /// sweep builds a body at every point).
    fn paper() -> Self {
        static PAPER: std::sync::OnceLock<ShapeNumbers> = std::sync::OnceLock::new();
        *PAPER.get_or_init(Self::paper_from_decimals)
    }

    fn paper_from_decimals() -> Self {
        let l = Dd::decimal(1.8751);
        ShapeNumbers {
            int_u: Dd::decimal(0.3915),
            int_u2: Dd::decimal(0.2503),
            int_u_xi: 1.0 / (l * l),
            beta1: Dd::decimal(1.564),
            stiffness_coefficient: Dd::decimal(4.840),
            base_moment_coefficient: l * l,
            weight_in_bending: false,
        }
    }

    /// The self-weighted mode psi, from its numbers in double precision.
    fn self_weighted(psi: &SelfWeightedShape) -> Self {
        let (int_psi, int_psi2) = (Dd::exact(psi.int_psi), Dd::exact(psi.int_psi2));
        let omega = Dd::exact(psi.omega_coefficient);
        ShapeNumbers {
            int_u: int_psi,
            int_u2: int_psi2,
            int_u_xi: Dd::exact(psi.int_psi_xi),
            beta1: int_psi / int_psi2,
            stiffness_coefficient: omega * int_psi,
            base_moment_coefficient: omega * psi.int_psi_xi,
            weight_in_bending: true,
        }
    }

    /// The numbers of a shape known only in double precision.
    fn of(shape: &ModeShapeIntegrals) -> Self {
        ShapeNumbers {
            int_u: Dd::exact(shape.int_u),
            int_u2: Dd::exact(shape.int_u2),
            int_u_xi: Dd::exact(shape.int_u_xi),
            beta1: Dd::exact(shape.beta1),
            stiffness_coefficient: Dd::exact(shape.stiffness_coefficient),
            base_moment_coefficient: Dd::exact(shape.base_moment_coefficient),
            weight_in_bending: shape.weight_in_bending,
        }
    }

    fn for_body(body: &Body) -> Option<Self> {
        match (body.self_weight, body.constant_set) {
            (SelfWeight::Paper, ConstantSet::Exact) => Some(Self::exact()),
            (SelfWeight::Paper, ConstantSet::Paper) => Some(Self::paper()),
            (SelfWeight::Consistent, _) => SelfWeightedShape::new(body.gravity_parameter())
                .map(|psi| Self::self_weighted(&psi)),
        }
    }

    fn rounded(&self) -> ModeShapeIntegrals {
        ModeShapeIntegrals {
            int_u: self.int_u.value(),
            int_u2: self.int_u2.value(),
            int_u_xi: self.int_u_xi.value(),
            beta1: self.beta1.value(),
            stiffness_coefficient: self.stiffness_coefficient.value(),
            base_moment_coefficient: self.base_moment_coefficient.value(),
            weight_in_bending: self.weight_in_bending,
        }
    }
}

/// The velocity shape while rocking, V = s' U + r' xi (eq. 13), with s' = ds/dq and r' = 1 - s'
/// constant while rocking (the paper's (-s_n U + B xi)/d), and its integrals per unit height.
struct RockingShape {
    ds: Dd,
    dr: Dd,
    /// int_0^1 U V dxi.
    int_uv: Dd,
    /// int_0^1 V dxi.
    int_v: Dd,
    /// int_0^1 V^2 dxi.
    int_v2: Dd,
}

impl RockingShape {
    fn new(shape: &ShapeNumbers, flexural_slope: Dd) -> Self {
        let (ds, dr) = (flexural_slope, 1.0 - flexural_slope);
        RockingShape {
            ds,
            dr,
            int_uv: ds * shape.int_u2 + dr * shape.int_u_xi,
            int_v: ds * shape.int_u + dr / 2.0,
            int_v2: ds * ds * shape.int_u2 + 2.0 * ds * dr * shape.int_u_xi + dr * dr / 3.0,
        }
    }
}

/// The coefficients of eq. 16 within each mode, written x'' + c x' + k x = -beta a with
/// x = q - q_eq: k = nu F'/Me and c = (gamma/E) nu F'/Me, each rounded once from the constants
/// to twice the precision. They are what the exact method integrates
/// ([`crate::Automaton::linear_form`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LinearRates {
    /// k before uplift, 1/s^2 (omega^2).
    pub pre_uplift_stiffness: f64,
    /// c before uplift, 1/s (2 h omega).
    pub pre_uplift_damping: f64,
    /// k while rocking, 1/s^2 (negative).
    pub rocking_stiffness: f64,
    /// c while rocking, 1/s (negative; 0 when the damping does not act while rocking).
    pub rocking_damping: f64,
}

/// Every constant the automaton and the reports need, derived once from a [`Body`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Constants {
    /// Exact or the paper's rounded mode-shape numbers.
    pub constant_set: ConstantSet,
    /// The paper's model or the self-weight-consistent variant.
    pub self_weight: SelfWeight,
    /// The flexural shape's numbers.
    pub mode_shape: ModeShapeIntegrals,
    /// Me, generalised mass, kg.
    pub generalised_mass: f64,
    /// Ke, generalised stiffness, N/m.
    pub generalised_stiffness: f64,
    /// omega, pre-uplift circular frequency, rad/s.
    pub omega: f64,
    /// T, pre-uplift period, s.
    pub period: f64,
    /// gamma/E = 2 h / omega, strain-rate damping coefficient, s.
    pub damping_coefficient: f64,
    /// s_n, top displacement at which uplift starts, m.
    pub uplift_displacement: f64,
    /// beta1, participation factor before uplift (nu1 = 1).
    pub beta1: f64,
    /// nu2, effectiveness factor while rocking.
    pub nu2: f64,
    /// beta2, participation factor while rocking.
    pub beta2: f64,
    /// zetaU: velocity ratio at uplift (q' -> zetaU q').
    pub zeta_uplift: f64,
    /// zetaL: velocity ratio at landing (q' -> q' / zetaL).
    pub zeta_landing: f64,
    /// dF/dq while rocking, N/m (negative): -Ke s_n/(B - s_n) in the paper's model.
    pub rocking_stiffness: f64,
    /// ds/dq while rocking: -s_n/(B - s_n) in the paper's model, near 0 in the consistent one.
    pub rocking_flexural_slope: f64,
    /// |q| at which the restoring force returns to zero and the body falls over, m: B in the
    /// paper's model.
    pub topple_displacement: f64,
    /// The flexural part s there, m: 0 in the paper's model.
    pub flexural_part_at_topple: f64,
    /// Floor acceleration that starts uplift quasi-statically: omega^2 s_n / beta1, m/s^2.
    pub quasi_static_uplift_acceleration: f64,
    /// M g H^2 / EI: the size of the self-weight effect the paper's model leaves out of bending.
    pub gravity_parameter: f64,
    /// gravity_parameter / 7.837 (1 = buckling under self-weight).
    pub gravity_parameter_ratio: f64,
    /// Width B, m.
    pub width: f64,
    /// e, the factor on q' at every landing on top of q' -> q'/zetaL (the body's
    /// `landing_restitution`; written out only when it is not 1).
    #[serde(
        default = "default_landing_restitution",
        skip_serializing_if = "is_default_landing_restitution"
    )]
    pub landing_restitution: f64,
    /// Whether the strain-rate damping term acts while rocking (written out only when it does
    /// not).
    #[serde(default = "acts", skip_serializing_if = "acts_given")]
    pub damping_while_rocking: bool,
    /// k and c of each mode, rounded once (not written out: they follow from the rest).
    #[serde(skip)]
    pub linear_rates: LinearRates,
}

fn default_landing_restitution() -> f64 {
    DEFAULT_LANDING_RESTITUTION
}

fn is_default_landing_restitution(e: &f64) -> bool {
    *e == DEFAULT_LANDING_RESTITUTION
}

fn acts() -> bool {
    true
}

fn acts_given(acts: &bool) -> bool {
    *acts
}

impl Constants {
    /// Derives the constants and rejects bodies for which the model has no meaning.
    ///
    /// They are computed to twice the precision from the body's numbers as written (0.7 is seven
    /// tenths) and each rounded once, so that every constant is the double nearest its true value
    /// (within an ulp): the exact method's event times depend on them, and near a grazing uplift
    /// or over a long chain of impacts they amplify a constant's rounding.
    pub fn new(body: &Body) -> Result<Self> {
        let written = Dd::decimal;
        let (h, b) = (written(body.height), written(body.width));
        let mass = written(body.mass);
        let flexural_rigidity = written(body.flexural_rigidity);
        let mg = mass * written(body.gravity);
        let gravity_parameter = body.gravity_parameter();

        // A cantilever buckles under its own weight at M g H^2/EI = 7.837: beyond it there is no
        // upright equilibrium to rock about. (This also keeps the paper's s_n below B: s_n
        // reaches B only at M g H^2/EI = 2 L^2/(1 - 2 int U) = 32.4.)
        let numbers = ShapeNumbers::for_body(body)
            .filter(|_| gravity_parameter < SELF_WEIGHT_BUCKLING_PARAMETER);
        let Some(numbers) = numbers else {
            return Err(InvalidParameter::new(
                "derived gravity parameter M g H^2/EI",
                // A derived number, to the digits that tell it from the limit.
                crate::base::format::significant(gravity_parameter, 6),
                &format!(
                    "the body buckles under its own weight: M g H^2/EI must be below \
                     {SELF_WEIGHT_BUCKLING_PARAMETER} (raise the flexural rigidity or lower the mass)"
                ),
            ));
        };
        let shape = numbers.rounded();

        let me = mass * numbers.int_u;
        let ke = numbers.stiffness_coefficient * flexural_rigidity / h.cube();
        let omega_squared = ke / me;
        let omega = omega_squared.sqrt();
        let period = (crate::base::double_double::TWO_PI / omega).value();
        if !(omega.value().is_finite()
            && omega.value() > 0.0
            && crate::base::limits::at_least(period, MIN_PERIOD))
        {
            return Err(InvalidParameter::new(
                "derived pre-uplift period T (s)",
                period,
                &format!(
                    "must be at least {MIN_PERIOD:e} s: no body that rocks on a floor is that stiff \
                     for its mass, and the solvers would need steps far below a microsecond"
                ),
            ));
        }

        // Moments about the toe (eq. 8; validation/SELF-WEIGHT.md): the base bending moment
        // c_M EI s/H^2 plus the weight's M g (int U) s equal the weight's M g B/2 at uplift.
        let s_n = b
            / (2.0 * flexural_rigidity * numbers.base_moment_coefficient / (mg * h * h)
                + 2.0 * numbers.int_u);
        let rocking = RockingBranch::new(&numbers, ke, s_n, b, mg / h);

        if !(rocking.stiffness.value() < 0.0 && rocking.topple_displacement.value() > s_n.value()) {
            return Err(InvalidParameter::new(
                "derived restoring force while rocking",
                format!(
                    "dF/dq = {} N/m, F = 0 at q = {} m",
                    crate::base::format::shortest(rocking.stiffness.value()),
                    crate::base::format::shortest(rocking.topple_displacement.value())
                ),
                &format!(
                    "the force must fall after uplift at s_n = {} m and vanish beyond it: this body \
                     is too close to buckling under its own weight for the model",
                    crate::base::format::shortest(s_n.value())
                ),
            ));
        }

        let v = RockingShape::new(&numbers, rocking.flexural_slope);
        let (ds, dr) = (v.ds, v.dr);
        let nu2 = v.int_uv / v.int_v2;
        let beta2 = v.int_v / v.int_v2;

        // Eqs. 19-22: angular momentum about the pivot toe (uplift) and the landing edge. The
        // body turns about the toe at r'/H per unit q', so the centroid's vertical motion adds
        // (B^2/4) r' (the paper: (B^2/4) B/d).
        let int_uy = h * h * numbers.int_u_xi;
        let int_vy = h * h * (ds * numbers.int_u_xi + dr / 3.0);
        let rotary = b * b / 12.0;
        let vertical = (b * b / 4.0) * dr;
        let zeta_uplift = (int_uy + rotary) / (int_vy + rotary + vertical);
        let zeta_landing = ((int_uy + rotary) / (int_vy + rotary - vertical)).value();
        if !(zeta_landing > 0.0 && zeta_landing < 1.0) {
            return Err(InvalidParameter::new(
                "derived landing ratio zetaL",
                zeta_landing,
                &format!(
                    "the body (H = {} m, B = {} m) is too squat for the slender-body model: zetaL must lie in (0, 1)",
                    body.height, body.width
                ),
            ));
        }

        // gamma/E = 2 h/omega; k = nu F'/Me and c = (gamma/E) k in each mode (nu = 1, F' = Ke
        // before uplift), c = 0 while rocking when the damping does not act then.
        let damping_coefficient = 2.0 * written(body.damping_ratio) / omega;
        let rocking_rate = nu2 * rocking.stiffness / me;
        let linear_rates = LinearRates {
            pre_uplift_stiffness: omega_squared.value(),
            pre_uplift_damping: (damping_coefficient * omega_squared).value(),
            rocking_stiffness: rocking_rate.value(),
            rocking_damping: if body.damping_while_rocking {
                (damping_coefficient * rocking_rate).value()
            } else {
                0.0
            },
        };

        Ok(Constants {
            constant_set: body.constant_set,
            self_weight: body.self_weight,
            mode_shape: shape,
            generalised_mass: me.value(),
            generalised_stiffness: ke.value(),
            omega: omega.value(),
            period,
            damping_coefficient: damping_coefficient.value(),
            uplift_displacement: s_n.value(),
            beta1: shape.beta1,
            nu2: nu2.value(),
            beta2: beta2.value(),
            zeta_uplift: zeta_uplift.value(),
            zeta_landing,
            rocking_stiffness: rocking.stiffness.value(),
            rocking_flexural_slope: rocking.flexural_slope.value(),
            topple_displacement: rocking.topple_displacement.value(),
            flexural_part_at_topple: rocking.flexural_part_at_topple.value(),
            quasi_static_uplift_acceleration: (omega_squared * s_n / numbers.beta1).value(),
            gravity_parameter,
            gravity_parameter_ratio: gravity_parameter / SELF_WEIGHT_BUCKLING_PARAMETER,
            width: b.value(),
            landing_restitution: body.landing_restitution,
            damping_while_rocking: body.damping_while_rocking,
            linear_rates,
        })
    }

    /// M int_0^1 (shape)^2 dxi, kg: the kinetic energy of the body's horizontal motion is this
    /// times q'^2/2, with the shape U before uplift and V while rocking (the inertial term of the
    /// virtual-work balance, book/src/model.md §4-§5). The mass M is Me / int U.
    pub fn kinetic_mass(&self, rocking: bool) -> f64 {
        let shape = ShapeNumbers::of(&self.mode_shape);
        let mass = self.generalised_mass / shape.int_u;
        let share = if rocking {
            RockingShape::new(&shape, Dd::exact(self.rocking_flexural_slope)).int_v2
        } else {
            shape.int_u2
        };
        (mass * share).value()
    }

    /// Flexural rigidity that gives `body` (whose own `flexural_rigidity` is ignored) the
    /// pre-uplift period `period` in its variant. The paper's model inverts omega = sqrt(Ke/Me)
    /// directly; in the consistent variant omega also depends on EI through M g H^2/EI, and the
    /// period falls monotonically as EI grows, so EI is bisected (on log EI) between self-weight
    /// buckling and a body far stiffer than asked.
    pub fn flexural_rigidity_for_period(period: f64, body: &Body) -> Result<f64> {
        let omega = 2.0 * std::f64::consts::PI / period;
        let weightless = |shape: ModeShapeIntegrals| {
            omega * omega * body.mass * shape.int_u * body.height.powi(3)
                / shape.stiffness_coefficient
        };
        match body.self_weight {
            SelfWeight::Paper => Ok(weightless(
                ModeShapeIntegrals::for_body(body).unwrap_or_else(ModeShapeIntegrals::exact),
            )),
            // Below MIN_PERIOD Constants::new refuses the body, naming the period.
            SelfWeight::Consistent if period.is_nan() || period < MIN_PERIOD => {
                Ok(weightless(ModeShapeIntegrals::exact()))
            }
            SelfWeight::Consistent => {
                let period_of = |flexural_rigidity: f64| {
                    let trial = Body {
                        flexural_rigidity,
                        ..body.clone()
                    };
                    // A body refused for a period below MIN_PERIOD is stiffer than asked for;
                    // one refused for buckling is softer.
                    Constants::new(&trial)
                        .map(|c| c.period)
                        .unwrap_or_else(|e| match e {
                            InvalidParameter { key, .. } if key.contains("period") => 0.0,
                            _ => f64::INFINITY,
                        })
                };
                // The weight only lengthens the period: the weightless EI is a lower bound.
                let mut low = weightless(ModeShapeIntegrals::exact());
                let mut high = 2.0 * low;
                let mut doublings = 0;
                while period_of(high) > period {
                    high *= 2.0;
                    doublings += 1;
                    if doublings > 200 || !high.is_finite() {
                        return Err(InvalidParameter::new(
                            "body.period",
                            period,
                            "no flexural rigidity gives this period with the weight in the bending",
                        ));
                    }
                }
                for _ in 0..200 {
                    let mid = (low * high).sqrt();
                    if mid <= low || mid >= high {
                        break;
                    }
                    if period_of(mid) > period {
                        low = mid;
                    } else {
                        high = mid;
                    }
                }
                // Near buckling the period grows without bound; the bisection cannot get
                // closer to buckling than the Ritz solve resolves, so check what it reached.
                // At a period of exactly MIN_PERIOD the stiff end may be refused (0): then the
                // soft end, within rounding of it, is the answer.
                let (high, reached) = match period_of(high) {
                    reached if reached > 0.0 => (high, reached),
                    _ => (low, period_of(low)),
                };
                if (reached - period).abs() > 1e-6 * period {
                    return Err(InvalidParameter::new(
                        "body.period",
                        period,
                        &format!(
                            "with the weight in the bending the longest period this body can have \
                             short of buckling under its own weight is about {} s",
                            crate::base::format::significant(reached, 4)
                        ),
                    ));
                }
                Ok(high)
            }
        }
    }
}

/// The rocking branch |q| > s_n on the right (mirror on the left), from equilibrium about the
/// pivot toe under inertial loads lambda m U (validation/SELF-WEIGHT.md):
///
/// ```text
/// M g B/2 - M g r/2 - M g (int U) s = lambda M H int U xi   (moments about the toe)
/// K s - c M g (int U) r/H           = lambda M int U^2     (the flexural part)
/// ```
///
/// with K = Ke int U^2/int U, c = 1 when the weight enters the bending and 0 in the paper's model,
/// and F = lambda M int U the base shear. Both s and F are then linear in q = s + r; with c = 0
/// this is the paper's eq. 9b, s = s_n (B - q)/(B - s_n).
struct RockingBranch {
    /// dF/dq, N/m.
    stiffness: Dd,
    /// ds/dq.
    flexural_slope: Dd,
    /// q where F = 0, m.
    topple_displacement: Dd,
    /// s there, m.
    flexural_part_at_topple: Dd,
}

impl RockingBranch {
    fn new(shape: &ShapeNumbers, ke: Dd, s_n: Dd, width: Dd, weight_per_height: Dd) -> Self {
        // Eliminating lambda: s [M g B/(2 s_n)] + r M g kappa = M g B/2, with kappa = 1/2 - c
        // (int U xi)(int U)/int U^2 the weight's net lever on r; so s = (B/2 - kappa q)/(B/(2 s_n)
        // - kappa). F = Ke s - k_r r with k_r = c M g (int U)^2/(int U^2 H).
        let coupling = if shape.weight_in_bending { 1.0 } else { 0.0 };
        let kappa = 0.5 - coupling * shape.int_u_xi * shape.int_u / shape.int_u2;
        let k_r = coupling * weight_per_height * shape.int_u * shape.int_u / shape.int_u2;
        let flexural_slope = -kappa / (width / (2.0 * s_n) - kappa);
        let stiffness = ke * flexural_slope - k_r * (1.0 - flexural_slope);
        if shape.weight_in_bending {
            // F = Ke s_n + F' (q - s_n) = 0.
            let topple_displacement = s_n - ke * s_n / stiffness;
            RockingBranch {
                stiffness,
                flexural_slope,
                topple_displacement,
                flexural_part_at_topple: s_n + flexural_slope * (topple_displacement - s_n),
            }
        } else {
            // Eq. 17: F = Ke s vanishes with s, exactly at q = B.
            RockingBranch {
                stiffness,
                flexural_slope,
                topple_displacement: width,
                flexural_part_at_topple: Dd::exact(0.0),
            }
        }
    }
}
