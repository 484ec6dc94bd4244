//! The floor acceleration written as closed forms, piece by piece, for the exact solver: each
//! kind of motion says what a(t) is on the stretch that starts at a given time and where that
//! stretch ends. Within a stretch the exact solver integrates the equation of motion in closed
//! form; at its end it re-anchors.

/// Highest degree of a [`Shape::Polynomial`]: the Ricker wavelet's Taylor pieces use all of it.
pub const MAX_DEGREE: usize = 18;

/// What a(t) is on one stretch of a floor motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// a = 0.
    Rest,
    /// a = sin_part sin(2 pi t / period) + cos_part cos(2 pi t / period), with t the run's own
    /// time (the phase is formed as the motion forms it, 2 pi t / period).
    Sinusoid {
        /// Coefficient of the sine, m/s^2.
        sin_part: f64,
        /// Coefficient of the cosine, m/s^2.
        cos_part: f64,
        /// Period, s.
        period: f64,
    },
    /// a = sum over j <= degree of `coefficients[j]` (t - origin)^j, m/s^2.
    Polynomial {
        /// The time the powers are taken about, s.
        origin: f64,
        /// Coefficients, m/s^(2 + j); those beyond `degree` are zero.
        coefficients: [f64; MAX_DEGREE + 1],
        /// Degree of the polynomial.
        degree: usize,
    },
}

/// The closed form of a(t) on `[from, until)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedForm {
    /// Where this closed form stops holding, s (`f64::INFINITY` when it never does).
    pub until: f64,
    /// What a(t) is there.
    pub shape: Shape,
    /// A bound on |a(t) - shape(t)| over the stretch, m/s^2: zero where the shape is the motion's
    /// own formula, the Taylor remainder where it is a truncated series (the Ricker wavelet).
    pub error_bound: f64,
}

impl ClosedForm {
    /// An exact closed form until `until`.
    pub fn exact(until: f64, shape: Shape) -> Self {
        ClosedForm {
            until,
            shape,
            error_bound: 0.0,
        }
    }

    /// a = A sin(2 pi t / Tp) for good.
    pub fn sine(amplitude: f64, period: f64) -> Self {
        ClosedForm::exact(
            f64::INFINITY,
            Shape::Sinusoid {
                sin_part: amplitude,
                cos_part: 0.0,
                period,
            },
        )
    }

    /// A polynomial about `origin` with the given low-order coefficients, exact until `until`.
    pub fn polynomial(origin: f64, low: &[f64], until: f64) -> Self {
        let mut coefficients = [0.0; MAX_DEGREE + 1];
        coefficients[..low.len()].copy_from_slice(low);
        ClosedForm::exact(
            until,
            Shape::Polynomial {
                origin,
                coefficients,
                degree: low.len().saturating_sub(1),
            },
        )
    }
}

impl Shape {
    /// a(t) from the closed form, m/s^2.
    pub fn value(&self, t: f64) -> f64 {
        match *self {
            Shape::Rest => 0.0,
            Shape::Sinusoid {
                sin_part,
                cos_part,
                period,
            } => {
                let (s, c) = (2.0 * std::f64::consts::PI * t / period).sin_cos();
                sin_part * s + cos_part * c
            }
            Shape::Polynomial {
                origin,
                coefficients,
                degree,
            } => {
                let u = t - origin;
                coefficients[..=degree]
                    .iter()
                    .rev()
                    .fold(0.0, |acc, &c| acc * u + c)
            }
        }
    }
}
