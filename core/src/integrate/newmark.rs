//! Fixed-step Newmark integration of the automaton, as the paper solved its SDOF model
//! (linear acceleration, beta = 1/6, dt = 0.02 s, "compensation for moment overshoot").
//!
//! One step of length h from (q0, q'0, q''0) in mode m:
//!
//! ```text
//! q1  = q0 + h q'0 + h^2 ((1/2 - beta) q''0 + beta q''1)
//! q'1 = q'0 + h ((1 - gamma) q''0 + gamma q''1)
//! q''1 = acceleration(m, q1, q'1, a(t1))
//! ```
//!
//! Eq. 16 is affine in (q, q') on each branch of F, so the implicit relation for q''1 is solved
//! exactly by one evaluation of the automaton's acceleration and its (constant) Jacobian: no
//! iteration and no second copy of the model.
//!
//! A step that ends past a guard of its mode is handled by one of two variants:
//!
//! * [`NewmarkVariant::Compensate`] (the paper's reading): the step is kept as computed on the old
//!   branch. At its end t1 the mode changes, the angular-momentum reset is applied to q'1, and
//!   q''1 is evaluated again from the true F(q1) on the new branch. The restoring force the step
//!   ended with, nu_old F_old(q1), overshoots the true nu_new F_new(q1); replacing q''1 removes
//!   that overshoot before the next step starts, so it never enters the following steps. The
//!   event is logged at the detection time t1 (a multiple of dt) with the state q1 found there
//!   (past the guard by the overshoot).
//! * [`NewmarkVariant::Substep`]: the step length h* that lands the Newmark step exactly on the
//!   guard is found (Illinois regula falsi on h; q1(h) is smooth in h), the sub-step is taken, q is
//!   placed on the guard, the reset is applied, and the rest of the step is taken in the new mode.
//!   Events are logged at the located crossing.
//!
//! A fixed-step method sees only step ends: a guard crossed and re-crossed inside one step goes
//! unnoticed by both variants (the adaptive method stops at every root of q' and catches it).
//!
//! Between step ends the history is the cubic Hermite interpolant of (q, q') at both ends. For
//! linear acceleration (beta = 1/6, gamma = 1/2) that cubic is exactly the trajectory the method
//! assumes. Peaks of q are located on it. The energy integrals use the trapezoid rule per step.

use std::time::Instant;

use serde::Serialize;

use crate::integrate::SolverError;
use crate::physics::automaton::{Automaton, Guard, Mode};

type Result<T> = std::result::Result<T, SolverError>;
use crate::floor::FloorMotion;
use crate::integrate::solution::{Recorder, Solution, SolverStats};
use crate::integrate::{History, InitialState, OutputGrid};

/// How a step that crosses a guard is treated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NewmarkVariant {
    /// Change mode at the step end and remove the restoring-force overshoot (the paper).
    Compensate,
    /// Sub-step to the located crossing, change mode there, finish the step.
    Substep,
}

impl NewmarkVariant {
    /// The variant's model-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            NewmarkVariant::Compensate => "compensate",
            NewmarkVariant::Substep => "substep",
        }
    }

    /// The variant spelled `name` in a model file.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "compensate" => Some(NewmarkVariant::Compensate),
            "substep" => Some(NewmarkVariant::Substep),
            _ => None,
        }
    }
}

/// Settings of a Newmark run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct NewmarkSettings {
    /// Time step, s.
    pub dt: f64,
    /// Newmark's beta.
    pub beta: f64,
    /// Newmark's gamma.
    pub gamma: f64,
    /// How a mode change inside a step is handled.
    pub variant: NewmarkVariant,
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}

impl NewmarkSettings {
    /// "newmark-compensate" or "newmark-substep": the method's name in statistics and tables.
    pub fn label(&self) -> String {
        format!("newmark-{}", self.variant.name())
    }
}

/// Largest stable omega dt of Newmark's method on an undamped linear oscillator, or None when
/// the method is unconditionally stable (2 beta >= gamma >= 1/2). Damping does not lower it for
/// gamma = 1/2. Only the pre-uplift omega matters here: on the rocking branch the stiffness is
/// negative, the exact solution grows like exp(sqrt(k) t) and the method follows that growth
/// (without spurious oscillation) at any step that resolves it.
pub fn critical_omega_dt(beta: f64, gamma: f64) -> Option<f64> {
    let margin = 0.5 * gamma - beta;
    (margin > 0.0).then(|| 1.0 / margin.sqrt())
}

/// omega dt at the stability limit of the linear acceleration method (beta = 1/6, gamma = 1/2):
/// sqrt(12), dt = 0.551 T.
pub fn linear_acceleration_omega_dt() -> f64 {
    critical_omega_dt(1.0 / 6.0, 0.5).unwrap_or(f64::INFINITY)
}

