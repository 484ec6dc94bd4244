//! Values from outside the model file (command-line flags, Python arguments) that take
//! precedence over the file's.

use super::setting::Setting;

/// Values from outside the model file (command-line flags, Python arguments) that take
/// precedence over the file's.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    /// The solver (solver.method).
    pub method: Option<String>,
    /// Relative tolerance (solver.rtol).
    pub rtol: Option<f64>,
    /// Absolute tolerance (solver.atol), m.
    pub atol: Option<f64>,
    /// Duration (simulation.duration), s.
    pub duration: Option<f64>,
    /// Newmark time step (solver.dt).
    pub dt: Option<f64>,
    /// Newmark variant (solver.newmark_variant).
    pub newmark_variant: Option<String>,
    /// Any model-file key set to a value (`--set KEY=VALUE`), applied to the file's table
    /// before the fields above.
    pub settings: Vec<Setting>,
}

/// What a message about `solver.dt` set from outside the file adds when the method is not
/// Newmark's (the command line names the flags instead).
pub const DT_WITHOUT_NEWMARK: &str = " (solver.dt is read only with solver.method = \"newmark\")";

impl Overrides {
    /// The `--set` settings of the body's keys, as given ("--set body.youngs_modulus=100000",
    /// comma-separated); empty without any.
    pub fn body_settings(&self) -> String {
        self.settings
            .iter()
            .filter(|s| s.key.starts_with("body."))
            .map(|s| match s.value {
                // Shortest digits, with an exponent where large or small (1e-300, not 300
                // digits of zeros).
                toml::Value::Float(x) => format!("--set {}={x:?}", s.key),
                ref other => format!("--set {}={other}", s.key),
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Whether a value from outside the model file set the key `key` (an error about it is then
    /// not the file's: the caller names it as it was given, e.g. by the flag that set it).
    pub fn sets(&self, key: &str) -> bool {
        let field = match key {
            "solver.method" => self.method.is_some(),
            "solver.rtol" => self.rtol.is_some(),
            "solver.atol" => self.atol.is_some(),
            "solver.dt" => self.dt.is_some(),
            "solver.newmark_variant" => self.newmark_variant.is_some(),
            "simulation.duration" => self.duration.is_some(),
            _ => false,
        };
        field || self.settings.iter().any(|s| s.key == key)
    }
}
