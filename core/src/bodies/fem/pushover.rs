//! Static pushover with unilateral base contact.

use std::collections::HashMap;

use super::assembly::Assembly;
use super::banded::{BandedLdl, BandedSym};
use super::body::{validate_body, BaseSupport, FemBody};
use super::decomposition::decompose;
use super::error::{invalid, FemError};
use super::limits::validate_mesh;
use super::results::{Pushover, PushoverPoint};
use crate::physics::constants::cantilever_mode;

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
    let model = Assembly::build(body, nx, ny)?;
    let mut problem = ContactProblem::new(body, &model, p_delta);
    let base_nodes = problem.base_nodes;
    let mut contact: Vec<bool> = (0..base_nodes)
        .map(|i| is_contact_candidate(body, i, base_nodes))
        .collect();
    let mut points = Vec::with_capacity(top_displacements.len());
    for &q in top_displacements {
        let (mut converged, mut any_solvable) = problem.active_set(&mut contact, q);
        // The discrete node-to-floor contact with P-Delta softening can leave no exactly
        // admissible contact set at a prescribed q (a node sits on the floor with neither a
        // compressive reaction nor a gap while the zone shrinks from two nodes to one) and the
        // iteration then cycles. Fall back to the contact zones progressive uplift produces
        // (contiguous, ending at the toe q leans to) and take the least violating one, if its
        // violation (penetration / |q|, tension / weight) is below 1 %.
        let mut approximate = false;
        if converged.is_none() {
            let (best, solvable) = problem.least_violating_zone(q);
            any_solvable |= solvable;
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
        points.push(problem.point(q, &u, load_factor, approximate));
    }
    Ok(Pushover {
        points,
        free_rotation_at: None,
    })
}

/// The static contact problem of a pushover: the tangent, the gravity load and the lateral
/// load pattern of one mesh, and the factorised tangents of the contact sets tried so far.
struct ContactProblem<'a> {
    body: &'a FemBody,
    model: &'a Assembly,
    /// Degrees of freedom of the mesh.
    n: usize,
    base_nodes: usize,
    tangent: BandedSym,
    constant_load: Vec<f64>,
    /// The lateral load pattern m_i U(y_i/H) on the x dofs, N per unit load factor.
    pattern: Vec<f64>,
    top: Vec<usize>,
    /// Reactions less tensile than this (N) count as compressive.
    tension_tolerance: f64,
    /// Gaps smaller than this (m) count as contact.
    penetration_tolerance: f64,
    factors: HashMap<Vec<bool>, BandedLdl>,
}

impl<'a> ContactProblem<'a> {
    fn new(body: &'a FemBody, model: &'a Assembly, p_delta: bool) -> Self {
        let mesh = &model.mesh;
        let n = mesh.dof_count();
        let pattern: Vec<f64> = (0..n)
            .map(|d| {
                if d % 2 == 0 {
                    model.mass[d] * cantilever_mode(mesh.coords[d / 2][1] / body.height)
                } else {
                    0.0
                }
            })
            .collect();
        ContactProblem {
            body,
            model,
            n,
            base_nodes: mesh.nx + 1,
            tangent: model.tangent(p_delta),
            constant_load: model.constant_load(p_delta),
            pattern,
            top: mesh.top_nodes(),
            tension_tolerance: 1e-9 * model.total_mass * body.gravity.max(1.0),
            // a node tied to the rigid plate sits off the plate's line by the plate's own
            // compliance: that much is not a gap or a penetration
            penetration_tolerance: match body.base {
                BaseSupport::Flexible => 1e-12 * body.height,
                BaseSupport::RigidPlate => Assembly::plate_compliance_gap(body),
            },
            factors: HashMap::new(),
        }
    }

    /// Mean ux of the top nodes, m.
    fn mean_top(&self, u: &[f64]) -> f64 {
        self.top.iter().map(|&k| u[2 * k]).sum::<f64>() / self.top.len() as f64
    }

