//! The event loop of every diffsol run: a hybrid body (one column, a row of columns) stepped by
//! any diffsol method, its events located on the dense output of each step and applied there.
//!
//! The loop owns what every body shares: the stop times (the floor motion's breakpoints, then
//! the end), the clock put onto every stop it reaches (see [`STOP_TOLERANCE`]), the restart of
//! the method at a jump of the floor, the step that is taken again four times shorter from its
//! exact start when the body cannot place a crossing on its dense output, the move back to an
//! event and the restart from the state the body leaves there, the sampled history's grid, and
//! the cap on steps. The body ([`EventBody`]) says what its guards are and where the first is
//! crossed in a step, what happens at an event, and what it records.

use std::marker::PhantomData;

use diffsol::{OdeEquations, OdeSolverMethod, OdeSolverStopReason, Vector as _};

use super::budget::RunBudget;
use crate::floor::FloorMotion;
use crate::integrate::{History, OutputGrid, SolverError};

type Result<T> = std::result::Result<T, SolverError>;
type Vector = diffsol::NalgebraVec<f64>;

/// A stop time counts as reached when the solver lands this close to it (relative to max(1, t)).
/// diffsol's own test (100 ulps of t + h) misses landings a little further off, after which it
/// takes a sliver step of 1e-15 s that ends the run with "step size too small".
pub(crate) const STOP_TOLERANCE: f64 = 1e-12;
/// Drift of the solver's clock from a stop time, in ulps of the stop, that is left alone.
pub(crate) const SNAP_ULPS: f64 = 8.0;
/// Retakes of one step whose crossing its dense output could not resolve before giving up.
const MAX_CROSSING_RETRIES: usize = 60;

/// The exact state at the start of a step, kept so that a step can be taken again.
pub(crate) struct StepStart {
    /// Time, s.
    pub t: f64,
    /// The state.
    pub y: Vec<f64>,
    /// The integrated outputs.
    pub g: Vec<f64>,
}

/// The step just taken, as a body sees it when it looks for its events.
pub(crate) trait DenseOutput {
    /// The state at `t` within the step (the solver's own state at its end).
    fn state_at(&self, t: f64) -> Result<Vec<f64>>;
}

/// What a body finds in a step.
pub(crate) enum Found<E> {
    /// No event.
    None,
    /// The first event, at `.0`.
    At(f64, E),
    /// The dense output cannot place a crossing: the step is taken again, shorter.
    Unresolved,
}

/// What a body does at an event.
pub(crate) enum Outcome {
    /// The run ends here.
    Stop,
    /// Nothing changed: the method goes on as it is.
    Continue,
    /// The method restarts from this state, in the body's new configuration.
    Restart(Vec<f64>),
}

/// A hybrid body the loop integrates: its equations are diffsol's; the rest is here.
pub(crate) trait EventBody {
    /// An event the body locates.
    type Event: Copy;

    /// The derivatives of the state `y` and of the integrated outputs, in the body's current
    /// configuration, with the floor's acceleration at `t`.
    fn derivatives(&self, t: f64, y: &[f64], dy: &mut [f64], dg: &mut [f64]);

    /// Looks for the first event of the step from `start` to `t1`; `grid` holds the history's
    /// times not yet sampled.
    fn find_event(
        &mut self,
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
        grid: &OutputGrid,
    ) -> Result<Found<Self::Event>>;

    /// Books what the accepted stretch [start, `until`] of the step holds (its peaks).
    fn book_step(&mut self, dense: &dyn DenseOutput, start: &StepStart, until: f64) -> Result<()>;

    /// Applies `event` (None: the start of the run) at `t` to the state `y` with integrated
    /// outputs `g`, then whatever else the new state asks for at the same instant.
    fn apply(
        &mut self,
        t: f64,
        y: &[f64],
        g: &[f64],
        event: Option<Self::Event>,
    ) -> Result<Outcome>;

    /// Records the state at the history's time `t`.
    fn sample(&mut self, t: f64, y: &[f64], g: &[f64]) -> Result<()>;

