//! Adaptive integration of the automaton with diffsol (BDF, ESDIRK34, TR-BDF2; Tsit45).
//!
//! How events are found. After every step the driver splits the step at the root of q' inside it
//! (a sign change of q' between its ends, located on diffsol's dense output; it is also a peak of
//! q, so max q and min q are located to solver accuracy). On each piece q is monotone, so a guard
//! can be crossed at most once there, and only in the direction q moves: a landing only moving
//! back towards the floor, an uplift or an overturn only moving away from it. The first guard so
//! crossed is located on the dense output by regula falsi. diffsol's own root finder is not used:
//! it reports any sign change of a guard function, whichever way the state moves.
//!
//! A step whose dense output cannot resolve its crossing is taken again, four times shorter, from
//! its exact start: that is a crossing placed where q' already points back into the mode, or a
//! piece that starts beyond the guard, or a step that ends beyond a guard with no crossing found
//! (q turned twice). This happens at a grazing uplift, where the excursion beyond s_n is shorter
//! than the step and a low-order interpolant puts q back inside before q' turns; taking such a
//! crossing at face value logged hundreds of uplifts and landings within 1e-12 s.
//!
//! At an event the solver is moved back to the event time, q is placed exactly on the guard, the
//! angular-momentum reset is applied to q', and the method restarts in the new mode. A state that
//! starts on a guard and moves back into its mode does not trigger it; a state on a guard moving
//! across it does, at once. Breakpoints of the floor motion are stop times, so that no step
//! straddles a kink of a(t), and the solver's clock is put onto every stop it reaches (see
//! `STOP_TOLERANCE`). `RunBudget` caps steps and events, so that every run ends.

use std::cell::Cell;
use std::time::Instant;

use diffsol::{
    NalgebraLU, NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverStopReason,
    Vector as _,
};

use super::budget::RunBudget;
use serde::Serialize;

use crate::integrate::SolverError;
use crate::physics::automaton::{Automaton, Guard, Mode};

type Result<T> = std::result::Result<T, SolverError>;
use crate::floor::FloorMotion;
use crate::integrate::solution::{Recorder, Solution, SolverStats};
use crate::integrate::{History, InitialState, OutputGrid};

type Matrix = NalgebraMat<f64>;
type LinearSolver = NalgebraLU<f64>;
type Vector = diffsol::NalgebraVec<f64>;

/// Number of state components: q and q'.
const NSTATES: usize = 2;
/// Number of integrated outputs: the input and damping work, per unit Me.
const NOUT: usize = 2;
/// A stop time counts as reached when the solver lands this close to it (relative to max(1, t)).
/// diffsol's own test (100 ulps of t + h) misses landings a little further off, after which it
/// takes a sliver step of 1e-15 s that ends the run with "step size too small".
pub(crate) const STOP_TOLERANCE: f64 = 1e-12;
/// Drift of the solver's clock from a stop time, in ulps of the stop, that is left alone.
pub(crate) const SNAP_ULPS: f64 = 8.0;
/// Retakes of one step whose crossing its dense output could not resolve before giving up.
const MAX_CROSSING_RETRIES: usize = 60;

/// The implicit methods diffsol offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AdaptiveMethod {
    /// Variable-order BDF.
    Bdf,
    /// ESDIRK 3(4), a singly diagonally implicit Runge-Kutta method.
    Esdirk34,
    /// TR-BDF2, trapezoidal rule then BDF2.
    TrBdf2,
    /// Tsitouras 5(4), explicit: the model is not stiff (its frequencies are those of the body),
    /// and a fifth-order one-step method keeps its order between the samples of a record.
    Tsit45,
}

impl AdaptiveMethod {
    /// The method's model-file spelling, e.g. "tr-bdf2".
    pub fn name(self) -> &'static str {
        match self {
            AdaptiveMethod::Bdf => "bdf",
            AdaptiveMethod::Esdirk34 => "esdirk34",
            AdaptiveMethod::TrBdf2 => "tr-bdf2",
            AdaptiveMethod::Tsit45 => "tsit45",
        }
    }

    /// The method spelled `name` in a model file.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "bdf" => Some(AdaptiveMethod::Bdf),
            "esdirk34" => Some(AdaptiveMethod::Esdirk34),
            "tr-bdf2" => Some(AdaptiveMethod::TrBdf2),
            "tsit45" => Some(AdaptiveMethod::Tsit45),
            _ => None,
        }
    }
}

