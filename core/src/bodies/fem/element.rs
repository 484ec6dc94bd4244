//! Incompatible-mode plane-stress quadrilateral (QM6, Taylor-Beresford-Wilson 1976).
//!
//! The bilinear Q4 displacement field is enriched by the bubble modes `1 - ξ²` and `1 - η²`
//! in each direction (4 internal dofs), which reproduce pure bending of a rectangle exactly
//! and so remove the shear locking of Q4 in the slender body. The internal dofs are condensed
//! statically: `K = Kcc - Kci Kii⁻¹ Kic`. Their derivatives are taken with the Jacobian at
//! the element centre and scaled by `det J0 / det J` (Taylor's correction), so that
//! `∫ B_incompatible dA = 0` under 2 x 2 Gauss integration and distorted patches still pass
//! the constant-strain patch test.

use nalgebra::{Matrix2, Matrix3, SMatrix, Vector3};

use super::error::FemError;

pub(crate) type Matrix8 = SMatrix<f64, 8, 8>;
type Matrix3x8 = SMatrix<f64, 3, 8>;
type Matrix3x4 = SMatrix<f64, 3, 4>;
type Matrix8x4 = SMatrix<f64, 8, 4>;
type Matrix4x8 = SMatrix<f64, 4, 8>;

const GAUSS: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
const GAUSS_POINTS: [(f64, f64); 4] = [
    (-GAUSS, -GAUSS),
    (GAUSS, -GAUSS),
    (GAUSS, GAUSS),
    (-GAUSS, GAUSS),
];
const XI_NODE: [f64; 4] = [-1.0, 1.0, 1.0, -1.0];
const ETA_NODE: [f64; 4] = [-1.0, -1.0, 1.0, 1.0];

/// Plane-stress elasticity matrix (Pa) relating (εxx, εyy, γxy) to (σxx, σyy, σxy).
pub(crate) fn plane_stress_matrix(youngs_modulus: f64, poisson_ratio: f64) -> Matrix3<f64> {
    let f = youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
    Matrix3::new(
        f,
        f * poisson_ratio,
        0.0,
        f * poisson_ratio,
        f,
        0.0,
        0.0,
        0.0,
        f * (1.0 - poisson_ratio) / 2.0,
    )
}

/// Jacobian rows (∂x/∂ξ, ∂y/∂ξ), (∂x/∂η, ∂y/∂η) at (ξ, η).
fn jacobian(coords: &[[f64; 2]; 4], xi: f64, eta: f64) -> (Matrix2<f64>, [f64; 4], [f64; 4]) {
    let mut dn_dxi = [0.0; 4];
    let mut dn_deta = [0.0; 4];
    let mut j = Matrix2::zeros();
    for a in 0..4 {
        dn_dxi[a] = XI_NODE[a] * (1.0 + eta * ETA_NODE[a]) / 4.0;
        dn_deta[a] = ETA_NODE[a] * (1.0 + xi * XI_NODE[a]) / 4.0;
        j[(0, 0)] += dn_dxi[a] * coords[a][0];
        j[(0, 1)] += dn_dxi[a] * coords[a][1];
        j[(1, 0)] += dn_deta[a] * coords[a][0];
        j[(1, 1)] += dn_deta[a] * coords[a][1];
    }
    (j, dn_dxi, dn_deta)
}

/// Data of one Gauss point of a QM6 element.
#[derive(Debug, Clone)]
struct GaussPoint {
    /// ∂N_a/∂x, ∂N_a/∂y of the bilinear shape functions.
    dn_dx: [[f64; 2]; 4],
    /// Strain-displacement matrix of the compatible (nodal) dofs.
    b_nodal: Matrix3x8,
    /// Strain-displacement matrix of the incompatible modes (α1x, α1y, α2x, α2y).
    b_modes: Matrix3x4,
    /// det J × Gauss weight × thickness: the volume the point stands for, m³.
    volume: f64,
}

/// A QM6 element with its internal modes condensed out.
#[derive(Debug, Clone)]
pub(crate) struct Qm6 {
    points: Vec<GaussPoint>,
    elasticity: Matrix3<f64>,
    /// Condensed 8 x 8 stiffness (N/m), dofs (x1, y1, .. x4, y4).
    pub stiffness: Matrix8,
    /// Internal-mode amplitudes from the nodal displacements: α = R u.
    mode_recovery: Matrix4x8,
}

