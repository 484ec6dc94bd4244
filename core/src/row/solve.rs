//! The exact solution of a row of columns: every column moves by its own exact
//! flows, planned and taken exactly as a run of the column alone takes them, and the row
//! searches the gap of each pair of neighbours along the two flows for its first closing.
//!
//! The row advances in windows: each column plans its next flow ([`Run::plan`]), which stops at
//! its own next event or at the end of its closed form; the window ends at the earliest such
//! stop. The gap of each pair is searched over the window as q is for a guard (`scan`): it is a
//! smooth function of time there with bounds on its derivatives from the two flows', so a
//! closing cannot be missed. With no closing, the columns whose stop ends the window take their
//! flow, the others keep theirs, unchanged. At a closing, the columns in contact are cut there
//! ([`Run::cut`]), the impulses of every contact closing at that instant are found together
//! ([`impulses`]), and each column's q' jumps by its share ([`Run::impact`]). A column
//! that takes no part never re-anchors, so a row whose gaps never close gives, column by
//! column, the runs of the columns alone to the last digit.
//!
//! Impacts that accumulate (a pair pressed together bounces ever shorter) are detected when a
//! closing velocity falls below [`ACCUMULATION_SHARE`] of the largest the pair has had: the run
//! stops there with an error, since persistent contact is not part of the row model yet. The
//! run budget of each column counts its impacts as events, so no run takes more than its budget.

use std::time::Instant;

use super::{impulses, Contact, Row};
use crate::automaton::{Automaton, EventKind, Guard, Mode};
use crate::solver::exact::flow::{Flow, Point};
use crate::solver::exact::scan::{self, first_crossing, ScanError, Smooth, Watch};
use crate::solver::exact::{ExactSettings, Planned, Run, NAME};

use crate::double_double::DoubleDouble as Dd;
use crate::excitation::FloorMotion;
use crate::solution::Solution;
use crate::solver::budget::RunBudget;
use crate::solver::{History, SolverError};

/// A closing whose velocity is below this share of the largest closing velocity of the pair
/// so far marks impacts that accumulate.
pub const ACCUMULATION_SHARE: f64 = 1e-6;
/// Contacts whose closings lie within this many seconds (relative to max(1, t)) of the first are
/// one simultaneous impact.
const SIMULTANEOUS: f64 = 1e-12;

/// One impact at one contact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ImpactRecord {
    /// Time, s.
    pub t: f64,
    /// The contact: between column `contact` and `contact + 1`.
    pub contact: usize,
    /// Closing velocity of the contact points before the impact, m/s (positive).
    pub closing_velocity: f64,
    /// Their separating velocity after it, m/s.
    pub separating_velocity: f64,
    /// The impulse, N s.
    pub impulse: f64,
}

/// What the row's run returns.
#[derive(Debug, Clone)]
pub struct RowSolution {
    /// Each column's solution, left to right: its history, its events (impacts among them),
    /// its peaks and its energy books.
    pub columns: Vec<Solution>,
    /// Every impact, in time order.
    pub impacts: Vec<ImpactRecord>,
    /// The body's kinetic energy taken by each instant of impacts, J (positive), in time order.
    pub impact_energy_loss: Vec<(f64, f64)>,
    /// The column that overturned and when, if one did: the row's run ends there.
    pub overturned: Option<(usize, f64)>,
    /// The time the run ended, s.
    pub final_time: f64,
}

/// The gap of one contact along the flows of its two columns.
struct Gap<'f> {
    contact: &'f Contact,
    automata: (&'f Automaton, &'f Automaton),
    modes: (Mode, Mode),
    flows: (&'f Flow, &'f Flow),
    slopes: (f64, f64),
}

