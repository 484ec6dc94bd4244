//! The convergence study: how Newmark converges as dt shrinks, and what each adaptive method
//! costs for a given accuracy, all measured against one tight adaptive reference (what
//! `flexrock converge` writes to convergence.csv and convergence.json).
//!
//! [`configurations`] lays out the study (both Newmark variants at every dt, every adaptive
//! method at every tolerance); [`converge`] runs it, one case after another (not in parallel,
//! so that their wall times do not disturb each other on a small machine), into typed
//! [`Case`]s, and fits the [`Slope`]s of their errors ([`slopes`]).

use serde::{Deserialize, Serialize};

use crate::analysis::compare::{compare, max_event_shift};
use crate::base::format::number;
use crate::error::{Error, Result};
use crate::integrate::adaptive::AdaptiveMethod;
use crate::integrate::newmark::NewmarkVariant;
use crate::integrate::solution::Solution;
use crate::integrate::SolverSettings;
use crate::model::Model;
use crate::simulate::simulate_with;
use crate::tables::fields::{nan_if_null, optional, required, Column};

/// Newmark time steps of the study by default, s.
pub const DEFAULT_DTS: [f64; 8] = [
    0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125,
];
/// Relative tolerances of the adaptive methods of the study by default.
pub const DEFAULT_RTOLS: [f64; 9] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];

/// The status of a case that ran.
pub const OK: &str = "ok";

/// One solver configuration measured against the reference (a row of convergence.csv).
///
/// Read back by `flexrock report`: NaN metrics are written as null and read back as NaN, and
/// `dt`, `rtol` must be present (null for the other kind of method).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Case {
    /// The solver, e.g. "newmark-compensate" or "bdf".
    pub method: String,
    /// Newmark time step, s (Newmark cases).
    #[serde(deserialize_with = "required")]
    pub dt: Option<f64>,
    /// Relative tolerance (adaptive cases).
    #[serde(deserialize_with = "required")]
    pub rtol: Option<f64>,
    /// Largest |q - q_reference| on the common output grid, m.
    #[serde(deserialize_with = "nan_if_null")]
    pub max_q_error: f64,
    /// Largest |t - t_reference| over matched events, s.
    #[serde(deserialize_with = "nan_if_null")]
    pub max_event_time_error: f64,
    /// Larger of the errors of max q and min q, m.
    #[serde(deserialize_with = "nan_if_null")]
    pub peak_error: f64,
    /// Number of events minus the reference's.
    pub event_count_difference: i64,
    /// Events of either solution without a partner in the other.
    pub unmatched_events: usize,
    /// Accepted steps.
    pub steps: usize,
    /// Evaluations of the right-hand side.
    pub rhs_evaluations: usize,
    /// Wall-clock time of the solve, s.
    #[serde(deserialize_with = "nan_if_null")]
    pub wall_time_s: f64,
    /// Largest energy residual over the samples, J.
    #[serde(deserialize_with = "nan_if_null")]
    pub max_energy_residual: f64,
    /// [`OK`], or why the case has no result.
    pub status: String,
}

impl Case {
    /// A case whose run failed with `status`: nothing measured (NaN errors, no counts).
    pub fn failed(method: &str, dt: Option<f64>, rtol: Option<f64>, status: String) -> Case {
        Case {
            method: method.to_string(),
            dt,
            rtol,
            max_q_error: f64::NAN,
            max_event_time_error: f64::NAN,
            peak_error: f64::NAN,
            event_count_difference: 0,
            unmatched_events: 0,
            steps: 0,
            rhs_evaluations: 0,
            wall_time_s: 0.0,
            max_energy_residual: f64::NAN,
            status,
        }
    }

    /// The case ran and was measured.
    pub fn is_ok(&self) -> bool {
        self.status == OK
    }

    /// The error named `metric` (one of [`METRICS`]).
    pub fn metric(&self, metric: &str) -> f64 {
        match metric {
            "max_q_error" => self.max_q_error,
            "max_event_time_error" => self.max_event_time_error,
            _ => self.peak_error,
        }
    }
}

