//! `flexrock compare`: a tight adaptive reference and Newmark at the paper's dt, side by side.
//!
//! The pieces are reusable: [`match_events`] aligns two event logs, [`compare`] measures two
//! solutions of one model against each other (events, peaks, q(t) on the common output grid).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::automaton::{EventKind, Mode};
use crate::error::Result;
use crate::findings::{self, Findings};
use crate::model::Model;
use crate::output::{self, count, number, readable, Table};
use crate::plot::{self, Legend, Panel, Series};
use crate::run::{simulate_with, VERSION};
use crate::solution::{Event, Extremum, Sample, Solution, SolverStats};
use crate::solver::{OutputGrid, SolverSettings};

/// Column names of compare.csv (a contract).
pub const COMPARE_COLUMNS: [&str; 11] = [
    "index",
    "kind",
    "from",
    "to",
    "t_reference",
    "t_newmark",
    "t_difference",
    "q_reference",
    "q_newmark",
    "qdot_after_reference",
    "qdot_after_newmark",
];

/// Column names of compare_history.csv (a contract).
pub const COMPARE_HISTORY_COLUMNS: [&str; 10] = [
    "t",
    "q_reference",
    "q_newmark",
    "q_difference",
    "s_reference",
    "s_newmark",
    "r_reference",
    "r_newmark",
    "qdot_reference",
    "qdot_newmark",
];

/// A reference event and the other solution's event matched with it; either may be missing.
#[derive(Debug, Clone, Serialize)]
pub struct EventPair {
    /// The kind of event.
    pub kind: EventKind,
    /// The mode before the event.
    pub from: Mode,
    /// The mode after the event.
    pub to: Mode,
    /// The reference solution's event, if it has one.
    pub reference: Option<Event>,
    /// The other solution's event, if it has one.
    pub other: Option<Event>,
}

impl EventPair {
    /// t_other - t_reference, when both exist.
    pub fn time_difference(&self) -> Option<f64> {
        Some(self.other.as_ref()?.t - self.reference.as_ref()?.t)
    }
}

/// Aligns two event logs in order (a least-cost alignment): two events match when they are the
/// same transition (kind, from, to) no more than `max_shift` apart; the cost of a match is the
/// time difference, the cost of an unmatched event is max_shift / 2, so that a match is preferred
/// exactly when it is cheaper than calling one event missed and the other spurious.
pub fn match_events(reference: &[Event], other: &[Event], max_shift: f64) -> Vec<EventPair> {
    let (n, m) = (reference.len(), other.len());
    let gap = 0.5 * max_shift;
    let pair_cost = |a: &Event, b: &Event| {
        let shift = (a.t - b.t).abs();
        (a.kind == b.kind && a.from == b.from && a.to == b.to && shift <= max_shift)
            .then_some(shift)
    };
    // cost[i][j]: cheapest alignment of reference[i..] with other[j..].
    let mut cost = vec![vec![0.0; m + 1]; n + 1];
    for i in (0..=n).rev() {
        for j in (0..=m).rev() {
            cost[i][j] = if i == n {
                (m - j) as f64 * gap
            } else if j == m {
                (n - i) as f64 * gap
            } else {
                let skip = gap + cost[i + 1][j].min(cost[i][j + 1]);
                match pair_cost(&reference[i], &other[j]) {
                    Some(c) => skip.min(c + cost[i + 1][j + 1]),
                    None => skip,
                }
            };
        }
    }
    let mut pairs = Vec::new();
    let (mut i, mut j) = (0, 0);
    let single = |e: &Event, is_reference: bool| EventPair {
        kind: e.kind,
        from: e.from,
        to: e.to,
        reference: is_reference.then(|| e.clone()),
        other: (!is_reference).then(|| e.clone()),
    };
    while i < n || j < m {
        if i < n && j < m {
            if let Some(c) = pair_cost(&reference[i], &other[j]) {
                if c + cost[i + 1][j + 1] <= cost[i][j] {
                    pairs.push(EventPair {
                        kind: reference[i].kind,
                        from: reference[i].from,
                        to: reference[i].to,
                        reference: Some(reference[i].clone()),
                        other: Some(other[j].clone()),
                    });
                    i += 1;
                    j += 1;
                    continue;
                }
            }
        }
        let take_reference = j == m || (i < n && gap + cost[i + 1][j] <= cost[i][j]);
        if take_reference {
            pairs.push(single(&reference[i], true));
            i += 1;
        } else {
            pairs.push(single(&other[j], false));
            j += 1;
        }
    }
    pairs
}