impl Smooth for Gap<'_> {
    fn point(&self, t: f64) -> Point {
        let (l, r) = (self.flows.0.point(t), self.flows.1.point(t));
        let (sl, sr) = self.slopes;
        Point {
            t,
            q: self
                .contact
                .gap(self.automata, (self.modes.0, l.q), (self.modes.1, r.q)),
            v: sr * r.v - sl * l.v,
            acc: sr * r.acc - sl * l.acc,
            jerk: sr * r.jerk - sl * l.jerk,
        }
    }

    fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64) {
        let (l, r) = (self.flows.0.point(p.t), self.flows.1.point(p.t));
        let bl = self.flows.0.derivative_bounds(&l, h);
        let br = self.flows.1.derivative_bounds(&r, h);
        let (sl, sr) = (self.slopes.0.abs(), self.slopes.1.abs());
        (
            sl * bl.0 + sr * br.0,
            sl * bl.1 + sr * br.1,
            sl * bl.2 + sr * br.2,
        )
    }
}

/// Solves `row` on `floor` exactly over [0, duration].
pub fn solve_row(
    row: &Row,
    floor: &dyn FloorMotion,
    duration: f64,
    settings: &ExactSettings,
    history: History,
) -> Result<RowSolution, SolverError> {
    let started = Instant::now();
    let energy = history == History::Sampled;
    let columns = row.columns();
    let n = columns.len();
    let in_column = |i: usize, e: SolverError| match e {
        SolverError::Failed { method, t, message } => SolverError::Failed {
            method,
            t,
            message: format!("column {i}: {message}"),
        },
        other => other,
    };
    let mut runs: Vec<Run> = columns
        .iter()
        .map(|c| {
            Run::new(
                &c.automaton,
                floor,
                c.initial,
                duration,
                settings,
                history,
                energy,
            )
        })
        .collect();
    let mut budgets: Vec<RunBudget> = (0..n).map(|_| RunBudget::new()).collect();
    let mut plans: Vec<Option<Planned>> = Vec::with_capacity(n);
    for i in 0..n {
        let plan = runs[i]
            .plan(duration, &mut budgets[i])
            .map_err(|e| in_column(i, e))?;
        plans.push(plan);
    }
    let mut impacts = Vec::new();
    let mut losses = Vec::new();
    let mut largest_closing = vec![0.0_f64; n.saturating_sub(1)];
    let mut now = 0.0_f64;
    let mut overturned = None;
    loop {
        if let Some(i) = (0..n).find(|&i| runs[i].state().1 == Mode::Overturned) {
            // A column fell: what it falls onto is beyond the model; the row's run ends.
            let t = runs[i].state().0;
            overturned = Some((i, t));
            for (j, plan) in plans.iter_mut().enumerate() {
                if let Some(plan) = plan.take() {
                    runs[j].cut(plan, t);
                }
            }
            now = t;
            break;
        }
        let Some(window_end) = plans
            .iter()
            .flatten()
            .map(Planned::stop)
            .min_by(f64::total_cmp)
        else {
            break;
        };
        // The first closing of each contact within the window.
        let mut closings: Vec<(usize, f64)> = Vec::new();
        for contact in row.contacts() {
            let c = contact.index;
            let (Some(left), Some(right)) = (&plans[c], &plans[c + 1]) else {
                continue;
            };
            let automata = (&columns[c].automaton, &columns[c + 1].automaton);
            let modes = (runs[c].state().1, runs[c + 1].state().1);
            let gap = Gap {
                contact,
                automata,
                modes,
                flows: (left.flow(), right.flow()),
                slopes: contact.slopes(automata, modes),
            };
            if let Some(t) = first_closing(&gap, now, window_end).map_err(|e| scan_failed(e, c))? {
                closings.push((c, t));
            }
        }
        let Some(first) = closings.iter().map(|&(_, t)| t).min_by(f64::total_cmp) else {
            // No closing: the columns whose own stop ends the window take their flow.
            for i in 0..n {
                if plans[i].as_ref().is_some_and(|p| p.stop() == window_end) {
                    let plan = plans[i].take().expect("checked");
                    let going = runs[i]
                        .commit(plan, duration, &mut budgets[i])
                        .map_err(|e| in_column(i, e))?;
                    if going {
                        plans[i] = runs[i]
                            .plan(duration, &mut budgets[i])
                            .map_err(|e| in_column(i, e))?;
                    }
                }
            }
            now = window_end;
            continue;
        };
        let t = first;
        let active: Vec<usize> = closings
            .iter()
            .filter(|&&(_, tc)| tc <= t + SIMULTANEOUS * t.max(1.0))
            .map(|&(c, _)| c)
            .collect();
        let mut involved: Vec<usize> = active.iter().flat_map(|&c| [c, c + 1]).collect();
        involved.sort_unstable();
        involved.dedup();
        for &i in &involved {
            // A column whose own event falls at the very instant takes it first.
            if plans[i].as_ref().is_some_and(|p| p.stop() <= t) {
                let plan = plans[i].take().expect("checked");
                runs[i]
                    .commit(plan, duration, &mut budgets[i])
                    .map_err(|e| in_column(i, e))?;
                plans[i] = runs[i]
                    .plan(duration, &mut budgets[i])
                    .map_err(|e| in_column(i, e))?;
            }
            if let Some(plan) = plans[i].take() {
                runs[i].cut(plan, t);
            }
        }
        now = t;
        // The contacts' closing velocities, slopes and masses at t.
        let states: Vec<(f64, Mode, f64, Dd)> = runs.iter().map(Run::state).collect();
        let state = |i: usize| states[i];
        let k = active.len();
        let mut closing = vec![0.0; k];
        let mut matrix = vec![0.0; k * k];
        let mut shares: Vec<(f64, f64)> = Vec::with_capacity(k);
        for (a, &c) in active.iter().enumerate() {
            let contact = &row.contacts()[c];
            let automata = (&columns[c].automaton, &columns[c + 1].automaton);
            let (sl, ml, vl) = (state(c).1, automata.0.kinetic_mass(state(c).1), state(c).3);
            let (sr, mr, vr) = (
                state(c + 1).1,
                automata.1.kinetic_mass(state(c + 1).1),
                state(c + 1).3,
            );
            let (pl, pr) = contact.slopes(automata, (sl, sr));
            closing[a] = pl * vl.value() - pr * vr.value();
            matrix[a * k + a] = pl * pl / ml + pr * pr / mr;
            shares.push((pl / ml, pr / mr));
        }
        for a in 0..k.saturating_sub(1) {
            if active[a + 1] == active[a] + 1 {
                // Contacts a and a + 1 share column active[a] + 1: its right share at contact a
                // times its left slope at contact a + 1.
                let shared = active[a] + 1;
                let contact_next = &row.contacts()[active[a + 1]];
                let automata = (&columns[shared].automaton, &columns[shared + 1].automaton);
                let (p_next, _) =
                    contact_next.slopes(automata, (state(shared).1, state(shared + 1).1));
                let value = -shares[a].1 * p_next;
                matrix[a * k + a + 1] = value;
                matrix[(a + 1) * k + a] = value;
            }
        }
        for (a, &c) in active.iter().enumerate() {
            let w = closing[a];
            if w <= ACCUMULATION_SHARE * largest_closing[c] || w <= 0.0 {
                return Err(SolverError::Failed {
                    method: NAME.to_string(),
                    t,
                    message: format!(
                        "impacts between columns {c} and {} accumulate (closing at {w:e} m/s, \
                         after closings up to {:e} m/s): the columns would stay in contact, \
                         which the row model does not include yet",
                        c + 1,
                        largest_closing[c]
                    ),
                });
            }
            largest_closing[c] = largest_closing[c].max(w);
        }
        let j =
            impulses(&closing, &matrix, row.restitution()).map_err(|e| SolverError::Failed {
                method: NAME.to_string(),
                t,
                message: e.to_string(),
            })?;
        // Each column's jump of q': the sum of its shares of the impulses on either side.
        let mut jumps = vec![0.0; n];
        for (a, &c) in active.iter().enumerate() {
            let automata = (&columns[c].automaton, &columns[c + 1].automaton);
            let (pl, pr) = row.contacts()[c].slopes(automata, (state(c).1, state(c + 1).1));
            jumps[c] -= pl * j[a] / automata.0.kinetic_mass(state(c).1);
            jumps[c + 1] += pr * j[a] / automata.1.kinetic_mass(state(c + 1).1);
        }
        let mut loss = 0.0;
        for &i in &involved {
            let (_, mode, _, v) = runs[i].state();
            let after = v + jumps[i];
            let automaton = &columns[i].automaton;
            loss += automaton.body_kinetic_energy(mode, v.value())
                - automaton.body_kinetic_energy(mode, after.value());
            let error = 2.0 * scan::ulp(t) + SIMULTANEOUS * t.max(1.0);
            runs[i]
                .impact(after, error, &mut budgets[i])
                .map_err(|e| in_column(i, e))?;
        }
        losses.push((t, loss));
        let after: Vec<Dd> = runs.iter().map(|r| r.state().3).collect();
        for (a, &c) in active.iter().enumerate() {
            let automata = (&columns[c].automaton, &columns[c + 1].automaton);
            let (pl, pr) = row.contacts()[c].slopes(automata, (state(c).1, state(c + 1).1));
            impacts.push(ImpactRecord {
                t,
                contact: c,
                closing_velocity: closing[a],
                separating_velocity: pr * after[c + 1].value() - pl * after[c].value(),
                impulse: j[a],
            });
        }
        for &i in &involved {
            plans[i] = runs[i]
                .plan(duration, &mut budgets[i])
                .map_err(|e| in_column(i, e))?;
        }
    }
    let solutions = runs
        .into_iter()
        .map(|run| {
            let t = run.state().0;
            run.finish(t, started).0
        })
        .collect();
    Ok(RowSolution {
        columns: solutions,
        impacts,
        impact_energy_loss: losses,
        overturned,
        final_time: now.min(duration).max(now),
    })
}

