//! A linear oscillator on the floor, solved exactly: its peak response is the spectral
//! acceleration Sa of a floor motion; with the ground's own measures
//! (`floor/intensity.rs`), a record's intensity measures.
//!
//! - Sa(T, zeta), the pseudo-spectral acceleration: omega^2 max |u|, omega = 2 pi / T, u the
//!   response of u'' + 2 zeta omega u' + omega^2 u = -a(t) from rest, solved exactly by the
//!   exact method's recurrence between samples (`integrate/exact/oscillator.rs`). max |u| is
//!   taken over the whole response up to the last sample, between samples included, found by
//!   the method's certified search for extrema. [`SpectralOrdinate::sa_at_samples`] gives the largest over
//!   the samples alone, the usual definition of programs that step from sample to sample (for
//!   a response that oscillates freely near its peak, below Sa by up to 1 - cos(omega dt / 2)
//!   of it).
//!
//! No baseline correction and no filtering is made: the measures are of the samples as given.

use serde::Serialize;

use crate::base::invalid::InvalidParameter;
use crate::floor::intensity::{ground_measures, GroundMeasures};
use crate::floor::RecordedMotion;
use crate::integrate::exact::kernel::oscillator_peak;
use crate::integrate::SolverError;

/// The damping ratio of a response spectrum unless another is given: 5 %.
pub const DEFAULT_DAMPING: f64 = 0.05;

/// Shortest period of a spectral ordinate, s: 1 ms. Far below any period of engineering
/// interest (a spectrum at 1 ms is the PGA), and the shorter the period, the more steps of the
/// exact series between two samples.
pub const MIN_SPECTRAL_PERIOD: f64 = 1e-3;

/// Longest period of a spectral ordinate, s: 1e4 s, beyond any record's length by far.
pub const MAX_SPECTRAL_PERIOD: f64 = 1e4;

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
                crate::base::format::shortest(MIN_SPECTRAL_PERIOD),
                crate::base::format::shortest(MAX_SPECTRAL_PERIOD)
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
