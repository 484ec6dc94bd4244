//! `flexrock converge`: how Newmark converges as dt shrinks, and what each adaptive method costs
//! for a given accuracy, all measured against one tight adaptive reference. The study is
//! [`flexrock_core::analysis::converge`] (re-exported here); this module checks the flags, writes
//! convergence.csv, convergence.json and the figures, and prints the table.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::commands::run::VERSION;
use crate::error::Result;
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Dash, Figure, Panel, Series};
use crate::writers::{self, count, readable, scientific, Table};
use flexrock_core::integrate::solution::SolverStats;
use flexrock_core::integrate::SolverSettings;
use flexrock_core::model::Model;
use flexrock_core::tables::fields;

pub use flexrock_core::analysis::converge::{
    converge, methods, slopes, Case, Configuration, Convergence, Slope, SlopeKind, CASE_COLUMNS,
    DEFAULT_DTS, DEFAULT_RTOLS, METRICS,
};

/// Column names of convergence.csv (a contract): the names of [`CASE_COLUMNS`].
pub const CONVERGENCE_COLUMNS: [&str; 13] = fields::names(&CASE_COLUMNS);

/// Options of `flexrock converge`.
#[derive(Debug, Clone)]
pub struct ConvergeOptions {
    /// Newmark time steps, s; each runs with both variants.
    pub dts: Vec<f64>,
    /// Relative tolerances; each runs with every adaptive method.
    pub rtols: Vec<f64>,
    /// Relative tolerance of an adaptive reference; None: the exact solution is the reference.
    pub reference_rtol: Option<f64>,
    /// Where the solves' wall times go (convergence.json and .csv, or timings.json).
    pub wall_times: writers::WallTimes,
    /// The figures' formats and size.
    pub figures: FigureOptions,
}

impl Default for ConvergeOptions {
    fn default() -> Self {
        ConvergeOptions {
            dts: DEFAULT_DTS.to_vec(),
            rtols: DEFAULT_RTOLS.to_vec(),
            reference_rtol: None,
            wall_times: writers::WallTimes::Inline,
            figures: FigureOptions::default(),
        }
    }
}

