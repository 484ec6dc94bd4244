//! The flexural shape of the self-weight-consistent variant (validation/SELF-WEIGHT.md): psi(xi),
//! psi(1) = 1, the first mode of a uniform cantilever carrying its own weight, found by a Ritz
//! solve over the first [`RITZ_MODES`] cantilever modes.
//!
//! With gamma_g = M g H^2/EI its weak form is
//!
//! ```text
//! int psi''^2 dxi - gamma_g int (1 - xi) psi'^2 dxi = Omega int psi^2 dxi,
//! omega^2 = Omega EI/(m H^4),   psi(0) = psi'(0) = 0,
//! ```
//!
//! whose first term is the bending energy and second the work of the axial force
//! N(y) = M g (H - y)/H. As gamma_g -> 0 the solve returns the paper's U(xi) and Omega -> L^4.

use nalgebra::{DMatrix, DVector};

/// Number of cantilever modes in the Ritz basis. The solve converges algebraically: at the
/// paper's gamma_g = 1.845, 8 modes give Omega to 3e-7 relative and 12 to 3e-8 (tested against
/// 16), far below every other approximation of the model.
pub const RITZ_MODES: usize = 12;

/// Gauss-Legendre points on [0, 1]. The integrands are products of two mode derivatives
/// (growth e^{L xi} with L <= 24.4): 96 points integrate them to rounding (the orthogonality
/// of the cantilever modes is checked to 1e-13).
const QUADRATURE_POINTS: usize = 96;

/// The numbers of psi the model needs, per unit height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfWeightedShape {
    /// gamma_g = M g H^2/EI it was solved for.
    pub gravity_parameter: f64,
    /// Omega: omega^2 = Omega EI/(m H^4) (L^4 = 12.362 without weight).
    pub omega_coefficient: f64,
    /// int_0^1 psi dxi.
    pub int_psi: f64,
    /// int_0^1 psi^2 dxi.
    pub int_psi2: f64,
    /// int_0^1 psi xi dxi.
    pub int_psi_xi: f64,
    /// Ritz coefficients of psi on the cantilever modes phi_1..phi_n (phi_k(1) = +-1).
    pub coefficients: [f64; RITZ_MODES],
}

/// k-th root (k = 1, 2, ...) of cos L cosh L = -1, by Newton's method on cos L + 1/cosh L.
pub fn cantilever_root(k: usize) -> f64 {
    let mut l = (2.0 * k as f64 - 1.0) * std::f64::consts::FRAC_PI_2;
    for _ in 0..50 {
        let f = l.cos() + 1.0 / l.cosh();
        let df = -l.sin() - l.tanh() / l.cosh();
        let step = f / df;
        l -= step;
        if step.abs() < 1e-15 * l {
            break;
        }
    }
    l
}

/// A cantilever mode phi(xi) = [cosh z - cos z - sigma (sinh z - sin z)]/2, z = L xi, evaluated
/// without the cancellation of cosh z against sigma sinh z that ruins the higher modes.
#[derive(Debug, Clone, Copy)]
struct CantileverMode {
    root: f64,
    sigma: f64,
    /// 1 - sigma, computed without cancellation (it is about 2 e^{-L}).
    one_minus_sigma: f64,
}

impl CantileverMode {
    fn new(k: usize) -> Self {
        let l = cantilever_root(k);
        let denominator = l.sinh() + l.sin();
        let one_minus_sigma = (-(-l).exp() + l.sin() - l.cos()) / denominator;
        CantileverMode {
            root: l,
            sigma: 1.0 - one_minus_sigma,
            one_minus_sigma,
        }
    }

    /// (phi, phi', phi'') at xi, derivatives with respect to xi.
    fn values(&self, xi: f64) -> [f64; 3] {
        let (l, s) = (self.root, self.sigma);
        let z = l * xi;
        let (grow, decay) = ((z - l).exp(), (-z).exp());
        // cosh z - sigma sinh z and sinh z - sigma cosh z, with (1 - sigma) e^z written as
        // [(1 - sigma) e^L] e^{z - L} so that nothing overflows or cancels.
        let scaled = self.one_minus_sigma * l.exp();
        let even = 0.5 * (scaled * grow + (1.0 + s) * decay);
        let odd = 0.5 * (scaled * grow - (1.0 + s) * decay);
        let (c, sn) = (z.cos(), z.sin());
        [
            0.5 * (even - c + s * sn),
            0.5 * l * (odd + sn + s * c),
            0.5 * l * l * (even + c - s * sn),
        ]
    }
}

