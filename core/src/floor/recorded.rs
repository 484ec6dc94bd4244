//! A recorded ground motion: samples at a fixed interval, piecewise linear between them.

use serde::Serialize;

use super::closed_form::{ClosedForm, Shape};
use super::motion::FloorMotion;
use crate::floor::record::RecordMeta;

/// Floor acceleration given by samples a_k at t_k = k dt (k = 0..n-1, already in m/s^2 and
/// trimmed), linear between samples and zero after the last one: after the record the floor is
/// at rest. Every sample time is a breakpoint, so adaptive solvers never step across a kink.
#[derive(Debug, Clone, Serialize)]
pub struct RecordedMotion {
    /// Where the samples came from (the record file), for tables and messages.
    pub source: String,
    /// Sample spacing dt, s.
    pub dt: f64,
    #[serde(skip)]
    values: Vec<f64>,
    #[serde(skip)]
    sample_times: Vec<f64>,
    /// What the record file says about itself (event, station, component, units...).
    #[serde(skip)]
    meta: RecordMeta,
}

impl RecordedMotion {
    /// The recorded ground motion `floor` is, for its metadata and intensity measures; None for
    /// the analytic motions.
    pub fn of(floor: &dyn FloorMotion) -> Option<&RecordedMotion> {
        (floor as &dyn std::any::Any).downcast_ref()
    }

    /// `values` in m/s^2, first sample at t = 0.
    pub fn new(source: String, dt: f64, values: Vec<f64>) -> Self {
        let sample_times = (0..values.len()).map(|k| k as f64 * dt).collect();
        RecordedMotion {
            source,
            dt,
            values,
            sample_times,
            meta: RecordMeta::default(),
        }
    }

    /// The motion with the metadata of its record file.
    pub fn with_meta(mut self, meta: RecordMeta) -> Self {
        self.meta = meta;
        self
    }

    /// What the record file says about itself.
    pub fn meta(&self) -> &RecordMeta {
        &self.meta
    }

    /// Time of the last sample, s.
    pub fn end(&self) -> f64 {
        self.sample_times.last().copied().unwrap_or(0.0)
    }

    /// The samples a_k, m/s^2.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Largest |a| and its time.
    pub fn peak(&self) -> (f64, f64) {
        self.values
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(best, tb), (k, &a)| {
                if a.abs() > best {
                    (a.abs(), self.sample_times[k])
                } else {
                    (best, tb)
                }
            })
    }
}

impl FloorMotion for RecordedMotion {
    fn quiet_after(&self) -> Option<f64> {
        Some(self.end())
    }
    fn acceleration(&self, t: f64) -> f64 {
        let n = self.values.len();
        if n == 0 || t < 0.0 || t > self.end() {
            return 0.0;
        }
        let x = t / self.dt;
        // The index is clamped so that t = end (and rounding just below it) stays in range.
        let k = (x.floor() as usize).min(n.saturating_sub(2));
        if n == 1 {
            return self.values[0];
        }
        let frac = x - k as f64;
        self.values[k] + frac * (self.values[k + 1] - self.values[k])
    }
    fn breakpoints(&self) -> &[f64] {
        &self.sample_times
    }
    fn peak_acceleration(&self) -> f64 {
        self.peak().0
    }
    fn kind(&self) -> &'static str {
        "record"
    }
    fn closed_form(&self, t: f64) -> ClosedForm {
        let n = self.values.len();
        if n < 2 || t >= self.end() {
            return ClosedForm::exact(f64::INFINITY, Shape::Rest);
        }
        // The sample interval [t_k, t_(k+1)) that holds t, found from t/dt and corrected for
        // rounding against the sample times themselves.
        let mut k = ((t / self.dt).floor().max(0.0) as usize).min(n - 2);
        while k > 0 && self.sample_times[k] > t {
            k -= 1;
        }
        while k + 2 < n && self.sample_times[k + 1] <= t {
            k += 1;
        }
        let slope = (self.values[k + 1] - self.values[k]) / self.dt;
        ClosedForm::polynomial(
            self.sample_times[k],
            &[self.values[k], slope],
            self.sample_times[k + 1],
        )
    }
    fn sample_interval(&self) -> Option<f64> {
        Some(self.dt)
    }
    fn parameters(&self) -> serde_json::Value {
        let (peak, t_peak) = self.peak();
        serde_json::json!({
            "kind": self.kind(),
            "source": self.source,
            "dt": self.dt,
            "points": self.values.len(),
            "duration": self.end(),
            "pga": peak,
            "t_pga": t_peak,
            "record": self.meta,
        })
    }
}
