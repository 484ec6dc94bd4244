//! The physics of one body: the body, its derived constants, the flexural shape of the
//! self-weight-consistent variant, the hybrid automaton (the only home of the dynamics) and the
//! published rigid-body criteria.

pub mod automaton;
pub mod body;
pub mod constants;
pub(crate) mod flexural_shape;
pub mod rigid_criteria;
