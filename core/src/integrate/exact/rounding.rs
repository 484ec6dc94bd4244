//! The rounding of times: the spacing of doubles at a time, and lengths equal but for it.

/// Units in the last place of the piece's end time (the rounding of the grid's times) and of
/// h by which a piece may be longer or shorter than the length the forms were built for.
const LENGTH_ULPS: f64 = 4.0;

/// The spacing of doubles at |t|.
pub(crate) fn ulp(t: f64) -> f64 {
    let t = t.abs().max(f64::MIN_POSITIVE);
    f64::from_bits(t.to_bits() + 1) - t
}

/// Whether a piece of length `h` ending at `t` has the length `length` but for the rounding of
/// the grid's times.
pub(crate) fn near(h: f64, length: f64, t: f64) -> bool {
    (h - length).abs() <= LENGTH_ULPS * (ulp(t) + f64::EPSILON * length)
}
