//! The standard normal distribution function.

/// Phi(z), from the complementary error function of `libm` (a port of musl's, accurate to
/// an ulp or so), so that the tails keep their relative accuracy.
pub fn cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

/// ln Phi(z), accurate where Phi(z) underflows towards zero.
pub fn ln_cdf(z: f64) -> f64 {
    if z > -30.0 {
        cdf(z).ln()
    } else {
        // Mills ratio: Phi(z) ~ phi(z) / |z| (1 - 1/z^2 + 3/z^4) for z far below 0.
        let z2 = z * z;
        -0.5 * z2 - (-z).ln() - 0.5 * (2.0 * std::f64::consts::PI).ln()
            + (1.0 - 1.0 / z2 + 3.0 / (z2 * z2)).ln()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values() {
        // Tabulated: Phi(1) = 0.841344746068543, Phi(-1.96) = 0.0249978951482204.
        assert!((cdf(1.0) - 0.841_344_746_068_543).abs() < 1e-15);
        assert!((cdf(-1.96) - 0.024_997_895_148_220_4).abs() < 1e-15);
        assert_eq!(cdf(0.0), 0.5);
        // The two branches of ln Phi meet at z = -30 to many digits.
        let (a, b) = (cdf(-30.0).ln(), {
            let z: f64 = -30.0;
            let z2 = z * z;
            -0.5 * z2 - (-z).ln() - 0.5 * (2.0 * std::f64::consts::PI).ln()
                + (1.0 - 1.0 / z2 + 3.0 / (z2 * z2)).ln()
        });
        assert!((a - b).abs() < 1e-5 * a.abs(), "{a} {b}");
    }
}
