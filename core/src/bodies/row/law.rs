//! The compliant contact law's dashpot (book/src/row.md §4a): how much of it gives Newton's
//! restitution e.
//!
//! While two faces are pressed together the contact force is P = k delta + c delta', with
//! delta = -gap > 0 the penetration (Anagnostopoulos 1988), and the contact is let go where P
//! falls through zero (the faces cannot pull). Two contact points alone, of reduced mass m_red,
//! meeting at closing speed v0 follow delta'' + 2 zeta w delta' + w^2 delta = 0 with
//! w^2 = k / m_red and c = 2 zeta w m_red, from delta = 0, delta' = v0. Their force vanishes
//! where delta'' = 0, and they leave at -delta' = e v0 there with
//!
//! ```text
//! ln e = -2 zeta acos(zeta) / sqrt(1 - zeta^2)      (zeta < 1, at t = 2 acos(zeta) / w_d)
//! ln e = -2 zeta acosh(zeta) / sqrt(zeta^2 - 1)     (zeta > 1),
//! ```
//!
//! one analytic function of zeta, -2 at zeta = 1, falling from 0 at zeta = 0 to -infinity
//! (e ~ 1 / (4 zeta^2) for large zeta): e(zeta) is monotone, and [`damping_ratio_for`] inverts
//! it by bisection. e = 0 would need an infinite dashpot.

/// e of two contact points alone with damping ratio `zeta` >= 0, released where the force
/// falls to zero.
pub fn restitution_of(zeta: f64) -> f64 {
    log_restitution(zeta).exp()
}

/// ln e(zeta), by the closed form of the module's documentation.
fn log_restitution(zeta: f64) -> f64 {
    if zeta == 0.0 {
        return 0.0;
    }
    let x = 1.0 - zeta;
    // Near zeta = 1 both forms lose digits to cancellation: acos(1 - x) / sqrt(x (2 - x)) =
    // 1 + x/3 + 2 x^2/15 + O(x^3).
    let ratio = if x.abs() < 1e-4 {
        1.0 + x / 3.0 + 2.0 * x * x / 15.0
    } else if zeta < 1.0 {
        zeta.acos() / (1.0 - zeta * zeta).sqrt()
    } else {
        zeta.acosh() / (zeta * zeta - 1.0).sqrt()
    };
    -2.0 * zeta * ratio
}

/// The damping ratio zeta whose contact restitutes `e` in (0, 1], released at zero force.
/// `e` = 1 gives 0 (no dashpot).
pub fn damping_ratio_for(e: f64) -> f64 {
    assert!(e > 0.0 && e <= 1.0, "restitution {e} outside (0, 1]");
    if e == 1.0 {
        return 0.0;
    }
    let target = e.ln();
    // ln e(zeta) falls monotonically: bracket, then bisect to the last bit.
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while log_restitution(hi) > target {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if log_restitution(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// How long the contact of two points alone lasts, s: from delta = 0 to the zero of the force,
/// with natural frequency `omega` (rad/s) and damping ratio `zeta`.
pub fn release_time(zeta: f64, omega: f64) -> f64 {
    if (zeta - 1.0).abs() < 1e-12 {
        return 2.0 / omega;
    }
    if zeta < 1.0 {
        2.0 * zeta.acos() / (omega * (1.0 - zeta * zeta).sqrt())
    } else {
        2.0 * zeta.acosh() / (omega * (zeta * zeta - 1.0).sqrt())
    }
}

/// Anagnostopoulos' damping ratio for `e`, which restitutes e where the penetration returns to
/// zero (the force then being tensile): -ln e / sqrt(pi^2 + ln^2 e).
pub fn damping_ratio_released_at_zero_penetration(e: f64) -> f64 {
    let l = e.ln();
    -l / (std::f64::consts::PI * std::f64::consts::PI + l * l).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// delta'' + 2 zeta w delta' + w^2 delta = 0 from (0, 1) by classical Runge-Kutta with a
    /// fine step, to the zero of delta'' (the force), interpolated linearly: -delta' there.
    fn integrated_restitution(zeta: f64) -> (f64, f64) {
        let w = 1.0;
        let acc = |d: f64, v: f64| -2.0 * zeta * w * v - w * w * d;
        let (mut t, mut d, mut v) = (0.0, 0.0, 1.0);
        let h = 1e-4;
        loop {
            let (k1d, k1v) = (v, acc(d, v));
            let (k2d, k2v) = (v + 0.5 * h * k1v, acc(d + 0.5 * h * k1d, v + 0.5 * h * k1v));
            let (k3d, k3v) = (v + 0.5 * h * k2v, acc(d + 0.5 * h * k2d, v + 0.5 * h * k2v));
            let (k4d, k4v) = (v + h * k3v, acc(d + h * k3d, v + h * k3v));
            let nd = d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
            let nv = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            let (a0, a1) = (acc(d, v), acc(nd, nv));
            if a0 < 0.0 && a1 >= 0.0 {
                let s = a0 / (a0 - a1);
                return (-(v + s * (nv - v)), t + s * h);
            }
            (t, d, v) = (t + h, nd, nv);
        }
    }

    #[test]
    fn the_closed_form_is_the_integrated_contact() {
        for zeta in [0.02, 0.3, 0.9, 0.99999, 1.0, 1.00001, 1.5, 6.0] {
            let (e, t) = integrated_restitution(zeta);
            assert!(
                (restitution_of(zeta) - e).abs() < 1e-7,
                "zeta = {zeta}: {} vs {e}",
                restitution_of(zeta)
            );
            assert!((release_time(zeta, 1.0) - t).abs() < 1e-6, "zeta = {zeta}");
        }
        assert!((restitution_of(1.0) - (-2.0_f64).exp()).abs() < 1e-15);
    }

    #[test]
    fn the_inverse_restitutes_e_and_e_falls_with_zeta() {
        let mut last = 1.0;
        for k in 1..2000 {
            let e = restitution_of(k as f64 * 0.005);
            assert!(e < last, "not monotone at zeta = {}", k as f64 * 0.005);
            last = e;
        }
        for e in [1e-3, 0.05, 0.1353, 0.3, 0.6, 0.9, 0.999] {
            let zeta = damping_ratio_for(e);
            assert!(
                (restitution_of(zeta) - e).abs() < 1e-13 * e.max(1e-3),
                "e = {e}"
            );
            // Releasing at zero force needs more damping than releasing at zero penetration:
            // the force falls to zero first, before the dashpot has taken as much.
            assert!(zeta > damping_ratio_released_at_zero_penetration(e));
        }
        assert_eq!(damping_ratio_for(1.0), 0.0);
    }
}