/// How two event logs agree.
#[derive(Debug, Clone, Serialize)]
pub struct EventAgreement {
    /// Events of the reference solution.
    pub n_reference: usize,
    /// Events of the other solution.
    pub n_other: usize,
    /// Reference events matched with an event of the other solution.
    pub n_matched: usize,
    /// Reference events without a partner.
    pub n_missed: usize,
    /// Events of the other solution without a partner.
    pub n_spurious: usize,
    /// Largest |t_other - t_reference| over matched events, s (NaN when none matched).
    pub max_abs_time_difference: f64,
    /// Mean |t_other - t_reference| over matched events, s (NaN when none matched).
    pub mean_abs_time_difference: f64,
    /// The largest difference is at this matched event (index into the pairs).
    pub worst_pair: Option<usize>,
}

/// Peaks of q of both solutions.
#[derive(Debug, Clone, Serialize)]
pub struct PeakComparison {
    /// Largest q of the reference solution, m, and when.
    pub reference_max_q: Extremum,
    /// Largest q of the other solution, m, and when.
    pub other_max_q: Extremum,
    /// Smallest q of the reference solution, m, and when.
    pub reference_min_q: Extremum,
    /// Smallest q of the other solution, m, and when.
    pub other_min_q: Extremum,
    /// other - reference.
    pub max_q_difference: f64,
    /// other - reference of the smallest q, m.
    pub min_q_difference: f64,
    /// The larger of the two differences in absolute value, m.
    pub peak_error: f64,
}

/// Differences on the common output grid.
#[derive(Debug, Clone, Serialize)]
pub struct GridDifferences {
    /// Spacing of the grid, s.
    pub output_dt: f64,
    /// Grid points where both solutions have a value.
    pub points: usize,
    /// Root mean square of q_other - q_reference over those points, m (NaN when none).
    pub rms_q_difference: f64,
    /// Largest |q_other - q_reference|, m.
    pub max_abs_q_difference: f64,
    /// When that largest difference is, s.
    pub t_max_abs_q_difference: f64,
    /// Largest |q'_other - q'_reference|, m/s.
    pub max_abs_qdot_difference: f64,
}

/// Two solutions of one model measured against each other.
#[derive(Debug, Clone, Serialize)]
pub struct NewmarkComparison {
    /// How the event logs agree.
    pub events: EventAgreement,
    /// How the peaks of q agree.
    pub peaks: PeakComparison,
    /// How the histories differ on the output grid.
    pub grid: GridDifferences,
    #[serde(skip)]
    /// Every reference event with its partner, in order.
    pub pairs: Vec<EventPair>,
}

/// The sample of `solution` at each of `times` (the last sample at that exact time, i.e. after an
/// event there), or None where the solution has none (it ended, or it was sampled elsewhere).
pub fn on_grid<'s>(solution: &'s Solution, times: &[f64]) -> Vec<Option<&'s Sample>> {
    times
        .iter()
        .map(|&t| {
            let after = solution.samples.partition_point(|s| s.t <= t);
            after
                .checked_sub(1)
                .map(|i| &solution.samples[i])
                .filter(|s| s.t == t)
        })
        .collect()
}

/// Measures `other` against `reference`; both sampled on the grid of spacing `output_dt`.
/// Events more than `max_shift` apart are not matched.
pub fn compare(
    reference: &Solution,
    other: &Solution,
    output_dt: f64,
    max_shift: f64,
) -> NewmarkComparison {
    let pairs = match_events(&reference.events, &other.events, max_shift);
    let differences: Vec<(usize, f64)> = pairs
        .iter()
        .enumerate()
        .filter_map(|(i, p)| Some((i, p.time_difference()?.abs())))
        .collect();
    let worst = differences
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let n_matched = differences.len();
    let events = EventAgreement {
        n_reference: reference.events.len(),
        n_other: other.events.len(),
        n_matched,
        n_missed: pairs.iter().filter(|p| p.other.is_none()).count(),
        n_spurious: pairs.iter().filter(|p| p.reference.is_none()).count(),
        max_abs_time_difference: worst.map_or(f64::NAN, |w| w.1),
        mean_abs_time_difference: if n_matched == 0 {
            f64::NAN
        } else {
            differences.iter().map(|d| d.1).sum::<f64>() / n_matched as f64
        },
        worst_pair: worst.map(|w| w.0),
    };

    let max_q_difference = other.max_q.value - reference.max_q.value;
    let min_q_difference = other.min_q.value - reference.min_q.value;
    let peaks = PeakComparison {
        reference_max_q: reference.max_q,
        other_max_q: other.max_q,
        reference_min_q: reference.min_q,
        other_min_q: other.min_q,
        max_q_difference,
        min_q_difference,
        peak_error: max_q_difference.abs().max(min_q_difference.abs()),
    };

    let end = reference.final_time.min(other.final_time);
    let times = OutputGrid::times(end, output_dt);
    let (mut sum, mut points, mut worst_q, mut t_worst, mut worst_qdot) = (0.0, 0, 0.0, 0.0, 0.0);
    for (a, b) in on_grid(reference, &times)
        .into_iter()
        .zip(on_grid(other, &times))
    {
        if let (Some(a), Some(b)) = (a, b) {
            let d = b.q - a.q;
            sum += d * d;
            points += 1;
            if d.abs() > worst_q {
                (worst_q, t_worst) = (d.abs(), a.t);
            }
            worst_qdot = f64::max(worst_qdot, (b.qdot - a.qdot).abs());
        }
    }
    let grid = GridDifferences {
        output_dt,
        points,
        rms_q_difference: if points == 0 {
            f64::NAN
        } else {
            (sum / points as f64).sqrt()
        },
        max_abs_q_difference: worst_q,
        t_max_abs_q_difference: t_worst,
        max_abs_qdot_difference: worst_qdot,
    };
    NewmarkComparison {
        events,
        peaks,
        grid,
        pairs,
    }
}

