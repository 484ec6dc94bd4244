//! Derived constants of the SDOF model (book/src/model.md §2-§5 and §7a-§7b).

use serde::{Deserialize, Serialize};

use crate::body::{Body, ConstantSet, SelfWeight};
use crate::invalid::InvalidParameter;

type Result<T> = std::result::Result<T, InvalidParameter>;
use crate::flexural_shape::SelfWeightedShape;

/// First root of cos L cosh L = -1 (first cantilever mode).
pub const MODE_ROOT: f64 = 1.875_104_068_711_961;

/// sigma = (cosh L + cos L)/(sinh L + sin L) of the first cantilever mode (book/src/model.md §2).
pub fn mode_sigma() -> f64 {
    let l = MODE_ROOT;
    (l.cosh() + l.cos()) / (l.sinh() + l.sin())
}

/// The first cantilever mode U(xi), scaled to U(1) = 1 (book/src/model.md §2).
pub fn cantilever_mode(xi: f64) -> f64 {
    let (l, sigma) = (MODE_ROOT, mode_sigma());
    let z = l * xi;
    (z.cosh() - z.cos() - sigma * (z.sinh() - z.sin())) / 2.0
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
        let l = MODE_ROOT;
        let sigma = mode_sigma();
        let int_u = sigma / l;
        let int_u2 = 0.25;
        ModeShapeIntegrals {
            int_u,
            int_u2,
            int_u_xi: 1.0 / (l * l),
            beta1: int_u / int_u2,
            stiffness_coefficient: l.powi(3) * sigma,
            base_moment_coefficient: l * l,
            weight_in_bending: false,
        }
    }

    /// The rounded values printed in the paper: L = 1.8751, int U = 0.3915 (Me = 0.3915 M),
    /// int U^2 = 0.2503, beta1 = 1.564, Ke = 4.840 EI/H^3.
    pub fn paper() -> Self {
        let l: f64 = 1.8751;
        ModeShapeIntegrals {
            int_u: 0.3915,
            int_u2: 0.2503,
            int_u_xi: 1.0 / (l * l),
            beta1: 1.564,
            stiffness_coefficient: 4.840,
            base_moment_coefficient: l * l,
            weight_in_bending: false,
        }
    }

    /// The numbers of the self-weighted mode psi of the consistent variant. With
    /// omega^2 = Omega EI/(m H^4): Ke = K_psi int psi/int psi^2 = Omega (int psi) EI/H^3 (the
    /// base shear of the loads m psi per s), and the base moment of those loads per s is
    /// K_psi H (int psi xi)/int psi^2 = Omega (int psi xi) EI/H^2.
    pub fn self_weighted(psi: &SelfWeightedShape) -> Self {
        ModeShapeIntegrals {
            int_u: psi.int_psi,
            int_u2: psi.int_psi2,
            int_u_xi: psi.int_psi_xi,
            beta1: psi.int_psi / psi.int_psi2,
            stiffness_coefficient: psi.omega_coefficient * psi.int_psi,
            base_moment_coefficient: psi.omega_coefficient * psi.int_psi_xi,
            weight_in_bending: true,
        }
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
        match (body.self_weight, body.constant_set) {
            (SelfWeight::Paper, ConstantSet::Exact) => Some(Self::exact()),
            (SelfWeight::Paper, ConstantSet::Paper) => Some(Self::paper()),
            (SelfWeight::Consistent, _) => SelfWeightedShape::new(body.gravity_parameter())
                .map(|psi| Self::self_weighted(&psi)),
        }
    }
}

/// The velocity shape while rocking, V = s' U + r' xi (eq. 13), with s' = ds/dq and r' = 1 - s'
/// constant while rocking (the paper's (-s_n U + B xi)/d), and its integrals per unit height.
struct RockingShape {
    ds: f64,
    dr: f64,
    /// int_0^1 U V dxi.
    int_uv: f64,
    /// int_0^1 V dxi.
    int_v: f64,
    /// int_0^1 V^2 dxi.
    int_v2: f64,
}

