//! The `flexrock fem` command as library functions: the finite element run's files
//! (fem_history.csv, fem_events.csv, fem_summary.json, the figures), its comparison with the
//! one-degree-of-freedom model written out, the printed summaries, and the fixed-base modes'
//! table. The analysis (uplift episodes, peaks, line fits, the comparison's numbers) is
//! [`flexrock_core::analysis::fem_check`], re-exported here.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::commands::run::VERSION;
use crate::error::{Error, Result};
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Figure, Panel, Series};
use crate::writers::{self, count, readable, Table};
use flexrock_core::analysis::fem_check;
use flexrock_core::bodies::fem::{FemResult, FemStep};
use flexrock_core::integrate::solution::Solution;
use flexrock_core::model::{FemSetup, Model, ModelFile};
use flexrock_core::tables::fields;

use flexrock_core::analysis::fem_check::{analyse as analyse_run, compare as compare_solutions};
pub use flexrock_core::analysis::fem_check::{
    event_rows, history_rows, modes, peaks, uplift_episodes, EventRow, FemAnalysis, FemComparison,
    FemComparisonRow, FemPeaks, FemWarning, HistoryRow, Modes, UpliftEpisode, COMPARISON_COLUMNS,
    ELEMENT, MODE_COUNT, UPLIFT_ROCKING_FRACTION,
};

/// Column names of fem_history.csv (a contract): the names of
/// [`flexrock_core::analysis::fem_check::HISTORY_COLUMNS`].
pub const HISTORY_COLUMNS: [&str; 12] = fields::names(&fem_check::HISTORY_COLUMNS);

/// Column names of fem_events.csv (a contract): the names of
/// [`flexrock_core::analysis::fem_check::EVENT_COLUMNS`].
pub const EVENT_COLUMNS: [&str; 7] = fields::names(&fem_check::EVENT_COLUMNS);

/// Magnification of the deformed shapes (the paper's Fig. 9).
pub const SHAPE_MAGNIFICATION: f64 = 5.0;

/// A warning of a run as the user reads it (printed, and written to fem_summary.json): the
/// scheme is named by its flag.
pub fn warning_text(warning: &FemWarning) -> String {
    warning.text("--scheme")
}

/// Runs the finite element analysis of a model ([`flexrock_core::analysis::fem_check::analyse`]); the
/// command refuses an initial velocity, since the run starts at rest.
pub fn analyse(model: &Model, setup: &FemSetup) -> Result<FemAnalysis> {
    if model.initial.qdot != 0.0 {
        return Err(Error::invalid(
            "simulation.qdot0",
            model.initial.qdot,
            "the finite element analysis starts at rest: qdot0 must be 0 for `flexrock fem`",
        ));
    }
    Ok(analyse_run(model, setup)?)
}

pub(crate) fn history_csv(model: &Model, steps: &[FemStep]) -> Vec<u8> {
    let mut table = Table::new(&HISTORY_COLUMNS);
    for row in history_rows(model, steps) {
        table.row(fields::fields(&fem_check::HISTORY_COLUMNS, &row));
    }
    table.into_bytes()
}

pub(crate) fn events_csv(result: &FemResult) -> Vec<u8> {
    let mut table = Table::new(&EVENT_COLUMNS);
    for row in event_rows(result) {
        table.row(fields::fields(&fem_check::EVENT_COLUMNS, &row));
    }
    table.into_bytes()
}

/// fem_summary.json.
#[derive(Debug, Serialize)]
pub(crate) struct FemSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::commands::run::Provenance,
    pub element: &'static str,
    pub body: &'a flexrock_core::bodies::fem::FemBody,
    pub settings: &'a flexrock_core::bodies::fem::FemSettings,
    pub scheme: &'static str,
    pub mass: f64,
    pub flexural_rigidity: f64,
    pub gravity_parameter: f64,
    pub gravity_parameter_ratio: f64,
    #[serde(rename = "sdof_T")]
    pub sdof_period: f64,
    pub sdof_s_n: f64,
    pub highest_frequency: f64,
    pub shortest_period: f64,
    pub linear_acceleration_stability_limit: f64,
    pub scheme_stability_limit: Option<f64>,
    pub dt_beyond_stability_limit: bool,
    pub warnings: Vec<String>,
    pub static_reactions: &'a [[f64; 2]],
    pub steps: usize,
    pub contact_changes: usize,
    pub uplifts: &'a [UpliftEpisode],
    pub peaks: FemPeaks,
    pub overturned_at: Option<f64>,
    pub wall_time_s: f64,
    pub excitation: serde_json::Value,
    pub inputs: &'a ModelFile,
}

