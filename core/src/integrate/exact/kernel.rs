//! The exact method's kernel, as a body other than the single body uses it. A body whose parts
//! each move by eq. 16 in closed form between events (a row of columns under the impact law)
//! plans each part's stretches of motion with an [`ExactRun`] (one [`Planned`] flow at a time),
//! evaluates a flow at any time with [`Flow::point`], finds the first time a smooth function of
//! the flows crosses zero with [`first_crossing`] (bracketed between certified bounds and
//! refined to a few ulps of t; [`evaluate`] counts its evaluations against [`MAX_EVALUATIONS`]),
//! and sizes its rounding with [`ulp`]. The single body uses the same pieces through
//! [`solve`](super::solve); nothing else of the method is reached from outside it.

pub(crate) use super::flow::{Flow, Point, STEADY_BOUND_GAIN};
pub(crate) use super::oscillator::oscillator_peak;
pub(crate) use super::rounding::ulp;
pub(crate) use super::run::{ExactRun, Planned};
pub(crate) use super::scan::{evaluate, first_crossing, ScanError, Smooth, Watch, MAX_EVALUATIONS};
