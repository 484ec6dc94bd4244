//! Adaptive integration of the automaton with diffsol (BDF, ESDIRK34, TR-BDF2; Tsit45).
//!
//! The steps, stops, retakes and restarts are the event loop's (`event_loop.rs`); the
//! body's equations, guards, resets and records are here.
//!
//! How events are found. After every step the body splits the step at the root of q' inside it
//! (a sign change of q' between its ends, located on diffsol's dense output; it is also a peak of
//! q, so max q and min q are located to solver accuracy). On each piece q is monotone, so a guard
//! can be crossed at most once there, and only in the direction q moves: a landing only moving
//! back towards the floor, an uplift or an overturn only moving away from it. The first guard so
//! crossed is located on the dense output by regula falsi. diffsol's own root finder is not used:
//! it reports any sign change of a guard function, whichever way the state moves.
//!
//! A step whose dense output cannot resolve its crossing is taken again by the loop, four times
//! shorter, from its exact start: that is a crossing placed where q' already points back into
//! the mode, or a piece that starts beyond the guard, or a step that ends beyond a guard with no
//! crossing found (q turned twice). This happens at a grazing uplift, where the excursion beyond
//! s_n is shorter than the step and a low-order interpolant puts q back inside before q' turns;
//! taking such a crossing at face value logged hundreds of uplifts and landings within 1e-12 s.
//!
//! At an event the solver is moved back to the event time, q is placed exactly on the guard, the
//! angular-momentum reset is applied to q', and the method restarts in the new mode. A state that
//! starts on a guard and moves back into its mode does not trigger it; a state on a guard moving
//! across it does, at once. `RunBudget` caps events (and the loop steps), so that every run ends.

use std::cell::Cell;
use std::time::Instant;

use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder};
use serde::Serialize;

use super::budget::RunBudget;
use super::event_loop::{self, DenseOutput, EventBody, Found, LoopSetup, Outcome, StepStart};
use super::monotone::MonotonePieces;
use crate::floor::FloorMotion;
use crate::integrate::solution::{Recorder, Solution, SolverStats};
use crate::integrate::SolverError;
use crate::integrate::{History, InitialState, OutputGrid};
use crate::physics::automaton::{Automaton, Guard, Mode};

type Result<T> = std::result::Result<T, SolverError>;
type Matrix = NalgebraMat<f64>;
type LinearSolver = NalgebraLU<f64>;

/// Number of state components: q and q'.
const NSTATES: usize = 2;
/// Number of integrated outputs: the input and damping work, per unit Me.
const NOUT: usize = 2;
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

    let run = LoopSetup {
        method: settings.method.name(),
        floor,
        vertical: None,
        duration,
        history,
        output_dt: settings.output_dt,
    };
    let mut body = Column {
        method: settings.method,
        automaton,
        floor,
        mode: &mode,
        recorder: Recorder::new(automaton, 0.0, initial.q, initial.qdot, mode.get(), history),
        budget: RunBudget::new(),
        peak: None,
    };
    let finish = match settings.method {
        AdaptiveMethod::Bdf => event_loop::run(
            &run,
            &mut body,
            problem
                .bdf::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::Esdirk34 => event_loop::run(
            &run,
            &mut body,
            problem
                .esdirk34::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::TrBdf2 => event_loop::run(
            &run,
            &mut body,
            problem
                .tr_bdf2::<LinearSolver>()
                .map_err(|e| solver_error(0.0, &e))?,
        ),
        AdaptiveMethod::Tsit45 => event_loop::run(
            &run,
            &mut body,
            problem.tsit45().map_err(|e| solver_error(0.0, &e))?,
        ),
    }?;
    let s = &finish.statistics;
    let stats = SolverStats {
        method: settings.method.name().to_string(),
        steps: s.number_of_steps,
        error_test_failures: s.number_of_error_test_failures,
        nonlinear_iterations: s.number_of_nonlinear_solver_iterations,
        jacobian_evaluations: s.number_of_linear_solver_setups,
        crossing_retries: finish.crossing_retries,
        rhs_evaluations: rhs_evaluations.get(),
        wall_time_s: started.elapsed().as_secs_f64(),
    };
    Ok(body.recorder.finish(finish.t, mode.get(), stats))
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

/// The single body, as the event loop drives it.
struct Column<'d> {
    method: AdaptiveMethod,
    automaton: &'d Automaton,
    floor: &'d dyn FloorMotion,
    mode: &'d Cell<Mode>,
    recorder: Recorder<'d>,
    budget: RunBudget,
    /// The root of q' (a peak of q: time and q) the last step found before its first event.
    peak: Option<(f64, f64)>,
}

impl Column<'_> {
    fn error(&self, t: f64, e: impl std::fmt::Display) -> SolverError {
        SolverError::Failed {
            method: self.method.name().to_string(),
            t,
            message: e.to_string(),
        }
    }
}

