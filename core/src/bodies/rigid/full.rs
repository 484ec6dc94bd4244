//! The rocking block's equation integrated adaptively (Housner's full equation, and the
//! small-angle one under vertical floor motion): each stretch of rocking is a run of diffsol's
//! Tsit45 method in the event loop every diffsol run shares
//! ([`crate::integrate::event_loop`]), to the tolerance of [`RigidSettings`](super::RigidSettings).
//!
//! A stretch starts where the block lifts off (or where a run starts it rocking) and ends when
//! the block comes to rest after its chatter, when it overturns, or at the stretch's end. Its
//! impacts are events of the loop: located on the step's dense output, applied (q' -> e q', the
//! other toe), and the method restarted from there.

use std::cell::Cell;

use diffsol::{NalgebraMat, OdeBuilder};

use super::{RigidPhase, RigidState};
use crate::floor::{FloorMotion, Shaking};
use crate::integrate::event_loop::{self, DenseOutput, EventBody, Found, Outcome, StepStart};
use crate::integrate::monotone::MonotonePieces;
use crate::integrate::{History, OutputGrid, SolverError};

type Result<T> = std::result::Result<T, SolverError>;
type Matrix = NalgebraMat<f64>;

/// The rocking equation in q = theta H units, integrated adaptively: Housner's full equation,
/// or the small-angle one where the floor also moves vertically (its propagator is exact only
/// for constant gravity). The vertical acceleration a_v multiplies gravity by 1 + a_v/g.
#[derive(Clone, Copy)]
pub(super) struct RockingEquation<'a> {
    /// Which form, with its numbers.
    pub restoring: Restoring,
    /// g, m/s^2.
    pub gravity: f64,
    /// The floor's motions: the vertical one, if any, scales gravity.
    pub shaking: &'a Shaking<'a>,
    /// Relative tolerance of the integration.
    pub rtol: f64,
    /// Absolute tolerance, m.
    pub atol: f64,
}

/// The restoring term of a form of the equation.
#[derive(Debug, Clone, Copy)]
pub(super) enum Restoring {
    /// q'' = -H p^2 [f sin(s alpha - q/H) + (a/g) cos(s alpha - q/H)], s the side the block
    /// rocks on and f = 1 + a_v/g.
    Full {
        /// H, m.
        height: f64,
        /// alpha = atan(B/H), rad.
        alpha: f64,
        /// H p^2, m/s^2.
        scale: f64,
    },
    /// q'' = f k^2 (q - s B) - (3/2) a.
    SmallAngle {
        /// k^2 = 3 g/(2 H), 1/s^2.
        k2: f64,
        /// B, m.
        width: f64,
    },
}

impl RockingEquation<'_> {
    /// The method's name in messages.
    fn method(&self) -> &'static str {
        match self.restoring {
            Restoring::Full { .. } => "rigid full equation (tsit45)",
            Restoring::SmallAngle { .. } => "rigid small-angle equation (tsit45)",
        }
    }

    /// 1 + a_v(t)/g.
    fn gravity_factor(&self, t: f64) -> f64 {
        self.shaking.gravity_factor(t, self.gravity)
    }

    /// q'' rocking on `side` at q at time t under the horizontal floor acceleration `a`.
    fn acceleration(&self, side: f64, q: f64, t: f64, a: f64) -> f64 {
        let f = self.gravity_factor(t);
        match self.restoring {
            Restoring::Full {
                height,
                alpha,
                scale,
            } => {
                let angle = side * alpha - q / height;
                -scale * (f * angle.sin() + a / self.gravity * angle.cos())
            }
            Restoring::SmallAngle { k2, width } => f * k2 * (q - side * width) - 1.5 * a,
        }
    }

    /// d q''/dq rocking on `side` at q at time t under the horizontal floor acceleration `a`.
    fn stiffness(&self, side: f64, q: f64, t: f64, a: f64) -> f64 {
        let f = self.gravity_factor(t);
        match self.restoring {
            Restoring::Full {
                height,
                alpha,
                scale,
            } => {
                let angle = side * alpha - q / height;
                scale / height * (f * angle.cos() - a / self.gravity * angle.sin())
            }
            Restoring::SmallAngle { k2, .. } => f * k2,
        }
    }
}

