//! A run of the exact method: flows planned and committed one after another, each to its
//! first guard crossing, where the event is booked and its reset applied; the history sampled
//! and the energy books kept along the way.

use std::time::Instant;

use super::energy_books::{work_pieces, SampleBooks, Work, WorkFactors};
use super::extremes::{Candidate, Top};
use super::flow::{self, Flow, Point};
use super::graze::{self, Approach, Kick, ESTIMATE_SAFETY};
use super::rounding;
use super::scan::{self, first_crossing, ScanError, Watch};
use super::settings::{ExactSettings, NAME};
use super::step::StepCache;
use super::work::{self, FormCache};
use crate::base::double_double::DoubleDouble as Dd;
use crate::floor::{FloorMotion, Shape};
use crate::integrate::budget::RunBudget;
use crate::integrate::solution::{Recorder, RoundingEstimate, Solution, SolverStats};
use crate::integrate::{History, InitialState, OutputGrid, SolverError};
use crate::physics::automaton::{Automaton, EventKind, Guard, LinearForm, Mode};

/// Most samples of the history inside one of a record's intervals for which the run keeps the
/// exact recurrence over their offsets ([`Run::interval_point`]): with the interval's own and
/// those of three modes, [`step::KEPT`] recurrences.
const OFFSETS_KEPT: usize = 3;

/// A run of the automaton by the exact method, from one flow to the next.
pub(crate) struct ExactRun<'a> {
    automaton: &'a Automaton,
    floor: &'a dyn FloorMotion,
    mode: Mode,
    t: f64,
    /// The time of the last event beyond the double `t` (a fraction of its ulp), 0 after a flow
    /// that ends without one.
    t_lo: f64,
    q: Dd,
    v: Dd,
    /// Whether the energy books are kept.
    energy: bool,
    /// Whether the local rounding is booked (a run with a history: the shadow runs and runs
    /// without one leave their estimate unread).
    estimate: bool,
    recorder: Recorder<'a>,
    grid: OutputGrid,
    work: Work,
    max_q: f64,
    min_q: f64,
    /// |q| at the peak of the rocking episode under way.
    episode_peak: f64,
    event_errors: Vec<f64>,
    /// The local estimates of the earlier events' times, added as a random walk (the root of the
    /// sum of their squares), s: an error of an event's time is carried by the motion after it
    /// (in free motion exactly, as a shift of time), so every later event and peak time books
    /// it too. The rounding of separate events has independent signs, and each local estimate
    /// is already a generous multiple of its rounding.
    carried: f64,
    /// The largest |q'| the run has met (at its samples and events), m/s: a shift of time dt
    /// moves q by at most that times dt.
    speed: f64,
    /// The candidates for the largest and the smallest q ([`Top`]).
    tops: [Top; 2],
    flows: usize,
    evaluations: usize,
    unresolved: usize,
    /// True until the run's first state has been sampled.
    first: bool,
    /// While the column is held against a neighbour (a row's persistent contact): the linear
    /// form its flows follow instead of its mode's own.
    bond: Option<LinearForm>,
    /// Buffers of the scans (extrema found, intervals to search), kept from flow to flow.
    spare: (Vec<Point>, Vec<scan::Interval>),
    /// The last flow's box, which the next flow takes instead of an allocation of its own (a
    /// record has a flow per sample).
    spare_flow: Option<Box<Flow>>,
    /// The work integrals over the history's pieces as quadratic forms, kept from flow to flow
    /// (`work.rs`).
    work_forms: FormCache,
    /// The exact recurrence over a record's interval for the modes met, kept from flow to flow
    /// (`step.rs`).
    steps: StepCache,
    /// What the pieces between the history's samples take from the flow under way, once one of
    /// them has been integrated by kept forms ([`SampleBooks`]).
    sample_books: Option<SampleBooks>,
    /// The close approaches of q to a guard, in time order (`graze.rs`).
    approaches: Vec<Approach>,
    /// The largest and smallest q before each event, m.
    extremes: Vec<(f64, f64)>,
    /// The time of the last event (0 before the first), s.
    last_event: f64,
    /// Changes of q' still to make, in time order (the runs that measure a graze's effect).
    pub(super) kicks: Vec<Kick>,
}

/// What a run books for the estimate of its own error.
pub(crate) struct Books {
    /// The local estimate: the rounding where each result is computed, and the earlier events'
    /// carried.
    pub estimate: RoundingEstimate,
    /// The close approaches of q to a guard ([`Approach`]).
    pub approaches: Vec<Approach>,
    /// The largest and smallest q before each event, m.
    pub extremes: Vec<(f64, f64)>,
}