pub(crate) fn summary<'a>(model: &'a Model, a: &'a FemAnalysis) -> FemSummary<'a> {
    let b = &a.setup.body;
    let c = &model.constants;
    let r = &a.result;
    FemSummary {
        provenance: crate::commands::run::Provenance::of(model),
        element: ELEMENT,
        body: b,
        settings: &a.setup.settings,
        scheme: a.setup.scheme_name,
        mass: b.mass(),
        flexural_rigidity: b.flexural_rigidity(),
        gravity_parameter: c.gravity_parameter,
        gravity_parameter_ratio: c.gravity_parameter_ratio,
        sdof_period: c.period,
        sdof_s_n: c.uplift_displacement,
        highest_frequency: r.highest_frequency,
        shortest_period: 2.0 * std::f64::consts::PI / r.highest_frequency,
        linear_acceleration_stability_limit: a.linear_acceleration_limit,
        scheme_stability_limit: r.critical_time_step,
        dt_beyond_stability_limit: r
            .critical_time_step
            .is_some_and(|limit| a.setup.settings.dt > limit),
        warnings: a.warnings.iter().map(warning_text).collect(),
        static_reactions: &r.static_reactions,
        steps: r.steps.len(),
        contact_changes: r.events.len(),
        uplifts: &a.uplifts,
        peaks: peaks(&r.steps),
        overturned_at: r.overturned_at,
        wall_time_s: a.wall_time_s,
        excitation: model.floor.parameters(),
        inputs: &model.file,
    }
}

fn time_series(steps: &[FemStep], f: fn(&FemStep) -> f64) -> Vec<(f64, f64)> {
    steps.iter().map(|s| (s.t, f(s))).collect()
}

fn sn_lines(s_n: f64) -> Vec<(f64, String)> {
    vec![
        (s_n, "±sₙ (SDOF uplift)".to_string()),
        (-s_n, String::new()),
    ]
}

/// Deformed shapes (x5) at the stored snapshots, side by side, relative to the floor.
fn deformed_shapes(a: &FemAnalysis) -> Panel {
    let s = &a.setup.settings;
    let b = &a.setup.body;
    let coords = &a.result.node_coordinates;
    let spacing = 2.0 * b.width + 2.0 * SHAPE_MAGNIFICATION * b.width;
    let mut chart = Panel::new(
        &format!(
            "Deformed shapes (×{SHAPE_MAGNIFICATION}), {} × {} mesh",
            s.nx, s.ny
        ),
        "x (m, shapes offset)",
        "y (m)",
    );
    chart.equal_aspect = true;
    let node = |i: usize, j: usize| j * (s.nx + 1) + i;
    for (k, snap) in a.result.snapshots.iter().enumerate() {
        let offset = k as f64 * spacing;
        let point = |n: usize| {
            let d = snap.displacements.get(n).copied().unwrap_or([f64::NAN; 2]);
            (
                offset + coords[n][0] + SHAPE_MAGNIFICATION * d[0],
                coords[n][1] + SHAPE_MAGNIFICATION * d[1],
            )
        };
        let mut lines: Vec<Vec<(f64, f64)>> = (0..=s.ny)
            .map(|j| (0..=s.nx).map(|i| point(node(i, j))).collect())
            .collect();
        lines.extend((0..=s.nx).map(|i| (0..=s.ny).map(|j| point(node(i, j))).collect()));
        for (l, points) in lines.into_iter().enumerate() {
            let label = if l == 0 {
                format!("t = {:.3} s", snap.t)
            } else {
                String::new()
            };
            chart.series.push(Series::line(&label, points, k + 2));
        }
    }
    let end = a.result.snapshots.len().max(1) as f64 * spacing;
    chart.series.push(Series::line(
        "floor",
        vec![(-spacing / 2.0, 0.0), (end - spacing / 2.0, 0.0)],
        0,
    ));
    chart
}

