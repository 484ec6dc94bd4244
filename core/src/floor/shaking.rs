//! The floor's horizontal and vertical motions together, as a body standing on the floor feels
//! them: the horizontal acceleration drives it sideways, the vertical one adds to gravity.

use super::motion::FloorMotion;
use crate::base::format::{shortest, significant};
use crate::base::invalid::InvalidParameter;

/// Grid points per period (or per run, for motions without one) at which the vertical motion is
/// checked against gravity when its peak reaches g.
const POINTS_PER_PERIOD: f64 = 2048.0;
const POINTS_PER_RUN: f64 = 65536.0;

/// A horizontal floor motion with an optional vertical one: the horizontal acceleration drives
/// the body, [`Shaking::gravity_factor`] gives the vertical motion's share of gravity, and a
/// solver stops at the breakpoints of both.
pub struct Shaking<'a> {
    horizontal: &'a dyn FloorMotion,
    vertical: Option<&'a dyn FloorMotion>,
    /// The breakpoints of both motions, in order, without repeats.
    breakpoints: Vec<f64>,
}

/// Where the floor's vertical motion would pull it away from a body resting on it: the first
/// time at which g + a_v(t) <= 0, and the lowest a_v seen, with its time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftOff {
    /// The first time at which g + a_v <= 0, s.
    pub t: f64,
    /// The lowest vertical acceleration found, m/s^2, and when.
    pub lowest: f64,
    /// When a_v is lowest, s.
    pub t_lowest: f64,
}

impl<'a> Shaking<'a> {
    /// The floor moving horizontally by `horizontal` and vertically by `vertical` (upwards
    /// positive), if given.
    pub fn new(horizontal: &'a dyn FloorMotion, vertical: Option<&'a dyn FloorMotion>) -> Self {
        let mut breakpoints = horizontal.breakpoints().to_vec();
        if let Some(v) = vertical {
            breakpoints.extend_from_slice(v.breakpoints());
            breakpoints.sort_by(f64::total_cmp);
            breakpoints.dedup();
        }
        Shaking {
            horizontal,
            vertical,
            breakpoints,
        }
    }

