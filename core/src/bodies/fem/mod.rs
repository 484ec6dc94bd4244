//! 2D plane-stress finite element model of an elastic prismatic body rocking on a rigid floor,
//! after the verification analysis of Ichinose (1986), Section 3.
//!
//! Units are SI throughout: metres, seconds, kilograms, newtons, pascals. x is horizontal
//! (positive to the right), y vertical (positive up); the body occupies `0 <= x <= width`,
//! `0 <= y <= height` undeformed, with its base on the floor at y = 0. The left toe is
//! (0, 0), the right toe (width, 0).
//!
//! # Discretisation
//!
//! * **Element**: 4-node incompatible-mode quadrilateral QM6 (Wilson-Taylor), plane stress,
//!   thickness = `depth`, 2 x 2 Gauss integration, the four bubble modes condensed statically.
//!   Chosen because a bilinear Q4 locks in shear when bent (a 2 x 5 mesh of the slender body
//!   would be several times too stiff), whereas QM6 represents pure bending of rectangles
//!   exactly at the cost of a 4-node stencil that keeps the matrices narrow-banded. Taylor's
//!   centre-Jacobian correction keeps the constant-strain patch test exact on distorted meshes.
//! * **Mass**: lumped, row-sum of the consistent mass (each node gets ∫ N_a ρ D dA; a quarter of
//!   each adjacent rectangle). Diagonal, so gravity loads, the inertial floor load and
//!   the impact of a landing node are all node-local.
//! * **Gravity**: applied statically first with every base node pinned; the body then starts
//!   from this state (u = u_g, at rest).
//! * **P-Delta** (`p_delta`, default true): the geometric (initial-stress) stiffness K_σ of the
//!   static gravity stresses (all element stresses, incompatible modes included, integrated with
//!   the bilinear shape-function gradients) is added to K. It acts on u - u_g only: the
//!   constant load vector is F_g + K_σ u_g, so the static state is unchanged. For a rigid
//!   rotation θ about a toe it supplies the second-order moment -M g (H/2) θ, so the weight's
//!   moment about the toe is M g (B - q)/2 for small rotations and the body can overturn
//!   (the restoring force vanishes at q = B as in the SDOF model, book/src/model.md §3).
//!   Without it the restoring moment of a linear model stays at M g B/2 after uplift.
//!   The formulation remains geometrically linear (small rotations).
//! * **Damping**: \[C\] = (h T_d/π)\[K\] with the *elastic* K only. K_σ is left out of C: the
//!   paper's damping is a property of the material, it stays positive semi-definite, and it is
//!   the same with and without P-Delta.
//!
//! # Floor, contact and friction
//!
//! Displacements and velocities are relative to the floor; the floor acceleration a(t) enters
//! as the horizontal inertial load -m a(t) on every node. Each base node is
//! [`ContactState::Free`] (no constraint), [`ContactState::Slip`] (uy = 0; the kinetic
//! friction force Rx = s μk Ry acts on its x dof, s = ±1 the friction direction chosen at slip
//! onset as the sign of Rx then, i.e. opposing the slip) or [`ContactState::Fixed`] (uy = 0 and
//! ux held where it was when the node stuck — 0 unless the node slipped earlier; the paper's
//! "stay at the position of the previous time step"). Constrained dofs have zero velocity
//! and acceleration. The reactions (Rx, Ry) of the constrained dofs are the equilibrium
//! residuals M a + C v + K_t u - F at the end of the step.
//!
//! State changes follow the paper: they are decided from the solution at the end of step n and
//! apply from step n + 1 (no re-solution of step n):
//!
//! | from | condition | to | applied to the state at t_n |
//! |---|---|---|---|
//! | Free | uy <= 0 | Fixed | uy = 0, node velocity and acceleration = 0 (plastic impact of the node), ux held |
//! | Fixed | Ry < 0 | Free | - |
//! | Fixed | Ry >= 0 and \|Rx\| > μs Ry | Slip | friction direction s = sign(Rx) |
//! | Slip | Ry < 0 | Free | - |
//! | Slip | Ry >= 0 and s ux' >= 0 | Fixed | node velocity and acceleration = 0, ux held |
//!
//! The last row is the paper's `Rx ux' >= 0` with Rx = s μk Ry written through its sign, so
//! that a frictionless (μk = 0) node still slides instead of re-sticking at once.
//! Setting the landing node's velocity to zero is a plastic impact of that node's lumped
//! mass only; the rest of the body is stopped through the elastic body over the next steps.
//! Within a step the only iteration is on the friction force of slipping nodes (fixed-point
//! on Ry, at most 10 re-solves with the same factors), so friction is implicit in Ry.
//! The effective stiffness is factorised once per distinct constraint pattern and cached.
//!
//! # Time integration
//!
//! [`TimeScheme::Newmark`] (β, γ) in displacement form; β = 1/6, γ = 1/2 is the paper's linear
//! acceleration method (stable for dt <= sqrt(12)/ω_max = 0.551 T_min, undamped or damped since
//! γ = 1/2), β = 1/4 the unconditionally stable average acceleration. [`TimeScheme::WilsonTheta`]
//! solves the linear acceleration step over θ dt with the load extrapolated linearly and
//! interpolates back (θ >= 1.37 is unconditionally stable; θ = 1.4 usual). Use
//! [`stability_limit`] / [`critical_time_step`] to warn or refuse before running;
//! [`FemResult::critical_time_step`] repeats the check for the settings used.
//!
//! # Output decomposition of the top displacement
//!
//! With θ_j = (uy(0, y_j) - uy(B, y_j))/B the rotation of the node row j (clockwise positive,
//! from the two edge nodes), the top displacement q = mean ux of the top nodes splits exactly:
//! * rocking r = θ_0 H (base rotation from the two base corners' uplift difference);
//! * slipping = mean ux of the base nodes;
//! * flexural s = ∫_0^H (θ(y) - θ_0) dy, trapezoidal over the node rows;
//! * shearing = q - r - slipping - s (the remainder: shear strain plus any non-plane-section
//!   warping of the rows).
//!
//! # Static pushover and the meaning of "uplift"
//!
//! [`pushover`] applies lateral loads λ m U(y) (U the first cantilever mode) from the gravity
//! state under top-displacement control; base nodes in contact are held in x and y, and leave
//! or re-enter contact by a no-tension/no-penetration active-set iteration.
//!
//! On the flexible base ([`BaseSupport::Flexible`], the paper's) a continuum on a rigid floor
//! has no sharp uplift: its base starts to open at the heel once the base moment passes roughly
//! the kern value (≈ M g B/6) and the contact zone then shrinks towards the toe.
//! [`PushoverPoint::heel_lifted`] marks the opening, [`PushoverPoint::uplift`] the state where
//! only one corner node is on the floor. For a stiff body (E = 500 MPa) the curve still follows
//! the SDOF model closely (its pre-uplift line and rocking line meet within 3 % of s_n, and the
//! rocking branch matches F(q) within 2 % for 0.1 B <= q <= 0.6 B). For the paper's soft body
//! (E = 5 MPa, toe strains of several %) the contact zone at the toe stays 1/4-1/3 of B wide:
//! the base shear peaks at about 1050 N near q ≈ 0.205 m (mesh-converged from 8 x 40 to
//! 32 x 80).
//!
//! On a rigid base plate ([`BaseSupport::RigidPlate`]) the base stays flat until the base moment
//! reaches N B/2 and then pivots about the toe, as the beam-column model of book/src/model.md §7a
//! (a rigid base section on toe springs) and the SDOF model assume: the reference body lifts off at
//! q = 0.194 m with 1549 N (beam-column: 0.1895 m, 1565 N). The plate is a set of penalty springs
//! on the base nodes (stretching and the second difference of uy) 1e4 times stiffer than the body's
//! base section; the results do not change from 1e3 to 1e5.
//!
//! # Stability of the paper's run
//!
//! With the lumped mass and the base free the 2 x 5 mesh has ω_max = 539.1 rad/s
//! (T_min = 0.01165 s; 534.6 rad/s with the base held), so the linear acceleration limit is
//! dt = 0.00643 s and the paper's dt = 0.0071 s lies beyond it.
//! The run does not blow up (every contact change resets the growing highest mode) but it
//! shows spurious contact chatter (5x the state changes of an average-acceleration run);
//! dt <= 0.0064 s, average acceleration or Wilson θ = 1.4 avoid it.

mod assembly;
mod banded;
mod body;
mod decomposition;
mod dynamics;
mod eigen;
mod element;
mod error;
mod frequencies;
mod limits;
mod mesh;
mod pushover;
mod results;
mod settings;
#[cfg(test)]
mod tests;

pub use body::{BaseSupport, FemBody};
pub use dynamics::simulate_fem;
pub use error::FemError;
pub use frequencies::{critical_time_step, fixed_base_periods, highest_frequency, stability_limit};
pub use limits::{
    band_entries, check_mesh_size, check_run_size, SizeLimit, FACTOR_CACHE_BYTES, MAX_BAND_ENTRIES,
    MAX_ELEMENTS_PER_SIDE, MAX_STEPS, MAX_STEP_WORK,
};
pub use pushover::pushover;
pub use results::{
    ContactEvent, ContactState, FemResult, FemStep, Pushover, PushoverPoint, Snapshot,
};
pub use settings::{FemSettings, TimeScheme};
