//! The exact solution of a row of columns under the impact law: every column moves by its own exact
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
//! closing velocity falls below [`ACCUMULATION_SHARE`] of the largest the pair has had: that
//! impact is taken as plastic and the pair is held in contact from then on (persistent
//! contact). Columns held together form a cluster that moves with one degree of freedom: each
//! column's q is affine in the leftmost one's (the gaps held closed), and the members'
//! equations summed with the weights of their virtual displacements (the contact forces do no
//! work on the cluster) are one linear equation with constant coefficients, which each member
//! follows as an exact flow of its own. The force of each held contact is affine in the
//! leader's q, q' and q'' along that flow; the contact is let go where the force would become
//! tensile, found by the same search as a guard. An uplift or landing of a member disturbs the
//! cluster: its reset is applied, and a plastic impact among the held contacts makes the
//! velocities agree again. The run budget of each column counts its impacts and releases as
//! events, so no run takes more than its budget.

use std::time::Instant;

use super::contact::{
    Contact, ContactSample, ContactState, GAP_ROUNDING_ULPS, OVERLAP_ERROR_SHARE,
};
use super::description::Row;
use super::impact::impulses;
use super::solution::{HeldContact, ImpactRecord, RowSolution};
use crate::integrate::exact::kernel::{
    evaluate, first_crossing, ulp, ExactRun, Flow, Planned, Point, ScanError, Smooth, Watch,
    MAX_EVALUATIONS, STEADY_BOUND_GAIN,
};
use crate::integrate::exact::{ExactSettings, NAME};
use crate::physics::automaton::{Automaton, EventKind, Guard, LinearForm, Mode};

use crate::base::double_double::DoubleDouble as Dd;
use crate::floor::FloorMotion;
use crate::integrate::budget::RunBudget;
use crate::integrate::solution::Solution;
use crate::integrate::{History, SolverError};

/// A closing whose velocity is below this share of the largest closing velocity of the pair
/// so far marks impacts that accumulate.
pub const ACCUMULATION_SHARE: f64 = 1e-6;
/// Contacts whose closings lie within this many seconds (relative to max(1, t)) of the first are
/// one simultaneous impact.
const SIMULTANEOUS: f64 = 1e-12;
/// Each bounce of a pair resting on each other is found the rounding allowance
/// ([`GAP_ROUNDING_ULPS`]) lower, so its closing velocity cannot fall below
/// sqrt(2 |g''| allowance): a closing within this factor of that speed (4.5e-7 m/s for 1e-16 m
/// under 1 m/s^2) also marks impacts that accumulate. Bounces that decay by e settle at
/// 1/sqrt(1 - e^2) of it, below the factor for any e up to 0.9995.
pub const ROUNDING_SPEED_FACTOR: f64 = 32.0;

/// The gap of one contact along the flows of its two columns.
struct Gap<'f> {
    contact: &'f Contact,
    automata: (&'f Automaton, &'f Automaton),
    modes: (Mode, Mode),
    flows: (&'f Flow, &'f Flow),
    slopes: (f64, f64),
    /// Added to the gap: the rounding allowed below zero for a contact let go (0 otherwise).
    allowance: f64,
}

impl Smooth for Gap<'_> {
    fn point(&self, t: f64) -> Point {
        let (l, r) = (self.flows.0.point(t), self.flows.1.point(t));
        let (sl, sr) = self.slopes;
        Point {
            t,
            q: self
                .contact
                .gap(self.automata, (self.modes.0, l.q), (self.modes.1, r.q))
                + self.allowance,
            v: sr * r.v - sl * l.v,
            acc: sr * r.acc - sl * l.acc,
            jerk: sr * r.jerk - sl * l.jerk,
            free: [0.0; 2],
        }
    }

    /// The sum of the two flows' bounds; where the columns follow one equation and move alike,
    /// the bounds of their difference ([`Flow::combined_bounds`]) when these are at least
    /// [`STEADY_BOUND_GAIN`] times smaller (identical columns under one floor: the gap stays
    /// where it is, and a gap of 1e-12 m is no harder to search than one of 1 m).
    fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64) {
        let (l, r) = (self.flows.0.point(p.t), self.flows.1.point(p.t));
        let bl = self.flows.0.derivative_bounds(&l, h);
        let br = self.flows.1.derivative_bounds(&r, h);
        let (sl, sr) = self.slopes;
        let sum = (
            sl.abs() * bl.0 + sr.abs() * br.0,
            sl.abs() * bl.1 + sr.abs() * br.1,
            sl.abs() * bl.2 + sr.abs() * br.2,
        );
        match Flow::combined_bounds((self.flows.0, &l, sl), (self.flows.1, &r, sr), h) {
            Some(d) if d.0 * STEADY_BOUND_GAIN <= sum.0 => {
                (d.0.min(sum.0), d.1.min(sum.1), d.2.min(sum.2))
            }
            _ => sum,
        }
    }
}

/// A smooth function of time along a cluster leader's flow: a held contact's force,
/// P = alpha q + gamma q' + delta q'' + epsilon (N) in the leader's q. Its point gives P and
/// its rate; the higher derivatives are left at zero with no bound on the third, so the search
/// cuts it into monotone pieces by its rate and the bound on its second derivative alone.
struct Force<'f> {
    flow: &'f Flow,
    coefficients: [f64; 4],
}

