//! The `flexrock fem` command as library functions: the finite element run and its files,
//! the comparison with the one-degree-of-freedom model, and the fixed-base modes.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

use super::{
    critical_time_step, fixed_base_periods, simulate_fem, ContactEvent, ContactState, FemResult,
    FemStep, TimeScheme,
};
use crate::automaton::EventKind;
use crate::error::{Error, Result};
use crate::model::{FemSetup, Model, ModelFile};
use crate::output::{self, count, number, readable, Table};
use crate::plot::{self, Panel, Series};
use crate::run::VERSION;
use crate::solution::Solution;

/// Column names of fem_history.csv (a contract).
pub const HISTORY_COLUMNS: [&str; 12] = [
    "t",
    "floor_acc",
    "q",
    "flexural",
    "rocking",
    "slipping",
    "shearing",
    "top_velocity",
    "momentum_left_toe",
    "momentum_right_toe",
    "lowest_base_uy",
    "base_states",
];

/// Column names of fem_events.csv (a contract).
pub const EVENT_COLUMNS: [&str; 7] = ["t", "node", "x", "from", "to", "rx", "ry"];

/// Magnification of the deformed shapes (the paper's Fig. 9).
pub const SHAPE_MAGNIFICATION: f64 = 5.0;

/// A finished finite element run and what was derived from it.
pub struct FemAnalysis {
    /// The validated finite element analysis.
    pub setup: FemSetup,
    /// The time history, contact events and snapshots.
    pub result: FemResult,
    /// Stability limit of the linear acceleration method on this mesh, s.
    pub linear_acceleration_limit: f64,
    /// Messages the user must see (also written to fem_summary.json).
    pub warnings: Vec<String>,
    /// Wall-clock time of the run, s.
    pub wall_time_s: f64,
    /// The stretches of steps with one base corner off the floor.
    pub uplifts: Vec<UpliftEpisode>,
}

/// A stretch of steps during which exactly one base corner is off the floor (see
/// [`uplift_episodes`]).
#[derive(Debug, Clone, Serialize)]
pub struct UpliftEpisode {
    /// First step with the corner off the floor, s.
    pub t_start: f64,
    /// First step with both corners back on the floor (or the end of the run), s.
    pub t_end: f64,
    /// "rock-right" (pivot on the right toe, left corner lifted) or "rock-left".
    pub side: &'static str,
    /// Largest |rocking part| during the episode, m.
    pub max_rocking: f64,
}

fn state_name(s: ContactState) -> &'static str {
    match s {
        ContactState::Free => "free",
        ContactState::Slip => "slip",
        ContactState::Fixed => "fixed",
    }
}

fn state_letter(s: ContactState) -> char {
    match s {
        ContactState::Free => 'F',
        ContactState::Slip => 'S',
        ContactState::Fixed => 'X',
    }
}

/// Which side the body rocks on at a step: Some("rock-right") when the left corner is off the
/// floor and the right corner on it, Some("rock-left") for the mirror, None otherwise.
fn rocking_side(step: &FemStep) -> Option<&'static str> {
    let on = |s: &ContactState| *s != ContactState::Free;
    match (step.base_states.first(), step.base_states.last()) {
        (Some(l), Some(r)) if !on(l) && on(r) => Some("rock-right"),
        (Some(l), Some(r)) if on(l) && !on(r) => Some("rock-left"),
        _ => None,
    }
}

/// Rocking part (fraction of the width B) an episode must reach to count as an uplift: smaller
/// ones are the heel opening of the continuum's base, not rocking on a toe.
pub const UPLIFT_ROCKING_FRACTION: f64 = 0.01;

/// The uplift episodes of a run, in time order. Episodes on the same side separated by at most
/// two steps are one episode (a corner node chattering on and off the floor), and episodes whose
/// rocking part stays below [`UPLIFT_ROCKING_FRACTION`] x `width` are left out.
pub fn uplift_episodes(steps: &[FemStep], width: f64) -> Vec<UpliftEpisode> {
    let dt = match steps {
        [a, b, ..] => b.t - a.t,
        _ => 0.0,
    };
    let mut merged: Vec<UpliftEpisode> = Vec::new();
    for e in corner_episodes(steps) {
        match merged.last_mut() {
            Some(last) if last.side == e.side && e.t_start - last.t_end <= 2.5 * dt => {
                last.t_end = e.t_end;
                last.max_rocking = last.max_rocking.max(e.max_rocking);
            }
            _ => merged.push(e),
        }
    }
    merged.retain(|e| e.max_rocking >= UPLIFT_ROCKING_FRACTION * width);
    merged
}

