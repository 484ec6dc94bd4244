//! The exact solution: eq. 16 solved in closed form within each mode, events found as roots of
//! closed-form functions that cannot be missed, and the state carried across re-anchors in
//! twice the working precision.
//!
//! Within a mode eq. 16 is linear with constant coefficients ([`Automaton::linear_form`]), so
//! the state moves by the mode's 2x2 matrix exponential plus the response to the floor, which is
//! closed form for every kind of motion the model has ([`crate::floor::ClosedForm`]):
//! nothing at all for free motion, a steady state for a sinusoid, and for polynomial pieces (a
//! record's linear pieces between samples, the ramp's cubic, the Ricker wavelet's Taylor pieces
//! with their stated remainder) the Taylor series of the solution, summed to rounding
//! (`flow.rs`); across a record's whole interval between two samples, the exact piecewise-linear
//! recurrence, a 2x4 matrix built once for each mode to twice the precision (`step.rs`). The
//! automaton is the only model: the solver reads each mode's coefficients, its
//! guards and its resets from it.
//!
//! Events (`scan.rs`): the first guard crossing of each flow is bracketed between consecutive
//! extrema of q, located with certified bounds on q'' and q''', and refined by Newton steps to
//! a few ulps of t; q is then put on the guard and the reset applied to q'.
//!
//! Precision: a flow is summed from its anchor, so free motion and a sine need no steps; the
//! state is carried from flow to flow (a record's samples) compensated, as hi + lo. At an event
//! the crossing's time is kept beyond its double (the next flow's anchor is hi + lo), and the
//! state there is summed to twice the precision (while rocking, from the free motion's growing
//! and decaying exponentials, whose terms do not cancel when the body barely lifts off); the
//! mode's coefficients are the constants rounded once from twice the precision; and a sine's
//! phase is reduced to a fraction of a turn in twice the precision. The solver
//! books a first-order estimate of its own error. Locally, within each flow: the rounding of
//! every term summed and of every phase formed since the flow's anchor (growing with the flow's
//! rates), and the stated error of the floor's closed form, turned into an error of each event
//! time (the error of q over |q'|) and of each peak (of q, and of its time, the error of q'
//! over |q''|). Carried: the local errors of the earlier events' times, added as a random walk,
//! are added to every later event's and peak's time, as the shift of time they are in free
//! motion (and to a peak's value, times the speed of the free part of the motion there, or the
//! largest speed met where the flow does not split it off). And measured: the spread of two
//! runs whose constants and initial state are moved by a few ulps (see [`solve`]), which
//! carries a relative error of a few ulps in the model's constants through the whole run,
//! grazing events and their amplification included.
//!
//! Energy books: the input and damping work are integrated along each flow on pieces short
//! against the flow's rates (one per sample of the history), each from the Taylor series of the
//! motion and of the forcing about its end, whose products are integrated term by term to
//! rounding; the energy residual therefore checks these integrals and the resets, not the
//! solution. The series are linear in the state and the forcing at the piece's end, so over
//! pieces of the grid's spacing the integrals are quadratic forms of those, whose matrices are
//! built once for each mode and kind of forcing and kept (`work.rs`); after a flow's first
//! sample, its pieces take those forms and the factors that turn them into work without
//! searching for them again (`SampleBooks`), to the same bits.

pub(crate) mod equation;
pub(crate) mod flow;
pub(crate) mod graze;
pub(crate) mod kept;
pub(crate) mod oscillator;
pub(crate) mod rounding;
pub(crate) mod scan;
pub(crate) mod step;
pub(crate) mod work;

use std::time::Instant;

use serde::Serialize;

use super::budget::RunBudget;
use crate::base::double_double::DoubleDouble as Dd;
use crate::floor::{FloorMotion, Shape};
use crate::integrate::solution::{Recorder, RoundingEstimate, Solution, SolverStats};
use crate::integrate::{History, InitialState, OutputGrid, SolverError};
use crate::physics::automaton::{Automaton, EventKind, Guard, LinearForm, Mode};

use flow::{Flow, Point};
pub use graze::SHADOW_RUNS;
use graze::{Approach, Kick, ESTIMATE_SAFETY};
use scan::{first_crossing, ScanError, Watch};
use step::StepCache;
use work::FormCache;

