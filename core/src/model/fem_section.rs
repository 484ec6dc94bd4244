//! Rules of the `[fem]` section and `body.poisson_ratio`: the finite element analysis.

use serde::Serialize;

use super::schema::{FemOverrides, FemSection, ModelFile};
use crate::base::format::readable;
use crate::bodies::fem::{
    check_run_size, BaseSupport, FemBody, FemSettings, SizeLimit, TimeScheme,
};
use crate::error::{Error, Result};
use crate::physics::body::{positive, Body};
use crate::physics::constants::Constants;

/// Default Poisson's ratio of the plane-stress body (`[body] poisson_ratio`).
pub const DEFAULT_POISSON_RATIO: f64 = 0.25;

/// A validated finite element analysis: the plane-stress body and the run settings.
#[derive(Debug, Clone, Serialize)]
pub struct FemSetup {
    /// The plane-stress body.
    pub body: FemBody,
    /// Mesh, time stepping, friction and output settings.
    pub settings: FemSettings,
    /// The scheme's name as written in the model file.
    pub scheme_name: &'static str,
}

/// Default elements across the width (`[fem] nx`), the paper's mesh.
pub const DEFAULT_FEM_NX: usize = 2;
/// Default elements up the height (`[fem] ny`), the paper's mesh.
pub const DEFAULT_FEM_NY: usize = 5;
/// Default time step of the finite element run (`[fem] dt`), s.
pub const DEFAULT_FEM_DT: f64 = 0.0071;
/// Default Wilson θ (`[fem] theta`).
pub const DEFAULT_FEM_THETA: f64 = 1.4;
/// Default static friction coefficient μs (`[fem] mu_s`).
pub const DEFAULT_FEM_MU_S: f64 = 0.8;
/// Default kinetic friction coefficient μk (`[fem] mu_k`).
pub const DEFAULT_FEM_MU_K: f64 = 0.4;
/// Deformed shapes are stored at these times (the paper's Fig. 9), s.
pub const FEM_SNAPSHOT_TIMES: [f64; 6] = [0.9, 1.0, 1.1, 1.2, 1.3, 1.4];

/// The model-file keys of the settings `flexrock fem` can override.
struct Names {
    nx: &'static str,
    ny: &'static str,
    dt: &'static str,
    scheme: &'static str,
}

const FILE_NAMES: Names = Names {
    nx: "fem.nx",
    ny: "fem.ny",
    dt: "fem.dt",
    scheme: "fem.scheme",
};

/// Builds the finite element analysis from `[body]` and `[fem]`, with command-line values in
/// place of the file's, checked by the same rules; messages name the model-file key
/// ([`FemOverrides::sets`] tells which values came from outside the file). The plane-stress body
/// takes E = 12 EI/(D B^3) and the density M/(H B D) from the validated body, so every way of
/// giving the stiffness and the mass works; the damping period defaults to the pre-uplift period
/// T. Every rule is here, the size limits of `crate::bodies::fem` included. Only `flexrock fem` builds
/// it: `run` and `sweep` do not fail for settings that only the finite element analysis uses.
pub fn fem_with_overrides(
    file: &ModelFile,
    body: &Body,
    constants: &Constants,
    simulation_duration: f64,
    overrides: &FemOverrides,
) -> Result<FemSetup> {
    let mut file = file.clone();
    let section = file.fem.get_or_insert_with(FemSection::default);
    section.nx = overrides.nx.or(section.nx);
    section.ny = overrides.ny.or(section.ny);
    section.dt = overrides.dt.or(section.dt);
    if let Some(scheme) = &overrides.scheme {
        section.scheme = Some(scheme.clone());
    }
    fem_setup(&file, body, constants, simulation_duration, &FILE_NAMES)
}