/// convergence.json.
#[derive(Debug, Serialize)]
pub struct ConvergeSummary {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::commands::run::Provenance,
    /// The reference's method.
    pub reference_method: String,
    /// The reference's relative tolerance (null: the reference is the exact solution).
    pub reference_rtol: Option<f64>,
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

/// The reference's settings and every case's, checked by the rules `run` and `compare` apply
/// (`Model::reference_settings`, `Model::newmark_settings`) before anything is computed. An
/// error names the flag (`--dt`, `--rtol`, `--reference-rtol`), the value and the rule.
pub fn configurations(
    model: &Model,
    options: &ConvergeOptions,
) -> Result<(SolverSettings, Vec<Configuration>)> {
    let flag = |flag: &'static str| {
        move |e: flexrock_core::Error| e.renamed("rtol", flag).renamed("solver.rtol", flag)
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
    let reference_settings =
        crate::commands::compare::reference_settings(model, options.reference_rtol)?;
    let mut configurations =
        flexrock_core::analysis::converge::newmark_configurations(model, &options.dts)
            .map_err(|e| e.renamed("solver.dt", "--dt"))?;
    configurations.extend(
        flexrock_core::analysis::converge::adaptive_configurations(model, &options.rtols)
            .map_err(flag("--rtol"))?,
    );
    // Every value is valid on its own; errors are measured against the reference: one no tighter than a case measures the
    // reference's own error, and the orders printed would mean nothing.
    let tightest = options.rtols.iter().copied().fold(f64::INFINITY, f64::min);
    let reference_rtol = options.reference_rtol.unwrap_or(0.0);
    if reference_rtol.partial_cmp(&tightest) != Some(std::cmp::Ordering::Less) {
        return Err(crate::Error::invalid(
            "--reference-rtol",
            reference_rtol,
            &format!(
                "the reference must be tighter than every case: give a --reference-rtol below \
                 the smallest --rtol ({}), e.g. 1e-12",
                crate::writers::shortest(tightest)
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
    let Convergence {
        mut reference,
        reference_settings,
        output_dt,
        mut cases,
        slopes,
    } = converge(model, reference_settings, &configurations)?;
    let mut timings = writers::Timings::new(options.wall_times);
    timings.take(
        "convergence.json/reference_statistics/wall_time_s",
        &mut reference.stats.wall_time_s,
    );
    for (i, case) in cases.iter_mut().enumerate() {
        if case.is_ok() {
            timings.take(
                &format!("convergence.json/cases/{i}/wall_time_s"),
                &mut case.wall_time_s,
            );
        }
    }
    let summary = ConvergeSummary {
        provenance: timings.provenance("convergence.json", model),
        reference_method: reference_settings.label(),
        reference_rtol: options.reference_rtol,
        reference_statistics: reference.stats.clone(),
        reference_events: reference.events.len(),
        output_dt,
        cases,
        slopes,
    };
    let (by_dt, by_work) = figures(&summary);
    let mut figure_files = plot::files("convergence_dt", &by_dt, &options.figures, PAGE_MM)?;
    figure_files.extend(plot::files(
        "convergence_work",
        &by_work,
        &options.figures,
        PAGE_MM,
    )?);
    let mut files = vec![
        ("convergence.csv", cases_table(&summary.cases)),
        ("convergence.json", writers::json_bytes(&summary)),
    ];
    files.extend(timings.file());
    let mut files: Vec<(String, Vec<u8>)> = (files.into_iter())
        .map(|(name, bytes)| (name.to_string(), bytes))
        .collect();
    files.extend(figure_files);
    let files = writers::write_named_atomically(out_dir, files)?;
    Ok(ConvergeReport { summary, files })
}

fn cases_table(cases: &[Case]) -> Vec<u8> {
    let mut table = Table::new(&CONVERGENCE_COLUMNS);
    for c in cases {
        table.row(fields::fields(&CASE_COLUMNS, c));
    }
    table.into_bytes()
}

/// Error against dt (Newmark, with slope-1 and slope-2 guides) and error against work (all).
/// The panels need no titles: each y label names its error (what it is measured against is
/// convergence.json's reference_method).
fn figures(summary: &ConvergeSummary) -> (Figure, Figure) {
    let ok = |c: &&Case| c.is_ok();
    let methods = methods(&summary.cases);
    // (column, axis label with unit)
    let titles = [
        ("max_q_error", "max |Δq| on the grid (m)"),
        ("max_event_time_error", "max |Δt_event| (s)"),
        ("peak_error", "|Δq_peak| (m)"),
    ];
    let mut dt_panels = Vec::new();
    let mut work_panels = Vec::new();
    for (name, y_label) in titles {
        let mut dt_series = Vec::new();
        let mut work_series = Vec::new();
        for (i, method) in methods.iter().enumerate() {
            let cases: Vec<&Case> = summary
                .cases
                .iter()
                .filter(|c| c.method == *method)
                .filter(ok)
                .collect();
            let work: Vec<(f64, f64)> = cases
                .iter()
                .map(|c| (c.rhs_evaluations as f64, c.metric(name)))
                .collect();
            work_series.push(
                Series::line(method, work, i + 1)
                    .with_width(1.2)
                    .with_markers(),
            );
            if cases.first().is_some_and(|c| c.dt.is_some()) {
                let points: Vec<(f64, f64)> = cases
                    .iter()
                    .map(|c| (c.dt.unwrap_or(f64::NAN), c.metric(name)))
                    .collect();
                dt_series.push(
                    Series::line(method, points, i + 1)
                        .with_width(1.2)
                        .with_markers(),
                );
            }
        }
        // Guides through the first compensate point: slopes 1 and 2.
        if let Some(anchor) = summary
            .cases
            .iter()
            .find(|c| c.dt.is_some() && c.is_ok() && c.metric(name) > 0.0)
        {
            let (x0, y0) = (anchor.dt.unwrap_or(1.0), anchor.metric(name));
            let x1 = summary.cases.iter().filter_map(|c| c.dt).fold(x0, f64::min);
            for (order, color) in [(1.0, 5), (2.0, 6)] {
                // Guides, not data: thin and dashed.
                dt_series.push(
                    Series::line(
                        &format!("slope {order}"),
                        vec![(x0, y0), (x1, y0 * (x1 / x0).powf(order))],
                        color,
                    )
                    .with_width(0.5)
                    .with_dash(Dash::Dotted),
                );
            }
        }
        dt_panels.push(Panel {
            x_label: "Δt (s)".to_string(),
            y_label: y_label.to_string(),
            series: dt_series,
            log_x: true,
            log_y: true,
            ..Panel::default()
        });
        work_panels.push(Panel {
            x_label: "right-hand-side evaluations".to_string(),
            y_label: y_label.to_string(),
            series: work_series,
            log_x: true,
            log_y: true,
            ..Panel::default()
        });
    }
    (
        Figure::new(dt_panels, 1).aspect(2.6, 35.0),
        Figure::new(work_panels, 1).aspect(2.6, 35.0),
    )
}

/// How a reference is as accurate as it is, for the printed tables: "the closed form" or
/// "rtol = 1e-12".
pub fn reference_accuracy(rtol: Option<f64>) -> String {
    rtol.map_or("the closed form, errors are true errors".to_string(), |r| {
        format!("rtol = {r:e}")
    })
}

/// The printed table, orders and efficiency slopes of `flexrock converge`.
pub fn converge_text(report: &ConvergeReport) -> String {
    let s = &report.summary;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION} converge: reference {} ({}; {}, {})",
        s.reference_method,
        reference_accuracy(s.reference_rtol),
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
        if !c.is_ok() {
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