/// Options of `flexrock compare`.
#[derive(Debug, Clone)]
pub struct CompareOptions {
    /// Relative tolerance of the adaptive reference.
    pub reference_rtol: f64,
    /// Newmark step (default: the file's, else the paper's 0.02 s).
    pub dt: Option<f64>,
    /// Newmark variant (default: the file's, else "compensate").
    pub variant: Option<String>,
    /// Where the two solves' wall times go (compare.json, or timings.json).
    pub wall_times: output::WallTimes,
}

/// Relative tolerance of the adaptive reference solution (`--reference-rtol`).
pub const DEFAULT_REFERENCE_RTOL: f64 = 1e-12;

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            reference_rtol: DEFAULT_REFERENCE_RTOL,
            dt: None,
            variant: None,
            wall_times: output::WallTimes::Inline,
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
        findings: findings::measure(s, &crate::automaton::Automaton::new(&model.constants)),
    }
}

/// compare.json.
#[derive(Debug, Serialize)]
pub(crate) struct CompareSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::run::Provenance,
    #[serde(rename = "T")]
    pub period: f64,
    pub s_n: f64,
    pub duration: f64,
    /// Events further apart than this are not matched, s.
    pub max_event_shift: f64,
    pub reference: SolutionSummary<'a>,
    pub newmark: SolutionSummary<'a>,
    pub comparison: &'a NewmarkComparison,
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
    pub comparison: NewmarkComparison,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Events further apart than a quarter of the pre-uplift period are different events.
pub fn max_event_shift(model: &Model) -> f64 {
    0.25 * model.constants.period
}

/// The reference's and Newmark's settings, checked before anything is computed; an error names
/// the flag its value came from (`--reference-rtol`, `--dt`, `--variant`).
pub fn compare_settings(
    model: &Model,
    options: &CompareOptions,
) -> Result<(SolverSettings, SolverSettings)> {
    let reference = model
        .reference_settings(options.reference_rtol)
        .map_err(|e| {
            e.renamed("rtol", "--reference-rtol")
                .renamed("solver.rtol", "--reference-rtol")
        })?;
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
    Ok((
        SolverSettings::Adaptive(reference),
        SolverSettings::Newmark(newmark),
    ))
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
    let mut timings = output::Timings::new(options.wall_times);
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
        provenance: crate::run::Provenance::of(model),
        period: model.constants.period,
        s_n: model.constants.uplift_displacement,
        duration: model.duration,
        max_event_shift: max_shift,
        reference: solution_summary(model, reference_settings, &reference),
        newmark: solution_summary(model, newmark_settings, &newmark),
        comparison: &comparison,
    };
    let figure = compare_figure(model, &reference, &newmark, &newmark_settings.label())?;
    let relations = relations_figure(&reference, &newmark, &newmark_settings.label())?;
    let mut files = vec![
        ("compare.csv", events_table(&comparison.pairs)),
        (
            "compare_history.csv",
            history_table(&reference, &newmark, output_dt),
        ),
        ("compare.json", output::json_bytes(&summary)),
        ("compare.svg", figure.into_bytes()),
        ("compare_relations.svg", relations.into_bytes()),
    ];
    files.extend(timings.file());
    let files = output::write_atomically(out_dir, &files)?;
    Ok(CompareReport {
        reference,
        newmark,
        reference_settings,
        newmark_settings,
        comparison,
        files,
    })
}

fn optional(x: Option<f64>) -> String {
    x.map(number).unwrap_or_default()
}

