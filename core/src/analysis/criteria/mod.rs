//! Overturning criteria of the elastic body, beside the rigid block's: the smallest floor peak
//! acceleration (and the peak velocity of the same floor motion) that overturns bodies of one
//! height, a few slendernesses B/H and a range of flexibilities, under sines of a few cycles, one-sine and one-cosine
//! pulses across period, and records scaled; with Housner's rigid block of the same geometry
//! (full and small-angle equations) and the elastic model's own rigid limit at the same points.
//!
//! - Ishiyama's (1982) acceleration and velocity conditions for rigid bodies come from
//!   [`crate::physics::rigid_criteria`], their one home;
//! - [`velocity`]: the peak floor velocity of a motion, in closed form;
//! - [`continuity`]: the elastic body against the rigid block, decade by decade of E;
//! - [`fit`]: a closed-form criterion fitted to the points, its error on each.
//!
//! Every minimum is the sweep's search ([`crate::analysis::sweep::find_min`]: a scan of the interval,
//! then a bisection of the first transition to overturning, with the bands above it that leave
//! the body standing reported), run by [`crate::Sweep`] over the Young's moduli and the
//! excitation periods, with the exact method.
//!
//! # The flexibility parameter
//!
//! phi = p T, the body's pre-uplift period T (s) over the rocking time scale 1/p of the rigid
//! block of the same geometry, p = sqrt(3 g/(4 R)), R the half-diagonal. The rigid block's
//! overturning is governed by p and the excitation alone (Housner 1963; Zhang and Makris 2001
//! plot the critical acceleration against omega_p/p); flexibility adds one time scale, T, and
//! phi says how it compares with p's: phi -> 0 is the rigid block, and a body whose elastic
//! vibration is slow against its rocking (phi of order one and above) rocks with its bending
//! lagging behind. phi varies as E^(-1/2) (T ~ sqrt(M H^3/(E I))), so a decade of E is a factor
//! sqrt(10) in phi. The paper's body (H = 4 m, B = 0.7 m, E = 5 MPa, T = 1.55 s, p = 1.904 rad/s)
//! has phi = 2.95.

pub mod continuity;
pub mod fit;
mod point;
mod run;
mod study;
pub mod velocity;

pub use point::Point;
pub use run::run;
pub use study::{
    record_name, slendernesses, valid_slenderness, Excitation, Study, AMPLITUDE, PERIODS, SCALE,
    SCAN, SINE_CYCLES, SLENDERNESS_RULE, TAIL, TOL_SHARE, YOUNGS_MODULI,
};
