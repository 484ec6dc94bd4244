//! Units the model reads its inputs in: those of the model file's keys, and the standard
//! gravity that turns records in g into m/s^2.

/// Standard gravity, m/s^2, for records in units of g (independent of the body's `gravity`).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Units of the model file's numeric keys (for the message about a unit suffix, and for the
/// run header's excitation parameters).
const UNITS: [(&str, Unit); 31] = [
    ("body.height", Unit::Si("m")),
    ("body.width", Unit::Si("m")),
    ("body.depth", Unit::Si("m")),
    ("body.density", Unit::Si("kg/m^3")),
    ("body.mass", Unit::Si("kg")),
    ("body.youngs_modulus", Unit::Si("Pa")),
    ("body.flexural_rigidity", Unit::Si("N m^2")),
    ("body.period", Unit::Si("s")),
    ("body.damping_ratio", Unit::Dimensionless("a ratio")),
    ("body.gravity", Unit::Si("m/s^2")),
    ("body.poisson_ratio", Unit::Dimensionless("a ratio")),
    ("body.landing_restitution", Unit::Dimensionless("a ratio")),
    ("excitation.amplitude", Unit::Si("m/s^2")),
    ("excitation.period", Unit::Si("s")),
    ("excitation.ramp", Unit::Si("s")),
    ("excitation.cycles", Unit::Dimensionless("a count")),
    ("excitation.center", Unit::Si("s")),
    ("excitation.scale", Unit::Dimensionless("a factor")),
    ("excitation.start", Unit::Si("s")),
    ("excitation.end", Unit::Si("s")),
    ("excitation.tail", Unit::Si("s")),
    ("excitation.dt", Unit::Si("s")),
    ("simulation.duration", Unit::Si("s")),
    ("simulation.q0", Unit::Si("m")),
    ("simulation.qdot0", Unit::Si("m/s")),
    ("solver.rtol", Unit::Dimensionless("a ratio")),
    ("solver.atol", Unit::Si("m")),
    ("solver.output_dt", Unit::Si("s")),
    ("solver.dt", Unit::Si("s")),
    ("fem.dt", Unit::Si("s")),
    ("fem.duration", Unit::Si("s")),
];

/// The unit a number of the model file is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// An SI unit, by its symbol ("m/s^2").
    Si(&'static str),
    /// None: what the number is instead ("a ratio", "a count", "a factor").
    Dimensionless(&'static str),
}

impl Unit {
    /// The unit's symbol; None for a number without one.
    pub fn symbol(self) -> Option<&'static str> {
        match self {
            Unit::Si(symbol) => Some(symbol),
            Unit::Dimensionless(_) => None,
        }
    }
}

impl std::fmt::Display for Unit {
    /// The symbol, or what the number is: "m/s^2", "a count, no unit".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unit::Si(symbol) => f.write_str(symbol),
            Unit::Dimensionless(what) => write!(f, "{what}, no unit"),
        }
    }
}

/// The unit of a model file's numeric key (`excitation.amplitude`: m/s^2; `excitation.cycles`:
/// none, a count); None for a key that is not a number.
pub fn unit_of_key(key: &str) -> Option<Unit> {
    UNITS.iter().find(|(k, _)| *k == key).map(|(_, u)| *u)
}
