//! The figures of a run (`flexrock plot DIR`, `flexrock run --plot`), drawn from the files of
//! its output directory as [`RunData`] reads them:
//!
//! - `plot_motion.svg`: floor acceleration a(t); q(t) with +-s_n and +-B; s(t) and r(t);
//!   q'(t) with the uplifts, landings and overturning marked (the paper's Fig. 6);
//! - `plot_force.svg`: the model's restoring force F(q) over [-B, B] with the run's path on it
//!   (Fig. 3); q against r (Fig. 12); s against r (Fig. 13);
//! - `plot_energy.svg`: the energy books against t (kinetic, potential, their sum, input work,
//!   damping work, energy lost at events); the energy residual over the run's energy scale.
//!
//! The model's curves (F(q), V(q), Me q'^2/2, the energy jumps at events) come from the
//! [`Automaton`] rebuilt from the constants in summary.json: no formula of the model is written
//! here. Long histories are thinned for drawing by [`plot::decimate`], which keeps the peaks.

use std::path::{Path, PathBuf};

use crate::automaton::{Automaton, EventKind};
use crate::error::Result;
use crate::output;
use crate::plot::{self, Legend, Marker, Panel, Series};
use crate::run_dir::{HistoryRow, RunData};

/// The figure files, in the order they are written.
pub const FIGURES: [&str; 3] = ["plot_motion.svg", "plot_force.svg", "plot_energy.svg"];

/// Reads the run directory `dir` and writes its figures into it, as one atomic set. Nothing is
/// written when a file of the run is missing or malformed.
pub fn plot_dir(dir: &Path) -> Result<Vec<PathBuf>> {
    let data = RunData::read(dir)?;
    let figures = figures(&data)?;
    output::write_atomically(dir, &figures)
}

/// The SVG files of a run, named as in [`FIGURES`]. Each figure is drawn and its series dropped
/// before the next, so that a history of a million rows is held once, not once per figure.
pub fn figures(data: &RunData) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let automaton = Automaton::new(&data.summary.constants);
    let motion = plot::figure(FIGURES[0], &motion_panels(data), 1, (1150, 330))?;
    let force = plot::figure(FIGURES[1], &force_panels(data, &automaton), 3, (640, 560))?;
    let energy = plot::figure(FIGURES[2], &energy_panels(data, &automaton), 1, (1150, 380))?;
    Ok(vec![
        (FIGURES[0], motion.into_bytes()),
        (FIGURES[1], force.into_bytes()),
        (FIGURES[2], energy.into_bytes()),
    ])
}

fn series(rows: &[HistoryRow], xy: impl Fn(&HistoryRow) -> (f64, f64)) -> Vec<(f64, f64)> {
    rows.iter().map(xy).collect()
}

/// A time series drawn one pixel wide (a record's floor motion is dense).
fn curve(name: &str, points: Vec<(f64, f64)>, color: usize) -> Series {
    Series::line(name, points, color).with_width(1)
}

/// +-level with one legend entry.
fn pair(level: f64, label: String) -> Vec<(f64, String)> {
    vec![(level, label), (-level, String::new())]
}

/// Panels of plot_motion.svg.
pub fn motion_panels(data: &RunData) -> Vec<Panel> {
    let h = &data.history;
    let c = &data.summary.constants;
    let (s_n, b) = (c.uplift_displacement, c.width);
    let s_n_label = format!("±s_n = {} m", output::significant(s_n, 4));
    let b_label = format!("±B = {} m", output::significant(b, 4));

    let mut floor = Panel::new("floor acceleration a(t)", "t (s)", "a (m/s²)").with(curve(
        "a(t)",
        series(h, |r| (r.t, r.floor_acc)),
        0,
    ));
    floor.legend = Legend::Outside;

    let mut q = Panel::new("top displacement q(t)", "t (s)", "q (m)").with(curve(
        "q(t)",
        series(h, |r| (r.t, r.q)),
        0,
    ));
    q.reference_lines = pair(s_n, format!("{s_n_label} (uplift)"));
    q.dashed_lines = pair(b, format!("{b_label} (overturning)"));
    q.legend = Legend::Outside;

    let mut parts = Panel::new(
        "flexural part s(t) and rocking part r(t)",
        "t (s)",
        "s, r (m)",
    )
    .with(curve("s(t), flexural", series(h, |r| (r.t, r.s)), 2))
    .with(curve("r(t), rocking", series(h, |r| (r.t, r.r)), 1));
    parts.reference_lines = pair(s_n, s_n_label);
    parts.legend = Legend::Outside;

    let mut velocity = Panel::new("top velocity q'(t) (Fig. 6)", "t (s)", "q' (m/s)").with(curve(
        "q'(t)",
        series(h, |r| (r.t, r.qdot)),
        0,
    ));
    for (kind, color, marker) in [
        (EventKind::Uplift, 1, Marker::TriangleUp),
        (EventKind::Landing, 2, Marker::TriangleDown),
        (EventKind::Overturn, 4, Marker::Cross),
    ] {
        let points: Vec<(f64, f64)> = data
            .events
            .iter()
            .filter(|e| e.kind == kind)
            .map(|e| (e.t, e.qdot_before))
            .collect();
        if !points.is_empty() {
            let name = format!("{} ({})", kind.name(), points.len());
            velocity = velocity.with(Series::markers(&name, points, color, marker));
        }
    }
    velocity.legend = Legend::Outside;
    vec![floor, q, parts, velocity]
}

