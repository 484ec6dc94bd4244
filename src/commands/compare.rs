//! `flexrock compare`: a tight adaptive reference and Newmark at the paper's dt, side by side:
//! the solves, the files (compare.csv, compare_history.csv, compare.json and the figures) and the
//! printed table. The measuring is [`flexrock_core::analysis::compare`] (re-exported here): [`match_events`]
//! aligns two event logs, [`compare`] measures two solutions of one model against each other.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::commands::run::{simulate_with, VERSION};
use crate::error::Result;
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Dash, Figure, Panel, Series};
use crate::writers::{self, count, readable, Table};
use flexrock_core::analysis::findings::{self, Findings};
use flexrock_core::integrate::solution::{Extremum, Sample, Solution, SolverStats};
use flexrock_core::integrate::SolverSettings;
use flexrock_core::model::Model;
use flexrock_core::physics::automaton::EventKind;
use flexrock_core::tables::fields;

pub use flexrock_core::analysis::compare::{
    compare, grid_rows, match_events, max_event_shift, on_grid, Comparison, EventAgreement,
    EventPair, EventRow, GridDifferences, GridRow, PeakComparison, EVENT_COLUMNS, GRID_COLUMNS,
};

/// Column names of compare.csv (a contract): the names of [`EVENT_COLUMNS`].
pub const COMPARE_COLUMNS: [&str; 11] = fields::names(&EVENT_COLUMNS);

/// Column names of compare_history.csv (a contract): the names of [`GRID_COLUMNS`].
pub const COMPARE_HISTORY_COLUMNS: [&str; 10] = fields::names(&GRID_COLUMNS);

/// Options of `flexrock compare`.
#[derive(Debug, Clone)]
pub struct CompareOptions {
    /// Relative tolerance of an adaptive reference; None: the exact solution is the reference.
    pub reference_rtol: Option<f64>,
    /// Newmark step (default: the file's, else the paper's 0.02 s).
    pub dt: Option<f64>,
    /// Newmark variant (default: the file's, else "compensate").
    pub variant: Option<String>,
    /// Where the two solves' wall times go (compare.json, or timings.json).
    pub wall_times: writers::WallTimes,
    /// The figures' formats and size.
    pub figures: FigureOptions,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            reference_rtol: None,
            dt: None,
            variant: None,
            wall_times: writers::WallTimes::Inline,
            figures: FigureOptions::default(),
        }
    }
}

/// One solution's description in compare.json.
#[derive(Debug, Serialize)]
pub(crate) struct SolutionSummary<'a> {
    pub method: String,
    pub solver: SolverSettings,
    pub n_events: usize,
    pub n_uplift: usize,
    pub n_landing: usize,
    pub overturned: bool,
    pub max_q: Extremum,
    pub min_q: Extremum,
    pub max_energy_residual: f64,
    pub statistics: &'a SolverStats,
    pub findings: Findings,
}

fn solution_summary<'a>(
    model: &Model,
    settings: SolverSettings,
    s: &'a Solution,
) -> SolutionSummary<'a> {
    SolutionSummary {
        method: settings.label(),
        solver: settings,
        n_events: s.events.len(),
        n_uplift: s.count(EventKind::Uplift),
        n_landing: s.count(EventKind::Landing),
        overturned: s.overturned,
        max_q: s.max_q,
        min_q: s.min_q,
        max_energy_residual: s.max_energy_residual,
        statistics: &s.stats,
        findings: findings::measure(
            s,
            &flexrock_core::physics::automaton::Automaton::new(&model.constants),
        ),
    }
}

/// compare.json.
#[derive(Debug, Serialize)]
pub(crate) struct CompareSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::commands::run::Provenance,
    #[serde(rename = "T")]
    pub period: f64,
    pub s_n: f64,
    pub duration: f64,
    /// Events further apart than this are not matched, s.
    pub max_event_shift: f64,
    pub reference: SolutionSummary<'a>,
    pub newmark: SolutionSummary<'a>,
    pub comparison: &'a Comparison,
}

