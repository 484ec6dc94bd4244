//! Two solutions of one model measured against each other: the Newmark solution against a tight
//! adaptive reference, as `flexrock compare` writes it (compare.csv, compare_history.csv,
//! compare.json) and `flexrock converge` measures every case.
//!
//! [`match_events`] aligns two event logs; [`compare`] measures two solutions (matched events,
//! peaks, q(t) on the common output grid) into a typed [`Comparison`]; [`EventRow`] and
//! [`GridRow`] are the rows of the two tables, with their columns in [`EVENT_COLUMNS`] and
//! [`GRID_COLUMNS`].

use serde::Serialize;

use crate::base::format::number;
use crate::integrate::solution::{Event, Extremum, Sample, Solution};
use crate::integrate::OutputGrid;
use crate::model::Model;
use crate::physics::automaton::{EventKind, Mode};
use crate::tables::fields::{optional, Column};

/// Events further apart than a quarter of the pre-uplift period are different events.
pub fn max_event_shift(model: &Model) -> f64 {
    0.25 * model.constants.period
}

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
pub struct Comparison {
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
) -> Comparison {
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

    let (mut sum, mut worst_q, mut t_worst, mut worst_qdot) = (0.0, 0.0, 0.0, 0.0);
    let rows = grid_rows(reference, other, output_dt);
    let points = rows.len();
    for row in &rows {
        let d = row.q_difference;
        sum += d * d;
        if d.abs() > worst_q {
            (worst_q, t_worst) = (d.abs(), row.t);
        }
        worst_qdot = f64::max(worst_qdot, (row.qdot_newmark - row.qdot_reference).abs());
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
    Comparison {
        events,
        peaks,
        grid,
        pairs,
    }
}

impl Comparison {
    /// The rows of compare.csv: every reference event with its partner, in order.
    pub fn event_rows(&self) -> Vec<EventRow> {
        self.pairs
            .iter()
            .enumerate()
            .map(|(index, p)| {
                let r = p.reference.as_ref();
                let o = p.other.as_ref();
                EventRow {
                    index,
                    kind: p.kind,
                    from: p.from,
                    to: p.to,
                    t_reference: r.map(|e| e.t),
                    t_newmark: o.map(|e| e.t),
                    t_difference: p.time_difference(),
                    q_reference: r.map(|e| e.q),
                    q_newmark: o.map(|e| e.q),
                    qdot_after_reference: r.map(|e| e.qdot_after),
                    qdot_after_newmark: o.map(|e| e.qdot_after),
                }
            })
            .collect()
    }
}

/// One row of compare.csv: a reference event and its Newmark partner; a value of a missing
/// event is None (an empty field).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventRow {
    /// Position of the pair, from 0.
    pub index: usize,
    /// The kind of event.
    pub kind: EventKind,
    /// The mode before the event.
    pub from: Mode,
    /// The mode after the event.
    pub to: Mode,
    /// Time of the reference event, s.
    pub t_reference: Option<f64>,
    /// Time of the Newmark event, s.
    pub t_newmark: Option<f64>,
    /// t_newmark - t_reference, s.
    pub t_difference: Option<f64>,
    /// q at the reference event, m.
    pub q_reference: Option<f64>,
    /// q at the Newmark event, m.
    pub q_newmark: Option<f64>,
    /// q' after the reference event's reset, m/s.
    pub qdot_after_reference: Option<f64>,
    /// q' after the Newmark event's reset, m/s.
    pub qdot_after_newmark: Option<f64>,
}

/// The columns of compare.csv (a contract), one per field of [`EventRow`].
pub const EVENT_COLUMNS: [Column<EventRow>; 11] = [
    Column::new("index", |r| r.index.to_string()),
    Column::new("kind", |r| r.kind.name().to_string()),
    Column::new("from", |r| r.from.name().to_string()),
    Column::new("to", |r| r.to.name().to_string()),
    Column::new("t_reference", |r| optional(r.t_reference)),
    Column::new("t_newmark", |r| optional(r.t_newmark)),
    Column::new("t_difference", |r| optional(r.t_difference)),
    Column::new("q_reference", |r| optional(r.q_reference)),
    Column::new("q_newmark", |r| optional(r.q_newmark)),
    Column::new("qdot_after_reference", |r| optional(r.qdot_after_reference)),
    Column::new("qdot_after_newmark", |r| optional(r.qdot_after_newmark)),
];

/// One row of compare_history.csv: both solutions at a time of the common output grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridRow {
    /// Time of the grid point, s.
    pub t: f64,
    /// q of the reference, m.
    pub q_reference: f64,
    /// q of the Newmark solution, m.
    pub q_newmark: f64,
    /// q_newmark - q_reference, m.
    pub q_difference: f64,
    /// Flexural part of the reference, m.
    pub s_reference: f64,
    /// Flexural part of the Newmark solution, m.
    pub s_newmark: f64,
    /// Rocking part of the reference, m.
    pub r_reference: f64,
    /// Rocking part of the Newmark solution, m.
    pub r_newmark: f64,
    /// q' of the reference, m/s.
    pub qdot_reference: f64,
    /// q' of the Newmark solution, m/s.
    pub qdot_newmark: f64,
}