/// A field of a case that only a case that ran has: empty for a failed case, whose errors,
/// counts and cost were never measured (not NaN or zeros that read as values).
fn measured(case: &Case, field: String) -> String {
    if case.is_ok() {
        field
    } else {
        String::new()
    }
}

/// The columns of convergence.csv (a contract), one per field of [`Case`].
pub const CASE_COLUMNS: [Column<Case>; 13] = [
    Column::new("method", |c| c.method.clone()),
    Column::new("dt", |c| optional(c.dt)),
    Column::new("rtol", |c| optional(c.rtol)),
    Column::new("max_q_error", |c| measured(c, number(c.max_q_error))),
    Column::new("max_event_time_error", |c| {
        measured(c, number(c.max_event_time_error))
    }),
    Column::new("peak_error", |c| measured(c, number(c.peak_error))),
    Column::new("event_count_difference", |c| {
        measured(c, c.event_count_difference.to_string())
    }),
    Column::new("unmatched_events", |c| {
        measured(c, c.unmatched_events.to_string())
    }),
    Column::new("steps", |c| measured(c, c.steps.to_string())),
    Column::new("rhs_evaluations", |c| {
        measured(c, c.rhs_evaluations.to_string())
    }),
    // Empty where the time was taken out (NaN).
    Column::new("wall_time_s", |c| {
        measured(c, optional(Some(c.wall_time_s).filter(|t| t.is_finite())))
    }),
    Column::new("max_energy_residual", |c| {
        measured(c, number(c.max_energy_residual))
    }),
    Column::new("status", |c| c.status.clone()),
];

/// What a fitted slope is: an order where the error is fitted against the step, an efficiency
/// slope where it is fitted against the work. The two are different quantities (an adaptive
/// method's step is not set, so it has no order in this sense), and are named apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SlopeKind {
    /// The slope of log(error) against log(dt): the observed order of a fixed-step method.
    Order,
    /// The slope of log(error) against log(right-hand-side evaluations): how fast the error
    /// falls with the work of an adaptive method (-p for a method of order p on a smooth
    /// problem, steeper where the step sequence adapts).
    EfficiencySlope,
}

impl SlopeKind {
    /// The name in printed tables.
    pub fn name(self) -> &'static str {
        match self {
            SlopeKind::Order => "order",
            SlopeKind::EfficiencySlope => "efficiency slope",
        }
    }
}

/// A least-squares slope of log(error) against log(dt) or log(work).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Slope {
    /// The solver, e.g. "newmark-compensate" or "bdf".
    pub method: String,
    /// "max_q_error", "max_event_time_error" or "peak_error".
    pub metric: String,
    /// An order (against dt) or an efficiency slope (against work).
    pub kind: SlopeKind,
    /// "dt" or "rhs_evaluations".
    pub against: String,
    /// The fitted slope.
    #[serde(deserialize_with = "nan_if_null")]
    pub slope: f64,
    /// Cases in the fit (those with every event matched and a positive error).
    pub points: usize,
}

/// The errors of a case, by their names in convergence.csv.
pub const METRICS: [&str; 3] = ["max_q_error", "max_event_time_error", "peak_error"];

/// Slope of the least-squares line through (log x, log y).
fn log_log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + x.ln() / n, b + y.ln() / n)
    });
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        let dx = x.ln() - mx;
        (a + dx * (y.ln() - my), b + dx * dx)
    });
    sxy / sxx
}

/// The methods of `cases`, in the order they first appear.
pub fn methods(cases: &[Case]) -> Vec<&str> {
    let mut methods: Vec<&str> = Vec::new();
    for c in cases {
        if !methods.contains(&c.method.as_str()) {
            methods.push(&c.method);
        }
    }
    methods
}

