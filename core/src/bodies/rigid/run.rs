//! A rigid-block run: the block at rest until the floor lifts it, its stretches of rocking,
//! impacts, chatter and overturning.

use super::full::{self, Restoring, RockingEquation, Stretch};
use super::small_angle::Propagator;
use super::{
    Result, RigidBlock, RigidEvent, RigidEventKind, RigidForm, RigidOutcome, RigidOverturning,
    RigidPhase, RigidSettings, RigidState, ZENO_TIME,
};
use crate::base::invalid::InvalidParameter;
use crate::base::limits::MAX_DURATION;
use crate::floor::{floor_limit_rule, within_floor_limit, FloorMotion, Shaking};
use crate::integrate::budget::RunBudget;
use crate::integrate::{InitialState, SolverError};
use crate::physics::body::positive;

/// Points per step at which a resting block checks the floor acceleration against a_up.
const REST_SAMPLES: usize = 8;

/// Simulates the block from rest over [0, duration] with the default settings.
pub fn simulate_block(
    block: &RigidBlock,
    floor: &dyn FloorMotion,
    duration: f64,
) -> Result<RigidOutcome> {
    simulate_from(
        block,
        floor,
        InitialState { q: 0.0, qdot: 0.0 },
        duration,
        &RigidSettings::for_block(block),
    )
}

/// Simulates the block from `initial` (|q0| < B) over [0, duration]. q0 > 0 starts rocking right,
/// q0 < 0 left; q0 = 0 starts rocking the way q'0 points, or at rest when q'0 = 0.
pub fn simulate_from(
    block: &RigidBlock,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &RigidSettings,
) -> Result<RigidOutcome> {
    simulate_shaken(
        block,
        &Shaking::new(floor, None),
        initial,
        duration,
        settings,
    )
}

/// [`simulate_from`] on a floor that may also move vertically: gravity is then g + a_v(t) in
/// the block's equation, in its uplift acceleration and in its pull towards the floor, and the
/// small-angle form is integrated adaptively as the full one is. A vertical motion that
/// reaches -g is refused.
pub fn simulate_shaken(
    block: &RigidBlock,
    shaking: &Shaking<'_>,
    initial: InitialState,
    duration: f64,
    settings: &RigidSettings,
) -> Result<RigidOutcome> {
    if !(duration.is_finite() && duration > 0.0 && duration <= MAX_DURATION) {
        return Err(InvalidParameter::new(
            "rigid.duration",
            duration,
            &format!("must be a finite number greater than 0 and at most {MAX_DURATION:e} s"),
        )
        .into());
    }
    for (key, value) in [
        ("rigid.max_step", settings.max_step),
        ("rigid.rtol", settings.rtol),
        ("rigid.atol", settings.atol),
    ] {
        positive(key, value)?;
    }
    let limit = block.overturning_displacement();
    if !(initial.q.is_finite() && initial.q.abs() < limit) {
        let rule = match block.form() {
            RigidForm::SmallAngle => format!("must lie strictly between -B and B ({limit} m)"),
            RigidForm::Full => format!(
                "must lie strictly between -H atan(B/H) and H atan(B/H) ({limit} m), where the \
                 full equation's block overturns"
            ),
        };
        return Err(InvalidParameter::new("rigid.q0", initial.q, &rule).into());
    }
    if !initial.qdot.is_finite() {
        return Err(
            InvalidParameter::new("rigid.qdot0", initial.qdot, "must be a finite number").into(),
        );
    }
    let peak = shaking.horizontal().peak_acceleration();
    if !within_floor_limit(peak) {
        return Err(InvalidParameter::new(
            "rigid floor motion",
            shaking.horizontal().kind(),
            &floor_limit_rule(peak),
        )
        .into());
    }
    shaking.check_contact(block.gravity(), duration)?;
    BlockRun::new(block, shaking, initial, duration, settings).run()
}

