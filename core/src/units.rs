//! Units the model reads its inputs in: the standard gravity that turns records in g into m/s^2.

/// Standard gravity, m/s^2, for records in units of g (independent of the body's `gravity`).
pub const STANDARD_GRAVITY: f64 = 9.80665;