impl EventBody for Column<'_> {
    type Event = Guard;

    fn derivatives(&self, t: f64, y: &[f64], dy: &mut [f64], dg: &mut [f64]) {
        let floor_acc = self.floor.acceleration(t);
        right_hand_side(self.automaton, self.mode.get(), floor_acc, y, dy);
        energy_integrands(self.automaton, self.mode.get(), floor_acc, y, dg);
    }

    /// Looks for the first guard the step [start, t1] crossed. Between roots of q' the top
    /// displacement is monotone, so the step is split at the root of q' (a sign change of q'
    /// between its ends), and on each monotone piece only the guards crossed in the direction q
    /// moves there are candidates: a landing can only be met moving back towards the floor, an
    /// uplift or an overturn only moving away from it. A candidate whose crossing the dense
    /// output places where q' already points back (or at the very start of a piece) was not
    /// resolved by the step, and neither was a step that ends beyond a guard without a crossing.
    fn find_event(
        &mut self,
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
        _grid: &OutputGrid,
    ) -> Result<Found<Guard>> {
        let automaton = self.automaton;
        let mode = self.mode.get();
        let state_at = |t: f64| -> Result<[f64; 2]> {
            let y = dense.state_at(t)?;
            Ok([y[0], y[1]])
        };
        let locate = |lo: f64, hi: f64, f: &dyn Fn([f64; 2]) -> f64| {
            crate::integrate::sign_change::locate(lo, hi, |t| -> Result<f64> {
                Ok(f(state_at(t)?))
            })
        };
        let split = MonotonePieces::of(dense, start, t1)?;
        let end_state = split.end;
        self.peak = split.turn;
        for piece in split.pieces() {
            for &slot in automaton.guards(mode) {
                let guard = automaton.guard(mode, slot);
                if guard.direction != piece.direction {
                    continue;
                }
                if guard.overshoot(piece.q_to) <= 0.0 {
                    continue;
                }
                if guard.overshoot(piece.q_from) >= 0.0 {
                    return Ok(Found::Unresolved);
                }
                let t = locate(piece.from, piece.to, &|y| guard.overshoot(y[0]))?;
                let qdot = state_at(t)?[1];
                if guard.direction * qdot <= 0.0 {
                    return Ok(Found::Unresolved);
                }
                self.peak = self.peak.filter(|&(t_peak, _)| t_peak < t);
                return Ok(Found::At(t, guard));
            }
        }
        // The state must end inside its mode; if not, q turned more than once in the step.
        if automaton
            .guards(mode)
            .iter()
            .any(|&slot| automaton.guard(mode, slot).overshoot(end_state[0]) > 0.0)
        {
            return Ok(Found::Unresolved);
        }
        Ok(Found::None)
    }

    fn book_step(
        &mut self,
        _dense: &dyn DenseOutput,
        _start: &StepStart,
        _until: f64,
    ) -> Result<()> {
        if let Some((t_peak, q_peak)) = self.peak.take() {
            self.recorder.peak_candidate(t_peak, q_peak);
        }
        Ok(())
    }

    /// Books the event, applies the reset and switches the mode (at the start of the run: the
    /// guard the state sits on moving across it, if any).
    fn apply(&mut self, t: f64, y: &[f64], g: &[f64], event: Option<Guard>) -> Result<Outcome> {
        let automaton = self.automaton;
        let me = automaton.generalised_mass();
        let Some(mut guard) =
            event.or_else(|| automaton.crossed_guard(self.mode.get(), y[0], y[1]))
        else {
            return Ok(Outcome::Continue);
        };
        let mut qdot_before = y[1];
        // A reset can leave the state on a guard of the new mode moving across it only in
        // degenerate grazing cases; follow such a chain, but never forever.
        for _ in 0..4 {
            let from = self.mode.get();
            // Place q exactly on the guard: the event was located to solver accuracy.
            let q = guard.level;
            let qdot_after = automaton.reset_velocity(guard.kind, qdot_before);
            self.recorder.event(
                t,
                guard.kind,
                from,
                guard.to,
                q,
                qdot_before,
                qdot_after,
                self.floor.acceleration(t),
                me * g[0],
                me * g[1],
            );
            self.mode.set(guard.to);
            if guard.to == Mode::Overturned {
                return Ok(Outcome::Stop);
            }
            match automaton.crossed_guard(guard.to, q, qdot_after) {
                Some(next) => {
                    guard = next;
                    qdot_before = qdot_after;
                }
                None => {
                    self.budget.event(t).map_err(|m| self.error(t, m))?;
                    return Ok(Outcome::Restart(vec![q, qdot_after]));
                }
            }
        }
        Err(self.error(t, "endless chain of events at one instant"))
    }

    fn sample(&mut self, t: f64, y: &[f64], g: &[f64]) -> Result<()> {
        let me = self.automaton.generalised_mass();
        self.recorder.sample(
            t,
            self.mode.get(),
            y[0],
            y[1],
            self.floor.acceleration(t),
            me * g[0],
            me * g[1],
        );
        Ok(())
    }

    fn finish(&mut self, t: f64, y: &[f64], _g: &[f64]) {
        self.recorder.peak_candidate(t, y[0]);
    }
}