    /// Solution for a given contact set: (u, λ, worst penetration, worst tension).
    /// None when the set leaves the body unstable (singular tangent).
    fn solve_with(&mut self, contact: &[bool], q: f64) -> Option<ContactTrial> {
        let (n, base_nodes) = (self.n, self.base_nodes);
        let constrained: Vec<bool> = (0..n)
            .map(|d| d / 2 < base_nodes && contact[d / 2])
            .collect();
        if !self.factors.contains_key(contact) {
            let f = BandedLdl::factor(&self.tangent.with_identity_rows(&constrained)).ok()?;
            self.factors.insert(contact.to_vec(), f);
        }
        let factor = &self.factors[contact];
        let solve = |rhs: &[f64]| {
            let mut x: Vec<f64> = rhs
                .iter()
                .zip(&constrained)
                .map(|(r, c)| if *c { 0.0 } else { *r })
                .collect();
            factor.solve_in_place(&mut x);
            x
        };
        let u_gravity = solve(&self.constant_load);
        let u_pattern = solve(&self.pattern);
        let load_factor = (q - self.mean_top(&u_gravity)) / self.mean_top(&u_pattern);
        let u: Vec<f64> = u_gravity
            .iter()
            .zip(&u_pattern)
            .map(|(g, p)| g + load_factor * p)
            .collect();
        let mut internal = vec![0.0; n];
        self.tangent.mul_vec(&u, &mut internal);
        let mut trial = ContactTrial {
            u,
            load_factor,
            penetration: None,
            tension: None,
        };
        for (i, &in_contact) in contact.iter().enumerate() {
            let d = 2 * i + 1;
            let ry = internal[d] - self.constant_load[d] - load_factor * self.pattern[d];
            if in_contact && ry < -self.tension_tolerance {
                if trial.tension.is_none_or(|(_, r)| ry < r) {
                    trial.tension = Some((i, ry));
                }
            } else if !in_contact
                && is_contact_candidate(self.body, i, base_nodes)
                && trial.u[d] < -self.penetration_tolerance
                && trial.penetration.is_none_or(|(_, v)| trial.u[d] < v)
            {
                trial.penetration = Some((i, trial.u[d]));
            }
        }
        Some(trial)
    }

    /// Active-set iteration from the previous point's `contact`: one change per pass,
    /// re-adding the most penetrating node first, else releasing the most tensile one. Returns
    /// the admissible solution, if found, and whether any contact set tried could be solved.
    fn active_set(&mut self, contact: &mut [bool], q: f64) -> (Option<ContactTrial>, bool) {
        let mut any_solvable = false;
        for _ in 0..(2 * self.base_nodes + 4) {
            let Some(trial) = self.solve_with(contact, q) else {
                break;
            };
            any_solvable = true;
            if let Some((i, _)) = trial.penetration {
                contact[i] = true;
            } else if let Some((i, _)) = trial.tension {
                contact[i] = false;
            } else {
                return (Some(trial), any_solvable);
            }
            if !contact.contains(&true) {
                break;
            }
        }
        (None, any_solvable)
    }

    /// Of the contact zones progressive uplift produces (contiguous, ending at the toe q leans
    /// to), the one whose solution violates the contact conditions least: (violation, zone,
    /// solution), the violation the larger of penetration / |q| and tension / weight. Also
    /// whether any zone could be solved.
    fn least_violating_zone(&mut self, q: f64) -> (Option<ScoredZone>, bool) {
        let (body, base_nodes) = (self.body, self.base_nodes);
        let weight = self.model.total_mass * body.gravity.max(1e-12);
        let mut any_solvable = false;
        let mut best: Option<ScoredZone> = None;
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
            let Some(trial) = self.solve_with(&zone, q) else {
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
        (best, any_solvable)
    }

    /// The point of the curve at top displacement q for the solution u with load factor λ.
    fn point(&self, q: f64, u: &[f64], load_factor: f64, approximate: bool) -> PushoverPoint {
        let base_nodes = self.base_nodes;
        let [_, rocking, _, flexural, shearing] = decompose(&self.model.mesh, u);
        // judged by the gaps, not by the contact set: a rigid plate holds nodes on the floor
        // that carry no reaction
        let on_floor: Vec<bool> = (0..base_nodes)
            .map(|i| u[2 * i + 1] <= self.penetration_tolerance)
            .collect();
        let contact_nodes = on_floor.iter().filter(|c| **c).count();
        let corner_only = contact_nodes == 1 && (on_floor[0] || on_floor[base_nodes - 1]);
        PushoverPoint {
            q,
            base_shear: load_factor * self.pattern.iter().sum::<f64>(),
            load_factor,
            uplift: corner_only && base_nodes > 1,
            heel_lifted: !(on_floor[0] && on_floor[base_nodes - 1]),
            contact_nodes,
            flexural,
            rocking,
            shearing,
            approximate_contact: approximate,
        }
    }
}

/// A contact zone with its solution and how much that violates the contact conditions:
/// (violation, zone, solution).
type ScoredZone = (f64, Vec<bool>, ContactTrial);

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