fn fem_setup(
    file: &ModelFile,
    body: &Body,
    constants: &Constants,
    simulation_duration: f64,
    names: &Names,
) -> Result<FemSetup> {
    let default = FemSection::default();
    let s = file.fem.as_ref().unwrap_or(&default);
    let poisson_ratio = file.body.poisson_ratio.unwrap_or(DEFAULT_POISSON_RATIO);
    if !(poisson_ratio.is_finite() && (0.0..0.5).contains(&poisson_ratio)) {
        return Err(Error::invalid(
            "body.poisson_ratio",
            poisson_ratio,
            "Poisson's ratio must lie in [0, 0.5)",
        ));
    }
    let nx = s.nx.unwrap_or(DEFAULT_FEM_NX);
    let ny = s.ny.unwrap_or(DEFAULT_FEM_NY);
    let dt = s.dt.unwrap_or(DEFAULT_FEM_DT);
    positive(names.dt, dt)?;
    let (duration, duration_key) = match s.duration {
        Some(d) => (d, "fem.duration"),
        None => (simulation_duration, "simulation.duration"),
    };
    positive("fem.duration", duration)?;
    let size_error = |limit: SizeLimit| {
        let rule = limit.rule();
        match limit {
            SizeLimit::Nx(n) => Error::invalid(names.nx, n, &rule),
            SizeLimit::Ny(n) => Error::invalid(names.ny, n, &rule),
            SizeLimit::Band { nx, ny } => Error::invalid(
                &format!("{}, {}", names.nx, names.ny),
                format!("{nx}, {ny}"),
                &rule,
            ),
            SizeLimit::Steps { .. } | SizeLimit::Work { .. } => Error::invalid(
                names.dt,
                dt,
                &format!("over {duration_key} = {} s {rule}", readable(duration)),
            ),
        }
    };
    if file.fem.is_none() {
        // The defaults: only the mesh (see above).
        crate::bodies::fem::check_mesh_size(nx, ny).map_err(size_error)?;
    } else {
        if dt > duration {
            return Err(Error::invalid(
                names.dt,
                dt,
                &format!(
                    "the time step must not exceed the duration of the analysis, {duration_key} \
                     = {} s (there would be no step after t = 0)",
                    readable(duration)
                ),
            ));
        }
        check_run_size(nx, ny, dt, duration).map_err(size_error)?;
    }
    let name = s.scheme.as_deref().unwrap_or("linear-acceleration");
    let (scheme, scheme_name) = match name {
        "linear-acceleration" => (TimeScheme::linear_acceleration(), "linear-acceleration"),
        "average-acceleration" => (TimeScheme::average_acceleration(), "average-acceleration"),
        "wilson-theta" => {
            let theta = s.theta.unwrap_or(DEFAULT_FEM_THETA);
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(Error::invalid("fem.theta", theta, "must lie in [1, 3]"));
            }
            (TimeScheme::WilsonTheta { theta }, "wilson-theta")
        }
        other => {
            return Err(Error::invalid(
                names.scheme,
                format!("\"{other}\""),
                "must be \"linear-acceleration\", \"average-acceleration\" or \"wilson-theta\"",
            ))
        }
    };
    if let (Some(theta), false) = (s.theta, scheme_name == "wilson-theta") {
        return Err(Error::invalid(
            "fem.theta",
            theta,
            &format!("not a parameter of scheme = \"{scheme_name}\" (only of \"wilson-theta\")"),
        ));
    }
    let mu_s = s.mu_s.unwrap_or(DEFAULT_FEM_MU_S);
    let mu_k = s.mu_k.unwrap_or(DEFAULT_FEM_MU_K);
    for (key, mu) in [("fem.mu_s", mu_s), ("fem.mu_k", mu_k)] {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::invalid(
                key,
                mu,
                "a friction coefficient must be finite and >= 0",
            ));
        }
    }
    if mu_k > mu_s {
        return Err(Error::invalid(
            "fem.mu_k",
            mu_k,
            &format!(
                "kinetic friction cannot exceed static friction (fem.mu_s = {})",
                crate::base::format::shortest(mu_s)
            ),
        ));
    }
    let base_name = s.base.as_deref().unwrap_or(BaseSupport::Flexible.name());
    let base = BaseSupport::from_name(base_name).ok_or_else(|| {
        Error::invalid(
            "fem.base",
            format!("\"{base_name}\""),
            "must be \"flexible\" (base nodes touch the floor one by one) or \"rigid-plate\"",
        )
    })?;
    let damping_period = s.damping_period.unwrap_or(constants.period);
    positive("fem.damping_period", damping_period)?;
    if damping_period > crate::base::limits::MAX_DURATION {
        // The damping is C = (h T_d / pi) K: at 1e12 s it swamps the mass in the stepped matrix,
        // which rounds to singular.
        return Err(Error::invalid(
            "fem.damping_period",
            damping_period,
            &format!(
                "must be at most {:e} s, the longest run: a vibration of a longer period is never \
                 seen, and far beyond it the damping matrix swamps the mass matrix",
                crate::base::limits::MAX_DURATION
            ),
        ));
    }
    let fem_body = FemBody {
        height: body.height,
        width: body.width,
        depth: body.depth,
        density: body.mass / (body.height * body.width * body.depth),
        youngs_modulus: 12.0 * body.flexural_rigidity / (body.depth * body.width.powi(3)),
        poisson_ratio,
        damping_ratio: body.damping_ratio,
        damping_period,
        gravity: body.gravity,
        base,
    };
    let settings = FemSettings {
        nx,
        ny,
        dt,
        duration,
        scheme,
        mu_s,
        mu_k,
        p_delta: s.p_delta.unwrap_or(true),
        snapshot_times: FEM_SNAPSHOT_TIMES.to_vec(),
        initial_rotation: 0.0,
    };
    Ok(FemSetup {
        body: fem_body,
        settings,
        scheme_name,
    })
}