/// What ends a piece of rocking.
#[derive(Debug, Clone, Copy)]
enum Crossing {
    /// q reaches 0 moving towards the floor.
    Impact,
    /// |q| reaches the overturning displacement moving away from it.
    Overturn,
}

/// What a stretch of rocking needs of the run it is part of.
pub(super) trait Stretch {
    /// The block's state.
    fn state(&self) -> RigidState;
    /// Puts the block in `state`.
    fn set_state(&mut self, state: RigidState);
    /// Counts `steps` more steps.
    fn add_steps(&mut self, steps: usize);
    /// Books q at t as a candidate for the largest |q|.
    fn peak(&mut self, t: f64, q: f64);
    /// The block, at q = 0 at t, hits the floor at q' = `qdot_before`: it rocks on about the
    /// other toe, or comes to rest.
    fn impact(&mut self, t: f64, qdot_before: f64) -> Result<()>;
    /// The block has overturned at q, q'.
    fn overturn(&mut self, t: f64, q: f64, qdot: f64) -> Result<()>;
    /// |q| at which a block moving away from the floor has overturned.
    fn away_limit(&self) -> f64;
}

/// Rocks the block of `run` on `floor` from its state until it comes to rest, overturns, or
/// `until`.
pub(super) fn rock(
    run: &mut dyn Stretch,
    floor: &dyn FloorMotion,
    full: &RockingEquation<'_>,
    until: f64,
) -> Result<()> {
    let method = full.method();
    let start = run.state();
    let side = Cell::new(start.phase.side());
    let (t0, q0, v0) = (start.t, start.q, start.qdot);
    let failed = |t: f64, e: &dyn std::fmt::Display| SolverError::Failed {
        method: method.to_string(),
        t,
        message: e.to_string(),
    };
    let mut problem = OdeBuilder::<Matrix>::new()
        .t0(t0)
        .rtol(full.rtol)
        .atol([full.atol; 2])
        .rhs_implicit(
            |x, _p, t, y| {
                y[0] = x[1];
                y[1] = full.acceleration(side.get(), x[0], t, floor.acceleration(t));
            },
            |x, _p, t, v, y| {
                y[0] = v[1];
                y[1] = full.stiffness(side.get(), x[0], t, floor.acceleration(t)) * v[0];
            },
        )
        .init(
            |_p, _t, y| {
                y[0] = q0;
                y[1] = v0;
            },
            2,
        )
        .build()
        .map_err(|e| failed(t0, &e))?;
    problem.ode_options.min_timestep = problem.ode_options.min_timestep.min(1e-3 * (until - t0));
    let solver = problem.tsit45().map_err(|e| failed(t0, &e))?;
    let stretch = event_loop::LoopSetup {
        method,
        floor,
        vertical: full.shaking.vertical(),
        duration: until,
        history: History::PeaksOnly,
        output_dt: until - t0,
    };
    let mut body = Rocking {
        run,
        floor,
        full,
        side: &side,
        peak: None,
        end: None,
    };
    let finish = event_loop::run(&stretch, &mut body, solver)?;
    let end = body.end;
    run.add_steps(finish.statistics.number_of_steps);
    if let Some((t, q, qdot)) = end {
        let phase = run.state().phase;
        run.set_state(RigidState { t, q, qdot, phase });
    }
    Ok(())
}

/// The rocking block, as the event loop drives it.
struct Rocking<'r> {
    run: &'r mut dyn Stretch,
    floor: &'r dyn FloorMotion,
    full: &'r RockingEquation<'r>,
    /// The side it rocks on, +1 or -1, shared with the solver's right-hand side.
    side: &'r Cell<f64>,
    /// The root of q' (a peak of |q|: time and q) the last step found before its first event.
    peak: Option<(f64, f64)>,
    /// The state where the stretch ended without an event.
    end: Option<(f64, f64, f64)>,
}

