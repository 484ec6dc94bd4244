//! The ground's own intensity measures, computed exactly for the motion flexrock applies: the
//! samples a_k at t_k = k dt, linear between them ([`RecordedMotion`]).
//!
//!
//! - PGA = max |a|, over the samples (a linear piece peaks at an end).
//! - Velocity and displacement from rest at t = 0 are the exact integrals: v is quadratic and
//!   d cubic on each interval. PGV and PGD are the largest |v| and |d| over the whole curve,
//!   between samples included (v peaks where a crosses zero inside an interval, d where v
//!   does), up to the last sample.
//! - Arias intensity I_a = pi / (2 g) * integral of a^2 dt, g standard gravity (9.80665 m/s^2):
//!   on each interval h (a0^2 + a0 a1 + a1^2) / 3 exactly. In m/s.
//! - CAV, the cumulative absolute velocity, integral of |a| dt: on each interval h (|a0| + |a1|)
//!   / 2, or h (a0^2 + a1^2) / (2 (|a0| + |a1|)) where a changes sign inside it. In m/s.
//!
//!
//! No baseline correction and no filtering is made: the measures are of the samples as given.
//! Sa, which needs an oscillator, is in `bodies/oscillator.rs`.

use serde::Serialize;

use crate::base::double_double::DoubleDouble as Dd;
use crate::base::units::STANDARD_GRAVITY;
use crate::floor::RecordedMotion;

/// The measures that do not depend on an oscillator.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct GroundMeasures {
    /// Peak ground acceleration, m/s^2.
    pub pga: f64,
    /// Its time, s.
    pub t_pga: f64,
    /// Peak ground velocity, m/s.
    pub pgv: f64,
    /// Its time, s.
    pub t_pgv: f64,
    /// Peak ground displacement, m.
    pub pgd: f64,
    /// Its time, s.
    pub t_pgd: f64,
    /// Arias intensity, m/s.
    pub arias: f64,
    /// Cumulative absolute velocity, m/s.
    pub cav: f64,
}

/// PGA, PGV, PGD, Arias intensity and CAV of `motion` (see the module).
pub fn ground_measures(motion: &RecordedMotion) -> GroundMeasures {
    let (a, h) = (motion.values(), motion.dt);
    let mut m = GroundMeasures::default();
    let (mut v, mut d) = (Dd::default(), Dd::default());
    let (mut arias, mut cav) = (Dd::default(), Dd::default());
    let offer = |peak: &mut f64, at: &mut f64, value: f64, t: f64| {
        if value.abs() > *peak {
            *peak = value.abs();
            *at = t;
        }
    };
    if let Some(&first) = a.first() {
        offer(&mut m.pga, &mut m.t_pga, first, 0.0);
    }
    for (k, pair) in a.windows(2).enumerate() {
        let (a0, a1) = (pair[0], pair[1]);
        let t0 = k as f64 * h;
        let slope = (a1 - a0) / h;
        let (v0, d0) = (v.value(), d.value());
        // v peaks where a crosses zero inside the interval.
        if a0 * a1 < 0.0 {
            let tau = a0 * h / (a0 - a1);
            offer(&mut m.pgv, &mut m.t_pgv, v0 + 0.5 * a0 * tau, t0 + tau);
        }
        // d peaks where v = v0 + a0 tau + slope tau^2 / 2 crosses zero inside it.
        for tau in quadratic_roots(0.5 * slope, a0, v0) {
            if tau > 0.0 && tau < h {
                let value = d0 + tau * (v0 + tau * (0.5 * a0 + tau * slope / 6.0));
                offer(&mut m.pgd, &mut m.t_pgd, value, t0 + tau);
            }
        }
        d = d + Dd::exact(v0) * h + (Dd::exact(v.lo) * h + h * h * (2.0 * a0 + a1) / 6.0);
        v = v + Dd::exact(0.5 * h) * (a0 + a1);
        let t1 = (k + 1) as f64 * h;
        offer(&mut m.pga, &mut m.t_pga, a1, t1);
        offer(&mut m.pgv, &mut m.t_pgv, v.value(), t1);
        offer(&mut m.pgd, &mut m.t_pgd, d.value(), t1);
        arias = arias + h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
        cav = cav
            + if a0 * a1 >= 0.0 {
                0.5 * h * (a0.abs() + a1.abs())
            } else {
                0.5 * h * (a0 * a0 + a1 * a1) / (a0.abs() + a1.abs())
            };
    }
    m.arias = std::f64::consts::PI / (2.0 * STANDARD_GRAVITY) * arias.value();
    m.cav = cav.value();
    m
}