    /// Records the state at the end of the run (the state there may be a peak).
    fn finish(&mut self, t: f64, y: &[f64], g: &[f64]);
}

/// How a run ended.
pub(crate) struct Finish {
    /// The time it ended, s.
    pub t: f64,
    /// diffsol's counts.
    pub statistics: diffsol::ode_solver::OdeSolverStatistics,
    /// Steps taken again because their crossing was not resolved.
    pub crossing_retries: usize,
}

/// What the loop needs to know of the run.
pub(crate) struct LoopSetup<'r> {
    /// The method's name, for the messages.
    pub method: &'r str,
    /// The floor motion: its breakpoints are stop times.
    pub floor: &'r dyn FloorMotion,
    /// The floor's vertical motion, if any: its breakpoints are stop times too.
    pub vertical: Option<&'r dyn FloorMotion>,
    /// The run is over [0, duration].
    pub duration: f64,
    /// Which history is kept.
    pub history: History,
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}

/// True when `t` is at the stop time `stop` for the loop.
pub(crate) fn at_stop(t: f64, stop: f64) -> bool {
    (t - stop).abs() <= STOP_TOLERANCE * stop.abs().max(1.0)
}

/// Moves the solver's clock onto a stop time it reached to within [`STOP_TOLERANCE`]. Left
/// alone, its time drifts from the stop times by the rounding of every step (7e-13 s after
/// 33 s of a record), until a stop is missed by more than diffsol's own tolerance; and a
/// landing just short of a stop leaves it a sliver step. The state is not changed: it is that
/// of a time within 1e-12 s.
fn snap_to_stop<'a, Eqn, S>(solver: &mut S, stop: f64, h_taken: f64)
where
    Eqn: OdeEquations<T = f64, V = Vector> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    // A step shortened to a sliver to hit the stop would start the next stretch from it.
    let sliver = solver.state().h < 1e-3 * h_taken;
    // A few ulps of drift are left alone: moving the clock makes BDF restart at order 1.
    let drift = (solver.state().t - stop).abs();
    if !sliver && drift <= SNAP_ULPS * f64::EPSILON * stop.abs() {
        return;
    }
    let state = solver.state_mut();
    *state.t = stop;
    if sliver {
        *state.h = h_taken;
    }
}

/// The solver seen through [`DenseOutput`].
struct Dense<'s, 'a, Eqn, S> {
    solver: &'s S,
    method: &'s str,
    equations: PhantomData<&'a Eqn>,
}

impl<'a, Eqn, S> DenseOutput for Dense<'_, 'a, Eqn, S>
where
    Eqn: OdeEquations<T = f64, V = Vector> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    fn state_at(&self, t: f64) -> Result<Vec<f64>> {
        if t == self.solver.state().t {
            return Ok(values(self.solver.state().y));
        }
        let y = self
            .solver
            .interpolate(t)
            .map_err(|e| failed(self.method, t, e))?;
        Ok(values(&y))
    }
}

fn values(v: &Vector) -> Vec<f64> {
    (0..v.len()).map(|i| v[i]).collect()
}

fn failed(method: &str, t: f64, message: impl std::fmt::Display) -> SolverError {
    SolverError::Failed {
        method: method.to_string(),
        t,
        message: message.to_string(),
    }
}

