//! The exact recurrence between a record's samples.
//!
//! Between two samples of a record the floor's acceleration is linear, so within a mode the
//! state at the end of the interval is linear in four numbers at its start: x and x' (x = q -
//! q_eq) and the forcing's value f0 and slope f1 there (f = f0 + f1 u, f = -beta a):
//!
//! ```text
//! x(h)  = X0 x + X1 x' + X2 f0 + X3 f1,     x'(h) = V0 x + V1 x' + V2 f0 + V3 f1,
//! ```
//!
//! the classic piecewise-linear recurrence of response-spectrum computation, written for the
//! mode's 2x2 system (a saddle while rocking as well as an oscillator before uplift). Its eight
//! coefficients depend only on the mode's k and c and on the record's sample interval h, so a
//! run builds them once for each mode it meets ([`StepCache`]) and a flow from one sample to the
//! next costs eight products instead of the Taylor series of its motion. They are built from
//! the series of each unit datum, a_(n+2) = (f_n - k a_n - c (n+1) a_(n+1)) / ((n+1)(n+2)),
//! with every coefficient and every sum carried to twice the precision (the k and c of the mode
//! are the model's doubles, taken as exact), and the state is carried through the products to
//! twice the precision as well: the repeated propagation accumulates no rounding of its own
//! beyond about 1e-30 of the state per step.
//!
//! An interval differs from h by the rounding of the samples' times (k dt, rounded: up to an ulp
//! of t). That sliver, of length d, is added by the Taylor step d x' + d^2/2 x'' (and d x'' +
//! d^2/2 x''' for x'), whose remainder, of the order of d^3, lies below 1e-40 of the state.

use super::equation::{by_the_equation, SERIES_REACH};
use super::kept::Kept;
use super::rounding::near;
use crate::base::double_double::{fused, two_product, two_sum, DoubleDouble as Dd};

/// Propagators kept at once: a run meets at most three modes' forms (before uplift and rocking
/// about either toe; in a row, also those of the clusters it is held in), each over the
/// record's interval and over the offsets of the history's samples within it.
pub(crate) const KEPT: usize = 12;

/// Most terms of the series of a unit datum: with rho = max(|k|^(1/2), |c|) h <= 1/2 the terms
/// fall below 2^-112 of the first by the 27th.
const TERMS: usize = 40;

/// The state at the end of an interval of length h from the data at its start, for one mode's
/// k and c.
#[derive(Debug, Clone)]
pub(crate) struct Propagator {
    k: f64,
    c: f64,
    h: f64,
    /// x(h) and x'(h) of each unit datum: x, x', f0, f1.
    x: [Dd; 4],
    v: [Dd; 4],
}

impl Propagator {
    /// The propagator of x'' + c x' + k x = f0 + f1 u over [0, h]; None where the series would
    /// not reach rounding within [`TERMS`] terms (max(|k|^(1/2), |c|) h above the series'
    /// reach), or the numbers are not finite.
    pub fn new(k: f64, c: f64, h: f64) -> Option<Self> {
        let rho = k.abs().sqrt().max(c.abs()) * h;
        if !(rho <= SERIES_REACH && h > 0.0 && h.is_finite() && k.is_finite() && c.is_finite()) {
            return None;
        }
        let mut x = [Dd::default(); 4];
        let mut v = [Dd::default(); 4];
        for datum in 0..4 {
            let (xh, vh) = unit_response(k, c, h, datum);
            x[datum] = xh;
            v[datum] = vh;
        }
        Some(Propagator { k, c, h, x, v })
    }

    /// Whether this propagator serves a flow of `k` and `c` over an interval of length `span`
    /// ending at `t`.
    pub fn serves(&self, k: f64, c: f64, span: f64, t: f64) -> bool {
        self.k == k && self.c == c && near(span, self.h, t)
    }

    /// x and x' after `span` as [`Propagator::advance`] gives them, but each to the working
    /// precision only: a sample of the history, from which the motion does not go on.
    pub fn sample(&self, x: Dd, v: Dd, [f0, f1]: [f64; 2], span: f64) -> (f64, f64) {
        let row = |m: &[Dd; 4]| {
            m[0].hi * x.hi
                + (m[1].hi * v.hi
                    + (m[2].hi * f0 + m[3].hi * f1)
                    + (m[0].hi * x.lo + m[0].lo * x.hi + m[1].hi * v.lo + m[1].lo * v.hi))
        };
        let (mut xe, mut ve) = (row(&self.x), row(&self.v));
        let d = span - self.h;
        if d != 0.0 {
            let (acc, _) = by_the_equation(self.k, self.c, [f0 + f1 * self.h, f1], xe, ve);
            (xe, ve) = (xe + d * ve, ve + d * acc);
        }
        (xe, ve)
    }