/// Result of `flexrock compare`.
pub struct CompareReport {
    /// The adaptive reference solution.
    pub reference: Solution,
    /// The Newmark solution.
    pub newmark: Solution,
    /// The reference's solver settings.
    pub reference_settings: SolverSettings,
    /// The Newmark solver settings.
    pub newmark_settings: SolverSettings,
    /// The Newmark solution measured against the reference.
    pub comparison: Comparison,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// The reference's and Newmark's settings, checked before anything is computed; an error names
/// the flag its value came from (`--reference-rtol`, `--dt`, `--variant`).
pub fn compare_settings(
    model: &Model,
    options: &CompareOptions,
) -> Result<(SolverSettings, SolverSettings)> {
    let reference = reference_settings(model, options.reference_rtol)?;
    let newmark = model
        .newmark_settings(options.dt, options.variant.as_deref())
        .map_err(|e| {
            let e = match options.dt {
                Some(_) => e.renamed("solver.dt", "--dt"),
                None => e,
            };
            match options.variant {
                Some(_) => e.renamed("solver.newmark_variant", "--variant"),
                None => e,
            }
        })?;
    Ok((reference, SolverSettings::Newmark(newmark)))
}

/// The reference of `compare` and `converge`: the exact solution, or the model's adaptive method
/// at `rtol` when one is given (an error names `--reference-rtol`).
pub fn reference_settings(model: &Model, rtol: Option<f64>) -> Result<SolverSettings> {
    model.reference(rtol).map_err(|e| {
        e.renamed("rtol", "--reference-rtol")
            .renamed("solver.rtol", "--reference-rtol")
            .into()
    })
}

/// Runs the reference and Newmark, compares them, writes compare.csv, compare_history.csv,
/// compare.json, compare.svg and compare_relations.svg into `out_dir`.
pub fn run_compare(
    model: &Model,
    options: &CompareOptions,
    out_dir: &Path,
) -> Result<CompareReport> {
    let (reference_settings, newmark_settings) = compare_settings(model, options)?;
    let mut reference = simulate_with(model, &reference_settings)?;
    let mut newmark = simulate_with(model, &newmark_settings)?;
    let mut timings = writers::Timings::new(options.wall_times);
    timings.take(
        "compare.json/reference/statistics/wall_time_s",
        &mut reference.stats.wall_time_s,
    );
    timings.take(
        "compare.json/newmark/statistics/wall_time_s",
        &mut newmark.stats.wall_time_s,
    );
    let output_dt = model.solver.output_dt();
    let max_shift = max_event_shift(model);
    let comparison = compare(&reference, &newmark, output_dt, max_shift);

    let summary = CompareSummary {
        provenance: timings.provenance("compare.json", model),
        period: model.constants.period,
        s_n: model.constants.uplift_displacement,
        duration: model.duration,
        max_event_shift: max_shift,
        reference: solution_summary(model, reference_settings, &reference),
        newmark: solution_summary(model, newmark_settings, &newmark),
        comparison: &comparison,
    };
    let figure = compare_figure(model, &reference, &newmark, &newmark_settings.label());
    let relations = relations_figure(&reference, &newmark, &newmark_settings.label());
    let mut figure_files = plot::files("compare", &figure, &options.figures, PAGE_MM)?;
    figure_files.extend(plot::files(
        "compare_relations",
        &relations,
        &options.figures,
        PAGE_MM,
    )?);
    let mut files = vec![
        ("compare.csv", events_table(&comparison)),
        (
            "compare_history.csv",
            history_table(&reference, &newmark, output_dt),
        ),
        ("compare.json", writers::json_bytes(&summary)),
    ];
    files.extend(timings.file());
    let mut files: Vec<(String, Vec<u8>)> = (files.into_iter())
        .map(|(name, bytes)| (name.to_string(), bytes))
        .collect();
    files.extend(figure_files);
    let files = writers::write_named_atomically(out_dir, files)?;
    Ok(CompareReport {
        reference,
        newmark,
        reference_settings,
        newmark_settings,
        comparison,
        files,
    })
}

fn events_table(comparison: &Comparison) -> Vec<u8> {
    let mut table = Table::new(&COMPARE_COLUMNS);
    for row in comparison.event_rows() {
        table.row(fields::fields(&EVENT_COLUMNS, &row));
    }
    table.into_bytes()
}

fn history_table(reference: &Solution, other: &Solution, output_dt: f64) -> Vec<u8> {
    let mut table = Table::new(&COMPARE_HISTORY_COLUMNS);
    for row in grid_rows(reference, other, output_dt) {
        table.row(fields::fields(&GRID_COLUMNS, &row));
    }
    table.into_bytes()
}

/// The paper's Fig. 6 panels (q, s, r, q') with both solutions overlaid.
fn compare_figure(model: &Model, reference: &Solution, other: &Solution, label: &str) -> Figure {
    let s_n = model.constants.uplift_displacement;
    let panel = |title: &str, y_label: &str, value: fn(&Sample) -> f64, s_n_lines: bool| {
        let series = vec![
            Series::line(
                &format!("reference ({})", reference.stats.method),
                reference.samples.iter().map(|x| (x.t, value(x))).collect(),
                0,
            ),
            Series::line(
                label,
                other.samples.iter().map(|x| (x.t, value(x))).collect(),
                1,
            )
            .with_dash(Dash::Dashed),
        ];
        let reference_lines = if s_n_lines {
            vec![(s_n, "±sₙ (uplift)".to_string()), (-s_n, String::new())]
        } else {
            Vec::new()
        };
        Panel {
            title: title.to_string(),
            x_label: "t (s)".to_string(),
            y_label: y_label.to_string(),
            series,
            reference_lines,
            ..Panel::default()
        }
    };
    let panels = [
        panel("", "q (m)", |x| x.q, true),
        panel("", "s (m)", |x| x.s, true),
        panel("", "r (m)", |x| x.r, false),
        panel("", "q\u{307} (m/s)", |x| x.qdot, false),
    ];
    Figure::new(panels.to_vec(), 1).shared_x().aspect(4.5, 24.0)
}

/// The paper's Figs. 12-13: q against r and s against r, both solutions.
fn relations_figure(reference: &Solution, other: &Solution, label: &str) -> Figure {
    let panel = |title: &str, x_label: &str, y_label: &str, xy: fn(&Sample) -> (f64, f64)| Panel {
        title: title.to_string(),
        x_label: x_label.to_string(),
        y_label: y_label.to_string(),
        series: vec![
            Series::line(
                &format!("reference ({})", reference.stats.method),
                reference.samples.iter().map(xy).collect(),
                0,
            ),
            Series::line(label, other.samples.iter().map(xy).collect(), 1).with_dash(Dash::Dashed),
        ],
        ..Panel::default()
    };
    let panels = [
        panel("", "r (m)", "q (m)", |x| (x.r, x.q)),
        panel("", "r (m)", "s (m)", |x| (x.r, x.s)),
    ];
    Figure::new(panels.to_vec(), 2).aspect(1.1, 40.0)
}

/// The printed table of `flexrock compare`.
pub fn compare_text(model: &Model, report: &CompareReport) -> String {
    let c = &report.comparison;
    let mut t = String::new();
    let newmark_label = report.newmark_settings.label();
    let dt = match report.newmark_settings {
        SolverSettings::Newmark(n) => {
            format!(
                "dt = {} s, beta = {:.6}, gamma = {}",
                readable(n.dt),
                n.beta,
                readable(n.gamma)
            )
        }
        SolverSettings::Adaptive(_) | SolverSettings::Exact(_) => String::new(),
    };
    let reference_rtol = match report.reference_settings {
        SolverSettings::Adaptive(a) => format!("rtol = {:e}", a.rtol),
        SolverSettings::Exact(_) => "closed form".to_string(),
        SolverSettings::Newmark(_) => String::new(),
    };
    let _ = writeln!(
        t,
        "flexrock {VERSION} compare: reference {} ({reference_rtol}) vs {newmark_label} ({dt}) over {} s",
        report.reference_settings.label(),
        readable(model.duration)
    );
    let e = &c.events;
    let _ = writeln!(
        t,
        "events: reference {}, newmark {}, matched {} (same transition, in order, within {:.3} s), missed {}, spurious {}",
        e.n_reference,
        e.n_other,
        e.n_matched,
        max_event_shift(model),
        e.n_missed,
        e.n_spurious
    );
    let _ = writeln!(
        t,
        "  {:>3}  {:<8} {:<24} {:>12} {:>12} {:>11}",
        "#", "kind", "transition", "t_reference", "t_newmark", "difference"
    );
    let cell =
        |x: Option<f64>, digits: usize| x.map_or("-".to_string(), |v| format!("{v:.digits$}"));
    for (i, p) in c.pairs.iter().enumerate() {
        let _ = writeln!(
            t,
            "  {:>3}  {:<8} {:<24} {:>12} {:>12} {:>11}",
            i,
            p.kind.name(),
            format!("{} -> {}", p.from.name(), p.to.name()),
            cell(p.reference.as_ref().map(|e| e.t), 6),
            cell(p.other.as_ref().map(|e| e.t), 6),
            cell(p.time_difference(), 6),
        );
    }
    if e.n_matched == 0 {
        let _ = writeln!(t, "  event times: no event matched, none to time");
    } else {
        let _ = writeln!(
            t,
            "  event times: max |difference| {:.6} s, mean {:.6} s",
            e.max_abs_time_difference, e.mean_abs_time_difference
        );
    }
    let p = &c.peaks;
    let _ = writeln!(
        t,
        "peaks of q:         reference (t)             newmark (t)               difference"
    );
    let _ = writeln!(
        t,
        "  max q   {:>10.6} m ({:>8.4} s)   {:>10.6} m ({:>8.4} s)   {:>+10.6} m",
        p.reference_max_q.value,
        p.reference_max_q.t,
        p.other_max_q.value,
        p.other_max_q.t,
        p.max_q_difference
    );
    let _ = writeln!(
        t,
        "  min q   {:>10.6} m ({:>8.4} s)   {:>10.6} m ({:>8.4} s)   {:>+10.6} m",
        p.reference_min_q.value,
        p.reference_min_q.t,
        p.other_min_q.value,
        p.other_min_q.t,
        p.min_q_difference
    );
    let g = &c.grid;
    let _ = writeln!(
        t,
        "q(t) on the common {} s grid ({}): RMS difference {:.6} m, max {:.6} m at t = {:.3} s; max |q' difference| {:.6} m/s",
        readable(g.output_dt), count(g.points, "point", "points"), g.rms_q_difference, g.max_abs_q_difference, g.t_max_abs_q_difference, g.max_abs_qdot_difference
    );
    let _ = writeln!(
        t,
        "cost: reference {}, {}{}; newmark {}, {}{}",
        count(report.reference.stats.steps, "step", "steps"),
        count(
            report.reference.stats.rhs_evaluations,
            "rhs evaluation",
            "rhs evaluations"
        ),
        writers::milliseconds(report.reference.stats.wall_time_s, 1)
            .map_or_else(String::new, |t| format!(", {t}")),
        count(report.newmark.stats.steps, "step", "steps"),
        count(
            report.newmark.stats.rhs_evaluations,
            "rhs evaluation",
            "rhs evaluations"
        ),
        writers::milliseconds(report.newmark.stats.wall_time_s, 1)
            .map_or_else(String::new, |t| format!(", {t}"))
    );
    for f in &report.files {
        let _ = writeln!(t, "wrote {}", f.display());
    }
    t
}
