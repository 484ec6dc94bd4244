//! What a rigid-block run gives: its phases, events and result.

use serde::Serialize;

/// What the block is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidPhase {
    /// Standing on both toes, q = 0, q' = 0.
    Rest,
    /// Rocking about the right (+x) toe, q > 0.
    RockRight,
    /// Rocking about the left (-x) toe, q < 0.
    RockLeft,
    /// |q| reached B. Terminal.
    Overturned,
}

impl RigidPhase {
    /// The phase's name in tables, e.g. "rock-right".
    pub fn name(self) -> &'static str {
        match self {
            RigidPhase::Rest => "rest",
            RigidPhase::RockRight => "rock-right",
            RigidPhase::RockLeft => "rock-left",
            RigidPhase::Overturned => "overturned",
        }
    }

    /// +1 rocking right, -1 rocking left, 0 otherwise.
    pub(super) fn side(self) -> f64 {
        match self {
            RigidPhase::RockRight => 1.0,
            RigidPhase::RockLeft => -1.0,
            RigidPhase::Rest | RigidPhase::Overturned => 0.0,
        }
    }

    pub(super) fn rocking(side: f64) -> Self {
        if side > 0.0 {
            RigidPhase::RockRight
        } else {
            RigidPhase::RockLeft
        }
    }
}

/// What happened at an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RigidEventKind {
    /// The block at rest started rocking.
    Uplift,
    /// q crossed 0: q' -> e q', rocking on about the other toe.
    Impact,
    /// The chatter after an impact was cut short: the block is at rest (see the module
    /// documentation).
    Settle,
    /// The block overturned: |q| reached the overturning displacement, or, by
    /// [`RigidOverturning::CannotReturn`](super::RigidOverturning::CannotReturn), it can no longer come back.
    Overturn,
}

impl RigidEventKind {
    /// The event's name in tables, e.g. "impact".
    pub fn name(self) -> &'static str {
        match self {
            RigidEventKind::Uplift => "uplift",
            RigidEventKind::Impact => "impact",
            RigidEventKind::Settle => "settle",
            RigidEventKind::Overturn => "overturn",
        }
    }
}

/// One event.
#[derive(Debug, Clone, Serialize)]
pub struct RigidEvent {
    /// Time, s.
    pub t: f64,
    /// What happened.
    pub kind: RigidEventKind,
    /// q at the event, m (0, or where the block was when it overturned).
    pub q: f64,
    /// q' just before, m/s.
    pub qdot_before: f64,
    /// q' just after, m/s.
    pub qdot_after: f64,
    /// The phase after the event.
    pub to: RigidPhase,
}

/// The state of the block at a time.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RigidState {
    /// Time, s.
    pub t: f64,
    /// Top displacement q = theta H, m.
    pub q: f64,
    /// q', m/s.
    pub qdot: f64,
    /// Phase.
    pub phase: RigidPhase,
}

/// The result of a rigid-block run.
#[derive(Debug, Clone, Serialize)]
pub struct RigidOutcome {
    /// The block overturned within the duration.
    pub overturned: bool,
    /// When it overturned, s.
    pub t_overturn: Option<f64>,
    /// Uplifts from rest.
    pub n_uplift: usize,
    /// Impacts (crossings of q = 0 while rocking).
    pub n_impact: usize,
    /// Chatters cut short by putting the block at rest.
    pub n_settle: usize,
    /// Time of the first uplift from rest, s.
    pub first_uplift: Option<f64>,
    /// Largest |q| over the run, m (the overturning displacement if it overturned when it
    /// reached it; by [`RigidOverturning::CannotReturn`](super::RigidOverturning::CannotReturn) it may pass it and come back).
    pub max_abs_q: f64,
    /// When |q| was largest, s.
    pub t_max_abs_q: f64,
    /// The state at the end: at the duration, or at the overturn.
    pub final_state: RigidState,
    /// Every event, in order.
    pub events: Vec<RigidEvent>,
    /// Steps taken.
    pub steps: usize,
}