/// Settings of an adaptive run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct AdaptiveSettings {
    /// The method.
    pub method: AdaptiveMethod,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}

/// Integrates the automaton from `initial` over [0, duration].
pub fn solve(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &AdaptiveSettings,
    history: History,
) -> Result<Solution> {
    let started = Instant::now();
    let mode = Cell::new(automaton.initial_mode(initial.q));
    let rhs_evaluations = Cell::new(0usize);
    let me = automaton.generalised_mass();

    let solver_error = |t: f64, e: &dyn std::fmt::Display| SolverError::Failed {
        method: settings.method.name().to_string(),
        t,
        message: e.to_string(),
    };

    // The floor acceleration is asked for several times at one t (right-hand side, Jacobian,
    // energy integrands); evaluate it once.
    let floor_cache = Cell::new((f64::NAN, 0.0));
    let floor_acc = |t: f64| {
        let (t_cached, a_cached) = floor_cache.get();
        if t == t_cached {
            a_cached
        } else {
            let a = floor.acceleration(t);
            floor_cache.set((t, a));
            a
        }
    };

    let mut problem = OdeBuilder::<Matrix>::new()
        .t0(0.0)
        .rtol(settings.rtol)
        .atol([settings.atol; NSTATES])
        .rhs_implicit(
            |x, _p, t, y| {
                rhs_evaluations.set(rhs_evaluations.get() + 1);
                let a = floor_acc(t);
                y[0] = x[1];
                y[1] = automaton.acceleration(mode.get(), x[0], x[1], a);
            },
            |_x, _p, _t, v, y| {
                let (d_q, d_qdot) = automaton.acceleration_jacobian(mode.get());
                y[0] = v[1];
                y[1] = d_q * v[0] + d_qdot * v[1];
            },
        )
        .init(
            |_p, _t, y| {
                y[0] = initial.q;
                y[1] = initial.qdot;
            },
            NSTATES,
        )
        // The energy integrals ride along as quadratures of the accepted steps: they are not
        // part of the implicit solve and do not steer the step size.
        .out_implicit(
            |x, _p, t, y| energy_integrands(automaton, mode.get(), floor_acc(t), x, y),
            |x, _p, t, v, y| {
                let m = mode.get();
                y[0] = automaton.input_power(m, v[1], floor_acc(t)) / me;
                y[1] = 2.0 * automaton.damping(m) * x[1] * v[1] / me;
            },
            NOUT,
        )
        .integrate_out(true)
        .build()
        .map_err(|e| solver_error(0.0, &e))?;
    // diffsol counts Newton failures over the solver's whole life, not per step. Every mode
    // switch leaves it a stale Jacobian and so costs one failure, which would end any run with
    // more than 50 events. A Newton solve that truly cannot converge still ends the run: the
    // step is cut by 0.3 per failure until it falls below the minimum step.
    problem.ode_options.max_nonlinear_solver_failures = usize::MAX;
    // diffsol's smallest step (1e-13 s) is longer than a trivially short run (1e-20 s is valid
    // input: the state barely moves); such a run may take steps down to 1e-3 of its length.
    problem.ode_options.min_timestep = problem.ode_options.min_timestep.min(1e-3 * duration);

    let driver = Driver {
        automaton,
        floor,
        mode: &mode,
        duration,
        settings,
        history,
    };
    let (recorder, final_time, mut stats) = match settings.method {
        AdaptiveMethod::Bdf => driver.run(
            problem
                .bdf::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::Esdirk34 => driver.run(
            problem
                .esdirk34::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::TrBdf2 => driver.run(
            problem
                .tr_bdf2::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::Tsit45 => driver.run(problem.tsit45().map_err(|e| solver_error(0.0, &e))?),
    }?;
    stats.rhs_evaluations = rhs_evaluations.get();
    stats.wall_time_s = started.elapsed().as_secs_f64();
    Ok(recorder.finish(final_time, mode.get(), stats))
}

/// The first-order system (q, q').
fn right_hand_side(automaton: &Automaton, mode: Mode, floor_acc: f64, x: &[f64], y: &mut [f64]) {
    y[0] = x[1];
    y[1] = automaton.acceleration(mode, x[0], x[1], floor_acc);
}

/// Integrands of the energy books, per unit Me: input power and damping power.
fn energy_integrands(automaton: &Automaton, mode: Mode, floor_acc: f64, x: &[f64], y: &mut [f64]) {
    let me = automaton.generalised_mass();
    y[0] = automaton.input_power(mode, x[1], floor_acc) / me;
    y[1] = automaton.damping_power(mode, x[1]) / me;
}

/// The event loop, written once for every diffsol method.
struct Driver<'d> {
    automaton: &'d Automaton,
    floor: &'d dyn FloorMotion,
    mode: &'d Cell<Mode>,
    duration: f64,
    settings: &'d AdaptiveSettings,
    history: History,
}

/// The exact state at the start of a step, kept so that a step can be taken again.
struct StepStart {
    t: f64,
    y: [f64; NSTATES],
    work: [f64; NOUT],
}

/// The history's grid and the buffers its samples are interpolated into, allocated once.
struct Sampler {
    grid: OutputGrid,
    y: Vector,
    work: Vector,
}

/// What one accepted step holds.
enum Crossing {
    /// No guard crossed; a root of q' (a peak of q) inside, if any.
    None { peak: Option<(f64, f64)> },
    /// The first guard crossed, at `t`, with q' pointing across it; a peak of q before it, if any.
    At {
        t: f64,
        guard: Guard,
        peak: Option<(f64, f64)>,
    },
    /// The dense output puts a crossing where q' points back into the mode (a grazing excursion
    /// shorter than the step): the step must be taken again, shorter.
    Unresolved,
}

/// True when `t` is at the stop time `stop` for the driver.
pub(crate) fn at_stop(t: f64, stop: f64) -> bool {
    (t - stop).abs() <= STOP_TOLERANCE * stop.abs().max(1.0)
}

/// Moves the solver's clock onto a stop time it reached to within [`STOP_TOLERANCE`]. Left
/// alone, its time drifts from the stop times by the rounding of every step (7e-13 s after
/// 33 s of a record), until a stop is missed by more than diffsol's own tolerance; and a
/// landing just short of a stop leaves it a sliver step. The state is not changed: it is that
/// of a time within 1e-12 s.
pub(crate) fn snap_to_stop<'a, Eqn, S>(solver: &mut S, stop: f64, h_taken: f64)
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

impl<'d> Driver<'d> {
    fn error(&self, t: f64, e: impl std::fmt::Display) -> SolverError {
        SolverError::Failed {
            method: self.settings.method.name().to_string(),
            t,
            message: e.to_string(),
        }
    }

    fn run<'a, Eqn, S>(&self, mut solver: S) -> Result<(Recorder<'d>, f64, SolverStats)>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let automaton = self.automaton;
        let end = self.duration;
        let mut budget = RunBudget::new();
        let mut crossing_retries = 0usize;
        // Retakes of the current step; an accepted step starts the count again.
        let mut retries_in_a_row = 0usize;

        // Stop times: the floor motion's breakpoints inside (0, end), then the end.
        let mut stops: Vec<f64> = self
            .floor
            .breakpoints()
            .iter()
            .copied()
            .filter(|&b| b > 0.0 && !at_stop(b, end) && b < end)
            .collect();
        stops.push(end);
        let mut stop_index = 0;
        // diffsol takes a stop time within 100 ulps of its first step for the current time (and
        // refuses it): a run far shorter than that first step (1e-20 s) starts with a step of its
        // whole length instead. Longer runs are unchanged: their first step is cut to the stop.
        if solver.state().h > stops[0] {
            *solver.state_mut().h = stops[0];
        }
        solver
            .set_stop_time(stops[0])
            .map_err(|e| self.error(0.0, e))?;

        let y0 = solver.state().y.clone();
        let mut recorder =
            Recorder::new(automaton, 0.0, y0[0], y0[1], self.mode.get(), self.history);
        let mut sampler = Sampler {
            grid: OutputGrid::for_history(self.history, end, self.settings.output_dt),
            y: y0.clone(),
            work: solver.state().g.clone(),
        };
        self.emit(&solver, &mut recorder, &mut sampler, 0.0, true)?;

        // A start on a guard, moving across it, is an event at t = 0.
        if let Some(guard) = automaton.crossed_guard(self.mode.get(), y0[0], y0[1]) {
            if self.apply_event(&mut solver, &mut recorder, 0.0, guard, false)? {
                return Ok((recorder, 0.0, self.stats(&solver, crossing_retries)));
            }
            budget.event(0.0).map_err(|m| self.error(0.0, m))?;
        }

        loop {
            let start = Self::step_start(&solver);
            let reason = solver.step().map_err(|e| self.error(start.t, e))?;
            let step_end = solver.state().t;
            let stop = stops[stop_index];
            budget
                .step(step_end, solver.get_statistics().number_of_steps)
                .map_err(|m| self.error(step_end, m))?;
            if step_end > stop && !at_stop(step_end, stop) {
                // Never expected: a run that went past its stop time would never end.
                return Err(self.error(step_end, format!("stepped past the stop time {stop} s")));
            }

            match self.find_crossing(&solver, &start, step_end)? {
                Crossing::Unresolved => {
                    crossing_retries += 1;
                    retries_in_a_row += 1;
                    if retries_in_a_row == MAX_CROSSING_RETRIES {
                        return Err(self.error(
                            start.t,
                            format!(
                                "a guard crossing could not be resolved: {MAX_CROSSING_RETRIES} ever shorter steps \
                                 from t = {} s all put q back inside its mode while q' points outward",
                                start.t
                            ),
                        ));
                    }
                    self.restart_from(&mut solver, &start, 0.25 * (step_end - start.t))?;
                    solver
                        .set_stop_time(stop)
                        .map_err(|e| self.error(start.t, e))?;
                    continue;
                }
                Crossing::At { t, guard, peak } => {
                    retries_in_a_row = 0;
                    if let Some((t_peak, q_peak)) = peak {
                        recorder.peak_candidate(t_peak, q_peak);
                    }
                    self.emit(&solver, &mut recorder, &mut sampler, t, false)?;
                    if self.apply_event(&mut solver, &mut recorder, t, guard, true)? {
                        return Ok((recorder, t, self.stats(&solver, crossing_retries)));
                    }
                    budget.event(t).map_err(|m| self.error(t, m))?;
                    if at_stop(t, stop) {
                        if stop_index + 1 == stops.len() {
                            return Ok((recorder, t, self.stats(&solver, crossing_retries)));
                        }
                        stop_index += 1;
                    }
                    // Moving the state back out of a step that had reached the stop time leaves
                    // the solver without one: set it again, or the run would go past it.
                    solver
                        .set_stop_time(stops[stop_index])
                        .map_err(|e| self.error(t, e))?;
                }
                Crossing::None { peak } => {
                    retries_in_a_row = 0;
                    if let Some((t_peak, q_peak)) = peak {
                        recorder.peak_candidate(t_peak, q_peak);
                    }
                    self.emit(&solver, &mut recorder, &mut sampler, step_end, true)?;
                    if matches!(reason, OdeSolverStopReason::TstopReached)
                        || at_stop(step_end, stop)
                    {
                        snap_to_stop(&mut solver, stop, step_end - start.t);
                        let now = solver.state().t;
                        if self.floor.jumps_at(stop) {
                            // The floor jumps here: restart the method from the state, with
                            // the derivative of the new floor value, as at an event. BDF's
                            // history across the jump would otherwise ask for steps below the
                            // minimum at tight tolerances.
                            let y = [solver.state().y[0], solver.state().y[1]];
                            let floor_acc = self.floor.acceleration(stop);
                            self.set_state(&mut solver, self.mode.get(), now, y, floor_acc);
                        }
                        // A grid time at the stop, if the step ended just short of it.
                        self.emit(&solver, &mut recorder, &mut sampler, now, true)?;
                        if stop_index + 1 == stops.len() {
                            recorder.peak_candidate(now, solver.state().y[0]);
                            return Ok((recorder, now, self.stats(&solver, crossing_retries)));
                        }
                        stop_index += 1;
                        solver
                            .set_stop_time(stops[stop_index])
                            .map_err(|e| self.error(now, e))?;
                    }
                }
            }
        }
    }

    fn step_start<'a, Eqn, S>(solver: &S) -> StepStart
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let state = solver.state();
        StepStart {
            t: state.t,
            y: [state.y[0], state.y[1]],
            work: [state.g[0], state.g[1]],
        }
    }

    /// Looks for the first guard the step [start, t1] crossed. Between roots of q' the top
    /// displacement is monotone, so the step is split at the root of q' (a sign change of q'
    /// between its ends), and on each monotone piece only the guards crossed in the direction q
    /// moves there are candidates: a landing can only be met moving back towards the floor, an
    /// uplift or an overturn only moving away from it. A candidate whose crossing the dense
    /// output places where q' already points back (or at the very start of a piece) was not
    /// resolved by the step, and neither was a step that ends beyond a guard without a crossing.
    fn find_crossing<'a, Eqn, S>(&self, solver: &S, start: &StepStart, t1: f64) -> Result<Crossing>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let automaton = self.automaton;
        let mode = self.mode.get();
        let end_state = self.state_at(solver, t1)?;
        let (qdot0, qdot1) = (start.y[1], end_state[1]);

        let mut peak = None;
        // Pieces of monotone q: (from, q at from, to, direction of motion).
        let mut pieces = [(start.t, start.y[0], t1, 0.0); 2];
        let count = if qdot0 * qdot1 < 0.0 {
            let t_peak = self.locate(solver, start.t, t1, |y| y[1])?;
            let q_peak = self.state_at(solver, t_peak)?[0];
            peak = Some((t_peak, q_peak));
            pieces[0] = (start.t, start.y[0], t_peak, qdot0.signum());
            pieces[1] = (t_peak, q_peak, t1, qdot1.signum());
            2
        } else {
            let direction = if qdot1 != 0.0 { qdot1 } else { qdot0 };
            pieces[0].3 = if direction == 0.0 {
                0.0
            } else {
                direction.signum()
            };
            1
        };

        for &(from, q_from, to, direction) in &pieces[..count] {
            for &slot in automaton.guards(mode) {
                let guard = automaton.guard(mode, slot);
                if guard.direction != direction {
                    continue;
                }
                let q_to = if to == t1 {
                    end_state[0]
                } else {
                    self.state_at(solver, to)?[0]
                };
                if guard.overshoot(q_to) <= 0.0 {
                    continue;
                }
                if guard.overshoot(q_from) >= 0.0 {
                    return Ok(Crossing::Unresolved);
                }
                let t = self.locate(solver, from, to, |y| guard.overshoot(y[0]))?;
                let qdot = self.state_at(solver, t)?[1];
                if guard.direction * qdot <= 0.0 {
                    return Ok(Crossing::Unresolved);
                }
                return Ok(Crossing::At {
                    t,
                    guard,
                    peak: peak.filter(|&(t_peak, _)| t_peak < t),
                });
            }
        }
        // The state must end inside its mode; if not, q turned more than once in the step.
        if automaton
            .guards(mode)
            .iter()
            .any(|&slot| automaton.guard(mode, slot).overshoot(end_state[0]) > 0.0)
        {
            return Ok(Crossing::Unresolved);
        }
        Ok(Crossing::None { peak })
    }

    /// Puts the solver back at the exact start of a step, to take it again with step size `h`.
    fn restart_from<'a, Eqn, S>(&self, solver: &mut S, start: &StepStart, h: f64) -> Result<()>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let floor_acc = self.floor.acceleration(start.t);
        self.set_state(solver, self.mode.get(), start.t, start.y, floor_acc);
        let state = solver.state_mut();
        for (i, value) in start.work.into_iter().enumerate() {
            state.g[i] = value;
        }
        *state.h = h;
        Ok(())
    }

    /// The state (q, q') at `t` inside the current step, from the dense output.
    fn state_at<'a, Eqn, S>(&self, solver: &S, t: f64) -> Result<[f64; 2]>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        if t == solver.state().t {
            let y = &solver.state().y;
            return Ok([y[0], y[1]]);
        }
        let y = solver.interpolate(t).map_err(|e| self.error(t, e))?;
        Ok([y[0], y[1]])
    }

    /// Samples the history at every grid time up to `until` (inclusive when `inclusive`).
    fn emit<'a, Eqn, S>(
        &self,
        solver: &S,
        recorder: &mut Recorder<'d>,
        sampler: &mut Sampler,
        until: f64,
        inclusive: bool,
    ) -> Result<()>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let me = self.automaton.generalised_mass();
        let Sampler { grid, y, work } = sampler;
        while let Some(t) = grid.peek() {
            if t > until || (!inclusive && t == until) {
                break;
            }
            // The state itself serves a grid time within the stop tolerance of it: after the
            // clock was moved onto a stop, the solver cannot interpolate until its next step.
            if at_stop(t, solver.state().t) {
                y.copy_from(solver.state().y);
                work.copy_from(solver.state().g);
            } else {
                solver
                    .interpolate_inplace(t, y)
                    .map_err(|e| self.error(t, e))?;
                solver
                    .interpolate_out_inplace(t, work)
                    .map_err(|e| self.error(t, e))?;
            }
            recorder.sample(
                t,
                self.mode.get(),
                y[0],
                y[1],
                self.floor.acceleration(t),
                me * work[0],
                me * work[1],
            );
            grid.advance();
        }
        Ok(())
    }

    /// Finds the time in [lo, hi] at which `f` of the dense-output state passes from the sign it
    /// has at `lo` to the sign it has at `hi` ([`crate::integrate::sign_change::locate`]).
    fn locate<'a, Eqn, S>(
        &self,
        solver: &S,
        lo: f64,
        hi: f64,
        f: impl Fn([f64; 2]) -> f64,
    ) -> Result<f64>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        crate::integrate::sign_change::locate(lo, hi, |t| Ok(f(self.state_at(solver, t)?)))
    }

    /// Moves the solver to `t`, books the event, applies the reset and switches the mode.
    /// Returns true when the new mode is terminal.
    fn apply_event<'a, Eqn, S>(
        &self,
        solver: &mut S,
        recorder: &mut Recorder<'d>,
        t: f64,
        guard: Guard,
        move_back: bool,
    ) -> Result<bool>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let automaton = self.automaton;
        let me = automaton.generalised_mass();
        if move_back {
            solver.state_mut_back(t).map_err(|e| self.error(t, e))?;
        }
        let mut guard = guard;
        // A reset can leave the state on a guard of the new mode moving across it only in
        // degenerate grazing cases; follow such a chain, but never forever.
        for _ in 0..4 {
            let from = self.mode.get();
            let y = solver.state().y.clone();
            let work = solver.state().g.clone();
            let qdot_before = y[1];
            // Place q exactly on the guard: the event was located to solver accuracy.
            let q = guard.level;
            let qdot_after = automaton.reset_velocity(guard.kind, qdot_before);
            let floor_acc = self.floor.acceleration(t);
            recorder.event(
                t,
                guard.kind,
                from,
                guard.to,
                q,
                qdot_before,
                qdot_after,
                floor_acc,
                me * work[0],
                me * work[1],
            );
            self.mode.set(guard.to);
            if guard.to == Mode::Overturned {
                return Ok(true);
            }
            self.set_state(solver, guard.to, t, [q, qdot_after], floor_acc);
            match automaton.crossed_guard(guard.to, q, qdot_after) {
                Some(next) => guard = next,
                None => return Ok(false),
            }
        }
        Err(self.error(t, "endless chain of events at one instant"))
    }

    /// Sets the solver's time and state, with derivatives consistent with `mode`, from which the
    /// method restarts (the work integrals are left as they are).
    fn set_state<'a, Eqn, S>(
        &self,
        solver: &mut S,
        mode: Mode,
        t: f64,
        x: [f64; NSTATES],
        floor_acc: f64,
    ) where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let mut dy = [0.0; NSTATES];
        right_hand_side(self.automaton, mode, floor_acc, &x, &mut dy);
        let mut dg = [0.0; NOUT];
        energy_integrands(self.automaton, mode, floor_acc, &x, &mut dg);
        let state = solver.state_mut();
        *state.t = t;
        for i in 0..NSTATES {
            state.y[i] = x[i];
            state.dy[i] = dy[i];
        }
        for (i, value) in dg.into_iter().enumerate() {
            state.dg[i] = value;
        }
    }

    fn stats<'a, Eqn, S>(&self, solver: &S, crossing_retries: usize) -> SolverStats
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let s = solver.get_statistics();
        SolverStats {
            method: self.settings.method.name().to_string(),
            steps: s.number_of_steps,
            error_test_failures: s.number_of_error_test_failures,
            nonlinear_iterations: s.number_of_nonlinear_solver_iterations,
            jacobian_evaluations: s.number_of_linear_solver_setups,
            crossing_retries,
            rhs_evaluations: 0,
            wall_time_s: 0.0,
        }
    }
}
