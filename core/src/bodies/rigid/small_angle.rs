//! The exact propagator of the small-angle equation, q'' = k^2 (q - s B) - (3/2) a(t), within a
//! stretch of rocking (the forcing integrals by Gauss-Legendre quadrature).

use crate::floor::FloorMotion;

/// Nodes (positive half) and weights of the 8-point Gauss-Legendre rule on [-1, 1].
const GAUSS_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GAUSS_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// The exact propagator of a rocking block (see the module documentation).
#[derive(Clone, Copy)]
pub(super) struct Propagator<'a> {
    pub(super) floor: &'a dyn FloorMotion,
    /// When the floor comes to rest for good ([`FloorMotion::quiet_after`]).
    pub(super) quiet_after: Option<f64>,
    pub(super) k: f64,
    pub(super) width: f64,
}

impl Propagator<'_> {
    /// (q, q') a time `tau` after t0, from (q0, v0) at t0 rocking on `side`.
    pub(super) fn propagate(&self, t0: f64, q0: f64, v0: f64, side: f64, tau: f64) -> (f64, f64) {
        self.propagate_small_angle(t0, q0, v0, side, tau)
    }

    /// The exact solution of q'' = k^2 (q - side B) - (3/2) a(t), with the forcing integrals by
    /// 8-point Gauss-Legendre quadrature.
    fn propagate_small_angle(&self, t0: f64, q0: f64, v0: f64, side: f64, tau: f64) -> (f64, f64) {
        let k = self.k;
        let (sinh, cosh) = ((k * tau).sinh(), (k * tau).cosh());
        let half_sinh = (0.5 * k * tau).sinh();
        let (mut int_sinh, mut int_cosh) = (0.0, 0.0);
        // Once the floor is at rest for good the forcing integrals vanish.
        let forced = self.quiet_after.is_none_or(|quiet| t0 < quiet);
        if forced {
            let half = 0.5 * tau;
            for (x, w) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
                for u in [half * (1.0 - x), half * (1.0 + x)] {
                    let f = -1.5 * self.floor.acceleration(t0 + u);
                    // sinh and cosh of the lag from one exponential.
                    let grow = (k * (tau - u)).exp();
                    let decay = 1.0 / grow;
                    int_sinh += w * 0.5 * (grow - decay) * f;
                    int_cosh += w * 0.5 * (grow + decay) * f;
                }
            }
            int_sinh *= half;
            int_cosh *= half;
        }
        let q = q0 * cosh - 2.0 * side * self.width * half_sinh * half_sinh
            + v0 / k * sinh
            + int_sinh / k;
        let v = (q0 - side * self.width) * k * sinh + v0 * cosh + int_cosh;
        (q, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gauss_rule_is_exact_to_degree_15() {
        // int_{-1}^{1} x^n dx = 2/(n + 1) for even n, 0 for odd n.
        for n in 0..=15 {
            let mut sum = 0.0;
            for (x, w) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
                sum += w * (x.powi(n) + (-x).powi(n));
            }
            let exact = if n % 2 == 0 {
                2.0 / (n as f64 + 1.0)
            } else {
                0.0
            };
            assert!((sum - exact).abs() < 2e-15, "x^{n}: {sum} against {exact}");
        }
    }
}
