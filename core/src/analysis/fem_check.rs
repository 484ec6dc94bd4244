//! The finite element check of the paper's Section 3, as an analysis: a finite element run of a
//! model ([`analyse`]), what is read off it (uplift episodes, peaks, the rows of its history and
//! contact events), its comparison with the one-degree-of-freedom model ([`compare`]: peaks,
//! uplift times and least-squares lines through the rocking branches), and the mesh's fixed-base
//! modes ([`modes`]). The numerics themselves are in [`crate::bodies::fem`].

use std::time::Instant;

use serde::Serialize;

use crate::base::format::number;
use crate::bodies::fem::{
    critical_time_step, fixed_base_periods, highest_frequency, simulate_fem, ContactEvent,
    ContactState, FemResult, FemStep, TimeScheme,
};
use crate::error::{Error, Result};
use crate::integrate::solution::{Sample, Solution};
use crate::model::{FemSetup, Model};
use crate::physics::automaton::EventKind;
use crate::tables::fields::Column;

/// The element, in one line, for summaries and reports.
pub const ELEMENT: &str = "QM6 4-node incompatible-mode quadrilateral, plane stress, lumped mass";

/// Something about a run the user must see.
#[derive(Debug, Clone, PartialEq)]
pub enum FemWarning {
    /// The time step exceeds the stability limit of the scheme on this mesh: the highest mode
    /// grows between contact changes and the base chatters.
    DtBeyondStabilityLimit {
        /// The time step, s.
        dt: f64,
        /// The scheme's stability limit on this mesh, s.
        limit: f64,
        /// The scheme's name as written in the model file.
        scheme: &'static str,
        /// Elements across the width.
        nx: usize,
        /// Elements up the height.
        ny: usize,
        /// Highest circular frequency of the mesh, rad/s.
        highest_frequency: f64,
    },
    /// The body overturned (|q| > B) at `t`, s; the run stops there.
    Overturned {
        /// When, s.
        t: f64,
    },
}

impl FemWarning {
    /// The warning as the user reads it; `scheme_named` is how the scheme's setting was given
    /// (`--scheme` on the command line, an argument's name in Python).
    pub fn text(&self, scheme_named: &str) -> String {
        match *self {
            FemWarning::DtBeyondStabilityLimit {
                dt,
                limit,
                scheme,
                nx,
                ny,
                highest_frequency,
            } => format!(
                "fem.dt = {} s exceeds the stability limit {} s of the {} method on this {} x {} \
                 mesh (highest frequency {:.1} rad/s, shortest period {} s): the highest mode grows \
                 between contact changes and the base chatters; use scheme \
                 \"average-acceleration\" or \"wilson-theta\" ({scheme_named}), or dt <= {} s",
                dt,
                crate::base::format::short_seconds(limit),
                scheme,
                nx,
                ny,
                highest_frequency,
                crate::base::format::short_seconds(2.0 * std::f64::consts::PI / highest_frequency),
                crate::base::format::short_seconds(limit)
            ),
            FemWarning::Overturned { t } => format!(
                "the body overturned (|q| > B) at t = {} s; the run stops there",
                crate::base::format::readable(t)
            ),
        }
    }
}

/// A finished finite element run and what was derived from it.
pub struct FemAnalysis {
    /// The validated finite element analysis.
    pub setup: FemSetup,
    /// The time history, contact events and snapshots.
    pub result: FemResult,
    /// Stability limit of the linear acceleration method on this mesh, s.
    pub linear_acceleration_limit: f64,
    /// What the user must see about the run.
    pub warnings: Vec<FemWarning>,
    /// Wall-clock time of the run, s.
    pub wall_time_s: f64,
    /// The stretches of steps with one base corner off the floor.
    pub uplifts: Vec<UpliftEpisode>,
}

