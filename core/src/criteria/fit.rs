//! A closed-form criterion fitted to the study: for each self-weight variant,
//!
//! - the thresholds, Ishiyama's two conditions made functions of the flexibility phi: the
//!   smallest critical peak acceleration over the fitted excitations, over g B/H, and the
//!   smallest critical peak velocity, over c B/sqrt(H) ([`crate::rigid_criteria`]), each fitted as
//!   k(phi) = k0 + k1 phi + k2 phi^2 by least squares: a body can overturn only if the floor's
//!   peak acceleration exceeds k_A(phi) g B/H and its peak velocity k_V(phi) c B/sqrt(H);
//! - the ratio of the elastic body's critical peak acceleration (and velocity: the same motion,
//!   so the same ratio) to Housner's full-equation block's under the same motion, fitted as
//!   r(phi) = r0 + r1 phi + r2 phi^2: critical ~ r(phi) x rigid.
//!
//! Each fit's error is given on every point it was fitted to, and on the points it was not
//! (records held out).

use serde::Serialize;

use super::Point;
use crate::rigid_criteria::{ishiyama_acceleration, ishiyama_velocity};

/// A quadratic in phi and its errors.
#[derive(Debug, Clone, Serialize)]
pub struct Quadratic {
    /// k0, k1, k2 of k0 + k1 phi + k2 phi^2.
    pub coefficients: [f64; 3],
    /// The points fitted: (phi, value, fitted / value - 1).
    pub errors: Vec<(f64, f64, f64)>,
    /// Largest |fitted / value - 1| over them.
    pub max_abs_error: f64,
}

impl Quadratic {
    /// The value at phi.
    pub fn at(&self, phi: f64) -> f64 {
        let [a, b, c] = self.coefficients;
        a + phi * (b + phi * c)
    }

    /// Least squares through (phi, value) points; None with fewer than three.
    pub fn fit(points: &[(f64, f64)]) -> Option<Quadratic> {
        if points.len() < 3 {
            return None;
        }
        let mut m = [[0.0f64; 4]; 3];
        for &(x, y) in points {
            let basis = [1.0, x, x * x];
            for i in 0..3 {
                for j in 0..3 {
                    m[i][j] += basis[i] * basis[j];
                }
                m[i][3] += basis[i] * y;
            }
        }
        // Gaussian elimination with partial pivoting.
        for col in 0..3 {
            let pivot = (col..3).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
            m.swap(col, pivot);
            if m[col][col].abs() < 1e-300 {
                return None;
            }
            let pivot_row = m[col];
            for (row, line) in m.iter_mut().enumerate() {
                if row != col {
                    let f = line[col] / pivot_row[col];
                    for (x, p) in line.iter_mut().zip(pivot_row).skip(col) {
                        *x -= f * p;
                    }
                }
            }
        }
        let coefficients = [m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]];
        let mut q = Quadratic {
            coefficients,
            errors: Vec::new(),
            max_abs_error: 0.0,
        };
        q.errors = points
            .iter()
            .map(|&(x, y)| (x, y, q.at(x) / y - 1.0))
            .collect();
        q.max_abs_error = q.errors.iter().map(|e| e.2.abs()).fold(0.0, f64::max);
        Some(q)
    }
}

/// A held-out point checked against the fit.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    /// The excitation.
    pub excitation: String,
    /// phi.
    pub flexibility: f64,
    /// Critical peak acceleration over the fitted threshold k_A(phi) g B/H (at least 1: the
    /// acceleration condition holds).
    pub acceleration_margin: Option<f64>,
    /// Critical peak velocity over the fitted threshold k_V(phi) c B/sqrt(H) (at least 1: the
    /// velocity condition holds).
    pub velocity_margin: Option<f64>,
    /// r(phi) x rigid / critical - 1: the ratio fit's error on the point.
    pub ratio_error: Option<f64>,
}

