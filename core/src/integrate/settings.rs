//! Which solver a model runs with, and its settings.

use serde::Serialize;

use super::{adaptive, exact, newmark};

/// Which solver a model runs with, and its settings.
#[derive(Debug, Clone, Copy)]
pub enum SolverSettings {
    /// An adaptive diffsol method.
    Adaptive(adaptive::AdaptiveSettings),
    /// Newmark's method with a fixed step.
    Newmark(newmark::NewmarkSettings),
    /// The closed-form solution within each mode.
    Exact(exact::ExactSettings),
}

impl SolverSettings {
    /// The method's name in statistics and tables, e.g. "bdf" or "newmark-compensate".
    pub fn label(&self) -> String {
        match self {
            SolverSettings::Adaptive(a) => a.method.name().to_string(),
            SolverSettings::Newmark(n) => n.label(),
            SolverSettings::Exact(_) => exact::NAME.to_string(),
        }
    }

    /// Spacing of the sampled history, s.
    pub fn output_dt(&self) -> f64 {
        match self {
            SolverSettings::Adaptive(a) => a.output_dt,
            SolverSettings::Newmark(n) => n.output_dt,
            SolverSettings::Exact(e) => e.output_dt,
        }
    }
}

/// Serialised with the model file's key names, so that summary.json reads like `[solver]`.
impl Serialize for SolverSettings {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct NewmarkKeys {
            method: &'static str,
            dt: f64,
            newmark_beta: f64,
            newmark_gamma: f64,
            newmark_variant: &'static str,
            output_dt: f64,
        }
        #[derive(Serialize)]
        struct ExactKeys {
            method: &'static str,
            output_dt: f64,
        }
        match self {
            SolverSettings::Exact(e) => ExactKeys {
                method: exact::NAME,
                output_dt: e.output_dt,
            }
            .serialize(serializer),
            SolverSettings::Adaptive(a) => a.serialize(serializer),
            SolverSettings::Newmark(n) => NewmarkKeys {
                method: "newmark",
                dt: n.dt,
                newmark_beta: n.beta,
                newmark_gamma: n.gamma,
                newmark_variant: n.variant.name(),
                output_dt: n.output_dt,
            }
            .serialize(serializer),
        }
    }
}