    /// The state (x, x') after `span` (this propagator's length but for a sliver) from the
    /// state `x`, `v` at the interval's start, under the forcing f = forcing[0] + forcing[1] u.
    pub fn advance(&self, x: Dd, v: Dd, forcing: [f64; 2], span: f64) -> (Dd, Dd) {
        advance(self, x, v, forcing, span)
    }
}

fused! {
    /// [`Propagator::advance`], its products to twice the precision.
    fn advance(p: &Propagator, x: Dd, v: Dd, forcing: [f64; 2], span: f64) -> (Dd, Dd) {
        let [f0, f1] = forcing;
        let (mut xe, mut ve) = (row(&p.x, x, v, f0, f1), row(&p.v, x, v, f0, f1));
        let d = span - p.h;
        if d != 0.0 {
            // The sliver, by the Taylor step from h; the equation gives x'' and x'''.
            let (acc, jerk) = by_the_equation(p.k, p.c, [f0 + f1 * p.h, f1], xe.hi, ve.hi);
            let half = 0.5 * d * d;
            xe = xe + (Dd::exact(d) * ve.hi + half * acc);
            ve = ve + (Dd::exact(d) * acc + half * jerk);
        }
        (xe, ve)
    }
}

/// One row of the propagator applied to the data: a dot product summed as if in twice the
/// precision (Ogita, Rump and Oishi 2005: each product and each sum error-free, their errors
/// summed apart, with the products of the lo parts), inlined into the fused [`advance`].
#[inline(always)]
fn row(m: &[Dd; 4], x: Dd, v: Dd, f0: f64, f1: f64) -> Dd {
    let (mut sum, mut error) = two_product(m[0].hi, x.hi);
    error += m[0].hi * x.lo + m[0].lo * x.hi;
    let terms = [(m[1], v.hi, v.lo), (m[2], f0, 0.0), (m[3], f1, 0.0)];
    for (coefficient, hi, lo) in terms {
        let (p, e) = two_product(coefficient.hi, hi);
        let (s, f) = two_sum(sum, p);
        sum = s;
        error += (e + f) + (coefficient.hi * lo + coefficient.lo * hi);
    }
    Dd::new(sum, error)
}

/// x(h) and x'(h) of x'' + c x' + k x = f with one unit datum (0: x(0) = 1; 1: x'(0) = 1; 2:
/// f = 1; 3: f = u) and the others zero, from its Taylor series in twice the precision.
fn unit_response(k: f64, c: f64, h: f64, datum: usize) -> (Dd, Dd) {
    let mut a = [Dd::default(); TERMS];
    let mut forcing = [0.0; 2];
    match datum {
        0 | 1 => a[datum] = Dd::exact(1.0),
        _ => forcing[datum - 2] = 1.0,
    }
    let rho = k.abs().sqrt().max(c.abs()) * h;
    for n in 0..TERMS - 2 {
        let f = forcing.get(n).copied().unwrap_or(0.0);
        let sum = Dd::exact(f) - a[n] * k - a[n + 1] * Dd::from(c) * (n + 1) as f64;
        a[n + 2] = sum / ((n + 1) * (n + 2)) as f64;
    }
    // Terms beyond those that reach 2^-112 of the largest are left out (they are zeros or
    // below rounding); Horner's rule from the last kept.
    let mut terms = 4;
    let mut tail: f64 = rho.powi(4) / 24.0;
    while terms < TERMS && tail > 2f64.powi(-112) {
        terms += 1;
        tail *= rho / terms as f64;
    }
    let (mut x, mut v) = (Dd::default(), Dd::default());
    for n in (0..terms).rev() {
        x = x * h + a[n];
        if n >= 1 {
            v = v * h + a[n] * n as f64;
        }
    }
    (x, v)
}

/// The propagators a run has built, the last [`KEPT`] of them.
#[derive(Debug, Default)]
pub(crate) struct StepCache {
    kept: Kept<Propagator, KEPT>,
}

