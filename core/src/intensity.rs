//! Intensity measures of a ground motion, computed exactly for the motion flexrock applies: the
//! samples a_k at t_k = k dt, linear between them ([`RecordedMotion`]).
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
//! - Sa(T, zeta), the pseudo-spectral acceleration: omega^2 max |u|, omega = 2 pi / T, u the
//!   response of u'' + 2 zeta omega u' + omega^2 u = -a(t) from rest, solved exactly by the
//!   exact method's recurrence between samples (`solver/exact/oscillator.rs`). max |u| is
//!   taken over the whole response up to the last sample, between samples included, found by
//!   the method's certified search for extrema. [`SpectralOrdinate::sa_at_samples`] gives the largest over
//!   the samples alone, the usual definition of programs that step from sample to sample (for
//!   a response that oscillates freely near its peak, below Sa by up to 1 - cos(omega dt / 2)
//!   of it).
//!
//! No baseline correction and no filtering is made: the measures are of the samples as given.

use serde::Serialize;

use crate::double_double::DoubleDouble as Dd;
use crate::excitation::RecordedMotion;
use crate::invalid::InvalidParameter;
use crate::solver::exact::oscillator::oscillator_peak;
use crate::solver::SolverError;
use crate::units::STANDARD_GRAVITY;

/// The damping ratio of a response spectrum unless another is given: 5 %.
pub const DEFAULT_DAMPING: f64 = 0.05;

/// Shortest period of a spectral ordinate, s: 1 ms. Far below any period of engineering
/// interest (a spectrum at 1 ms is the PGA), and the shorter the period, the more steps of the
/// exact series between two samples.
pub const MIN_SPECTRAL_PERIOD: f64 = 1e-3;

/// Longest period of a spectral ordinate, s: 1e4 s, beyond any record's length by far.
pub const MAX_SPECTRAL_PERIOD: f64 = 1e4;

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

/// One ordinate of a response spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpectralOrdinate {
    /// The oscillator's period T, s.
    pub period: f64,
    /// Its damping ratio zeta.
    pub damping: f64,
    /// Pseudo-spectral acceleration omega^2 Sd, m/s^2.
    pub sa: f64,
    /// Spectral displacement max |u|, m.
    pub sd: f64,
    /// When |u| peaks, s.
    pub t_peak: f64,
    /// omega^2 max |u| over the samples alone, m/s^2.
    pub sa_at_samples: f64,
}

/// Every measure of a motion: the ground's, and Sa at one period.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IntensityMeasures {
    /// PGA, PGV, PGD, Arias intensity, CAV.
    #[serde(flatten)]
    pub ground: GroundMeasures,
    /// Sa(T, zeta) at the period asked for.
    pub sa: SpectralOrdinate,
}

