//! A closed-form criterion fitted to the study: for each self-weight variant,
//!
//! - the thresholds, Ishiyama's two conditions made functions of the flexibility phi and the
//!   slenderness s = B/H: the smallest critical peak acceleration over the fitted excitations,
//!   over g B/H, and the smallest critical peak velocity, over c B/sqrt(H)
//!   ([`crate::physics::rigid_criteria`]), each fitted by least squares as a quadratic in phi whose
//!   coefficients are linear in s,
//!   k(phi, s) = k0(s) + k1(s) phi + k2(s) phi^2, ki(s) = ai + bi (s - s0),
//!   s0 the model's own slenderness (with one slenderness, bi = 0: a quadratic in phi): a body
//!   can overturn only if the floor's peak acceleration exceeds k_A g B/H and its peak
//!   velocity k_V c B/sqrt(H);
//! - the ratio of the elastic body's critical peak acceleration (and velocity: the same motion,
//!   so the same ratio) to Housner's full-equation block's under the same motion, fitted in the
//!   same form r(phi, s): critical ~ r x rigid.
//!
//! Each fit's error is given on every point it was fitted to, and on the points it was not
//! (records held out); its range of validity is the range of phi computed at each slenderness,
//! and the range of slenderness. A body that overturned at the bottom of the searched interval
//! under some fitted motion ([`Point::at_interval_bottom`]) has no known smallest critical
//! value: it is left out of the fits, and listed.

use serde::Serialize;

use super::point::Point;
use crate::physics::rigid_criteria::{ishiyama_acceleration, ishiyama_velocity};

/// A fitted point: (phi, s, value, fitted / value - 1).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Residual {
    /// phi.
    pub flexibility: f64,
    /// s = B/H.
    pub slenderness: f64,
    /// The computed value.
    pub value: f64,
    /// fitted / value - 1.
    pub error: f64,
}

/// k(phi, s) = k0(s) + k1(s) phi + k2(s) phi^2 with ki(s) = ai + bi (s - s0), and its errors.
#[derive(Debug, Clone, Serialize)]
pub struct Surface {
    /// s0, the slenderness the coefficients are centred on.
    pub reference_slenderness: f64,
    /// a0, a1, a2: the quadratic in phi at s = s0.
    pub coefficients: [f64; 3],
    /// b0, b1, b2: their slopes in s (zero when one slenderness was fitted).
    pub slenderness_slopes: [f64; 3],
    /// The points fitted, with the fit's error on each.
    pub errors: Vec<Residual>,
    /// Largest |fitted / value - 1| over them.
    pub max_abs_error: f64,
}

impl Surface {
    /// The value at (phi, s).
    pub fn at(&self, phi: f64, s: f64) -> f64 {
        let d = s - self.reference_slenderness;
        let k = |i: usize| self.coefficients[i] + self.slenderness_slopes[i] * d;
        k(0) + phi * (k(1) + phi * k(2))
    }

    /// Least squares through (phi, s, value) points, centred on `s0`: six coefficients when the
    /// points have two slendernesses or more (and at least six points), else the three of a
    /// quadratic in phi (at least three points). None when too few points, or singular.
    pub fn fit(points: &[(f64, f64, f64)], s0: f64) -> Option<Surface> {
        let mut distinct: Vec<f64> = points.iter().map(|p| p.1).collect();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        let with_slope = distinct.len() >= 2;
        let n = if with_slope { 6 } else { 3 };
        if points.len() < n {
            return None;
        }
        let basis = |phi: f64, s: f64| {
            let d = s - s0;
            [1.0, phi, phi * phi, d, d * phi, d * phi * phi]
        };
        let rows: Vec<(Vec<f64>, f64)> = points
            .iter()
            .map(|&(phi, s, y)| (basis(phi, s)[..n].to_vec(), y))
            .collect();
        let c = least_squares(&rows, n)?;
        let mut surface = Surface {
            reference_slenderness: s0,
            coefficients: [c[0], c[1], c[2]],
            slenderness_slopes: if with_slope {
                [c[3], c[4], c[5]]
            } else {
                [0.0; 3]
            },
            errors: Vec::new(),
            max_abs_error: 0.0,
        };
        surface.errors = points
            .iter()
            .map(|&(phi, s, value)| Residual {
                flexibility: phi,
                slenderness: s,
                value,
                error: surface.at(phi, s) / value - 1.0,
            })
            .collect();
        surface.max_abs_error = surface
            .errors
            .iter()
            .map(|e| e.error.abs())
            .fold(0.0, f64::max);
        Some(surface)
    }
}

