//! Rules of the `[solver]` section: the adaptive methods' tolerances and Newmark's step.

use super::schema::{SolverSection, DEFAULT_ATOL, DEFAULT_OUTPUT_DT, DEFAULT_RTOL};
use crate::error::{Error, Result};
use crate::integrate::adaptive::{AdaptiveMethod, AdaptiveSettings};
use crate::integrate::exact::ExactSettings;
use crate::integrate::newmark::{critical_omega_dt, NewmarkSettings, NewmarkVariant};
use crate::integrate::{History, SolverSettings};
use crate::physics::body::positive;

/// The paper's time step (section 2.5).
pub const DEFAULT_NEWMARK_DT: f64 = 0.02;
/// Linear acceleration, the paper's choice.
pub const DEFAULT_NEWMARK_BETA: f64 = 1.0 / 6.0;
/// Newmark gamma = 1/2: no numerical damping.
pub const DEFAULT_NEWMARK_GAMMA: f64 = 0.5;
/// More Newmark steps than this is a mistake in dt, not a wish.
const MAX_NEWMARK_STEPS: f64 = 1e8;
/// More history rows than this is a mistake in output_dt, not a wish.
const MAX_SAMPLES: f64 = 1e6;
/// Loosest relative tolerance of the adaptive methods: beyond it the solution is not worth having
/// (at rtol = 0.5 the paper's example logs 817 uplifts and an overturning instead of 11 and none).
pub const MAX_RTOL: f64 = 1e-2;
/// Tightest relative tolerance: below it rounding (1e-16 of t and q) is the error of every step.
pub const MIN_RTOL: f64 = 1e-14;
/// Loosest absolute tolerance, as a share of the width B: beyond it neither uplift (at s_n < B)
/// nor overturning (at q = B) is resolved.
pub const MAX_ATOL_OVER_WIDTH: f64 = 1e-2;

/// The rule for a relative tolerance; `key` names where it came from.
pub(crate) fn check_rtol(key: &str, rtol: f64) -> Result<()> {
    if (MIN_RTOL..=MAX_RTOL).contains(&rtol) {
        Ok(())
    } else {
        Err(Error::invalid(
            key,
            rtol,
            &format!("the relative tolerance must lie in [{MIN_RTOL:e}, {MAX_RTOL:e}]"),
        ))
    }
}

/// Tightest absolute tolerance, as a share of the width B: q ranges over B, whose rounding is
/// 1.1e-16 B; far below it (1e-30 B, say) the adaptive methods find no step small enough.
pub const MIN_ATOL_OVER_WIDTH: f64 = 1e-18;

/// The rule for an absolute tolerance (m for q, m/s for q') of a body of width `width`.
pub(crate) fn check_atol(key: &str, atol: f64, width: f64) -> Result<()> {
    let (min, max) = (MIN_ATOL_OVER_WIDTH * width, MAX_ATOL_OVER_WIDTH * width);
    if crate::base::limits::at_least(atol, min) && crate::base::limits::at_most(atol, max) {
        Ok(())
    } else {
        Err(Error::invalid(
            key,
            atol,
            &format!(
                "the absolute tolerance must lie in [{}, {}] (1e-18 to 0.01 of the width B = \
                 {} m: a looser one resolves neither uplift nor overturning, a tighter one is \
                 far below the rounding of q)",
                crate::base::format::readable(min),
                crate::base::format::readable(max),
                crate::base::format::shortest(width)
            ),
        ))
    }
}

/// The family of methods a `[solver]` key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    Adaptive,
    Newmark,
}

/// Which family of methods `name` belongs to: Newmark, the exact method, or the adaptive
/// methods (any other name). `--method` of another family sets aside the file's keys of its
/// method's family: they were written for the file's method. A `--set solver.method` does not:
/// it is the file's line changed, and meets the rules the file meets.
pub(crate) fn method_family(name: &str) -> u8 {
    match name {
        "newmark" => 1,
        EXACT => 2,
        _ => 0,
    }
}

/// The method of a `[solver]` section that names none: the exact method, or BDF (the default
/// before the exact method existed) when the section gives an adaptive tolerance, so that such
/// files run as they always have.
pub(crate) fn default_method(gives_tolerance: bool) -> &'static str {
    if gives_tolerance {
        "bdf"
    } else {
        EXACT
    }
}

/// The exact method's model-file name.
const EXACT: &str = crate::integrate::exact::NAME;