/// The real roots of A x^2 + B x + C = 0 (one for a linear equation, none for a constant),
/// computed without cancellation.
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(dt: f64, values: Vec<f64>) -> RecordedMotion {
        RecordedMotion::new("test".into(), dt, values)
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    /// A triangle up and down, a = 0, 2, 0 at dt = 0.5, integrated by hand.
    #[test]
    fn a_triangle_has_the_measures_of_its_integrals() {
        let m = ground_measures(&motion(0.5, vec![0.0, 2.0, 0.0]));
        assert_eq!((m.pga, m.t_pga), (2.0, 0.5));
        // v(t) = 2 t^2 on [0, 0.5] (slope 4), then 0.5 + 2 (t - 0.5) - 2 (t - 0.5)^2: v(1) = 1.
        assert!(close(m.pgv, 1.0, 1e-15) && m.t_pgv == 1.0, "{m:?}");
        // d = 2 t^3 / 3 to d(0.5) = 1/12; then 1/12 + 0.5 u + u^2 - 2 u^3 / 3: d(1) = 1/2.
        assert!(close(m.pgd, 0.5, 1e-15) && m.t_pgd == 1.0, "{m:?}");
        // integral of a^2: 2 * (0.5/3) 4 = 4/3; Arias pi/(2 g) 4/3.
        assert!(close(
            m.arias,
            std::f64::consts::PI / (2.0 * STANDARD_GRAVITY) * 4.0 / 3.0,
            1e-15
        ));
        assert!(close(m.cav, 1.0, 1e-15));
    }

    /// A sign change inside an interval: a = 1, -3 over h = 1 crosses zero at 1/4. |a| there
    /// integrates to (1 + 9) / (2 * 4) = 1.25; v peaks at 1/4 with 1/8, and ends at -1.
    #[test]
    fn a_sign_change_inside_an_interval_is_integrated_exactly() {
        let m = ground_measures(&motion(1.0, vec![1.0, -3.0]));
        assert!(close(m.cav, 1.25, 1e-15));
        assert!(close(m.pgv, 1.0, 1e-15) && m.t_pgv == 1.0);
        // The quarter: v = t - 2 t^2 peaks at 0.25 with 0.125, below |v(1)| = 1; but d peaks
        // where v = 0, t = 0.5: d = t^2/2 - 2 t^3 / 3 = 0.125 - 1/12 = 1/24; d(1) = 1/2 - 2/3.
        assert!(close(m.pgd, 1.0 / 6.0, 1e-15) && m.t_pgd == 1.0, "{m:?}");
        let m = ground_measures(&motion(1.0, vec![1.0, -3.0, 0.0]));
        // From t = 1: v = -1 - 3 u + 1.5 u^2 (never zero in (0, 1)): no peak of d inside.
        assert!(m.pgd > 1.0 / 6.0);
    }

    #[test]
    fn velocity_peaks_between_samples() {
        // a = 1, -1: v = t - t^2 on [0, 1], peak 1/4 at t = 1/2, v(1) = 0.
        let m = ground_measures(&motion(1.0, vec![1.0, -1.0]));
        assert!(
            close(m.pgv, 0.25, 1e-15) && close(m.t_pgv, 0.5, 1e-15),
            "{m:?}"
        );
    }
}