/// The first time in (from, to] at which the gap closes (falls through 0), if it does.
fn first_closing(gap: &Gap, from: f64, to: f64) -> Result<Option<f64>, ScanError> {
    if to <= from {
        return Ok(None);
    }
    let closing = Guard {
        level: 0.0,
        direction: -1.0,
        kind: EventKind::Impact,
        to: Mode::PreUplift,
    };
    let mut watch = Watch {
        guard_up: f64::INFINITY,
        guard_down: 0.0,
        max: f64::INFINITY,
        min: f64::NEG_INFINITY,
        extrema: Vec::new(),
        evaluations: 0,
        unresolved: 0,
    };
    let mut a = scan::evaluate(gap, from, &mut watch)?;
    if a.q < 0.0 {
        // Closed at the start: a contact just struck, whose gap the rounding of the two
        // states leaves a hair below zero. It is on the guard, so that closing on from there is
        // found at once (and the impacts accumulate), while opening is no crossing.
        a.q = 0.0;
    }
    let b = scan::evaluate(gap, to, &mut watch)?;
    Ok(first_crossing(gap, a, b, &[closing], &mut watch)?.map(|(p, _)| p.t))
}

fn scan_failed(e: ScanError, contact: usize) -> SolverError {
    let (t, what) = match e {
        ScanError::NotFinite(t) => (t, "is not finite".to_string()),
        ScanError::TooMuchWork(t) => (
            t,
            format!("took more than {} evaluations", scan::MAX_EVALUATIONS),
        ),
    };
    SolverError::Failed {
        method: NAME.to_string(),
        t,
        message: format!(
            "the gap between columns {contact} and {} {what}",
            contact + 1
        ),
    }
}
