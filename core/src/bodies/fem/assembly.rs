//! Assembly of the global matrices and the static gravity state.

use nalgebra::SMatrix;

use super::banded::{BandedLdl, BandedSym};
use super::body::{BaseSupport, FemBody};
use super::element::{plane_stress_matrix, Qm6};
use super::error::FemError;
use super::mesh::Mesh;

/// The discretised body: lumped masses, elastic and geometric stiffness, gravity state.
#[derive(Debug, Clone)]
pub(crate) struct Assembly {
    pub mesh: Mesh,
    /// Lumped mass of every dof (the node's mass on both its dofs), kg.
    pub mass: Vec<f64>,
    /// Elastic stiffness K, N/m.
    pub stiffness: BandedSym,
    /// Geometric stiffness K_σ of the static gravity prestress, N/m.
    pub geometric: BandedSym,
    /// Nodal weights (-m g on the y dofs), N.
    pub gravity_load: Vec<f64>,
    /// Static gravity displacement u_g with every base node pinned, m.
    pub static_displacement: Vec<f64>,
    /// Reactions (Rx, Ry) of the base nodes in the static gravity state, N.
    pub static_reactions: Vec<[f64; 2]>,
    pub total_mass: f64,
}

impl Assembly {
    pub fn build(body: &FemBody, nx: usize, ny: usize) -> Result<Self, FemError> {
        let mesh = Mesh::rectangle(body.width, body.height, nx, ny);
        let n = mesh.dof_count();
        let hb = mesh.half_bandwidth();
        let elasticity = plane_stress_matrix(body.youngs_modulus, body.poisson_ratio);
        let mut stiffness = BandedSym::zeros(n, hb);
        let mut mass = vec![0.0; n];
        let mut elements = Vec::with_capacity(mesh.elements.len());
        for e in 0..mesh.elements.len() {
            let coords = mesh.element_coords(e);
            let element = Qm6::new(&coords, elasticity, body.depth)?;
            let dofs = mesh.element_dofs(e);
            scatter(&mut stiffness, &dofs, &element.stiffness);
            let masses = Qm6::lumped_masses(&coords, body.density, body.depth);
            for (a, m) in masses.iter().enumerate() {
                mass[dofs[2 * a]] += m;
                mass[dofs[2 * a + 1]] += m;
            }
            elements.push(element);
        }
        if body.base == BaseSupport::RigidPlate {
            tie_base_to_plate(&mut stiffness, nx, body);
        }
        let gravity_load: Vec<f64> = (0..n)
            .map(|d| {
                if d % 2 == 1 {
                    -mass[d] * body.gravity
                } else {
                    0.0
                }
            })
            .collect();

        // static gravity step: every base node pinned (x and y)
        let base_dofs = 2 * (nx + 1);
        let constrained: Vec<bool> = (0..n).map(|d| d < base_dofs).collect();
        let factors = BandedLdl::factor(&stiffness.with_identity_rows(&constrained))?;
        let mut static_displacement = gravity_load.clone();
        static_displacement[..base_dofs]
            .iter_mut()
            .for_each(|v| *v = 0.0);
        factors.solve_in_place(&mut static_displacement);
        let mut internal = vec![0.0; n];
        stiffness.mul_vec(&static_displacement, &mut internal);
        let static_reactions = (0..=nx)
            .map(|i| {
                [
                    internal[2 * i] - gravity_load[2 * i],
                    internal[2 * i + 1] - gravity_load[2 * i + 1],
                ]
            })
            .collect();

        let mut geometric = BandedSym::zeros(n, hb);
        for (e, element) in elements.iter().enumerate() {
            let dofs = mesh.element_dofs(e);
            let nodal = SMatrix::<f64, 8, 1>::from_fn(|r, _| static_displacement[dofs[r]]);
            let stresses = element.stresses(&nodal);
            scatter(
                &mut geometric,
                &dofs,
                &element.geometric_stiffness(&stresses),
            );
        }
        let total_mass = mass.iter().step_by(2).sum();
        Ok(Self {
            mesh,
            mass,
            stiffness,
            geometric,
            gravity_load,
            static_displacement,
            static_reactions,
            total_mass,
        })
    }

    /// Tangent stiffness K (+ K_σ with P-Delta).
    pub fn tangent(&self, p_delta: bool) -> BandedSym {
        let mut k = self.stiffness.clone();
        if p_delta {
            k.add_scaled(&self.geometric, 1.0);
        }
        k
    }

    /// Constant load vector of the incremental formulation: F_g (+ K_σ u_g with P-Delta), so that
    /// `K_t u = F_const + reactions` holds at u = u_g and K_σ acts only on u - u_g.
    pub fn constant_load(&self, p_delta: bool) -> Vec<f64> {
        let mut f = self.gravity_load.clone();
        if p_delta {
            self.geometric
                .mul_vec_add(&self.static_displacement, 1.0, &mut f);
        }
        f
    }

    /// Gap below which a base node tied to the rigid plate still counts as on the floor: the
    /// plate's own deflection under the whole weight over its width, M g B³/EI_plate, m.
    pub fn plate_compliance_gap(body: &FemBody) -> f64 {
        body.mass() * body.gravity * body.width.powi(3)
            / (PLATE_RIGIDITY_RATIO * body.flexural_rigidity())
    }

    pub fn base_dof_count(&self) -> usize {
        2 * (self.mesh.nx + 1)
    }
}

/// Rigidity of the base plate relative to the body's base section (EI_plate/EI and
/// EA_plate/(E D B)): rigid enough that the plate's own deformation is ~1e-4 of the body's,
/// soft enough that LDLᵀ pivots stay well above round-off.
pub(crate) const PLATE_RIGIDITY_RATIO: f64 = 1.0e4;

/// Ties the base nodes (dofs 0..2(nx+1), spacing h = B/nx) to a stiff plate by penalty springs
/// on the plate's two deformations: stretching, EA/h on (ux_{i+1} - ux_i), and bending, EI/h³
/// on (uy_{i-1} - 2 uy_i + uy_{i+1}) (the discrete ∫ EI w''² dx). Their null space is the
/// plate's rigid motion (ux equal, uy linear in x), so the static gravity state, with every
/// base node pinned, is unchanged.
fn tie_base_to_plate(stiffness: &mut BandedSym, nx: usize, body: &FemBody) {
    let spacing = body.width / nx as f64;
    let axial = PLATE_RIGIDITY_RATIO * body.youngs_modulus * body.depth * body.width / spacing;
    let bending = PLATE_RIGIDITY_RATIO * body.flexural_rigidity() / spacing.powi(3);
    let mut spring = |k: f64, dofs: &[usize], weights: &[f64]| {
        for (a, &da) in dofs.iter().enumerate() {
            for (b, &db) in dofs.iter().enumerate().take(a + 1) {
                stiffness.add(da, db, k * weights[a] * weights[b]);
            }
        }
    };
    for i in 0..nx {
        spring(axial, &[2 * i, 2 * i + 2], &[-1.0, 1.0]);
    }
    for i in 1..nx {
        spring(
            bending,
            &[2 * i - 1, 2 * i + 1, 2 * i + 3],
            &[1.0, -2.0, 1.0],
        );
    }
}

fn scatter(global: &mut BandedSym, dofs: &[usize; 8], local: &SMatrix<f64, 8, 8>) {
    for r in 0..8 {
        for c in 0..=r {
            global.add(dofs[r], dofs[c], local[(r, c)]);
        }
    }
}
