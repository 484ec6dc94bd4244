//! The closed-form solution of eq. 16 within one mode over one stretch of the floor motion.
//!
//! Within a mode eq. 16 reads x'' + c x' + k x = f(t), x = q - q_eq, f = -beta a(t), with
//! constant k and c ([`crate::physics::automaton::LinearForm`]). Two closed forms serve every motion:
//!
//! * **Oscillator form** (floor at rest, or a sinusoid): x = x_p + x_h, x_p the steady state of
//!   the sinusoid, x_h = e^(sigma tau) [C h0 + S (g0 - sigma h0)] the free motion from the
//!   anchor, sigma = -c/2, omega^2 = k - sigma^2, C = cos(omega tau), S = sin(omega tau)/omega
//!   (cosh and sinh of mu tau, mu^2 = -omega^2, when omega^2 < 0; 1 and tau when it is 0). This
//!   is e^(A tau) written out, A the mode's 2x2 matrix: (A - sigma I)^2 = -omega^2 I. It holds
//!   for any length of time, so free motion and a sine need no steps at all.
//! * **Series form** (a polynomial floor: a record's linear pieces, the ramp's cubic, the Ricker
//!   wavelet's Taylor pieces, and a sine at resonance): the Taylor series of x about the anchor,
//!   whose coefficients follow from the equation, a_(n+2) = (f_n - k a_n - c (n+1) a_(n+1)) /
//!   ((n+1)(n+2)). It is summed with compensated Horner, and a flow of this form is kept short
//!   enough (|k|^(1/2) tau, |c| tau <= 1/2) that [`SERIES_TERMS`] terms reach rounding.
//!   A flow over a record's whole interval takes its end from the exact recurrence between the
//!   record's samples instead (`step.rs`), and computes its coefficients only where a point
//!   inside it is asked for (to look for an event or an extremum, or for a sample of the
//!   history at an offset the recurrence is not kept for).

use crate::base::double_double::{
    fused, quick_two_sum, two_product, two_sum, DoubleDouble as Dd, TWO_PI,
};
use std::cell::OnceCell;
use std::f64::consts::PI;

use crate::floor::{ClosedForm, Shape, MAX_DEGREE};
use crate::physics::automaton::LinearForm;

use super::equation::{by_the_equation, SERIES_REACH};
use super::step::Propagator;

/// Terms of the series form: with rho = max(|k|^(1/2), |c|) tau <= 1/2 the first term left
/// out is below 0.5^30 / 15! of the state, far below rounding.
const SERIES_TERMS: usize = 30;
/// Largest growth exponent (|sigma| + mu) tau of a flow of the oscillator form before it is
/// re-anchored: e^30 keeps every term far from overflow.
const OSCILLATOR_REACH: f64 = 30.0;
/// How much smaller the oscillator form's bound on the derivatives (free motion and steady
/// state apart) must be than the bound on the whole state to be used instead
/// ([`Flow::derivative_bounds`]).
pub(crate) const STEADY_BOUND_GAIN: f64 = 1e3;
/// A sinusoid whose steady state amplifies it by more than this (|k - Omega^2 + i c Omega| below
/// this share of max(|k|, Omega^2)) is integrated in series form instead: at resonance the steady
/// state and the free motion cancel.
const RESONANCE_SHARE: f64 = 1e-3;

/// The state and its derivatives at one time: x (from q_eq), x', x'', x'''.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point {
    pub t: f64,
    /// q itself, m.
    pub q: f64,
    pub v: f64,
    pub acc: f64,
    pub jerk: f64,
    /// The free motion x_h and x_h' at t of a flow of the oscillator form, as
    /// [`Flow::point`] found them, for [`Flow::derivative_bounds`] (which would otherwise
    /// evaluate them again); zero for other points.
    pub free: [f64; 2],
}

/// sum c_n u^n by compensated Horner (Graillat, Langlois and Louvet 2005), as if in twice the
/// working precision: started from the highest coefficient, then stepped down through the others.
#[derive(Clone, Copy)]
struct CompensatedHorner {
    sum: f64,
    correction: f64,
}

impl CompensatedHorner {
    #[inline(always)]
    fn new(highest: f64) -> Self {
        CompensatedHorner {
            sum: highest,
            correction: 0.0,
        }
    }

    /// sum u + c, with the rounding of the product and of the sum kept.
    #[inline(always)]
    fn step(&mut self, c: f64, u: f64) {
        let (p, pe) = two_product(self.sum, u);
        let (sum, se) = two_sum(p, c);
        self.sum = sum;
        self.correction = self.correction * u + (pe + se);
    }

    #[inline(always)]
    fn value(self) -> Dd {
        Dd::new(self.sum, self.correction)
    }
}

/// What drives a flow, and how it is summed. One flow lives at a time, on the stack.
#[derive(Debug, Clone)]
enum Form {
    Oscillator(Oscillator),
    Series(Series),
}

/// The series form: the Taylor series of x about the anchor.
#[derive(Debug, Clone)]
struct Series {
    /// x and x' at the anchor, to twice the precision.
    x: Dd,
    v: Dd,
    /// The flow's length, s.
    span: f64,
    /// The forcing f as a polynomial in the time since the anchor, and its degree.
    forcing: [f64; MAX_DEGREE + 1],
    degree: usize,
    /// The coefficients, computed where a point inside the flow is first asked for (boxed:
    /// most of a record's flows never need them, [`Series::end`]).
    coefficients: OnceCell<Box<Coefficients>>,
    /// The state (x, x') at the flow's end by the exact recurrence between a record's samples
    /// (`step.rs`), where the flow is one whole interval of the record.
    end: Option<(Dd, Dd)>,
}

/// The Taylor coefficients of a flow of the series form.
#[derive(Debug, Clone)]
struct Coefficients {
    /// Terms summed: the rest lie below 2^-70 of the state over the flow.
    terms: usize,
    /// Of x about the anchor from its hi part with the forcing.
    hi: [f64; SERIES_TERMS],
    /// Of the free motion from the anchor's lo part.
    lo: [f64; SERIES_TERMS],
}