/// A run in progress.
struct BlockRun<'a> {
    /// The horizontal floor motion.
    floor: &'a dyn FloorMotion,
    /// Both motions: the factor on gravity, the breakpoints of both.
    shaking: &'a Shaking<'a>,
    /// g, m/s^2.
    gravity: f64,
    propagator: Propagator<'a>,
    /// The equation integrated adaptively: the full form, or the small-angle one under vertical
    /// floor motion; None for the small-angle form's exact propagator.
    full: Option<RockingEquation<'a>>,
    /// |q| at which the block has overturned ([`RigidOverturning::ReachesLimit`]).
    limit: f64,
    /// |q| at which a block rocking on past the limit lies on its side, H pi/2
    /// ([`RigidOverturning::CannotReturn`]).
    on_side: f64,
    overturning: RigidOverturning,
    restitution: f64,
    tipping: f64,
    /// See [`RigidBlock::pull_factor`].
    pull_factor: f64,
    uplift: f64,
    duration: f64,
    max_step: f64,
    breakpoint: usize,
    state: RigidState,
    budget: RunBudget,
    outcome: RigidOutcome,
}

impl<'a> BlockRun<'a> {
    fn new(
        block: &RigidBlock,
        shaking: &'a Shaking<'a>,
        initial: InitialState,
        duration: f64,
        settings: &RigidSettings,
    ) -> Self {
        let side = if initial.q != 0.0 {
            initial.q.signum()
        } else if initial.qdot != 0.0 {
            initial.qdot.signum()
        } else {
            0.0
        };
        let phase = if side == 0.0 {
            RigidPhase::Rest
        } else {
            RigidPhase::rocking(side)
        };
        let state = RigidState {
            t: 0.0,
            q: initial.q,
            qdot: initial.qdot,
            phase,
        };
        let floor = shaking.horizontal();
        let restoring = match block.form() {
            RigidForm::SmallAngle => Restoring::SmallAngle {
                k2: block.frequency().powi(2),
                width: block.width(),
            },
            RigidForm::Full => Restoring::Full {
                height: block.height(),
                alpha: block.slenderness(),
                scale: block.height() * block.frequency().powi(2),
            },
        };
        let adaptive = block.form() == RigidForm::Full || shaking.vertical().is_some();
        BlockRun {
            floor,
            shaking,
            gravity: block.gravity(),
            propagator: Propagator {
                floor,
                quiet_after: floor.quiet_after(),
                k: block.frequency(),
                width: block.width(),
            },
            full: adaptive.then_some(RockingEquation {
                restoring,
                gravity: block.gravity(),
                shaking,
                rtol: settings.rtol,
                atol: settings.atol,
            }),
            limit: block.overturning_displacement(),
            on_side: block.height() * std::f64::consts::FRAC_PI_2,
            overturning: block.overturning(),
            restitution: block.restitution(),
            tipping: block.tipping_acceleration(),
            pull_factor: block.pull_factor(),
            uplift: block.uplift_acceleration(),
            duration,
            max_step: settings.max_step,
            breakpoint: 0,
            state,
            budget: RunBudget::new(),
            outcome: RigidOutcome {
                overturned: false,
                t_overturn: None,
                n_uplift: 0,
                n_impact: 0,
                n_settle: 0,
                first_uplift: None,
                max_abs_q: initial.q.abs(),
                t_max_abs_q: 0.0,
                final_state: state,
                events: Vec::new(),
                steps: 0,
            },
        }
    }

