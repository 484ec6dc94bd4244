//! Solvers that drive the hybrid automaton. They share the initial state, the output grid and the
//! result type ([`crate::integrate::solution::Solution`]).

pub mod adaptive;
pub mod budget;
mod error;
pub(crate) mod event_loop;
pub mod exact;
pub mod newmark;
pub(crate) mod sign_change;
pub mod solution;

use serde::Serialize;

/// The state a run starts from, at t = 0.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct InitialState {
    /// q0, m.
    pub q: f64,
    /// q'0, m/s.
    pub qdot: f64,
}

pub use crate::integrate::solution::History;
pub use error::SolverError;

/// The times at which the history is sampled: every `output_dt` from 0, and the final time.
#[derive(Debug, Clone)]
pub struct OutputGrid {
    output_dt: f64,
    count: usize,
    end: f64,
    next: usize,
}

impl OutputGrid {
    /// The grid of a run that keeps `history`: none at all for [`History::PeaksOnly`].
    pub fn for_history(history: History, end: f64, output_dt: f64) -> Self {
        match history {
            History::Sampled => OutputGrid::new(end, output_dt),
            History::PeaksOnly => OutputGrid {
                output_dt,
                count: 0,
                end,
                next: 0,
            },
        }
    }

    /// The grid 0, dt, 2 dt, ... over [0, end] (s) with dt = `output_dt` (s), ending at `end`.
    pub fn new(end: f64, output_dt: f64) -> Self {
        // Points closer to `end` than a millionth of a step merge with it.
        let count = (end / output_dt * (1.0 + 1e-12) + 1e-6).floor() as usize + 1;
        OutputGrid {
            output_dt,
            count,
            end,
            next: 0,
        }
    }

    fn time(&self, index: usize) -> f64 {
        if index + 1 >= self.count {
            // Clamp to the end; the last point is always the final time.
            (index as f64 * self.output_dt).min(self.end)
        } else {
            index as f64 * self.output_dt
        }
    }

    /// The next grid time not yet emitted, if any.
    pub fn peek(&self) -> Option<f64> {
        if self.next < self.count {
            Some(self.time(self.next))
        } else if self.count > 0 && self.next == self.count && self.time(self.count - 1) < self.end
        {
            Some(self.end)
        } else {
            None
        }
    }

    /// How many grid times are not yet emitted (the final time included).
    pub fn remaining(&self) -> usize {
        (self.count + 1).saturating_sub(self.next)
    }

    /// The grid's spacing, s.
    pub fn spacing(&self) -> f64 {
        self.output_dt
    }

    /// Marks the next grid time emitted.
    pub fn advance(&mut self) {
        self.next += 1;
    }

    /// Every time of the grid over [0, end], as every solver samples it.
    pub fn times(end: f64, output_dt: f64) -> Vec<f64> {
        let mut grid = OutputGrid::new(end, output_dt);
        let mut times = Vec::new();
        while let Some(t) = grid.peek() {
            times.push(t);
            grid.advance();
        }
        times
    }
}

/// Which solver a model runs with, and its settings.
#[derive(Debug, Clone, Copy)]
pub enum SolverSettings {
    /// An adaptive diffsol method.
    Adaptive(adaptive::AdaptiveSettings),
    /// Newmark's method with a fixed step.
    Newmark(newmark::NewmarkSettings),
    /// The closed-form solution within each mode.
    Exact(exact::ExactSettings),
}

impl SolverSettings {
    /// The method's name in statistics and tables, e.g. "bdf" or "newmark-compensate".
    pub fn label(&self) -> String {
        match self {
            SolverSettings::Adaptive(a) => a.method.name().to_string(),
            SolverSettings::Newmark(n) => n.label(),
            SolverSettings::Exact(_) => exact::NAME.to_string(),
        }
    }

    /// Spacing of the sampled history, s.
    pub fn output_dt(&self) -> f64 {
        match self {
            SolverSettings::Adaptive(a) => a.output_dt,
            SolverSettings::Newmark(n) => n.output_dt,
            SolverSettings::Exact(e) => e.output_dt,
        }
    }
}

/// Serialised with the model file's key names, so that summary.json reads like `[solver]`.
impl Serialize for SolverSettings {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct NewmarkKeys {
            method: &'static str,
            dt: f64,
            newmark_beta: f64,
            newmark_gamma: f64,
            newmark_variant: &'static str,
            output_dt: f64,
        }
        #[derive(Serialize)]
        struct ExactKeys {
            method: &'static str,
            output_dt: f64,
        }
        match self {
            SolverSettings::Exact(e) => ExactKeys {
                method: exact::NAME,
                output_dt: e.output_dt,
            }
            .serialize(serializer),
            SolverSettings::Adaptive(a) => a.serialize(serializer),
            SolverSettings::Newmark(n) => NewmarkKeys {
                method: "newmark",
                dt: n.dt,
                newmark_beta: n.beta,
                newmark_gamma: n.gamma,
                newmark_variant: n.variant.name(),
                output_dt: n.output_dt,
            }
            .serialize(serializer),
        }
    }
}