/// Runs the finite element analysis of a model: the floor acceleration comes from the model's
/// excitation, so every excitation kind works. The FEM starts at rest in the gravity state;
/// `simulation.q0` is applied as a rigid tilt about the toe (q = q0, all of it rocking), and
/// `simulation.qdot0` must be 0.
pub fn analyse(model: &Model, setup: &FemSetup) -> Result<FemAnalysis> {
    crate::simulate::refuse_vertical(
        model,
        "the finite element analysis and the SDOF runs beside it",
    )?;
    if model.initial.qdot != 0.0 {
        return Err(Error::invalid(
            "simulation.qdot0",
            model.initial.qdot,
            "the finite element analysis starts at rest: qdot0 must be 0",
        ));
    }
    let mut setup = setup.clone();
    setup.settings.initial_rotation = model.initial.q / setup.body.height;
    let floor = |t: f64| model.floor.acceleration(t);
    let started = Instant::now();
    let result = simulate_fem(&setup.body, &setup.settings, &floor)?;
    let wall_time_s = started.elapsed().as_secs_f64();
    let linear_acceleration_limit =
        crate::integrate::newmark::linear_acceleration_omega_dt() / result.highest_frequency;
    let mut warnings = Vec::new();
    if let Some(limit) = result.critical_time_step {
        if setup.settings.dt > limit {
            warnings.push(FemWarning::DtBeyondStabilityLimit {
                dt: setup.settings.dt,
                limit,
                scheme: setup.scheme_name,
                nx: setup.settings.nx,
                ny: setup.settings.ny,
                highest_frequency: result.highest_frequency,
            });
        }
    }
    if let Some(t) = result.overturned_at {
        warnings.push(FemWarning::Overturned { t });
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

/// A stretch of steps during which exactly one base corner is off the floor (see
/// [`uplift_episodes`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
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

/// Peak values of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FemPeaks {
    /// Largest q, m.
    pub max_q: f64,
    /// When, s.
    pub t_max_q: f64,
    /// Smallest q, m.
    pub min_q: f64,
    /// When, s.
    pub t_min_q: f64,
    /// Largest |flexural part|, m.
    pub max_abs_flexural: f64,
    /// Largest |rocking part|, m.
    pub max_abs_rocking: f64,
    /// Largest |slipping part|, m.
    pub max_abs_slipping: f64,
    /// Largest |shearing part|, m.
    pub max_abs_shearing: f64,
    /// Largest |top velocity|, m/s.
    pub max_abs_top_velocity: f64,
}

/// The peaks of a run's steps (zeros for no steps).
pub fn peaks(steps: &[FemStep]) -> FemPeaks {
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

/// A base node's state as fem_events.csv names it.
pub fn state_name(s: ContactState) -> &'static str {
    match s {
        ContactState::Free => "free",
        ContactState::Slip => "slip",
        ContactState::Fixed => "fixed",
    }
}

/// A base node's state in one letter, as the base_states column of fem_history.csv writes it.
pub fn state_letter(s: ContactState) -> char {
    match s {
        ContactState::Free => 'F',
        ContactState::Slip => 'S',
        ContactState::Fixed => 'X',
    }
}

/// One row of fem_history.csv: a step of the run, with the floor's acceleration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HistoryRow {
    /// Time, s.
    pub t: f64,
    /// Floor acceleration, m/s^2.
    pub floor_acc: f64,
    /// Top displacement relative to the floor, m.
    pub q: f64,
    /// Flexural part, m.
    pub flexural: f64,
    /// Rocking part, m.
    pub rocking: f64,
    /// Slipping part, m.
    pub slipping: f64,
    /// Shearing part, m.
    pub shearing: f64,
    /// Top velocity relative to the floor, m/s.
    pub top_velocity: f64,
    /// Angular momentum about the left toe, kg m²/s.
    pub momentum_left_toe: f64,
    /// Angular momentum about the right toe, kg m²/s.
    pub momentum_right_toe: f64,
    /// Lowest vertical displacement of a base node, m.
    pub lowest_base_uy: f64,
    /// The base nodes' states, left to right, one letter each ([`state_letter`]).
    pub base_states: String,
}

/// The columns of fem_history.csv (a contract), one per field of [`HistoryRow`].
pub const HISTORY_COLUMNS: [Column<HistoryRow>; 12] = [
    Column::new("t", |r| number(r.t)),
    Column::new("floor_acc", |r| number(r.floor_acc)),
    Column::new("q", |r| number(r.q)),
    Column::new("flexural", |r| number(r.flexural)),
    Column::new("rocking", |r| number(r.rocking)),
    Column::new("slipping", |r| number(r.slipping)),
    Column::new("shearing", |r| number(r.shearing)),
    Column::new("top_velocity", |r| number(r.top_velocity)),
    Column::new("momentum_left_toe", |r| number(r.momentum_left_toe)),
    Column::new("momentum_right_toe", |r| number(r.momentum_right_toe)),
    Column::new("lowest_base_uy", |r| number(r.lowest_base_uy)),
    Column::new("base_states", |r| r.base_states.clone()),
];

/// The rows of fem_history.csv: every step, with the model's floor acceleration at its time.
pub fn history_rows(model: &Model, steps: &[FemStep]) -> Vec<HistoryRow> {
    steps
        .iter()
        .map(|s| HistoryRow {
            t: s.t,
            floor_acc: model.floor.acceleration(s.t),
            q: s.q,
            flexural: s.flexural,
            rocking: s.rocking,
            slipping: s.slipping,
            shearing: s.shearing,
            top_velocity: s.top_velocity,
            momentum_left_toe: s.momentum_left_toe,
            momentum_right_toe: s.momentum_right_toe,
            lowest_base_uy: s.lowest_base_uy,
            base_states: s.base_states.iter().map(|s| state_letter(*s)).collect(),
        })
        .collect()
}

