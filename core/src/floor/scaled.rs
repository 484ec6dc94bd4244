//! A floor motion times a constant: the vertical acceleration given as a ratio of the
//! horizontal one.

use super::closed_form::{ClosedForm, Shape};
use super::motion::FloorMotion;

/// `factor` times `motion`: a(t) = factor x motion(t), with the motion's breakpoints and stretches.
pub struct Scaled {
    /// The motion scaled.
    pub motion: Box<dyn FloorMotion>,
    /// The factor, e.g. the ratio of the vertical to the horizontal acceleration.
    pub factor: f64,
}

impl FloorMotion for Scaled {
    fn acceleration(&self, t: f64) -> f64 {
        self.factor * self.motion.acceleration(t)
    }
    fn breakpoints(&self) -> &[f64] {
        self.motion.breakpoints()
    }
    fn jumps_at(&self, t: f64) -> bool {
        self.factor != 0.0 && self.motion.jumps_at(t)
    }
    fn peak_acceleration(&self) -> f64 {
        self.factor.abs() * self.motion.peak_acceleration()
    }
    fn quiet_after(&self) -> Option<f64> {
        self.motion.quiet_after()
    }
    fn period(&self) -> Option<f64> {
        self.motion.period()
    }
    fn kind(&self) -> &'static str {
        "ratio"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": self.kind(), "ratio": self.factor })
    }
    fn closed_form(&self, t: f64) -> ClosedForm {
        let form = self.motion.closed_form(t);
        let f = self.factor;
        let shape = match form.shape {
            Shape::Rest => Shape::Rest,
            Shape::Sinusoid {
                sin_part,
                cos_part,
                period,
            } => Shape::Sinusoid {
                sin_part: f * sin_part,
                cos_part: f * cos_part,
                period,
            },
            Shape::Polynomial {
                origin,
                coefficients,
                degree,
            } => Shape::Polynomial {
                origin,
                coefficients: coefficients.map(|c| f * c),
                degree,
            },
        };
        ClosedForm {
            until: form.until,
            shape,
            error_bound: f.abs() * form.error_bound,
        }
    }
    fn sample_interval(&self) -> Option<f64> {
        self.motion.sample_interval()
    }
}