/// Gauss-Legendre nodes and weights on [0, 1].
pub(crate) fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut rule = Vec::with_capacity(n);
    for i in 1..=n {
        let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let step = p1 / derivative;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        rule.push((0.5 * (1.0 + x), 0.5 * weight));
    }
    rule
}

/// The Ritz matrices over the first `n` cantilever modes: mass int phi_i phi_j, bending
/// int phi_i'' phi_j'', geometric int (1 - xi) phi_i' phi_j', and the load vectors int phi_i and
/// int phi_i xi.
struct RitzMatrices {
    mass: DMatrix<f64>,
    bending: DMatrix<f64>,
    geometric: DMatrix<f64>,
    int_phi: DVector<f64>,
    int_phi_xi: DVector<f64>,
    /// L^-1 of the mass matrix's Cholesky factor M = L L^T.
    mass_factor_inverse: DMatrix<f64>,
}

fn ritz_matrices(n: usize) -> RitzMatrices {
    let modes: Vec<CantileverMode> = (1..=n).map(CantileverMode::new).collect();
    let mut m = RitzMatrices {
        mass: DMatrix::zeros(n, n),
        bending: DMatrix::zeros(n, n),
        geometric: DMatrix::zeros(n, n),
        int_phi: DVector::zeros(n),
        int_phi_xi: DVector::zeros(n),
        mass_factor_inverse: DMatrix::zeros(n, n),
    };
    for (xi, w) in gauss_legendre(QUADRATURE_POINTS) {
        let v: Vec<[f64; 3]> = modes.iter().map(|mode| mode.values(xi)).collect();
        for i in 0..n {
            m.int_phi[i] += w * v[i][0];
            m.int_phi_xi[i] += w * v[i][0] * xi;
            for j in 0..n {
                m.mass[(i, j)] += w * v[i][0] * v[j][0];
                m.bending[(i, j)] += w * v[i][2] * v[j][2];
                m.geometric[(i, j)] += w * (1.0 - xi) * v[i][1] * v[j][1];
            }
        }
    }
    // The mass matrix is the identity over 4 up to quadrature error: positive definite.
    if let Some(l_inv) = m.mass.clone().cholesky().and_then(|c| c.l().try_inverse()) {
        m.mass_factor_inverse = l_inv;
    }
    m
}

/// Solves for psi at `gravity_parameter` = M g H^2/EI with `n` modes. Returns `None` when the
/// lowest eigenvalue is not positive (at or beyond self-weight buckling, gamma_g = 7.837).
fn solve(gravity_parameter: f64, m: &RitzMatrices) -> Option<(f64, DVector<f64>)> {
    let stiffness = &m.bending - gravity_parameter * &m.geometric;
    // K c = Omega M c with M = L L^T: the symmetric problem L^-1 K L^-T y = Omega y, c = L^-T y.
    let l_inv = &m.mass_factor_inverse;
    let reduced = l_inv * stiffness * l_inv.transpose();
    let reduced = 0.5 * (&reduced + reduced.transpose());
    let eigen = reduced.symmetric_eigen();
    let (lowest, omega) = eigen
        .eigenvalues
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, &v)| (i, v))?;
    if omega.is_nan() || omega <= 0.0 {
        return None;
    }
    let coefficients = l_inv.transpose() * eigen.eigenvectors.column(lowest);
    // psi(1) = sum c_k phi_k(1); phi_k(1) = (-1)^(k+1).
    let tip: f64 = coefficients
        .iter()
        .enumerate()
        .map(|(k, c)| if k % 2 == 0 { *c } else { -*c })
        .sum();
    Some((omega, coefficients / tip))
}

/// The Ritz matrices of [`RITZ_MODES`] modes, computed once: they do not depend on the body, and
/// a sweep derives the constants at every point.
fn basis() -> &'static RitzMatrices {
    static BASIS: std::sync::OnceLock<RitzMatrices> = std::sync::OnceLock::new();
    BASIS.get_or_init(|| ritz_matrices(RITZ_MODES))
}