/// The coefficients minimising sum (basis . c - y)^2 over `rows` (basis, y), by the normal
/// equations and Gaussian elimination with partial pivoting; None if singular.
fn least_squares(rows: &[(Vec<f64>, f64)], n: usize) -> Option<Vec<f64>> {
    let mut m = vec![vec![0.0f64; n + 1]; n];
    for (basis, y) in rows {
        for i in 0..n {
            for j in 0..n {
                m[i][j] += basis[i] * basis[j];
            }
            m[i][n] += basis[i] * y;
        }
    }
    let scale = (0..n).map(|i| m[i][i].abs()).fold(0.0, f64::max);
    for col in 0..n {
        let pivot = (col..n).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        m.swap(col, pivot);
        if m[col][col].abs() <= 1e-13 * scale {
            return None;
        }
        let pivot_row = m[col].clone();
        for (row, line) in m.iter_mut().enumerate() {
            if row != col {
                let f = line[col] / pivot_row[col];
                for (x, p) in line.iter_mut().zip(&pivot_row).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    Some((0..n).map(|i| m[i][n] / m[i][i]).collect())
}

/// A held-out point checked against the fit.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    /// The excitation.
    pub excitation: String,
    /// s = B/H.
    pub slenderness: f64,
    /// phi.
    pub flexibility: f64,
    /// Critical peak acceleration over the fitted threshold k_A(phi, s) g B/H (at least 1: the
    /// acceleration condition holds).
    pub acceleration_margin: Option<f64>,
    /// Critical peak velocity over the fitted threshold k_V(phi, s) c B/sqrt(H) (at least 1:
    /// the velocity condition holds).
    pub velocity_margin: Option<f64>,
    /// r(phi, s) x rigid / critical - 1: the ratio fit's error on the point.
    pub ratio_error: Option<f64>,
    /// True when phi lies outside the range fitted at this slenderness (an extrapolation).
    pub extrapolated: bool,
}

/// The range of phi computed at one slenderness.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Validity {
    /// s = B/H.
    pub slenderness: f64,
    /// The smallest and largest phi fitted at it.
    pub flexibility_range: (f64, f64),
}

/// A body left out of the fits.
#[derive(Debug, Clone, Serialize)]
pub struct LeftOut {
    /// s = B/H.
    pub slenderness: f64,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// phi.
    pub flexibility: f64,
    /// Why.
    pub reason: String,
}

/// The fits of one self-weight variant.
#[derive(Debug, Clone, Serialize)]
pub struct Fit {
    /// `body.self_weight`.
    pub self_weight: String,
    /// The range of phi fitted, over all slendernesses.
    pub flexibility_range: (f64, f64),
    /// The range of s fitted.
    pub slenderness_range: (f64, f64),
    /// The range of validity: the range of phi at each slenderness fitted (in between, the
    /// ranges interpolated linearly in s).
    pub validity: Vec<Validity>,
    /// Excitations fitted.
    pub fitted: Vec<String>,
    /// k_A(phi, s): smallest critical peak acceleration over g B/H.
    pub acceleration: Option<Surface>,
    /// k_V(phi, s): smallest critical peak velocity over c B/sqrt(H).
    pub velocity: Option<Surface>,
    /// r(phi, s): critical over Housner's full-equation block's, under the same motion.
    pub ratio: Option<Surface>,
    /// The held-out points.
    pub checks: Vec<Check>,
    /// Bodies left out of the fits.
    pub left_out: Vec<LeftOut>,
}

/// Ishiyama's two lines of a point's body (B, H its own) under `gravity`.
fn lines(p: &Point, gravity: f64) -> (f64, f64) {
    (
        ishiyama_acceleration(p.width, p.height, gravity),
        ishiyama_velocity(p.width, p.height),
    )
}

/// Fits the points of `self_weight` whose excitation is not in `held_out`, and checks those
/// that are; the coefficients are centred on the slenderness `s0`, and `gravity` is the
/// bodies'.
pub fn fit(points: &[Point], self_weight: &str, held_out: &[String], s0: f64, gravity: f64) -> Fit {
    // Points with a critical value ran, so they have their flexibility.
    let mine: Vec<&Point> = points
        .iter()
        .filter(|p| {
            p.self_weight == self_weight && p.critical_pga.is_some() && p.flexibility.is_some()
        })
        .collect();
    let flexibility = |p: &Point| p.flexibility.unwrap_or(f64::NAN);
    let (fitted, checked): (Vec<&Point>, Vec<&Point>) =
        mine.iter().partition(|p| !held_out.contains(&p.excitation));
    // Bodies with a fitted motion that overturned them at the bottom of the searched interval.
    let mut left_out: Vec<LeftOut> = Vec::new();
    for p in fitted.iter().filter(|p| p.at_interval_bottom()) {
        if !left_out
            .iter()
            .any(|l| l.slenderness == p.slenderness && l.youngs_modulus == p.youngs_modulus)
        {
            left_out.push(LeftOut {
                slenderness: p.slenderness,
                youngs_modulus: p.youngs_modulus,
                flexibility: flexibility(p),
                reason: format!(
                    "{} overturned it at the bottom of the searched interval: its smallest \
                     critical value is not known",
                    p.excitation
                ),
            });
        }
    }
    let fitted: Vec<&Point> = fitted
        .into_iter()
        .filter(|p| {
            !left_out
                .iter()
                .any(|l| l.slenderness == p.slenderness && l.youngs_modulus == p.youngs_modulus)
        })
        .collect();
    // One body per (slenderness, modulus): its smallest critical values over the excitations.
    let mut bodies: Vec<(f64, f64)> = fitted
        .iter()
        .map(|p| (p.slenderness, p.youngs_modulus))
        .collect();
    bodies.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    bodies.dedup();
    let mut envelope_a = Vec::new();
    let mut envelope_v = Vec::new();
    for (s, e) in &bodies {
        let same: Vec<&&Point> = fitted
            .iter()
            .filter(|p| p.slenderness == *s && p.youngs_modulus == *e)
            .collect();
        let (a_scale, v_scale) = lines(same[0], gravity);
        let phi = flexibility(same[0]);
        let a = same
            .iter()
            .filter_map(|p| p.critical_pga)
            .fold(f64::INFINITY, f64::min);
        let v = same
            .iter()
            .filter_map(|p| p.critical_pgv())
            .fold(f64::INFINITY, f64::min);
        envelope_a.push((phi, *s, a / a_scale));
        envelope_v.push((phi, *s, v / v_scale));
    }
    let ratios: Vec<(f64, f64, f64)> = fitted
        .iter()
        .filter_map(|p| {
            Some((
                flexibility(p),
                p.slenderness,
                p.critical_pga? / p.rigid_full_pga?,
            ))
        })
        .collect();
    let acceleration = Surface::fit(&envelope_a, s0);
    let velocity = Surface::fit(&envelope_v, s0);
    let ratio = Surface::fit(&ratios, s0);
    let range = |xs: &mut dyn Iterator<Item = f64>| {
        xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        })
    };
    let mut slendernesses: Vec<f64> = bodies.iter().map(|b| b.0).collect();
    slendernesses.dedup();
    let validity: Vec<Validity> = slendernesses
        .iter()
        .map(|s| Validity {
            slenderness: *s,
            flexibility_range: range(
                &mut fitted
                    .iter()
                    .filter(|p| p.slenderness == *s)
                    .map(|p| flexibility(p)),
            ),
        })
        .collect();
    let checks = checked
        .iter()
        .map(|p| {
            let (a_scale, v_scale) = lines(p, gravity);
            let (phi, s) = (flexibility(p), p.slenderness);
            let extrapolated = !validity.iter().any(|v: &Validity| {
                v.slenderness == s && phi >= v.flexibility_range.0 && phi <= v.flexibility_range.1
            });
            Check {
                excitation: p.excitation.clone(),
                slenderness: s,
                flexibility: phi,
                acceleration_margin: acceleration
                    .as_ref()
                    .and_then(|q| Some(p.critical_pga? / (q.at(phi, s) * a_scale))),
                velocity_margin: velocity
                    .as_ref()
                    .and_then(|q| Some(p.critical_pgv()? / (q.at(phi, s) * v_scale))),
                ratio_error: ratio
                    .as_ref()
                    .and_then(|q| Some(q.at(phi, s) * p.rigid_full_pga? / p.critical_pga? - 1.0)),
                extrapolated,
            }
        })
        .collect();
    let mut names: Vec<String> = Vec::new();
    for p in &fitted {
        if !names.contains(&p.excitation) {
            names.push(p.excitation.clone());
        }
    }
    Fit {
        self_weight: self_weight.to_string(),
        flexibility_range: range(&mut fitted.iter().map(|p| flexibility(p))),
        slenderness_range: range(&mut slendernesses.iter().copied()),
        validity,
        fitted: names,
        acceleration,
        velocity,
        ratio,
        checks,
        left_out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With one slenderness the surface is the quadratic in phi, fitted exactly.
    #[test]
    fn a_quadratic_is_fitted_exactly() {
        let f = |x: f64| 1.5 - 0.25 * x + 0.125 * x * x;
        let pts: Vec<(f64, f64, f64)> = [0.1, 0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|&x| (x, 0.175, f(x)))
            .collect();
        let q = Surface::fit(&pts, 0.175).unwrap();
        for (c, e) in q.coefficients.iter().zip([1.5, -0.25, 0.125]) {
            assert!((c - e).abs() < 1e-12, "{c} {e}");
        }
        assert_eq!(q.slenderness_slopes, [0.0; 3]);
        assert!(q.max_abs_error < 1e-12);
        assert!((q.at(3.0, 0.9) - f(3.0)).abs() < 1e-12);
    }

    /// Over three slendernesses, a surface of the fitted form is recovered exactly, centred on
    /// s0; and a term outside the form (s^2) shows as an error on the points.
    #[test]
    fn a_surface_linear_in_the_slenderness_is_fitted_exactly() {
        let (a, b) = ([1.2, -0.3, 0.02], [0.8, 1.5, -0.4]);
        let s0 = 0.175;
        let f = |phi: f64, s: f64| {
            let d = s - s0;
            (0..3)
                .map(|i| (a[i] + b[i] * d) * phi.powi(i as i32))
                .sum::<f64>()
        };
        let mut pts = Vec::new();
        for s in [0.1, 0.175, 0.25] {
            for phi in [0.03, 0.1, 0.3, 1.0, 3.0] {
                pts.push((phi / s, s, f(phi / s, s)));
            }
        }
        let q = Surface::fit(&pts, s0).unwrap();
        for i in 0..3 {
            assert!(
                (q.coefficients[i] - a[i]).abs() < 1e-9,
                "{:?}",
                q.coefficients
            );
            assert!(
                (q.slenderness_slopes[i] - b[i]).abs() < 1e-8,
                "{:?}",
                q.slenderness_slopes
            );
        }
        assert!(q.max_abs_error < 1e-10, "{}", q.max_abs_error);
        let bent: Vec<(f64, f64, f64)> = pts
            .iter()
            .map(|&(phi, s, y)| (phi, s, y + 40.0 * (s - s0).powi(2)))
            .collect();
        assert!(Surface::fit(&bent, s0).unwrap().max_abs_error > 0.01);
    }

    fn point(excitation: &str, s: f64, e: f64, phi: f64, critical: f64, safe: bool) -> Point {
        Point {
            self_weight: "paper".into(),
            slenderness: s,
            width: 4.0 * s,
            height: 4.0,
            excitation: excitation.into(),
            period: Some(1.0),
            youngs_modulus: e,
            flexibility: Some(phi),
            pre_uplift_period: Some(1.0),
            p: Some(1.0),
            pga_per_unit: 1.0,
            pgv_per_unit: 0.5,
            critical_pga: Some(critical),
            safe_below_pga: safe.then_some(0.9 * critical),
            bands: String::new(),
            n_bands: 1,
            rigid_full_pga: Some(critical),
            rigid_small_angle_pga: None,
            rigid_limit_pga: None,
            reason: String::new(),
        }
    }

    /// The envelope of each body is its smallest critical value over the fitted motions, over
    /// its own line g B/H: thresholds built in the fitted form on each body's own line are
    /// recovered exactly, which they would not be over one body's line. A body overturned at
    /// the bottom of the interval is left out and listed; a held-out record is checked at its
    /// own slenderness, and flagged beyond the range of phi fitted there.
    #[test]
    fn each_body_is_scaled_by_its_own_lines_and_a_body_at_the_interval_bottom_is_left_out() {
        let g = 9.81;
        let (s0, a, b) = (0.175, [1.1, -0.2, 0.01], [0.5, 0.3, -0.05]);
        let k = |phi: f64, s: f64| {
            (0..3)
                .map(|i| (a[i] + b[i] * (s - s0)) * phi.powi(i as i32))
                .sum::<f64>()
        };
        let mut points = Vec::new();
        for s in [0.1, 0.175, 0.25] {
            for (j, e) in [5e9, 5e8, 5e7, 5e6].into_iter().enumerate() {
                let phi = 0.03 * 10f64.powf(0.5 * j as f64) * 0.175 / s;
                let line = ishiyama_acceleration(4.0 * s, 4.0, g);
                // The smallest of two motions is on the surface; the other lies above it.
                points.push(point("x", s, e, phi, k(phi, s) * line, true));
                points.push(point("y", s, e, phi, 1.3 * k(phi, s) * line, true));
                points.push(point("held", s, e, phi, 2.0 * k(phi, s) * line, true));
            }
        }
        // The most flexible slender body: overturned at the bottom of the interval by "y".
        let bottom = points
            .iter_mut()
            .find(|p| p.slenderness == 0.1 && p.youngs_modulus == 5e6 && p.excitation == "y")
            .unwrap();
        bottom.safe_below_pga = None;
        bottom.critical_pga = Some(0.01);
        let f = fit(&points, "paper", &["held".into()], s0, g);
        let q = f.acceleration.as_ref().unwrap();
        assert!(q.max_abs_error < 1e-9, "{}", q.max_abs_error);
        for i in 0..3 {
            assert!(
                (q.coefficients[i] - a[i]).abs() < 1e-9,
                "{:?}",
                q.coefficients
            );
            let slope = q.slenderness_slopes[i];
            assert!((slope - b[i]).abs() < 1e-7, "{:?}", q.slenderness_slopes);
        }
        assert_eq!(q.errors.len(), 11);
        assert_eq!(f.left_out.len(), 1);
        let gone = &f.left_out[0];
        assert_eq!((gone.slenderness, gone.youngs_modulus), (0.1, 5e6));
        assert_eq!(f.checks.len(), 12);
        for c in &f.checks {
            assert!((c.acceleration_margin.unwrap() - 2.0).abs() < 1e-9, "{c:?}");
            let beyond = c.slenderness == 0.1 && c.flexibility > 1.0;
            assert_eq!(c.extrapolated, beyond, "{c:?}");
        }
        assert_eq!(f.validity.len(), 3);
    }
}