/// For each method and metric, the least-squares slope of log(error) over the cases that ran
/// with every event matched and a positive finite error (two at least): against log(dt) for a
/// Newmark method (an order), against log(rhs evaluations) for an adaptive one.
pub fn slopes(cases: &[Case]) -> Vec<Slope> {
    let mut fitted = Vec::new();
    for method in methods(cases) {
        for name in METRICS {
            let good: Vec<&Case> = cases
                .iter()
                .filter(|c| c.method == method && c.is_ok() && c.unmatched_events == 0)
                .filter(|c| c.metric(name) > 0.0 && c.metric(name).is_finite())
                .collect();
            if good.len() < 2 {
                continue;
            }
            let (kind, against, points): (SlopeKind, &str, Vec<(f64, f64)>) = match good[0].dt {
                Some(_) => (
                    SlopeKind::Order,
                    "dt",
                    good.iter()
                        .map(|c| (c.dt.unwrap_or(f64::NAN), c.metric(name)))
                        .collect(),
                ),
                None => (
                    SlopeKind::EfficiencySlope,
                    "rhs_evaluations",
                    good.iter()
                        .map(|c| (c.rhs_evaluations as f64, c.metric(name)))
                        .collect(),
                ),
            };
            fitted.push(Slope {
                method: method.to_string(),
                metric: name.to_string(),
                kind,
                against: against.to_string(),
                slope: log_log_slope(&points),
                points: points.len(),
            });
        }
    }
    fitted
}

/// One case to run.
#[derive(Debug, Clone)]
pub struct Configuration {
    /// The method's label, e.g. "newmark-compensate" or "bdf".
    pub method: String,
    /// Newmark time step, s (Newmark cases).
    pub dt: Option<f64>,
    /// Relative tolerance (adaptive cases).
    pub rtol: Option<f64>,
    /// The solver settings of the case.
    pub settings: SolverSettings,
}

/// Every case of the study, checked by the rules `Model::newmark_settings` and
/// `Model::reference_settings` apply: both Newmark variants at each of `dts`
/// ([`newmark_configurations`]), then each adaptive method at each of `rtols`
/// ([`adaptive_configurations`]).
/// A study without any case is refused: it would measure nothing.
pub fn configurations(model: &Model, dts: &[f64], rtols: &[f64]) -> Result<Vec<Configuration>> {
    if dts.is_empty() && rtols.is_empty() {
        return Err(Error::invalid(
            "dts, rtols",
            "(none)",
            "a convergence study needs at least one Newmark step or adaptive tolerance",
        ));
    }
    let mut configurations = newmark_configurations(model, dts)?;
    configurations.extend(adaptive_configurations(model, rtols)?);
    Ok(configurations)
}

/// The Newmark cases: the compensate variant at each of `dts`, then the substep variant. An
/// error names the model key the value stands for (`solver.dt`).
pub fn newmark_configurations(model: &Model, dts: &[f64]) -> Result<Vec<Configuration>> {
    let mut configurations = Vec::new();
    for variant in [NewmarkVariant::Compensate, NewmarkVariant::Substep] {
        for &dt in dts {
            let settings = model.newmark_settings(Some(dt), Some(variant.name()))?;
            configurations.push(Configuration {
                method: format!("newmark-{}", variant.name()),
                dt: Some(dt),
                rtol: None,
                settings: SolverSettings::Newmark(settings),
            });
        }
    }
    Ok(configurations)
}

/// The adaptive cases: each adaptive method at each of `rtols`. An error names the key the
/// value stands for (`rtol`).
pub fn adaptive_configurations(model: &Model, rtols: &[f64]) -> Result<Vec<Configuration>> {
    let mut configurations = Vec::new();
    for method in [
        AdaptiveMethod::Bdf,
        AdaptiveMethod::Esdirk34,
        AdaptiveMethod::TrBdf2,
        AdaptiveMethod::Tsit45,
    ] {
        for &rtol in rtols {
            let mut settings = model.reference_settings(rtol)?;
            settings.method = method;
            configurations.push(Configuration {
                method: method.name().to_string(),
                dt: None,
                rtol: Some(rtol),
                settings: SolverSettings::Adaptive(settings),
            });
        }
    }
    Ok(configurations)
}

