//! Adaptive integration of the automaton with diffsol (BDF, ESDIRK34, TR-BDF2; Tsit45).
//!
//! How events are found. diffsol's root finding watches the active mode's two guards; a root is
//! always an event, after which the state is changed (and diffsol restarts its root search).
//! After every step the driver also looks for a sign change of q' over the step; a root of q' is
//! located on diffsol's dense output, and it is both a peak of q (so max q and min q are located
//! to solver accuracy) and a check point: between two roots of q', q is monotone, so a guard
//! crossed and re-crossed inside one step leaves q beyond the guard at the root of q' between the
//! two crossings, and the crossing is then located on the dense output. The state at the end of
//! every step is checked against the guards too.
//!
//! At an event the solver is moved back to the event time, q is placed exactly on the guard, the
//! angular-momentum reset is applied to q', and the method restarts in the new mode. A state that
//! starts on a guard and moves back into its mode does not trigger it (a zero guard value at the
//! start of a step is not a sign change); a state on a guard moving across it does, at once.
//! Breakpoints of the floor motion are stop times, so that no step straddles a kink of a(t).

use std::cell::Cell;
use std::time::Instant;

use diffsol::{
    NalgebraLU, NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverStopReason,
    Vector as _,
};
use serde::Serialize;

use crate::automaton::{Automaton, Guard, Mode};
use crate::error::{Error, Result};
use crate::excitation::FloorMotion;
use crate::solution::{Recorder, Solution, SolverStats};
use crate::solver::{InitialState, OutputGrid};

type Matrix = NalgebraMat<f64>;
type LinearSolver = NalgebraLU<f64>;
type Vector = diffsol::NalgebraVec<f64>;

/// Number of state components: q and q'.
const NSTATES: usize = 2;
/// Number of integrated outputs: the input and damping work, per unit Me.
const NOUT: usize = 2;
/// Number of root functions: the active mode's two guards.
const NROOTS: usize = 2;

/// The implicit methods diffsol offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AdaptiveMethod {
    Bdf,
    Esdirk34,
    TrBdf2,
    /// Tsitouras 5(4), explicit: the model is not stiff (its frequencies are those of the body),
    /// and a fifth-order one-step method keeps its order between the samples of a record.
    Tsit45,
}