/// The solver settings of a `[solver]` section, for a run of `duration` s that keeps `history`
/// (the limit on history rows applies only to a run that keeps one).
pub(super) fn solver_from_section(
    s: &SolverSection,
    duration: f64,
    omega: f64,
    width: f64,
    history: History,
) -> Result<SolverSettings> {
    let name = s
        .method
        .as_deref()
        .unwrap_or(default_method(s.rtol.is_some() || s.atol.is_some()));
    let is_newmark = name == "newmark";
    let is_exact = name == EXACT;
    let adaptive = AdaptiveMethod::from_name(name);
    if adaptive.is_none() && !is_newmark && !is_exact {
        return Err(Error::invalid(
            "solver.method",
            format!("\"{name}\""),
            "must be \"exact\", \"bdf\", \"esdirk34\", \"tr-bdf2\", \"tsit45\" or \"newmark\"",
        ));
    }
    // Keys of the other family of methods are mistakes, not silently ignored settings. The
    // section is taken apart field by field, so that a new key must be placed in a family.
    let SolverSection {
        method: _,
        output_dt: _,
        rtol,
        atol,
        dt,
        newmark_beta,
        newmark_gamma,
        newmark_variant,
    } = s;
    let number = |x: &Option<f64>| x.map(crate::base::format::shortest);
    let family_keys: [(&str, Option<String>, Family); 6] = [
        ("rtol", number(rtol), Family::Adaptive),
        ("atol", number(atol), Family::Adaptive),
        ("dt", number(dt), Family::Newmark),
        ("newmark_beta", number(newmark_beta), Family::Newmark),
        ("newmark_gamma", number(newmark_gamma), Family::Newmark),
        ("newmark_variant", newmark_variant.clone(), Family::Newmark),
    ];
    for (key, value, family) in &family_keys {
        let belongs_to_newmark = *family == Family::Newmark;
        if let Some(v) = value {
            // The exact method has no tolerance and no step: every such key is a mistake.
            if is_exact || belongs_to_newmark != is_newmark {
                return Err(Error::invalid(
                    &format!("solver.{key}"),
                    v,
                    &format!("not a parameter of method = \"{name}\""),
                ));
            }
        }
    }
    let output_dt = s.output_dt.unwrap_or(DEFAULT_OUTPUT_DT);
    positive("solver.output_dt", output_dt)?;
    if history == History::Sampled
        && !crate::base::limits::at_most(duration / output_dt, MAX_SAMPLES)
    {
        return Err(Error::invalid(
            "solver.output_dt",
            output_dt,
            &format!(
                "gives more than {MAX_SAMPLES:e} history rows over {} s; choose a larger spacing",
                crate::base::format::shortest(duration)
            ),
        ));
    }
    if is_exact {
        return Ok(SolverSettings::Exact(ExactSettings { output_dt }));
    }
    match adaptive {
        Some(method) => {
            let rtol = s.rtol.unwrap_or(DEFAULT_RTOL);
            check_rtol("solver.rtol", rtol)?;
            let atol = s.atol.unwrap_or(DEFAULT_ATOL);
            check_atol("solver.atol", atol, width)?;
            Ok(SolverSettings::Adaptive(AdaptiveSettings {
                method,
                rtol,
                atol,
                output_dt,
            }))
        }
        None => newmark_from_section(s, duration, omega, output_dt).map(SolverSettings::Newmark),
    }
}

pub(super) fn newmark_from_section(
    s: &SolverSection,
    duration: f64,
    omega: f64,
    output_dt: f64,
) -> Result<NewmarkSettings> {
    let dt = s.dt.unwrap_or(DEFAULT_NEWMARK_DT);
    positive("solver.dt", dt)?;
    if !crate::base::limits::at_most(duration / dt, MAX_NEWMARK_STEPS) {
        return Err(Error::invalid(
            "solver.dt",
            dt,
            &format!(
                "gives more than {MAX_NEWMARK_STEPS:e} steps over {} s; choose a larger step",
                crate::base::format::shortest(duration)
            ),
        ));
    }
    let gamma = s.newmark_gamma.unwrap_or(DEFAULT_NEWMARK_GAMMA);
    if !(0.5..=1.0).contains(&gamma) {
        return Err(Error::invalid(
            "solver.newmark_gamma",
            gamma,
            "must lie in [1/2, 1] (below 1/2 Newmark's method amplifies every oscillation)",
        ));
    }
    let beta = s.newmark_beta.unwrap_or(DEFAULT_NEWMARK_BETA);
    if !(0.0..=0.5).contains(&beta) {
        return Err(Error::invalid(
            "solver.newmark_beta",
            beta,
            "must lie in [0, 1/2]",
        ));
    }
    let variant_name = s.newmark_variant.as_deref().unwrap_or("compensate");
    let variant = NewmarkVariant::from_name(variant_name).ok_or_else(|| {
        Error::invalid(
            "solver.newmark_variant",
            format!("\"{variant_name}\""),
            "must be \"compensate\" or \"substep\"",
        )
    })?;
    // Only the pre-uplift omega can make the method unstable: see critical_omega_dt.
    if let Some(limit) = critical_omega_dt(beta, gamma) {
        let dt_limit = limit / omega;
        if dt >= dt_limit {
            let period = 2.0 * std::f64::consts::PI / omega;
            return Err(Error::invalid(
                "solver.dt",
                dt,
                &format!(
                    "Newmark with beta = {beta:.6}, gamma = {gamma} is stable only for dt < {dt_limit:.6} s \
                     = {:.4} T (pre-uplift period T = {period:.6} s): omega dt must stay below 1/sqrt(gamma/2 - beta) = {limit:.6}; \
                     choose a smaller dt, or beta >= gamma/2 (e.g. 1/4) for unconditional stability",
                    dt_limit / period
                ),
            ));
        }
    }
    Ok(NewmarkSettings {
        dt,
        beta,
        gamma,
        variant,
        output_dt,
    })
}
