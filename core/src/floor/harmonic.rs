//! A sine from t = 0 of a given amplitude and period.

use std::f64::consts::PI;

use serde::Serialize;

use super::closed_form::ClosedForm;
use super::motion::FloorMotion;

/// a(t) = A sin(2 pi t / Tp) from t = 0 (the floor starts with velocity -A Tp / 2 pi).
#[derive(Debug, Clone, Serialize)]
pub struct Harmonic {
    /// A, peak floor acceleration, m/s^2.
    pub amplitude: f64,
    /// Tp, period of the sine, s.
    pub period: f64,
}

impl FloorMotion for Harmonic {
    fn period(&self) -> Option<f64> {
        Some(self.period)
    }
    fn acceleration(&self, t: f64) -> f64 {
        self.amplitude * (2.0 * PI * t / self.period).sin()
    }
    fn peak_acceleration(&self) -> f64 {
        self.amplitude.abs()
    }
    fn kind(&self) -> &'static str {
        "harmonic"
    }
    fn closed_form(&self, _t: f64) -> ClosedForm {
        ClosedForm::sine(self.amplitude, self.period)
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": self.kind(), "amplitude": self.amplitude, "period": self.period })
    }
}
