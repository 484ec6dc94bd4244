//! Units the model reads its inputs in: those of the model file's keys, and the standard
//! gravity that turns records in g into m/s^2.

/// Standard gravity, m/s^2, for records in units of g (independent of the body's `gravity`).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Units of the model file's numeric keys (for the message about a unit suffix, and for the
/// run header's excitation parameters).
const UNITS: [(&str, &str); 30] = [
    ("body.height", "m"),
    ("body.width", "m"),
    ("body.depth", "m"),
    ("body.density", "kg/m^3"),
    ("body.mass", "kg"),
    ("body.youngs_modulus", "Pa"),
    ("body.flexural_rigidity", "N m^2"),
    ("body.period", "s"),
    ("body.damping_ratio", "a ratio, no unit"),
    ("body.gravity", "m/s^2"),
    ("body.poisson_ratio", "a ratio, no unit"),
    ("excitation.amplitude", "m/s^2"),
    ("excitation.period", "s"),
    ("excitation.ramp", "s"),
    ("excitation.cycles", "a count, no unit"),
    ("excitation.center", "s"),
    ("excitation.scale", "a factor, no unit"),
    ("excitation.start", "s"),
    ("excitation.end", "s"),
    ("excitation.tail", "s"),
    ("excitation.dt", "s"),
    ("simulation.duration", "s"),
    ("simulation.q0", "m"),
    ("simulation.qdot0", "m/s"),
    ("solver.rtol", "a ratio, no unit"),
    ("solver.atol", "m"),
    ("solver.output_dt", "s"),
    ("solver.dt", "s"),
    ("fem.dt", "s"),
    ("fem.duration", "s"),
];

/// The unit of a model-file's numeric key (`excitation.amplitude`: "m/s^2"; a count or a ratio
/// says that it has none, "a count, no unit"); None for a key that is not a number.
pub fn unit_of_key(key: &str) -> Option<&'static str> {
    UNITS.iter().find(|(k, _)| *k == key).map(|(_, u)| *u)
}