/// The method's name in statistics, tables and model files.
pub const NAME: &str = "exact";

/// Settings of the exact solver: it has no tolerance, only the spacing of its history.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ExactSettings {
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}

/// Solves the automaton exactly from `initial` over [0, duration].
///
/// A run that keeps its history also estimates its own error: to the rounding of each event
/// time and peak where it is computed, it adds the spread of [`SHADOW_RUNS`] runs of the same
/// model whose constants and initial state are moved by their own uncertainty in pseudo-random
/// directions (`Automaton::nudged`), times a safety factor. This is discrete stochastic
/// arithmetic in the manner of CESTAC (Vignes 1993): the spread measures how far rounding of
/// that size carries each result, including through ill-conditioned (grazing) events.
pub fn solve(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &ExactSettings,
    history: History,
) -> Result<Solution, SolverError> {
    let started = Instant::now();
    // A run without a history keeps no energy books (Recorder::without_energy_books).
    let energy = history == History::Sampled;
    let run = || {
        solve_once(
            automaton,
            floor,
            initial,
            duration,
            settings,
            history,
            energy,
            Vec::new(),
        )
    };
    if history != History::Sampled {
        let (mut solution, _) = run()?;
        solution.stats.wall_time_s = started.elapsed().as_secs_f64();
        return Ok(solution);
    }
    let size = automaton.constants_uncertainty();
    let shadow = |pattern: usize| {
        let nudged = automaton.nudged(pattern as u64 + 1, size);
        let moved = InitialState {
            q: initial.q
                * (1.0 + size * crate::physics::automaton::nudge_sign(pattern as u64 + 1, 100)),
            qdot: initial.qdot
                * (1.0 + size * crate::physics::automaton::nudge_sign(pattern as u64 + 1, 101)),
        };
        solve_once(
            &nudged,
            floor,
            moved,
            duration,
            settings,
            History::PeaksOnly,
            false,
            Vec::new(),
        )
    };
    // The shadow runs are independent of the run: with the `parallel` feature they run beside
    // it on another core (the same results, in less time on a machine with a core to spare).
    let (main, (first, second)) = beside(run, || (shadow(0), shadow(1)));
    let (mut solution, books) = main?;
    let shadows = [first?, second?];
    let mut estimate = books.estimate;
    let mut diverged: Option<usize> = None;
    for (shadow, _) in &shadows {
        if let Some(index) = spread_into(&mut estimate, &solution, shadow, duration) {
            diverged = Some(diverged.map_or(index, |other| other.min(index)));
        }
    }
    let diverged = diverged.map(|index| {
        let (max, min) = index
            .checked_sub(1)
            .map_or((initial.q, initial.q), |before| books.extremes[before]);
        (index, max, min)
    });
    let kicks = graze::assess(
        &mut estimate,
        &solution,
        &books.approaches,
        [&shadows[0].1.approaches, &shadows[1].1.approaches],
        diverged,
        automaton,
        floor,
        duration,
    );
    // The small episodes of the grazes: their effect on the rest of the run, measured by two
    // runs whose q' is kicked by each episode's bound, one way and the other.
    if !kicks.is_empty() {
        for sign in [1.0, -1.0] {
            let kicked = kicks
                .iter()
                .map(|kick| Kick {
                    dv: sign * kick.dv,
                    ..*kick
                })
                .collect();
            let (other, _) = solve_once(
                automaton,
                floor,
                initial,
                duration,
                settings,
                History::PeaksOnly,
                false,
                kicked,
            )?;
            spread_peaks(&mut estimate, &solution, &other);
        }
    }
    solution.rounding = Some(estimate);
    solution.stats.wall_time_s = started.elapsed().as_secs_f64();
    Ok(solution)
}

/// `main()` on this thread, and `aside()` beside it on the thread pool: the caller's thread
/// starts the main run at once instead of waiting for a pool thread to wake (a join from
/// outside the pool would hand both to the pool and wait). The shadow runs keep no history
/// and are much shorter than the main run, so one pool thread takes both.
#[cfg(feature = "parallel")]
fn beside<A, B: Send>(main: impl FnOnce() -> A, aside: impl FnOnce() -> B + Send) -> (A, B) {
    let mut other = None;
    let first = rayon::in_place_scope(|scope| {
        scope.spawn(|_| other = Some(aside()));
        main()
    });
    (
        first,
        other.expect("a scope ends after the work it spawned"),
    )
}

