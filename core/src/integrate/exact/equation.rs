//! The mode's linear equation x'' + c x' + k x = f, which every flow of the exact method
//! solves: its higher derivatives at a point, and how far its series form reaches.

/// Largest rho = max(|k|^(1/2), |c|, forcing rate) tau of a flow of the series form.
pub(crate) const SERIES_REACH: f64 = 0.5;

/// x'' and x''' from the mode's equation x'' + c x' + k x = f at a point, given f and f' there.
#[inline(always)]
pub(crate) fn by_the_equation(k: f64, c: f64, [f, df]: [f64; 2], x: f64, v: f64) -> (f64, f64) {
    let acc = f - k * x - c * v;
    (acc, df - k * v - c * acc)
}