/// The rounding of a guard's level as the run compares q with it, m: the guard carries the
/// rounding of the constants it is made of, and q the rounding of its evaluation.
fn level_error(guard: &Guard, flow: &Flow) -> f64 {
    4.0 * f64::EPSILON * (guard.level.abs() + flow.equilibrium().abs())
}

/// A flow planned by [`Run::plan`]: its first guard crossing, if any, and the extrema of q the
/// search found on the way.
pub(crate) struct Planned {
    /// Boxed: a record's flow holds its Taylor coefficients (about 600 bytes), which moving
    /// the plan from the search to the commit copied several times.
    flow: Box<Flow>,
    found: Option<(Point, Guard)>,
    /// The flow's point at its end.
    finish: Point,
    extrema: Vec<Point>,
}

impl Planned {
    /// The flow.
    pub(crate) fn flow(&self) -> &Flow {
        &self.flow
    }

    /// Where the flow stops on its own: its guard crossing, or its end.
    pub(crate) fn stop(&self) -> f64 {
        self.found.map_or(self.flow.until, |(p, _)| p.t)
    }
}

impl<'a> ExactRun<'a> {
    /// A run of `automaton` from `initial` at t = 0 over [0, duration]; with `energy`, the
    /// energy books are kept.
    pub(crate) fn new(
        automaton: &'a Automaton,
        floor: &'a dyn FloorMotion,
        initial: InitialState,
        duration: f64,
        settings: &ExactSettings,
        history: History,
        energy: bool,
    ) -> Self {
        let recorder = Recorder::new(
            automaton,
            0.0,
            initial.q,
            initial.qdot,
            automaton.initial_mode(initial.q),
            history,
        );
        let mut recorder = if energy {
            recorder
        } else {
            recorder.without_energy_books()
        };
        let grid = OutputGrid::for_history(history, duration, settings.output_dt);
        // Room for the grid and for the two samples of each event (a guess: an eighth of the
        // grid, or 64 events).
        recorder.reserve(grid.remaining() + grid.remaining() / 8 + 128);
        ExactRun {
            automaton,
            floor,
            mode: automaton.initial_mode(initial.q),
            t: 0.0,
            t_lo: 0.0,
            q: Dd::exact(initial.q),
            v: Dd::exact(initial.qdot),
            energy,
            estimate: history == History::Sampled,
            recorder,
            grid,
            work: Work::default(),
            max_q: initial.q,
            min_q: initial.q,
            episode_peak: initial.q.abs(),
            event_errors: Vec::new(),
            carried: 0.0,
            speed: initial.qdot.abs(),
            tops: [
                Top::initial(1.0, initial.q, duration),
                Top::initial(-1.0, initial.q, duration),
            ],
            flows: 0,
            evaluations: 0,
            unresolved: 0,
            first: true,
            bond: None,
            spare: (Vec::new(), Vec::new()),
            spare_flow: None,
            work_forms: FormCache::default(),
            steps: StepCache::default(),
            sample_books: None,
            approaches: Vec::new(),
            extremes: Vec::new(),
            last_event: 0.0,
            kicks: Vec::new(),
        }
    }

    /// The solution booked up to `final_time`, and what the run booked for its estimate.
    pub(crate) fn finish(self, final_time: f64, started: Instant) -> (Solution, Books) {
        let stats = SolverStats {
            method: NAME.to_string(),
            steps: self.flows,
            error_test_failures: 0,
            nonlinear_iterations: 0,
            jacobian_evaluations: 0,
            crossing_retries: self.unresolved,
            rhs_evaluations: self.evaluations,
            wall_time_s: started.elapsed().as_secs_f64(),
        };
        let ((max_q, t_max_q), (min_q, t_min_q)) = (self.tops[0].errors(), self.tops[1].errors());
        let estimate = RoundingEstimate {
            event_time: self.event_errors,
            max_q,
            t_max_q,
            min_q,
            t_min_q,
            grazes: Vec::new(),
            uncertain_from: None,
        };
        let books = Books {
            estimate,
            approaches: self.approaches,
            extremes: self.extremes,
        };
        (self.recorder.finish(final_time, self.mode, stats), books)
    }

    fn failed(&self, t: f64, message: impl Into<String>) -> SolverError {
        SolverError::Failed {
            method: NAME.to_string(),
            t,
            message: message.into(),
        }
    }

    /// Runs to `end` or to overturning; the final time.
    pub(super) fn go(&mut self, end: f64) -> Result<f64, SolverError> {
        let mut budget = RunBudget::new();
        while let Some(planned) = self.plan(end, &mut budget)? {
            if let Some(&kick) = self.kicks.first() {
                if planned.stop() > kick.t {
                    // Re-anchored at the kick, q' changed there.
                    self.cut(planned, kick.t.max(self.t));
                    self.v = self.v + kick.dv;
                    self.kicks.remove(0);
                    continue;
                }
            }
            if !self.commit(planned, end, &mut budget)? {
                break;
            }
        }
        Ok(self.t)
    }