/// Every stretch of steps with exactly one corner off the floor.
fn corner_episodes(steps: &[FemStep]) -> Vec<UpliftEpisode> {
    let mut episodes: Vec<UpliftEpisode> = Vec::new();
    let mut current: Option<UpliftEpisode> = None;
    for step in steps {
        let side = rocking_side(step);
        if let Some(e) = current.as_mut() {
            if side == Some(e.side) {
                e.max_rocking = e.max_rocking.max(step.rocking.abs());
                continue;
            }
            e.t_end = step.t;
            episodes.extend(current.take());
        }
        if let Some(side) = side {
            current = Some(UpliftEpisode {
                t_start: step.t,
                t_end: step.t,
                side,
                max_rocking: step.rocking.abs(),
            });
        }
    }
    if let (Some(mut e), Some(last)) = (current, steps.last()) {
        e.t_end = last.t;
        episodes.push(e);
    }
    episodes
}

/// Runs the finite element analysis of a model: the floor acceleration comes from the model's
/// excitation, so every excitation kind works. The FEM starts at rest in the gravity state;
/// `simulation.q0` is applied as a rigid tilt about the toe (q = q0, all of it rocking).
pub fn analyse(model: &Model, setup: &FemSetup) -> Result<FemAnalysis> {
    if model.initial.qdot != 0.0 {
        return Err(Error::invalid(
            "simulation.qdot0",
            model.initial.qdot,
            "the finite element analysis starts at rest: qdot0 must be 0 for `flexrock fem`",
        ));
    }
    let mut setup = setup.clone();
    setup.settings.initial_rotation = model.initial.q / setup.body.height;
    let floor = |t: f64| model.floor.acceleration(t);
    let started = Instant::now();
    let result = simulate_fem(&setup.body, &setup.settings, &floor)?;
    let wall_time_s = started.elapsed().as_secs_f64();
    let linear_acceleration_limit =
        crate::solver::newmark::linear_acceleration_omega_dt() / result.highest_frequency;
    let mut warnings = Vec::new();
    if let Some(limit) = result.critical_time_step {
        if setup.settings.dt > limit {
            warnings.push(format!(
                "fem.dt = {} s exceeds the stability limit {} s of the {} method on this {} x {} mesh \
                 (highest frequency {:.1} rad/s, shortest period {} s): the highest mode grows between \
                 contact changes and the base chatters; use scheme \"average-acceleration\" or \
                 \"wilson-theta\" (--scheme), or dt <= {} s",
                setup.settings.dt,
                short_seconds(limit),
                setup.scheme_name,
                setup.settings.nx,
                setup.settings.ny,
                result.highest_frequency,
                short_seconds(2.0 * std::f64::consts::PI / result.highest_frequency),
                short_seconds(limit)
            ));
        }
    }
    if let Some(t) = result.overturned_at {
        warnings.push(format!(
            "the body overturned (|q| > B) at t = {} s; the run stops there",
            readable(t)
        ));
    }
    let uplifts = uplift_episodes(&result.steps, setup.body.width);
    Ok(FemAnalysis {
        setup,
        result,
        linear_acceleration_limit,
        warnings,
        wall_time_s,
        uplifts,
    })
}

pub(crate) fn history_csv(model: &Model, steps: &[FemStep]) -> Vec<u8> {
    let mut table = Table::new(&HISTORY_COLUMNS);
    for s in steps {
        table.row([
            number(s.t),
            number(model.floor.acceleration(s.t)),
            number(s.q),
            number(s.flexural),
            number(s.rocking),
            number(s.slipping),
            number(s.shearing),
            number(s.top_velocity),
            number(s.momentum_left_toe),
            number(s.momentum_right_toe),
            number(s.lowest_base_uy),
            s.base_states
                .iter()
                .map(|s| state_letter(*s))
                .collect::<String>(),
        ]);
    }
    table.into_bytes()
}