impl Series {
    /// The coefficients of the series, computed once.
    fn coefficients(&self, k: f64, c: f64) -> &Coefficients {
        self.coefficients.get_or_init(|| {
            // The coefficients of the anchor's hi part with the forcing, and of its lo part
            // without, in one loop; 1 / ((n+1)(n+2)) from a table (a division per term was most
            // of the flow's cost). The extra rounding, an ulp of each coefficient, lies within
            // the rounding the estimate books per term. The last two coefficients of each are
            // carried in variables, not read back from the arrays: the recurrence is a chain,
            // and a store read back at once lengthens each link.
            let (x, v, f) = (self.x, self.v, &self.forcing);
            // rho^n / n! below 2^-70 beyond the forcing's own terms, rho = the flow's reach.
            let rho = k.abs().sqrt().max(c.abs()) * self.span;
            let mut terms = self.degree + 3;
            let mut tail = (1..=terms).fold(1.0, |acc, n| acc * rho * RECIPROCALS[n - 1]);
            while terms < SERIES_TERMS && tail > 2f64.powi(-70) {
                terms += 1;
                tail *= rho * RECIPROCALS[terms - 1];
            }
            let terms = terms.min(SERIES_TERMS);
            let (mut hi, mut lo) = ([0.0; SERIES_TERMS], [0.0; SERIES_TERMS]);
            (hi[0], hi[1], lo[0], lo[1]) = (x.hi, v.hi, x.lo, v.lo);
            let (mut hi_n, mut hi_next, mut lo_n, mut lo_next) = (x.hi, v.hi, x.lo, v.lo);
            for n in 0..terms - 2 {
                let forcing = if n <= self.degree { f[n] } else { 0.0 };
                let hi_new = next_coefficient(forcing, k, c, n, hi_n, hi_next);
                let lo_new = next_coefficient(0.0, k, c, n, lo_n, lo_next);
                (hi[n + 2], lo[n + 2]) = (hi_new, lo_new);
                (hi_n, hi_next, lo_n, lo_next) = (hi_next, hi_new, lo_next, lo_new);
            }
            Box::new(Coefficients { terms, hi, lo })
        })
    }

    /// The forcing's value and slope at the anchor, f(0) and f'(0).
    fn linear_forcing(&self) -> [f64; 2] {
        let slope = if self.degree >= 1 {
            self.forcing[1]
        } else {
            0.0
        };
        [self.forcing[0], slope]
    }

    /// The first four coefficients of x (hi and lo parts added), without the rest.
    fn first_coefficients(&self, k: f64, c: f64) -> [f64; 4] {
        let (x, v) = (self.x, self.v);
        let [f0, f1] = self.linear_forcing();
        let hi2 = next_coefficient(f0, k, c, 0, x.hi, v.hi);
        let lo2 = next_coefficient(0.0, k, c, 0, x.lo, v.lo);
        let hi3 = next_coefficient(f1, k, c, 1, v.hi, hi2);
        let lo3 = next_coefficient(0.0, k, c, 1, v.lo, lo2);
        [x.hi + x.lo, v.hi + v.lo, hi2 + lo2, hi3 + lo3]
    }
}

/// The series' recurrence, a_(n+2) = (f_n - k a_n - c (n+1) a_(n+1)) / ((n+1)(n+2)).
#[inline(always)]
fn next_coefficient(forcing: f64, k: f64, c: f64, n: usize, a_n: f64, a_next: f64) -> f64 {
    let (cn, pair) = (c * (n + 1) as f64, RECIPROCAL_PAIRS[n]);
    (forcing - k * a_n - cn * a_next) * pair
}

/// The oscillator form: the free motion from the anchor and a sinusoid's steady state.
#[derive(Debug, Clone)]
struct Oscillator {
    sigma: f64,
    /// omega^2 = k - sigma^2.
    omega2: f64,
    /// |omega^2|^(1/2).
    omega: f64,
    /// Free motion at the anchor: x_h and x_h'.
    h0: f64,
    g0: f64,
    /// While rocking (k < 0), the free motion as a growing and a decaying exponential,
    /// x_h = a e^(growth u) + b e^(decay u): the form in which a motion that rises and returns
    /// (as the body's does between uplift and landing) is summed without cancellation.
    saddle: Option<Saddle>,
    /// Steady state x_p = xs sin(phi) + xc cos(phi), phi = 2 pi t / period.
    xs: f64,
    xc: f64,
    period: f64,
    /// 2 pi / the period, rad/s.
    big_omega: f64,
    /// 1 / the period, to twice the precision (for the phase).
    frequency_twice: Dd,
    /// Forcing f = fs sin(phi) + fc cos(phi).
    fs: f64,
    fc: f64,
    /// The steady state's amplitude A_p times Omega^2, Omega^3 and Omega^4: bounds on its
    /// derivatives ([`Flow::derivative_bounds`]).
    steady_bounds: [f64; 3],
    /// The free motion's amplitude (h0^2 + ((g0 - sigma h0)/omega)^2)^(1/2) and A_p, where
    /// [`Flow::envelope`] holds (omega^2 > 0, sigma <= 0).
    envelope: Option<(f64, f64)>,
}

/// x_h = a e^(growth u) + b e^(decay u), growth = sigma + |omega|, decay = sigma - |omega|.
#[derive(Debug, Clone, Copy)]
struct Saddle {
    a: f64,
    b: f64,
    /// a and b to twice the precision, for the state at an event.
    a_twice: Dd,
    b_twice: Dd,
    growth: f64,
    decay: f64,
}

impl Saddle {
    /// The saddle of x'' + c x' + k x = 0 (k < 0) from x_h, x_h' at the anchor, each given to
    /// twice the precision: a and b are computed to twice the precision and rounded once, so
    /// that the rounding of the anchor state is not amplified by e^(growth u).
    fn new(sigma: f64, omega: f64, h0: Dd, g0: Dd) -> Self {
        // a + b = h0, growth a + decay b = g0.
        let growth = sigma + omega;
        let decay = sigma - omega;
        let spread = Dd::from(two_sum(growth, -decay));
        let a = (g0 - h0 * decay) / spread;
        let b = (h0 * growth - g0) / spread;
        Saddle {
            a: a.value(),
            b: b.value(),
            a_twice: a,
            b_twice: b,
            growth,
            decay,
        }
    }

    /// x_h and x_h' at u to twice the precision (but for the rounding of growth and decay).
    fn at_twice(&self, u: f64) -> (Dd, Dd) {
        let up = self.a_twice * Dd::from(two_product(self.growth, u)).exp();
        let down = self.b_twice * Dd::from(two_product(self.decay, u)).exp();
        (up + down, up * self.growth + down * self.decay)
    }

    /// x_h, x_h' and the sizes of their terms at u.
    fn at(&self, u: f64) -> [f64; 4] {
        let up = self.a * (self.growth * u).exp();
        let down = self.b * (self.decay * u).exp();
        [
            up + down,
            self.growth * up + self.decay * down,
            up.abs() + down.abs(),
            (self.growth * up).abs() + (self.decay * down).abs(),
        ]
    }
}