/// One row of fem_events.csv: a base node's change of state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventRow {
    /// Time of the step that triggered the change, s.
    pub t: f64,
    /// Base node index, 0 = left corner .. nx = right corner.
    pub node: usize,
    /// The node's x, m (NaN for a node the mesh lacks).
    pub x: f64,
    /// The state before ([`state_name`]).
    pub from: &'static str,
    /// The state after.
    pub to: &'static str,
    /// Horizontal reaction, N.
    pub rx: f64,
    /// Vertical reaction, N.
    pub ry: f64,
}

/// The columns of fem_events.csv (a contract), one per field of [`EventRow`].
pub const EVENT_COLUMNS: [Column<EventRow>; 7] = [
    Column::new("t", |r| number(r.t)),
    Column::new("node", |r| r.node.to_string()),
    Column::new("x", |r| number(r.x)),
    Column::new("from", |r| r.from.to_string()),
    Column::new("to", |r| r.to.to_string()),
    Column::new("rx", |r| number(r.rx)),
    Column::new("ry", |r| number(r.ry)),
];

/// The rows of fem_events.csv: every contact event of the run.
pub fn event_rows(result: &FemResult) -> Vec<EventRow> {
    result
        .events
        .iter()
        .map(
            |ContactEvent {
                 t,
                 node,
                 from,
                 to,
                 rx,
                 ry,
             }| EventRow {
                t: *t,
                node: *node,
                // Base node i is node i of the mesh (row 0).
                x: result
                    .node_coordinates
                    .get(*node)
                    .map_or(f64::NAN, |c| c[0]),
                from: state_name(*from),
                to: state_name(*to),
                rx: *rx,
                ry: *ry,
            },
        )
        .collect()
}

/// One row of the comparison table (compare.csv of `flexrock fem --compare`).
#[derive(Debug, Clone, PartialEq, Serialize)]
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

/// The columns of the comparison table (a contract), one per field of [`FemComparisonRow`]
/// that is written.
pub const COMPARISON_COLUMNS: [Column<FemComparisonRow>; 3] = [
    Column::new("quantity", |r| r.quantity.clone()),
    Column::new("sdof", |r| number(r.sdof)),
    Column::new("fem", |r| number(r.fem)),
];

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

/// Least-squares line y = a + b x through the points, as (a, b); None for fewer than 2
/// distinct x.
pub fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
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
pub const ROCKING_FIT_THRESHOLD: f64 = 0.03;

/// Folds (r, y) onto r > 0 (mirror the left rocking branch) and keeps |r| above
/// [`ROCKING_FIT_THRESHOLD`] x `width`.
fn rocking_branch(points: impl Iterator<Item = (f64, f64)>, width: f64) -> Vec<(f64, f64)> {
    points
        .filter(|(r, _)| r.abs() > ROCKING_FIT_THRESHOLD * width)
        .map(|(r, y)| (r.abs(), y * r.signum()))
        .collect()
}