/// The fits of one self-weight variant.
#[derive(Debug, Clone, Serialize)]
pub struct Fit {
    /// `body.self_weight`.
    pub self_weight: String,
    /// The range of phi fitted (the range of validity).
    pub flexibility_range: (f64, f64),
    /// Excitations fitted.
    pub fitted: Vec<String>,
    /// k_A(phi): smallest critical peak acceleration over g B/H.
    pub acceleration: Option<Quadratic>,
    /// k_V(phi): smallest critical peak velocity over c B/sqrt(H).
    pub velocity: Option<Quadratic>,
    /// r(phi): critical over Housner's full-equation block's, under the same motion.
    pub ratio: Option<Quadratic>,
    /// The held-out points.
    pub checks: Vec<Check>,
}

/// Fits the points of `self_weight` whose excitation is not in `held_out`, and checks those
/// that are. `height`, `width`, `gravity` are the body's.
pub fn fit(
    points: &[Point],
    self_weight: &str,
    held_out: &[String],
    (height, width, gravity): (f64, f64, f64),
) -> Fit {
    let a_scale = ishiyama_acceleration(width, height, gravity);
    let v_scale = ishiyama_velocity(width, height);
    let mine: Vec<&Point> = points
        .iter()
        .filter(|p| p.self_weight == self_weight && p.critical_pga.is_some())
        .collect();
    let (fitted, checked): (Vec<&Point>, Vec<&Point>) =
        mine.iter().partition(|p| !held_out.contains(&p.excitation));
    let mut moduli: Vec<f64> = fitted.iter().map(|p| p.youngs_modulus).collect();
    moduli.sort_by(f64::total_cmp);
    moduli.dedup();
    let mut envelope_a = Vec::new();
    let mut envelope_v = Vec::new();
    for e in &moduli {
        let same: Vec<&&Point> = fitted.iter().filter(|p| p.youngs_modulus == *e).collect();
        let phi = same[0].flexibility;
        let a = same
            .iter()
            .filter_map(|p| p.critical_pga)
            .fold(f64::INFINITY, f64::min);
        let v = same
            .iter()
            .filter_map(|p| p.critical_pgv())
            .fold(f64::INFINITY, f64::min);
        envelope_a.push((phi, a / a_scale));
        envelope_v.push((phi, v / v_scale));
    }
    let ratios: Vec<(f64, f64)> = fitted
        .iter()
        .filter_map(|p| Some((p.flexibility, p.critical_pga? / p.rigid_full_pga?)))
        .collect();
    let acceleration = Quadratic::fit(&envelope_a);
    let velocity = Quadratic::fit(&envelope_v);
    let ratio = Quadratic::fit(&ratios);
    let range = fitted
        .iter()
        .map(|p| p.flexibility)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    let checks = checked
        .iter()
        .map(|p| Check {
            excitation: p.excitation.clone(),
            flexibility: p.flexibility,
            acceleration_margin: acceleration
                .as_ref()
                .and_then(|q| Some(p.critical_pga? / (q.at(p.flexibility) * a_scale))),
            velocity_margin: velocity
                .as_ref()
                .and_then(|q| Some(p.critical_pgv()? / (q.at(p.flexibility) * v_scale))),
            ratio_error: ratio.as_ref().and_then(|q| {
                Some(q.at(p.flexibility) * p.rigid_full_pga? / p.critical_pga? - 1.0)
            }),
        })
        .collect();
    let mut names: Vec<String> = fitted.iter().map(|p| p.excitation.clone()).collect();
    names.dedup();
    Fit {
        self_weight: self_weight.to_string(),
        flexibility_range: range,
        fitted: names,
        acceleration,
        velocity,
        ratio,
        checks,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quadratic_is_fitted_exactly() {
        let f = |x: f64| 1.5 - 0.25 * x + 0.125 * x * x;
        let pts: Vec<(f64, f64)> = [0.1, 0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|&x| (x, f(x)))
            .collect();
        let q = Quadratic::fit(&pts).unwrap();
        for (c, e) in q.coefficients.iter().zip([1.5, -0.25, 0.125]) {
            assert!((c - e).abs() < 1e-12, "{c} {e}");
        }
        assert!(q.max_abs_error < 1e-12);
    }
}