impl Oscillator {
    /// The free motion x_h = e^(sigma u) [C h0 + S (g0 - sigma h0)] and its rate
    /// x_h' = e^(sigma u) [C g0 + S (sigma g0 - k h0)] at u, and the sizes of the terms summed
    /// for each (for the rounding estimate).
    #[inline(always)]
    fn free(&self, k: f64, u: f64) -> [f64; 4] {
        if let Some(saddle) = &self.saddle {
            return saddle.at(u);
        }
        let (cc, ss) = trig(self.omega2, self.omega, u);
        let e = (self.sigma * u).exp();
        let (h0, g0, sigma) = (self.h0, self.g0, self.sigma);
        [
            e * (cc * h0 + ss * (g0 - sigma * h0)),
            e * (cc * g0 + ss * (-k * h0 + sigma * g0)),
            e.abs() * (cc.abs() * h0.abs() + ss.abs() * (g0.abs() + sigma.abs() * h0.abs())),
            e.abs()
                * (cc.abs() * g0.abs() + ss.abs() * (k.abs() * h0.abs() + sigma.abs() * g0.abs())),
        ]
    }

    /// The steady state and the forcing at t: x_p, x_p', f and f'.
    fn steady(&self, t: f64) -> [f64; 4] {
        if self.xs == 0.0 && self.xc == 0.0 && self.fs == 0.0 && self.fc == 0.0 {
            return [0.0; 4];
        }
        let big_omega = self.big_omega;
        let (s, co) = phase(t, 0.0, self.frequency_twice);
        [
            self.xs * s + self.xc * co,
            big_omega * (self.xs * co - self.xc * s),
            self.fs * s + self.fc * co,
            big_omega * (self.fs * co - self.fc * s),
        ]
    }
}

/// The solution within one mode from an anchor state over `[anchor, until]`.
#[derive(Debug, Clone)]
pub(crate) struct Flow {
    pub anchor: f64,
    /// The anchor's time beyond the double `anchor`: an event's time found to a fraction of an
    /// ulp, so that rounding event times does not shift the rest of the motion.
    anchor_lo: f64,
    pub until: f64,
    k: f64,
    c: f64,
    /// beta, the forcing's factor: f = -beta a.
    beta: f64,
    q_eq: f64,
    /// Bounds on |f| and |f'| over the flow, m/s^2 and m/s^3.
    pub force_bound: f64,
    pub force_rate_bound: f64,
    /// Bound on |f''| over the flow, m/s^4.
    pub force_curvature_bound: f64,
    /// Bound on |f - (the closed form's f)|, m/s^2 (a truncated series of the motion).
    pub force_error: f64,
    /// |k|^(1/2) and |k|^(1/2) + |c|, 1/s, for [`Flow::derivative_bounds`] (called many times
    /// a flow).
    w: f64,
    growth_rate: f64,
    form: Form,
}

