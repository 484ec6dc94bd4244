//! The energy books' pieces: the work integrated up to a time, and the short way to the books
//! of a flow's samples.

use super::flow;
use crate::physics::automaton::{Automaton, Mode};

/// The integrals of the input and damping power up to `t`, J.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct Work {
    pub(super) t: f64,
    pub(super) input: f64,
    pub(super) damping: f64,
    /// The work of a neighbour's contact force while the column is held against it (a row's
    /// persistent contact), J.
    pub(super) contact: f64,
    /// The integrands f x' and x'^2 at t, of the flow that reached it; None where the motion
    /// may jump at t (an event's reset, a neighbour's impulse, a change of the linear form).
    pub(super) start: Option<[f64; 2]>,
}

/// The energy books of the pieces between a flow's samples, shortened. After the first such
/// piece, the rest of the flow's recur with the same forms and the same factors, so that each
/// takes the forms' two products and the factors, by the same arithmetic as the general path
/// ([`Run::advance_work_to`](super::run::Run::advance_work_to)) and to the same bits, without searching for them again.
#[derive(Debug, Clone, Copy)]
pub(super) struct SampleBooks {
    /// The flow's number ([`Run::flows`](super::run::Run::flows) when it was planned; a flow keeps one mode, an event
    /// ends it).
    pub(super) flow: usize,
    /// The kept forms ([`FormCache::last`](super::work::FormCache::last)).
    pub(super) forms: (usize, usize),
    /// The flow's rate (the pieces a span is cut into follow from it, [`work_pieces`]).
    pub(super) rate: f64,
    pub(super) factors: WorkFactors,
}

/// What turns a lone column's integrals of f x' and of x'^2 over a piece into its input and
/// damping work, J.
#[derive(Debug, Clone, Copy)]
pub(super) struct WorkFactors {
    /// The input power -beta Me a q' is Me times f q' (f = -beta a): this times the integral of
    /// f x'; none where beta is 0 (no input).
    pub(super) input: Option<f64>,
    /// The damping power's factor on q'^2.
    pub(super) damping: f64,
}

impl WorkFactors {
    /// The factors of `mode`'s flows, whose forcing is f = -`beta` a.
    pub(super) fn of(automaton: &Automaton, mode: Mode, beta: f64) -> Self {
        WorkFactors {
            input: (beta != 0.0).then(|| automaton.input_power(mode, 1.0, 1.0) / -beta),
            damping: automaton.damping_power(mode, 1.0),
        }
    }

    /// The input work of a piece whose integral of f x' is `force_work`.
    pub(super) fn input(&self, force_work: f64) -> f64 {
        self.input.map_or(0.0, |factor| factor * force_work)
    }
}

/// The pieces a span of the energy books is cut into: each short against the flow's `rate`.
pub(super) fn work_pieces(span: f64, rate: f64) -> usize {
    (span * rate / flow::WORK_REACH).ceil().clamp(1.0, 1e7) as usize
}