    /// The next flow from the current state, searched for its first guard crossing, but not yet
    /// taken: None in the terminal mode. A row of columns plans every column's flow and takes
    /// each up to its own stop or up to a contact between columns ([`Run::cut`]).
    pub(crate) fn plan(
        &mut self,
        end: f64,
        budget: &mut RunBudget,
    ) -> Result<Option<Planned>, SolverError> {
        let automaton = self.automaton;
        if self.mode == Mode::Overturned {
            return Ok(None);
        }
        let Some(linear) = self.bond.or_else(|| automaton.linear_form(self.mode)) else {
            return Ok(None);
        };
        let stretch = self.floor.closed_form(self.t);
        // NaN included: a closed form that does not end after t cannot be followed.
        if stretch.until.partial_cmp(&self.t) != Some(std::cmp::Ordering::Greater) {
            return Err(self.failed(
                self.t,
                format!(
                    "the floor motion's closed form at t = {} s ends at {} s, not after it",
                    self.t, stretch.until
                ),
            ));
        }
        // A record's interval: the exact recurrence over it, which the flow takes where it is
        // the whole interval (`Flow::new`).
        let step = match (stretch.shape, self.floor.sample_interval()) {
            (Shape::Polynomial { .. }, Some(interval)) => self.steps.serve(
                linear.stiffness,
                linear.damping,
                stretch.until - self.t,
                stretch.until,
                interval,
            ),
            _ => None,
        };
        let new = Flow::new(
            &linear,
            &stretch,
            self.t,
            self.t_lo,
            self.q,
            self.v,
            stretch.until.min(end),
            step,
        );
        let flow = match self.spare_flow.take() {
            Some(mut spare) => {
                *spare = new;
                spare
            }
            None => Box::new(new),
        };
        self.flows += 1;
        budget
            .step(self.t, self.flows)
            .map_err(|m| self.failed(self.t, m))?;
        // At most two guards per mode, kept on the stack.
        let slots = automaton.guards(self.mode);
        let mut buffer = [automaton.guard(self.mode, slots[0]); 2];
        for (guard, &slot) in buffer.iter_mut().zip(slots) {
            *guard = automaton.guard(self.mode, slot);
        }
        let guards = &buffer[..slots.len()];
        let mut watch = self.watch(guards);
        let start = flow.point(self.t);
        if self.first {
            // The run's first state is a sample.
            self.emit(&flow, self.t, true);
            self.first = false;
        }
        let found = scan::evaluate(&*flow, flow.until, &mut watch).and_then(|finish| {
            first_crossing(&*flow, start, finish, guards, &mut watch).map(|f| (f, finish))
        });
        self.evaluations += watch.evaluations;
        self.unresolved += watch.unresolved;
        // The search's buffer serves the next flow; the extrema go with the plan.
        self.spare.1 = std::mem::take(&mut watch.stack);
        let (found, finish) = match found {
            Ok(found) => found,
            Err(ScanError::NotFinite(t)) => {
                return Err(self.failed(
                    t,
                    format!(
                        "the closed-form state is not finite (floor acceleration {} m/s^2)",
                        self.floor.acceleration(t)
                    ),
                ))
            }
            Err(ScanError::TooMuchWork(t)) => {
                return Err(self.failed(
                    t,
                    format!(
                        "more than {} evaluations of one closed form: the run would not end in \
                         a useful time",
                        scan::MAX_EVALUATIONS
                    ),
                ))
            }
        };
        Ok(Some(Planned {
            flow,
            found,
            finish,
            extrema: watch.extrema,
        }))
    }

    /// Takes `planned` up to its stop: its guard crossing (the event booked, the reset applied)
    /// or its end. False when the run has reached `end`.
    pub(crate) fn commit(
        &mut self,
        planned: Planned,
        end: f64,
        budget: &mut RunBudget,
    ) -> Result<bool, SolverError> {
        let Planned {
            flow,
            found,
            finish,
            mut extrema,
        } = planned;
        let stop = found.map_or(flow.until, |(p, _)| p.t);
        for extremum in &extrema {
            self.approach(&flow, extremum);
            self.peak(&flow, extremum);
        }
        extrema.clear();
        self.spare.0 = extrema;
        self.emit(&flow, stop, true);
        let going = match found {
            Some((p, guard)) => {
                self.event(&flow, p, guard);
                budget.event(p.t).map_err(|m| self.failed(p.t, m))?;
                true
            }
            None => {
                self.advance_work(&flow, flow.until);
                let (q, v) = flow.state_at(&finish);
                self.q = q;
                self.v = v;
                self.t = flow.until;
                self.t_lo = 0.0;
                self.peak(&flow, &finish);
                self.t < end
            }
        };
        self.spare_flow = Some(flow);
        Ok(going)
    }

