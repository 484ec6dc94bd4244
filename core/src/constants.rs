//! Derived constants of the SDOF model (MODEL.md sections 2-5 and 7a).

use serde::{Deserialize, Serialize};

use crate::body::{Body, ConstantSet};
use crate::error::{Error, Result};

/// First root of cos L cosh L = -1 (first cantilever mode).
pub const MODE_ROOT: f64 = 1.875_104_068_711_961;

/// sigma = (cosh L + cos L)/(sinh L + sin L) of the first cantilever mode (MODEL.md section 2).
pub fn mode_sigma() -> f64 {
    let l = MODE_ROOT;
    (l.cosh() + l.cos()) / (l.sinh() + l.sin())
}

/// The first cantilever mode U(xi), scaled to U(1) = 1 (MODEL.md section 2).
pub fn cantilever_mode(xi: f64) -> f64 {
    let (l, sigma) = (MODE_ROOT, mode_sigma());
    let z = l * xi;
    (z.cosh() - z.cos() - sigma * (z.sinh() - z.sin())) / 2.0
}

/// Value of M g H^2 / EI at which a uniform cantilever buckles under its own weight.
pub const SELF_WEIGHT_BUCKLING_PARAMETER: f64 = 7.837;

/// Share of [`SELF_WEIGHT_BUCKLING_PARAMETER`] above which a run warns that the self-weight the
/// model leaves out of bending matters: at the paper's own 0.235 a beam-column with it lifts off
/// 24 % later than s_n (MODEL.md 7a); at 0.1 the errors are of order 10 %.
pub const SELF_WEIGHT_WARNING_SHARE: f64 = 0.1;

/// Shortest pre-uplift period a model may have, s.
pub const MIN_PERIOD: f64 = 1e-4;

/// The mode-shape numbers the model is built from: either exact, or as printed in the paper.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct ModeShapeIntegrals {
    /// lambda: U''(0) = lambda^2 / H^2; int U xi = 1 / lambda^2.
    pub lambda: f64,
    /// int_0^1 U dxi.
    pub int_u: f64,
    /// int_0^1 U^2 dxi.
    pub int_u2: f64,
    /// beta1 = int U / int U^2.
    pub beta1: f64,
    /// Ke = stiffness_coefficient * EI / H^3.
    pub stiffness_coefficient: f64,
}

impl ModeShapeIntegrals {
    pub fn exact() -> Self {
        let l = MODE_ROOT;
        let sigma = mode_sigma();
        let int_u = sigma / l;
        let int_u2 = 0.25;
        ModeShapeIntegrals {
            lambda: l,
            int_u,
            int_u2,
            beta1: int_u / int_u2,
            stiffness_coefficient: l.powi(3) * sigma,
        }
    }

    /// The rounded values printed in the paper: lambda = 1.8751, int U = 0.3915 (Me = 0.3915 M),
    /// int U^2 = 0.2503, beta1 = 1.564, Ke = 4.840 EI/H^3.
    pub fn paper() -> Self {
        ModeShapeIntegrals {
            lambda: 1.8751,
            int_u: 0.3915,
            int_u2: 0.2503,
            beta1: 1.564,
            stiffness_coefficient: 4.840,
        }
    }

    /// The rigid-limit uplift factor: the quasi-static uplift acceleration omega^2 s_n / beta1 of
    /// the elastic model as EI -> infinity, in units of Housner's g B / H (the acceleration at which
    /// a rigid block tips). With omega^2 = Ke/Me = c_K EI/(int U M H^3) and, as EI -> infinity,
    /// s_n -> B M g H^2/(2 EI lambda^2) (eq. 8), omega^2 s_n / beta1 -> [c_K/(2 int U lambda^2
    /// beta1)] g B/H. With the exact constants (c_K = lambda^3 sigma, int U = sigma/lambda,
    /// beta1 = 4 sigma/lambda) the bracket is lambda^3/(8 sigma) = 1.122622; with the paper's
    /// rounded ones 1.124082.
    ///
    /// It exceeds 1 because the one-mode model takes the base bending moment from the curvature of
    /// the first mode, EI (lambda/H)^2 s. Under the quasi-static uniform inertia load M a that a
    /// stiff body carries before uplift, the first mode alone gives a base moment of
    /// 4 sigma M a H / lambda^3 = (8 sigma/lambda^3) M a H/2 = 0.891 of the exact M a H/2, so the
    /// floor must push 1.1226 times harder before the moment reaches the weight's M g B/2. A rigid
    /// block (and the exact statics of a stiff continuum) tips at g B/H. Once rocking, the
    /// elastic model's rigid limit is Housner's equation (MODEL.md section 7): only the uplift
    /// from rest differs.
    pub fn rigid_limit_uplift_factor(&self) -> f64 {
        self.stiffness_coefficient / (2.0 * self.int_u * self.lambda * self.lambda * self.beta1)
    }

    pub fn for_set(set: ConstantSet) -> Self {
        match set {
            ConstantSet::Exact => Self::exact(),
            ConstantSet::Paper => Self::paper(),
        }
    }
}

