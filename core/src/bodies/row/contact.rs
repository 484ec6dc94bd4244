//! Where two neighbouring columns touch, and how far apart they are (book/src/row.md §2).
//!
//! The contact is at the height of the shorter column's top, y_c = min(H_left, H_right). There
//! each column's section moves horizontally by u = U(xi) s + xi r (xi = y_c / H), with s and r
//! the flexural and rocking parts of its q; within a mode u is affine in q, with slope Phi(xi),
//! the mode's velocity shape. To the same small-rotation order as the single column, the faces
//! stay vertical, so the clear gap is the gap at rest plus the right column's u minus the left
//! column's.
//!
//! The faces also move vertically (book/src/row.md §6): rocking about its right toe by r/H, a
//! column's left face rises by B r/H and its right face stays; bending turns the section at the
//! contact by U'(xi) s/H, raising the face on the side the column bends away from by B/2 times
//! that. Within a mode this too is affine in q, and two faces in contact slide past each other at
//! the difference of their vertical velocities ([`Contact::sliding_slopes`]).

use crate::physics::automaton::{Automaton, Mode};

/// The share of a gap's size (the gap at rest plus both columns' displacements at the contact)
/// by which a contact out of force may read below zero, beyond its rounding allowance, before
/// the run stops with an error: far above the rounding of the states (about 1e-16 of the size),
/// far below anything physical (a nanometre for a gap summed from terms of a metre).
pub const OVERLAP_ERROR_SHARE: f64 = 1e-9;
/// After an impact, or where a held contact is let go, the two states leave the gap at zero up
/// to rounding, and it may open very slowly: a pair separating at 1e-8 m/s after the last
/// bounces of a series, or a held contact let go, which opens only at third order (its force is
/// zero there, so the held motion is the free one). Read from a gap rounded below zero, its
/// first instants look like a new closing. So a contact that has been struck or let go closes
/// only when its gap falls this many ulps of the gap's size (the gap at rest plus both
/// displacements) below zero, or below where the gap is if it is below zero already: 1e-16 m
/// for a gap of 1 cm.
pub const GAP_ROUNDING_ULPS: f64 = 64.0;

/// A column's face at a contact: what moves it vertically.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Face {
    /// +1 for the column's right face, -1 for its left face.
    pub side: f64,
    /// The column's width B, m.
    pub width: f64,
    /// The column's height H, m.
    pub height: f64,
    /// The slope U'(xi) of its flexural shape at the contact.
    pub shape_slope: f64,
}

impl Face {
    /// dv/dq of the face's point at the contact in `mode`, v its vertical displacement (up):
    /// v = (r/H)(x_p - x_f) - x_f U'(xi) s/H with x_f = +-B/2 the face and x_p = +-B/2 the
    /// pivot toe, on the side the column leans to (`q` gives the side of an overturned column).
    pub fn vertical_slope(&self, automaton: &Automaton, mode: Mode, q: f64) -> f64 {
        let ds = automaton.flexural_slope(mode);
        let half = 0.5 * self.width;
        let pivot = match mode {
            Mode::PreUplift => 0.0,
            Mode::RockRight => half,
            Mode::RockLeft => -half,
            Mode::Overturned => half * q.signum(),
        };
        let face = self.side * half;
        ((1.0 - ds) * (pivot - face) - face * self.shape_slope * ds) / self.height
    }
}

/// The contact between column `index` and `index + 1` of a row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Which contact: between columns `index` and `index + 1`.
    pub index: usize,
    /// y_c, m: the top of the shorter column.
    pub height: f64,
    /// The clear gap at rest, m.
    pub clearance: f64,
    /// xi = y_c / H and the flexural shape U(xi) there, of the left and the right column.
    pub left: (f64, f64),
    /// As `left`, of the right column.
    pub right: (f64, f64),
    /// The left column's right face.
    pub left_face: Face,
    /// The right column's left face.
    pub right_face: Face,
}

impl Contact {
    pub(crate) fn new(
        index: usize,
        height: f64,
        clearance: f64,
        left: (f64, f64),
        right: (f64, f64),
        faces: (Face, Face),
    ) -> Self {
        Contact {
            index,
            height,
            clearance,
            left,
            right,
            left_face: faces.0,
            right_face: faces.1,
        }
    }

    /// The clear gap, m, with the left column in `left` = (mode, q) and the right in `right`.
    /// Negative where the faces would overlap.
    pub fn gap(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> f64 {
        let (u_left, u_right) = self.displacements(automata, left, right);
        self.clearance - u_left + u_right
    }

    /// The size of the terms the gap is summed from, m: the gap at rest plus both columns'
    /// displacements at the contact. The gap's rounding is a few ulps of it.
    pub fn gap_size(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> f64 {
        let (u_left, u_right) = self.displacements(automata, left, right);
        self.clearance.abs() + u_left.abs() + u_right.abs()
    }

    /// Each column's horizontal displacement at the contact, m.
    fn displacements(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> (f64, f64) {
        (
            automata
                .0
                .displacement_at(left.0, left.1, self.left.0, self.left.1),
            automata
                .1
                .displacement_at(right.0, right.1, self.right.0, self.right.1),
        )
    }

    /// du/dq of the left and the right column at the contact, in their modes: the closing
    /// velocity is `slopes.0` q'_left - `slopes.1` q'_right.
    pub fn slopes(&self, automata: (&Automaton, &Automaton), modes: (Mode, Mode)) -> (f64, f64) {
        (
            automata
                .0
                .displacement_slope_at(modes.0, self.left.0, self.left.1),
            automata
                .1
                .displacement_slope_at(modes.1, self.right.0, self.right.1),
        )
    }

    /// dv/dq of the left column's face and of the right column's at the contact, each column
    /// given as (mode, q): the faces slide at sigma = `.0` q'_left - `.1` q'_right (the left
    /// face rising past the right one where sigma > 0).
    pub fn sliding_slopes(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> (f64, f64) {
        (
            self.left_face.vertical_slope(automata.0, left.0, left.1),
            self.right_face.vertical_slope(automata.1, right.0, right.1),
        )
    }
}

/// What a contact is doing at a sampled instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactState {
    /// The faces are apart (or, under the impact law, touching for an instant only).
    Open,
    /// Held closed after impacts accumulated (the impact law's persistent contact).
    Held,
    /// Under the compliant law, faces let go where their force fell to zero that still overlap
    /// and move apart, with no force between them (book/src/row.md §4a).
    Parting,
    /// Pressing on each other under the compliant law, without friction.
    Pressing,
    /// Pressing and sliding past each other against friction.
    Sliding,
    /// Pressing and stuck by friction.
    Sticking,
}

/// One contact at one sampled instant (a row of contacts.csv).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ContactSample {
    /// Time, s.
    pub t: f64,
    /// The contact: between columns `contact` and `contact + 1`.
    pub contact: usize,
    /// What it is doing.
    pub state: ContactState,
    /// The clear gap, m (below zero: the compliant law's penetration).
    pub gap: f64,
    /// How fast the contact points approach each other, m/s.
    pub closing_velocity: f64,
    /// How fast the left column's face slides up past the right one's, m/s.
    pub sliding_velocity: f64,
    /// The contact force, N: the compliant law's k delta + c delta' while pressing (0 when
    /// open); none under the impact law, whose forces are impulses (impacts.csv).
    pub force: Option<f64>,
    /// The friction force on the left column's face (up), N (the right one's takes its
    /// opposite); none under the impact law.
    pub friction_force: Option<f64>,
}