/// Every measure of `motion`, Sa at `period` (s) and damping ratio `damping`.
pub fn intensity_measures(
    motion: &RecordedMotion,
    period: f64,
    damping: f64,
) -> Result<IntensityMeasures, SolverError> {
    Ok(IntensityMeasures {
        ground: ground_measures(motion),
        sa: spectral_acceleration(motion, period, damping)?,
    })
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

/// Checks a spectral period (s) and damping ratio, named `period_key` and `damping_key`.
pub fn check_oscillator(
    period_key: &str,
    period: f64,
    damping_key: &str,
    damping: f64,
) -> Result<(), InvalidParameter> {
    if !(period.is_finite() && (MIN_SPECTRAL_PERIOD..=MAX_SPECTRAL_PERIOD).contains(&period)) {
        return Err(InvalidParameter::new(
            period_key,
            period,
            &format!(
                "must lie in [{}, {}] s",
                crate::format::shortest(MIN_SPECTRAL_PERIOD),
                crate::format::shortest(MAX_SPECTRAL_PERIOD)
            ),
        ));
    }
    if !(damping.is_finite() && (0.0..1.0).contains(&damping)) {
        return Err(InvalidParameter::new(
            damping_key,
            damping,
            "must lie in [0, 1): the damping ratio of an oscillator that vibrates",
        ));
    }
    Ok(())
}

/// Sa(T, zeta) of `motion` (see the module), T = `period` s and zeta = `damping`.
pub fn spectral_acceleration(
    motion: &RecordedMotion,
    period: f64,
    damping: f64,
) -> Result<SpectralOrdinate, SolverError> {
    check_oscillator("period", period, "damping", damping)?;
    let omega = 2.0 * std::f64::consts::PI / period;
    let k = omega * omega;
    let peak = oscillator_peak(k, 2.0 * damping * omega, motion, motion.end())?;
    Ok(SpectralOrdinate {
        period,
        damping,
        sa: k * peak.max_abs,
        sd: peak.max_abs,
        t_peak: peak.t,
        sa_at_samples: k * peak.max_abs_at_breakpoints,
    })
}

/// The response spectrum of `motion` at `periods` (s), damping ratio `damping`.
pub fn spectrum(
    motion: &RecordedMotion,
    periods: &[f64],
    damping: f64,
) -> Result<Vec<SpectralOrdinate>, SolverError> {
    for &period in periods {
        check_oscillator("period", period, "damping", damping)?;
    }
    periods
        .iter()
        .map(|&period| spectral_acceleration(motion, period, damping))
        .collect()
}

/// The periods of a spectrum unless others are given: 0.01 s to 10 s, 20 a decade evenly on a
/// logarithmic scale (61 periods, each 10^(k/20) / 100 s).
pub fn default_periods() -> Vec<f64> {
    (0..=60)
        .map(|k| 10f64.powf(k as f64 / 20.0 - 2.0))
        .collect()
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

    /// The exact response of a piecewise-linear forcing, written out apart from the method's
    /// series and recurrence (the Nigam-Jennings closed form over each interval), sampled
    /// finely: its peak is Sa's peak to the grid's resolution.
    fn closed_form_peak(
        omega: f64,
        zeta: f64,
        dt: f64,
        a: &[f64],
        per_interval: usize,
    ) -> (f64, f64) {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let (mut u, mut v) = (0.0f64, 0.0f64);
        let (mut peak, mut at_samples) = (0.0f64, 0.0f64);
        for pair in a.windows(2) {
            let f0 = -pair[0];
            let f1 = -(pair[1] - pair[0]) / dt;
            let c1 = f1 / (omega * omega);
            let c0 = (f0 - 2.0 * zeta * omega * c1) / (omega * omega);
            let (x0, x1) = (u - c0, v - c1);
            let b = (x1 + zeta * omega * x0) / wd;
            let at = |tau: f64| {
                let e = (-zeta * omega * tau).exp();
                let (c, s) = ((wd * tau).cos(), (wd * tau).sin());
                (
                    c0 + c1 * tau + e * (x0 * c + b * s),
                    c1 + e * (-zeta * omega * (x0 * c + b * s) + wd * (-x0 * s + b * c)),
                )
            };
            for j in 1..=per_interval {
                peak = peak.max(at(dt * j as f64 / per_interval as f64).0.abs());
            }
            (u, v) = at(dt);
            at_samples = at_samples.max(u.abs());
        }
        (peak, at_samples)
    }

    #[test]
    fn sa_is_the_peak_of_the_exact_response_between_samples_included() {
        let dt = 0.02;
        let a: Vec<f64> = (0..400)
            .map(|k| {
                let t = k as f64 * dt;
                2.5 * (3.1 * t).sin() + 1.7 * (11.3 * t + 0.4).sin() - 0.8 * (29.0 * t).cos()
            })
            .collect();
        let record = motion(dt, a.clone());
        for period in [0.05, 0.2, 1.0, 3.0] {
            let omega = 2.0 * std::f64::consts::PI / period;
            let s = spectral_acceleration(&record, period, 0.05).unwrap();
            let per_interval = 200;
            let (fine, samples) = closed_form_peak(omega, 0.05, dt, &a, per_interval);
            assert!(
                close(s.sa_at_samples, omega * omega * samples, 1e-10),
                "T = {period}: {s:?}"
            );
            // A grid of spacing delta finds the peak below the true one by at most
            // (omega delta)^2 / 8 of it, never above it.
            let grid = (omega * dt / per_interval as f64).powi(2) / 8.0;
            assert!(
                s.sd >= fine * (1.0 - 1e-12),
                "T = {period}: {} < {fine}",
                s.sd
            );
            assert!(
                s.sd <= fine * (1.0 + grid + 1e-12),
                "T = {period}: {} against {fine}",
                s.sd
            );
            assert!(s.sa > s.sa_at_samples);
        }
    }

    #[test]
    fn bad_periods_and_damping_are_refused() {
        let record = motion(0.01, vec![0.0, 1.0, 0.0]);
        let e = spectral_acceleration(&record, 0.0, 0.05)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("period = 0: must lie in [0.001, 1e4] s"),
            "{e}"
        );
        let e = spectral_acceleration(&record, 1.0, 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("damping = 1: must lie in [0, 1)"), "{e}");
        assert_eq!(default_periods().len(), 61);
        assert!(close(default_periods()[60], 10.0, 1e-15));
    }
}