    /// Takes `planned` up to `t` (before its stop) and stays there, re-anchored at the state
    /// the flow reaches: where a contact between columns interrupts the column's own motion.
    pub(crate) fn cut(&mut self, planned: Planned, t: f64) {
        let Planned { flow, extrema, .. } = planned;
        for extremum in extrema.iter().filter(|p| p.t <= t) {
            self.peak(&flow, extremum);
        }
        self.emit(&flow, t, false);
        self.advance_work(&flow, t);
        let (q, v) = flow.state(t);
        self.q = q;
        self.v = v;
        self.t = t;
        self.t_lo = 0.0;
        self.peak(&flow, &flow.point(t));
    }

    /// Events booked so far.
    pub(crate) fn event_count(&self) -> usize {
        self.event_errors.len()
    }

    /// The run's time, mode, q and q' (q' to twice the precision).
    pub(crate) fn state(&self) -> (f64, Mode, f64, Dd) {
        (self.t, self.mode, self.q.value(), self.v)
    }

    /// A neighbour's impulse at the current time: q' becomes `after`, the mode stays; booked as
    /// an impact event, counted against `budget`. `time_error` is the error of the contact's
    /// time, s.
    pub(crate) fn impact(
        &mut self,
        after: Dd,
        time_error: f64,
        budget: &mut RunBudget,
    ) -> Result<(), SolverError> {
        // At the run's own time, with the rest of an event's crossing that lies between
        // doubles (as that event was booked), so that the impact is not booked before it.
        let (t, q) = (self.t + self.t_lo, self.q.value());
        self.event_errors.push(time_error);
        self.recorder.event(
            t,
            EventKind::Impact,
            self.mode,
            self.mode,
            q,
            self.v.value(),
            after.value(),
            self.floor.acceleration(t),
            self.work.input,
            self.work.damping,
        );
        self.v = after;
        self.work.start = None;
        budget.event(t).map_err(|m| self.failed(t, m))
    }

    /// The levels that matter in this mode's flows.
    fn watch(&mut self, guards: &[Guard]) -> Watch {
        let guard_up = guards
            .iter()
            .filter(|g| g.direction > 0.0)
            .map(|g| g.level)
            .fold(f64::INFINITY, f64::min);
        let guard_down = guards
            .iter()
            .filter(|g| g.direction < 0.0)
            .map(|g| g.level)
            .fold(f64::NEG_INFINITY, f64::max);
        let (max, min) = match self.mode {
            Mode::RockRight => (self.episode_peak.min(self.max_q), self.min_q),
            Mode::RockLeft => (self.max_q, (-self.episode_peak).max(self.min_q)),
            _ => (self.max_q, self.min_q),
        };
        let (extrema, stack) = std::mem::take(&mut self.spare);
        Watch {
            guard_up,
            guard_down,
            max,
            min,
            extrema,
            stack,
            evaluations: 0,
            unresolved: 0,
        }
    }

    /// Offers a state where q may be extremal to the recorder and to the peak trackers.
    fn peak(&mut self, flow: &Flow, p: &Point) {
        self.max_q = self.max_q.max(p.q);
        self.min_q = self.min_q.min(p.q);
        if self.estimate && self.tops.iter().any(|top| top.reaches(p.q)) {
            let (error, t_error) = self.peak_error(flow, p);
            let candidate = Candidate {
                t: p.t,
                q: p.q,
                error,
                t_error,
            };
            for top in &mut self.tops {
                if top.reaches(p.q) {
                    top.offer(candidate);
                }
            }
        }
        if matches!(self.mode, Mode::RockRight | Mode::RockLeft) {
            self.episode_peak = self.episode_peak.max(p.q.abs());
        }
        self.recorder.peak_candidate(p.t, p.q);
    }

    /// Books `p`, an extremum of q, where it comes close to a guard of the mode on its way back
    /// ([`Approach`]).
    fn approach(&mut self, flow: &Flow, p: &Point) {
        let automaton = self.automaton;
        for &slot in automaton.guards(self.mode) {
            let guard = automaton.guard(self.mode, slot);
            let margin = guard.overshoot(p.q);
            if guard.direction * p.acc < 0.0 && margin <= 0.0 && Approach::close(&guard, margin) {
                self.book_approach(flow, p, guard, margin, p.t);
            }
        }
    }

