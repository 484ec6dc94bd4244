//! Inclusive limits, checked so that the limit's own decimal value passes.
//!
//! A limit computed from a product or a quotient (0.01 B, 20 g, T from a given period, a step
//! count duration/dt) carries the rounding of that arithmetic: 0.01 * 0.7 is
//! 0.006999999999999999 and 20 * 9.80665 is 196.13299999999998, so a plain comparison would
//! refuse `atol = 0.007` for B = 0.7 m and an amplitude of exactly 20 g. An inclusive limit
//! therefore admits values within a few units in the last place beyond it, far below any
//! difference a person means, and messages print the limit rounded as a person writes it
//! ([`crate::base::format::readable`]).

/// Longest simulated time, s.
pub const MAX_DURATION: f64 = 1e4;

/// Relative slack of an inclusive limit: a few units in the last place.
const SLACK: f64 = 8.0 * f64::EPSILON;

/// `value <= limit`, admitting `value` within rounding of `limit` (NaN is not admitted).
pub fn at_most(value: f64, limit: f64) -> bool {
    value <= limit + SLACK * limit.abs()
}

/// `value >= limit`, admitting `value` within rounding of `limit` (NaN is not admitted).
pub fn at_least(value: f64, limit: f64) -> bool {
    value >= limit - SLACK * limit.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limit_computed_with_rounding_admits_its_decimal_value() {
        // 0.01 * 0.7 and 20 * 9.80665 round below the decimal values 0.007 and 196.133.
        let (width, g) = (std::hint::black_box(0.7), std::hint::black_box(9.80665));
        assert!(0.01 * width < 0.007);
        assert!(at_most(0.007, 0.01 * width));
        assert!(20.0 * g < 196.133);
        assert!(at_most(196.133, 20.0 * g));
        assert!(at_least(1e-4, 1e-4 * (1.0 + 2.0 * f64::EPSILON)));
    }

    #[test]
    fn values_meaningfully_beyond_the_limit_are_refused() {
        assert!(!at_most(0.00700001, 0.007));
        assert!(!at_most(196.1331, 196.133));
        assert!(!at_least(0.99999e-4, 1e-4));
        assert!(!at_most(f64::NAN, 1.0));
        assert!(!at_least(f64::NAN, 1.0));
        assert!(!at_most(f64::INFINITY, 1.0));
    }
}