/// The state at a step end.
#[derive(Debug, Clone, Copy)]
struct State {
    t: f64,
    q: f64,
    qdot: f64,
    qddot: f64,
    floor_acc: f64,
    /// Work of the floor and of damping since t = 0 (J).
    work_input: f64,
    work_damping: f64,
}

/// Integrates the automaton from `initial` over [0, duration] with fixed steps.
pub fn solve(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &NewmarkSettings,
    history: History,
) -> Result<Solution> {
    let started = Instant::now();
    let mut stepper = Stepper {
        automaton,
        floor,
        settings,
        mode: automaton.initial_mode(initial.q),
        grid: OutputGrid::for_history(history, duration, settings.output_dt),
        stats: SolverStats {
            method: settings.label(),
            ..SolverStats::default()
        },
    };
    let a0 = floor.acceleration(0.0);
    let mut state = State {
        t: 0.0,
        q: initial.q,
        qdot: initial.qdot,
        qddot: stepper.acceleration(stepper.mode, initial.q, initial.qdot, a0),
        floor_acc: a0,
        work_input: 0.0,
        work_damping: 0.0,
    };
    let mut recorder = Recorder::new(
        automaton,
        0.0,
        initial.q,
        initial.qdot,
        stepper.mode,
        history,
    );

    // A start on a guard, moving across it, is an event at t = 0.
    if let Some(guard) = automaton.crossed_guard(stepper.mode, state.q, state.qdot) {
        stepper.emit_at(&mut recorder, &state, false);
        if stepper.apply_event(&mut recorder, &mut state, guard, false)? {
            return Ok(stepper.finish(recorder, state.t, started));
        }
    }
    stepper.emit_at(&mut recorder, &state, true);

    // Step ends are k dt, computed afresh so that rounding does not accumulate; the last step
    // is shortened to end at `duration`.
    let steps = (duration / settings.dt * (1.0 - 1e-12)).ceil().max(1.0) as usize;
    for k in 1..=steps {
        let target = if k == steps {
            duration
        } else {
            k as f64 * settings.dt
        };
        if stepper.advance(&mut recorder, &mut state, target)? {
            return Ok(stepper.finish(recorder, state.t, started));
        }
    }
    recorder.peak_candidate(state.t, state.q);
    Ok(stepper.finish(recorder, state.t, started))
}

/// Most events one step may hold before the run is declared stuck.
const MAX_EVENTS_PER_STEP: usize = 16;

struct Stepper<'a> {
    automaton: &'a Automaton,
    floor: &'a dyn FloorMotion,
    settings: &'a NewmarkSettings,
    mode: Mode,
    grid: OutputGrid,
    stats: SolverStats,
}

impl<'a> Stepper<'a> {
    fn error(&self, t: f64, message: impl std::fmt::Display) -> SolverError {
        SolverError::Failed {
            method: self.settings.label(),
            t,
            message: message.to_string(),
        }
    }

    fn acceleration(&mut self, mode: Mode, q: f64, qdot: f64, floor_acc: f64) -> f64 {
        self.stats.rhs_evaluations += 1;
        self.automaton.acceleration(mode, q, qdot, floor_acc)
    }

    /// One Newmark step in `mode` from `s` to time `t1`.
    fn step(&mut self, mode: Mode, s: &State, t1: f64) -> Result<State> {
        let (beta, gamma) = (self.settings.beta, self.settings.gamma);
        let h = t1 - s.t;
        let floor_acc = self.floor.acceleration(t1);
        let q_pred = s.q + h * s.qdot + h * h * (0.5 - beta) * s.qddot;
        let qdot_pred = s.qdot + h * (1.0 - gamma) * s.qddot;
        // q'' = acceleration(q_pred + beta h^2 q'', qdot_pred + gamma h q''), affine in q''.
        let (d_q, d_qdot) = self.automaton.acceleration_jacobian(mode);
        let denominator = 1.0 - d_q * beta * h * h - d_qdot * gamma * h;
        if denominator <= f64::EPSILON {
            return Err(self.error(
                s.t,
                format!(
                    "the step {h} s is too long for the {} branch (the implicit Newmark equation has no solution); choose a smaller dt",
                    mode.name()
                ),
            ));
        }
        let qddot = self.acceleration(mode, q_pred, qdot_pred, floor_acc) / denominator;
        let qdot = qdot_pred + gamma * h * qddot;
        let a = self.automaton;
        let work_input = s.work_input
            + 0.5
                * h
                * (a.input_power(mode, s.qdot, s.floor_acc) + a.input_power(mode, qdot, floor_acc));
        let work_damping = s.work_damping
            + 0.5 * h * (a.damping_power(mode, s.qdot) + a.damping_power(mode, qdot));
        Ok(State {
            t: t1,
            q: q_pred + beta * h * h * qddot,
            qdot,
            qddot,
            floor_acc,
            work_input,
            work_damping,
        })
    }

