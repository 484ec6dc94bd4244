//! The paper's floor motion: a sine whose first stretch is replaced by a cubic so that the floor
//! starts at rest.

use std::f64::consts::PI;

use serde::Serialize;

use super::closed_form::ClosedForm;
use super::motion::FloorMotion;

/// The paper's excitation (book/src/model.md §8): a sine whose first `ramp` seconds are replaced by
/// a cubic c1 t + c2 t^2 + c3 t^3 chosen so that the floor starts at rest and its acceleration,
/// velocity and displacement join those of the pure sine at t = ramp.
#[derive(Debug, Clone, Serialize)]
pub struct PaperSine {
    /// A, amplitude of the sine, m/s^2.
    pub amplitude: f64,
    /// Tp, period of the sine, s.
    pub period: f64,
    /// Length of the cubic ramp at the start, s.
    pub ramp: f64,
    /// [c1, c2, c3], computed by [`PaperSine::new`].
    pub ramp_coefficients: [f64; 3],
    #[serde(skip)]
    breakpoints: [f64; 1],
}

impl PaperSine {
    /// The paper's sine of amplitude A (m/s^2) and period Tp (s), ramped in over `ramp` seconds.
    pub fn new(amplitude: f64, period: f64, ramp: f64) -> Self {
        PaperSine {
            amplitude,
            period,
            ramp,
            ramp_coefficients: ramp_cubic(amplitude, period, ramp),
            breakpoints: [ramp],
        }
    }
}

impl FloorMotion for PaperSine {
    fn period(&self) -> Option<f64> {
        Some(self.period)
    }
    fn acceleration(&self, t: f64) -> f64 {
        if t < self.ramp {
            let [c1, c2, c3] = self.ramp_coefficients;
            // + 0 leaves every value as it is but the start's: with c1 < 0, 0 times it is -0,
            // which the tables would print as "-0".
            t * (c1 + t * (c2 + t * c3)) + 0.0
        } else {
            self.amplitude * (2.0 * PI * t / self.period).sin()
        }
    }
    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
    fn peak_acceleration(&self) -> f64 {
        // The cubic's extremes on [0, ramp]: its ends and the roots of c1 + 2 c2 t + 3 c3 t^2.
        let [c1, c2, c3] = self.ramp_coefficients;
        let cubic = |t: f64| t * (c1 + t * (c2 + t * c3));
        let mut peak = self.amplitude.abs().max(cubic(self.ramp).abs());
        let discriminant = 4.0 * c2 * c2 - 12.0 * c1 * c3;
        if discriminant >= 0.0 && c3 != 0.0 {
            for sign in [-1.0, 1.0] {
                let t = (-2.0 * c2 + sign * discriminant.sqrt()) / (6.0 * c3);
                if t > 0.0 && t < self.ramp {
                    peak = peak.max(cubic(t).abs());
                }
            }
        }
        // Coefficients that overflowed make the motion meaningless: say so through the peak.
        if [c1, c2, c3].iter().all(|c| c.is_finite()) {
            peak
        } else {
            f64::INFINITY
        }
    }
    fn kind(&self) -> &'static str {
        "paper-sine"
    }
    fn closed_form(&self, t: f64) -> ClosedForm {
        if t < self.ramp {
            let [c1, c2, c3] = self.ramp_coefficients;
            ClosedForm::polynomial(0.0, &[0.0, c1, c2, c3], self.ramp)
        } else {
            ClosedForm::sine(self.amplitude, self.period)
        }
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({
            "kind": self.kind(),
            "amplitude": self.amplitude,
            "period": self.period,
            "ramp": self.ramp,
            "ramp_coefficients": self.ramp_coefficients,
        })
    }
}

/// Solves for c1..c3 such that, at t = ramp, the cubic's acceleration, velocity (from rest) and
/// displacement (from rest) equal the sine's A sin(wt), -(A/w) cos(wt) and -(A/w^2) sin(wt).
fn ramp_cubic(amplitude: f64, period: f64, ramp: f64) -> [f64; 3] {
    let w = 2.0 * PI / period;
    let t = ramp;
    let (s, c) = ((w * t).sin(), (w * t).cos());
    // Rows: acceleration, velocity, displacement of c1 t + c2 t^2 + c3 t^3 at t.
    let m = nalgebra::Matrix3::new(
        t,
        t * t,
        t.powi(3),
        t * t / 2.0,
        t.powi(3) / 3.0,
        t.powi(4) / 4.0,
        t.powi(3) / 6.0,
        t.powi(4) / 12.0,
        t.powi(5) / 20.0,
    );
    let rhs = nalgebra::Vector3::new(amplitude * s, -amplitude / w * c, -amplitude / (w * w) * s);
    // The matrix is regular for any t > 0 (its determinant is t^9 / 8640), but its entries
    // underflow for a ramp far below a second: then there are no coefficients, and NaN says so
    // through the peak (zeros would be a floor that jumps to the sine's velocity).
    let x = m
        .lu()
        .solve(&rhs)
        .unwrap_or_else(|| nalgebra::Vector3::repeat(f64::NAN));
    [x[0], x[1], x[2]]
}