impl AdaptiveMethod {
    pub fn name(self) -> &'static str {
        match self {
            AdaptiveMethod::Bdf => "bdf",
            AdaptiveMethod::Esdirk34 => "esdirk34",
            AdaptiveMethod::TrBdf2 => "tr-bdf2",
            AdaptiveMethod::Tsit45 => "tsit45",
        }
    }

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
    pub method: AdaptiveMethod,
    pub rtol: f64,
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
) -> Result<Solution> {
    let started = Instant::now();
    let mode = Cell::new(automaton.initial_mode(initial.q));
    let rhs_evaluations = Cell::new(0usize);
    let me = automaton.generalised_mass();

    let solver_error = |t: f64, e: &dyn std::fmt::Display| Error::Solver {
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
        .root(
            |x, _p, _t, y| {
                let m = mode.get();
                let slots = automaton.guards(m);
                for (i, value) in y.iter_mut().enumerate().take(NROOTS) {
                    // Unused slots (the overturned mode has no guards) never change sign.
                    *value = slots
                        .get(i)
                        .map_or(1.0, |&slot| automaton.guard(m, slot).overshoot(x[0]));
                }
            },
            NROOTS,
        )
        .build()
        .map_err(|e| solver_error(0.0, &e))?;
    // diffsol counts Newton failures over the solver's whole life, not per step. Every mode
    // switch leaves it a stale Jacobian and so costs one failure, which would end any run with
    // more than 50 events. A Newton solve that truly cannot converge still ends the run: the
    // step is cut by 0.3 per failure until it falls below the minimum step.
    problem.ode_options.max_nonlinear_solver_failures = usize::MAX;

    let driver = Driver {
        automaton,
        floor,
        mode: &mode,
        duration,
        settings,
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
}

impl<'d> Driver<'d> {
    fn error(&self, t: f64, e: impl std::fmt::Display) -> Error {
        Error::Solver {
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

        // Stop times: the floor motion's breakpoints inside (0, end), then the end.
        let mut stops: Vec<f64> = self
            .floor
            .breakpoints()
            .iter()
            .copied()
            .filter(|&b| b > 0.0 && b < end * (1.0 - 1e-12))
            .collect();
        stops.push(end);
        let mut stop_index = 0;
        solver
            .set_stop_time(stops[0])
            .map_err(|e| self.error(0.0, e))?;

        let y0 = solver.state().y.clone();
        // Buffers for dense output, allocated once.
        let mut y_buf = y0.clone();
        let mut work_buf = solver.state().g.clone();
        let mut recorder = Recorder::new(automaton, 0.0, y0[0], y0[1], self.mode.get());
        let mut grid = OutputGrid::new(end, self.settings.output_dt);
        self.emit(
            &solver,
            &mut recorder,
            &mut grid,
            (&mut y_buf, &mut work_buf),
            0.0,
            true,
        )?;

        // A start on a guard, moving across it, is an event at t = 0.
        if let Some(guard) = automaton.crossed_guard(self.mode.get(), y0[0], y0[1]) {
            if self.apply_event(&mut solver, &mut recorder, 0.0, guard, false)? {
                return Ok((recorder, 0.0, self.stats(&solver)));
            }
        }

        let mut step_start = 0.0;
        let mut qdot_at_start = y0[1];
        loop {
            let reason = solver.step().map_err(|e| self.error(step_start, e))?;
            let step_end = solver.state().t;
            let stop = stops[stop_index];
            if step_end > stop + 1e-12 * stop.abs().max(1.0) {
                // Never expected: a run that went past its stop time would never end.
                return Err(self.error(step_end, format!("stepped past the stop time {stop} s")));
            }
            let mode = self.mode.get();
            let guard_root = match reason {
                OdeSolverStopReason::RootFound(t, i) => {
                    Some((t, automaton.guard(mode, automaton.guards(mode)[i])))
                }
                _ => None,
            };
            // The part of the step that belongs to this mode, and q' at its end.
            let until = guard_root.map_or(step_end, |(t, _)| t);
            let qdot_at_end = if until == step_end {
                solver.state().y[1]
            } else {
                self.state_at(&solver, until)?[1]
            };

            // A root of q' inside: a peak of q, and a point where q must still be in its mode.
            let mut crossing = guard_root;
            if qdot_at_start * qdot_at_end < 0.0 {
                let t_peak = self.locate(&solver, step_start, until, |y| y[1])?;
                let q_peak = self.state_at(&solver, t_peak)?[0];
                match automaton.crossed_guard(mode, q_peak, 0.0) {
                    Some(g) => {
                        let t = self.locate(&solver, step_start, t_peak, |y| g.overshoot(y[0]))?;
                        crossing = Some((t, g));
                    }
                    None => recorder.peak_candidate(t_peak, q_peak),
                }
            }
            // A guard the root finder passed over leaves the state beyond it.
            if crossing.is_none() {
                let y = &solver.state().y;
                if let Some(g) = automaton.crossed_guard(mode, y[0], y[1]) {
                    if g.overshoot(y[0]) > 0.0 {
                        let t =
                            self.locate(&solver, step_start, step_end, |y| g.overshoot(y[0]))?;
                        crossing = Some((t, g));
                    }
                }
            }

            if let Some((t_event, guard)) = crossing {
                self.emit(
                    &solver,
                    &mut recorder,
                    &mut grid,
                    (&mut y_buf, &mut work_buf),
                    t_event,
                    false,
                )?;
                if self.apply_event(&mut solver, &mut recorder, t_event, guard, true)? {
                    return Ok((recorder, t_event, self.stats(&solver)));
                }
                step_start = t_event;
                // Moving the state back out of a step that had reached the stop time leaves the
                // solver without one: set it again, or the run would go past it.
                solver
                    .set_stop_time(stop)
                    .map_err(|e| self.error(step_start, e))?;
            } else {
                self.emit(
                    &solver,
                    &mut recorder,
                    &mut grid,
                    (&mut y_buf, &mut work_buf),
                    step_end,
                    true,
                )?;
                step_start = step_end;
            }
            qdot_at_start = solver.state().y[1];

            // At a stop time: finish, or go on towards the next one.
            if (step_start - stop).abs() <= 1e-12 * stop.abs().max(1.0) {
                if stop_index + 1 == stops.len() {
                    let y = &solver.state().y;
                    recorder.peak_candidate(step_start, y[0]);
                    return Ok((recorder, step_start, self.stats(&solver)));
                }
                stop_index += 1;
                solver
                    .set_stop_time(stops[stop_index])
                    .map_err(|e| self.error(step_start, e))?;
            }
        }
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
        grid: &mut OutputGrid,
        buffers: (&mut Vector, &mut Vector),
        until: f64,
        inclusive: bool,
    ) -> Result<()>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        let me = self.automaton.generalised_mass();
        let (y, work) = buffers;
        while let Some(t) = grid.peek() {
            if t > until || (!inclusive && t == until) {
                break;
            }
            if t == solver.state().t {
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
    /// has at `lo` (zero counts as that side: a state that starts on a guard is not past it) to
    /// the sign it has at `hi`, by the Illinois variant of regula falsi, to a few ulps of t.
    fn locate<'a, Eqn, S>(
        &self,
        solver: &S,
        mut lo: f64,
        mut hi: f64,
        f: impl Fn([f64; 2]) -> f64,
    ) -> Result<f64>
    where
        Eqn: OdeEquations<T = f64, V = Vector> + 'a,
        S: OdeSolverMethod<'a, Eqn>,
    {
        // Orient f so that the far end is positive; then "past" means g > 0.
        let f_hi = f(self.state_at(solver, hi)?);
        let orientation = if f_hi > 0.0 { 1.0 } else { -1.0 };
        let g = |t: f64| -> Result<f64> { Ok(orientation * f(self.state_at(solver, t)?)) };
        let mut g_lo = g(lo)?;
        let mut g_hi = orientation * f_hi;
        if g_lo > 0.0 || g_hi <= 0.0 {
            // Already past at `lo`, or never past: nothing to refine.
            return Ok(if g_lo > 0.0 { lo } else { hi });
        }
        let mut last_side = 0i8;
        for _ in 0..200 {
            if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()) {
                break;
            }
            let secant = hi - g_hi * (hi - lo) / (g_hi - g_lo);
            // Fall back to bisection when the secant leaves the bracket or stalls at its ends.
            let mid = if secant > lo && secant < hi {
                secant
            } else {
                0.5 * (lo + hi)
            };
            let g_mid = g(mid)?;
            if g_mid > 0.0 {
                hi = mid;
                g_hi = g_mid;
                if last_side == 1 {
                    g_lo *= 0.5;
                }
                last_side = 1;
            } else {
                lo = mid;
                g_lo = g_mid;
                if last_side == -1 {
                    g_hi *= 0.5;
                }
                last_side = -1;
            }
        }
        Ok(hi)
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
            let state = solver.state_mut();
            state.y[0] = q;
            state.y[1] = qdot_after;
            // Derivatives consistent with the new mode, from which the method restarts.
            let x = [q, qdot_after];
            let mut dy = [0.0; NSTATES];
            right_hand_side(automaton, guard.to, floor_acc, &x, &mut dy);
            let mut dg = [0.0; NOUT];
            energy_integrands(automaton, guard.to, floor_acc, &x, &mut dg);
            for (i, value) in dy.into_iter().enumerate() {
                state.dy[i] = value;
            }
            for (i, value) in dg.into_iter().enumerate() {
                state.dg[i] = value;
            }
            match automaton.crossed_guard(guard.to, q, qdot_after) {
                Some(next) => guard = next,
                None => return Ok(false),
            }
        }
        Err(self.error(t, "endless chain of events at one instant"))
    }

    fn stats<'a, Eqn, S>(&self, solver: &S) -> SolverStats
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
            rhs_evaluations: 0,
            wall_time_s: 0.0,
        }
    }
}