/// The figures of a run: (file stem, chart). A chart's axes and legend say what it shows.
pub fn figures(model: &Model, a: &FemAnalysis) -> Vec<(&'static str, Panel)> {
    let steps = &a.result.steps;
    let s_n = model.constants.uplift_displacement;
    let mut components = Panel::new("", "t (s)", "q and parts (m)")
        .with(Series::line("q", time_series(steps, |s| s.q), 0))
        .with(Series::line(
            "flexural",
            time_series(steps, |s| s.flexural),
            2,
        ))
        .with(Series::line(
            "rocking",
            time_series(steps, |s| s.rocking),
            1,
        ))
        .with(Series::line(
            "slipping",
            time_series(steps, |s| s.slipping),
            3,
        ))
        .with(Series::line(
            "shearing",
            time_series(steps, |s| s.shearing),
            4,
        ));
    components.reference_lines = sn_lines(s_n);
    let q_r = Panel::new("", "r (m)", "q (m)").with(Series::line(
        "",
        steps.iter().map(|s| (s.rocking, s.q)).collect(),
        2,
    ));
    let s_r = Panel::new("", "r (m)", "s (m)").with(Series::line(
        "",
        steps.iter().map(|s| (s.rocking, s.flexural)).collect(),
        2,
    ));
    let velocity = Panel::new("", "t (s)", "q\u{307} (m/s)").with(Series::line(
        "",
        time_series(steps, |s| s.top_velocity),
        2,
    ));
    let momentum = Panel::new("clockwise positive", "t (s)", "L (kg m²/s)")
        .with(Series::line(
            "about the left toe",
            time_series(steps, |s| s.momentum_left_toe),
            2,
        ))
        .with(Series::line(
            "about the right toe",
            time_series(steps, |s| s.momentum_right_toe),
            1,
        ));
    vec![
        ("fem_deformed_shapes", deformed_shapes(a)),
        ("fem_components", components),
        ("fem_q_vs_r", q_r),
        ("fem_s_vs_r", s_r),
        ("fem_top_velocity", velocity),
        ("fem_angular_momentum", momentum),
    ]
}

/// The width over the height of what `chart` draws, with the paddings of an equal-aspect panel
/// (3 % each side across, 5 % up and down), from 0.5 to 8 (1.8 for a chart of no extent).
fn drawing_aspect(chart: &Panel) -> f64 {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in chart.series.iter().flat_map(|s| &s.points) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let aspect = (1.06 * (x1 - x0)) / (1.1 * (y1 - y0));
    if aspect.is_finite() && aspect > 0.0 {
        aspect.clamp(0.5, 8.0)
    } else {
        1.8
    }
}