    /// Advances `state` to `target` (one step, or sub-steps around events). True when the body
    /// overturned.
    fn advance(
        &mut self,
        recorder: &mut Recorder<'a>,
        state: &mut State,
        target: f64,
    ) -> Result<bool> {
        for _ in 0..MAX_EVENTS_PER_STEP {
            let mode = self.mode;
            let end = self.step(mode, state, target)?;
            self.stats.steps += 1;
            let Some(guard) = self.automaton.crossed_guard(mode, end.q, end.qdot) else {
                self.emit_between(recorder, state, &end, true);
                *state = end;
                return Ok(false);
            };
            match self.settings.variant {
                NewmarkVariant::Compensate => {
                    self.emit_between(recorder, state, &end, false);
                    *state = end;
                    if self.apply_event(recorder, state, guard, false)? {
                        return Ok(true);
                    }
                    self.emit_at(recorder, state, true);
                    return Ok(false);
                }
                NewmarkVariant::Substep => {
                    let landed = self.locate(mode, state, &end, guard)?;
                    self.emit_between(recorder, state, &landed, false);
                    *state = landed;
                    if self.apply_event(recorder, state, guard, true)? {
                        return Ok(true);
                    }
                    self.emit_at(recorder, state, true);
                    if state.t >= target {
                        return Ok(false);
                    }
                }
            }
        }
        Err(self.error(state.t, "too many events within one step"))
    }

    /// The sub-step from `start` that lands on `guard`, given that the full step to `end` passes
    /// it: Illinois regula falsi on the step length.
    fn locate(&mut self, mode: Mode, start: &State, end: &State, guard: Guard) -> Result<State> {
        let (mut lo, mut f_lo) = (start.t, guard.overshoot(start.q));
        let (mut hi, mut f_hi) = (end.t, guard.overshoot(end.q));
        let mut best = *end;
        if f_hi == 0.0 {
            return Ok(best);
        }
        if f_lo >= 0.0 {
            // The step starts on the guard, moving into the mode (an event has just placed it
            // there; crossed_guard would have fired otherwise), and ends back across it: a
            // grazing uplift or landing. The crossing lies inside the step, not at its start
            // (taking it at the start would undo the event at once and redo it, without end).
            // Bracket it by a sub-step that ends inside the mode.
            match self.inside_point(mode, start, end, guard)? {
                Some((inside, past)) => {
                    (lo, f_lo) = inside;
                    (hi, f_hi, best) = past;
                }
                // No sub-step ends inside the mode: the state leaves the mode at once.
                None => return Ok(*start),
            }
        }
        let tolerance = 1e-14 * guard.level.abs().max(1e-3);
        let mut side = 0;
        for _ in 0..100 {
            let t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            let t = if t > lo && t < hi { t } else { 0.5 * (lo + hi) };
            let trial = self.step(mode, start, t)?;
            self.stats.nonlinear_iterations += 1;
            let f = guard.overshoot(trial.q);
            if f >= 0.0 {
                (hi, f_hi, best) = (t, f, trial);
                if side == 1 {
                    f_lo *= 0.5;
                }
                side = 1;
            } else {
                (lo, f_lo) = (t, f);
                if side == -1 {
                    f_hi *= 0.5;
                }
                side = -1;
            }
            if f_hi <= tolerance || hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(1.0) {
                break;
            }
        }
        Ok(best)
    }

    /// For a step from `start` on `guard` to `end` past it: the end of a sub-step that lies
    /// inside the mode (its time and overshoot), and the shortest sub-step tried beyond it that
    /// ends past the guard (time, overshoot, state), found by halving the step. None when no
    /// sub-step down to rounding ends inside the mode.
    #[allow(clippy::type_complexity)]
    fn inside_point(
        &mut self,
        mode: Mode,
        start: &State,
        end: &State,
        guard: Guard,
    ) -> Result<Option<((f64, f64), (f64, f64, State))>> {
        let mut past = (end.t, guard.overshoot(end.q), *end);
        let mut h = 0.5 * (end.t - start.t);
        while start.t + h > start.t {
            let t = start.t + h;
            let trial = self.step(mode, start, t)?;
            self.stats.nonlinear_iterations += 1;
            let f = guard.overshoot(trial.q);
            if f < 0.0 {
                return Ok(Some(((t, f), past)));
            }
            if f > 0.0 {
                past = (t, f, trial);
            }
            h *= 0.5;
        }
        Ok(None)
    }