pub(crate) fn events_csv(result: &FemResult) -> Vec<u8> {
    let mut table = Table::new(&EVENT_COLUMNS);
    for ContactEvent {
        t,
        node,
        from,
        to,
        rx,
        ry,
    } in &result.events
    {
        // Base node i is node i of the mesh (row 0).
        let x = result
            .node_coordinates
            .get(*node)
            .map_or(f64::NAN, |c| c[0]);
        table.row([
            number(*t),
            node.to_string(),
            number(x),
            state_name(*from).to_string(),
            state_name(*to).to_string(),
            number(*rx),
            number(*ry),
        ]);
    }
    table.into_bytes()
}

/// Peak values of a run.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct FemPeaks {
    pub max_q: f64,
    pub t_max_q: f64,
    pub min_q: f64,
    pub t_min_q: f64,
    pub max_abs_flexural: f64,
    pub max_abs_rocking: f64,
    pub max_abs_slipping: f64,
    pub max_abs_shearing: f64,
    pub max_abs_top_velocity: f64,
}

pub(crate) fn peaks(steps: &[FemStep]) -> FemPeaks {
    let max_abs = |f: fn(&FemStep) -> f64| steps.iter().map(|s| f(s).abs()).fold(0.0, f64::max);
    let max = steps.iter().max_by(|a, b| a.q.total_cmp(&b.q));
    let min = steps.iter().min_by(|a, b| a.q.total_cmp(&b.q));
    FemPeaks {
        max_q: max.map_or(0.0, |s| s.q),
        t_max_q: max.map_or(0.0, |s| s.t),
        min_q: min.map_or(0.0, |s| s.q),
        t_min_q: min.map_or(0.0, |s| s.t),
        max_abs_flexural: max_abs(|s| s.flexural),
        max_abs_rocking: max_abs(|s| s.rocking),
        max_abs_slipping: max_abs(|s| s.slipping),
        max_abs_shearing: max_abs(|s| s.shearing),
        max_abs_top_velocity: max_abs(|s| s.top_velocity),
    }
}

/// fem_summary.json.
#[derive(Debug, Serialize)]
pub(crate) struct FemSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::run::Provenance,
    pub element: &'static str,
    pub body: &'a super::FemBody,
    pub settings: &'a super::FemSettings,
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
    pub warnings: &'a [String],
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

/// The element, in one line, for summaries and reports.
pub const ELEMENT: &str = "QM6 4-node incompatible-mode quadrilateral, plane stress, lumped mass";

