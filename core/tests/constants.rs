//! Derived constants against the tables of book/src/model.md §2 (constants) and the closed forms of
//! §7 (limits).

use crate::common;

use approx::assert_relative_eq;
use flexrock_core::physics::constants::{Constants, ModeShapeIntegrals, MODE_ROOT};

#[test]
fn mode_shape_integrals_match_the_table() {
    let exact = ModeShapeIntegrals::exact();
    // book/src/model.md §2: int U = sig/L = 0.391495878, int U^2 = 1/4, beta1 = 1.565983512,
    // Ke = 4.8398 EI/H^3, sig = 0.7340955137589.
    let sigma = exact.int_u * MODE_ROOT;
    assert_relative_eq!(sigma, 0.734_095_513_758_9, max_relative = 1e-12);
    assert_relative_eq!(exact.int_u, 0.391_495_878, max_relative = 1e-9);
    assert_relative_eq!(exact.int_u2, 0.25);
    assert_relative_eq!(exact.beta1, 1.565_983_512, max_relative = 1e-9);
    assert_relative_eq!(exact.stiffness_coefficient, 4.8398, max_relative = 1e-4);
    // lambda is the first root of cos L cosh L = -1.
    assert!((MODE_ROOT.cos() * MODE_ROOT.cosh() + 1.0).abs() < 1e-14);

    let paper = ModeShapeIntegrals::paper();
    assert_eq!(paper.int_u, 0.3915);
    assert_eq!(paper.int_u2, 0.2503);
    assert_eq!(paper.beta1, 1.564);
    assert_eq!(paper.base_moment_coefficient, 1.8751 * 1.8751);
    assert_eq!(paper.int_u_xi, 1.0 / (1.8751 * 1.8751));
}

#[test]
fn reference_body_constants() {
    let m = common::model(&common::reference_body(
        "[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n",
    ));
    let c = &m.constants;
    let mass = 600.0 * 4.0 * 0.7;
    let ei = 5.0e6 * 0.7_f64.powi(3) / 12.0;
    assert_relative_eq!(m.body.mass, mass, max_relative = 1e-15);
    assert_relative_eq!(m.body.flexural_rigidity, ei, max_relative = 1e-15);
    assert_relative_eq!(
        c.generalised_mass,
        0.391_495_878 * mass,
        max_relative = 1e-9
    );
    assert_relative_eq!(
        c.generalised_stiffness,
        4.8398 * ei / 64.0,
        max_relative = 1e-4
    );
    // book/src/model.md §8 (the paper's example): T = 1.5500 s, s_n = 0.15237 m; §7a (self-weight):
    // gamma_g = 1.845, 0.235 of 7.837.
    assert!((c.period - 1.5500).abs() < 5e-5, "T = {}", c.period);
    assert!((c.uplift_displacement - 0.15237).abs() < 5e-6);
    assert!((c.gravity_parameter - 1.845).abs() < 5e-4);
    assert!((c.gravity_parameter_ratio - 0.235).abs() < 5e-4);
    // Quasi-static uplift: omega^2 s_n / beta1.
    assert_relative_eq!(
        c.quasi_static_uplift_acceleration,
        c.omega * c.omega * c.uplift_displacement / c.beta1,
        max_relative = 1e-14
    );
    // nu2 and beta2 in the ranges the paper quotes for s_n/B = 0.218.
    assert!(c.nu2 > 0.6 && c.nu2 < 0.86, "nu2 = {}", c.nu2);
    assert!(c.beta2 > 1.1 && c.beta2 < 1.5, "beta2 = {}", c.beta2);
    assert!(c.zeta_uplift < 1.0 && c.zeta_landing < 1.0);
    // Damping: gamma/E = 2 h / omega.
    assert_relative_eq!(c.damping_coefficient, 0.1 / c.omega, max_relative = 1e-14);
}

#[test]
fn paper_constant_set_uses_the_printed_values() {
    let m = common::model(
        &common::reference_body("[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n")
            .replace("gravity = 9.81", "gravity = 9.81\nconstants = \"paper\""),
    );
    let c = &m.constants;
    let mass = 1680.0;
    let ei = 5.0e6 * 0.343 / 12.0;
    assert_relative_eq!(c.generalised_mass, 0.3915 * mass, max_relative = 1e-15);
    assert_relative_eq!(
        c.generalised_stiffness,
        4.840 * ei / 64.0,
        max_relative = 1e-15
    );
    assert_eq!(c.beta1, 1.564);
    // s_n = B / (2 EI lambda^2 / (M g H^2) + 2 * 0.3915) with lambda = 1.8751.
    let s_n = 0.7 / (2.0 * ei * 1.8751_f64.powi(2) / (mass * 9.81 * 16.0) + 2.0 * 0.3915);
    assert_relative_eq!(c.uplift_displacement, s_n, max_relative = 1e-14);
    // The rounding moves the constants by parts in 1e4, not more.
    let exact = Constants::new(
        &common::model(&common::reference_body(
            "[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n",
        ))
        .body,
    )
    .unwrap();
    assert_relative_eq!(c.period, exact.period, max_relative = 1e-3);
    assert_relative_eq!(c.nu2, exact.nu2, max_relative = 2e-3);
}