    /// Books the event `guard` at the current state, applies the reset and re-evaluates q'' on
    /// the new branch (this removes the restoring-force overshoot). `on_guard` places q exactly on
    /// the guard (sub-stepping located it); otherwise q stays where the step ended. True when the
    /// new mode is terminal.
    fn apply_event(
        &mut self,
        recorder: &mut Recorder<'a>,
        state: &mut State,
        guard: Guard,
        on_guard: bool,
    ) -> Result<bool> {
        let mut guard = guard;
        // A reset can only chain into another event in degenerate cases; never loop forever.
        for _ in 0..4 {
            let from = self.mode;
            if on_guard {
                state.q = guard.level;
            }
            let qdot_before = state.qdot;
            let qdot_after = self.automaton.reset_velocity(guard.kind, qdot_before);
            recorder.event(
                state.t,
                guard.kind,
                from,
                guard.to,
                state.q,
                qdot_before,
                qdot_after,
                state.floor_acc,
                state.work_input,
                state.work_damping,
            );
            self.mode = guard.to;
            state.qdot = qdot_after;
            if guard.to == Mode::Overturned {
                return Ok(true);
            }
            state.qddot = self.acceleration(guard.to, state.q, state.qdot, state.floor_acc);
            match self.automaton.crossed_guard(guard.to, state.q, state.qdot) {
                Some(next) => guard = next,
                None => return Ok(false),
            }
        }
        Err(self.error(state.t, "endless chain of events at one instant"))
    }

    /// Samples the history at the grid times in (start.t, end.t], or (start.t, end.t) when not
    /// `inclusive`, on the cubic Hermite interpolant of the step in the current mode.
    fn emit_between(
        &mut self,
        recorder: &mut Recorder<'a>,
        start: &State,
        end: &State,
        inclusive: bool,
    ) {
        let h = end.t - start.t;
        while let Some(t) = self.grid.peek() {
            if t > end.t || (!inclusive && t == end.t) {
                break;
            }
            if t < start.t {
                // Emitted already (an event sat exactly on a grid time).
                self.grid.advance();
                continue;
            }
            let (q, qdot, weight) = if t == end.t {
                (end.q, end.qdot, 1.0)
            } else if h > 0.0 {
                let (q, qdot) = hermite(start, end, (t - start.t) / h);
                (q, qdot, (t - start.t) / h)
            } else {
                (start.q, start.qdot, 0.0)
            };
            recorder.sample(
                t,
                self.mode,
                q,
                qdot,
                self.floor.acceleration(t),
                start.work_input + weight * (end.work_input - start.work_input),
                start.work_damping + weight * (end.work_damping - start.work_damping),
            );
            self.grid.advance();
        }
        self.offer_peak(recorder, start, end);
    }

    /// Samples the grid time at `state.t`, if there is one and `inclusive`; skips grid times
    /// before it.
    fn emit_at(&mut self, recorder: &mut Recorder<'a>, state: &State, inclusive: bool) {
        self.emit_between(recorder, state, state, inclusive);
    }

    /// Offers the extremum of the step's interpolant, if q' changes sign inside the step.
    fn offer_peak(&self, recorder: &mut Recorder<'a>, start: &State, end: &State) {
        recorder.peak_candidate(end.t, end.q);
        let h = end.t - start.t;
        if h <= 0.0 || start.qdot * end.qdot >= 0.0 {
            return;
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        let rising = start.qdot < 0.0;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let (_, v) = hermite(start, end, mid);
            if (v < 0.0) == rising {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let theta = 0.5 * (lo + hi);
        let (q, _) = hermite(start, end, theta);
        recorder.peak_candidate(start.t + theta * h, q);
    }

    fn finish(self, recorder: Recorder<'a>, final_time: f64, started: Instant) -> Solution {
        let mut stats = self.stats;
        stats.wall_time_s = started.elapsed().as_secs_f64();
        recorder.finish(final_time, self.mode, stats)
    }
}

/// (q, q') at fraction `theta` of the step on the cubic Hermite interpolant of its end states.
fn hermite(start: &State, end: &State, theta: f64) -> (f64, f64) {
    let h = end.t - start.t;
    let (t2, t3) = (theta * theta, theta * theta * theta);
    let q = (2.0 * t3 - 3.0 * t2 + 1.0) * start.q
        + (t3 - 2.0 * t2 + theta) * h * start.qdot
        + (-2.0 * t3 + 3.0 * t2) * end.q
        + (t3 - t2) * h * end.qdot;
    let qdot = (6.0 * t2 - 6.0 * theta) * (start.q - end.q) / h
        + (3.0 * t2 - 4.0 * theta + 1.0) * start.qdot
        + (3.0 * t2 - 2.0 * theta) * end.qdot;
    (q, qdot)
}
