//! Floor motions. Every solver sees an excitation only through the [`FloorMotion`] trait, so new
//! kinds (recorded ground motions, pulses) need no change in any solver.

use std::f64::consts::PI;

use serde::Serialize;

/// Largest floor acceleration a model may have, m/s^2: 20 g. No earthquake record and no seismic
/// shaking table comes near it (the largest recorded ground accelerations are a few g), and far
/// beyond it the numbers stop meaning anything (a floor of 1e150 m/s^2 left one method running
/// forever).
pub const MAX_FLOOR_ACCELERATION: f64 = 20.0 * crate::base::units::STANDARD_GRAVITY;

/// True when a peak floor acceleration `peak` (m/s^2) is within [`MAX_FLOOR_ACCELERATION`]
/// (NaN is not).
pub fn within_floor_limit(peak: f64) -> bool {
    crate::base::limits::at_most(peak, MAX_FLOOR_ACCELERATION)
}

/// The rule a peak floor acceleration beyond the limit breaks, for error messages.
pub fn floor_limit_rule(peak: f64) -> String {
    let peak = if peak.is_finite() {
        format!("{peak:.6e} m/s^2")
    } else {
        "beyond the range of numbers".to_string()
    };
    format!(
        "the peak floor acceleration {peak} is beyond the limit of {} m/s^2 (20 g)",
        crate::base::format::readable(MAX_FLOOR_ACCELERATION)
    )
}

/// Smallest peak floor acceleration other than 0, m/s^2. The body's response is of the order
/// of A T^2 / (4 pi^2), and with T at least [`crate::physics::constants::MIN_PERIOD`] (1e-4 s) a peak of
/// 1e-140 m/s^2 keeps it above 1e-150 m, where its square is still a normal floating-point
/// number (from 2.2e-308 on); below, the closed forms lose their digits to underflow. No floor
/// motion is anywhere near it: 1e-140 m/s^2 is a displacement of 1e-140 m in a second.
pub const MIN_FLOOR_ACCELERATION: f64 = 1e-140;

/// True when a peak floor acceleration `peak` (m/s^2) is 0 or at least
/// [`MIN_FLOOR_ACCELERATION`].
pub fn above_floor_minimum(peak: f64) -> bool {
    peak == 0.0 || peak.abs() >= MIN_FLOOR_ACCELERATION
}

/// The rule a nonzero peak floor acceleration below the minimum breaks, for error messages.
pub fn floor_minimum_rule(peak: f64) -> String {
    format!(
        "the peak floor acceleration {} m/s^2 is neither 0 nor at least {} m/s^2: the body's \
         response would be below 1e-150 m, where floating point loses its digits",
        crate::base::format::shortest(peak.abs()),
        crate::base::format::shortest(MIN_FLOOR_ACCELERATION)
    )
}

/// Shortest period of an analytic floor motion, s: 1 ms, far above any frequency of earthquake or
/// shaking-table motion, and a motion faster than that would take the solvers millions of steps
/// per simulated second.
pub const MIN_EXCITATION_PERIOD: f64 = 1e-3;

/// A prescribed horizontal floor acceleration a(t) = u0''(t).
pub trait FloorMotion: Send + Sync {
    /// Floor acceleration at time `t` (s), m/s^2.
    fn acceleration(&self, t: f64) -> f64;

    /// Times (s, increasing) at which a(t) or one of its derivatives jumps. Adaptive solvers stop
    /// and restart there so that their order is not spoiled by integrating across a kink.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }

    /// True when a(t) itself jumps at the breakpoint `t` (not only its slope): an adaptive
    /// multistep method must then restart there, as at an event.
    fn jumps_at(&self, _t: f64) -> bool {
        false
    }

    /// Largest |a(t)| over the motion, m/s^2 (for a pulse of less than a quarter cycle, a bound).
    fn peak_acceleration(&self) -> f64;

    /// A time after which the floor is at rest for good (a(t) = 0), if there is one: the end of a
    /// pulse or a record. A solver may take the rest of the run as free motion.
    fn quiet_after(&self) -> Option<f64> {
        None
    }

    /// The period of an analytic motion (sine, pulse), s; None for records and free vibration.
    fn period(&self) -> Option<f64> {
        None
    }

    /// A short name for reports, e.g. `paper-sine`.
    fn kind(&self) -> &'static str;

    /// The parameters as understood (including derived ones), for result files.
    fn parameters(&self) -> serde_json::Value;

    /// The closed form of a(t) on the stretch of the motion that holds `t` (s, t >= 0), and where
    /// that stretch ends: the exact solver's view of the motion. It must agree with
    /// [`FloorMotion::acceleration`] to rounding (or within the stated error bound).
    fn closed_form(&self, t: f64) -> ClosedForm;

    /// The recorded ground motion this is, for its metadata and intensity measures; None for
    /// the analytic motions.
    fn recorded(&self) -> Option<&RecordedMotion> {
        None
    }

    /// The nominal length of the closed form's stretches where they are the intervals between
    /// a record's samples (its dt, s), each linear: the exact solver carries the state across
    /// such an interval by a recurrence it builds once for that length. None for other motions.
    fn sample_interval(&self) -> Option<f64> {
        None
    }
}

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

mod closed_form;
pub mod intensity;
mod pulse;
pub mod record;
mod recorded;

pub use closed_form::{ClosedForm, Shape, MAX_DEGREE};

pub use pulse::{PulseShape, Ricker, SinePulse};
pub use recorded::RecordedMotion;