impl Flow {
    /// The flow of `linear` from state (q, q') at time `anchor` + `anchor_lo` (|anchor_lo| below
    /// an ulp of `anchor`), under the floor's closed form `floor`, ending at `end` at the latest
    /// (the end of the stretch or of the run). `step`: the exact recurrence over a record's
    /// interval for this mode, which gives the state at the flow's end where the flow is one
    /// whole interval.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        linear: &LinearForm,
        floor: &ClosedForm,
        anchor: f64,
        anchor_lo: f64,
        q: Dd,
        v: Dd,
        end: f64,
        step: Option<&Propagator>,
    ) -> Self {
        let (k, c, beta) = (linear.stiffness, linear.damping, linear.participation);
        let q_eq = linear.equilibrium;
        // x = q - q_eq, kept compensated.
        let (x_hi, x_e) = two_sum(q.hi, -q_eq);
        let x = Dd::new(x_hi, x_e + q.lo);
        let rate = k.abs().sqrt().max(c.abs());
        let force_error = beta.abs() * floor.error_bound;
        match floor.shape {
            Shape::Rest => Self::oscillator(
                k,
                c,
                beta,
                q_eq,
                (anchor, anchor_lo),
                x,
                v,
                end,
                0.0,
                0.0,
                1.0,
                force_error,
            ),
            Shape::Sinusoid {
                sin_part,
                cos_part,
                period,
            } => {
                let big_omega = 2.0 * PI / period;
                let detuning = (k - big_omega * big_omega).hypot(c * big_omega);
                if detuning > RESONANCE_SHARE * k.abs().max(big_omega * big_omega) {
                    Self::oscillator(
                        k,
                        c,
                        beta,
                        q_eq,
                        (anchor, anchor_lo),
                        x,
                        v,
                        end,
                        -beta * sin_part,
                        -beta * cos_part,
                        period,
                        force_error,
                    )
                } else {
                    // The sine's Taylor series about the anchor, as a polynomial floor.
                    let (s, co) = phase(anchor, anchor_lo, 1.0 / Dd::exact(period));
                    let mut coefficients = [0.0; MAX_DEGREE + 1];
                    let mut scale = 1.0;
                    // d^n/dt^n of sin(phi) and cos(phi): rotate by a quarter turn per order.
                    let (mut ds, mut dc) = (s, co);
                    for (n, coefficient) in coefficients.iter_mut().enumerate() {
                        *coefficient = (sin_part * ds + cos_part * dc) * scale;
                        (ds, dc) = (dc, -ds);
                        scale *= big_omega / (n + 1) as f64;
                    }
                    let reach = SERIES_REACH / rate.max(big_omega);
                    // Remainder of the sine's series of degree MAX_DEGREE over the flow.
                    let remainder = (sin_part.abs() + cos_part.abs())
                        * (big_omega * reach).powi(MAX_DEGREE as i32 + 1)
                        / (1..=MAX_DEGREE + 1).map(|i| i as f64).product::<f64>();
                    Self::series(
                        k,
                        c,
                        beta,
                        q_eq,
                        (anchor, anchor_lo),
                        x,
                        v,
                        end.min(anchor + reach),
                        anchor,
                        &coefficients,
                        MAX_DEGREE,
                        force_error + beta.abs() * remainder,
                        None,
                    )
                }
            }
            Shape::Polynomial {
                origin,
                coefficients,
                degree,
            } => {
                let reach = SERIES_REACH / rate.max(1e-300);
                Self::series(
                    k,
                    c,
                    beta,
                    q_eq,
                    (anchor, anchor_lo),
                    x,
                    v,
                    end.min(anchor + reach),
                    origin,
                    &coefficients,
                    degree,
                    force_error,
                    step,
                )
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn oscillator(
        k: f64,
        c: f64,
        beta: f64,
        q_eq: f64,
        (anchor, anchor_lo): (f64, f64),
        x: Dd,
        v: Dd,
        end: f64,
        fs: f64,
        fc: f64,
        period: f64,
        force_error: f64,
    ) -> Self {
        let sigma = -0.5 * c;
        let omega2 = k - sigma * sigma;
        let omega = omega2.abs().sqrt();
        let big_omega = 2.0 * PI / period;
        // Steady state: (k - W^2) xs - c W xc = fs, (k - W^2) xc + c W xs = fc.
        let (xs, xc) = if fs == 0.0 && fc == 0.0 {
            (0.0, 0.0)
        } else {
            let d = k - big_omega * big_omega;
            let e = c * big_omega;
            let det = d * d + e * e;
            ((d * fs + e * fc) / det, (d * fc - e * fs) / det)
        };
        let frequency_twice = 1.0 / Dd::exact(period);
        let (s, co) = phase(anchor, 0.0, frequency_twice);
        // The steady state at anchor + anchor_lo: one Taylor step from the anchor's double.
        let xp = xs * s + xc * co;
        let vp = big_omega * (xs * co - xc * s);
        let (xp, vp) = (
            xp + vp * anchor_lo,
            vp - big_omega * big_omega * xp * anchor_lo,
        );
        let h0 = (x.hi - xp) + x.lo;
        let g0 = (v.hi - vp) + v.lo;
        let saddle = (k < 0.0 && omega2 < 0.0).then(|| {
            let h0 = Dd::from(two_sum(x.hi, -xp)) + x.lo;
            let g0 = Dd::from(two_sum(v.hi, -vp)) + v.lo;
            Saddle::new(sigma, omega, h0, g0)
        });
        let growth = sigma.abs() + if omega2 < 0.0 { omega } else { 0.0 };
        let until = if growth > 0.0 {
            end.min(anchor + OSCILLATOR_REACH / growth)
        } else {
            end
        };
        let amplitude = fs.hypot(fc);
        let steady = (xs * xs + xc * xc).sqrt();
        let steady_bounds = [2, 3, 4].map(|n| steady * big_omega.powi(n));
        let envelope = (omega2 > 0.0 && sigma <= 0.0).then(|| {
            let b = (g0 - sigma * h0) / omega;
            ((h0 * h0 + b * b).sqrt(), steady)
        });
        let w = k.abs().sqrt();
        Flow {
            anchor,
            anchor_lo,
            until,
            k,
            c,
            beta,
            q_eq,
            force_bound: amplitude + force_error,
            force_rate_bound: amplitude * big_omega,
            force_curvature_bound: amplitude * big_omega * big_omega,
            force_error,
            w,
            growth_rate: w + c.abs(),
            form: Form::Oscillator(Oscillator {
                sigma,
                omega2,
                omega,
                h0,
                g0,
                saddle,
                xs,
                xc,
                period,
                big_omega,
                frequency_twice,
                fs,
                fc,
                steady_bounds,
                envelope,
            }),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn series(
        k: f64,
        c: f64,
        beta: f64,
        q_eq: f64,
        (anchor, anchor_lo): (f64, f64),
        x: Dd,
        v: Dd,
        until: f64,
        origin: f64,
        floor: &[f64; MAX_DEGREE + 1],
        degree: usize,
        force_error: f64,
        step: Option<&Propagator>,
    ) -> Self {
        // The forcing f = -beta a as a polynomial in u = t - anchor (Taylor shift from origin).
        let shift = (anchor - origin) + anchor_lo;
        let mut f = [0.0; MAX_DEGREE + 1];
        f[..=degree].copy_from_slice(&floor[..=degree]);
        for i in 0..degree {
            for j in (i..degree).rev() {
                f[j] += shift * f[j + 1];
            }
        }
        for value in f[..=degree].iter_mut() {
            *value *= -beta;
        }
        let span = (until - anchor).max(0.0);
        // A whole interval of a record, from its sample on: the exact recurrence gives its end.
        let end = step
            .filter(|p| degree <= 1 && shift == 0.0 && p.serves(k, c, span, until))
            .map(|p| p.advance(x, v, [f[0], f[1]], span));
        let force_bound = f[..=degree]
            .iter()
            .rev()
            .fold(0.0, |acc: f64, value| acc * span + value.abs());
        let force_rate_bound = (1..=degree)
            .rev()
            .fold(0.0, |acc: f64, j| acc * span + j as f64 * f[j].abs());
        let force_curvature_bound = (2..=degree).rev().fold(0.0, |acc: f64, j| {
            acc * span + (j * (j - 1)) as f64 * f[j].abs()
        });
        Flow {
            anchor,
            anchor_lo,
            until,
            k,
            c,
            beta,
            q_eq,
            force_bound: force_bound + force_error,
            force_rate_bound,
            force_curvature_bound,
            force_error,
            w: k.abs().sqrt(),
            growth_rate: k.abs().sqrt() + c.abs(),
            form: Form::Series(Series {
                x,
                v,
                span,
                forcing: f,
                degree,
                coefficients: OnceCell::new(),
                end,
            }),
        }
    }

    /// Time since the anchor.
    fn local(&self, t: f64) -> f64 {
        (t - self.anchor) - self.anchor_lo
    }

    /// The mode's k.
    pub fn stiffness(&self) -> f64 {
        self.k
    }

    /// The mode's c.
    pub fn damping(&self) -> f64 {
        self.c
    }

    /// The state (q, q') at `t`, compensated: the next flow's anchor.
    pub fn state(&self, t: f64) -> (Dd, Dd) {
        self.state_with(t, || self.point(t))
    }

    /// [`Flow::state`] at the time of `p`, a point of this flow ([`Flow::point`]), which the
    /// oscillator form's state is.
    pub fn state_at(&self, p: &Point) -> (Dd, Dd) {
        self.state_with(p.t, || *p)
    }

    /// [`Flow::state`] at `t`, with `point()` the flow's point there.
    fn state_with(&self, t: f64, point: impl FnOnce() -> Point) -> (Dd, Dd) {
        let u = self.local(t);
        match &self.form {
            Form::Series(Series {
                end: Some((x, v)), ..
            }) if t == self.until => (*x + self.q_eq, *v),
            Form::Series(series) => {
                let Coefficients { terms, hi, lo } = series.coefficients(self.k, self.c);
                let terms = *terms;
                series_state(&hi[..terms], &lo[..terms], u, self.q_eq)
            }
            Form::Oscillator(_) => {
                let p = point();
                (Dd::exact(p.q), Dd::exact(p.v))
            }
        }
    }

    /// q and q' at `t` to twice the precision where the flow's form allows (the series, and
    /// the free motion while rocking, whose terms nearly cancel when the body barely lifts off),
    /// else as [`Flow::point`]: the state at an event, from which the motion goes on.
    pub fn state_at_event(&self, t: f64) -> (Dd, Dd) {
        match &self.form {
            Form::Oscillator(o) => match &o.saddle {
                Some(saddle) => {
                    let (x, v) = saddle.at_twice(self.local(t));
                    let [xp, vp, _, _] = o.steady(t);
                    (x + xp + self.q_eq, v + vp)
                }
                None => {
                    let p = self.point(t);
                    (Dd::exact(p.q), Dd::exact(p.v))
                }
            },
            Form::Series(_) => {
                let (q, v) = self.state(t);
                (Dd::new(q.hi, q.lo), Dd::new(v.hi, v.lo))
            }
        }
    }

    /// q, q', q'' and q''' at `t`.
    pub fn point(&self, t: f64) -> Point {
        self.point_with_force(t).0
    }

    /// The point at `t`, and the forcing f and f' there for the oscillator form (zero for the
    /// series form, whose forcing is a polynomial the work integrals read directly).
    #[inline]
    pub fn point_with_force(&self, t: f64) -> (Point, [f64; 2]) {
        let u = self.local(t);
        let (k, c) = (self.k, self.c);
        match &self.form {
            Form::Oscillator(o) => {
                let [xh, vh, _, _] = o.free(k, u);
                let [xp, vp, f, df] = o.steady(t);
                let x = xh + xp;
                let v = vh + vp;
                let (acc, jerk) = by_the_equation(k, c, [f, df], x, v);
                (
                    Point {
                        t,
                        q: x + self.q_eq,
                        v,
                        acc,
                        jerk,
                        free: [xh, vh],
                    },
                    [f, df],
                )
            }
            Form::Series(series) if u == 0.0 => {
                // At the anchor (a flow that starts on a record's sample): the first
                // coefficients, as the sums below give them there.
                let a = series.first_coefficients(k, c);
                (
                    Point {
                        t,
                        q: a[0] + self.q_eq,
                        v: a[1],
                        acc: 2.0 * a[2],
                        jerk: 3.0 * (2.0 * a[3]),
                        free: [0.0; 2],
                    },
                    [0.0; 2],
                )
            }
            Form::Series(
                series @ Series {
                    end: Some((x, v)), ..
                },
            ) if t == self.until => {
                // A record's whole interval: its end from the exact recurrence.
                self.point_from_state(t, x.value(), v.value(), series.linear_forcing())
            }
            Form::Series(series) => {
                let Coefficients { terms, hi, lo } = series.coefficients(k, c);
                let terms = *terms;
                // x and its first three derivatives by Horner, hi and lo together.
                let mut d = [0.0; 4];
                for n in (0..terms).rev() {
                    let a = hi[n] + lo[n];
                    d[3] = d[3] * u + d[2] * 3.0;
                    d[2] = d[2] * u + d[1] * 2.0;
                    d[1] = d[1] * u + d[0];
                    d[0] = d[0] * u + a;
                }
                // x itself from its hi part with the anchor's lo part added apart, so that the
                // anchor's extra precision is not lost in the sum.
                let x = horner(&hi[..terms], u) + horner(&lo[..terms], u);
                (
                    Point {
                        t,
                        q: x + self.q_eq,
                        v: d[1],
                        acc: d[2],
                        jerk: d[3],
                        free: [0.0; 2],
                    },
                    [0.0; 2],
                )
            }
        }
    }

    /// For a flow that is one whole interval of a record (whose end the exact recurrence gives,
    /// `step.rs`): x and x' at its anchor and the forcing's value and slope there.
    pub fn interval_data(&self) -> Option<(Dd, Dd, [f64; 2])> {
        match &self.form {
            Form::Series(series @ Series { end: Some(_), .. }) => {
                Some((series.x, series.v, series.linear_forcing()))
            }
            _ => None,
        }
    }

    /// The point at `t` of a flow that is a record's whole interval ([`Flow::interval_data`]),
    /// from x and x' there (by the exact recurrence) and the forcing's value and slope at the
    /// anchor: x'' and x''' by the equation.
    pub fn point_from_state(
        &self,
        t: f64,
        x: f64,
        v: f64,
        [f0, f1]: [f64; 2],
    ) -> (Point, [f64; 2]) {
        let force = [f0 + f1 * self.local(t), f1];
        let (acc, jerk) = by_the_equation(self.k, self.c, force, x, v);
        (
            Point {
                t,
                q: x + self.q_eq,
                v,
                acc,
                jerk,
                free: [0.0; 2],
            },
            [0.0; 2],
        )
    }

    /// The integrals of f x' and of x'^2 over the piece `[end.t - h, end.t]`, from the Taylor
    /// series of the motion about its end, given by the piece's [`Flow::work_data`] (from the
    /// point at the end, with the forcing there as [`Flow::point_with_force`] gives it): the
    /// coefficients follow from x and x' there by the
    /// equation, a_(n+2) = (f_n - k a_n - c (n+1) a_(n+1)) / ((n+1)(n+2)), and the products are
    /// integrated term by term. No closed form is evaluated inside the piece, and the series is
    /// cut where its terms fall below 1e-17 of the state (h times the flow's rate at most
    /// [`WORK_REACH`]).
    pub fn work_integrals(&self, data: &[f64], h: f64) -> (f64, f64) {
        let terms = self.work_terms(h);
        let (f, v) = self.work_series(data, h, terms);
        let (f, v) = (&f[..terms], &v[..terms]);
        // Integrate over sigma in [0, 1] (s = -h sigma): sum of v_i w_j / (i + j + 1).
        let (mut force_work, mut square) = (0.0, 0.0);
        for (i, (&fi, &vi)) in f.iter().zip(v).enumerate() {
            // sum_j v_j / (i + j + 1) over every j (fv) and over j >= i (vv): two sums in one
            // loop, each in the order of j from -0 (as `sum` adds), so that they run side by
            // side.
            let (mut fv, mut vv) = (-0.0, -0.0);
            for (j, (&vj, &w)) in v.iter().zip(&RECIPROCALS[i..]).enumerate() {
                let term = vj * w;
                fv += term;
                if j >= i {
                    vv += term;
                }
            }
            force_work += fi * fv;
            // v_i v_j twice for j > i, once for j = i.
            square += vi * (2.0 * vv - vi * RECIPROCALS[2 * i]);
        }
        // v was scaled by -h (x' = v / -h), and ds = h d sigma.
        (-force_work, square / h)
    }

    /// What the work integrals over a piece depend on besides its length and the data at its
    /// end ([`Flow::work_data`]): the flow's k and c, and the kind of its forcing.
    pub fn work_key(&self) -> WorkKey {
        let (period, degree) = match &self.form {
            Form::Oscillator(o) => (o.period, None),
            Form::Series(Series { degree, .. }) => (0.0, Some(*degree)),
        };
        WorkKey {
            k: self.k,
            c: self.c,
            period,
            degree,
        }
    }

    /// The data at the end of a piece that its work integrals follow from, linearly through
    /// the series: x and x' there, then the forcing there, f and f' for the oscillator form
    /// (f'' = -Omega^2 f gives the rest), and for the series form the polynomial's Taylor
    /// coefficients about the end, f^(n)(end)/n!. Its length is [`WorkKey::len`], at most N.
    #[inline]
    pub fn work_data<const N: usize>(&self, end: &Point, force: [f64; 2]) -> [f64; N] {
        let mut data = [0.0; N];
        data[0] = end.q - self.q_eq;
        data[1] = end.v;
        match &self.form {
            Form::Oscillator(_) => {
                data[2] = force[0];
                data[3] = force[1];
            }
            Form::Series(Series {
                forcing, degree, ..
            }) => {
                // Taylor shift of the polynomial from the anchor to the end.
                let u = self.local(end.t);
                let shifted = &mut data[2..=*degree + 2];
                shifted.copy_from_slice(&forcing[..=*degree]);
                for i in 0..*degree {
                    for j in (i..*degree).rev() {
                        shifted[j] += u * shifted[j + 1];
                    }
                }
            }
        }
        data
    }

    /// Terms of the work integrals' series over a piece of length `h`.
    pub fn work_terms(&self, h: f64) -> usize {
        let (k, c) = (self.k, self.c);
        // The series' terms shrink as (lambda h)^n / n!, lambda the free motion's rates
        // (|lambda| <= |c|/2 + (c^2/4 + |k|)^(1/2)) or the forcing's.
        let free = 0.5 * c.abs() + (0.25 * c * c + k.abs()).sqrt();
        let rho = match &self.form {
            Form::Oscillator(o) => free.max(o.big_omega),
            Form::Series(_) => free,
        } * h;
        let mut terms = 4;
        let mut tail = rho.powi(4) / 24.0;
        while terms < WORK_TERMS && tail > 1e-17 {
            terms += 1;
            tail *= rho * RECIPROCALS[terms - 1];
        }
        // A polynomial forcing's every coefficient enters (those of x up to its degree + 2): the
        // bound above follows the free motion's rates, and a polynomial can change faster (the
        // Ricker wavelet's pieces of degree 18 under a slow rocking motion).
        if let Form::Series(Series { degree, .. }) = &self.form {
            terms = terms.max((degree + 2).min(WORK_TERMS));
        }
        terms
    }

    /// The first `terms` Taylor coefficients of f and of x' about the end of a piece of length
    /// `h`, scaled by (-h)^n (x' also by -h), from the piece's [`Flow::work_data`]. Both are
    /// linear in the data.
    pub fn work_series(
        &self,
        data: &[f64],
        h: f64,
        terms: usize,
    ) -> ([f64; WORK_TERMS], [f64; WORK_TERMS]) {
        let (k, c) = (self.k, self.c);
        // The forcing's Taylor coefficients about the end, scaled by (-h)^n.
        let mut f = [0.0; WORK_TERMS];
        match &self.form {
            Form::Oscillator(o) => {
                let big_omega = o.big_omega;
                // f^(2m) = (-W^2)^m f, f^(2m+1) = (-W^2)^m f'.
                let (mut even, mut odd) = (data[2], data[3] * -h);
                let step = -(big_omega * h) * (big_omega * h);
                for n in (0..terms).step_by(2) {
                    f[n] = even;
                    f[n + 1] = odd;
                    even *= step * RECIPROCAL_PAIRS[n];
                    odd *= step * RECIPROCAL_PAIRS[n + 1];
                }
            }
            Form::Series(Series { degree, .. }) => {
                let mut scale = 1.0;
                for n in 0..=(*degree).min(terms - 1) {
                    f[n] = data[2 + n] * scale;
                    scale *= -h;
                }
            }
        }
        // x's coefficients scaled by (-h)^n: a_(n+2) h^2 from the equation, and x' scaled by
        // -h, (n+1) a_(n+1).
        let (kh2, ch, h2) = (k * h * h, c * -h, h * h);
        let mut v = [0.0; WORK_TERMS];
        let (mut a0, mut a1) = (data[0], data[1] * -h);
        v[0] = a1;
        for n in 0..terms - 1 {
            let a2 = (f[n] * h2 - kh2 * a0 - ch * (n + 1) as f64 * a1) * RECIPROCAL_PAIRS[n];
            v[n + 1] = (n + 2) as f64 * a2;
            (a0, a1) = (a1, a2);
        }
        (f, v)
    }

    /// The fastest rate of the flow, 1/s: of its free motion and of its forcing.
    pub fn rate(&self) -> f64 {
        let free = self.k.abs().sqrt().max(self.c.abs());
        match &self.form {
            Form::Oscillator(o) => free.max(o.big_omega),
            Form::Series(_) => free,
        }
    }

    /// Whether the flow's points give their free motion apart ([`Point::free`]): the oscillator
    /// form does, the series form sums the free and the forced motion as one.
    pub fn splits_free_motion(&self) -> bool {
        matches!(self.form, Form::Oscillator(_))
    }

    /// The mode's q_eq.
    pub fn equilibrium(&self) -> f64 {
        self.q_eq
    }

    /// Bounds on |x''| and |x'''| over `[t0, t0 + h]` from the state at t0: the free motion
    /// grows at most as e^((|k|^(1/2) + |c|) h) in the energy norm, and the forcing adds at most
    /// h max|f| to it.
    ///
    /// In the oscillator form a second bound holds: the steady state's derivatives are known
    /// exactly (a sinusoid of amplitude A_p, |x_p^(n)| <= A_p Omega^n), so the growth bound need
    /// apply to the free motion alone. Where the steady state dominates (a stiff body under a
    /// slow floor: a quasi-static lean far larger than its free motion), the first bound would
    /// make the body look as fast as its own frequency times the whole state, and the search
    /// would cut its monotone pieces a million times too short. Both bounds hold; the second is
    /// taken where it is at least [`STEADY_BOUND_GAIN`] times smaller, so that elsewhere the
    /// search (and the last bits of the event times it finds) stays as it was.
    /// `p` must be a point of this flow ([`Flow::point`], or one with only q changed).
    pub fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64) {
        let (c, w, rate) = (self.c, self.w, self.growth_rate);
        let growth = (rate * h).exp();
        let x0 = p.q - self.q_eq;
        let z0 = (w * w * x0 * x0 + p.v * p.v).sqrt();
        let z = growth * (z0 + h * self.force_bound);
        let m2 = rate * z + self.force_bound;
        let m3 = w * w * z + c.abs() * m2 + self.force_rate_bound;
        // The fourth derivative is f'' - k x'' - c x''' by the equation.
        let m4 = w * w * m2 + c.abs() * m3 + self.force_curvature_bound;
        let safe = 1.0 + 1e-9;
        if let Form::Oscillator(o) = &self.form {
            let [xh, vh] = p.free;
            debug_assert_eq!(
                [xh, vh].map(f64::to_bits),
                {
                    let [xh, vh, _, _] = o.free(self.k, self.local(p.t));
                    [xh, vh].map(f64::to_bits)
                },
                "a point of another flow"
            );
            let zh = growth * (w * w * xh * xh + vh * vh).sqrt();
            let h2 = rate * zh;
            let h3 = w * w * zh + c.abs() * h2;
            let h4 = w * w * h2 + c.abs() * h3;
            // Plus the rounding of the sum of the two parts: a few ulps of each.
            let split = |free: f64, steady: f64| (free + steady) * (1.0 + 16.0 * f64::EPSILON);
            let [p2, p3, p4] = o.steady_bounds;
            let (s2, s3, s4) = (split(h2, p2), split(h3, p3), split(h4, p4));
            if s2 * STEADY_BOUND_GAIN <= m2 && s2.is_finite() && s3.is_finite() && s4.is_finite() {
                return (s2 * safe, s3 * safe, s4 * safe);
            }
        }
        (m2 * safe, m3 * safe, m4 * safe)
    }

    /// Bounds on the second, third and fourth derivatives of z = b x_r - a x_l over
    /// `[t0, t0 + h]`, for the flows and points `left` = (flow, point at t0, a) and `right` = (…,
    /// b) of one equation (the same k and c; None otherwise): z is then itself a flow of it,
    /// z'' + c z' + k z = b f_r - a f_l, its forcing -(b beta_r - a beta_l) times the floor's
    /// acceleration, and [`Flow::derivative_bounds`] holds for it from z's own state. Two
    /// columns that move alike have a small z however large their own motions; their forcings
    /// are taken as cancelling only in value (each within its closed form's error), not in
    /// their rates.
    pub fn combined_bounds(
        left: (&Flow, &Point, f64),
        right: (&Flow, &Point, f64),
        h: f64,
    ) -> Option<(f64, f64, f64)> {
        let ((fl, pl, a), (fr, pr, b)) = (left, right);
        if fl.k != fr.k || fl.c != fr.c {
            return None;
        }
        let (k, c) = (fl.k, fl.c);
        let w = k.abs().sqrt();
        let (xl, xr) = (pl.q - fl.q_eq, pr.q - fr.q_eq);
        let (z, v) = (b * xr - a * xl, b * pr.v - a * pl.v);
        // The rounding of z's state, formed from the two: a few ulps of each term.
        let rounding = 4.0
            * f64::EPSILON
            * (w * (b.abs() * xr.abs() + a.abs() * xl.abs())
                + b.abs() * pr.v.abs()
                + a.abs() * pl.v.abs());
        let z0 = (w * w * z * z + v * v).sqrt() + rounding;
        // |a(t)| at most the larger of the two flows' own bounds over beta.
        let floor = |f: &Flow| f.force_bound / f.beta.abs().max(f64::MIN_POSITIVE);
        let force = (b * fr.beta - a * fl.beta).abs() * floor(fl).max(floor(fr))
            + b.abs() * fr.force_error
            + a.abs() * fl.force_error;
        let growth = ((w + c.abs()) * h).exp() * (z0 + h * force);
        let m2 = (w + c.abs()) * growth + force;
        let m3 = w * w * growth
            + c.abs() * m2
            + b.abs() * fr.force_rate_bound
            + a.abs() * fl.force_rate_bound;
        let m4 = w * w * m2
            + c.abs() * m3
            + b.abs() * fr.force_curvature_bound
            + a.abs() * fl.force_curvature_bound;
        let safe = 1.0 + 1e-9;
        Some((m2 * safe, m3 * safe, m4 * safe))
    }

    /// A bound on |x - x_p| (the free motion) over the rest of an oscillator flow from `t0`
    /// on, and |x_p|; None for other flows. Before uplift with c >= 0 the free motion's
    /// amplitude never grows: |x_h| <= e^(sigma u) (h0^2 + ((g0 - sigma h0)/omega)^2)^(1/2).
    pub fn envelope(&self, t0: f64) -> Option<f64> {
        match &self.form {
            Form::Oscillator(Oscillator {
                envelope: Some((r, steady)),
                sigma,
                ..
            }) => {
                let u = self.local(t0).max(0.0);
                Some((sigma * u).exp() * r * (1.0 + 1e-12) + steady)
            }
            _ => None,
        }
    }

    /// The size of the terms q at `t` is summed from, m: q_eq, and the free motion's and the
    /// steady state's terms (oscillator form) or x itself (series form). One evaluation of q
    /// rounds to a few ulps of it, which near resonance (the steady state and the free motion
    /// nearly cancelling) is far more than a few ulps of q.
    pub fn term_size(&self, t: f64) -> f64 {
        let x = match &self.form {
            Form::Oscillator(o) => o.free(self.k, self.local(t))[2] + o.xs.hypot(o.xc),
            Form::Series(_) => (self.point(t).q - self.q_eq).abs(),
        };
        self.q_eq.abs() + x
    }

    /// An estimate of the rounding error of the state carried to `t` (in |x| + |x'| / |k|^(1/2)):
    /// unit roundoff times the size of the terms summed and of the phases formed. The rounding
    /// of one evaluation of a point, a few ulps of its q, is booked apart where it is used.
    pub fn rounding(&self, t: f64) -> f64 {
        let u = self.local(t);
        let w = self.k.abs().sqrt().max(1e-300);
        let size = match &self.form {
            Form::Oscillator(o) => {
                let [_, _, x_size, v_size] = o.free(self.k, u);
                let free = x_size + v_size / w;
                let steady = o.xs.hypot(o.xc) * (1.0 + 2.0 * PI / o.period / w);
                // Phases: omega u and 2 pi t / Tp carry relative errors of a few ulps.
                free * (1.0 + (o.omega + o.sigma.abs()) * u.abs())
                    + steady * (1.0 + 2.0 * PI * t.abs() / o.period)
            }
            Form::Series(series) => {
                // Carried compensated: only the rounding of the coefficients beyond the anchor's
                // own (each a few ulps) is left (a record's interval carried by the exact
                // recurrence has less: its coefficients are carried to twice the precision).
                let Coefficients { terms, hi, .. } = series.coefficients(self.k, self.c);
                let x = horner_abs(&hi[2..*terms], u.abs()) * u * u;
                x * (1.0 + 1.0 / w)
            }
        };
        // The response to the forcing's stated error (a truncated series of the motion).
        let forcing = self.force_error * u.abs() * (u.abs() + 1.0 / w);
        ROUNDING_ULPS * f64::EPSILON * size + forcing
    }
}

/// Most terms of the series of the work integrals.
pub(crate) const WORK_TERMS: usize = 24;
/// Longest data of a piece ([`Flow::work_data`]): x, x' and a polynomial forcing's every
/// coefficient.
pub(crate) const WORK_DATA: usize = MAX_DEGREE + 3;

/// What a flow's work integrals depend on besides a piece's length and the data at its end
/// ([`Flow::work_key`]): flows with equal keys have the same integrals over pieces of one length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct WorkKey {
    pub k: f64,
    pub c: f64,
    /// A sinusoid's period, s (oscillator form).
    period: f64,
    /// A polynomial's degree (series form).
    degree: Option<usize>,
}

impl WorkKey {
    /// The length of the flow's [`Flow::work_data`].
    pub fn len(&self) -> usize {
        match self.degree {
            None => 4,
            Some(degree) => degree + 3,
        }
    }
}
/// 1 / (n + 1).
pub(crate) const RECIPROCALS: [f64; 2 * SERIES_TERMS] = {
    let mut r = [0.0; 2 * SERIES_TERMS];
    let mut n = 0;
    while n < r.len() {
        r[n] = 1.0 / (n + 1) as f64;
        n += 1;
    }
    r
};
/// 1 / ((n + 1)(n + 2)).
const RECIPROCAL_PAIRS: [f64; SERIES_TERMS] = {
    let mut r = [0.0; SERIES_TERMS];
    let mut n = 0;
    while n < r.len() {
        r[n] = 1.0 / ((n + 1) * (n + 2)) as f64;
        n += 1;
    }
    r
};
/// Longest piece of a work integral, in units of 1 / (the flow's fastest rate): with
/// |lambda| h <= 1 the series' 19th term is below 1e-17.
pub(super) const WORK_REACH: f64 = 0.5;

/// Multiple of the unit roundoff per summed term that the rounding estimate books.
const ROUNDING_ULPS: f64 = 8.0;

/// C and S of the oscillator form at u.
fn trig(omega2: f64, omega: f64, u: f64) -> (f64, f64) {
    if omega2 > 0.0 {
        let (s, c) = (omega * u).sin_cos();
        (c, if omega > 0.0 { s / omega } else { u })
    } else if omega2 < 0.0 {
        let y = omega * u;
        (y.cosh(), y.sinh() / omega)
    } else {
        (1.0, u)
    }
}

fused! {
    /// The state (q, q') at u of the series form with coefficients `hi` + `lo` (of x = q - q_eq),
    /// compensated: the next flow's anchor.
    fn series_state(hi: &[f64], lo: &[f64], u: f64, q_eq: f64) -> (Dd, Dd) {
        // x = sum hi_i u^i and v = sum i hi_i u^(i-1), each by compensated Horner's rule, in
        // one loop so that the two chains of products run side by side.
        let top = hi.len().saturating_sub(1);
        let mut x = CompensatedHorner::new(hi.get(top).copied().unwrap_or(0.0));
        let mut v = CompensatedHorner::new(if top >= 1 { top as f64 * hi[top] } else { 0.0 });
        for i in (0..top).rev() {
            x.step(hi[i], u);
            if i >= 1 {
                v.step(i as f64 * hi[i], u);
            }
        }
        let (x, v) = (x.value(), v.value());
        let xl = horner(lo, u);
        let vl = derivative(lo).rev().fold(0.0, |acc, value| acc * u + value);
        let (q_hi, q_e) = two_sum(x.hi, q_eq);
        (Dd::new(q_hi, q_e + x.lo + xl), Dd::new(v.hi, v.lo + vl))
    }
}

fused! {
    /// sin and cos of 2 pi (t + t_lo) f, f = 1/period to twice the precision. The angle is
    /// reduced to a fraction of a turn in twice the precision before the double functions see
    /// it: over a long run the rounding of 2 pi t/period itself (an ulp of the angle) would be an
    /// error of the phase of the forcing, and near resonance the steady state it moves is many
    /// times the motion.
    fn phase(t: f64, t_lo: f64, frequency: Dd) -> (f64, f64) {
        let fraction = if t_lo == 0.0 {
            fraction_of_turn(t, frequency)
        } else {
            let turns = (Dd::exact(t) + t_lo) * frequency;
            turns - turns.hi.round()
        };
        let angle = TWO_PI * fraction;
        let (s, c) = angle.hi.sin_cos();
        (s + c * angle.lo, c - s * angle.lo)
    }
}

/// t f less its nearest whole number, to twice the precision, for a time t that is a double
/// (a sample's, or an anchor's without a remainder): what [`phase`]'s general arithmetic,
/// `(Dd::exact(t) + 0.0) * f - round`, gives bit for bit (tested), without its steps that only
/// add exact zeros, at a third of the cost on every sample of a history. The sum with a remainder
/// of 0 leaves t with nothing beyond it; and hi - round(hi) is exact (|hi - round(hi)| <= 1/2,
/// and round(hi) is 0 or within a factor two of hi), so the subtraction's first two-sum has no
/// error term, and the whole number's low part is 0.
#[inline(always)]
fn fraction_of_turn(t: f64, frequency: Dd) -> Dd {
    let turns = Dd::exact(t) * frequency;
    let (hi, lo) = quick_two_sum(turns.hi - turns.hi.round(), turns.lo);
    Dd { hi, lo }
}

/// The coefficients i a_i of the derivative of sum a_i u^i.
#[inline(always)]
fn derivative(a: &[f64]) -> impl DoubleEndedIterator<Item = f64> + '_ {
    a.iter()
        .enumerate()
        .skip(1)
        .map(|(i, &value)| i as f64 * value)
}

#[inline(always)]
fn horner(coefficients: &[f64], u: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |acc, &c| acc * u + c)
}

