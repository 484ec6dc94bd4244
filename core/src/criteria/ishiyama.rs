//! Ishiyama's (1982) two conditions for the overturning of a rigid body, in the form most
//! commonly quoted: a body of full width B and full height H (m) on a rigid floor can overturn
//! only if the floor's peak acceleration exceeds g B/H **and** its peak velocity exceeds
//! c B/sqrt(H).
//!
//! Y. Ishiyama (1982), "Motions of rigid bodies and criteria for overturning by earthquake
//! excitations", Earthquake Engineering and Structural Dynamics 10, 635-650. The velocity
//! condition is quoted there as V > 10 B/sqrt(H) in cm/s with B and H in cm, that is
//! c = 10 cm^(1/2)/s = 1.0 m^(1/2)/s with B and H in m.

/// c of the velocity condition, m^(1/2)/s (10 cm^(1/2)/s).
// constants: see the anchors chapter
pub const VELOCITY_CONSTANT: f64 = 1.0;

/// The acceleration condition's threshold g B/H, m/s^2.
pub fn acceleration_threshold(height: f64, width: f64, gravity: f64) -> f64 {
    gravity * width / height
}

/// The velocity condition's threshold c B/sqrt(H), m/s.
pub fn velocity_threshold(height: f64, width: f64) -> f64 {
    VELOCITY_CONSTANT * width / height.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_velocity_condition_in_si_is_the_cgs_one() {
        // V > 10 B/sqrt(H) cm/s with B, H in cm, for B = 0.7 m, H = 4 m.
        let cgs = 10.0 * 70.0 / 400f64.sqrt(); // cm/s
        assert!((velocity_threshold(4.0, 0.7) - cgs / 100.0).abs() < 1e-12);
        assert!((acceleration_threshold(4.0, 0.7, 9.81) - 9.81 * 0.175).abs() < 1e-12);
    }
}
