//! The exact solution: eq. 16 solved in closed form within each mode, events found as roots of
//! closed-form functions that cannot be missed, and the state carried across re-anchors in
//! twice the working precision.
//!
//! Within a mode eq. 16 is linear with constant coefficients ([`Automaton::linear_form`](crate::physics::automaton::Automaton::linear_form)), so
//! the state moves by the mode's 2x2 matrix exponential plus the response to the floor, which is
//! closed form for every kind of motion the model has ([`crate::floor::ClosedForm`]):
//! nothing at all for free motion, a steady state for a sinusoid, and for polynomial pieces (a
//! record's linear pieces between samples, the ramp's cubic, the Ricker wavelet's Taylor pieces
//! with their stated remainder) the Taylor series of the solution, summed to rounding
//! (`flow.rs`); across a record's whole interval between two samples, the exact piecewise-linear
//! recurrence, a 2x4 matrix built once for each mode to twice the precision (`step.rs`). The
//! automaton is the only model: the solver reads each mode's coefficients, its
//! guards and its resets from it.
//!
//! Events (`scan.rs`): the first guard crossing of each flow is bracketed between consecutive
//! extrema of q, located with certified bounds on q'' and q''', and refined by Newton steps to
//! a few ulps of t; q is then put on the guard and the reset applied to q'.
//!
//! Precision: a flow is summed from its anchor, so free motion and a sine need no steps; the
//! state is carried from flow to flow (a record's samples) compensated, as hi + lo. At an event
//! the crossing's time is kept beyond its double (the next flow's anchor is hi + lo), and the
//! state there is summed to twice the precision (while rocking, from the free motion's growing
//! and decaying exponentials, whose terms do not cancel when the body barely lifts off); the
//! mode's coefficients are the constants rounded once from twice the precision; and a sine's
//! phase is reduced to a fraction of a turn in twice the precision. The solver
//! books a first-order estimate of its own error. Locally, within each flow: the rounding of
//! every term summed and of every phase formed since the flow's anchor (growing with the flow's
//! rates), and the stated error of the floor's closed form, turned into an error of each event
//! time (the error of q over |q'|) and of each peak (of q, and of its time, the error of q'
//! over |q''|). Carried: the local errors of the earlier events' times, added as a random walk,
//! are added to every later event's and peak's time, as the shift of time they are in free
//! motion (and to a peak's value, times the speed of the free part of the motion there, or the
//! largest speed met where the flow does not split it off). And measured: the spread of two
//! runs whose constants and initial state are moved by a few ulps (see [`solve`]), which
//! carries a relative error of a few ulps in the model's constants through the whole run,
//! grazing events and their amplification included.
//!
//! Energy books: the input and damping work are integrated along each flow on pieces short
//! against the flow's rates (one per sample of the history), each from the Taylor series of the
//! motion and of the forcing about its end, whose products are integrated term by term to
//! rounding; the energy residual therefore checks these integrals and the resets, not the
//! solution. The series are linear in the state and the forcing at the piece's end, so over
//! pieces of the grid's spacing the integrals are quadratic forms of those, whose matrices are
//! built once for each mode and kind of forcing and kept (`work.rs`); after a flow's first
//! sample, its pieces take those forms and the factors that turn them into work without
//! searching for them again (`SampleBooks`), to the same bits.

pub(crate) mod kernel;

mod energy_books;
mod equation;
mod extremes;
mod flow;
mod graze;
mod kept;
mod oscillator;
mod rounding;
mod run;
mod scan;
mod settings;
mod solve;
mod step;
mod work;

pub use graze::SHADOW_RUNS;
pub use settings::{ExactSettings, NAME};
pub use solve::solve;