#[test]
fn rocking_factors_tend_to_the_rigid_values() {
    // book/src/model.md §7 (rigid limit, eq. A4): s_n -> 0 gives nu2 = 3/L^2, beta2 = 3/2;
    // eq. A7 there: zetaU/zetaL -> Housner's (2H^2 - B^2)/(2(H^2 + B^2)).
    let m = common::model(
        &common::reference_body("[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n")
            .replace("5.0e6", "5.0e11"),
    );
    let c = &m.constants;
    assert!(c.uplift_displacement < 2e-6);
    assert_relative_eq!(c.nu2, 3.0 / MODE_ROOT.powi(2), max_relative = 2e-5);
    assert_relative_eq!(c.beta2, 1.5, max_relative = 2e-5);
    let (h, b) = (4.0_f64, 0.7_f64);
    let housner = (2.0 * h * h - b * b) / (2.0 * (h * h + b * b));
    assert_relative_eq!(housner, 0.955_428, max_relative = 1e-6);
    assert_relative_eq!(c.zeta_uplift / c.zeta_landing, housner, max_relative = 1e-5);
}

#[test]
fn quasi_static_uplift_tends_to_the_rigid_limit_factor() {
    // omega^2 s_n / beta1 -> lambda^3/(8 sigma) g B/H as E -> infinity (derivation at
    // ModeShapeIntegrals::rigid_limit_uplift_factor). Algebraically: lambda^3/(8 sigma), sigma from
    // its own definition, not from the crate.
    let l = MODE_ROOT;
    let sigma = (l.cosh() + l.cos()) / (l.sinh() + l.sin());
    let factor = ModeShapeIntegrals::exact().rigid_limit_uplift_factor();
    assert_relative_eq!(factor, l.powi(3) / (8.0 * sigma), max_relative = 1e-14);
    assert_relative_eq!(factor, 1.122_622_058_7, max_relative = 1e-10);
    assert_relative_eq!(
        ModeShapeIntegrals::paper().rigid_limit_uplift_factor(),
        1.124_082,
        max_relative = 1e-6
    );
    // Numerically, from the constants the model derives: a_up/limit = x/(x + 2 sigma/lambda) with
    // x = 2 lambda^2/gamma_g (gamma_g = M g H^2/EI), so the relative distance is
    // -(sigma/lambda^3) gamma_g to first order: -0.205 at E = 5e6 (gamma_g = 1.845), falling with
    // 1/E to -2.05e-9 at E x 1e8 (the stiffest body the period floor of 1e-4 s allows).
    let (g, h, b) = (9.81, 4.0, 0.7);
    for (scale, tolerance) in [(1e2, 3e-3), (1e4, 3e-5), (1e8, 3e-9)] {
        let m = common::model(
            &common::reference_body(
                "[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n",
            )
            .replace("5.0e6", &format!("{:e}", 5.0e6 * scale)),
        );
        let c = &m.constants;
        let relative = c.quasi_static_uplift_acceleration / (g * b / h) / factor - 1.0;
        let predicted = sigma / l.powi(3) * c.gravity_parameter;
        assert!(
            (relative + predicted).abs() < 2.0 * predicted * predicted + 1e-13,
            "E x {scale}: relative distance {relative:e}, first-order prediction -{predicted:e}"
        );
        assert!(relative.abs() < tolerance, "E x {scale}: {relative:e}");
    }
}

#[test]
fn period_input_gives_that_period() {
    let m = common::model(
        &common::reference_body("[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n")
            .replace("youngs_modulus = 5.0e6", "period = 1.2"),
    );
    assert_relative_eq!(m.constants.period, 1.2, max_relative = 1e-13);
}

#[test]
fn paper_ramp_coefficients() {
    // book/src/model.md §8: for A = 5, Tp = 1, ramp = 0.412:
    // c1 = -133.694, c2 = 1043.29, c3 = -1707.09.
    let ramp = flexrock_core::floor::PaperSine::new(5.0, 1.0, 0.412);
    let [c1, c2, c3] = ramp.ramp_coefficients;
    assert!((c1 + 133.694).abs() < 5e-4, "c1 = {c1}");
    assert!((c2 - 1043.29).abs() < 5e-3, "c2 = {c2}");
    assert!((c3 + 1707.09).abs() < 5e-3, "c3 = {c3}");
    // Continuity at the join: acceleration from both sides.
    use flexrock_core::floor::FloorMotion;
    let before = ramp.acceleration(0.412 - 1e-12);
    let after = 5.0 * (2.0 * std::f64::consts::PI * 0.412).sin();
    assert!((before - after).abs() < 1e-8);
    // The floor starts at rest: 0, not the -0 that c1 < 0 times 0 is (tables print "-0").
    let start = ramp.acceleration(0.0);
    assert!(start == 0.0 && start.is_sign_positive(), "a(0) = {start}");
}
