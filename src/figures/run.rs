//! The figures of a run (`flexrock plot DIR`, `flexrock run --plot`), drawn from the files of
//! its output directory as [`RunData`] reads them:
//!
//! - `plot_motion.svg`: floor acceleration a(t); q(t) with +-s_n and +-B; s(t) and r(t);
//!   q'(t) with the uplifts, landings and overturning marked (the paper's Fig. 6);
//! - `plot_force.svg`: the model's restoring force F(q) over [-B, B] with the run's path on it
//!   (Fig. 3); q against r (Fig. 12); s against r (Fig. 13);
//! - `plot_energy.svg`: the energy books against t (kinetic, potential, their sum, input work,
//!   damping work, net energy lost at events); the energy residual over the run's energy scale.
//!
//! The model's curves (F(q), V(q), Me q'^2/2, the energy jumps at events) come from the
//! [`Automaton`] rebuilt from the constants in summary.json: no formula of the model is written
//! here. Long histories are thinned for drawing by [`plot::decimate`], which keeps the peaks.

use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::error::Result;
use crate::figures::page::{Sizes, PAGE_MM};
use crate::figures::plot::{self, Dash, Figure, Format, Marker, Panel, RugMark, Series};
use crate::writers;
use crate::writers::run_dir::{HistoryRow, RunData};
use flexrock_core::physics::automaton::{Automaton, EventKind};

/// The figure files, in the order they are written.
pub const FIGURES: [&str; 3] = ["plot_motion.svg", "plot_force.svg", "plot_energy.svg"];

/// What `flexrock plot` draws: formats, size and time window.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotOptions {
    /// The formats, each a file per figure (plot_motion.svg, plot_motion.pdf, ...).
    pub formats: Vec<Format>,
    /// The size on paper and a PNG's resolution.
    pub sizes: Sizes,
    /// Draw only t in [from, to], s [default: the whole run].
    pub from: Option<f64>,
    /// See `from`.
    pub to: Option<f64>,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            formats: vec![Format::Svg],
            sizes: Sizes::default(),
            from: None,
            to: None,
        }
    }
}

