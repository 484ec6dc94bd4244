//! How a dynamic run steps in time: the scheme, the step, friction, the output.

use serde::{Deserialize, Serialize};

use super::error::{check_positive, invalid, FemError};
use super::limits::{check_run_size, size_error, validate_mesh};

/// Time-stepping scheme.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TimeScheme {
    /// Newmark family: 0 < β <= 1/2, 1/2 <= γ <= 1.
    Newmark {
        /// β.
        beta: f64,
        /// γ.
        gamma: f64,
    },
    /// Wilson θ (linear acceleration over θ dt), θ >= 1.
    WilsonTheta {
        /// θ.
        theta: f64,
    },
}

impl TimeScheme {
    /// Linear acceleration method (Newmark β = 1/6, γ = 1/2), the paper's scheme.
    pub fn linear_acceleration() -> Self {
        Self::Newmark {
            beta: 1.0 / 6.0,
            gamma: 0.5,
        }
    }
    /// Average acceleration (Newmark β = 1/4, γ = 1/2), unconditionally stable.
    pub fn average_acceleration() -> Self {
        Self::Newmark {
            beta: 0.25,
            gamma: 0.5,
        }
    }
    /// Wilson θ = 1.4.
    pub fn wilson() -> Self {
        Self::WilsonTheta { theta: 1.4 }
    }
}

/// Mesh, time stepping, friction and output settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemSettings {
    /// Elements across the width (>= 1).
    pub nx: usize,
    /// Elements up the height (>= 1).
    pub ny: usize,
    /// Time step, s.
    pub dt: f64,
    /// Duration of the run, s.
    pub duration: f64,
    /// The time-stepping scheme.
    pub scheme: TimeScheme,
    /// Static friction coefficient μs.
    pub mu_s: f64,
    /// Kinetic friction coefficient μk <= μs.
    pub mu_k: f64,
    /// Include the geometric stiffness of the gravity prestress.
    pub p_delta: bool,
    /// Times (s) at which nodal displacements are stored (the first step at or after each).
    pub snapshot_times: Vec<f64>,
    /// Initial rigid rotation (rad, clockwise positive) about the right toe if positive, about
    /// the left toe if negative, applied at rest on top of the gravity state; the other base
    /// nodes start Free. 0 = upright.
    pub initial_rotation: f64,
}

impl FemSettings {
    /// The paper's analysis: 2 x 5 mesh, dt = 0.0071 s, 6 s, linear acceleration,
    /// μs = 0.8, μk = 0.4, with P-Delta.
    pub fn paper() -> Self {
        Self {
            nx: 2,
            ny: 5,
            dt: 0.0071,
            duration: 6.0,
            scheme: TimeScheme::linear_acceleration(),
            mu_s: 0.8,
            mu_k: 0.4,
            p_delta: true,
            snapshot_times: Vec::new(),
            initial_rotation: 0.0,
        }
    }
}

impl Default for FemSettings {
    fn default() -> Self {
        Self::paper()
    }
}

pub(super) fn validate_settings(settings: &FemSettings) -> Result<(), FemError> {
    validate_mesh(settings.nx, settings.ny)?;
    check_positive("dt", settings.dt)?;
    if !(settings.duration.is_finite() && settings.duration >= 0.0) {
        return Err(invalid(
            "duration",
            settings.duration,
            "must be finite and >= 0",
        ));
    }
    check_run_size(settings.nx, settings.ny, settings.dt, settings.duration).map_err(size_error)?;
    if !(settings.mu_s.is_finite() && settings.mu_s >= 0.0) {
        return Err(invalid("mu_s", settings.mu_s, "must be finite and >= 0"));
    }
    if !(settings.mu_k.is_finite() && settings.mu_k >= 0.0) {
        return Err(invalid("mu_k", settings.mu_k, "must be finite and >= 0"));
    }
    if settings.mu_k > settings.mu_s {
        return Err(invalid(
            "mu_k",
            settings.mu_k,
            "must be <= mu_s (kinetic friction cannot exceed static)",
        ));
    }
    match settings.scheme {
        TimeScheme::Newmark { beta, gamma } => {
            if !(beta.is_finite() && beta > 0.0 && beta <= 0.5) {
                return Err(invalid("beta", beta, "must lie in (0, 1/2]"));
            }
            if !(gamma.is_finite() && (0.5..=1.0).contains(&gamma)) {
                return Err(invalid("gamma", gamma, "must lie in [1/2, 1]"));
            }
        }
        TimeScheme::WilsonTheta { theta } => {
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(invalid("theta", theta, "must lie in [1, 3]"));
            }
        }
    }
    if let Some(t) = settings.snapshot_times.iter().find(|t| !t.is_finite()) {
        return Err(invalid("snapshot_times", t, "must be finite"));
    }
    if !(settings.initial_rotation.is_finite() && settings.initial_rotation.abs() < 0.5) {
        return Err(invalid(
            "initial_rotation",
            settings.initial_rotation,
            "must be finite with |rotation| < 0.5 rad (small-rotation kinematics)",
        ));
    }
    Ok(())
}