impl Smooth for Force<'_> {
    fn point(&self, t: f64) -> Point {
        let p = self.flow.point(t);
        let [alpha, gamma, delta, epsilon] = self.coefficients;
        Point {
            t,
            q: alpha * p.q + gamma * p.v + delta * p.acc + epsilon,
            v: alpha * p.v + gamma * p.acc + delta * p.jerk,
            acc: 0.0,
            jerk: 0.0,
            free: [0.0; 2],
        }
    }

    fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64) {
        let leader = self.flow.point(p.t);
        let (m2, m3, m4) = self.flow.derivative_bounds(&leader, h);
        let [alpha, gamma, delta, _] = self.coefficients;
        (
            alpha.abs() * m2 + gamma.abs() * m3 + delta.abs() * m4,
            f64::INFINITY,
            f64::INFINITY,
        )
    }
}

/// A cluster of columns held together, planned from one instant: each member's linear form,
/// and each held contact's force in the leader's q, q', q''.
struct Cluster {
    first: usize,
    forms: Vec<LinearForm>,
    forces: Vec<[f64; 4]>,
}

/// What ends a window early.
#[derive(Debug, Clone, Copy)]
enum Interrupt {
    /// A gap closes; `rounding_speed` is the closing velocity that falling through its
    /// rounding allowance alone would give there, m/s (0 for a contact never struck).
    Closing { rounding_speed: f64 },
    /// A held contact's force falls to zero.
    Release,
}