impl PlotOptions {
    /// Checks the options: sizes as [`Sizes::check`] says, times finite, not negative, and from
    /// before to. The error names the flag, its value and the rule.
    pub fn check(&self) -> Result<()> {
        let bad = |flag: &str, value: String, rule: String| {
            Error::from(flexrock_core::Error::InvalidParameter {
                key: flag.to_string(),
                value,
                rule,
            })
        };
        self.sizes.check()?;
        for (flag, t) in [("--from", self.from), ("--to", self.to)] {
            if let Some(t) = t {
                if !t.is_finite() || t < 0.0 {
                    return Err(bad(
                        flag,
                        flexrock_core::base::format::shortest(t),
                        "must be a finite time in seconds, 0 or more".to_string(),
                    ));
                }
            }
        }
        if let (Some(from), Some(to)) = (self.from, self.to) {
            if from >= to {
                return Err(bad(
                    "--from",
                    flexrock_core::base::format::shortest(from),
                    format!(
                        "must be less than --to ({} s)",
                        flexrock_core::base::format::shortest(to)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The time window, if any: [from, to], either end open.
    fn window(&self) -> Option<(f64, f64)> {
        (self.from.is_some() || self.to.is_some()).then(|| {
            (
                self.from.unwrap_or(f64::NEG_INFINITY),
                self.to.unwrap_or(f64::INFINITY),
            )
        })
    }
}

/// Reads the run directory `dir` and writes its figures into it, as one atomic set. Nothing is
/// written when a file of the run is missing or malformed.
pub fn plot_dir(dir: &Path) -> Result<Vec<PathBuf>> {
    plot_dir_with(dir, &PlotOptions::default())
}

/// [`plot_dir`] with formats, size and time window. A window that holds no row of the history
/// is refused, naming the flag.
pub fn plot_dir_with(dir: &Path, options: &PlotOptions) -> Result<Vec<PathBuf>> {
    options.check()?;
    let data = RunData::read(dir)?;
    let files = figures_with(&data, options)?;
    let set: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    writers::write_atomically(dir, &set)
}

/// The SVG files of a run, named as in [`FIGURES`]. Each figure is drawn and its series dropped
/// before the next, so that a history of a million rows is held once, not once per figure.
pub fn figures(data: &RunData) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let files = figures_with(data, &PlotOptions::default())?;
    Ok(FIGURES
        .iter()
        .copied()
        .zip(files.into_iter().map(|(_, b)| b))
        .collect())
}

/// The figure files of a run in every format of `options`: plot_motion.svg, plot_motion.png, ...
pub fn figures_with(data: &RunData, options: &PlotOptions) -> Result<Vec<(String, Vec<u8>)>> {
    let automaton = Automaton::new(&data.summary.constants);
    let windowed;
    let (shown, window) = match options.window() {
        None => (data, None),
        Some((t0, t1)) => {
            let history: Vec<HistoryRow> = data
                .history
                .iter()
                .filter(|r| r.t >= t0 && r.t <= t1)
                .cloned()
                .collect();
            if history.len() < 2 {
                let end = data.history.last().map_or(0.0, |r| r.t);
                let (flag, value) = match (options.from, options.to) {
                    (Some(from), _) if from >= end => ("--from", from),
                    (_, Some(to)) => ("--to", to),
                    (Some(from), None) => ("--from", from),
                    (None, None) => ("--from", t0),
                };
                return Err(flexrock_core::Error::InvalidParameter {
                    key: flag.to_string(),
                    value: value.to_string(),
                    rule: format!(
                        "the window holds fewer than two rows of the history (the run spans 0 to {} s)",
                        writers::significant(end, 6)
                    ),
                }
                .into());
            }
            windowed = RunData {
                history,
                events: data
                    .events
                    .iter()
                    .filter(|e| e.t >= t0 && e.t <= t1)
                    .cloned()
                    .collect(),
                summary: data.summary.clone(),
            };
            (&windowed, Some((t0, t1)))
        }
    };
    let page = options.sizes.page(PAGE_MM);
    let mut energy = energy_panels(data, &automaton);
    if let Some((t0, t1)) = window {
        for panel in &mut energy {
            for s in &mut panel.series {
                s.points = clip_time(&s.points, t0, t1);
            }
        }
    }
    let mut files = Vec::new();
    for (i, figure) in [
        Figure::new(motion_panels(shown), 1)
            .shared_x()
            .aspect(4.5, 24.0),
        Figure::new(force_panels(shown, &automaton), 3).aspect(1.0, 25.0),
        Figure::new(energy, 1).shared_x().aspect(3.2, 30.0),
    ]
    .into_iter()
    .enumerate()
    {
        for &format in &options.formats {
            let stem = FIGURES[i].trim_end_matches(".svg");
            let name = format!("{stem}.{}", format.extension());
            let bytes = plot::render(format, &name, &figure, &page)?;
            files.push((name, bytes));
        }
    }
    Ok(files)
}

/// The points of a curve whose x never decreases, within [t0, t1], with the curve's value
/// at t0 and t1 interpolated when they fall between two points.
fn clip_time(points: &[(f64, f64)], t0: f64, t1: f64) -> Vec<(f64, f64)> {
    let at = |a: (f64, f64), b: (f64, f64), t: f64| {
        let f = if b.0 > a.0 {
            (t - a.0) / (b.0 - a.0)
        } else {
            0.0
        };
        (t, a.1 + f * (b.1 - a.1))
    };
    let mut out = Vec::new();
    for (i, &p) in points.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| points[j]);
        if let Some(a) = prev {
            if a.0 < t0 && p.0 > t0 {
                out.push(at(a, p, t0));
            }
        }
        if p.0 >= t0 && p.0 <= t1 {
            out.push(p);
        }
        if let Some(a) = prev {
            if a.0 < t1 && p.0 > t1 {
                out.push(at(a, p, t1));
            }
        }
    }
    out
}

fn series(rows: &[HistoryRow], xy: impl Fn(&HistoryRow) -> (f64, f64)) -> Vec<(f64, f64)> {
    rows.iter().map(xy).collect()
}

/// +-level with one legend entry.
fn pair(level: f64, label: String) -> Vec<(f64, String)> {
    vec![(level, label), (-level, String::new())]
}

/// Palette colour, marker and side of the rug of each kind of event: colours that no curve of
/// the figures uses (vermillion and blue are r and s), told apart in greyscale by the marker.
const EVENT_STYLES: [(EventKind, usize, Marker, bool); 3] = [
    (EventKind::Uplift, 4, Marker::TriangleUp, false),
    (EventKind::Landing, 3, Marker::TriangleDown, true),
    (EventKind::Overturn, 0, Marker::Cross, false),
];

/// The run's events as a rug: a short tick per event, uplifts along the bottom edge and
/// landings along the top, in the colours of the markers of the velocity panel.
fn event_rug(data: &RunData) -> Vec<RugMark> {
    EVENT_STYLES
        .iter()
        .flat_map(|&(kind, color, marker, top)| {
            let n = data.events.iter().filter(|e| e.kind == kind).count();
            let label = event_label(kind, n);
            data.events
                .iter()
                .filter(move |e| e.kind == kind)
                .map(move |e| RugMark {
                    x: e.t,
                    color,
                    top,
                    label: label.clone(),
                    marker,
                })
        })
        .collect()
}

/// The legend text of `n` events of a kind.
fn event_label(kind: EventKind, n: usize) -> String {
    format!("{} ({n})", kind.name())
}

/// Panels of plot_motion: floor acceleration, q with +-s_n and +-B, s and r, and the top
/// velocity with the events marked; the events as a rug on the first three.
pub fn motion_panels(data: &RunData) -> Vec<Panel> {
    let h = &data.history;
    let c = &data.summary.constants;
    let (s_n, b) = (c.uplift_displacement, c.width);
    let s_n_label = format!("±sₙ = {} m (uplift)", writers::significant(s_n, 4));
    let b_label = format!("±B = {} m (overturning)", writers::significant(b, 4));
    let rug = event_rug(data);

    let floor = Panel::new("", "t (s)", "a (m/s²)").with(Series::line(
        "",
        series(h, |r| (r.t, r.floor_acc)),
        0,
    ));
    let mut q =
        Panel::new("", "t (s)", "q (m)").with(Series::line("", series(h, |r| (r.t, r.q)), 0));
    q.reference_lines = pair(s_n, s_n_label.clone());
    q.dashed_lines = pair(b, b_label);
    let mut parts = Panel::new("", "t (s)", "s, r (m)")
        .with(Series::line(
            "s, flexural part",
            series(h, |r| (r.t, r.s)),
            2,
        ))
        .with(
            Series::line("r, rocking part", series(h, |r| (r.t, r.r)), 1).with_dash(Dash::Dashed),
        );
    parts.reference_lines = pair(s_n, s_n_label);
    let mut velocity = Panel::new("", "t (s)", "q\u{307} (m/s)").with(Series::line(
        "",
        series(h, |r| (r.t, r.qdot)),
        0,
    ));
    for (kind, color, marker, _) in EVENT_STYLES {
        let points: Vec<(f64, f64)> = data
            .events
            .iter()
            .filter(|e| e.kind == kind)
            .map(|e| (e.t, e.qdot_before))
            .collect();
        if !points.is_empty() {
            let name = event_label(kind, points.len());
            velocity = velocity.with(Series::markers(&name, points, color, marker));
        }
    }
    let mut panels = vec![floor, q, parts, velocity];
    for panel in &mut panels[..3] {
        panel.rug = rug.clone();
    }
    panels
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

/// Panels of plot_force: F(q) with the run's path on the model's curve, q against r, s
/// against r.
pub fn force_panels(data: &RunData, automaton: &Automaton) -> Vec<Panel> {
    let h = &data.history;
    // The run's path first and wide, the model's curve over it and thin: where the run went,
    // the black line runs inside a pale band.
    let force = Panel::new("", "q (m)", "F (N)")
        .with(Series::line("this run", series(h, |r| (r.q, r.restoring_force)), 6).with_width(3.0))
        .with(Series::line("model F(q)", restoring_force_curve(automaton), 0).with_width(0.6));
    let mut q_r =
        Panel::new("", "r (m)", "q (m)").with(Series::line("", series(h, |r| (r.r, r.q)), 0));
    let mut s_r =
        Panel::new("", "r (m)", "s (m)").with(Series::line("", series(h, |r| (r.r, r.s)), 0));
    q_r.pad_x = true;
    s_r.pad_x = true;
    vec![force, q_r, s_r]
}

/// The net energy lost at events up to each event, J: minus the sum of the jumps of
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

/// Panels of plot_energy: the energy books against t, and the energy residual over the run's
/// energy scale. Six curves: told apart by dashes as well as colours.
pub fn energy_panels(data: &RunData, automaton: &Automaton) -> Vec<Panel> {
    let h = &data.history;
    let kinetic = |r: &HistoryRow| automaton.kinetic_energy(r.qdot);
    let potential = |r: &HistoryRow| automaton.potential_energy(r.mode, r.q);
    let books = Panel::new("", "t (s)", "energy E (J)")
        .with(Series::line(
            "kinetic Mₑq\u{307}²/2",
            series(h, |r| (r.t, kinetic(r))),
            2,
        ))
        .with(
            Series::line("potential V(q)", series(h, |r| (r.t, potential(r))), 3)
                .with_dash(Dash::Dashed),
        )
        .with(
            Series::line(
                "E = kinetic + V",
                series(h, |r| (r.t, kinetic(r) + potential(r))),
                0,
            )
            .with_width(1.2),
        )
        .with(
            Series::line("input work", series(h, |r| (r.t, r.work_input)), 1)
                .with_dash(Dash::DashDot),
        )
        .with(
            Series::line("damping work", series(h, |r| (r.t, r.work_damping)), 4)
                .with_dash(Dash::Dotted)
                .with_width(1.2),
        )
        .with(
            Series::line(
                "net loss at events",
                energy_lost_at_events(data, automaton),
                5,
            )
            .with_dash(Dash::Dashed),
        );

    let summary = &data.summary;
    // A run without motion has no energy: measure against 1 J then.
    let scale = if summary.energy_scale > 0.0 {
        summary.energy_scale
    } else {
        1.0
    };
    let mut residual = Panel::new(
        "",
        "t (s)",
        &format!("ΔE/Eₛ, Eₛ = {} J", writers::significant(scale, 3)),
    )
    .with(Series::line(
        "",
        series(h, |r| (r.t, r.energy_residual / scale)),
        0,
    ));
    residual.reference_lines = pair(
        summary.max_energy_residual / scale,
        "±max |ΔE|/Eₛ".to_string(),
    );
    vec![books, residual]
}
