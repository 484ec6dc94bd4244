//! Solvers that drive the hybrid automaton. They share the initial state, the output grid and the
//! result type ([`crate::integrate::solution::Solution`]).

pub mod adaptive;
pub mod budget;
mod error;
pub(crate) mod event_loop;
pub mod exact;
mod initial_state;
pub(crate) mod monotone;
pub mod newmark;
mod output_grid;
mod settings;
pub(crate) mod sign_change;
pub mod solution;

pub use error::SolverError;
pub use initial_state::InitialState;
pub use output_grid::OutputGrid;
pub use settings::SolverSettings;
pub use solution::History;