    fn run(mut self) -> Result<RigidOutcome> {
        let quiet_after = self.shaking.quiet_after();
        while self.state.t < self.duration && self.state.phase != RigidPhase::Overturned {
            let quiet = quiet_after.is_some_and(|quiet| self.state.t >= quiet);
            // At rest on a floor at rest for good: nothing more can happen.
            if self.state.phase == RigidPhase::Rest && quiet {
                self.state.t = self.duration;
                break;
            }
            // Rocking on a floor at rest for good: its free motion decides.
            if quiet && self.judge_free_motion()? {
                break;
            }
            // The full form rocks in adaptive stretches of its own.
            if let (Some(full), true) = (self.full, self.state.phase != RigidPhase::Rest) {
                self.budget
                    .step(self.state.t, self.outcome.steps)
                    .map_err(|m| self.failure(m))?;
                let until = self.stretch_end();
                let floor = self.floor;
                full::rock(&mut self, floor, &full, until)?;
                continue;
            }
            let t_end = self.next_stop();
            self.outcome.steps += 1;
            self.budget
                .step(self.state.t, self.outcome.steps)
                .map_err(|m| self.failure(m))?;
            match self.state.phase {
                RigidPhase::Rest => self.rest_step(t_end)?,
                _ => self.rocking_step(t_end)?,
            }
        }
        if self.state.phase != RigidPhase::Overturned {
            self.judge_free_motion()?;
        }
        self.outcome.final_state = self.state;
        Ok(self.outcome)
    }

    fn failure(&self, message: String) -> SolverError {
        SolverError::Failed {
            method: "rigid".to_string(),
            t: self.state.t,
            message,
        }
    }

    /// Where a stretch of the full form's rocking ends: the moment the floor comes to rest for
    /// good (where, by the rule that a block has overturned once it cannot come back, its free
    /// motion is judged; both rules end the stretch there, so that they take the same steps), or
    /// the end of the run.
    fn stretch_end(&self) -> f64 {
        match self.shaking.quiet_after() {
            Some(quiet) if quiet > self.state.t => quiet.min(self.duration),
            _ => self.duration,
        }
    }

    /// The end of the next step: a step later, the next breakpoint, or the end of the run.
    fn next_stop(&mut self) -> f64 {
        let t = self.state.t;
        let breakpoints = self.shaking.breakpoints();
        while self.breakpoint < breakpoints.len() && breakpoints[self.breakpoint] <= t {
            self.breakpoint += 1;
        }
        let mut end = (t + self.max_step).min(self.duration);
        if let Some(&b) = breakpoints.get(self.breakpoint) {
            end = end.min(b);
        }
        end
    }

    /// The side (+1 right, -1 left) a resting block starts rocking to under the floor
    /// acceleration `a`, or None if it stays. A floor at the uplift acceleration itself does not
    /// lift it: for Housner's block the moments about the toe then balance, and the block has no
    /// pull away from the floor.
    fn uplift_side(&self, t: f64) -> Option<f64> {
        let a = self.floor.acceleration(t);
        // Vertical floor motion scales gravity, and the uplift acceleration with it.
        let uplift = self.uplift * self.shaking.gravity_factor(t, self.gravity);
        if a < -uplift {
            Some(1.0)
        } else if a > uplift {
            Some(-1.0)
        } else {
            None
        }
    }

    fn rest_step(&mut self, t_end: f64) -> Result<()> {
        let t0 = self.state.t;
        let lifts = |t: f64| self.uplift_side(t).is_some();
        let mut found = None;
        if lifts(t0) {
            found = Some(t0);
        } else {
            let mut previous = t0;
            for j in 1..=REST_SAMPLES {
                let t = if j == REST_SAMPLES {
                    t_end
                } else {
                    t0 + (t_end - t0) * j as f64 / REST_SAMPLES as f64
                };
                if lifts(t) {
                    found = Some(first_true(previous, t, &lifts));
                    break;
                }
                previous = t;
            }
        }
        match found {
            None => self.state.t = t_end,
            Some(t) => {
                let side = self.uplift_side(t).unwrap_or(1.0);
                self.state = RigidState {
                    t,
                    q: 0.0,
                    qdot: 0.0,
                    phase: RigidPhase::rocking(side),
                };
                self.outcome.n_uplift += 1;
                self.outcome.first_uplift.get_or_insert(t);
                self.book(RigidEventKind::Uplift, 0.0, 0.0)?;
            }
        }
        Ok(())
    }

