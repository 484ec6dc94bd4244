//! What a row's run returns: each column's solution, the impacts, the stretches of contact
//! under either law, and every contact at every sampled instant.

use super::contact::ContactSample;
use crate::integrate::solution::Solution;

/// One impact at one contact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ImpactRecord {
    /// Time, s.
    pub t: f64,
    /// The contact: between column `contact` and `contact + 1`.
    pub contact: usize,
    /// Closing velocity of the contact points before the impact, m/s (positive).
    pub closing_velocity: f64,
    /// Their separating velocity after it, m/s.
    pub separating_velocity: f64,
    /// The impulse, N s.
    pub impulse: f64,
}

/// A stretch of persistent contact: two neighbours held together.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HeldContact {
    /// The contact: between columns `contact` and `contact + 1`.
    pub contact: usize,
    /// When the pair was first held together, s.
    pub t_start: f64,
    /// When it was let go (its contact force fell to zero), s; None if held to the end.
    pub t_end: Option<f64>,
}

/// What the row's run returns.
#[derive(Debug, Clone)]
pub struct RowSolution {
    /// Each column's solution, left to right: its history, its events (impacts among them),
    /// its peaks and its energy books.
    pub columns: Vec<Solution>,
    /// Every impact, in time order.
    pub impacts: Vec<ImpactRecord>,
    /// The body's kinetic energy taken by each instant of impacts, J (positive), in time order.
    pub impact_energy_loss: Vec<(f64, f64)>,
    /// The column that overturned and when, if one did: the row's run ends there.
    pub overturned: Option<(usize, f64)>,
    /// Every stretch of persistent contact: the contact, when it was formed and when let go.
    pub held: Vec<HeldContact>,
    /// Every stretch of contact under the compliant law (empty under the impact law).
    pub contacts: Vec<ContactStretch>,
    /// Every contact at every sampled instant (empty without a sampled history).
    pub contact_history: Vec<ContactSample>,
    /// Every stretch over which the faces of a contact stuck by friction (the compliant law
    /// with friction; empty otherwise).
    pub sticking: Vec<StickStretch>,
    /// The time the run ended, s.
    pub final_time: f64,
}

/// A stretch of contact under the compliant law: from the gap's closing to the zero of the force.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ContactStretch {
    /// The contact: between columns `contact` and `contact + 1`.
    pub contact: usize,
    /// When the faces met, s.
    pub t_start: f64,
    /// When the force fell to zero, s; None if in contact at the end.
    pub t_end: Option<f64>,
    /// The reduced mass of the two contact points at the start, kg.
    pub reduced_mass: f64,
    /// The dashpot c over the stretch, N s/m.
    pub damping: f64,
    /// Closing velocity of the contact points at the start, m/s.
    pub closing_velocity: f64,
    /// Their separating velocity at the end, m/s.
    pub separating_velocity: Option<f64>,
    /// The largest contact force, N.
    pub peak_force: f64,
    /// When it was largest, s.
    pub t_peak_force: f64,
    /// The energy the contact took from the two bodies, J: the integral of P delta' (the
    /// dashpot's dissipation and the spring's energy left at the release).
    pub energy_dissipated: f64,
    /// The energy friction between the faces took from the two bodies, J: the integral of
    /// mu P |sigma| while they slid (0 without friction).
    pub friction_dissipated: f64,
    /// The largest friction force, N (its magnitude, up to mu times the contact force).
    pub peak_friction_force: f64,
    /// Changes between sticking and sliding over the stretch, after the faces met (each, and
    /// how they met, is a `friction-stick` or `friction-slip` event of both columns).
    pub friction_changes: usize,
}

/// A stretch over which the faces of a contact stuck (book/src/row.md §4b).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StickStretch {
    /// The contact: between columns `contact` and `contact + 1`.
    pub contact: usize,
    /// When the faces stuck, s.
    pub t_start: f64,
    /// When they slid again or the contact ended, s; None if stuck at the end of the run.
    pub t_end: Option<f64>,
}