    /// Books an approach to `guard` whose hump, at `p` on `flow`, tops at `t`, `margin` beyond
    /// the guard.
    fn book_approach(&mut self, flow: &Flow, p: &Point, guard: Guard, margin: f64, t: f64) {
        let error = if self.estimate {
            self.peak_error(flow, p).0 + ESTIMATE_SAFETY * level_error(&guard, flow)
        } else {
            0.0
        };
        self.approaches.push(Approach {
            t,
            guard,
            margin,
            curvature: p.acc.abs(),
            jerk: p.jerk.abs(),
            error,
            events_before: self.extremes.len(),
            since: self.last_event,
            max_before: self.max_q,
            min_before: self.min_q,
        });
    }

    /// The error estimate of a peak at `p`: of its value (m) and of its time (s).
    fn peak_error(&self, flow: &Flow, p: &Point) -> (f64, f64) {
        let (error_q, error_v) = self.local_error(flow, p.t);
        let t_error = if p.acc != 0.0 {
            error_v / p.acc.abs()
        } else {
            0.0
        };
        // The earlier events' errors, carried as a shift of time of the free part of the motion
        // (the forced part keeps the floor's time): of the peak's time, and of its value by the
        // free part's speed times that shift (at a peak of q the forced part's speed; nothing in
        // free motion). The series form does not split the two: there the largest speed met.
        let free_speed = if flow.splits_free_motion() {
            p.free[1].abs()
        } else {
            self.speed
        };
        let t_error = t_error + 2.0 * rounding::ulp(p.t) + self.carried;
        let error_q = error_q
            + 4.0 * f64::EPSILON * (p.q.abs() + flow.equilibrium().abs())
            + free_speed.max(p.v.abs()) * self.carried;
        (error_q, t_error)
    }

    /// The rounding of the closed form at `t` in `flow`, with a safety factor, as an error of
    /// q (m) and of q' (m/s).
    fn local_error(&self, flow: &Flow, t: f64) -> (f64, f64) {
        let w = flow.stiffness().abs().sqrt();
        let x = ESTIMATE_SAFETY * flow.rounding(t);
        (x, w * x)
    }

    /// Books the grid's samples up to `until` (and at it when `inclusive`).
    fn emit(&mut self, flow: &Flow, until: f64, inclusive: bool) {
        while let Some(t) = self.grid.peek() {
            if t > until || (!inclusive && t == until) {
                break;
            }
            let (p, force) = match self.interval_point(flow, t) {
                Some(found) => found,
                None => flow.point_with_force(t),
            };
            self.advance_work_to(flow, &p, force, true);
            self.speed = self.speed.max(p.v.abs());
            self.recorder.sample(
                t,
                self.mode,
                p.q,
                p.v,
                self.floor.acceleration(t),
                self.work.input,
                self.work.damping,
            );
            self.grid.advance();
        }
    }

    /// The point at `t` inside a flow that is one whole interval of a record, by the exact
    /// recurrence over the time since the interval's start (a multiple of the grid's spacing, so
    /// that the recurrence is built once for each such offset, and kept); None where the flow
    /// is not such an interval or `t` is not at such an offset. Only where an interval holds at
    /// most [`OFFSETS_KEPT`] samples: a finer grid would need more recurrences than are kept
    /// (each built anew, at the cost of many samples), and there the series, computed once for
    /// the interval, serves its samples.
    fn interval_point(&mut self, flow: &Flow, t: f64) -> Option<(Point, [f64; 2])> {
        let (x, v, forcing) = flow.interval_data()?;
        let u = t - flow.anchor;
        let spacing = self.grid.spacing();
        // (An interval of length h holds fewer than h / spacing samples inside it; the grid's
        // rounding aside.)
        if flow.until - flow.anchor > (OFFSETS_KEPT as f64 + 1.0) * spacing * (1.0 + 1e-9) {
            return None;
        }
        let nominal = (u / spacing).round() * spacing;
        if nominal.is_nan() || nominal <= 0.0 {
            return None;
        }
        let step = self
            .steps
            .serve(flow.stiffness(), flow.damping(), u, t, nominal)?;
        let (x, v) = step.sample(x, v, forcing, u);
        Some(flow.point_from_state(t, x, v, forcing))
    }

    /// Integrates the input and damping power along `flow` up to `t`.
    fn advance_work(&mut self, flow: &Flow, t: f64) {
        if !self.energy || t <= self.work.t {
            return;
        }
        let (p, force) = flow.point_with_force(t);
        self.advance_work_to(flow, &p, force, false);
    }

