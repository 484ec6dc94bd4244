//! The state a run starts from.

use serde::Serialize;

/// The state a run starts from, at t = 0.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct InitialState {
    /// q0, m.
    pub q: f64,
    /// q'0, m/s.
    pub qdot: f64,
}
