//! The geometry of a model file's body as the overturning criteria and their figures take it.

use serde::Serialize;

/// The model file's body: its height, width and gravity (the study's other slendernesses
/// keep its height and gravity).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Geometry {
    /// H, m.
    pub height: f64,
    /// B, m.
    pub width: f64,
    /// g, m/s^2.
    pub gravity: f64,
}

impl Geometry {
    /// B/H of the model file's body.
    pub fn slenderness(&self) -> f64 {
        self.width / self.height
    }
}