impl RockingShape {
    fn new(shape: &ModeShapeIntegrals, flexural_slope: f64) -> Self {
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
}

impl Constants {
    /// Derives the constants and rejects bodies for which the model has no meaning.
    pub fn new(body: &Body) -> Result<Self> {
        let (h, b) = (body.height, body.width);
        let mg = body.mass * body.gravity;
        let gravity_parameter = body.gravity_parameter();

        // A cantilever buckles under its own weight at M g H^2/EI = 7.837: beyond it there is no
        // upright equilibrium to rock about. (This also keeps the paper's s_n below B: s_n
        // reaches B only at M g H^2/EI = 2 L^2/(1 - 2 int U) = 32.4.)
        let shape = ModeShapeIntegrals::for_body(body)
            .filter(|_| gravity_parameter < SELF_WEIGHT_BUCKLING_PARAMETER);
        let Some(shape) = shape else {
            return Err(InvalidParameter::new(
                "derived gravity parameter M g H^2/EI",
                gravity_parameter,
                &format!(
                    "the body buckles under its own weight: M g H^2/EI must be below \
                     {SELF_WEIGHT_BUCKLING_PARAMETER} (raise the flexural rigidity or lower the mass)"
                ),
            ));
        };

        let me = body.mass * shape.int_u;
        let ke = shape.stiffness_coefficient * body.flexural_rigidity / h.powi(3);
        let omega = (ke / me).sqrt();
        if !(omega.is_finite()
            && omega > 0.0
            && crate::limits::at_least(2.0 * std::f64::consts::PI / omega, MIN_PERIOD))
        {
            return Err(InvalidParameter::new(
                "derived pre-uplift period T (s)",
                2.0 * std::f64::consts::PI / omega,
                &format!(
                    "must be at least {MIN_PERIOD:e} s: no body that rocks on a floor is that stiff \
                     for its mass, and the solvers would need steps far below a microsecond"
                ),
            ));
        }

        // Moments about the toe (eq. 8; validation/SELF-WEIGHT.md): the base bending moment
        // c_M EI s/H^2 plus the weight's M g (int U) s equal the weight's M g B/2 at uplift.
        let s_n = b
            / (2.0 * body.flexural_rigidity * shape.base_moment_coefficient / (mg * h * h)
                + 2.0 * shape.int_u);
        let rocking = RockingBranch::new(&shape, ke, s_n, b, mg / h);

        if !(rocking.stiffness < 0.0 && rocking.topple_displacement > s_n) {
            return Err(InvalidParameter::new(
                "derived restoring force while rocking",
                format!(
                    "dF/dq = {} N/m, F = 0 at q = {} m",
                    crate::format::shortest(rocking.stiffness),
                    crate::format::shortest(rocking.topple_displacement)
                ),
                &format!(
                    "the force must fall after uplift at s_n = {} m and vanish beyond it: this body \
                     is too close to buckling under its own weight for the model",
                    crate::format::shortest(s_n)
                ),
            ));
        }

        let v = RockingShape::new(&shape, rocking.flexural_slope);
        let (ds, dr) = (v.ds, v.dr);
        let nu2 = v.int_uv / v.int_v2;
        let beta2 = v.int_v / v.int_v2;

        // Eqs. 19-22: angular momentum about the pivot toe (uplift) and the landing edge. The
        // body turns about the toe at r'/H per unit q', so the centroid's vertical motion adds
        // (B^2/4) r' (the paper: (B^2/4) B/d).
        let int_uy = h * h * shape.int_u_xi;
        let int_vy = h * h * (ds * shape.int_u_xi + dr / 3.0);
        let rotary = b * b / 12.0;
        let vertical = (b * b / 4.0) * dr;
        let zeta_uplift = (int_uy + rotary) / (int_vy + rotary + vertical);
        let zeta_landing = (int_uy + rotary) / (int_vy + rotary - vertical);
        if !(zeta_landing > 0.0 && zeta_landing < 1.0) {
            return Err(InvalidParameter::new(
                "derived landing ratio zetaL",
                zeta_landing,
                &format!(
                    "the body (H = {h} m, B = {b} m) is too squat for the slender-body model: zetaL must lie in (0, 1)"
                ),
            ));
        }

        Ok(Constants {
            constant_set: body.constant_set,
            self_weight: body.self_weight,
            mode_shape: shape,
            generalised_mass: me,
            generalised_stiffness: ke,
            omega,
            period: 2.0 * std::f64::consts::PI / omega,
            damping_coefficient: 2.0 * body.damping_ratio / omega,
            uplift_displacement: s_n,
            beta1: shape.beta1,
            nu2,
            beta2,
            zeta_uplift,
            zeta_landing,
            rocking_stiffness: rocking.stiffness,
            rocking_flexural_slope: rocking.flexural_slope,
            topple_displacement: rocking.topple_displacement,
            flexural_part_at_topple: rocking.flexural_part_at_topple,
            quasi_static_uplift_acceleration: omega * omega * s_n / shape.beta1,
            gravity_parameter,
            gravity_parameter_ratio: gravity_parameter / SELF_WEIGHT_BUCKLING_PARAMETER,
            width: b,
        })
    }

    /// M int_0^1 (shape)^2 dxi, kg: the kinetic energy of the body's horizontal motion is this
    /// times q'^2/2, with the shape U before uplift and V while rocking (the inertial term of the
    /// virtual-work balance, book/src/model.md §4-§5). The mass M is Me / int U.
    pub fn kinetic_mass(&self, rocking: bool) -> f64 {
        let shape = &self.mode_shape;
        let mass = self.generalised_mass / shape.int_u;
        if rocking {
            mass * RockingShape::new(shape, self.rocking_flexural_slope).int_v2
        } else {
            mass * shape.int_u2
        }
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
                            crate::format::significant(reached, 4)
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
    stiffness: f64,
    /// ds/dq.
    flexural_slope: f64,
    /// q where F = 0, m.
    topple_displacement: f64,
    /// s there, m.
    flexural_part_at_topple: f64,
}

impl RockingBranch {
    fn new(
        shape: &ModeShapeIntegrals,
        ke: f64,
        s_n: f64,
        width: f64,
        weight_per_height: f64,
    ) -> Self {
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
                flexural_part_at_topple: 0.0,
            }
        }
    }
}
