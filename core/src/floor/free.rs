//! No floor motion: the body's free vibration from its initial state.

use serde::Serialize;

use super::closed_form::{ClosedForm, Shape};
use super::motion::FloorMotion;

/// No floor motion: free vibration or free rocking from the initial state.
#[derive(Debug, Clone, Serialize)]
pub struct Free;

impl FloorMotion for Free {
    fn quiet_after(&self) -> Option<f64> {
        Some(0.0)
    }
    fn acceleration(&self, _t: f64) -> f64 {
        0.0
    }
    fn peak_acceleration(&self) -> f64 {
        0.0
    }
    fn kind(&self) -> &'static str {
        "free"
    }
    fn closed_form(&self, _t: f64) -> ClosedForm {
        ClosedForm::exact(f64::INFINITY, Shape::Rest)
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": self.kind() })
    }
}