pub(crate) fn summary<'a>(model: &'a Model, a: &'a FemAnalysis) -> FemSummary<'a> {
    let b = &a.setup.body;
    let c = &model.constants;
    let r = &a.result;
    FemSummary {
        provenance: crate::run::Provenance::of(model),
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
        warnings: &a.warnings,
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
        (s_n, "±s_n (SDOF uplift)".to_string()),
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

/// The figures of a run: (file name, chart).
pub fn figures(model: &Model, a: &FemAnalysis) -> Vec<(&'static str, Panel)> {
    let steps = &a.result.steps;
    let s_n = model.constants.uplift_displacement;
    let mut components = Panel::new(
        "Top displacement and its parts (FEM)",
        "t (s)",
        "q and parts (m)",
    )
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
    let q_r = Panel::new(
        "Top displacement against rocking part (FEM)",
        "r (m)",
        "q (m)",
    )
    .with(Series::line(
        "",
        steps.iter().map(|s| (s.rocking, s.q)).collect(),
        2,
    ));
    let s_r = Panel::new("Flexural part against rocking part (FEM)", "r (m)", "s (m)").with(
        Series::line(
            "",
            steps.iter().map(|s| (s.rocking, s.flexural)).collect(),
            2,
        ),
    );
    let velocity = Panel::new(
        "Top velocity relative to the floor (FEM)",
        "t (s)",
        "dq/dt (m/s)",
    )
    .with(Series::line("", time_series(steps, |s| s.top_velocity), 2));
    let momentum = Panel::new(
        "Angular momentum about the toes (FEM, clockwise positive)",
        "t (s)",
        "L (kg m²/s)",
    )
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
        ("fem_deformed_shapes.svg", deformed_shapes(a)),
        ("fem_components.svg", components),
        ("fem_q_vs_r.svg", q_r),
        ("fem_s_vs_r.svg", s_r),
        ("fem_top_velocity.svg", velocity),
        ("fem_angular_momentum.svg", momentum),
    ]
}

fn render(charts: Vec<(&'static str, Panel)>) -> Result<Vec<(&'static str, Vec<u8>)>> {
    charts
        .into_iter()
        .map(|(name, chart)| {
            // Drawings of shapes get more room than curves.
            let size = if chart.equal_aspect {
                (1000, 600)
            } else {
                (900, 500)
            };
            plot::figure(name, &[chart], 1, size).map(|svg| (name, svg.into_bytes()))
        })
        .collect()
}

/// The files of a run: CSVs, summary and figures.
fn run_files(model: &Model, a: &FemAnalysis) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let mut files = vec![
        ("fem_history.csv", history_csv(model, &a.result.steps)),
        ("fem_events.csv", events_csv(&a.result)),
        ("fem_summary.json", output::json_bytes(&summary(model, a))),
    ];
    files.extend(render(figures(model, a))?);
    Ok(files)
}

/// Result of `flexrock fem`.
pub struct FemReport {
    /// The run and what was derived from it.
    pub analysis: FemAnalysis,
    /// The one-mode model side by side with the run, when compared.
    pub comparison: Option<FemComparison>,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// [`analyse`], with its wall time taken into timings.json when `wall_times` says so.
fn analyse_timed(
    model: &Model,
    setup: &FemSetup,
    wall_times: output::WallTimes,
) -> Result<(FemAnalysis, output::Timings)> {
    let mut analysis = analyse(model, setup)?;
    let mut timings = output::Timings::new(wall_times);
    timings.take("fem_summary.json/wall_time_s", &mut analysis.wall_time_s);
    Ok((analysis, timings))
}

/// Runs the finite element analysis and writes its files into `out_dir` (all or none); with
/// [`output::WallTimes::Apart`] its wall time goes to timings.json.
pub fn fem(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: output::WallTimes,
) -> Result<FemReport> {
    let (analysis, timings) = analyse_timed(model, setup, wall_times)?;
    let mut files = run_files(model, &analysis)?;
    files.extend(timings.file());
    let files = output::write_atomically(out_dir, &files)?;
    Ok(FemReport {
        analysis,
        comparison: None,
        files,
    })
}

/// One row of the comparison table.
#[derive(Debug, Clone, Serialize)]
pub struct FemComparisonRow {
    /// What the row measures.
    pub quantity: String,
    /// Its value in the SDOF model.
    pub sdof: f64,
    /// Its value in the finite element run.
    pub fem: f64,
    /// The row counts something (printed without decimals).
    #[serde(skip)]
    pub is_count: bool,
}

/// The SDOF model and the FEM side by side.
#[derive(Debug, Clone, Serialize)]
pub struct FemComparison {
    /// The quantities side by side.
    pub rows: Vec<FemComparisonRow>,
    /// Uplift times of the SDOF model, s.
    pub sdof_uplift_times: Vec<f64>,
    /// Starts of the finite element run's uplift episodes, s.
    pub fem_uplift_times: Vec<f64>,
}

/// Least-squares line y = a + b x through the points; None for fewer than 2 distinct x.
fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
    let (mx, my) = (sx / n, sy / n);
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| (my - sxy / sxx * mx, sxy / sxx))
}

/// Rocking part below which a state counts as upright when fitting the rocking branch, as a
/// fraction of the width (the FEM's base opens gradually; small r is the opening, not rocking).
const ROCKING_FIT_THRESHOLD: f64 = 0.03;

/// Folds (r, y) onto r > 0 (mirror the left rocking branch) and keeps |r| above the threshold.
fn rocking_branch(points: impl Iterator<Item = (f64, f64)>, width: f64) -> Vec<(f64, f64)> {
    points
        .filter(|(r, _)| r.abs() > ROCKING_FIT_THRESHOLD * width)
        .map(|(r, y)| (r.abs(), y * r.signum()))
        .collect()
}