/// `main()`, then `aside()`.
#[cfg(not(feature = "parallel"))]
fn beside<A, B>(main: impl FnOnce() -> A, aside: impl FnOnce() -> B) -> (A, B) {
    (main(), aside())
}

/// Most samples of the history inside one of a record's intervals for which the run keeps the
/// exact recurrence over their offsets ([`Run::interval_point`]): with the interval's own and
/// those of three modes, [`step::KEPT`] recurrences.
const OFFSETS_KEPT: usize = 3;

/// Adds to `estimate` the safety factor times the distance of the shadow run from the run.
/// From the first event whose kind differs (or that one run lacks) on, the event sequence itself
/// is not robust to rounding, and the estimate is the whole duration; returns that event's
/// index (the run's count of events where the shadow run logs more).
fn spread_into(
    estimate: &mut RoundingEstimate,
    run: &Solution,
    shadow: &Solution,
    duration: f64,
) -> Option<usize> {
    let mut robust = true;
    let mut diverged = None;
    for (i, error) in estimate.event_time.iter_mut().enumerate() {
        let other = shadow.events.get(i);
        robust = robust
            && other.is_some_and(|o| o.kind == run.events[i].kind && o.to == run.events[i].to);
        *error = if robust {
            error.max(0.0) + ESTIMATE_SAFETY * (run.events[i].t - other.map_or(0.0, |o| o.t)).abs()
        } else {
            diverged = diverged.or(Some(i));
            duration
        };
    }
    if robust && shadow.events.len() > run.events.len() {
        diverged = Some(run.events.len());
    }
    spread_peaks(estimate, run, shadow);
    diverged
}

/// Adds to the estimates of the peaks the safety factor times their distance in `shadow` (a run
/// of the same model moved within its rounding).
fn spread_peaks(estimate: &mut RoundingEstimate, run: &Solution, shadow: &Solution) {
    let spread = |a: f64, b: f64| ESTIMATE_SAFETY * (a - b).abs();
    estimate.max_q += spread(run.max_q.value, shadow.max_q.value);
    estimate.t_max_q += spread(run.max_q.t, shadow.max_q.t);
    estimate.min_q += spread(run.min_q.value, shadow.min_q.value);
    estimate.t_min_q += spread(run.min_q.t, shadow.min_q.t);
}

/// One run; with `energy`, the energy books are kept; q' changed by each of `kicks` on the way.
/// Returns what it books for its own estimate.
#[allow(clippy::too_many_arguments)]
fn solve_once(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &ExactSettings,
    history: History,
    energy: bool,
    kicks: Vec<Kick>,
) -> Result<(Solution, Books), SolverError> {
    let started = Instant::now();
    let mut run = Run::new(
        automaton, floor, initial, duration, settings, history, energy,
    );
    run.kicks = kicks;
    let final_time = run.go(duration)?;
    Ok(run.finish(final_time, started))
}

/// The integrals of the input and damping power up to `t`, J.
#[derive(Debug, Default, Clone, Copy)]
struct Work {
    t: f64,
    input: f64,
    damping: f64,
    /// The work of a neighbour's contact force while the column is held against it (a row's
    /// persistent contact), J.
    contact: f64,
    /// The integrands f x' and x'^2 at t, of the flow that reached it; None where the motion
    /// may jump at t (an event's reset, a neighbour's impulse, a change of the linear form).
    start: Option<[f64; 2]>,
}

/// A candidate for the largest or smallest q: its time and value, with their estimates.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    t: f64,
    q: f64,
    error: f64,
    t_error: f64,
}

/// Share of |q| below the extreme so far within which a candidate's errors are estimated to
/// see whether it is told apart from the extreme: far beyond any estimate.
const CLOSE_SHARE: f64 = 1e-6;

