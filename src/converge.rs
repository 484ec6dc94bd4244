//! `flexrock converge`: how Newmark converges as dt shrinks, and what each adaptive method costs
//! for a given accuracy, all measured against one tight adaptive reference.
//!
//! Cases run one after another (not in parallel) so that their wall times do not disturb each
//! other on a small machine.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::compare::{compare, max_event_shift};
use crate::error::Result;
use crate::model::Model;
use crate::output::{self, count, number, readable, scientific, Table};
use crate::plot::{self, Legend, Panel, Series};
use crate::run::{simulate_with, VERSION};
use crate::solution::SolverStats;
use crate::solver::adaptive::AdaptiveMethod;
use crate::solver::newmark::NewmarkVariant;
use crate::solver::SolverSettings;

/// Column names of convergence.csv (a contract).
pub const CONVERGENCE_COLUMNS: [&str; 13] = [
    "method",
    "dt",
    "rtol",
    "max_q_error",
    "max_event_time_error",
    "peak_error",
    "event_count_difference",
    "unmatched_events",
    "steps",
    "rhs_evaluations",
    "wall_time_s",
    "max_energy_residual",
    "status",
];

/// Newmark time steps of `flexrock converge` (`--dt`), s.
pub const DEFAULT_DTS: [f64; 8] = [
    0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125,
];
/// Relative tolerances of the adaptive methods of `flexrock converge` (`--rtol`).
pub const DEFAULT_RTOLS: [f64; 9] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];

/// Options of `flexrock converge`.
#[derive(Debug, Clone)]
pub struct ConvergeOptions {
    /// Newmark time steps, s; each runs with both variants.
    pub dts: Vec<f64>,
    /// Relative tolerances; each runs with every adaptive method.
    pub rtols: Vec<f64>,
    /// Relative tolerance of the adaptive reference.
    pub reference_rtol: f64,
    /// Where the solves' wall times go (convergence.json and .csv, or timings.json).
    pub wall_times: output::WallTimes,
}

impl Default for ConvergeOptions {
    fn default() -> Self {
        ConvergeOptions {
            dts: DEFAULT_DTS.to_vec(),
            rtols: DEFAULT_RTOLS.to_vec(),
            reference_rtol: crate::compare::DEFAULT_REFERENCE_RTOL,
            wall_times: output::WallTimes::Inline,
        }
    }
}

/// One solver configuration measured against the reference.
///
/// Read back by `flexrock report`: NaN metrics are written as null and read back as NaN, and
/// `dt`, `rtol` must be present (null for the other kind of method).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Case {
    /// The solver, e.g. "newmark-compensate" or "bdf".
    pub method: String,
    /// Newmark time step, s (Newmark cases).
    #[serde(deserialize_with = "crate::report::required")]
    pub dt: Option<f64>,
    /// Relative tolerance (adaptive cases).
    #[serde(deserialize_with = "crate::report::required")]
    pub rtol: Option<f64>,
    /// Largest |q - q_reference| on the common output grid, m.
    #[serde(deserialize_with = "crate::report::nan_if_null")]
    pub max_q_error: f64,
    /// Largest |t - t_reference| over matched events, s.
    #[serde(deserialize_with = "crate::report::nan_if_null")]
    pub max_event_time_error: f64,
    /// Larger of the errors of max q and min q, m.
    #[serde(deserialize_with = "crate::report::nan_if_null")]
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
    #[serde(deserialize_with = "crate::report::nan_if_null")]
    pub wall_time_s: f64,
    /// Largest energy residual over the samples, J.
    #[serde(deserialize_with = "crate::report::nan_if_null")]
    pub max_energy_residual: f64,
    /// "ok", or why the case has no result.
    pub status: String,
}

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
    #[serde(deserialize_with = "crate::report::nan_if_null")]
    pub slope: f64,
    /// Cases in the fit (those with every event matched and a positive error).
    pub points: usize,
}