pub(crate) fn compare_solutions(model: &Model, sdof: &Solution, a: &FemAnalysis) -> FemComparison {
    let steps = &a.result.steps;
    let p = peaks(steps);
    let width = model.body.width;
    let sdof_uplift_times: Vec<f64> = sdof
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Uplift)
        .map(|e| e.t)
        .collect();
    let fem_uplift_times: Vec<f64> = a.uplifts.iter().map(|e| e.t_start).collect();
    let sdof_max_abs = |f: fn(&crate::solution::Sample) -> f64| {
        sdof.samples.iter().map(|s| f(s).abs()).fold(0.0, f64::max)
    };
    // q-r: intercept on the q axis (where rocking starts) and slope dq/dr of the rocking branch.
    let q_r_sdof = fit_line(&rocking_branch(
        sdof.samples.iter().map(|s| (s.r, s.q)),
        width,
    ));
    let q_r_fem = fit_line(&rocking_branch(
        steps.iter().map(|s| (s.rocking, s.q)),
        width,
    ));
    let s_r_sdof = fit_line(&rocking_branch(
        sdof.samples.iter().map(|s| (s.r, s.s)),
        width,
    ));
    let s_r_fem = fit_line(&rocking_branch(
        steps.iter().map(|s| (s.rocking, s.flexural)),
        width,
    ));
    let nan = (f64::NAN, f64::NAN);
    let row = |quantity: &str, sdof: f64, fem: f64| FemComparisonRow {
        quantity: quantity.to_string(),
        sdof,
        fem,
        is_count: false,
    };
    let rows = vec![
        row("max q (m)", sdof.max_q.value, p.max_q),
        row("t of max q (s)", sdof.max_q.t, p.t_max_q),
        row("min q (m)", sdof.min_q.value, p.min_q),
        row("t of min q (s)", sdof.min_q.t, p.t_min_q),
        FemComparisonRow {
            is_count: true,
            ..row(
                "uplifts",
                sdof_uplift_times.len() as f64,
                fem_uplift_times.len() as f64,
            )
        },
        row(
            "first uplift t (s)",
            sdof_uplift_times.first().copied().unwrap_or(f64::NAN),
            fem_uplift_times.first().copied().unwrap_or(f64::NAN),
        ),
        row(
            "max |s| flexural (m)",
            sdof_max_abs(|s| s.s),
            p.max_abs_flexural,
        ),
        row(
            "max |r| rocking (m)",
            sdof_max_abs(|s| s.r),
            p.max_abs_rocking,
        ),
        row("max |slipping| (m)", 0.0, p.max_abs_slipping),
        row("max |shearing| (m)", 0.0, p.max_abs_shearing),
        row(
            "max |top velocity| (m/s)",
            sdof_max_abs(|s| s.qdot),
            p.max_abs_top_velocity,
        ),
        row(
            "q-r rocking branch: q at r = 0 (m)",
            q_r_sdof.unwrap_or(nan).0,
            q_r_fem.unwrap_or(nan).0,
        ),
        row(
            "q-r rocking branch: dq/dr",
            q_r_sdof.unwrap_or(nan).1,
            q_r_fem.unwrap_or(nan).1,
        ),
        row(
            "s-r rocking branch: s at r = 0 (m)",
            s_r_sdof.unwrap_or(nan).0,
            s_r_fem.unwrap_or(nan).0,
        ),
        row(
            "s-r rocking branch: ds/dr",
            s_r_sdof.unwrap_or(nan).1,
            s_r_fem.unwrap_or(nan).1,
        ),
    ];
    FemComparison {
        rows,
        sdof_uplift_times,
        fem_uplift_times,
    }
}

