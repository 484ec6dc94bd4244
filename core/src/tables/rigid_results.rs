//! What a run of the rigid block alone writes: events.csv's columns and rows, and summary.json.

use serde::Serialize;

use crate::bodies::rigid::{RigidBlock, RigidEvent, RigidOutcome};
use crate::model::Model;
use crate::simulate::Provenance;

/// The columns of a rigid block's events.csv.
pub const RIGID_EVENT_COLUMNS: [&str; 6] = [
    "t_s",
    "event",
    "q_m",
    "qdot_before_m_s",
    "qdot_after_m_s",
    "to",
];

/// One row of events.csv, in the order of [`RIGID_EVENT_COLUMNS`], numbers in their shortest
/// exact form.
pub fn rigid_event_row(event: &RigidEvent) -> [String; 6] {
    let n = crate::base::format::shortest;
    [
        n(event.t),
        event.kind.name().to_string(),
        n(event.q),
        n(event.qdot_before),
        n(event.qdot_after),
        event.to.name().to_string(),
    ]
}

/// The block a rigid run solved, as summary.json describes it.
#[derive(Debug, Clone, Serialize)]
pub struct BlockDescription {
    /// "small-angle" or "full".
    pub equation: &'static str,
    /// "reaches-limit" or "cannot-return".
    pub overturning: &'static str,
    /// H, m.
    pub height_m: f64,
    /// B, m.
    pub width_m: f64,
    /// g, m/s^2.
    pub gravity_m_s2: f64,
    /// alpha = atan(B/H), rad.
    pub alpha_rad: f64,
    /// p, rad/s, the frequency of its equation.
    pub p_rad_s: f64,
    /// The floor acceleration that lifts it off on a still floor vertically, m/s^2.
    pub uplift_acceleration_m_s2: f64,
    /// Its coefficient of restitution.
    pub restitution: f64,
    /// |q| at which it has overturned by the rule `reaches-limit`, m.
    pub overturning_displacement_m: f64,
}

/// summary.json of a rigid run.
#[derive(Debug, Clone, Serialize)]
pub struct RigidSummary {
    /// Which flexrock made it, from which model file.
    #[serde(flatten)]
    pub provenance: Provenance,
    /// The block.
    pub block: BlockDescription,
    /// The horizontal floor motion.
    pub excitation: serde_json::Value,
    /// The vertical floor motion (upwards positive), or null.
    pub vertical_excitation: Option<serde_json::Value>,
    /// Simulated time, s.
    pub duration_s: f64,
    /// Whether it overturned, and when.
    pub overturned: bool,
    /// When it overturned, s.
    pub t_overturn_s: Option<f64>,
    /// When it first lifted off, s.
    pub first_uplift_s: Option<f64>,
    /// Uplifts from rest, impacts, and returns to rest after chatter.
    pub n_uplift: usize,
    /// Impacts.
    pub n_impact: usize,
    /// Returns to rest after chatter.
    pub n_settle: usize,
    /// The largest |q| = |theta| H, m, and when.
    pub max_abs_q_m: f64,
    /// When |q| was largest, s.
    pub t_max_abs_q_s: f64,
    /// The largest |theta| over alpha.
    pub max_abs_theta_over_alpha: f64,
    /// Steps taken.
    pub steps: usize,
}

impl RigidSummary {
    /// The summary of `outcome`, the run of `block` on the floor of `model`.
    pub fn of(model: &Model, block: &RigidBlock, outcome: &RigidOutcome) -> Self {
        RigidSummary {
            provenance: Provenance::of(model),
            block: BlockDescription {
                equation: block.form().name(),
                overturning: block.overturning().name(),
                height_m: block.height(),
                width_m: block.width(),
                gravity_m_s2: block.gravity(),
                alpha_rad: block.slenderness(),
                p_rad_s: block.frequency(),
                uplift_acceleration_m_s2: block.uplift_acceleration(),
                restitution: block.restitution(),
                overturning_displacement_m: block.overturning_displacement(),
            },
            excitation: model.floor.parameters(),
            vertical_excitation: model.vertical.as_ref().map(|v| v.parameters()),
            duration_s: model.duration,
            overturned: outcome.overturned,
            t_overturn_s: outcome.t_overturn,
            first_uplift_s: outcome.first_uplift,
            n_uplift: outcome.n_uplift,
            n_impact: outcome.n_impact,
            n_settle: outcome.n_settle,
            max_abs_q_m: outcome.max_abs_q,
            t_max_abs_q_s: outcome.t_max_abs_q,
            max_abs_theta_over_alpha: outcome.max_abs_q / block.height() / block.slenderness(),
            steps: outcome.steps,
        }
    }
}
