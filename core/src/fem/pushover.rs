//! Static pushover with unilateral base contact.

use std::collections::HashMap;

use super::banded::BandedLdl;
use super::model::Model;
use super::{
    cantilever_mode, decompose, invalid, validate_body, validate_mesh, BaseSupport, FemBody,
    FemError, Pushover, PushoverPoint,
};

/// Displacement-controlled static pushover from the gravity state.
///
/// Lateral loads λ m_i U(y_i/H) on the x dofs of every node (U the first cantilever mode,
/// U(1) = 1) are scaled so that the mean ux of the top nodes equals each requested q
/// (the contact problem is elastic and without friction losses, so the solution does not
/// depend on the path; each point starts from the previous point's contact set). Base nodes in contact have ux = uy = 0 (no sliding,
/// no penetration); a node leaves contact when its vertical reaction would be tensile and
/// returns when it would penetrate (active-set iteration, releasing all tensile and
/// re-adding all penetrating nodes per pass).
pub fn pushover(
    body: &FemBody,
    nx: usize,
    ny: usize,
    p_delta: bool,
    top_displacements: &[f64],
) -> Result<Pushover, FemError> {
    validate_body(body)?;
    validate_mesh(nx, ny)?;
    if let Some(q) = top_displacements.iter().find(|q| !q.is_finite()) {
        return Err(invalid("top_displacements", q, "must be finite"));
    }
    let model = Model::build(body, nx, ny)?;
    let mesh = &model.mesh;
    let n = mesh.dof_count();
    let base_nodes = nx + 1;
    let tangent = model.tangent(p_delta);
    let constant_load = model.constant_load(p_delta);
    let pattern: Vec<f64> = (0..n)
        .map(|d| {
            if d % 2 == 0 {
                model.mass[d] * cantilever_mode(mesh.coords[d / 2][1] / body.height)
            } else {
                0.0
            }
        })
        .collect();
    let pattern_sum: f64 = pattern.iter().sum();
    let top = mesh.top_nodes();
    let mean_top = |u: &[f64]| top.iter().map(|&k| u[2 * k]).sum::<f64>() / top.len() as f64;
    let tension_tolerance = 1e-9 * model.total_mass * body.gravity.max(1.0);
    // a node tied to the rigid plate sits off the plate's line by the plate's own compliance:
    // that much is not a gap or a penetration
    let penetration_tolerance = match body.base {
        BaseSupport::Flexible => 1e-12 * body.height,
        BaseSupport::RigidPlate => Model::plate_compliance_gap(body),
    };

    let mut factors: HashMap<Vec<bool>, BandedLdl> = HashMap::new();
    // Solution for a given contact set: (u, λ, worst penetration, worst tension).
    // None when the set leaves the body unstable (singular tangent).
    let mut solve_with = |contact: &[bool], q: f64| -> Option<ContactTrial> {
        let constrained: Vec<bool> = (0..n)
            .map(|d| d / 2 < base_nodes && contact[d / 2])
            .collect();
        if !factors.contains_key(contact) {
            let f = BandedLdl::factor(&tangent.with_identity_rows(&constrained)).ok()?;
            factors.insert(contact.to_vec(), f);
        }
        let factor = &factors[contact];
        let solve = |rhs: &[f64]| {
            let mut x: Vec<f64> = rhs
                .iter()
                .zip(&constrained)
                .map(|(r, c)| if *c { 0.0 } else { *r })
                .collect();
            factor.solve_in_place(&mut x);
            x
        };
        let u_gravity = solve(&constant_load);
        let u_pattern = solve(&pattern);
        let load_factor = (q - mean_top(&u_gravity)) / mean_top(&u_pattern);
        let u: Vec<f64> = u_gravity
            .iter()
            .zip(&u_pattern)
            .map(|(g, p)| g + load_factor * p)
            .collect();
        let mut internal = vec![0.0; n];
        tangent.mul_vec(&u, &mut internal);
        let mut trial = ContactTrial {
            u,
            load_factor,
            penetration: None,
            tension: None,
        };
        for (i, &in_contact) in contact.iter().enumerate() {
            let d = 2 * i + 1;
            let ry = internal[d] - constant_load[d] - load_factor * pattern[d];
            if in_contact && ry < -tension_tolerance {
                if trial.tension.is_none_or(|(_, r)| ry < r) {
                    trial.tension = Some((i, ry));
                }
            } else if !in_contact
                && is_contact_candidate(body, i, base_nodes)
                && trial.u[d] < -penetration_tolerance
                && trial.penetration.is_none_or(|(_, v)| trial.u[d] < v)
            {
                trial.penetration = Some((i, trial.u[d]));
            }
        }
        Some(trial)
    };

    let mut contact: Vec<bool> = (0..base_nodes)
        .map(|i| is_contact_candidate(body, i, base_nodes))
        .collect();
    let mut points = Vec::with_capacity(top_displacements.len());
    for &q in top_displacements {
        // active set from the previous point: one change per pass, re-adding the most
        // penetrating node first, else releasing the most tensile one
        let mut converged = None;
        let mut any_solvable = false;
        for _ in 0..(2 * base_nodes + 4) {
            let Some(trial) = solve_with(&contact, q) else {
                break;
            };
            any_solvable = true;
            if let Some((i, _)) = trial.penetration {
                contact[i] = true;
            } else if let Some((i, _)) = trial.tension {
                contact[i] = false;
            } else {
                converged = Some(trial);
                break;
            }
            if !contact.contains(&true) {
                break;
            }
        }
        // The discrete node-to-floor contact with P-Delta softening can leave no exactly
        // admissible contact set at a prescribed q (a node sits on the floor with neither a
        // compressive reaction nor a gap while the zone shrinks from two nodes to one) and the
        // iteration then cycles. Fall back to the contact zones progressive uplift produces
        // (contiguous, ending at the toe q leans to) and take the least violating one, if its
        // violation (penetration / |q|, tension / weight) is below 1 %.
        let mut approximate = false;
        if converged.is_none() {
            let weight = model.total_mass * body.gravity.max(1e-12);
            let mut best: Option<(f64, Vec<bool>, ContactTrial)> = None;
            for size in (1..=base_nodes).rev() {
                let zone: Vec<bool> = (0..base_nodes)
                    .map(|i| {
                        is_contact_candidate(body, i, base_nodes)
                            && if q >= 0.0 {
                                i + size >= base_nodes
                            } else {
                                i < size
                            }
                    })
                    .collect();
                let Some(trial) = solve_with(&zone, q) else {
                    continue;
                };
                any_solvable = true;
                let violation = trial
                    .penetration
                    .map_or(0.0, |(_, v)| -v / q.abs().max(1e-6 * body.height))
                    .max(trial.tension.map_or(0.0, |(_, r)| -r / weight));
                if best.as_ref().is_none_or(|(b, _, _)| violation < *b) {
                    best = Some((violation, zone, trial));
                }
            }
            if let Some((violation, zone, trial)) = best.filter(|(v, _, _)| *v <= 0.01) {
                contact = zone;
                converged = Some(trial);
                approximate = violation > 0.0;
            }
        }
        if converged.is_none() && !points.is_empty() && (!any_solvable || !p_delta) {
            // the body stands on its toe and nothing resists its turning about it: the curve
            // has ended. Without P-Delta the contact problem is convex (an elastic body on
            // unilateral supports), so it fails only this way: the restoring moment stays at
            // its uplift value and the tangent is singular or nearly so.
            return Ok(Pushover {
                points,
                free_rotation_at: Some(q),
            });
        }
        let Some(ContactTrial { u, load_factor, .. }) = converged else {
            return Err(if any_solvable {
                FemError::ContactNotConverged {
                    context: format!("pushover at q = {q} m"),
                }
            } else {
                FemError::SingularMatrix {
                    context: format!(
                        "pushover at q = {q} m: no contact set holds the body (without p_delta, \
                         a body resting on one point of its base turns about it freely)"
                    ),
                }
            });
        };
        let [_, rocking, _, flexural, shearing] = decompose(mesh, &u);
        // judged by the gaps, not by the contact set: a rigid plate holds nodes on the floor
        // that carry no reaction
        let on_floor: Vec<bool> = (0..base_nodes)
            .map(|i| u[2 * i + 1] <= penetration_tolerance)
            .collect();
        let contact_nodes = on_floor.iter().filter(|c| **c).count();
        let corner_only = contact_nodes == 1 && (on_floor[0] || on_floor[base_nodes - 1]);
        points.push(PushoverPoint {
            q,
            base_shear: load_factor * pattern_sum,
            load_factor,
            uplift: corner_only && base_nodes > 1,
            heel_lifted: !(on_floor[0] && on_floor[base_nodes - 1]),
            contact_nodes,
            flexural,
            rocking,
            shearing,
            approximate_contact: approximate,
        });
    }
    Ok(Pushover {
        points,
        free_rotation_at: None,
    })
}

/// Whether base node `i` of `base_nodes` takes part in the contact problem: every one on the
/// flexible base; only the two corners of a rigid plate (the nodes between lie on the line
/// joining them, so they meet the floor only when both corners do, and a flat plate's reactions
/// split among them indeterminately). The dynamic run keeps all base nodes in contact, so that
/// a landing plate stops at every node.
fn is_contact_candidate(body: &FemBody, i: usize, base_nodes: usize) -> bool {
    match body.base {
        BaseSupport::Flexible => true,
        BaseSupport::RigidPlate => i == 0 || i + 1 == base_nodes,
    }
}

/// Static solution for one trial contact set.
struct ContactTrial {
    u: Vec<f64>,
    load_factor: f64,
    /// Most penetrating lifted node (index, uy).
    penetration: Option<(usize, f64)>,
    /// Most tensile node in contact (index, Ry).
    tension: Option<(usize, f64)>,
}