/// Every constant the automaton and the reports need, derived once from a [`Body`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Constants {
    pub constant_set: ConstantSet,
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
    /// nu1 = 1, effectiveness factor before uplift.
    pub nu1: f64,
    /// beta1, participation factor before uplift.
    pub beta1: f64,
    /// nu2, effectiveness factor while rocking.
    pub nu2: f64,
    /// beta2, participation factor while rocking.
    pub beta2: f64,
    /// zetaU: velocity ratio at uplift (q' -> zetaU q').
    pub zeta_uplift: f64,
    /// zetaL: velocity ratio at landing (q' -> q' / zetaL).
    pub zeta_landing: f64,
    /// Floor acceleration that starts uplift quasi-statically: omega^2 s_n / beta1, m/s^2.
    pub quasi_static_uplift_acceleration: f64,
    /// M g H^2 / EI: the size of the self-weight effect the model leaves out of bending.
    pub gravity_parameter: f64,
    /// gravity_parameter / 7.837 (1 = buckling under self-weight).
    pub gravity_parameter_ratio: f64,
    /// Width B, m; the overturning limit of q.
    pub width: f64,
}

impl Constants {
    /// Derives the constants and rejects bodies for which the model has no meaning.
    pub fn new(body: &Body) -> Result<Self> {
        let shape = ModeShapeIntegrals::for_set(body.constant_set);
        let l2 = shape.lambda * shape.lambda;
        let (h, b) = (body.height, body.width);
        let mg = body.mass * body.gravity;

        let me = body.mass * shape.int_u;
        let ke = shape.stiffness_coefficient * body.flexural_rigidity / h.powi(3);
        let omega = (ke / me).sqrt();
        let gravity_parameter = mg * h * h / body.flexural_rigidity;

        // A cantilever buckles under its own weight at M g H^2/EI = 7.837: beyond it there is no
        // upright equilibrium to rock about. (This also keeps s_n below B: s_n reaches B only at
        // M g H^2/EI = 2 lambda^2/(1 - 2 int U) = 32.4.)
        if gravity_parameter.is_nan() || gravity_parameter >= SELF_WEIGHT_BUCKLING_PARAMETER {
            return Err(Error::invalid(
                "derived gravity parameter M g H^2/EI",
                gravity_parameter,
                &format!(
                    "the body buckles under its own weight: M g H^2/EI must be below \
                     {SELF_WEIGHT_BUCKLING_PARAMETER} (raise the flexural rigidity or lower the mass)"
                ),
            ));
        }
        if !(omega.is_finite() && omega > 0.0 && 2.0 * std::f64::consts::PI / omega >= MIN_PERIOD) {
            return Err(Error::invalid(
                "derived pre-uplift period T (s)",
                2.0 * std::f64::consts::PI / omega,
                &format!(
                    "must be at least {MIN_PERIOD:e} s: no body that rocks on a floor is that stiff \
                     for its mass, and the solvers would need steps far below a microsecond"
                ),
            ));
        }

        // Eq. 8: base bending moment EI (lambda/H)^2 s equals the gravity moment about the toe.
        let s_n = b / (2.0 * body.flexural_rigidity * l2 / (mg * h * h) + 2.0 * shape.int_u);
        let d = b - s_n;

        // Eq. 13 (per unit H): integrals of the rocking velocity shape V = (-s_n U + B xi)/d.
        let int_uv = (-s_n * shape.int_u2 + b / l2) / d;
        let int_v = (-s_n * shape.int_u + b / 2.0) / d;
        let int_v2 = (s_n * s_n * shape.int_u2 - 2.0 * b * s_n / l2 + b * b / 3.0) / (d * d);
        let nu2 = int_uv / int_v2;
        let beta2 = int_v / int_v2;

        // Eqs. 19-22: angular momentum about the pivot toe (uplift) and the landing edge.
        let int_uy = h * h / l2;
        let int_vy = h * h * (b / 3.0 - s_n / l2) / d;
        let rotary = b * b / 12.0;
        let vertical = (b * b / 4.0) * b / d;
        let zeta_uplift = (int_uy + rotary) / (int_vy + rotary + vertical);
        let zeta_landing = (int_uy + rotary) / (int_vy + rotary - vertical);
        if !(zeta_landing > 0.0 && zeta_landing < 1.0) {
            return Err(Error::invalid(
                "derived landing ratio zetaL",
                zeta_landing,
                &format!(
                    "the body (H = {h} m, B = {b} m) is too squat for the slender-body model: zetaL must lie in (0, 1)"
                ),
            ));
        }

        Ok(Constants {
            constant_set: body.constant_set,
            mode_shape: shape,
            generalised_mass: me,
            generalised_stiffness: ke,
            omega,
            period: 2.0 * std::f64::consts::PI / omega,
            damping_coefficient: 2.0 * body.damping_ratio / omega,
            uplift_displacement: s_n,
            nu1: 1.0,
            beta1: shape.beta1,
            nu2,
            beta2,
            zeta_uplift,
            zeta_landing,
            quasi_static_uplift_acceleration: omega * omega * s_n / shape.beta1,
            gravity_parameter,
            gravity_parameter_ratio: gravity_parameter / SELF_WEIGHT_BUCKLING_PARAMETER,
            width: b,
        })
    }

    /// Flexural rigidity that gives the pre-uplift period `period` for a body of the given mass and
    /// height under the constant set `set` (inverse of omega = sqrt(Ke/Me)).
    pub fn flexural_rigidity_for_period(
        period: f64,
        mass: f64,
        height: f64,
        set: ConstantSet,
    ) -> f64 {
        let shape = ModeShapeIntegrals::for_set(set);
        let omega = 2.0 * std::f64::consts::PI / period;
        omega * omega * mass * shape.int_u * height.powi(3) / shape.stiffness_coefficient
    }
}