impl SelfWeightedShape {
    /// psi for `gravity_parameter` = M g H^2/EI in [0, 7.837); `None` beyond buckling.
    pub fn new(gravity_parameter: f64) -> Option<Self> {
        let m = basis();
        let (omega, c) = solve(gravity_parameter, m)?;
        let mut coefficients = [0.0; RITZ_MODES];
        coefficients.copy_from_slice(c.as_slice());
        Some(SelfWeightedShape {
            gravity_parameter,
            omega_coefficient: omega,
            int_psi: c.dot(&m.int_phi),
            int_psi2: (c.transpose() * &m.mass * &c)[(0, 0)],
            int_psi_xi: c.dot(&m.int_phi_xi),
            coefficients,
        })
    }

    /// psi(xi).
    pub fn value(&self, xi: f64) -> f64 {
        self.coefficients
            .iter()
            .enumerate()
            .map(|(k, c)| c * CantileverMode::new(k + 1).values(xi)[0])
            .sum()
    }

    /// dpsi/dxi.
    pub fn slope(&self, xi: f64) -> f64 {
        self.coefficients
            .iter()
            .enumerate()
            .map(|(k, c)| c * CantileverMode::new(k + 1).values(xi)[1])
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::constants::{mode_sigma, MODE_ROOT};

    #[test]
    fn cantilever_modes_are_orthogonal_and_their_roots_exact() {
        // Known roots of cos L cosh L = -1.
        for (k, root) in [(1, 1.875_104_068_711_961), (2, 4.694_091_132_974_175)] {
            assert!((cantilever_root(k) - root).abs() < 1e-12, "root {k}");
        }
        for k in 1..=12 {
            let l = cantilever_root(k);
            assert!((l.cos() + 1.0 / l.cosh()).abs() < 1e-14, "root {k}");
        }
        // int phi_i phi_j = delta_ij/4 and int phi_i'' phi_j'' = L_i^4 delta_ij/4 (the modes of
        // the uniform cantilever are orthogonal, and phi(1) = +-1 with this scaling).
        let m = ritz_matrices(12);
        for i in 0..12 {
            let l4 = cantilever_root(i + 1).powi(4);
            for j in 0..12 {
                let (mass, bending) = if i == j {
                    (0.25, 0.25 * l4)
                } else {
                    (0.0, 0.0)
                };
                assert!((m.mass[(i, j)] - mass).abs() < 1e-12, "mass {i} {j}");
                assert!(
                    (m.bending[(i, j)] - bending).abs() < 1e-9 * l4.max(1.0),
                    "bending {i} {j}"
                );
            }
        }
    }

    #[test]
    fn without_weight_psi_is_the_paper_u() {
        let psi = SelfWeightedShape::new(0.0).unwrap();
        let l = MODE_ROOT;
        assert!((psi.omega_coefficient - l.powi(4)).abs() < 1e-11);
        assert!((psi.int_psi - mode_sigma() / l).abs() < 1e-13);
        assert!((psi.int_psi2 - 0.25).abs() < 1e-13);
        assert!((psi.int_psi_xi - 1.0 / (l * l)).abs() < 1e-13);
        assert!((psi.value(0.5) - crate::physics::constants::cantilever_mode(0.5)).abs() < 1e-13);
    }

    #[test]
    fn the_paper_body_matches_an_independent_ritz_solve_and_converges_in_the_basis() {
        // book/src/model.md §7b (an independent Ritz solve, book/constants.py): gamma_g = 1.845
        // gives Omega/L^4 = 0.7653, int psi = 0.39056, int psi^2 = 0.24938, int psi xi = 0.28397.
        let psi = SelfWeightedShape::new(1.845).unwrap();
        assert!((psi.omega_coefficient / MODE_ROOT.powi(4) - 0.7653).abs() < 1e-4);
        assert!((psi.int_psi - 0.39056).abs() < 1e-5);
        assert!((psi.int_psi2 - 0.24938).abs() < 1e-5);
        assert!((psi.int_psi_xi - 0.28397).abs() < 1e-5);
        let (omega16, _) = solve(1.845, &ritz_matrices(16)).unwrap();
        assert!((psi.omega_coefficient - omega16).abs() < 1e-7 * omega16);
    }

    #[test]
    fn buckling_under_self_weight_is_found_at_7_837() {
        // The uniform cantilever buckles under its own weight at gamma_g = 7.837 (Timoshenko):
        // Omega passes through zero there.
        assert!(SelfWeightedShape::new(7.83).is_some());
        assert!(SelfWeightedShape::new(7.84).is_none());
    }
}