/// Integrates `body` with `solver` from the solver's time (0 for a whole run) to run.duration.
pub(crate) fn run<'a, Eqn, S, B>(run: &LoopSetup<'_>, body: &mut B, mut solver: S) -> Result<Finish>
where
    Eqn: OdeEquations<T = f64, V = Vector> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
    B: EventBody,
{
    let method = run.method;
    let error = |t: f64, e: &dyn std::fmt::Display| failed(method, t, e);
    let end = run.duration;
    let budget = RunBudget::new();
    let mut crossing_retries = 0usize;
    // Retakes of the current step; an accepted step starts the count again.
    let mut retries_in_a_row = 0usize;
    let finish = |t: f64, solver: &S, crossing_retries: usize| Finish {
        t,
        statistics: solver.get_statistics().clone(),
        crossing_retries,
    };

    // The run starts where the solver starts (0, or where an earlier stretch of the body's
    // motion handed over).
    let begin = solver.state().t;
    // Stop times: the floor motions' breakpoints inside (begin, end), then the end.
    let vertical = run.vertical.map_or(&[][..], |v| v.breakpoints());
    let mut stops: Vec<f64> = run
        .floor
        .breakpoints()
        .iter()
        .chain(vertical)
        .copied()
        .filter(|&b| b > begin && !at_stop(b, end) && b < end)
        .collect();
    if !vertical.is_empty() {
        stops.sort_by(f64::total_cmp);
        stops.dedup();
    }
    stops.push(end);
    let mut stop_index = 0;
    // diffsol takes a stop time within 100 ulps of its first step for the current time (and
    // refuses it): a run far shorter than that first step (1e-20 s) starts with a step of its
    // whole length instead. Longer runs are unchanged: their first step is cut to the stop.
    if solver.state().h > stops[0] - begin {
        *solver.state_mut().h = stops[0] - begin;
    }
    solver
        .set_stop_time(stops[0])
        .map_err(|e| error(begin, &e))?;

    let mut grid = OutputGrid::for_history(run.history, end, run.output_dt);
    let mut sampler = Sampler {
        y: solver.state().y.clone(),
        g: solver.state().g.clone(),
    };
    sampler.emit(run, body, &solver, &mut grid, begin, true)?;

    // A start on a guard, moving across it, is an event at the start.
    let (y0, g0) = (values(solver.state().y), values(solver.state().g));
    match body.apply(begin, &y0, &g0, None)? {
        Outcome::Stop => return Ok(finish(begin, &solver, crossing_retries)),
        Outcome::Continue => {}
        Outcome::Restart(y) => set_state(body, &mut solver, begin, &y, begin),
    }

    loop {
        let start = StepStart {
            t: solver.state().t,
            y: values(solver.state().y),
            g: values(solver.state().g),
        };
        let reason = solver.step().map_err(|e| error(start.t, &e))?;
        let step_end = solver.state().t;
        let stop = stops[stop_index];
        budget
            .step(step_end, solver.get_statistics().number_of_steps)
            .map_err(|m| error(step_end, &m))?;
        if step_end > stop && !at_stop(step_end, stop) {
            // Never expected: a run that went past its stop time would never end.
            return Err(error(
                step_end,
                &format!("stepped past the stop time {stop} s"),
            ));
        }

        let dense = Dense {
            solver: &solver,
            method,
            equations: PhantomData,
        };
        match body.find_event(&dense, &start, step_end, &grid)? {
            Found::Unresolved => {
                crossing_retries += 1;
                retries_in_a_row += 1;
                if retries_in_a_row == MAX_CROSSING_RETRIES {
                    return Err(error(
                        start.t,
                        &format!(
                            "an event could not be resolved: {MAX_CROSSING_RETRIES} ever shorter \
                             steps from t = {} s all left its crossing where the dense output \
                             could not place it",
                            start.t
                        ),
                    ));
                }
                // Back to the exact start of the step, to take it again four times shorter.
                set_state(body, &mut solver, start.t, &start.y, start.t);
                let state = solver.state_mut();
                for (i, value) in start.g.iter().enumerate() {
                    state.g[i] = *value;
                }
                *state.h = 0.25 * (step_end - start.t);
                solver.set_stop_time(stop).map_err(|e| error(start.t, &e))?;
            }
            Found::At(t, event) => {
                retries_in_a_row = 0;
                body.book_step(&dense, &start, t)?;
                sampler.emit(run, body, &solver, &mut grid, t, false)?;
                solver.state_mut_back(t).map_err(|e| error(t, &e))?;
                let (y, g) = (values(solver.state().y), values(solver.state().g));
                match body.apply(t, &y, &g, Some(event))? {
                    Outcome::Stop => return Ok(finish(t, &solver, crossing_retries)),
                    Outcome::Continue => {}
                    Outcome::Restart(y) => set_state(body, &mut solver, t, &y, t),
                }
                if at_stop(t, stop) {
                    if stop_index + 1 == stops.len() {
                        sampler.emit(run, body, &solver, &mut grid, t, true)?;
                        let (y, g) = (values(solver.state().y), values(solver.state().g));
                        body.finish(t, &y, &g);
                        return Ok(finish(t, &solver, crossing_retries));
                    }
                    stop_index += 1;
                }
                // Moving the state back out of a step that had reached the stop time leaves
                // the solver without one: set it again, or the run would go past it.
                solver
                    .set_stop_time(stops[stop_index])
                    .map_err(|e| error(t, &e))?;
            }
            Found::None => {
                retries_in_a_row = 0;
                body.book_step(&dense, &start, step_end)?;
                sampler.emit(run, body, &solver, &mut grid, step_end, true)?;
                if matches!(reason, OdeSolverStopReason::TstopReached) || at_stop(step_end, stop) {
                    snap_to_stop(&mut solver, stop, step_end - start.t);
                    let now = solver.state().t;
                    if run.floor.jumps_at(stop) || run.vertical.is_some_and(|v| v.jumps_at(stop)) {
                        // The floor jumps here: restart the method from the state, with the
                        // derivative of the new floor value, as at an event. BDF's history
                        // across the jump would otherwise ask for steps below the minimum at
                        // tight tolerances.
                        let y = values(solver.state().y);
                        set_state(body, &mut solver, now, &y, stop);
                    }
                    // A grid time at the stop, if the step ended just short of it.
                    sampler.emit(run, body, &solver, &mut grid, now, true)?;
                    if stop_index + 1 == stops.len() {
                        let (y, g) = (values(solver.state().y), values(solver.state().g));
                        body.finish(now, &y, &g);
                        return Ok(finish(now, &solver, crossing_retries));
                    }
                    stop_index += 1;
                    solver
                        .set_stop_time(stops[stop_index])
                        .map_err(|e| error(now, &e))?;
                }
            }
        }
    }
}