    /// Integrates the input and damping power along `flow` up to the point `end` (with the
    /// forcing there): in pieces short against the flow's rates, each from the Taylor series of
    /// the motion about its end ([`Flow::work_integrals`]). `sample`: `end` is a sample of the
    /// history, so that a span of the grid's spacing will recur and its integrals are worth
    /// keeping as quadratic forms (`work.rs`).
    fn advance_work_to(&mut self, flow: &Flow, end: &Point, force: [f64; 2], sample: bool) {
        if !self.energy || (sample && self.sample_work(flow, end, force)) {
            return;
        }
        let from = self.work.t;
        let span = end.t - from;
        if span <= 0.0 {
            return;
        }
        let pieces = work_pieces(span, flow.rate());
        let h = span / pieces as f64;
        let spacing = self.grid.spacing();
        // Forms for a piece of the grid's spacing are built at the spacing itself (not at this
        // span, which differs from it by the rounding of the grid's times), so that they, and
        // the integrals they give, do not depend on which span came first.
        let nominal =
            (sample && rounding::near(span, spacing, end.t)).then(|| spacing / pieces as f64);
        let (a, mode) = (self.automaton, self.mode);
        let (mut force_work, mut square) = (0.0, 0.0);
        let mut start = self.work.start;
        let mut by_forms = false;
        for i in 1..=pieces {
            let ((fv, vv), integrands, forms) = if i == pieces {
                let last = end.t - (from + (i - 1) as f64 * h);
                self.piece_work(flow, end, force, last, nominal, start)
            } else {
                let (p, force) = flow.point_with_force(from + i as f64 * h);
                self.piece_work(flow, &p, force, h, nominal, start)
            };
            force_work += fv;
            square += vv;
            start = Some(integrands);
            by_forms = forms;
        }
        // The flow's forcing is f = -beta_flow a: the column's own beta, or a held cluster's.
        let beta_flow = self.bond.map_or(a.participation(mode), |f| f.participation);
        let floor_power = if beta_flow != 0.0 {
            -force_work / beta_flow
        } else {
            0.0
        };
        let factors = WorkFactors::of(a, mode, beta_flow);
        // The input power with the column's own beta (a held column's beta differs from its
        // cluster's).
        let input = match self.bond {
            None => factors.input(force_work),
            Some(_) => a.input_power(mode, 1.0, 1.0) * floor_power,
        };
        let damping = factors.damping * square;
        // A sample's piece, whole and by kept forms, of a lone column: the flow's next ones
        // take the short way.
        self.sample_books =
            (sample && pieces == 1 && by_forms && self.bond.is_none()).then(|| SampleBooks {
                flow: self.flows,
                forms: self.work_forms.last(),
                rate: flow.rate(),
                factors,
            });
        // (The column's own form only where it is held: a lone column's pieces do not need it.)
        let contact = match self
            .bond
            .and_then(|held| Some((held, a.linear_form(mode)?)))
        {
            Some((held, own)) => {
                // Me (q'' - q''_own) q' integrated: with q'' from the held form and q''_own
                // from the column's, (c - C) q'^2 + (k (q - e) - K (q - E)) q' + (beta - B) a q',
                // whose middle term is an exact differential.
                let me = a.generalised_mass();
                let q0 = flow.point(from).q;
                let potential = |q: f64| {
                    own.stiffness * (q - own.equilibrium).powi(2)
                        - held.stiffness * (q - held.equilibrium).powi(2)
                };
                me * ((own.damping - held.damping) * square
                    + 0.5 * (potential(end.q) - potential(q0))
                    + (own.participation - held.participation) * floor_power)
            }
            None => 0.0,
        };
        self.book_work(end.t, [input, damping, contact], start);
        if self.bond.is_some() {
            self.recorder.set_contact_work(self.work.contact);
        }
    }

    /// The integrals of f x' and of x'^2 over the piece of `flow` of length `h` that ends at
    /// `end`, and the integrands there: from the quadratic forms kept where they serve (with
    /// the integrands at the piece's `start`, for the sliver by which its length differs from
    /// theirs), from new ones of length `nominal` for a piece of the grid's spacing, and from
    /// the piece's own series otherwise.
    fn piece_work(
        &mut self,
        flow: &Flow,
        end: &Point,
        force: [f64; 2],
        h: f64,
        nominal: Option<f64>,
        start: Option<[f64; 2]>,
    ) -> ((f64, f64), [f64; 2], bool) {
        // The data at the end: as long as forms take where they serve, as long as the longest
        // polynomial's otherwise.
        let integrands = |data: &[f64]| [data[2] * data[1], data[1] * data[1]];
        match (self.work_forms.serve(flow, h, end.t, nominal), start) {
            (Some(forms), Some(start)) => {
                let data = flow.work_data::<{ work::FORM_LEN }>(end, force);
                (forms.integrals(&data, h, start), integrands(&data), true)
            }
            _ => {
                let data = flow.work_data::<{ flow::WORK_DATA }>(end, force);
                (flow.work_integrals(&data, h), integrands(&data), false)
            }
        }
    }