/// The files of `charts` (a figure of one panel each, named by its stem) in the formats and size
/// of `options`.
fn render(
    charts: Vec<(&'static str, Panel)>,
    options: &FigureOptions,
) -> Result<Vec<(String, Vec<u8>)>> {
    let mut files = Vec::new();
    for (stem, chart) in charts {
        // A drawing to scale takes a plotting area of its own proportions.
        let (aspect, min_mm) = if chart.equal_aspect {
            (drawing_aspect(&chart), 0.0)
        } else {
            (1.8, 40.0)
        };
        let figure = Figure::new(vec![chart], 1).aspect(aspect, min_mm);
        files.extend(plot::files(stem, &figure, options, PAGE_MM)?);
    }
    Ok(files)
}

/// The files of a run: CSVs, summary and figures.
fn run_files(
    model: &Model,
    a: &FemAnalysis,
    timings: &mut writers::Timings,
    options: &FigureOptions,
) -> Result<Vec<(String, Vec<u8>)>> {
    let mut fem_summary = summary(model, a);
    timings.take_commit("fem_summary.json", &mut fem_summary.provenance);
    let mut files = vec![
        (
            "fem_history.csv".to_string(),
            history_csv(model, &a.result.steps),
        ),
        ("fem_events.csv".to_string(), events_csv(&a.result)),
        (
            "fem_summary.json".to_string(),
            writers::json_bytes(&fem_summary),
        ),
    ];
    files.extend(render(figures(model, a), options)?);
    Ok(files)
}

/// Writes `files` and the timings into `out_dir`, all or none.
fn write_all(
    out_dir: &Path,
    mut files: Vec<(String, Vec<u8>)>,
    timings: &writers::Timings,
) -> Result<Vec<PathBuf>> {
    files.extend((timings.file()).map(|(name, bytes)| (name.to_string(), bytes)));
    writers::write_named_atomically(out_dir, files)
}

/// Result of `flexrock fem`.
pub struct FemReport {
    /// The run and what was derived from it.
    pub analysis: FemAnalysis,
    /// The run's warnings as the user reads them ([`warning_text`]).
    pub warnings: Vec<String>,
    /// The one-mode model side by side with the run, when compared.
    pub comparison: Option<FemComparison>,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// [`analyse`], with its wall time taken into timings.json when `wall_times` says so.
fn analyse_timed(
    model: &Model,
    setup: &FemSetup,
    wall_times: writers::WallTimes,
) -> Result<(FemAnalysis, writers::Timings)> {
    let mut analysis = analyse(model, setup)?;
    let mut timings = writers::Timings::new(wall_times);
    timings.take("fem_summary.json/wall_time_s", &mut analysis.wall_time_s);
    Ok((analysis, timings))
}

/// Runs the finite element analysis and writes its files into `out_dir` (all or none); with
/// [`writers::WallTimes::Apart`] its wall time goes to timings.json.
pub fn fem(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: writers::WallTimes,
    options: &FigureOptions,
) -> Result<FemReport> {
    let (analysis, mut timings) = analyse_timed(model, setup, wall_times)?;
    let files = run_files(model, &analysis, &mut timings, options)?;
    let files = write_all(out_dir, files, &timings)?;
    Ok(FemReport {
        warnings: analysis.warnings.iter().map(warning_text).collect(),
        analysis,
        comparison: None,
        files,
    })
}

pub(crate) fn comparison_csv(c: &FemComparison) -> Vec<u8> {
    let mut table = Table::new(&fields::names(&COMPARISON_COLUMNS));
    for r in &c.rows {
        table.row(fields::fields(&COMPARISON_COLUMNS, r));
    }
    table.into_bytes()
}

/// The comparison as a text table.
pub fn comparison_text(c: &FemComparison) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "  {:<36} {:>12} {:>12}", "quantity", "SDOF", "FEM");
    for r in &c.rows {
        let digits = if r.is_count { 0 } else { 5 };
        let _ = writeln!(
            t,
            "  {:<36} {:>12.digits$} {:>12.digits$}",
            r.quantity, r.sdof, r.fem
        );
    }
    let list = |v: &[f64]| {
        let shown: Vec<String> = v.iter().take(12).map(|t| format!("{t:.3}")).collect();
        let more = if v.len() > 12 { ", ..." } else { "" };
        format!("{}{more}", shown.join(", "))
    };
    let _ = writeln!(t, "  SDOF uplift times (s): {}", list(&c.sdof_uplift_times));
    let _ = writeln!(t, "  FEM uplift times (s):  {}", list(&c.fem_uplift_times));
    t
}

fn comparison_figures(
    model: &Model,
    sdof: &Solution,
    a: &FemAnalysis,
) -> Vec<(&'static str, Panel)> {
    let steps = &a.result.steps;
    let sdof_series = |f: fn(&flexrock_core::integrate::solution::Sample) -> (f64, f64)| {
        Series::line("SDOF", sdof.samples.iter().map(f).collect(), 1)
    };
    let mut q = Panel::new("", "t (s)", "q (m)")
        .with(sdof_series(|s| (s.t, s.q)))
        .with(Series::line("FEM", time_series(steps, |s| s.q), 2));
    q.reference_lines = sn_lines(model.constants.uplift_displacement);
    let mut s = Panel::new("", "t (s)", "s (m)")
        .with(sdof_series(|s| (s.t, s.s)))
        .with(Series::line("FEM", time_series(steps, |s| s.flexural), 2));
    s.reference_lines = sn_lines(model.constants.uplift_displacement);
    let velocity = Panel::new("", "t (s)", "q\u{307} (m/s)")
        .with(sdof_series(|s| (s.t, s.qdot)))
        .with(Series::line(
            "FEM",
            time_series(steps, |s| s.top_velocity),
            2,
        ));
    let q_r = Panel::new("", "r (m)", "q (m)")
        .with(sdof_series(|s| (s.r, s.q)))
        .with(Series::line(
            "FEM",
            steps.iter().map(|s| (s.rocking, s.q)).collect(),
            2,
        ));
    let s_r = Panel::new("", "r (m)", "s (m)")
        .with(sdof_series(|s| (s.r, s.s)))
        .with(Series::line(
            "FEM",
            steps.iter().map(|s| (s.rocking, s.flexural)).collect(),
            2,
        ));
    vec![
        ("compare_q", q),
        ("compare_flexural", s),
        ("compare_top_velocity", velocity),
        ("compare_q_vs_r", q_r),
        ("compare_s_vs_r", s_r),
    ]
}

