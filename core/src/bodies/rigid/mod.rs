//! The rigid block of the rigid limit (book/src/model.md §7; Housner 1963): the reference
//! that overturning spectra of the elastic body are plotted against, and what the elastic model
//! must tend to as E grows.
//!
//! Everything is in top-displacement units, q = theta H (theta the tilt), so that results compare
//! directly with the elastic model's q. With k^2 = 3 g/(2 H) (book/src/model.md §7, eq. A5;
//! p = k):
//!
//! - rocking right (q > 0): q'' = k^2 (q - B) - (3/2) a(t); rocking left (q < 0):
//!   q'' = k^2 (q + B) - (3/2) a(t);
//! - at rest (q = 0, q' = 0) the block stays until the floor acceleration reaches the uplift
//!   acceleration a_up: it starts rocking right when a(t) < -a_up, left when a(t) > a_up.
//!   Housner's block has a_up = g B/H ([`RigidBlock::housner`]); the elastic model's rigid limit
//!   uplifts at (lambda^3/(8 sigma)) g B/H = 1.1226 g B/H ([`RigidBlock::elastic_limit`], see
//!   [`ModeShapeIntegrals::rigid_limit_uplift_factor`](crate::physics::constants::ModeShapeIntegrals::rigid_limit_uplift_factor));
//! - when q crosses 0 the block hits the floor: q' -> e q' with Housner's restitution
//!   e = (2 H^2 - B^2)/(2 (H^2 + B^2)) (eq. A7), and it rocks on about the other toe;
//! - when |q| reaches B it has overturned (terminal).
//!
//! That is the small-angle (linearised, slender) form of Housner's equation, the default
//! ([`RigidForm::SmallAngle`]), and the form the elastic model tends to as E grows. The other
//! form ([`RigidForm::Full`]) is the full equation of a rectangular rigid block, the paper's
//! eq. A6 (Ichinose 1986, appendix), also Housner 1963 (Bull. Seismol. Soc. Am. 53(2)), Zhang and
//! Makris 2001 (J. Eng. Mech. 127(5)) and Dimitrakopoulos and DeJong 2012 (Proc. R. Soc. A 468).
//! With alpha = atan(B/H), R = sqrt(H^2 + B^2)/2 (the half-diagonal), p^2 = 3 g/(4 R) and
//! theta = q/H:
//!
//! ```text
//! theta'' = -p^2 [ sin(s alpha - theta) + (a(t)/g) cos(s alpha - theta) ],   s = sgn(theta)
//! ```
//!
//! with the same sign convention as the small-angle form: a(t) > 0 is the floor accelerating
//! towards +x, which tilts the block towards -x (q < 0). With sin x ~ x, cos x ~ 1, alpha ~ B/H
//! and R ~ H/2 it is the small-angle equation above; the two differ by O(alpha^2). The rules
//! are the same in both forms:
//!
//! - uplift when |a| reaches a_up (g tan alpha = g B/H for Housner's block), in the direction
//!   above;
//! - at an impact q' -> e q' with Housner's e = 1 - (3/2) sin^2 alpha, which follows from the
//!   conservation of angular momentum about the new toe for a rectangular block of any
//!   slenderness, so it is no small-angle approximation;
//! - overturned when theta reaches the equation's unstable equilibrium: |theta| = alpha, that
//!   is |q| = H atan(B/H), in the full form; |theta| = B/H, |q| = B, in the small-angle form
//!   ([`RigidBlock::overturning_displacement`]); or, by the other rule
//!   ([`RigidOverturning::CannotReturn`], that of Zhang and Makris 2001 and Makris and Roussos
//!   2000), only once the block cannot come back (below);
//! - chatter is cut short by the same rule (below), with each form's pull towards the floor.
//!
//! # When a block has overturned
//!
//! By default ([`RigidOverturning::ReachesLimit`]) a block has overturned the moment |theta|
//! reaches the limit above, and the run ends there. Past the limit the floor can still bring it
//! back: a pulse's second half pushes a block that passed alpha early in the pulse back towards
//! the floor. The rocking literature's minimum overturning accelerations count such a block as
//! standing: a block has overturned only if it never returns to the floor. By that rule
//! ([`RigidOverturning::CannotReturn`]) the run goes on past the limit (both equations hold there,
//! up to |theta| = pi/2, where the block lies on its side), and the block has overturned
//!
//! - when it lies on its side, |q| = H pi/2; or
//! - at the first moment the floor is at rest for good ([`FloorMotion::quiet_after`](crate::floor::FloorMotion::quiet_after)) or the run
//!   ends, if its free motion from there never brings it back to the floor: in the small-angle
//!   form when s (q - s B) + s q'/k >= 0 (the free motion q - s B = c1 e^(k t) + c2 e^(-k t)
//!   then never returns, c1 >= 0); in the full form when it is past alpha and not moving back
//!   fast enough to cross it again, or before alpha and moving out fast enough to cross it: the
//!   energy (1/2) theta'^2 - 2 p^2 sin^2((alpha - s theta)/2), conserved by the free motion,
//!   decides whether it crosses theta = s alpha (above 0) or not (below), and the direction of
//!   motion which way. (A block still past the limit when a run ends with the floor moving is
//!   judged as if the floor stopped then.)
//!
//! Its overturning time is then that moment, and its q where it was judged.
//!
//! # Numerical method
//!
//! Within a mode the equation is linear with constant coefficients, x'' = k^2 x + f(t) with
//! x = q - s B (s = +1 right, -1 left) and f = -(3/2) a. Its solution over a time tau from
//! (q0, v0) is exact up to the forcing integral:
//!
//! ```text
//! q(tau) = q0 cosh(k tau) - 2 s B sinh^2(k tau/2) + (v0/k) sinh(k tau) + (1/k) int_0^tau sinh(k (tau - u)) f(u) du
//! v(tau) = (q0 - s B) k sinh(k tau) + v0 cosh(k tau)                 + int_0^tau cosh(k (tau - u)) f(u) du
//! ```
//!
//! The integrals are taken by 8-point Gauss-Legendre quadrature over [0, tau] (exact for a
//! forcing that is a polynomial of degree 13 or less, e.g. a record's linear pieces; for a sine
//! of period Tp its relative error is of order (2 pi tau/Tp)^16). Steps are at most
//! [`RigidSettings::max_step`] long and stop exactly at every breakpoint of the floor motion, so
//! that no quadrature straddles a kink. Every event is located by bisection on the exact
//! propagator from the step's start (each trial time is a fresh propagation, not an
//! interpolation), down to the resolution of the floating-point time. A step is split at a root
//! of q' (located the same way) when q' changes sign in it, so that q is monotone on each piece
//! and a guard can be crossed at most once on it, in the direction q moves: an impact only moving
//! towards the floor, an overturn only moving away. The turning points are also the peaks of |q|.
//! At rest, the floor acceleration is sampled at eight points per step and a crossing of +-a_up
//! is located by bisection; an excursion beyond a_up shorter than an eighth of a step can be
//! missed. Halving the step changes event times and peaks by about 1e-13 (see the tests).
//!
//! The full equation has no closed-form propagator: each stretch of rocking is integrated by
//! diffsol's Tsit45 method (an explicit Runge-Kutta pair of orders 5 and 4) to the tolerances of
//! [`RigidSettings`] (by default [`DEFAULT_FULL_RTOL`] and [`DEFAULT_FULL_ATOL_FRACTION`] H), in
//! the event loop every diffsol run of the project shares: the floor's breakpoints are stops,
//! impacts and the overturn are located on each step's dense output, and the method restarts
//! after each impact. Checked against an independent integration of the full equation to 1e-11
//! (see the tests).
//!
//! # Chatter
//!
//! A block that lands slowly while |a| < g B/H falls back from either side: its impacts form a
//! geometric sequence whose flights shrink by e each time and which ends in finite time (Zeno).
//! After an impact with |q'| = v while |a(t)| < g B/H, the remaining sequence, if the floor
//! acceleration stayed as it is, would last at most 2 v / (c (g B/H - |a|) (1 - e)), with
//! c = 3/2 in the small-angle form and c = (3/2) cos^2 alpha in the full form (its pull towards
//! the floor at theta = 0, H p^2 (sin alpha - (|a|/g) cos alpha)). When that
//! is at most [`ZENO_TIME`] the block is put at rest ([`RigidEventKind::Settle`]). Since
//! g B/H <= a_up, the resting block stays until the floor reaches a_up.

#![warn(missing_docs)]

mod block;
mod full;
mod outcome;
mod run;
mod settings;
mod small_angle;

pub use block::{check_restitution, RigidBlock, RigidForm, RigidOverturning};
pub use outcome::{RigidEvent, RigidEventKind, RigidOutcome, RigidPhase, RigidState};
pub use run::{simulate_block, simulate_from, simulate_shaken};
pub use settings::{
    RigidSettings, DEFAULT_FULL_ATOL_FRACTION, DEFAULT_FULL_RTOL, DEFAULT_MAX_STEP,
    DEFAULT_STEP_FRACTION, ZENO_TIME,
};

type Result<T> = std::result::Result<T, crate::integrate::SolverError>;
