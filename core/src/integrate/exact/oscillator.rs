//! The peak response of a linear oscillator to a floor motion, by this method's flows: the
//! response spectra of [`crate::analysis::intensity`] take the exact solution of the body before
//! uplift from here, for an oscillator of any k and c.
//!
//! The oscillator x'' + c x' + k x = -a(t), from rest at t = 0, is one mode of the method
//! ([`LinearForm`] with q_eq = 0 and beta = 1): its flows follow the floor's closed form stretch
//! by stretch (across a record's whole interval by the exact piecewise-linear recurrence,
//! `step.rs`), and its extrema between the flows' ends are found by the same certified scan as
//! the body's peaks (`scan.rs`), with no guard to cross.

use crate::base::double_double::DoubleDouble as Dd;
use crate::floor::{FloorMotion, Shape};
use crate::integrate::SolverError;
use crate::physics::automaton::LinearForm;

use super::flow::Flow;
use super::scan::{self, first_crossing, ScanError, Watch};
use super::step::StepCache;
use super::NAME;

/// The largest |x| of an oscillator's response.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OscillatorPeak {
    /// max |x| over [0, end], between the floor's breakpoints included, m.
    pub max_abs: f64,
    /// When it is reached, s.
    pub t: f64,
    /// max |x| over the ends of the floor's stretches only (a record's samples), m.
    pub max_abs_at_breakpoints: f64,
}

/// The peak of |x| for x'' + c x' + k x = -a(t) from x = x' = 0 at t = 0 until `end`, a(t) the
/// floor's acceleration.
pub fn oscillator_peak(
    k: f64,
    c: f64,
    floor: &dyn FloorMotion,
    end: f64,
) -> Result<OscillatorPeak, SolverError> {
    let linear = LinearForm {
        stiffness: k,
        damping: c,
        equilibrium: 0.0,
        participation: 1.0,
    };
    let failed = |t: f64, message: String| SolverError::Failed {
        method: NAME.to_string(),
        t,
        message,
    };
    let mut steps = StepCache::default();
    let mut watch = Watch {
        guard_up: f64::INFINITY,
        guard_down: f64::NEG_INFINITY,
        max: 0.0,
        min: 0.0,
        extrema: Vec::new(),
        stack: Vec::new(),
        evaluations: 0,
        unresolved: 0,
    };
    let mut peak = OscillatorPeak {
        max_abs: 0.0,
        t: 0.0,
        max_abs_at_breakpoints: 0.0,
    };
    let (mut t, mut x, mut v) = (0.0, Dd::default(), Dd::default());
    while t < end {
        let stretch = floor.closed_form(t);
        if stretch.until.partial_cmp(&t) != Some(std::cmp::Ordering::Greater) {
            return Err(failed(
                t,
                format!(
                    "the floor motion's closed form at t = {t} s ends at {} s, not after it",
                    stretch.until
                ),
            ));
        }
        let step = match (stretch.shape, floor.sample_interval()) {
            (Shape::Polynomial { .. }, Some(interval)) => {
                steps.serve(k, c, stretch.until - t, stretch.until, interval)
            }
            _ => None,
        };
        let flow = Flow::new(
            &linear,
            &stretch,
            t,
            0.0,
            x,
            v,
            stretch.until.min(end),
            step,
        );
        watch.extrema.clear();
        watch.evaluations = 0;
        let scanned = scan::evaluate(&flow, flow.until, &mut watch).and_then(|finish| {
            first_crossing(&flow, flow.point(t), finish, &[], &mut watch).map(|_| finish)
        });
        let finish = scanned.map_err(|e| match e {
            ScanError::NotFinite(t) => failed(t, "the closed-form state is not finite".into()),
            ScanError::TooMuchWork(t) => failed(
                t,
                format!(
                    "more than {} evaluations of one closed form",
                    scan::MAX_EVALUATIONS
                ),
            ),
        })?;
        for p in watch.extrema.iter().chain([&finish]) {
            if p.q.abs() > peak.max_abs {
                peak.max_abs = p.q.abs();
                peak.t = p.t;
            }
        }
        watch.max = watch.max.max(finish.q);
        watch.min = watch.min.min(finish.q);
        if flow.until == stretch.until {
            peak.max_abs_at_breakpoints = peak.max_abs_at_breakpoints.max(finish.q.abs());
        }
        (x, v) = flow.state_at(&finish);
        t = flow.until;
    }
    Ok(peak)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::{Harmonic, RecordedMotion};

    /// The steady state of x'' + c x' + k x = -A sin(W t) after its start has died out: the
    /// peaks of the response over a late cycle reach A / |k - W^2 + i c W|.
    #[test]
    fn a_damped_oscillator_reaches_its_steady_amplitude() {
        let (w0, zeta, big_w, amplitude) = (2.0 * std::f64::consts::PI, 0.2, 5.0, 3.0);
        let (k, c) = (w0 * w0, 2.0 * zeta * w0);
        let floor = Harmonic {
            amplitude,
            period: 2.0 * std::f64::consts::PI / big_w,
        };
        let steady = amplitude / (k - big_w * big_w).hypot(c * big_w);
        // e^(-zeta w0 t) at t = 40 s is 1e-22: the free motion is gone.
        let peak = oscillator_peak(k, c, &floor, 40.0).unwrap();
        assert!(peak.max_abs >= steady * (1.0 - 1e-12), "{peak:?} {steady}");
        // A sine has no breakpoints: its one stretch ends at the end.
        assert!(peak.max_abs_at_breakpoints <= peak.max_abs);
    }

    /// Between two samples the peak of x lies where x' = 0, inside an interval: the peak found
    /// there is above every sample's (the spectra's tests check its value).
    #[test]
    fn the_peak_between_samples_is_found() {
        let (k, c) = (39.478, 0.6);
        // A pulse, then the floor at rest for 1.5 periods: the free vibration peaks off the
        // samples.
        let record = RecordedMotion::new(
            "r".into(),
            0.3,
            vec![0.0, 2.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        );
        let peak = oscillator_peak(k, c, &record, record.end()).unwrap();
        assert!(peak.max_abs > peak.max_abs_at_breakpoints);
        let on_a_sample = (peak.t / 0.3 - (peak.t / 0.3).round()).abs() < 1e-9;
        assert!(
            peak.t > 0.0 && peak.t < record.end() && !on_a_sample,
            "{peak:?}"
        );
    }
}