/// The SDOF solution `sdof` of `model` and the finite element run side by side: peaks, uplifts,
/// and the lines through the q-r and s-r rocking branches (intercept and slope).
pub fn compare(model: &Model, sdof: &Solution, a: &FemAnalysis) -> FemComparison {
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
    let sdof_max_abs =
        |f: fn(&Sample) -> f64| sdof.samples.iter().map(|s| f(s).abs()).fold(0.0, f64::max);
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

/// Number of modes [`modes`] reports.
pub const MODE_COUNT: usize = 3;

/// The lowest fixed-base periods of the mesh, with and without P-Delta.
pub fn modes(model: &Model, setup: &FemSetup) -> Result<Modes> {
    let (b, s) = (&setup.body, &setup.settings);
    let omega = highest_frequency(b, s.nx, s.ny)?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::fields::{fields, names, serialized_keys};
    use ContactState::{Fixed, Free, Slip};

    /// A step at `t` with rocking part `rocking` and the given base states (q = rocking).
    fn step(t: f64, rocking: f64, base_states: &[ContactState]) -> FemStep {
        FemStep {
            t,
            q: rocking,
            rocking,
            slipping: 0.0,
            flexural: 0.0,
            shearing: 0.0,
            top_velocity: -rocking,
            momentum_left_toe: 0.0,
            momentum_right_toe: 0.0,
            lowest_base_uy: 0.0,
            base_states: base_states.to_vec(),
        }
    }

    #[test]
    fn a_line_through_exact_points_is_found_exactly() {
        // y = 0.5 - 2 x
        let points: Vec<(f64, f64)> = [0.0, 0.25, 1.0, 3.0]
            .iter()
            .map(|&x| (x, 0.5 - 2.0 * x))
            .collect();
        let (a, b) = fit_line(&points).unwrap();
        assert!(
            (a - 0.5).abs() < 1e-15 && (b + 2.0).abs() < 1e-15,
            "{a} {b}"
        );
        // Symmetric scatter about y = 1 + x: the least-squares line is that line.
        let (a, b) = fit_line(&[(0.0, 1.1), (0.0, 0.9), (2.0, 3.1), (2.0, 2.9)]).unwrap();
        assert!(
            (a - 1.0).abs() < 1e-12 && (b - 1.0).abs() < 1e-12,
            "{a} {b}"
        );
        assert_eq!(fit_line(&[(1.0, 2.0)]), None);
        assert_eq!(fit_line(&[(1.0, 2.0), (1.0, 3.0)]), None);
    }

    /// The left branch is mirrored onto r > 0, and small |r| is left out of the fit.
    #[test]
    fn the_rocking_branch_folds_the_left_side_onto_the_right() {
        let width = 1.0;
        let points = [(-0.5, -2.0), (0.01, 7.0), (0.25, 1.0), (-0.02, 5.0)];
        assert_eq!(
            rocking_branch(points.into_iter(), width),
            [(0.5, 2.0), (0.25, 1.0)]
        );
    }

    /// Two episodes on the right separated by one upright step merge; a short rock to the left
    /// too small to count is dropped; an episode still open at the end ends with the run.
    #[test]
    fn uplift_episodes_merge_chatter_and_drop_the_heel_opening() {
        let width = 1.0;
        let right = [Free, Fixed, Fixed];
        let left = [Fixed, Slip, Free];
        let both = [Fixed, Fixed, Fixed];
        let steps = [
            step(0.0, 0.0, &both),
            step(0.1, 0.02, &right),
            step(0.2, 0.05, &right),
            step(0.3, 0.0, &both),
            step(0.4, 0.03, &right),
            step(0.5, 0.0, &both),
            step(0.6, 0.0, &both),
            step(0.7, 0.0, &both),
            step(0.8, -0.005, &left),
            step(0.9, 0.0, &both),
            step(1.0, 0.0, &both),
            step(1.1, 0.0, &both),
            step(1.2, -0.2, &left),
        ];
        let episodes = uplift_episodes(&steps, width);
        assert_eq!(
            episodes,
            [
                UpliftEpisode {
                    t_start: 0.1,
                    t_end: 0.5,
                    side: "rock-right",
                    max_rocking: 0.05,
                },
                UpliftEpisode {
                    t_start: 1.2,
                    t_end: 1.2,
                    side: "rock-left",
                    max_rocking: 0.2,
                },
            ]
        );
    }

    #[test]
    fn peaks_are_the_extremes_and_when() {
        let both = [Fixed, Fixed];
        let steps = [
            step(0.0, 0.0, &both),
            step(0.5, 0.3, &both),
            step(1.0, -0.7, &both),
        ];
        let p = peaks(&steps);
        assert_eq!(
            (p.max_q, p.t_max_q, p.min_q, p.t_min_q),
            (0.3, 0.5, -0.7, 1.0)
        );
        assert_eq!((p.max_abs_rocking, p.max_abs_top_velocity), (0.7, 0.7));
        assert_eq!(peaks(&[]).max_q, 0.0);
    }

    /// The columns of the three tables are the fields of their rows, in order.
    #[test]
    fn the_columns_are_the_fields_of_the_rows() {
        let s = step(0.5, 0.25, &[Free, Slip, Fixed]);
        let history = HistoryRow {
            t: s.t,
            floor_acc: 1.5,
            q: s.q,
            flexural: s.flexural,
            rocking: s.rocking,
            slipping: s.slipping,
            shearing: s.shearing,
            top_velocity: s.top_velocity,
            momentum_left_toe: s.momentum_left_toe,
            momentum_right_toe: s.momentum_right_toe,
            lowest_base_uy: s.lowest_base_uy,
            base_states: "FSX".to_string(),
        };
        assert_eq!(serialized_keys(&history), names(&HISTORY_COLUMNS));
        assert_eq!(
            fields(&HISTORY_COLUMNS, &history),
            ["0.5", "1.5", "0.25", "0", "0.25", "0", "0", "-0.25", "0", "0", "0", "FSX"]
        );
        let event = EventRow {
            t: 0.5,
            node: 2,
            x: 0.35,
            from: state_name(Fixed),
            to: state_name(Free),
            rx: 0.0,
            ry: -10.0,
        };
        assert_eq!(serialized_keys(&event), names(&EVENT_COLUMNS));
        assert_eq!(
            fields(&EVENT_COLUMNS, &event),
            ["0.5", "2", "0.35", "fixed", "free", "0", "-10"]
        );
        let row = FemComparisonRow {
            quantity: "uplifts".to_string(),
            sdof: 3.0,
            fem: 4.0,
            is_count: true,
        };
        assert_eq!(serialized_keys(&row), names(&COMPARISON_COLUMNS));
    }
}
