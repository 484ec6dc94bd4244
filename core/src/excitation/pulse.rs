//! Idealised pulses of the rocking literature.

use std::f64::consts::PI;

use serde::Serialize;

use super::FloorMotion;

/// Shape of a [`SinePulse`] over its cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PulseShape {
    /// a = A sin(2 pi t/Tp): antisymmetric about the middle of each cycle; the floor velocity
    /// is one-sided and returns to zero after each cycle (the "type-A", forward pulse).
    Antisymmetric,
    /// a = A cos(2 pi t/Tp): symmetric about the middle of each cycle (the "type-B" pulse).
    Symmetric,
}

/// A whole number of sine (or cosine) cycles of acceleration starting at t = 0, then rest:
/// the one-sine and one-cosine acceleration pulses with which Zhang & Makris (2001, "Rocking
/// response of free-standing blocks under cycloidal pulses", J. Eng. Mech. 127(5)) and Makris &
/// Roussos (2000, Geotechnique 50(3)) idealise near-source ground motions. `cycles` = 1 gives
/// their single pulse; more cycles give the n-cycle variants.
#[derive(Debug, Clone, Serialize)]
pub struct SinePulse {
    /// A, peak floor acceleration, m/s^2.
    pub amplitude: f64,
    /// Tp, period of one cycle, s.
    pub period: f64,
    /// Number of cycles before the floor comes to rest.
    pub cycles: f64,
    /// Sine or cosine cycles.
    pub shape: PulseShape,
    #[serde(skip)]
    breakpoints: [f64; 1],
}

impl SinePulse {
    /// `cycles` cycles of period Tp (s) and amplitude A (m/s^2), of the given shape.
    pub fn new(amplitude: f64, period: f64, cycles: f64, shape: PulseShape) -> Self {
        SinePulse {
            amplitude,
            period,
            cycles,
            shape,
            breakpoints: [cycles * period],
        }
    }

    /// End of the pulse, s.
    pub fn end(&self) -> f64 {
        self.breakpoints[0]
    }
}

impl FloorMotion for SinePulse {
    fn quiet_after(&self) -> Option<f64> {
        Some(self.end())
    }
    fn period(&self) -> Option<f64> {
        Some(self.period)
    }
    fn acceleration(&self, t: f64) -> f64 {
        if !(0.0..self.end()).contains(&t) {
            return 0.0;
        }
        let phase = 2.0 * PI * t / self.period;
        self.amplitude
            * match self.shape {
                PulseShape::Antisymmetric => phase.sin(),
                PulseShape::Symmetric => phase.cos(),
            }
    }
    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
    fn jumps_at(&self, t: f64) -> bool {
        // The pulse's own value at its end, which the floor drops from to rest: A for a cosine
        // pulse, 0 for a whole number of sine cycles.
        let phase = 2.0 * PI * self.cycles;
        let last = match self.shape {
            PulseShape::Antisymmetric => phase.sin(),
            PulseShape::Symmetric => phase.cos(),
        };
        t == self.end() && (self.amplitude * last).abs() > 1e-12 * self.amplitude.abs()
    }
    fn peak_acceleration(&self) -> f64 {
        self.amplitude.abs()
    }
    fn kind(&self) -> &'static str {
        "sine-pulse"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({
            "kind": self.kind(),
            "amplitude": self.amplitude,
            "period": self.period,
            "cycles": self.cycles,
            "shape": self.shape,
            "end": self.end(),
        })
    }
}

/// The Ricker wavelet (second derivative of a Gaussian) as floor acceleration:
/// a(t) = A (1 - 2 pi^2 f^2 (t - tc)^2) exp(-pi^2 f^2 (t - tc)^2), f = 1/Tp the peak
/// frequency of its spectrum. Ricker (1943, Geophysics 8(3)) introduced it for seismic
/// wavelets; Vassiliou & Makris (2011, Earthq. Eng. Struct. Dyn. 40(10)) use it for near-source
/// pulses acting on rocking blocks. Its peak, A, is at tc.
#[derive(Debug, Clone, Serialize)]
pub struct Ricker {
    /// A, the peak acceleration (at tc), m/s^2.
    pub amplitude: f64,
    /// Tp = 1/f, the inverse of the spectrum's peak frequency, s.
    pub period: f64,
    /// tc, the time of the peak, s.
    pub center: f64,
}

impl FloorMotion for Ricker {
    fn period(&self) -> Option<f64> {
        Some(self.period)
    }
    fn acceleration(&self, t: f64) -> f64 {
        let x = PI * (t - self.center) / self.period;
        let x2 = x * x;
        self.amplitude * (1.0 - 2.0 * x2) * (-x2).exp()
    }
    fn peak_acceleration(&self) -> f64 {
        // (1 - 2 x^2) exp(-x^2) is largest in size at x = 0.
        self.amplitude.abs()
    }
    fn kind(&self) -> &'static str {
        "ricker"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({
            "kind": self.kind(),
            "amplitude": self.amplitude,
            "period": self.period,
            "center": self.center,
        })
    }
}