/// The columns of compare_history.csv (a contract), one per field of [`GridRow`].
pub const GRID_COLUMNS: [Column<GridRow>; 10] = [
    Column::new("t", |r| number(r.t)),
    Column::new("q_reference", |r| number(r.q_reference)),
    Column::new("q_newmark", |r| number(r.q_newmark)),
    Column::new("q_difference", |r| number(r.q_difference)),
    Column::new("s_reference", |r| number(r.s_reference)),
    Column::new("s_newmark", |r| number(r.s_newmark)),
    Column::new("r_reference", |r| number(r.r_reference)),
    Column::new("r_newmark", |r| number(r.r_newmark)),
    Column::new("qdot_reference", |r| number(r.qdot_reference)),
    Column::new("qdot_newmark", |r| number(r.qdot_newmark)),
];

/// Both solutions at every point of the grid of spacing `output_dt` (up to the earlier of their
/// ends) where both have a sample: the rows of compare_history.csv.
pub fn grid_rows(reference: &Solution, other: &Solution, output_dt: f64) -> Vec<GridRow> {
    let end = reference.final_time.min(other.final_time);
    let times = OutputGrid::times(end, output_dt);
    times
        .iter()
        .zip(on_grid(reference, &times))
        .zip(on_grid(other, &times))
        .filter_map(|((&t, a), b)| {
            let (a, b) = (a?, b?);
            Some(GridRow {
                t,
                q_reference: a.q,
                q_newmark: b.q,
                q_difference: b.q - a.q,
                s_reference: a.s,
                s_newmark: b.s,
                r_reference: a.r,
                r_newmark: b.r,
                qdot_reference: a.qdot,
                qdot_newmark: b.qdot,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::fields::{names, serialized_keys};

    fn event(t: f64, kind: EventKind, from: Mode, to: Mode) -> Event {
        Event {
            index: 0,
            t,
            kind,
            from,
            to,
            q: 10.0 * t,
            qdot_before: -t,
            qdot_after: t,
        }
    }

    fn uplift_right(t: f64) -> Event {
        event(t, EventKind::Uplift, Mode::PreUplift, Mode::RockRight)
    }

    fn landing_right(t: f64) -> Event {
        event(t, EventKind::Landing, Mode::RockRight, Mode::PreUplift)
    }

    fn uplift_left(t: f64) -> Event {
        event(t, EventKind::Uplift, Mode::PreUplift, Mode::RockLeft)
    }

    /// (reference time, other time) of each pair, None where that side has no event.
    fn times(pairs: &[EventPair]) -> Vec<(Option<f64>, Option<f64>)> {
        pairs
            .iter()
            .map(|p| {
                (
                    p.reference.as_ref().map(|e| e.t),
                    p.other.as_ref().map(|e| e.t),
                )
            })
            .collect()
    }

    #[test]
    fn a_missed_event_leaves_the_others_matched_in_order() {
        let reference = [uplift_right(1.0), landing_right(2.0), uplift_left(3.0)];
        let other = [uplift_right(1.1), uplift_left(3.05)];
        let pairs = match_events(&reference, &other, 0.5);
        assert_eq!(
            times(&pairs),
            [
                (Some(1.0), Some(1.1)),
                (Some(2.0), None),
                (Some(3.0), Some(3.05))
            ]
        );
        assert_eq!(pairs[1].kind, EventKind::Landing);
        assert_eq!(pairs[2].to, Mode::RockLeft);
    }

    /// Matching 1.0 with 0.6 costs 0.4 plus 0.25 for leaving 1.05 out; leaving 0.6 out and
    /// matching 1.05 costs 0.25 + 0.05: the second is the alignment.
    #[test]
    fn the_cheaper_alignment_wins() {
        let reference = [uplift_right(1.0)];
        let other = [uplift_right(0.6), uplift_right(1.05)];
        let pairs = match_events(&reference, &other, 0.5);
        assert_eq!(times(&pairs), [(None, Some(0.6)), (Some(1.0), Some(1.05))]);
    }

    #[test]
    fn events_too_far_apart_or_of_another_transition_do_not_match() {
        let pairs = match_events(&[uplift_right(1.0)], &[uplift_right(1.6)], 0.5);
        assert_eq!(times(&pairs), [(Some(1.0), None), (None, Some(1.6))]);
        let pairs = match_events(&[uplift_right(1.0)], &[uplift_left(1.0)], 0.5);
        assert_eq!(times(&pairs), [(Some(1.0), None), (None, Some(1.0))]);
        assert!(match_events(&[], &[], 0.5).is_empty());
    }

    #[test]
    fn event_rows_hold_both_events_and_their_difference() {
        let reference = [uplift_right(1.0), landing_right(2.0)];
        let other = [uplift_right(1.25)];
        let comparison = Comparison {
            events: EventAgreement {
                n_reference: 2,
                n_other: 1,
                n_matched: 1,
                n_missed: 1,
                n_spurious: 0,
                max_abs_time_difference: 0.25,
                mean_abs_time_difference: 0.25,
                worst_pair: Some(0),
            },
            peaks: PeakComparison {
                reference_max_q: Extremum { value: 0.0, t: 0.0 },
                other_max_q: Extremum { value: 0.0, t: 0.0 },
                reference_min_q: Extremum { value: 0.0, t: 0.0 },
                other_min_q: Extremum { value: 0.0, t: 0.0 },
                max_q_difference: 0.0,
                min_q_difference: 0.0,
                peak_error: 0.0,
            },
            grid: GridDifferences {
                output_dt: 0.01,
                points: 0,
                rms_q_difference: f64::NAN,
                max_abs_q_difference: 0.0,
                t_max_abs_q_difference: 0.0,
                max_abs_qdot_difference: 0.0,
            },
            pairs: match_events(&reference, &other, 0.5),
        };
        let rows = comparison.event_rows();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].t_difference, Some(0.25));
        assert_eq!(rows[0].q_newmark, Some(12.5));
        assert_eq!(rows[1].index, 1);
        assert_eq!(rows[1].t_newmark, None);
        let fields = crate::tables::fields::fields(&EVENT_COLUMNS, &rows[1]);
        assert_eq!(
            fields,
            [
                "1",
                "landing",
                "rock-right",
                "pre-uplift",
                "2",
                "",
                "",
                "20",
                "",
                "2",
                ""
            ]
        );
    }

    /// The columns of both tables are the rows' fields, in order: a field added to a row and
    /// not to its columns (or the reverse) fails here.
    #[test]
    fn the_columns_are_the_fields_of_the_rows() {
        let event_row = EventRow {
            index: 0,
            kind: EventKind::Uplift,
            from: Mode::PreUplift,
            to: Mode::RockRight,
            t_reference: None,
            t_newmark: None,
            t_difference: None,
            q_reference: None,
            q_newmark: None,
            qdot_after_reference: None,
            qdot_after_newmark: None,
        };
        assert_eq!(serialized_keys(&event_row), names(&EVENT_COLUMNS));
        let grid_row = GridRow {
            t: 0.0,
            q_reference: 0.0,
            q_newmark: 0.0,
            q_difference: 0.0,
            s_reference: 0.0,
            s_newmark: 0.0,
            r_reference: 0.0,
            r_newmark: 0.0,
            qdot_reference: 0.0,
            qdot_newmark: 0.0,
        };
        assert_eq!(serialized_keys(&grid_row), names(&GRID_COLUMNS));
    }
}

/// A run measured against the exact solution of its model: the run's certificate
/// (`flexrock run --check`, check.json).
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    /// The method of the run checked, e.g. "bdf".
    pub method: String,
    /// The run against the exact solution: events, peaks and the output grid.
    pub comparison: Comparison,
    /// Every event of either solution, paired in order, with the run's error.
    pub events: Vec<EventCheck>,
    /// The exact solution's own estimate of its largest event-time error, s: the run's errors
    /// are true errors to within it.
    pub exact_error_estimate: f64,
}

/// One event of a [`Check`].
#[derive(Debug, Clone, Serialize)]
pub struct EventCheck {
    /// The kind of event, e.g. "uplift".
    pub kind: &'static str,
    /// The run's time of it, s; None when the run missed it.
    pub t: Option<f64>,
    /// The exact time, s; None when the run has an event the exact solution lacks.
    pub t_exact: Option<f64>,
    /// t - t_exact, s.
    pub error: Option<f64>,
}

/// Checks `solution`, a run of `model` with any method, against the exact solution of `model`.
pub fn check(model: &Model, solution: &Solution) -> crate::Result<Check> {
    let exact = crate::simulate::simulate_with(model, &model.reference(None)?)?;
    let comparison = compare(
        &exact,
        solution,
        model.solver.output_dt(),
        max_event_shift(model),
    );
    let events = comparison
        .pairs
        .iter()
        .map(|p| EventCheck {
            kind: p.kind.name(),
            t: p.other.as_ref().map(|e| e.t),
            t_exact: p.reference.as_ref().map(|e| e.t),
            error: p.time_difference(),
        })
        .collect();
    let exact_error_estimate = exact
        .rounding
        .as_ref()
        .map_or(0.0, |r| r.event_time.iter().copied().fold(0.0, f64::max));
    Ok(Check {
        method: model.solver.label(),
        comparison,
        events,
        exact_error_estimate,
    })
}
