//! Idealised pulses of the rocking literature.

use std::f64::consts::PI;

use serde::Serialize;

use super::closed_form::{ClosedForm, Shape, MAX_DEGREE};
use super::motion::FloorMotion;

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
    fn closed_form(&self, t: f64) -> ClosedForm {
        if t < self.end() {
            let (sin_part, cos_part) = match self.shape {
                PulseShape::Antisymmetric => (self.amplitude, 0.0),
                PulseShape::Symmetric => (0.0, self.amplitude),
            };
            ClosedForm::exact(
                self.end(),
                Shape::Sinusoid {
                    sin_part,
                    cos_part,
                    period: self.period,
                },
            )
        } else {
            ClosedForm::exact(f64::INFINITY, Shape::Rest)
        }
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
        // exp(-x^2) is 0 in floating point from x^2 = 746 on: beyond, x^2 is held there, so that
        // a wavelet far from t (|tc| of 1e154 s, where x^2 overflows) gives the 0 it gives
        // nearer, not inf * 0.
        let x2 = (x * x).min(RICKER_FLAT);
        self.amplitude * (1.0 - 2.0 * x2) * (-x2).exp()
    }
    fn peak_acceleration(&self) -> f64 {
        // (1 - 2 x^2) exp(-x^2) is largest in size at x = 0.
        self.amplitude.abs()
    }
    fn kind(&self) -> &'static str {
        "ricker"
    }
    fn closed_form(&self, t: f64) -> ClosedForm {
        self.taylor_piece(t)
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

/// A value of x^2 at which exp(-x^2) is 0 in floating point (from 745.2 on), and (1 - 2 x^2) is
/// finite.
const RICKER_FLAT: f64 = 1e4;
/// Beyond |x| = RICKER_TAIL (x = pi (t - tc) / Tp) the wavelet is taken as rest: there
/// |a| <= |A| (2 x^2 - 1) exp(-x^2) <= 5.1e-20 |A|, which is the stated error bound.
const RICKER_TAIL: f64 = 7.0;
/// Width, in x, of one Taylor piece of the wavelet; the series of degree [`MAX_DEGREE`] about the
/// middle of the piece then has a remainder below 1.1e-20 |A| (see [`Ricker::taylor_piece`]).
const RICKER_PIECE: f64 = 0.3;
/// Cramer's bound: |H_n(x)| exp(-x^2/2) <= K sqrt(2^n n!) for the Hermite polynomials H_n.
const CRAMER: f64 = 1.086_435;

impl Ricker {
    /// The time at which x = pi (t - tc) / Tp takes the value `x`, s.
    fn time_at(&self, x: f64) -> f64 {
        self.center + x * self.period / PI
    }

    /// The time at which piece `index` starts (and the one before ends), s: the tails end at
    /// pieces 0 and 2 RICKER_TAIL / RICKER_PIECE.
    fn boundary(&self, index: usize) -> f64 {
        self.time_at(-RICKER_TAIL + index as f64 * RICKER_PIECE)
    }

    /// The wavelet on the piece holding `t`: rest in the tails, and in between the Taylor series
    /// of degree [`MAX_DEGREE`] about the middle of a piece 0.3 wide in x.
    ///
    /// With g(x) = (1 - 2 x^2) exp(-x^2) = -(1/2) d^2/dx^2 exp(-x^2) and
    /// d^n/dx^n exp(-x^2) = (-1)^n H_n(x) exp(-x^2), the Taylor coefficients about x0 are
    /// g^(m)(x0)/m! = -(1/2) (-1)^m (m+1)(m+2) h_(m+2)(x0) exp(-x0^2), h_n = H_n/n!, from
    /// h_(n+1) = (2 x h_n - 2 h_(n-1))/(n+1). Cramer's inequality bounds every derivative,
    /// |g^(m)| <= K sqrt(2^(m+2) (m+2)!)/2, so the remainder on |x - x0| <= r is at most
    /// |A| K sqrt(2^(n+3) (n+3)!) r^(n+1) / (2 (n+1)!) for degree n.
    pub fn taylor_piece(&self, t: f64) -> ClosedForm {
        let x = PI * (t - self.center) / self.period;
        let tail_bound = self.amplitude.abs()
            * (2.0 * RICKER_TAIL * RICKER_TAIL - 1.0)
            * (-RICKER_TAIL * RICKER_TAIL).exp();
        if x < -RICKER_TAIL && self.boundary(0) > t {
            return ClosedForm {
                until: self.boundary(0),
                shape: Shape::Rest,
                error_bound: tail_bound,
            };
        }
        if x >= RICKER_TAIL {
            return ClosedForm {
                until: f64::INFINITY,
                shape: Shape::Rest,
                error_bound: tail_bound,
            };
        }
        let pieces = (2.0 * RICKER_TAIL / RICKER_PIECE).round() as usize;
        let mut index = (((x + RICKER_TAIL) / RICKER_PIECE).floor() as usize).min(pieces - 1);
        // The piece must end after t. At the end of a piece (where a flow re-plans) x computed
        // from t can round to just below the boundary: the piece is then the next one, whose
        // own series holds from t on (t lies within rounding of its start).
        if self.boundary(index + 1) <= t {
            index += 1;
            if index == pieces {
                return ClosedForm {
                    until: f64::INFINITY,
                    shape: Shape::Rest,
                    error_bound: tail_bound,
                };
            }
        }
        let until = self.boundary(index + 1);
        let x0 = -RICKER_TAIL + (index as f64 + 0.5) * RICKER_PIECE;
        let origin = self.time_at(x0);
        // h_n = H_n(x0)/n! up to n = MAX_DEGREE + 2.
        let mut h = [0.0; MAX_DEGREE + 3];
        h[0] = 1.0;
        h[1] = 2.0 * x0;
        for n in 1..MAX_DEGREE + 2 {
            h[n + 1] = (2.0 * x0 * h[n] - 2.0 * h[n - 1]) / (n + 1) as f64;
        }
        let gauss = (-x0 * x0).exp();
        let scale = PI / self.period;
        let mut coefficients = [0.0; MAX_DEGREE + 1];
        let mut power = self.amplitude;
        for (m, c) in coefficients.iter_mut().enumerate() {
            let sign = if m % 2 == 0 { -0.5 } else { 0.5 };
            *c = power * sign * ((m + 1) * (m + 2)) as f64 * h[m + 2] * gauss;
            power *= scale;
        }
        // The remainder bound of the series on the piece (r = RICKER_PIECE / 2, and a little
        // more where rounding put t just outside it).
        let r = 0.5 * RICKER_PIECE * (1.0 + 1e-9);
        let n = MAX_DEGREE as i32;
        let factorial = |k: i32| (1..=k).map(f64::from).product::<f64>();
        let remainder = self.amplitude.abs()
            * CRAMER
            * (2f64.powi(n + 3) * factorial(n + 3)).sqrt()
            * r.powi(n + 1)
            / (2.0 * factorial(n + 1));
        ClosedForm {
            until,
            shape: Shape::Polynomial {
                origin,
                coefficients,
                degree: MAX_DEGREE,
            },
            error_bound: remainder,
        }
    }
}