impl Qm6 {
    pub fn new(
        coords: &[[f64; 2]; 4],
        elasticity: Matrix3<f64>,
        thickness: f64,
    ) -> Result<Self, FemError> {
        let (j0, _, _) = jacobian(coords, 0.0, 0.0);
        let det0 = j0.determinant();
        let j0_inv =
            j0.try_inverse()
                .filter(|_| det0 > 0.0)
                .ok_or_else(|| FemError::DegenerateElement {
                    detail: format!("non-positive Jacobian {det0:e} at the centre"),
                })?;
        let mut points = Vec::with_capacity(4);
        for &(xi, eta) in &GAUSS_POINTS {
            let (j, dn_dxi, dn_deta) = jacobian(coords, xi, eta);
            let det = j.determinant();
            let j_inv = j.try_inverse().filter(|_| det > 0.0).ok_or_else(|| {
                FemError::DegenerateElement {
                    detail: format!("non-positive Jacobian {det:e} at a Gauss point"),
                }
            })?;
            let mut dn_dx = [[0.0; 2]; 4];
            let mut b_nodal = Matrix3x8::zeros();
            for a in 0..4 {
                let dx = j_inv[(0, 0)] * dn_dxi[a] + j_inv[(0, 1)] * dn_deta[a];
                let dy = j_inv[(1, 0)] * dn_dxi[a] + j_inv[(1, 1)] * dn_deta[a];
                dn_dx[a] = [dx, dy];
                b_nodal[(0, 2 * a)] = dx;
                b_nodal[(1, 2 * a + 1)] = dy;
                b_nodal[(2, 2 * a)] = dy;
                b_nodal[(2, 2 * a + 1)] = dx;
            }
            // bubble derivatives with the centre Jacobian, scaled so ∫ B_modes dA = 0
            let scale = det0 / det;
            let bubbles = [(-2.0 * xi, 0.0), (0.0, -2.0 * eta)];
            let mut b_modes = Matrix3x4::zeros();
            for (m, &(dxi, deta)) in bubbles.iter().enumerate() {
                let dx = scale * (j0_inv[(0, 0)] * dxi + j0_inv[(0, 1)] * deta);
                let dy = scale * (j0_inv[(1, 0)] * dxi + j0_inv[(1, 1)] * deta);
                b_modes[(0, 2 * m)] = dx;
                b_modes[(1, 2 * m + 1)] = dy;
                b_modes[(2, 2 * m)] = dy;
                b_modes[(2, 2 * m + 1)] = dx;
            }
            points.push(GaussPoint {
                dn_dx,
                b_nodal,
                b_modes,
                volume: det * thickness,
            });
        }
        let mut k_cc = Matrix8::zeros();
        let mut k_ci = Matrix8x4::zeros();
        let mut k_ii = SMatrix::<f64, 4, 4>::zeros();
        for p in &points {
            let db_c = elasticity * p.b_nodal * p.volume;
            let db_i = elasticity * p.b_modes * p.volume;
            k_cc += p.b_nodal.transpose() * db_c;
            k_ci += p.b_nodal.transpose() * db_i;
            k_ii += p.b_modes.transpose() * db_i;
        }
        let k_ii_inv = k_ii
            .try_inverse()
            .ok_or_else(|| FemError::DegenerateElement {
                detail: "singular incompatible-mode stiffness".into(),
            })?;
        let mode_recovery = -(k_ii_inv * k_ci.transpose());
        let stiffness = k_cc + k_ci * mode_recovery;
        // symmetrise the round-off of the condensation
        let stiffness = (stiffness + stiffness.transpose()) * 0.5;
        Ok(Self {
            points,
            elasticity,
            stiffness,
            mode_recovery,
        })
    }

    /// Stresses (σxx, σyy, σxy) in Pa at the four Gauss points, internal modes included.
    pub fn stresses(&self, nodal: &SMatrix<f64, 8, 1>) -> Vec<Vector3<f64>> {
        let modes = self.mode_recovery * nodal;
        self.points
            .iter()
            .map(|p| self.elasticity * (p.b_nodal * nodal + p.b_modes * modes))
            .collect()
    }

    /// Geometric (initial-stress) stiffness ∫ Gᵀ S G dV from Gauss-point stresses, built on the
    /// bilinear shape functions: the second-order work of the prestress on the displacement
    /// gradients, the same for the x and the y displacement components.
    pub fn geometric_stiffness(&self, stresses: &[Vector3<f64>]) -> Matrix8 {
        let mut k = Matrix8::zeros();
        for (p, s) in self.points.iter().zip(stresses) {
            for a in 0..4 {
                for b in 0..4 {
                    let (ga, gb) = (p.dn_dx[a], p.dn_dx[b]);
                    let g = ga[0] * (s[0] * gb[0] + s[2] * gb[1])
                        + ga[1] * (s[2] * gb[0] + s[1] * gb[1]);
                    let v = g * p.volume;
                    k[(2 * a, 2 * b)] += v;
                    k[(2 * a + 1, 2 * b + 1)] += v;
                }
            }
        }
        k
    }

    /// Row-sum lumped masses ∫ N_a ρ t dA of the four nodes, kg.
    pub fn lumped_masses(coords: &[[f64; 2]; 4], density: f64, thickness: f64) -> [f64; 4] {
        let mut m = [0.0; 4];
        for &(xi, eta) in &GAUSS_POINTS {
            let (j, _, _) = jacobian(coords, xi, eta);
            let dv = j.determinant() * density * thickness;
            for (a, ma) in m.iter_mut().enumerate() {
                *ma += (1.0 + xi * XI_NODE[a]) * (1.0 + eta * ETA_NODE[a]) / 4.0 * dv;
            }
        }
        m
    }
}
