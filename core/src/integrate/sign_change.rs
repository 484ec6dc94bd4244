//! Where a function of time passes from one side of zero to the other, by the Illinois variant
//! of regula falsi: the one root finder of the bodies of the diffsol event loop (the single body
//! and the compliant row), which locate each event on a step's dense output.

/// The time in [lo, hi] at which `f` passes from the sign it has at `lo` (zero counts as that
/// side: a state that starts on a guard is not past it) to the sign it has at `hi`, to a few
/// ulps of t. Returns `lo` when `f` has at `lo` the sign it has at `hi` (already past).
/// `f` may fail (a dense output that cannot be evaluated); its error is passed on.
pub(crate) fn locate<E>(
    mut lo: f64,
    mut hi: f64,
    f: impl Fn(f64) -> Result<f64, E>,
) -> Result<f64, E> {
    // Orient f so that the far end is positive; then "past" means g > 0.
    let f_hi = f(hi)?;
    let orientation = if f_hi > 0.0 { 1.0 } else { -1.0 };
    let mut g_lo = orientation * f(lo)?;
    let mut g_hi = orientation * f_hi;
    if g_lo > 0.0 || g_hi <= 0.0 {
        return Ok(if g_lo > 0.0 { lo } else { hi });
    }
    let mut last_side = 0i8;
    for _ in 0..200 {
        if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()) {
            break;
        }
        let secant = hi - g_hi * (hi - lo) / (g_hi - g_lo);
        // Fall back to bisection when the secant leaves the bracket or stalls at its ends.
        let mid = if secant > lo && secant < hi {
            secant
        } else {
            0.5 * (lo + hi)
        };
        let g_mid = orientation * f(mid)?;
        if g_mid > 0.0 {
            hi = mid;
            g_hi = g_mid;
            if last_side == 1 {
                g_lo *= 0.5;
            }
            last_side = 1;
        } else {
            lo = mid;
            g_lo = g_mid;
            if last_side == -1 {
                g_hi *= 0.5;
            }
            last_side = -1;
        }
    }
    Ok(hi)
}

#[cfg(test)]
mod tests {
    use super::locate;

    #[test]
    fn finds_the_sign_change_to_a_few_ulps() {
        // A root of cos t - t (the Dottie number) and one of a cubic with a flat side.
        let dottie = 0.739_085_133_215_160_6_f64;
        let t = locate(0.0, 1.0, |t: f64| Ok::<_, ()>(t.cos() - t)).unwrap();
        assert!((t - dottie).abs() <= 4.0 * f64::EPSILON, "{t}");
        let t = locate(-1.0, 3.0, |t: f64| Ok::<_, ()>((t - 0.3).powi(3))).unwrap();
        assert!((t - 0.3).abs() < 1e-5, "{t}");
        // Either direction of the change; no change (the sign at hi is the sign at lo): lo.
        let t = locate(0.0, 1.0, |t: f64| Ok::<_, ()>(0.5 - t)).unwrap();
        assert!((t - 0.5).abs() <= 4.0 * f64::EPSILON, "{t}");
        assert_eq!(locate(0.0, 1.0, |t: f64| Ok::<_, ()>(t + 1.0)), Ok(0.0));
        assert_eq!(
            locate(0.0, 1.0, |_| Err::<f64, _>("no output")),
            Err("no output")
        );
    }
}