/// `flexrock fem --compare`: the FEM run, the SDOF solution of the same model
/// ([`crate::commands::run::simulate`]) and both side by side, all written into `out_dir` (all or none);
/// with [`writers::WallTimes::Apart`] the FEM's wall time goes to timings.json.
pub fn compare(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: writers::WallTimes,
    options: &FigureOptions,
) -> Result<FemReport> {
    let (analysis, mut timings) = analyse_timed(model, setup, wall_times)?;
    let sdof = crate::commands::run::simulate(model)?;
    let comparison = compare_solutions(model, &sdof, &analysis);
    let mut files = run_files(model, &analysis, &mut timings, options)?;
    files.push(("compare.csv".to_string(), comparison_csv(&comparison)));
    files.push(("compare.json".to_string(), writers::json_bytes(&comparison)));
    files.push((
        "sdof_history.csv".to_string(),
        writers::history_csv(&sdof.samples),
    ));
    files.extend(render(
        comparison_figures(model, &sdof, &analysis),
        options,
    )?);
    let files = write_all(out_dir, files, &timings)?;
    Ok(FemReport {
        warnings: analysis.warnings.iter().map(warning_text).collect(),
        analysis,
        comparison: Some(comparison),
        files,
    })
}

/// The short human summary printed after `flexrock fem`.
pub fn report_text(report: &FemReport) -> String {
    let a = &report.analysis;
    let s = &a.setup.settings;
    let p = peaks(&a.result.steps);
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION} fem: {} x {} QM6 mesh, {} dt = {} s over {} s, P-Delta {}",
        s.nx,
        s.ny,
        a.setup.scheme_name,
        readable(s.dt),
        readable(s.duration),
        if s.p_delta { "on" } else { "off" }
    );
    let _ = writeln!(
        t,
        "  highest frequency {:.1} rad/s: linear acceleration stable for dt <= {} s",
        a.result.highest_frequency,
        flexrock_core::base::format::short_seconds(a.linear_acceleration_limit)
    );
    let _ = writeln!(
        t,
        "  max q = {:.6} m at t = {:.4} s; min q = {:.6} m at t = {:.4} s",
        p.max_q, p.t_max_q, p.min_q, p.t_min_q
    );
    let _ = writeln!(
        t,
        "  {}, {}; {}{}",
        count(
            a.result.events.len(),
            "base-node state change",
            "base-node state changes"
        ),
        count(a.uplifts.len(), "uplift episode", "uplift episodes"),
        count(a.result.steps.len(), "step", "steps"),
        writers::milliseconds(a.wall_time_s, 1).map_or_else(String::new, |t| format!(" in {t}"))
    );
    if let Some(c) = &report.comparison {
        t.push_str(&comparison_text(c));
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}

/// The text `flexrock fem --modes` prints.
pub fn modes_text(m: &Modes) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "fixed-base natural periods of the {} x {} mesh (s); SDOF pre-uplift period T = {:.4} s",
        m.nx, m.ny, m.sdof_period
    );
    let _ = writeln!(
        t,
        "  {:<6} {:>14} {:>14} {:>14}",
        "mode", "no P-Delta", "with P-Delta", "ratio to T"
    );
    for (k, (e, p)) in m.periods_elastic.iter().zip(&m.periods_p_delta).enumerate() {
        let _ = writeln!(
            t,
            "  {:<6} {:>14.4} {:>14.4} {:>14.4}",
            k + 1,
            e,
            p,
            p / m.sdof_period
        );
    }
    let _ = writeln!(
        t,
        "  highest frequency {:.1} rad/s; linear acceleration stable for dt <= {} s",
        m.highest_frequency,
        flexrock_core::base::format::short_seconds(m.linear_acceleration_stability_limit)
    );
    t
}