/// Sets the solver's time to `t` and its state to `y`, with the derivatives of the body's
/// current configuration and the floor's acceleration at `floor_t`, from which the method
/// restarts (the integrated outputs are left as they are).
fn set_state<'a, Eqn, S, B>(body: &B, solver: &mut S, t: f64, y: &[f64], floor_t: f64)
where
    Eqn: OdeEquations<T = f64, V = Vector> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
    B: EventBody,
{
    let mut dy = vec![0.0; y.len()];
    let mut dg = vec![0.0; solver.state().g.len()];
    body.derivatives(floor_t, y, &mut dy, &mut dg);
    let state = solver.state_mut();
    *state.t = t;
    for i in 0..y.len() {
        state.y[i] = y[i];
        state.dy[i] = dy[i];
    }
    for (i, value) in dg.into_iter().enumerate() {
        state.dg[i] = value;
    }
}

/// The buffers the history's samples are interpolated into, allocated once.
struct Sampler {
    y: Vector,
    g: Vector,
}

impl Sampler {
    /// Samples the history at every grid time up to `until` (inclusive when `inclusive`).
    fn emit<'a, Eqn, S, B>(
        &mut self,
        run: &LoopSetup<'_>,
        body: &mut B,
        solver: &S,
        grid: &mut OutputGrid,
        until: f64,
        inclusive: bool,
    ) -> Result<()>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
        B: EventBody,
    {
        while let Some(t) = grid.peek() {
            if t > until || (!inclusive && t == until) {
                break;
            }
            // The state itself serves a grid time within the stop tolerance of it: after the
            // clock was moved onto a stop, the solver cannot interpolate until its next step.
            if at_stop(t, solver.state().t) {
                self.y.copy_from(solver.state().y);
                self.g.copy_from(solver.state().g);
            } else {
                solver
                    .interpolate_inplace(t, &mut self.y)
                    .map_err(|e| failed(run.method, t, e))?;
                solver
                    .interpolate_out_inplace(t, &mut self.g)
                    .map_err(|e| failed(run.method, t, e))?;
            }
            body.sample(t, &values(&self.y), &values(&self.g))?;
            grid.advance();
        }
        Ok(())
    }
}
