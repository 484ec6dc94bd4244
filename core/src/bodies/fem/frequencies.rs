//! The mesh's natural frequencies: the fixed-base periods, the highest frequency, and the
//! stability limit of the time step it sets.

use super::assembly::Assembly;
use super::banded::BandedSym;
use super::body::{validate_body, FemBody};
use super::eigen;
use super::error::{invalid, FemError};
use super::limits::validate_mesh;
use super::settings::TimeScheme;

/// Flags of the dofs held in the fixed-base eigenproblems: both dofs of every base node.
pub(super) fn fixed_base_dofs(model: &Assembly) -> Vec<bool> {
    let base = model.base_dof_count();
    (0..model.mesh.dof_count()).map(|d| d < base).collect()
}

/// The `count` lowest fixed-base (base nodes pinned) natural periods, s, longest first,
/// with or without the geometric stiffness of the gravity prestress.
pub fn fixed_base_periods(
    body: &FemBody,
    nx: usize,
    ny: usize,
    p_delta: bool,
    count: usize,
) -> Result<Vec<f64>, FemError> {
    validate_body(body)?;
    validate_mesh(nx, ny)?;
    let model = Assembly::build(body, nx, ny)?;
    let fixed = fixed_base_dofs(&model);
    let free = fixed.iter().filter(|f| !**f).count();
    if count == 0 || count > free {
        return Err(invalid(
            "count",
            count,
            "must lie in 1..=number of free dofs",
        ));
    }
    let k: BandedSym = model.tangent(p_delta);
    let values = eigen::lowest_eigenvalues(&k, &model.mass, &fixed, count)?;
    values
        .iter()
        .map(|&w2| {
            if w2 > 0.0 {
                Ok(2.0 * std::f64::consts::PI / w2.sqrt())
            } else {
                Err(FemError::SingularMatrix {
                    context: format!(
                        "non-positive eigenvalue {w2:e}: the body buckles under its own weight"
                    ),
                })
            }
        })
        .collect()
}

/// Highest circular frequency ω_max of the mesh with the base free (elastic K, lumped M), rad/s.
pub fn highest_frequency(body: &FemBody, nx: usize, ny: usize) -> Result<f64, FemError> {
    validate_body(body)?;
    validate_mesh(nx, ny)?;
    let model = Assembly::build(body, nx, ny)?;
    highest_frequency_of(&model)
}

/// Highest natural frequency with the base free, rad/s. Holding dofs can only lower the top of
/// the spectrum (eigenvalue interlacing), so this bounds every contact state of a run; a rigid
/// base plate raises it by orders of magnitude once its nodes leave the floor.
pub(super) fn highest_frequency_of(model: &Assembly) -> Result<f64, FemError> {
    let free = vec![false; model.mesh.dof_count()];
    Ok(eigen::highest_eigenvalue(&model.stiffness, &model.mass, &free)?.sqrt())
}

/// Stability limit of the linear acceleration method on this mesh, dt_crit = sqrt(12)/ω_max
/// (= 0.551 T_min), s. Uses the elastic K with the base free; K_σ lowers ω_max slightly, so the
/// limit is on the safe side. Stiffness-proportional damping does not change it (γ = 1/2).
pub fn stability_limit(body: &FemBody, nx: usize, ny: usize) -> Result<f64, FemError> {
    Ok(
        crate::integrate::newmark::linear_acceleration_omega_dt()
            / highest_frequency(body, nx, ny)?,
    )
}

/// Undamped stability limit of a scheme for a highest frequency `omega_max` (rad/s), s;
/// None when the scheme is unconditionally stable (Newmark 2β >= γ >= 1/2, Wilson θ >= 1.37).
/// For Newmark, dt_crit = 1/(ω_max sqrt(γ/2 - β)). For Wilson θ < 1.37 the linear acceleration
/// limit sqrt(12)/ω_max is returned as a conservative value.
pub fn critical_time_step(scheme: TimeScheme, omega_max: f64) -> Option<f64> {
    match scheme {
        TimeScheme::Newmark { beta, gamma } => {
            crate::integrate::newmark::critical_omega_dt(beta, gamma).map(|limit| limit / omega_max)
        }
        TimeScheme::WilsonTheta { theta } => {
            if theta >= 1.37 {
                None
            } else {
                Some(crate::integrate::newmark::linear_acceleration_omega_dt() / omega_max)
            }
        }
    }
}