/// convergence.json.
#[derive(Debug, Serialize)]
pub struct ConvergeSummary {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::run::Provenance,
    /// The reference's method.
    pub reference_method: String,
    /// The reference's relative tolerance.
    pub reference_rtol: f64,
    /// What the reference solution cost.
    pub reference_statistics: SolverStats,
    /// Number of events of the reference solution.
    pub reference_events: usize,
    /// Spacing of the output grid the errors are measured on, s.
    pub output_dt: f64,
    /// Every solver configuration measured.
    pub cases: Vec<Case>,
    /// The orders (Newmark, against dt) and efficiency slopes (adaptive methods, against work)
    /// of each method.
    pub slopes: Vec<Slope>,
}

/// Result of `flexrock converge`.
pub struct ConvergeReport {
    /// What convergence.json holds.
    pub summary: ConvergeSummary,
    /// The files written.
    pub files: Vec<PathBuf>,
}

const METRICS: [&str; 3] = ["max_q_error", "max_event_time_error", "peak_error"];

fn metric(case: &Case, name: &str) -> f64 {
    match name {
        "max_q_error" => case.max_q_error,
        "max_event_time_error" => case.max_event_time_error,
        _ => case.peak_error,
    }
}

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

fn slopes(cases: &[Case]) -> Vec<Slope> {
    let mut methods: Vec<&str> = Vec::new();
    for c in cases {
        if !methods.contains(&c.method.as_str()) {
            methods.push(&c.method);
        }
    }
    let mut fitted = Vec::new();
    for method in methods {
        for name in METRICS {
            let good: Vec<&Case> = cases
                .iter()
                .filter(|c| c.method == method && c.status == "ok" && c.unmatched_events == 0)
                .filter(|c| metric(c, name) > 0.0 && metric(c, name).is_finite())
                .collect();
            if good.len() < 2 {
                continue;
            }
            let (kind, against, points): (SlopeKind, &str, Vec<(f64, f64)>) = match good[0].dt {
                Some(_) => (
                    SlopeKind::Order,
                    "dt",
                    good.iter()
                        .map(|c| (c.dt.unwrap_or(f64::NAN), metric(c, name)))
                        .collect(),
                ),
                None => (
                    SlopeKind::EfficiencySlope,
                    "rhs_evaluations",
                    good.iter()
                        .map(|c| (c.rhs_evaluations as f64, metric(c, name)))
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

/// One case to run: method label, dt, rtol, and its settings.
type Configuration = (String, Option<f64>, Option<f64>, SolverSettings);

/// The reference's settings and every case's, checked by the rules `run` and `compare` apply
/// (`Model::reference_settings`, `Model::newmark_settings`) before anything is computed. An
/// error names the flag (`--dt`, `--rtol`, `--reference-rtol`), the value and the rule.
pub fn configurations(
    model: &Model,
    options: &ConvergeOptions,
) -> Result<(SolverSettings, Vec<Configuration>)> {
    let flag = |flag: &'static str| {
        move |e: crate::Error| e.renamed("rtol", flag).renamed("solver.rtol", flag)
    };
    for (name, empty) in [
        ("--dt", options.dts.is_empty()),
        ("--rtol", options.rtols.is_empty()),
    ] {
        if empty {
            return Err(crate::Error::invalid(
                name,
                "(an empty list)",
                "give at least one value (several, separated by commas, to see convergence)",
            ));
        }
    }
    let reference_settings = SolverSettings::Adaptive(
        model
            .reference_settings(options.reference_rtol)
            .map_err(flag("--reference-rtol"))?,
    );
    let mut configurations: Vec<Configuration> = Vec::new();
    for variant in [NewmarkVariant::Compensate, NewmarkVariant::Substep] {
        for &dt in &options.dts {
            let settings = model
                .newmark_settings(Some(dt), Some(variant.name()))
                .map_err(|e| e.renamed("solver.dt", "--dt"))?;
            configurations.push((
                format!("newmark-{}", variant.name()),
                Some(dt),
                None,
                SolverSettings::Newmark(settings),
            ));
        }
    }
    for method in [
        AdaptiveMethod::Bdf,
        AdaptiveMethod::Esdirk34,
        AdaptiveMethod::TrBdf2,
        AdaptiveMethod::Tsit45,
    ] {
        for &rtol in &options.rtols {
            let mut settings = model.reference_settings(rtol).map_err(flag("--rtol"))?;
            settings.method = method;
            configurations.push((
                method.name().to_string(),
                None,
                Some(rtol),
                SolverSettings::Adaptive(settings),
            ));
        }
    }
    // Every value is valid on its own; errors are measured against the reference: one no tighter than a case measures the
    // reference's own error, and the orders printed would mean nothing.
    let tightest = options.rtols.iter().copied().fold(f64::INFINITY, f64::min);
    if options.reference_rtol.partial_cmp(&tightest) != Some(std::cmp::Ordering::Less) {
        return Err(crate::Error::invalid(
            "--reference-rtol",
            options.reference_rtol,
            &format!(
                "the reference must be tighter than every case: give a --reference-rtol below \
                 the smallest --rtol ({}), e.g. 1e-12",
                crate::output::shortest(tightest)
            ),
        ));
    }
    Ok((reference_settings, configurations))
}

/// Runs the reference, every Newmark variant at every dt and every adaptive method at every
/// tolerance; writes convergence.csv, convergence.json and the figures into `out_dir`. Every
/// setting is checked before the first computation ([`configurations`]).
pub fn run_converge(
    model: &Model,
    options: &ConvergeOptions,
    out_dir: &Path,
) -> Result<ConvergeReport> {
    let (reference_settings, configurations) = configurations(model, options)?;
    let mut reference = simulate_with(model, &reference_settings)?;
    let mut timings = output::Timings::new(options.wall_times);
    timings.take(
        "convergence.json/reference_statistics/wall_time_s",
        &mut reference.stats.wall_time_s,
    );
    let output_dt = model.solver.output_dt();
    let max_shift = max_event_shift(model);

    let mut cases = Vec::new();
    for (method, dt, rtol, settings) in configurations {
        let failed = |status: String| Case::failed(&method, dt, rtol, status);
        let mut solution = match simulate_with(model, &settings) {
            Ok(s) => s,
            Err(e) => {
                cases.push(failed(e.to_string()));
                continue;
            }
        };
        timings.take(
            &format!("convergence.json/cases/{}/wall_time_s", cases.len()),
            &mut solution.stats.wall_time_s,
        );
        let c = compare(&reference, &solution, output_dt, max_shift);
        cases.push(Case {
            method: method.clone(),
            dt,
            rtol,
            max_q_error: c.grid.max_abs_q_difference,
            max_event_time_error: c.events.max_abs_time_difference,
            peak_error: c.peaks.peak_error,
            event_count_difference: solution.events.len() as i64 - reference.events.len() as i64,
            unmatched_events: c.events.n_missed + c.events.n_spurious,
            steps: solution.stats.steps,
            rhs_evaluations: solution.stats.rhs_evaluations,
            wall_time_s: solution.stats.wall_time_s,
            max_energy_residual: solution.max_energy_residual,
            status: "ok".to_string(),
        });
    }
    let slopes = slopes(&cases);
    let summary = ConvergeSummary {
        provenance: crate::run::Provenance::of(model),
        reference_method: reference_settings.label(),
        reference_rtol: options.reference_rtol,
        reference_statistics: reference.stats.clone(),
        reference_events: reference.events.len(),
        output_dt,
        cases,
        slopes,
    };
    let (by_dt, by_work) = figures(&summary)?;
    let mut files = vec![
        ("convergence.csv", cases_table(&summary.cases)),
        ("convergence.json", output::json_bytes(&summary)),
        ("convergence_dt.svg", by_dt.into_bytes()),
        ("convergence_work.svg", by_work.into_bytes()),
    ];
    files.extend(timings.file());
    let files = output::write_atomically(out_dir, &files)?;
    Ok(ConvergeReport { summary, files })
}

impl Case {
    /// A case whose run failed with `status`: nothing measured (NaN errors, no counts).
    fn failed(method: &str, dt: Option<f64>, rtol: Option<f64>, status: String) -> Case {
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
}

fn cases_table(cases: &[Case]) -> Vec<u8> {
    let mut table = Table::new(&CONVERGENCE_COLUMNS);
    let optional = |x: Option<f64>| x.map(number).unwrap_or_default();
    for c in cases {
        if c.status != "ok" {
            // A case that failed measured nothing: its error, count and cost fields are empty,
            // not NaN or zeros that read as values.
            let mut row = vec![c.method.clone(), optional(c.dt), optional(c.rtol)];
            row.resize(CONVERGENCE_COLUMNS.len() - 1, String::new());
            row.push(c.status.clone());
            table.row(row);
            continue;
        }
        table.row([
            c.method.clone(),
            optional(c.dt),
            optional(c.rtol),
            number(c.max_q_error),
            number(c.max_event_time_error),
            number(c.peak_error),
            c.event_count_difference.to_string(),
            c.unmatched_events.to_string(),
            c.steps.to_string(),
            c.rhs_evaluations.to_string(),
            // Empty where the time was taken out to timings.json.
            optional(Some(c.wall_time_s).filter(|t| t.is_finite())),
            number(c.max_energy_residual),
            c.status.clone(),
        ]);
    }
    table.into_bytes()
}

/// Error against dt (Newmark, with slope-1 and slope-2 guides) and error against work (all).
fn figures(summary: &ConvergeSummary) -> Result<(String, String)> {
    let ok = |c: &&Case| c.status == "ok";
    let methods: Vec<String> = {
        let mut m: Vec<String> = Vec::new();
        for c in &summary.cases {
            if !m.contains(&c.method) {
                m.push(c.method.clone());
            }
        }
        m
    };
    // (column, panel title, axis label with unit)
    let titles = [
        (
            "max_q_error",
            "Error of q on the output grid",
            "max |Δq| (m)",
        ),
        (
            "max_event_time_error",
            "Error of the event times",
            "max |Δt_event| (s)",
        ),
        ("peak_error", "Error of the peak of |q|", "|Δq_peak| (m)"),
    ];
    let mut dt_panels = Vec::new();
    let mut work_panels = Vec::new();
    for (name, title, y_label) in titles {
        let mut dt_series = Vec::new();
        let mut work_series = Vec::new();
        for (i, method) in methods.iter().enumerate() {
            let cases: Vec<&Case> = summary
                .cases
                .iter()
                .filter(|c| &c.method == method)
                .filter(ok)
                .collect();
            let work: Vec<(f64, f64)> = cases
                .iter()
                .map(|c| (c.rhs_evaluations as f64, metric(c, name)))
                .collect();
            work_series.push(
                Series::line(method, work, i + 1)
                    .with_width(2)
                    .with_markers(),
            );
            if cases.first().is_some_and(|c| c.dt.is_some()) {
                let points: Vec<(f64, f64)> = cases
                    .iter()
                    .map(|c| (c.dt.unwrap_or(f64::NAN), metric(c, name)))
                    .collect();
                dt_series.push(
                    Series::line(method, points, i + 1)
                        .with_width(2)
                        .with_markers(),
                );
            }
        }
        // Guides through the first compensate point: slopes 1 and 2.
        if let Some(anchor) = summary
            .cases
            .iter()
            .find(|c| c.dt.is_some() && c.status == "ok" && metric(c, name) > 0.0)
        {
            let (x0, y0) = (anchor.dt.unwrap_or(1.0), metric(anchor, name));
            let x1 = summary.cases.iter().filter_map(|c| c.dt).fold(x0, f64::min);
            for (order, color) in [(1.0, 5), (2.0, 6)] {
                // Guides, not data: thin and dashed.
                dt_series.push(
                    Series::line(
                        &format!("slope {order}"),
                        vec![(x0, y0), (x1, y0 * (x1 / x0).powf(order))],
                        color,
                    )
                    .with_width(1)
                    .dashed(),
                );
            }
        }
        dt_panels.push(Panel {
            title: format!("Newmark: {title}"),
            x_label: "Δt (s)".to_string(),
            y_label: y_label.to_string(),
            series: dt_series,
            log_x: true,
            log_y: true,
            legend: Legend::Outside,
            ..Panel::default()
        });
        work_panels.push(Panel {
            title: title.to_string(),
            x_label: "right-hand-side evaluations".to_string(),
            y_label: y_label.to_string(),
            series: work_series,
            log_x: true,
            log_y: true,
            // Beside the plot: inside, it covered the slowest method's curve.
            legend: Legend::Outside,
            ..Panel::default()
        });
    }
    Ok((
        plot::figure("convergence_dt.svg", &dt_panels, 1, (1050, 380))?,
        plot::figure("convergence_work.svg", &work_panels, 1, (1050, 380))?,
    ))
}

/// The printed table, orders and efficiency slopes of `flexrock converge`.
pub fn converge_text(report: &ConvergeReport) -> String {
    let s = &report.summary;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION} converge: reference {} at rtol = {:e} ({}, {})",
        s.reference_method,
        s.reference_rtol,
        count(s.reference_events, "event", "events"),
        count(s.reference_statistics.steps, "step", "steps")
    );
    let _ = writeln!(
        t,
        "  {:<19} {:>10} {:>7} {:>11} {:>11} {:>11} {:>6} {:>8} {:>9} {:>9}",
        "method",
        "dt",
        "rtol",
        "q error",
        "t_event err",
        "peak error",
        "n diff",
        "steps",
        "rhs evals",
        "ms"
    );
    let optional = |x: Option<f64>, f: &dyn Fn(f64) -> String| x.map_or("-".to_string(), f);
    for c in &s.cases {
        if c.status != "ok" {
            let _ = writeln!(
                t,
                "  {:<19} {:>10} {:>7}  failed: {}",
                c.method,
                optional(c.dt, &readable),
                optional(c.rtol, &scientific),
                c.status
            );
            continue;
        }
        let _ = writeln!(
            t,
            "  {:<19} {:>10} {:>7} {:>11.3e} {:>11.3e} {:>11.3e} {:>+6} {:>8} {:>9} {:>9}",
            c.method,
            optional(c.dt, &readable),
            optional(c.rtol, &scientific),
            c.max_q_error,
            c.max_event_time_error,
            c.peak_error,
            c.event_count_difference,
            c.steps,
            c.rhs_evaluations,
            // "-" where the time was taken out to timings.json.
            if c.wall_time_s.is_finite() {
                format!("{:.2}", c.wall_time_s * 1e3)
            } else {
                "-".to_string()
            }
        );
    }
    let _ = writeln!(
        t,
        "orders against dt (Newmark) and efficiency slopes against work (adaptive methods), least squares over the cases with every event matched:"
    );
    for o in &s.slopes {
        let meaning = match o.kind {
            SlopeKind::Order => format!("error ~ dt^{:.2}", o.slope),
            SlopeKind::EfficiencySlope => format!("error ~ work^{:.2}", o.slope),
        };
        let _ = writeln!(
            t,
            "  {:<19} {:<21} {:<17} {meaning:<20} ({})",
            o.method,
            o.metric,
            o.kind.name(),
            count(o.points, "point", "points")
        );
    }
    for f in &report.files {
        let _ = writeln!(t, "wrote {}", f.display());
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failed case's row holds its method, settings and status, and nothing measured.
    #[test]
    fn a_failed_case_has_empty_measurements() {
        let case = Case::failed(
            "newmark-compensate",
            Some(0.5),
            None,
            "the newmark solver failed at t = 1 s: too many events".to_string(),
        );
        let text = String::from_utf8(cases_table(&[case])).unwrap();
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let row = reader.records().next().unwrap().unwrap();
        assert_eq!(row.len(), CONVERGENCE_COLUMNS.len());
        assert_eq!(&row[0], "newmark-compensate");
        assert_eq!(&row[1], "0.5");
        assert_eq!(&row[2], "");
        for (k, field) in row
            .iter()
            .enumerate()
            .take(CONVERGENCE_COLUMNS.len() - 1)
            .skip(3)
        {
            assert_eq!(field, "", "{} of a failed case", CONVERGENCE_COLUMNS[k]);
        }
        assert!(row[CONVERGENCE_COLUMNS.len() - 1].starts_with("the newmark solver failed"));
    }
}