    /// The energy books up to the sample `end` of `flow` the short way ([`SampleBooks`]), where
    /// the general path would take the same steps: the flow's forms are kept and serve a piece
    /// of this span, which is whole (one piece), and the flow starts from the integrands at the
    /// last sample. False, with nothing booked, where it would not.
    fn sample_work(&mut self, flow: &Flow, end: &Point, force: [f64; 2]) -> bool {
        #[cfg(test)]
        if !tests::SHORT_WAY.get() {
            return false;
        }
        let (Some(books), Some(start)) = (self.sample_books, self.work.start) else {
            return false;
        };
        if books.flow != self.flows || self.bond.is_some() {
            return false;
        }
        let Some(forms) = self.work_forms.get(books.forms) else {
            return false;
        };
        let span = end.t - self.work.t;
        // (The general path's count of pieces, and the forms' test of a length.)
        let whole = work_pieces(span, books.rate) == 1;
        if !(span > 0.0 && whole && rounding::near(span, forms.length(), end.t)) {
            return false;
        }
        let data = flow.work_data::<{ work::FORM_LEN }>(end, force);
        let (force_work, square) = forms.integrals(&data, span, start);
        // The same sums as the general path's, from 0.
        let (force_work, square) = (0.0 + force_work, 0.0 + square);
        let factors = books.factors;
        self.book_work(
            end.t,
            [factors.input(force_work), factors.damping * square, 0.0],
            Some([data[2] * data[1], data[1] * data[1]]),
        );
        #[cfg(test)]
        tests::SHORT_PIECES.set(tests::SHORT_PIECES.get() + 1);
        true
    }

    /// Adds a piece's input, damping and contact work (J) to the books, which now reach `t`,
    /// with the integrands f x' and x'^2 there (`start`, for the next piece).
    fn book_work(&mut self, t: f64, [input, damping, contact]: [f64; 3], start: Option<[f64; 2]>) {
        self.work = Work {
            t,
            input: self.work.input + input,
            damping: self.work.damping + damping,
            contact: self.work.contact + contact,
            start,
        };
    }

    /// Holds the column against a neighbour (`Some`: its flows follow that linear form from
    /// the next plan on) or lets it go (`None`).
    pub(crate) fn set_bond(&mut self, bond: Option<LinearForm>) {
        if bond != self.bond {
            // The forcing changes here.
            self.work.start = None;
        }
        self.bond = bond;
    }