/// A finished convergence study.
pub struct Convergence {
    /// The reference solution every case is measured against.
    pub reference: Solution,
    /// Its solver settings.
    pub reference_settings: SolverSettings,
    /// Spacing of the output grid the errors are measured on, s.
    pub output_dt: f64,
    /// Every case, in the order of the configurations.
    pub cases: Vec<Case>,
    /// The orders (Newmark, against dt) and efficiency slopes (adaptive methods, against work)
    /// of each method.
    pub slopes: Vec<Slope>,
}

/// Runs the reference, then every configuration one after another, measures each against the
/// reference ([`compare`]) and fits the slopes. A case whose run fails is kept with its error
/// as status ([`Case::failed`]); only the reference's failure is an error.
pub fn converge(
    model: &Model,
    reference_settings: SolverSettings,
    configurations: &[Configuration],
) -> Result<Convergence> {
    let reference = simulate_with(model, &reference_settings)?;
    let output_dt = model.solver.output_dt();
    let max_shift = max_event_shift(model);
    let cases: Vec<Case> = configurations
        .iter()
        .map(|c| match simulate_with(model, &c.settings) {
            Ok(solution) => measure(c, &reference, &solution, output_dt, max_shift),
            Err(e) => Case::failed(&c.method, c.dt, c.rtol, e.to_string()),
        })
        .collect();
    let slopes = slopes(&cases);
    Ok(Convergence {
        reference,
        reference_settings,
        output_dt,
        cases,
        slopes,
    })
}