/// The candidates for one extreme of q (`sign` 1 the largest, -1 the smallest) that the run
/// cannot tell apart: the extreme so far (the first of equal values, as the recorder keeps it),
/// and every other whose value is within the two estimates of it. Which of two such humps is
/// the extreme is not decided by the run's arithmetic, and the time of the extreme may be
/// either's.
#[derive(Debug)]
struct Top {
    sign: f64,
    best: Candidate,
    close: Vec<Candidate>,
}

impl Top {
    /// The initial state as the extreme so far: its q is the file's number rounded to a double
    /// (half an ulp), and its time t = 0, which a root of q' found in other arithmetic puts
    /// within rounding of it: an ulp of the run's duration.
    fn initial(sign: f64, q0: f64, duration: f64) -> Self {
        let best = Candidate {
            t: 0.0,
            q: q0,
            error: 0.5 * rounding::ulp(q0),
            t_error: rounding::ulp(duration),
        };
        Top {
            sign,
            best,
            close: Vec::new(),
        }
    }

    /// Whether `q` is beyond the extreme so far or near enough to it to be a candidate.
    fn reaches(&self, q: f64) -> bool {
        let b = &self.best;
        self.sign * (q - b.q) > -(b.error + CLOSE_SHARE * b.q.abs())
    }

    /// Takes `c`: as the extreme where it is beyond the one so far, as a close one where the
    /// estimates do not tell the two apart.
    fn offer(&mut self, c: Candidate) {
        let (s, b) = (self.sign, self.best);
        if s * (c.q - b.q) > 0.0 {
            self.close.push(b);
            self.close
                .retain(|o| s * (o.q - c.q) + o.error + c.error >= 0.0);
            self.best = c;
        } else if s * (c.q - b.q) + c.error + b.error >= 0.0 {
            self.close.push(c);
        }
    }

    /// The estimates of the extreme's value and time (m, s): its own, or those of any candidate
    /// it cannot be told from, with the time between the two.
    fn errors(&self) -> (f64, f64) {
        let b = &self.best;
        self.close.iter().fold((b.error, b.t_error), |(e, te), o| {
            (e.max(o.error), te.max((o.t - b.t).abs() + o.t_error))
        })
    }
}

pub(crate) struct Run<'a> {
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
    kicks: Vec<Kick>,
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

/// The energy books of the pieces between a flow's samples, shortened. After the first such
/// piece, the rest of the flow's recur with the same forms and the same factors, so that each
/// takes the forms' two products and the factors, by the same arithmetic as the general path
/// ([`Run::advance_work_to`]) and to the same bits, without searching for them again.
#[derive(Debug, Clone, Copy)]
struct SampleBooks {
    /// The flow's number ([`Run::flows`] when it was planned; a flow keeps one mode, an event
    /// ends it).
    flow: usize,
    /// The kept forms ([`FormCache::last`]).
    forms: (usize, usize),
    /// The flow's rate (the pieces a span is cut into follow from it, [`work_pieces`]).
    rate: f64,
    factors: WorkFactors,
}

/// What turns a lone column's integrals of f x' and of x'^2 over a piece into its input and
/// damping work, J.
#[derive(Debug, Clone, Copy)]
struct WorkFactors {
    /// The input power -beta Me a q' is Me times f q' (f = -beta a): this times the integral of
    /// f x'; none where beta is 0 (no input).
    input: Option<f64>,
    /// The damping power's factor on q'^2.
    damping: f64,
}

impl WorkFactors {
    /// The factors of `mode`'s flows, whose forcing is f = -`beta` a.
    fn of(automaton: &Automaton, mode: Mode, beta: f64) -> Self {
        WorkFactors {
            input: (beta != 0.0).then(|| automaton.input_power(mode, 1.0, 1.0) / -beta),
            damping: automaton.damping_power(mode, 1.0),
        }
    }

    /// The input work of a piece whose integral of f x' is `force_work`.
    fn input(&self, force_work: f64) -> f64 {
        self.input.map_or(0.0, |factor| factor * force_work)
    }
}

/// The pieces a span of the energy books is cut into: each short against the flow's `rate`.
fn work_pieces(span: f64, rate: f64) -> usize {
    (span * rate / flow::WORK_REACH).ceil().clamp(1.0, 1e7) as usize
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

impl<'a> Run<'a> {
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
        Run {
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
    fn go(&mut self, end: f64) -> Result<f64, SolverError> {
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