    fn rocking_step(&mut self, t_end: f64) -> Result<()> {
        let RigidState {
            t: t0,
            q: q0,
            qdot: v0,
            phase,
        } = self.state;
        let side = phase.side();
        let propagator = self.propagator;
        let at = |t: f64| propagator.propagate(t0, q0, v0, side, t - t0);
        let (q1, v1) = at(t_end);
        if !(q1.is_finite() && v1.is_finite()) {
            return Err(self.failure(format!(
                "the state is no longer finite at t = {t_end} s (q = {q1}, q' = {v1}): the floor \
                 acceleration is not a finite number"
            )));
        }

        // Pieces on which q is monotone: (start time, q there, direction of motion). The first
        // moves the way q' points, or away from the floor when the block has just lifted off
        // (q' = 0, its acceleration pointing away from the floor); a second starts where q'
        // changes sign.
        let direction = if v0 != 0.0 { v0.signum() } else { side };
        let mut pieces = vec![(t0, q0, direction)];
        if v1 * direction < 0.0 {
            let t_turn = first_true(t0, t_end, |t| at(t).1 * direction <= 0.0);
            pieces.push((t_turn, at(t_turn).0, -direction));
        }
        for (i, &(ta, qa, d)) in pieces.iter().enumerate() {
            let (tb, qb) = pieces.get(i + 1).map_or((t_end, q1), |p| (p.0, p.1));
            self.peak(ta, qa);
            if d * side < 0.0 {
                // Moving towards the floor: an impact when q reaches 0.
                if side * qb <= 0.0 {
                    let te = if side * qa <= 0.0 {
                        ta
                    } else {
                        first_true(ta, tb, |t| side * at(t).0 <= 0.0)
                    };
                    return self.impact(te, at(te).1);
                }
            } else if side * qb >= self.away_limit() {
                // Moving away from it: overturned when |q| reaches the overturning displacement
                // (or, by the rule that it cannot return, when it lies on its side).
                let limit = self.away_limit();
                let te = first_true(ta, tb, |t| side * at(t).0 >= limit);
                return self.overturn(te, side * limit, at(te).1);
            }
        }
        self.peak(t_end, q1);
        self.state = RigidState {
            t: t_end,
            q: q1,
            qdot: v1,
            phase,
        };
        Ok(())
    }

    fn peak(&mut self, t: f64, q: f64) {
        if q.abs() > self.outcome.max_abs_q {
            self.outcome.max_abs_q = q.abs();
            self.outcome.t_max_abs_q = t;
        }
    }

    fn impact(&mut self, t: f64, qdot_before: f64) -> Result<()> {
        let side = -self.state.phase.side();
        let qdot = self.restitution * qdot_before;
        self.state = RigidState {
            t,
            q: 0.0,
            qdot,
            phase: RigidPhase::rocking(side),
        };
        self.outcome.n_impact += 1;
        self.book(RigidEventKind::Impact, qdot_before, qdot)?;

        // Chatter (see the module documentation): the impacts still to come would end within
        // 2 |q'| / (c (g B/H - |a|)(1 - e)).
        let a = self.floor.acceleration(t).abs();
        let tipping = self.tipping * self.shaking.gravity_factor(t, self.gravity);
        let pull = self.pull_factor * (tipping - a);
        if pull > 0.0 && 2.0 * qdot.abs() <= ZENO_TIME * pull * (1.0 - self.restitution) {
            self.state = RigidState {
                t,
                q: 0.0,
                qdot: 0.0,
                phase: RigidPhase::Rest,
            };
            self.outcome.n_settle += 1;
            self.book(RigidEventKind::Settle, qdot, 0.0)?;
        }
        Ok(())
    }