fn events_table(pairs: &[EventPair]) -> Vec<u8> {
    let mut table = Table::new(&COMPARE_COLUMNS);
    for (i, p) in pairs.iter().enumerate() {
        let r = p.reference.as_ref();
        let o = p.other.as_ref();
        table.row([
            i.to_string(),
            p.kind.name().to_string(),
            p.from.name().to_string(),
            p.to.name().to_string(),
            optional(r.map(|e| e.t)),
            optional(o.map(|e| e.t)),
            optional(p.time_difference()),
            optional(r.map(|e| e.q)),
            optional(o.map(|e| e.q)),
            optional(r.map(|e| e.qdot_after)),
            optional(o.map(|e| e.qdot_after)),
        ]);
    }
    table.into_bytes()
}

fn history_table(reference: &Solution, other: &Solution, output_dt: f64) -> Vec<u8> {
    let end = reference.final_time.min(other.final_time);
    let times = OutputGrid::times(end, output_dt);
    let mut table = Table::new(&COMPARE_HISTORY_COLUMNS);
    for ((t, a), b) in times
        .iter()
        .zip(on_grid(reference, &times))
        .zip(on_grid(other, &times))
    {
        if let (Some(a), Some(b)) = (a, b) {
            table.row([
                number(*t),
                number(a.q),
                number(b.q),
                number(b.q - a.q),
                number(a.s),
                number(b.s),
                number(a.r),
                number(b.r),
                number(a.qdot),
                number(b.qdot),
            ]);
        }
    }
    table.into_bytes()
}

/// The paper's Fig. 6 panels (q, s, r, q') with both solutions overlaid.
fn compare_figure(
    model: &Model,
    reference: &Solution,
    other: &Solution,
    label: &str,
) -> Result<String> {
    let s_n = model.constants.uplift_displacement;
    let panel = |title: &str, y_label: &str, value: fn(&Sample) -> f64, s_n_lines: bool| {
        let series = vec![
            Series::line(
                "reference",
                reference.samples.iter().map(|x| (x.t, value(x))).collect(),
                0,
            ),
            Series::line(
                label,
                other.samples.iter().map(|x| (x.t, value(x))).collect(),
                1,
            ),
        ];
        let reference_lines = if s_n_lines {
            vec![(s_n, "±s_n (uplift)".to_string()), (-s_n, String::new())]
        } else {
            Vec::new()
        };
        Panel {
            title: title.to_string(),
            x_label: "t (s)".to_string(),
            y_label: y_label.to_string(),
            series,
            reference_lines,
            // Beside the plot: inside, it covered the curves of the last seconds.
            legend: Legend::Outside,
            ..Panel::default()
        }
    };
    let panels = [
        panel("Top displacement", "q (m)", |x| x.q, true),
        panel("Flexural part", "s (m)", |x| x.s, true),
        panel("Rocking part", "r (m)", |x| x.r, false),
        panel("Top velocity", "dq/dt (m/s)", |x| x.qdot, false),
    ];
    plot::figure("compare.svg", &panels, 1, (1150, 300))
}

/// The paper's Figs. 12-13: q against r and s against r, both solutions.
fn relations_figure(reference: &Solution, other: &Solution, label: &str) -> Result<String> {
    let panel = |title: &str, x_label: &str, y_label: &str, xy: fn(&Sample) -> (f64, f64)| Panel {
        title: title.to_string(),
        x_label: x_label.to_string(),
        y_label: y_label.to_string(),
        series: vec![
            Series::line("reference", reference.samples.iter().map(xy).collect(), 0),
            Series::line(label, other.samples.iter().map(xy).collect(), 1),
        ],
        // A preference: the figure moves it to a corner the curves leave free, or beside the plot.
        legend: Legend::LowerRight,
        ..Panel::default()
    };
    let panels = [
        panel(
            "Top displacement against rocking part",
            "r (m)",
            "q (m)",
            |x| (x.r, x.q),
        ),
        panel(
            "Flexural part against rocking part",
            "r (m)",
            "s (m)",
            |x| (x.r, x.s),
        ),
    ];
    plot::figure("compare_relations.svg", &panels, 2, (680, 560))
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
        SolverSettings::Adaptive(_) => String::new(),
    };
    let reference_rtol = match report.reference_settings {
        SolverSettings::Adaptive(a) => format!("rtol = {:e}", a.rtol),
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
    let _ = writeln!(
        t,
        "  event times: max |difference| {:.6} s, mean {:.6} s",
        e.max_abs_time_difference, e.mean_abs_time_difference
    );
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
        output::milliseconds(report.reference.stats.wall_time_s, 1)
            .map_or_else(String::new, |t| format!(", {t}")),
        count(report.newmark.stats.steps, "step", "steps"),
        count(
            report.newmark.stats.rhs_evaluations,
            "rhs evaluation",
            "rhs evaluations"
        ),
        output::milliseconds(report.newmark.stats.wall_time_s, 1)
            .map_or_else(String::new, |t| format!(", {t}"))
    );
    for f in &report.files {
        let _ = writeln!(t, "wrote {}", f.display());
    }
    t
}
