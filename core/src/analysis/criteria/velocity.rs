//! The peak floor velocity of a floor motion, in closed form: the floor starts at rest and its
//! velocity is the integral of the acceleration's closed forms ([`FloorMotion::closed_form`]),
//! stretch by stretch; within a stretch |v| peaks at its ends or where a(t) = 0. Exact for the
//! sines and pulses (sinusoids) and for records (linear between samples); None for a motion
//! with a stretch of higher degree (the Ricker wavelet's Taylor pieces).

use std::f64::consts::PI;

use crate::floor::{FloorMotion, Shape};

/// max |v(t)| over [0, end] (the floor velocity from rest), m/s; `end` is where the motion
/// stops being looked at (a pulse's or record's end; past it the floor is at rest).
pub fn peak_velocity(floor: &dyn FloorMotion, end: f64) -> Option<f64> {
    let (mut t, mut v, mut peak) = (0.0f64, 0.0f64, 0.0f64);
    // Each stretch ends after it starts (or the walk stops), and a motion has finitely many
    // before `end`.
    loop {
        if t >= end {
            return Some(peak);
        }
        let form = floor.closed_form(t);
        let until = form.until.min(end);
        if until <= t {
            return None;
        }
        match form.shape {
            Shape::Rest => {}
            Shape::Sinusoid {
                sin_part,
                cos_part,
                period,
            } => {
                let w = 2.0 * PI / period;
                // v(u) = v(t) + F(u) - F(t), F(u) = (-s cos(w u) + c sin(w u))/w.
                let f = |u: f64| (-sin_part * (w * u).cos() + cos_part * (w * u).sin()) / w;
                let v0 = v - f(t);
                // a = 0 where w u = phase + k pi.
                let phase = (-cos_part).atan2(sin_part);
                let k_lo = ((w * t - phase) / PI).ceil() as i64;
                let k_hi = ((w * until - phase) / PI).floor() as i64;
                for k in k_lo..=k_hi {
                    let u = (phase + k as f64 * PI) / w;
                    if u >= t && u <= until {
                        peak = peak.max((v0 + f(u)).abs());
                    }
                }
                v = v0 + f(until);
            }
            Shape::Polynomial {
                origin,
                coefficients,
                degree,
            } => {
                if degree > 1 {
                    return None;
                }
                let (c0, c1) = (
                    coefficients[0],
                    if degree == 1 { coefficients[1] } else { 0.0 },
                );
                let a = |u: f64| c0 + c1 * (u - origin);
                let (a0, a1, h) = (a(t), a(until), until - t);
                if a0 * a1 < 0.0 {
                    // v peaks where the line crosses zero.
                    let s = a0 / (a0 - a1) * h;
                    peak = peak.max((v + a0 * s + 0.5 * (a1 - a0) / h * s * s).abs());
                }
                v += 0.5 * (a0 + a1) * h;
            }
        }
        peak = peak.max(v.abs());
        t = until;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::{PulseShape, RecordedMotion, SinePulse};

    #[test]
    fn pulses_peak_at_their_closed_forms() {
        // a = A sin(2 pi t/Tp): v = A Tp/(2 pi) (1 - cos), peak A Tp/pi after each half cycle.
        let sine = SinePulse::new(3.0, 0.8, 1.0, PulseShape::Antisymmetric);
        let v = peak_velocity(&sine, sine.end()).unwrap();
        assert!((v - 3.0 * 0.8 / PI).abs() < 1e-12, "{v}");
        // a = A cos: v = A Tp/(2 pi) sin, peak A Tp/(2 pi).
        let cosine = SinePulse::new(3.0, 0.8, 3.0, PulseShape::Symmetric);
        let v = peak_velocity(&cosine, cosine.end()).unwrap();
        assert!((v - 3.0 * 0.8 / (2.0 * PI)).abs() < 1e-12, "{v}");
    }

    #[test]
    fn a_record_peaks_where_its_line_crosses_zero() {
        // a = 0, 1, -1, 0 at t = 0, 1, 2, 3: v = 0.5 at t = 1, then peaks at t = 1.5 where
        // a = 0: 0.5 + 1 * 0.5 - 0.5 * 2 * 0.25 = 0.75, and returns to 0.
        let record = RecordedMotion::new("x".into(), 1.0, vec![0.0, 1.0, -1.0, 0.0]);
        let v = peak_velocity(&record, record.end()).unwrap();
        assert!((v - 0.75).abs() < 1e-15, "{v}");
    }
}
