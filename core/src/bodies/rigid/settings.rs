//! The settings of a rigid-block run: its steps and tolerances.

use serde::Serialize;

use super::RigidBlock;

/// Longest default step, s. The propagator is exact between steps up to the forcing quadrature,
/// so the step length serves mainly to bound the time in which q' could turn twice unseen.
pub const DEFAULT_MAX_STEP: f64 = 1e-3;

/// The default step is also at most this fraction of the block's time scale 1/k.
pub const DEFAULT_STEP_FRACTION: f64 = 0.05;

/// A chattering block is put at rest when the impacts still to come would end within this
/// time, s (see the module documentation).
pub const ZENO_TIME: f64 = 1e-6;

/// Relative tolerance of the full equation's adaptive integration.
pub const DEFAULT_FULL_RTOL: f64 = 1e-12;

/// Absolute tolerance of the full equation's adaptive integration, as a fraction of H.
pub const DEFAULT_FULL_ATOL_FRACTION: f64 = 1e-13;

/// Settings of a rigid-block run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RigidSettings {
    /// Longest step of the small-angle form and of a block at rest, s. Steps also stop at every
    /// breakpoint of the floor motion.
    pub max_step: f64,
    /// Relative tolerance of the full form's adaptive integration.
    pub rtol: f64,
    /// Absolute tolerance of the full form's adaptive integration, m.
    pub atol: f64,
}

impl RigidSettings {
    /// The default for a block: a longest step of min([`DEFAULT_MAX_STEP`],
    /// [`DEFAULT_STEP_FRACTION`] / k), and the full form's tolerances [`DEFAULT_FULL_RTOL`] and
    /// [`DEFAULT_FULL_ATOL_FRACTION`] H.
    pub fn for_block(block: &RigidBlock) -> Self {
        RigidSettings {
            max_step: DEFAULT_MAX_STEP.min(DEFAULT_STEP_FRACTION / block.frequency()),
            rtol: DEFAULT_FULL_RTOL,
            atol: DEFAULT_FULL_ATOL_FRACTION * block.height(),
        }
    }
}