    /// The column's automaton.
    pub(crate) fn automaton(&self) -> &'a Automaton {
        self.automaton
    }

    /// The event at `p` through `guard`: booked, reset applied, mode changed.
    fn event(&mut self, flow: &Flow, p: Point, guard: Guard) {
        let automaton = self.automaton;
        // The part of q'' that turns q back towards the mode (none where it carries q on).
        let deceleration = -guard.direction * p.acc;
        let beyond = if guard.level == flow.equilibrium() {
            // The overturning point is the rocking mode's saddle, where q'' vanishes: a crossing
            // at speed v is as far from turning back as a hump that stops v/sqrt(|k|) short of
            // it (free motion keeps v^2 + k (q - q_eq)^2 there).
            Some((p.v.abs() / flow.stiffness().abs().sqrt(), p.t))
        } else {
            (deceleration > 0.0).then(|| {
                (
                    p.v * p.v / (2.0 * deceleration),
                    p.t + p.v.abs() / deceleration,
                )
            })
        };
        if let Some((beyond, top)) = beyond.filter(|(beyond, _)| Approach::close(&guard, *beyond)) {
            self.book_approach(flow, &p, guard, beyond, top);
        }
        self.extremes.push((self.max_q, self.min_q));
        self.last_event = p.t;
        if self.estimate {
            let (error_q, _) = self.local_error(flow, p.t);
            // The transverse error of q becomes an error of the time q reaches the guard.
            let crossing_time = graze::crossing_time_error(
                error_q + ESTIMATE_SAFETY * level_error(&guard, flow),
                p.v.abs(),
                -deceleration,
            ) + 2.0 * rounding::ulp(p.t);
            // The earlier events' shift of time.
            self.speed = self.speed.max(p.v.abs());
            self.event_errors.push(crossing_time + self.carried);
            self.carried = self.carried.hypot(crossing_time);
        }
        self.advance_work(flow, p.t);
        // The reset changes q' here.
        self.work.start = None;
        // The crossing lies between doubles: the rest of it, from q at the double found. Taken
        // into the next flow's anchor, it keeps the rounding of event times (biased to the side
        // beyond the guard) from adding up over a chain of events. (p is the flow's point at
        // p.t with q put on the guard: its q'' is the flow's there.)
        let (q_found, v_found) = flow.state_at_event(p.t);
        let rest = (Dd::exact(guard.level) - q_found).value() / v_found.value();
        // The search stops within a few ulps of the crossing; more would be no rest of it.
        let rest = if rest.abs() <= 16.0 * rounding::ulp(p.t) {
            rest
        } else {
            0.0
        };
        let before = v_found + p.acc * rest;
        let after = automaton.reset_velocity_twice(guard.kind, before);
        let (qdot_before, qdot_after) = (before.value(), after.value());
        let from = self.mode;
        let t_event = p.t + rest;
        self.recorder.event(
            t_event,
            guard.kind,
            from,
            guard.to,
            guard.level,
            qdot_before,
            qdot_after,
            self.floor.acceleration(t_event),
            self.work.input,
            self.work.damping,
        );
        self.mode = guard.to;
        self.t = p.t;
        self.t_lo = rest;
        self.q = Dd::exact(guard.level);
        self.v = after;
        if guard.to != Mode::PreUplift {
            self.episode_peak = guard.level.abs();
        }
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use crate::model::{Model, Overrides};

    thread_local! {
        /// Whether a run on this thread may take the short way to a sample's energy books.
        pub(super) static SHORT_WAY: Cell<bool> = const { Cell::new(true) };
        /// The pieces booked the short way on this thread.
        pub(super) static SHORT_PIECES: Cell<usize> = const { Cell::new(0) };
    }

    /// A whole run of the exact method, its history, events, energy books and error estimates,
    /// as text that tells every double apart (wall time left out).
    fn run_text(file: &str, duration: f64) -> String {
        run_text_with(file, duration, &[])
    }

    /// As [`run_text`], with `settings` ("section.key=value") over the file's.
    fn run_text_with(file: &str, duration: f64, settings: &[&str]) -> String {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../models")
            .join(file);
        let overrides = Overrides {
            method: Some(super::NAME.to_string()),
            duration: Some(duration),
            settings: settings
                .iter()
                .map(|text| crate::model::Setting::parse(text).expect("a setting"))
                .collect(),
            ..Overrides::default()
        };
        let model = Model::load(&path, &overrides).expect("the model loads");
        let mut solution = crate::simulate::simulate(&model).expect("it solves");
        solution.stats.wall_time_s = 0.0;
        format!("{solution:?}")
    }

    /// The functions compiled twice (`double_double::fused`) give the same run to the bit with
    /// the processor's fused multiply-add and without it: the paper's example (the oscillator
    /// form, rocking, the sine's phase) and 8 s of El Centro (the series form of a record).
    #[test]
    fn a_run_is_the_same_with_and_without_the_processors_fma() {
        let runs = || {
            [
                run_text("ichinose1986.toml", 6.0),
                run_text("elcentro1940.toml", 8.0),
            ]
        };
        let fused = runs();
        crate::base::double_double::set_fma_in_use(false);
        let library = runs();
        crate::base::double_double::set_fma_in_use(true);
        for (fused, library) in fused.iter().zip(&library) {
            assert!(fused == library, "the runs differ");
        }
    }

    /// The short way to a sample's energy books (`Run::sample_work`) gives the run the general
    /// path gives, to the bit (history, energy books, events and estimates): the paper's example
    /// (the oscillator form, before uplift and rocking, its ramp's cubic and its sine), the same
    /// with a ramp of 0.42 s (whose flow ends on a sample, and the sine's flow follows without an
    /// event: its first sample must not take the ramp's forms), a sine pulse and 8 s of El Centro (a record's linear pieces). Most of the paper's
    /// pieces take it.
    #[test]
    fn the_short_way_to_a_samples_books_is_the_general_path_to_the_bit() {
        for (file, duration, settings, least) in [
            ("ichinose1986.toml", 6.0, &[][..], 1_000),
            (
                "ichinose1986.toml",
                6.0,
                &["excitation.ramp=0.42"][..],
                1_000,
            ),
            ("sine-pulse.toml", 6.8, &[][..], 1_000),
            ("elcentro1940.toml", 8.0, &[][..], 1),
        ] {
            SHORT_PIECES.set(0);
            let short = run_text_with(file, duration, settings);
            let taken = SHORT_PIECES.get();
            SHORT_WAY.set(false);
            let general = run_text_with(file, duration, settings);
            SHORT_WAY.set(true);
            assert!(taken >= least, "{file}: {taken} pieces the short way");
            assert!(short == general, "{file}: the runs differ");
        }
    }
}