    /// |q| at which a block moving away from the floor has overturned.
    fn away_limit(&self) -> f64 {
        match self.overturning {
            RigidOverturning::ReachesLimit => self.limit,
            RigidOverturning::CannotReturn => self.on_side,
        }
    }

    /// By [`RigidOverturning::CannotReturn`], a rocking block whose free motion never brings it
    /// back to the floor has overturned now (see the module documentation); true if it has.
    fn judge_free_motion(&mut self) -> Result<bool> {
        let RigidState { t, q, qdot, phase } = self.state;
        if self.overturning != RigidOverturning::CannotReturn
            || !matches!(phase, RigidPhase::RockRight | RigidPhase::RockLeft)
        {
            return Ok(false);
        }
        let side = phase.side();
        // Judged once both floor motions are at rest for good, under gravity alone.
        let restoring = self.full.map(|f| f.restoring);
        let gone = match restoring {
            // q - s B = c1 e^(k t) + c2 e^(-k t), 2 s c1 = s (q - s B) + s q'/k.
            None | Some(Restoring::SmallAngle { .. }) => {
                let k = self.propagator.k;
                side * q - self.propagator.width + side * qdot / k >= 0.0
            }
            Some(Restoring::Full { height, alpha, .. }) => {
                let p = self.propagator.k;
                // u = s theta, w = s theta'; the energy above that of the barrier u = alpha.
                let (u, w) = (side * q / height, side * qdot / height);
                let half = 0.5 * (alpha - u);
                let excess = 0.5 * w * w - 2.0 * p * p * half.sin() * half.sin();
                if u >= alpha {
                    w >= 0.0 || excess <= 0.0
                } else {
                    w > 0.0 && excess >= 0.0
                }
            }
        };
        if gone {
            self.overturn(t, q, qdot)?;
        }
        Ok(gone)
    }

    /// The block has overturned at `q`.
    fn overturn(&mut self, t: f64, q: f64, qdot: f64) -> Result<()> {
        self.state = RigidState {
            t,
            q,
            qdot,
            phase: RigidPhase::Overturned,
        };
        self.peak(t, q);
        self.outcome.overturned = true;
        self.outcome.t_overturn = Some(t);
        self.book(RigidEventKind::Overturn, qdot, qdot)
    }

    /// Logs an event at the current state and counts it against the budget.
    fn book(&mut self, kind: RigidEventKind, qdot_before: f64, qdot_after: f64) -> Result<()> {
        let s = self.state;
        self.outcome.events.push(RigidEvent {
            t: s.t,
            kind,
            q: s.q,
            qdot_before,
            qdot_after,
            to: s.phase,
        });
        self.budget.event(s.t).map_err(|m| self.failure(m))
    }
}

impl Stretch for BlockRun<'_> {
    fn state(&self) -> RigidState {
        self.state
    }

    fn set_state(&mut self, state: RigidState) {
        self.state = state;
    }

    fn add_steps(&mut self, steps: usize) {
        self.outcome.steps += steps;
    }

    fn peak(&mut self, t: f64, q: f64) {
        BlockRun::peak(self, t, q);
    }

    fn impact(&mut self, t: f64, qdot_before: f64) -> Result<()> {
        BlockRun::impact(self, t, qdot_before)
    }

    fn overturn(&mut self, t: f64, q: f64, qdot: f64) -> Result<()> {
        BlockRun::overturn(self, t, q, qdot)
    }

    fn away_limit(&self) -> f64 {
        BlockRun::away_limit(self)
    }
}

/// The earliest time in (lo, hi] at which `holds` is true, to the resolution of the floating-point
/// time, given that it holds at `hi` (and is taken not to at `lo`), by bisection.
fn first_true(lo: f64, hi: f64, mut holds: impl FnMut(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_the_first_time_to_the_last_bit() {
        let t = first_true(1.0, 2.0, |t| t >= std::f64::consts::SQRT_2);
        assert!((t - std::f64::consts::SQRT_2).abs() <= 2.0 * f64::EPSILON);
    }
}