fn horner_abs(coefficients: &[f64], u: f64) -> f64 {
    coefficients
        .iter()
        .rev()
        .fold(0.0, |acc, &c| acc * u + c.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fraction of a turn at a double time is bit for bit what the general double-double
    /// arithmetic gives (`(t + 0) f - round`), for times from 0 through subnormal, whole periods
    /// and half periods to 1e9 s, and periods from a millisecond to an hour: the shortcut leaves
    /// out only additions of exact zeros.
    #[test]
    fn the_fraction_of_a_turn_is_the_general_arithmetics_bit_for_bit() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            // SplitMix64.
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut checked = 0;
        for _ in 0..2_000 {
            let period = 10f64.powf(-3.0 + 6.5 * next());
            let frequency = 1.0 / Dd::exact(period);
            let mut times = vec![0.0, -0.0, 5e-324, period, 0.5 * period, 3.0 * period];
            for _ in 0..100 {
                let scale = 10f64.powf(-6.0 + 15.0 * next());
                times.push(scale * next());
                // Near whole and half turns, where the rounding to a whole number decides.
                let turns = (1e6 * next()).round();
                times.push(turns * period);
                times.push((turns + 0.5) * period);
            }
            for t in times {
                let general = (Dd::exact(t) + 0.0) * frequency;
                let general = general - general.hi.round();
                let short = fraction_of_turn(t, frequency);
                assert_eq!(
                    (short.hi.to_bits(), short.lo.to_bits()),
                    (general.hi.to_bits(), general.lo.to_bits()),
                    "t = {t:e}, period = {period:e}: {short:?} against {general:?}"
                );
                checked += 1;
            }
        }
        assert!(checked > 500_000);
    }
}