    /// The horizontal motion alone.
    pub fn horizontal(&self) -> &'a dyn FloorMotion {
        self.horizontal
    }

    /// The vertical motion, if any.
    pub fn vertical(&self) -> Option<&'a dyn FloorMotion> {
        self.vertical
    }

    /// 1 + a_v(t)/g: the factor on gravity at `t` for gravity `g` (1 without vertical motion).
    pub fn gravity_factor(&self, t: f64, g: f64) -> f64 {
        match self.vertical {
            None => 1.0,
            Some(v) => 1.0 + v.acceleration(t) / g,
        }
    }

    /// Where, within [0, `duration`], the floor's vertical acceleration reaches -g, so that a
    /// body on it would be pulled off the floor; None if it never does. A record is linear
    /// between its samples, so checking the samples is exact; another motion is checked at its
    /// breakpoints and on a grid of 2048 points per period (or 65536 over the run), and only
    /// when its peak reaches g at all.
    pub fn lift_off(&self, g: f64, duration: f64) -> Option<LiftOff> {
        let v = self.vertical?;
        if v.peak_acceleration() < g {
            return None;
        }
        let mut times: Vec<f64> = v
            .breakpoints()
            .iter()
            .copied()
            .filter(|&t| (0.0..=duration).contains(&t))
            .collect();
        if v.sample_interval().is_none() {
            let spacing = match v.period() {
                Some(p) => (p / POINTS_PER_PERIOD).min(duration / POINTS_PER_RUN),
                None => duration / POINTS_PER_RUN,
            };
            let n = (duration / spacing).ceil().min(1e7) as usize;
            times.extend((0..=n).map(|k| duration * k as f64 / n as f64));
        }
        times.push(0.0);
        times.push(duration);
        times.sort_by(f64::total_cmp);
        times.dedup();
        let pulls = |t: f64| g + v.acceleration(t) <= 0.0;
        if v.sample_interval().is_none() && !times.iter().any(|&t| pulls(t)) {
            // A trough that just reaches -g can fall between grid points: the lowest one's
            // neighbourhood is searched for its minimum, which then counts as a grid point.
            let lowest = (0..times.len()).min_by(|&i, &j| {
                v.acceleration(times[i])
                    .total_cmp(&v.acceleration(times[j]))
            })?;
            let (lo, hi) = (
                times[lowest.saturating_sub(1)],
                times[(lowest + 1).min(times.len() - 1)],
            );
            let trough = lowest_between(|t| v.acceleration(t), lo, hi);
            times.push(trough);
            times.sort_by(f64::total_cmp);
        }
        let first = times.iter().position(|&t| pulls(t))?;
        let t = if first == 0 {
            times[0]
        } else {
            let (mut lo, mut hi) = (times[first - 1], times[first]);
            while 0.5 * (lo + hi) > lo && 0.5 * (lo + hi) < hi {
                let mid = 0.5 * (lo + hi);
                if pulls(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            hi
        };
        let (t_lowest, lowest) =
            times
                .iter()
                .map(|&t| (t, v.acceleration(t)))
                .fold(
                    (t, v.acceleration(t)),
                    |low, p| if p.1 < low.1 { p } else { low },
                );
        Some(LiftOff {
            t,
            lowest,
            t_lowest,
        })
    }
}

/// Where `f` is lowest in [lo, hi], by golden-section search to the resolution of the time
/// (f taken to have one trough there).
fn lowest_between(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    for _ in 0..200 {
        let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
        if !(a < c && c < d && d < b) {
            break;
        }
        if f(c) <= f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

impl Shaking<'_> {
    /// Refuses a vertical motion that reaches -g within [0, `duration`] (see
    /// [`Shaking::lift_off`]): the floor would then fall faster than gravity and the body leave
    /// it, which no model here describes.
    pub fn check_contact(&self, g: f64, duration: f64) -> Result<(), InvalidParameter> {
        match self.lift_off(g, duration) {
            None => Ok(()),
            Some(off) => Err(InvalidParameter::new(
                "excitation.vertical",
                format!(
                    "a_v = {} m/s^2 at t = {} s",
                    significant(off.lowest, 6),
                    significant(off.t_lowest, 6)
                ),
                &format!(
                    "must stay above -g = -{} m/s^2: from t = {} s the floor falls faster than \
                     gravity and the body would leave it, which the model does not describe",
                    shortest(g),
                    significant(off.t, 9)
                ),
            )),
        }
    }
}

impl Shaking<'_> {
    /// The breakpoints of both motions, in order: a solver stops at either's kinks.
    pub fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }

    /// The floor is at rest for good once both motions are.
    pub fn quiet_after(&self) -> Option<f64> {
        let h = self.horizontal.quiet_after()?;
        match self.vertical {
            None => Some(h),
            Some(v) => v.quiet_after().map(|v| v.max(h)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::{Harmonic, RecordedMotion};

    #[test]
    fn a_sine_deeper_than_gravity_pulls_away_where_its_closed_form_says() {
        // a_v = -A sin(2 pi t/T) reaches -g first at t = (T/2 pi) asin(g/A).
        let (g, amplitude, period) = (9.81, 12.0, 0.4);
        let h = Harmonic {
            amplitude: 0.0,
            period: 1.0,
        };
        let v = Harmonic {
            amplitude: -amplitude,
            period,
        };
        let shaking = Shaking::new(&h, Some(&v));
        let found = shaking.lift_off(g, 1.0).expect("it reaches -g");
        let expected = period / (2.0 * std::f64::consts::PI) * (g / amplitude).asin();
        assert!(
            (found.t - expected).abs() < 1e-12,
            "{} against {expected}",
            found.t
        );
        assert!((found.lowest + amplitude).abs() < 1e-5 * amplitude);
        // A trough that just reaches -g, between grid points, is found.
        let grazing = Harmonic {
            amplitude: -g,
            period: 0.37,
        };
        let found = Shaking::new(&h, Some(&grazing))
            .lift_off(g, 1.0)
            .expect("it reaches -g");
        assert!((found.t - 0.37 / 4.0).abs() < 1e-6, "{}", found.t);
        // Within gravity it never does.
        let gentle = Harmonic {
            amplitude: 0.99 * g,
            period,
        };
        assert_eq!(Shaking::new(&h, Some(&gentle)).lift_off(g, 1.0), None);
    }

    #[test]
    fn a_record_pulls_away_between_its_samples_where_the_line_crosses() {
        // Samples 0, -5, -15 at dt = 0.1: the line from -5 to -15 crosses -10 at t = 0.15.
        let v = RecordedMotion::new("v".into(), 0.1, vec![0.0, -5.0, -15.0]);
        let h = Harmonic {
            amplitude: 0.0,
            period: 1.0,
        };
        let found = Shaking::new(&h, Some(&v)).lift_off(10.0, 0.2).unwrap();
        assert!((found.t - 0.15).abs() < 1e-15, "{}", found.t);
        assert_eq!((found.lowest, found.t_lowest), (-15.0, 0.2));
    }
}