pub(crate) fn comparison_csv(c: &FemComparison) -> Vec<u8> {
    let mut table = Table::new(&["quantity", "sdof", "fem"]);
    for r in &c.rows {
        table.row([r.quantity.clone(), number(r.sdof), number(r.fem)]);
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
    let sdof_series = |f: fn(&crate::solution::Sample) -> (f64, f64)| {
        Series::line("SDOF", sdof.samples.iter().map(f).collect(), 1)
    };
    let mut q = Panel::new("Top displacement: SDOF and FEM", "t (s)", "q (m)")
        .with(sdof_series(|s| (s.t, s.q)))
        .with(Series::line("FEM", time_series(steps, |s| s.q), 2));
    q.reference_lines = sn_lines(model.constants.uplift_displacement);
    let mut s = Panel::new("Flexural part: SDOF and FEM", "t (s)", "s (m)")
        .with(sdof_series(|s| (s.t, s.s)))
        .with(Series::line("FEM", time_series(steps, |s| s.flexural), 2));
    s.reference_lines = sn_lines(model.constants.uplift_displacement);
    let velocity = Panel::new("Top velocity: SDOF and FEM", "t (s)", "dq/dt (m/s)")
        .with(sdof_series(|s| (s.t, s.qdot)))
        .with(Series::line(
            "FEM",
            time_series(steps, |s| s.top_velocity),
            2,
        ));
    let q_r = Panel::new(
        "Top displacement against rocking part: SDOF and FEM",
        "r (m)",
        "q (m)",
    )
    .with(sdof_series(|s| (s.r, s.q)))
    .with(Series::line(
        "FEM",
        steps.iter().map(|s| (s.rocking, s.q)).collect(),
        2,
    ));
    let s_r = Panel::new(
        "Flexural part against rocking part: SDOF and FEM",
        "r (m)",
        "s (m)",
    )
    .with(sdof_series(|s| (s.r, s.s)))
    .with(Series::line(
        "FEM",
        steps.iter().map(|s| (s.rocking, s.flexural)).collect(),
        2,
    ));
    vec![
        ("compare_q.svg", q),
        ("compare_flexural.svg", s),
        ("compare_top_velocity.svg", velocity),
        ("compare_q_vs_r.svg", q_r),
        ("compare_s_vs_r.svg", s_r),
    ]
}

/// `flexrock fem --compare`: the FEM run, the SDOF solution of the same model
/// ([`crate::run::simulate`]) and both side by side, all written into `out_dir` (all or none);
/// with [`output::WallTimes::Apart`] the FEM's wall time goes to timings.json.
pub fn compare(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: output::WallTimes,
) -> Result<FemReport> {
    let (analysis, timings) = analyse_timed(model, setup, wall_times)?;
    let sdof = crate::run::simulate(model)?;
    let comparison = compare_solutions(model, &sdof, &analysis);
    let mut files = run_files(model, &analysis)?;
    files.push(("compare.csv", comparison_csv(&comparison)));
    files.push(("compare.json", output::json_bytes(&comparison)));
    files.push(("sdof_history.csv", output::history_csv(&sdof.samples)));
    files.extend(render(comparison_figures(model, &sdof, &analysis))?);
    files.extend(timings.file());
    let files = output::write_atomically(out_dir, &files)?;
    Ok(FemReport {
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
        short_seconds(a.linear_acceleration_limit)
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
        output::milliseconds(a.wall_time_s, 1).map_or_else(String::new, |t| format!(" in {t}"))
    );
    if let Some(c) = &report.comparison {
        t.push_str(&comparison_text(c));
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}

/// Fixed-base natural periods of the mesh against the SDOF period.
#[derive(Debug, Clone, Serialize)]
pub struct Modes {
    /// Elements across the width.
    pub nx: usize,
    /// Elements up the height.
    pub ny: usize,
    /// The lowest periods without the self-weight's P-Delta, s.
    pub periods_elastic: Vec<f64>,
    /// The lowest periods with it, s.
    pub periods_p_delta: Vec<f64>,
    #[serde(rename = "sdof_T")]
    /// Pre-uplift period T of the SDOF model, s.
    pub sdof_period: f64,
    /// Highest circular frequency ω_max of the mesh, rad/s.
    pub highest_frequency: f64,
    /// Stability limit of the linear acceleration method on this mesh, s.
    pub linear_acceleration_stability_limit: f64,
}

/// Number of modes `--modes` reports.
const MODE_COUNT: usize = 3;

/// The lowest fixed-base periods of the mesh, with and without P-Delta (`flexrock fem --modes`).
pub fn modes(model: &Model, setup: &FemSetup) -> Result<Modes> {
    let (b, s) = (&setup.body, &setup.settings);
    let omega = super::highest_frequency(b, s.nx, s.ny)?;
    Ok(Modes {
        nx: s.nx,
        ny: s.ny,
        periods_elastic: fixed_base_periods(b, s.nx, s.ny, false, MODE_COUNT)?,
        periods_p_delta: fixed_base_periods(b, s.nx, s.ny, true, MODE_COUNT)?,
        sdof_period: model.constants.period,
        highest_frequency: omega,
        linear_acceleration_stability_limit: critical_time_step(
            TimeScheme::linear_acceleration(),
            omega,
        )
        .unwrap_or(f64::INFINITY),
    })
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
        short_seconds(m.linear_acceleration_stability_limit)
    );
    t
}

/// A short time in seconds to three significant figures, without exponent down to 1 ms.
fn short_seconds(t: f64) -> String {
    if t >= 1e-3 {
        format!("{t:.5}")
    } else {
        format!("{t:.2e}")
    }
}