/// The case of `configuration`, whose run gave `solution`.
fn measure(
    configuration: &Configuration,
    reference: &Solution,
    solution: &Solution,
    output_dt: f64,
    max_shift: f64,
) -> Case {
    let c = compare(reference, solution, output_dt, max_shift);
    Case {
        method: configuration.method.clone(),
        dt: configuration.dt,
        rtol: configuration.rtol,
        max_q_error: c.grid.max_abs_q_difference,
        max_event_time_error: c.events.max_abs_time_difference,
        peak_error: c.peaks.peak_error,
        event_count_difference: solution.events.len() as i64 - reference.events.len() as i64,
        unmatched_events: c.events.n_missed + c.events.n_spurious,
        steps: solution.stats.steps,
        rhs_evaluations: solution.stats.rhs_evaluations,
        wall_time_s: solution.stats.wall_time_s,
        max_energy_residual: solution.max_energy_residual,
        status: OK.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::fields::{fields, names, serialized_keys};

    /// A case that ran, with the given step (or tolerance and work) and errors.
    fn case(method: &str, dt: Option<f64>, work: usize, errors: [f64; 3]) -> Case {
        Case {
            max_q_error: errors[0],
            max_event_time_error: errors[1],
            peak_error: errors[2],
            rhs_evaluations: work,
            status: OK.to_string(),
            wall_time_s: 0.5,
            ..Case::failed(method, dt, dt.is_none().then_some(1e-6), String::new())
        }
    }

    /// Errors e = C h^p with known p: the fitted slopes are p (orders against dt for a Newmark
    /// method, efficiency slopes against work for an adaptive one).
    #[test]
    fn slopes_of_power_laws_are_their_exponents() {
        let mut cases = Vec::new();
        for dt in [0.1_f64, 0.05, 0.025, 0.0125] {
            let errors = [3.0 * dt * dt, 0.5 * dt, 2.0 * dt.powi(3)];
            cases.push(case("newmark-compensate", Some(dt), 10, errors));
        }
        for work in [100_usize, 1000, 10000] {
            let n = work as f64;
            cases.push(case(
                "bdf",
                None,
                work,
                [5.0 * n.powi(-4), n.powf(-1.5), 1.0 / n],
            ));
        }
        let fitted = slopes(&cases);
        let expected = [
            (
                "newmark-compensate",
                "max_q_error",
                SlopeKind::Order,
                2.0,
                4,
            ),
            (
                "newmark-compensate",
                "max_event_time_error",
                SlopeKind::Order,
                1.0,
                4,
            ),
            ("newmark-compensate", "peak_error", SlopeKind::Order, 3.0, 4),
            ("bdf", "max_q_error", SlopeKind::EfficiencySlope, -4.0, 3),
            (
                "bdf",
                "max_event_time_error",
                SlopeKind::EfficiencySlope,
                -1.5,
                3,
            ),
            ("bdf", "peak_error", SlopeKind::EfficiencySlope, -1.0, 3),
        ];
        assert_eq!(fitted.len(), expected.len());
        for (s, (method, metric, kind, slope, points)) in fitted.iter().zip(expected) {
            assert_eq!((s.method.as_str(), s.metric.as_str()), (method, metric));
            assert_eq!(s.kind, kind);
            assert_eq!(
                s.against,
                if kind == SlopeKind::Order {
                    "dt"
                } else {
                    "rhs_evaluations"
                }
            );
            assert!(
                (s.slope - slope).abs() < 1e-12,
                "{method} {metric}: {}",
                s.slope
            );
            assert_eq!(s.points, points);
        }
    }

    /// Cases with an unmatched event, a failed run or a zero error stay out of the fit; a method
    /// left with one good case gets no slope.
    #[test]
    fn only_clean_cases_are_fitted() {
        let dts = [0.1, 0.05, 0.025];
        let mut cases: Vec<Case> = dts
            .iter()
            .map(|&dt| case("newmark-substep", Some(dt), 10, [dt * dt, dt, 0.0]))
            .collect();
        // A wild error at the first dt, but one event unmatched: left out.
        cases[0].max_q_error = 1e3;
        cases[0].unmatched_events = 1;
        cases.push(Case::failed(
            "newmark-substep",
            Some(0.0125),
            None,
            "x".into(),
        ));
        cases.push(case("tsit45", None, 100, [1.0, 1.0, 1.0]));
        let fitted = slopes(&cases);
        // peak_error is zero everywhere (no fit), tsit45 has one case (no fit).
        assert_eq!(fitted.len(), 2);
        assert!((fitted[0].slope - 2.0).abs() < 1e-12);
        assert_eq!(fitted[0].points, 2);
        assert!((fitted[1].slope - 1.0).abs() < 1e-12);
    }

    /// A failed case's row holds its method, settings and status, and nothing measured.
    #[test]
    fn a_failed_case_has_empty_measurements() {
        let failed = Case::failed(
            "newmark-compensate",
            Some(0.5),
            None,
            "the newmark solver failed at t = 1 s: too many events".to_string(),
        );
        let row = fields(&CASE_COLUMNS, &failed);
        assert_eq!(row.len(), 13);
        assert_eq!(row[..3], ["newmark-compensate", "0.5", ""]);
        for (k, field) in row.iter().enumerate().take(12).skip(3) {
            assert_eq!(field, "", "{} of a failed case", CASE_COLUMNS[k].name);
        }
        assert!(row[12].starts_with("the newmark solver failed"));
        let ran = case("bdf", None, 7, [0.25, 0.5, 1.0]);
        assert_eq!(
            fields(&CASE_COLUMNS, &ran),
            ["bdf", "", "0.000001", "0.25", "0.5", "1", "0", "0", "0", "7", "0.5", "NaN", "ok"]
        );
    }

    /// The columns of convergence.csv are the fields of a case, in order.
    #[test]
    fn the_columns_are_the_fields_of_a_case() {
        let c = case("bdf", None, 1, [1.0; 3]);
        assert_eq!(serialized_keys(&c), names(&CASE_COLUMNS));
    }
}