/// Solves `row`, under the impact law, on `floor` exactly over [0, duration].
pub(super) fn solve_row_exact(
    row: &Row,
    floor: &dyn FloorMotion,
    duration: f64,
    settings: &ExactSettings,
    history: History,
) -> Result<RowSolution, SolverError> {
    let started = Instant::now();
    let energy = history == History::Sampled;
    let n = row.columns().len();
    let runs: Vec<ExactRun> = row
        .columns()
        .iter()
        .map(|c| {
            ExactRun::new(
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
    let mut state = RowRun {
        row,
        duration,
        runs,
        budgets: (0..n).map(|_| RunBudget::new()).collect(),
        plans: (0..n).map(|_| None).collect(),
        held: vec![false; n - 1],
        clusters: Vec::new(),
        largest_closing: vec![0.0; n - 1],
        impacts: Vec::new(),
        losses: Vec::new(),
        stretches: Vec::new(),
        rounding: vec![None; n - 1],
        widest_rounding: vec![0.0; n - 1],
        fall: vec![0.0; n - 1],
        fresh_rounding: vec![false; n - 1],
        rounding_speed: vec![0.0; n - 1],
        now: 0.0,
    };
    let everyone: Vec<usize> = (0..n).collect();
    state.replan(&everyone)?;
    let overturned = state.go()?;
    let now = state.now;
    let solutions: Vec<Solution> = state
        .runs
        .into_iter()
        .map(|run| {
            let t = run.state().0;
            run.finish(t, started).0
        })
        .collect();
    let contact_history =
        contact_history_from_samples(row, &solutions, &state.stretches, &state.widest_rounding)?;
    Ok(RowSolution {
        columns: solutions,
        impacts: state.impacts,
        impact_energy_loss: state.losses,
        overturned,
        held: state.stretches,
        contacts: Vec::new(),
        contact_history,
        sticking: Vec::new(),
        final_time: now,
    })
}

struct RowRun<'a> {
    row: &'a Row,
    duration: f64,
    runs: Vec<ExactRun<'a>>,
    budgets: Vec<RunBudget>,
    plans: Vec<Option<Planned>>,
    /// Per contact: held closed (persistent contact).
    held: Vec<bool>,
    /// The clusters of held columns as last planned.
    clusters: Vec<Cluster>,
    largest_closing: Vec<f64>,
    impacts: Vec<ImpactRecord>,
    losses: Vec<(f64, f64)>,
    stretches: Vec<HeldContact>,
    /// Per contact struck or let go: the rounding its gap may fall below zero before it counts
    /// as closed ([`GAP_ROUNDING_ULPS`]), from the states when it was last struck or let go.
    rounding: Vec<Option<f64>>,
    /// Per contact: the widest of its roundings over the run, m.
    widest_rounding: Vec<f64>,
    /// Per contact: how far its gap falls, from where it stands, before it counts as closing:
    /// its rounding less how far below zero the gap already is, m. Only this fall, not the
    /// whole allowance, gives a pair resting on each other its closing speed at each bounce.
    fall: Vec<f64>,
    /// Per contact: its rounding was set from the states at the current instant, and waits for
    /// the flows planned from them ([`Self::settle_gaps`]).
    fresh_rounding: Vec<bool>,
    /// Per contact: the closing velocity that falling through its rounding allowance alone
    /// gives at the closing being struck, m/s.
    rounding_speed: Vec<f64>,
    now: f64,
}

fn in_column(i: usize, e: SolverError) -> SolverError {
    match e {
        SolverError::Failed { method, t, message } => SolverError::Failed {
            method,
            t,
            message: format!("column {i}: {message}"),
        },
        other => other,
    }
}

fn failed(t: f64, message: String) -> SolverError {
    SolverError::Failed {
        method: NAME.to_string(),
        t,
        message,
    }
}

impl<'a> RowRun<'a> {
    /// The columns held together with column `i`, first and last.
    fn cluster_of(&self, i: usize) -> (usize, usize) {
        let mut first = i;
        while first > 0 && self.held[first - 1] {
            first -= 1;
        }
        let mut last = i;
        while last + 1 < self.runs.len() && self.held[last] {
            last += 1;
        }
        (first, last)
    }

    /// Every column of the clusters of `columns`, in order.
    fn with_clusters(&self, columns: &[usize]) -> Vec<usize> {
        let mut all: Vec<usize> = columns
            .iter()
            .flat_map(|&i| {
                let (a, b) = self.cluster_of(i);
                a..=b
            })
            .collect();
        all.sort_unstable();
        all.dedup();
        all
    }

    /// The held contacts between columns of `columns`.
    fn held_within(&self, columns: &[usize]) -> Vec<usize> {
        columns
            .iter()
            .filter(|&&i| i + 1 < self.runs.len() && self.held[i] && columns.contains(&(i + 1)))
            .copied()
            .collect()
    }

    /// Cuts every column of `columns` that has a plan at `t`.
    fn cut(&mut self, columns: &[usize], t: f64) {
        for &i in columns {
            if let Some(plan) = self.plans[i].take() {
                self.runs[i].cut(plan, t);
            }
        }
    }

    /// Plans `columns` (whole clusters, all at the same instant) anew: each free column by its
    /// own mode, each cluster by its combined linear form.
    fn replan(&mut self, columns: &[usize]) -> Result<(), SolverError> {
        let columns = self.with_clusters(columns);
        self.clusters.retain(|c| !columns.contains(&c.first));
        let mut i = 0;
        while i < columns.len() {
            let (first, last) = self.cluster_of(columns[i]);
            if first == last {
                self.runs[first].set_bond(None);
            } else {
                let cluster = self.cluster(first, last)?;
                for (j, form) in (first..=last).zip(&cluster.forms) {
                    self.runs[j].set_bond(Some(*form));
                }
                self.clusters.push(cluster);
            }
            for j in first..=last {
                if self.runs[j].state().1 == Mode::Overturned {
                    continue;
                }
                self.plans[j] = self.runs[j]
                    .plan(self.duration, &mut self.budgets[j])
                    .map_err(|e| in_column(j, e))?;
            }
            i = columns
                .iter()
                .position(|&c| c > last)
                .unwrap_or(columns.len());
        }
        Ok(())
    }

    /// The combined motion of the held columns first..=last from their current states.
    fn cluster(&self, first: usize, last: usize) -> Result<Cluster, SolverError> {
        let t = self.runs[first].state().0;
        let contacts = self.row.contacts();
        let size = last - first + 1;
        // Each member's q = rho q_leader + kappa; its kinetic mass and its own linear form.
        let mut rho = vec![1.0; size];
        let mut kappa = vec![0.0; size];
        let q_leader = self.runs[first].state().2;
        let mut own = Vec::with_capacity(size);
        for k in 0..size {
            let j = first + k;
            let (_, mode, q, _) = self.runs[j].state();
            let a = self.runs[j].automaton();
            let Some(form) = a.linear_form(mode) else {
                return Err(failed(t, format!("column {j} has overturned while held")));
            };
            own.push((a.kinetic_mass(mode), form));
            if k > 0 {
                let c = j - 1;
                let automata = (self.runs[c].automaton(), a);
                let (left, right) = contacts[c].slopes(automata, (self.runs[c].state().1, mode));
                rho[k] = rho[k - 1] * left / right;
                kappa[k] = q - rho[k] * q_leader;
            }
        }
        let mu: f64 = (0..size).map(|k| rho[k] * rho[k] * own[k].0).sum();
        let sum = |f: &dyn Fn(usize) -> f64| (0..size).map(f).sum::<f64>() / mu;
        let damping = sum(&|k| rho[k] * rho[k] * own[k].0 * own[k].1.damping);
        let stiffness = sum(&|k| rho[k] * rho[k] * own[k].0 * own[k].1.stiffness);
        let participation = sum(&|k| rho[k] * own[k].0 * own[k].1.participation);
        let stiffness_equilibrium =
            sum(&|k| rho[k] * own[k].0 * own[k].1.stiffness * (own[k].1.equilibrium - kappa[k]));
        let scale = sum(&|k| (rho[k] * rho[k] * own[k].0 * own[k].1.stiffness).abs());
        if stiffness.abs() <= 1e-9 * scale {
            return Err(failed(
                t,
                format!(
                    "columns {first} to {last} held together have no net stiffness (their \
                     rocking and swaying cancel): their held motion is not modelled"
                ),
            ));
        }
        let equilibrium = stiffness_equilibrium / stiffness;
        let forms = (0..size)
            .map(|k| LinearForm {
                stiffness,
                damping,
                equilibrium: rho[k] * equilibrium + kappa[k],
                participation: rho[k] * participation,
            })
            .collect();
        // Each member's share of the contact forces, m (q_j'' - f_j), in the leader's q, q',
        // q'' (the floor eliminated by the combined equation, beta a = -(q'' + C q' + K (q - e))).
        let r = |k: usize| {
            let (m, f) = own[k];
            let b = f.participation / participation;
            [
                m * (f.stiffness * rho[k] - b * stiffness),
                m * (f.damping * rho[k] - b * damping),
                m * (rho[k] - b),
                m * (f.stiffness * (kappa[k] - f.equilibrium) + b * stiffness * equilibrium),
            ]
        };
        // The force of the contact right of member k: (Phi_left P_before - R_k) / Phi_right.
        let mut forces = Vec::with_capacity(size - 1);
        let mut before = [0.0; 4];
        for k in 0..size - 1 {
            let j = first + k;
            let automata = (self.runs[j].automaton(), self.runs[j + 1].automaton());
            let modes = (self.runs[j].state().1, self.runs[j + 1].state().1);
            let (right_slope, _) = contacts[j].slopes(automata, modes);
            let left_slope = if k == 0 {
                0.0
            } else {
                let c = j - 1;
                let automata = (self.runs[c].automaton(), self.runs[j].automaton());
                contacts[c]
                    .slopes(automata, (self.runs[c].state().1, self.runs[j].state().1))
                    .1
            };
            let rk = r(k);
            let p: [f64; 4] =
                std::array::from_fn(|x| (left_slope * before[x] - rk[x]) / right_slope);
            forces.push(p);
            before = p;
        }
        Ok(Cluster {
            first,
            forms,
            forces,
        })
    }

    /// Runs the windows to the end; the column that overturned, if one did.
    fn go(&mut self) -> Result<Option<(usize, f64)>, SolverError> {
        let n = self.runs.len();
        loop {
            if let Some(i) = (0..n).find(|&i| self.runs[i].state().1 == Mode::Overturned) {
                // A column fell: what it falls onto is beyond the model; the row's run ends.
                let t = self.runs[i].state().0;
                let all: Vec<usize> = (0..n).collect();
                self.cut(&all, t);
                self.now = t;
                self.end_stretches(t);
                return Ok(Some((i, t)));
            }
            self.settle_gaps()?;
            let Some(window_end) = self
                .plans
                .iter()
                .flatten()
                .map(Planned::stop)
                .min_by(f64::total_cmp)
            else {
                return Ok(None);
            };
            let mut found = self.closings(window_end)?;
            found.extend(self.releases(window_end)?);
            let Some(t) = found.iter().map(|f| f.1).min_by(f64::total_cmp) else {
                self.take_window(window_end)?;
                continue;
            };
            let tolerance = SIMULTANEOUS * t.max(1.0);
            let now: Vec<(usize, Interrupt)> = found
                .iter()
                .filter(|f| f.1 <= t + tolerance)
                .map(|f| (f.0, f.2))
                .collect();
            let releases: Vec<usize> = now
                .iter()
                .filter(|f| matches!(f.1, Interrupt::Release))
                .map(|f| f.0)
                .collect();
            if !releases.is_empty() {
                self.release(&releases, t)?;
                continue;
            }
            for &(c, interrupt) in &now {
                if let Interrupt::Closing { rounding_speed } = interrupt {
                    self.rounding_speed[c] = rounding_speed;
                }
            }
            let closing: Vec<usize> = now.iter().map(|f| f.0).collect();
            self.strike(&closing, t)?;
        }
    }

    /// Keeps every open contact's gap at or above its rounding allowance at the start of a
    /// window. An allowance set at this instant from the columns' states is taken as
    /// [`GAP_ROUNDING_ULPS`] of the terms the flows planned from them sum, where those are
    /// larger than the gap's own ([`Flow::term_size`]): near resonance a column's steady state
    /// and free motion nearly cancel, and the gap read along the two flows dips a hundred of
    /// its own ulps below where it is (a pair opening at 1e-9 m/s from a gap of 2e-18 m was
    /// found closing there, struck with no impulse, and found closing again, until the step cap
    /// stopped the run). A column re-anchored at its own event, or at an
    /// impact at another of its
    /// contacts, starts a flow whose q differs from the old one's by the rounding of its terms
    /// (a few ulps of its q_eq, which may be far larger than the gap's own terms), so a gap
    /// resting at its allowance may start a window a hair below it, where the search of a fall
    /// through zero cannot begin; its allowance is then widened to where the gap is, as when it
    /// was set. A gap below its allowance by more than [`OVERLAP_ERROR_SHARE`] of its size is no
    /// rounding but a closing missed: an error naming the pair, never a row whose columns pass
    /// through each other.
    fn settle_gaps(&mut self) -> Result<(), SolverError> {
        for c in (0..self.held.len()).filter(|&c| !self.held[c]) {
            let Some(terms) = self.gap(c).map(|gap| {
                gap.slopes.0.abs() * gap.flows.0.term_size(self.now)
                    + gap.slopes.1.abs() * gap.flows.1.term_size(self.now)
            }) else {
                continue;
            };
            if std::mem::take(&mut self.fresh_rounding[c]) {
                // As many ulps of the terms the two flows sum, where those are larger.
                let (ulps, below) = self.gap_rounding(c);
                let flows = GAP_ROUNDING_ULPS * ulp(terms);
                if flows > ulps {
                    self.rounding[c] = Some(flows + below);
                    self.fall[c] = flows;
                    self.widest_rounding[c] = self.widest_rounding[c].max(flows + below);
                }
            }
            let Some(gap) = self.gap(c) else {
                continue;
            };
            let below = -gap.point(self.now).q;
            if below <= 0.0 {
                continue;
            }
            let (l, r) = (gap.flows.0.point(self.now), gap.flows.1.point(self.now));
            let size = gap
                .contact
                .gap_size(gap.automata, (gap.modes.0, l.q), (gap.modes.1, r.q));
            let tolerance = OVERLAP_ERROR_SHARE * size;
            if below > tolerance {
                return Err(failed(
                    self.now,
                    format!(
                        "the gap between columns {c} and {} is {:e} m, below zero by more than \
                         its rounding ({:e} m) with no impact: a closing was missed, and the run \
                         stops rather than let them pass through each other",
                        c + 1,
                        -below - gap.allowance,
                        gap.allowance + tolerance
                    ),
                ));
            }
            let rounding = gap.allowance + below + GAP_ROUNDING_ULPS * ulp(size);
            self.rounding[c] = Some(rounding);
            self.fall[c] = GAP_ROUNDING_ULPS * ulp(size);
            self.widest_rounding[c] = self.widest_rounding[c].max(rounding);
        }
        Ok(())
    }

    /// Ends the stretches of persistent contact still open at `t` (a column overturned).
    fn end_stretches(&mut self, t: f64) {
        for s in self.stretches.iter_mut().filter(|s| s.t_end.is_none()) {
            s.t_end = Some(t);
        }
    }

    /// Contact `c`'s gap (with its rounding allowance) along the two columns' plans; None where
    /// a column has no plan.
    fn gap(&self, c: usize) -> Option<Gap<'_>> {
        let contact = &self.row.contacts()[c];
        let (Some(left), Some(right)) = (&self.plans[c], &self.plans[c + 1]) else {
            return None;
        };
        let automata = (self.runs[c].automaton(), self.runs[c + 1].automaton());
        let modes = (self.runs[c].state().1, self.runs[c + 1].state().1);
        Some(Gap {
            contact,
            automata,
            modes,
            flows: (left.flow(), right.flow()),
            slopes: contact.slopes(automata, modes),
            allowance: self.rounding[c].unwrap_or(0.0),
        })
    }

    /// Contact `c`'s gap at `t`, as [`Self::gap`].
    fn gap_at(&self, c: usize, t: f64) -> Option<Point> {
        self.gap(c).map(|gap| gap.point(t))
    }

    /// `closing` with every contact next to the columns struck that is as good as closed at
    /// `t`: its gap within the distance the contacts close at over the simultaneity window. In a
    /// chain of columns pressed together, one impact sends the next pair into contact an
    /// instant later, and so on back and forth; struck one pair at a time, such a chain took
    /// more impacts within 1e-11 s than any budget allows. Struck together, it is one impact.
    fn with_touching(&self, closing: &[usize], t: f64) -> Vec<usize> {
        let n = self.runs.len();
        let speed = closing
            .iter()
            .filter_map(|&c| self.gap_at(c, t))
            .map(|p| -p.v)
            .fold(0.0, f64::max);
        let reach = SIMULTANEOUS * t.max(1.0) * speed;
        let mut set = closing.to_vec();
        loop {
            let ends: Vec<usize> = set.iter().flat_map(|&c| [c, c + 1]).collect();
            let members = self.with_clusters(&ends);
            let (first, last) = (members[0], members[members.len() - 1]);
            let next = [first.checked_sub(1), (last + 1 < n).then_some(last)]
                .into_iter()
                .flatten()
                .find(|&c| {
                    !self.held[c]
                        && !set.contains(&c)
                        && self.gap_at(c, t).is_some_and(|p| p.q <= reach)
                });
            match next {
                Some(c) => set.push(c),
                None => break,
            }
        }
        set.sort_unstable();
        set
    }

    /// The first closing of each open contact within (now, window_end].
    fn closings(&self, window_end: f64) -> Result<Vec<(usize, f64, Interrupt)>, SolverError> {
        let mut out = Vec::new();
        for contact in self.row.contacts() {
            let c = contact.index;
            if self.held[c] {
                continue;
            }
            let Some(gap) = self.gap(c) else {
                continue;
            };
            if let Some(t) =
                first_fall(&gap, self.now, window_end).map_err(|e| scan_failed(e, c))?
            {
                let rounding_speed = (2.0 * gap.point(t).acc.abs() * self.fall[c]).sqrt();
                out.push((c, t, Interrupt::Closing { rounding_speed }));
            }
        }
        Ok(out)
    }

    /// The first time each held contact's force falls to zero within [now, window_end]: at
    /// once where it is not compressive now.
    fn releases(&self, window_end: f64) -> Result<Vec<(usize, f64, Interrupt)>, SolverError> {
        let mut out = Vec::new();
        for cluster in &self.clusters {
            let Some(leader) = &self.plans[cluster.first] else {
                continue;
            };
            for (k, coefficients) in cluster.forces.iter().enumerate() {
                let c = cluster.first + k;
                let force = Force {
                    flow: leader.flow(),
                    coefficients: *coefficients,
                };
                if force.point(self.now).q <= 0.0 {
                    out.push((c, self.now, Interrupt::Release));
                    continue;
                }
                if let Some(t) =
                    first_fall(&force, self.now, window_end).map_err(|e| scan_failed(e, c))?
                {
                    out.push((c, t, Interrupt::Release));
                }
            }
        }
        Ok(out)
    }

    /// No closing and no release within the window: the columns whose own stop ends it take
    /// their flow; a cluster one of whose members had an event is settled.
    fn take_window(&mut self, window_end: f64) -> Result<(), SolverError> {
        let n = self.runs.len();
        let mut stopped = Vec::new();
        let mut disturbed = Vec::new();
        for i in 0..n {
            if self.plans[i]
                .as_ref()
                .is_some_and(|p| p.stop() == window_end)
            {
                let plan = self.plans[i].take().expect("checked");
                let events_before = self.runs[i].event_count();
                let going = self.runs[i]
                    .commit(plan, self.duration, &mut self.budgets[i])
                    .map_err(|e| in_column(i, e))?;
                if self.runs[i].event_count() > events_before {
                    disturbed.push(i);
                }
                if going {
                    stopped.push(i);
                }
            }
        }
        self.now = window_end;
        if (0..n).any(|i| self.runs[i].state().1 == Mode::Overturned) {
            return Ok(());
        }
        // Free columns plan on; held ones plan with their cluster, from one instant.
        let members = self.with_clusters(&stopped);
        let others: Vec<usize> = members
            .iter()
            .copied()
            .filter(|i| !stopped.contains(i))
            .collect();
        self.cut(&others, window_end);
        let disturbed = self.with_clusters(&disturbed);
        let held = self.held_within(&disturbed);
        if !held.is_empty() {
            // A member's reset broke the agreement of the held velocities: a plastic impact
            // among the held contacts restores it (those that open are let go).
            let restitution = vec![0.0; held.len()];
            self.impulses(&held, &restitution, window_end)?;
        }
        self.replan(&members)
    }

    /// Lets go of held contacts `contacts` at `t`.
    fn release(&mut self, contacts: &[usize], t: f64) -> Result<(), SolverError> {
        let ends: Vec<usize> = contacts.iter().flat_map(|&c| [c, c + 1]).collect();
        let members = self.with_clusters(&ends);
        self.cut(&members, t);
        self.now = t;
        for &c in contacts {
            self.held[c] = false;
            self.set_rounding(c);
            self.end_stretch(c, t);
            for i in [c, c + 1] {
                self.budgets[i]
                    .event(t)
                    .map_err(|m| in_column(i, failed(t, m)))?;
            }
        }
        self.replan(&members)
    }

    /// Sets contact `c`'s rounding from the columns' current states ([`Self::gap_rounding`]).
    fn set_rounding(&mut self, c: usize) {
        let (ulps, below) = self.gap_rounding(c);
        self.rounding[c] = Some(ulps + below);
        self.fall[c] = ulps;
        self.widest_rounding[c] = self.widest_rounding[c].max(ulps + below);
        self.fresh_rounding[c] = true;
    }

    /// How far below zero contact `c`'s gap may fall before it counts as closing, m, from the
    /// columns' current states: its rounding ([`GAP_ROUNDING_ULPS`] of its size), and how far
    /// the gap is below zero already, if it is (a pair struck at a gap a hair below zero and
    /// held there keeps that gap).
    fn gap_rounding(&self, c: usize) -> (f64, f64) {
        let automata = (self.runs[c].automaton(), self.runs[c + 1].automaton());
        let (left, right) = (self.runs[c].state(), self.runs[c + 1].state());
        let (left, right) = ((left.1, left.2), (right.1, right.2));
        let contact = &self.row.contacts()[c];
        let rounding = GAP_ROUNDING_ULPS * ulp(contact.gap_size(automata, left, right));
        (rounding, (-contact.gap(automata, left, right)).max(0.0))
    }

    /// Ends the open stretch of `contact` at `t`; one that ends the instant it began (a plastic
    /// impact whose pair is not pressed together) was no stretch and is dropped.
    fn end_stretch(&mut self, contact: usize, t: f64) {
        if let Some(i) = self
            .stretches
            .iter()
            .rposition(|s| s.contact == contact && s.t_end.is_none())
        {
            if self.stretches[i].t_start == t {
                self.stretches.remove(i);
            } else {
                self.stretches[i].t_end = Some(t);
            }
        }
    }

    /// Contacts `closing` close at `t`: the impacts, with every held contact of the columns
    /// involved, resolved together.
    fn strike(&mut self, closing: &[usize], t: f64) -> Result<(), SolverError> {
        let closing = &self.with_touching(closing, t);
        let ends: Vec<usize> = closing.iter().flat_map(|&c| [c, c + 1]).collect();
        let members = self.with_clusters(&ends);
        for &i in &members {
            // A column whose own event falls at the very instant takes it first.
            if self.plans[i].as_ref().is_some_and(|p| p.stop() <= t) {
                let plan = self.plans[i].take().expect("checked");
                self.runs[i]
                    .commit(plan, self.duration, &mut self.budgets[i])
                    .map_err(|e| in_column(i, e))?;
                if self.runs[i].state().1 != Mode::Overturned {
                    self.plans[i] = self.runs[i]
                        .plan(self.duration, &mut self.budgets[i])
                        .map_err(|e| in_column(i, e))?;
                }
            }
        }
        self.cut(&members, t);
        self.now = t;
        if members
            .iter()
            .any(|&i| self.runs[i].state().1 == Mode::Overturned)
        {
            return Ok(());
        }
        let mut contacts: Vec<usize> = closing.to_vec();
        contacts.extend(self.held_within(&members));
        contacts.sort_unstable();
        contacts.dedup();
        let restitution: Vec<f64> = contacts
            .iter()
            .map(|&c| {
                if self.held[c] {
                    0.0
                } else {
                    self.row.restitution()
                }
            })
            .collect();
        self.impulses(&contacts, &restitution, t)?;
        self.replan(&members)
    }

    /// The impulses at `contacts` (each with its restitution) at `t`, applied to the columns'
    /// velocities and booked: an impact event of every column struck, a row of the impacts
    /// for every contact that carries an impulse. A closing too slow against the pair's earlier
    /// ones is taken as plastic and the pair held together; a held contact stays held unless
    /// it opens.
    fn impulses(
        &mut self,
        contacts: &[usize],
        restitution: &[f64],
        t: f64,
    ) -> Result<(), SolverError> {
        let n = self.runs.len();
        let states: Vec<(f64, Mode, f64, Dd)> = self.runs.iter().map(ExactRun::state).collect();
        let k = contacts.len();
        let mut slopes = Vec::with_capacity(k);
        let mut masses = Vec::with_capacity(k);
        let mut closing = vec![0.0; k];
        for (a, &c) in contacts.iter().enumerate() {
            let automata = (self.runs[c].automaton(), self.runs[c + 1].automaton());
            let (pl, pr) = self.row.contacts()[c].slopes(automata, (states[c].1, states[c + 1].1));
            closing[a] = pl * states[c].3.value() - pr * states[c + 1].3.value();
            slopes.push((pl, pr));
            masses.push((
                automata.0.kinetic_mass(states[c].1),
                automata.1.kinetic_mass(states[c + 1].1),
            ));
        }
        // Accumulating impacts are taken as plastic, and their pair is held.
        let mut e: Vec<f64> = restitution.to_vec();
        let mut hold = vec![false; k];
        for (a, &c) in contacts.iter().enumerate() {
            if self.held[c] {
                hold[a] = true;
                continue;
            }
            let w = closing[a];
            // A closing no faster than a fall through the rounding below the gap gives (the
            // bounces of a pair resting on each other) accumulates as well.
            let resting = w <= ROUNDING_SPEED_FACTOR * self.rounding_speed[c];
            self.rounding_speed[c] = 0.0;
            if w <= ACCUMULATION_SHARE * self.largest_closing[c] || resting || w <= 0.0 {
                e[a] = 0.0;
                hold[a] = true;
            }
            self.largest_closing[c] = self.largest_closing[c].max(w);
        }
        let mut matrix = vec![0.0; k * k];
        for a in 0..k {
            matrix[a * k + a] =
                slopes[a].0 * slopes[a].0 / masses[a].0 + slopes[a].1 * slopes[a].1 / masses[a].1;
            if a + 1 < k && contacts[a + 1] == contacts[a] + 1 {
                // Contacts a and a + 1 share a column: its slopes at both over its mass.
                let value = -slopes[a].1 * slopes[a + 1].0 / masses[a].1;
                matrix[a * k + a + 1] = value;
                matrix[(a + 1) * k + a] = value;
            }
        }
        let targets: Vec<f64> = (0..k).map(|a| (1.0 + e[a]) * closing[a]).collect();
        // Newton's law with each contact's own restitution: impulses() with e = 0 on the
        // targets (1 + e_c) w_c.
        let j = impulses(&targets, &matrix, 0.0).map_err(|m| failed(t, m.to_string()))?;
        let mut jumps = vec![0.0; n];
        for (a, &c) in contacts.iter().enumerate() {
            jumps[c] -= slopes[a].0 * j[a] / masses[a].0;
            jumps[c + 1] += slopes[a].1 * j[a] / masses[a].1;
        }
        let mut involved: Vec<usize> = contacts.iter().flat_map(|&c| [c, c + 1]).collect();
        involved.sort_unstable();
        involved.dedup();
        let mut loss = 0.0;
        // The columns struck: those at a contact that carries an impulse (a middle column
        // pushed equally both ways among them, its velocity unchanged).
        let struck: Vec<bool> = (0..n)
            .map(|i| {
                contacts
                    .iter()
                    .zip(&j)
                    .any(|(&c, &x)| x > 0.0 && (c == i || c + 1 == i))
            })
            .collect();
        for &i in &involved {
            if !struck[i] {
                continue;
            }
            let (_, mode, _, v) = states[i];
            let after = v + jumps[i];
            let automaton = self.runs[i].automaton();
            loss += automaton.body_kinetic_energy(mode, v.value())
                - automaton.body_kinetic_energy(mode, after.value());
            let error = 2.0 * ulp(t) + SIMULTANEOUS * t.max(1.0);
            self.runs[i]
                .impact(after, error, &mut self.budgets[i])
                .map_err(|e| in_column(i, e))?;
        }
        if j.iter().any(|&x| x > 0.0) {
            self.losses.push((t, loss));
        }
        let after: Vec<Dd> = self.runs.iter().map(|r| r.state().3).collect();
        for (a, &c) in contacts.iter().enumerate() {
            let separating = slopes[a].1 * after[c + 1].value() - slopes[a].0 * after[c].value();
            if j[a] > 0.0 {
                self.impacts.push(ImpactRecord {
                    t,
                    contact: c,
                    closing_velocity: closing[a],
                    separating_velocity: separating,
                    impulse: j[a],
                });
            }
            let scale = closing[a]
                .abs()
                .max(self.largest_closing[c])
                .max(f64::MIN_POSITIVE);
            let opens = separating > 1e-9 * scale;
            let was_held = self.held[c];
            self.held[c] = hold[a] && !opens;
            self.set_rounding(c);
            if self.held[c] && !was_held {
                self.stretches.push(HeldContact {
                    contact: c,
                    t_start: t,
                    t_end: None,
                });
            } else if was_held && !self.held[c] {
                self.end_stretch(c, t);
            }
        }
        Ok(())
    }
}

/// The first time in (from, to] at which `f` falls through zero (a gap closing, a held
/// contact's force vanishing), if it does.
fn first_fall<F: Smooth>(f: &F, from: f64, to: f64) -> Result<Option<f64>, ScanError> {
    if to <= from {
        return Ok(None);
    }
    let zero = Guard {
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
        stack: Vec::new(),
        evaluations: 0,
        unresolved: 0,
    };
    let a = evaluate(f, from, &mut watch)?;
    let b = evaluate(f, to, &mut watch)?;
    Ok(first_crossing(f, a, b, &[zero], &mut watch)?.map(|(p, _)| p.t))
}

fn scan_failed(e: ScanError, contact: usize) -> SolverError {
    let (t, what) = match e {
        ScanError::NotFinite(t) => (t, "is not finite".to_string()),
        ScanError::TooMuchWork(t) => (t, format!("took more than {} evaluations", MAX_EVALUATIONS)),
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

/// The contact history of an impact-law row from its columns' sampled histories: the gap, the
/// closing and sliding velocities from each column's q, q' and mode at every instant both
/// columns of the contact sampled (the output grid, and the instants of their shared impacts,
/// before and after), held where a stretch of persistent contact covers the instant. Rows are
/// in time order, contacts left to right within an instant. An open contact's gap may stand
/// below zero by its rounding only: the widest `rounding` allowance it had over the run (m, per
/// contact) and [`OVERLAP_ERROR_SHARE`] of its size; beyond that, an error.
fn contact_history_from_samples(
    row: &Row,
    columns: &[Solution],
    held: &[HeldContact],
    rounding: &[f64],
) -> Result<Vec<ContactSample>, SolverError> {
    let mut rows = Vec::new();
    for contact in row.contacts() {
        let c = contact.index;
        let automata = (&row.columns()[c].automaton, &row.columns()[c + 1].automaton);
        let (left, right) = (&columns[c].samples, &columns[c + 1].samples);
        let (mut i, mut j) = (0, 0);
        while i < left.len() && j < right.len() {
            let (l, r) = (&left[i], &right[j]);
            if l.t < r.t {
                i += 1;
                continue;
            }
            if r.t < l.t {
                j += 1;
                continue;
            }
            let t = l.t;
            let (pl, pr) = contact.slopes(automata, (l.mode, r.mode));
            let (vl, vr) = contact.sliding_slopes(automata, (l.mode, l.q), (r.mode, r.q));
            let is_held = held
                .iter()
                .any(|h| h.contact == c && h.t_start <= t && h.t_end.is_none_or(|end| t < end));
            let gap = contact.gap(automata, (l.mode, l.q), (r.mode, r.q));
            let tolerance = rounding[c]
                + OVERLAP_ERROR_SHARE * contact.gap_size(automata, (l.mode, l.q), (r.mode, r.q));
            if !is_held && gap < -tolerance {
                return Err(SolverError::Failed {
                    method: NAME.to_string(),
                    t,
                    message: format!(
                        "the gap between columns {c} and {} is {gap:e} m with no impact, below \
                         zero by more than its rounding ({tolerance:e} m): the columns would pass \
                         through each other",
                        c + 1
                    ),
                });
            }
            rows.push(ContactSample {
                t,
                contact: c,
                state: if is_held {
                    ContactState::Held
                } else {
                    ContactState::Open
                },
                gap,
                closing_velocity: pl * l.qdot - pr * r.qdot,
                sliding_velocity: vl * l.qdot - vr * r.qdot,
                force: None,
                friction_force: None,
            });
            i += 1;
            j += 1;
        }
    }
    // Stable: within an instant, contacts stay left to right, and the samples of one contact in
    // the order taken.
    rows.sort_by(|a, b| a.t.total_cmp(&b.t));
    Ok(rows)
}