impl StepCache {
    /// The propagator of `k` and `c` over an interval of `span` ending at `t`, built over the
    /// `nominal` interval (the record's sample interval, so that it does not depend on which
    /// interval came first) if none kept serves; None where `span` is not the nominal interval
    /// but for the rounding of the samples' times, or the interval is beyond the series' reach.
    pub fn serve(
        &mut self,
        k: f64,
        c: f64,
        span: f64,
        t: f64,
        nominal: f64,
    ) -> Option<&Propagator> {
        if !near(span, nominal, t) {
            return None;
        }
        // A kept propagator of this k and c over the nominal interval serves (any other over
        // an interval near `span` would be the same one: kept lengths are nominal ones).
        self.kept.serve(
            |p: &Propagator| p.k == k && p.c == c && p.h == nominal,
            || Propagator::new(k, c, nominal),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::ClosedForm;
    use crate::integrate::exact::flow::Flow;
    use crate::physics::automaton::LinearForm;

    /// x and x' at t of x'' + c x' + k x = f0 + f1 t from x0, v0, written out apart from the
    /// series: the steady response to the ramp, (f0 + f1 t)/k - c f1/k^2, plus the free motion
    /// e^(sigma t) [C h0 + S (g0 - sigma h0)], C and S the cosine and sine of omega t (cosh
    /// and sinh while rocking, k < 0), S divided by omega.
    fn closed_form(k: f64, c: f64, [x0, v0, f0, f1]: [f64; 4], t: f64) -> (f64, f64) {
        let (xp0, vp) = ((f0 / k) - c * f1 / (k * k), f1 / k);
        let (h0, g0) = (x0 - xp0, v0 - vp);
        let sigma = -0.5 * c;
        let omega2 = k - sigma * sigma;
        let (cc, ss) = if omega2 > 0.0 {
            let w = omega2.sqrt();
            ((w * t).cos(), (w * t).sin() / w)
        } else {
            let m = (-omega2).sqrt();
            ((m * t).cosh(), (m * t).sinh() / m)
        };
        let e = (sigma * t).exp();
        let x = e * (cc * h0 + ss * (g0 - sigma * h0)) + xp0 + vp * t;
        let v = e * (cc * g0 + ss * (sigma * g0 - k * h0)) + vp;
        (x, v)
    }

    /// Modes like the bodies' (k, c): before uplift (damped and undamped) and while rocking
    /// (a saddle with negative damping), each over a record's interval.
    const MODES: [(f64, f64, f64); 4] = [
        (16.4, 0.41, 0.02),
        (250.0, 0.0, 0.01),
        (-3.7, -0.09, 0.02),
        (-60.0, -1.2, 0.005),
    ];

    /// Data x, x', f0, f1 at an interval's start.
    const DATA: [[f64; 4]; 3] = [
        [0.012, -0.31, 2.7, -40.0],
        [-0.15, 0.02, -0.8, 130.0],
        [1e-5, 3e-4, 0.0, 0.0],
    ];

    #[test]
    fn the_recurrence_gives_the_closed_form() {
        for (k, c, h) in MODES {
            let p = Propagator::new(k, c, h).expect("within the series' reach");
            for data in DATA {
                let (x, v) = p.advance(
                    Dd::exact(data[0]),
                    Dd::exact(data[1]),
                    [data[2], data[3]],
                    h,
                );
                let (xe, ve) = closed_form(k, c, data, h);
                // The scale: the state and the forcing's part over the interval.
                let scale =
                    data[0].abs() + data[1].abs() * h + (data[2].abs() + data[3].abs() * h) * h * h;
                assert!(
                    (x.value() - xe).abs() <= 1e-14 * scale
                        && (v.value() - ve).abs() * h <= 1e-14 * scale,
                    "k = {k}, c = {c}, data {data:?}: ({}, {}) against ({xe}, {ve})",
                    x.value(),
                    v.value()
                );
            }
        }
    }

    /// Two intervals of h by the recurrence end where one of 2h does, to twice the precision:
    /// its coefficients are not rounded to doubles.
    #[test]
    fn the_recurrence_is_carried_to_twice_the_precision() {
        for (k, c, h) in MODES {
            let (one, two) = (
                Propagator::new(k, c, h).unwrap(),
                Propagator::new(k, c, 2.0 * h).unwrap(),
            );
            for data in DATA {
                // Free motion (the forcing's slope would differ between the two halves).
                let (x0, v0) = (Dd::new(data[0], data[0] * 1e-17), Dd::exact(data[1]));
                let (x1, v1) = one.advance(x0, v0, [data[2], 0.0], h);
                let (x1, v1) = one.advance(x1, v1, [data[2], 0.0], h);
                let (x2, v2) = two.advance(x0, v0, [data[2], 0.0], 2.0 * h);
                let scale = data[0].abs() + data[1].abs() * h + data[2].abs() * h * h;
                let (dx, dv) = ((x1 - x2).value(), (v1 - v2).value());
                assert!(
                    dx.abs() <= 1e-28 * scale && dv.abs() * h <= 1e-28 * scale,
                    "k = {k}, c = {c}, data {data:?}: {dx:e}, {dv:e} apart"
                );
            }
        }
    }

    /// An interval longer or shorter than the propagator's by the rounding of the samples' times
    /// ends where a propagator built over its own length puts it.
    #[test]
    fn a_sliver_is_added_by_the_taylor_step() {
        for (k, c, h) in MODES {
            let p = Propagator::new(k, c, h).unwrap();
            for sliver in [3.5e-15, -7.1e-15] {
                let span = h + sliver;
                let own = Propagator::new(k, c, span).unwrap();
                for data in DATA {
                    let (x0, v0) = (Dd::exact(data[0]), Dd::exact(data[1]));
                    let (x, v) = p.advance(x0, v0, [data[2], data[3]], span);
                    let (xo, vo) = own.advance(x0, v0, [data[2], data[3]], span);
                    let scale = data[0].abs() + data[1].abs() * h + data[2].abs() * h * h;
                    let (dx, dv) = ((x - xo).value(), (v - vo).value());
                    assert!(
                        dx.abs() <= 1e-28 * scale && dv.abs() * h <= 1e-28 * scale,
                        "k = {k}, sliver {sliver:e}: {dx:e}, {dv:e} apart"
                    );
                    // The history's sample, to the working precision, agrees to rounding.
                    let (xs, vs) = p.sample(x0, v0, [data[2], data[3]], span);
                    assert!(
                        (xs - x.value()).abs() <= 4.0 * f64::EPSILON * scale
                            && (vs - v.value()).abs() * h <= 4.0 * f64::EPSILON * scale,
                        "k = {k}, sliver {sliver:e}: the sample {xs}, {vs} against {}, {}",
                        x.value(),
                        v.value()
                    );
                }
            }
        }
    }

    /// A flow over a record's whole interval ends, by the recurrence, where its Taylor series
    /// puts it; a flow that starts inside the interval, or of another mode, is not served.
    #[test]
    fn a_record_interval_ends_where_its_series_does() {
        for (k, c, h) in MODES {
            let linear = LinearForm {
                stiffness: k,
                damping: c,
                equilibrium: if k < 0.0 { 0.16 } else { 0.0 },
                participation: 1.3,
            };
            let (origin, a0, slope) = (4.0 * h, 0.9, -25.0);
            let floor = ClosedForm::polynomial(origin, &[a0, slope], origin + h);
            let mut cache = StepCache::default();
            let step = cache.serve(k, c, h, floor.until, h);
            assert!(step.is_some());
            let (q, v) = (Dd::exact(0.05), Dd::exact(-0.2));
            let by_step = Flow::new(&linear, &floor, origin, 0.0, q, v, floor.until, step);
            let by_series = Flow::new(&linear, &floor, origin, 0.0, q, v, floor.until, None);
            assert!(by_step.interval_data().is_some() && by_series.interval_data().is_none());
            let (qs, vs) = by_step.state(floor.until);
            let (qt, vt) = by_series.state(floor.until);
            let scale = 0.2 + 0.2 * h;
            assert!(
                (qs - qt).value().abs() <= 1e-16 * scale
                    && (vs - vt).value().abs() * h <= 1e-16 * scale,
                "k = {k}: ({}, {}) against ({}, {})",
                qs.value(),
                vs.value(),
                qt.value(),
                vt.value()
            );
            // Inside the interval the series still serves every point.
            let mid = origin + 0.5 * h;
            assert_eq!(
                by_step.point(mid).q.to_bits(),
                by_series.point(mid).q.to_bits()
            );
            // A flow from inside the interval (after an event) is not a whole interval.
            let late = Flow::new(
                &linear,
                &floor,
                mid,
                0.0,
                q,
                v,
                floor.until,
                cache.serve(k, c, h, floor.until, h),
            );
            assert!(late.interval_data().is_none());
            // Another mode's propagator does not serve.
            assert!(!cache.serve(k, c, h, floor.until, h).unwrap().serves(
                k * 1.001,
                c,
                h,
                floor.until
            ));
        }
    }

    #[test]
    fn intervals_beyond_the_series_reach_are_not_served() {
        // max(|k|^(1/2), |c|) h = 0.6 > 1/2.
        assert!(Propagator::new(36.0, 0.0, 0.1).is_none());
        assert!(Propagator::new(1.0, f64::NAN, 0.01).is_none());
        let mut cache = StepCache::default();
        // Not the nominal interval but for rounding.
        assert!(cache
            .serve(16.0, 0.1, 0.02 * (1.0 + 1e-9), 1.0, 0.02)
            .is_none());
        assert!(cache.serve(16.0, 0.1, 0.02 + 2e-16, 1.0, 0.02).is_some());
    }
}
