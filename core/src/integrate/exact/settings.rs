//! The exact method's name and settings.

use serde::Serialize;

/// The method's name in statistics, tables and model files.
pub const NAME: &str = "exact";

/// Settings of the exact solver: it has no tolerance, only the spacing of its history.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ExactSettings {
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}