impl Rocking<'_> {
    /// How far q is past the crossing (negative before it), for a block rocking on `side`.
    fn overshoot(&self, crossing: Crossing, side: f64, q: f64) -> f64 {
        match crossing {
            Crossing::Impact => -side * q,
            Crossing::Overturn => side * q - self.run.away_limit(),
        }
    }
}

impl EventBody for Rocking<'_> {
    type Event = Crossing;

    fn derivatives(&self, t: f64, y: &[f64], dy: &mut [f64], _dg: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = self
            .full
            .acceleration(self.side.get(), y[0], t, self.floor.acceleration(t));
    }

    /// Looks for the first crossing of the step [start, t1]. The step is split where q' changes
    /// sign, so that q is monotone on each piece; moving towards the floor only an impact can
    /// be met, moving away only the overturning displacement.
    fn find_event(
        &mut self,
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
        _grid: &OutputGrid,
    ) -> Result<Found<Crossing>> {
        let side = self.side.get();
        let state_at = |t: f64| -> Result<[f64; 2]> {
            let y = dense.state_at(t)?;
            Ok([y[0], y[1]])
        };
        let split = MonotonePieces::of(dense, start, t1)?;
        let end_state = split.end;
        self.peak = split.turn;
        for piece in split.pieces() {
            let crossing = if piece.direction == -side {
                Crossing::Impact
            } else if piece.direction == side {
                Crossing::Overturn
            } else {
                continue;
            };
            if self.overshoot(crossing, side, piece.q_to) <= 0.0 {
                continue;
            }
            if self.overshoot(crossing, side, piece.q_from) >= 0.0 {
                return Ok(Found::Unresolved);
            }
            let t =
                crate::integrate::sign_change::locate(piece.from, piece.to, |t| -> Result<f64> {
                    Ok(self.overshoot(crossing, side, state_at(t)?[0]))
                })?;
            if piece.direction * state_at(t)?[1] <= 0.0 {
                return Ok(Found::Unresolved);
            }
            self.peak = self.peak.filter(|&(t_peak, _)| t_peak < t);
            return Ok(Found::At(t, crossing));
        }
        // The state must end between the floor and the overturning displacement; if not, q
        // turned more than once in the step.
        if [Crossing::Impact, Crossing::Overturn]
            .iter()
            .any(|&c| self.overshoot(c, side, end_state[0]) > 0.0)
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
        if let Some((t, q)) = self.peak.take() {
            self.run.peak(t, q);
        }
        Ok(())
    }

    /// An impact turns the block onto its other toe (or puts it at rest after its chatter); an
    /// overturn ends the stretch. The start of the stretch is no event.
    fn apply(&mut self, t: f64, y: &[f64], _g: &[f64], event: Option<Crossing>) -> Result<Outcome> {
        let side = self.side.get();
        match event {
            None => Ok(Outcome::Continue),
            Some(Crossing::Overturn) => {
                let limit = self.run.away_limit();
                self.run.overturn(t, side * limit, y[1])?;
                Ok(Outcome::Stop)
            }
            Some(Crossing::Impact) => {
                self.run.impact(t, y[1])?;
                let state = self.run.state();
                if state.phase == RigidPhase::Rest {
                    return Ok(Outcome::Stop);
                }
                self.side.set(state.phase.side());
                Ok(Outcome::Restart(vec![0.0, state.qdot]))
            }
        }
    }

    fn sample(&mut self, _t: f64, _y: &[f64], _g: &[f64]) -> Result<()> {
        Ok(())
    }

    fn finish(&mut self, t: f64, y: &[f64], _g: &[f64]) {
        self.run.peak(t, y[0]);
        self.end = Some((t, y[0], y[1]));
    }
}
