//! The numerics layer's error: what the solvers and the rigid block report.

use crate::base::invalid::InvalidParameter;

/// A solver could not start (a setting breaks a rule) or could not go on.
#[derive(Debug, thiserror::Error)]
pub enum SolverError {
    /// A setting or an input breaks a rule.
    #[error(transparent)]
    Invalid(#[from] InvalidParameter),

    /// The integrator could not continue.
    #[error("the {method} solver failed at t = {} s: {message}", crate::base::format::readable(*.t))]
    Failed {
        /// The solver's name, e.g. "bdf".
        method: String,
        /// Where it stopped, s.
        t: f64,
        /// Why.
        message: String,
    },
}

impl SolverError {
    /// True when the input broke a rule, false when the computation failed.
    pub fn is_input_error(&self) -> bool {
        matches!(self, SolverError::Invalid(_))
    }
}