/// Points of the model's F(q) over [-B, B], with the kinks at +-s_n exactly.
pub fn restoring_force_curve(automaton: &Automaton) -> Vec<(f64, f64)> {
    let (s_n, b) = (automaton.uplift_displacement(), automaton.width());
    let mut qs: Vec<f64> = (0..=800)
        .map(|i| -b + 2.0 * b * f64::from(i) / 800.0)
        .chain([-s_n, s_n])
        .collect();
    qs.sort_by(f64::total_cmp);
    qs.into_iter()
        .map(|q| (q, automaton.restoring_force(automaton.initial_mode(q), q)))
        .collect()
}

/// Panels of plot_force.svg.
pub fn force_panels(data: &RunData, automaton: &Automaton) -> Vec<Panel> {
    let h = &data.history;
    // The run's path first and wide, the model's curve over it and thin: where the run went,
    // the black line runs inside a red band.
    let mut force = Panel::new("restoring force F(q) (Fig. 3)", "q (m)", "F (N)")
        .with(Series::line("this run", series(h, |r| (r.q, r.restoring_force)), 1).with_width(6))
        .with(Series::line("model F(q)", restoring_force_curve(automaton), 0).with_width(1));
    // F has the sign of q: the upper left quarter is empty.
    force.legend = Legend::UpperLeft;
    let q_r = Panel::new("q against r (Fig. 12)", "r (m)", "q (m)").with(Series::line(
        "",
        series(h, |r| (r.r, r.q)),
        0,
    ));
    let s_r = Panel::new("s against r (Fig. 13)", "r (m)", "s (m)").with(Series::line(
        "",
        series(h, |r| (r.r, r.s)),
        0,
    ));
    vec![force, q_r, s_r]
}

/// The energy lost at events up to each event, J: minus the sum of the jumps of
/// Me q'^2/2 + V(q) at them, as a step curve from the first to the last time of the history.
pub fn energy_lost_at_events(data: &RunData, automaton: &Automaton) -> Vec<(f64, f64)> {
    let (t0, t1) = match (data.history.first(), data.history.last()) {
        (Some(a), Some(b)) => (a.t, b.t),
        _ => return Vec::new(),
    };
    let mut lost = 0.0;
    let mut points = vec![(t0, 0.0)];
    for e in &data.events {
        points.push((e.t, lost));
        lost -= automaton.event_energy_jump(e.from, e.to, e.q, e.qdot_before, e.qdot_after);
        points.push((e.t, lost));
    }
    points.push((t1, lost));
    points
}

/// Panels of plot_energy.svg.
pub fn energy_panels(data: &RunData, automaton: &Automaton) -> Vec<Panel> {
    let h = &data.history;
    let kinetic = |r: &HistoryRow| automaton.kinetic_energy(r.qdot);
    let potential = |r: &HistoryRow| automaton.potential_energy(r.mode, r.q);
    let mut books = Panel::new("energy books", "t (s)", "energy (J)")
        .with(curve(
            "kinetic Me q'²/2",
            series(h, |r| (r.t, kinetic(r))),
            2,
        ))
        .with(curve(
            "potential V(q)",
            series(h, |r| (r.t, potential(r))),
            3,
        ))
        .with(curve(
            "E = kinetic + V",
            series(h, |r| (r.t, kinetic(r) + potential(r))),
            0,
        ))
        .with(curve("input work", series(h, |r| (r.t, r.work_input)), 1))
        .with(curve(
            "damping work",
            series(h, |r| (r.t, r.work_damping)),
            4,
        ))
        .with(curve(
            "lost at events",
            energy_lost_at_events(data, automaton),
            5,
        ));
    books.legend = Legend::Outside;

    let summary = &data.summary;
    // A run without motion has no energy: measure against 1 J then.
    let scale = if summary.energy_scale > 0.0 {
        summary.energy_scale
    } else {
        1.0
    };
    let mut residual = Panel::new(
        &format!(
            "energy residual / energy scale ({} J, summary.json)",
            output::significant(scale, 4)
        ),
        "t (s)",
        "residual / scale",
    )
    .with(curve(
        "residual / scale",
        series(h, |r| (r.t, r.energy_residual / scale)),
        0,
    ));
    residual.reference_lines = pair(
        summary.max_energy_residual / scale,
        "±max |residual|".to_string(),
    );
    residual.legend = Legend::Outside;
    vec![books, residual]
}
