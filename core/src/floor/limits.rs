//! The limits every floor motion keeps: the largest and smallest peak acceleration, and the
//! shortest period.

/// Largest floor acceleration a model may have, m/s^2: 20 g. No earthquake record and no seismic
/// shaking table comes near it (the largest recorded ground accelerations are a few g), and far
/// beyond it the numbers stop meaning anything (a floor of 1e150 m/s^2 left one method running
/// forever).
pub const MAX_FLOOR_ACCELERATION: f64 = 20.0 * crate::base::units::STANDARD_GRAVITY;

/// True when a peak floor acceleration `peak` (m/s^2) is within [`MAX_FLOOR_ACCELERATION`]
/// (NaN is not).
pub fn within_floor_limit(peak: f64) -> bool {
    crate::base::limits::at_most(peak, MAX_FLOOR_ACCELERATION)
}

/// The rule a peak floor acceleration beyond the limit breaks, for error messages.
pub fn floor_limit_rule(peak: f64) -> String {
    let peak = if peak.is_finite() {
        format!("{peak:.6e} m/s^2")
    } else {
        "beyond the range of numbers".to_string()
    };
    format!(
        "the peak floor acceleration {peak} is beyond the limit of {} m/s^2 (20 g)",
        crate::base::format::readable(MAX_FLOOR_ACCELERATION)
    )
}

/// Smallest peak floor acceleration other than 0, m/s^2. The body's response is of the order
/// of A T^2 / (4 pi^2), and with T at least [`crate::physics::constants::MIN_PERIOD`] (1e-4 s) a peak of
/// 1e-140 m/s^2 keeps it above 1e-150 m, where its square is still a normal floating-point
/// number (from 2.2e-308 on); below, the closed forms lose their digits to underflow. No floor
/// motion is anywhere near it: 1e-140 m/s^2 is a displacement of 1e-140 m in a second.
pub const MIN_FLOOR_ACCELERATION: f64 = 1e-140;

/// True when a peak floor acceleration `peak` (m/s^2) is 0 or at least
/// [`MIN_FLOOR_ACCELERATION`].
pub fn above_floor_minimum(peak: f64) -> bool {
    peak == 0.0 || peak.abs() >= MIN_FLOOR_ACCELERATION
}

/// The rule a nonzero peak floor acceleration below the minimum breaks, for error messages.
pub fn floor_minimum_rule(peak: f64) -> String {
    format!(
        "the peak floor acceleration {} m/s^2 is neither 0 nor at least {} m/s^2: the body's \
         response would be below 1e-150 m, where floating point loses its digits",
        crate::base::format::shortest(peak.abs()),
        crate::base::format::shortest(MIN_FLOOR_ACCELERATION)
    )
}

/// Shortest period of an analytic floor motion, s: 1 ms, far above any frequency of earthquake or
/// shaking-table motion, and a motion faster than that would take the solvers millions of steps
/// per simulated second.
pub const MIN_EXCITATION_PERIOD: f64 = 1e-3;
