//! What an analysis gives: the steps of a dynamic run, its contact events and snapshots, and
//! the points of a pushover.

use serde::{Deserialize, Serialize};

/// Contact state of a base node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ContactState {
    /// Uplifted: no constraint.
    Free,
    /// On the floor, sliding: uy = 0, kinetic friction.
    Slip,
    /// On the floor, stuck: ux and uy held.
    Fixed,
}

/// One output step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemStep {
    /// Time, s.
    pub t: f64,
    /// Top displacement relative to the floor (mean ux of the top nodes), m.
    pub q: f64,
    /// Rocking part r = H (uy_left_corner - uy_right_corner)/B, m.
    pub rocking: f64,
    /// Slipping part: mean ux of the base nodes, m.
    pub slipping: f64,
    /// Flexural part s: integrated section rotation relative to the base, m.
    pub flexural: f64,
    /// Shearing part: q - rocking - slipping - flexural, m.
    pub shearing: f64,
    /// Top velocity relative to the floor (mean vx of the top nodes), m/s.
    pub top_velocity: f64,
    /// Angular momentum about the left toe, Σ m (Δy vx - Δx vy) with deformed positions and
    /// velocities relative to the floor, clockwise positive (same sign as q'), kg m²/s.
    pub momentum_left_toe: f64,
    /// Angular momentum about the right toe (same convention), kg m²/s.
    pub momentum_right_toe: f64,
    /// Lowest vertical displacement of a base node, m (negative = below the floor).
    pub lowest_base_uy: f64,
    /// State of each base node, left to right.
    pub base_states: Vec<ContactState>,
}

/// A base-node state change.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactEvent {
    /// Time of the step whose solution triggered the change (it applies from the next step), s.
    pub t: f64,
    /// Base node index, 0 = left corner .. nx = right corner.
    pub node: usize,
    /// The state before the change.
    pub from: ContactState,
    /// The state after the change.
    pub to: ContactState,
    /// Reactions at that step (0 for a Free node), N: horizontal Rx.
    pub rx: f64,
    /// Vertical reaction Ry at that step, N.
    pub ry: f64,
}

/// Nodal displacements at one time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// Requested time, s.
    pub requested: f64,
    /// Time of the stored step, s.
    pub t: f64,
    /// (ux, uy) of every node relative to the floor, m (node order of
    /// [`FemResult::node_coordinates`]).
    pub displacements: Vec<[f64; 2]>,
}

/// Result of [`simulate_fem`](super::simulate_fem).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FemResult {
    /// One entry per time step, t = 0 first.
    pub steps: Vec<FemStep>,
    /// Every base-node state change, in order.
    pub events: Vec<ContactEvent>,
    /// The displacements at the requested snapshot times.
    pub snapshots: Vec<Snapshot>,
    /// Undeformed node coordinates (x, y), m; node (i, j) is `j (nx + 1) + i`.
    pub node_coordinates: Vec<[f64; 2]>,
    /// Static gravity reactions (Rx, Ry) of the base nodes, N.
    pub static_reactions: Vec<[f64; 2]>,
    /// Highest fixed-base circular frequency of the mesh, rad/s.
    pub highest_frequency: f64,
    /// Stability limit of the scheme on this mesh, s (None = unconditionally stable).
    pub critical_time_step: Option<f64>,
    /// Time at which |q| exceeded the width B (static overturning limit); the run stops there.
    pub overturned_at: Option<f64>,
}

/// A static pushover curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pushover {
    /// One point per requested top displacement, in order, up to where the curve ended.
    pub points: Vec<PushoverPoint>,
    /// The first requested q at which the body, standing on one corner, turned about it
    /// freely (no stiffness: without P-Delta the restoring moment stays at its uplift value), so
    /// the displacement-controlled sweep stopped there.
    pub free_rotation_at: Option<f64>,
}

/// A pushover point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PushoverPoint {
    /// Prescribed top displacement q (mean ux of the top nodes), m.
    pub q: f64,
    /// Base shear = sum of the applied lateral loads, N.
    pub base_shear: f64,
    /// Load factor λ of the pattern m U(y) λ, m/s².
    pub load_factor: f64,
    /// True when the body rocks on one toe: every base node but one corner is off the floor
    /// (the discrete counterpart of the SDOF model's uplift).
    pub uplift: bool,
    /// True when at least one corner is off the floor (the base has started to open).
    pub heel_lifted: bool,
    /// Number of base nodes on the floor (no gap).
    pub contact_nodes: usize,
    /// Flexural part s, m.
    pub flexural: f64,
    /// Rocking part r, m.
    pub rocking: f64,
    /// Shearing part (remainder), m.
    pub shearing: f64,
    /// True when no contact set was exactly admissible and the least violating contiguous
    /// contact zone was taken (violation <= 1 % of |q| or of the weight; see [`pushover`](super::pushover)).
    pub approximate_contact: bool,
}
